/* fracterra — unit tests of core/topology.c: arcs shared by adjacent rings, sides, junctions, closed
 * arcs, snapping, and rebuilding rings from edited arcs.
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

/* Adds a one-ring polygon feature (xy interleaved, n vertices). */
static void add_polygon(ft_layer *l, const double *xy, size_t n)
{
    assert_true(ft_layer_add_feature(l, (int64_t)l->nfeatures, FT_GEOM_POLYGON, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(xy, xy + 1, n, 2, 1), FT_ROLE_OUTER, 0), FT_OK);
}

/* Index of vertex (x, y) in chain c, or -1. */
static long find_vertex(const ft_chain *c, double x, double y)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->x[i] == x && c->y[i] == y)
            return (long)i;
    return -1;
}

static int count_sides(const ft_topology *t, int both)
{
    int n = 0;
    for (size_t a = 0; a < t->narcs; a++)
        n += both ? (t->arc_left[a] >= 0 && t->arc_right[a] >= 0) : (t->arc_left[a] < 0 || t->arc_right[a] < 0);
    return n;
}

static const double sq_a[] = {0, 0, 1, 0, 1, 1, 0, 1};
static const double sq_b[] = {1, 0, 2, 0, 2, 1, 1, 1};

static void test_two_squares_share_one_arc(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("two", NULL);
    add_polygon(l, sq_a, 4);
    add_polygon(l, sq_b, 4);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    const ft_topology *t = l->topology;
    assert_non_null(t);
    assert_int_equal(t->nparts, 2);
    assert_int_equal(t->narcs, 3);
    assert_int_equal(t->nrings[0], 2);
    assert_int_equal(t->nrings[1], 2);

    /* the shared arc runs (1,0) -> (1,1): A (CCW, walks it forward) is on its left, B on its right */
    size_t shared = t->narcs;
    for (size_t a = 0; a < t->narcs; a++)
        if (t->arc_left[a] >= 0 && t->arc_right[a] >= 0)
            shared = a;
    assert_true(shared < t->narcs);
    const ft_chain *s = t->arcs[shared];
    assert_int_equal(s->n, 2);
    assert_int_equal(s->closed, 0);
    assert_true(s->x[0] == 1.0 && s->y[0] == 0.0 && s->x[1] == 1.0 && s->y[1] == 1.0);
    assert_int_equal(t->arc_left[shared], 0);
    assert_int_equal(t->arc_right[shared], 1);
    assert_int_equal(count_sides(t, 0), 2);
    for (size_t a = 0; a < t->narcs; a++)
        if (a != shared) {
            assert_int_equal(t->arcs[a]->n, 4); /* three edges from junction to junction */
            assert_int_equal(t->arc_right[a], -1);
        }
    /* each ring refers to the shared arc once, in opposite directions */
    int dir[2] = {-1, -1};
    for (int p = 0; p < 2; p++)
        for (size_t r = 0; r < t->nrings[p]; r++)
            if (t->rings[p][r].arc == shared)
                dir[p] = t->rings[p][r].reversed;
    assert_int_equal(dir[0], 0);
    assert_int_equal(dir[1], 1);
    ft_layer_free(l);
}

