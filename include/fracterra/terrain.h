/* fracterra — terrain.h: terrain synthesis (spectral, successive random addition, midpoint displacement,
 * exact circulant embedding), Clarke's scale-based model (trend + significant harmonics + fractal noise)
 * and reconstruction of dense terrain from sparse points (regularization with fractal priors).
 *
 * Papers: Clarke (1987) "Scale-based simulation of topography"; Arakawa & Krotkov §3 (SRA and
 * reconstruction); Voss (1985); Fournier, Fussell & Carpenter (1982); Stein (2002) for exact 2-D fBm.
 * docs/terrain-*.md hold the equations and limits.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_TERRAIN_H
#define FRACTERRA_TERRAIN_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------------
 * Synthesis of fractional Brownian surfaces of dimension D = 3 - H.
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_SYNTH_FFT = 0,      /**< spectral synthesis: amplitude ~ |f|^-(H+1), Gaussian coefficients */
    FT_SYNTH_SRA = 1,      /**< successive random addition (Voss), calibrated: run at the parameter whose
                                surfaces have the asked D by the variogram over lags 1-16 cells */
    FT_SYNTH_MIDPOINT = 2, /**< diamond-square midpoint displacement (creases are a known artefact),
                                calibrated like sra */
    FT_SYNTH_EXACT = 3,    /**< stationary-increment circulant embedding (Stein 2002): exact fBm increments */
    FT_SYNTH_SRA_RAW = 4,  /**< Voss's SRA at H = 3 - D as published ("sra-raw"; Arakawa & Krotkov's data) */
    FT_SYNTH_MIDPOINT_RAW = 5 /**< diamond-square at H = 3 - D as published ("midpoint-raw") */
} ft_synth_method;

typedef struct {
    size_t struct_size; /**< sizeof(ft_synth_opts); see FT_OPTS in core.h */
    ft_synth_method method;
    double dim;        /**< fractal dimension D in (2, 3); default 2.3 */
    double sigma;      /**< standard deviation of the output; default 1 (0 = leave as generated) */
    double cell;       /**< cell size in ground units; default 1 */
    double origin_x;   /**< upper-left corner x; default 0 */
    double origin_y;   /**< upper-left corner y; default 0 (with cell, gives a north-up geotransform) */
    int periodic;      /**< fft: keep the periodic tile instead of synthesizing on a padded grid; default 0 */
    uint64_t seed;     /**< default 1 */
    ft_progress_fn progress;
    void *progress_arg;
} ft_synth_opts;
#define FT_SYNTH_OPTS_DEFAULT                                                                                        \
    {.struct_size = sizeof(ft_synth_opts), .method = FT_SYNTH_FFT, .dim = 2.3, .sigma = 1.0, .cell = 1.0,            \
     .origin_x = 0.0, .origin_y = 0.0, .periodic = 0, .seed = 1, .progress = NULL, .progress_arg = NULL}

/** A new nx x ny grid of a fractional Brownian surface. Same options and seed => bit-identical cells on
 *  any thread count. */
FT_API int ft_terrain_synth(size_t nx, size_t ny, const ft_synth_opts *opts, ft_grid **out);

/** Working memory for repeated syntheses of one size, method and periodic flag into the caller's grid
 *  (Monte Carlo realizations, a bench loop): for method fft the padded half-spectrum (1.6 x the grid's
 *  bytes with the default pad), every page touched here, so that the syntheses that reuse it take no
 *  page fault and allocate nothing of the grid's size. The other methods keep nothing in it. A workspace
 *  serves one call at a time (threads each need their own). */
typedef struct ft_synth_workspace ft_synth_workspace;
FT_API int ft_synth_workspace_create(size_t nx, size_t ny, const ft_synth_opts *opts, ft_synth_workspace **ws);
FT_API void ft_synth_workspace_free(ft_synth_workspace *ws);
/** ft_terrain_synth into out (its nx x ny cells overwritten, its mask, if any, set to all valid and
 *  kept, its geotransform set from the options; its CRS and nodata fields left as they are; no pointer
 *  of out is freed or replaced, so out may wrap the caller's arrays), with ws made for
 *  the same size, method and periodic flag: the cells are ft_terrain_synth's bit for bit. On error the
 *  cells are undefined. */
