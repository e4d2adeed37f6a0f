/* fracterra — tests/unit/test_line_simplify_target.c: ft_line_simplify_tolerance_for, the Douglas-Peucker
 * tolerance that leaves a layer at most N vertices: at most N at the tolerance found, more than N just
 * below it, checked through the chain function ft_line_simplify.
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
#include "fracterra/line.h"

/* An open chain along x with 9 teeth: vertex 2k+1 at height h[k] above the x axis, the others on it. */
static ft_layer *zigzag(void)
{
    static const double h[9] = {1, 2, 4, 8, 16, 32, 64, 128, 256};
    ft_chain *c = ft_chain_create(19, 0);
    assert_non_null(c);
    for (size_t i = 0; i < 19; i++)
        assert_int_equal(ft_chain_push(c, 1000.0 * (double)i, i % 2 ? h[i / 2] : 0.0), FT_OK);
    ft_layer *l = ft_layer_create("zigzag", NULL);
    assert_non_null(l);
    assert_true(ft_layer_add_feature(l, 1, FT_GEOM_LINE, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, c, FT_ROLE_LINE, 0), FT_OK);
    return l;
}

/* Vertices of the zigzag simplified with tolerance tol, by the chain function (not the layer driver). */
static size_t simplified(const ft_layer *l, double tol)
{
    ft_chain *out = NULL;
    assert_int_equal(ft_line_simplify(l->parts[0].chain, tol, &out), FT_OK);
    size_t n = out->n;
    ft_chain_free(out);
    return n;
}

/* The contract: at most target vertices at the tolerance found, more than target just below it (the
 * bisection stops within 1e-12 of the diagonal, 2e-8 here; the teeth's thresholds are whole numbers). */
static void test_smallest_tolerance(void **state)
{
    (void)state;
    ft_layer *l = zigzag();
    for (size_t target = 3; target < 19; target += 3) {
        double tol = -1.0;
        size_t n = 0;
        assert_int_equal(ft_line_simplify_tolerance_for(l, target, 0, &tol, &n), FT_OK);
        assert_true(n <= target);
        assert_int_equal(simplified(l, tol), n);
        assert_true(simplified(l, tol - 1e-6) > target);
    }
    assert_int_equal(ft_layer_vertex_count(l), 19); /* the layer itself is not simplified */
    ft_layer_free(l);
}

static void test_reached_or_unreachable(void **state)
{
    (void)state;
    ft_layer *l = zigzag();
    double tol = -1.0;
    size_t n = 0;
    /* enough vertices already: tolerance 0 */
    assert_int_equal(ft_line_simplify_tolerance_for(l, 19, 0, &tol, &n), FT_OK);
    assert_true(tol == 0.0);
    assert_int_equal(n, 19);
    /* fewer than an open chain's two end points cannot be reached */
    assert_int_equal(ft_line_simplify_tolerance_for(l, 1, 0, &tol, &n), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "keeps at least 2"));
    assert_int_equal(ft_line_simplify_tolerance_for(NULL, 1, 0, &tol, &n), FT_E_INVALID);
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_smallest_tolerance),
        cmocka_unit_test(test_reached_or_unreachable),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
