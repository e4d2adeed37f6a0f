/* fracterra — unit tests of src/contour/shrink.c and clean.c: polygon shrinking and growing with the four
 * corner joins (Misawa, Chiba & Saito, §2-3), and the removal of twists and loops (§4.4).
 *
 * Expected values are derived by hand from the geometry, never from the code under test:
 *  - inner parallel polygon of a convex polygon (no edge vanishing): every vertex of the shrunk polygon
 *    lies on two moved edge lines, its area is A - P d + d^2 sum_i cot(alpha_i / 2) (alpha_i the interior
 *    angles: each corner loses a kite of area d^2 cot(alpha_i / 2) beyond the strips P d); a regular n-gon
 *    of apothem a shrinks to the regular n-gon of apothem a - d, area n (a - d)^2 tan(pi / n);
 *  - square of side s shrunk by d: (s - 2d)^2 whatever the join (it has no reflex corner);
 *  - a square grown by d: (s + 2d)^2 with mitres, minus 4 d^2/2 with bevels, s^2 + 4 s d + pi d^2 with arcs
 *    (GEOS draws the arc as quad_segs chords per quarter, so pi d^2 becomes 2 q d^2 sin(pi / 2q)), and with
 *    the d' join one point on the diagonal at d' from the corner when d' < sqrt(2) d (the mitre corner's
 *    distance): the corner M, the moved edge ends A and B at d from M and the d' point P at t = d - d'/sqrt(2)
 *    from M along both axes bound the quadrilateral M A P B of area d t, which the join cuts off;
 *  - the L-shape [0,2a]^2 minus [a,2a]^2 shrunk by d < a/2: with mitres its moved edges meet in the L with
 *    corners (d,d), (2a-d,d), (2a-d,a-d), (a-d,a-d), (a-d,2a-d), (d,2a-d), area (2a-2d)^2 - a^2. At the
 *    reflex corner (a,a) the other joins keep more than the square notch corner at M = (a-d,a-d): the bevel
 *    the triangle M A B (d^2/2), the arc the square [a-d,a]^2 minus the quarter disc of radius d about (a,a)
 *    (d^2 - pi d^2/4, with chords d^2 - q d^2 sin(pi/2q)/2), the d' join (d' = 1.2 d < sqrt(2) d, the mitre
 *    point's distance) the quadrilateral M A P B of area d t, t = d - 1.2 d / sqrt(2).
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
#include "fracterra/io.h"
#include "ft_test_assert.h"

/* ---- helpers ------------------------------------------------------------------------------------ */

/* Results are noded on a grid of 1e-9 d (shrinking) or 1e-12 of the extent (cleaning): vertices move by
 * up to a grid cell, areas by about perimeter x cell. */
#define AREA_RTOL 1e-8
#define COORD_TOL(d) (2e-9 * fabs(d))
#define CLEAN_TOL 1e-9

static ft_chain *ring_of(const double *xy, size_t n)
{
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, n, 2, 1);
    assert_non_null(c);
    return c;
}

/* Appends a polygon (outer ring xy[0..n), optional hole hxy[0..hn)) to s. */
static void add_poly(ft_polygon_set *s, const double *xy, size_t n, const double *hxy, size_t hn)
{
    ft_chain **holes = NULL;
    if (hxy != NULL) {
        holes = malloc(sizeof *holes);
        assert_non_null(holes);
        holes[0] = ring_of(hxy, hn);
    }
    assert_int_equal(ft_polygon_set_add(s, ring_of(xy, n), holes, hxy ? 1 : 0), FT_OK);
}

static ft_polygon_set *set_of(const double *xy, size_t n)
{
    ft_polygon_set *s = ft_polygon_set_create();
    assert_non_null(s);
    add_poly(s, xy, n, NULL, 0);
    return s;
}

static void assert_valid(const ft_polygon_set *s)
{
    const char *why = NULL;
    int ok = ft_polygon_set_is_valid(s, &why);
    if (ok != 1)
        print_error("invalid result: %s\n", ok == 2 ? ft_last_error() : why ? why : "?");
    assert_int_equal(ok, 1);
}

/* Shrinks by d with a join (dprime for FT_JOIN_DPRIME), checks success and validity. */
static ft_polygon_set *shrink_join(const ft_polygon_set *in, double d, ft_contour_join join, double dprime)
{
    ft_shrink_opts o = FT_SHRINK_OPTS_DEFAULT;
    o.join = join;
    o.dprime = dprime;
    ft_polygon_set *out = NULL;
    int rc = ft_contour_shrink(in, d, &o, &out);
    if (rc != FT_OK)
        print_error("ft_contour_shrink(%s, d=%g): %s\n", ft_contour_join_name(join), d, ft_last_error());
    assert_int_equal(rc, FT_OK);
    assert_non_null(out);
    assert_valid(out);
    return out;
}

/* Distance from (x, y) to the nearest edge of a ring. */
static double dist_to_ring(const ft_chain *c, double x, double y)
{
    double best = INFINITY;
    for (size_t i = 0; i < c->n; i++) {
        size_t j = i + 1 == c->n ? 0 : i + 1;
        double ex = c->x[j] - c->x[i], ey = c->y[j] - c->y[i];
        double t = ((x - c->x[i]) * ex + (y - c->y[i]) * ey) / (ex * ex + ey * ey);
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, hypot(x - c->x[i] - t * ex, y - c->y[i] - t * ey));
    }
    return best;
}

static const ft_contour_join all_joins[] = {FT_JOIN_DPRIME, FT_JOIN_MITRE, FT_JOIN_BEVEL, FT_JOIN_ROUND};

/* Polygonal area of a quarter disc of radius d drawn with q chords (vertices on the arc). */
static double quarter_chords(double d, int q)
{
    return 0.5 * q * d * d * sin(M_PI / (2.0 * q));
}

/* ---- convex polygons ---------------------------------------------------------------------------- */