FT_API int ft_terrain_synth_into(const ft_synth_opts *opts, ft_synth_workspace *ws, ft_grid *out);
FT_API const char *ft_synth_method_name(ft_synth_method m);
FT_API int ft_synth_method_parse(const char *name, ft_synth_method *m);
/** The D the raw algorithm runs at (H = 3 - raw D) when sra or midpoint is asked for D on an nx x ny grid
 *  (sra: from its exact expected variogram, which depends on the size; midpoint: its measured table;
 *  src/terrain/synth/synth_calibration.c); D itself for the other methods. */
FT_API double ft_synth_raw_dim(ft_synth_method m, double D, size_t nx, size_t ny);

/* Distributed fft synthesis (docs/tiling.md): ft_terrain_synth's method fft in slabs of rows for a caller that
 * runs the 2-D inverse transform across processes (FFTW's MPI c2r, as `mpiexec -n N fracterra synth` does).
 * Steps: ft_synth_fft_grid_size; on each slab ft_synth_fft_spectrum_rows, the distributed c2r (unnormalised,
 * in place, row stride 2 * (px/2 + 1) floats), ft_synth_fft_surface_rows; the rows' sums of every slab put
 * together in row order; ft_synth_rescale_rows. The cells are ft_terrain_synth's up to the transform's
 * rounding. opts->method must be FT_SYNTH_FFT. */
/** The padded py x px synthesis grid of an nx x ny fft surface (px = nx, py = ny with opts->periodic). */
FT_API int ft_synth_fft_grid_size(size_t nx, size_t ny, const ft_synth_opts *opts, size_t *px, size_t *py);
/** Rows [row0, row0 + nrows) of the py x (px/2 + 1) half-spectrum, complex as interleaved floats (re, im),
 *  Hermitian on the self-paired columns: the values ft_terrain_synth transforms, bit for bit. */
FT_API int ft_synth_fft_spectrum_rows(size_t nx, size_t ny, const ft_synth_opts *opts, size_t row0, size_t nrows,
                                      float *spec);
/** rows: the transformed grid rows [row0, row0 + nrows) (row stride 2 * (px/2 + 1) floats). Its rows below ny
 *  become output rows in place (stride nx: cropped to nx columns, the random plane added); row_sums (may be
 *  NULL) gets the sum and sum of squares of each, 2 doubles a row. Rows at or beyond ny are left alone. */
FT_API int ft_synth_fft_surface_rows(size_t nx, size_t ny, const ft_synth_opts *opts, size_t row0, size_t nrows,
                                     float *rows, double *row_sums);
/** Rescales nrows output rows (stride nx) to the whole surface's mean 0 and standard deviation opts->sigma
 *  from row_sums, the 2 * ny sums of all the surface's rows in row order (no-op for sigma 0). */
FT_API int ft_synth_rescale_rows(size_t nx, size_t ny, const ft_synth_opts *opts, const double *row_sums,
                                 size_t nrows, float *rows);


/* ------------------------------------------------------------------------------------------------
 * Clarke's scale-based model z = T + cF + H (Clarke 1987, eqs. vi, ix-xv; docs/terrain-clarke.md).
 * T is the least-squares plane, H the significant harmonics of the detrended DEM, F fractal noise whose
 * power follows the log-log regression of harmonic power on wavelength, scaled by c.
 * Harmonic (k, l) is the plane wave a cos(theta) + b sin(theta), theta = 2 pi (k col / nx + l row / ny),
 * col and row the cell-centre indices of the fitted grid (0 at the upper-left cell); k >= 0 and
 * l in (-ny/2, ny/2], one of each conjugate pair.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    int k, l;           /**< cycles across the grid's columns and rows */
    double a, b;        /**< cosine and sine coefficients (elevation units) */
    double power;       /**< eq. vi for one plane wave: a² + b² */
    double share;       /**< fraction of the detrended variance, in [0, 1] (power / 2 over the variance;
                             power alone for the self-conjugate Nyquist waves) */
    double wavelength;  /**< 1 / sqrt((k / Lx)² + (l / Ly)²), ground units (eq. ix, see the docs) */
    double direction;   /**< azimuth of the wave vector, degrees clockwise from north in [0, 180) */
} ft_clarke_harmonic;

