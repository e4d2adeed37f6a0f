/* fracterra — reconstruct.c: ft_reconstruct_points and the machinery shared with ft_reconstruct_voids
 * (recon_voids.c): option checks naming the bad value, the choice of D, sigma0, T_0 and the fBm amplitude
 * from the data, the realizations (per-cell mean and standard deviation by Welford's update with double
 * accumulators), the info record and the method names. Arakawa & Krotkov §3; docs/terrain-reconstruct.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

static const char *const method_names[] = {"fractal", "conditional", "smooth"};
#define N_METHODS (sizeof method_names / sizeof method_names[0])

const char *ft_recon_method_name(ft_recon_method m)
{
    return (unsigned)m < N_METHODS ? method_names[m] : "unknown";
}

int ft_recon_method_parse(const char *name, ft_recon_method *m)
{
    if (name == NULL || m == NULL)
        return ft_error(FT_E_INVALID, "method name is NULL");
    for (size_t i = 0; i < N_METHODS; i++)
        if (strcasecmp(name, method_names[i]) == 0) {
            *m = (ft_recon_method)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "unknown method '%s' (expected fractal, conditional or smooth)",
                    name);
}

static int check_opts(const ft_recon_opts *o)
{
    if ((unsigned)o->method >= N_METHODS)
        return ft_error(FT_E_INVALID, "unknown method %d", (int)o->method);
    if (!(o->dim == 0.0 || (o->dim > 2.0 && o->dim < 3.0)))
        return ft_error(FT_E_INVALID, "dim must be 0 (estimate from the data) or in (2, 3), got %g",
                        o->dim);
    if (!((o->tension >= 0.0 && o->tension <= 1.0) || o->tension == FT_RECON_TENSION_FROM_DIM))
        return ft_error(FT_E_INVALID, "tension must be in [0, 1] (or FT_RECON_TENSION_FROM_DIM: from D), got %g",
                        o->tension);
    if (!(o->lambda > 0.0) || !isfinite(o->lambda))
        return ft_error(FT_E_INVALID, "lambda must be > 0 and finite, got %g", o->lambda);
    if (!(o->sigma >= 0.0) || !isfinite(o->sigma))
        return ft_error(FT_E_INVALID, "sigma must be >= 0 and finite, got %g", o->sigma);
    if (!(o->temperature >= 0.0) || !isfinite(o->temperature))
        return ft_error(FT_E_INVALID, "temperature must be > 0 (or 0 for k sigma0²), got %g",
                        o->temperature);
    if (!(o->k >= 0.0) || !isfinite(o->k))
        return ft_error(FT_E_INVALID, "k must be > 0 (or 0 for the calibrated default), got %g", o->k);
    if (o->sweeps < 0 || o->sweeps > 1000)
        return ft_error(FT_E_INVALID, "sweeps (unused: the fractal method draws an exact sample) must be in "
                        "[0, 1000], got %d", o->sweeps);
    if (o->realizations < 1 || o->realizations > 1000000)
        return ft_error(FT_E_INVALID, "realizations must be >= 1, got %d", o->realizations);
    if (o->threads < 0)
        return ft_error(FT_E_INVALID, "threads must be >= 0, got %d", o->threads);
    return FT_OK;
}

static int thread_count(int requested)
{
    if (requested > 0)
        return requested;
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

/* The stochastic part never moves a data node: with soft data, their nodes become fixed at the smooth
 * solution's values (which weighed them against the prior) and the hierarchy is rebuilt. */
static int fix_soft_data(ft_recon_problem *p, const float *ustar, double lambda, double tension)
{
    ft_recon_level *L = &p->lev[0];
    size_t n = p->nx * p->ny, soft = 0;
    for (size_t i = 0; i < n; i++)
        if (L->c[i] > 0.0f) {
            L->fixed[i] = 1;
            L->c[i] = 0.0f;
            p->d[i] = ustar[i];
            soft++;
        }
    return soft ? ft_recon_hierarchy(p, lambda, tension) : FT_OK;
}

