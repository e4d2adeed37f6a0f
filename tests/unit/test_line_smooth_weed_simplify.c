/* fracterra — unit tests of line/smooth.c, weed.c, simplify_dp.c and self_intersections.c: Chaikin quarter
 * points, the ST/SM window, weeding, Douglas-Peucker by hand, crossings counted against brute force,
 * loops removed, bad input.
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
#include "ft_test_assert.h"

static ft_chain *chain_of(const double *xy, size_t n, int closed)
{
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, n, 2, closed);
    assert_non_null(c);
    return c;
}

static void assert_vertices(const ft_chain *c, const double *xy, size_t n)
{
    assert_int_equal(c->n, n);
    for (size_t i = 0; i < n; i++) {
        assert_near(c->x[i], xy[2 * i], 1e-12);
        assert_near(c->y[i], xy[2 * i + 1], 1e-12);
    }
}

/* A seeded random walk: n vertices, unit steps, turns up to +-turn radians. */
static ft_chain *walk(size_t n, uint64_t seed, double turn)
{
    ft_chain *c = ft_chain_create(n, 0);
    ft_rng *r = ft_rng_create(seed, 0);
    double x = 0, y = 0, d = 0;
    for (size_t i = 0; i < n; i++) {
        ft_chain_push(c, x, y);
        d += (ft_rng_uniform(r) - 0.5) * 2.0 * turn;
        x += cos(d);
        y += sin(d);
    }
    ft_rng_free(r);
    return c;
}

static double seg_len(const ft_chain *c, size_t i)
{
    size_t j = (i + 1) % c->n;
    return hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
}

static void expect_msg(int rc, int code, const char *msg)
{
    assert_int_equal(rc, code);
    if (strstr(ft_last_error(), msg) == NULL)
        print_error("message '%s' lacks '%s'\n", ft_last_error(), msg);
    assert_non_null(strstr(ft_last_error(), msg));
}

/* ---- smoothing ---------------------------------------------------------------------------------- */

static void test_smooth_chaikin_quarter_points(void **state)
{
    (void)state;
    const double l[] = {0, 0, 4, 0, 4, 4};
    ft_chain *in = chain_of(l, 3, 0), *out = NULL;
    ft_smooth_opts o = FT_SMOOTH_OPTS_DEFAULT;
    assert_int_equal(ft_line_smooth(in, &o, &out), FT_OK);
    const double want[] = {0, 0, 3, 0, 4, 1, 4, 4};
    assert_vertices(out, want, 4);
    ft_chain_free(in);
    ft_chain_free(out);

    const double sq[] = {0, 0, 4, 0, 4, 4, 0, 4};
    in = chain_of(sq, 4, 1);
    assert_int_equal(ft_line_smooth(in, &o, &out), FT_OK);
    const double ring[] = {0, 1, 1, 0, 3, 0, 4, 1, 4, 3, 3, 4, 1, 4, 0, 3};
    assert_vertices(out, ring, 8);
    assert_int_equal(out->closed, 1);
    ft_chain_free(out);

    o.roundness = 1.0; /* the midpoint polygon, each midpoint once */
    o.passes = 1;
    assert_int_equal(ft_line_smooth(in, &o, &out), FT_OK);
    const double mid[] = {0, 2, 2, 0, 4, 2, 2, 4};
    assert_vertices(out, mid, 4);
    ft_chain_free(out);

    o.roundness = 0.25;
    o.passes = 3;
    assert_int_equal(ft_line_smooth(in, &o, &out), FT_OK);
    assert_int_equal(out->n, 32);
    ft_chain_free(out);
    ft_chain_free(in);
}

