/* fracterra — surface/profile_extract.c: profiles at a regular spacing for surface/profile_dim.c: a raster
 * row, a transect across a grid (bilinear interpolation between cell centres), a 3-D line resampled along
 * its horizontal length (linear interpolation of z). The estimators of Gneiting et al. (2012) need equal
 * spacing; nodata is never interpolated across.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/surface.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>

int ft_profile_from_grid_row(const ft_grid *g, size_t row, double **z, size_t *n, double *spacing)
{
    if (g == NULL || z == NULL || n == NULL || spacing == NULL)
        return ft_error(FT_E_INVALID, "profile from a grid row: NULL argument");
    *z = NULL;
    if (row >= g->ny)
        return ft_error(FT_E_INVALID, "profile from a grid row: row %zu outside the grid's %zu rows", row, g->ny);
    if (g->nx < 3)
        return ft_error(FT_E_EMPTY, "profile from a grid row: the grid has %zu columns, fewer than 3", g->nx);
    double *v = ft_malloc(g->nx * sizeof *v);
    if (v == NULL)
        return FT_E_NOMEM;
    for (size_t c = 0; c < g->nx; c++) {
        if (!ft_grid_is_valid(g, c, row) || !isfinite(g->z[row * g->nx + c])) {
            free(v);
            return ft_error(FT_E_NUMERIC, "profile from a grid row: row %zu, column %zu is nodata", row, c);
        }
        v[c] = g->z[row * g->nx + c];
    }
    *z = v;
    *n = g->nx;
    *spacing = hypot(g->gt[1], g->gt[4]);
    return FT_OK;
}

/* Bilinear value at fractional cell-centre coordinates (u, v) (u = column, v = row of centres); 0 if a
 * corner is nodata. */
static int bilinear(const ft_grid *g, double u, double v, double *out)
{
    size_t c0 = (size_t)floor(u), r0 = (size_t)floor(v);
    size_t c1 = c0 + 1 < g->nx ? c0 + 1 : c0, r1 = r0 + 1 < g->ny ? r0 + 1 : r0;
    double fu = u - (double)c0, fv = v - (double)r0;
    size_t cs[4] = {c0, c1, c0, c1}, rs[4] = {r0, r0, r1, r1};
    double w[4] = {(1 - fu) * (1 - fv), fu * (1 - fv), (1 - fu) * fv, fu * fv}, s = 0.0;
    for (int k = 0; k < 4; k++) {
        if (w[k] == 0.0)
            continue;
        if (!ft_grid_is_valid(g, cs[k], rs[k]) || !isfinite(g->z[rs[k] * g->nx + cs[k]]))
            return 0;
        s += w[k] * g->z[rs[k] * g->nx + cs[k]];
    }
    *out = s;
    return 1;
}

int ft_profile_transect(const ft_grid *g, double x0, double y0, double x1, double y1, double **z, size_t *n,
                        double *spacing)
{
    if (g == NULL || z == NULL || n == NULL || spacing == NULL)
        return ft_error(FT_E_INVALID, "transect: NULL argument");
    *z = NULL;
    if (!isfinite(x0) || !isfinite(y0) || !isfinite(x1) || !isfinite(y1))
        return ft_error(FT_E_INVALID, "transect: end points must be finite, got (%g, %g) to (%g, %g)", x0, y0, x1, y1);
    const double *gt = g->gt;
    double det = gt[1] * gt[5] - gt[2] * gt[4];
    if (!(fabs(det) > 0.0))
        return ft_error(FT_E_INVALID, "transect: the grid's geotransform is singular");
    double step = fmin(hypot(gt[1], gt[4]), hypot(gt[2], gt[5]));
    double len = hypot(x1 - x0, y1 - y0);
    size_t m = (size_t)floor(len / step) + 1;
    if (m < 3)
        return ft_error(FT_E_EMPTY, "transect: (%g, %g) to (%g, %g) is %g long, fewer than 3 samples at the cell "
                        "size %g", x0, y0, x1, y1, len, step);
    double *v = ft_malloc(m * sizeof *v);
    if (v == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < m; i++) {
        double t = (double)i * step / len, x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
        double dx = x - gt[0], dy = y - gt[3];
        double col = (gt[5] * dx - gt[2] * dy) / det - 0.5, row = (-gt[4] * dx + gt[1] * dy) / det - 0.5;
        if (!(col >= 0.0 && row >= 0.0 && col <= (double)(g->nx - 1) && row <= (double)(g->ny - 1))) {
            free(v);
            return ft_error(FT_E_INVALID, "transect: point (%g, %g), %g along it, lies outside the grid's cell "
                            "centres", x, y, (double)i * step);
        }
        if (!bilinear(g, col, row, &v[i])) {
            free(v);
            return ft_error(FT_E_NUMERIC, "transect: point (%g, %g), %g along it, is next to nodata", x, y,
                            (double)i * step);
        }
    }
    *z = v;
    *n = m;
    *spacing = step;
    return FT_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int ft_profile_resample(const double *x, const double *y, const double *z, size_t n, double spacing,
                        double **zout, size_t *nout, double *step)
{
    if (x == NULL || y == NULL || z == NULL || zout == NULL || nout == NULL || step == NULL)
        return ft_error(FT_E_INVALID, "profile from a 3-D line: NULL argument");
    *zout = NULL;
    if (n < 3)
        return ft_error(FT_E_EMPTY, "profile from a 3-D line: needs at least 3 vertices, got %zu", n);
    double *cum = ft_malloc(n * sizeof *cum), *seg = ft_malloc(n * sizeof *seg);
    if (cum == NULL || seg == NULL) {
        free(cum);
        free(seg);
        return FT_E_NOMEM;
    }
    size_t ns = 0;
    cum[0] = 0.0;
    for (size_t i = 1; i < n; i++) {
        double d = hypot(x[i] - x[i - 1], y[i] - y[i - 1]);
        if (!isfinite(d) || !isfinite(z[i]) || !isfinite(z[0])) {
            free(cum);
            free(seg);
            return ft_error(FT_E_NUMERIC, "profile from a 3-D line: vertex %zu is not finite", i);
        }
        cum[i] = cum[i - 1] + d;
        if (d > 0.0)
            seg[ns++] = d;
    }
    if (ns == 0) {
        free(cum);
        free(seg);
        return ft_error(FT_E_EMPTY, "profile from a 3-D line: the line has no horizontal length");
    }
    qsort(seg, ns, sizeof *seg, cmp_double);
    double h = spacing > 0.0 ? spacing : seg[ns / 2];
    free(seg);
    size_t m = (size_t)floor(cum[n - 1] / h) + 1;
    if (m < 3) {
        double total = cum[n - 1];
        free(cum);
        return ft_error(FT_E_EMPTY, "profile from a 3-D line: %g long, fewer than 3 samples at spacing %g", total,
                        h);
    }
    double *v = ft_malloc(m * sizeof *v);
    if (v == NULL) {
        free(cum);
        return FT_E_NOMEM;
    }
    size_t j = 0;
    for (size_t i = 0; i < m; i++) {
        double s = (double)i * h;
        while (j + 2 < n && cum[j + 1] < s)
            j++;
        double d = cum[j + 1] - cum[j], t = d > 0.0 ? (s - cum[j]) / d : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        v[i] = z[j] + t * (z[j + 1] - z[j]);
    }
    free(cum);
    *zout = v;
    *nout = m;
    *step = h;
    return FT_OK;
}
