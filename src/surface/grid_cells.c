/* fracterra — grid_cells.c: small helpers of the grid estimators (src/surface/grid_internal.h): cell
 * sizes from the geotransform, the range of the valid elevations, grid checks and the final fit of a
 * log-log table.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"

#include "surface/grid_internal.h"

/* Automatic elevation scale of prism and cubes: the valid range becomes this many times the grid's larger
 * ground extent (docs/surface-grid.md: 1, Gwyddion's convention, biases prism by -0.06 on fBm; 4
 * keeps every measured scale steep while a smooth bowl stays within 0.02 of D = 2). */
#define AUTO_RELIEF 4.0

void ft_surface_cell_size(const ft_grid *g, double *cx, double *cy)
{
    *cx = hypot(g->gt[1], g->gt[4]);
    *cy = hypot(g->gt[2], g->gt[5]);
}

int ft_surface_valid_range(const ft_grid *g, const char *name, double *zmin, double *zmax)
{
    double lo = INFINITY, hi = -INFINITY;
    size_t n = g->nx * g->ny;
    for (size_t i = 0; i < n; i++)
        if (ft_surface_cell_ok(g, i)) {
            double v = (double)g->z[i];
            lo = v < lo ? v : lo;
            hi = v > hi ? v : hi;
        }
    if (!(lo <= hi))
        return ft_error(FT_E_EMPTY, "%s: the %zux%zu grid has no valid cell (all nodata)", name, g->nx, g->ny);
    *zmin = lo;
    *zmax = hi;
    return FT_OK;
}

int ft_surface_check_grid(const ft_grid *g, const char *name, size_t min_side)
{
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "%s: the grid is NULL or empty", name);
    if (g->nx < min_side || g->ny < min_side)
        return ft_error(FT_E_INVALID, "%s: needs a grid of at least %zux%zu cells, got %zux%zu", name, min_side,
                        min_side, g->nx, g->ny);
    double cx, cy;
    ft_surface_cell_size(g, &cx, &cy);
    if (!(cx > 0.0) || !(cy > 0.0) || !isfinite(cx) || !isfinite(cy))
        return ft_error(FT_E_INVALID, "%s: the geotransform gives cells of %g x %g ground units", name, cx, cy);
    return FT_OK;
}

int ft_surface_dyadic_setup(const ft_grid *g, const ft_dyadic_opts *o, const char *name, int *kmin, int *kmax,
                            double *zmin, double *zs)
{
    int rc = ft_surface_check_grid(g, name, 3);
    if (rc != FT_OK)
        return rc;
    if (!(o->min_size >= 0.0) || !isfinite(o->min_size))
        return ft_error(FT_E_INVALID, "%s: min_size must be >= 0 cells, got %g", name, o->min_size);
    if (!(o->max_size >= 0.0) || !isfinite(o->max_size))
        return ft_error(FT_E_INVALID, "%s: max_size must be >= 0 cells, got %g", name, o->max_size);
    if (!(o->zscale >= 0.0) || !isfinite(o->zscale))
        return ft_error(FT_E_INVALID, "%s: zscale must be >= 0 (0 = automatic), got %g", name, o->zscale);
    size_t span = (g->nx < g->ny ? g->nx : g->ny) - 1;
    double hi = o->max_size > 0.0 ? o->max_size : (double)span / 8.0;
    if (hi > (double)span)
        return ft_error(FT_E_INVALID, "%s: max_size %g cells exceeds the grid's %zu cells between edges", name, hi,
                        span);
    *kmin = o->min_size > 1.0 ? (int)ceil(log2(o->min_size) - 1e-9) : 0;
    *kmax = hi >= 1.0 ? (int)floor(log2(hi) + 1e-9) : -1;
    if (*kmax - *kmin < 1)
        return ft_error(FT_E_INVALID, "%s: needs at least two powers of two between min_size %g and max_size %g "
                        "cells on a %zux%zu grid", name, o->min_size > 0.0 ? o->min_size : 1.0, hi, g->nx, g->ny);
    double zmax = 0.0;
    if ((rc = ft_surface_valid_range(g, name, zmin, &zmax)) != FT_OK)
        return rc;
    double cx, cy;
    ft_surface_cell_size(g, &cx, &cy);
    double extent = fmax((double)g->nx * cx, (double)g->ny * cy);
    *zs = o->zscale > 0.0 ? o->zscale : zmax > *zmin ? AUTO_RELIEF * extent / (zmax - *zmin) : 1.0;
    return FT_OK;
}

void ft_surface_sum_rows(const double *part, size_t rows, double *first, double *second)
{
    double a = 0.0, b = 0.0;
    for (size_t r = 0; r < rows; r++) {
        a += part[2 * r];
        b += part[2 * r + 1];
    }
    *first = a;
    *second = b;
}

int ft_surface_dyadic_dim(const ft_grid *g, const ft_dyadic_opts *opts, const char *name, const char *what,
                          const ft_dim_map *map, ft_dyadic_size_fn fn, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "%s: output pointer is NULL", name);
    *out = NULL;
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_dyadic_opts) != FT_OK)
        return FT_E_INVALID;
    int kmin, kmax;
    ft_dyadic_ctx c;
    int rc = ft_surface_dyadic_setup(g, &o, name, &kmin, &kmax, &c.zmin, &c.zs);
    if (rc != FT_OK)
        return rc;
    ft_surface_cell_size(g, &c.cx, &c.cy);
    size_t rows_max = (g->ny - 1) >> kmin;
    double *part = ft_malloc(2 * (rows_max ? rows_max : 1) * sizeof *part);
    ft_loglog *t = ft_loglog_create((size_t)(kmax - kmin + 1));
    if (part == NULL || t == NULL) {
        free(part);
        ft_loglog_free(t);
        return FT_E_NOMEM;
    }
    for (int k = kmin; k <= kmax && rc == FT_OK; k++) {
        size_t s = (size_t)1 << k;
        double value = 0.0, count = 0.0, frac = (double)(k - kmin) / (double)(kmax - kmin + 1);
        if ((rc = ft_progress(o.progress, o.progress_arg, frac, name)) != FT_OK ||
            (rc = fn(g, s, &c, part, &value, &count)) != FT_OK)
            break;
        if (count > 0.0)
            rc = ft_loglog_push(t, (double)s * sqrt(c.cx * c.cy), value, count);
    }
    free(part);
    if (rc == FT_OK && t->n < 2)
        rc = ft_error(FT_E_EMPTY, "%s: fewer than two sizes (%d to %d cells) have %s", name, 1 << kmin, 1 << kmax,
                      what);
    if (rc == FT_OK)
        rc = ft_surface_fit_table(t, o.fit_whole_range, &o.fit, map, name, out);
    if (rc == FT_OK && (rc = ft_progress(o.progress, o.progress_arg, 1.0, name)) != FT_OK) {
        ft_dim_result_free(*out);
        *out = NULL;
    }
    ft_loglog_free(t);
    return rc;
}

int ft_surface_fit_table(const ft_loglog *t, int whole, const ft_loglog_opts *fit, const ft_dim_map *map,
                         const char *name, ft_dim_result **out)
{
    int rc = whole ? ft_loglog_fit_range(t, 0.0, 0.0, map, out) : ft_loglog_fit_auto(t, 0.0, 0.0, fit, map, out);
    if (rc == FT_OK)
        (*out)->method = name;
    return rc;
}
