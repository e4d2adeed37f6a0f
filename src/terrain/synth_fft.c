/* fracterra — synth_fft.c: spectral synthesis of fractional Brownian surfaces (Voss 1985, "Random
 * fractal forgeries"; Saupe 1988 in "The Science of Fractal Images", algorithm SpectralSynthesisFM2D).
 *
 * A stationary Gaussian field whose Fourier coefficients c(f) are independent complex Gaussians with
 * E|c(f)|^2 ~ |f|^-(2H+2), i.e. amplitude ~ |f|^-(H+1), H = 3 - D, has the radially averaged power
 * spectrum P(f) ~ f^-(2H+2) of 2-D fBm, hence a variogram ~ h^(2H) over lags well below the period.
 * The half-spectrum is filled in FFTW's r2c layout and made Hermitian by construction
 * (ft_synth_fill_hermitian), so one in-place c2r transform gives the real field; the DC term is 0.
 *
 * The field is periodic with the period of the synthesis grid. With opts->periodic the grid is the
 * output itself (a tile that wraps seamlessly); otherwise the grid is FT_SYNTH_FFT_PAD_DEFAULT times the
 * output per axis, rounded up to a 2·3·5·7-smooth size, and the output is its upper-left corner, so
 * opposite edges are no longer neighbours. docs/terrain-synthesis.md discusses the choice of pad.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth_internal.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/core.h"
#include "internal.h"

int ft_synth_fill_hermitian(fftw_complex *spec, size_t py, size_t px, uint64_t seed, uint64_t stream_base,
                            ft_synth_amp_fn amp_fn, void *ctx)
{
    size_t ncx = px / 2 + 1;
    int failed = 0;
#pragma omp parallel reduction(| : failed)
    {
        double *amp = malloc(ncx * sizeof *amp);
        failed |= amp == NULL;
#pragma omp for schedule(static)
        for (size_t ky = 0; ky < py; ky++) {
            ft_rng *r = amp ? ft_rng_create(seed, stream_base + ky) : NULL;
            if (r == NULL) {
                failed = 1;
                continue;
            }
            amp_fn(ky, amp, ctx);
            fftw_complex *row = spec + ky * ncx;
            for (size_t kx = 0; kx < ncx; kx++) {
                double s = amp[kx] * M_SQRT1_2;
                row[kx][0] = ft_rng_gaussian(r, 1.0) * s;
                row[kx][1] = ft_rng_gaussian(r, 1.0) * s;
            }
            ft_rng_free(r);
        }
        free(amp);
    }
    if (failed)
        return ft_error(FT_E_NOMEM, "synth: out of memory filling a %zu x %zu spectrum", py, px);
    size_t cols[2] = {0, px / 2};
    int ncols = (px % 2 == 0 && px > 1) ? 2 : 1;
    for (int c = 0; c < ncols; c++) {
        size_t kx = cols[c];
        for (size_t ky = 0; ky <= py / 2; ky++) {
            fftw_complex *a = &spec[ky * ncx + kx];
            size_t mirror = (py - ky) % py;
            if (mirror == ky) { /* self-conjugate: real, with the whole variance */
                (*a)[0] *= M_SQRT2;
                (*a)[1] = 0.0;
            } else {
                fftw_complex *b = &spec[mirror * ncx + kx];
                (*b)[0] = (*a)[0];
                (*b)[1] = -(*a)[1];
            }
        }
    }
    return FT_OK;
}

/* Aliasing of the lattice: a surface sampled once per cell has the folded spectrum
 * S_d(f) = sum over integer (m, n) of S(f + (m, n)), f in cycles per cell, and its variogram at whole lags
 * is exactly the continuous one when the Nyquist square carries S_d instead of S. S_d / S is smooth on the
 * square, so it is tabulated (ALIAS_N x ALIAS_N over [0, 1/2]^2, folded terms |m|, |n| <= ALIAS_K plus the
 * integral of the rest) and interpolated bilinearly. Without it the small lags lack variance and D comes
 * out low, the more so the rougher the surface. */
