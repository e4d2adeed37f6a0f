/* fracterra — unit tests of line/dutton_calibrate.c: calibrated mode of Dutton's (1981) enhancement.
 * The steady-state dimension of an apex angle and its inverse; that the per-pass length growth of real
 * enhanced chains is the one the canonical cell predicts; the apex angle and the wiring of target_dim;
 * the accuracy target (6 passes, target 1.3, UC = 1, divider over the fine scales within 0.05) on
 * random walks, a coarse circle and the 158-point Newfoundland coast; the divider with rulers well inside
 * the generated scales for targets 1.1 to 1.7; bad targets.
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

#include "fracterra/io.h"
#include "fracterra/line.h"
#include "ft_test_assert.h"
#include "test_line.h"

#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"

static const double PI = 3.14159265358979323846;
static const double DEG = 3.14159265358979323846 / 180.0;

/* ------------------------------------------------------------------------------------------------
 * Inputs: random walks, a coarse circle, the generalized Newfoundland coast
 * --------------------------------------------------------------------------------------------- */

/* A random walk of n vertices with steps in [0.5, 1.5] and turns up to +-100 degrees (seeded). */
static ft_chain *walk(size_t n, uint64_t seed)
{
    ft_chain *c = ft_chain_create(n, 0);
    ft_rng *r = ft_rng_create(seed, 0);
    assert_true(c != NULL && r != NULL);
    double x = 0, y = 0, dir = 0;
    for (size_t i = 0; i < n; i++) {
        assert_int_equal(ft_chain_push(c, x, y), FT_OK);
        dir += (ft_rng_uniform(r) - 0.5) * 2.0 * (100.0 * DEG);
        double step = 0.5 + ft_rng_uniform(r);
        x += step * cos(dir);
        y += step * sin(dir);
    }
    ft_rng_free(r);
    return c;
}

/* A regular n-gon of radius 10 (a ring). */
static ft_chain *circle(size_t n)
{
    ft_chain *c = ft_chain_create(n, 1);
    assert_non_null(c);
    for (size_t i = 0; i < n; i++) {
        double a = 2.0 * PI * (double)i / (double)n;
        assert_int_equal(ft_chain_push(c, 10.0 * cos(a), 10.0 * sin(a)), FT_OK);
    }
    return c;
}

/* The GSHHG Newfoundland ring, Douglas-Peucker generalized to 158 vertices as Dutton's Fig. 6A (the
 * tolerance is searched by bisection, about 9.2 km). */
static ft_chain *newfoundland_158(void)
{
    ft_layer *l = NULL;
    assert_int_equal(ft_io_read_layer(NEWFOUNDLAND, NULL, &l), FT_OK);
    const ft_chain *full = l->parts[0].chain;
    double lo = 1000.0, hi = 100000.0;
    ft_chain *best = NULL;
    for (int i = 0; i < 40 && (best == NULL || best->n != 158); i++) {
        double tol = sqrt(lo * hi);
        ft_chain *s = NULL;
        assert_int_equal(ft_line_simplify(full, tol, &s), FT_OK);
        if (s->n > 158)
            lo = tol;
        else
            hi = tol;
        ft_chain_free(best);
        best = s;
    }
    ft_layer_free(l);
    assert_true(best->n >= 150 && best->n <= 166);
    return best;
}

typedef struct {
    const char *name;
    ft_chain *chain;
} input;

enum { NINPUTS = 5 };

/* Walks of 40 vertices (seeds 11-13, as test_line_dutton.c), a 16-gon, the 158-point coast. */
static void make_inputs(input *in)
{
    in[0] = (input){"walk 11", walk(40, 11)};
    in[1] = (input){"walk 12", walk(40, 12)};
    in[2] = (input){"walk 13", walk(40, 13)};
    in[3] = (input){"16-gon", circle(16)};
    in[4] = (input){"Newfoundland 158", newfoundland_158()};
}

static void free_inputs(input *in)
{
    for (int i = 0; i < NINPUTS; i++)
        ft_chain_free(in[i].chain);
}

static ft_chain *enhance_to(const ft_chain *in, double target, int iterations)
{
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.target_dim = target;
    o.iterations = iterations;
    o.allow_crossings = 1; /* the calibration of the raw algorithm */
    ft_chain *out = NULL;
    int rc = ft_line_enhance(in, &o, &out);
    if (rc != FT_OK)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    return out;
}

static double mean_segment(const ft_chain *c)
{
    return ft_chain_length(c) / (double)ft_chain_segments(c);
}

