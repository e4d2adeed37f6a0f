/* fracterra — terrain/clarke/clarke_variogram.c: F's measured spectrum corrected so that the variogram it
 * implies is the DEM's.
 *
 * The rings of clarke_spectrum.c come from a periodogram of a finite, non-periodic grid under a Hann taper,
 * with nodata footprints filled by the trend. Its expectation is the true spectrum convolved with the
 * window's (Percival & Walden 1993, Spectral Analysis for Physical Applications, §6.3): on a grid of
 * 60-120 cells a side, or half of it empty, that convolution moves power between the longest and the
 * shortest rings (Luxembourg UTM, half nodata: a simulation at c = 1 has 1.5 times the DEM's variogram at
 * one cell and 0.9 times it at 32), and Clarke's variance scaling c then trades one error for the other.
 * The variogram has no such bias: it uses the pairs of valid cells only, whatever the footprint.
 *
 * A stationary field of the grid's plane waves, wave w of variance v_w and integer frequency (k_w, l_w),
 * has the expected variogram along rows gamma_x(h) = sum_w v_w (1 - cos(2 pi k_w h / nx)) (and along
 * columns with l_w, ny): Wiener-Khinchin on the periodic grid. Rows and columns are pooled with the DEM's
 * pair counts. Each ring's power is multiplied, MATCH_ITERATIONS times, by the square root of the ratio
 * of the DEM's variogram (of z - T - H, valid pairs) to the model's at the lag of half the ring's
 * wavelength in cells (where the ring's waves weigh most: 1 - cos is largest at half a period), at most
 * a factor 2 per step and MATCH_MAX_GAIN in all from the measured ring; rings longer than twice the last
 * lag take the ratio at the last lag. Lags: every one to 8 cells, then about 8 per octave. The iteration is the multiplicative spectral correction of iterated
 * amplitude-adjusted surrogates (Schreiber & Schmitz 1996, Phys. Rev. Lett. 77, 635), on the variogram.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/clarke/clarke_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#define MATCH_MAX_LAG 64
#define MATCH_ITERATIONS 12
#define MATCH_MAX_GAIN 4.0

typedef struct {
    size_t nlag;                        /* lags 1 .. nlag cells; only those of used[] are measured */
    unsigned char used[MATCH_MAX_LAG + 1];
    double dem[MATCH_MAX_LAG + 1];      /* the DEM residual's pooled variogram */
    double wx[MATCH_MAX_LAG + 1];       /* share of row pairs at each lag */
    double cos_x[MATCH_MAX_LAG + 1], cos_y[MATCH_MAX_LAG + 1];
} match_lags;

/* The variogram of the residual z - T - H over the pairs of valid cells h apart along rows and columns;
 * *wx the row pairs' share. 0 if there is no pair. */
static double residual_variogram(const ft_grid *dem, const uint8_t *ok, const double *res, size_t rs, size_t h,
                                 double *wx)
{
    double sx = 0.0, sy = 0.0, nx = 0.0, ny = 0.0;
    size_t w = dem->nx;
    for (size_t row = 0; row < dem->ny; row++)
        for (size_t col = 0; col < w; col++) {
            if (!ok[row * w + col])
                continue;
            double r = res[row * rs + col];
            if (col + h < w && ok[row * w + col + h]) {
                double d = res[row * rs + col + h] - r;
                sx += d * d;
                nx += 1.0;
            }
            if (row + h < dem->ny && ok[(row + h) * w + col]) {
                double d = res[(row + h) * rs + col] - r;
                sy += d * d;
                ny += 1.0;
            }
        }
    *wx = nx + ny > 0.0 ? nx / (nx + ny) : 0.5;
    return nx + ny > 0.0 ? 0.5 * (sx + sy) / (nx + ny) : 0.0;
}

/* 1 at the DEM's valid cells; NULL (error set) if out of memory. */
static uint8_t *valid_mask(const ft_grid *dem)
{
    uint8_t *ok = ft_malloc(dem->nx * dem->ny);
    for (size_t row = 0; ok && row < dem->ny; row++)
        for (size_t col = 0; col < dem->nx; col++)
            ok[row * dem->nx + col] =
                (uint8_t)(ft_grid_is_valid(dem, col, row) && isfinite(dem->z[row * dem->nx + col]));
    return ok;
}

/* Where each wave of the half-spectrum sits on the rings, computed once: F's power there is
 * exp((1 - t) log p[lo] + t log p[lo + 1]) between two rings, p[last] beyond the longest, and
 * p[0] exp(t) (t = the finest law's slope times log(wavelength / w[0])) below the shortest. */
#define BIN_NONE 0xFFFF  /* the DC term, a conjugate twin, or one of H's bins: no wave of F */
#define BIN_BELOW 0xFFFE /* below the shortest ring */

