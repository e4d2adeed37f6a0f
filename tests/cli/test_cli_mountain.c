/* fracterra — tests/cli/test_cli_mountain.c: `fracterra mountain` end to end on the bundled seed contour
 * (the 130 m contour of Maunga Whau): the contour layer read back through OGR (one `elev` per level, in
 * steps of the interval, the seed's CRS, every level inside the one below), the DEM and the bird's-eye
 * view read back, the same seed giving the same bytes, a closed GMT text ring as seed, and every error
 * (exit code, message naming the culprit, nothing written).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fracterra/fracterra.h"
#include "ft_test_assert.h"
#include "ft_test_util.h"

#define SEED FT_TEST_DATA "/seed_contour_volcano.geojson"
#define SEED_ELEV 130.0

/* The features' `elev` values, in file order. */
static double *read_elevs(const ft_layer *l)
{
    int k = ft_layer_field_index(l, "elev");
    assert_true(k >= 0);
    assert_int_equal(l->fields[k].type, FT_FIELD_REAL);
    double *e = malloc(l->nfeatures * sizeof *e);
    assert_non_null(e);
    for (size_t f = 0; f < l->nfeatures; f++) {
        assert_false(l->features[f].values[k].is_null);
        e[f] = l->features[f].values[k].r;
    }
    return e;
}

static void assert_png(const char *path, int width)
{
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    assert_int_equal(cairo_image_surface_get_width(s), width);
    cairo_surface_destroy(s);
}

/* The mountain with a foot, its DEM and view: what was written reads back and agrees with the JSON. */
static void test_mountain_end_to_end(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("contours.gpkg"), *dem = ft_test_tmp("dem.tif"), *view = ft_test_tmp("view.png");
    const char *map = ft_test_tmp("map.svg");
    json_object *o = FT_TEST_RUN_JSON("mountain", SEED, out, "--interval", "5", "--levels-down", "2", "--levels-up",
                                      "6", "--seed", "3", "--dem", dem, "--cell", "4", "--view", view, "--map", map,
                                      "--json");
    assert_string_equal(ft_test_json_str(o, "method"), "improved");
    assert_string_equal(ft_test_json_str(o, "join"), "dprime");
    assert_int_equal(ft_test_json_int(o, "seed"), 3);
    assert_near(ft_test_json_num(o, "seed_elevation"), SEED_ELEV, 0.0); /* from the seed's `elev` field */
    assert_near(ft_test_json_num(o, "interval"), 5.0, 0.0);
    assert_true(ft_test_json_num(o, "spacing") > 0.0);
    int64_t levels = ft_test_json_int(o, "levels");
    assert_int_equal(levels, 9); /* 2 below, the seed, 6 above (the volcano is wide enough) */
    json_object *elevs = ft_test_json_key(o, "elevations"), *verts = ft_test_json_key(o, "vertices");
    assert_int_equal(json_object_array_length(elevs), (size_t)levels);
    assert_int_equal(json_object_array_length(verts), (size_t)levels);
    for (int64_t k = 0; k < levels; k++) {
        assert_near(json_object_get_double(ft_test_json_at(elevs, (size_t)k)), SEED_ELEV + 5.0 * (double)(k - 2),
                    1e-9);
        assert_true(json_object_get_int64(ft_test_json_at(verts, (size_t)k)) >= 3);
    }
    assert_int_equal(json_object_array_length(ft_test_json_key(o, "outputs")), 4);
    json_object *d = ft_test_json_key(o, "dem");
    assert_near(ft_test_json_num(d, "cell"), 4.0, 0.0);
    json_object_put(o);

    /* the contour layer: elev non-decreasing over the features, every level present, the seed's CRS */
    ft_layer *l = ft_test_read_layer(out);
    ft_test_assert_crs_epsg(l->crs_wkt, 27200);
    double *e = read_elevs(l);
    int seen[9] = {0};
    for (size_t f = 0; f < l->nfeatures; f++) {
        assert_int_equal(l->features[f].type, FT_GEOM_POLYGON);
        if (f > 0)
            assert_true(e[f] >= e[f - 1]);
        double k = (e[f] - (SEED_ELEV - 10.0)) / 5.0;
        assert_true(k >= 0.0 && k <= 8.0 && k == floor(k));
        seen[(int)k] = 1;
    }
    for (int k = 0; k < 9; k++)
        assert_true(seen[k]);
    free(e);
    /* each level lies inside the level below it (read back through the library's own stack reader) */
    ft_contour_stack *st = NULL;
    assert_int_equal(ft_contour_stack_from_layer(l, "elev", &st), FT_OK);
    assert_int_equal(st->n, 9);
    for (size_t k = 1; k < st->n; k++)
        assert_true(ft_polygon_set_within(st->levels[k].polys, st->levels[k - 1].polys));
    ft_contour_stack_free(st);
    ft_layer_free(l);

    /* the DEM: the seed's CRS, nodata outside the foot, elevations from the lowest contour to the summit */
    ft_grid *g = NULL;
    assert_int_equal(ft_io_read_grid(dem, NULL, &g), FT_OK);
    ft_test_assert_crs_epsg(g->crs_wkt, 27200);
    assert_near(g->gt[1], 4.0, 0.0);
    double zmin, zmax;
    assert_int_equal(ft_grid_minmax(g, &zmin, &zmax), FT_OK);
    assert_true(zmin >= SEED_ELEV - 10.0 && zmin < SEED_ELEV - 10.0 + 5.0);
    assert_true(zmax > SEED_ELEV + 30.0 && zmax <= SEED_ELEV + 30.0 + 0.5 * 5.0 + 1e-3);
    assert_true(ft_grid_count_valid(g) < g->nx * g->ny);
    ft_grid_free(g);
    assert_png(view, 1200);
    char *svg = ft_test_read_svg(map, NULL);
    int paths = 0;
    for (const char *q = svg; (q = strstr(q, "<path")) != NULL; q++)
        paths++;
    assert_true(paths >= 4); /* contours, seed and the legend's samples */
    free(svg);
    assert_int_equal(ft_test_dir_count(), 4); /* no temporary left behind */
}

