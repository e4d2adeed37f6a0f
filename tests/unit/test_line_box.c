/* fracterra — unit tests of src/line/box_count.c: exact cell counts on hand cases. Cells are half-open,
 * [x0, x0 + r) x [y0, y0 + r): a point on a grid line belongs to the cell on its right (above).
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

/* Cells crossed by one chain given as xy pairs, side `size`, origin (ox, oy). */
static uint64_t count1(const double *xy, size_t n, int closed, double size, double ox, double oy)
{
    ft_chain *c = chain_of(xy, n, closed);
    const ft_chain *cs[] = {c};
    uint64_t k = 0;
    assert_int_equal(ft_line_box_count(cs, 1, size, ox, oy, &k), FT_OK);
    ft_chain_free(c);
    return k;
}

/* Along the grid line y = 0 from x = 0 to 3: the cells above it, columns 0..3 (the end point x = 3 is in
 * column 3). Off the grid corners, 0.5 .. 2.5: columns 0..2. Along x = 1: column 1, rows 0..2. */
static void test_segment_on_grid_line(void **state)
{
    (void)state;
    const double h[] = {0, 0, 3, 0}, h2[] = {0.5, 0, 2.5, 0}, v[] = {1, 0.5, 1, 2.5};
    assert_int_equal(count1(h, 2, 0, 1.0, 0, 0), 4);
    assert_int_equal(count1(h2, 2, 0, 1.0, 0, 0), 3);
    assert_int_equal(count1(v, 2, 0, 1.0, 0, 0), 3);
    /* backwards gives the same cells */
    const double hb[] = {3, 0, 0, 0};
    assert_int_equal(count1(hb, 2, 0, 1.0, 0, 0), 4);
    /* the same line with the grid shifted by half a cell: 0 .. 3 spans columns -1 .. 2 of [k - 0.5, k + 0.5) */
    assert_int_equal(count1(h, 2, 0, 1.0, 0.5, 0.5), 4);
    assert_int_equal(count1(h, 2, 0, 1.0, 0.5, 0), 4);
}

/* The diagonal (0,0) -> (3,3) goes through grid corners: each corner point belongs to the cell up and to the
 * right, so only the diagonal cells (k,k), k = 0..3: 4. The anti-diagonal (0,3) -> (3,0) meets the corners
 * with x increasing and y decreasing: (0,3) (0,2) (1,2) (1,1) (2,1) (2,0) (3,0): 7. Off the ends:
 * (0.5,0.5) -> (2.5,2.5): 3; (0.5,2.5) -> (2.5,0.5): (0,2) (1,2) (1,1) (2,1) (2,0): 5. */
static void test_diagonal_through_corners(void **state)
{
    (void)state;
    const double d[] = {0, 0, 3, 3}, db[] = {3, 3, 0, 0}, a[] = {0, 3, 3, 0}, ab[] = {3, 0, 0, 3};
    const double d2[] = {0.5, 0.5, 2.5, 2.5}, a2[] = {0.5, 2.5, 2.5, 0.5};
    assert_int_equal(count1(d, 2, 0, 1.0, 0, 0), 4);
    assert_int_equal(count1(db, 2, 0, 1.0, 0, 0), 4);
    assert_int_equal(count1(a, 2, 0, 1.0, 0, 0), 7);
    assert_int_equal(count1(ab, 2, 0, 1.0, 0, 0), 7);
    assert_int_equal(count1(d2, 2, 0, 1.0, 0, 0), 3);
    assert_int_equal(count1(a2, 2, 0, 1.0, 0, 0), 5);
    /* scaled: side 0.25, the same geometry divided by 4 */
    const double q[] = {0, 0, 0.75, 0.75};
    assert_int_equal(count1(q, 2, 0, 0.25, 0, 0), 4);
}

/* A chain of one vertex occupies the cell holding it; an empty chain none. */
static void test_single_point_chain(void **state)
{
    (void)state;
    const double p[] = {1, 1};
    assert_int_equal(count1(p, 1, 0, 1.0, 0, 0), 1);
    assert_int_equal(count1(p, 1, 0, 0.3, 0.05, -7), 1);
    ft_chain *e = ft_chain_create(0, 0);
    const ft_chain *cs[] = {e};
    uint64_t k = 99;
    assert_int_equal(ft_line_box_count(cs, 1, 1.0, 0, 0, &k), FT_OK);
    assert_int_equal(k, 0);
    ft_chain_free(e);
}

/* A unit square ring on grid lines: (0,0) (1,0) (1,1) (0,1): 4 cells; vertices at cell centres: 4; inside
 * one cell of side 2: 1. Duplicates across chains are counted once. */
