/* fracterra — unit tests of src/contour/polygon_set.c: polygon sets (create, copy, add with reorientation,
 * area, vertices), GEOS validity and containment, and the polygons of a layer (polygon and closed-line
 * layers) with their errors.
 *
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

#include "fracterra/contour.h"
#include "ft_test_assert.h"

static ft_chain *ring_of(const double *xy, size_t n)
{
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, n, 2, 1);
    assert_non_null(c);
    return c;
}

static ft_chain **one_hole(const double *xy, size_t n)
{
    ft_chain **h = malloc(sizeof *h);
    assert_non_null(h);
    h[0] = ring_of(xy, n);
    return h;
}

static const double square10_cw[] = {0, 0, 0, 10, 10, 10, 10, 0}; /* clockwise on purpose */
static const double hole_ccw[] = {4, 4, 6, 4, 6, 6, 4, 6};        /* counter-clockwise on purpose */

static void test_add_reorients_and_measures(void **state)
{
    (void)state;
    ft_polygon_set *s = ft_polygon_set_create();
    assert_non_null(s);
    assert_int_equal(s->n, 0);
    assert_true(ft_polygon_set_area(s) == 0.0);
    assert_int_equal(ft_polygon_set_vertices(s), 0);
    assert_int_equal(ft_polygon_set_add(s, ring_of(square10_cw, 4), one_hole(hole_ccw, 4), 1), FT_OK);
    assert_int_equal(s->n, 1);
    /* outer counter-clockwise, hole clockwise (y up) */
    assert_near(ft_chain_signed_area(s->polys[0].outer), 100.0, 1e-12);
    assert_near(ft_chain_signed_area(s->polys[0].holes[0]), -4.0, 1e-12);
    assert_int_equal(s->polys[0].outer->closed, 1);
    assert_near(ft_polygon_set_area(s), 96.0, 1e-12);
    assert_int_equal(ft_polygon_set_vertices(s), 8);

    /* a repeated closing vertex is dropped; an empty holes array (nholes 0) is taken too */
    const double tri[] = {20, 0, 23, 0, 20, 4, 20, 0};
    ft_chain **none = malloc(sizeof *none);
    assert_non_null(none);
    assert_int_equal(ft_polygon_set_add(s, ring_of(tri, 4), none, 0), FT_OK);
    assert_int_equal(s->polys[1].outer->n, 3);
    assert_null(s->polys[1].holes);
    assert_near(ft_polygon_set_area(s), 96.0 + 6.0, 1e-12);
    assert_int_equal(ft_polygon_set_vertices(s), 11);

    /* a deep copy */
    ft_polygon_set *c = ft_polygon_set_copy(s);
    assert_non_null(c);
    assert_int_equal(c->n, 2);
    s->polys[0].outer->x[0] = -5;
    assert_true(c->polys[0].outer->x[0] != -5);
    assert_near(ft_polygon_set_area(c), 102.0, 1e-12);
    assert_int_equal(c->polys[0].nholes, 1);
    ft_polygon_set_free(c);
    ft_polygon_set_free(s);
    ft_polygon_set_free(NULL);
    assert_null(ft_polygon_set_copy(NULL));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
}

