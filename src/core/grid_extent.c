/* fracterra — core/grid_extent.c: the grid of a given cell size over an extent: the shape and geotransform
 * of a raster that covers a box (an --extent), or a bounding box of scattered points snapped outward to
 * whole multiples of the cell, as gdal_grid and GRASS's g.region -a align a region.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/core.h"

#define MAX_SIDE 2147483647.0

/* Cells along a side of length len (the last cell may reach past the end; a side shorter than one cell or
 * of zero length is one cell). */
static double cells_along(double len, double cell)
{
    double n = ceil(len / cell - 1e-9);
    return n < 1.0 ? 1.0 : n;
}

int ft_grid_shape_for_extent(double xmin, double ymin, double xmax, double ymax, double cell, int snap, size_t *nx,
                             size_t *ny, double gt[6])
{
    if (nx == NULL || ny == NULL || gt == NULL)
        return ft_error(FT_E_INVALID, "ft_grid_shape_for_extent: NULL output");
    if (!(cell > 0.0) || !isfinite(cell))
        return ft_error(FT_E_INVALID, "cell size must be > 0 and finite, got %g", cell);
    if (!isfinite(xmin) || !isfinite(ymin) || !isfinite(xmax) || !isfinite(ymax) || !(xmin <= xmax) ||
        !(ymin <= ymax))
        return ft_error(FT_E_INVALID, "extent must be finite with xmin <= xmax and ymin <= ymax, got %g,%g,%g,%g",
                        xmin, ymin, xmax, ymax);
    if (snap) { /* outward to multiples of cell; the box's right and bottom edges strictly inside */
        xmin = floor(xmin / cell) * cell;
        xmax = (floor(xmax / cell) + 1.0) * cell;
        ymin = (ceil(ymin / cell) - 1.0) * cell;
        ymax = ceil(ymax / cell) * cell;
    }
    double cx = cells_along(xmax - xmin, cell), cy = cells_along(ymax - ymin, cell);
    if (!(cx <= MAX_SIDE && cy <= MAX_SIDE))
        return ft_error(FT_E_INVALID, "cell %g over %g x %g gives %.0f x %.0f cells, more than %.0f per side", cell,
                        xmax - xmin, ymax - ymin, cx, cy, MAX_SIDE);
    *nx = (size_t)cx;
    *ny = (size_t)cy;
    const double t[6] = {xmin, cell, 0.0, ymax, 0.0, -cell};
    for (int i = 0; i < 6; i++)
        gt[i] = t[i];
    return FT_OK;
}
