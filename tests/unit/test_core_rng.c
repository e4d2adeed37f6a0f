/* fracterra — unit tests of core/rng.c: reproducible streams, distributions, unbiased integers.
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

#include <gsl/gsl_cdf.h>

#include "fracterra/core.h"
#include "ft_test_assert.h"

static void test_same_seed_and_stream_identical(void **state)
{
    (void)state;
    ft_rng *a = ft_rng_create(42, 7), *b = ft_rng_create(42, 7);
    assert_non_null(a);
    assert_non_null(b);
    for (int i = 0; i < 10000; i++) {
        double ua = ft_rng_uniform(a), ub = ft_rng_uniform(b);
        assert_memory_equal(&ua, &ub, sizeof ua);
        double ga = ft_rng_gaussian(a, 3.0), gb = ft_rng_gaussian(b, 3.0);
        assert_memory_equal(&ga, &gb, sizeof ga);
        assert_true(ft_rng_uint(a, UINT64_MAX) == ft_rng_uint(b, UINT64_MAX));
    }
    ft_rng_free(a);
    ft_rng_free(b);
}

static int count_equal_draws(uint64_t s1, uint64_t t1, uint64_t s2, uint64_t t2)
{
    ft_rng *a = ft_rng_create(s1, t1), *b = ft_rng_create(s2, t2);
    int same = 0;
    for (int i = 0; i < 1000; i++)
        same += ft_rng_uint(a, UINT64_MAX) == ft_rng_uint(b, UINT64_MAX);
    ft_rng_free(a);
    ft_rng_free(b);
    return same;
}

static void test_streams_and_seeds_differ(void **state)
{
    (void)state;
    assert_int_equal(count_equal_draws(42, 0, 42, 1), 0);
    assert_int_equal(count_equal_draws(42, 0, 43, 0), 0);
    assert_int_equal(count_equal_draws(0, 1, 1, 0), 0);
    assert_true(ft_rng_mix(42, 0) != ft_rng_mix(42, 1));
    assert_true(ft_rng_mix(0, 1) != ft_rng_mix(1, 0));
    assert_true(ft_rng_mix(5, 9) == ft_rng_mix(5, 9));
    /* streams 0 .. 9999 of one seed: all mixed seeds distinct (a bijection of the stream id) */
    static uint64_t m[10000];
    for (uint64_t s = 0; s < 10000; s++)
        m[s] = ft_rng_mix(2024, s);
    for (int i = 0; i < 10000; i++)
        for (int j = i + 1; j < i + 50 && j < 10000; j++)
            assert_true(m[i] != m[j]);
}

static void test_uniform_range_and_moments(void **state)
{
    (void)state;
    ft_rng *r = ft_rng_create(1, 2);
    const int n = 100000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; i++) {
        double u = ft_rng_uniform(r);
        assert_true(u >= 0.0 && u < 1.0);
        sum += u;
        sum2 += u * u;
    }
    double mean = sum / n, var = sum2 / n - mean * mean;
    assert_near(mean, 0.5, 0.005);     /* sd of the mean: 0.29/316 = 0.0009 */
    assert_near(var, 1.0 / 12.0, 0.002);
    ft_rng_free(r);
}

static void test_gaussian_moments(void **state)
{
    (void)state;
    ft_rng *r = ft_rng_create(123, 0);
    const int n = 100000;
    const double sigma = 2.0;
    double sum = 0.0, sum2 = 0.0;
    int beyond_2sigma = 0;
    for (int i = 0; i < n; i++) {
        double g = ft_rng_gaussian(r, sigma);
        sum += g;
        sum2 += g * g;
        beyond_2sigma += fabs(g) > 2.0 * sigma;
    }
    double mean = sum / n, var = sum2 / n - mean * mean;
    assert_near(mean, 0.0, 0.03);   /* sd of the mean: 2/316 = 0.0063 */
    assert_near(var, 4.0, 0.1);     /* sd of the variance: 4 sqrt(2/n) = 0.018 */
    assert_near((double)beyond_2sigma / n, 0.0455, 0.004);
    ft_rng_free(r);
}

static void test_uint_in_range_and_unbiased(void **state)
{
    (void)state;
    ft_rng *r = ft_rng_create(9, 9);
    assert_true(ft_rng_uint(r, 0) == 0);
    assert_true(ft_rng_uint(r, 1) == 0);
    int counts[3] = {0, 0, 0};
    for (int i = 0; i < 30000; i++) {
        uint64_t v = ft_rng_uint(r, 3);
        assert_true(v < 3);
        counts[v]++;
    }
    for (int k = 0; k < 3; k++)
        assert_true(counts[k] > 9500 && counts[k] < 10500);
    const uint64_t big[] = {UINT64_C(0xffffffff), UINT64_C(0x100000000), UINT64_C(0x100000001),
                            UINT64_C(1) << 40, (UINT64_C(1) << 63) + 1, UINT64_MAX};
    for (size_t k = 0; k < sizeof big / sizeof big[0]; k++) {
        int high = 0;
        for (int i = 0; i < 2000; i++) {
            uint64_t v = ft_rng_uint(r, big[k]);
            assert_true(v < big[k]);
            high += v >= big[k] / 2;
        }
        assert_true(high > 850 && high < 1150); /* both halves of the range are reached */
    }
    ft_rng_free(r);
}