/** Which fractal noise F a Clarke model simulates. */
typedef enum {
    FT_CLARKE_NOISE_POWER_LAW = 0, /**< Clarke's one power law (slope, intercept) at every wavelength */
    FT_CLARKE_NOISE_SPECTRUM = 1   /**< the DEM's measured radially averaged spectrum (spectrum_*), log-log
                                        interpolated; below its shortest wavelength the finest regime's law */
} ft_clarke_noise;

/** One straight regime of the binned radial spectrum: log10 power = intercept + slope log10 wavelength
 *  over wavelengths [wavelength_lo, wavelength_hi] (ground units), found by the log-log regime search
 *  (src/core/loglog_regimes.c). */
typedef struct {
    double wavelength_lo, wavelength_hi; /**< ground units */
    double slope, intercept;             /**< of log10 power on log10 wavelength */
    double D;                            /**< (8 - slope) / 2 (may lie outside [2, 3]: then a warning) */
    double r2, stderr_D;
    size_t bins;                         /**< spectrum bins in the regime */
} ft_clarke_regime;

typedef struct {
    /* T (eq. xii): z = beta0 + beta1 x + beta2 y, x and y map coordinates of cell centres */
    double beta0, beta1, beta2;
    double trend_r2;        /**< r² of the plane over the valid cells */
    /* georeferencing of the fitted grid */
    size_t nx, ny;
    double gt[6];
    char *crs_wkt;          /**< may be NULL */
    /* the original's statistics (valid cells) */
    double mean, sd;
    size_t valid;           /**< valid cells */
    size_t nodata_filled;   /**< nodata cells filled with the trend before the Fourier analysis */
    /* H: harmonics whose share is at least cutoff percent, by decreasing share */
    double cutoff;          /**< percent */
    int taper;              /**< 1 if the regression used a Hann-tapered periodogram */
    double min_wavelength;  /**< shortest wavelength in the regression, in cells (0 = every wave) */
    ft_clarke_harmonic *harmonics;
    size_t nharmonics;
    double harmonic_share;  /**< sum of their shares */
    /* F (eqs. ix, x, xv): log10 power = intercept + slope log10 wavelength over all harmonics of
     * non-zero power */
    double slope, intercept, r2, stderr_slope;
    size_t npairs;          /**< harmonics in the regression */
    double D;               /**< (8 - slope) / 2: slope = beta of a 2-D isotropic spectrum P ~ f^-beta */
    double D_clarke_eq8;    /**< 3 - slope / 2, Clarke's eq. viii as printed (the variogram relation) */
    double c;               /**< scale of F so that var(T + cF + H) = sd² on the fitted grid */
    /* F's measured spectrum (model file format 2): the tapered periodogram of the residual without H,
     * averaged over quarter-octave rings of frequency; bin i holds spectrum_count[i] waves of mean power
     * spectrum_power[i] (per plane wave, as the regression's) at the geometric-mean wavelength
     * spectrum_wavelength[i] (ground units, strictly increasing) */
    ft_clarke_noise noise;  /**< the F ft_clarke_simulate draws */
    size_t nspectrum;
    double *spectrum_wavelength, *spectrum_power, *spectrum_count;
    ft_clarke_regime *regimes; /**< the regimes of the bins of at least min_wavelength cells, by increasing
                                    wavelength (0 if the search found none) */
    size_t nregimes;
    double *breaks;         /**< nregimes - 1 wavelengths (ground units) where neighbouring regimes meet */
} ft_clarke_model;

