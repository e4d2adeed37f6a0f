/* fracterra — lag_stripes.c: the exhaustive lag estimators (variogram, Yokoya, Pentland; lag_pairs.c, after
 * Mark & Aronson 1984 and Arakawa & Krotkov §2.4) of a grid too large for memory, stripe by stripe.
 *
 * The counters A = Σ|Δz|, B = Σ(Δz)², C = pairs and the summed pair distances are additive over the pairs.
 * The whole-grid estimate (lag_pairs.c) sums, for every row i, the pairs whose left (row pairs) or upper
 * (column pairs) cell lies in row i, then adds the rows' partial sums in row order. Here the same per-row
 * partials are formed from a stripe of rows [r0, r1) that also holds the largest lag's rows below it (the
 * halo), with the same pair band (midpoints at least max_lag / 2 from the grid's edges, in global rows and
 * columns), the same pair-sum kernel (ft_lag_pair_sums) and the same order of additions; the caller adds
 * the stripes' rows in global row order (ft_surface_lag_stripes_add refuses any other), so the counters,
 * the table and D are bit for bit those of ft_surface_dim on the whole grid, for any stripe height, in one
 * process or across MPI ranks. docs/tiling.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "surface/grid_internal.h"

struct ft_lag_stripes {
    size_t nx, ny;      /* the whole grid */
    double cx, cy;      /* its cell sizes, ground units */
    ft_variogram_opts v;
    ft_lag_stat stat;
    ft_dim_map map;
    const char *name;
    size_t *lags, nl;
    ft_lag_acc *tot;    /* rows 0 .. next_row - 1 added */
    size_t next_row;
};

void ft_surface_lag_stripes_free(ft_lag_stripes *s)
{
    if (s == NULL)
        return;
    free(s->lags);
    free(s->tot);
    free(s);
}

int ft_surface_lag_stripes_create(const ft_grid *header, ft_surface_method m, const ft_surface_dim_opts *opts,
                                  ft_lag_stripes **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "lag stripes: output pointer is NULL");
    *out = NULL;
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    if (opts != NULL)
        o = *opts;
    if (header == NULL || header->nx == 0 || header->ny == 0)
        return ft_error(FT_E_INVALID, "lag stripes: the grid header is NULL or empty");
    if (m != FT_SURFACE_VARIOGRAM && m != FT_SURFACE_YOKOYA && m != FT_SURFACE_PENTLAND)
        return ft_error(FT_E_UNSUPPORTED, "%s cannot be measured stripe by stripe: only the exhaustive lag methods "
                        "(variogram, yokoya, pentland) can", ft_surface_method_name(m));
    if (o.pairs != 0)
        return ft_error(FT_E_UNSUPPORTED, "%s: random pairs (pairs = %zu) cannot be drawn stripe by stripe; use "
                        "every pair (pairs = 0)", ft_surface_method_name(m), o.pairs);
    ft_lag_stripes *s = ft_calloc(1, sizeof *s);
    if (s == NULL)
        return FT_E_NOMEM;
    s->nx = header->nx;
    s->ny = header->ny;
    s->name = ft_surface_method_name(m);
    s->stat = m == FT_SURFACE_VARIOGRAM ? FT_LAG_STAT_MEAN_SQ : m == FT_SURFACE_YOKOYA ? FT_LAG_STAT_MEAN_ABS
                                                                                     : FT_LAG_STAT_SD_ABS;
    s->map = m == FT_SURFACE_VARIOGRAM ? (ft_dim_map)FT_DIM_MAP_VARIOGRAM_SURFACE
                                       : (ft_dim_map)FT_DIM_MAP_INCREMENT_SURFACE;
    ft_surface_cell_size(header, &s->cx, &s->cy);
    int rc = ft_surface_lag_opts(&o, s->cx, s->cy, &s->v);
    if (rc == FT_OK)
        rc = ft_surface_lag_plan(s->nx, s->ny, &s->v, s->name, &s->lags, &s->nl);
    if (rc == FT_OK && (s->tot = ft_calloc(s->nl, sizeof *s->tot)) == NULL)
        rc = FT_E_NOMEM;
    if (rc != FT_OK) {
        ft_surface_lag_stripes_free(s);
        return rc;
    }
    *out = s;
    return FT_OK;
}

size_t ft_surface_lag_stripes_halo(const ft_lag_stripes *s)
{
    return s ? s->lags[s->nl - 1] : 0;
}

size_t ft_surface_lag_stripes_nsums(const ft_lag_stripes *s)
{
    return s ? 4 * s->nl : 0;
}

/* The pairs of global row i at lag k (zi, wi: its sanitized cells; zh, wh: those of row i + h, read only
 * when the row has column pairs at that lag), as exhaustive_row of lag_pairs.c forms them. */
