/* fracterra — private helpers shared by Clarke's model fit and simulation (src/terrain/clarke_*.c).
 * Clarke (1987) "Scale-based simulation of topography", eqs. vi, ix, xv.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLARKE_INTERNAL_H
#define FRACTERRA_CLARKE_INTERNAL_H

#include <stddef.h>

#include "fracterra/terrain.h"

/* What bin (kx, ky) of an ny x (nx/2+1) half-spectrum is, as one of the grid's real plane waves. */
typedef enum {
    CLARKE_BIN_SKIP = 0, /* the DC term, or the conjugate twin of a bin already counted */
    CLARKE_BIN_PAIR = 1, /* a wave with its conjugate twin outside the half-spectrum (or in column 0/Nyquist) */
    CLARKE_BIN_SELF = 2  /* a self-conjugate Nyquist bin: a real cosine alone */
} clarke_bin;

clarke_bin clarke_bin_kind(size_t kx, size_t ky, size_t nx, size_t ny);
/* The signed row frequency of half-spectrum row ky: ky for ky <= ny/2, ky - ny above. */
int clarke_signed_l(size_t ky, size_t ny);

/* Ground geometry of the fitted grid: unit vectors of its column and row axes and their lengths. */
typedef struct {
    double ex[2], ey[2]; /* map-coordinate unit vectors along increasing column and increasing row */
    double lx, ly;       /* extent along the columns (nx cells) and the rows (ny cells), ground units */
} clarke_frame;

/* FT_E_INVALID naming the bad value unless the geotransform has finite, non-degenerate axes. */
int clarke_frame_init(const double gt[6], size_t nx, size_t ny, clarke_frame *f);
/* Wavelength (ground units) of wave (k, l): 1 / |(k / lx) ex + (l / ly) ey|; INFINITY for (0, 0). */
double clarke_wavelength(const clarke_frame *f, int k, int l);
/* Wavelength (ground units) and direction (degrees clockwise from north, in [0, 180)) of wave (k, l). */
void clarke_wave_geometry(const clarke_frame *f, int k, int l, double *wavelength, double *direction);
/* The same for a wave of (u, v) cycles across the grid's columns and rows, u and v not necessarily whole. */
void clarke_wave_geometry_at(const clarke_frame *f, double u, double v, double *wavelength, double *direction);
/* Sets the wavelength and direction of each of the n harmonics to those of the plane wave of continuous
 * frequency that fits the residual best near the harmonic's mode (clarke_peak.c). res: the untapered
 * residual z - T of the DEM's cells, row stride rs (read at the DEM's valid cells only). */
int clarke_refine_harmonics(const ft_grid *dem, const double *res, size_t rs, const clarke_frame *fr,
                            ft_clarke_harmonic *h, size_t n);
/* The regression's power for one plane wave of this wavelength (eq. xv, log10 form). */
double clarke_power(const ft_clarke_model *m, double wavelength);

/* F's measured spectrum (clarke_spectrum.c): the quarter-octave rings of wave_power (per half-spectrum
 * bin, NaN where there is no wave: the periodogram of z - T - H) into m->spectrum_*. */
int clarke_measure_spectrum(ft_clarke_model *m, const clarke_frame *fr, const double *wave_power);
/* The regimes and breaks of the rings of at least min_wl ground units into m->regimes, m->breaks. */
int clarke_spectrum_regimes(ft_clarke_model *m, double min_wl);
/* Corrects m->spectrum_power so that the variogram F implies at lags of 1 .. min(64, side/2) cells is the
 * variogram of res (z - T - H, row stride rs) over the DEM's valid pairs (clarke_variogram.c). */
int clarke_match_variogram(ft_clarke_model *m, const clarke_frame *fr, const ft_grid *dem, const double *res,
                           size_t rs);
/* Where wavelength falls among the measured rings (nspectrum >= 2): 1 at or beyond the longest, -1 at or
 * below the shortest, else 0 with rings *lo and *lo + 1 around it and t its log-wavelength weight toward
 * *lo + 1. */
int clarke_ring_bracket(const ft_clarke_model *m, double wavelength, size_t *lo, double *t);
/* The power of one plane wave of this wavelength in the F the model simulates (m->noise). */
double clarke_noise_power(const ft_clarke_model *m, double wavelength);
/* FT_E_INVALID naming the bad value unless the noise, spectrum and regimes of m are usable. */
int clarke_check_spectrum(const ft_clarke_model *m);

#endif /* FRACTERRA_CLARKE_INTERNAL_H */