typedef struct {
    size_t struct_size; /**< sizeof(ft_clarke_opts); see FT_OPTS in core.h */
    double cutoff;          /**< percent of the detrended variance a harmonic must reach, in (0, 100];
                                 default 2.5 (Clarke) */
    int taper;              /**< 1 (default): the regression uses the periodogram of the residual under a
                                 2-D Hann taper, less biased by the grid's edges; 0: Clarke's raw one */
    double min_wavelength;  /**< regress over the waves of at least this many cells' wavelength; >= 0;
                                 default 4, which leaves out the band near the Nyquist frequency that
                                 aliasing flattens; 0 = every wave (Clarke) */
    ft_progress_fn progress;
    void *progress_arg;
    ft_clarke_noise noise;  /**< the F the model simulates; default FT_CLARKE_NOISE_SPECTRUM (the spectrum
                                 and its regimes are measured and reported either way) */
} ft_clarke_opts;
#define FT_CLARKE_OPTS_DEFAULT                                                                                       \
    {.struct_size = sizeof(ft_clarke_opts), .cutoff = 2.5, .taper = 1, .min_wavelength = 4.0, .progress = NULL,      \
     .progress_arg = NULL, .noise = FT_CLARKE_NOISE_SPECTRUM}

/** Fits Clarke's model to a DEM of any size (at least 4 x 4 cells with 3 valid ones not on a line).
 *  Nodata cells are filled with the trend before the Fourier analysis (model->nodata_filled says how
 *  many); the statistics and the trend use the valid cells only. */
FT_API int ft_clarke_fit(const ft_grid *dem, const ft_clarke_opts *opts, ft_clarke_model **out);
/** A zeroed model with room for nharmonics harmonics (nharmonics set), for readers of saved models;
 *  NULL (error set) if out of memory. */
FT_API ft_clarke_model *ft_clarke_model_create(size_t nharmonics);
FT_API void ft_clarke_model_free(ft_clarke_model *m);

typedef struct {
    size_t struct_size; /**< sizeof(ft_clarke_sim_opts); see FT_OPTS in core.h */
    int refine;             /**< K >= 1: K times more cells along each axis over the same extent; default 1 */
    int extent;             /**< E >= 1: E times the extent along each axis, from the same upper-left
                                 corner (the harmonics repeat, the trend continues); default 1 */
    uint64_t seed;          /**< phases of F; default 1 */
    double *c_used;         /**< if not NULL, receives the c of this realization */
    ft_progress_fn progress;
    void *progress_arg;
} ft_clarke_sim_opts;
#define FT_CLARKE_SIM_OPTS_DEFAULT                                                                                   \
    {.struct_size = sizeof(ft_clarke_sim_opts), .refine = 1, .extent = 1, .seed = 1, .c_used = NULL,                 \
     .progress = NULL, .progress_arg = NULL}

/** Simulates T + cF + H on a grid of (E K nx) x (E K ny) cells: T and H from the model, F with the
 *  fitted power per harmonic (scaled to the new harmonic spacing) and uniform random phases, at every
 *  harmonic of the new grid except the DC term and those of H. c is chosen on this realization so that
 *  the cells covering the fitted extent have the original's mean and variance (Clarke's procedure).
 *  Same model, options and seed => bit-identical cells. */
FT_API int ft_clarke_simulate(const ft_clarke_model *m, const ft_clarke_sim_opts *opts, ft_grid **out);


/* ------------------------------------------------------------------------------------------------
 * Reconstruction of dense terrain from sparse elevations (Arakawa & Krotkov §3, after Szeliski):
 * regularization with a fractal prior (Szeliski's spline under tension with the eq. 7 blend of D), solved
 * by multigrid (T = 0: the smooth solution); the fractal method's prior is Szeliski's multilevel one (a
 * thin plate on every pyramid level l weighted 2^(-2Hl), eq. 8) and it draws an exact sample of the
 * posterior, the Gibbs distribution exp(-E / (lambda T)) conditioned on the data, by perturbation and
 * optimization (Papandreou & Yuille 2010), at T = g(D) k sigma0² with sigma0 from the Pentland estimate
 * (points: over the data's shortest lags, 0.5-1.5 x their mean spacing), k = FT_RECON_K_DEFAULT and g(D) calibrated on the structure function.
 * docs/terrain-reconstruct.md holds the discretization, the calibration and the limits.
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_RECON_FRACTAL = 0,     /**< the paper's method: smooth solution + an exact posterior sample at T */
    FT_RECON_CONDITIONAL = 1, /**< conditional simulation: unconditional fBm of dimension D plus the smooth
                                   interpolation of the residuals at the data; honours the data exactly */
    FT_RECON_SMOOTH = 2       /**< T = 0: thin-plate/membrane regularization only (the paper's baseline) */
} ft_recon_method;

