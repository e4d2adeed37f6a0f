/* fracterra — surface.h: the fractal dimension of elevation grids and of scattered elevations.
 *
 * Papers: Mark & Aronson (1984) variogram; Arakawa & Krotkov §2 (Yokoya and Pentland estimators, log-log
 * segmentation); Clarke (1986, 1987) triangular prism and spectrum.
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

/* ------------------------------------------------------------------------------------------------
 * Noise on the elevations (the nugget) for the lag estimators: docs/surface-noise.md.
 * --------------------------------------------------------------------------------------------- */

/** The structure function a lag estimator's table holds. */
typedef enum {
    FT_STRUCT_MEAN_SQ = 0,  /**< mean Δz² (variogram): nugget 2σ² */
    FT_STRUCT_MEAN_ABS = 1, /**< mean |Δz| (Yokoya): its square has nugget 4σ²/π */
    FT_STRUCT_SD_ABS = 2    /**< sd of |Δz| (Pentland): its square has nugget 2σ²(1 - 2/π) */
} ft_structure_stat;

/** What the lag estimators know or assume about white noise in the data. */
typedef struct {
    size_t struct_size; /**< sizeof(ft_noise_opts); see FT_OPTS in core.h */
    int mode;        /**< 0 (default): detect a nugget and remove it; -1: no noise model */
    double sigma_z;  /**< known sd of white noise on z (z units); 0 = unknown (estimated when detected) */
    double sigma_xy; /**< known sd of noise on x and y (ground units); 0 = unknown. Lags below 3 sigma_xy are
                          left out of the fit */
} ft_noise_opts;
#define FT_NOISE_OPTS_DEFAULT {.struct_size = sizeof(ft_noise_opts), .mode = 0, .sigma_z = 0.0, .sigma_xy = 0.0}

/** Fits value^power = c0 + a scale^(2H) to every row of t (power 1 for FT_STRUCT_MEAN_SQ, 2 otherwise),
 *  weights 1/value^(2 power), profiling H; with sigma_z > 0, c0 is held at the nugget that sigma_z gives.
 *  m receives c0, a, H, the F statistic of c0 (automatic case) and the sigma_z c0 implies. Needs 4 rows
 *  (3 with sigma_z); FT_E_NUMERIC when no increasing power law fits. */
FT_API int ft_nugget_fit(const ft_loglog *t, ft_structure_stat stat, double sigma_z, ft_noise_model *m);
/** 1 if the fitted model m of t holds a significant nugget: F above the 5% point of F(1, t->n - 3) and
 *  c0 >= 5% of the smallest lag's value^power (ft_surface_fit_noise passes the lags within 4 x the
 *  smallest, at least 4: docs/surface-noise.md). */
FT_API int ft_nugget_detected(const ft_noise_model *m, const ft_loglog *t);
/** A new table of t with c0 removed from each value^power (rows with nothing left dropped); sets
 *  m->applied and m->floor = max(min_floor, the scale where a scale^(2H) = c0). */
FT_API int ft_nugget_remove(const ft_loglog *t, ft_noise_model *m, double min_floor, ft_loglog **out);
/** Scattered points with noise on x, y (sd sigma_p) and z: E Δz²(d) = c0 + a E|d + δ|^(2H), δ ~ N(0, s² I₂),
 *  s = sqrt(2) sigma_p, fitted to the mean squared differences q at the n increasing distances d
 *  (profiling H and s; c0 = 2 sigma_z² and s held when sigma_z, sigma_xy > 0 are given). m->detected
 *  says whether the noise terms are significant (F >= 3 on the two extra parameters and the noise >= 2%
 *  of q at the smallest lag) or given. Needs 6 lags. docs/surface-noise.md. */
FT_API int ft_nugget_fit_positions(const double *d, const double *q, size_t n, double sigma_z, double sigma_xy,
                            ft_noise_model *m);