static void test_add_refuses_bad_rings_and_takes_nothing(void **state)
{
    (void)state;
    ft_polygon_set *s = ft_polygon_set_create();
    const double two[] = {0, 0, 1, 1};
    const double nan_ring[] = {0, 0, 1, 0, NAN, 1};
    ft_chain *outer = ring_of(square10_cw, 4);
    assert_error_names(ft_polygon_set_add(NULL, outer, NULL, 0), FT_E_INVALID, "NULL set");
    assert_error_names(ft_polygon_set_add(s, NULL, NULL, 0), FT_E_INVALID, "outer ring 0 is NULL");
    assert_error_names(ft_polygon_set_add(s, outer, NULL, 2), FT_E_INVALID, "2 holes");
    ft_chain *bad = ring_of(two, 2);
    assert_error_names(ft_polygon_set_add(s, bad, NULL, 0), FT_E_INVALID, "2 vertices");
    ft_chain_free(bad);
    bad = ring_of(nan_ring, 3);
    assert_error_names(ft_polygon_set_add(s, bad, NULL, 0), FT_E_INVALID, "vertex 2 is not finite");
    /* a bad hole: nothing is taken, the caller still owns outer and the hole */
    ft_chain *holes[1] = {bad};
    assert_error_names(ft_polygon_set_add(s, outer, holes, 1), FT_E_INVALID, "hole 0 vertex 2");
    assert_int_equal(s->n, 0);
    assert_near(ft_chain_signed_area(outer), -100.0, 1e-12); /* untouched */
    ft_chain_free(bad);
    ft_chain_free(outer);
    ft_polygon_set_free(s);
}