static void test_edit_shared_arc_then_apply(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("two", NULL);
    add_polygon(l, sq_a, 4);
    add_polygon(l, sq_b, 4);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    ft_topology *t = l->topology;
    size_t shared = t->narcs;
    for (size_t a = 0; a < t->narcs; a++)
        if (t->arc_left[a] >= 0 && t->arc_right[a] >= 0)
            shared = a;
    /* insert (1.2, 0.5) between (1,0) and (1,1) */
    ft_chain *s = t->arcs[shared];
    assert_int_equal(ft_chain_push(s, 1.0, 1.0), FT_OK);
    s->x[1] = 1.2;
    s->y[1] = 0.5;
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    const ft_chain *a = l->parts[0].chain, *b = l->parts[1].chain;
    assert_int_equal(a->n, 5);
    assert_int_equal(b->n, 5);
    assert_int_equal(a->closed, 1);
    assert_true(find_vertex(a, 1.2, 0.5) >= 0);
    assert_true(find_vertex(b, 1.2, 0.5) >= 0);
    /* A gains the triangle (1,0) (1.2,0.5) (1,1) of area 0.1, B loses it */
    assert_near(ft_chain_signed_area(a), 1.1, 1e-12);
    assert_near(ft_chain_signed_area(b), 0.9, 1e-12);
    /* the same boundary: in A from (1,0) to (1,1) through the new vertex, in B the other way */
    long ia = find_vertex(a, 1.0, 0.0), ib = find_vertex(b, 1.0, 1.0);
    assert_true(ia >= 0 && ib >= 0);
    assert_true(a->x[(ia + 1) % 5] == 1.2 && b->x[(ib + 1) % 5] == 1.2);
    /* every original corner is still there, none is repeated */
    for (int i = 0; i < 4; i++) {
        assert_true(find_vertex(a, sq_a[2 * i], sq_a[2 * i + 1]) >= 0);
        assert_true(find_vertex(b, sq_b[2 * i], sq_b[2 * i + 1]) >= 0);
    }
    ft_layer_free(l);
}

/* A = [0,1]^2, B = [1,2]x[0,1], C = [0,2]x[1,2] with a vertex at (1,1): a T-junction at (1,1). */
static void test_t_junction(void **state)
{
    (void)state;
    const double c[] = {0, 1, 1, 1, 2, 1, 2, 2, 0, 2};
    ft_layer *l = ft_layer_create("t", NULL);
    add_polygon(l, sq_a, 4);
    add_polygon(l, sq_b, 4);
    add_polygon(l, c, 5);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    const ft_topology *t = l->topology;
    /* shared: (1,0)-(1,1), (0,1)-(1,1), (1,1)-(2,1); outer: A's, B's and C's remaining boundary */
    assert_int_equal(t->narcs, 6);
    assert_int_equal(count_sides(t, 1), 3);
    assert_int_equal(count_sides(t, 0), 3);
    for (int p = 0; p < 3; p++)
        assert_int_equal(t->nrings[p], 3);
    /* every arc touching (1,1) ends there, and C's top boundary runs (0,1)..(2,1) via (0,2), (2,2) */
    int at_t = 0;
    for (size_t a = 0; a < t->narcs; a++) {
        const ft_chain *ch = t->arcs[a];
        at_t += (ch->x[0] == 1.0 && ch->y[0] == 1.0) || (ch->x[ch->n - 1] == 1.0 && ch->y[ch->n - 1] == 1.0);
        if (ch->n == 4 && find_vertex(ch, 0, 2) >= 0) {
            assert_true(find_vertex(ch, 2, 2) >= 0);
            assert_true(t->arc_left[a] == 2 || t->arc_right[a] == 2);
        }
    }
    assert_int_equal(at_t, 3);
    /* unedited, apply gives back the same rings (up to the starting vertex) */
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    assert_int_equal(l->parts[2].chain->n, 5);
    assert_near(ft_chain_signed_area(l->parts[2].chain), 2.0, 1e-15);
    assert_near(ft_chain_signed_area(l->parts[0].chain), 1.0, 1e-15);
    ft_layer_free(l);
}

static void test_lone_ring_is_one_closed_arc(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("one", NULL);
    add_polygon(l, sq_a, 4);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    const ft_topology *t = l->topology;
    assert_int_equal(t->narcs, 1);
    assert_int_equal(t->arcs[0]->closed, 1);
    assert_int_equal(t->arcs[0]->n, 4);
    assert_int_equal(t->nrings[0], 1);
    assert_int_equal(t->rings[0][0].reversed, 0);
    assert_int_equal(t->arc_left[0], 0);
    assert_int_equal(t->arc_right[0], -1);
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    const ft_chain *c = l->parts[0].chain;
    assert_int_equal(c->n, 4);
    for (int i = 0; i < 4; i++)
        assert_true(c->x[i] == sq_a[2 * i] && c->y[i] == sq_a[2 * i + 1]);
    ft_layer_free(l);
}

