/* fracterra — tests/cli/test_cli_bad_input.c: bad input never crashes, gives a clear message naming the
 * culprit ("fracterra: COMMAND: ..."), a non-zero exit (1 failure, 2 usage) and leaves no output behind.
 * A 1-vertex chain and an all-nodata grid are facts about a file: info warns and succeeds.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <gdal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"

/* Runs `fracterra info [extra] path` and checks a failure: exit code in {1, 2} (or exactly `code` if > 0),
 * nothing on stdout, "fracterra: info: " then each of the NULL-terminated needles in stderr. */
static void expect_info_failure(const char *extra, const char *extra_val, const char *path, int code, ...)
{
    ft_run_result r;
    if (extra)
        assert_int_equal(ft_run(&r, "info", extra, extra_val, path, NULL), 0);
    else
        assert_int_equal(ft_run(&r, "info", path, NULL), 0);
    if (code > 0)
        assert_int_equal(r.status, code);
    else
        assert_true(r.status == 1 || r.status == 2);
    assert_false(r.signaled);
    assert_int_equal(r.out_len, 0);
    assert_true(strncmp(r.err, "fracterra: info: ", 17) == 0);
    va_list ap;
    va_start(ap, code);
    const char *needle;
    while ((needle = va_arg(ap, const char *)) != NULL) {
        if (strstr(r.err, needle) == NULL)
            fprintf(stderr, "expected '%s' in: %s", needle, r.err);
        assert_non_null(strstr(r.err, needle));
    }
    va_end(ap);
    ft_run_free(&r);
}

static void test_missing_file(void **state)
{
    expect_info_failure(NULL, NULL, "/nonexistent/fracterra/x.tif", 1, "/nonexistent/fracterra/x.tif", NULL);
}

static void test_garbage_bytes(void **state)
{
    const char *p = ft_test_tmp("garbage.dat");
    unsigned char bytes[4096];
    uint32_t s = 12345u;
    for (size_t i = 0; i < sizeof bytes; i++) {
        s = s * 1664525u + 1013904223u;
        bytes[i] = (unsigned char)(s >> 24);
    }
    assert_int_equal(ft_test_write_file(p, bytes, sizeof bytes), 0);
    expect_info_failure(NULL, NULL, p, 1, "garbage.dat", NULL);
}

/* A raster where a vector layer is expected (--layer on a GeoTIFF), and the reverse (--band on GeoJSON). */
static void test_raster_as_vector(void **state)
{
    expect_info_failure("--layer", "coast", VOLCANO, 0, "dem_volcano_maunga_whau_10m.tif", NULL);
}

static void test_vector_as_raster(void **state)
{
    expect_info_failure("--band", "1", NEWFOUNDLAND, 2, "gshhg_newfoundland_utm21n.geojson", "--band", NULL);
}

static void test_bad_layer_name(void **state)
{
    expect_info_failure("--layer", "nosuch", NEWFOUNDLAND, 1, "'nosuch'", NULL);
}

static void test_bad_band(void **state)
{
    expect_info_failure("--band", "3", VOLCANO, 1, "band 3", "dem_volcano_maunga_whau_10m.tif", NULL);
}

/* The same mismatches through the library: each reader refuses the other kind, naming the file. */
static void test_library_kind_mismatch(void **state)
{
    ft_io_init();
    ft_layer *l = NULL;
    ft_grid *g = NULL;
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_read_layer(VOLCANO, &lo, &l), FT_E_FORMAT);
    assert_null(l);
    assert_non_null(strstr(ft_last_error(), "dem_volcano_maunga_whau_10m.tif"));
    assert_int_equal(ft_io_read_grid(NEWFOUNDLAND, &go, &g), FT_E_FORMAT);
    assert_null(g);
    assert_non_null(strstr(ft_last_error(), "gshhg_newfoundland_utm21n.geojson"));
}

static void test_empty_layer(void **state)
{
    const char *p = ft_test_tmp_text("empty.geojson", "{\"type\":\"FeatureCollection\",\"features\":[]}\n");
    expect_info_failure(NULL, NULL, p, 1, "empty.geojson", NULL);
}

/* Runs info --json on path and expects success with a warning naming the file and `warning`. */
static json_object *expect_info_warning(const char *path, const char *name, const char *warning)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", "--json", path, NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "fracterra: info: warning: "));
    assert_non_null(strstr(r.err, name));
    assert_non_null(strstr(r.err, warning));
    json_object *o = ft_run_json(&r);
    assert_non_null(o);
    ft_run_free(&r);
    return o;
}

static void test_one_vertex_chain_gmt(void **state)
{
    const char *p = ft_test_tmp_text("short.gmt", ">\n0 0\n1 1\n2 2\n>\n5 5\n");
    json_object *o = expect_info_warning(p, "short.gmt", "1 chain has fewer than 2 vertices");
    assert_int_equal(ft_test_json_int(o, "short_chains"), 1);
    assert_int_equal(ft_test_json_int(o, "vertices"), 4);
    json_object_put(o);
}

static void test_one_vertex_chains_geojson(void **state)
{
    const char *p = ft_test_tmp_text("short.geojson",
                                     "{\"type\":\"FeatureCollection\",\"features\":["
                                     "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"LineString\","
                                     "\"coordinates\":[[0,0]]}},"
                                     "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"LineString\","
                                     "\"coordinates\":[[1,1]]}},"
                                     "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"LineString\","
                                     "\"coordinates\":[[0,0],[1,1],[2,0]]}}]}\n");
    json_object *o = expect_info_warning(p, "short.geojson", "2 chains have fewer than 2 vertices");
    json_object_put(o);
}

