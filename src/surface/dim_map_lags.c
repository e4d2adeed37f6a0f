/* fracterra — dim_map_lags.c: the local D map (src/surface/dim_map.c) of the exhaustive lag methods,
 * variogram, Yokoya and Pentland (src/surface/lag_pairs.c; Mark & Aronson 1984, Arakawa & Krotkov §2.4),
 * by block sums instead of one estimate per window.
 *
 * In a window of W x W cells the exhaustive estimator sums, for every lag h, the counters of §2.4 step 1
 * (A = Σ|Δz|, B = Σ(Δz)², C = pairs) over the pairs along rows whose left cell lies in a rectangle of
 * anchors, rows 0 .. W - 1 by columns j0(h) .. j1(h) (the pairs whose midpoint is at least max_lag / 2
 * from the window's edges), and over the pairs along columns whose upper cell lies in rows j0 .. j1 by
 * columns 0 .. W - 1. Windows start at multiples of the step S, so along each axis the anchors of window
 * t are blocks t .. t + m - 1 of S cells, block q starting at q S + j0, and the first p cells of block
 * t + m (m = len / S, p = len mod S, the same for every window). Each block's sums over whole and partial
 * rows and columns are computed once per lag and direction, and a window adds at most (m + 1)² of them:
 * every pair of the grid is read once per lag and direction instead of about (W / S)² times. The window's
 * valid cells (min_valid) are counted the same way.
 *
 * The counters then go through the estimator's own table and fit (ft_surface_lag_plan / _fit), so the map
 * equals ft_surface_dim on each window up to the order of the additions (a few ulps). Block rows and
 * windows run in parallel (OpenMP) with every sum in a fixed order: the same bits on any thread count.
 * The grid is processed in bands of window rows so that memory stays bounded whatever the step.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "surface/grid_internal.h"

#define NAME "dim map"
#define NSTAT 3                       /* A, B, C */
#define NVAR 4                        /* block sums: whole or partial rows x whole or partial columns */
#define BAND_BYTES ((size_t)64 << 20) /* scratch of one band of window rows */

/* The anchors of the windows along one axis: window t covers [t step + o0, t step + o0 + len - 1], i.e.
 * whole blocks t .. t + m - 1 and the first p cells of block t + m; block q starts at q step + o0. */
typedef struct {
    size_t o0, len, m, p;
    size_t nfull; /* blocks whose whole sum some window uses: 0 .. nfull - 1 */
    size_t npart; /* blocks whose partial sum some window uses: 0 .. npart - 1 */
    size_t nb;    /* max(nfull, npart) */
} axis_plan;

static axis_plan make_axis(size_t nw, size_t step, size_t o0, size_t len)
{
    axis_plan a = {o0, len, len / step, len % step, 0, 0, 0};
    a.nfull = a.m > 0 ? nw + a.m - 1 : 0;
    a.npart = a.p > 0 ? nw + a.m : 0;
    a.nb = a.nfull > a.npart ? a.nfull : a.npart;
    return a;
}

/* What a block sums: the valid cells, or the counters of the pairs (i, j)-(i, j + h) or (i, j)-(i + h, j)
 * anchored at (i, j). */
typedef enum { FIELD_CELLS = 0, FIELD_ROW_PAIRS = 1, FIELD_COL_PAIRS = 2 } field_kind;

typedef struct {
    const float *z, *w; /* elevations with invalid cells 0, weights 1 valid / 0 not */
    size_t nx;
    field_kind kind;
    size_t h;
} field;

/* Adds the field's values at anchors (i, j0 .. j0 + n - 1) to s (NSTAT). */
static void add_run(const field *f, size_t i, size_t j0, size_t n, double s[NSTAT])
{
    const float *zp = f->z + i * f->nx + j0, *wp = f->w + i * f->nx + j0;
    if (f->kind == FIELD_CELLS) {
        for (size_t j = 0; j < n; j++)
            s[2] += (double)wp[j];
        return;
    }
    size_t off = f->kind == FIELD_ROW_PAIRS ? f->h : f->h * f->nx;
    const float *zq = zp + off, *wq = wp + off;
    ft_lag_acc acc = {0.0, 0.0, 0.0, 0.0};
    ft_lag_pair_sums(zp, wp, zq, wq, n, &acc);
    s[0] += acc.a;
    s[1] += acc.b;
    s[2] += acc.c;
}

/* Block sums of one band: block rows q0 .. q0 + nq - 1, every block column; blk[((qi nbc + b) NVAR + v)
 * NSTAT + s]. */
