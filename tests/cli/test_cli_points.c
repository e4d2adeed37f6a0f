/* fracterra — tests/cli/test_cli_points.c: `fracterra dim points` end to end, through the built binary:
 * the bundled Davis (1973) spot heights (52 points: the default lags are too thin for them and the command
 * says which lags it dropped; explicit lags work), a plane of points in a CSV with its own column names
 * (D = 2 by both methods, --exact giving the same table as the grid), --sample with its standard error and
 * seed, --plot, the human table's warning about dropped lags, and bad input (each refused with the value
 * named and the right exit code).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define DAVIS FT_TEST_DATA "/points_mass_topo_davis1973.csv"
#define DAVIS_LAGS "1,1.5,2,2.5,3"

/* Runs `fracterra dim points ARGS...`; returns the result (free with ft_run_free). */
static ft_run_result points(const char *const *args)
{
    const char *argv[32] = {"dim", "points"};
    size_t n = 2;
    for (; args[n - 2] != NULL && n < 31; n++)
        argv[n] = args[n - 2];
    argv[n] = NULL;
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    assert_false(r.signaled);
    return r;
}
#define POINTS(...) points((const char *const[]){__VA_ARGS__, NULL})

/* Expects exit 0 and one JSON object on stdout. */
static json_object *json_of(ft_run_result *r)
{
    if (r->status != 0)
        print_error("exit %d: %s\n", r->status, r->err);
    assert_int_equal(r->status, 0);
    json_object *o = ft_run_json(r);
    assert_non_null(o);
    ft_run_free(r);
    return o;
}

/* Expects exit `code`, "fracterra: dim points: " and every needle on stderr, nothing on stdout. */
static void expect_error(ft_run_result r, int code, const char *needle1, const char *needle2)
{
    if (r.status != code || strstr(r.err, "fracterra: dim points: ") != r.err || strstr(r.err, needle1) == NULL ||
        (needle2 && strstr(r.err, needle2) == NULL))
        print_error("exit %d, stderr: %s\n", r.status, r.err);
    assert_int_equal(r.status, code);
    assert_ptr_equal(strstr(r.err, "fracterra: dim points: "), r.err);
    assert_non_null(strstr(r.err, needle1));
    if (needle2)
        assert_non_null(strstr(r.err, needle2));
    assert_int_equal(r.out_len, 0);
    ft_run_free(&r);
}

/* The default lags (0.5 to 4 mean spacings, eps half the smallest gap) hold fewer than 100 pairs each
 * among 52 points: a clear failure listing every dropped lag with its pair count. */
static void test_davis_default_too_few_lags(void **state)
{
    (void)state;
    expect_error(POINTS(DAVIS), 1, "too few lags", "dropped lags: 0.426412 (3 pairs)");
}

static void test_davis_explicit_lags(void **state)
{
    (void)state;
    ft_run_result r = POINTS(DAVIS, "--lags", DAVIS_LAGS, "--eps", "0.25", "--min-pairs", "10", "--json");
    json_object *o = json_of(&r);
    assert_int_equal(ft_test_json_int(o, "points"), 52);
    assert_string_equal(ft_test_json_str(o, "method"), "yokoya");
    assert_string_equal(ft_test_json_str(o, "pairs"), "grid");
    assert_true(ft_test_json_num(o, "eps") == 0.25);
    double D = ft_test_json_num(o, "D");
    assert_true(D > 2.0 && D < 3.0);
    assert_int_equal(json_object_array_length(ft_test_json_key(o, "table")), 5);
    assert_int_equal(json_object_array_length(ft_test_json_key(o, "dropped_lags")), 0);
    json_object_put(o);
    /* with 100 pairs needed, lags 1 and 1.5 (91 and 92 pairs) are dropped and listed */
    r = POINTS(DAVIS, "--lags", DAVIS_LAGS, "--eps", "0.25", "--json");
    o = json_of(&r);
    json_object *dropped = ft_test_json_key(o, "dropped_lags");
    assert_int_equal(json_object_array_length(dropped), 2);
    json_object *d0 = json_object_array_get_idx(dropped, 0);
    assert_true(ft_test_json_num(d0, "lag") == 1.0);
    assert_int_equal(ft_test_json_int(d0, "pairs"), 91);
    assert_string_equal(ft_test_json_str(d0, "reason"), "pairs");
    assert_int_equal(json_object_array_length(ft_test_json_key(o, "table")), 3);
    assert_int_equal(ft_test_json_int(o, "lags_kept"), 3);
    json_object_put(o);
    /* the table output says the same on stderr */
    r = POINTS(DAVIS, "--lags", DAVIS_LAGS, "--eps", "0.25");
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "warning: dropped lags"));
    assert_non_null(strstr(r.err, "1 (pairs 91), 1.5 (pairs 92)"));
    assert_non_null(strstr(r.out, "yokoya"));
    ft_run_free(&r);
}

