/* fracterra — line/dutton_raw.c: the raw positions of a run of vertices in one pass of Dutton's (1981)
 * enhancement (dutton.c), several vertices at a time.
 *
 * ft_dutton_raw_vertex costs a square root and two divisions per vertex, and a branch on V's side that the
 * data leaves unpredictable; done one vertex at a time it is most of the unguarded pass's arithmetic and a
 * sizeable part of the guarded one's. The interior vertices of a run (both neighbours inside the chain, no
 * wrap round a ring) are done eight (AVX-512) or four (AVX2) at a time with the very operations of
 * ft_dutton_move, in the same order: IEEE square root, division, product, sum and difference are correctly
 * rounded in the vector units as in the scalar ones, and the library is built in ISO C (-std=c11: no
 * contraction into fused multiply-adds), so every lane gives the scalar function's bits. V's side becomes a
 * blend; a vertex whose segments are not both split keeps its input position; the lanes the vector form does
 * not decide — a junction with no clear side (|turn| not above 1e-12 a c: straight runs, reversals, zero-length
 * segments, which ft_dutton_move may bend in calibrated mode) — are redone by ft_dutton_raw_vertex, as are a
 * run's ends that wrap and its last few vertices. Elsewhere (no AVX2, other processors) every vertex is done
 * by ft_dutton_raw_vertex. test_line_dutton_raw.c compares each path with it bit for bit.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "line/dutton_internal.h"

#include <stdint.h>
#include <string.h>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define RAW_X86 1
#else
#define RAW_X86 0
#endif

/* Vertices [lo, hi) one at a time: raw position of v at xy[2 (v - v0)]. */
static void run_scalar(const ft_chain *in, const unsigned char *split, const ft_dutton_pass_params *pp, size_t v0,
                       size_t lo, size_t hi, double *xy)
{
    for (size_t v = lo; v < hi; v++)
        (void)ft_dutton_raw_vertex(in, split, pp, v, &xy[2 * (v - v0)], &xy[2 * (v - v0) + 1]);
}

#if RAW_X86
/* Interior vertices [lo, lo + 8 m) (1 <= lo, lo + 8 m <= n - 1), eight at a time; the expressions are
 * ft_dutton_move's, term by term. Lanes with no clear side are redone by the scalar function. */
__attribute__((target("avx512f"))) static size_t run_avx512(const ft_chain *in, const unsigned char *split,
                                                            const ft_dutton_pass_params *pp, size_t v0, size_t lo,
                                                            size_t hi, double *xy)
{
    const double *X = in->x, *Y = in->y;
    const __m512d half = _mm512_set1_pd(0.5), one = _mm512_set1_pd(1.0), two = _mm512_set1_pd(2.0);
    const __m512d mone = _mm512_set1_pd(-1.0), zero = _mm512_setzero_pd();
    const __m512d tiny = _mm512_set1_pd(FT_DUTTON_STRAIGHT_SIN), cos_t = _mm512_set1_pd(pp->cos_t);
    const __m512d sin_t = _mm512_set1_pd(pp->sin_t), uc = _mm512_set1_pd(pp->uc);
    const __m512i lo4 = _mm512_set_epi64(11, 3, 10, 2, 9, 1, 8, 0), hi4 = _mm512_set_epi64(15, 7, 14, 6, 13, 5, 12, 4);
    size_t v = lo;
    for (; v + 8 <= hi; v += 8) {
        /* both segments split: split[v - 1] and split[v] non-zero */
        __m512i sp = _mm512_cvtepu8_epi64(_mm_loadl_epi64((const __m128i *)(split + v - 1)));
        __m512i sn = _mm512_cvtepu8_epi64(_mm_loadl_epi64((const __m128i *)(split + v)));
        __mmask8 go = _mm512_test_epi64_mask(sp, sp) & _mm512_test_epi64_mask(sn, sn);
        __m512d vx = _mm512_loadu_pd(X + v), vy = _mm512_loadu_pd(Y + v), ox = vx, oy = vy;
        __mmask8 sided = 0;
        if (go != 0) {
            __m512d px = _mm512_loadu_pd(X + v - 1), py = _mm512_loadu_pd(Y + v - 1);
            __m512d nx = _mm512_loadu_pd(X + v + 1), ny = _mm512_loadu_pd(Y + v + 1);
            __m512d ax = _mm512_sub_pd(vx, px), ay = _mm512_sub_pd(vy, py);
            __m512d cx = _mm512_sub_pd(nx, vx), cy = _mm512_sub_pd(ny, vy);
            __m512d a2 = _mm512_add_pd(_mm512_mul_pd(ax, ax), _mm512_mul_pd(ay, ay));
            __m512d c2 = _mm512_add_pd(_mm512_mul_pd(cx, cx), _mm512_mul_pd(cy, cy));
            __m512d ac = _mm512_sqrt_pd(_mm512_mul_pd(a2, c2));
            __m512d turn = _mm512_sub_pd(_mm512_mul_pd(ax, cy), _mm512_mul_pd(ay, cx));
            sided = go & _mm512_cmp_pd_mask(_mm512_abs_pd(turn), _mm512_mul_pd(tiny, ac), _CMP_GT_OQ);
            __m512d side = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(turn, zero, _CMP_LT_OQ), mone, one);
            __m512d e2 = _mm512_sub_pd(_mm512_add_pd(a2, c2), _mm512_mul_pd(_mm512_mul_pd(two, ac), cos_t));
            __m512d s = _mm512_mul_pd(half, _mm512_add_pd(one, _mm512_div_pd(_mm512_sub_pd(a2, c2), e2)));
            __m512d h = _mm512_div_pd(_mm512_mul_pd(_mm512_mul_pd(side, ac), sin_t), e2);
            __m512d ux = _mm512_mul_pd(half, _mm512_sub_pd(nx, px)), uy = _mm512_mul_pd(half, _mm512_sub_pd(ny, py));
            __m512d sx = _mm512_sub_pd(_mm512_add_pd(_mm512_mul_pd(half, _mm512_add_pd(px, vx)), _mm512_mul_pd(s, ux)),
                                       _mm512_mul_pd(h, uy));
            __m512d sy = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(half, _mm512_add_pd(py, vy)), _mm512_mul_pd(s, uy)),
                                       _mm512_mul_pd(h, ux));
            ox = _mm512_mask_blend_pd(sided, vx, _mm512_add_pd(vx, _mm512_mul_pd(uc, _mm512_sub_pd(sx, vx))));
            oy = _mm512_mask_blend_pd(sided, vy, _mm512_add_pd(vy, _mm512_mul_pd(uc, _mm512_sub_pd(sy, vy))));
        }
        double *o = xy + 2 * (v - v0);
        _mm512_storeu_pd(o, _mm512_permutex2var_pd(ox, lo4, oy));
        _mm512_storeu_pd(o + 8, _mm512_permutex2var_pd(ox, hi4, oy));
        for (unsigned rest = (unsigned)(go & (__mmask8)~sided); rest != 0; rest &= rest - 1)
            run_scalar(in, split, pp, v0, v + (size_t)__builtin_ctz(rest), v + (size_t)__builtin_ctz(rest) + 1, xy);
    }
    return v;
}