/* Segments outside [SM, ST) keep their vertices; a vertex is cut only when both of its segments are in. */
static void test_smooth_window(void **state)
{
    (void)state;
    const double l[] = {0, 0, 1, 0, 1, 1, 11, 1, 11, 2, 12, 2};
    ft_chain *in = chain_of(l, 6, 0), *out = NULL;
    ft_smooth_opts o = FT_SMOOTH_OPTS_DEFAULT;
    o.st = 5.0; /* the 10-long segment from (1,1) to (11,1) is too long */
    assert_int_equal(ft_line_smooth(in, &o, &out), FT_OK);
    const double want[] = {0, 0, 0.75, 0, 1, 0.25, 1, 1, 11, 1, 11, 1.75, 11.25, 2, 12, 2};
    assert_vertices(out, want, 8);
    ft_chain_free(out);
    o.st = INFINITY;
    o.sm = 2.0; /* now only the long segment is in the window: no vertex has both segments in */
    assert_int_equal(ft_line_smooth(in, &o, &out), FT_OK);
    assert_vertices(out, l, 6);
    ft_chain_free(out);
    ft_chain_free(in);
}

/* ---- weeding ------------------------------------------------------------------------------------- */

static void test_weed(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 4; seed++) {
        ft_chain *in = walk(2000, seed, 1.0), *out = NULL;
        const double sm = 2.5;
        assert_int_equal(ft_line_weed(in, sm, &out), FT_OK);
        assert_true(out->n < in->n && out->n > 10);
        for (size_t i = 0; i + 1 < out->n; i++)
            assert_true(seg_len(out, i) >= sm);
        assert_true(out->x[0] == in->x[0] && out->y[0] == in->y[0]);
        assert_true(out->x[out->n - 1] == in->x[in->n - 1] && out->y[out->n - 1] == in->y[in->n - 1]);
        ft_chain_free(out);
        in->closed = 1;
        assert_int_equal(ft_line_weed(in, sm, &out), FT_OK);
        for (size_t i = 0; i < out->n; i++)
            assert_true(seg_len(out, i) >= sm);
        ft_chain_free(out);
        ft_chain_free(in);
    }
    const double tiny[] = {0, 0, 0.1, 0, 0.1, 0.1, 0, 0.1};
    ft_chain *in = chain_of(tiny, 4, 1), *out = NULL;
    assert_int_equal(ft_line_weed(in, 1.0, &out), FT_OK); /* smaller than SM: keeps a triangle */
    assert_int_equal(out->n, 3);
    ft_chain_free(out);
    in->closed = 0;
    assert_int_equal(ft_line_weed(in, 1.0, &out), FT_OK); /* an open chain keeps its end points */
    const double ends[] = {0, 0, 0, 0.1};
    assert_vertices(out, ends, 2);
    ft_chain_free(out);
    assert_int_equal(ft_line_weed(in, 0.0, &out), FT_OK);
    assert_vertices(out, tiny, 4);
    ft_chain_free(out);
    expect_msg(ft_line_weed(in, -1.0, &out), FT_E_INVALID, "weeding length (sm) must be finite and >= 0, got -1");
    ft_chain_free(in);
}

/* 1 if (x, y) is a vertex of c. */
static int has_vertex(const ft_chain *c, double x, double y)
{
    for (size_t i = 0; i < c->n; i++)
        if (c->x[i] == x && c->y[i] == y)
            return 1;
    return 0;
}

/* A headland: S (9.6, 7.5) lies 0.64 before the tip T (10, 8). Greedy weeding keeps S and drops the tip;
 * keep-shape drops S (0.14 from the chord A T) and keeps T (0.64 from the chord S C). On random walks:
 * no short segment left, every vertex an input vertex, ends kept; rings keep at least 3. */
