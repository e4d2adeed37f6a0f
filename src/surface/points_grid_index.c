/* fracterra — surface/points_grid_index.c: scattered points sorted into a uniform grid of square cells
 * (a counting sort by cell, coordinates copied cell by cell), the spatial index through which the pair
 * enumeration of Arakawa & Krotkov §2.4 step 1 visits only the pairs that can fall on a lag.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "points_internal.h"

#define SLACK 1e-6 /* relative to the cell side: rounding at cell borders never hides a pair */

static size_t cell_of(const pts_grid *g, double x, double y)
{
    double fx = (x - g->x0) / g->cell, fy = (y - g->y0) / g->cell;
    size_t ix = fx > 0.0 ? (size_t)fx : 0, iy = fy > 0.0 ? (size_t)fy : 0;
    if (ix >= g->nx)
        ix = g->nx - 1;
    if (iy >= g->ny)
        iy = g->ny - 1;
    return iy * g->nx + ix;
}

int pts_grid_build(pts_grid *g, const ft_points *p, double cell)
{
    *g = (pts_grid){0};
    double x0 = p->x[0], x1 = p->x[0], y0 = p->y[0], y1 = p->y[0];
    for (size_t i = 1; i < p->n; i++) {
        x0 = fmin(x0, p->x[i]);
        x1 = fmax(x1, p->x[i]);
        y0 = fmin(y0, p->y[i]);
        y1 = fmax(y1, p->y[i]);
    }
    double limit = p->n * 4.0 > 4096.0 ? (double)p->n * 4.0 : 4096.0;
    if (!(cell > 0.0))
        cell = fmax(x1 - x0, y1 - y0) + 1.0;
    for (;;) {
        double nx = floor((x1 - x0) / cell) + 1.0, ny = floor((y1 - y0) / cell) + 1.0;
        if (nx * ny <= limit) {
            g->nx = (size_t)nx;
            g->ny = (size_t)ny;
            break;
        }
        cell *= 1.5;
    }
    g->x0 = x0;
    g->y0 = y0;
    g->cell = cell;
    size_t ncell = g->nx * g->ny, n = p->n;
    size_t *idx = ft_malloc(n * sizeof *idx);
    g->start = ft_calloc(ncell + 1, sizeof *g->start);
    g->x = ft_malloc(n * sizeof *g->x);
    g->y = ft_malloc(n * sizeof *g->y);
    g->z = ft_malloc(n * sizeof *g->z);
    if (idx == NULL || g->start == NULL || g->x == NULL || g->y == NULL || g->z == NULL) {
        free(idx);
        pts_grid_free(g);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < n; i++) {
        idx[i] = cell_of(g, p->x[i], p->y[i]);
        g->start[idx[i] + 1]++;
    }
    for (size_t c = 0; c < ncell; c++)
        g->start[c + 1] += g->start[c];
    for (size_t i = 0; i < n; i++) {
        size_t at = g->start[idx[i]]++;
        g->x[at] = p->x[i];
        g->y[at] = p->y[i];
        g->z[at] = p->z[i];
    }
    for (size_t c = ncell; c > 0; c--)
        g->start[c] = g->start[c - 1];
    g->start[0] = 0;
    free(idx);
    return FT_OK;
}

void pts_grid_free(pts_grid *g)
{
    if (g == NULL)
        return;
    free(g->start);
    free(g->x);
    free(g->y);
    free(g->z);
    *g = (pts_grid){0};
}

/* Along one axis, the separations between a point of cell 0 and one of cell o lie in
 * [(|o| - 1)c, (|o| + 1)c] (from 0 when o = 0). */
static void axis_range(double c, long o, double *lo, double *hi)
{
    double a = (double)labs(o);
    *lo = a >= 1.0 ? (a - 1.0 - SLACK) * c : 0.0;
    if (*lo < 0.0)
        *lo = 0.0;
    *hi = (a + 1.0 + SLACK) * c;
}

void pts_grid_offset_range(const pts_grid *g, long ox, long oy, double *dmin2, double *dmax2)
{
    double xl, xh, yl, yh;
    axis_range(g->cell, ox, &xl, &xh);
    axis_range(g->cell, oy, &yl, &yh);
    *dmin2 = xl * xl + yl * yl;
    *dmax2 = xh * xh + yh * yh;
}

int pts_grid_offsets(const pts_grid *g, const pts_lags *L, int half, pts_offsets *o)
{
    long r = (long)(L->rmax / g->cell) + 1;
    size_t cap = (size_t)(2 * r + 1) * (size_t)(2 * r + 1);
    o->ox = ft_malloc(cap * sizeof *o->ox);
    o->oy = ft_malloc(cap * sizeof *o->oy);
    o->n = 0;
    if (o->ox == NULL || o->oy == NULL)
        return FT_E_NOMEM;
    for (long oy = half ? 0 : -r; oy <= r; oy++)
        for (long ox = -r; ox <= r; ox++) {
            if (half && oy == 0 && ox <= 0)
                continue;
            double lo2, hi2;
            pts_grid_offset_range(g, ox, oy, &lo2, &hi2);
            if (lo2 <= L->rmax2 && pts_lags_meet(L, lo2, hi2)) {
                o->ox[o->n] = ox;
                o->oy[o->n] = oy;
                o->n++;
            }
        }
    return FT_OK;
}

void pts_offsets_free(pts_offsets *o)
{
    free(o->ox);
    free(o->oy);
    *o = (pts_offsets){NULL, NULL, 0};
}
