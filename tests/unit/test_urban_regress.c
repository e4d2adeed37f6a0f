/* fracterra — unit tests of src/urban/regress.c: the regression of ln(area) on D of Zhang, Yu & Fan (2008,
 * Eq. 5) on their Table 2, a hand-checkable exact line, and bad input.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "fracterra/urban.h"

#include "test_urban.h"

/* Table 2 (years 1959, 1980, 1989, 1997). By hand, x = D, y = ln(area):
 *   y = 11.66515, 12.15718, 12.56173, 12.93147 (the paper prints 11.6651, 12.1572, 12.5617, 12.9315);
 *   mean x = 5.6622 / 4 = 1.41555, mean y = 49.31552 / 4 = 12.32888;
 *   centred x = -0.05415, -0.04335, 0.02585, 0.07165; centred y = -0.66373, -0.17170, 0.23285, 0.60259;
 *   Sxx = 0.0029322 + 0.0018792 + 0.0006682 + 0.0051337 = 0.0106134;
 *   Syy = 0.440540 + 0.029482 + 0.054218 + 0.363113 = 0.887353;
 *   Sxy = 0.035941 + 0.007443 + 0.006019 + 0.043175 = 0.092579;
 *   r = Sxy / sqrt(Sxx Syy) = 0.092579 / sqrt(0.0094178) = 0.092579 / 0.097045 = 0.9540;
 *   slope = Sxy / Sxx = 8.7229, intercept = 12.32888 - 8.7229 x 1.41555 = -0.0188;
 *   s² = (Syy - slope Sxy) / 2 = (0.887353 - 0.807553) / 2 = 0.039900, se(slope) = sqrt(s² / Sxx) = 1.939;
 *   se(r) = sqrt((1 - 0.9540²) / 2) = 0.2121, t = r / se(r) = 4.50 on 2 degrees of freedom. */
static void test_paper_table_2(void **state)
{
    (void)state;
    const double D[] = {1.3614, 1.3722, 1.4414, 1.4872}, area[] = {116442, 190456, 285423, 413110};
    ft_urban_regression r;
    assert_int_equal(ft_urban_regress(D, area, 4, 1, &r), FT_OK);
    print_message("  ln(area) = %.4f + %.4f D, r = %.4f (se %.4f), se slope %.4f, se intercept %.4f, t = %.3f, "
                  "p = %.4f\n", r.intercept, r.slope, r.r, r.stderr_r, r.stderr_slope, r.stderr_intercept, r.t,
                  r.p_value);
    assert_near(r.r, 0.954, 0.0005);
    assert_int_equal(r.n, 4);
    assert_int_equal(r.log_y, 1);
    assert_near(r.slope, 8.7229, 1e-3);
    assert_near(r.intercept, -0.0188, 1e-3);
    assert_near(r.r2, r.r * r.r, 1e-15);
    assert_near(r.stderr_slope, 1.939, 1e-3);
    assert_near(r.stderr_intercept, 2.7465, 1e-3);
    assert_near(r.stderr_r, 0.2121, 1e-4);
    assert_near(r.t, r.slope / r.stderr_slope, 1e-9);
    /* two-sided p of t = 4.4989 with 2 df: 1 - t / sqrt(2 + t²) */
    assert_near(r.p_value, 1.0 - r.t / sqrt(2.0 + r.t * r.t), 1e-9);
}

/* An exact line y = 3 - 2x: r = -1, zero standard errors; without the log. */
static void test_exact_line(void **state)
{
    (void)state;
    const double x[] = {0, 1, 2, 3, 4}, y[] = {3, 1, -1, -3, -5};
    ft_urban_regression r;
    assert_int_equal(ft_urban_regress(x, y, 5, 0, &r), FT_OK);
    assert_near(r.slope, -2.0, 1e-12);
    assert_near(r.intercept, 3.0, 1e-12);
    assert_near(r.r, -1.0, 1e-12);
    assert_near(r.stderr_slope, 0.0, 1e-7);
    assert_near(r.stderr_r, 0.0, 1e-7);
    assert_near(r.p_value, 0.0, 1e-12);
}

static void test_bad_input(void **state)
{
    (void)state;
    const double x[] = {1, 2, 3}, y[] = {1, 2, -1}, same[] = {2, 2, 2}, nan_y[] = {1, NAN, 2};
    ft_urban_regression r;
    assert_error_names(ft_urban_regress(x, y, 2, 0, &r), FT_E_INVALID, "at least 3 rows");
    assert_error_names(ft_urban_regress(x, y, 3, 1, &r), FT_E_INVALID, "row 3: y = -1 must be > 0");
    assert_error_names(ft_urban_regress(x, nan_y, 3, 0, &r), FT_E_NUMERIC, "row 2: y = nan");
    assert_error_names(ft_urban_regress(same, y, 3, 0, &r), FT_E_INVALID,
                       "regression: line fit: all 3 x values are equal (2)");
    assert_error_names(ft_urban_regress(x, same, 3, 1, &r), FT_E_NUMERIC, "every ln y is the same");
    assert_error_names(ft_urban_regress(NULL, y, 3, 0, &r), FT_E_INVALID, "NULL x");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_paper_table_2),
        cmocka_unit_test(test_exact_line),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