static void test_nan_geojson(void **state)
{
    const char *p = ft_test_tmp_text("nan.geojson",
                                     "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
                                     "\"properties\":{},\"geometry\":{\"type\":\"LineString\","
                                     "\"coordinates\":[[0,0],[1,NaN],[2,2]]}}]}\n");
    expect_info_failure(NULL, NULL, p, 1, "nan.geojson", "vertex 1", NULL);
}

static void test_nan_gmt_text(void **state)
{
    const char *p = ft_test_tmp_text("nan.gmt", "0 0\n1 nan\n2 2\n");
    expect_info_failure(NULL, NULL, p, 1, "nan.gmt:2", "nan", NULL);
}

static void test_non_numeric_csv(void **state)
{
    const char *p = ft_test_tmp_text("bad.csv", "x,y,z\n1,2,3\n4,abc,6\n");
    expect_info_failure(NULL, NULL, p, 1, "bad.csv:3", "'y'", "abc", NULL);
}

/* An all-nodata grid is reported (exit 0, valid 0, z_range null) with a warning. */
static void test_all_nodata_grid(void **state)
{
    const char *p = ft_test_tmp("all_nodata.tif");
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), p, 8, 6, 1, GDT_Float32, NULL);
    assert_non_null(ds);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    assert_int_equal(GDALSetRasterNoDataValue(b, -9999.0), CE_None);
    assert_int_equal(GDALFillRaster(b, -9999.0, 0.0), CE_None);
    GDALClose(ds);

    json_object *o = expect_info_warning(p, "all_nodata.tif", "nodata");
    assert_int_equal(ft_test_json_int(o, "valid"), 0);
    assert_int_equal(ft_test_json_int(o, "nodata"), 48);
    assert_null(ft_test_json_key(o, "z_range"));
    json_object_put(o);
}

static void test_demo_missing_parent(void **state)
{
    const char *parent = ft_test_tmp("no_such_parent");
    char *out = ft_test_path(parent, "out");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "demo", out, NULL), 0);
    assert_int_equal(r.status, 1);
    assert_int_equal(r.out_len, 0);
    assert_non_null(strstr(r.err, "fracterra: demo: "));
    assert_non_null(strstr(r.err, out));
    assert_false(ft_test_exists(parent));
    assert_int_equal(ft_test_dir_count(), 0);
    ft_run_free(&r);
    free(out);
}

/* Runs `fracterra demo out` with FRACTERRA_DATA=data and expects a failure (exit 1, "fracterra: demo: "
 * and needle in stderr) that leaves no OUTDIR behind. */
static void expect_demo_failure(const char *data, const char *out, const char *needle)
{
    setenv("FRACTERRA_DATA", data, 1);
    ft_run_result r;
    assert_int_equal(ft_run(&r, "demo", out, NULL), 0);
    unsetenv("FRACTERRA_DATA");
    assert_int_equal(r.status, 1);
    assert_non_null(strstr(r.err, "fracterra: demo: "));
    assert_non_null(strstr(r.err, needle));
    assert_false(ft_test_exists(out));
    ft_run_free(&r);
}

/* A demo step that fails (broken input data) removes what the demo wrote, and OUTDIR it created. */
static void test_demo_failure_leaves_nothing(void **state)
{
    const char *data = ft_test_tmp("data");
    char *tif = ft_test_path(data, "dem_volcano_maunga_whau_10m.tif");
    assert_int_equal(mkdir(data, 0777), 0);
    assert_int_equal(ft_test_write_text(tif, "this is not a GeoTIFF\n"), 0);
    expect_demo_failure(data, ft_test_tmp("out"), "dem_volcano_maunga_whau_10m.tif");
    free(tif);
}

static void test_demo_bad_data_dir(void **state)
{
    expect_demo_failure("/nonexistent/fracterra-data", ft_test_tmp("out"),
                        "fracterra: demo: FRACTERRA_DATA=/nonexistent/fracterra-data");
}

static void test_unknown_option_and_missing_argument(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", "--frobnicate", VOLCANO, NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: info: unknown option '--frobnicate'"));
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "info", "--json", NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: info: missing FILE"));
    assert_int_equal(r.out_len, 0);
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "demo", "--json", NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: demo: missing OUTDIR"));
    ft_run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_missing_file),
        cmocka_unit_test(test_garbage_bytes),
        cmocka_unit_test(test_raster_as_vector),
        cmocka_unit_test(test_vector_as_raster),
        cmocka_unit_test(test_bad_layer_name),
        cmocka_unit_test(test_bad_band),
        cmocka_unit_test(test_library_kind_mismatch),
        cmocka_unit_test(test_empty_layer),
        cmocka_unit_test(test_one_vertex_chain_gmt),
        cmocka_unit_test(test_one_vertex_chains_geojson),
        cmocka_unit_test(test_nan_geojson),
        cmocka_unit_test(test_nan_gmt_text),
        cmocka_unit_test(test_non_numeric_csv),
        cmocka_unit_test(test_all_nodata_grid),
        cmocka_unit_test(test_demo_missing_parent),
        cmocka_unit_test(test_demo_failure_leaves_nothing),
        cmocka_unit_test(test_demo_bad_data_dir),
        cmocka_unit_test(test_unknown_option_and_missing_argument),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