static void test_weed_keep_shape(void **state)
{
    (void)state;
    const double head[] = {0, 0, 9.6, 7.5, 10, 8, 20, 0};
    ft_chain *in = chain_of(head, 4, 0), *out = NULL;
    assert_int_equal(ft_line_weed(in, 1.0, &out), FT_OK);
    assert_false(has_vertex(out, 10, 8));
    ft_chain_free(out);
    assert_int_equal(ft_line_weed_shape(in, 1.0, &out), FT_OK);
    const double kept[] = {0, 0, 10, 8, 20, 0};
    assert_vertices(out, kept, 3);
    ft_chain_free(out);
    ft_chain_free(in);
    for (uint64_t seed = 1; seed <= 4; seed++) {
        in = walk(2000, seed, 1.0);
        const double sm = 2.5;
        for (int closed = 0; closed < 2; closed++) {
            in->closed = closed;
            assert_int_equal(ft_line_weed_shape(in, sm, &out), FT_OK);
            assert_true(out->n < in->n && out->n > 10);
            for (size_t i = 0; i + (closed ? 0 : 1) < out->n; i++)
                assert_true(seg_len(out, i) >= sm);
            for (size_t i = 0; i < out->n; i++)
                assert_true(has_vertex(in, out->x[i], out->y[i]));
            if (!closed) {
                assert_true(out->x[0] == in->x[0] && out->y[0] == in->y[0]);
                assert_true(out->x[out->n - 1] == in->x[in->n - 1] && out->y[out->n - 1] == in->y[in->n - 1]);
            }
            ft_chain_free(out);
        }
        ft_chain_free(in);
    }
    const double tiny[] = {0, 0, 0.1, 0, 0.1, 0.1, 0, 0.1};
    in = chain_of(tiny, 4, 1);
    assert_int_equal(ft_line_weed_shape(in, 1.0, &out), FT_OK); /* all shorter than SM: 3 are left */
    assert_int_equal(out->n, 3);
    ft_chain_free(out);
    in->closed = 0;
    assert_int_equal(ft_line_weed_shape(in, 1.0, &out), FT_OK);
    const double ends[] = {0, 0, 0, 0.1};
    assert_vertices(out, ends, 2);
    ft_chain_free(out);
    expect_msg(ft_line_weed_shape(in, -1.0, &out), FT_E_INVALID, "weeding length (sm) must be finite and >= 0");
    ft_chain_free(in);
}

/* ---- Douglas-Peucker ---------------------------------------------------------------------------- */

static void test_simplify_by_hand(void **state)
{
    (void)state;
    const double l[] = {0, 0, 1, 0.5, 2, 0, 3, 0.2, 4, 0};
    ft_chain *in = chain_of(l, 5, 0), *out = NULL;
    assert_int_equal(ft_line_simplify(in, 0.1, &out), FT_OK); /* offsets 0.5 and 0.2: both kept */
    assert_vertices(out, l, 5);
    ft_chain_free(out);
    assert_int_equal(ft_line_simplify(in, 0.35, &out), FT_OK); /* 0.5 kept; 0.33 and 0.03 from (1,.5)-(4,0) go */
    const double a[] = {0, 0, 1, 0.5, 4, 0};
    assert_vertices(out, a, 3);
    ft_chain_free(out);
    assert_int_equal(ft_line_simplify(in, 0.6, &out), FT_OK);
    const double b[] = {0, 0, 4, 0};
    assert_vertices(out, b, 2);
    ft_chain_free(out);
    ft_chain_free(in);

    const double sq[] = {0, 0, 1, 0, 2, 0, 2, 2, 0, 2};
    in = chain_of(sq, 5, 1);
    assert_int_equal(ft_line_simplify(in, 0.5, &out), FT_OK); /* the collinear (1,0) goes */
    const double s4[] = {0, 0, 2, 0, 2, 2, 0, 2};
    assert_vertices(out, s4, 4);
    assert_int_equal(out->closed, 1);
    ft_chain_free(out);
    assert_int_equal(ft_line_simplify(in, 100.0, &out), FT_OK); /* rings keep 3 vertices */
    assert_int_equal(out->n, 3);
    assert_int_equal(out->closed, 1);
    assert_true(fabs(ft_chain_signed_area(out)) > 1.0);
    ft_chain_free(out);
    expect_msg(ft_line_simplify(in, -0.5, &out), FT_E_INVALID, "simplify tolerance must be finite and >= 0, got -0.5");
    expect_msg(ft_line_simplify(in, NAN, &out), FT_E_INVALID, "got nan");
    ft_chain_free(in);
}

/* Every dropped vertex lies within the tolerance of the simplified segment that spans it. */
static void test_simplify_band(void **state)
{
    (void)state;
    ft_chain *in = walk(20000, 3, 0.7), *out = NULL;
    const double tol = 3.0;
    assert_int_equal(ft_line_simplify(in, tol, &out), FT_OK);
    assert_true(out->n > 10 && out->n < in->n / 4);
    size_t k = 0;
    for (size_t i = 0; i < in->n; i++) {
        if (k + 1 < out->n && in->x[i] == out->x[k + 1] && in->y[i] == out->y[k + 1]) {
            k++;
            continue;
        }
        double ax = out->x[k], ay = out->y[k], dx = out->x[k + 1] - ax, dy = out->y[k + 1] - ay;
        double t = ((in->x[i] - ax) * dx + (in->y[i] - ay) * dy) / (dx * dx + dy * dy);
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        assert_true(hypot(in->x[i] - ax - t * dx, in->y[i] - ay - t * dy) <= tol + 1e-9);
    }
    assert_int_equal(k, out->n - 1);
    ft_chain_free(in);
    ft_chain_free(out);
}

