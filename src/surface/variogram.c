/* fracterra — variogram.c: the variogram dimension of an elevation grid (Mark & Aronson 1984, "Scale-
 * dependent fractal dimensions of topographic surfaces", Math. Geology 16(7); Clarke's survey, seeds 004).
 *
 * For fBm, E(z(x + d) - z(x))^2 ~ d^(2H), so the slope s of log mean squared difference against log lag
 * gives H = s/2 and D = 3 - s/2 (FT_DIM_MAP_VARIOGRAM_SURFACE). Lags are whole numbers of cells, a
 * geometric series from min_lag to max_lag with duplicates after rounding removed.
 *  - Exhaustive (pairs == 0): every pair of cells `lag` apart along a row or along a column (the two axis
 *    directions; diagonals are not used). The row's scale is the mean ground distance of its pairs
 *    (lag x the cell size when cells are square).
 *  - Random (pairs = N): Mark & Aronson's sampling: N points uniform inside the largest circle inscribed
 *    in the grid, each paired at every lag with the cell nearest to the point lag cells away in a random
 *    direction (the partner must lie inside the circle); the row's scale is the mean ground distance of
 *    the pairs actually formed. One RNG stream per block of 256 points.
 * Pairs touching a nodata or non-finite cell are skipped. Per-row (per-block) partial sums are reduced in
 * order, so the result does not depend on the thread count. docs/surface-variogram.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "fracterra/surface.h"
#include "internal.h"

#define RANDOM_BLOCK 256
#define STREAM_VARIOGRAM UINT64_C(0x5600000000)

/* Accumulators of one lag: sum of squared differences, pairs, sum of ground distances. */
typedef struct {
    double sq, n, dist;
} lag_acc;

static int cell_ok(const ft_grid *g, size_t i)
{
    return (g->mask == NULL || g->mask[i]) && isfinite(g->z[i]);
}

/* Integer lags of the geometric series from lo to hi (cells), duplicates removed; returns the count. */
static size_t make_lags(double lo, double hi, int nlags, size_t *lags)
{
    if (nlags <= 0)
        nlags = 4 * (int)ceil(log2(hi / lo)) + 1;
    size_t n = 0;
    for (int k = 0; k < nlags; k++) {
        double v = nlags == 1 ? lo : lo * pow(hi / lo, (double)k / (double)(nlags - 1));
        size_t l = (size_t)llround(v);
        if (l < 1)
            l = 1;
        if (n == 0 || l > lags[n - 1])
            lags[n++] = l;
    }
    return n;
}

static void exhaustive_row(const ft_grid *g, size_t i, const size_t *lags, size_t nl, double cx, double cy,
                           lag_acc *acc)
{
    size_t nx = g->nx, ny = g->ny;
    const float *z = g->z;
    for (size_t k = 0; k < nl; k++) {
        size_t h = lags[k];
        double sq = 0.0, nr = 0.0, nc = 0.0;
        for (size_t j = 0; j + h < nx; j++) {
            size_t a = i * nx + j, b = a + h;
            if (cell_ok(g, a) && cell_ok(g, b)) {
                double d = (double)z[b] - (double)z[a];
                sq += d * d;
                nr += 1.0;
            }
        }
        if (i + h < ny)
            for (size_t j = 0; j < nx; j++) {
                size_t a = i * nx + j, b = a + h * nx;
                if (cell_ok(g, a) && cell_ok(g, b)) {
                    double d = (double)z[b] - (double)z[a];
                    sq += d * d;
                    nc += 1.0;
                }
            }
        acc[k].sq = sq;
        acc[k].n = nr + nc;
        acc[k].dist = (double)h * (nr * cx + nc * cy);
    }
}

