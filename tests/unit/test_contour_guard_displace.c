/* fracterra — tests/unit/test_contour_guard_displace.c: the crossing guard on the mountain generator's random
 * midpoint displacement and Fourier phase randomization (contour/guard_displace.c). Two squares side by side 2 apart, 1 inside a square of
 * the level below, displaced by up to 1.5 (d''): the raw displacement crosses (checked,
 * so that the test can fail), the guarded rings are simple, disjoint from each other and strictly inside
 * the level below (GEOS, not the guard's own contact test), keep every undisplaced vertex and vertex count,
 * and keep most moves in full. The same squares phase-randomized from a low f0 (the contour's wiggles as
 * large as the gap): the raw rings cross, the guarded ones are simple, disjoint and inside.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdlib.h>
#include <geos_c.h>

#include "fracterra/contour.h"
#include "fracterra/line.h"
#include "contour/contour_internal.h"

static ft_chain *square(double x0, double y0, double x1, double y1)
{
    const double x[] = {x0, x1, x1, x0}, y[] = {y0, y0, y1, y1};
    ft_chain *c = ft_chain_create(4, 1);
    for (int i = 0; i < 4; i++)
        assert_int_equal(ft_chain_push(c, x[i], y[i]), FT_OK);
    return c;
}

static GEOSGeometry *geom(GEOSContextHandle_t h, const ft_chain *c, int polygon)
{
    GEOSCoordSequence *s = GEOSCoordSeq_create_r(h, (unsigned)c->n + 1, 2);
    for (size_t i = 0; i <= c->n; i++)
        GEOSCoordSeq_setXY_r(h, s, (unsigned)i, c->x[i % c->n], c->y[i % c->n]);
    if (!polygon)
        return GEOSGeom_createLineString_r(h, s);
    return GEOSGeom_createPolygon_r(h, GEOSGeom_createLinearRing_r(h, s), NULL, 0);
}

/* Rings not simple + pairs that meet + rings not strictly inside the outer square. */
static int faults(const ft_chain *const *r, size_t n, const ft_chain *outer)
{
    GEOSContextHandle_t h = GEOS_init_r();
    GEOSGeometry *o = geom(h, outer, 1), *ob = geom(h, outer, 0), *g[2];
    int f = 0;
    for (size_t k = 0; k < n; k++) {
        GEOSGeometry *l = geom(h, r[k], 0);
        g[k] = l;
        f += GEOSisSimple_r(h, l) != 1;
        f += GEOSWithin_r(h, l, o) != 1 || GEOSIntersects_r(h, l, ob) != 0;
    }
    f += GEOSIntersects_r(h, g[0], g[1]) != 0;
    for (size_t k = 0; k < n; k++)
        GEOSGeom_destroy_r(h, g[k]);
    GEOSGeom_destroy_r(h, o);
    GEOSGeom_destroy_r(h, ob);
    GEOS_finish_r(h);
    return f;
}

static void test_guarded_rings_stay_apart_and_inside(void **state)
{
    (void)state;
    ft_chain *used[2] = {square(1, 1, 49, 99), square(51, 1, 99, 99)};
    ft_polygon_set *below = ft_polygon_set_create();
    assert_non_null(below);
    assert_int_equal(ft_polygon_set_add(below, square(0, 0, 100, 100), NULL, 0), FT_OK);
    ft_midpoint_opts m = FT_MIDPOINT_OPTS_DEFAULT;
    m.max_seg = 4.0;
    m.max_offset = 1.5;
    m.theta_min = 20.0;
    m.theta_max = 40.0;
    ft_chain *r[2], *raw[2];
    for (int k = 0; k < 2; k++) {
        assert_int_equal(ft_contour_midpoint_displace(used[k], &m, 7, (uint64_t)k, &r[k]), FT_OK);
        raw[k] = ft_chain_copy(r[k]);
    }
    assert_true(faults((const ft_chain *const *)raw, 2, below->polys[0].outer) > 0);
    ft_line_guard_stats st = {0, 0, 0, 0};
    assert_int_equal(ft_contour_guard_displaced(r, (const ft_chain *const *)used, 2, below, &st), FT_OK);
    assert_int_equal(faults((const ft_chain *const *)r, 2, below->polys[0].outer), 0);
    size_t full = 0;
    for (int k = 0; k < 2; k++) {
        assert_int_equal(r[k]->n, raw[k]->n);
        size_t found = 0;
        for (size_t i = 0; i < r[k]->n; i++) {
            full += r[k]->x[i] == raw[k]->x[i] && r[k]->y[i] == raw[k]->y[i];
            found += found < 4 && r[k]->x[i] == used[k]->x[found] && r[k]->y[i] == used[k]->y[found];
        }
        assert_int_equal(found, 4); /* the undisplaced corners, in order */
    }
    print_message("%zu moves: %zu reduced, %zu dropped; %zu of %zu vertices where drawn\n", st.moves, st.reduced,
                  st.dropped, full, r[0]->n + r[1]->n);
    assert_true(st.reduced + st.dropped > 0);
    assert_true(2 * full > r[0]->n + r[1]->n);
    for (int k = 0; k < 2; k++) {
        ft_chain_free(r[k]);
        ft_chain_free(raw[k]);
        ft_chain_free(used[k]);
    }
    ft_polygon_set_free(below);
}

