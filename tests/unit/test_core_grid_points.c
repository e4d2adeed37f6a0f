/* fracterra — unit tests of core/grid.c and core/points.c.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fracterra/core.h"
#include "ft_test_assert.h"

static void test_grid_create_defaults(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(3, 2);
    assert_non_null(g);
    assert_int_equal(g->nx, 3);
    assert_int_equal(g->ny, 2);
    assert_null(g->mask);
    assert_null(g->crs_wkt);
    for (int i = 0; i < 6; i++)
        assert_true(g->z[i] == 0.0f);
    const double gt[6] = {0, 1, 0, 0, 0, 1};
    assert_memory_equal(g->gt, gt, sizeof gt);
    assert_int_equal(ft_grid_count_valid(g), 6);
    ft_grid_free(g);
    ft_grid_free(NULL);
}

static void test_grid_rejects_bad_sizes(void **state)
{
    (void)state;
    assert_null(ft_grid_create(0, 5));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "0 x 5"));
    assert_null(ft_grid_create(7, 0));
    assert_non_null(strstr(ft_last_error(), "7 x 0"));
    size_t big = SIZE_MAX / 2;
    assert_null(ft_grid_create(big, 3));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    char num[32];
    snprintf(num, sizeof num, "%zu", big);
    assert_non_null(strstr(ft_last_error(), num));
    assert_null(ft_grid_create((size_t)1 << 32, (size_t)1 << 31)); /* 2^63 cells * 4 bytes overflows */
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
}

static void test_grid_mask_and_minmax(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(2, 2);
    g->z[0] = 5.0f;
    g->z[1] = -3.0f;
    g->z[2] = 10.0f;
    g->z[3] = 1.0f;
    double lo, hi;
    assert_int_equal(ft_grid_minmax(g, &lo, &hi), FT_OK);
    assert_true(lo == -3.0 && hi == 10.0);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    assert_non_null(g->mask);
    assert_int_equal(ft_grid_count_valid(g), 4);
    g->mask[2] = 0; /* hides 10 */
    assert_int_equal(ft_grid_is_valid(g, 0, 1), 0);
    assert_int_equal(ft_grid_is_valid(g, 1, 1), 1);
    assert_int_equal(ft_grid_count_valid(g), 3);
    assert_int_equal(ft_grid_minmax(g, &lo, &hi), FT_OK);
    assert_true(lo == -3.0 && hi == 5.0);
    memset(g->mask, 0, 4);
    assert_int_equal(ft_grid_minmax(g, &lo, &hi), FT_E_EMPTY);
    ft_grid_free(g);
}

static void test_grid_mask_nonfinite(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(3, 1);
    g->z[0] = NAN;
    g->z[1] = 2.0f;
    g->z[2] = -INFINITY;
    assert_int_equal(ft_grid_mask_nonfinite(g), 2);
    assert_non_null(g->mask);
    assert_true(g->mask[0] == 0 && g->mask[1] == 1 && g->mask[2] == 0);
    assert_int_equal(ft_grid_mask_nonfinite(g), 0); /* already masked */
    double lo, hi;
    assert_int_equal(ft_grid_minmax(g, &lo, &hi), FT_OK);
    assert_true(lo == 2.0 && hi == 2.0);
    ft_grid_free(g);

    g = ft_grid_create(2, 2);
    assert_int_equal(ft_grid_mask_nonfinite(g), 0);
    assert_null(g->mask); /* no mask made when nothing needs masking */
    ft_grid_free(g);
}

static void test_grid_georeferencing(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(4, 3);
    const double gt[6] = {100.0, 10.0, 0.0, 500.0, 0.0, -10.0}; /* north-up, 10 m cells */
    memcpy(g->gt, gt, sizeof gt);
    double x, y;
    ft_grid_cell_center(g, 0, 0, &x, &y);
    assert_near(x, 105.0, 1e-12);
    assert_near(y, 495.0, 1e-12);
    ft_grid_cell_center(g, 3, 2, &x, &y);
    assert_near(x, 135.0, 1e-12);
    assert_near(y, 475.0, 1e-12);
    double x0, y0, x1, y1;
    ft_grid_extent(g, &x0, &y0, &x1, &y1);
    assert_near(x0, 100.0, 1e-12);
    assert_near(x1, 140.0, 1e-12);
    assert_near(y0, 470.0, 1e-12);
    assert_near(y1, 500.0, 1e-12);
    ft_grid_free(g);
}