/** E|d + δ|^(2H) for δ ~ N(0, s² I₂) (d^(2H) when s = 0). */
FT_API double ft_nugget_eiv_moment(double H, double d, double s);
/** The model of ft_nugget_fit_positions at distance d: c0 + a E|d + δ|^(2H). */
FT_API double ft_nugget_model_value(const ft_noise_model *m, double d);

/** The fit of a lag estimator's table with the noise model of no: a nugget detected (or given) is removed
 *  and the fit starts at the floor (whole: least squares from there; otherwise ft_loglog_fit_auto from
 *  there); result->nugget holds the model and "warnings" say what was done. */
FT_API int ft_surface_fit_noise(const ft_loglog *t, const ft_noise_opts *no, ft_structure_stat stat, int whole,
                         const ft_loglog_opts *fit, const ft_dim_map *map, ft_dim_result **out);

typedef struct {
    size_t struct_size; /**< sizeof(ft_variogram_opts); see FT_OPTS in core.h */
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
    ft_noise_opts noise; /**< white noise on z (nugget): detected and removed by default */
} ft_variogram_opts;
#define FT_VARIOGRAM_OPTS_DEFAULT                                                                                    \
    {.struct_size = sizeof(ft_variogram_opts), .min_lag = 0.0, .max_lag = 0.0, .nlags = 0, .pairs = 0, .seed = 1,    \
     .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_whole_range = 0, .progress = NULL, .progress_arg = NULL,                    \
     .noise = FT_NOISE_OPTS_DEFAULT}

/** Variogram dimension of a grid: mean squared elevation difference against lag (in ground units),
 *  D = 3 - slope/2. Pairs touching nodata are skipped. */
FT_API int ft_surface_dim_variogram(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out);

/* ------------------------------------------------------------------------------------------------
 * Grids: Yokoya, Pentland, power spectrum, triangular prisms, cube counting; one dispatcher over them
 * and the variogram; local D maps (docs/surface-grid.md).
 * --------------------------------------------------------------------------------------------- */

/** Yokoya's estimator on a grid: mean |Δz| of the pairs at each lag (the variogram's lags, pairs and
 *  nodata rules: ft_variogram_opts), E|Δz| ~ d^H, D = 3 - H. result->method is "yokoya". */
FT_API int ft_surface_dim_yokoya(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out);
/** Pentland's: the sample standard deviation of |Δz| at each lag, sqrt((B - A²/C) / (C - 1)) with
 *  A = Σ|Δz|, B = Σ(Δz)², C = pairs (Arakawa & Krotkov §2.4), ~ d^H, D = 3 - H. "pentland". */
FT_API int ft_surface_dim_pentland(const ft_grid *g, const ft_variogram_opts *opts, ft_dim_result **out);

typedef struct {
    size_t struct_size; /**< sizeof(ft_spectrum_opts); see FT_OPTS in core.h */
    double min_wavelength; /**< shortest wavelength fitted, cells, >= 2; 0 = 8 (the band near the Nyquist
                                frequency, flattened by aliasing, is left out) */
    double max_wavelength; /**< longest, cells, <= tile; 0 = tile / 8 (at least twice min_wavelength):
                                the lowest frequencies are bent by the taper and the plane removed */
    int nbins;             /**< radial frequency bins, log-spaced between them (2..1000); 0 = 4 per octave */
    size_t tile;           /**< side of the square tiles (Welch), cells, >= 8; 0 = automatic: min(nx, ny),
                                halved while no tile is usable (see elevations; down to 16) */
    int window;            /**< elevations = 1 only: 1 (default) a 2-D Hann taper on each tile, 0 none */
    ft_loglog_opts fit;
    int fit_whole_range;   /**< 1: least squares over every bin, no segmentation */
    ft_progress_fn progress;
    void *progress_arg;
    int elevations;        /**< 0 (default): the periodogram of the first differences along rows and
                                columns (prewhitening), untapered (window is ignored), the differencing
                                gain divided out; differences touching nodata are left out and the power
                                normalised by the valid ones, so tiles may hold nodata (a tile is used
                                when half of its differences are valid; the automatic tile is halved
                                while none is). 1: the periodogram of the detrended elevations, tapered
                                as window says, on tiles free of nodata (as described above). */
    ft_noise_opts noise;   /**< white noise on z: a flat floor N0 = sigma_z² under the power law, detected
                                and removed by default (sigma_xy is not used); docs/surface-noise.md */
} ft_spectrum_opts;
#define FT_SPECTRUM_OPTS_DEFAULT                                                                                     \
    {.struct_size = sizeof(ft_spectrum_opts), .min_wavelength = 0.0, .max_wavelength = 0.0, .nbins = 0, .tile = 0,   \
     .window = 1, .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_whole_range = 0, .progress = NULL, .progress_arg = NULL,       \
     .elevations = 0, .noise = FT_NOISE_OPTS_DEFAULT}

