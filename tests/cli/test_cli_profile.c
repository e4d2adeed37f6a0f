/* fracterra — tests/cli/test_cli_profile.c: `dim profile` end to end (a DEM row, a transect, a 3-D line;
 * bad input), and the log-log behaviours every estimator shares through the CLI: `dim line` pointing a
 * profile to `dim profile`, --regime, a D outside its domain as exit 1.
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
#include "ft_test_run.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"

static void check_profile_json(json_object *o, const char *source)
{
    assert_string_equal(ft_test_json_str(o, "profile"), source);
    json_object *res = ft_test_json_key(o, "results");
    assert_int_equal(json_object_array_length(res), 2);
    const char *names[] = {"madogram", "variogram"};
    for (size_t i = 0; i < 2; i++) {
        json_object *r = ft_test_json_at(res, i);
        assert_string_equal(ft_test_json_str(r, "method"), names[i]);
        double D = ft_test_json_num(r, "D");
        assert_true(D >= 1.0 && D <= 2.0);
        assert_int_equal(json_object_array_length(ft_test_json_key(r, "table")), 2);
        assert_true(json_object_is_type(ft_test_json_key(r, "warnings"), json_type_array));
    }
}

static void test_row_and_transect(void **state)
{
    (void)state;
    json_object *o = FT_TEST_RUN_JSON("dim", "profile", VOLCANO, "--row", "40", "--json");
    check_profile_json(o, "row");
    assert_int_equal(ft_test_json_int(o, "samples"), 61);
    assert_true(fabs(ft_test_json_num(o, "spacing") - 10.0) < 1e-9);
    json_object_put(o);
    /* a transect along the centres of row 40: the row itself */
    o = FT_TEST_RUN_JSON("dim", "profile", VOLCANO, "--from", "2667399,6479367", "--to", "2667999,6479367",
                         "--json");
    check_profile_json(o, "transect");
    assert_int_equal(ft_test_json_int(o, "samples"), 61);
    json_object *a = FT_TEST_RUN_JSON("dim", "profile", VOLCANO, "--row", "40", "--method", "madogram", "--json");
    assert_true(fabs(ft_test_json_num(a, "D") -
                     ft_test_json_num(ft_test_json_at(ft_test_json_key(o, "results"), 0), "D")) < 1e-6);
    json_object_put(a);
    json_object_put(o);
}

static void test_line_3d_and_bad_input(void **state)
{
    (void)state;
    char *dir = ft_test_mkdtemp(), *line = ft_test_path(dir, "p.geojson"), *flat = ft_test_path(dir, "f.geojson");
    /* a 3-D line: z = a random walk over 513 vertices 10 m apart, in a projected CRS (a GeoJSON without a
     * "crs" member is longitude/latitude by RFC 7946) */
    char *buf = malloc(64 * 1024);
    size_t n = (size_t)snprintf(buf, 64 * 1024, "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\","
                                "\"properties\":{\"name\":\"urn:ogc:def:crs:EPSG::32633\"}},\"features\":[{\"type\":\"Feature\","
                                "\"properties\":{},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[");
    double z = 0.0;
    unsigned s = 12345;
    for (int i = 0; i <= 512; i++) {
        s = s * 1103515245u + 12345u;
        z += ((double)((s >> 16) & 0x7fff) / 32767.0 - 0.5) * 4.0;
        n += (size_t)snprintf(buf + n, 64 * 1024 - n, "%s[%d,0,%.4f]", i ? "," : "", 10 * i, z);
    }
    snprintf(buf + n, 64 * 1024 - n, "]}}]}");
    ft_test_write_text(line, buf);
    json_object *o = FT_TEST_RUN_JSON("dim", "profile", line, "--json");
    check_profile_json(o, "line");
    assert_int_equal(ft_test_json_int(o, "samples"), 513);
    json_object_put(o);
    /* `dim line` on the same (2-D view of the) line: a warning pointing to dim profile */
    ft_run_result r;
    assert_int_equal(ft_run(&r, "dim", "line", line, "--json", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "use `fracterra dim profile`"));
    ft_run_free(&r);

    ft_test_write_text(flat, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                             "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0],[1,0],[2,1],[3,0]]}}]}");
    FT_TEST_EXPECT_FAILURE(1, "dim profile", "has no z", "dim", "profile", flat);
    FT_TEST_EXPECT_FAILURE(1, "dim profile", "row 500 outside", "dim", "profile", VOLCANO, "--row", "500");
    FT_TEST_EXPECT_FAILURE(1, "dim profile", "outside the grid", "dim", "profile", VOLCANO, "--from", "0,0", "--to",
                           "100,100");
    FT_TEST_EXPECT_FAILURE(2, "dim profile", "--from and --to go together", "dim", "profile", VOLCANO, "--from",
                           "0,0");
    FT_TEST_EXPECT_FAILURE(2, "dim profile", "--from must be X,Y", "dim", "profile", VOLCANO, "--from", "zero",
                           "--to", "1,1");
    FT_TEST_EXPECT_FAILURE(2, "dim profile", "do not apply", "dim", "profile", VOLCANO, "--row", "3", "--min-scale",
                           "10");
    FT_TEST_EXPECT_FAILURE(2, "dim profile", "madogram, variogram or both", "dim", "profile", VOLCANO, "--row", "3",
                           "--method", "divider");
    FT_TEST_EXPECT_FAILURE(1, "dim profile", "cannot open", "dim", "profile", "/nonexistent/p.tif", "--row", "1");
    free(buf);
    ft_test_rmtree(dir);
    free(line);
    free(flat);
    free(dir);
}

/* --regime: a regime that does not exist is an error, with a range a usage error */
static void test_regime_option(void **state)
{
    (void)state;
    FT_TEST_EXPECT_FAILURE(1, "dim line", "regime 9 asked for", "dim", "line", FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson",
                           "--regime", "9");
    FT_TEST_EXPECT_FAILURE(2, "dim line", "cannot be combined", "dim", "line",
                           FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson", "--regime", "1", "--min-scale", "1000",
                           "--max-scale", "9000");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_row_and_transect),
        cmocka_unit_test(test_line_3d_and_bad_input),
        cmocka_unit_test(test_regime_option),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