static void band_blocks(const field *f, const axis_plan *ar, const axis_plan *ac, size_t step, size_t q0,
                        size_t nq, double *blk)
{
    size_t nbc = ac->nb;
    memset(blk, 0, nq * nbc * NVAR * NSTAT * sizeof *blk);
#pragma omp parallel for schedule(dynamic, 1)
    for (size_t qi = 0; qi < nq; qi++) {
        size_t q = q0 + qi;
        int row_full = q < ar->nfull, row_part = q < ar->npart;
        size_t rows = row_full ? step : row_part ? ar->p : 0;
        for (size_t k = 0; k < rows; k++) {
            size_t i = q * step + ar->o0 + k;
            for (size_t b = 0; b < nbc; b++) {
                int col_full = b < ac->nfull, col_part = b < ac->npart;
                size_t j = b * step + ac->o0;
                double part[NSTAT] = {0.0, 0.0, 0.0}, whole[NSTAT];
                if (col_part)
                    add_run(f, i, j, ac->p, part);
                memcpy(whole, part, sizeof whole);
                if (col_full)
                    add_run(f, i, j + ac->p, step - ac->p, whole);
                double *o = blk + (qi * nbc + b) * NVAR * NSTAT;
                for (int s = 0; s < NSTAT; s++) {
                    if (row_full) {
                        o[0 * NSTAT + s] += whole[s];
                        o[1 * NSTAT + s] += part[s];
                    }
                    if (row_part && k < ar->p) {
                        o[2 * NSTAT + s] += whole[s];
                        o[3 * NSTAT + s] += part[s];
                    }
                }
            }
        }
    }
}

/* The sums of window (tr, tc) from the band's blocks (tr relative to the band's first block row). */
static void window_sum(const double *blk, size_t nbc, const axis_plan *ar, const axis_plan *ac, size_t tr,
                       size_t tc, double s[NSTAT])
{
    s[0] = s[1] = s[2] = 0.0;
    for (size_t a = 0; a <= ar->m; a++) {
        if (a == ar->m && ar->p == 0)
            break;
        for (size_t b = 0; b <= ac->m; b++) {
            if (b == ac->m && ac->p == 0)
                break;
            int v = (a == ar->m) * 2 + (b == ac->m); /* 0 whole x whole ... 3 partial x partial */
            const double *o = blk + ((tr + a) * nbc + tc + b) * NVAR * NSTAT + v * NSTAT;
            for (int k = 0; k < NSTAT; k++)
                s[k] += o[k];
        }
    }
}

typedef struct {
    const ft_grid *g;
    float *z, *w;
    size_t win, step, nox, noy;
    size_t *lags, nl;
    ft_variogram_opts v;
    ft_lag_stat stat;
    const char *name;
    ft_dim_map map;
    double cx, cy;
    unsigned char *measured; /* nox x noy: enough valid cells */
    double *blk, *sums;      /* band scratch */
    size_t band;             /* window rows per band */
} map_ctx;

/* Every window's flag: at least min_valid of its cells valid (and one). */
static void count_cells(map_ctx *c, double min_valid)
{
    field f = {c->z, c->w, c->g->nx, FIELD_CELLS, 0};
    axis_plan ar = make_axis(c->noy, c->step, 0, c->win), ac = make_axis(c->nox, c->step, 0, c->win);
    for (size_t t0 = 0; t0 < c->noy; t0 += c->band) {
        size_t nt = c->noy - t0 < c->band ? c->noy - t0 : c->band;
        band_blocks(&f, &ar, &ac, c->step, t0, nt + ar.m, c->blk);
#pragma omp parallel for schedule(static)
        for (size_t k = 0; k < nt * c->nox; k++) {
            double s[NSTAT];
            window_sum(c->blk, ac.nb, &ar, &ac, k / c->nox, k % c->nox, s);
            double need = min_valid * (double)(c->win * c->win);
            c->measured[(t0 + k / c->nox) * c->nox + k % c->nox] = (unsigned char)(s[2] > 0.0 && !(s[2] < need));
        }
    }
}

/* The anchors of lag h along its axis in a window: [j0, j1] (len 0 when no pair qualifies), as
 * exhaustive_row in lag_pairs.c. */
static void lag_span(size_t win, size_t h, size_t hmax, size_t *j0, size_t *len)
{
    *j0 = 0;
    *len = 0;
    if (h + hmax > 2 * (win - 1))
        return;
    size_t a = (hmax - h + 1) / 2, b = (2 * (win - 1) - h - hmax) / 2;
    if (a <= b) {
        *j0 = a;
        *len = b - a + 1;
    }
}

/* Window rows t0 .. t0 + nt - 1: the counters of every lag and direction into c->sums
 * [((window nl) + lag) 2 + direction] NSTAT. */