/** Power-spectrum dimension: square tiles overlapping by half (Welch); by default the periodograms of
 *  the first differences along rows and columns (nodata-aware, the differencing gain divided out), or
 *  with opts->elevations those of the detrended, tapered elevations of nodata-free tiles; averaged and
 *  radially averaged in log-spaced frequency bins; P(f) ~ f^-beta, D = (8 - beta) / 2 (FT_DIM_MAP_SPECTRUM_SURFACE). The table's scale is
 *  the frequency in cycles per ground unit. A plane (nothing left after detrending) or a surface smoother
 *  than any fBm (beta > 4.2, D < 1.9) is FT_E_NUMERIC "degenerate for the spectrum". A white-noise floor
 *  P = N0 + A f^-beta is detected and removed by default (opts->noise; docs/surface-noise.md). "spectrum". */
FT_API int ft_surface_dim_spectrum(const ft_grid *g, const ft_spectrum_opts *opts, ft_dim_result **out);

/** Options of the estimators measuring at cell sizes by powers of two (prism, cubes). */
typedef struct {
    size_t struct_size; /**< sizeof(ft_dyadic_opts); see FT_OPTS in core.h */
    double min_size;   /**< smallest square side or cube side, cells, rounded up to a power of two; 0 = 1 */
    double max_size;   /**< largest, cells, rounded down to a power of two; 0 = the largest power of two
                            <= min(nx - 1, ny - 1) / 8 */
    double zscale;     /**< ground units per elevation unit; 0 = automatic: the range of the valid
                            elevations is stretched to 4 times the grid's larger ground extent, which
                            keeps every measured scale steep (Gwyddion stretches to 1 times);
                            1 = elevations taken in ground units as they are (Clarke) */
    ft_loglog_opts fit;
    int fit_whole_range; /**< 1: least squares over every size, no segmentation */
    ft_progress_fn progress;
    void *progress_arg;
} ft_dyadic_opts;
#define FT_DYADIC_OPTS_DEFAULT                                                                                       \
    {.struct_size = sizeof(ft_dyadic_opts), .min_size = 0.0, .max_size = 0.0, .zscale = 0.0,                         \
     .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_whole_range = 0, .progress = NULL, .progress_arg = NULL}

/** Clarke's (1986) triangular prism surface area: squares of side s = 2^k cells, four triangles from
 *  the edges to the centre (mean of the corners); surface area over planimetric area against s,
 *  A(s) ~ s^(2-D) (FT_DIM_MAP_PRISM). Squares with a nodata corner are skipped. "prism". */
FT_API int ft_surface_dim_prism(const ft_grid *g, const ft_dyadic_opts *opts, ft_dim_result **out);
/** Cube counting: blocks of (s+1) x (s+1) cells (s = 2^k, neighbouring blocks share an edge), each
 *  covered by the cubes of side s it meets, z scaled as zscale says; the cubes per block times the
 *  blocks tiling the grid, N(s) ~ s^-D (FT_DIM_MAP_BOXCOUNT_SURFACE). Blocks touching nodata are
 *  skipped. "cubes". */
