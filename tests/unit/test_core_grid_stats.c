/* fracterra — tests/unit/test_core_grid_stats.c: ft_grid_compute_stats on cells worked by hand: nodata and
 * non-finite cells left out, the population sd, a high flat grid's sd exact, no valid cell.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "fracterra/core.h"

static void test_hand_values(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(3, 2);
    assert_non_null(g);
    const float z[6] = {2, 4, 4, 4, 5, 999};
    for (int i = 0; i < 6; i++)
        g->z[i] = z[i];
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    g->mask[5] = 0; /* the 999 is nodata */
    ft_grid_stats s;
    assert_int_equal(ft_grid_compute_stats(g, &s), FT_OK);
    /* 2 4 4 4 5: mean 19/5 = 3.8, deviations -1.8 .2 .2 .2 1.2, squares sum 4.8, sd sqrt(0.96) */
    assert_int_equal(s.n, 5);
    assert_true(fabs(s.mean - 3.8) < 1e-12);
    assert_true(fabs(s.sd - sqrt(0.96)) < 1e-12);
    assert_true(s.min == 2.0 && s.max == 5.0);
    g->z[0] = NAN; /* a non-finite valid cell is left out too */
    assert_int_equal(ft_grid_compute_stats(g, &s), FT_OK);
    assert_int_equal(s.n, 4);
    assert_true(fabs(s.mean - 4.25) < 1e-12);
    ft_grid_free(g);
}

static void test_high_flat_and_empty(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(1000, 1000);
    assert_non_null(g);
    for (size_t i = 0; i < 1000000; i++)
        g->z[i] = 8848.0f + (i % 2 ? 0.5f : -0.5f); /* sd exactly 0.5 */
    ft_grid_stats s;
    assert_int_equal(ft_grid_compute_stats(g, &s), FT_OK);
    assert_true(fabs(s.sd - 0.5) < 1e-9);
    assert_true(fabs(s.mean - 8848.0) < 1e-9);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t i = 0; i < 1000000; i++)
        g->mask[i] = 0;
    assert_int_equal(ft_grid_compute_stats(g, &s), FT_OK);
    assert_int_equal(s.n, 0);
    assert_true(isnan(s.mean) && isnan(s.sd) && isnan(s.min) && isnan(s.max));
    assert_int_equal(ft_grid_compute_stats(NULL, &s), FT_E_INVALID);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hand_values),
        cmocka_unit_test(test_high_flat_and_empty),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
