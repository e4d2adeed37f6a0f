/* fracterra — src/urban/class_stats.c: area, perimeter and polygon count of a land-use class, the columns
 * that accompany D in the per-year table (Zhang, Yu & Fan 2008, Table 2: area of residence
 * against D, the data of the regression of Eq. 5).
 *
 * Vector: area = sum of |outer ring areas| - sum of |inner ring areas| (shoelace), perimeter = total ring
 * length, one polygon per outer ring. Raster: cells of the class times the cell area |gt[1] gt[5] - gt[2]
 * gt[4]|; the perimeter is the length of the cell edges between a class cell and a non-class one (another
 * value, nodata or off the grid), and a polygon is a 4-connected patch of class cells (labelled by a flood
 * fill over an explicit stack).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "fracterra/urban.h"
#include "internal.h"
#include "urban/urban_internal.h"

int ft_urban_layer_stats(const ft_layer *l, const size_t *features, size_t nfeatures, ft_urban_stats *out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_layer_stats: NULL out");
    *out = (ft_urban_stats){0};
    ft_polygon_index s;
    int rc = ft_polygon_index_collect(l, features, nfeatures, 0, &s);
    if (rc != FT_OK)
        return rc;
    out->nfeatures = s.nfeatures;
    for (size_t r = 0; r < s.nrings; r++) {
        double a = fabs(ft_chain_signed_area(s.rings[r]));
        out->area += s.inner[r] ? -a : a;
        out->perimeter += ft_chain_length(s.rings[r]);
        out->nholes += s.inner[r];
        out->npolygons += !s.inner[r];
    }
    ft_polygon_index_clear(&s);
    return FT_OK;
}

static inline int is_class(const ft_grid *g, float v, size_t col, size_t row)
{
    return ft_grid_is_valid(g, col, row) && g->z[row * g->nx + col] == v;
}

/* Number of 4-connected patches of class cells. */
static int count_patches(const ft_grid *g, float v, size_t *patches)
{
    const size_t n = g->nx * g->ny;
    unsigned char *seen = ft_calloc(n, 1);
    size_t *stack = ft_malloc(n * sizeof *stack);
    if (seen == NULL || stack == NULL) {
        free(seen);
        free(stack);
        return FT_E_NOMEM;
    }
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        if (seen[i] || !is_class(g, v, i % g->nx, i / g->nx))
            continue;
        count++;
        size_t top = 0;
        stack[top++] = i;
        seen[i] = 1;
        while (top > 0) {
            size_t c = stack[--top], col = c % g->nx, row = c / g->nx;
            size_t nb[4] = {col > 0 ? c - 1 : SIZE_MAX, col + 1 < g->nx ? c + 1 : SIZE_MAX,
                            row > 0 ? c - g->nx : SIZE_MAX, row + 1 < g->ny ? c + g->nx : SIZE_MAX};
            for (int k = 0; k < 4; k++)
                if (nb[k] != SIZE_MAX && !seen[nb[k]] && is_class(g, v, nb[k] % g->nx, nb[k] / g->nx)) {
                    seen[nb[k]] = 1;
                    stack[top++] = nb[k];
                }
        }
    }
    free(seen);
    free(stack);
    *patches = count;
    return FT_OK;
}

int ft_urban_grid_stats(const ft_grid *classes, double class_value, ft_urban_stats *out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_grid_stats: NULL out");
    *out = (ft_urban_stats){0};
    if (classes == NULL || classes->z == NULL || classes->nx == 0 || classes->ny == 0)
        return ft_error(FT_E_EMPTY, "class statistics: empty grid");
    if (!isfinite(class_value))
        return ft_error(FT_E_INVALID, "class statistics: class value must be finite, got %g", class_value);
    const ft_grid *g = classes;
    const float v = (float)class_value;
    const double *gt = g->gt;
    const double ew = hypot(gt[1], gt[4]), eh = hypot(gt[2], gt[5]); /* cell width and height */
    size_t vertical = 0, horizontal = 0; /* class / non-class edges between columns, between rows */
    for (size_t row = 0; row < g->ny; row++)
        for (size_t col = 0; col < g->nx; col++) {
            if (!is_class(g, v, col, row))
                continue;
            out->ncells++;
            vertical += (col == 0 || !is_class(g, v, col - 1, row)) +
                        (col + 1 == g->nx || !is_class(g, v, col + 1, row));
            horizontal += (row == 0 || !is_class(g, v, col, row - 1)) +
                          (row + 1 == g->ny || !is_class(g, v, col, row + 1));
        }
    out->area = (double)out->ncells * fabs(gt[1] * gt[5] - gt[2] * gt[4]);
    out->perimeter = (double)vertical * eh + (double)horizontal * ew;
    return out->ncells > 0 ? count_patches(g, v, &out->npolygons) : FT_OK;
}
