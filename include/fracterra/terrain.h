/* fracterra — terrain.h: terrain synthesis (spectral, successive random addition, midpoint displacement,
 * exact circulant embedding) and Clarke's scale-based model (trend + significant harmonics + fractal noise).
 *
 * Papers: Clarke (1987) "Scale-based simulation of topography" (seeds 004); Arakawa & Krotkov §3.4 (SRA,
 * seeds 003); Voss (1985); Fournier, Fussell & Carpenter (1982); Stein (2002) for exact 2-D fBm.
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
    FT_SYNTH_SRA = 1,      /**< successive random addition (Voss) */
    FT_SYNTH_MIDPOINT = 2, /**< diamond-square midpoint displacement (creases are a known artefact) */
    FT_SYNTH_EXACT = 3     /**< stationary-increment circulant embedding (Stein 2002): exact fBm increments */
} ft_synth_method;

typedef struct {
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
#define FT_SYNTH_OPTS_DEFAULT {FT_SYNTH_FFT, 2.3, 1.0, 1.0, 0.0, 0.0, 0, 1, NULL, NULL}

/** A new nx x ny grid of a fractional Brownian surface. Same options and seed => bit-identical cells on
 *  any thread count. */
int ft_terrain_synth(size_t nx, size_t ny, const ft_synth_opts *opts, ft_grid **out);
const char *ft_synth_method_name(ft_synth_method m);
int ft_synth_method_parse(const char *name, ft_synth_method *m);


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
} ft_clarke_model;

typedef struct {
    double cutoff;          /**< percent of the detrended variance a harmonic must reach, in (0, 100];
                                 default 2.5 (Clarke) */
    int taper;              /**< 1 (default): the regression uses the periodogram of the residual under a
                                 2-D Hann taper, less biased by the grid's edges; 0: Clarke's raw one */
    double min_wavelength;  /**< regress over the waves of at least this many cells' wavelength; >= 0;
                                 default 4, which leaves out the band near the Nyquist frequency that
                                 aliasing flattens; 0 = every wave (Clarke) */
    ft_progress_fn progress;
    void *progress_arg;
} ft_clarke_opts;
#define FT_CLARKE_OPTS_DEFAULT {2.5, 1, 4.0, NULL, NULL}

/** Fits Clarke's model to a DEM of any size (at least 4 x 4 cells with 3 valid ones not on a line).
 *  Nodata cells are filled with the trend before the Fourier analysis (model->nodata_filled says how
 *  many); the statistics and the trend use the valid cells only. */
int ft_clarke_fit(const ft_grid *dem, const ft_clarke_opts *opts, ft_clarke_model **out);
/** A zeroed model with room for nharmonics harmonics (nharmonics set), for readers of saved models;
 *  NULL (error set) if out of memory. */
ft_clarke_model *ft_clarke_model_create(size_t nharmonics);
void ft_clarke_model_free(ft_clarke_model *m);

typedef struct {
    int refine;             /**< K >= 1: K times more cells along each axis over the same extent; default 1 */
    int extent;             /**< E >= 1: E times the extent along each axis, from the same upper-left
                                 corner (the harmonics repeat, the trend continues); default 1 */
    uint64_t seed;          /**< phases of F; default 1 */
    double *c_used;         /**< if not NULL, receives the c of this realization */
    ft_progress_fn progress;
    void *progress_arg;
} ft_clarke_sim_opts;
#define FT_CLARKE_SIM_OPTS_DEFAULT {1, 1, 1, NULL, NULL, NULL}

/** Simulates T + cF + H on a grid of (E K nx) x (E K ny) cells: T and H from the model, F with the
 *  fitted power per harmonic (scaled to the new harmonic spacing) and uniform random phases, at every
 *  harmonic of the new grid except the DC term and those of H. c is chosen on this realization so that
 *  the cells covering the fitted extent have the original's mean and variance (Clarke's procedure).
 *  Same model, options and seed => bit-identical cells. */
int ft_clarke_simulate(const ft_clarke_model *m, const ft_clarke_sim_opts *opts, ft_grid **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_TERRAIN_H */