static void test_validity_names_the_fault(void **state)
{
    (void)state;
    const char *why = NULL;
    ft_polygon_set *s = ft_polygon_set_create();
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 1); /* empty is valid */
    assert_int_equal(ft_polygon_set_add(s, ring_of(square10_cw, 4), one_hole(hole_ccw, 4), 1), FT_OK);
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 1);
    assert_null(why);

    /* orientation broken by hand */
    ft_chain_reverse(s->polys[0].outer);
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 0);
    assert_non_null(strstr(why, "polygon 0: outer ring is not counter-clockwise"));
    ft_chain_reverse(s->polys[0].outer);
    ft_chain_reverse(s->polys[0].holes[0]);
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 0);
    assert_non_null(strstr(why, "polygon 0 hole 0: not clockwise"));
    ft_chain_reverse(s->polys[0].holes[0]);

    /* a hole outside its shell */
    s->polys[0].holes[0]->x[0] += 20, s->polys[0].holes[0]->x[1] += 20;
    s->polys[0].holes[0]->x[2] += 20, s->polys[0].holes[0]->x[3] += 20;
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 0);
    assert_non_null(strstr(why, "Hole lies outside shell"));
    ft_polygon_set_free(s);

    /* a self-intersecting ring (its larger lobe counter-clockwise) */
    const double bow[] = {0, -2, 3, 1, 3, -1, 0, 2};
    s = ft_polygon_set_create();
    assert_int_equal(ft_polygon_set_add(s, ring_of(bow, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 0);
    assert_non_null(strstr(why, "elf-intersection"));
    assert_int_equal(ft_polygon_set_is_valid(s, NULL), 0);
    ft_polygon_set_free(s);

    /* two overlapping polygons; two that touch at a corner are valid */
    const double a[] = {0, 0, 2, 0, 2, 2, 0, 2}, b[] = {1, 1, 3, 1, 3, 3, 1, 3}, c[] = {2, 2, 4, 2, 4, 4, 2, 4};
    s = ft_polygon_set_create();
    assert_int_equal(ft_polygon_set_add(s, ring_of(a, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_add(s, ring_of(c, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 1);
    assert_int_equal(ft_polygon_set_add(s, ring_of(b, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_is_valid(s, &why), 0);
    assert_non_null(why);
    ft_polygon_set_free(s);

    why = NULL;
    assert_error_names(ft_polygon_set_is_valid(NULL, &why), 2, "NULL polygon set"); /* undecided */
    assert_null(why);
}

static void test_within(void **state)
{
    (void)state;
    const double big[] = {0, 0, 10, 0, 10, 10, 0, 10}, small[] = {1, 1, 3, 1, 3, 3, 1, 3};
    const double edge[] = {0, 0, 5, 0, 5, 5, 0, 5}, out[] = {8, 8, 12, 8, 12, 12, 8, 12};
    ft_polygon_set *B = ft_polygon_set_create(), *S = ft_polygon_set_create(), *E = ft_polygon_set_create();
    ft_polygon_set *O = ft_polygon_set_create(), *empty = ft_polygon_set_create();
    assert_int_equal(ft_polygon_set_add(B, ring_of(big, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_add(S, ring_of(small, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_add(E, ring_of(edge, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_add(O, ring_of(out, 4), NULL, 0), FT_OK);
    assert_int_equal(ft_polygon_set_within(S, B), 1);
    assert_int_equal(ft_polygon_set_within(B, S), 0);
    assert_int_equal(ft_polygon_set_within(E, B), 1); /* covers: sharing the boundary counts */
    assert_int_equal(ft_polygon_set_within(O, B), 0);
    assert_int_equal(ft_polygon_set_within(empty, B), 1);
    assert_int_equal(ft_polygon_set_within(S, empty), 0);
    /* inside the hole is not inside */
    ft_polygon_set *H = ft_polygon_set_create();
    const double hole[] = {0.5, 0.5, 3.5, 0.5, 3.5, 3.5, 0.5, 3.5};
    assert_int_equal(ft_polygon_set_add(H, ring_of(big, 4), one_hole(hole, 4), 1), FT_OK);
    assert_int_equal(ft_polygon_set_within(S, H), 0);
    /* undecided, as GEOS's predicates: 2 with the error set */
    assert_error_names(ft_polygon_set_within(NULL, B), 2, "NULL inner set");
    assert_error_names(ft_polygon_set_within(S, NULL), 2, "NULL outer set");
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    ft_polygon_set_free(H);
    ft_polygon_set_free(B);
    ft_polygon_set_free(S);
    ft_polygon_set_free(E);
    ft_polygon_set_free(O);
    ft_polygon_set_free(empty);
}

/* ---- from a layer ----------------------------------------------------------------------------- */

static void add_feature(ft_layer *l, int64_t fid, ft_geom_type type, int multi)
{
    assert_true(ft_layer_add_feature(l, fid, type, multi) >= 0);
}

static void add_part(ft_layer *l, const double *xy, size_t n, int closed, ft_part_role role, int polygon)
{
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, n, 2, closed);
    assert_non_null(c);
    assert_int_equal(ft_layer_add_part(l, c, role, polygon), FT_OK);
}

static void test_from_polygon_layer(void **state)
{
    (void)state;
    const double sq[] = {0, 0, 0, 10, 10, 10, 10, 0}; /* clockwise, as GDAL may hand it */
    const double tri[] = {20, 0, 23, 0, 20, 4};
    const double tri2[] = {30, 0, 33, 0, 30, 4};
    ft_layer *l = ft_layer_create("lakes", NULL);
    assert_non_null(l);
    add_feature(l, 7, FT_GEOM_POLYGON, 0);
    add_part(l, sq, 4, 1, FT_ROLE_OUTER, 0);
    add_part(l, hole_ccw, 4, 1, FT_ROLE_INNER, 0);
    add_feature(l, 8, FT_GEOM_NONE, 0); /* no geometry: skipped */
    add_feature(l, 9, FT_GEOM_POLYGON, 1); /* a multipolygon of two triangles */
    add_part(l, tri, 3, 1, FT_ROLE_OUTER, 0);
    add_part(l, tri2, 3, 1, FT_ROLE_OUTER, 1);
    ft_polygon_set *s = NULL;
    assert_int_equal(ft_polygon_set_from_layer(l, &s), FT_OK);
    assert_int_equal(s->n, 3);
    assert_int_equal(s->polys[0].nholes, 1);
    assert_int_equal(s->polys[1].nholes, 0);
    assert_near(ft_polygon_set_area(s), 96.0 + 6.0 + 6.0, 1e-12);
    assert_true(ft_chain_signed_area(s->polys[0].outer) > 0);
    assert_true(ft_chain_signed_area(s->polys[0].holes[0]) < 0);
    assert_int_equal(ft_polygon_set_is_valid(s, NULL), 1);
    /* the layer is untouched (copies were made) */
    assert_true(ft_chain_signed_area(l->parts[0].chain) < 0);
    ft_polygon_set_free(s);
    ft_layer_free(l);
}

static void test_from_line_layer(void **state)
{
    (void)state;
    /* a line whose first and last vertices are equal, and a chain flagged closed */
    const double loop[] = {0, 0, 4, 0, 4, 3, 0, 3, 0, 0};
    const double flagged[] = {10, 0, 12, 0, 11, 2};
    ft_layer *l = ft_layer_create("contours", NULL);
    add_feature(l, 1, FT_GEOM_LINE, 0);
    add_part(l, loop, 5, 0, FT_ROLE_LINE, 0);
    add_feature(l, 2, FT_GEOM_LINE, 0);
    add_part(l, flagged, 3, 1, FT_ROLE_LINE, 0);
    ft_polygon_set *s = NULL;
    assert_int_equal(ft_polygon_set_from_layer(l, &s), FT_OK);
    assert_int_equal(s->n, 2);
    assert_int_equal(s->polys[0].outer->n, 4);
    assert_near(ft_polygon_set_area(s), 12.0 + 2.0, 1e-12);
    ft_polygon_set_free(s);

    /* an open line is named */
    const double open[] = {0, 0, 5, 0, 5, 5};
    add_feature(l, 42, FT_GEOM_LINE, 0);
    add_part(l, open, 3, 0, FT_ROLE_LINE, 0);
    s = (ft_polygon_set *)1;
    assert_error_names(ft_polygon_set_from_layer(l, &s), FT_E_FORMAT, "feature 42 part 0 is an open line");
    assert_null(s);
    ft_layer_free(l);
}

static void test_from_layer_errors(void **state)
{
    (void)state;
    ft_polygon_set *s = NULL;
    ft_layer *l = ft_layer_create("empty", NULL);
    assert_error_names(ft_polygon_set_from_layer(l, &s), FT_E_EMPTY, "no polygon");
    add_feature(l, 3, FT_GEOM_NONE, 0);
    assert_error_names(ft_polygon_set_from_layer(l, &s), FT_E_EMPTY, "'empty'");
    /* a two-vertex closed ring, a non-finite vertex */
    const double two[] = {0, 0, 1, 1, 0, 0};
    add_feature(l, 5, FT_GEOM_LINE, 0);
    add_part(l, two, 3, 0, FT_ROLE_LINE, 0);
    assert_error_names(ft_polygon_set_from_layer(l, &s), FT_E_FORMAT, "feature 5 part 0");
    ft_layer_free(l);
    l = ft_layer_create("nan", NULL);
    const double bad[] = {0, 0, 1, 0, 1, INFINITY};
    add_feature(l, 6, FT_GEOM_POLYGON, 0);
    add_part(l, bad, 3, 1, FT_ROLE_OUTER, 0);
    assert_error_names(ft_polygon_set_from_layer(l, &s), FT_E_FORMAT, "feature 6 part 0: vertex 2 is not finite");
    ft_layer_free(l);
    /* an inner ring with no outer ring before it */
    l = ft_layer_create("orphan", NULL);
    add_feature(l, 11, FT_GEOM_POLYGON, 0);
    add_part(l, hole_ccw, 4, 1, FT_ROLE_INNER, 0);
    assert_error_names(ft_polygon_set_from_layer(l, &s), FT_E_FORMAT, "feature 11 part 0: an inner ring");
    assert_error_names(ft_polygon_set_from_layer(l, NULL), FT_E_INVALID, "NULL output");
    ft_layer_free(l);
    assert_error_names(ft_polygon_set_from_layer(NULL, &s), FT_E_INVALID, "NULL layer");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_add_reorients_and_measures),
        cmocka_unit_test(test_add_refuses_bad_rings_and_takes_nothing),
        cmocka_unit_test(test_validity_names_the_fault),
        cmocka_unit_test(test_within),
        cmocka_unit_test(test_from_polygon_layer),
        cmocka_unit_test(test_from_line_layer),
        cmocka_unit_test(test_from_layer_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
