/* fracterra — surface/grid_internal.h (private): what the grid estimators of src/surface/ share.
 *
 *  - lag_pair_sums.c: the counters' inner loop over a run of pairs, in a fixed order (vectorised);
 *  - lag_pairs.c: the pairs of cells at integer lags (exhaustive along rows and columns, or Mark &
 *    Aronson's random points in the inscribed circle) with the sums A = Σ|Δz|, B = Σ(Δz)², C = pairs
 *    of Arakawa & Krotkov §2.4, and the whole estimate from them: the variogram (B/C), Yokoya (A/C)
 *    and Pentland (the sample standard deviation of |Δz|) differ only in the statistic and the map;
 *  - grid_cells.c: validity of a cell, cell sizes, the elevation range, the sizes and elevation scale of
 *    the estimators measuring at powers of two (prism, cubes), the final fit.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_SURFACE_GRID_INTERNAL_H
#define FRACTERRA_SURFACE_GRID_INTERNAL_H

#include <math.h>

#include "fracterra/surface.h"

/* The statistic of the pairs at one lag that the log-log table holds. */
typedef enum {
    FT_LAG_STAT_MEAN_SQ = 0, /* B / C: twice the semivariance (variogram) */
    FT_LAG_STAT_MEAN_ABS = 1, /* A / C: mean |Δz| (Yokoya) */
    FT_LAG_STAT_SD_ABS = 2    /* sqrt((B - A²/C) / (C - 1)): sample sd of |Δz| (Pentland) */
} ft_lag_stat;

/* The whole lag-based estimate: checks the options, accumulates the pairs (OpenMP, per-row or
 * per-block partial sums added in order), builds the table of the statistic against the mean ground
 * distance of the pairs and fits it with map. name (static) is result->method and starts messages. */
int ft_surface_lag_dim(const ft_grid *g, const ft_variogram_opts *opts, ft_lag_stat stat, const char *name,
                       const ft_dim_map *map, ft_dim_result **out);

/* Counters of one lag (Arakawa & Krotkov §2.4): A = Σ|Δz|, B = Σ(Δz)², C = pairs, and the sum of the
 * pairs' ground distances. */
typedef struct {
    double a, b, c, dist;
} ft_lag_acc;

/** Adds to acc the sums over j < n of |zq[j] - zp[j]|, (zq[j] - zp[j])² and the pair weight, each pair
 *  weighted by wp[j] wq[j] (0 or 1: nodata; wp and wq both NULL: every weight 1, the same bits as weights
 *  of 1), in the fixed order of lag_pair_sums.c. acc->dist is left alone. */
void ft_lag_pair_sums(const float *zp, const float *wp, const float *zq, const float *wq, size_t n, ft_lag_acc *acc);
/** Streams of ft_lag_pair_sums run together (faster: their additions interleave): for s < ns (1 ..
 *  FT_LAG_STREAMS), acc[s] gets exactly what ft_lag_pair_sums(zp[s], wp[s], zq[s], wq[s], n, &acc[s]) adds;
 *  wp and wq NULL: no weights (every weight 1). */
#define FT_LAG_STREAMS 4
void ft_lag_pair_sums_streams(const float *const *zp, const float *const *wp, const float *const *zq,
                              const float *const *wq, size_t ns, size_t n, ft_lag_acc *acc);
/** Tests only: on != 0 makes the two calls above take the portable copy even where AVX2 is present (not
 *  thread-safe; the default is 0). */
void ft_lag_pair_sums_generic(int on);
/* The steps of ft_surface_lag_dim, for callers that count the pairs themselves (dim_map_lags.c):
 * the options checked against an nx x ny grid and the integer lags (malloc'd, increasing; FT_E_INVALID
 * naming the value otherwise), and the table of the statistic and its fit from the counters. */
int ft_surface_lag_plan(size_t nx, size_t ny, const ft_variogram_opts *o, const char *name, size_t **lags,
                        size_t *nl);
int ft_surface_lag_fit(const size_t *lags, const ft_lag_acc *tot, size_t nl, const ft_variogram_opts *o,
                       ft_lag_stat stat, const char *name, const ft_dim_map *map, ft_dim_result **out);
/* The options ft_surface_dim gives the lag methods for a grid of cells cx x cy (scales converted from
 * ground units to cells); FT_E_INVALID naming the value if o is out of range. */
int ft_surface_lag_opts(const ft_surface_dim_opts *o, double cx, double cy, ft_variogram_opts *v);
/* A local D map of the exhaustive lag methods by block sums (dim_map_lags.c): D, r2 and the noise flags N
 * (the output lattice, all nodata on entry; N may be NULL) filled as ft_surface_dim_map_noise does, within
 * rounding of its per-window estimates. */
