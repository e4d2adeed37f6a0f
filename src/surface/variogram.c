/* fracterra — variogram.c: the variogram dimension of an elevation grid (Mark & Aronson 1984, "Scale-
 * dependent fractal dimensions of topographic surfaces", Math. Geology 16(7); Clarke's survey).
 *
 * For fBm, E(z(x + d) - z(x))^2 ~ d^(2H), so the slope s of log mean squared difference against log lag
 * gives H = s/2 and D = 3 - s/2 (FT_DIM_MAP_VARIOGRAM_SURFACE): the table holds B/C, the mean squared
 * difference, of the pairs of src/surface/lag_pairs.c (shared with Yokoya and Pentland). Lags are whole
 * numbers of cells, a geometric series from min_lag to max_lag with duplicates after rounding removed.
 *  - Exhaustive (pairs == 0): every pair of cells `lag` apart along a row or along a column (the two axis
 *    directions; diagonals are not used). The row's scale is the mean ground distance of its pairs
 *    (lag x the cell size when cells are square).
 *  - Random (pairs = N): Mark & Aronson's sampling: N points uniform inside the largest circle inscribed
 *    in the grid, each paired at every lag with the cell nearest to the point lag cells away in a random
 *    direction (the partner must lie inside the circle); the row's scale is the mean ground distance of
 *    the pairs actually formed. One RNG stream per block of 256 points.
 * Pairs touching a nodata or non-finite cell are skipped. Per-row (per-block) partial sums are reduced in
 * order, so the result does not depend on the thread count. docs/surface-variogram.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "surface/grid_internal.h"

int ft_surface_dim_variogram(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out)
{
    ft_dim_map map = FT_DIM_MAP_VARIOGRAM_SURFACE;
    return ft_surface_lag_dim(g, opts, FT_LAG_STAT_MEAN_SQ, "variogram", &map, out);
}