static void band_counters(map_ctx *c, size_t t0, size_t nt)
{
    size_t hmax = c->lags[c->nl - 1];
    memset(c->sums, 0, nt * c->nox * c->nl * 2 * NSTAT * sizeof *c->sums);
    for (size_t k = 0; k < c->nl; k++)
        for (int dir = 0; dir < 2; dir++) {
            size_t j0, len;
            lag_span(c->win, c->lags[k], hmax, &j0, &len);
            if (len == 0)
                continue;
            field f = {c->z, c->w, c->g->nx, dir == 0 ? FIELD_ROW_PAIRS : FIELD_COL_PAIRS, c->lags[k]};
            /* row pairs: every row of the window, anchor columns j0 .. j1; column pairs the transpose */
            axis_plan ar = dir == 0 ? make_axis(c->noy, c->step, 0, c->win) : make_axis(c->noy, c->step, j0, len);
            axis_plan ac = dir == 0 ? make_axis(c->nox, c->step, j0, len) : make_axis(c->nox, c->step, 0, c->win);
            band_blocks(&f, &ar, &ac, c->step, t0, nt + ar.m, c->blk);
#pragma omp parallel for schedule(static)
            for (size_t q = 0; q < nt * c->nox; q++) {
                if (!c->measured[t0 * c->nox + q])
                    continue;
                double *s = c->sums + ((q * c->nl + k) * 2 + (size_t)dir) * NSTAT;
                window_sum(c->blk, ac.nb, &ar, &ac, q / c->nox, q % c->nox, s);
            }
        }
}

typedef struct {
    int code;
    char msg[512];
} map_failure;

static int is_fatal(int rc)
{
    return rc == FT_E_INVALID || rc == FT_E_NOMEM || rc == FT_E_UNSUPPORTED || rc == FT_E_CANCELLED;
}

/* The estimate of every measured window of the band into D and r2, and its noise flag into N (if any). */
static void band_fits(map_ctx *c, size_t t0, size_t nt, ft_grid *D, ft_grid *r2, ft_grid *N, map_failure *fail)
{
#pragma omp parallel
    {
        ft_lag_acc *tot = ft_malloc(c->nl * sizeof *tot);
        if (tot == NULL) {
#pragma omp critical(ft_dim_map_lags_failure)
            if (fail->code == FT_OK) {
                fail->code = FT_E_NOMEM;
                snprintf(fail->msg, sizeof fail->msg, "out of memory");
            }
        }
#pragma omp for schedule(dynamic, 64)
        for (size_t q = 0; q < nt * c->nox; q++) {
            size_t cell = t0 * c->nox + q;
            if (tot == NULL || !c->measured[cell])
                continue;
            for (size_t k = 0; k < c->nl; k++) {
                const double *x = c->sums + ((q * c->nl + k) * 2) * NSTAT, *y = x + NSTAT;
                tot[k] = (ft_lag_acc){x[0] + y[0], x[1] + y[1], x[2] + y[2],
                                      (double)c->lags[k] * (x[2] * c->cx + y[2] * c->cy)};
            }
            ft_dim_result *r = NULL;
            int rc = ft_surface_lag_fit(c->lags, tot, c->nl, &c->v, c->stat, c->name, &c->map, &r);
            if (rc == FT_OK) {
                D->z[cell] = (float)r->D;
                r2->z[cell] = (float)r->r2;
                D->mask[cell] = r2->mask[cell] = 1;
                if (N != NULL) {
                    N->z[cell] = (float)(r->nugget.applied != 0);
                    N->mask[cell] = 1;
                }
            } else if (is_fatal(rc)) {
#pragma omp critical(ft_dim_map_lags_failure)
                if (fail->code == FT_OK) {
                    fail->code = rc;
                    snprintf(fail->msg, sizeof fail->msg, "%s", ft_last_error());
                }
            }
            ft_dim_result_free(r);
        }
        free(tot);
    }
}

/* The grid's elevations with invalid cells 0 and their 0/1 weights (as lag_pairs.c's sanitize_grid). */
static int sanitize(const ft_grid *g, float **z, float **w)
{
    size_t n = g->nx * g->ny;
    *z = ft_malloc(n * sizeof **z);
    *w = ft_malloc(n * sizeof **w);
    if (*z == NULL || *w == NULL)
        return FT_E_NOMEM;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        int ok = ft_surface_cell_ok(g, i);
        (*z)[i] = ok ? g->z[i] : 0.0f;
        (*w)[i] = (float)ok;
    }
    return FT_OK;
}

/* Window rows per band: the block sums (band + m rows of blocks) and the counters of a band fit in
 * BAND_BYTES; at least one. */
