/* fracterra — surface/points_pairs_grid.c: the counters of Arakawa & Krotkov §2.4 step 1 over every pair
 * of points, found through a uniform grid instead of the paper's O(N²) loop over all pairs.
 *
 * The points are sorted into square cells of side (max lag + ε) / CELLS_PER_LAG. A pair can fall on a lag
 * only if its separation is at most max lag + ε, so each cell is paired with itself (i < j inside it) and
 * with the cells at the offsets of one half-plane (oy > 0, or oy = 0 and ox > 0) whose range of possible
 * separations meets some annulus [Δd_i - ε, Δd_i + ε]: every such pair of points is visited exactly once,
 * pairs that cannot fall on a lag are never visited. The per-pair test and the fixed-point sums are the
 * exact enumeration's (points_internal.h), so the counters are bit-identical to it. Cost: O(N k), k the
 * points within max lag + ε of a point. OpenMP over cells, one set of counters per thread, merged as
 * integers (order-free, so the result does not depend on the thread count).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>

#include "internal.h"
#include "points_internal.h"

/* Cells across the largest annulus radius: finer cells cut the area scanned around each point from
 * (3 (max lag + ε))² towards π (max lag + ε)² (about 1.2 times it with 16) and let whole cells between
 * two annuli be skipped. */
#define CELLS_PER_LAG 16
#define MIN_PER_CELL 16.0
#define CHUNKS 64

static void cell_self(const pts_grid *g, size_t c, const pts_lags *L, pts_acc *acc)
{
    for (size_t i = g->start[c]; i < g->start[c + 1]; i++)
        for (size_t j = i + 1; j < g->start[c + 1]; j++) {
            double dx = g->x[j] - g->x[i], dy = g->y[j] - g->y[i];
            pts_add_pair(L, acc, dx * dx + dy * dy, g->z[j] - g->z[i]);
        }
}

/* Every point of cell a against every point of cell b: the squared separations and their bins for a
 * whole row first (a loop the compiler vectorises), then the rare pairs whose bin an annulus meets. */
static void cell_pair(const pts_grid *g, size_t a, size_t b, const pts_lags *L, pts_acc *acc, double *d2,
                      int32_t *bin)
{
    size_t b0 = g->start[b], nb = g->start[b + 1] - b0;
    const double *restrict xb = g->x + b0, *restrict yb = g->y + b0, *restrict zb = g->z + b0;
    const double cap = L->bin_cap, scale = L->bin_scale;
    const uint8_t *hit = L->bin_hit;
    for (size_t i = g->start[a]; i < g->start[a + 1]; i++) {
        double xi = g->x[i], yi = g->y[i];
        for (size_t j = 0; j < nb; j++) {
            double dx = xb[j] - xi, dy = yb[j] - yi, q = dx * dx + dy * dy;
            d2[j] = q;
            bin[j] = (int32_t)((q < cap ? q : cap) * scale);
        }
        for (size_t j = 0; j < nb; j++)
            if (hit[bin[j]])
                pts_add_binned(L, acc, d2[j], zb[j] - g->z[i], (size_t)bin[j]);
    }
}

static void one_cell(const pts_grid *g, size_t c, const pts_offsets *o, const pts_lags *L, pts_acc *acc, double *d2,
                     int32_t *bin)
{
    if (g->start[c] == g->start[c + 1])
        return;
    long cx = (long)(c % g->nx), cy = (long)(c / g->nx);
    if (pts_lags_meet(L, 0.0, 2.0 * g->cell * g->cell * (1.0 + 1e-6)))
        cell_self(g, c, L, acc);
    for (size_t k = 0; k < o->n; k++) {
        long bx = cx + o->ox[k], by = cy + o->oy[k];
        if (bx < 0 || by < 0 || bx >= (long)g->nx || by >= (long)g->ny)
            continue;
        cell_pair(g, c, (size_t)by * g->nx + (size_t)bx, L, acc, d2, bin);
    }
}

/* Cell side: CELLS_PER_LAG cells across max lag + ε, but not so small that cells hold fewer than about
 * MIN_PER_CELL points on average (per-cell overhead would then dominate). */
static double cell_side(const ft_points *p, const pts_lags *L)
{
    double x0, y0, x1, y1;
    ft_points_bbox(p, &x0, &y0, &x1, &y1);
    double area = fmax(x1 - x0, 1e-300) * fmax(y1 - y0, 1e-300);
    double c = L->rmax / CELLS_PER_LAG, dense = sqrt(MIN_PER_CELL * area / (double)p->n);
    return c > dense ? c : fmin(dense, L->rmax);
}

int pts_pairs_grid(const ft_points *p, const pts_lags *L, pts_acc *acc, ft_progress_fn fn, void *arg)
{
    pts_grid g;
    pts_offsets o = {NULL, NULL, 0};
    int nt = omp_get_max_threads();
    pts_acc *part = ft_calloc((size_t)nt * L->n, sizeof *part);
    int rc = part ? pts_grid_build(&g, p, cell_side(p, L)) : FT_E_NOMEM;
    if (rc != FT_OK) {
        free(part);
        return rc;
    }
    size_t ncell = g.nx * g.ny, most = 1;
    for (size_t c = 0; c < ncell; c++)
        if (g.start[c + 1] - g.start[c] > most)
            most = g.start[c + 1] - g.start[c];
    double *buf = ft_malloc((size_t)nt * most * sizeof *buf);
    int32_t *bins = ft_malloc((size_t)nt * most * sizeof *bins);
    rc = buf && bins ? pts_grid_offsets(&g, L, 1, &o) : FT_E_NOMEM;
    for (size_t chunk = 0; rc == FT_OK && chunk < CHUNKS; chunk++) {
        size_t c0 = ncell * chunk / CHUNKS, c1 = ncell * (chunk + 1) / CHUNKS;
#pragma omp parallel for schedule(dynamic, 16)
        for (size_t c = c0; c < c1; c++) {
            size_t t = (size_t)omp_get_thread_num();
            one_cell(&g, c, &o, L, part + t * L->n, buf + t * most, bins + t * most);
        }
        rc = ft_progress(fn, arg, (double)(chunk + 1) / CHUNKS, "pairs");
    }
    for (int t = 0; rc == FT_OK && t < nt; t++)
        pts_acc_merge(acc, part + (size_t)t * L->n, L->n);
    pts_offsets_free(&o);
    free(buf);
    free(bins);
    free(part);
    pts_grid_free(&g);
    return rc;
}