int ft_recon_run(ft_recon_problem *p, double lambda, double tension, const ft_recon_params *par, float *mean,
                 float *sd, size_t stride, const ft_recon_progress *prog)
{
    size_t nx = p->nx, ny = p->ny, n = nx * ny;
    /* the fractal method's prior is the multilevel one (recon_levels.c); the others keep level 0's */
    p->prior_H = par->method == FT_RECON_FRACTAL ? par->H : 0.0;
    int rc = ft_recon_hierarchy(p, lambda, tension);
    if (rc != FT_OK)
        return rc;
    int stochastic = par->method != FT_RECON_SMOOTH, nr = stochastic ? par->realizations : 1;
    /* one fractal realization on hard data: u* and the sample in one solve (recon_perturb.c) */
    int one_solve = par->method == FT_RECON_FRACTAL && nr == 1 && p->ndata == 0;
    double t_smooth = one_solve ? 0.0 : stochastic ? 0.15 : 1.0;
    float *ustar = ft_calloc(n, sizeof *ustar), *u = stochastic ? ft_malloc(n * sizeof *u) : NULL;
    double *acc = nr > 1 ? ft_calloc(2 * n, sizeof *acc) : NULL;
    if (ustar == NULL || (stochastic && u == NULL) || (nr > 1 && acc == NULL)) {
        rc = FT_E_NOMEM;
        goto done;
    }
    /* soft data: the solution at opts.lambda or, if it misses the data by more than their sigmas, at the
     * discrepancy principle's lambda (recon_discrepancy.c) */
    ft_recon_progress sp = ft_progress_range_sub(prog, 0.0, t_smooth);
    if (p->ndata > 0)
        rc = ft_recon_discrepancy(p, tension, &lambda, ustar, &sp, NULL);
    else if (!one_solve)
        rc = ft_recon_solve(p, ustar, &sp, NULL);
    if (rc == FT_OK && stochastic)
        rc = fix_soft_data(p, ustar, lambda, tension);
    for (int r = 0; rc == FT_OK && r < nr; r++) {
        const float *res = ustar;
        ft_recon_progress rp = ft_progress_range_sub(prog, t_smooth + (1.0 - t_smooth) * r / nr,
                                            t_smooth + (1.0 - t_smooth) * (r + 1) / nr);
        uint64_t seed = par->seed + (uint64_t)r;
        if (par->method == FT_RECON_FRACTAL)
            rc = ft_recon_fractal(p, one_solve ? NULL : ustar, par->T0, seed, u, &rp);
        else if (par->method == FT_RECON_CONDITIONAL)
            rc = ft_recon_conditional(p, ustar, par->H, par->amp, par->nugget, seed, u, &rp);
        if (stochastic)
            res = u;
        if (rc != FT_OK)
            break;
        if (nr == 1) {
            for (size_t y = 0; y < ny; y++)
                for (size_t x = 0; x < nx; x++) {
                    mean[y * stride + x] = res[y * nx + x];
                    if (sd)
                        sd[y * stride + x] = 0.0f;
                }
            break;
        }
        /* Welford: acc[2i] the running mean, acc[2i + 1] the sum of squared deviations */
        double inv = 1.0 / (double)(r + 1);
#pragma omp parallel for num_threads(ft_recon_threads(p->nthreads, n)) schedule(static)
        for (size_t i = 0; i < n; i++) {
            double v = res[i], d = v - acc[2 * i];
            acc[2 * i] += d * inv;
            acc[2 * i + 1] += d * (v - acc[2 * i]);
        }
    }
    if (rc == FT_OK && nr > 1)
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++) {
                size_t i = y * nx + x;
                mean[y * stride + x] = (float)acc[2 * i];
                if (sd)
                    sd[y * stride + x] = (float)sqrt(acc[2 * i + 1] / (double)(nr - 1));
            }
done:
    free(ustar);
    free(u);
    free(acc);
    return rc;
}

/* Bilinear interpolation of the grid between its cell centres at pixel position (col, row). */
static double bilinear_at(const ft_grid *g, double col, double row)
{
    double fx = fmin(fmax(col - 0.5, 0.0), (double)(g->nx - 1)), fy = fmin(fmax(row - 0.5, 0.0), (double)(g->ny - 1));
    size_t x0 = (size_t)fx, y0 = (size_t)fy;
    size_t x1 = x0 + 1 < g->nx ? x0 + 1 : x0, y1 = y0 + 1 < g->ny ? y0 + 1 : y0;
    double tx = fx - (double)x0, ty = fy - (double)y0;
    double a = g->z[y0 * g->nx + x0], b = g->z[y0 * g->nx + x1], c = g->z[y1 * g->nx + x0], d = g->z[y1 * g->nx + x1];
    return (1 - ty) * ((1 - tx) * a + tx * b) + ty * ((1 - tx) * c + tx * d);
}

static double data_rms(const ft_points *p, const ft_grid *g)
{
    double det = g->gt[1] * g->gt[5] - g->gt[2] * g->gt[4], s = 0.0;
    size_t m = 0;
    for (size_t i = 0; i < p->n; i++) {
        double dx = p->x[i] - g->gt[0], dy = p->y[i] - g->gt[3];
        double col = (g->gt[5] * dx - g->gt[2] * dy) / det, row = (-g->gt[4] * dx + g->gt[1] * dy) / det;
        if (!(col >= 0.0 && row >= 0.0 && col < (double)g->nx && row < (double)g->ny))
            continue;
        double e = bilinear_at(g, col, row) - p->z[i];
        s += e * e;
        m++;
    }
    return m ? sqrt(s / (double)m) : 0.0;
}

