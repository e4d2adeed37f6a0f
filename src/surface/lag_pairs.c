/* fracterra — lag_pairs.c: the pairs of grid cells at integer lags, shared by the variogram (Mark &
 * Aronson 1984), Yokoya's and Pentland's estimators (Arakawa & Krotkov, "Fractal modeling of natural
 * terrain", §2.3-2.4).
 *
 * For every lag the counters of §2.4 step 1 are accumulated over the pairs: A = Σ|Δz|, B = Σ(Δz)²,
 * C = the number of pairs, and the sum of the pairs' ground distances (the table's scale is their mean).
 * Lags are whole numbers of cells, a geometric series from min_lag to max_lag with duplicates after
 * rounding removed.
 *  - Exhaustive (pairs == 0): every pair of cells `lag` apart along a row or along a column (the two axis
 *    directions; diagonals are not used) whose midpoint lies at least max_lag / 2 from the edges along
 *    its axis, the same band for every lag.
 *  - Random (pairs = N): Mark & Aronson's sampling: N points uniform inside the largest circle inscribed
 *    in the grid, each paired at every lag with the cell nearest to the point lag cells away in a random
 *    direction (the partner must lie inside the circle). One RNG stream per block of 256 points.
 * Pairs touching a nodata or non-finite cell are skipped. Per-row (per-block) partial sums are reduced in
 * order, so the result does not depend on the thread count. docs/surface-variogram.md, docs/surface-grid.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "surface/grid_internal.h"

#define RANDOM_BLOCK 256
#define STREAM_VARIOGRAM UINT64_C(0x5600000000)

static void acc_add(ft_lag_acc *acc, double d, double dist)
{
    acc->a += fabs(d);
    acc->b += d * d;
    acc->c += 1.0;
    acc->dist += dist;
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

/* The grid's elevations with invalid cells set to 0 (so that 0 x NaN never happens) and their weights
 * (1 valid, 0 not), made once for the exhaustive pairs: the pair loops are then branch-free. */
static int sanitize_grid(const ft_grid *g, float **z, float **w)
{
    size_t n = g->nx * g->ny;
    *z = ft_malloc(n * sizeof **z);
    *w = ft_malloc(n * sizeof **w);
    if (*z == NULL || *w == NULL) {
        free(*z);
        free(*w);
        return FT_E_NOMEM;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        int ok = ft_surface_cell_ok(g, i);
        (*z)[i] = ok ? g->z[i] : 0.0f;
        (*w)[i] = (float)ok;
    }
    return FT_OK;
}

/* Σ over j < n of the pairs (zp[j], zq[j]) weighted by wp[j] wq[j] (grid_internal.h), branch-free with four
 * interleaved sets of sums (added in a fixed order, so the result depends on the input only). */
void ft_lag_pair_sums(const float *zp, const float *wp, const float *zq, const float *wq, size_t n, ft_lag_acc *acc)
{
    double a[4] = {0.0, 0.0, 0.0, 0.0}, b[4] = {0.0, 0.0, 0.0, 0.0}, c[4] = {0.0, 0.0, 0.0, 0.0};
    size_t j = 0;
    for (; j + 3 < n; j += 4)
        for (int l = 0; l < 4; l++) {
            double d = (double)zq[j + l] - (double)zp[j + l], w = (double)(wp[j + l] * wq[j + l]);
            a[l] += w * fabs(d);
            b[l] += w * d * d;
            c[l] += w;
        }
    for (; j < n; j++) {
        double d = (double)zq[j] - (double)zp[j], w = (double)(wp[j] * wq[j]);
        a[0] += w * fabs(d);
        b[0] += w * d * d;
        c[0] += w;
    }
    acc->a += (a[0] + a[1]) + (a[2] + a[3]);
    acc->b += (b[0] + b[1]) + (b[2] + b[3]);
    acc->c += (c[0] + c[1]) + (c[2] + c[3]);
}

