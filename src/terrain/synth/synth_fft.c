/* fracterra — synth_fft.c: spectral synthesis of fractional Brownian surfaces (Voss 1985, "Random
 * fractal forgeries"; Saupe 1988 in "The Science of Fractal Images", algorithm SpectralSynthesisFM2D).
 *
 * A stationary Gaussian field whose Fourier coefficients c(f) are independent complex Gaussians with
 * E|c(f)|^2 ~ |f|^-(2H+2), i.e. amplitude ~ |f|^-(H+1), H = 3 - D, has the radially averaged power
 * spectrum P(f) ~ f^-(2H+2) of 2-D fBm, hence a variogram ~ h^(2H) over lags well below the period.
 * The half-spectrum is filled in FFTW's r2c layout and made Hermitian by construction, so one in-place
 * c2r transform gives the real field; the DC term is 0.
 *
 * Speed (docs/terrain-synthesis.md): the spectrum is single precision (the output is float; the
 * transform's rounding, ~1e-7 of the field's range, is far below its finest increments), filled by
 * row pairs ky, py - ky that share one amplitude row (|f| is the same), each row drawing its Gaussians
 * from its own xoshiro256++ stream with a ziggurat (ft_rng_fast_normals), amplitudes by a vectorized
 * float pow; the transform is ft_fft_c2r_2df (blocked row-column, threaded, thread-count independent).
 * ft_synth_fill_hermitian (double, GSL streams) remains the exact method's filler.
 *
 * The field is periodic with the period of the synthesis grid. With opts->periodic the grid is the
 * output itself (a tile that wraps seamlessly); otherwise the grid is FT_SYNTH_FFT_PAD_DEFAULT times the
 * output per axis, rounded up to a 2·3·5·7-smooth size, and the output is its upper-left corner, so
 * opposite edges are no longer neighbours. docs/terrain-synthesis.md discusses the choice of pad.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth/synth_internal.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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
    /* 33^2 x 13^2 pow calls (a few ms): rows of the table on the threads, each entry summed as ever */
#pragma omp parallel for schedule(static)
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

/* Multiplies row fy's amp[0 .. ncx-1] by alias_ratio / sqrt(2). Along a row the bilinear table is
 * piecewise linear in kx, so it is evaluated segment by segment as a + b kx (a vectorizable loop);
 * a bin on a knot may take either neighbouring segment, which agree there. */
static void alias_row(const fft_amp_ctx *c, double fy, float *amp, int ncx)
{
    double y = fabs(fy) * 2.0 * (ALIAS_N - 1);
    int i = (int)y < ALIAS_N - 1 ? (int)y : ALIAS_N - 2;
    double v = y - i, knot[ALIAS_N];
    for (int j = 0; j < ALIAS_N; j++)
        knot[j] = ((1 - v) * c->ratio[i][j] + v * c->ratio[i + 1][j]) * M_SQRT1_2;
    double per_kx = 2.0 * (ALIAS_N - 1) / (double)c->px; /* table steps per bin */
    int kx = 0;
    for (int j = 0; j < ALIAS_N - 1 && kx < ncx; j++) {
        double end_d = j == ALIAS_N - 2 ? (double)ncx : ceil((j + 1) / per_kx);
        int end = end_d < (double)ncx ? (int)end_d : ncx;
        float b = (float)((knot[j + 1] - knot[j]) * per_kx);
        float a = (float)(knot[j] - (knot[j + 1] - knot[j]) * j);
#pragma omp simd
        for (int k = kx; k < end; k++)
            amp[k] *= a + b * (float)k;
        kx = end > kx ? end : kx;
    }
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

/* x^e for x > 0, in float arithmetic without branches so that an `omp simd` loop vectorizes (a libm
 * pow per bin was a third of the synthesis time). log2 x = k + ln(m) / ln 2 with x = m 2^k,
 * m in [sqrt(1/2), sqrt(2)), and ln m = 2 atanh(t), t = (m - 1) / (m + 1), |t| < 0.172, summed to t^9
 * (truncation < 1e-9); 2^y = 2^n 2^r with n = round(y) (the 1.5 * 2^23 trick, exact for |y| < 2^22)
 * and 2^r, |r| <= 1/2, by its Taylor series to degree 7 (truncation < 6e-9). Relative error < 2e-6
 * over the range used here (x in [1e-9, 1], |e| <= 1), far below the sampling noise of the amplitudes. */
static inline float pow_pos(float x, float e)
{
    uint32_t b;
    memcpy(&b, &x, sizeof b);
    int32_t k = (int32_t)((b >> 23) & 0xffu) - 127;
    uint32_t mb = (b & 0x007fffffu) | 0x3f800000u;
    float m;
    memcpy(&m, &mb, sizeof m);
    int32_t big = m > 1.41421356f;
    k += big;
    m *= 1.0f - 0.5f * (float)big;
    float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
    float ln_m = 2.0f * t * (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7 + t2 * (1.0f / 9)))));
    float y = e * ((float)k + ln_m * 1.44269504f);
    float n = (y + 12582912.0f) - 12582912.0f, r = (y - n) * 0.693147181f;
    float p = 1.0f + r * (1.0f + r * (1.0f / 2 + r * (1.0f / 6 + r * (1.0f / 24 + r * (1.0f / 120 +
              r * (1.0f / 720 + r * (1.0f / 5040)))))));
    uint32_t sb = (uint32_t)((int32_t)n + 127) << 23;
    float scale;
    memcpy(&scale, &sb, sizeof scale);
    return p * scale;
}

