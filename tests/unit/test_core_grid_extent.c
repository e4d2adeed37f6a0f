/* fracterra — tests/unit/test_core_grid_extent.c: ft_grid_shape_for_extent, the grid of a cell size over an
 * extent (as given) or over the bounding box of points (snapped outward, the box's right and bottom edges
 * strictly inside), worked by hand.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/core.h"

static void expect_shape(double x0, double y0, double x1, double y1, double cell, int snap, size_t nx, size_t ny,
                         double left, double top)
{
    size_t gx = 0, gy = 0;
    double gt[6];
    assert_int_equal(ft_grid_shape_for_extent(x0, y0, x1, y1, cell, snap, &gx, &gy, gt), FT_OK);
    assert_int_equal(gx, nx);
    assert_int_equal(gy, ny);
    const double want[6] = {left, cell, 0.0, top, 0.0, -cell};
    for (int i = 0; i < 6; i++)
        assert_true(gt[i] == want[i]);
}

static void test_extent_as_given(void **state)
{
    (void)state;
    expect_shape(0, 0, 100, 50, 10, 0, 10, 5, 0, 50);
    expect_shape(0, 0, 95, 50, 10, 0, 10, 5, 0, 50);             /* the last column reaches past 95 */
    expect_shape(-7.5, 2, -7.5, 2, 2.5, 0, 1, 1, -7.5, 2);       /* a point: one cell */
    expect_shape(1000, 2000, 1003, 2001, 0.1, 0, 30, 10, 1000, 2001); /* 3 / 0.1 rounds either side of 30 */
}

static void test_points_box_snapped(void **state)
{
    (void)state;
    /* x 3..42 -> 0..50, y 7..58 -> 0..60 */
    expect_shape(3, 7, 42, 58, 10, 1, 5, 6, 0, 60);
    /* on the multiples: the right edge 40 moves out to 50, the bottom edge 10 down to 0 */
    expect_shape(20, 10, 40, 30, 10, 1, 3, 3, 20, 30);
    /* negative coordinates and one point */
    expect_shape(-15, -15, -15, -15, 10, 1, 1, 1, -20, -10);
}

static void test_refused(void **state)
{
    (void)state;
    size_t nx, ny;
    double gt[6];
    assert_int_equal(ft_grid_shape_for_extent(0, 0, 1, 1, 0.0, 0, &nx, &ny, gt), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "cell size"));
    assert_int_equal(ft_grid_shape_for_extent(0, 0, NAN, 1, 1.0, 0, &nx, &ny, gt), FT_E_INVALID);
    assert_int_equal(ft_grid_shape_for_extent(5, 0, 1, 1, 1.0, 0, &nx, &ny, gt), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "xmin <= xmax"));
    assert_int_equal(ft_grid_shape_for_extent(0, 0, 1e300, 1, 1e-10, 0, &nx, &ny, gt), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "per side"));
    assert_int_equal(ft_grid_shape_for_extent(0, 0, 1, 1, 1.0, 0, NULL, &ny, gt), FT_E_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_extent_as_given),
        cmocka_unit_test(test_points_box_snapped),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