/* One block of random points: each point in the inscribed circle, paired at every lag. */
static int random_block(const ft_grid *g, size_t block, size_t npts, uint64_t seed, const size_t *lags,
                        size_t nl, double cx, double cy, lag_acc *acc)
{
    ft_rng *r = ft_rng_create(seed, STREAM_VARIOGRAM + block);
    if (r == NULL)
        return FT_E_NOMEM;
    double xc = 0.5 * (double)(g->nx - 1), yc = 0.5 * (double)(g->ny - 1);
    double rad = 0.5 * (double)((g->nx < g->ny ? g->nx : g->ny) - 1), rad2 = (rad + 0.5) * (rad + 0.5);
    for (size_t k = 0; k < nl; k++)
        acc[k] = (lag_acc){0.0, 0.0, 0.0};
    for (size_t p = 0; p < npts; p++) {
        double u, v;
        do {
            u = 2.0 * ft_rng_uniform(r) - 1.0;
            v = 2.0 * ft_rng_uniform(r) - 1.0;
        } while (u * u + v * v > 1.0);
        long px = lround(xc + rad * u), py = lround(yc + rad * v);
        size_t a = (size_t)py * g->nx + (size_t)px;
        int a_ok = cell_ok(g, a);
        for (size_t k = 0; k < nl; k++) {
            double th = 2.0 * M_PI * ft_rng_uniform(r);
            long qx = lround((double)px + (double)lags[k] * cos(th));
            long qy = lround((double)py + (double)lags[k] * sin(th));
            double ex = (double)qx - xc, ey = (double)qy - yc;
            if (!a_ok || qx < 0 || qy < 0 || (size_t)qx >= g->nx || (size_t)qy >= g->ny || ex * ex + ey * ey > rad2)
                continue;
            size_t b = (size_t)qy * g->nx + (size_t)qx;
            if (!cell_ok(g, b))
                continue;
            double d = (double)g->z[b] - (double)g->z[a];
            acc[k].sq += d * d;
            acc[k].n += 1.0;
            acc[k].dist += hypot((double)(qx - px) * cx, (double)(qy - py) * cy);
        }
    }
    ft_rng_free(r);
    return FT_OK;
}

/* Per-row or per-block partials (nparts x nl), computed in parallel, summed in order into tot. */
static int accumulate(const ft_grid *g, const ft_variogram_opts *o, const size_t *lags, size_t nl, double cx,
                      double cy, lag_acc *tot)
{
    size_t nparts = o->pairs ? (o->pairs + RANDOM_BLOCK - 1) / RANDOM_BLOCK : g->ny;
    lag_acc *part = ft_calloc(nparts * nl, sizeof *part);
    if (part == NULL)
        return FT_E_NOMEM;
    int failed = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(| : failed)
    for (size_t p = 0; p < nparts; p++) {
        if (o->pairs) {
            size_t npts = (p + 1) * RANDOM_BLOCK <= o->pairs ? RANDOM_BLOCK : o->pairs - p * RANDOM_BLOCK;
            failed |= random_block(g, p, npts, o->seed, lags, nl, cx, cy, part + p * nl) != FT_OK;
        } else {
            exhaustive_row(g, p, lags, nl, cx, cy, part + p * nl);
        }
    }
    for (size_t k = 0; k < nl; k++)
        tot[k] = (lag_acc){0.0, 0.0, 0.0};
    for (size_t p = 0; p < nparts; p++)
        for (size_t k = 0; k < nl; k++) {
            tot[k].sq += part[p * nl + k].sq;
            tot[k].n += part[p * nl + k].n;
            tot[k].dist += part[p * nl + k].dist;
        }
    free(part);
    return failed ? ft_error(FT_E_NOMEM, "variogram: out of memory") : FT_OK;
}

