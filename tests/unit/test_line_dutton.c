/* fracterra — unit tests of line/dutton.c: Dutton's (1981) fractal enhancement. The standard position
 * (SD angle, leg ratio, side), UC = 0 / 1 / -1 / 0.5, the ST/SM window segment by segment, 2n - 1
 * vertices, fixed end points, rings, the divider dimension after 6 iterations, bad input.
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
#include "test_line.h"

static const double PI = 3.14159265358979323846;

/* A random walk of n vertices with steps in [0.5, 1.5] and turns up to +-100 degrees (seeded). */
static ft_chain *wiggly(size_t n, uint64_t seed, int closed)
{
    ft_chain *c = ft_chain_create(n, closed);
    assert_non_null(c);
    ft_rng *r = ft_rng_create(seed, 0);
    assert_non_null(r);
    double x = 0, y = 0, dir = 0;
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(ft_chain_push(c, x, y), FT_OK);
        dir += (ft_rng_uniform(r) - 0.5) * 2.0 * (100.0 * PI / 180.0);
        double step = 0.5 + ft_rng_uniform(r);
        x += step * cos(dir);
        y += step * sin(dir);
    }
    ft_rng_free(r);
    return c;
}

/* A regular polygon of n vertices, radius 10, with radii jittered by +-30% (seeded). */
static ft_chain *blob(size_t n, uint64_t seed)
{
    ft_chain *c = ft_chain_create(n, 1);
    ft_rng *r = ft_rng_create(seed, 1);
    for (size_t i = 0; i < n; i++) {
        double a = 2.0 * PI * (double)i / (double)n, rad = 10.0 * (0.7 + 0.6 * ft_rng_uniform(r));
        assert_int_equal(ft_chain_push(c, rad * cos(a), rad * sin(a)), FT_OK);
    }
    ft_rng_free(r);
    return c;
}

static ft_chain *enhance(const ft_chain *in, double sd, double uc, double st, double sm, int iterations)
{
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = sd;
    o.uc = uc;
    o.st = st;
    o.sm = sm;
    o.iterations = iterations;
    o.literal_sd = 1;      /* these tests check Dutton's literal geometry, */
    o.allow_crossings = 1; /* move by move */
    ft_chain *out = NULL;
    int rc = ft_line_enhance(in, &o, &out);
    if (rc != FT_OK)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    assert_non_null(out);
    return out;
}