/* The points inside the target grid (the roughness is measured on the data used). */
static ft_points *points_inside(const ft_points *p, const ft_grid *g)
{
    ft_points *q = ft_points_create(p->n);
    if (q == NULL)
        return NULL;
    double det = g->gt[1] * g->gt[5] - g->gt[2] * g->gt[4];
    for (size_t i = 0; i < p->n; i++) {
        double dx = p->x[i] - g->gt[0], dy = p->y[i] - g->gt[3];
        double col = (g->gt[5] * dx - g->gt[2] * dy) / det, row = (-g->gt[4] * dx + g->gt[1] * dy) / det;
        if (!(col >= 0.0 && row >= 0.0 && col < (double)g->nx && row < (double)g->ny))
            continue;
        if (ft_points_push(q, p->x[i], p->y[i], p->z[i]) != FT_OK) {
            ft_points_free(q);
            return NULL;
        }
    }
    return q;
}

/* A grid shaped like `like` (size, geotransform, CRS), no mask. */
static ft_grid *grid_like(const ft_grid *like)
{
    ft_grid *g = ft_grid_create(like->nx, like->ny);
    if (g == NULL)
        return NULL;
    memcpy(g->gt, like->gt, sizeof g->gt);
    if (like->crs_wkt && ft_grid_set_crs(g, like->crs_wkt) != FT_OK) {
        ft_grid_free(g);
        return NULL;
    }
    return g;
}

int ft_recon_outputs(const ft_grid *like, int want_sd, ft_grid **out, ft_grid **sd_out)
{
    *out = grid_like(like);
    if (want_sd)
        *sd_out = grid_like(like);
    if (*out == NULL || (want_sd && *sd_out == NULL)) {
        ft_grid_free(*out);
        *out = NULL;
        if (want_sd) {
            ft_grid_free(*sd_out);
            *sd_out = NULL;
        }
        return FT_E_NOMEM;
    }
    return FT_OK;
}

/* The conditional method's small scales (mean |dz| at one cell, white share): from the closest pairs of
 * data nodes (the fixed nodes of `bound`, or dem's valid cells) when there are enough of them, else the
 * Yokoya line at one cell and no white part. */
static int conditional_small_scales(const ft_recon_line *yk, const ft_recon_problem *bound, const ft_grid *dem,
                                    double cell, ft_recon_params *par)
{
    int got = 0;
    par->nugget = 0.0;
    if (bound) {
        got = ft_recon_small_scales(bound->d, bound->lev[0].fixed, bound->nx, bound->ny, par->H, &par->amp,
                                    &par->nugget);
    } else if (dem) {
        size_t n = dem->nx * dem->ny;
        uint8_t *has = ft_malloc(n);
        if (has == NULL)
            return FT_E_NOMEM;
        for (size_t i = 0; i < n; i++)
            has[i] = (uint8_t)((dem->mask == NULL || dem->mask[i]) && isfinite(dem->z[i]));
        got = ft_recon_small_scales(dem->z, has, dem->nx, dem->ny, par->H, &par->amp, &par->nugget);
        free(has);
    }
    if (!got)
        par->amp = ft_recon_amplitude(yk, cell);
    return FT_OK;
}

int ft_recon_job_params(const ft_recon_opts *o, const ft_points *pts, const ft_grid *dem,
                        const ft_recon_problem *bound, double cell, ft_recon_params *par, ft_recon_info *info)
{
    *par = (ft_recon_params){.method = o->method,
                             .tension = o->tension,
                             .realizations = o->realizations,
                             .seed = o->seed};
    int tension_from_dim = o->tension == FT_RECON_TENSION_FROM_DIM;
    info->tension = o->tension;
    if (o->method == FT_RECON_SMOOTH) {
        /* the smooth method estimates nothing: its blend follows D when D is given, else the fixed one */
        info->dim = o->dim;
        if (tension_from_dim)
            par->tension = info->tension = o->dim > 0.0 ? ft_recon_tension_for_dim(o->dim) : FT_RECON_FRACTAL_TENSION;
        return FT_OK;
    }
    ft_recon_line yk = {0}, pe = {0};
    int need_yokoya = o->dim == 0.0 || o->method == FT_RECON_CONDITIONAL;
    int rc = FT_OK;
    if (need_yokoya)
        rc = pts ? ft_recon_fit_points(pts, 0, &yk) : ft_recon_fit_grid(dem, 0, &yk);
    if (rc != FT_OK)
        return rc;
    double D = o->dim;
    if (D == 0.0) {
        D = yk.D;
        info->dim_estimated = 1;
        if (!(D > 2.0 && D < 3.0))
            return ft_error(FT_E_NUMERIC, "the dimension estimated from the data, D = %.3f, is "
                            "outside (2, 3); give the dimension (opts->dim, --dim)", D);
    }
    info->dim = D;
    par->H = 3.0 - D;
    if (tension_from_dim)
        par->tension = info->tension =
            o->method == FT_RECON_FRACTAL ? ft_recon_fractal_tension(D) : ft_recon_tension_for_dim(D);
    if (o->method == FT_RECON_CONDITIONAL) {
        return conditional_small_scales(&yk, bound, dem, cell, par);
    }
    info->k = o->k > 0.0 ? o->k : FT_RECON_K_DEFAULT;
    if (o->temperature > 0.0) {
        par->T0 = o->temperature;
    } else {
        rc = pts ? ft_recon_fit_points(pts, 1, &pe) : ft_recon_fit_grid(dem, 1, &pe);
        if (rc != FT_OK)
            return rc;
        info->sigma0 = ft_recon_line_at(&pe, cell);
        par->T0 = ft_recon_fractal_gain(D) * ft_recon_temperature0(info->k, info->sigma0);
    }
    info->temperature = par->T0;
    return FT_OK;
}