FT_API int ft_surface_dim_cubes(const ft_grid *g, const ft_dyadic_opts *opts, ft_dim_result **out);

typedef enum {
    FT_SURFACE_VARIOGRAM = 0,
    FT_SURFACE_YOKOYA = 1,
    FT_SURFACE_PENTLAND = 2,
    FT_SURFACE_SPECTRUM = 3,
    FT_SURFACE_PRISM = 4,
    FT_SURFACE_CUBES = 5
} ft_surface_method;
#define FT_SURFACE_NMETHODS 6
/** The default method of `dim surface` and `dim map` (docs/surface-grid.md gives the evidence). */
#define FT_SURFACE_DEFAULT_METHOD FT_SURFACE_VARIOGRAM

/** Options of the dispatcher: each method's own options are filled from these (unset = its default). */
typedef struct {
    size_t struct_size; /**< sizeof(ft_surface_dim_opts); see FT_OPTS in core.h */
    double min_scale;  /**< ground units: smallest lag, square or cube side, or wavelength; 0 = default */
    double max_scale;  /**< largest; 0 = the method's default */
    int nscales;       /**< lags or frequency bins; 0 = default; prism and cubes use powers of two */
    size_t pairs;      /**< variogram, yokoya, pentland: 0 = exhaustive, N = N random points */
    uint64_t seed;     /**< random pairs; default 1 */
    double zscale;     /**< prism, cubes: see ft_dyadic_opts; default 0 (automatic) */
    size_t tile;       /**< spectrum: see ft_spectrum_opts; default 0 (automatic) */
    double min_valid;  /**< dim map: a window with a smaller fraction of valid cells is nodata; (0, 1],
                            default 0.5 */
    ft_loglog_opts fit;
    int fit_whole_range; /**< 1: least squares over the whole range, no segmentation */
    ft_progress_fn progress;
    void *progress_arg;
    ft_noise_opts noise; /**< variogram, yokoya, pentland: the noise model (nugget); spectrum: its white-noise
                              floor; default automatic */
} ft_surface_dim_opts;
#define FT_SURFACE_DIM_OPTS_DEFAULT                                                                                  \
    {.struct_size = sizeof(ft_surface_dim_opts), .min_scale = 0.0, .max_scale = 0.0, .nscales = 0, .pairs = 0,       \
     .seed = 1, .zscale = 0.0, .tile = 0, .min_valid = 0.5, .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_whole_range = 0,     \
     .progress = NULL, .progress_arg = NULL, .noise = FT_NOISE_OPTS_DEFAULT}

/** "variogram", "yokoya", "pentland", "spectrum", "prism", "cubes" ("?" for a bad value). */
FT_API const char *ft_surface_method_name(ft_surface_method m);
/** The method named (case-insensitive); FT_E_INVALID naming the text otherwise. */
FT_API int ft_surface_method_parse(const char *name, ft_surface_method *m);
/** Fractal dimension of a grid by one method. result->method is the method's name. */
FT_API int ft_surface_dim(const ft_grid *g, ft_surface_method m, const ft_surface_dim_opts *opts, ft_dim_result **out);

/** A local D map: ft_surface_dim in every window of window x window cells whose upper-left cell is a
 *  multiple of step along both axes (windows inside the grid). D_out and r2_out (either may be NULL)
 *  receive grids of ((nx - window) / step + 1) x ((ny - window) / step + 1) cells on the lattice of the
 *  window centres: each output cell is step x step input cells centred on its window's centre, with the
 *  input's CRS. A window with fewer valid cells than opts->min_valid, or where the method fails, is
 *  nodata. OpenMP over windows; the same on every thread count. Progress from 0 to 1. */
FT_API int ft_surface_dim_map(const ft_grid *g, size_t window, size_t step, ft_surface_method m,
                       const ft_surface_dim_opts *opts, ft_grid **D_out, ft_grid **r2_out);