/* The same four at a time. */
__attribute__((target("avx2"))) static size_t run_avx2(const ft_chain *in, const unsigned char *split,
                                                       const ft_dutton_pass_params *pp, size_t v0, size_t lo,
                                                       size_t hi, double *xy)
{
    const double *X = in->x, *Y = in->y;
    const __m256d half = _mm256_set1_pd(0.5), one = _mm256_set1_pd(1.0), two = _mm256_set1_pd(2.0);
    const __m256d mone = _mm256_set1_pd(-1.0), zero = _mm256_setzero_pd();
    const __m256d tiny = _mm256_set1_pd(FT_DUTTON_STRAIGHT_SIN), cos_t = _mm256_set1_pd(pp->cos_t);
    const __m256d sin_t = _mm256_set1_pd(pp->sin_t), uc = _mm256_set1_pd(pp->uc);
    const __m256d sign = _mm256_set1_pd(-0.0);
    size_t v = lo;
    for (; v + 4 <= hi; v += 4) {
        int32_t bp, bn;
        memcpy(&bp, split + v - 1, 4);
        memcpy(&bn, split + v, 4);
        __m256i sp = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(bp)), sn = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(bn));
        __m256i zi = _mm256_setzero_si256();
        __m256d stay = _mm256_castsi256_pd(_mm256_or_si256(_mm256_cmpeq_epi64(sp, zi), _mm256_cmpeq_epi64(sn, zi)));
        unsigned go = ~(unsigned)_mm256_movemask_pd(stay) & 15u;
        __m256d vx = _mm256_loadu_pd(X + v), vy = _mm256_loadu_pd(Y + v), ox = vx, oy = vy;
        unsigned sided = 0;
        if (go != 0) {
            __m256d px = _mm256_loadu_pd(X + v - 1), py = _mm256_loadu_pd(Y + v - 1);
            __m256d nx = _mm256_loadu_pd(X + v + 1), ny = _mm256_loadu_pd(Y + v + 1);
            __m256d ax = _mm256_sub_pd(vx, px), ay = _mm256_sub_pd(vy, py);
            __m256d cx = _mm256_sub_pd(nx, vx), cy = _mm256_sub_pd(ny, vy);
            __m256d a2 = _mm256_add_pd(_mm256_mul_pd(ax, ax), _mm256_mul_pd(ay, ay));
            __m256d c2 = _mm256_add_pd(_mm256_mul_pd(cx, cx), _mm256_mul_pd(cy, cy));
            __m256d ac = _mm256_sqrt_pd(_mm256_mul_pd(a2, c2));
            __m256d turn = _mm256_sub_pd(_mm256_mul_pd(ax, cy), _mm256_mul_pd(ay, cx));
            __m256d clear = _mm256_cmp_pd(_mm256_andnot_pd(sign, turn), _mm256_mul_pd(tiny, ac), _CMP_GT_OQ);
            sided = go & (unsigned)_mm256_movemask_pd(clear);
            __m256d side = _mm256_blendv_pd(mone, one, _mm256_cmp_pd(turn, zero, _CMP_LT_OQ));
            __m256d e2 = _mm256_sub_pd(_mm256_add_pd(a2, c2), _mm256_mul_pd(_mm256_mul_pd(two, ac), cos_t));
            __m256d s = _mm256_mul_pd(half, _mm256_add_pd(one, _mm256_div_pd(_mm256_sub_pd(a2, c2), e2)));
            __m256d h = _mm256_div_pd(_mm256_mul_pd(_mm256_mul_pd(side, ac), sin_t), e2);
            __m256d ux = _mm256_mul_pd(half, _mm256_sub_pd(nx, px)), uy = _mm256_mul_pd(half, _mm256_sub_pd(ny, py));
            __m256d sx = _mm256_sub_pd(_mm256_add_pd(_mm256_mul_pd(half, _mm256_add_pd(px, vx)), _mm256_mul_pd(s, ux)),
                                       _mm256_mul_pd(h, uy));
            __m256d sy = _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(half, _mm256_add_pd(py, vy)), _mm256_mul_pd(s, uy)),
                                       _mm256_mul_pd(h, ux));
            __m256d take = _mm256_andnot_pd(stay, clear);
            ox = _mm256_blendv_pd(vx, _mm256_add_pd(vx, _mm256_mul_pd(uc, _mm256_sub_pd(sx, vx))), take);
            oy = _mm256_blendv_pd(vy, _mm256_add_pd(vy, _mm256_mul_pd(uc, _mm256_sub_pd(sy, vy))), take);
        }
        __m256d l = _mm256_unpacklo_pd(ox, oy), r = _mm256_unpackhi_pd(ox, oy); /* x0 y0 x2 y2, x1 y1 x3 y3 */
        double *o = xy + 2 * (v - v0);
        _mm256_storeu_pd(o, _mm256_permute2f128_pd(l, r, 0x20));
        _mm256_storeu_pd(o + 4, _mm256_permute2f128_pd(l, r, 0x31));
        for (unsigned rest = go & ~sided; rest != 0; rest &= rest - 1)
            run_scalar(in, split, pp, v0, v + (size_t)__builtin_ctz(rest), v + (size_t)__builtin_ctz(rest) + 1, xy);
    }
    return v;
}
#endif