static int check_opts(const ft_grid *g, const ft_variogram_opts *o, double *lo, double *hi)
{
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "variogram: the grid is NULL or empty");
    if (!(o->min_lag >= 0.0) || !isfinite(o->min_lag))
        return ft_error(FT_E_INVALID, "variogram: min_lag must be >= 0 cells, got %g", o->min_lag);
    if (!(o->max_lag >= 0.0) || !isfinite(o->max_lag))
        return ft_error(FT_E_INVALID, "variogram: max_lag must be >= 0 cells, got %g", o->max_lag);
    if (o->nlags < 0 || o->nlags > 10000)
        return ft_error(FT_E_INVALID, "variogram: nlags must be in [0, 10000], got %d", o->nlags);
    size_t small = g->nx < g->ny ? g->nx : g->ny, big = g->nx > g->ny ? g->nx : g->ny;
    double limit = o->pairs ? (double)(small - 1) : (double)(big - 1);
    *lo = o->min_lag > 0.0 ? o->min_lag : 1.0;
    *hi = o->max_lag > 0.0 ? o->max_lag : floor((double)small / 8.0);
    if (*lo < 1.0)
        *lo = 1.0;
    if (*hi > limit)
        return ft_error(FT_E_INVALID, "variogram: max_lag %g cells exceeds the %s (%g cells)", *hi,
                        o->pairs ? "inscribed circle's diameter" : "grid", limit);
    if (llround(*hi) <= llround(*lo))
        return ft_error(FT_E_INVALID, "variogram: needs at least two lags, got min_lag %g and max_lag %g cells "
                        "on a %zux%zu grid", *lo, *hi, g->nx, g->ny);
    return FT_OK;
}

static int build_table(const size_t *lags, const lag_acc *tot, size_t nl, ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create(nl);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t k = 0; k < nl && rc == FT_OK; k++)
        if (tot[k].n > 0.0 && tot[k].sq > 0.0)
            rc = ft_loglog_push(t, tot[k].dist / tot[k].n, tot[k].sq / tot[k].n, tot[k].n);
    if (rc == FT_OK)
        rc = ft_loglog_sort(t);
    if (rc == FT_OK && t->n < 2)
        rc = ft_error(FT_E_EMPTY, "variogram: fewer than two lags (of %zu, up to %zu cells) have valid pairs "
                      "with a non-zero difference (flat or nodata-only grid)", nl, lags[nl - 1]);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

int ft_surface_dim_variogram(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "variogram: output pointer is NULL");
    *out = NULL;
    ft_variogram_opts o = FT_VARIOGRAM_OPTS_DEFAULT;
    if (opts != NULL)
        o = *opts;
    double lo = 1.0, hi = 0.0;
    int rc = check_opts(g, &o, &lo, &hi);
    if (rc != FT_OK)
        return rc;
    int cap = o.nlags > 0 ? o.nlags : 4 * (int)ceil(log2(hi / lo)) + 1;
    size_t *lags = ft_malloc((size_t)cap * sizeof *lags);
    lag_acc *tot = ft_malloc((size_t)cap * sizeof *tot);
    ft_loglog *t = NULL;
    if (lags == NULL || tot == NULL) {
        rc = FT_E_NOMEM;
        goto done;
    }
    size_t nl = make_lags(lo, hi, o.nlags, lags);
    double cx = hypot(g->gt[1], g->gt[4]), cy = hypot(g->gt[2], g->gt[5]);
    rc = ft_progress(o.progress, o.progress_arg, 0.0, "variogram");
    if (rc == FT_OK)
        rc = accumulate(g, &o, lags, nl, cx, cy, tot);
    if (rc == FT_OK)
        rc = build_table(lags, tot, nl, &t);
    ft_dim_map map = FT_DIM_MAP_VARIOGRAM_SURFACE;
    if (rc == FT_OK)
        rc = o.fit_whole_range ? ft_loglog_fit_range(t, 0.0, 0.0, &map, out)
                               : ft_loglog_fit_auto(t, 0.0, 0.0, &o.fit, &map, out);
    if (rc == FT_OK) {
        (*out)->method = "variogram";
        rc = ft_progress(o.progress, o.progress_arg, 1.0, "variogram");
        if (rc != FT_OK) {
            ft_dim_result_free(*out);
            *out = NULL;
        }
    }
done:
    ft_loglog_free(t);
    free(lags);
    free(tot);
    return rc;
}