/* Row ky's (0 <= ky <= py/2) standard deviation of the real and of the imaginary part of each
 * coefficient, sqrt(S_d(f) / 2) with S(f) = |f|^-(2H+2), f in cycles per cell; the DC term is 0. It
 * depends on |fy| only, so row py - ky has the same. */
static void fft_amp_row(const fft_amp_ctx *c, size_t ky, float *amp)
{
    int ncx = (int)(c->px / 2 + 1);
    float fy = (float)((double)ky / (double)c->py), fy2 = fy * fy, e = (float)c->expo;
    float dfx = (float)(1.0 / (double)c->px);
#pragma omp simd
    for (int kx = 0; kx < ncx; kx++) {
        float fx = (float)kx * dfx;
        amp[kx] = pow_pos(fx * fx + fy2, e); /* kx = ky = 0 gives a finite value, replaced below */
    }
    double fyd = (double)ky / (double)c->py;
    alias_row(c, fyd, amp, ncx);
    for (int kx = 0; ky <= NEAR && kx <= NEAR && kx < ncx; kx++) {
        double p = kx == 0 && ky == 0 ? 0.0 : near_origin_power(c, (double)kx, (double)ky);
        amp[kx] = (float)(sqrt(p) * alias_ratio(c, (double)kx / (double)c->px, fyd) * M_SQRT1_2);
    }
}

/* One half-spectrum row of independent complex Gaussians, real and imaginary parts N(0, amp[kx]^2),
 * from its own stream (xoshiro256++ with a ziggurat: ft_rng_fast_normals). */
static void fill_row(fftwf_complex *row, const float *amp, size_t ncx, uint64_t seed, uint64_t stream)
{
    ft_rng_fast r;
    ft_rng_fast_init(&r, seed, stream);
    float *v = (float *)row;
    ft_rng_fast_normals(&r, v, 2 * ncx);
    for (size_t kx = 0; kx < ncx; kx++) {
        v[2 * kx] *= amp[kx];
        v[2 * kx + 1] *= amp[kx];
    }
}

/* Hermitian symmetry on the self-paired columns kx = 0 and kx = px/2 (px even) of rows a = ky and
 * b = py - ky: b is a's conjugate there; when a is its own mirror (ky = 0, py/2) the bins are real with
 * the whole variance, as in ft_synth_fill_hermitian. */
static void pair_columns(fftwf_complex *a, fftwf_complex *b, size_t px)
{
    size_t cols[2] = {0, px / 2};
    int ncols = (px % 2 == 0 && px > 1) ? 2 : 1;
    for (int c = 0; c < ncols; c++) {
        size_t kx = cols[c];
        if (a == b) {
            a[kx][0] *= (float)M_SQRT2;
            a[kx][1] = 0.0f;
        } else {
            b[kx][0] = a[kx][0];
            b[kx][1] = -a[kx][1];
        }
    }
}

/* The py x (px/2+1) half-spectrum, Hermitian by construction. Rows ky and py - ky are filled together
 * from one amplitude row (half the pow calls), each from its own stream FT_SYNTH_STREAM_FFT + row, so
 * the cells do not depend on the thread count. */