/* Divider D over [lo, hi], 12 rulers, every scale fitted (line_divider_fit), and its r2. */
static double divider(const ft_chain *c, double lo, double hi, double *r2)
{
    ft_dim_result *res = line_divider_fit(c, lo, hi);
    double d = res->D;
    *r2 = res->r2;
    ft_dim_result_free(res);
    return d;
}

/* ------------------------------------------------------------------------------------------------
 * The steady-state dimension and its inverse
 * --------------------------------------------------------------------------------------------- */

static void test_steady_dimension(void **state)
{
    (void)state;
    assert_near(ft_dutton_steady_dimension(PI), 1.0, 1e-12);
    double prev = 1.0;
    for (double apex = 175.0; apex >= 60.0; apex -= 5.0) {
        double d = ft_dutton_steady_dimension(apex * DEG);
        assert_true(d > prev);
        prev = d;
    }
    double dmax = ft_dutton_steady_dimension(FT_DUTTON_APEX_MIN);
    assert_true(dmax > 1.77 && dmax < 1.78);
    /* SD's literal angles: the dimensions test_line_dutton.c measures (growth 1.077 at SD 1.3: D 1.12) */
    assert_near(ft_dutton_steady_dimension(ft_dutton_apex_angle(1.3)), log(2.0) / log(2.0 / 1.0766), 0.002);
    assert_near(ft_dutton_steady_dimension(ft_dutton_apex_angle(1.7)), 1.238, 0.002);
    assert_near(ft_dutton_steady_dimension(ft_dutton_apex_angle(2.0)), 1.305, 0.002);
    /* the symmetric estimate (1 + cos(a/3) / cos a) / 2 holds at small base angles a, drifts high at large */
    double a = (PI - ft_dutton_apex_angle(1.1)) / 2.0, f = 0.5 * (1.0 + cos(a / 3.0) / cos(a));
    assert_near(ft_dutton_steady_dimension(ft_dutton_apex_angle(1.1)), log(2.0) / log(2.0 / f), 0.001);
    assert_true(isnan(ft_dutton_steady_dimension(59.0 * DEG)));
    assert_true(isnan(ft_dutton_steady_dimension(PI + 1e-9)));
    assert_true(isnan(ft_dutton_steady_dimension(NAN)));
}

static void test_apex_for_dimension(void **state)
{
    (void)state;
    double dmax = ft_dutton_steady_dimension(FT_DUTTON_APEX_MIN);
    assert_near(ft_dutton_apex_for_dimension(1.0), PI, 0.0);
    double prev = PI;
    const double targets[] = {1.01, 1.1, 1.2, 1.3, 1.4, 1.5, 1.6, 1.7, 1.75};
    for (size_t i = 0; i < sizeof targets / sizeof targets[0]; i++) {
        double apex = ft_dutton_apex_for_dimension(targets[i]);
        print_message("target %.2f: apex %.3f degrees\n", targets[i], apex / DEG);
        assert_true(apex < prev && apex >= FT_DUTTON_APEX_MIN);
        assert_near(ft_dutton_steady_dimension(apex), targets[i], 1e-9);
        prev = apex;
    }
    assert_near(ft_dutton_apex_for_dimension(1.3) / DEG, 90.47, 0.01);
    assert_near(ft_dutton_apex_for_dimension(dmax), FT_DUTTON_APEX_MIN, 1e-9);
    /* deterministic, whatever was asked before (the per-thread cache) */
    double a13 = ft_dutton_apex_for_dimension(1.3);
    ft_dutton_apex_for_dimension(1.6);
    assert_true(ft_dutton_apex_for_dimension(1.3) == a13);
    const double bad[] = {0.99, 2.0, -1.0, NAN, INFINITY};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        assert_true(isnan(ft_dutton_apex_for_dimension(bad[i])));
    assert_true(isnan(ft_dutton_apex_for_dimension(dmax + 1e-6)));
}

/* ------------------------------------------------------------------------------------------------
 * Calibrated mode on real chains
 * --------------------------------------------------------------------------------------------- */

/* One pass: every moved junction has the calibrated apex angle; target_dim equal to the steady dimension
 * of SD 1.4's angle gives SD 1.4's output; sd is ignored in calibrated mode. */