static void lag_row_sums(const ft_lag_stripes *s, size_t k, const float *zi, const float *wi, const float *zh,
                         const float *wh, size_t i, double *acc)
{
    size_t nx = s->nx, ny = s->ny, hmax = s->lags[s->nl - 1];
    size_t h = s->lags[k], j0 = (hmax - h + 1) / 2;
    ft_lag_acc r = {0.0, 0.0, 0.0, 0.0}, c = {0.0, 0.0, 0.0, 0.0};
    if (h + hmax <= 2 * (nx - 1) && (2 * (nx - 1) - h - hmax) / 2 >= j0)
        ft_lag_pair_sums(zi + j0, wi + j0, zi + j0 + h, wi + j0 + h, (2 * (nx - 1) - h - hmax) / 2 + 1 - j0, &r);
    if (2 * i + h >= hmax && 2 * i + h + hmax <= 2 * (ny - 1)) /* then i + h < ny */
        ft_lag_pair_sums(zi, wi, zh, wh, nx, &c);
    acc[4 * k] = r.a + c.a;
    acc[4 * k + 1] = r.b + c.b;
    acc[4 * k + 2] = r.c + c.c;
    acc[4 * k + 3] = (double)h * (r.c * s->cx + c.c * s->cy);
}

/* Every lag of global row i; the rows below it follow at stride nx. */
static void row_sums(const ft_lag_stripes *s, const float *zi, const float *wi, size_t i, double *acc)
{
    for (size_t k = 0; k < s->nl; k++)
        lag_row_sums(s, k, zi, wi, zi + s->lags[k] * s->nx, wi + s->lags[k] * s->nx, i, acc);
}

/* The sanitized cells (0 where not valid) and weights of rows [first, first + rows) of g. */
static int sanitize(const ft_grid *g, size_t first, size_t rows, float **zo, float **wo)
{
    size_t n = rows * g->nx, base = first * g->nx;
    float *z = ft_malloc((n ? n : 1) * sizeof *z), *w = ft_malloc((n ? n : 1) * sizeof *w);
    if (z == NULL || w == NULL) {
        free(z);
        free(w);
        return FT_E_NOMEM;
    }
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < n; k++) {
        int ok = ft_surface_cell_ok(g, base + k);
        z[k] = ok ? g->z[base + k] : 0.0f;
        w[k] = (float)ok;
    }
    *zo = z;
    *wo = w;
    return FT_OK;
}

int ft_surface_lag_stripes_rows(const ft_lag_stripes *s, const ft_grid *stripe, size_t stripe_row0, size_t r0,
                                size_t r1, double *sums)
{
    if (s == NULL || stripe == NULL || stripe->z == NULL || sums == NULL)
        return ft_error(FT_E_INVALID, "lag stripes: NULL argument");
    size_t need = r1 + s->lags[s->nl - 1] < s->ny ? r1 + s->lags[s->nl - 1] : s->ny;
    if (stripe->nx != s->nx || r0 >= r1 || r1 > s->ny || r0 < stripe_row0 || stripe_row0 + stripe->ny < need)
        return ft_error(FT_E_INVALID, "%s: a stripe of %zu x %zu cells from row %zu cannot give rows %zu-%zu of the "
                        "%zu x %zu grid (it must be %zu cells wide and hold rows %zu-%zu)", s->name, stripe->nx,
                        stripe->ny, stripe_row0, r0, r1 - 1, s->nx, s->ny, s->nx, r0, need - 1);
    size_t first = r0 - stripe_row0, rows = need - stripe_row0 - first;
    float *z = NULL, *w = NULL;
    if (sanitize(stripe, first, rows, &z, &w) != FT_OK)
        return FT_E_NOMEM;
#pragma omp parallel for schedule(dynamic, 4)
    for (size_t i = r0; i < r1; i++)
        row_sums(s, z + (i - r0) * s->nx, w + (i - r0) * s->nx, i, sums + (i - r0) * 4 * s->nl);
    free(z);
    free(w);
    return FT_OK;
}

/* Rows [lo, hi) through read, checked, sanitized. */
static int read_rows(const ft_lag_stripes *s, ft_rows_fn read, void *arg, size_t lo, size_t hi, float **z, float **w)
{
    ft_grid *g = NULL;
    int rc = read(arg, lo, hi - lo, &g);
    if (rc == FT_OK && (g == NULL || g->z == NULL || g->nx != s->nx || g->ny != hi - lo))
        rc = ft_error(FT_E_INVALID, "%s: the reader gave %zu x %zu cells for rows %zu-%zu of a %zu-wide grid", s->name,
                      g ? g->nx : 0, g ? g->ny : 0, lo, hi - 1, s->nx);
    if (rc == FT_OK)
        rc = sanitize(g, 0, hi - lo, z, w);
    ft_grid_free(g);
    return rc;
}