static int fill_spectrum(fftwf_complex *spec, size_t py, size_t px, uint64_t seed, const fft_amp_ctx *c)
{
    size_t ncx = px / 2 + 1;
    int failed = 0;
#pragma omp parallel reduction(| : failed)
    {
        float *amp = malloc(ncx * sizeof *amp);
        failed |= amp == NULL;
#pragma omp for schedule(static)
        for (size_t ky = 0; ky <= py / 2; ky++) {
            if (amp == NULL)
                continue;
            size_t my = (py - ky) % py;
            fftwf_complex *a = spec + ky * ncx, *b = spec + my * ncx;
            fft_amp_row(c, ky, amp);
            fill_row(a, amp, ncx, seed, FT_SYNTH_STREAM_FFT + ky);
            if (my != ky)
                fill_row(b, amp, ncx, seed, FT_SYNTH_STREAM_FFT + my);
            pair_columns(a, b, px);
        }
        free(amp);
    }
    if (failed)
        return ft_error(FT_E_NOMEM, "synth: out of memory filling a %zu x %zu spectrum", py, px);
    return FT_OK;
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

/* The spectrum's memory, which becomes the output: malloc'd (the caller frees the cells with free()),
 * aligned as fftwf_malloc aligns, with the huge-page hint before its first touch. */
static fftwf_complex *alloc_spectrum(size_t n)
{
    void *p = NULL;
    if (n > SIZE_MAX / sizeof(fftwf_complex) || posix_memalign(&p, 64, n * sizeof(fftwf_complex)) != 0) {
        ft_error(FT_E_NOMEM, "synth: out of memory allocating a %zu-bin spectrum", n);
        return NULL;
    }
    ft_fft_advise_huge(p, n * sizeof(fftwf_complex));
    return p;
}

/* The output's upper-left nx x ny corner of the transformed rows (stride rs floats) plus the plane
 * a_x j + a_y i, written to dst. dst may be re itself: cell (i, j) then goes from float i rs + j to
 * i nx + j, never above where it came from (nx <= rs), and everything it overwrites has been read (rows
 * in order, cells in order), so no second buffer is touched. One pass in order: memory-bound, and threads
 * would need a barrier for every wave of rows that may move at once (measured: more CPU, no gain under
 * load). */
static void crop(const float *re, float *dst, size_t nx, size_t ny, size_t rs, double ax, double ay)
{
    for (size_t i = 0; i < ny; i++) {
        const float *src = re + i * rs;
        float *out = dst + i * nx;
        for (size_t j = 0; j < nx; j++)
            out[j] = (float)((double)src[j] + ax * (double)j + ay * (double)i);
    }
}

/* The synthesis up to the crop: the half-spectrum filled in spec (py x (px/2+1) bins), transformed in
 * place (only the ny rows the output keeps: the padded rows below are never read), and the DC plane's
 * slopes. */
static int synthesize(size_t ny, size_t px, size_t py, double H, const ft_synth_opts *o,
                      fftwf_complex *spec, double *ax, double *ay)
{
    int rc = ft_progress(o->progress, o->progress_arg, 0.05, "fft: spectrum");
    fft_amp_ctx *ctx = ft_malloc(sizeof *ctx);
    if (ctx == NULL)
        return FT_E_NOMEM;
    ctx->py = py;
    ctx->px = px;
    ctx->expo = -(H + 1.0) / 2.0;
    alias_table(ctx, H);
    if (rc == FT_OK)
        rc = fill_spectrum(spec, py, px, o->seed, ctx);
    free(ctx);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 0.4, "fft: inverse transform");
    if (rc == FT_OK)
        rc = ft_fft_c2r_2df_rows(py, px, spec, ny);
    if (rc == FT_OK)
        rc = ft_synth_fft_plane(px, py, H, o, ax, ay);
    return rc;
}

/* The padded grid of an nx x ny output, checked against the sizes the transform can take. */
static int grid_size(size_t nx, size_t ny, int periodic, size_t *px, size_t *py)
{
    *px = padded_size(nx, periodic);
    *py = padded_size(ny, periodic);
    if (*px == 0 || *py == 0 || *px > INT_MAX || *py > INT_MAX || *py > SIZE_MAX / (*px / 2 + 1))
        return ft_error(FT_E_INVALID, "synth: fft grid for %zu x %zu is too large", nx, ny);
    return FT_OK;
}