/* ---- self-intersections ---------------------------------------------------------------------------- */

static int brute_proper(const ft_chain *c, size_t a, size_t b)
{
    double p[8];
    size_t idx[4] = {a, (a + 1) % c->n, b, (b + 1) % c->n};
    for (int i = 0; i < 4; i++) {
        p[2 * i] = c->x[idx[i]];
        p[2 * i + 1] = c->y[idx[i]];
    }
#define OR(i, j, k) ((p[2 * j] - p[2 * i]) * (p[2 * k + 1] - p[2 * i + 1]) - (p[2 * j + 1] - p[2 * i + 1]) * (p[2 * k] - p[2 * i]))
    double o1 = OR(0, 1, 2), o2 = OR(0, 1, 3), o3 = OR(2, 3, 0), o4 = OR(2, 3, 1);
#undef OR
    return ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) && ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0));
}

static size_t brute_count(const ft_chain *c)
{
    size_t nseg = ft_chain_segments(c), n = 0;
    for (size_t a = 0; a < nseg; a++)
        for (size_t b = a + 2; b < nseg; b++)
            if (!(c->closed && a == 0 && b == nseg - 1))
                n += (size_t)brute_proper(c, a, b);
    return n;
}

static size_t crossings(const ft_chain *c)
{
    size_t n = 999;
    assert_int_equal(ft_line_count_self_intersections(c, &n), FT_OK);
    return n;
}

static void test_count_by_hand(void **state)
{
    (void)state;
    const double eight[] = {0, 0, 1, 1, 1, 0, 0, 1};
    ft_chain *c = chain_of(eight, 4, 1);
    assert_int_equal(crossings(c), 1);
    c->closed = 0; /* open: (0,0)-(1,1) and (1,0)-(0,1) still cross */
    assert_int_equal(crossings(c), 1);
    ft_chain_free(c);
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    c = chain_of(sq, 4, 1);
    assert_int_equal(crossings(c), 0);
    ft_chain_free(c);
    const double touch[] = {0, 0, 2, 0, 1, 0, 1, 1}; /* collinear overlap and a T: not proper */
    c = chain_of(touch, 4, 0);
    assert_int_equal(crossings(c), 0);
    ft_chain_free(c);
}

static void test_count_matches_brute_force(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 6; seed++) {
        ft_chain *c = walk(600, seed, 1.2);
        c->closed = (int)(seed % 2);
        size_t want = brute_count(c);
        assert_true(want > 0);
        assert_int_equal(crossings(c), want);
        ft_chain_free(c);
    }
}

static void test_remove_loops(void **state)
{
    (void)state;
    const double loop[] = {0, 0, 4, 0, 4, 2, 3, 2, 3, -1, 8, -1};
    ft_chain *in = chain_of(loop, 6, 0), *out = NULL;
    assert_int_equal(crossings(in), 1);
    assert_int_equal(ft_line_remove_loops(in, &out), FT_OK);
    const double want[] = {0, 0, 3, 0, 3, -1, 8, -1};
    assert_vertices(out, want, 4);
    assert_int_equal(crossings(out), 0);
    ft_chain_free(out);
    ft_chain_free(in);

    const double eight[] = {0, 0, 1, 1, 1, 0, 0, 1}; /* keeps the lobe with the lowest vertex */
    in = chain_of(eight, 4, 1);
    assert_int_equal(ft_line_remove_loops(in, &out), FT_OK);
    assert_int_equal(out->closed, 1);
    assert_int_equal(out->n, 3);
    assert_int_equal(crossings(out), 0);
    ft_chain_free(out);
    ft_chain_free(in);

    for (uint64_t seed = 1; seed <= 4; seed++) {
        in = walk(50000, seed, 1.0);
        in->closed = (int)(seed % 2);
        assert_true(crossings(in) > 100);
        assert_int_equal(ft_line_remove_loops(in, &out), FT_OK);
        assert_int_equal(crossings(out), 0);
        assert_true(out->n >= 3);
        if (!in->closed) {
            assert_true(out->x[0] == in->x[0] && out->y[0] == in->y[0]);
            assert_true(out->x[out->n - 1] == in->x[in->n - 1] && out->y[out->n - 1] == in->y[in->n - 1]);
        }
        ft_chain_free(out);
        ft_chain_free(in);
    }
}

