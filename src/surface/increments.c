/* fracterra — increments.c: Yokoya's and Pentland's estimators on an elevation grid (Arakawa & Krotkov,
 * "Fractal modeling of natural terrain", §2.3 eqs. 3-5 and §2.4 step 1; Pentland 1984, Yokoya
 * et al. 1989).
 *
 * For a fractal Brownian function the absolute elevation difference |Δz| of two points a distance Δd
 * apart is distributed as Δd^H times a fixed law, so both its mean E|Δz| (Yokoya) and its standard
 * deviation S(|Δz|) (Pentland) grow as Δd^H and D = 3 - H (FT_DIM_MAP_INCREMENT_SURFACE). On a grid the
 * pairs are those of the variogram (src/surface/lag_pairs.c: exhaustive along rows and columns, or Mark &
 * Aronson's random points; pairs touching nodata skipped), with the paper's counters A = Σ|Δz|,
 * B = Σ(Δz)², C = pairs per lag:
 *    Yokoya    E = A / C
 *    Pentland  S = sqrt((B - A²/C) / (C - 1))   (the sample standard deviation of |Δz|)
 * the same statistics as the scattered-points estimators (ft_surface_dim_points), so a grid and the points
 * sampled from it are measured alike. docs/surface-grid.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "surface/grid_internal.h"

int ft_surface_dim_yokoya(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out)
{
    ft_dim_map map = FT_DIM_MAP_INCREMENT_SURFACE;
    return ft_surface_lag_dim(g, opts, FT_LAG_STAT_MEAN_ABS, "yokoya", &map, out);
}

int ft_surface_dim_pentland(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out)
{
    ft_dim_map map = FT_DIM_MAP_INCREMENT_SURFACE;
    return ft_surface_lag_dim(g, opts, FT_LAG_STAT_SD_ABS, "pentland", &map, out);
}