#define ALIAS_N 33
#define ALIAS_K 6

typedef struct {
    size_t py, px;
    double expo;                      /* -(H + 1) / 2, applied to |f|^2 */
    double ratio[ALIAS_N][ALIAS_N];  /* sqrt(S_d / S) at (fy, fx) = (i, j) / (2 (ALIAS_N - 1)) */
} fft_amp_ctx;

static void alias_table(fft_amp_ctx *c, double H)
{
    double e = -(2.0 * H + 2.0) / 2.0, rk = ALIAS_K + 0.5;
    /* sum over |k| > K of |k|^-(2H+2), by the integral outside the square of side 2K+1 (as a disc of
     * the same area) */
    double tail = 2.0 * M_PI * pow((2.0 * rk) / sqrt(M_PI), -2.0 * H) / (2.0 * H);
    for (int i = 0; i < ALIAS_N; i++)
        for (int j = 0; j < ALIAS_N; j++) {
            double fy = 0.5 * i / (ALIAS_N - 1), fx = 0.5 * j / (ALIAS_N - 1), f2 = fx * fx + fy * fy;
            if (f2 == 0.0) {
                c->ratio[i][j] = 1.0;
                continue;
            }
            double sum = 0.0;
            for (int m = -ALIAS_K; m <= ALIAS_K; m++)
                for (int n = -ALIAS_K; n <= ALIAS_K; n++) {
                    double ax = fx + n, ay = fy + m;
                    sum += pow(ax * ax + ay * ay, e);
                }
            c->ratio[i][j] = sqrt((sum + tail) / pow(f2, e));
        }
}

static double alias_ratio(const fft_amp_ctx *c, double fx, double fy)
{
    double x = fabs(fx) * 2.0 * (ALIAS_N - 1), y = fabs(fy) * 2.0 * (ALIAS_N - 1);
    int j = (int)x, i = (int)y;
    if (j >= ALIAS_N - 1)
        j = ALIAS_N - 2;
    if (i >= ALIAS_N - 1)
        i = ALIAS_N - 2;
    double u = x - j, v = y - i;
    return (1 - v) * ((1 - u) * c->ratio[i][j] + u * c->ratio[i][j + 1]) +
           v * ((1 - u) * c->ratio[i + 1][j] + u * c->ratio[i + 1][j + 1]);
}

/* Near the origin S varies too fast across a frequency cell for its centre value to stand for the cell:
 * the bins with |kx|, |ky| <= NEAR carry the cell average of S(f) |f|^2 over |f_k|^2 (the weight of a bin
 * in the variogram at lags well below the period, where 1 - cos(2 pi f.h) ~ 2 pi^2 (f.h)^2), sampled
 * NEAR_SUB x NEAR_SUB times per cell. */
#define NEAR 3
#define NEAR_SUB 16

static double near_origin_power(const fft_amp_ctx *c, double kx, double ky)
{
    double sum = 0.0, e = c->expo * 2.0 + 1.0; /* S(f) |f|^2 = |f|^-2H = (|f|^2)^(-H) */
    for (int a = 0; a < NEAR_SUB; a++)
        for (int b = 0; b < NEAR_SUB; b++) {
            double fx = (kx + (b + 0.5) / NEAR_SUB - 0.5) / (double)c->px;
            double fy = (ky + (a + 0.5) / NEAR_SUB - 0.5) / (double)c->py;
            sum += pow(fx * fx + fy * fy, e);
        }
    double fx = kx / (double)c->px, fy = ky / (double)c->py;
    return sum / (NEAR_SUB * NEAR_SUB) / (fx * fx + fy * fy);
}