typedef struct {
    uint16_t *lo;
    float *t;
    float *p;     /* each wave's variance, per iteration */
    double *logp; /* log of each ring's power, per iteration */
} bin_table;

static void bin_place(const ft_clarke_model *m, double wl, uint16_t *lo, float *t)
{
    size_t a = 0;
    double ta = 0.0;
    int where = clarke_ring_bracket(m, wl, &a, &ta);
    if (where > 0) {
        *lo = (uint16_t)(m->nspectrum - 1);
        *t = 0.0f;
    } else if (where < 0) {
        double slope = m->nregimes > 0 ? m->regimes[0].slope : m->slope;
        *lo = BIN_BELOW;
        *t = (float)(slope * log(wl / m->spectrum_wavelength[0]));
    } else {
        *lo = (uint16_t)a;
        *t = (float)ta;
    }
}

static int bin_table_init(const ft_clarke_model *m, const clarke_frame *fr, bin_table *bt)
{
    size_t nx = m->nx, ny = m->ny, hx = nx / 2 + 1;
    bt->lo = ft_malloc(hx * ny * sizeof *bt->lo);
    bt->t = bt->lo ? ft_malloc(hx * ny * sizeof *bt->t) : NULL;
    bt->p = bt->t ? ft_malloc(hx * ny * sizeof *bt->p) : NULL;
    bt->logp = bt->p ? ft_malloc(m->nspectrum * sizeof *bt->logp) : NULL;
    if (bt->logp == NULL)
        return ft_last_error_code();
    for (size_t ky = 0; ky < ny; ky++)
        for (size_t kx = 0; kx < hx; kx++) {
            size_t i = ky * hx + kx;
            bt->lo[i] = BIN_NONE;
            if (clarke_bin_kind(kx, ky, nx, ny) != CLARKE_BIN_SKIP)
                bin_place(m, clarke_wavelength(fr, (int)kx, clarke_signed_l(ky, ny)), &bt->lo[i], &bt->t[i]);
        }
    for (size_t i = 0; i < m->nharmonics; i++) { /* the simulation leaves F out of H's bins */
        const ft_clarke_harmonic *h = &m->harmonics[i];
        bt->lo[(size_t)(((long)h->l % (long)ny + (long)ny) % (long)ny) * hx + (size_t)h->k] = BIN_NONE;
        bt->lo[(size_t)(((-(long)h->l) % (long)ny + (long)ny) % (long)ny) * hx + (size_t)h->k] = BIN_NONE;
    }
    return FT_OK;
}

static void bin_table_free(bin_table *bt)
{
    free(bt->lo);
    free(bt->t);
    free(bt->p);
    free(bt->logp);
}

/* Per-wave variance of F (c = 1) summed into marginals over the rows (sx[k]) and the columns (sy[|l|]).
 * Each sum runs in a fixed order: the same bits on any thread count. */
static void marginals(const ft_clarke_model *m, bin_table *bt, double *sx, double *sy)
{
    const long nx = (long)m->nx, ny = (long)m->ny, hx = nx / 2 + 1;
    for (size_t i = 0; i < m->nspectrum; i++)
        bt->logp[i] = log(m->spectrum_power[i]);
#pragma omp parallel for schedule(static)
    for (long ky = 0; ky < ny; ky++)
        for (long kx = 0; kx < hx; kx++) {
            size_t i = (size_t)(ky * hx + kx);
            uint16_t lo = bt->lo[i];
            if (lo == BIN_NONE) {
                bt->p[i] = 0.0f;
                continue;
            }
            double t = bt->t[i];
            double lp = lo == BIN_BELOW ? bt->logp[0] + t
                        : t > 0.0 ? (1.0 - t) * bt->logp[lo] + t * bt->logp[lo + 1] : bt->logp[lo];
            int self = clarke_bin_kind((size_t)kx, (size_t)ky, (size_t)nx, (size_t)ny) == CLARKE_BIN_SELF;
            bt->p[i] = (float)(self ? exp(lp) : 0.5 * exp(lp));
        }
#pragma omp parallel for schedule(static)
    for (long kx = 0; kx < hx; kx++) {
        double sum = 0.0;
        for (long ky = 0; ky < ny; ky++)
            sum += bt->p[ky * hx + kx];
        sx[kx] = sum;
    }
    const long hy = ny / 2 + 1;
#pragma omp parallel for schedule(static)
    for (long al = 0; al < hy; al++) {
        double sum = 0.0;
        long rows[2] = {al, (ny - al) % ny};
        for (int r = 0; r < (al == 0 || rows[1] == al ? 1 : 2); r++)
            for (long kx = 0; kx < hx; kx++)
                sum += bt->p[rows[r] * hx + kx];
        sy[al] = sum;
    }
}