int ft_recon_begin(const ft_recon_opts *opts, ft_recon_opts *o, ft_recon_info *info, ft_grid **out,
                   ft_grid **sd_out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "output pointer is NULL");
    *out = NULL;
    if (sd_out)
        *sd_out = NULL;
    *o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(*o, opts, ft_recon_opts) != FT_OK)
        return FT_E_INVALID;
    memset(info, 0, sizeof *info);
    o->threads = thread_count(o->threads);
    return check_opts(o);
}

int ft_recon_end(int rc, const ft_recon_info *inf, ft_recon_info *info, ft_grid **out, ft_grid **sd_out)
{
    if (rc != FT_OK) {
        ft_grid_free(*out);
        *out = NULL;
        if (sd_out) {
            ft_grid_free(*sd_out);
            *sd_out = NULL;
        }
        return rc;
    }
    if (info)
        *info = *inf;
    return FT_OK;
}

int ft_reconstruct_points(const ft_points *p, const ft_grid *target, const ft_recon_opts *opts, ft_grid **out,
                          ft_grid **sd_out, ft_recon_info *info)
{
    ft_recon_opts o;
    ft_recon_info inf;
    int rc = ft_recon_begin(opts, &o, &inf, out, sd_out);
    if (rc != FT_OK)
        return rc;
    if (target == NULL || target->nx == 0 || target->ny == 0)
        return ft_error(FT_E_INVALID, "the target grid is NULL or empty");
    if (target->nx > ((size_t)1 << 20) || target->ny > ((size_t)1 << 20))
        return ft_error(FT_E_INVALID, "target grid %zu x %zu is too large", target->nx, target->ny);
    ft_recon_progress prog = ft_progress_range_whole(o.progress, o.progress_arg);
    ft_recon_problem *pr = NULL;
    size_t outside = 0;
    rc = ft_recon_bind_points(p, target, o.sigma, o.threads, &pr, &outside);
    if (rc != FT_OK)
        return rc;
    double cell = sqrt(fabs(target->gt[1] * target->gt[5] - target->gt[2] * target->gt[4]));
    ft_recon_params par;
    ft_points *inside = outside ? points_inside(p, target) : NULL;
    if (outside && inside == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = ft_recon_job_params(&o, inside ? inside : p, NULL, pr, cell, &par, &inf);
    ft_points_free(inside);
    if (rc == FT_OK)
        rc = ft_recon_report(&prog, 0.02, "reconstruct: roughness of the data");
    if (rc == FT_OK)
        rc = ft_recon_outputs(target, sd_out != NULL, out, sd_out);
    if (rc == FT_OK) {
        ft_recon_progress rp = ft_progress_range_sub(&prog, 0.02, 1.0);
        rc = ft_recon_run(pr, o.lambda, par.tension, &par, (*out)->z, sd_out ? (*sd_out)->z : NULL, target->nx, &rp);
    }
    if (rc == FT_OK) {
        inf.levels = pr->nlev;
        inf.lambda = pr->lambda;
        size_t n = pr->nx * pr->ny, used = 0;
        for (size_t i = 0; i < n; i++)
            used += pr->lev[0].fixed[i] || pr->lev[0].c[i] > 0.0f;
        inf.data_used = p->n - outside;
        inf.data_outside = outside;
        inf.filled = n - used;
        inf.data_rms = data_rms(p, *out);
        rc = ft_progress(o.progress, o.progress_arg, 1.0, "reconstruct: done");
    }
    ft_recon_problem_free(pr);
    return ft_recon_end(rc, &inf, info, out, sd_out);
}
