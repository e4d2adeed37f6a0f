/* fracterra — surface/points_from_grid.c: scattered elevations sampled from a grid, the synthetic data
 * of Arakawa & Krotkov §2.5 and Table 1: "discarding 95% of the data points, selected randomly", then
 * independent Gaussian noise on x, y and z. Each kept cell gives a point at its centre with its value, or
 * (jitter) at a uniform position inside the cell with z interpolated bilinearly between the centres of
 * the four nearest cells (clamped at the border), so that positions are irregular as in a range scan.
 * The cells are chosen by a partial Fisher-Yates shuffle of the valid cells (exactly round(fraction x
 * valid) of them), then kept in row order; one RNG stream for the choice and one for positions and noise.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "fracterra/surface.h"

#define STREAM_CHOICE UINT64_C(0x5047000000000001)
#define STREAM_PLACE UINT64_C(0x5047000000000002)

static int cmp_size(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

static int cell_ok(const ft_grid *g, size_t i)
{
    return (g->mask == NULL || g->mask[i]) && isfinite(g->z[i]);
}

/* Bilinear interpolation of the cell-centre values at pixel position (u, v) (cell (c, r) covers
 * [c, c+1) x [r, r+1)); invalid neighbours fall back to the cell's own value. */
static double interpolate(const ft_grid *g, size_t cell, double u, double v)
{
    double fu = u - 0.5, fv = v - 0.5;
    long c0 = (long)floor(fu), r0 = (long)floor(fv);
    double tu = fu - (double)c0, tv = fv - (double)r0, z = 0.0;
    for (int dr = 0; dr < 2; dr++)
        for (int dc = 0; dc < 2; dc++) {
            long c = c0 + dc, r = r0 + dr;
            c = c < 0 ? 0 : c >= (long)g->nx ? (long)g->nx - 1 : c;
            r = r < 0 ? 0 : r >= (long)g->ny ? (long)g->ny - 1 : r;
            size_t i = (size_t)r * g->nx + (size_t)c;
            double w = (dc ? tu : 1.0 - tu) * (dr ? tv : 1.0 - tv);
            z += w * (cell_ok(g, i) ? (double)g->z[i] : (double)g->z[cell]);
        }
    return z;
}

int ft_surface_points_from_grid(const ft_grid *g, const ft_grid_sample_opts *opts, ft_points **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "points from grid: output pointer is NULL");
    *out = NULL;
    ft_grid_sample_opts o = FT_GRID_SAMPLE_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_grid_sample_opts) != FT_OK)
        return FT_E_INVALID;
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "points from grid: the grid is NULL or empty");
    if (!(o.fraction > 0.0 && o.fraction <= 1.0))
        return ft_error(FT_E_INVALID, "points from grid: fraction must be in (0, 1], got %g", o.fraction);
    if (!(o.noise_xy >= 0.0) || !isfinite(o.noise_xy) || !(o.noise_z >= 0.0) || !isfinite(o.noise_z))
        return ft_error(FT_E_INVALID, "points from grid: noise must be >= 0, got %g (x, y) and %g (z)", o.noise_xy,
                        o.noise_z);
    size_t ncell = g->nx * g->ny, nvalid = 0;
    size_t *cells = ft_malloc(ncell * sizeof *cells);
    ft_rng *choice = ft_rng_create(o.seed, STREAM_CHOICE), *place = ft_rng_create(o.seed, STREAM_PLACE);
    int rc = cells && choice && place ? FT_OK : FT_E_NOMEM;
    for (size_t i = 0; rc == FT_OK && i < ncell; i++)
        if (cell_ok(g, i))
            cells[nvalid++] = i;
    size_t keep = (size_t)llround(o.fraction * (double)nvalid);
    if (rc == FT_OK && keep == 0)
        rc = ft_error(FT_E_EMPTY, "points from grid: %g of %zu valid cells keeps no point", o.fraction, nvalid);
    ft_points *p = rc == FT_OK ? ft_points_create(keep) : NULL;
    if (rc == FT_OK && p == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK) {
        for (size_t k = 0; k < keep; k++) {
            size_t j = k + (size_t)ft_rng_uint(choice, nvalid - k), t = cells[k];
            cells[k] = cells[j];
            cells[j] = t;
        }
        qsort(cells, keep, sizeof *cells, cmp_size);
        for (size_t k = 0; k < keep && rc == FT_OK; k++) {
            size_t i = cells[k];
            double col = (double)(i % g->nx), row = (double)(i / g->nx), z = (double)g->z[i];
            double u = col + 0.5, v = row + 0.5;
            if (o.jitter) {
                u = col + ft_rng_uniform(place);
                v = row + ft_rng_uniform(place);
                z = interpolate(g, i, u, v);
            }
            double x, y;
            ft_grid_cell_center(g, u - 0.5, v - 0.5, &x, &y);
            x += o.noise_xy > 0.0 ? ft_rng_gaussian(place, o.noise_xy) : 0.0;
            y += o.noise_xy > 0.0 ? ft_rng_gaussian(place, o.noise_xy) : 0.0;
            z += o.noise_z > 0.0 ? ft_rng_gaussian(place, o.noise_z) : 0.0;
            rc = ft_points_push(p, x, y, z);
        }
    }
    if (rc == FT_OK && g->crs_wkt != NULL)
        rc = ft_points_set_crs(p, g->crs_wkt);
    if (rc == FT_OK) {
        *out = p;
        p = NULL;
    }
    ft_points_free(p);
    ft_rng_free(choice);
    ft_rng_free(place);
    free(cells);
    return rc;
}