static size_t band_rows(const map_ctx *c)
{
    size_t nbc = make_axis(c->nox, c->step, 0, c->win).nb, m = c->win / c->step + 1;
    size_t per_block_row = nbc * NVAR * NSTAT * sizeof(double);
    size_t per_window_row = c->nox * c->nl * 2 * NSTAT * sizeof(double) + per_block_row;
    size_t rows = BAND_BYTES > m * per_block_row ? (BAND_BYTES - m * per_block_row) / per_window_row : 1;
    rows = rows < 1 ? 1 : rows;
    return rows < c->noy ? rows : c->noy;
}

int ft_surface_dim_map_lags(const ft_grid *g, size_t window, size_t step, ft_surface_method m,
                            const ft_surface_dim_opts *o, ft_grid *D, ft_grid *r2, ft_grid *N)
{
    map_ctx c;
    memset(&c, 0, sizeof c);
    c.g = g;
    c.win = window;
    c.step = step;
    c.nox = D->nx;
    c.noy = D->ny;
    c.stat = m == FT_SURFACE_VARIOGRAM ? FT_LAG_STAT_MEAN_SQ : m == FT_SURFACE_YOKOYA ? FT_LAG_STAT_MEAN_ABS
                                                                                       : FT_LAG_STAT_SD_ABS;
    c.name = ft_surface_method_name(m);
    c.map = m == FT_SURFACE_VARIOGRAM ? (ft_dim_map)FT_DIM_MAP_VARIOGRAM_SURFACE
                                      : (ft_dim_map)FT_DIM_MAP_INCREMENT_SURFACE;
    ft_surface_cell_size(g, &c.cx, &c.cy);
    int rc = sanitize(g, &c.z, &c.w);
    c.nl = 1; /* the counting pass sizes its band as for one lag */
    c.band = band_rows(&c);
    size_t nbc = make_axis(c.nox, step, 0, window).nb;
    c.measured = rc == FT_OK ? ft_malloc(c.nox * c.noy) : NULL;
    c.blk = rc == FT_OK ? ft_malloc((c.band + window / step + 1) * nbc * NVAR * NSTAT * sizeof *c.blk) : NULL;
    if (rc == FT_OK && (c.measured == NULL || c.blk == NULL))
        rc = FT_E_NOMEM;
    size_t nmeasured = 0;
    if (rc == FT_OK) {
        count_cells(&c, o->min_valid);
        for (size_t k = 0; k < c.nox * c.noy; k++)
            nmeasured += c.measured[k];
    }
    /* the options as every window's estimator sees them; only an error if a window is measured, as
     * ft_surface_dim is only called on those */
    if (rc == FT_OK && nmeasured > 0) {
        ft_surface_dim_opts wo = *o;
        wo.progress = NULL;
        wo.progress_arg = NULL;
        rc = ft_surface_lag_opts(&wo, c.cx, c.cy, &c.v);
        if (rc == FT_OK)
            rc = ft_surface_lag_plan(window, window, &c.v, c.name, &c.lags, &c.nl);
        if (rc != FT_OK && rc != FT_E_NOMEM) {
            char msg[512];
            snprintf(msg, sizeof msg, "%s", ft_last_error());
            rc = ft_error(rc, NAME ": window of %zu cells: %s", window, msg);
        }
    }
    if (rc == FT_OK && nmeasured > 0) {
        c.band = band_rows(&c);
        free(c.blk);
        c.blk = ft_malloc((c.band + window / step + 1) * nbc * NVAR * NSTAT * sizeof *c.blk);
        c.sums = ft_malloc(c.band * c.nox * c.nl * 2 * NSTAT * sizeof *c.sums);
        if (c.blk == NULL || c.sums == NULL)
            rc = FT_E_NOMEM;
    }
    map_failure fail = {FT_OK, ""};
    for (size_t t0 = 0; rc == FT_OK && nmeasured > 0 && t0 < c.noy; t0 += c.band) {
        size_t nt = c.noy - t0 < c.band ? c.noy - t0 : c.band;
        band_counters(&c, t0, nt);
        band_fits(&c, t0, nt, D, r2, N, &fail);
        if (fail.code != FT_OK)
            rc = ft_error(fail.code, NAME ": window of %zu cells: %s", window, fail.msg);
        else if (ft_progress(o->progress, o->progress_arg, (double)(t0 + nt) / (double)c.noy, NAME) != FT_OK)
            rc = ft_error(FT_E_CANCELLED, NAME ": cancelled");
    }
    free(c.z);
    free(c.w);
    free(c.measured);
    free(c.blk);
    free(c.sums);
    free(c.lags);
    return rc;
}