static void test_regular_64gon_round_is_exact_inner_offset(void **state)
{
    (void)state;
    const int n = 64;
    const double R = 10.0, d = 2.0;
    double xy[2 * 64];
    for (int i = 0; i < n; i++) {
        xy[2 * i] = 100.0 + R * cos(2 * M_PI * i / n);
        xy[2 * i + 1] = -50.0 + R * sin(2 * M_PI * i / n);
    }
    ft_polygon_set *in = set_of(xy, (size_t)n);
    double a = R * cos(M_PI / n);
    double expected = n * (a - d) * (a - d) * tan(M_PI / n);
    for (size_t k = 0; k < 2; k++) {
        ft_contour_join join = k == 0 ? FT_JOIN_ROUND : FT_JOIN_DPRIME;
        ft_polygon_set *out = shrink_join(in, d, join, 1.2);
        assert_int_equal(out->n, 1);
        assert_int_equal(out->polys[0].nholes, 0);
        const ft_chain *r = out->polys[0].outer;
        assert_true(r->n >= 64);
        for (size_t i = 0; i < r->n; i++)
            assert_near(dist_to_ring(in->polys[0].outer, r->x[i], r->y[i]), d, 2e-9 * d); /* noding grid 1e-9 d */
        assert_near(ft_polygon_set_area(out), expected, AREA_RTOL * expected);
        assert_int_equal(ft_polygon_set_within(out, in), 1);
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(in);
}

static void test_convex_hexagon_all_joins_match_parallel_polygon(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 6, 0, 9, 3, 8, 7, 3, 8, -1, 4};
    const double d = 1.0;
    ft_polygon_set *in = set_of(xy, 6);
    /* A - P d + d^2 sum cot(alpha_i / 2), cot(alpha/2) = tan(phi/2) = sin(phi) / (1 + cos(phi)), phi the
     * turning angle at the vertex (pi - alpha) */
    double A = 0, P = 0, corners = 0;
    for (int i = 0; i < 6; i++) {
        int j = (i + 1) % 6, h = (i + 5) % 6;
        A += 0.5 * (xy[2 * i] * xy[2 * j + 1] - xy[2 * j] * xy[2 * i + 1]);
        P += hypot(xy[2 * j] - xy[2 * i], xy[2 * j + 1] - xy[2 * i + 1]);
        double ux = xy[2 * i] - xy[2 * h], uy = xy[2 * i + 1] - xy[2 * h + 1];
        double vx = xy[2 * j] - xy[2 * i], vy = xy[2 * j + 1] - xy[2 * i + 1];
        double lu = hypot(ux, uy), lv = hypot(vx, vy);
        double s = (ux * vy - uy * vx) / (lu * lv), c = (ux * vx + uy * vy) / (lu * lv);
        assert_true(s > 0); /* convex */
        corners += s / (1 + c);
    }
    double expected = A - P * d + d * d * corners;
    for (size_t k = 0; k < 4; k++) {
        ft_polygon_set *out = shrink_join(in, d, all_joins[k], 1.2);
        assert_int_equal(out->n, 1);
        assert_int_equal(out->polys[0].outer->n, 6);
        /* round goes through GEOS, which offsets its input simplified by 1% of d */
        assert_near(ft_polygon_set_area(out), expected, 5e-3 * expected);
        assert_near(ft_polygon_set_area(out), expected, AREA_RTOL * expected);
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(in);
}

static void test_square_shrinks_to_square_with_every_join(void **state)
{
    (void)state;
    const double s = 10.0, d = 1.5;
    const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10};
    ft_polygon_set *in = set_of(xy, 4);
    for (size_t k = 0; k < 4; k++) {
        ft_polygon_set *out = shrink_join(in, d, all_joins[k], 1.2);
        assert_int_equal(out->n, 1);
        assert_near(ft_polygon_set_area(out), (s - 2 * d) * (s - 2 * d), AREA_RTOL * (s - 2 * d) * (s - 2 * d));
        double xmin, ymin, xmax, ymax;
        assert_int_equal(ft_chain_bbox(out->polys[0].outer, &xmin, &ymin, &xmax, &ymax), FT_OK);
        assert_near(xmin, d, COORD_TOL(d));
        assert_near(ymax, s - d, COORD_TOL(d));
        /* the outer ring is counter-clockwise */
        assert_true(ft_chain_signed_area(out->polys[0].outer) > 0);
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(in);
}

/* ---- reflex corners: the L-shape ---------------------------------------------------------------- */

static void test_l_shape_joins_match_analytic_areas(void **state)
{
    (void)state;
    const double a = 4.0, d = 1.0;
    const double xy[] = {0, 0, 2 * a, 0, 2 * a, a, a, a, a, 2 * a, 0, 2 * a};
    ft_polygon_set *in = set_of(xy, 6);
    const int q = 8; /* FT_SHRINK_OPTS_DEFAULT.quad_segs */
    double mitre = (2 * a - 2 * d) * (2 * a - 2 * d) - a * a;
    double t12 = d - 1.2 * d / sqrt(2.0);
    struct {
        ft_contour_join join;
        double dprime, area;
    } cases[] = {
        {FT_JOIN_MITRE, 1.2, mitre},
        {FT_JOIN_BEVEL, 1.2, mitre + 0.5 * d * d},
        {FT_JOIN_ROUND, 1.2, mitre + d * d - quarter_chords(d, q)},
        {FT_JOIN_DPRIME, 1.2, mitre + d * t12},
        {FT_JOIN_DPRIME, 1.4, mitre + d * (d - 1.4 * d / sqrt(2.0))},
        {FT_JOIN_DPRIME, 2.0, mitre}, /* 2 d > sqrt(2) d: the extension lines' intersection is nearer */
    };
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        ft_polygon_set *out = shrink_join(in, d, cases[k].join, cases[k].dprime);
        assert_int_equal(out->n, 1);
        assert_int_equal(out->polys[0].nholes, 0);
        assert_near(ft_polygon_set_area(out), cases[k].area, AREA_RTOL * cases[k].area);
        assert_int_equal(ft_polygon_set_within(out, in), 1);
        ft_polygon_set_free(out);
    }
    /* the d' point itself: on the bisector at 1.2 d from the reflex vertex (a, a) */
    ft_polygon_set *out = shrink_join(in, d, FT_JOIN_DPRIME, 1.2);
    const ft_chain *r = out->polys[0].outer;
    int found = 0;
    double pxy = a - 1.2 * d / sqrt(2.0);
    for (size_t i = 0; i < r->n; i++)
        if (fabs(r->x[i] - pxy) < COORD_TOL(d) && fabs(r->y[i] - pxy) < COORD_TOL(d))
            found++;
    assert_int_equal(found, 1);
    assert_int_equal(r->n, 8); /* 5 convex corners, and the moved edges' ends with the d' point between */
    ft_polygon_set_free(out);
    ft_polygon_set_free(in);
}

