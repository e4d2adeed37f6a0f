/* fracterra — surface/points_lags.c: the lags Δd_i of Arakawa & Krotkov §2.4 step 1 and their annuli
 * |d - Δd_i| <= ε, held as squared-distance intervals [(Δd_i - ε)², (Δd_i + ε)²] with a lookup table from
 * d² to the (consecutive) lags an interval of d² may meet, and the fixed-point scales of the counters.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "points_internal.h"

#define MAX_BINS 65536 /* flags of 64 KB: the lookup stays in the L2 cache */
#define MIN_BINS 64
#define FIXED_BITS 61 /* a term is below 2^61: 2^64 such terms still fit a signed 128-bit sum */
#define EXP_LIMIT 1000

/* 2^(FIXED_BITS - k·e) where v < 2^e (v = 0: e = 0), the exponent clamped to the range of double. */
static double fixed_scale(double v, int k)
{
    int e = 0;
    if (v > 0.0 && isfinite(v))
        frexp(v, &e);
    long x = FIXED_BITS - (long)k * e;
    if (x > EXP_LIMIT)
        x = EXP_LIMIT;
    if (x < -EXP_LIMIT)
        x = -EXP_LIMIT;
    return ldexp(1.0, (int)x);
}

int pts_lags_meet(const pts_lags *L, double dmin2, double dmax2)
{
    for (size_t k = 0; k < L->n; k++)
        if (L->lo2[k] <= dmax2 && L->hi2[k] >= dmin2)
            return 1;
    return 0;
}

/* Bins of equal width in d² over [0, rmax2], fine enough that the narrowest annulus spans a few bins. */
static int build_bins(pts_lags *L)
{
    double narrow = INFINITY;
    for (size_t k = 0; k < L->n; k++)
        if (L->hi2[k] - L->lo2[k] < narrow)
            narrow = L->hi2[k] - L->lo2[k];
    double want = narrow > 0.0 ? 4.0 * L->rmax2 / narrow : MAX_BINS;
    L->nbins = want > MAX_BINS ? MAX_BINS : want < MIN_BINS ? MIN_BINS : (size_t)want;
    L->bin_cap = L->rmax2 * (1.0 + 1e-9);
    L->bin_scale = (double)L->nbins / L->bin_cap;
    /* The annuli live in squared distance: lags whose squares underflow (below about 1e-150) or overflow
     * cannot be binned, and would index the lookup with an infinite scale. */
    if (!(L->rmax2 > 0.0) || !isfinite(L->bin_cap) || !isfinite(L->bin_scale))
        return ft_error(FT_E_INVALID,
                        "lags up to %g (annulus half-width %g) are too small or too large to square in double "
                        "precision; use lags between 1e-150 and 1e150 in the points' units",
                        L->lag[L->n - 1], L->eps);
    L->bin_first = ft_malloc(L->nbins * sizeof *L->bin_first);
    L->bin_count = ft_malloc(L->nbins * sizeof *L->bin_count);
    L->bin_hit = ft_calloc(L->nbins + 1, sizeof *L->bin_hit);
    if (L->bin_first == NULL || L->bin_count == NULL || L->bin_hit == NULL)
        return FT_E_NOMEM;
    /* Lower and upper annulus bounds both increase with the lag, so the lags meeting an interval are
     * consecutive; the bin's interval is widened a little so that rounding in (size_t)(d2 * scale) can
     * never leave out a lag (the kernel tests the exact bounds anyway). */
    size_t first = 0;
    for (size_t b = 0; b < L->nbins; b++) {
        double lo = ((double)b - 1e-6) / L->bin_scale, hi = ((double)b + 1.0 + 1e-6) / L->bin_scale;
        while (first < L->n && L->hi2[first] < lo)
            first++;
        size_t end = first;
        while (end < L->n && L->lo2[end] <= hi)
            end++;
        L->bin_first[b] = (uint32_t)first;
        L->bin_count[b] = (uint32_t)(end - first);
        L->bin_hit[b] = end > first;
    }
    return FT_OK;
}

int pts_lags_init(pts_lags *L, double *lags, size_t n, double eps, double zrange)
{
    *L = (pts_lags){0};
    L->lag = lags;
    L->n = n;
    L->eps = eps;
    L->lo2 = ft_malloc(n * sizeof *L->lo2);
    L->hi2 = ft_malloc(n * sizeof *L->hi2);
    if (L->lo2 == NULL || L->hi2 == NULL)
        return FT_E_NOMEM;
    for (size_t k = 0; k < n; k++) {
        double lo = lags[k] - eps > 0.0 ? lags[k] - eps : 0.0, hi = lags[k] + eps;
        L->lo2[k] = lo * lo;
        L->hi2[k] = hi * hi;
    }
    L->rmin2 = L->lo2[0];
    L->rmax2 = L->hi2[n - 1];
    L->rmax = lags[n - 1] + eps;
    L->qa = fixed_scale(zrange, 1);
    L->qb = fixed_scale(zrange, 2);
    L->qs = fixed_scale(sqrt(L->rmax2) * (1.0 + 1e-12), 1);
    return build_bins(L);
}

void pts_lags_free(pts_lags *L)
{
    if (L == NULL)
        return;
    free(L->lag);
    free(L->lo2);
    free(L->hi2);
    free(L->bin_first);
    free(L->bin_count);
    free(L->bin_hit);
    *L = (pts_lags){0};
}

void pts_acc_merge(pts_acc *dst, const pts_acc *src, size_t n)
{
    for (size_t k = 0; k < n; k++) {
        dst[k].a += src[k].a;
        dst[k].b += src[k].b;
        dst[k].s += src[k].s;
        dst[k].c += src[k].c;
    }
}