/* The model's pooled variogram at every lag from the marginals. */
static void model_variogram(const ft_clarke_model *m, const match_lags *ml, const double *sx, const double *sy,
                            double *out)
{
    size_t hx = m->nx / 2 + 1, hy = m->ny / 2 + 1;
    for (size_t h = 1; h <= ml->nlag; h++) {
        if (!ml->used[h])
            continue;
        double gx = 0.0, gy = 0.0;
        for (size_t k = 1; k < hx; k++)
            gx += sx[k] * (1.0 - cos(2.0 * M_PI * (double)k * (double)h / (double)m->nx));
        for (size_t l = 1; l < hy; l++)
            gy += sy[l] * (1.0 - cos(2.0 * M_PI * (double)l * (double)h / (double)m->ny));
        out[h] = ml->wx[h] * gx + (1.0 - ml->wx[h]) * gy;
    }
}

int clarke_match_variogram(ft_clarke_model *m, const clarke_frame *fr, const ft_grid *dem, const double *res,
                           size_t rs)
{
    if (m->noise != FT_CLARKE_NOISE_SPECTRUM || m->nspectrum < 2)
        return FT_OK;
    match_lags ml;
    size_t side = m->nx < m->ny ? m->nx : m->ny;
    ml.nlag = side / 2 < MATCH_MAX_LAG ? side / 2 : MATCH_MAX_LAG;
    uint8_t *ok = valid_mask(dem);
    if (ok == NULL)
        return ft_last_error_code();
    /* every lag to 8, then about 8 per octave: the correction interpolates between them */
    memset(ml.used, 0, sizeof ml.used);
    for (size_t h = 1; h <= ml.nlag; h++)
        ml.used[h] = h <= 8 || h == ml.nlag || h % (size_t)(1u << (int)floor(log2((double)h) - 2.0)) == 0;
    const long nlag = (long)ml.nlag;
#pragma omp parallel for schedule(dynamic)
    for (long h = 1; h <= nlag; h++)
        if (ml.used[h])
            ml.dem[h] = residual_variogram(dem, ok, res, rs, (size_t)h, &ml.wx[h]);
    for (size_t h = 1; h <= ml.nlag; h++) {
        if (ml.used[h] && !(ml.dem[h] > 0.0)) { /* too few pairs to compare: stop before */
            ml.nlag = h - 1;
            break;
        }
    }
    while (ml.nlag > 0 && !ml.used[ml.nlag])
        ml.nlag--;
    free(ok);
    if (ml.nlag < 2)
        return FT_OK;
    double cell_x = fr->lx / (double)m->nx, cell_y = fr->ly / (double)m->ny;
    double *sx = ft_malloc((m->nx / 2 + 1) * sizeof *sx), *sy = sx ? ft_malloc((m->ny / 2 + 1) * sizeof *sy) : NULL;
    if (sy == NULL) {
        free(sx);
        return ft_last_error_code();
    }
    double model[MATCH_MAX_LAG + 1], *measured = ft_malloc(m->nspectrum * sizeof *measured);
    if (measured == NULL) {
        free(sx);
        free(sy);
        return ft_last_error_code();
    }
    memcpy(measured, m->spectrum_power, m->nspectrum * sizeof *measured);
    bin_table bt = {0};
    int rc = bin_table_init(m, fr, &bt);
    for (int it = 0; it < MATCH_ITERATIONS && rc == FT_OK; it++) {
        marginals(m, &bt, sx, sy);
        model_variogram(m, &ml, sx, sy, model);
        for (size_t i = 0; i < m->nspectrum; i++) {
            /* the ring's half wavelength in cells, on the pooled cell size of its lags */
            double h = 0.5 * m->spectrum_wavelength[i] / sqrt(cell_x * cell_y);
            size_t lo = 1, hi = 1;
            while (hi < ml.nlag && (double)hi < h) {
                lo = hi++;
                while (hi < ml.nlag && !ml.used[hi])
                    hi++;
            }
            if (h <= 1.0 || h >= (double)ml.nlag)
                lo = hi = h <= 1.0 ? 1 : ml.nlag;
            double t = hi > lo ? fmin(1.0, fmax(0.0, log(h / (double)lo) / log((double)hi / (double)lo))) : 0.0;
            double q = (1.0 - t) * log(ml.dem[lo] / model[lo]) + t * log(ml.dem[hi] / model[hi]);
            if (!isfinite(q))
                continue;
            /* half a step, at most a factor 2 per step and MATCH_MAX_GAIN in all, from the measured ring */
            q = fmin(M_LN2, fmax(-M_LN2, 0.5 * q));
            double p = m->spectrum_power[i] * exp(q);
            m->spectrum_power[i] = fmin(measured[i] * MATCH_MAX_GAIN, fmax(measured[i] / MATCH_MAX_GAIN, p));
        }
    }
    bin_table_free(&bt);
    free(measured);
    free(sx);
    free(sy);
    return rc;
}
