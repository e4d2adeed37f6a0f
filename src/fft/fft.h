/* fracterra — fft.h (private): FFTW3 plans created once per (size, direction, layout) and cached, and
 * the transforms that use them. Every FFT in the library goes through this module: FFTW's planner is
 * not thread-safe, so planning is serialised behind one mutex here, and no other file may call
 * fftw_plan_* / fftw_destroy_plan directly. Executing a cached plan on new arrays (fftw_execute_dft_*)
 * is thread-safe, so the transforms below may run concurrently from many threads.
 *
 * Plans use FFTW_ESTIMATE: deterministic (no timing measurements), so the same input gives the same
 * bits on every run, and planning never touches the arrays.
 *
 * Normalisation: FFTW's, i.e. NONE. A forward transform followed by an inverse multiplies by the number
 * of points (ny * nx for 2-D, n for 1-D); divide once yourself. Forward uses exp(-2 pi i k x / n),
 * inverse exp(+2 pi i k x / n).
 *
 * Layouts (row-major, row 0 first):
 *  - real ny x nx arrays: element (row, col) at row * rs + col, with rs = nx (out-of-place) or
 *    rs = ft_fft_real_stride(nx) = 2 * (nx / 2 + 1) (in-place, sharing the complex buffer);
 *  - half-spectrum ny x (nx / 2 + 1) complex: element (ky, kx) at ky * (nx / 2 + 1) + kx, with
 *    ky = 0 .. ny - 1 (frequency ky for ky <= ny / 2, ky - ny above) and kx = 0 .. nx / 2; the other half
 *    of the spectrum is the complex conjugate (Hermitian symmetry of a real signal).
 *
 * Arrays may come from anywhere (malloc, ft_fft_alloc_*): a misaligned array gets its own FFTW_UNALIGNED
 * plan; arrays from ft_fft_alloc_* are SIMD-aligned and fastest.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_FFT_H
#define FRACTERRA_FFT_H

#include <stddef.h>

#include <fftw3.h>

#define FT_FFT_FORWARD FFTW_FORWARD   /**< -1: exp(-2 pi i k x / n) */
#define FT_FFT_BACKWARD FFTW_BACKWARD /**< +1: exp(+2 pi i k x / n), unnormalised */

/** The smallest 2·3·5·7-smooth integer >= n (1 for n <= 1); 0 if that would overflow size_t. */
size_t ft_fft_good_size(size_t n);

/** Row stride, in doubles, of a real array transformed in place: 2 * (nx / 2 + 1). */
size_t ft_fft_real_stride(size_t nx);

/** SIMD-aligned arrays of n doubles / n complex values (fftw_malloc), NULL (FT_E_NOMEM set) on failure
 *  or overflow. Release with ft_fft_free (never free()). */
double *ft_fft_alloc_real(size_t n);
fftw_complex *ft_fft_alloc_complex(size_t n);
void ft_fft_free(void *p);

/** Single precision (fftw3f), for spectral synthesis where float output makes double arithmetic moot:
 *  SIMD-aligned array of n fftwf_complex (fftwf_malloc), NULL (FT_E_NOMEM set) on failure; release
 *  with ft_fft_freef. */
fftwf_complex *ft_fft_alloc_complexf(size_t n);
/** Asks for transparent huge pages over the whole 2 MB pages inside [p, p + bytes) of a large array not
 *  yet written (a hint, as ft_fft_alloc_complexf gives its arrays): its first touch then takes one fault
 *  per 2 MB instead of one per 4 kB. */
void ft_fft_advise_huge(void *p, size_t bytes);
void ft_fft_freef(void *p);

/** Forward 2-D real-to-complex transform: ny x nx reals -> ny x (nx/2+1) complex (unnormalised).
 *  Out-of-place (in != out): in has row stride nx and is left unchanged.
 *  In-place ((void *)in == (void *)out): in has row stride ft_fft_real_stride(nx).
 *  0, or FT_E_INVALID (zero or too large size, NULL array) / FT_E_NOMEM (planning failed). */
int ft_fft_r2c_2d(size_t ny, size_t nx, const double *in, fftw_complex *out);

/** Inverse 2-D complex-to-real transform: ny x (nx/2+1) complex -> ny x nx reals, unnormalised (a round
 *  trip r2c then c2r multiplies by ny * nx). The input spectrum is DESTROYED (FFTW cannot preserve it
 *  in multi-dimensional c2r). Out-of-place: out has row stride nx. In-place ((void *)in == (void *)out):
 *  out has row stride ft_fft_real_stride(nx). The imaginary parts of the kx = 0 (and kx = nx/2 for even
 *  nx) column's self-conjugate bins are ignored, as the Hermitian half-spectrum implies. */
int ft_fft_c2r_2d(size_t ny, size_t nx, fftw_complex *in, double *out);

/** In-place inverse 2-D complex-to-real transform in single precision: the ny x (nx/2+1) half-spectrum
 *  `spec` becomes ny x nx reals at (float *)spec with row stride ft_fft_real_stride(nx); unnormalised,
 *  same conventions as ft_fft_c2r_2d. Computed as blocked column then row passes of 1-D transforms over
 *  the OpenMP threads; bit-identical on any thread count. 0, FT_E_INVALID or FT_E_NOMEM. */
int ft_fft_c2r_2df(size_t ny, size_t nx, fftwf_complex *spec);
/** ft_fft_c2r_2df when only the first nrows (1 <= nrows <= ny) output rows are wanted (a cropped
 *  synthesis): the column pass is whole, the row pass stops after the batch that holds row nrows - 1.
 *  Those rows are ft_fft_c2r_2df's bit for bit; the rows after them are left undefined. */
int ft_fft_c2r_2df_rows(size_t ny, size_t nx, fftwf_complex *spec, size_t nrows);

/** 1-D complex transform of n points, sign FT_FFT_FORWARD or FT_FFT_BACKWARD (unnormalised); in-place
 *  when in == out. Errors as above. */
int ft_fft_c2c_1d(size_t n, fftw_complex *in, fftw_complex *out, int sign);

/** Destroys every cached plan and FFTW's internal state (fftw_cleanup). Only for the end of a program
 *  or a test: no transform may be running in another thread. The cache refills on the next call. */
void ft_fft_cleanup(void);

#endif /* FRACTERRA_FFT_H */