static void test_gsl_handle(void **state)
{
    (void)state;
    ft_rng *r = ft_rng_create(0, 0);
    assert_non_null(ft_rng_gsl(r));
    ft_rng_free(r);
    ft_rng_free(NULL);
}

/* The fast ziggurat normals (Marsaglia & Tsang 2000) against N(0, 1) itself: moments, tail frequencies
 * and a Kolmogorov-Smirnov test, for three (seed, stream) pairs. Every bound is 5 standard errors of the
 * statistic (KS: the 0.1% critical value 1.95 / sqrt(n)), computed from the normal law, not from the
 * generator: a wrong layer table, a biased sign bit or a broken tail shows up here. */
static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static void check_fast_normals(uint64_t seed, uint64_t stream)
{
    enum { N = 1 << 22, NKS = 100000 };
    float *v = malloc(N * sizeof *v);
    assert_non_null(v);
    ft_rng_fast r;
    ft_rng_fast_init(&r, seed, stream);
    ft_rng_fast_normals(&r, v, N);
    double m1 = 0, m2 = 0, m3 = 0, m4 = 0;
    size_t over3 = 0, over4 = 0, neg = 0;
    for (size_t i = 0; i < N; i++) {
        double x = v[i], x2 = x * x;
        assert_true(isfinite(x));
        m1 += x;
        m2 += x2;
        m3 += x2 * x;
        m4 += x2 * x2;
        over3 += fabs(x) > 3.0;
        over4 += fabs(x) > 4.0;
        neg += x < 0.0;
    }
    double n = N;
    m1 /= n, m2 /= n, m3 /= n, m4 /= n;
    assert_near(m1, 0.0, 5.0 / sqrt(n));
    assert_near(m2, 1.0, 5.0 * sqrt(2.0 / n));
    assert_near(m3, 0.0, 5.0 * sqrt(15.0 / n));
    assert_near(m4, 3.0, 5.0 * sqrt(96.0 / n));
    assert_near((double)neg / n, 0.5, 5.0 * 0.5 / sqrt(n));
    double p3 = 2.0 * gsl_cdf_ugaussian_Q(3.0), p4 = 2.0 * gsl_cdf_ugaussian_Q(4.0);
    assert_near((double)over3, n * p3, 5.0 * sqrt(n * p3 * (1 - p3)));
    assert_near((double)over4, n * p4, 5.0 * sqrt(n * p4 * (1 - p4)));
    /* KS on the first NKS deviates */
    qsort(v, NKS, sizeof *v, cmp_float);
    double d = 0.0;
    for (size_t i = 0; i < NKS; i++) {
        double f = gsl_cdf_ugaussian_P(v[i]);
        d = fmax(d, fmax(fabs((double)(i + 1) / NKS - f), fabs(f - (double)i / NKS)));
    }
    assert_true(d < 1.95 / sqrt((double)NKS));
    free(v);
}

static void test_fast_normals_distribution(void **state)
{
    (void)state;
    check_fast_normals(1, 0);
    check_fast_normals(42, 7);
    check_fast_normals(0xdeadbeefULL, 123456789ULL);
}

/* The same (seed, stream) and the same calls give the same deviates; another stream gives others. (The
 * sequence depends on how the draws are split into calls: see ft_rng_fast_normals.) */
static void test_fast_normals_reproducible(void **state)
{
    (void)state;
    enum { N = 1000 };
    float a[N], b[N], c[N];
    ft_rng_fast r;
    ft_rng_fast_init(&r, 9, 3);
    ft_rng_fast_normals(&r, a, N);
    ft_rng_fast_init(&r, 9, 3);
    ft_rng_fast_normals(&r, b, N);
    assert_memory_equal(a, b, sizeof a);
    ft_rng_fast_init(&r, 9, 4);
    ft_rng_fast_normals(&r, c, N);
    assert_true(memcmp(a, c, sizeof a) != 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_seed_and_stream_identical),
        cmocka_unit_test(test_streams_and_seeds_differ),
        cmocka_unit_test(test_uniform_range_and_moments),
        cmocka_unit_test(test_gaussian_moments),
        cmocka_unit_test(test_uint_in_range_and_unbiased),
        cmocka_unit_test(test_gsl_handle),
        cmocka_unit_test(test_fast_normals_distribution),
        cmocka_unit_test(test_fast_normals_reproducible),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
