/* fracterra — fill_internal.h (private): what the void-filling files of src/terrain/ share
 * (docs/terrain-fill.md).
 *
 *  - fill_variogram.c: the power-variogram model of a void from the valid cells of a ring around it;
 *  - fill_kriging.c: intrinsic kriging of one void from the valid cells around it, and conditional
 *    realizations (exact fBm minus its own kriging);
 *  - fill.c: ft_terrain_fill: the voids, max_void, the loop over voids, outputs and result.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_FILL_INTERNAL_H
#define FRACTERRA_FILL_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/terrain.h"

/** Lags (cells) of the ring's variogram fit. */
#define FT_FILL_LAG_MAX 8
/** A lag enters the fit with at least this many pairs; the fit needs at least 3 lags. */
#define FT_FILL_MIN_PAIRS 32
/** Fitted D is clamped to [FT_FILL_D_MIN, FT_FILL_D_MAX] (the kriging needs 0 < H < 1). */
#define FT_FILL_D_MIN 2.01
#define FT_FILL_D_MAX 2.99

/** A power variogram E(z(x) - z(y))² = v1 r^(2H), r in cells. */
typedef struct {
    double H, v1, r2;
    int clamped;
    size_t pairs1; /**< pairs at lag 1 */
} ft_fill_model;

/** Fits the model to the cells of z (nx x ny, row-major) where use[i] != 0: mean squared differences
 *  along rows and columns at lags 1..FT_FILL_LAG_MAX, least squares in log-log over the lags with at
 *  least FT_FILL_MIN_PAIRS pairs and a non-zero mean. H_fixed > 0: the slope is 2 H_fixed and only v1
 *  is fitted. Returns FT_OK, FT_E_EMPTY (fewer than 3 usable lags; 1 usable lag is enough with
 *  H_fixed), or FT_E_NUMERIC when every difference is zero (m->v1 = 0: flat). */
int ft_fill_fit_model(const float *z, const uint8_t *use, size_t nx, size_t ny, double H_fixed,
                      ft_fill_model *m);

/** One void on its box: bw x bh cells, role[i] = 0 outside the problem, 1 void cell to fill,
 *  2 conditioning cell (value z[i]). */
typedef struct ft_fill_krige ft_fill_krige;
/** Factors the kriging system of the conditioning cells for exponent H (0 < H < 1). */
int ft_fill_krige_create(const uint8_t *role, size_t bw, size_t bh, double H, ft_fill_krige **out);
void ft_fill_krige_free(ft_fill_krige *k);
/** out[i] = the kriging of the values vals[] (bw x bh, read at the conditioning cells) at every void
 *  cell i (other cells untouched). */
int ft_fill_krige_predict(const ft_fill_krige *k, const float *vals, float *out);

#endif /* FRACTERRA_FILL_INTERNAL_H */
