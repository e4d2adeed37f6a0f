/* fracterra — unit tests of surface/lag_pair_sums.c: the counters A = Σ w|Δz|, B = Σ w(Δz)², C = Σ w of a
 * run of pairs are bit-identical to a plain scalar loop in the documented order (four interleaved sums,
 * the rest into the first, added as (s0 + s1) + (s2 + s3)) for every run length, with 0/1 weights, without
 * weights (NULL: the same bits as weights of 1), in streams of 1 to 4 runs, in the AVX2 and the portable
 * copy. The exhaustive estimators' D depends on these bits (docs/surface-grid.md).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/core.h"
#include "surface/grid_internal.h"

#define LEN 1031

/* The documented order, one pair at a time (the loop the vector code replaced). */
static void reference(const float *zp, const float *wp, const float *zq, const float *wq, size_t n, ft_lag_acc *acc)
{
    double a[4] = {0.0, 0.0, 0.0, 0.0}, b[4] = {0.0, 0.0, 0.0, 0.0}, c[4] = {0.0, 0.0, 0.0, 0.0};
    size_t j = 0;
    for (; j + 3 < n; j += 4)
        for (int l = 0; l < 4; l++) {
            double d = (double)zq[j + l] - (double)zp[j + l], w = (double)(wp[j + l] * wq[j + l]);
            a[l] += w * fabs(d);
            b[l] += w * d * d;
            c[l] += w;
        }
    for (; j < n; j++) {
        double d = (double)zq[j] - (double)zp[j], w = (double)(wp[j] * wq[j]);
        a[0] += w * fabs(d);
        b[0] += w * d * d;
        c[0] += w;
    }
    acc->a += (a[0] + a[1]) + (a[2] + a[3]);
    acc->b += (b[0] + b[1]) + (b[2] + b[3]);
    acc->c += (c[0] + c[1]) + (c[2] + c[3]);
}

static void assert_same_bits(const ft_lag_acc *x, const ft_lag_acc *y)
{
    assert_memory_equal(&x->a, &y->a, sizeof x->a);
    assert_memory_equal(&x->b, &y->b, sizeof x->b);
    assert_memory_equal(&x->c, &y->c, sizeof x->c);
    assert_memory_equal(&x->dist, &y->dist, sizeof x->dist);
}

typedef struct {
    float z[4][LEN + 8], w[4][LEN + 8], ones[LEN + 8];
} runs;

/* Elevations with a large offset and small differences (where rounding shows), 0/1 weights with about 1 in
 * 5 cells invalid (their elevations 0, as lag_pairs.c makes them). */
static void fill(runs *r, unsigned seed)
{
    srand(seed);
    for (int s = 0; s < 4; s++)
        for (size_t j = 0; j < LEN + 8; j++) {
            r->w[s][j] = rand() % 5 == 0 ? 0.0f : 1.0f;
            r->z[s][j] = r->w[s][j] ? 1234.5f + (float)rand() / (float)RAND_MAX * 37.0f - 18.0f : 0.0f;
        }
    for (size_t j = 0; j < LEN + 8; j++)
        r->ones[j] = 1.0f;
}

static void check_lengths(int generic)
{
    static runs r;
    fill(&r, 17u + (unsigned)generic);
    ft_lag_pair_sums_generic(generic);
    static const size_t lens[] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 255, 1024, 1027, LEN};
    for (size_t t = 0; t < sizeof lens / sizeof lens[0]; t++) {
        size_t n = lens[t];
        for (size_t off = 0; off < 3; off++) { /* unaligned starts */
            const float *zp = r.z[0] + off, *zq = r.z[1] + off + 1, *wp = r.w[0] + off, *wq = r.w[1] + off + 1;
            ft_lag_acc want = {1.5, 2.5, 3.0, 7.0}, got = want; /* the sums are added to what acc holds */
            reference(zp, wp, zq, wq, n, &want);
            ft_lag_pair_sums(zp, wp, zq, wq, n, &got);
            assert_same_bits(&want, &got);
            /* no weights: as weights of 1 */
            ft_lag_acc want1 = {0.0, 0.0, 0.0, 0.0}, got1 = want1;
            reference(zp, r.ones, zq, r.ones, n, &want1);
            ft_lag_pair_sums(zp, NULL, zq, NULL, n, &got1);
            assert_same_bits(&want1, &got1);
        }
    }
    ft_lag_pair_sums_generic(0);
}

static void test_lengths(void **state)
{
    (void)state;
    check_lengths(0);
}

static void test_lengths_generic(void **state)
{
    (void)state;
    check_lengths(1);
}

/* Streams of 1 .. 4 runs: each stream's sums are those of its run alone, weighted or not, both copies. */
static void test_streams(void **state)
{
    (void)state;
    static runs r;
    fill(&r, 5u);
    for (int generic = 0; generic < 2; generic++) {
        ft_lag_pair_sums_generic(generic);
        for (size_t ns = 1; ns <= FT_LAG_STREAMS; ns++)
            for (size_t n = LEN - 6; n <= LEN; n++)
                for (int weighted = 0; weighted < 2; weighted++) {
                    const float *zp[4], *zq[4], *wp[4], *wq[4];
                    ft_lag_acc got[4], want[4];
                    for (size_t s = 0; s < ns; s++) {
                        zp[s] = r.z[s];
                        zq[s] = r.z[(s + 1) % 4] + s + 1;
                        wp[s] = weighted ? r.w[s] : r.ones;
                        wq[s] = weighted ? r.w[(s + 1) % 4] + s + 1 : r.ones;
                        got[s] = want[s] = (ft_lag_acc){(double)s, 0.25, 0.0, 0.0};
                        reference(zp[s], wp[s], zq[s], wq[s], n, &want[s]);
                    }
                    ft_lag_pair_sums_streams(zp, weighted ? wp : NULL, zq, weighted ? wq : NULL, ns, n, got);
                    for (size_t s = 0; s < ns; s++)
                        assert_same_bits(&want[s], &got[s]);
                }
    }
    ft_lag_pair_sums_generic(0);
}

/* Float differences that do not cancel in double: the sums really are in double (a float sum differs). */
static void test_double_accumulation(void **state)
{
    (void)state;
    float zp[9], zq[9], w[9];
    for (int j = 0; j < 9; j++) {
        zp[j] = 16777216.0f; /* 2^24: the next float is 2^24 + 2 */
        zq[j] = j % 2 ? 16777218.0f : 0.5f;
        w[j] = 1.0f;
    }
    ft_lag_acc acc = {0.0, 0.0, 0.0, 0.0};
    ft_lag_pair_sums(zp, w, zq, w, 9, &acc);
    assert_true(acc.a == 4.0 * 2.0 + 5.0 * 16777215.5);
    assert_true(acc.b == 4.0 * 4.0 + 5.0 * 16777215.5 * 16777215.5);
    assert_true(acc.c == 9.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lengths),
        cmocka_unit_test(test_lengths_generic),
        cmocka_unit_test(test_streams),
        cmocka_unit_test(test_double_accumulation),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
