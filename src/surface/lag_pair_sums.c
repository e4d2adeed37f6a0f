/* fracterra — lag_pair_sums.c: the inner sums of the exhaustive lag estimators (src/surface/lag_pairs.c,
 * src/surface/dim_map_lags.c), the counters of Arakawa & Krotkov §2.4 step 1 over a run of pairs:
 * A = Σ w|Δz|, B = Σ w(Δz)², C = Σ w with Δz = zq[j] - zp[j] and w = wp[j] wq[j] (0 or 1: nodata).
 *
 * The order of the additions is part of the result and never changes: four interleaved double sums, pair j
 * of the run going to sum j mod 4 for j < 4 floor(n / 4) and the remaining pairs to sum 0, the four added
 * as (s0 + s1) + (s2 + s3) at the end; per pair d = (double)zq - (double)zp, w = (double)(wp wq) (a float
 * product), A += w |d|, B += (w d) d, C += w. The four sums are the four lanes of one vector, so the loop
 * runs four pairs per instruction, and up to four independent runs (streams: four grid rows) go through
 * one loop so that the additions of one run do not wait on each other. Without weights (every cell valid)
 * w is 1, the products by w are exact and left out, and C is the pair count n: the same bits.
 * On x86-64 a copy compiled for AVX2 (no FMA: every operation is rounded as in the scalar order) is taken
 * when the processor has it, else the SSE2 one; both give the same bits (tests/unit/test_surface_lag_sums.c
 * checks them against a plain scalar loop).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdint.h>
#include <string.h>

#include "surface/grid_internal.h"

typedef double v4d __attribute__((vector_size(32)));
typedef float v4f __attribute__((vector_size(16)));
typedef long long v4l __attribute__((vector_size(32)));

/* Four floats from p (any alignment), as floats or widened to doubles; |d| by clearing the sign bits.
 * Macros rather than functions: a function returning a 32-byte vector has no fixed ABI without AVX. */
#define LOAD4F(f, p) memcpy(&(f), (p), sizeof(f))
#define WIDEN(f) __builtin_convertvector((f), v4d)
#define VABS(d) ((v4d)((v4l)(d) & abs_mask))

/* The sums of ns streams (a compile-time constant once inlined) of n pairs each; weighted: wp, wq hold the
 * weights, else every weight is 1. Adds to acc[s] (a, b, c; dist untouched). */
static inline __attribute__((always_inline)) void streams_body(const float *const *zp, const float *const *wp,
                                                               const float *const *zq, const float *const *wq,
                                                               size_t n, const int ns, const int weighted,
                                                               ft_lag_acc *acc)
{
    const v4l abs_mask = {INT64_MAX, INT64_MAX, INT64_MAX, INT64_MAX};
    v4d a[FT_LAG_STREAMS], b[FT_LAG_STREAMS], c[FT_LAG_STREAMS];
    for (int s = 0; s < ns; s++)
        a[s] = b[s] = c[s] = (v4d){0.0, 0.0, 0.0, 0.0};
    size_t j = 0;
    for (; j + 3 < n; j += 4)
        for (int s = 0; s < ns; s++) {
            v4f p, q;
            LOAD4F(p, zp[s] + j);
            LOAD4F(q, zq[s] + j);
            v4d d = WIDEN(q) - WIDEN(p);
            if (weighted) {
                v4f u, v;
                LOAD4F(u, wp[s] + j);
                LOAD4F(v, wq[s] + j);
                v4d w = WIDEN(u * v);
                a[s] += w * VABS(d);
                b[s] += w * d * d;
                c[s] += w;
            } else {
                a[s] += VABS(d);
                b[s] += d * d;
            }
        }
    for (int s = 0; s < ns; s++) {
        double a0 = a[s][0], b0 = b[s][0], c0 = c[s][0];
        for (size_t t = j; t < n; t++) {
            double d = (double)zq[s][t] - (double)zp[s][t];
            if (weighted) {
                double w = (double)(wp[s][t] * wq[s][t]);
                a0 += w * __builtin_fabs(d);
                b0 += w * d * d;
                c0 += w;
            } else {
                a0 += __builtin_fabs(d);
                b0 += d * d;
            }
        }
        acc[s].a += (a0 + a[s][1]) + (a[s][2] + a[s][3]);
        acc[s].b += (b0 + b[s][1]) + (b[s][2] + b[s][3]);
        acc[s].c += weighted ? (c0 + c[s][1]) + (c[s][2] + c[s][3]) : (double)n;
    }
}

typedef void (*streams_fn)(const float *const *, const float *const *, const float *const *,
                           const float *const *, size_t, ft_lag_acc *);

/* One function per (stream count, weighted), named sums<ns><w|u><suffix>, around the body of its target. */
#define STREAMS_FN(ns, w, tag, body, attr)                                                                   \
    attr static void sums##ns##tag(const float *const *zp, const float *const *wp, const float *const *zq, \
                                   const float *const *wq, size_t n, ft_lag_acc *acc)                     \
    {                                                                                                        \
        body(zp, wp, zq, wq, n, ns, w, acc);                                                                 \
    }
