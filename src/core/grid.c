/* fracterra — core/grid.c: float grids (ft_grid) with a nodata mask and a GDAL geotransform.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

ft_grid *ft_grid_create(size_t nx, size_t ny)
{
    if (nx == 0 || ny == 0) {
        ft_error(FT_E_INVALID, "grid size must be at least 1 x 1, got %zu x %zu", nx, ny);
        return NULL;
    }
    if (nx > SIZE_MAX / ny || nx * ny > SIZE_MAX / sizeof(float)) {
        ft_error(FT_E_INVALID, "grid size %zu x %zu overflows the address space", nx, ny);
        return NULL;
    }
    ft_grid *g = ft_calloc(1, sizeof *g);
    if (g == NULL)
        return NULL;
    g->z = ft_calloc(nx * ny, sizeof *g->z);
    if (g->z == NULL) {
        free(g);
        return NULL;
    }
    g->nx = nx;
    g->ny = ny;
    const double gt[6] = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    memcpy(g->gt, gt, sizeof gt);
    return g;
}

ft_grid *ft_grid_copy(const ft_grid *g)
{
    if (g == NULL) {
        ft_error(FT_E_INVALID, "ft_grid_copy: NULL grid");
        return NULL;
    }
    ft_grid *d = ft_grid_create(g->nx, g->ny);
    if (d == NULL)
        return NULL;
    size_t ncells = g->nx * g->ny;
    memcpy(d->z, g->z, ncells * sizeof *d->z);
    memcpy(d->gt, g->gt, sizeof d->gt);
    d->has_nodata = g->has_nodata;
    d->nodata_value = g->nodata_value;
    if (g->mask != NULL) {
        d->mask = ft_malloc(ncells);
        if (d->mask == NULL)
            goto fail;
        memcpy(d->mask, g->mask, ncells);
    }
    if (g->crs_wkt != NULL && (d->crs_wkt = ft_strdup(g->crs_wkt)) == NULL)
        goto fail;
    return d;
fail:
    ft_grid_free(d);
    return NULL;
}

void ft_grid_free(ft_grid *g)
{
    if (g == NULL)
        return;
    free(g->z);
    free(g->mask);
    free(g->crs_wkt);
    free(g);
}

int ft_grid_ensure_mask(ft_grid *g)
{
    if (g == NULL)
        return ft_error(FT_E_INVALID, "ft_grid_ensure_mask: NULL grid");
    if (g->mask != NULL)
        return FT_OK;
    g->mask = ft_malloc(g->nx * g->ny);
    if (g->mask == NULL)
        return FT_E_NOMEM;
    memset(g->mask, 1, g->nx * g->ny);
    return FT_OK;
}

size_t ft_grid_count_valid(const ft_grid *g)
{
    if (g == NULL)
        return 0;
    size_t ncells = g->nx * g->ny;
    if (g->mask == NULL)
        return ncells;
    size_t count = 0;
    for (size_t i = 0; i < ncells; i++)
        count += g->mask[i] != 0;
    return count;
}

/* NaN cells that are not masked are skipped too, so that one stray NaN cannot poison the range. */
int ft_grid_minmax(const ft_grid *g, double *zmin, double *zmax)
{
    if (g == NULL)
        return ft_error(FT_E_INVALID, "ft_grid_minmax: NULL grid");
    size_t ncells = g->nx * g->ny;
    double lo = INFINITY, hi = -INFINITY;
    int any = 0;
    for (size_t i = 0; i < ncells; i++) {
        if ((g->mask != NULL && g->mask[i] == 0) || isnan(g->z[i]))
            continue;
        double v = g->z[i];
        lo = v < lo ? v : lo;
        hi = v > hi ? v : hi;
        any = 1;
    }
    if (!any)
        return ft_error(FT_E_EMPTY, "grid of %zu x %zu cells has no valid cell", g->nx, g->ny);
    if (zmin) *zmin = lo;
    if (zmax) *zmax = hi;
    return FT_OK;
}

void ft_grid_cell_center(const ft_grid *g, double col, double row, double *x, double *y)
{
    double c = col + 0.5, r = row + 0.5;
    if (x) *x = g->gt[0] + c * g->gt[1] + r * g->gt[2];
    if (y) *y = g->gt[3] + c * g->gt[4] + r * g->gt[5];
}

void ft_grid_extent(const ft_grid *g, double *xmin, double *ymin, double *xmax, double *ymax)
{
    const double cols[4] = {0.0, (double)g->nx, 0.0, (double)g->nx};
    const double rows[4] = {0.0, 0.0, (double)g->ny, (double)g->ny};
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (int k = 0; k < 4; k++) {
        double x = g->gt[0] + cols[k] * g->gt[1] + rows[k] * g->gt[2];
        double y = g->gt[3] + cols[k] * g->gt[4] + rows[k] * g->gt[5];
        x0 = fmin(x0, x);
        x1 = fmax(x1, x);
        y0 = fmin(y0, y);
        y1 = fmax(y1, y);
    }
    if (xmin) *xmin = x0;
    if (ymin) *ymin = y0;
    if (xmax) *xmax = x1;
    if (ymax) *ymax = y1;
}

int ft_grid_set_crs(ft_grid *g, const char *wkt)
{
    if (g == NULL)
        return ft_error(FT_E_INVALID, "ft_grid_set_crs: NULL grid");
    char *copy = NULL;
    if (wkt != NULL && (copy = ft_strdup(wkt)) == NULL)
        return FT_E_NOMEM;
    free(g->crs_wkt);
    g->crs_wkt = copy;
    return FT_OK;
}

/* Counts the cells that were valid and held NaN or Inf, and masks them. */
long ft_grid_mask_nonfinite(ft_grid *g)
{
    if (g == NULL)
        return ft_error(FT_E_INVALID, "ft_grid_mask_nonfinite: NULL grid");
    size_t ncells = g->nx * g->ny;
    long found = 0;
    for (size_t i = 0; i < ncells; i++) {
        if (isfinite(g->z[i]) || (g->mask != NULL && g->mask[i] == 0))
            continue;
        if (g->mask == NULL && ft_grid_ensure_mask(g) != FT_OK)
            return FT_E_NOMEM;
        g->mask[i] = 0;
        found++;
    }
    return found;
}