/* Exhaustive pairs whose upper (column pairs) or left (row pairs) cell is in row i, on the sanitized grid
 * (z, w). A pair counts only if its midpoint lies at least hmax / 2 cells from the edges along the pair's
 * axis, hmax the largest lag: every lag then samples the same central band, so a trend or a bowl is seen
 * alike at every lag (without it, long lags see only the middle of a paraboloid, flatter than its edges,
 * and D drifts above 2). In doubled coordinates the midpoint 2j + h must lie in [hmax, 2(n - 1) - hmax]. */
static void exhaustive_row(const ft_grid *g, const float *z, const float *w, size_t i, const size_t *lags,
                           size_t nl, double cx, double cy, ft_lag_acc *acc)
{
    size_t nx = g->nx, ny = g->ny, hmax = lags[nl - 1];
    const float *zi = z + i * nx, *wi = w + i * nx;
    for (size_t k = 0; k < nl; k++) {
        size_t h = lags[k], j0 = (hmax - h + 1) / 2;
        ft_lag_acc r = {0.0, 0.0, 0.0, 0.0}, c = {0.0, 0.0, 0.0, 0.0};
        /* j from j0 to jmax = (2(nx - 1) - h - hmax) / 2; none when hmax reaches past a row (nx < ny) */
        if (h + hmax <= 2 * (nx - 1) && (2 * (nx - 1) - h - hmax) / 2 >= j0)
            ft_lag_pair_sums(zi + j0, wi + j0, zi + j0 + h, wi + j0 + h, (2 * (nx - 1) - h - hmax) / 2 + 1 - j0, &r);
        if (2 * i + h >= hmax && 2 * i + h + hmax <= 2 * (ny - 1))
            ft_lag_pair_sums(zi, wi, zi + h * nx, wi + h * nx, nx, &c);
        acc[k] = (ft_lag_acc){r.a + c.a, r.b + c.b, r.c + c.c, (double)h * (r.c * cx + c.c * cy)};
    }
}

/* One block of random points: each point in the inscribed circle, paired at every lag. */
static int random_block(const ft_grid *g, size_t block, size_t npts, uint64_t seed, const size_t *lags,
                        size_t nl, double cx, double cy, ft_lag_acc *acc)
{
    ft_rng *r = ft_rng_create(seed, STREAM_VARIOGRAM + block);
    if (r == NULL)
        return FT_E_NOMEM;
    double xc = 0.5 * (double)(g->nx - 1), yc = 0.5 * (double)(g->ny - 1);
    double rad = 0.5 * (double)((g->nx < g->ny ? g->nx : g->ny) - 1), rad2 = (rad + 0.5) * (rad + 0.5);
    for (size_t k = 0; k < nl; k++)
        acc[k] = (ft_lag_acc){0.0, 0.0, 0.0, 0.0};
    for (size_t p = 0; p < npts; p++) {
        double u, v;
        do {
            u = 2.0 * ft_rng_uniform(r) - 1.0;
            v = 2.0 * ft_rng_uniform(r) - 1.0;
        } while (u * u + v * v > 1.0);
        long px = lround(xc + rad * u), py = lround(yc + rad * v);
        size_t a = (size_t)py * g->nx + (size_t)px;
        int a_ok = ft_surface_cell_ok(g, a);
        for (size_t k = 0; k < nl; k++) {
            double th = 2.0 * M_PI * ft_rng_uniform(r);
            long qx = lround((double)px + (double)lags[k] * cos(th));
            long qy = lround((double)py + (double)lags[k] * sin(th));
            double ex = (double)qx - xc, ey = (double)qy - yc;
            if (!a_ok || qx < 0 || qy < 0 || (size_t)qx >= g->nx || (size_t)qy >= g->ny || ex * ex + ey * ey > rad2)
                continue;
            size_t b = (size_t)qy * g->nx + (size_t)qx;
            if (ft_surface_cell_ok(g, b))
                acc_add(&acc[k], (double)g->z[b] - (double)g->z[a],
                        hypot((double)(qx - px) * cx, (double)(qy - py) * cy));
        }
    }
    ft_rng_free(r);
    return FT_OK;
}