#define STREAMS_TABLE(suffix, body, attr)                                                                    \
    STREAMS_FN(1, 1, w##suffix, body, attr)                                                                  \
    STREAMS_FN(2, 1, w##suffix, body, attr)                                                                  \
    STREAMS_FN(3, 1, w##suffix, body, attr)                                                                  \
    STREAMS_FN(4, 1, w##suffix, body, attr)                                                                  \
    STREAMS_FN(1, 0, u##suffix, body, attr)                                                                  \
    STREAMS_FN(2, 0, u##suffix, body, attr)                                                                  \
    STREAMS_FN(3, 0, u##suffix, body, attr)                                                                  \
    STREAMS_FN(4, 0, u##suffix, body, attr)                                                                  \
    static const streams_fn table##suffix[2][FT_LAG_STREAMS] = {                                             \
        {sums1u##suffix, sums2u##suffix, sums3u##suffix, sums4u##suffix},                                    \
        {sums1w##suffix, sums2w##suffix, sums3w##suffix, sums4w##suffix}};

STREAMS_TABLE(_base, streams_body, )

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define HAVE_AVX2_COPY 1
#include <immintrin.h>

/* streams_body in AVX2 intrinsics (GCC 12 splits __builtin_convertvector of 4 floats into two halves):
 * the same operations on the same lanes, so the same bits. */
__attribute__((target("avx2"))) static inline __attribute__((always_inline)) void
streams_body_avx2(const float *const *zp, const float *const *wp, const float *const *zq, const float *const *wq,
                  size_t n, const int ns, const int weighted, ft_lag_acc *acc)
{
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(INT64_MAX));
    __m256d a[FT_LAG_STREAMS], b[FT_LAG_STREAMS], c[FT_LAG_STREAMS];
    for (int s = 0; s < ns; s++)
        a[s] = b[s] = c[s] = _mm256_setzero_pd();
    size_t j = 0;
    for (; j + 3 < n; j += 4)
        for (int s = 0; s < ns; s++) {
            __m256d d = _mm256_sub_pd(_mm256_cvtps_pd(_mm_loadu_ps(zq[s] + j)), _mm256_cvtps_pd(_mm_loadu_ps(zp[s] + j)));
            __m256d ad = _mm256_and_pd(d, abs_mask);
            if (weighted) {
                __m256d w = _mm256_cvtps_pd(_mm_mul_ps(_mm_loadu_ps(wp[s] + j), _mm_loadu_ps(wq[s] + j)));
                a[s] = _mm256_add_pd(a[s], _mm256_mul_pd(w, ad));
                b[s] = _mm256_add_pd(b[s], _mm256_mul_pd(_mm256_mul_pd(w, d), d));
                c[s] = _mm256_add_pd(c[s], w);
            } else {
                a[s] = _mm256_add_pd(a[s], ad);
                b[s] = _mm256_add_pd(b[s], _mm256_mul_pd(d, d));
            }
        }
    for (int s = 0; s < ns; s++) {
        double la[4], lb[4], lc[4];
        _mm256_storeu_pd(la, a[s]);
        _mm256_storeu_pd(lb, b[s]);
        _mm256_storeu_pd(lc, c[s]);
        for (size_t t = j; t < n; t++) {
            double d = (double)zq[s][t] - (double)zp[s][t];
            if (weighted) {
                double w = (double)(wp[s][t] * wq[s][t]);
                la[0] += w * __builtin_fabs(d);
                lb[0] += w * d * d;
                lc[0] += w;
            } else {
                la[0] += __builtin_fabs(d);
                lb[0] += d * d;
            }
        }
        acc[s].a += (la[0] + la[1]) + (la[2] + la[3]);
        acc[s].b += (lb[0] + lb[1]) + (lb[2] + lb[3]);
        acc[s].c += weighted ? (lc[0] + lc[1]) + (lc[2] + lc[3]) : (double)n;
    }
}

STREAMS_TABLE(_avx2, streams_body_avx2, __attribute__((target("avx2"))))
#endif

static int force_generic; /* tests only: ft_lag_pair_sums_generic */

void ft_lag_pair_sums_generic(int on)
{
    force_generic = on;
}

void ft_lag_pair_sums_streams(const float *const *zp, const float *const *wp, const float *const *zq,
                              const float *const *wq, size_t ns, size_t n, ft_lag_acc *acc)
{
    if (ns == 0 || ns > FT_LAG_STREAMS)
        return;
    int weighted = wp != NULL && wq != NULL;
#ifdef HAVE_AVX2_COPY
    if (!force_generic && __builtin_cpu_supports("avx2")) {
        table_avx2[weighted][ns - 1](zp, wp, zq, wq, n, acc);
        return;
    }
#endif
    table_base[weighted][ns - 1](zp, wp, zq, wq, n, acc);
}

void ft_lag_pair_sums(const float *zp, const float *wp, const float *zq, const float *wq, size_t n, ft_lag_acc *acc)
{
    const float *const p[1] = {zp}, *const q[1] = {zq}, *const u[1] = {wp}, *const v[1] = {wq};
    ft_lag_pair_sums_streams(p, wp != NULL ? u : NULL, q, wq != NULL ? v : NULL, 1, n, acc);
}
