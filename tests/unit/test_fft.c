/* fracterra — unit tests of fft/fft.c: good sizes, r2c/c2r round trips (in and out of place, aligned
 * or not, odd sizes), a known sinusoid's bin, 1-D complex transforms and concurrent use of one plan.
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

#include "fft/fft.h"
#include "fracterra/core.h"
#include "ft_test_assert.h"

static void test_good_size(void **state)
{
    (void)state;
    assert_int_equal(ft_fft_good_size(0), 1);
    assert_int_equal(ft_fft_good_size(1), 1);
    assert_int_equal(ft_fft_good_size(7), 7);
    assert_int_equal(ft_fft_good_size(11), 12);
    assert_int_equal(ft_fft_good_size(13), 14);
    assert_int_equal(ft_fft_good_size(97), 98);
    assert_int_equal(ft_fft_good_size(257), 270);
    assert_int_equal(ft_fft_good_size(1021), 1024);
    assert_int_equal(ft_fft_good_size(4096), 4096);
    assert_int_equal(ft_fft_good_size(5121), 5145);
    for (size_t n = 1; n < 3000; n++) {
        size_t g = ft_fft_good_size(n), m = g;
        assert_true(g >= n);
        static const size_t p[4] = {2, 3, 5, 7};
        for (int i = 0; i < 4; i++)
            while (m % p[i] == 0)
                m /= p[i];
        assert_int_equal(m, 1);
        if (g > n)
            assert_int_equal(ft_fft_good_size(n + 1), g); /* nothing smooth in between */
    }
    assert_int_equal(ft_fft_real_stride(7), 8);
    assert_int_equal(ft_fft_real_stride(8), 10);
}

static void round_trip(size_t ny, size_t nx, int inplace, int misalign)
{
    size_t nc = ny * (nx / 2 + 1), rs = inplace ? ft_fft_real_stride(nx) : nx;
    fftw_complex *spec = ft_fft_alloc_complex(nc + 1);
    double *buf = inplace ? (double *)spec : ft_fft_alloc_real(ny * nx + 1);
    assert_non_null(spec);
    assert_non_null(buf);
    double *re = buf + (misalign && !inplace ? 1 : 0);
    double *orig = malloc(ny * nx * sizeof *orig);
    assert_non_null(orig);
    ft_rng *r = ft_rng_create(3, 0);
    for (size_t i = 0; i < ny; i++)
        for (size_t j = 0; j < nx; j++)
            re[i * rs + j] = orig[i * nx + j] = ft_rng_gaussian(r, 1.0);
    ft_rng_free(r);
    assert_int_equal(ft_fft_r2c_2d(ny, nx, re, spec), 0);
    if (!inplace)
        for (size_t i = 0; i < ny * nx; i++)
            assert_true(re[i] == orig[i]); /* out-of-place r2c keeps its input */
    assert_int_equal(ft_fft_c2r_2d(ny, nx, spec, inplace ? (double *)spec : re), 0);
    double scale = 1.0 / (double)(ny * nx);
    for (size_t i = 0; i < ny; i++)
        for (size_t j = 0; j < nx; j++)
            assert_near(re[i * rs + j] * scale, orig[i * nx + j], 1e-12);
    free(orig);
    if (!inplace)
        ft_fft_free(buf);
    ft_fft_free(spec);
}

static void test_round_trip(void **state)
{
    (void)state;
    round_trip(64, 64, 0, 0);
    round_trip(64, 64, 1, 0);
    round_trip(13, 7, 0, 0);
    round_trip(13, 7, 1, 0);
    round_trip(130, 257, 0, 1);
    round_trip(1, 9, 0, 0);
    round_trip(9, 1, 1, 0);
}

/* cos(2 pi (3 x / nx + 5 y / ny)) has all its power in bins (ky, kx) = (5, 3) and (-5, -3): the half
 * spectrum holds (5, 3) with value nx * ny / 2 and nothing else. */
