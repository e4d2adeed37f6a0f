/* fracterra — tests/unit/test_profile_dim.c: the madogram and variogram estimators of profile dimension
 * (Gneiting, Sevcikova & Percival 2012) on exact fractional Brownian motion profiles, simulated here by
 * circulant embedding (Davies & Harte 1987; Wood & Chan 1994): fractional Gaussian noise of Hurst index H
 * has autocovariance g(k) = (|k + 1|^2H - 2|k|^2H + |k - 1|^2H) / 2; the circulant of g(0..n), g(n-1..1)
 * has non-negative eigenvalues for 0 < H < 1, and its square root applied to complex white noise gives
 * exact noise; its cumulative sum is fBm, D = 2 - H. The paper's RMSE (about 0.03 at n = 1024, 0.016 at
 * 4096) and a bias within 0.005 are checked over 200 and 100 seeds; the extraction of profiles from grids
 * and 3-D lines, and bad input, by hand.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <complex.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "fracterra/fracterra.h"
#include "ft_test_assert.h"

/* In-place radix-2 FFT (m a power of two), forward sign. */
static void fft(double complex *a, size_t m)
{
    for (size_t i = 1, j = 0; i < m; i++) {
        size_t bit = m >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j) {
            double complex t = a[i];
            a[i] = a[j];
            a[j] = t;
        }
    }
    for (size_t len = 2; len <= m; len <<= 1) {
        double complex w = cexp(-2.0 * M_PI * I / (double)len);
        for (size_t i = 0; i < m; i += len) {
            double complex u = 1.0;
            for (size_t k = 0; k < len / 2; k++) {
                double complex x = a[i + k], y = a[i + k + len / 2] * u;
                a[i + k] = x + y;
                a[i + k + len / 2] = x - y;
                u *= w;
            }
        }
    }
}

static double fgn_cov(size_t k, double H)
{
    double h2 = 2.0 * H, kk = (double)k;
    return 0.5 * (pow(kk + 1.0, h2) - 2.0 * pow(kk, h2) + (k > 0 ? pow(kk - 1.0, h2) : 1.0));
}

/* n + 1 samples of fBm (n a power of two) of Hurst index H, seed `seed`. */
static double *fbm(size_t n, double H, uint64_t seed)
{
    size_t m = 2 * n;
    double complex *lam = malloc(m * sizeof *lam), *w = malloc(m * sizeof *w);
    for (size_t k = 0; k < m; k++)
        lam[k] = fgn_cov(k <= n ? k : m - k, H);
    fft(lam, m);
    ft_rng *r = ft_rng_create(seed, 0);
    for (size_t k = 0; k <= n; k++) {
        double l = creal(lam[k]) > 0.0 ? creal(lam[k]) : 0.0;
        if (k == 0 || k == n) {
            w[k] = sqrt(l / (double)m) * ft_rng_gaussian(r, 1.0);
        } else {
            double a = ft_rng_gaussian(r, 1.0), b = ft_rng_gaussian(r, 1.0);
            w[k] = sqrt(l / (2.0 * (double)m)) * (a + I * b);
            w[m - k] = conj(w[k]);
        }
    }
    ft_rng_free(r);
    fft(w, m);
    double *z = malloc((n + 1) * sizeof *z);
    z[0] = 0.0;
    for (size_t i = 0; i < n; i++)
        z[i + 1] = z[i] + creal(w[i]);
    free(lam);
    free(w);
    return z;
}

static void check_accuracy(size_t n, int seeds, double rmse_max)
{
    const double Hs[] = {0.25, 0.5, 0.75};
    for (int h = 0; h < 3; h++) {
        for (int m = 0; m < 2; m++) {
            double sum = 0.0, sum2 = 0.0, D = 2.0 - Hs[h];
            for (int s = 1; s <= seeds; s++) {
                double *z = fbm(n, Hs[h], (uint64_t)s);
                ft_dim_result *r = NULL;
                assert_int_equal(ft_profile_dim(z, n, 1.0, (ft_profile_method)m, &r), FT_OK);
                sum += r->D - D;
                sum2 += (r->D - D) * (r->D - D);
                ft_dim_result_free(r);
                free(z);
            }
            double bias = sum / seeds, rmse = sqrt(sum2 / seeds);
            print_message("  n = %zu, H = %.2f, %-9s bias %+.4f  RMSE %.4f (%d seeds)\n", n, Hs[h],
                          ft_profile_method_name((ft_profile_method)m), bias, rmse, seeds);
            assert_true(fabs(bias) <= 0.005);
            assert_true(rmse <= rmse_max);
        }
    }
}

static void test_fbm_1024(void **state)
{
    (void)state;
    check_accuracy(1024, 200, 0.035);
}

