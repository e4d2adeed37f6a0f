/* fracterra — synth_internal.h (private): the synthesizers behind ft_terrain_synth (synth.c) and the
 * helpers they share. Each synthesizer fills an nx x ny float array (row-major, row 0 north) with a
 * fractional Brownian surface of Hurst exponent H = 3 - D at its own raw scale; synth.c validates the
 * options, rescales to sigma and georeferences. Random numbers come from ft_rng_create(seed, stream)
 * with one stream per row (or per block), so cells are bit-identical on any thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_SYNTH_INTERNAL_H
#define FRACTERRA_SYNTH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fft/fft.h"
#include "fracterra/terrain.h"

/** Stream ids: each synthesizer draws from its own range so no two share a stream. */
#define FT_SYNTH_STREAM_FFT UINT64_C(0x1000000000)
#define FT_SYNTH_STREAM_SRA UINT64_C(0x2000000000)
#define FT_SYNTH_STREAM_MIDPOINT UINT64_C(0x3000000000)
#define FT_SYNTH_STREAM_EXACT UINT64_C(0x4000000000)

/** Default size of the fft synthesis grid as a multiple of the output, per axis (see synth_fft.c). */
#define FT_SYNTH_FFT_PAD_DEFAULT 1.25

/** The fft surface's nx x ny cells in *z (malloc'd: the spectrum's own memory, cropped in place). */
int ft_synth_fft_make(size_t nx, size_t ny, double H, const ft_synth_opts *o, float **z);
/** The working memory of an nx x ny fft synthesis (the padded half-spectrum, malloc'd,
 *  every page touched) for ft_synth_fft_into. */
int ft_synth_fft_workspace(size_t nx, size_t ny, int periodic, fftwf_complex **spec);
/** ft_synth_fft_make's cells written to z (nx * ny floats) with spec (from ft_synth_fft_workspace for
 *  the same nx, ny and periodic) as the working memory: the same bits, no allocation of the grid's
 *  size. */
int ft_synth_fft_into(size_t nx, size_t ny, double H, const ft_synth_opts *o, fftwf_complex *spec, float *z);
/** For the distributed run (synth_fft_rows.c): the padded synthesis grid's side for an output side n; rows
 *  [row0, row0 + nrows) of the py x (px/2+1) half-spectrum (Hermitian included), the bits
 *  ft_synth_fft_make gives them; the random plane (ax, ay) added to the non-periodic output (0 if
 *  periodic). */
size_t ft_synth_fft_padded(size_t n, int periodic);
int ft_synth_fft_fill_rows(size_t py, size_t px, double H, uint64_t seed, size_t row0, size_t nrows,
                           fftwf_complex *rows);
int ft_synth_fft_plane(size_t px, size_t py, double H, const ft_synth_opts *o, double *ax, double *ay);
int ft_synth_sra_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z);
int ft_synth_midpoint_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z);
int ft_synth_exact_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z);

/** Fills row ky's standard deviations amp[0 .. px/2] of the half-spectrum coefficients. */
typedef void (*ft_synth_amp_fn)(size_t ky, double *amp, void *ctx);

/** Fills the py x (px/2+1) half-spectrum `spec` with independent complex Gaussian coefficients of
 *  E|c|^2 = amp^2 (real and imaginary parts each of variance amp^2 / 2; one RNG stream per row,
 *  stream_base + ky), then makes it Hermitian by construction: on the self-paired columns kx = 0 and
 *  kx = px/2 (px even) row py-ky is the conjugate of row ky, and the self-conjugate bins are real with
 *  variance amp^2. The c2r transform of the result is a real stationary Gaussian field whose covariance
 *  has the (unnormalised) DFT py*px*amp^2. amp_fn may read spec's row ky: it is called before the row
 *  is overwritten. */
int ft_synth_fill_hermitian(fftw_complex *spec, size_t py, size_t px, uint64_t seed, uint64_t stream_base,
                            ft_synth_amp_fn amp_fn, void *ctx);

/** The dyadic lattice of sra and midpoint: a base of bx x by squares refined `levels` times, giving
 *  (bx * 2^levels + 1) x (by * 2^levels + 1) nodes, the smallest such with at most 4 base squares on the
 *  longer side that covers nx x ny. */
typedef struct {
    size_t bx, by;   /**< base squares per axis (1 .. 4) */
    int levels;      /**< refinements */
    size_t gx, gy;   /**< final nodes per axis */
} ft_synth_dyadic;
void ft_synth_dyadic_plan(size_t nx, size_t ny, ft_synth_dyadic *d);

#endif /* FRACTERRA_SYNTH_INTERNAL_H */