/** ft_surface_dim_map with, in *nugget_out (may be NULL, as D_out and r2_out), the noise flag of every
 *  window on the same lattice: 1 where the window's noise model removed white noise (variogram, yokoya,
 *  pentland: a nugget, nugget_fit.c; spectrum: a floor, spectrum_floor.c), 0 where the window was measured
 *  without, nodata where D is. The D and r2 cells are those of ft_surface_dim_map. docs/surface-noise.md. */
FT_API int ft_surface_dim_map_noise(const ft_grid *g, size_t window, size_t step, ft_surface_method m,
                                    const ft_surface_dim_opts *opts, ft_grid **D_out, ft_grid **r2_out,
                                    ft_grid **nugget_out);

/** The exhaustive lag estimate (variogram, yokoya or pentland with pairs = 0) of a grid too large for memory,
 *  accumulated stripe by stripe (lag_stripes.c; docs/tiling.md): the per-row counters of a stripe of rows
 *  [r0, r1) are formed from the stripe plus the halo rows below it, and added in global row order, so D, the
 *  table and every figure of the result are bit for bit those of ft_surface_dim on the whole grid, for any
 *  stripe height and any number of processes. */
typedef struct ft_lag_stripes ft_lag_stripes;

/** A stripe accumulator for the grid described by header (nx, ny, geotransform; its cells are not read).
 *  FT_E_UNSUPPORTED for another method or random pairs; the options' errors as ft_surface_dim. */
FT_API int ft_surface_lag_stripes_create(const ft_grid *header, ft_surface_method m, const ft_surface_dim_opts *opts,
                                         ft_lag_stripes **out);
/** Rows a stripe must hold below its last row (the largest lag in cells; fewer at the grid's bottom). */
FT_API size_t ft_surface_lag_stripes_halo(const ft_lag_stripes *s);
/** Doubles of one row's counters (4 per lag). */
FT_API size_t ft_surface_lag_stripes_nsums(const ft_lag_stripes *s);
/** The counters of rows [r0, r1) into sums ((r1 - r0) x nsums doubles) from stripe, a grid of the whole
 *  width whose row 0 is global row stripe_row0 and which holds rows r0 .. min(r1 + halo, ny) - 1. OpenMP
 *  over rows; the same on any thread count. s is not changed. */
FT_API int ft_surface_lag_stripes_rows(const ft_lag_stripes *s, const ft_grid *stripe, size_t stripe_row0, size_t r0,
                                       size_t r1, double *sums);
/** Reads nrows rows of the grid from row0 (the whole width) into *out; FT_OK or an FT_E_* code (error set). */
typedef int (*ft_rows_fn)(void *arg, size_t row0, size_t nrows, ft_grid **out);
/** The counters of ft_surface_lag_stripes_rows for rows [r0, r1), bit for bit, without holding the max_lag rows
 *  below the stripe: rows [r0, r1 + near) are read once through read and give the lags <= near; each longer
 *  lag h reads rows [r0 + h, r1 + h) (clipped to the grid) for its column pairs. Peak memory: about
 *  (2 (r1 - r0) + near) rows of 8 bytes a cell instead of (r1 - r0 + max_lag); reads: the stripe once more
 *  per lag beyond near. */
FT_API int ft_surface_lag_stripes_rows_read(const ft_lag_stripes *s, ft_rows_fn read, void *arg, size_t r0,
                                            size_t r1, size_t near, double *sums);
/** Adds the counters of rows [r0, r1) to the running totals; r0 must be the first row not yet added. */
FT_API int ft_surface_lag_stripes_add(ft_lag_stripes *s, size_t r0, size_t r1, const double *sums);
/** The running totals (nsums doubles into sums, which may be NULL); returns the first row not yet added. For
 *  handing the accumulation from one process to the next (MPI ranks in row order). */
