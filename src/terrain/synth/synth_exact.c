/* fracterra — synth_exact.c: exact simulation of 2-D fractional Brownian surfaces by Stein's
 * stationary-increment ("intrinsic") circulant embedding (M. L. Stein, "Fast and exact simulation of
 * fractional Brownian surfaces", J. Comp. Graph. Stat. 11(3), 2002, 587-599).
 *
 * With alpha = 2H, distances r scaled so the output's diagonal is 1, the isotropic function
 *     K(r) = c0 - r^alpha + c2 r^2          0 <= r <= 1
 *          = beta (R - r)^3 / r             1 <= r <= R
 *          = 0                              r >= R
 * with, for alpha <= 3/2: R = 1, beta = 0, c2 = alpha/2, c0 = 1 - alpha/2 (Stein's Theorem: K is a
 * covariance on R^2); for alpha > 3/2: R = 2 and beta = alpha (2 - alpha) / (3 R (R^2 - 1)),
 * c2 = (alpha - beta (R - 1)^2 (R + 2)) / 2, c0 = beta (R - 1)^3 + 1 - c2 (K twice differentiable at 1).
 * A stationary field Z with covariance K has E(Z(x) - Z(y))^2 = 2 (r^alpha - c2 r^2) for r <= 1.
 *
 * K is sampled on a torus of M_x x M_y nodes with M >= 2 R / h (h = grid step in the scaled units), so
 * its support fits in half a period and the block-circulant matrix holds K exactly between any two
 * output nodes. Its eigenvalues are the DFT of the first row (an even real array: one r2c transform).
 * They are checked non-negative (an error naming D otherwise; round-off below 1e-9 of the largest is
 * set to 0). For alpha > 3/2, when R = 2 does not give a non-negative embedding the torus is enlarged
 * and then R raised to 3 and 4 (Stein notes larger R is needed as alpha -> 2). A field with that
 * circulant covariance is the c2r transform of a Hermitian half-spectrum with E|c_k|^2 = lambda_k / N
 * (the real part of Dietrich & Newsam's complex construction). Finally
 *     X(x) = Z(x) - Z(0) + sqrt(2 c2) (W1 x1 + W2 x2),   W1, W2 ~ N(0, 1),
 * whose increments have exactly E(X(x) - X(y))^2 = 2 r^alpha: the fBm variogram. The raw output is
 * rescaled so that E(z(x) - z(y))^2 = d^(2H), d in cells.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/core.h"

typedef struct {
    double alpha, R, beta, c0, c2;
} stein_cov;

static void stein_init(stein_cov *k, double alpha, double R)
{
    k->alpha = alpha;
    k->R = R;
    if (R <= 1.0) {
        k->beta = 0.0;
        k->c2 = alpha / 2.0;
        k->c0 = 1.0 - alpha / 2.0;
    } else {
        k->beta = alpha * (2.0 - alpha) / (3.0 * R * (R * R - 1.0));
        k->c2 = (alpha - k->beta * (R - 1.0) * (R - 1.0) * (R + 2.0)) / 2.0;
        k->c0 = k->beta * pow(R - 1.0, 3.0) + 1.0 - k->c2;
    }
}

static double stein_K(const stein_cov *k, double r)
{
    if (r <= 1.0)
        return k->c0 - pow(r, k->alpha) + k->c2 * r * r;
    if (r < k->R)
        return k->beta * pow(k->R - r, 3.0) / r;
    return 0.0;
}

/* First row of the block-circulant covariance, in the in-place r2c layout (row stride rs). K depends on
 * min(i, M - i) in each axis separately, so one quadrant is evaluated and mirrored. */
static void fill_circulant(double *c, size_t my, size_t mx, size_t rs, double h, const stein_cov *k)
{
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i <= my / 2; i++) {
        double *row = c + i * rs, *mir = c + ((my - i) % my) * rs;
        for (size_t j = 0; j <= mx / 2; j++) {
            double v = stein_K(k, h * hypot((double)i, (double)j));
            row[j] = v;
            row[(mx - j) % mx] = v;
            mir[j] = v;
            mir[(mx - j) % mx] = v;
        }
    }
}

/* Eigenvalues (real parts of the r2c output): the smallest relative to the largest. */
static double min_relative_eigen(const fftw_complex *spec, size_t n)
{
    double lo = spec[0][0], hi = spec[0][0];
    for (size_t i = 1; i < n; i++) {
        lo = fmin(lo, spec[i][0]);
        hi = fmax(hi, spec[i][0]);
    }
    return hi > 0.0 ? lo / hi : -1.0;
}

typedef struct {
    const fftw_complex *spec;
    size_t ncx;
    double inv_n, floor;
} eigen_amp_ctx;