static void test_ring_and_dedup_across_chains(void **state)
{
    (void)state;
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    assert_int_equal(count1(sq, 4, 1, 1.0, 0, 0), 4);
    assert_int_equal(count1(sq, 4, 1, 1.0, -0.5, -0.5), 4);
    assert_int_equal(count1(sq, 4, 1, 2.0, -0.5, -0.5), 1);
    /* the same square open: the closing side is missing, but its cells are the first and last vertex's */
    assert_int_equal(count1(sq, 4, 0, 1.0, 0, 0), 4);
    ft_chain *a = chain_of(sq, 4, 1), *b = chain_of(sq, 4, 1);
    const double far[] = {10.5, 10.5, 11.5, 10.5};
    ft_chain *f = chain_of(far, 2, 0);
    const ft_chain *cs[] = {a, b, f};
    uint64_t k = 0;
    assert_int_equal(ft_line_box_count(cs, 2, 1.0, 0, 0, &k), FT_OK);
    assert_int_equal(k, 4);
    assert_int_equal(ft_line_box_count(cs, 3, 1.0, 0, 0, &k), FT_OK);
    assert_int_equal(k, 6);
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(f);
}

/* A segment in general position (no grid corner on it) crosses 1 + |di| + |dj| cells, di and dj the column
 * and row differences of its end cells. Several seeds. */
static void test_generic_segments(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        ft_rng *r = ft_rng_create(seed, 0);
        assert_non_null(r);
        for (int t = 0; t < 200; t++) {
            double xy[4];
            for (int i = 0; i < 4; i++)
                xy[i] = 40.0 * ft_rng_uniform(r) - 20.0;
            double size = 0.1 + 3.0 * ft_rng_uniform(r), ox = ft_rng_uniform(r), oy = ft_rng_uniform(r);
            double di = fabs(floor((xy[2] - ox) / size) - floor((xy[0] - ox) / size));
            double dj = fabs(floor((xy[3] - oy) / size) - floor((xy[1] - oy) / size));
            assert_int_equal(count1(xy, 2, 0, size, ox, oy), (uint64_t)(1.0 + di + dj));
        }
        ft_rng_free(r);
    }
}

/* The minimum over k x k origins equals the smallest of the single counts on the shifted grids (dyadic
 * coordinates and sizes keep every division exact). The unit square in cells of side 2: 1 at best. */
static void test_min_over_offsets(void **state)
{
    (void)state;
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    ft_chain *s = chain_of(sq, 4, 1);
    const ft_chain *one[] = {s};
    uint64_t k = 0;
    assert_int_equal(ft_line_box_count_min(one, 1, 2.0, 2, -1.0, -1.0, &k), FT_OK);
    assert_int_equal(k, 1);
    ft_chain_free(s);
    ft_rng *r = ft_rng_create(7, 0);
    ft_chain *c = ft_chain_create(0, 0);
    for (int i = 0; i < 300; i++)
        ft_chain_push(c, ldexp(floor(ldexp(ft_rng_uniform(r), 20)), -20),
                      ldexp(floor(ldexp(ft_rng_uniform(r), 20)), -20));
    const ft_chain *cs[] = {c};
    const double size = 0.125;
    const int kk = 4;
    uint64_t best = UINT64_MAX;
    for (int a = 0; a < kk; a++)
        for (int b = 0; b < kk; b++) {
            uint64_t n = 0;
            assert_int_equal(ft_line_box_count(cs, 1, size, -a * size / kk, -b * size / kk, &n), FT_OK);
            best = n < best ? n : best;
        }
    assert_int_equal(ft_line_box_count_min(cs, 1, size, kk, 0.0, 0.0, &k), FT_OK);
    assert_int_equal(k, best);
    ft_chain_free(c);
    ft_rng_free(r);
}

static void test_box_bad_input(void **state)
{
    (void)state;
    const double p[] = {0, 0, 1, 1};
    ft_chain *c = chain_of(p, 2, 0);
    const ft_chain *cs[] = {c};
    uint64_t k;
    assert_error_names(ft_line_box_count(cs, 1, 0.0, 0, 0, &k), FT_E_INVALID, "box size");
    assert_error_names(ft_line_box_count(cs, 1, -1.0, 0, 0, &k), FT_E_INVALID, "-1");
    assert_error_names(ft_line_box_count(cs, 1, 1.0, NAN, 0, &k), FT_E_INVALID, "origin");
    assert_error_names(ft_line_box_count(cs, 0, 1.0, 0, 0, &k), FT_E_EMPTY, "no chains");
    assert_error_names(ft_line_box_count(cs, 1, 1e-12, 0, 0, &k), FT_E_INVALID, "cells");
    c->x[1] = INFINITY;
    assert_error_names(ft_line_box_count(cs, 1, 1.0, 0, 0, &k), FT_E_NUMERIC, "chain 0: vertex 1");
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_segment_on_grid_line),
        cmocka_unit_test(test_diagonal_through_corners),
        cmocka_unit_test(test_single_point_chain),
        cmocka_unit_test(test_ring_and_dedup_across_chains),
        cmocka_unit_test(test_generic_segments),
        cmocka_unit_test(test_min_over_offsets),
        cmocka_unit_test(test_box_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