static void test_sinusoid_bin(void **state)
{
    (void)state;
    size_t ny = 48, nx = 30, ncx = nx / 2 + 1;
    double *re = ft_fft_alloc_real(ny * nx);
    fftw_complex *spec = ft_fft_alloc_complex(ny * ncx);
    assert_non_null(re);
    assert_non_null(spec);
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++)
            re[y * nx + x] = cos(2.0 * M_PI * (3.0 * (double)x / (double)nx + 5.0 * (double)y / (double)ny));
    assert_int_equal(ft_fft_r2c_2d(ny, nx, re, spec), 0);
    for (size_t ky = 0; ky < ny; ky++)
        for (size_t kx = 0; kx < ncx; kx++) {
            double expect = (ky == 5 && kx == 3) ? (double)(nx * ny) / 2.0 : 0.0;
            assert_near(spec[ky * ncx + kx][0], expect, 1e-9);
            assert_near(spec[ky * ncx + kx][1], 0.0, 1e-9);
        }
    ft_fft_free(re);
    ft_fft_free(spec);
}

static void test_c2c_1d(void **state)
{
    (void)state;
    size_t n = 105;
    fftw_complex *a = ft_fft_alloc_complex(n), *b = ft_fft_alloc_complex(n);
    assert_non_null(a);
    assert_non_null(b);
    for (size_t i = 0; i < n; i++) {
        a[i][0] = sin(2.0 * M_PI * 4.0 * (double)i / (double)n);
        a[i][1] = 0.0;
    }
    assert_int_equal(ft_fft_c2c_1d(n, a, b, FT_FFT_FORWARD), 0);
    /* sin = (e^{i..} - e^{-i..}) / 2i: bin 4 holds -i n/2, bin n-4 holds +i n/2. */
    assert_near(b[4][1], -(double)n / 2.0, 1e-9);
    assert_near(b[n - 4][1], (double)n / 2.0, 1e-9);
    assert_near(b[4][0], 0.0, 1e-9);
    assert_int_equal(ft_fft_c2c_1d(n, b, b, FT_FFT_BACKWARD), 0);
    for (size_t i = 0; i < n; i++)
        assert_near(b[i][0] / (double)n, a[i][0], 1e-12);
    ft_fft_free(a);
    ft_fft_free(b);
}

static void test_bad_input(void **state)
{
    (void)state;
    double x[4] = {0};
    fftw_complex c[4] = {{0}};
    assert_int_equal(ft_fft_r2c_2d(0, 4, x, c), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "0 x 4"));
    assert_int_equal(ft_fft_c2r_2d(2, 2, NULL, x), FT_E_INVALID);
    assert_int_equal(ft_fft_c2c_1d(4, c, c, 3), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "3"));
    ft_fft_free(NULL);
}

/* Many threads executing the same cached plans on their own arrays give the serial answer. */
static void test_threads(void **state)
{
    (void)state;
    enum { N = 8, NY = 40, NX = 36 };
    double out[N];
#pragma omp parallel for schedule(static, 1)
    for (int t = 0; t < N; t++) {
        double *re = ft_fft_alloc_real(NY * NX);
        fftw_complex *spec = ft_fft_alloc_complex(NY * (NX / 2 + 1));
        for (int i = 0; i < NY * NX; i++)
            re[i] = sin(0.1 * i);
        ft_fft_r2c_2d(NY, NX, re, spec);
        ft_fft_c2r_2d(NY, NX, spec, re);
        out[t] = re[17];
        ft_fft_free(re);
        ft_fft_free(spec);
    }
    for (int t = 0; t < N; t++)
        assert_near(out[t] / (NY * NX), sin(1.7), 1e-12);
    ft_fft_cleanup();
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_good_size),   cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_sinusoid_bin), cmocka_unit_test(test_c2c_1d),
        cmocka_unit_test(test_bad_input),   cmocka_unit_test(test_threads),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