int ft_surface_lag_stripes_rows_read(const ft_lag_stripes *s, ft_rows_fn read, void *arg, size_t r0, size_t r1,
                                     size_t near, double *sums)
{
    if (s == NULL || read == NULL || sums == NULL)
        return ft_error(FT_E_INVALID, "lag stripes: NULL argument");
    if (r0 >= r1 || r1 > s->ny)
        return ft_error(FT_E_INVALID, "%s: rows %zu-%zu are not rows of the %zu-row grid", s->name, r0, r1 - 1, s->ny);
    size_t nx = s->nx, hmax = s->lags[s->nl - 1], nk = near < hmax ? near : hmax;
    size_t hi = r1 + nk < s->ny ? r1 + nk : s->ny;
    float *z = NULL, *w = NULL;
    int rc = read_rows(s, read, arg, r0, hi, &z, &w);
    if (rc != FT_OK)
        return rc;
#pragma omp parallel for schedule(dynamic, 4)
    for (size_t i = r0; i < r1; i++) {
        const float *zi = z + (i - r0) * nx, *wi = w + (i - r0) * nx;
        for (size_t k = 0; k < s->nl && s->lags[k] <= nk; k++)
            lag_row_sums(s, k, zi, wi, zi + s->lags[k] * nx, wi + s->lags[k] * nx, i, sums + (i - r0) * 4 * s->nl);
    }
    for (size_t k = 0; k < s->nl && rc == FT_OK; k++) {
        size_t h = s->lags[k];
        if (h <= nk)
            continue;
        float *zf = NULL, *wf = NULL; /* rows [r0 + h, r1 + h), clipped: the partners of the column pairs */
        if (r0 + h < s->ny && (rc = read_rows(s, read, arg, r0 + h, r1 + h < s->ny ? r1 + h : s->ny, &zf, &wf)) != FT_OK)
            break;
#pragma omp parallel for schedule(dynamic, 4)
        for (size_t i = r0; i < r1; i++) {
            size_t off = (i - r0) * nx;
            int below = i + h < s->ny;
            lag_row_sums(s, k, z + off, w + off, below ? zf + off : NULL, below ? wf + off : NULL, i,
                         sums + (i - r0) * 4 * s->nl);
        }
        free(zf);
        free(wf);
    }
    free(z);
    free(w);
    return rc;
}

int ft_surface_lag_stripes_add(ft_lag_stripes *s, size_t r0, size_t r1, const double *sums)
{
    if (s == NULL || sums == NULL)
        return ft_error(FT_E_INVALID, "lag stripes: NULL argument");
    if (r0 != s->next_row || r1 <= r0 || r1 > s->ny)
        return ft_error(FT_E_INVALID, "%s: rows %zu-%zu added where row %zu comes next: stripes must be added in "
                        "row order", s->name, r0, r1 - 1, s->next_row);
    for (size_t i = r0; i < r1; i++)
        for (size_t k = 0; k < s->nl; k++) {
            const double *q = sums + ((i - r0) * s->nl + k) * 4;
            ft_lag_acc *t = &s->tot[k];
            *t = (ft_lag_acc){t->a + q[0], t->b + q[1], t->c + q[2], t->dist + q[3]};
        }
    s->next_row = r1;
    return FT_OK;
}

size_t ft_surface_lag_stripes_state(const ft_lag_stripes *s, double *sums)
{
    if (s == NULL)
        return 0;
    if (sums != NULL)
        for (size_t k = 0; k < s->nl; k++)
            memcpy(sums + 4 * k, (double[4]){s->tot[k].a, s->tot[k].b, s->tot[k].c, s->tot[k].dist}, 4 * sizeof *sums);
    return s->next_row;
}

int ft_surface_lag_stripes_resume(ft_lag_stripes *s, const double *sums, size_t next_row)
{
    if (s == NULL || sums == NULL || next_row > s->ny)
        return ft_error(FT_E_INVALID, "lag stripes: bad state to resume from (row %zu)", next_row);
    for (size_t k = 0; k < s->nl; k++)
        s->tot[k] = (ft_lag_acc){sums[4 * k], sums[4 * k + 1], sums[4 * k + 2], sums[4 * k + 3]};
    s->next_row = next_row;
    return FT_OK;
}

int ft_surface_lag_stripes_fit(const ft_lag_stripes *s, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "lag stripes: output pointer is NULL");
    *out = NULL;
    if (s == NULL)
        return ft_error(FT_E_INVALID, "lag stripes: NULL");
    if (s->next_row != s->ny)
        return ft_error(FT_E_INVALID, "%s: rows %zu-%zu of the %zu-row grid were never added", s->name, s->next_row,
                        s->ny - 1, s->ny);
    return ft_surface_lag_fit(s->lags, s->tot, s->nl, &s->v, s->stat, s->name, &s->map, out);
}
