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

static void expect_msg(int rc, int code, const char *msg)
{
    assert_int_equal(rc, code);
    if (strstr(ft_last_error(), msg) == NULL)
        print_error("message '%s' lacks '%s'\n", ft_last_error(), msg);
    assert_non_null(strstr(ft_last_error(), msg));
}

/* A ring of 60 vertices whose radius wanders (a deterministic wiggle, uneven spacing), scale ~100. */
static ft_chain *wiggly_ring(size_t off)
{
    enum { N = 60 };
    double xy[2 * N];
    for (size_t j = 0; j < N; j++) {
        size_t i = (j + off) % N;
        double t = 2.0 * M_PI * (i + 0.3 * sin(1.7 * i)) / N, r = 100.0 * (1.0 + 0.25 * sin(7.0 * t) + 0.1 * cos(13.0 * t));
        xy[2 * j] = r * cos(t);
        xy[2 * j + 1] = r * sin(t);
    }
    return chain_of(xy, N, 1);
}

static ft_dim_result *ring_dim(const ft_chain *c, int starts, int only_start)
{
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = 15.0;
    o.max_scale = 60.0;
    o.nscales = 8;
    o.fit_whole_range = 1;
    o.starts = starts;
    o.only_start = only_start;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(&c, 1, FT_LINE_DIVIDER, &o, &r), FT_OK);
    return r;
}

/* starts = N: walk k alone is the one walk of the ring rotated to start at the first vertex at or after k/N
 * of its length (found here by summing the sides), and the lengths of the mean are the mean of the N walks. */
static void test_ring_starts(void **state)
{
    (void)state;
    enum { NS = 5 };
    ft_chain *c = wiggly_ring(0);
    ft_dim_result *one = ring_dim(c, 1, -1), *mean = ring_dim(c, NS, -1), *each[NS];
    ft_dim_result *first = ring_dim(c, NS, 0);
    for (size_t i = 0; i < one->table->n; i++) /* start 0 is vertex 0: the single walk, bit for bit */
        assert_true(first->table->rows[i].value == one->table->rows[i].value);
    double side[60], total = 0.0;
    for (size_t i = 0; i < 60; i++) {
        size_t j = (i + 1) % 60;
        side[i] = hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
        total += side[i];
    }
    for (int k = 0; k < NS; k++) {
        size_t v = 0;
        for (double s = 0.0; s < total * k / NS; s += side[v++])
            ;
        ft_chain *rot = wiggly_ring(v);
        ft_dim_result *expect = ring_dim(rot, 1, -1);
        each[k] = ring_dim(c, NS, k);
        assert_int_equal(each[k]->table->n, expect->table->n);
        for (size_t i = 0; i < expect->table->n; i++)
            assert_near(each[k]->table->rows[i].value, expect->table->rows[i].value, 1e-9);
        ft_dim_result_free(expect);
        ft_chain_free(rot);
    }
    double spread = 0.0;
    for (size_t i = 0; i < mean->table->n; i++) {
        double sum = 0.0;
        for (int k = 0; k < NS; k++)
            sum += each[k]->table->rows[i].value;
        assert_near(mean->table->rows[i].value, sum / NS, 1e-9);
    }
    for (int k = 1; k < NS; k++) /* the start does move D on this ring */
        spread = fmax(spread, fabs(each[k]->D - each[0]->D));
    assert_true(spread > 1e-3);
    for (int k = 0; k < NS; k++)
        ft_dim_result_free(each[k]);
    ft_dim_result_free(one);
    ft_dim_result_free(mean);
    ft_dim_result_free(first);

    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    ft_dim_result *r = NULL;
    c->closed = 0; /* an open chain: the starts change nothing, and the result says so */
    o.starts = 4;
    assert_int_equal(ft_line_dim((const ft_chain *const *)&c, 1, FT_LINE_DIVIDER, &o, &r), FT_OK);
    int said = 0;
    for (size_t w = 0; w < r->nwarnings; w++)
        said += strstr(r->warnings[w], "none of the chains is a ring") != NULL;
    assert_int_equal(said, 1);
    ft_dim_result_free(r);
    r = NULL;
    c->closed = 1;
    o.starts = 0;
    expect_msg(ft_line_dim((const ft_chain *const *)&c, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID,
               "starts must be in [1, 1000], got 0");
    o.starts = 3;
    expect_msg(ft_line_dim((const ft_chain *const *)&c, 1, FT_LINE_BOX, &o, &r), FT_E_INVALID,
               "starts (3) applies to the divider only, not to the box");
    o.only_start = 3;
    expect_msg(ft_line_dim((const ft_chain *const *)&c, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID,
               "only_start must be -1 (all) or in [0, 3), got 3");
    assert_null(r);
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
        cmocka_unit_test(test_ring_starts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
