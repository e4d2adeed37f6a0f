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

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_TERRAIN_H */