/* Tests only: the path ft_dutton_raw_run takes (FT_DUTTON_RAW_AUTO: the widest the processor has). */
static int forced = FT_DUTTON_RAW_AUTO;

int ft_dutton_raw_force(int path)
{
#if RAW_X86
    if ((path == FT_DUTTON_RAW_AVX512 && !__builtin_cpu_supports("avx512f")) ||
        (path == FT_DUTTON_RAW_AVX2 && !__builtin_cpu_supports("avx2")))
        return 0;
#else
    if (path == FT_DUTTON_RAW_AVX512 || path == FT_DUTTON_RAW_AVX2)
        return 0;
#endif
    forced = path;
    return 1;
}

void ft_dutton_raw_run(const ft_chain *in, const unsigned char *split, const ft_dutton_pass_params *pp, size_t v0,
                       size_t v1, double *xy)
{
    size_t n = in->n, lo = v0 > 0 ? v0 : 1, hi = v1 < n - 1 ? v1 : n - 1, v = lo;
    if (lo >= hi || forced == FT_DUTTON_RAW_SCALAR) {
        run_scalar(in, split, pp, v0, v0, v1, xy);
        return;
    }
    run_scalar(in, split, pp, v0, v0, lo, xy); /* vertex 0: a ring's wraps */
#if RAW_X86
    if (forced == FT_DUTTON_RAW_AVX512 || (forced == FT_DUTTON_RAW_AUTO && __builtin_cpu_supports("avx512f")))
        v = run_avx512(in, split, pp, v0, lo, hi, xy);
    else if (forced == FT_DUTTON_RAW_AVX2 || (forced == FT_DUTTON_RAW_AUTO && __builtin_cpu_supports("avx2")))
        v = run_avx2(in, split, pp, v0, lo, hi, xy);
#endif
    run_scalar(in, split, pp, v0, v, v1, xy); /* the last few, and vertex n - 1 */
}