/* Amplitude sqrt(S_d(f)) with S(f) = |f|^-(2H+2), f in cycles per cell; the DC term is 0. */
static void fft_amp(size_t ky, double *amp, void *arg)
{
    const fft_amp_ctx *c = arg;
    double kys = ky <= c->py / 2 ? (double)ky : (double)ky - (double)c->py;
    double fy = kys / (double)c->py, fy2 = fy * fy;
    size_t ncx = c->px / 2 + 1;
    for (size_t kx = 0; kx < ncx; kx++) {
        double fx = (double)kx / (double)c->px;
        double f2 = fx * fx + fy2;
        if (f2 == 0.0)
            amp[kx] = 0.0;
        else if (kx <= NEAR && fabs(kys) <= NEAR)
            amp[kx] = sqrt(near_origin_power(c, (double)kx, kys)) * alias_ratio(c, fx, fy);
        else
            amp[kx] = pow(f2, c->expo) * alias_ratio(c, fx, fy);
    }
}

/* The DC cell's share of the variogram, 2 pi^2 |h|^2 px py * integral over the cell of |f|^-2H (the cell
 * as a disc of equal area), is the variance of a random plane a.x, a ~ N(0, s^2 I): added to the cropped
 * (non-periodic) output. */
static double dc_plane_sd(size_t px, size_t py, double H)
{
    double rho = sqrt(1.0 / (M_PI * (double)px * (double)py));
    double integral = 2.0 * M_PI * pow(rho, 2.0 - 2.0 * H) / (2.0 - 2.0 * H);
    return sqrt(2.0 * M_PI * M_PI * (double)px * (double)py * integral);
}

static size_t padded_size(size_t n, int periodic)
{
    if (periodic)
        return n;
    double want = ceil((double)n * FT_SYNTH_FFT_PAD_DEFAULT);
    return ft_fft_good_size(want < (double)n + 2.0 ? n + 2 : (size_t)want);
}

int ft_synth_fft_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z)
{
    size_t px = padded_size(nx, o->periodic), py = padded_size(ny, o->periodic);
    if (px == 0 || py == 0 || py > SIZE_MAX / (px / 2 + 1))
        return ft_error(FT_E_INVALID, "synth: fft grid for %zu x %zu is too large", nx, ny);
    size_t ncx = px / 2 + 1, rs = ft_fft_real_stride(px);
    fftw_complex *spec = ft_fft_alloc_complex(py * ncx);
    if (spec == NULL)
        return FT_E_NOMEM;
    int rc = ft_progress(o->progress, o->progress_arg, 0.05, "fft: spectrum");
    fft_amp_ctx *ctx = ft_malloc(sizeof *ctx);
    if (ctx == NULL) {
        ft_fft_free(spec);
        return FT_E_NOMEM;
    }
    ctx->py = py;
    ctx->px = px;
    ctx->expo = -(H + 1.0) / 2.0;
    alias_table(ctx, H);
    if (rc == FT_OK)
        rc = ft_synth_fill_hermitian(spec, py, px, o->seed, FT_SYNTH_STREAM_FFT, fft_amp, ctx);
    free(ctx);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 0.4, "fft: inverse transform");
    if (rc == FT_OK)
        rc = ft_fft_c2r_2d(py, px, spec, (double *)spec);
    double ax = 0.0, ay = 0.0;
    if (rc == FT_OK && !o->periodic) {
        ft_rng *r = ft_rng_create(o->seed, FT_SYNTH_STREAM_FFT - 1);
        if (r == NULL)
            rc = FT_E_NOMEM;
        else {
            double sd = dc_plane_sd(px, py, H);
            ax = ft_rng_gaussian(r, sd);
            ay = ft_rng_gaussian(r, sd);
            ft_rng_free(r);
        }
    }
    if (rc == FT_OK) {
        const double *re = (const double *)spec;
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < ny; i++)
            for (size_t j = 0; j < nx; j++)
                z[i * nx + j] = (float)(re[i * rs + j] + ax * (double)j + ay * (double)i);
    }
    ft_fft_free(spec);
    return rc;
}
