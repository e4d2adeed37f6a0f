/* fracterra — unit tests of core/fit.c: OLS line fits and log-log fits, checked against hand values.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "fracterra/core.h"
#include "ft_test_assert.h"

static void test_exact_line(void **state)
{
    (void)state;
    const double x[] = {0, 1, 2, 3, 4, 5}, y[] = {1, 3, 5, 7, 9, 11};
    ft_fit f;
    assert_int_equal(ft_fit_line(x, y, 0, 5, &f), FT_OK);
    assert_near(f.slope, 2.0, 1e-14);
    assert_near(f.intercept, 1.0, 1e-14);
    assert_near(f.r2, 1.0, 1e-14);
    assert_near(f.stderr_slope, 0.0, 1e-14);
    assert_near(f.stderr_intercept, 0.0, 1e-14);
    assert_int_equal(f.n, 6);
    assert_int_equal(f.first, 0);
    assert_int_equal(f.last, 5);
}

/* x = 1..5, y = 2 4 5 4 5: xm = 3, ym = 4, Sxx = 10, Sxy = 6, Syy = 6 -> slope 0.6, intercept 2.2;
 * residuals -0.8 0.6 1.0 -0.6 -0.2 -> SSE = 2.4, r2 = 1 - 2.4/6 = 0.6, s2 = 2.4/3 = 0.8,
 * se(slope) = sqrt(0.8/10), se(intercept) = sqrt(0.8 (1/5 + 9/10)) = sqrt(0.88). */
static void test_noisy_hand_case(void **state)
{
    (void)state;
    const double x[] = {1, 2, 3, 4, 5}, y[] = {2, 4, 5, 4, 5};
    ft_fit f;
    assert_int_equal(ft_fit_line(x, y, 0, 4, &f), FT_OK);
    assert_near(f.slope, 0.6, 1e-14);
    assert_near(f.intercept, 2.2, 1e-14);
    assert_near(f.r2, 0.6, 1e-14);
    assert_near(f.stderr_slope, sqrt(0.08), 1e-14);
    assert_near(f.stderr_intercept, sqrt(0.88), 1e-14);
}

/* Only [first, last] is used: the outliers outside it must not matter. */
static void test_sub_range(void **state)
{
    (void)state;
    const double x[] = {0, 1, 2, 3, 4, 5, 6}, y[] = {100, -7, 2, 4, 6, 8, -50};
    ft_fit f;
    assert_int_equal(ft_fit_line(x, y, 2, 5, &f), FT_OK);
    assert_near(f.slope, 2.0, 1e-14);
    assert_near(f.intercept, -2.0, 1e-13);
    assert_int_equal(f.n, 4);
    assert_int_equal(f.first, 2);
    assert_int_equal(f.last, 5);
}

static void test_two_points_have_zero_stderr(void **state)
{
    (void)state;
    const double x[] = {1, 3}, y[] = {1, 2};
    ft_fit f;
    assert_int_equal(ft_fit_line(x, y, 0, 1, &f), FT_OK);
    assert_near(f.slope, 0.5, 1e-15);
    assert_near(f.intercept, 0.5, 1e-15);
    assert_near(f.r2, 1.0, 1e-15);
    assert_true(f.stderr_slope == 0.0 && f.stderr_intercept == 0.0);
}

static void test_far_from_origin(void **state)
{
    (void)state;
    double x[50], y[50];
    for (int i = 0; i < 50; i++) {
        x[i] = 1.0e8 + i;
        y[i] = 3.0 - 0.25 * i;
    }
    ft_fit f;
    assert_int_equal(ft_fit_line(x, y, 0, 49, &f), FT_OK);
    assert_near(f.slope, -0.25, 1e-9);
    assert_near(f.r2, 1.0, 1e-9);
}

static void test_errors(void **state)
{
    (void)state;
    const double x[] = {1, 1, 1}, y[] = {1, 2, 3};
    ft_fit f;
    assert_int_equal(ft_fit_line(x, y, 2, 1, &f), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "2"));
    assert_int_equal(ft_fit_line(x, y, 1, 1, &f), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "at least 2"));
    assert_int_equal(ft_fit_line(x, y, 0, 2, &f), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "equal"));
    const double xn[] = {1, 2, 3}, yn[] = {1, NAN, 3};
    assert_int_equal(ft_fit_line(xn, yn, 0, 2, &f), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "y[1]"));
    const double xi[] = {1, 2, INFINITY};
    assert_int_equal(ft_fit_line(xi, y, 0, 2, &f), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "x[2]"));
    assert_int_equal(ft_fit_line(NULL, y, 0, 2, &f), FT_E_INVALID);
    assert_int_equal(ft_fit_line(xn, y, 0, 2, NULL), FT_E_INVALID);
}

/* value = 1000 scale^-1.5: log10 value = 3 - 1.5 log10 scale exactly. */
static void test_loglog_power_law(void **state)
{
    (void)state;
    double s[6], v[6];
    for (int i = 0; i < 6; i++) {
        s[i] = pow(2.0, i);
        v[i] = 1000.0 * pow(s[i], -1.5);
    }
    ft_fit f;
    assert_int_equal(ft_fit_loglog(s, v, 0, 5, &f), FT_OK);
    assert_near(f.slope, -1.5, 1e-13);
    assert_near(f.intercept, 3.0, 1e-13);
    assert_near(f.r2, 1.0, 1e-13);
    assert_near(f.stderr_slope, 0.0, 1e-12);
    assert_int_equal(ft_fit_loglog(s, v, 1, 4, &f), FT_OK);
    assert_near(f.slope, -1.5, 1e-13);
    assert_int_equal(f.n, 4);
}

static void test_loglog_rejects_non_positive(void **state)
{
    (void)state;
    const double s[] = {1, 2, 4, 8}, v[] = {8, 4, 0, 1};
    ft_fit f;
    assert_int_equal(ft_fit_loglog(s, v, 0, 3, &f), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "value[2]"));
    assert_non_null(strstr(ft_last_error(), "= 0"));
    /* the same point left out of the range is fine */
    assert_int_equal(ft_fit_loglog(s, v, 0, 1, &f), FT_OK);
    const double sn[] = {1, -2, 4, 8};
    assert_int_equal(ft_fit_loglog(sn, s, 0, 3, &f), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "scale[1] = -2"));
    const double same[] = {5, 5, 5};
    assert_int_equal(ft_fit_loglog(same, s, 0, 2, &f), FT_E_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_line),
        cmocka_unit_test(test_noisy_hand_case),
        cmocka_unit_test(test_sub_range),
        cmocka_unit_test(test_two_points_have_zero_stderr),
        cmocka_unit_test(test_far_from_origin),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_loglog_power_law),
        cmocka_unit_test(test_loglog_rejects_non_positive),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