static void test_fbm_4096(void **state)
{
    (void)state;
    check_accuracy(4096, 100, 0.019);
}

/* By hand: z = 0, 1, 0, 1, ... has V_1 = 1/2, V_2 = 0 (constant at lag 2): an error; a line z = i has
 * V_p(2) = 2^p V_p(1): H = 1, D = 1; a grid row and a 3-D line resampled. */
static void test_by_hand_and_extraction(void **state)
{
    (void)state;
    double z[9];
    for (int i = 0; i < 9; i++)
        z[i] = i % 2;
    ft_dim_result *r = NULL;
    assert_error_names(ft_profile_dim(z, 9, 1.0, FT_PROFILE_MADOGRAM, &r), FT_E_NUMERIC, "constant at lag 2");
    for (int i = 0; i < 9; i++)
        z[i] = 3.0 * i + 0.25 * (i * i % 5);
    assert_int_equal(ft_profile_dim(z, 9, 2.0, FT_PROFILE_VARIOGRAM, &r), FT_OK);
    double v1 = 0, v2 = 0;
    for (int i = 0; i + 1 < 9; i++)
        v1 += (z[i + 1] - z[i]) * (z[i + 1] - z[i]);
    for (int i = 0; i + 2 < 9; i++)
        v2 += (z[i + 2] - z[i]) * (z[i + 2] - z[i]);
    v1 /= 16.0;
    v2 /= 14.0;
    assert_near(r->table->rows[0].value, v1, 1e-12);
    assert_near(r->table->rows[1].scale, 4.0, 0.0);
    double D = 2.0 - (log(v2) - log(v1)) / (2.0 * log(2.0));
    assert_near(r->D, D < 1.0 ? 1.0 : D, 1e-12);
    assert_string_equal(r->method, "variogram");
    assert_null(ft_dim_result_find_warning(r, "narrow band"));
    ft_dim_result_free(r);
    assert_error_names(ft_profile_dim(z, 2, 1.0, FT_PROFILE_VARIOGRAM, &r), FT_E_EMPTY, "at least 3");
    assert_error_names(ft_profile_dim(z, 9, 0.0, FT_PROFILE_VARIOGRAM, &r), FT_E_INVALID, "spacing");
    z[4] = NAN;
    assert_error_names(ft_profile_dim(z, 9, 1.0, FT_PROFILE_VARIOGRAM, &r), FT_E_NUMERIC, "elevation 4");

    ft_grid *g = ft_grid_create(5, 3);
    g->gt[1] = 30.0;
    g->gt[5] = -30.0;
    for (size_t i = 0; i < 15; i++)
        g->z[i] = (float)i;
    double *p = NULL, step = 0.0;
    size_t n = 0;
    assert_int_equal(ft_profile_from_grid_row(g, 1, &p, &n, &step), FT_OK);
    assert_int_equal(n, 5);
    assert_near(p[0], 5.0, 0.0);
    assert_near(step, 30.0, 0.0);
    free(p);
    /* a transect along the centres of row 1: the same values */
    assert_int_equal(ft_profile_transect(g, 15.0, -45.0, 135.0, -45.0, &p, &n, &step), FT_OK);
    assert_int_equal(n, 5);
    assert_near(p[4], 9.0, 1e-9);
    free(p);
    assert_error_names(ft_profile_transect(g, 0.0, -45.0, 135.0, -45.0, &p, &n, &step), FT_E_INVALID,
                       "outside the grid");
    assert_error_names(ft_profile_from_grid_row(g, 3, &p, &n, &step), FT_E_INVALID, "row 3");
    ft_grid_ensure_mask(g);
    g->mask[7] = 0;
    assert_error_names(ft_profile_from_grid_row(g, 1, &p, &n, &step), FT_E_NUMERIC, "column 2 is nodata");
    assert_error_names(ft_profile_transect(g, 15.0, -45.0, 135.0, -45.0, &p, &n, &step), FT_E_NUMERIC, "nodata");
    ft_grid_free(g);

    /* 3-D line: vertices at 0, 1, 3, 4 along x, z = 2 x: resampled at spacing 1 */
    const double x[] = {0, 1, 3, 4}, y[] = {0, 0, 0, 0}, zz[] = {0, 2, 6, 8};
    assert_int_equal(ft_profile_resample(x, y, zz, 4, 0.0, &p, &n, &step), FT_OK);
    assert_int_equal(n, 5);
    assert_near(step, 1.0, 0.0);
    for (size_t i = 0; i < n; i++)
        assert_near(p[i], 2.0 * (double)i, 1e-12);
    free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_by_hand_and_extraction),
        cmocka_unit_test(test_fbm_1024),
        cmocka_unit_test(test_fbm_4096),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