/* sqrt(lambda / N) of row ky, read from the eigenvalues the row still holds. */
static void eigen_amp(size_t ky, double *amp, void *arg)
{
    const eigen_amp_ctx *c = arg;
    const fftw_complex *row = c->spec + ky * c->ncx;
    for (size_t kx = 0; kx < c->ncx; kx++) {
        double l = row[kx][0];
        amp[kx] = l > c->floor ? sqrt(l * c->inv_n) : 0.0;
    }
}

/* The eigenvalues of the embedding with torus M x M (per axis) and cut-off R; 1 if non-negative. */
static int embed(fftw_complex *spec, size_t my, size_t mx, double h, const stein_cov *k, double *minrel)
{
    fill_circulant((double *)spec, my, mx, ft_fft_real_stride(mx), h, k);
    if (ft_fft_r2c_2d(my, mx, (double *)spec, spec) != FT_OK)
        return -1;
    *minrel = min_relative_eigen(spec, my * (mx / 2 + 1));
    return *minrel >= -1e-9;
}

static size_t torus_size(size_t n, double R, double diag, double extra)
{
    double want = ceil(2.0 * R * diag * extra);
    return ft_fft_good_size(want < (double)n ? n : (size_t)want);
}

int ft_synth_exact_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z)
{
    double alpha = 2.0 * H, diag = hypot((double)(nx - 1), (double)(ny - 1));
    if (diag == 0.0) {
        z[0] = 0.0f;
        return FT_OK;
    }
    double h = 1.0 / diag, minrel = -1.0;
    /* Attempts: (R, torus enlargement). Only alpha > 3/2 ever needs more than the first. */
    static const double tries[4][2] = {{2.0, 1.0}, {2.0, 1.5}, {3.0, 1.0}, {4.0, 1.0}};
    int ntries = alpha <= 1.5 ? 1 : 4, ok = 0;
    stein_cov k;
    fftw_complex *spec = NULL;
    size_t mx = 0, my = 0;
    for (int t = 0; t < ntries && !ok; t++) {
        double R = alpha <= 1.5 ? 1.0 : tries[t][0];
        stein_init(&k, alpha, R);
        mx = torus_size(nx, R, diag, tries[t][1]);
        my = torus_size(ny, R, diag, tries[t][1]);
        ft_fft_free(spec);
        spec = (mx && my && my <= SIZE_MAX / 2 / (mx / 2 + 1)) ? ft_fft_alloc_complex(my * (mx / 2 + 1)) : NULL;
        if (spec == NULL)
            return ft_error(FT_E_NOMEM, "synth: exact: out of memory for a %zu x %zu circulant embedding of a "
                            "%zu x %zu grid", mx, my, nx, ny);
        ok = embed(spec, my, mx, h, &k, &minrel);
        if (ok < 0) {
            ft_fft_free(spec);
            return FT_E_NOMEM;
        }
    }
    if (!ok) {
        ft_fft_free(spec);
        return ft_error(FT_E_NUMERIC, "synth: exact: the circulant embedding for D = %g has a negative "
                        "eigenvalue (%.3g of the largest); use a smaller D or another method", 3.0 - H, minrel);
    }
    int rc = ft_progress(o->progress, o->progress_arg, 0.3, "exact: embedding");
    size_t ncx = mx / 2 + 1;
    eigen_amp_ctx ctx = {spec, ncx, 1.0 / ((double)mx * (double)my), 0.0};
    if (rc == FT_OK)
        rc = ft_synth_fill_hermitian(spec, my, mx, o->seed, FT_SYNTH_STREAM_EXACT, eigen_amp, &ctx);
    if (rc == FT_OK)
        rc = ft_fft_c2r_2d(my, mx, spec, (double *)spec);
    if (rc == FT_OK) {
        ft_rng *r = ft_rng_create(o->seed, FT_SYNTH_STREAM_EXACT - 1);
        if (r == NULL) {
            ft_fft_free(spec);
            return FT_E_NOMEM;
        }
        double w1 = ft_rng_gaussian(r, 1.0), w2 = ft_rng_gaussian(r, 1.0);
        ft_rng_free(r);
        const double *re = (const double *)spec;
        size_t rs = ft_fft_real_stride(mx);
        double z0 = re[0], lin = sqrt(2.0 * k.c2) * h;
        double scale = pow(h, -H) * M_SQRT1_2; /* E(dz)^2 = 2 (h d)^(2H)  ->  d^(2H) */
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < ny; i++)
            for (size_t j = 0; j < nx; j++)
                z[i * nx + j] = (float)(scale * (re[i * rs + j] - z0 + lin * (w1 * (double)j + w2 * (double)i)));
        rc = ft_progress(o->progress, o->progress_arg, 1.0, "exact: done");
    }
    ft_fft_free(spec);
    return rc;
}