FT_API size_t ft_surface_lag_stripes_state(const ft_lag_stripes *s, double *sums);
/** Sets the running totals and the next row from ft_surface_lag_stripes_state of another accumulator. */
FT_API int ft_surface_lag_stripes_resume(ft_lag_stripes *s, const double *sums, size_t next_row);
/** The estimate once every row has been added (FT_E_INVALID naming the missing rows otherwise). */
FT_API int ft_surface_lag_stripes_fit(const ft_lag_stripes *s, ft_dim_result **out);
FT_API void ft_surface_lag_stripes_free(ft_lag_stripes *s);

/* ------------------------------------------------------------------------------------------------
 * Scattered elevations: Yokoya's and Pentland's estimators on irregularly sampled points
 * (Arakawa & Krotkov §2.3-2.4; docs/surface-points.md).
 *
 * Step 1 of §2.4: for every lag Δd_i, counters A_i = Σ|z - z'|, B_i = Σ(z - z')² and C_i = number of
 * pairs over every pair of points whose separation d satisfies |d - Δd_i| <= ε (an annulus of width 2ε).
 * The sums are accumulated in 128-bit fixed point (exact and order-free), so the grid, exact and any
 * thread count give bit-identical counters. Lags with fewer than min_pairs pairs are dropped and
 * reported. Steps 2-3: log statistic against log separation, D = 3 - H (FT_DIM_MAP_INCREMENT_SURFACE).
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_POINTS_YOKOYA = 0,  /**< mean of |Δz|: A_i / C_i (Yokoya; the paper's E_Δd) */
    FT_POINTS_PENTLAND = 1 /**< sample standard deviation of |Δz|: sqrt((B_i - A_i²/C_i) / (C_i - 1))
                                (Pentland; the paper's S_Δd) */
} ft_points_method;

/** Why a lag is not in the log-log table. */
typedef enum {
    FT_LAG_KEPT = 0,
    FT_LAG_FEW_PAIRS = 1, /**< fewer pairs than min_pairs (sample mode: fewer drawn pairs) */
    FT_LAG_NOISE = 2,     /**< the noise model removed all of the statistic (noise_sigma too large) */
    FT_LAG_ZERO = 3       /**< every pair has the same elevation: the statistic is 0 */
} ft_lag_status;

/** The counters of one lag. */
typedef struct {
    double lag;      /**< Δd_i, ground units */
    double dist;     /**< mean separation of the pairs counted: the table's scale (0 without pairs) */
    double A, B;     /**< Σ|z - z'| and Σ(z - z')² (sample mode: estimates of the sums over all pairs) */
    double C;        /**< pairs: an exact integer, or the estimate of the count in sample mode */
    uint64_t drawn;  /**< sample mode: drawn pairs that fell on this lag; otherwise equal to C */
    double value;    /**< the method's statistic after the noise model (NaN when dropped for noise) */
    double value_se; /**< sample mode: standard error of value from the sampling; 0 otherwise */
    ft_lag_status status;
} ft_points_lag;

/** The per-lag counters of one estimate, dropped lags included. Release with ft_points_counters_free. */
typedef struct {
    ft_points_method method;
    ft_points_lag *lags; /**< n lags by increasing Δd */
    size_t n;
    size_t kept;         /**< lags with status FT_LAG_KEPT */
    double eps;          /**< ε used */
    double spacing;      /**< mean point spacing sqrt(bounding-box area / N), the unit of the default lags */
    size_t min_pairs;
    const char *pairs;   /**< static: "grid", "exact" or "sample" */
    uint64_t sample;     /**< pairs drawn (sample mode), 0 otherwise */
    double D_sample_se;  /**< sample mode: standard error of D from the sampling (filled by
                              ft_surface_dim_points), 0 otherwise */
} ft_points_counters;

FT_API void ft_points_counters_free(ft_points_counters *c);

