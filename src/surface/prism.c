/* fracterra — prism.c: Clarke's triangular prism surface area dimension of an elevation grid (K. C.
 * Clarke 1986, "Computation of the fractal dimension of topographic surfaces using the triangular prism
 * surface area method", Computers & Geosciences 12(5); described in Clarke 1987).
 *
 * The grid is divided into squares of side s = 2^k cells, "the size of the cells into which it can be
 * divided equally by powers of two". Over each square with corners a, b, c, d the centre gets the mean
 * elevation e = (a + b + c + d) / 4 and the square's surface is the four triangles joining its edges to
 * the centre; their 3-D areas summed give A(s). For a fractal surface A(s) ~ s^(2 - D), so
 * D = 2 - slope of log A against log s (FT_DIM_MAP_PRISM). The table holds A(s) divided by the
 * planimetric area of the squares counted (a ratio >= 1), so squares skipped at the edges or because a
 * corner is nodata do not bend the plot; scale = s x the cell size (ground units).
 *
 * The elevations are scaled by zscale (ground units per elevation unit): the area mixes horizontal and
 * vertical lengths, so the dimension depends on that choice. Automatic (0): the range of the valid
 * elevations is stretched to the grid's larger ground extent (Gwyddion's triangulation does the same),
 * which keeps the surface steep at every measured scale, where A(s) follows s^(2 - D); with gentle relief
 * in ground units (zscale = 1 on most DEMs) the triangles are nearly flat and D is biased towards 2
 * (docs/surface-grid.md has the measurements). Rows of squares run in parallel with per-row sums added in
 * order: the same bits on any thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "surface/grid_internal.h"

#define NAME "prism"

/* Area of the 3-D triangle (p, q, r) given as edge vectors u = q - p, v = r - p. */
static double tri_area(double ux, double uy, double uz, double vx, double vy, double vz)
{
    double a = uy * vz - uz * vy, b = uz * vx - ux * vz, c = ux * vy - uy * vx;
    return 0.5 * sqrt(a * a + b * b + c * c);
}

/* Surface area of one square of side (sx, sy) ground units with scaled corner elevations: a upper-left,
 * b upper-right, c lower-left, d lower-right; four triangles to the centre (Clarke's prism). */
static double square_area(double sx, double sy, double a, double b, double c, double d)
{
    double e = 0.25 * (a + b + c + d), hx = 0.5 * sx, hy = 0.5 * sy;
    return tri_area(sx, 0.0, b - a, hx, hy, e - a)      /* top: a -> b, a -> centre */
           + tri_area(0.0, sy, d - b, -hx, hy, e - b)   /* right: b -> d, b -> centre */
           + tri_area(-sx, 0.0, c - d, -hx, -hy, e - d) /* bottom: d -> c, d -> centre */
           + tri_area(0.0, -sy, a - c, hx, -hy, e - c); /* left: c -> a, c -> centre */
}

/* One row r of squares of side s cells: area sum and count into acc[0], acc[1]. */
static void square_row(const ft_grid *g, size_t s, size_t r, size_t m, double cx, double cy, double zmin,
                       double zs, double acc[2])
{
    size_t nx = g->nx, top = r * s * nx, bot = (r + 1) * s * nx;
    double sum = 0.0, n = 0.0;
    for (size_t q = 0; q < m; q++) {
        size_t i0 = top + q * s, i1 = i0 + s, i2 = bot + q * s, i3 = i2 + s;
        if (!ft_surface_cell_ok(g, i0) || !ft_surface_cell_ok(g, i1) || !ft_surface_cell_ok(g, i2) ||
            !ft_surface_cell_ok(g, i3))
            continue;
        sum += square_area((double)s * cx, (double)s * cy, ((double)g->z[i0] - zmin) * zs,
                           ((double)g->z[i1] - zmin) * zs, ((double)g->z[i2] - zmin) * zs,
                           ((double)g->z[i3] - zmin) * zs);
        n += 1.0;
    }
    acc[0] = sum;
    acc[1] = n;
}

/* One size: rows of squares in parallel, per-row sums added in order. */
static int prism_size(const ft_grid *g, size_t s, const ft_dyadic_ctx *c, double *part, double *value,
                      double *count)
{
    size_t mx = (g->nx - 1) / s, my = (g->ny - 1) / s;
#pragma omp parallel for schedule(dynamic, 8)
    for (size_t r = 0; r < my; r++)
        square_row(g, s, r, mx, c->cx, c->cy, c->zmin, c->zs, part + 2 * r);
    double area, n;
    ft_surface_sum_rows(part, my, &area, &n);
    *count = n;
    *value = n > 0.0 ? area / (n * (double)s * (double)s * c->cx * c->cy) : 0.0;
    return FT_OK;
}

int ft_surface_dim_prism(const ft_grid *g, const ft_dyadic_opts *opts, ft_dim_result **out)
{
    ft_dim_map map = FT_DIM_MAP_PRISM;
    return ft_surface_dyadic_dim(g, opts, NAME, "a square without nodata corners", &map, prism_size, out);
}