typedef struct {
    size_t struct_size; /**< sizeof(ft_recon_opts); see FT_OPTS in core.h */
    ft_recon_method method;   /**< default FT_RECON_FRACTAL */
    double dim;               /**< D in (2, 3); 0 (default) = estimate from the data (points: the yokoya
                                   points estimator with its default range; grid voids: from the valid
                                   cells) */
    double tension;           /**< blend of the prior: 0 = thin plate, 1 = membrane; in [0, 1], or
                                   FT_RECON_TENSION_FROM_DIM (default): Szeliski's crossover from D,
                                   tau / (1 - tau) = 2 (D - 2) / (3 - D) (Arakawa & Krotkov eq. 7;
                                   docs/terrain-reconstruct.md) for the conditional method, and for
                                   the smooth one when dim is given (else 0.1); for the fractal
                                   method the finest level's blend of its multilevel prior,
                                   calibrated on the structure function (0.2 at D 2.2 .. 1 at 2.8) */
    double lambda;            /**< weight of the prior against the data term, > 0; default 1. No effect
                                   when the data are interpolated (sigma 0, no weights). With sigmas
                                   (sigma > 0 or per-point weights) it is an upper bound: if the fit
                                   at lambda misses the data by more than their sigmas (chi² = sum
                                   (u - d_i)² / sigma_i² > N, the number of data), lambda is lowered
                                   until (1 - 0.06) N <= chi² <= N (Morozov's discrepancy principle:
                                   the RMS of (u - d_i) / sigma_i is 0.97 .. 1); a lambda that fits
                                   already is kept (docs/terrain-reconstruct.md) */
    double sigma;             /**< standard deviation of a datum without its own weight (elevation
                                   units, >= 0): the data are fitted to within it (see lambda);
                                   0 (default) = interpolate (the data are honoured to the solver's
                                   tolerance) */
    double temperature;       /**< fractal: T override, > 0; 0 (default) = g(D) k sigma0² */
    double k;                 /**< fractal: calibration constant of T = g(D) k sigma0², > 0 (g: the
                                   multilevel prior's calibrated factor of D, docs/terrain-reconstruct.md);
                                   0 (default) = FT_RECON_K_DEFAULT */
    int sweeps;               /**< unused since the fractal method draws an exact sample (no Gibbs
                                   sweeps); kept for the layout, must be in [0, 1000] */
    int realizations;         /**< >= 1; default 1. With N > 1 the output is the per-cell mean of N runs
                                   (seeds seed, seed+1, ... as streams) and sd_out their standard
                                   deviation */
    uint64_t seed;            /**< default 1 */
    int threads;              /**< 0 (default) = OpenMP's default; results do not depend on it */
    ft_progress_fn progress;  /**< called often enough to cancel within a second */
    void *progress_arg;
} ft_recon_opts;
/** ft_recon_opts.tension: the prior's blend follows D (Szeliski's eq. 7 crossover). */
#define FT_RECON_TENSION_FROM_DIM (-1.0)
#define FT_RECON_OPTS_DEFAULT                                                                                        \
    {.struct_size = sizeof(ft_recon_opts), .method = FT_RECON_FRACTAL, .dim = 0.0,                                   \
     .tension = FT_RECON_TENSION_FROM_DIM, .lambda = 1.0, .sigma = 0.0, .temperature = 0.0, .k = 0.0, .sweeps = 0,  \
     .realizations = 1, .seed = 1, .threads = 0, .progress = NULL, .progress_arg = NULL}