/* Runs the mountain of the bundled seed into out with a seed; returns the file's bytes. */
static char *grow_bytes(const char *out, const char *seed, size_t *n)
{
    const char *argv[] = {"mountain", SEED, out, "--interval", "5", "--levels-up", "5", "--levels-down", "1",
                          "--seed", seed, NULL};
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    char *bytes = ft_test_read_file(out, n);
    assert_non_null(bytes);
    return bytes;
}

/* The JSON reports the d' the library applied, the paper's value for each method (Misawa et al.: 3 d for
 * the improved method, 1.4 d for midpoint and Fourier, Figs. 12 and 15), not a value re-derived by the CLI;
 * an explicit --dprime is reported as given. */
static void test_dprime_reported_as_applied(void **state)
{
    (void)state;
    static const struct {
        const char *method;
        double dprime;
    } cases[] = {{"improved", 3.0}, {"midpoint", 1.4}, {"fourier", 1.4}, {"simple", 1.2}};
    const char *out = ft_test_tmp("dp.geojson");
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        json_object *o = FT_TEST_RUN_JSON("mountain", SEED, out, "--interval", "5", "--levels-up", "2",
                                          "--method", cases[i].method, "--seed", "3", "--json");
        assert_near(ft_test_json_num(o, "dprime"), cases[i].dprime, 0.0);
        json_object_put(o);
    }
    json_object *o = FT_TEST_RUN_JSON("mountain", SEED, out, "--interval", "5", "--levels-up", "2", "--method",
                                      "midpoint", "--dprime", "1.7", "--json");
    assert_near(ft_test_json_num(o, "dprime"), 1.7, 0.0);
    json_object_put(o);
}

/* The crossing guard is reported: the Fourier method moves every vertex of every randomized ring (counted,
 * some reduced or dropped on this seed, never more than moved); --allow-crossings reports no guard, and
 * its contours differ from the guarded ones; the text report has the guard's line. */
