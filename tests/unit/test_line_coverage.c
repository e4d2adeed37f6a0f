/* fracterra — unit tests of line/apply_layer.c: operations on whole layers, and on coverages through the
 * arc-node topology (a 3 x 3 grid of squares with wiggly shared edges): shared boundaries stay identical
 * on both sides, nodes stay in place, the area is kept, collapsing rings keep their arcs, errors leave
 * the layer unchanged.
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

#define GRID 3
#define CELL 10.0
#define WIGGLES 7

/* The vertices strictly inside the edge from node (i0, j0) to node (i1, j1) (i0 <= i1, j0 <= j1): a
 * deterministic wiggle, the same whichever cell asks. */
static void edge_interior(int i0, int j0, int i1, int j1, double *x, double *y)
{
    ft_rng *r = ft_rng_create(1000u + (uint64_t)(i0 * 97 + j0 * 31 + i1 * 7 + j1), 5);
    for (int k = 0; k < WIGGLES; k++) {
        double t = (k + 1.0) / (WIGGLES + 1.0), off = (ft_rng_uniform(r) - 0.5) * 2.0;
        x[k] = CELL * (i0 + t * (i1 - i0)) + off * (j1 - j0);
        y[k] = CELL * (j0 + t * (j1 - j0)) + off * (i1 - i0);
    }
    ft_rng_free(r);
}

/* Appends node (i0, j0) and the interior of the edge to node (i1, j1), in walking order. */
static void walk_edge(ft_chain *c, int i0, int j0, int i1, int j1)
{
    double x[WIGGLES], y[WIGGLES];
    int fwd = i0 < i1 || j0 < j1;
    edge_interior(fwd ? i0 : i1, fwd ? j0 : j1, fwd ? i1 : i0, fwd ? j1 : j0, x, y);
    ft_chain_push(c, CELL * i0, CELL * j0);
    for (int k = 0; k < WIGGLES; k++) {
        int m = fwd ? k : WIGGLES - 1 - k;
        ft_chain_push(c, x[m], y[m]);
    }
}

static ft_layer *grid_coverage(void)
{
    ft_layer *l = ft_layer_create("cells", NULL);
    for (int j = 0; j < GRID; j++)
        for (int i = 0; i < GRID; i++) {
            assert_true(ft_layer_add_feature(l, 10 * j + i, FT_GEOM_POLYGON, 0) >= 0);
            ft_chain *c = ft_chain_create(4 * (WIGGLES + 1), 1);
            walk_edge(c, i, j, i + 1, j);
            walk_edge(c, i + 1, j, i + 1, j + 1);
            walk_edge(c, i + 1, j + 1, i, j + 1);
            walk_edge(c, i, j + 1, i, j);
            assert_int_equal(ft_layer_add_part(l, c, FT_ROLE_OUTER, 0), FT_OK);
        }
    return l;
}

static double total_area(const ft_layer *l)
{
    double a = 0.0;
    for (size_t p = 0; p < l->nparts; p++)
        a += fabs(ft_chain_signed_area(l->parts[p].chain));
    return a;
}

/* Arcs whose two sides are both parts: boundaries the rings share vertex for vertex (exact match). */
static size_t shared_arcs(ft_layer *l)
{
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    size_t n = 0;
    for (size_t a = 0; a < l->topology->narcs; a++)
        n += l->topology->arc_left[a] >= 0 && l->topology->arc_right[a] >= 0;
    ft_topology_free(l->topology);
    l->topology = NULL;
    return n;
}

static int has_vertex(const ft_chain *c, double x, double y)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->x[i] == x && c->y[i] == y)
            return 1;
    return 0;
}

/* Part a's vertices from (x0,y0) to (x1,y1), walking forward. */
static ft_chain *section(const ft_chain *c, double x0, double y0, double x1, double y1)
{
    size_t s = 0;
    while (s < c->n && !(c->x[s] == x0 && c->y[s] == y0))
        s++;
    assert_true(s < c->n);
    ft_chain *out = ft_chain_create(0, 0);
    for (size_t k = 0; k <= c->n; k++) {
        size_t i = (s + k) % c->n;
        ft_chain_push(out, c->x[i], c->y[i]);
        if (c->x[i] == x1 && c->y[i] == y1)
            return out;
    }
    fail_msg("section end not found");
    return out;
}