/* A plane z = 2 E - N + 7 at 3000 random points, columns named E, N, H. */
static const char *plane_csv(void)
{
    char *text = malloc(3000 * 64 + 16);
    assert_non_null(text);
    size_t used = (size_t)sprintf(text, "E,N,H\n");
    ft_rng *r = ft_rng_create(9, 0);
    for (int i = 0; i < 3000; i++) {
        double x = 1000.0 * ft_rng_uniform(r), y = 1000.0 * ft_rng_uniform(r);
        used += (size_t)sprintf(text + used, "%.6f,%.6f,%.6f\n", x, y, 2.0 * x - y + 7.0);
    }
    ft_rng_free(r);
    const char *path = ft_test_tmp_text("plane.csv", text);
    free(text);
    return path;
}

static void test_plane_all_methods_exact(void **state)
{
    (void)state;
    const char *csv = plane_csv();
    ft_run_result r = POINTS(csv, "--x", "E", "--y", "N", "--z", "H", "--method", "all", "--json");
    json_object *o = json_of(&r), *res = ft_test_json_key(o, "results");
    assert_int_equal(json_object_array_length(res), 2);
    for (size_t i = 0; i < 2; i++)
        assert_true(fabs(ft_test_json_num(json_object_array_get_idx(res, i), "D") - 2.0) < 0.02);
    double grid_D = ft_test_json_num(json_object_array_get_idx(res, 0), "D");
    json_object_put(o);
    r = POINTS(csv, "--x", "E", "--y", "N", "--z", "H", "--exact", "--json");
    o = json_of(&r);
    assert_string_equal(ft_test_json_str(o, "pairs"), "exact");
    assert_true(ft_test_json_num(o, "D") == grid_D);
    json_object_put(o);
    /* sampled pairs: reproducible per seed, with a standard error */
    r = POINTS(csv, "--x", "E", "--y", "N", "--z", "H", "--sample", "200000", "--seed", "5", "--json");
    o = json_of(&r);
    assert_string_equal(ft_test_json_str(o, "pairs"), "sample");
    assert_int_equal(ft_test_json_int(o, "seed"), 5);
    double se = ft_test_json_num(o, "sample_stderr"), D = ft_test_json_num(o, "D");
    assert_true(se > 0.0 && se < 0.05);
    assert_true(fabs(D - 2.0) < 0.03);
    json_object_put(o);
    r = POINTS(csv, "--x", "E", "--y", "N", "--z", "H", "--sample", "200000", "--seed", "5", "--json");
    o = json_of(&r);
    assert_true(ft_test_json_num(o, "D") == D);
    json_object_put(o);
    /* a plot */
    const char *svg = ft_test_tmp("plane.svg");
    r = POINTS(csv, "--x", "E", "--y", "N", "--z", "H", "--plot", svg, "--segments");
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    free(ft_test_read_svg(svg, NULL));
}