/* ---- growing ------------------------------------------------------------------------------------ */

static void test_square_grows_with_every_join(void **state)
{
    (void)state;
    const double s = 4.0, d = 1.0;
    const double xy[] = {0, 0, 4, 0, 4, 4, 0, 4};
    ft_polygon_set *in = set_of(xy, 4);
    const int q = 8;
    double t12 = d - 1.2 * d / sqrt(2.0);
    struct {
        ft_contour_join join;
        double area;
    } cases[] = {
        {FT_JOIN_MITRE, (s + 2 * d) * (s + 2 * d)},
        {FT_JOIN_BEVEL, (s + 2 * d) * (s + 2 * d) - 2 * d * d},
        {FT_JOIN_ROUND, s * s + 4 * s * d + 4 * quarter_chords(d, q)},
        {FT_JOIN_DPRIME, (s + 2 * d) * (s + 2 * d) - 4 * d * t12},
    };
    for (size_t k = 0; k < 4; k++) {
        ft_polygon_set *out = shrink_join(in, -d, cases[k].join, 1.2);
        assert_int_equal(out->n, 1);
        assert_near(ft_polygon_set_area(out), cases[k].area, AREA_RTOL * cases[k].area);
        assert_int_equal(ft_polygon_set_within(in, out), 1);
        ft_polygon_set_free(out);
    }
    /* the exact disc area is approached as the arcs get more chords */
    ft_shrink_opts o = FT_SHRINK_OPTS_DEFAULT;
    o.join = FT_JOIN_ROUND;
    o.quad_segs = 64;
    ft_polygon_set *out = NULL;
    assert_int_equal(ft_contour_shrink(in, -d, &o, &out), FT_OK);
    double exact = s * s + 4 * s * d + M_PI * d * d;
    assert_near(ft_polygon_set_area(out), exact, 1e-3 * M_PI * d * d);
    ft_polygon_set_free(out);
    ft_polygon_set_free(in);
}

static void test_grown_squares_merge(void **state)
{
    (void)state;
    const double a[] = {0, 0, 2, 0, 2, 2, 0, 2};
    const double b[] = {3, 0, 5, 0, 5, 2, 3, 2};
    const double c[] = {3, 2.5, 5, 2.5, 5, 4.5, 3, 4.5}; /* not aligned with a */
    const double d = 1.0, t12 = d - 1.2 * d / sqrt(2.0);
    ft_polygon_set *in = ft_polygon_set_create();
    add_poly(in, a, 4, NULL, 0);
    add_poly(in, b, 4, NULL, 0);
    /* shrinking keeps them apart, growing by 1 closes the gap of 1 between them */
    ft_polygon_set *apart = shrink_join(in, 0.25, FT_JOIN_DPRIME, 1.2);
    assert_int_equal(apart->n, 2);
    ft_polygon_set_free(apart);
    ft_polygon_set *m = shrink_join(in, -d, FT_JOIN_MITRE, 1.2);
    assert_int_equal(m->n, 1);
    assert_int_equal(m->polys[0].nholes, 0);
    assert_near(ft_polygon_set_area(m), 7.0 * 4.0, AREA_RTOL * 28);
    ft_polygon_set_free(m);
    /* with d' = 1.2 the four outer corners lose d t each, and where the squares meet (at x = 2.5, above
     * y = 2 and below y = 0) the two joins' segments from (2,3) to P = (2 + c, 2 + c) and from (3,3) to
     * (3 - c, 2 + c), c = 1.2 d / sqrt(2), leave a notch of base 1 (the gap) and height h = (1 - c) / (2 c):
     * the valley between two merged hills */
    double cc = 1.2 * d / sqrt(2.0), h = (1 - cc) / (2 * cc);
    m = shrink_join(in, -d, FT_JOIN_DPRIME, 1.2);
    assert_int_equal(m->n, 1);
    assert_near(ft_polygon_set_area(m), 7.0 * 4.0 - 4 * d * t12 - 2 * (0.5 * 1.0 * h), AREA_RTOL * 28);
    ft_polygon_set_free(m);
    /* a third square off the grid: all three meet in one polygon */
    add_poly(in, c, 4, NULL, 0);
    for (size_t k = 0; k < 4; k++) {
        m = shrink_join(in, -d, all_joins[k], 1.2);
        assert_int_equal(m->n, 1);
        assert_int_equal(ft_polygon_set_within(in, m), 1);
        ft_polygon_set_free(m);
    }
    ft_polygon_set_free(in);
}

/* ---- islands, vanishing, holes ---------------------------------------------------------------- */

