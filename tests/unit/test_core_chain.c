/* fracterra — unit tests of core/chain.c: creation, strided copy, growth, length, area, checks.
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

static const double square_ccw[] = {0, 0, 1, 0, 1, 1, 0, 1};

static void test_create_empty(void **state)
{
    (void)state;
    ft_chain *c = ft_chain_create(0, 1);
    assert_non_null(c);
    assert_int_equal(c->n, 0);
    assert_int_equal(c->closed, 1);
    assert_int_equal(ft_chain_segments(c), 0);
    assert_true(ft_chain_length(c) == 0.0);
    assert_int_equal(ft_chain_bbox(c, NULL, NULL, NULL, NULL), FT_E_EMPTY);
    ft_chain_free(c);
    ft_chain_free(NULL);
}

static void test_from_arrays_strided(void **state)
{
    (void)state;
    ft_chain *c = ft_chain_from_arrays(square_ccw, square_ccw + 1, 4, 2, 1);
    assert_non_null(c);
    assert_int_equal(c->n, 4);
    assert_true(c->x[2] == 1.0 && c->y[2] == 1.0);
    assert_true(c->x[3] == 0.0 && c->y[3] == 1.0);
    ft_chain_free(c);

    const double xs[] = {5, 6, 7}, ys[] = {-1, -2, -3};
    c = ft_chain_from_arrays(xs, ys, 3, 1, 0);
    assert_non_null(c);
    assert_true(c->x[1] == 6.0 && c->y[2] == -3.0);
    assert_int_equal(c->closed, 0);
    ft_chain_free(c);

    assert_null(ft_chain_from_arrays(xs, ys, 3, 0, 0));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    assert_null(ft_chain_from_arrays(NULL, ys, 3, 1, 0));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    assert_null(ft_chain_from_arrays(xs, ys, 3, SIZE_MAX, 0));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
}

static void test_push_grows_and_copy_is_deep(void **state)
{
    (void)state;
    ft_chain *c = ft_chain_create(1, 0);
    assert_non_null(c);
    for (int i = 0; i < 1000; i++)
        assert_int_equal(ft_chain_push(c, i, 2.0 * i), FT_OK);
    assert_int_equal(c->n, 1000);
    assert_true(c->cap >= 1000);
    assert_true(c->x[999] == 999.0 && c->y[999] == 1998.0);
    ft_chain *d = ft_chain_copy(c);
    assert_non_null(d);
    c->x[0] = 42.0;
    assert_true(d->x[0] == 0.0);
    assert_int_equal(d->n, 1000);
    assert_int_equal(ft_chain_reserve(d, 10), FT_OK); /* never shrinks */
    assert_int_equal(d->n, 1000);
    ft_chain_free(c);
    ft_chain_free(d);
    assert_int_equal(ft_chain_push(NULL, 0, 0), FT_E_INVALID);
}

static void test_reverse(void **state)
{
    (void)state;
    const double xs[] = {1, 2, 3, 4, 5}, ys[] = {10, 20, 30, 40, 50};
    ft_chain *c = ft_chain_from_arrays(xs, ys, 5, 1, 0);
    ft_chain_reverse(c);
    for (int i = 0; i < 5; i++)
        assert_true(c->x[i] == xs[4 - i] && c->y[i] == ys[4 - i]);
    c->n = 4;
    ft_chain_reverse(c);
    assert_true(c->x[0] == 2.0 && c->x[3] == 5.0);
    ft_chain_free(c);
}

static void test_length_and_segments(void **state)
{
    (void)state;
    ft_chain *ring = ft_chain_from_arrays(square_ccw, square_ccw + 1, 4, 2, 1);
    assert_int_equal(ft_chain_segments(ring), 4);
    assert_near(ft_chain_length(ring), 4.0, 1e-15); /* includes the closing segment */
    ring->closed = 0;
    assert_int_equal(ft_chain_segments(ring), 3);
    assert_near(ft_chain_length(ring), 3.0, 1e-15);
    ft_chain_free(ring);

    const double xs[] = {0, 3}, ys[] = {0, 4};
    ft_chain *seg = ft_chain_from_arrays(xs, ys, 2, 1, 0);
    assert_near(ft_chain_length(seg), 5.0, 1e-15);
    assert_int_equal(ft_chain_segments(seg), 1);
    seg->n = 1;
    assert_int_equal(ft_chain_segments(seg), 0);
    ft_chain_free(seg);
}

static void test_signed_area(void **state)
{
    (void)state;
    ft_chain *c = ft_chain_from_arrays(square_ccw, square_ccw + 1, 4, 2, 1);
    assert_near(ft_chain_signed_area(c), 1.0, 1e-15);
    ft_chain_reverse(c);
    assert_near(ft_chain_signed_area(c), -1.0, 1e-15);
    c->closed = 0;
    assert_true(ft_chain_signed_area(c) == 0.0);
    ft_chain_free(c);

    /* a 2 x 3 rectangle far from the origin (projected coordinates): area 6 exactly */
    const double xs[] = {500000, 500002, 500002, 500000}, ys[] = {6000000, 6000000, 6000003, 6000003};
    c = ft_chain_from_arrays(xs, ys, 4, 1, 1);
    assert_near(ft_chain_signed_area(c), 6.0, 1e-9);
    ft_chain_free(c);

    /* triangle (0,0) (4,0) (0,3): area 6 */
    const double tx[] = {0, 4, 0}, ty[] = {0, 0, 3};
    c = ft_chain_from_arrays(tx, ty, 3, 1, 1);
    assert_near(ft_chain_signed_area(c), 6.0, 1e-15);
    ft_chain_free(c);
}

static void test_bbox(void **state)
{
    (void)state;
    const double xs[] = {3, -1, 7, 2}, ys[] = {5, 9, -4, 0};
    ft_chain *c = ft_chain_from_arrays(xs, ys, 4, 1, 0);
    double a, b, cc, d;
    assert_int_equal(ft_chain_bbox(c, &a, &b, &cc, &d), FT_OK);
    assert_true(a == -1.0 && b == -4.0 && cc == 7.0 && d == 9.0);
    ft_chain_free(c);
}

static void test_checks_name_the_vertex(void **state)
{
    (void)state;
    const double xs[] = {0, 1, 2, 3}, ys[] = {0, 1, NAN, 3};
    ft_chain *c = ft_chain_from_arrays(xs, ys, 4, 1, 0);
    assert_int_equal(ft_chain_check_finite(c), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "vertex 2"));
    c->y[2] = 2.0;
    c->x[3] = INFINITY;
    assert_int_equal(ft_chain_check_finite(c), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "vertex 3"));
    c->x[3] = 3.0;
    assert_int_equal(ft_chain_check_finite(c), FT_OK);

    c->n = 1;
    assert_int_equal(ft_chain_check_min_vertices(c, 2), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "1 vertices"));
    assert_non_null(strstr(ft_last_error(), "2"));
    assert_int_equal(ft_chain_check_min_vertices(c, 1), FT_OK);
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_create_empty),
        cmocka_unit_test(test_from_arrays_strided),
        cmocka_unit_test(test_push_grows_and_copy_is_deep),
        cmocka_unit_test(test_reverse),
        cmocka_unit_test(test_length_and_segments),
        cmocka_unit_test(test_signed_area),
        cmocka_unit_test(test_bbox),
        cmocka_unit_test(test_checks_name_the_vertex),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
