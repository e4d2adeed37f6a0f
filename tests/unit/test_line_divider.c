/* fracterra — unit tests of src/line/divider.c, equipaced.c and hybrid_walk.c on walks that can be checked
 * by hand: a straight segment, a unit square ring, an L-shaped chain, rulers longer than the chain.
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

#include "fracterra/line.h"
#include "line/line_dim_internal.h"
#include "ft_test_assert.h"

static ft_chain *chain_of(const double *xy, size_t n, int closed)
{
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, n, 2, closed);
    assert_non_null(c);
    return c;
}

/* Length 10, ruler 3: whole steps end at x = 3, 6, 9; the last fraction is 1/3; length 3 x 3 + 1 = 10.
 * Same from the end, and with intermediate vertices that do not fall on divider points. */
static void test_straight_segment_ruler_3(void **state)
{
    (void)state;
    const double two[] = {0, 0, 10, 0};
    const double five[] = {0, 0, 2.5, 0, 5, 0, 7.5, 0, 10, 0};
    ft_chain *a = chain_of(two, 2, 0), *b = chain_of(five, 5, 0);
    for (int from_end = 0; from_end < 2; from_end++) {
        const ft_chain *cs[] = {a, b};
        for (int k = 0; k < 2; k++) {
            double len = 0;
            size_t steps = 99;
            assert_int_equal(ft_line_divider_walk(cs[k], 3.0, from_end, &len, &steps), FT_OK);
            assert_int_equal(steps, 3);
            assert_near(len, 10.0, 1e-12);
            assert_near(len / 3.0 - (double)steps, 1.0 / 3.0, 1e-12); /* the fractional last step */
        }
    }
    ft_chain_free(a);
    ft_chain_free(b);
}

/* A unit square ring (stored without the closing vertex) with ruler 1: four whole steps, back on vertex
 * 0, no fraction: length 4. */
static void test_unit_square_ring(void **state)
{
    (void)state;
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    ft_chain *c = chain_of(sq, 4, 1);
    double len = 0;
    size_t steps = 0;
    assert_int_equal(ft_line_divider_walk(c, 1.0, 0, &len, &steps), FT_OK);
    assert_int_equal(steps, 4);
    assert_near(len, 4.0, 1e-12);
    /* ruler 0.5: eight whole steps along the sides, back on vertex 0. */
    assert_int_equal(ft_line_divider_walk(c, 0.5, 0, &len, &steps), FT_OK);
    assert_int_equal(steps, 8);
    assert_near(len, 4.0, 1e-12);
    /* from_end is ignored for rings */
    assert_int_equal(ft_line_divider_walk(c, 1.0, 1, &len, &steps), FT_OK);
    assert_near(len, 4.0, 1e-12);
    ft_chain_free(c);
}

/* (0,0) -> (3,0) -> (3,4), ruler 4: from the start the circle |P| = 4 cuts the second side at y = sqrt(7),
 * then the rest 4 - sqrt(7): length 8 - sqrt(7). From the end: (3,4) -> (3,0) is exactly 4, then 3 left:
 * length 7. Ruler 5: one step to (3,4) exactly from either end. */
static void test_l_chain_circle_intersection_and_both_ends(void **state)
{
    (void)state;
    const double l[] = {0, 0, 3, 0, 3, 4};
    ft_chain *c = chain_of(l, 3, 0);
    double len = 0, steps = 0;
    size_t st = 0;
    assert_int_equal(ft_line_divider_walk(c, 4.0, 0, &len, &st), FT_OK);
    assert_int_equal(st, 1);
    assert_near(len, 8.0 - sqrt(7.0), 1e-12);
    assert_int_equal(ft_line_divider_walk(c, 4.0, 1, &len, &st), FT_OK);
    assert_int_equal(st, 1);
    assert_near(len, 7.0, 1e-12);
    ft_line_divider_length(c, NULL, 4.0, 1, &len, &steps);
    assert_near(len, 0.5 * (8.0 - sqrt(7.0) + 7.0), 1e-12);
    assert_near(steps, 1.0, 0);
    ft_line_divider_length(c, NULL, 4.0, 0, &len, &steps);
    assert_near(len, 8.0 - sqrt(7.0), 1e-12);
    for (int e = 0; e < 2; e++) {
        assert_int_equal(ft_line_divider_walk(c, 5.0, e, &len, &st), FT_OK);
        assert_int_equal(st, 1);
        assert_near(len, 5.0, 1e-12);
    }
    ft_chain_free(c);
}

/* A ruler longer than the chain takes no whole step: the length is the chord from start to end (0 for a
 * ring, which ends where it starts). */
static void test_ruler_longer_than_chain(void **state)
{
    (void)state;
    const double l[] = {0, 0, 1, 0, 1, 1};
    ft_chain *c = chain_of(l, 3, 0), *r = chain_of(l, 3, 1);
    double len = -1;
    size_t st = 99;
    assert_int_equal(ft_line_divider_walk(c, 5.0, 0, &len, &st), FT_OK);
    assert_int_equal(st, 0);
    assert_near(len, sqrt(2.0), 1e-15);
    assert_int_equal(ft_line_divider_walk(r, 5.0, 0, &len, &st), FT_OK);
    assert_int_equal(st, 0);
    assert_near(len, 0.0, 0);
    ft_chain_free(c);
    ft_chain_free(r);
}