static void test_grid_copy_is_deep(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(2, 3);
    g->z[5] = 7.5f;
    g->gt[0] = 3.0;
    g->has_nodata = 1;
    g->nodata_value = -9999.0;
    assert_int_equal(ft_grid_set_crs(g, "EPSG:5070"), FT_OK);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    g->mask[1] = 0;
    ft_grid *d = ft_grid_copy(g);
    assert_non_null(d);
    g->z[5] = 0.0f;
    g->mask[1] = 1;
    assert_int_equal(ft_grid_set_crs(g, NULL), FT_OK);
    assert_null(g->crs_wkt);
    assert_true(d->z[5] == 7.5f);
    assert_true(d->mask[1] == 0);
    assert_string_equal(d->crs_wkt, "EPSG:5070");
    assert_true(d->gt[0] == 3.0 && d->has_nodata == 1 && d->nodata_value == -9999.0);
    ft_grid_free(g);
    ft_grid_free(d);
}

static void test_points_push_weights_bbox(void **state)
{
    (void)state;
    ft_points *p = ft_points_create(0);
    assert_non_null(p);
    assert_int_equal(ft_points_bbox(p, NULL, NULL, NULL, NULL), FT_E_EMPTY);
    for (int i = 0; i < 100; i++)
        assert_int_equal(ft_points_push(p, i, -i, 0.5 * i), FT_OK);
    assert_int_equal(p->n, 100);
    assert_null(p->w);
    assert_int_equal(ft_points_ensure_weights(p), FT_OK);
    for (int i = 0; i < 100; i++)
        assert_true(p->w[i] == 1.0);
    p->w[3] = 0.25;
    for (int i = 100; i < 1000; i++)
        assert_int_equal(ft_points_push(p, i, -i, 0.5 * i), FT_OK);
    assert_true(p->w[999] == 1.0 && p->w[3] == 0.25);
    assert_true(p->z[999] == 499.5);
    double x0, y0, x1, y1;
    assert_int_equal(ft_points_bbox(p, &x0, &y0, &x1, &y1), FT_OK);
    assert_true(x0 == 0.0 && x1 == 999.0 && y0 == -999.0 && y1 == 0.0);
    ft_points_free(p);
    ft_points_free(NULL);
}

static void test_points_copy_is_deep(void **state)
{
    (void)state;
    ft_points *p = ft_points_create(4);
    ft_points_push(p, 1, 2, 3);
    ft_points_push(p, 4, 5, 6);
    ft_points_ensure_weights(p);
    p->w[1] = 2.0;
    ft_points_set_crs(p, "EPSG:4326");
    ft_points *d = ft_points_copy(p);
    assert_non_null(d);
    p->x[0] = -1.0;
    p->w[1] = 9.0;
    assert_int_equal(d->n, 2);
    assert_true(d->x[0] == 1.0 && d->z[1] == 6.0 && d->w[1] == 2.0);
    assert_string_equal(d->crs_wkt, "EPSG:4326");
    ft_points_free(p);
    ft_points_free(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid_create_defaults),
        cmocka_unit_test(test_grid_rejects_bad_sizes),
        cmocka_unit_test(test_grid_mask_and_minmax),
        cmocka_unit_test(test_grid_mask_nonfinite),
        cmocka_unit_test(test_grid_georeferencing),
        cmocka_unit_test(test_grid_copy_is_deep),
        cmocka_unit_test(test_points_push_weights_bbox),
        cmocka_unit_test(test_points_copy_is_deep),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