static void test_calibrated_angle_and_wiring(void **state)
{
    (void)state;
    ft_chain *in = walk(120, 7);
    ft_chain *out = enhance_to(in, 1.5, 1);
    assert_int_equal(out->n, 2 * in->n - 1);
    double theta = ft_dutton_apex_for_dimension(1.5);
    for (size_t i = 1; i + 1 < in->n; i++) {
        double ax = out->x[2 * i - 1] - out->x[2 * i], ay = out->y[2 * i - 1] - out->y[2 * i];
        double bx = out->x[2 * i + 1] - out->x[2 * i], by = out->y[2 * i + 1] - out->y[2 * i];
        assert_near(atan2(fabs(ax * by - ay * bx), ax * bx + ay * by), theta, 1e-9);
    }
    ft_chain_free(out);

    ft_dutton_opts lit = FT_DUTTON_OPTS_DEFAULT, cal = FT_DUTTON_OPTS_DEFAULT;
    lit.sd = 1.4;
    lit.literal_sd = 1;
    lit.iterations = cal.iterations = 3;
    lit.allow_crossings = cal.allow_crossings = 1;
    cal.target_dim = ft_dutton_steady_dimension(ft_dutton_apex_angle(1.4));
    cal.sd = 1.9; /* ignored */
    ft_chain *a = NULL, *b = NULL;
    assert_int_equal(ft_line_enhance(in, &lit, &a), FT_OK);
    assert_int_equal(ft_line_enhance(in, &cal, &b), FT_OK);
    assert_int_equal(a->n, b->n);
    for (size_t k = 0; k < a->n; k++) {
        assert_near(b->x[k], a->x[k], 1e-9);
        assert_near(b->y[k], a->y[k], 1e-9);
    }
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(in);
}

/* The length growth per pass of enhanced chains, sqrt(L_8 / L_6), is the canonical cell's: its dimension
 * ln 2 / ln(2 / f) is the target, on every input and every target. (8 passes from the input, not 2 more from
 * the 6-pass chain: a new call would cut that chain's longest segments again, its input being another.) */
static void test_growth_of_chains_is_steady_state(void **state)
{
    (void)state;
    input in[NINPUTS];
    make_inputs(in);
    const double targets[] = {1.1, 1.3, 1.5, 1.7};
    for (size_t t = 0; t < 4; t++)
        for (int i = 0; i < NINPUTS; i++) {
            ft_chain *six = enhance_to(in[i].chain, targets[t], 6), *eight = enhance_to(in[i].chain, targets[t], 8);
            double f = sqrt(ft_chain_length(eight) / ft_chain_length(six)), d = log(2.0) / log(2.0 / f);
            print_message("target %.1f, %-16s: growth %.4f per pass, D = %.4f\n", targets[t], in[i].name, f, d);
            assert_near(d, targets[t], 0.01);
            ft_chain_free(six);
            ft_chain_free(eight);
        }
    free_inputs(in);
}

/* The target: after 6 iterations with UC = 1 the divider D over the fine scales (the existing test's range:
 * 2 output segments to half an input segment) is within 0.05 of 1.3. The divider reads low at rulers of a
 * few segments (it needs ~10 segments to reach the scaling regime), so 6 passes give 1.25-1.27 here;
 * coarser polygons of 6-12 vertices read 1.227-1.250 (docs/line-enhance.md). The regular polygon's cells
 * are all alike, so its log-log points wiggle log-periodically about the line (r2 ~ 0.90). */
static void test_divider_six_passes_target_1_3(void **state)
{
    (void)state;
    input in[NINPUTS];
    make_inputs(in);
    for (int i = 0; i < NINPUTS; i++) {
        ft_chain *out = enhance_to(in[i].chain, 1.3, 6);
        double r2, d = divider(out, 2.0 * mean_segment(out), 0.5 * mean_segment(in[i].chain), &r2);
        print_message("target 1.3, 6 passes, %-16s: divider D = %.4f (r2 %.4f)\n", in[i].name, d, r2);
        assert_near(d, 1.3, 0.05);
        assert_true(r2 > (in[i].chain->closed && in[i].chain->n == 16 ? 0.9 : 0.99));
        ft_chain_free(out);
    }
    free_inputs(in);
}

/* With rulers well inside the generated scales (12 passes, rulers from 8 output segments to a quarter of
 * an input segment) the divider finds the target within 0.05 on every input, but for the coast at 1.7:
 * the steady state crosses itself below a 73 degree apex (D ~ 1.53) and the coast reads 1.63 there
 * (printed, not asserted). The 6-pass fine-scale reading is printed for the table. */