static void test_walk_bad_input(void **state)
{
    (void)state;
    const double l[] = {0, 0, 1, 0};
    ft_chain *c = chain_of(l, 2, 0), *one = chain_of(l, 1, 0);
    double len;
    size_t st;
    assert_error_names(ft_line_divider_walk(c, 0.0, 0, &len, &st), FT_E_INVALID, "ruler");
    assert_error_names(ft_line_divider_walk(c, -2.0, 0, &len, &st), FT_E_INVALID, "-2");
    assert_error_names(ft_line_divider_walk(c, NAN, 0, &len, &st), FT_E_INVALID, "nan");
    assert_error_names(ft_line_divider_walk(one, 1.0, 0, &len, &st), FT_E_INVALID, "1 vertices");
    assert_error_names(ft_line_divider_walk(NULL, 1.0, 0, &len, &st), FT_E_INVALID, "NULL");
    c->y[1] = NAN;
    assert_error_names(ft_line_divider_walk(c, 1.0, 0, &len, &st), FT_E_NUMERIC, "vertex 1");
    ft_chain_free(c);
    ft_chain_free(one);
}

/* Equipaced: samples every s along the arc. Straight length 10, s = 3: the polygon is the line, length 10,
 * three whole spacings. L-shaped (0,0) (3,0) (3,4), s = 2: samples (0,0) (2,0) (3,1) (3,3), end (3,4):
 * 2 + sqrt(2) + 2 + 1. A unit square ring with s = 1.5: samples at arc 0, 1.5, 3: (0,0) (1,0.5) (0,1),
 * closing to (0,0): 2 sqrt(1.25) + 1. */
static void test_equipaced_hand_cases(void **state)
{
    (void)state;
    const double line[] = {0, 0, 10, 0}, l[] = {0, 0, 3, 0, 3, 4}, sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    ft_chain *a = chain_of(line, 2, 0), *b = chain_of(l, 3, 0), *c = chain_of(sq, 4, 1);
    double len, steps;
    ft_line_equipaced_length(a, NULL, 3.0, &len, &steps);
    assert_near(len, 10.0, 1e-12);
    assert_near(steps, 3.0, 0);
    ft_line_equipaced_length(b, NULL, 2.0, &len, &steps);
    assert_near(len, 5.0 + sqrt(2.0), 1e-12);
    assert_near(steps, 3.0, 0);
    ft_line_equipaced_length(c, NULL, 1.5, &len, &steps);
    assert_near(len, 2.0 * sqrt(1.25) + 1.0, 1e-12);
    assert_near(steps, 2.0, 0);
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(c);
}

/* Hybrid walk: steps end on vertices, at the first one at least a ruler away, counted by their length.
 * (0,0) (1,0) (2,0) (2,2), ruler 1.5: (0,0) -> (2,0) (2) -> (2,2) (2): 4, from either end. Ruler 2.5:
 * (0,0) -> (2,2): 2 sqrt(2), and from the end (2,2) -> (0,0) likewise. */
static void test_hybrid_hand_cases(void **state)
{
    (void)state;
    const double p[] = {0, 0, 1, 0, 2, 0, 2, 2};
    ft_chain *c = chain_of(p, 4, 0);
    double len, steps;
    ft_line_hybrid_length(c, NULL, 1.5, 1, &len, &steps);
    assert_near(len, 4.0, 1e-12);
    assert_near(steps, 4.0 / 1.5, 1e-12);
    ft_line_hybrid_length(c, NULL, 2.5, 1, &len, &steps);
    assert_near(len, 2.0 * sqrt(2.0), 1e-12);
    /* ruler 2.1 from the start: (0,0): (2,2) is the first at >= 2.1 -> 2 sqrt(2); from the end: (2,2):
     * (1,0) is at sqrt(5) >= 2.1 -> sqrt(5), then (0,0) at 1 < 2.1 is the last fraction: mean of
     * 2 sqrt(2) and sqrt(5) + 1. */
    ft_line_hybrid_length(c, NULL, 2.1, 1, &len, &steps);
    assert_near(len, 0.5 * (2.0 * sqrt(2.0) + sqrt(5.0) + 1.0), 1e-12);
    ft_line_hybrid_length(c, NULL, 2.1, 0, &len, &steps);
    assert_near(len, 2.0 * sqrt(2.0), 1e-12);
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_straight_segment_ruler_3),
        cmocka_unit_test(test_unit_square_ring),
        cmocka_unit_test(test_l_chain_circle_intersection_and_both_ends),
        cmocka_unit_test(test_ruler_longer_than_chain),
        cmocka_unit_test(test_walk_bad_input),
        cmocka_unit_test(test_equipaced_hand_cases),
        cmocka_unit_test(test_hybrid_hand_cases),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