/* Per-row or per-block partials (nparts x nl), computed in parallel, summed in order into tot. */
static int accumulate(const ft_grid *g, const ft_variogram_opts *o, const char *name, const size_t *lags,
                      size_t nl, double cx, double cy, ft_lag_acc *tot)
{
    size_t nparts = o->pairs ? (o->pairs + RANDOM_BLOCK - 1) / RANDOM_BLOCK : g->ny;
    ft_lag_acc *part = ft_calloc(nparts * nl, sizeof *part);
    if (part == NULL)
        return FT_E_NOMEM;
    float *z = NULL, *w = NULL;
    if (!o->pairs && sanitize_grid(g, &z, &w) != FT_OK) {
        free(part);
        return FT_E_NOMEM;
    }
    int failed = 0;
#pragma omp parallel for schedule(dynamic, 4) reduction(| : failed)
    for (size_t p = 0; p < nparts; p++) {
        if (o->pairs) {
            size_t npts = (p + 1) * RANDOM_BLOCK <= o->pairs ? RANDOM_BLOCK : o->pairs - p * RANDOM_BLOCK;
            failed |= random_block(g, p, npts, o->seed, lags, nl, cx, cy, part + p * nl) != FT_OK;
        } else {
            exhaustive_row(g, z, w, p, lags, nl, cx, cy, part + p * nl);
        }
    }
    free(z);
    free(w);
    for (size_t k = 0; k < nl; k++)
        tot[k] = (ft_lag_acc){0.0, 0.0, 0.0, 0.0};
    for (size_t p = 0; p < nparts; p++)
        for (size_t k = 0; k < nl; k++) {
            const ft_lag_acc *q = &part[p * nl + k];
            tot[k] = (ft_lag_acc){tot[k].a + q->a, tot[k].b + q->b, tot[k].c + q->c, tot[k].dist + q->dist};
        }
    free(part);
    return failed ? ft_error(FT_E_NOMEM, "%s: out of memory", name) : FT_OK;
}

/* The options against an nx x ny grid, and the lag range in cells. */
static int check_opts(size_t nx, size_t ny, const ft_variogram_opts *o, const char *name, double *lo, double *hi)
{
    if (!(o->min_lag >= 0.0) || !isfinite(o->min_lag))
        return ft_error(FT_E_INVALID, "%s: min_lag must be >= 0 cells, got %g", name, o->min_lag);
    if (!(o->max_lag >= 0.0) || !isfinite(o->max_lag))
        return ft_error(FT_E_INVALID, "%s: max_lag must be >= 0 cells, got %g", name, o->max_lag);
    if (o->nlags < 0 || o->nlags > 10000)
        return ft_error(FT_E_INVALID, "%s: nlags must be in [0, 10000], got %d", name, o->nlags);
    size_t small = nx < ny ? nx : ny, big = nx > ny ? nx : ny;
    double limit = o->pairs ? (double)(small - 1) : (double)(big - 1);
    *lo = o->min_lag > 0.0 ? o->min_lag : 1.0;
    *hi = o->max_lag > 0.0 ? o->max_lag : floor((double)small / 8.0);
    if (*lo < 1.0)
        *lo = 1.0;
    if (*hi > limit)
        return ft_error(FT_E_INVALID, "%s: max_lag %g cells exceeds the %s (%g cells)", name, *hi,
                        o->pairs ? "inscribed circle's diameter" : "grid", limit);
    if (llround(*hi) <= llround(*lo))
        return ft_error(FT_E_INVALID, "%s: needs at least two lags, got min_lag %g and max_lag %g cells "
                        "on a %zux%zu grid", name, *lo, *hi, nx, ny);
    return FT_OK;
}