/* Phase randomization (§4.2) of two squares 2 apart, 1 inside the level below, from f0 = 4 of n = 256: the
 * randomized rings wander by several units, so the raw rings cross each other and the level below. */
static void test_guarded_fourier_rings_stay_apart_and_inside(void **state)
{
    (void)state;
    ft_chain *sq[2] = {square(1, 1, 49, 99), square(51, 1, 99, 99)};
    ft_polygon_set *below = ft_polygon_set_create();
    assert_non_null(below);
    assert_int_equal(ft_polygon_set_add(below, square(0, 0, 100, 100), NULL, 0), FT_OK);
    ft_fourier_opts fo = FT_FOURIER_OPTS_DEFAULT;
    fo.n = 256;
    fo.f0 = 4;
    ft_chain *r[2], *raw[2], *base[2];
    for (int k = 0; k < 2; k++) {
        assert_int_equal(ft_contour_fourier_randomize_paired(sq[k], &fo, 11, (uint64_t)k, &base[k], &r[k]), FT_OK);
        assert_int_equal(base[k]->n, r[k]->n);
        raw[k] = ft_chain_copy(r[k]);
        ft_chain *plain = NULL; /* the public function draws the same ring */
        assert_int_equal(ft_contour_fourier_randomize(sq[k], &fo, 11, (uint64_t)k, &plain), FT_OK);
        assert_memory_equal(plain->x, r[k]->x, r[k]->n * sizeof(double));
        ft_chain_free(plain);
    }
    assert_int_equal(faults((const ft_chain *const *)base, 2, below->polys[0].outer), 0); /* the resampled squares */
    assert_true(faults((const ft_chain *const *)raw, 2, below->polys[0].outer) > 0);
    ft_line_guard_stats st = {0, 0, 0, 0};
    assert_int_equal(ft_contour_guard_rings(r, base, 2, below, &st), FT_OK);
    assert_null(base[0]);
    assert_null(base[1]);
    assert_int_equal(faults((const ft_chain *const *)r, 2, below->polys[0].outer), 0);
    size_t full = 0;
    for (int k = 0; k < 2; k++) {
        assert_int_equal(r[k]->n, raw[k]->n);
        for (size_t i = 0; i < r[k]->n; i++)
            full += r[k]->x[i] == raw[k]->x[i] && r[k]->y[i] == raw[k]->y[i];
    }
    print_message("fourier: %zu moves: %zu reduced, %zu dropped; %zu of %zu vertices where drawn\n", st.moves,
                  st.reduced, st.dropped, full, r[0]->n + r[1]->n);
    assert_int_equal(st.moves, r[0]->n + r[1]->n); /* the whole ring moves (it is recentred too) */
    assert_true(st.reduced + st.dropped > 0);
    assert_true(full > 0);
    for (int k = 0; k < 2; k++) {
        ft_chain_free(r[k]);
        ft_chain_free(raw[k]);
        ft_chain_free(sq[k]);
    }
    ft_polygon_set_free(below);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_guarded_rings_stay_apart_and_inside),
        cmocka_unit_test(test_guarded_fourier_rings_stay_apart_and_inside),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
