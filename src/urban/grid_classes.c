/* fracterra — src/urban/grid_classes.c: the classes of a classified raster (land use coded 1, 2, ... per
 * cell, Zhang, Yu & Fan 2008, §1.2): the distinct values of its valid cells, increasing. A raster whose
 * values are not whole numbers, or that has more distinct values than a classification would, is a
 * continuous surface, and the error says so.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "fracterra/urban.h"
#include "internal.h"

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

/* Checks the distinct values v[0..m) of a classified raster. */
static int check_classes(const float *v, size_t m, size_t max_classes)
{
    if (m == 0)
        return ft_error(FT_E_EMPTY, "the raster has no valid cell");
    for (size_t i = 0; i < m; i++)
        if (!isfinite(v[i]) || v[i] != floorf(v[i]))
            return ft_error(FT_E_INVALID, "the raster holds %g, not a whole number: it does not look like a "
                                          "classified raster (one class code per cell)",
                            (double)v[i]);
    if (m > max_classes)
        return ft_error(FT_E_INVALID, "the raster has %zu distinct values, more than %zu: it does not look like a "
                                      "classified raster (one class per cell value)",
                        m, max_classes);
    return FT_OK;
}

int ft_urban_grid_classes(const ft_grid *g, size_t max_classes, float **values, size_t *n)
{
    if (g == NULL || values == NULL || n == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_grid_classes: NULL argument");
    *values = NULL;
    *n = 0;
    size_t cells = g->nx * g->ny, k = 0;
    float *v = ft_malloc((cells ? cells : 1) * sizeof *v);
    if (v == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < cells; i++)
        if (g->mask == NULL || g->mask[i])
            v[k++] = g->z[i];
    qsort(v, k, sizeof *v, cmp_float);
    size_t m = 0;
    for (size_t i = 0; i < k; i++)
        if (m == 0 || v[i] != v[m - 1])
            v[m++] = v[i];
    int rc = check_classes(v, m, max_classes);
    if (rc != FT_OK) {
        free(v);
        return rc;
    }
    *values = v;
    *n = m;
    return FT_OK;
}