int ft_synth_fft_make(size_t nx, size_t ny, double H, const ft_synth_opts *o, float **z)
{
    *z = NULL;
    size_t px, py;
    int rc = grid_size(nx, ny, o->periodic, &px, &py);
    if (rc != FT_OK)
        return rc;
    fftwf_complex *spec = alloc_spectrum(py * (px / 2 + 1));
    if (spec == NULL)
        return FT_E_NOMEM;
    double ax = 0.0, ay = 0.0;
    rc = synthesize(ny, px, py, H, o, spec, &ax, &ay);
    if (rc != FT_OK) {
        free(spec);
        return rc;
    }
    crop((float *)spec, (float *)spec, nx, ny, ft_fft_real_stride(px), ax, ay);
    float *cells = realloc(spec, nx * ny * sizeof *cells); /* shrinks in place (or keeps the block) */
    *z = cells != NULL ? cells : (float *)spec;
    return FT_OK;
}

int ft_synth_fft_workspace(size_t nx, size_t ny, int periodic, fftwf_complex **spec)
{
    *spec = NULL;
    size_t px, py;
    int rc = grid_size(nx, ny, periodic, &px, &py);
    if (rc != FT_OK)
        return rc;
    size_t n = py * (px / 2 + 1);
    fftwf_complex *p = alloc_spectrum(n);
    if (p == NULL)
        return FT_E_NOMEM;
    memset(p, 0, n * sizeof *p); /* every page faulted in now, not in the syntheses that reuse it */
    *spec = p;
    return FT_OK;
}

int ft_synth_fft_into(size_t nx, size_t ny, double H, const ft_synth_opts *o, fftwf_complex *spec, float *z)
{
    size_t px, py;
    int rc = grid_size(nx, ny, o->periodic, &px, &py);
    double ax = 0.0, ay = 0.0;
    if (rc == FT_OK)
        rc = synthesize(ny, px, py, H, o, spec, &ax, &ay);
    if (rc == FT_OK)
        crop((const float *)spec, z, nx, ny, ft_fft_real_stride(px), ax, ay);
    return rc;
}

/* ---- Slabs of rows for the distributed run (synth_fft_rows.c; docs/tiling.md). Same helpers, same
 * expressions as above, so a slab's spectrum rows are the bits fill_spectrum gives them. ---- */

size_t ft_synth_fft_padded(size_t n, int periodic)
{
    return padded_size(n, periodic);
}

int ft_synth_fft_fill_rows(size_t py, size_t px, double H, uint64_t seed, size_t row0, size_t nrows,
                           fftwf_complex *rows)
{
    size_t ncx = px / 2 + 1;
    fft_amp_ctx *ctx = ft_malloc(sizeof *ctx);
    if (ctx == NULL)
        return FT_E_NOMEM;
    ctx->py = py;
    ctx->px = px;
    ctx->expo = -(H + 1.0) / 2.0;
    alias_table(ctx, H);
    int failed = 0;
#pragma omp parallel reduction(| : failed)
    {
        float *amp = malloc(ncx * sizeof *amp);
        fftwf_complex *partner = malloc(ncx * sizeof *partner);
        failed |= amp == NULL || partner == NULL;
#pragma omp for schedule(static)
        for (size_t i = 0; i < nrows; i++) {
            if (amp == NULL || partner == NULL)
                continue;
            size_t r = row0 + i, ky = r <= py / 2 ? r : py - r; /* ky: the row whose amplitudes r shares */
            fftwf_complex *row = rows + i * ncx;
            fft_amp_row(ctx, ky, amp);
            fill_row(row, amp, ncx, seed, FT_SYNTH_STREAM_FFT + r);
            if (ky == r && (py - r) % py == r)
                pair_columns(row, row, px);
            else if (ky != r) { /* the conjugate of row ky on its self-paired columns: ky's stream again */
                fill_row(partner, amp, ncx, seed, FT_SYNTH_STREAM_FFT + ky);
                pair_columns(partner, row, px);
            }
        }
        free(partner);
        free(amp);
    }
    free(ctx);
    if (failed)
        return ft_error(FT_E_NOMEM, "synth: out of memory filling %zu rows of a %zu x %zu spectrum", nrows, py, px);
    return FT_OK;
}

int ft_synth_fft_plane(size_t px, size_t py, double H, const ft_synth_opts *o, double *ax, double *ay)
{
    *ax = *ay = 0.0;
    if (o->periodic)
        return FT_OK;
    ft_rng *r = ft_rng_create(o->seed, FT_SYNTH_STREAM_FFT - 1);
    if (r == NULL)
        return FT_E_NOMEM;
    double sd = dc_plane_sd(px, py, H);
    *ax = ft_rng_gaussian(r, sd);
    *ay = ft_rng_gaussian(r, sd);
    ft_rng_free(r);
    return FT_OK;
}
