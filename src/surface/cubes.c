/* fracterra — cubes.c: the cube-counting dimension of an elevation grid (box counting of the surface in
 * three dimensions; Voss 1986, Peitgen & Saupe "The Science of Fractal Images"; Arakawa & Krotkov §2.1 on
 * box counting and its saturation near 3).
 *
 * Space is divided into cubes of side s = 2^k cells; N(s) is the number of cubes the surface meets, and
 * N(s) ~ s^-D (FT_DIM_MAP_BOXCOUNT_SURFACE). Over each block of (s + 1) x (s + 1) cells (neighbouring
 * blocks share their edge row and column, so the surface is continuous across them) the column of cubes
 * from the one holding the block's lowest elevation to the one holding its highest is met:
 *    n = floor(zmax' / s') - floor(zmin' / s') + 1,   z' = (z - min z) x zscale,   s' = s x cell size.
 * Blocks touching nodata are skipped; the table holds the mean n per block counted times the number of
 * blocks tiling the grid, (nx - 1)(ny - 1) / s², so skipped blocks do not bend the plot.
 *
 * How z becomes cube units decides the result, since cubes are cubes: zscale is ground units per
 * elevation unit; automatic (0) stretches the range of the valid elevations to the grid's larger ground
 * extent, the convention of Gwyddion's cube counting, under which the vertical spread inside a block
 * exceeds its side at every scale of a fractal surface (no saturation at D = 2 from flat blocks). A flat
 * grid meets one cube per block and has D = 2. Rows of blocks run in parallel with per-row sums added in
 * order: the same bits on any thread count. docs/surface-grid.md.
 *
 * Biased: on exact fBm surfaces (circulant embedding, 512 x 512, seeds 1-3, automatic scales) cube
 * counting reads D - 0.06 at D = 2.1, -0.09 at 2.3, -0.13 at 2.5, -0.20 at 2.7, -0.21 at 2.8 (the count
 * of a block's column of cubes saturates as the surface roughens). Every result carries that warning.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "surface/grid_internal.h"

#define NAME "cubes"

/* One row r of blocks of side s cells (m blocks): cubes and blocks counted into acc[0], acc[1]. lo, hi
 * and bad are scratch arrays of m entries. */
static void block_row(const ft_grid *g, size_t s, size_t r, size_t m, double zmin, double zs, double side,
                      float *lo, float *hi, unsigned char *bad, double acc[2])
{
    for (size_t q = 0; q < m; q++) {
        lo[q] = INFINITY;
        hi[q] = -INFINITY;
        bad[q] = 0;
    }
    for (size_t i = r * s; i <= (r + 1) * s; i++) {
        const float *z = g->z + i * g->nx;
        for (size_t q = 0; q < m; q++) {
            if (bad[q])
                continue;
            for (size_t j = q * s; j <= (q + 1) * s; j++) {
                if (!ft_surface_cell_ok(g, i * g->nx + j)) {
                    bad[q] = 1;
                    break;
                }
                lo[q] = z[j] < lo[q] ? z[j] : lo[q];
                hi[q] = z[j] > hi[q] ? z[j] : hi[q];
            }
        }
    }
    double cubes = 0.0, n = 0.0;
    for (size_t q = 0; q < m; q++)
        if (!bad[q]) {
            cubes += floor(((double)hi[q] - zmin) * zs / side) - floor(((double)lo[q] - zmin) * zs / side) + 1.0;
            n += 1.0;
        }
    acc[0] = cubes;
    acc[1] = n;
}

/* One size: rows of blocks in parallel, per-row sums added in order; the cubes per block counted times
 * the blocks tiling the grid. */
static int cubes_size(const ft_grid *g, size_t s, const ft_dyadic_ctx *c, double *part, double *value,
                      double *count)
{
    size_t mx = (g->nx - 1) / s, my = (g->ny - 1) / s;
    double side = (double)s * sqrt(c->cx * c->cy);
    int failed = 0;
#pragma omp parallel reduction(| : failed)
    {
        float *lo = malloc(mx * sizeof *lo), *hi = malloc(mx * sizeof *hi);
        unsigned char *bad = malloc(mx);
        failed |= lo == NULL || hi == NULL || bad == NULL;
#pragma omp for schedule(dynamic, 4)
        for (size_t r = 0; r < my; r++)
            if (!failed)
                block_row(g, s, r, mx, c->zmin, c->zs, side, lo, hi, bad, part + 2 * r);
        free(lo);
        free(hi);
        free(bad);
    }
    if (failed)
        return ft_error(FT_E_NOMEM, NAME ": out of memory");
    double cubes, blocks, tiling = (double)(g->nx - 1) * (double)(g->ny - 1) / ((double)s * (double)s);
    ft_surface_sum_rows(part, my, &cubes, &blocks);
    *count = blocks;
    *value = blocks > 0.0 ? cubes / blocks * tiling : 0.0;
    return FT_OK;
}

int ft_surface_dim_cubes(const ft_grid *g, const ft_dyadic_opts *opts, ft_dim_result **out)
{
    ft_dim_map map = FT_DIM_MAP_BOXCOUNT_SURFACE;
    int rc = ft_surface_dyadic_dim(g, opts, NAME, "a block free of nodata", &map, cubes_size, out);
    if (rc == FT_OK)
        rc = ft_dim_result_warn(*out, "biased: cube counting reads low on fractal surfaces, measured on exact fBm "
                                "by -0.06 at D = 2.1, -0.13 at D = 2.5, -0.21 at D = 2.8 (docs/surface-grid.md); "
                                "prefer the variogram");
    if (rc != FT_OK) {
        ft_dim_result_free(*out);
        *out = NULL;
    }
    return rc;
}