static void test_bad_input(void **state)
{
    (void)state;
    expect_error(POINTS(DAVIS, "--eps", "-1"), 2, "--eps", "-1");
    expect_error(POINTS(DAVIS, "--min-pairs", "0"), 2, "--min-pairs", "0");
    expect_error(POINTS(DAVIS, "--method", "lunar"), 2, "--method", "lunar");
    expect_error(POINTS(DAVIS, "--lags", "1,x"), 2, "--lags", "1,x");
    expect_error(POINTS(DAVIS, "--exact", "--sample", "10"), 2, "--exact", "--sample");
    expect_error(POINTS(DAVIS, "--lags", DAVIS_LAGS, "--eps", "2"), 1, "eps", "got 2");
    expect_error(POINTS(DAVIS, "--z", "elevation"), 1, "elevation", DAVIS);
    const char *nan_csv = ft_test_tmp_text("nan.csv", "x,y,z\n0,0,1\n1,0,nan\n0,1,2\n1,1,3\n");
    expect_error(POINTS(nan_csv), 1, "column 'z'", "nan");
    const char *two = ft_test_tmp_text("two.csv", "x,y,z\n0,0,1\n1,0,2\n");
    expect_error(POINTS(two), 1, "at least 3 points", "got 2");
    expect_error(POINTS(ft_test_tmp("missing.csv")), 1, "missing.csv", NULL);
    expect_error(POINTS(DAVIS, "extra.csv"), 2, "extra.csv", NULL);
    expect_error(POINTS(DAVIS, "--noise-sigma", "1,2,3"), 2, "--noise-sigma", "1,2,3");
    expect_error(POINTS(DAVIS, "--noise-sigma", "-1"), 2, "--noise-sigma", "-1");
    expect_error(POINTS(DAVIS, "--noise-sigma", "1,"), 2, "--noise-sigma", "1,");
    expect_error(POINTS(DAVIS, "--noise-sigma", "x"), 2, "--noise-sigma", "x");
    expect_error(POINTS(DAVIS, "--noise-model", "maybe"), 2, "--noise-model", "maybe");
}

/* The real spot heights carry no detectable noise: the model is fitted and reported, nothing removed;
 * --noise-sigma XY,Z is used as given and echoed. */
static void test_davis_noise_model(void **state)
{
    (void)state;
    ft_run_result r = POINTS(DAVIS, "--lags", "0.5,0.75,1,1.25,1.5,1.75,2,2.5,3,3.5", "--eps", "0.2", "--min-pairs",
                             "10", "--json");
    json_object *o = json_of(&r), *n = ft_test_json_key(o, "noise");
    assert_false(json_object_get_boolean(ft_test_json_key(n, "removed")));
    assert_true(ft_test_json_num(n, "sigma_z") >= 0.0);
    json_object *warns = ft_test_json_key(o, "warnings"); /* the band and CRS warnings, none about noise */
    for (size_t i = 0; i < json_object_array_length(warns); i++)
        assert_null(strstr(json_object_get_string(ft_test_json_at(warns, i)), "noise"));
    json_object_put(o);
    r = POINTS(DAVIS, "--lags", "0.5,0.75,1,1.25,1.5,1.75,2,2.5,3,3.5", "--eps", "0.2", "--min-pairs", "10",
               "--noise-sigma", "0.1,5", "--json");
    o = json_of(&r);
    assert_true(ft_test_json_num(o, "noise_sigma") == 5.0);
    assert_true(ft_test_json_num(o, "noise_sigma_xy") == 0.1);
    n = ft_test_json_key(o, "noise");
    assert_true(json_object_get_boolean(ft_test_json_key(n, "removed")));
    assert_true(ft_test_json_num(n, "sigma_z") == 5.0);
    json_object *w = ft_test_json_key(o, "warnings");
    int said = 0;
    for (size_t i = 0; i < json_object_array_length(w); i++)
        said |= strstr(json_object_get_string(json_object_array_get_idx(w, i)), "noise model") != NULL;
    assert_true(said);
    json_object_put(o);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_davis_default_too_few_lags),
        cmocka_unit_test(test_davis_explicit_lags),
        cmocka_unit_test(test_plane_all_methods_exact),
        cmocka_unit_test(test_bad_input), cmocka_unit_test(test_davis_noise_model),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