static void test_crossing_guard_report(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("guard.geojson");
    json_object *o = FT_TEST_RUN_JSON("mountain", SEED, out, "--method", "fourier", "--f0", "16", "--levels-up",
                                      "8", "--seed", "2", "--json");
    assert_false(json_object_get_boolean(ft_test_json_key(o, "allow_crossings")));
    json_object *g = ft_test_json_key(o, "crossing_guard");
    assert_non_null(g);
    int64_t moves = ft_test_json_int(g, "moves"), reduced = ft_test_json_int(g, "reduced"),
            dropped = ft_test_json_int(g, "dropped");
    print_message("fourier, f0 16, 8 levels up: %lld moves, %lld reduced, %lld dropped\n", (long long)moves,
                  (long long)reduced, (long long)dropped);
    assert_int_equal(moves, 8 * 1024); /* one ring per level, n = 1024 */
    assert_true(reduced + dropped > 0 && reduced + dropped <= moves);
    int64_t levels = ft_test_json_int(o, "levels");
    json_object_put(o);
    size_t na = 0, nb = 0;
    char *a = ft_test_read_file(out, &na);
    unlink(out);
    o = FT_TEST_RUN_JSON("mountain", SEED, out, "--method", "fourier", "--f0", "16", "--levels-up", "8", "--seed",
                         "2", "--allow-crossings", "--json");
    assert_true(json_object_get_boolean(ft_test_json_key(o, "allow_crossings")));
    assert_null(ft_test_json_key(o, "crossing_guard"));
    assert_int_equal(ft_test_json_int(o, "levels"), levels);
    json_object_put(o);
    char *b = ft_test_read_file(out, &nb); /* the same file name: only the contours can differ */
    assert_true(na != nb || memcmp(a, b, na) != 0);
    free(a);
    free(b);
    ft_run_result r;
    assert_int_equal(ft_run(&r, "mountain", SEED, ft_test_tmp("text.geojson"), "--method", "midpoint", "--levels-up",
                            "3", NULL),
                     0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "crossing guard: "));
    ft_run_free(&r);
}

/* Same seed, same bytes (the same file name, so that the layer names agree); another seed, other
 * contours; --lines writes rings as lines. */
static void test_same_seed_same_output(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("m.geojson"), *lines = ft_test_tmp("lines.geojson");
    size_t na, nb, nc;
    char *a = grow_bytes(out, "11", &na), *b = grow_bytes(out, "11", &nb), *c = grow_bytes(out, "12", &nc);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na);
    assert_true(na != nc || memcmp(a, c, na) != 0);
    free(a);
    free(b);
    free(c);

    json_object *o = FT_TEST_RUN_JSON("mountain", SEED, lines, "--interval", "5", "--levels-up", "5",
                                      "--method", "simple", "--join", "round", "--lines", "--json");
    assert_string_equal(ft_test_json_str(o, "method"), "simple");
    assert_string_equal(ft_test_json_str(o, "join"), "round");
    json_object_put(o);
    ft_layer *l = ft_test_read_layer(lines);
    for (size_t f = 0; f < l->nfeatures; f++)
        assert_int_equal(l->features[f].type, FT_GEOM_LINE);
    ft_layer_free(l);
}

/* A closed chain in GMT text is a seed; without an `elev` field the seed sits at --seed-elevation. */
static void test_text_seed(void **state)
{
    (void)state;
    const char *seed = ft_test_tmp_text("square.gmt", "> a 400 m square\n0 0\n400 0\n400 400\n0 400\n0 0\n");
    const char *out = ft_test_tmp("square.gpkg");
    json_object *o = FT_TEST_RUN_JSON("mountain", seed, out, "--interval", "20", "--spacing", "25",
                                      "--seed-elevation", "500", "--method", "fourier", "--f0", "64", "--n", "256",
                                      "--json");
    assert_near(ft_test_json_num(o, "seed_elevation"), 500.0, 0.0);
    assert_near(ft_test_json_num(o, "spacing"), 25.0, 0.0);
    int64_t levels = ft_test_json_int(o, "levels");
    /* a 400 m square shrunk by 25 m per level vanishes after about 200 / 25 = 8 levels */
    assert_true(levels >= 6 && levels <= 8);
    json_object_put(o);
    ft_layer *l = ft_test_read_layer(out);
    double *e = read_elevs(l);
    assert_near(e[0], 500.0, 0.0);
    free(e);
    ft_layer_free(l);
}

/* A seed in degrees (GeoJSON without a crs member is WGS 84) is refused: spacing and shrinking are ground
 * lengths. The error names the file and the CRS, and nothing is written. */
static void test_geographic_seed_refused(void **state)
{
    (void)state;
    const char *seed = ft_test_tmp_text(
        "lonlat.geojson", "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                          "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[6.0,49.5],[6.01,49.5],[6.01,49.51],"
                          "[6.0,49.51],[6.0,49.5]]]}}]}");
    ft_run_result r;
    const char *out = ft_test_tmp("out_geo.geojson");
    assert_int_equal(ft_run(&r, "mountain", seed, out, "--method", "simple", NULL), 0);
    assert_int_equal(r.status, 1);
    assert_non_null(strstr(r.err, "fracterra: mountain: "));
    assert_non_null(strstr(r.err, "geographic CRS (WGS 84)"));
    assert_non_null(strstr(r.err, "reproject"));
    assert_int_equal(access(out, F_OK), -1);
    ft_run_free(&r);
}