static void test_enhance_coverage_shared_edges_identical(void **state)
{
    (void)state;
    ft_layer *l = grid_coverage();
    const size_t interior_edges = 2 * GRID * (GRID - 1);
    assert_int_equal(shared_arcs(l), interior_edges);
    double area0 = total_area(l);
    size_t nv0 = ft_layer_vertex_count(l);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 1.5;
    o.uc = 0.8;
    o.iterations = 3;
    o.literal_sd = 1;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, &o, 1), FT_OK);
    assert_null(l->topology);
    assert_true(ft_layer_vertex_count(l) > 6 * nv0);
    assert_int_equal(shared_arcs(l), interior_edges);
    /* cell 0 and cell 1 share the edge from node (1,0) to (1,1): the same vertices, reversed */
    ft_chain *a = section(l->parts[0].chain, CELL, 0, CELL, CELL);
    ft_chain *b = section(l->parts[1].chain, CELL, CELL, CELL, 0);
    assert_true(a->n > WIGGLES * 8);
    ft_chain_reverse(b);
    assert_int_equal(a->n, b->n);
    for (size_t i = 0; i < a->n; i++)
        assert_true(a->x[i] == b->x[i] && a->y[i] == b->y[i]);
    ft_chain_free(a);
    ft_chain_free(b);
    for (int j = 0; j <= GRID; j++) /* every node (3 or 4 cells, or the outside, meet) stays in place; */
        for (int i = 0; i <= GRID; i++) { /* the four outer corners are no nodes */
            if ((i == 0 || i == GRID) && (j == 0 || j == GRID))
                continue;
            int cell_i = i < GRID ? i : GRID - 1, cell_j = j < GRID ? j : GRID - 1;
            assert_true(has_vertex(l->parts[(size_t)(cell_j * GRID + cell_i)].chain, CELL * i, CELL * j));
        }
    double area1 = total_area(l);
    print_message("coverage: %zu -> %zu vertices, area %.4f -> %.4f (%.3f%%)\n", nv0, ft_layer_vertex_count(l),
                  area0, area1, 100.0 * (area1 - area0) / area0);
    assert_true(fabs(area1 - area0) <= 0.01 * area0);
    for (size_t p = 0; p < l->nparts; p++) {
        size_t n = 1;
        assert_int_equal(ft_line_count_self_intersections(l->parts[p].chain, &n), FT_OK);
        assert_int_equal(n, 0);
    }
    ft_layer_free(l);
}

/* Without coverage mode each ring moves its own corners, each its own way: the node (10, 10) is gone
 * from the four cells around it, and they no longer meet there. */
static void test_plain_mode_moves_nodes(void **state)
{
    (void)state;
    ft_layer *l = grid_coverage();
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.iterations = 2;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, &o, 0), FT_OK);
    const size_t around[] = {0, 1, GRID, GRID + 1};
    for (size_t k = 0; k < 4; k++)
        assert_false(has_vertex(l->parts[around[k]].chain, CELL, CELL));
    ft_layer_free(l);
}

static void test_smooth_weed_simplify_coverage(void **state)
{
    (void)state;
    const size_t interior_edges = 2 * GRID * (GRID - 1);
    ft_layer *l = grid_coverage();
    double area0 = total_area(l);
    ft_smooth_opts so = FT_SMOOTH_OPTS_DEFAULT;
    so.passes = 2;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_smooth, &so, 1), FT_OK);
    assert_int_equal(shared_arcs(l), interior_edges);
    double sm = 1.5;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_weed, &sm, 1), FT_OK);
    assert_int_equal(shared_arcs(l), interior_edges);
    double tol = 0.3;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_simplify, &tol, 1), FT_OK);
    assert_int_equal(shared_arcs(l), interior_edges);
    assert_true(fabs(total_area(l) - area0) <= 0.02 * area0);
    tol = 1000.0; /* every arc straight: inner cells become squares, corner cells lose their outer corner */
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_simplify, &tol, 1), FT_OK);
    assert_int_equal(shared_arcs(l), interior_edges);
    for (size_t p = 0; p < l->nparts; p++)
        assert_int_equal(l->parts[p].chain->n, p == 0 || p == GRID - 1 || p == GRID * (GRID - 1) || p == GRID * GRID - 1 ? 3 : 4);
    ft_layer_free(l);
}