static double cross3(double ax, double ay, double bx, double by, double cx, double cy)
{
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

static double dist(double ax, double ay, double bx, double by)
{
    return hypot(bx - ax, by - ay);
}

static void test_apex_angle(void **state)
{
    (void)state;
    assert_near(ft_dutton_apex_angle(1.0), PI, 1e-15);
    assert_near(ft_dutton_apex_angle(2.0), PI / 2, 1e-15);
    double a = acos(pow(2.0, 1.0 / 1.3 - 1.0));
    assert_near(ft_dutton_apex_angle(1.3), PI - 2 * a, 1e-15);
    assert_near(log(2.0) / log(2.0 * cos(a)), 1.3, 1e-12); /* the midpoint generator's D */
    assert_true(isnan(ft_dutton_apex_angle(2.7)));
    assert_true(isnan(ft_dutton_apex_angle(NAN)));
}

/* UC = 1: each moved junction M1-V'-M2 has the SD angle, legs in the ratio |PV| / |VN|, V' on V's side. */
static void check_standard_junctions(double sd, uint64_t seed)
{
    ft_chain *in = wiggly(200, seed, 0);
    ft_chain *out = enhance(in, sd, 1.0, INFINITY, 0.0, 1);
    assert_int_equal(out->n, 2 * in->n - 1);
    double theta = ft_dutton_apex_angle(sd);
    for (size_t i = 1; i + 1 < in->n; i++) {
        double px = in->x[i - 1], py = in->y[i - 1], vx = in->x[i], vy = in->y[i], nx = in->x[i + 1],
               ny = in->y[i + 1];
        double m1x = out->x[2 * i - 1], m1y = out->y[2 * i - 1], wx = out->x[2 * i], wy = out->y[2 * i];
        double m2x = out->x[2 * i + 1], m2y = out->y[2 * i + 1];
        assert_true(m1x == 0.5 * (px + vx) && m1y == 0.5 * (py + vy));
        assert_true(m2x == 0.5 * (vx + nx) && m2y == 0.5 * (vy + ny));
        double ax = m1x - wx, ay = m1y - wy, bx = m2x - wx, by = m2y - wy;
        double angle = atan2(fabs(ax * by - ay * bx), ax * bx + ay * by);
        assert_near(angle, theta, 1e-9);
        double ratio = dist(px, py, vx, vy) / dist(vx, vy, nx, ny);
        assert_near(dist(m1x, m1y, wx, wy) / dist(wx, wy, m2x, m2y), ratio, 1e-9 * ratio);
        double side_v = cross3(m1x, m1y, m2x, m2y, vx, vy), side_w = cross3(m1x, m1y, m2x, m2y, wx, wy);
        if (sd > 1.0)
            assert_true(side_v * side_w > 0.0);
    }
    ft_chain_free(in);
    ft_chain_free(out);
}

static void test_uc1_standard_angle_ratio_side(void **state)
{
    (void)state;
    const double sds[] = {1.05, 1.3, 1.5, 1.7, 1.9, 2.0};
    for (size_t k = 0; k < sizeof sds / sizeof sds[0]; k++)
        for (uint64_t seed = 1; seed <= 3; seed++)
            check_standard_junctions(sds[k], seed);
}

/* SD = 1 puts V on the base M1 M2, dividing it in V's ratio. */
static void test_sd1_straightens(void **state)
{
    (void)state;
    ft_chain *in = wiggly(50, 9, 0);
    ft_chain *out = enhance(in, 1.0, 1.0, INFINITY, 0.0, 1);
    for (size_t i = 1; i + 1 < in->n; i++) {
        double m1x = out->x[2 * i - 1], m1y = out->y[2 * i - 1], m2x = out->x[2 * i + 1], m2y = out->y[2 * i + 1];
        double b = dist(m1x, m1y, m2x, m2y);
        assert_near(cross3(m1x, m1y, m2x, m2y, out->x[2 * i], out->y[2 * i]) / b, 0.0, 1e-9);
        double a = dist(in->x[i - 1], in->y[i - 1], in->x[i], in->y[i]);
        double c = dist(in->x[i], in->y[i], in->x[i + 1], in->y[i + 1]);
        assert_near(dist(m1x, m1y, out->x[2 * i], out->y[2 * i]), b * a / (a + c), 1e-9);
    }
    ft_chain_free(in);
    ft_chain_free(out);
}

/* Distance from (x, y) to the polyline c. */
static double dist_to_chain(const ft_chain *c, double x, double y)
{
    double best = INFINITY;
    size_t nseg = ft_chain_segments(c);
    for (size_t s = 0; s < nseg; s++) {
        size_t t = (s + 1) % c->n;
        double dx = c->x[t] - c->x[s], dy = c->y[t] - c->y[s], l2 = dx * dx + dy * dy;
        double u = l2 > 0 ? ((x - c->x[s]) * dx + (y - c->y[s]) * dy) / l2 : 0.0;
        u = u < 0 ? 0 : (u > 1 ? 1 : u);
        best = fmin(best, dist(x, y, c->x[s] + u * dx, c->y[s] + u * dy));
    }
    return best;
}

static void test_uc0_on_input_polyline(void **state)
{
    (void)state;
    ft_chain *in = wiggly(120, 4, 0);
    ft_chain *out = enhance(in, 1.5, 0.0, INFINITY, 0.0, 3);
    assert_int_equal(out->n, 8 * (in->n - 1) + 1);
    for (size_t k = 0; k < out->n; k++)
        assert_near(dist_to_chain(in, out->x[k], out->y[k]), 0.0, 1e-12);
    for (size_t i = 0; i < in->n; i++)
        assert_true(out->x[8 * i] == in->x[i] && out->y[8 * i] == in->y[i]);
    ft_chain_free(in);
    ft_chain_free(out);
}

/* UC = -1 displaces each vertex by the opposite of UC = 1; UC = 0.5 by half of it. */
static void test_uc_mirror_and_fraction(void **state)
{
    (void)state;
    ft_chain *in = wiggly(150, 5, 0);
    ft_chain *pos = enhance(in, 1.4, 1.0, INFINITY, 0.0, 1), *neg = enhance(in, 1.4, -1.0, INFINITY, 0.0, 1);
    ft_chain *half = enhance(in, 1.4, 0.5, INFINITY, 0.0, 1);
    size_t moved = 0;
    for (size_t i = 0; i < in->n; i++) {
        double dxp = pos->x[2 * i] - in->x[i], dyp = pos->y[2 * i] - in->y[i];
        double dxn = neg->x[2 * i] - in->x[i], dyn = neg->y[2 * i] - in->y[i];
        assert_near(dxn, -dxp, 1e-12);
        assert_near(dyn, -dyp, 1e-12);
        assert_near(half->x[2 * i] - in->x[i], 0.5 * dxp, 1e-12);
        assert_near(half->y[2 * i] - in->y[i], 0.5 * dyp, 1e-12);
        moved += (dxp != 0.0 || dyp != 0.0);
    }
    assert_int_equal(moved, in->n - 2); /* every interior vertex, never the end points */
    for (size_t k = 1; k < pos->n; k += 2) /* midpoints are the same whatever UC */
        assert_true(pos->x[k] == neg->x[k] && pos->y[k] == neg->y[k]);
    ft_chain_free(in);
    ft_chain_free(pos);
    ft_chain_free(neg);
    ft_chain_free(half);
}

/* Segment by segment: in the window [SM, ST) a segment is split at its midpoint; outside it, it passes
 * unchanged and unsplit; a vertex moves only if both of its segments are in the window. */
static void test_tolerances_segment_by_segment(void **state)
{
    (void)state;
    ft_chain *in = ft_chain_create(0, 0);
    ft_rng *r = ft_rng_create(77, 0);
    double x = 0, y = 0, dir = 0;
    for (int i = 0; i < 300; i++) {
        ft_chain_push(in, x, y);
        double step = 0.1 + 3.9 * ft_rng_uniform(r); /* lengths in [0.1, 4] */
        dir += (ft_rng_uniform(r) - 0.5) * 2.5;
        x += step * cos(dir);
        y += step * sin(dir);
    }
    ft_rng_free(r);
    const double st = 2.5, sm = 0.8;
    ft_chain *out = enhance(in, 1.6, 1.0, st, sm, 1);
    size_t k = 0, split = 0, kept = 0;
    for (size_t i = 0; i < in->n; i++) {
        size_t nseg = in->n - 1;
        int prev_in = i > 0 && dist(in->x[i - 1], in->y[i - 1], in->x[i], in->y[i]) < st &&
                      dist(in->x[i - 1], in->y[i - 1], in->x[i], in->y[i]) >= sm;
        int next_in = i < nseg && dist(in->x[i], in->y[i], in->x[i + 1], in->y[i + 1]) < st &&
                      dist(in->x[i], in->y[i], in->x[i + 1], in->y[i + 1]) >= sm;
        assert_true(k < out->n);
        int same = out->x[k] == in->x[i] && out->y[k] == in->y[i];
        if (prev_in && next_in)
            assert_false(same);
        else
            assert_true(same);
        k++;
        if (next_in) {
            assert_true(out->x[k] == 0.5 * (in->x[i] + in->x[i + 1]) && out->y[k] == 0.5 * (in->y[i] + in->y[i + 1]));
            k++;
            split++;
        } else if (i < nseg) {
            kept++;
        }
    }
    assert_int_equal(k, out->n);
    assert_true(split > 50 && kept > 50);
    ft_chain_free(in);
    ft_chain_free(out);
}

static void test_vertex_counts_and_end_points(void **state)
{
    (void)state;
    for (size_t n = 2; n < 40; n += 7) {
        ft_chain *in = wiggly(n, n, 0);
        ft_chain *one = enhance(in, 1.3, 1.0, INFINITY, 0.0, 1);
        assert_int_equal(one->n, 2 * n - 1);
        ft_chain *four = enhance(in, 1.7, -0.8, INFINITY, 0.0, 4);
        assert_int_equal(four->n, 16 * (n - 1) + 1);
        assert_true(four->x[0] == in->x[0] && four->y[0] == in->y[0]);
        assert_true(four->x[four->n - 1] == in->x[n - 1] && four->y[four->n - 1] == in->y[n - 1]);
        assert_int_equal(four->closed, 0);
        ft_chain_free(in);
        ft_chain_free(one);
        ft_chain_free(four);
    }
}

/* A ring has no end points: 2n vertices, every vertex standardized, vertex 0 included. */
static void test_ring(void **state)
{
    (void)state;
    ft_chain *in = blob(40, 3);
    ft_chain *out = enhance(in, 1.5, 1.0, INFINITY, 0.0, 1);
    assert_int_equal(out->n, 80);
    assert_int_equal(out->closed, 1);
    double theta = ft_dutton_apex_angle(1.5);
    for (size_t i = 0; i < in->n; i++) {
        size_t km = (2 * i + 79) % 80, kp = 2 * i + 1;
        double ax = out->x[km] - out->x[2 * i], ay = out->y[km] - out->y[2 * i];
        double bx = out->x[kp] - out->x[2 * i], by = out->y[kp] - out->y[2 * i];
        assert_near(atan2(fabs(ax * by - ay * bx), ax * bx + ay * by), theta, 1e-9);
    }
    assert_false(out->x[0] == in->x[0] && out->y[0] == in->y[0]);
    ft_chain_free(in);
    ft_chain_free(out);
}

/* A straight run has no side: it stays straight (collinear vertices are left in place). */
static void test_straight_line_stays(void **state)
{
    (void)state;
    const double xs[] = {0, 1, 2.5, 3, 7}, ys[] = {0, 0, 0, 0, 0};
    ft_chain *in = ft_chain_from_arrays(xs, ys, 5, 1, 0);
    ft_chain *out = enhance(in, 1.8, 1.0, INFINITY, 0.0, 3);
    assert_int_equal(out->n, 8 * 4 + 1);
    for (size_t k = 0; k < out->n; k++)
        assert_true(out->y[k] == 0.0);
    ft_chain_free(in);
    ft_chain_free(out);
}

/* Six iterations with UC = 1, measured by the divider over the scales the iterations made (2 finest
 * segments to half the input's mean segment). The target is D within 0.05 of SD = 1.3; with
 * the contract's geometry (base M1 M2, apex angle pi - 2a, cos a = 2^(1/SD - 1)) that cannot hold: each
 * pass standardizes the former midpoints, already bent to about 159 degrees by their neighbours' moves
 * (not straight as in the midpoint generator the SD-angle relation comes from), so the length grows by
 * f = 1.076 per halving and D = ln 2 / ln(2 / f) = 1.12 (SD = 2 gives 1.30; docs/line-enhance.md has the
 * table). What holds, and is checked: the enhanced chain is self-similar over those scales (a straight
 * log-log line), D matches the per-pass length growth, and D rises with SD. The opt-in calibrated mode
 * (ft_dutton_opts.target_dim, ft_dutton_apex_for_dimension) picks the apex angle whose steady-state D is
 * the target; tests/unit/test_line_dutton_calibrated.c checks it, the 6-pass target included. */
static void test_divider_dimension_after_six_iterations(void **state)
{
    (void)state;
    const double sds[] = {1.3, 1.7, 2.0};
    for (uint64_t seed = 11; seed <= 13; seed++) {
        double prev_d = 1.0;
        for (size_t k = 0; k < 3; k++) {
            ft_chain *in = wiggly(40, seed, 0);
            double mean_in = ft_chain_length(in) / (double)(in->n - 1);
            ft_chain *five = enhance(in, sds[k], 1.0, INFINITY, 0.0, 5);
            ft_chain *out = enhance(in, sds[k], 1.0, INFINITY, 0.0, 6);
            assert_int_equal(out->n, 64 * (in->n - 1) + 1);
            double mean_out = ft_chain_length(out) / (double)(out->n - 1);
            ft_dim_result *res = line_divider_fit(out, 2.0 * mean_out, 0.5 * mean_in);
            double f = ft_chain_length(out) / ft_chain_length(five);
            double d_growth = log(2.0) / log(2.0 / f);
            print_message("seed %u, SD %.1f: divider D = %.4f (r2 %.5f) over [%g, %g]; growth %.4f per pass, "
                          "D = %.4f\n", (unsigned)seed, sds[k], res->D, res->r2, res->range[0], res->range[1], f,
                          d_growth);
            assert_true(res->r2 > 0.99);
            assert_near(res->D, d_growth, 0.06);
            assert_true(res->D > prev_d + 0.03 && res->D < sds[k]);
            prev_d = res->D;
            ft_dim_result_free(res);
            ft_chain_free(in);
            ft_chain_free(five);
            ft_chain_free(out);
        }
    }
}

static void expect_error(const ft_chain *in, const ft_dutton_opts *o, int code, const char *msg)
{
    ft_chain *out = (ft_chain *)1;
    assert_int_equal(ft_line_enhance(in, o, &out), code);
    assert_null(out);
    if (strstr(ft_last_error(), msg) == NULL)
        print_error("message '%s' lacks '%s'\n", ft_last_error(), msg);
    assert_non_null(strstr(ft_last_error(), msg));
}

/* sd 0: the target is the input's own divider D (measured as ft_line_dim measures it), whatever uc. */
static void test_sd_input(void **state)
{
    (void)state;
    ft_chain *in = wiggly(400, 3, 1);
    const ft_chain *cs[] = {in};
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(cs, 1, FT_LINE_DIVIDER, NULL, &r), FT_OK);
    double uc[] = {0.7, 1.0};
    for (int k = 0; k < 2; k++) {
        ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
        o.sd = 0.0;
        o.uc = uc[k];
        ft_dutton_plan p;
        int rc = ft_dutton_plan_make(cs, 1, &o, &p);
        if (rc != FT_OK)
            print_error("%s\n", ft_last_error());
        assert_int_equal(rc, FT_OK);
        assert_true(p.input_dim == fmin(fmax(r->D, 1.0), 2.0));
        assert_true(p.target_dim == p.input_dim);
    }
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT; /* D_in 1.48 is beyond what uc 0.4 reaches (1.355) */
    o.sd = 0.0;
    o.uc = 0.4;
    ft_dutton_plan p;
    assert_int_equal(ft_dutton_plan_make(cs, 1, &o, &p), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "out of reach with uc = 0.4"));
    ft_dim_result_free(r);
    ft_chain_free(in);
}