/* Dutton's warning: negative UC on a narrow feature makes crossings; remove_loops takes them out. */
static void test_negative_uc_loops_repaired(void **state)
{
    (void)state;
    const double fjord[] = {0, 0, 10, 0, 10, 5, 5.6, 5, 5.2, 1, 4.8, 1, 4.4, 5, 0, 5};
    ft_chain *in = chain_of(fjord, 8, 1), *e = NULL, *out = NULL;
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 1.2;
    o.uc = -1.0;
    o.iterations = 2;
    o.allow_crossings = 1; /* the raw algorithm, which loops */
    assert_int_equal(ft_line_enhance(in, &o, &e), FT_OK);
    size_t before = crossings(e);
    print_message("fjord enhanced with UC = -1: %zu vertices, %zu crossings\n", e->n, before);
    assert_true(before > 0);
    assert_int_equal(ft_line_remove_loops(e, &out), FT_OK);
    assert_int_equal(crossings(out), 0);
    ft_chain_free(in);
    ft_chain_free(e);
    ft_chain_free(out);
}

static void test_bad_input(void **state)
{
    (void)state;
    const double l[] = {0, 0, 1, 0, 1, 1};
    ft_chain *in = chain_of(l, 3, 0), *out = NULL;
    ft_smooth_opts o = FT_SMOOTH_OPTS_DEFAULT;
    o.roundness = 0.0;
    expect_msg(ft_line_smooth(in, &o, &out), FT_E_INVALID, "roundness must be in (0,1], got 0");
    o.roundness = 0.5;
    o.passes = 0;
    expect_msg(ft_line_smooth(in, &o, &out), FT_E_INVALID, "smoothing passes must be in [1,64], got 0");
    o.passes = 1;
    o.st = 1.0;
    o.sm = 3.0;
    expect_msg(ft_line_smooth(in, &o, &out), FT_E_INVALID, "st must be >= sm, got st = 1 and sm = 3");
    in->x[1] = INFINITY;
    expect_msg(ft_line_simplify(in, 1.0, &out), FT_E_NUMERIC, "vertex 1 is not finite");
    expect_msg(ft_line_weed(in, 1.0, &out), FT_E_NUMERIC, "vertex 1 is not finite");
    size_t n;
    expect_msg(ft_line_count_self_intersections(in, &n), FT_E_NUMERIC, "vertex 1 is not finite");
    expect_msg(ft_line_remove_loops(in, &out), FT_E_NUMERIC, "vertex 1 is not finite");
    in->x[1] = 1.0;
    in->n = 1;
    expect_msg(ft_line_simplify(in, 1.0, &out), FT_E_INVALID, "chain has 1 vertices, at least 2 needed");
    expect_msg(ft_line_smooth(in, &o, &out), FT_E_INVALID, "chain has 1 vertices");
    expect_msg(ft_line_count_self_intersections(in, &n), FT_E_INVALID, "chain has 1 vertices");
    assert_null(out);
    ft_chain_free(in);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_smooth_chaikin_quarter_points),
        cmocka_unit_test(test_smooth_window),
        cmocka_unit_test(test_weed),
        cmocka_unit_test(test_weed_keep_shape),
        cmocka_unit_test(test_simplify_by_hand),
        cmocka_unit_test(test_simplify_band),
        cmocka_unit_test(test_count_by_hand),
        cmocka_unit_test(test_count_matches_brute_force),
        cmocka_unit_test(test_remove_loops),
        cmocka_unit_test(test_negative_uc_loops_repaired),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