typedef struct {
    size_t struct_size; /**< sizeof(ft_points_dim_opts); see FT_OPTS in core.h */
    ft_points_method method;
    const double *lags;   /**< user lags Δd_i (ground units, > 0, distinct, any order), or NULL */
    size_t nuser_lags;    /**< number of user lags (>= 2 when lags is given) */
    double min_lag;       /**< geometric series: smallest lag; 0 = 0.5 x the mean spacing */
    double max_lag;       /**< largest lag; 0 = 4 x the mean spacing */
    int nlags;            /**< lags in the series (2..1000); 0 = 4 per octave + 1 */
    double eps;           /**< annulus half-width ε, 0 < ε < smallest lag; 0 = half the smallest gap
                               between consecutive lags */
    size_t min_pairs;     /**< >= 1; default 100 */
    int exact;            /**< 1: enumerate every pair i < j (O(N²)); same counters as the grid */
    size_t sample;        /**< > 0: estimate from this many random pairs within the largest lag */
    uint64_t seed;        /**< sample mode; default 1 */
    double noise_sigma;   /**< standard deviation of zero-mean Gaussian noise on z (>= 0; 0 = none):
                               removes 2σ² from E(Δz²) (docs/surface-points.md) */
    ft_loglog_opts fit;
    int fit_auto;         /**< 0 (default): least squares over every kept lag; 1: ft_loglog_fit_auto
                               (ILS segmentation) */
    ft_points_counters **counters; /**< if not NULL, receives the counters (release with
                                        ft_points_counters_free); set to NULL on failure */
    ft_progress_fn progress;
    void *progress_arg;
    double noise_sigma_xy; /**< known sd of noise on x and y (ground units, >= 0; 0 = unknown): lags below 3x
                                it are left out of the fit (docs/surface-noise.md) */
    int noise_mode;       /**< 0 (default): detect a nugget (white noise) in the statistic and remove it, the
                               default lags then extended to 32 x the mean spacing (at most a quarter of
                               the bounding box's shorter side); -1: no noise model */
} ft_points_dim_opts;
#define FT_POINTS_DIM_OPTS_DEFAULT                                                                                   \
    {.struct_size = sizeof(ft_points_dim_opts), .method = FT_POINTS_YOKOYA, .lags = NULL, .nuser_lags = 0,           \
     .min_lag = 0.0, .max_lag = 0.0, .nlags = 0, .eps = 0.0, .min_pairs = 100, .exact = 0, .sample = 0, .seed = 1,   \
     .noise_sigma = 0.0, .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_auto = 0, .counters = NULL, .progress = NULL,           \
     .progress_arg = NULL, .noise_sigma_xy = 0.0, .noise_mode = 0}

FT_API const char *ft_points_method_name(ft_points_method m);
/** "yokoya" or "pentland" (case-insensitive); FT_E_INVALID naming the text otherwise. */
FT_API int ft_points_method_parse(const char *name, ft_points_method *m);

/** Step 1 of §2.4 alone: the counters A, B, C per lag, the statistic of opts->method and each lag's
 *  status. Needs >= 3 points with finite x, y, z (the error names the first bad point). */
FT_API int ft_surface_points_counters(const ft_points *p, const ft_points_dim_opts *opts, ft_points_counters **out);

/** Fractal dimension of scattered elevations: the counters, then log statistic against log mean
 *  separation of the kept lags, D = 3 - H. Fewer than opts->fit.min_points kept lags is FT_E_EMPTY with
 *  a message listing the dropped lags. result->method is "yokoya" or "pentland". */
FT_API int ft_surface_dim_points(const ft_points *p, const ft_points_dim_opts *opts, ft_dim_result **out);

/** Scattered points from a grid, as in Arakawa & Krotkov §2.5 and Table 1: a random `fraction` of the
 *  valid cells (exactly round(fraction x valid) cells, without replacement), each at its cell centre with
 *  the cell's value, or with `jitter` at a uniform position inside the cell and z interpolated bilinearly
 *  between the centres of the four nearest cells; then independent N(0, noise_xy²) on x and y and
 *  N(0, noise_z²) on z. */