static void test_divider_deep_targets(void **state)
{
    (void)state;
    input in[NINPUTS];
    make_inputs(in);
    const double targets[] = {1.1, 1.3, 1.5, 1.7};
    for (size_t t = 0; t < 4; t++)
        for (int i = 0; i < NINPUTS; i++) {
            double mi = mean_segment(in[i].chain), r2, r2_6;
            ft_chain *six = enhance_to(in[i].chain, targets[t], 6), *twelve = enhance_to(in[i].chain, targets[t], 12);
            double d6 = divider(six, 2.0 * mean_segment(six), 0.5 * mi, &r2_6);
            double d12 = divider(twelve, 8.0 * mean_segment(twelve), 0.25 * mi, &r2);
            print_message("target %.1f, %-16s: divider D = %.4f after 6 passes (fine scales), %.4f after 12 "
                          "(r2 %.4f)\n", targets[t], in[i].name, d6, d12, r2);
            if (targets[t] < 1.6 || i < 4)
                assert_near(d12, targets[t], 0.05);
            ft_chain_free(six);
            ft_chain_free(twelve);
        }
    free_inputs(in);
}

static void expect_error(double target, const char *msg)
{
    ft_chain *in = walk(10, 1), *out = (ft_chain *)1;
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.target_dim = target;
    assert_int_equal(ft_line_enhance(in, &o, &out), FT_E_INVALID);
    assert_null(out);
    if (strstr(ft_last_error(), msg) == NULL)
        print_error("message '%s' lacks '%s'\n", ft_last_error(), msg);
    assert_non_null(strstr(ft_last_error(), msg));
    ft_chain_free(in);
}

static void test_bad_target(void **state)
{
    (void)state;
    expect_error(1.9, "a target dimension of 1.900 is out of reach with uc = 1: the enhanced chain's dimension "
                      "stops rising at 1.777");
    expect_error(2.0, "a target dimension of 2.000 is out of reach");
    expect_error(2.5, "target_dim must be 0 (from sd) or in [1,2], got 2.5");
    expect_error(0.5, "got 0.5");
    expect_error(-1.3, "got -1.3");
    expect_error(NAN, "got nan");
    expect_error(INFINITY, "got inf");
}

/* Calibrated default: a straight run bends, to alternate sides (left of the direction of travel at odd input
 * indices); --literal-sd leaves it straight. A segment 3 times the input's mean or longer is first cut into
 * ceil(L / mean) equal pieces; one just under 3 times is not. */
static void test_straight_runs_and_long_segments(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 10, 0, 20, 0, 30, 0, 40, 0};
    ft_chain *line = ft_chain_from_arrays(xy, xy + 1, 5, 2, 0);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.allow_crossings = 1;
    ft_chain *out = NULL;
    assert_int_equal(ft_line_enhance(line, &o, &out), FT_OK);
    assert_int_equal(out->n, 9);
    for (size_t i = 1; i < 4; i++) /* input vertex i is output vertex 2i: left (y > 0) when i is odd */
        assert_true(i % 2 ? out->y[2 * i] > 1.0 : out->y[2 * i] < -1.0);
    ft_chain_free(out);
    o.literal_sd = 1;
    assert_int_equal(ft_line_enhance(line, &o, &out), FT_OK);
    for (size_t k = 0; k < out->n; k++)
        assert_true(out->y[k] == 0.0);
    ft_chain_free(out);
    ft_chain_free(line);

    /* segments 10, 10, 10, 10, L: mean (40 + L) / 5; L = 100 gives mean 28 and 4 pieces (100 >= 84) */
    const double xy2[] = {0, 0, 10, 0, 10, 10, 20, 10, 20, 20, 120, 20};
    ft_chain *c = ft_chain_from_arrays(xy2, xy2 + 1, 6, 2, 0);
    o = (ft_dutton_opts)FT_DUTTON_OPTS_DEFAULT;
    o.allow_crossings = 1;
    assert_int_equal(ft_line_enhance(c, &o, &out), FT_OK);
    assert_int_equal(out->n, 2 * (6 + 3) - 1);
    ft_chain_free(out);
    c->x[5] = 70.0; /* L = 50: mean 18, 50 < 54: not cut */
    assert_int_equal(ft_line_enhance(c, &o, &out), FT_OK);
    assert_int_equal(out->n, 2 * 6 - 1);
    ft_chain_free(out);
    o.literal_sd = 1; /* nothing is cut in the literal reading */
    c->x[5] = 120.0;
    assert_int_equal(ft_line_enhance(c, &o, &out), FT_OK);
    assert_int_equal(out->n, 2 * 6 - 1);
    ft_chain_free(out);
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_steady_dimension),
        cmocka_unit_test(test_apex_for_dimension),
        cmocka_unit_test(test_calibrated_angle_and_wiring),
        cmocka_unit_test(test_growth_of_chains_is_steady_state),
        cmocka_unit_test(test_divider_six_passes_target_1_3),
        cmocka_unit_test(test_divider_deep_targets),
        cmocka_unit_test(test_straight_runs_and_long_segments),
        cmocka_unit_test(test_bad_target),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