/* The statistic of one lag's counters; 0 when it cannot be formed. */
static double lag_value(const ft_lag_acc *a, ft_lag_stat stat)
{
    if (a->c <= 0.0)
        return 0.0;
    if (stat == FT_LAG_STAT_MEAN_SQ)
        return a->b / a->c;
    if (stat == FT_LAG_STAT_MEAN_ABS)
        return a->a / a->c;
    if (a->c < 2.0)
        return 0.0;
    double ss = a->b - a->a * a->a / a->c; /* Σ(|Δz| - mean)² */
    return ss > 0.0 ? sqrt(ss / (a->c - 1.0)) : 0.0;
}

static int build_table(const size_t *lags, const ft_lag_acc *tot, size_t nl, ft_lag_stat stat, const char *name,
                       ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create(nl);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t k = 0; k < nl && rc == FT_OK; k++) {
        double v = lag_value(&tot[k], stat);
        if (v > 0.0)
            rc = ft_loglog_push(t, tot[k].dist / tot[k].c, v, tot[k].c);
    }
    if (rc == FT_OK)
        rc = ft_loglog_sort(t);
    if (rc == FT_OK && t->n < 2)
        rc = ft_error(FT_E_EMPTY, "%s: fewer than two lags (of %zu, up to %zu cells) have valid pairs "
                      "with a non-zero difference (flat or nodata-only grid)", name, nl, lags[nl - 1]);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

int ft_surface_lag_plan(size_t nx, size_t ny, const ft_variogram_opts *o, const char *name, size_t **lags,
                        size_t *nl)
{
    *lags = NULL;
    *nl = 0;
    double lo = 1.0, hi = 0.0;
    int rc = check_opts(nx, ny, o, name, &lo, &hi);
    if (rc != FT_OK)
        return rc;
    int cap = o->nlags > 0 ? o->nlags : 4 * (int)ceil(log2(hi / lo)) + 1;
    if ((*lags = ft_malloc((size_t)cap * sizeof **lags)) == NULL)
        return FT_E_NOMEM;
    *nl = make_lags(lo, hi, o->nlags, *lags);
    return FT_OK;
}

int ft_surface_lag_fit(const size_t *lags, const ft_lag_acc *tot, size_t nl, const ft_variogram_opts *o,
                       ft_lag_stat stat, const char *name, const ft_dim_map *map, ft_dim_result **out)
{
    ft_loglog *t = NULL;
    int rc = build_table(lags, tot, nl, stat, name, &t);
    if (rc == FT_OK) /* the nugget (white noise on z) detected and removed: nugget_fit.c */
        rc = ft_surface_fit_noise(t, &o->noise, (ft_structure_stat)stat, o->fit_whole_range, &o->fit, map, out);
    if (rc == FT_OK)
        (*out)->method = name;
    ft_loglog_free(t);
    return rc;
}

int ft_surface_lag_dim(const ft_grid *g, const ft_variogram_opts *opts, ft_lag_stat stat, const char *name,
                       const ft_dim_map *map, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "%s: output pointer is NULL", name);
    *out = NULL;
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "%s: the grid is NULL or empty", name);
    ft_variogram_opts o = FT_VARIOGRAM_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_variogram_opts) != FT_OK)
        return FT_E_INVALID;
    size_t *lags = NULL, nl = 0;
    int rc = ft_surface_lag_plan(g->nx, g->ny, &o, name, &lags, &nl);
    if (rc != FT_OK)
        return rc;
    ft_lag_acc *tot = ft_malloc(nl * sizeof *tot);
    if (tot == NULL) {
        free(lags);
        return FT_E_NOMEM;
    }
    double cx, cy;
    ft_surface_cell_size(g, &cx, &cy);
    rc = ft_progress(o.progress, o.progress_arg, 0.0, name);
    if (rc == FT_OK)
        rc = accumulate(g, &o, name, lags, nl, cx, cy, tot);
    if (rc == FT_OK)
        rc = ft_surface_lag_fit(lags, tot, nl, &o, stat, name, map, out);
    if (rc == FT_OK) {
        rc = ft_progress(o.progress, o.progress_arg, 1.0, name);
        if (rc != FT_OK) {
            ft_dim_result_free(*out);
            *out = NULL;
        }
    }
    free(lags);
    free(tot);
    return rc;
}