typedef struct {
    size_t struct_size; /**< sizeof(ft_grid_sample_opts); see FT_OPTS in core.h */
    double fraction;  /**< in (0, 1]; default 0.05 */
    int jitter;       /**< default 0 */
    double noise_xy;  /**< ground units, >= 0; default 0 */
    double noise_z;   /**< elevation units, >= 0; default 0 */
    uint64_t seed;    /**< default 1 */
} ft_grid_sample_opts;
#define FT_GRID_SAMPLE_OPTS_DEFAULT                                                                                  \
    {.struct_size = sizeof(ft_grid_sample_opts), .fraction = 0.05, .jitter = 0, .noise_xy = 0.0, .noise_z = 0.0,     \
     .seed = 1}

FT_API int ft_surface_points_from_grid(const ft_grid *g, const ft_grid_sample_opts *opts, ft_points **out);

/* ------------------------------------------------------------------------------------------------
 * Profiles: elevation z along a line at a regular spacing (a transect, a raster row, a 3-D line), whose
 * graph is self-affine: D = 2 - H. Gneiting, Sevcikova & Percival (2012), "Estimators of fractal
 * dimension: assessing the roughness of time series and spatial data", Statistical Science 27(2):
 * the power variation of order p at lag l, V_p(l) = 1 / (2 (n - l)) sum_i |z_{i+l} - z_i|^p, and
 * D = 2 - (log V_p(2) - log V_p(1)) / (p log 2) (their Eq. 8 and 9): p = 2 the variogram estimator,
 * p = 1 the madogram (docs/profile.md).
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_PROFILE_VARIOGRAM = 0, /**< p = 2 */
    FT_PROFILE_MADOGRAM = 1   /**< p = 1: more robust to outliers and to non-Gaussian increments */
} ft_profile_method;

/** "variogram" or "madogram"; "?" otherwise. */
FT_API const char *ft_profile_method_name(ft_profile_method m);
/** Parses a method name (case-insensitive); FT_E_INVALID naming it otherwise. */
FT_API int ft_profile_method_parse(const char *name, ft_profile_method *m);

/** Dimension of a profile of n >= 3 finite elevations at a regular spacing > 0 (ground units): the
 *  log-log table of V_p at lags 1 and 2 (scale = lag x spacing, value = V_p, count = pairs), D by the
 *  estimator of Gneiting et al. A D outside [1, 2] is an error; a constant profile is FT_E_NUMERIC. */
FT_API int ft_profile_dim(const double *z, size_t n, double spacing, ft_profile_method m, ft_dim_result **out);

/** Row `row` of a grid as a profile: its n = nx values at the spacing |gt[1]| (x cell size). Nodata in
 *  the row is an error naming the first such column. *z is allocated (free it). */
FT_API int ft_profile_from_grid_row(const ft_grid *g, size_t row, double **z, size_t *n, double *spacing);

/** The transect from (x0, y0) to (x1, y1) (ground coordinates) across a grid, sampled by bilinear
 *  interpolation of the cell centres at the spacing of the smaller cell side (the last sample at the
 *  end point's distance rounded down). Both ends must lie within the cell centres' hull; a sample next
 *  to nodata is an error naming the point. *z is allocated (free it). */
FT_API int ft_profile_transect(const ft_grid *g, double x0, double y0, double x1, double y1, double **z, size_t *n,
                        double *spacing);

/** A 3-D line (x, y, z of n >= 3 vertices) as a profile: z linearly interpolated at a regular spacing
 *  along the horizontal length, the spacing the median horizontal segment (spacing <= 0) or the one
 *  given. *zout is allocated (free it). */
FT_API int ft_profile_resample(const double *x, const double *y, const double *z, size_t n, double spacing,
                        double **zout, size_t *nout, double *step);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_SURFACE_H */