/** What a reconstruction used and achieved. */
typedef struct {
    double dim;               /**< D used */
    int dim_estimated;        /**< 1 if D came from the data */
    double sigma0;            /**< Pentland's standard deviation of elevation differences at one cell */
    double k;                 /**< calibration constant used (fractal) */
    double temperature;       /**< T_0 used (fractal; 0 otherwise) */
    int levels;               /**< multigrid levels */
    size_t data_used;         /**< data inside the grid (points) or known cells (voids) */
    size_t data_outside;      /**< points outside the grid, ignored */
    size_t filled;            /**< cells without data (voids: the filled cells) */
    double data_rms;          /**< RMS of (output - datum) over the data used, on the output grid
                                   interpolated bilinearly at the data positions */
    double lambda;            /**< the prior weight used: opts->lambda, or with soft data the discrepancy
                                   principle's value (at most opts->lambda) */
    double tension;           /**< the prior's blend used (opts->tension, or the one D gives) */
} ft_recon_info;

/** Fixed by a calibration on the structure function (docs/terrain-reconstruct.md says how). */
extern const double FT_RECON_K_DEFAULT;

FT_API const char *ft_recon_method_name(ft_recon_method m);
/** "fractal", "conditional" or "smooth" (case-insensitive); FT_E_INVALID naming the text otherwise. */
FT_API int ft_recon_method_parse(const char *name, ft_recon_method *m);

/** Reconstructs a grid shaped like `target` (its nx, ny, gt and crs; its cells and mask are ignored)
 *  from scattered points (p->w, when present, is each point's confidence 1/sigma). Points outside the
 *  grid are ignored and counted. Needs >= 3 points inside, not on a line. *out receives the
 *  reconstruction (the mean if realizations > 1); sd_out, if not NULL, the per-cell standard deviation
 *  over the realizations (zero with one realization or the smooth method). info may be NULL.
 *  Same data, options and seed => bit-identical cells on any thread count. */
FT_API int ft_reconstruct_points(const ft_points *p, const ft_grid *target, const ft_recon_opts *opts,
                          ft_grid **out, ft_grid **sd_out, ft_recon_info *info);

/** Fills the nodata cells of a DEM; the valid cells are kept exactly. The output has no mask. A grid
 *  without nodata is returned as a copy (info->filled = 0). All-nodata is FT_E_EMPTY. */
FT_API int ft_reconstruct_voids(const ft_grid *dem, const ft_recon_opts *opts, ft_grid **out, ft_grid **sd_out,
                         ft_recon_info *info);

/* ------------------------------------------------------------------------------------------------
 * Void filling of a DEM by conditional simulation (docs/terrain-fill.md): every void (8-connected
 * nodata cells) is filled on its own, with the roughness of the terrain around it. Its model is a
 * power variogram E(z(x) - z(y))² = v1 r^(2H), r in cells, fitted to the valid cells of a ring around
 * the void (lags 1-8 along rows and columns; D = 3 - H). The fill is intrinsic kriging (ordinary
 * kriging with that variogram; Matheron 1973, Chilès & Delfiner §4.4) of the valid cells within 2
 * cells of the void, plus, for a realization, an exact fBm of the same model (Stein 2002) minus its
 * own kriging from the same cells (Journel & Huijbregts 1978, ch. VII): every valid cell is honoured
 * exactly, and increments across the void's border have the model's statistics (no seam).
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_fill_opts); see FT_OPTS in core.h */
    double max_void;   /**< voids whose bounding box is longer than this many cells along either axis
                            stay nodata (coast, outside of a survey); > 0; 0 = no limit; default 100
                            (gdal_fillnodata's -md default) */
    int mean;          /**< 1: the kriging mean (the best linear prediction, smooth inside large voids)
                            instead of a realization; default 0 */
    int realizations;  /**< >= 1; N > 1: the output is the per-cell mean of N realizations and sd_out
                            their standard deviation; default 1 */
    double dim;        /**< D in (2, 3) for every void; 0 (default) = fitted on each void's ring */
    int ring;          /**< width of the ring whose variogram is fitted, cells, >= 2; 0 (default) =
                            half the void's longer side, clamped to [10, 64] */
    uint64_t seed;     /**< realization r of the void whose first cell (raster order) is cell i = row * nx + col:
                            streams of ft_rng_mix(ft_rng_mix(seed, i), r); default 1 */
    ft_progress_fn progress;
    void *progress_arg;
} ft_fill_opts;
#define FT_FILL_OPTS_DEFAULT                                                                                         \
    {.struct_size = sizeof(ft_fill_opts), .max_void = 100.0, .mean = 0, .realizations = 1, .dim = 0.0, .ring = 0,    \
     .seed = 1, .progress = NULL, .progress_arg = NULL}