/* keep_vertices: the input's vertices stay, and each new midpoint sits where it sits relative to its two
 * neighbours in Dutton's pass: Dutton's midpoint minus the mean of the neighbours' moves, both taken from
 * a plain Dutton pass of the same chain (SM lets about a third of the segments pass unsplit, so some vertices
 * do not move there and some midpoints do not exist). */
static void check_keep_vertices(const ft_chain *in, int literal)
{
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 1.4;
    o.uc = 0.7;
    o.sm = 0.8;
    o.literal_sd = literal;
    o.allow_crossings = 1;
    ft_chain *dut = NULL, *kv = NULL;
    assert_int_equal(ft_line_enhance(in, &o, &dut), FT_OK);
    o.keep_vertices = 1;
    assert_int_equal(ft_line_enhance(in, &o, &kv), FT_OK);
    assert_int_equal(kv->n, dut->n);
    size_t n = in->n, nseg = in->closed ? n : n - 1, k = 0, moved = 0;
    size_t *at = calloc(n, sizeof *at); /* output index of input vertex i */
    assert_non_null(at);
    for (size_t i = 0; i < n; i++) {
        at[i] = k++;
        if (i < nseg && dist(in->x[i], in->y[i], in->x[(i + 1) % n], in->y[(i + 1) % n]) >= o.sm)
            k++;
    }
    assert_int_equal(k, kv->n);
    for (size_t i = 0; i < n; i++) {
        assert_true(kv->x[at[i]] == in->x[i] && kv->y[at[i]] == in->y[i]);
        moved += dut->x[at[i]] != in->x[i] || dut->y[at[i]] != in->y[i];
        size_t m = at[i] + 1, j = (i + 1) % n;
        if (i >= nseg || m == (i + 1 < n ? at[i + 1] : kv->n))
            continue; /* no midpoint after vertex i */
        for (int d = 0; d < 2; d++) {
            const double *ci = d ? in->y : in->x, *cd = d ? dut->y : dut->x, *ck = d ? kv->y : kv->x;
            double want = cd[m] - 0.5 * ((cd[at[i]] - ci[i]) + (cd[at[j]] - ci[j]));
            assert_true(fabs(ck[m] - want) <= 1e-12 * (1.0 + fabs(want)));
        }
    }
    assert_true(moved > n / 3); /* Dutton's pass did move the vertices kept here */
    free(at);
    ft_chain_free(dut);
    ft_chain_free(kv);
}