/* Outer [0,4]^2 with hole [1,3]^2 (clockwise), and an island polygon filling the hole (CCW): the hole
 * and the island share one closed arc; the polygon with the hole is on one side, the island on the other. */
static void test_hole_and_island_share_closed_arc(void **state)
{
    (void)state;
    const double outer[] = {0, 0, 4, 0, 4, 4, 0, 4};
    const double hole[] = {1, 1, 1, 3, 3, 3, 3, 1};
    const double island[] = {3, 3, 1, 3, 1, 1, 3, 1}; /* starts elsewhere on the same cycle */
    ft_layer *l = ft_layer_create("lake", NULL);
    add_polygon(l, outer, 4);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(hole, hole + 1, 4, 2, 1), FT_ROLE_INNER, 0), FT_OK);
    add_polygon(l, island, 4);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    const ft_topology *t = l->topology;
    assert_int_equal(t->narcs, 2);
    size_t ha = t->rings[1][0].arc;
    assert_int_equal(t->nrings[1], 1);
    assert_int_equal(t->nrings[2], 1);
    assert_int_equal(t->rings[2][0].arc, ha);
    assert_int_equal(t->arcs[ha]->closed, 1);
    assert_int_equal(t->rings[1][0].reversed, 0);
    assert_int_equal(t->rings[2][0].reversed, 1);
    /* the hole's arc runs clockwise: the outer polygon (part 1, its hole) is on its left */
    assert_int_equal(t->arc_left[ha], 1);
    assert_int_equal(t->arc_right[ha], 2);
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    assert_near(ft_chain_signed_area(l->parts[1].chain), -4.0, 1e-15);
    assert_near(ft_chain_signed_area(l->parts[2].chain), 4.0, 1e-15);
    ft_layer_free(l);
}

static void test_tolerance_snaps_near_vertices(void **state)
{
    (void)state;
    const double b_off[] = {1 + 1e-9, 0, 2, 0, 2, 1, 1 - 1e-9, 1 + 1e-9};
    ft_layer *l = ft_layer_create("snap", NULL);
    add_polygon(l, sq_a, 4);
    add_polygon(l, b_off, 4);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    assert_int_equal(l->topology->narcs, 2); /* exact: nothing shared, two closed arcs */
    assert_int_equal(count_sides(l->topology, 1), 0);
    assert_int_equal(ft_layer_build_topology(l, 1e-6), FT_OK);
    assert_int_equal(l->topology->narcs, 3);
    assert_int_equal(count_sides(l->topology, 1), 1);
    /* apply moves B's corners onto A's */
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    assert_true(find_vertex(l->parts[1].chain, 1.0, 0.0) >= 0);
    assert_true(find_vertex(l->parts[1].chain, 1.0, 1.0) >= 0);
    assert_int_equal(ft_layer_build_topology(l, -1.0), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "-1"));
    ft_layer_free(l);
}