static void test_dumbbell_splits_into_two_islands(void **state)
{
    (void)state;
    /* squares [0,4]^2 and [6,10]x[0,4] joined by the neck [4,6]x[1.5,2.5] of width 1 < 2 d */
    const double xy[] = {0, 0, 4, 0, 4, 1.5, 6, 1.5, 6, 0, 10, 0, 10, 4, 6, 4, 6, 2.5, 4, 2.5, 4, 4, 0, 4};
    const double d = 0.8;
    ft_polygon_set *in = set_of(xy, 12);
    ft_polygon_set *whole = shrink_join(in, 0.4, FT_JOIN_DPRIME, 1.2); /* 2 x 0.4 < 1: the neck stays */
    assert_int_equal(whole->n, 1);
    ft_polygon_set_free(whole);
    for (size_t k = 0; k < 4; k++) {
        ft_polygon_set *out = shrink_join(in, d, all_joins[k], 1.2);
        assert_int_equal(out->n, 2);
        double side = 4 - 2 * d;
        for (size_t i = 0; i < 2; i++) {
            double xmin, xmax;
            assert_int_equal(ft_chain_bbox(out->polys[i].outer, &xmin, NULL, &xmax, NULL), FT_OK);
            assert_true(xmax < 5.0 || xmin > 5.0); /* each island on its own side of the neck */
            double ai = fabs(ft_chain_signed_area(out->polys[i].outer));
            assert_true(ai >= side * side - AREA_RTOL * 16);
            assert_true(ai <= side * side + 0.5 * d * d); /* at most the notch corners come back */
        }
        if (all_joins[k] == FT_JOIN_MITRE)
            assert_near(ft_polygon_set_area(out), 2 * side * side, AREA_RTOL * 16);
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(in);
}

static void test_narrow_polygons_vanish(void **state)
{
    (void)state;
    const double strip[] = {0, 0, 10, 0, 10, 1.8, 0, 1.8}; /* narrower than 2 d */
    const double square[] = {4, 4, 6, 4, 6, 6, 4, 6};       /* side 2 < 2 x 1.5 */
    ft_polygon_set *in = set_of(strip, 4);
    ft_polygon_set *sq = set_of(square, 4);
    for (size_t k = 0; k < 4; k++) {
        ft_polygon_set *out = shrink_join(in, 1.0, all_joins[k], 1.2);
        assert_int_equal(out->n, 0);
        assert_true(ft_polygon_set_area(out) == 0.0);
        ft_polygon_set_free(out);
        out = shrink_join(sq, 1.5, all_joins[k], 1.2);
        assert_int_equal(out->n, 0);
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(sq);
    ft_polygon_set_free(in);
}

static void test_inverted_parts_vanish_even_without_min_area(void **state)
{
    (void)state;
    /* every corner's moved edges meet within both edges, yet the square of side 2 shrunk by 1.5 turns
     * inside out: nothing may be left, whatever the smallest face kept */
    const double square[] = {4, 4, 6, 4, 6, 6, 4, 6};
    const double cross[] = {0, 2, 2, 2, 2, 0, 3, 0, 3, 2, 5, 2, 5, 3, 3, 3, 3, 5, 2, 5, 2, 3, 0, 3};
    ft_polygon_set *sq = set_of(square, 4), *cr = set_of(cross, 12);
    ft_shrink_opts o = FT_SHRINK_OPTS_DEFAULT;
    o.min_area = 0.0;
    for (size_t k = 0; k < 4; k++) {
        o.join = all_joins[k];
        ft_polygon_set *out = NULL;
        assert_int_equal(ft_contour_shrink(sq, 1.5, &o, &out), FT_OK);
        assert_int_equal(out->n, 0);
        ft_polygon_set_free(out);
        /* a plus sign of arm width 1 shrunk by 0.6: its arms turn inside out and go; in the centre square
         * [2,3]^2 only the joins at its four reflex corners decide. Mitres (lines x, y = 2.6 and 2.4) and
         * d' points (0.72 along the diagonals, past the centre) leave nothing; bevels (x + y = 4.6 and its
         * mirror images) leave the diamond |x - 2.5| + |y - 2.5| <= 0.4 of area 0.32; arcs leave the
         * points farther than 0.6 from all four corners around the centre (2.5, 2.5) */
        assert_int_equal(ft_contour_shrink(cr, 0.6, &o, &out), FT_OK);
        assert_valid(out);
        if (all_joins[k] == FT_JOIN_MITRE || all_joins[k] == FT_JOIN_DPRIME) {
            assert_int_equal(out->n, 0);
        } else {
            assert_int_equal(out->n, 1);
            double x0, y0, x1, y1;
            assert_int_equal(ft_chain_bbox(out->polys[0].outer, &x0, &y0, &x1, &y1), FT_OK);
            assert_near(0.5 * (x0 + x1), 2.5, 1e-9);
            assert_near(0.5 * (y0 + y1), 2.5, 1e-9);
            if (all_joins[k] == FT_JOIN_BEVEL)
                assert_near(ft_polygon_set_area(out), 0.32, AREA_RTOL);
            else { /* exact: 1 - (4 quarter discs of radius r - the halves of the 4 lenses where
                    * neighbouring discs, centres 1 apart, overlap): about 0.049. GEOS's chords lie
                    * inside the arcs, so it keeps a little more. */
                double r = 0.6, lens = 2 * r * r * acos(0.5 / r) - 0.5 * sqrt(4 * r * r - 1);
                double exact = 1.0 - (M_PI * r * r - 4 * 0.5 * lens);
                assert_true(ft_polygon_set_area(out) >= exact);
                assert_true(ft_polygon_set_area(out) <= 1.1 * exact);
            }
        }
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(sq);
    ft_polygon_set_free(cr);
}

static void test_hole_grows_when_polygon_shrinks(void **state)
{
    (void)state;
    const double outer[] = {0, 0, 10, 0, 10, 10, 0, 10};
    const double hole[] = {4, 4, 6, 4, 6, 6, 4, 6}; /* given counter-clockwise: add makes it clockwise */
    const double d = 1.0, t12 = d - 1.2 * d / sqrt(2.0);
    const int q = 8;
    ft_polygon_set *in = ft_polygon_set_create();
    add_poly(in, outer, 4, hole, 4);
    assert_true(ft_chain_signed_area(in->polys[0].holes[0]) < 0);
    /* the outer ring becomes [1,9]^2 (64); the hole [3,7]^2 (16) less what the joins give back at its
     * four corners, which are reflex corners of the polygon */
    struct {
        ft_contour_join join;
        double area;
    } cases[] = {
        {FT_JOIN_MITRE, 64 - 16},
        {FT_JOIN_BEVEL, 64 - (16 - 4 * 0.5 * d * d)},
        {FT_JOIN_ROUND, 64 - (4 + 4 * 2 * d + 4 * quarter_chords(d, q))},
        {FT_JOIN_DPRIME, 64 - (16 - 4 * d * t12)},
    };
    for (size_t k = 0; k < 4; k++) {
        ft_polygon_set *out = shrink_join(in, d, cases[k].join, 1.2);
        assert_int_equal(out->n, 1);
        assert_int_equal(out->polys[0].nholes, 1);
        assert_true(ft_chain_signed_area(out->polys[0].holes[0]) < 0);
        assert_near(ft_polygon_set_area(out), cases[k].area, AREA_RTOL * cases[k].area);
        assert_int_equal(ft_polygon_set_within(out, in), 1);
        ft_polygon_set_free(out);
    }
    /* shrunk by 2.5 the ring [2.5,7.5]^2 minus the hole [1.5,8.5]^2 (mitre) has nothing left */
    ft_polygon_set *gone = shrink_join(in, 2.5, FT_JOIN_MITRE, 1.2);
    assert_int_equal(gone->n, 0);
    ft_polygon_set_free(gone);
    /* grown by 1.5 the hole of side 2 closes */
    ft_polygon_set *filled = shrink_join(in, -1.5, FT_JOIN_DPRIME, 1.2);
    assert_int_equal(filled->n, 1);
    assert_int_equal(filled->polys[0].nholes, 0);
    ft_polygon_set_free(filled);
    ft_polygon_set_free(in);
}

/* ---- the d' join against GEOS's mitre and the order of the joins ------------------------------------ */

static void test_star_join_order_and_dprime_limit(void **state)
{
    (void)state;
    /* a 12-pointed star: 12 reflex vertices where the shrunk curve leaves gaps */
    double xy[48];
    for (int i = 0; i < 24; i++) {
        double r = i % 2 ? 6.0 : 10.0, th = 2 * M_PI * i / 24.0;
        xy[2 * i] = r * cos(th);
        xy[2 * i + 1] = r * sin(th);
    }
    ft_polygon_set *in = set_of(xy, 24);
    const double d = 0.5;
    double a_mitre, a_round, a_bevel, a_d1, a_dinf;
    ft_polygon_set *o;
    o = shrink_join(in, d, FT_JOIN_MITRE, 1.2), a_mitre = ft_polygon_set_area(o), ft_polygon_set_free(o);
    o = shrink_join(in, d, FT_JOIN_ROUND, 1.2), a_round = ft_polygon_set_area(o), ft_polygon_set_free(o);
    o = shrink_join(in, d, FT_JOIN_BEVEL, 1.2), a_bevel = ft_polygon_set_area(o), ft_polygon_set_free(o);
    o = shrink_join(in, d, FT_JOIN_DPRIME, 1.0), a_d1 = ft_polygon_set_area(o), ft_polygon_set_free(o);
    o = shrink_join(in, d, FT_JOIN_DPRIME, 1e6), a_dinf = ft_polygon_set_area(o), ft_polygon_set_free(o);
    /* extension lines cut the most; the arc is inscribed between them and the chord; d' = d puts one
     * point on the arc's middle, so its two segments lie inside the arc */
    assert_true(a_mitre < a_round);
    assert_true(a_round < a_d1);
    assert_true(a_d1 < a_bevel);
    /* a d' beyond every mitre distance is the mitre join */
    assert_near(a_dinf, a_mitre, AREA_RTOL * a_mitre);
    ft_polygon_set_free(in);
}

/* ---- clean: twists and loops ----------------------------------------------------------------- */

static void test_clean_figure_eight_keeps_positive_lobe(void **state)
{
    (void)state;
    /* (0,-2) -> (3,1) -> (3,-1) -> (0,2): the edges cross at (2,0); the left lobe (0,-2),(2,0),(0,2) runs
     * counter-clockwise (area 4), the right one (2,0),(3,1),(3,-1) clockwise (area 1) */
    const double xy[] = {0, -2, 3, 1, 3, -1, 0, 2};
    for (int rev = 0; rev < 2; rev++) {
        ft_polygon_set *in = set_of(xy, 4);
        if (rev) /* reversed, add makes the larger lobe counter-clockwise again */
            ft_chain_reverse(in->polys[0].outer);
        ft_polygon_set *out = NULL;
        assert_int_equal(ft_contour_clean(in, 0.0, &out), FT_OK);
        assert_valid(out);
        assert_int_equal(out->n, 1);
        assert_near(ft_polygon_set_area(out), 4.0, CLEAN_TOL);
        double xmin, xmax;
        assert_int_equal(ft_chain_bbox(out->polys[0].outer, &xmin, NULL, &xmax, NULL), FT_OK);
        assert_near(xmin, 0.0, CLEAN_TOL);
        assert_near(xmax, 2.0, CLEAN_TOL);
        ft_polygon_set_free(out);
        ft_polygon_set_free(in);
    }
}

static void test_clean_bow_tie_of_equal_lobes(void **state)
{
    (void)state;
    /* (0,0) -> (4,2) -> (4,0) -> (0,2): lobes of area 2 each, the left one counter-clockwise, the right
     * one clockwise; the total area is 0, so the orientation is kept as given */
    const double xy[] = {0, 0, 4, 2, 4, 0, 0, 2};
    ft_polygon_set *in = set_of(xy, 4);
    ft_polygon_set *out = NULL;
    assert_int_equal(ft_contour_clean(in, 0.0, &out), FT_OK);
    assert_valid(out);
    assert_int_equal(out->n, 1);
    assert_near(ft_polygon_set_area(out), 2.0, CLEAN_TOL);
    double xmax;
    assert_int_equal(ft_chain_bbox(out->polys[0].outer, NULL, NULL, &xmax, NULL), FT_OK);
    assert_near(xmax, 2.0, CLEAN_TOL);
    ft_polygon_set_free(out);
    ft_polygon_set_free(in);
}

static void test_clean_removes_small_twisted_loop(void **state)
{
    (void)state;
    /* the bottom edge runs to (6,0), down and back, and up across itself at (5,0): a clockwise loop of
     * area 1 below the square; what is left is [0,10]x[0.5,10] plus [0,5]x[0,0.5] = 97.5 */
    const double xy[] = {0, 0, 6, 0, 6, -1, 5, -1, 5, 0.5, 10, 0.5, 10, 10, 0, 10};
    ft_polygon_set *in = set_of(xy, 8);
    assert_near(ft_polygon_set_area(in), 96.5, CLEAN_TOL);
    assert_int_equal(ft_polygon_set_is_valid(in, NULL), 0);
    ft_polygon_set *out = NULL;
    assert_int_equal(ft_contour_clean(in, 0.0, &out), FT_OK);
    assert_valid(out);
    assert_int_equal(out->n, 1);
    assert_int_equal(out->polys[0].nholes, 0);
    assert_near(ft_polygon_set_area(out), 97.5, CLEAN_TOL);
    ft_polygon_set_free(out);
    ft_polygon_set_free(in);

    /* a valid set is unchanged; a tiny island under min_area goes */
    const double big[] = {0, 0, 10, 0, 10, 10, 0, 10}, tiny[] = {20, 0, 20.5, 0, 20.5, 0.5, 20, 0.5};
    in = ft_polygon_set_create();
    add_poly(in, big, 4, NULL, 0);
    add_poly(in, tiny, 4, NULL, 0);
    assert_int_equal(ft_contour_clean(in, 0.0, &out), FT_OK);
    assert_int_equal(out->n, 2);
    assert_near(ft_polygon_set_area(out), 100.25, CLEAN_TOL);
    ft_polygon_set_free(out);
    assert_int_equal(ft_contour_clean(in, 0.5, &out), FT_OK);
    assert_int_equal(out->n, 1);
    assert_near(ft_polygon_set_area(out), 100.0, CLEAN_TOL);
    ft_polygon_set_free(out);
    assert_int_equal(ft_contour_clean(in, 1000.0, &out), FT_OK);
    assert_int_equal(out->n, 0);
    ft_polygon_set_free(out);
    ft_polygon_set_free(in);
}

static void test_clean_merges_overlaps(void **state)
{
    (void)state;
    /* two overlapping squares (invalid as a set) wind twice over their overlap: one polygon, area 7 */
    const double a[] = {0, 0, 2, 0, 2, 2, 0, 2}, b[] = {1, 1, 3, 1, 3, 3, 1, 3};
    ft_polygon_set *in = ft_polygon_set_create();
    add_poly(in, a, 4, NULL, 0);
    add_poly(in, b, 4, NULL, 0);
    assert_int_equal(ft_polygon_set_is_valid(in, NULL), 0);
    ft_polygon_set *out = NULL;
    assert_int_equal(ft_contour_clean(in, 0.0, &out), FT_OK);
    assert_valid(out);
    assert_int_equal(out->n, 1);
    assert_near(ft_polygon_set_area(out), 7.0, CLEAN_TOL);
    ft_polygon_set_free(out);
    /* shrinking works on the same invalid input (through GEOS and through the d' curves alike) */
    for (size_t k = 0; k < 4; k++) {
        out = shrink_join(in, 0.25, all_joins[k], 1.2);
        assert_int_equal(out->n, 1);
        ft_polygon_set_free(out);
    }
    ft_polygon_set_free(in);
}

/* ---- repeated shrinking of a rough ring ----------------------------------------------------------- */

static void test_repeated_shrinking_stays_valid_and_nested(void **state)
{
    (void)state;
    /* a rough 400-vertex ring: radius modulated by several harmonics */
    enum { N = 400 };
    double xy[2 * N];
    for (int i = 0; i < N; i++) {
        double th = 2 * M_PI * i / N;
        double r = 100 * (1 + 0.25 * sin(3 * th) + 0.1 * cos(11 * th + 1) + 0.04 * sin(37 * th) + 0.02 * cos(97 * th));
        xy[2 * i] = r * cos(th);
        xy[2 * i + 1] = r * sin(th);
    }
    ft_polygon_set *cur = set_of(xy, N);
    double prev_area = ft_polygon_set_area(cur);
    int levels = 0;
    while (cur->n > 0 && levels < 40) {
        ft_polygon_set *next = shrink_join(cur, 3.0, FT_JOIN_DPRIME, 1.4);
        assert_int_equal(ft_polygon_set_within(next, cur), 1);
        double a = ft_polygon_set_area(next);
        assert_true(a < prev_area);
        prev_area = a;
        ft_polygon_set_free(cur);
        cur = next;
        levels++;
    }
    /* the smallest radius is about 100 (1 - 0.41) = 59, the largest 141: it vanishes within 40 levels of
     * 3 but not before the inscribed disc (radius >= 59 - a little for the roughness) is used up */
    assert_int_equal(cur->n, 0);
    assert_true(levels >= 15);
    ft_polygon_set_free(cur);
}

/* ---- offset curves of negative signed area ----------------------------------------------------------- */

/* The square [0,100]^2 with 4 spikes of width 1 and length 300 on its top edge, shrunk by d = 10 with the
 * d' join (d' = 1.2 d). Each spike, narrower than 2 d, turns inside out in the raw offset curve and adds
 * about -(2 d - 1) 300 = -5700 to its signed area, so the curve's signed area is negative (< 6400 -
 * 4 x 5700) although it winds +1 around most of the square. The mitre region is [10,90]^2 (the spikes,
 * 20 apart and 20 from the corners, meet the top edge's moved line at y = 90 and vanish); the d' join adds
 * at most the quadrilateral M A P B of area d t, t = d - d'/sqrt(2), at each of the 8 spike base corners
 * (see the L-shape test). So 80^2 <= area <= 80^2 + 8 d t. */
static void test_dprime_curve_of_negative_area_keeps_region(void **state)
{
    (void)state;
    double xy[2 * 20];
    size_t n = 0;
    xy[n++] = 0, xy[n++] = 0, xy[n++] = 100, xy[n++] = 0, xy[n++] = 100, xy[n++] = 100;
    for (int k = 3; k >= 0; k--) { /* right to left along the top edge */
        double xs = 20.0 + 20.0 * k;
        xy[n++] = xs + 1, xy[n++] = 100, xy[n++] = xs + 1, xy[n++] = 400;
        xy[n++] = xs, xy[n++] = 400, xy[n++] = xs, xy[n++] = 100;
    }
    xy[n++] = 0, xy[n++] = 100;
    ft_polygon_set *in = set_of(xy, n / 2);
    const double d = 10.0, t = d - 1.2 * d / sqrt(2.0);
    ft_polygon_set *out = shrink_join(in, d, FT_JOIN_DPRIME, 1.2);
    double a = ft_polygon_set_area(out);
    assert_int_equal(out->n, 1);
    assert_true(a >= 6400.0 * (1.0 - AREA_RTOL));
    assert_true(a <= (6400.0 + 8.0 * d * t) * (1.0 + AREA_RTOL));
    ft_polygon_set_free(out);
    ft_polygon_set_free(in);
}

/* The Newfoundland coastline (GSHHG, UTM 21N metres, 64,193 vertices), every 16th vertex kept (4,013,
 * for speed; the same fjords and peninsulas at 8-20 km), shrunk by 5-20 km: the d' curves of 12 and
 * 20 km have a negative signed area (their inverted fjord loops outweigh the island) and came out empty.
 * The d' polyline b P a of a gap corner lies in the triangle of the bevel chord b a and the mitre point
 * (P is on the bisector between the chord and the mitre point), so mitre <= d' <= bevel; GEOS moves the
 * mitre and bevel results by up to 1% of d (its input simplification), and the mitre limit squares the
 * sharpest spikes off: 5% margins. The d' result is also within 5% above the round one (the arc of radius
 * d against P at 1.2 d). */
static void test_dprime_newfoundland_between_mitre_and_bevel(void **state)
{
    (void)state;
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    ft_layer *l = NULL;
    assert_int_equal(ft_io_read_layer(FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson", &lo, &l), FT_OK);
    ft_polygon_set *in = NULL;
    assert_int_equal(ft_polygon_set_from_layer(l, &in), FT_OK);
    ft_layer_free(l);
    assert_int_equal(in->n, 1);
    ft_chain *c = in->polys[0].outer;
    assert_int_equal(c->n, 64193);
    size_t m = 0;
    for (size_t i = 0; i < c->n; i += 16, m++)
        c->x[m] = c->x[i], c->y[m] = c->y[i];
    c->n = m;
    const double ds[] = {5000, 8000, 12000, 20000};
    for (size_t k = 0; k < sizeof ds / sizeof ds[0]; k++) {
        ft_polygon_set *dp = shrink_join(in, ds[k], FT_JOIN_DPRIME, 1.2);
        ft_polygon_set *mi = shrink_join(in, ds[k], FT_JOIN_MITRE, 1.2);
        ft_polygon_set *be = shrink_join(in, ds[k], FT_JOIN_BEVEL, 1.2);
        ft_polygon_set *ro = shrink_join(in, ds[k], FT_JOIN_ROUND, 1.2);
        double a = ft_polygon_set_area(dp), am = ft_polygon_set_area(mi), ab = ft_polygon_set_area(be);
        double ar = ft_polygon_set_area(ro);
        if (!(dp->n > 0 && a >= 0.95 * am && a <= 1.05 * ab && a <= 1.05 * ar))
            print_error("d = %g: d' area %g, mitre %g, bevel %g, round %g\n", ds[k], a, am, ab, ar);
        assert_true(dp->n > 0);
        assert_true(a >= 0.95 * am);
        assert_true(a <= 1.05 * ab);
        assert_true(a <= 1.05 * ar);
        assert_int_equal(ft_polygon_set_within(dp, in), 1);
        ft_polygon_set_free(dp);
        ft_polygon_set_free(mi);
        ft_polygon_set_free(be);
        ft_polygon_set_free(ro);
    }
    ft_polygon_set_free(in);
}

/* ---- determinism, errors ----------------------------------------------------------------------- */

static void test_same_input_same_output(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 2, 0, 2, 1, 3, 1, 3, 0, 5, 0, 5, 3, 0, 3};
    ft_polygon_set *in = set_of(xy, 8);
    ft_polygon_set *a = shrink_join(in, 0.3, FT_JOIN_DPRIME, 1.2);
    ft_polygon_set *b = shrink_join(in, 0.3, FT_JOIN_DPRIME, 1.2);
    assert_int_equal(a->n, b->n);
    for (size_t i = 0; i < a->n; i++) {
        assert_int_equal(a->polys[i].outer->n, b->polys[i].outer->n);
        assert_memory_equal(a->polys[i].outer->x, b->polys[i].outer->x, a->polys[i].outer->n * sizeof(double));
        assert_memory_equal(a->polys[i].outer->y, b->polys[i].outer->y, a->polys[i].outer->n * sizeof(double));
    }
    ft_polygon_set_free(a);
    ft_polygon_set_free(b);
    ft_polygon_set_free(in);
}

static void test_bad_input_is_named(void **state)
{
    (void)state;
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    ft_polygon_set *in = set_of(sq, 4);
    ft_polygon_set *out = (ft_polygon_set *)1;
    ft_shrink_opts o = FT_SHRINK_OPTS_DEFAULT;
    assert_error_names(ft_contour_shrink(in, 0.0, &o, &out), FT_E_INVALID, "got 0");
    assert_null(out);
    assert_error_names(ft_contour_shrink(in, NAN, &o, &out), FT_E_INVALID, "nan");
    assert_error_names(ft_contour_shrink(in, INFINITY, &o, &out), FT_E_INVALID, "inf");
    o.join = (ft_contour_join)7;
    assert_error_names(ft_contour_shrink(in, 0.1, &o, &out), FT_E_INVALID, "unknown join 7");
    o = (ft_shrink_opts)FT_SHRINK_OPTS_DEFAULT;
    o.dprime = 0.5;
    assert_error_names(ft_contour_shrink(in, 0.1, &o, &out), FT_E_INVALID, "dprime");
    o = (ft_shrink_opts)FT_SHRINK_OPTS_DEFAULT;
    o.join = FT_JOIN_ROUND;
    o.quad_segs = 0;
    assert_error_names(ft_contour_shrink(in, 0.1, &o, &out), FT_E_INVALID, "quad_segs");
    o = (ft_shrink_opts)FT_SHRINK_OPTS_DEFAULT;
    o.min_area = -1;
    assert_error_names(ft_contour_shrink(in, 0.1, &o, &out), FT_E_INVALID, "min_area");
    assert_error_names(ft_contour_shrink(NULL, 0.1, NULL, &out), FT_E_INVALID, "NULL");
    assert_error_names(ft_contour_shrink(in, 0.1, NULL, NULL), FT_E_INVALID, "NULL");

    /* NaN coordinate (set built by hand: ft_polygon_set_add refuses it) */
    in->polys[0].outer->x[2] = NAN;
    assert_error_names(ft_contour_shrink(in, 0.1, NULL, &out), FT_E_INVALID, "polygon 0 outer ring: vertex 2");
    in->polys[0].outer->x[2] = 1;
    /* fewer than 3 distinct vertices, zero area */
    const double two[] = {0, 0, 1, 0, 1, 0, 0, 0}, flat[] = {0, 0, 1, 0, 2, 0};
    ft_polygon_set *bad = set_of(two, 4);
    assert_error_names(ft_contour_shrink(bad, 0.1, NULL, &out), FT_E_INVALID, "2 distinct vertices");
    ft_polygon_set_free(bad);
    bad = set_of(flat, 3);
    assert_error_names(ft_contour_shrink(bad, 0.1, NULL, &out), FT_E_INVALID, "zero area");
    ft_polygon_set_free(bad);
    /* a hole of one polygon among several is named */
    const double hole[] = {0.2, 0.2, 0.2, 0.2, 0.4, 0.4};
    bad = ft_polygon_set_create();
    add_poly(bad, sq, 4, NULL, 0);
    add_poly(bad, sq, 4, hole, 3);
    assert_error_names(ft_contour_shrink(bad, 0.1, NULL, &out), FT_E_INVALID, "polygon 1 hole 0");
    ft_polygon_set_free(bad);

    /* an empty set shrinks to an empty set */
    ft_polygon_set *empty = ft_polygon_set_create();
    assert_int_equal(ft_contour_shrink(empty, 1.0, NULL, &out), FT_OK);
    assert_int_equal(out->n, 0);
    ft_polygon_set_free(out);
    assert_int_equal(ft_contour_clean(empty, 0.0, &out), FT_OK);
    assert_int_equal(out->n, 0);
    ft_polygon_set_free(out);
    ft_polygon_set_free(empty);

    assert_error_names(ft_contour_clean(in, -1.0, &out), FT_E_INVALID, "min_area");
    assert_error_names(ft_contour_clean(in, NAN, &out), FT_E_INVALID, "min_area");
    assert_error_names(ft_contour_clean(NULL, 0.0, &out), FT_E_INVALID, "NULL");
    in->polys[0].outer->y[1] = INFINITY;
    assert_error_names(ft_contour_clean(in, 0.0, &out), FT_E_INVALID, "polygon 0 outer ring");
    ft_polygon_set_free(in);
}

static void test_join_names(void **state)
{
    (void)state;
    ft_contour_join j;
    const char *names[] = {"dprime", "mitre", "bevel", "round"};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(ft_contour_join_parse(names[k], &j), FT_OK);
        assert_int_equal((int)j, k);
        assert_string_equal(ft_contour_join_name(j), names[k]);
    }
    assert_int_equal(ft_contour_join_parse("miter", &j), FT_OK);
    assert_int_equal(j, FT_JOIN_MITRE);
    assert_int_equal(ft_contour_join_parse("Round", &j), FT_OK);
    assert_int_equal(j, FT_JOIN_ROUND);
    assert_error_names(ft_contour_join_parse("square", &j), FT_E_INVALID, "'square'");
    assert_error_names(ft_contour_join_parse(NULL, &j), FT_E_INVALID, "NULL");
    assert_string_equal(ft_contour_join_name((ft_contour_join)9), "unknown");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_regular_64gon_round_is_exact_inner_offset),
        cmocka_unit_test(test_convex_hexagon_all_joins_match_parallel_polygon),
        cmocka_unit_test(test_square_shrinks_to_square_with_every_join),
        cmocka_unit_test(test_l_shape_joins_match_analytic_areas),
        cmocka_unit_test(test_square_grows_with_every_join),
        cmocka_unit_test(test_grown_squares_merge),
        cmocka_unit_test(test_dumbbell_splits_into_two_islands),
        cmocka_unit_test(test_narrow_polygons_vanish),
        cmocka_unit_test(test_inverted_parts_vanish_even_without_min_area),
        cmocka_unit_test(test_hole_grows_when_polygon_shrinks),
        cmocka_unit_test(test_star_join_order_and_dprime_limit),
        cmocka_unit_test(test_clean_figure_eight_keeps_positive_lobe),
        cmocka_unit_test(test_clean_bow_tie_of_equal_lobes),
        cmocka_unit_test(test_clean_removes_small_twisted_loop),
        cmocka_unit_test(test_clean_merges_overlaps),
        cmocka_unit_test(test_repeated_shrinking_stays_valid_and_nested),
        cmocka_unit_test(test_dprime_curve_of_negative_area_keeps_region),
        cmocka_unit_test(test_dprime_newfoundland_between_mitre_and_bevel),
        cmocka_unit_test(test_same_input_same_output),
        cmocka_unit_test(test_bad_input_is_named),
        cmocka_unit_test(test_join_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