static void test_errors(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("out.gpkg"), *dem = ft_test_tmp("dem.tif");
    const char *open_line = ft_test_tmp_text(
        "open.geojson", "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                        "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0],[10,0],[10,10]]}}]}");
    const char *empty = ft_test_tmp_text("empty.geojson", "{\"type\":\"FeatureCollection\",\"features\":[]}");
    /* bad files: exit 1 */
    FT_TEST_EXPECT_FAILURE(1, "mountain", "missing.geojson", "mountain", FT_TEST_DATA "/missing.geojson", out);
    FT_TEST_EXPECT_FAILURE(1, "mountain", "empty.geojson", "mountain", empty, out);
    FT_TEST_EXPECT_FAILURE(1, "mountain", "open.geojson", "mountain", open_line, out);
    FT_TEST_EXPECT_FAILURE(1, "mountain", "no line or polygon", "mountain", SEED, out, "--where", "elev = 99");
    FT_TEST_EXPECT_FAILURE(1, "mountain", "no-such-folder", "mountain", SEED, "/tmp/no-such-folder/out.gpkg");
    /* an unwritable view: nothing at all is written, not even OUT */
    FT_TEST_EXPECT_FAILURE(1, "mountain", "no-such-folder", "mountain", SEED, out, "--levels-up", "2", "--view",
                           "/tmp/no-such-folder/v.png");
    FT_TEST_EXPECT_FAILURE(1, "mountain", "no-such-folder", "mountain", SEED, out, "--levels-up", "2", "--dem", dem,
                           "--map", "/tmp/no-such-folder/m.svg");
    /* GDAL's BMP driver cannot hold a Float32 DEM: that fails after OUT was made, and OUT is not left behind */
    FT_TEST_EXPECT_FAILURE(1, "mountain", "dem.bmp (nothing was written)", "mountain", SEED, out, "--levels-up", "2",
                           "--dem", ft_test_tmp("dem.bmp"));
    /* bad usage: exit 2 */
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--interval", "mountain", SEED, out, "--interval", "0");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--interval", "mountain", SEED, out, "--interval", "-5");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--spacing", "mountain", SEED, out, "--spacing", "nan");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--method", "mountain", SEED, out, "--method", "fractal");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--join", "mountain", SEED, out, "--join", "square");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--dprime", "mountain", SEED, out, "--dprime", "0.5");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--theta", "mountain", SEED, out, "--theta", "40,20");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--theta", "mountain", SEED, out, "--theta", "10");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--f0", "mountain", SEED, out, "--f0", "600");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--f0", "mountain", SEED, out, "--method", "simple", "--f0", "64");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--cell", "mountain", SEED, out, "--cell", "2");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--cell", "mountain", SEED, out, "--dem", dem, "--cell", "0");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "same file", "mountain", SEED, dem, "--dem", dem);
    FT_TEST_EXPECT_FAILURE(2, "mountain", "same file", "mountain", SEED, out, "--view", "v.png", "--map", "v.png");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--view", "mountain", SEED, out, "--view", "v.jpg");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--map", "mountain", SEED, out, "--map", "m.bmp");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "--seed", "mountain", SEED, out, "--seed", "-1");
    FT_TEST_EXPECT_FAILURE(2, "mountain", "OUT", "mountain", SEED);
    FT_TEST_EXPECT_FAILURE(2, "mountain", "stdout", "mountain", SEED, "-");
    assert_int_equal(ft_test_dir_count(), 2); /* the two seed files written above, nothing else */
}

static void test_help(void **state)
{
    (void)state;
    ft_run_result r;
    assert_int_equal(ft_run(&r, "mountain", "--help", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "Example:"));
    assert_non_null(strstr(r.out, "--levels-down"));
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "--help", NULL), 0);
    assert_non_null(strstr(r.out, "mountain"));
    ft_run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mountain_end_to_end), cmocka_unit_test(test_dprime_reported_as_applied),
        cmocka_unit_test(test_same_seed_same_output), cmocka_unit_test(test_crossing_guard_report),
        cmocka_unit_test(test_text_seed),           cmocka_unit_test(test_geographic_seed_refused),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_help),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