/* Lines, repeated vertices, a spike and a ring collapsed to a point must neither crash nor mislead. */
static void test_degenerate_inputs(void **state)
{
    (void)state;
    const double dup[] = {0, 0, 1, 0, 1, 0, 1, 1, 0, 1, 0, 0};             /* repeated + closing vertex */
    const double spike[] = {10, 0, 11, 0, 11, 0.5, 12, 0.5, 11, 0.5, 11, 1, 10, 1}; /* out to (12,0.5), back */
    const double point[] = {5, 5, 5, 5, 5, 5};
    ft_layer *l = ft_layer_create("odd", NULL);
    add_polygon(l, dup, 6);
    add_polygon(l, spike, 7);
    add_polygon(l, point, 3);
    assert_true(ft_layer_add_feature(l, 9, FT_GEOM_LINE, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(sq_a, sq_a + 1, 4, 2, 0), FT_ROLE_LINE, 0), FT_OK);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    const ft_topology *t = l->topology;
    assert_int_equal(t->nrings[2], 0); /* collapsed to one point */
    assert_int_equal(t->nrings[3], 0); /* a line */
    assert_int_equal(t->nrings[1], 3); /* spike arc out, spike arc back, the rest */
    assert_int_equal(t->rings[1][0].arc, t->rings[1][1].arc);
    assert_int_not_equal(t->rings[1][0].reversed, t->rings[1][1].reversed);
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    assert_int_equal(l->parts[0].chain->n, 4); /* duplicates dropped */
    assert_near(ft_chain_signed_area(l->parts[0].chain), 1.0, 1e-15);
    assert_int_equal(l->parts[1].chain->n, 7);
    assert_true(find_vertex(l->parts[1].chain, 12.0, 0.5) >= 0);
    assert_near(ft_chain_signed_area(l->parts[1].chain), 1.0, 1e-15);
    assert_int_equal(l->parts[2].chain->n, 3); /* untouched */
    assert_int_equal(l->parts[3].chain->closed, 0);

    l->parts[0].chain->x[0] = NAN;
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_E_NUMERIC);
    assert_non_null(l->topology); /* the previous topology survives a failed build */
    ft_layer_free(l);
}

static void test_apply_errors(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("e", NULL);
    add_polygon(l, sq_a, 4);
    assert_int_equal(ft_layer_apply_topology(l), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "ft_layer_build_topology"));
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    l->topology->arcs[0]->n = 2; /* a closed arc of 2 vertices is no ring */
    assert_int_equal(ft_layer_apply_topology(l), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "arc 0"));
    assert_int_equal(l->parts[0].chain->n, 4); /* unchanged on failure */
    ft_topology_free(NULL);
    ft_layer_free(l);
}

/* An n x n grid of unit squares: every interior grid edge is shared, and the four outer corners are
 * the only vertices of degree 2, so there are 2 n (n + 1) - 4 arcs. 160,000 ring vertices. */
static void test_large_grid(void **state)
{
    (void)state;
    const int n = 200;
    ft_layer *l = ft_layer_create("grid", NULL);
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            const double xy[] = {i, j, i + 1, j, i + 1, j + 1, i, j + 1};
            add_polygon(l, xy, 4);
        }
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    const ft_topology *t = l->topology;
    assert_int_equal(t->narcs, (size_t)(2 * n * (n + 1) - 4));
    assert_int_equal(count_sides(t, 1), 2 * n * (n - 1));
    assert_int_equal(count_sides(t, 0), 4 * n - 4);
    for (size_t p = 0; p < t->nparts; p++)
        for (size_t r = 0; r < t->nrings[p]; r++) {
            size_t a = t->rings[p][r].arc;
            assert_true(t->arc_left[a] == (int)p || t->arc_right[a] == (int)p);
        }
    /* with a tolerance too */
    assert_int_equal(ft_layer_build_topology(l, 0.01), FT_OK);
    assert_int_equal(l->topology->narcs, (size_t)(2 * n * (n + 1) - 4));
    assert_int_equal(ft_layer_apply_topology(l), FT_OK);
    assert_int_equal(ft_layer_vertex_count(l), (size_t)(4 * n * n));
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_two_squares_share_one_arc),
        cmocka_unit_test(test_edit_shared_arc_then_apply),
        cmocka_unit_test(test_t_junction),
        cmocka_unit_test(test_lone_ring_is_one_closed_arc),
        cmocka_unit_test(test_hole_and_island_share_closed_arc),
        cmocka_unit_test(test_tolerance_snaps_near_vertices),
        cmocka_unit_test(test_degenerate_inputs),
        cmocka_unit_test(test_apply_errors),
        cmocka_unit_test(test_large_grid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