/* Two polygons sharing one edge: each ring is two arcs, and simplifying both to straight segments would
 * leave 2-vertex rings: those keep their original arcs. An island (no node) is one closed arc. */
static void test_collapsing_rings_and_islands(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("pair", NULL);
    const double a[] = {0, 0, 5, -1, 10, 0, 10.5, 5, 10, 10, 5, 11, 0, 10};
    const double b[] = {10, 0, 15, 5, 10, 10, 10.5, 5};
    const double island[] = {20, 0, 24, 0, 25, 2, 24, 4, 20, 4, 19, 2};
    ft_layer_add_feature(l, 1, FT_GEOM_POLYGON, 0);
    ft_layer_add_part(l, ft_chain_from_arrays(a, a + 1, 7, 2, 1), FT_ROLE_OUTER, 0);
    ft_layer_add_feature(l, 2, FT_GEOM_POLYGON, 0);
    ft_layer_add_part(l, ft_chain_from_arrays(b, b + 1, 4, 2, 1), FT_ROLE_OUTER, 0);
    ft_layer_add_feature(l, 3, FT_GEOM_POLYGON, 0);
    ft_layer_add_part(l, ft_chain_from_arrays(island, island + 1, 6, 2, 1), FT_ROLE_OUTER, 0);
    double tol = 100.0;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_simplify, &tol, 1), FT_OK);
    assert_int_equal(l->parts[0].chain->n, 7); /* its arcs restored: a 2-vertex ring is no polygon */
    assert_int_equal(l->parts[1].chain->n, 3); /* its own arc straight, the shared one restored */
    assert_int_equal(l->parts[2].chain->n, 3); /* the island, simplified as a ring */
    assert_true(has_vertex(l->parts[0].chain, 10.5, 5) && has_vertex(l->parts[1].chain, 10.5, 5));
    ft_layer_free(l);
}

static void test_lines_and_errors(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("lines", NULL);
    const double xs[] = {0, 1, 2, 3}, ys[] = {0, 1, 0, 1};
    ft_layer_add_feature(l, 7, FT_GEOM_LINE, 1);
    ft_layer_add_part(l, ft_chain_from_arrays(xs, ys, 4, 1, 0), FT_ROLE_LINE, 0);
    ft_layer_add_part(l, ft_chain_from_arrays(ys, xs, 4, 1, 0), FT_ROLE_LINE, 1);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, &o, 1), FT_OK);
    assert_int_equal(l->parts[0].chain->n, 7);
    assert_int_equal(l->parts[1].chain->n, 7);
    ft_layer *before = ft_layer_copy(l);
    o.sd = 2.7;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, &o, 1), FT_E_INVALID);
    assert_string_equal(ft_last_error(), "feature 7, part 0: sd must be in [1,2], got 2.7");
    for (size_t p = 0; p < l->nparts; p++)
        assert_int_equal(l->parts[p].chain->n, before->parts[p].chain->n);
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, NULL, 0), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "enhance: NULL options"));
    assert_int_equal(ft_line_apply_layer(l, NULL, &o, 0), FT_E_INVALID);
    assert_int_equal(ft_line_apply_layer(NULL, ft_line_op_enhance, &o, 0), FT_E_INVALID);
    l->parts[1].chain->x[2] = NAN;
    o.sd = 1.3;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, &o, 0), FT_E_NUMERIC);
    ft_layer_free(before);
    ft_layer_free(l);

    l = grid_coverage(); /* a coverage error names the arc and leaves every ring as it was */
    before = ft_layer_copy(l);
    o.uc = 3.0;
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_enhance, &o, 1), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "arc 0 (boundary of feature 0): uc must be in [-1,1], got 3"));
    for (size_t p = 0; p < l->nparts; p++)
        assert_int_equal(l->parts[p].chain->n, before->parts[p].chain->n);
    assert_null(l->topology);
    ft_layer_free(before);
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_enhance_coverage_shared_edges_identical),
        cmocka_unit_test(test_plain_mode_moves_nodes),
        cmocka_unit_test(test_smooth_weed_simplify_coverage),
        cmocka_unit_test(test_collapsing_rings_and_islands),
        cmocka_unit_test(test_lines_and_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
