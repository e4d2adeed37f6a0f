/* fracterra — surface.h: the fractal dimension of elevation grids and of scattered elevations.
 *
 * Papers: Mark & Aronson (1984) variogram; Arakawa & Krotkov §2 (Yokoya and Pentland estimators, log-log
 * segmentation, seeds 003); Clarke (1986, 1987) triangular prism and spectrum (seeds 004).
 * docs/surface-*.md hold the equations and limits.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_SURFACE_H
#define FRACTERRA_SURFACE_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    double min_lag;     /**< smallest lag in cells; 0 = 1 */
    double max_lag;     /**< largest lag in cells; 0 = automatic */
    int nlags;          /**< lags in the geometric series; 0 = automatic */
    size_t pairs;       /**< 0 = exhaustive over the grid; N = N random points inside the largest inscribed
                             circle, each paired at every lag (Mark & Aronson) */
    uint64_t seed;      /**< for random pairs; default 1 */
    ft_loglog_opts fit;
    int fit_whole_range; /**< 1: fit every lag between min and max, no segmentation */
    ft_progress_fn progress;
    void *progress_arg;
} ft_variogram_opts;
#define FT_VARIOGRAM_OPTS_DEFAULT {0.0, 0.0, 0, 0, 1, FT_LOGLOG_OPTS_DEFAULT, 0, NULL, NULL}

/** Variogram dimension of a grid: mean squared elevation difference against lag (in ground units),
 *  D = 3 - slope/2. Pairs touching nodata are skipped. */
int ft_surface_dim_variogram(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_SURFACE_H */