static void test_keep_vertices(void **state)
{
    (void)state;
    ft_chain *open = wiggly(300, 11, 0), *ring = wiggly(300, 12, 1);
    check_keep_vertices(open, 1);
    check_keep_vertices(ring, 1);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.keep_vertices = 1;
    o.iterations = 2;
    expect_error(ring, &o, FT_E_INVALID, "iterations must be 1, got 2");
    ft_chain_free(open);
    ft_chain_free(ring);
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_chain *in = wiggly(10, 1, 0);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 2.7;
    expect_error(in, &o, FT_E_INVALID, "sd must be in [1,2], got 2.7");
    o.sd = NAN;
    expect_error(in, &o, FT_E_INVALID, "sd must be in [1,2], got nan");
    o.sd = 0.0; /* the input's own D: only in the calibrated mode with uc > 0 */
    o.literal_sd = 1;
    expect_error(in, &o, FT_E_INVALID, "sd 0 (the input's own dimension) needs the calibrated mode and uc > 0");
    o.literal_sd = 0;
    o.uc = -0.5;
    expect_error(in, &o, FT_E_INVALID, "sd 0 (the input's own dimension) needs the calibrated mode and uc > 0");
    o.sd = 1.3;
    o.uc = -1.5;
    expect_error(in, &o, FT_E_INVALID, "uc must be in [-1,1], got -1.5");
    o.uc = 1.0;
    o.st = 1.0;
    o.sm = 2.0;
    expect_error(in, &o, FT_E_INVALID, "st must be >= sm, got st = 1 and sm = 2");
    o.st = INFINITY;
    o.sm = -0.5;
    expect_error(in, &o, FT_E_INVALID, "sm must be finite and >= 0, got -0.5");
    o.sm = 0.0;
    o.st = -3.0;
    expect_error(in, &o, FT_E_INVALID, "st must be > 0, got -3");
    o.st = INFINITY;
    o.iterations = 0;
    expect_error(in, &o, FT_E_INVALID, "iterations must be in [1,64], got 0");
    o.iterations = 1;
    expect_error(in, NULL, FT_E_INVALID, "NULL options");
    in->y[3] = NAN;
    expect_error(in, &o, FT_E_NUMERIC, "vertex 3 is not finite");
    in->y[3] = 0.0;
    in->n = 1;
    expect_error(in, &o, FT_E_INVALID, "chain has 1 vertices, at least 2 needed");
    in->n = 2;
    in->closed = 1;
    expect_error(in, &o, FT_E_INVALID, "ring has 2 vertices, at least 3 needed");
    expect_error(NULL, &o, FT_E_INVALID, "NULL chain");
    ft_chain_free(in);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_apex_angle),
        cmocka_unit_test(test_uc1_standard_angle_ratio_side),
        cmocka_unit_test(test_sd1_straightens),
        cmocka_unit_test(test_uc0_on_input_polyline),
        cmocka_unit_test(test_uc_mirror_and_fraction),
        cmocka_unit_test(test_tolerances_segment_by_segment),
        cmocka_unit_test(test_vertex_counts_and_end_points),
        cmocka_unit_test(test_ring),
        cmocka_unit_test(test_straight_line_stays),
        cmocka_unit_test(test_divider_dimension_after_six_iterations),
        cmocka_unit_test(test_sd_input),
        cmocka_unit_test(test_keep_vertices),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