int ft_surface_dim_map_lags(const ft_grid *g, size_t window, size_t step, ft_surface_method m,
                            const ft_surface_dim_opts *o, ft_grid *D, ft_grid *r2, ft_grid *N);

/* 1 if cell i is valid: not masked and finite. */
static inline int ft_surface_cell_ok(const ft_grid *g, size_t i)
{
    return (g->mask == NULL || g->mask[i]) && isfinite(g->z[i]);
}

/* Ground size of a cell along rows (cx) and columns (cy), from the geotransform. */
void ft_surface_cell_size(const ft_grid *g, double *cx, double *cy);
/* Minimum and maximum of the valid cells; FT_E_EMPTY naming `name` if none is valid. */
int ft_surface_valid_range(const ft_grid *g, const char *name, double *zmin, double *zmax);
/* FT_E_INVALID naming `name` unless g holds at least min_side x min_side cells. */
int ft_surface_check_grid(const ft_grid *g, const char *name, size_t min_side);

/* Prism and cubes: the sizes 2^kmin .. 2^kmax cells of opts (checked, defaults applied), and the
 * elevation scale zs (ground units per elevation unit, automatic when opts->zscale is 0) with the
 * smallest valid elevation zmin. FT_E_INVALID / FT_E_EMPTY naming `name` and the value. */
int ft_surface_dyadic_setup(const ft_grid *g, const ft_dyadic_opts *opts, const char *name, int *kmin, int *kmax,
                            double *zmin, double *zs);

/* What a dyadic estimator's one size needs: the elevation offset and scale, the cell sizes. */
typedef struct {
    double zmin, zs, cx, cy;
} ft_dyadic_ctx;
/* Measures squares or blocks of side s cells: value (the table's value) and count (squares or blocks
 * measured; 0 = none, the size is left out). part is scratch of 2 doubles per row of squares. */
typedef int (*ft_dyadic_size_fn)(const ft_grid *g, size_t s, const ft_dyadic_ctx *c, double *part, double *value,
                                 double *count);
/* Sums the per-row pairs part[2r], part[2r + 1] of rows 0 .. rows - 1 in order. */
void ft_surface_sum_rows(const double *part, size_t rows, double *first, double *second);
/* The whole estimate of a dyadic estimator (prism, cubes): setup, every size 2^kmin .. 2^kmax with progress
 * (scale = s x sqrt(cx cy)), the fit with map; `what` names the unit in the message when fewer than two
 * sizes could be measured ("a square without nodata corners"). result->method is name. */
int ft_surface_dyadic_dim(const ft_grid *g, const ft_dyadic_opts *opts, const char *name, const char *what,
                          const ft_dim_map *map, ft_dyadic_size_fn fn, ft_dim_result **out);

/* Fits a finished table: least squares over every row (whole = 1) or ft_loglog_fit_auto; sets
 * result->method to name. */
int ft_surface_fit_table(const ft_loglog *t, int whole, const ft_loglog_opts *fit, const ft_dim_map *map,
                         const char *name, ft_dim_result **out);

/* The noise models' inner fit (nugget_fit.c, nugget_positions.c): weighted least squares of q on (1, x),
 * q = c0 + a x, with c0 held at c0_fixed when that is >= 0, else fitted and kept >= 0. Returns the weighted
 * RSS with *c0 and *a, or INFINITY (outputs untouched) when a is not > 0. */
double ft_nugget_wls(const double *x, const double *q, const double *w, size_t n, double c0_fixed, double *c0,
                     double *a);
/* q = c0 + a exp(e lr) fitted with weights w (ft_nugget_wls), profiling e over [emin, emax] (a grid of 0.1,
 * then golden section); scratch holds 2 n values. Returns the weighted RSS (INFINITY: no a > 0 anywhere). */
double ft_nugget_profile(const double *lr, const double *q, const double *w, size_t n, double c0_fixed, double emin,
                         double emax, double *scratch, double *e, double *c0, double *a);
/* The spectrum's fit with a white-noise floor, P(f) = N0 + A f^-beta (spectrum_floor.c): N0 detected (or
 * given by no->sigma_z: N0 = sigma_z²) and removed, the fit kept below the frequency where the power law
 * falls to N0; result->nugget holds the model and "warnings" say what was done. */
int ft_spectrum_fit_noise(const ft_loglog *t, const ft_noise_opts *no, int whole, const ft_loglog_opts *fit,
                          const ft_dim_map *map, ft_dim_result **out);

#endif /* FRACTERRA_SURFACE_GRID_INTERNAL_H */