typedef enum {
    FT_FILL_D_RING = 0,  /**< D and v1 fitted on the void's ring */
    FT_FILL_D_DEM = 1,   /**< the ring had too few pairs: fitted on every valid cell of the DEM */
    FT_FILL_D_GIVEN = 2, /**< opts->dim; v1 fitted on the ring (or the DEM) with that slope */
    FT_FILL_D_FLAT = 3   /**< every pair has the same elevation: the fill is the kriging mean, D undefined */
} ft_fill_d_source;

typedef struct {
    size_t x0, y0, x1, y1;   /**< bounding box, inclusive cell indices */
    size_t cells;            /**< void cells */
    int edge;                /**< 1 if the void touches the raster's edge */
    int filled;              /**< 0: larger than max_void, left nodata */
    double D;                /**< the model's D (NaN if not filled or flat) */
    double amplitude;        /**< sqrt(v1): RMS elevation difference at one cell, elevation units */
    double r2;               /**< r² of the log-log fit (NaN if D was given, flat or not fitted) */
    int clamped;             /**< 1 if the fitted D fell outside [2.01, 2.99] and was clamped */
    ft_fill_d_source source;
    size_t ring_cells;       /**< valid cells of the ring */
    size_t conditioning;     /**< valid cells the kriging honours (within 2 cells of the void) */
} ft_fill_void;

typedef struct {
    ft_fill_void *voids;     /**< every void, in raster order of its first cell */
    size_t nvoids;
    size_t voids_filled, cells_filled, cells_left;
} ft_fill_result;

/** Fills the voids of `dem`: cells whose mask is 0 or whose value is not finite, and, if `invalid` is
 *  not NULL (nx x ny bytes), the cells where invalid[i] == 0 (gdal_fillnodata's -mask convention).
 *  *out: a copy of dem with the filled voids (voids left nodata keep mask 0). sd_out (may be NULL):
 *  with realizations > 1 the per-cell sd (0 on valid cells), else zero on filled cells. *res (may be
 *  NULL): the voids and totals (ft_fill_result_free). Valid cells are copied bit for bit. Same DEM,
 *  options and seed => bit-identical cells. Errors: FT_E_EMPTY if no cell is valid. */
FT_API int ft_terrain_fill(const ft_grid *dem, const uint8_t *invalid, const ft_fill_opts *opts, ft_grid **out,
                    ft_grid **sd_out, ft_fill_result **res);
/** ft_terrain_fill on a window of whole rows (docs/tiling.md): win holds rows [row0, row0 + win->ny) of a
 *  raster of ny rows (win's width and geotransform are the raster's, shifted), invalid (may be NULL) the
 *  same window. Every void that meets rows [own0, own1) (the stripe, row0 <= own0 < own1 <= row0 +
 *  win->ny) is filled in *out (the window) with the cells ft_terrain_fill gives it on the whole raster;
 *  *res lists the voids whose first cell lies in the stripe (rows in the raster's numbering), and its
 *  totals count those voids, so that the stripes' results in row order are the whole run's.
 *  FT_E_UNSUPPORTED when a void meeting the stripe, with its ring, may go on beyond the window (read a
 *  larger window), or when its ring is too poor and the whole DEM's model would be needed. */
FT_API int ft_terrain_fill_rows(const ft_grid *win, const uint8_t *invalid, size_t row0, size_t ny, size_t own0,
                                size_t own1, const ft_fill_opts *opts, ft_grid **out, ft_grid **sd_out,
                                ft_fill_result **res);
FT_API void ft_fill_result_free(ft_fill_result *r);
FT_API const char *ft_fill_d_source_name(ft_fill_d_source s);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_TERRAIN_H */
