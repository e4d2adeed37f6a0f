/* fracterra — end-to-end tests of longitude/latitude input (docs/geographic.md): every command either
 * measures in metres or refuses clearly. The twins in tests/data were made with ogr2ogr/gdalwarp from the
 * projected files (tests/data/README.md), so a lon/lat file and its projected twin must agree.
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
#include <unistd.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define NF_UTM FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"
#define NF_LONLAT FT_TEST_DATA "/gshhg_newfoundland_lonlat.geojson"
#define SKYE_LONLAT FT_TEST_DATA "/gshhg_skye_lonlat.geojson"
#define SKYE_UTM FT_TEST_DATA "/gshhg_skye_utm29n.geojson"
#define US_ALBERS FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"
#define US_LONLAT FT_TEST_DATA "/dcw_us_states_small_lonlat.geojson"
#define LUX_LONLAT FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"
#define LUX_UTM FT_TEST_DATA "/dem_luxembourg_utm32n.tif"

/* The value of the table row whose scale is nearest s. */
static double row_value(json_object *o, double s)
{
    json_object *t = ft_test_json_key(o, "table");
    double best = INFINITY, v = NAN;
    for (size_t i = 0; i < json_object_array_length(t); i++) {
        json_object *row = ft_test_json_at(t, i);
        double d = fabs(log(ft_test_json_num(row, "scale") / s));
        if (d < best) {
            best = d;
            v = ft_test_json_num(row, "value");
        }
    }
    return v;
}

/* `dim KIND FILE --min-scale MIN --max-scale MAX --json [--method METHOD]` on a lon/lat file (*g) and on its
 * projected twin (*p): the lon/lat report is in metres; returns |D(lon/lat) - D(projected)|. */
static double twin_d(const char *kind, const char *method, const char *lonlat, const char *projected,
                     const char *min, const char *max, json_object **g, json_object **p)
{
    const char *files[2] = {lonlat, projected};
    json_object **out[2] = {g, p};
    for (int k = 0; k < 2; k++) {
        const char *argv[] = {"dim", kind, files[k], "--min-scale", min, "--max-scale", max, "--json",
                              method ? "--method" : NULL, method, NULL};
        *out[k] = ft_test_run_json(argv);
    }
    assert_string_equal(ft_test_json_str(*g, "units"), "m");
    return fabs(ft_test_json_num(*g, "D") - ft_test_json_num(*p, "D"));
}

/* Newfoundland (47-52 N) in lon/lat and in UTM 21N: divider D over 1-100 km within 0.01, the walked length
 * at a 1 km ruler within 0.5%; scales in metres. */
static void test_dim_line_twin(void **state)
{
    (void)state;
    json_object *g = NULL, *p = NULL;
    double dd = twin_d("line", NULL, NF_LONLAT, NF_UTM, "1000", "100000", &g, &p);
    double lg = row_value(g, 1000.0), lp = row_value(p, 1000.0);
    print_message("  D lon/lat %.4f, UTM %.4f; L(1 km) %.0f m, %.0f m (%+.3f%%)\n", ft_test_json_num(g, "D"),
                  ft_test_json_num(p, "D"), lg, lp, 100.0 * (lg / lp - 1.0));
    assert_true(dd < 0.01);
    assert_true(fabs(lg / lp - 1.0) < 0.005);
    assert_string_equal(ft_test_json_str(p, "units"), "m");
    json_object *geo = ft_test_json_key(g, "geographic");
    assert_string_equal(ft_test_json_str(geo, "ellipsoid"), "WGS 84");
    assert_null(ft_test_json_key(geo, "projection")); /* walked on the ellipsoid */
    json_object_put(g);
    json_object_put(p);
}

/* The Isle of Skye (57.0-57.7 N) as GSHHG stores it, in lon/lat (nobody here projected it), and its ogr2ogr to
 * UTM 29N: divider D over 0.5-10 km within 0.01, the walked length at a 1 km ruler within 0.5%. */
static void test_dim_line_native_lonlat(void **state)
{
    (void)state;
    json_object *g = NULL, *p = NULL;
    double dd = twin_d("line", NULL, SKYE_LONLAT, SKYE_UTM, "500", "10000", &g, &p);
    double lg = row_value(g, 1000.0), lp = row_value(p, 1000.0);
    print_message("  Skye: D lon/lat %.4f, UTM %.4f; L(1 km) %.0f m, %.0f m (%+.4f%%)\n", ft_test_json_num(g, "D"),
                  ft_test_json_num(p, "D"), lg, lp, 100.0 * (lg / lp - 1.0));
    assert_true(dd < 0.01);
    assert_true(fabs(lg / lp - 1.0) < 0.005);
    assert_true(lg > 400e3 && lg < 600e3); /* metres: Skye's shore is some 500 km at this ruler, not degrees */
    assert_string_equal(ft_test_json_str(g, "units"), "m");
    json_object_put(g);
    json_object_put(p);
}

/* A wiggly line at 60 N over 1.2 degrees of longitude centred on lon_centre (180: across the antimeridian,
 * longitudes wrapped to [-180, 180]), as a lon/lat GeoJSON in the test's temporary folder. */
static const char *wiggly_line(const char *name, double lon_centre)
{
    enum { N = 1200 };
    size_t cap = 64 * (N + 1) + 512, len = 0;
    char *text = malloc(cap);
    assert_non_null(text);
    len += (size_t)snprintf(text + len, cap - len, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":"
                            "\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[");
    for (int i = 0; i <= N; i++) {
        double t = -0.6 + 1.2 * i / N, lon = lon_centre + t;
        double lat = 60.0 + 0.05 * sin(7.0 * M_PI * t) + 0.02 * sin(53.0 * t) + 0.01 * sin(211.0 * t + 1.0);
        lon = lon > 180.0 ? lon - 360.0 : lon;
        len += (size_t)snprintf(text + len, cap - len, "%s[%.9f,%.9f]", i ? "," : "", lon, lat);
    }
    snprintf(text + len, cap - len, "]}}]}");
    const char *path = ft_test_tmp_text(name, text);
    free(text);
    return path;
}

/* The antimeridian: the same line across +-180 and across Greenwich gives the same divider walk (Earth-centred
 * chords do not see the longitude jump) and the same box count (the equal-area projection is centred on 180,
 * not on the mean longitude 0); the same grid across it gives the same variogram. Data spanning more than 180
 * degrees of longitude either way are refused where a local projection is needed, with the span named. */
static void test_antimeridian(void **state)
{
    (void)state;
    const char *zero = wiggly_line("am_zero.geojson", 0.0), *cross = wiggly_line("am_cross.geojson", 180.0);
    const char *methods[2] = {"divider", "box"};
    for (int m = 0; m < 2; m++) {
        json_object *a = FT_TEST_RUN_JSON("dim", "line", zero, "--method", methods[m], "--min-scale", "500",
                                          "--max-scale", "5000", "--json");
        json_object *b = FT_TEST_RUN_JSON("dim", "line", cross, "--method", methods[m], "--min-scale", "500",
                                          "--max-scale", "5000", "--json");
        double da = ft_test_json_num(a, "D"), db = ft_test_json_num(b, "D");
        double va = row_value(a, 500.0), vb = row_value(b, 500.0);
        print_message("  %s: D %.5f / %.5f, value(500 m) %.6g / %.6g\n", methods[m], da, db, va, vb);
        assert_true(fabs(da - db) < 1e-3);
        assert_true(fabs(va / vb - 1.0) < 1e-3);
        if (m == 1)
            assert_non_null(strstr(ft_test_json_str(ft_test_json_key(b, "geographic"), "projection"), "180.0000E"));
        json_object_put(a);
        json_object_put(b);
    }
    const char *wide = ft_test_tmp_text(
        "am_wide.geojson", "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                           "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[-170,60],[-60,61],[60,60],[170,61]]}}]}");
    FT_TEST_EXPECT_FAILURE(1, "dim line", "am_wide.geojson spans 240.0 degrees of longitude", "dim", "line", wide,
                           "--method", "box");
    FT_TEST_EXPECT_FAILURE(1, "simplify", "spans 240.0 degrees of longitude", "simplify", wide,
                           ft_test_tmp("am_wide_s.geojson"), "--tolerance", "1000");
    assert_int_equal(access(ft_test_tmp("am_wide_s.geojson"), F_OK), -1);
    const char *grids[2] = {ft_test_tmp("am_g0.tif"), ft_test_tmp("am_g180.tif")};
    const char *origins[2] = {"-0.5,60.5", "179.5,60.5"};
    double d[2];
    for (int i = 0; i < 2; i++) {
        ft_run_result r;
        assert_int_equal(ft_run(&r, "synth", grids[i], "--dim", "2.3", "--size", "200x150", "--cell", "0.005",
                                "--origin", origins[i], "--crs", "EPSG:4326", "--sigma", "50", "--seed", "5", NULL), 0);
        assert_int_equal(r.status, 0);
        ft_run_free(&r);
        json_object *o = FT_TEST_RUN_JSON("dim", "surface", grids[i], "--min-scale", "500", "--max-scale", "5000",
                                          "--json");
        d[i] = ft_test_json_num(o, "D");
        json_object_put(o);
    }
    print_message("  grid across 180: D %.6f (across Greenwich %.6f)\n", d[1], d[0]);
    assert_true(fabs(d[0] - d[1]) < 1e-6);
}

/* Box counting of a lon/lat layer runs in a local equal-area projection, named; the result is in metres and
 * agrees with the Albers twin over the same box sizes. */
static void test_dim_line_box_projection(void **state)
{
    (void)state;
    json_object *g = NULL, *p = NULL;
    double dd = twin_d("line", "box", US_LONLAT, US_ALBERS, "2000", "50000", &g, &p);
    const char *proj = ft_test_json_str(ft_test_json_key(g, "geographic"), "projection");
    assert_non_null(strstr(proj, "Lambert azimuthal equal-area centred on"));
    print_message("  box D lon/lat (LAEA) %.4f, Albers %.4f\n", ft_test_json_num(g, "D"), ft_test_json_num(p, "D"));
    assert_true(dd < 0.02);
    json_object_put(g);
    json_object_put(p);
}

/* The README's metre range on a short lon/lat line: exit 1, naming the file, the range and the length in m. */
static void test_dim_line_rulers_too_long(void **state)
{
    (void)state;
    const char *line = ft_test_tmp_text(
        "short.geojson", "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                         "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[6.0,50.0],[6.03,50.01],"
                         "[6.07,50.0]]}}]}");
    FT_TEST_EXPECT_FAILURE(1, "dim line", "short.geojson, divider: ruler", "dim", "line", line, "--min-scale", "1000",
                           "--max-scale", "100000");
    FT_TEST_EXPECT_FAILURE(1, "dim line", "m long and", "dim", "line", line, "--min-scale", "1000", "--max-scale",
                           "100000", "--json");
    FT_TEST_EXPECT_FAILURE(1, "dim line", "[1000, 100000] m", "dim", "line", line, "--min-scale", "1000",
                           "--max-scale", "100000");
}

/* Polygon areas and box counts of the US states in lon/lat equal their Albers twin's (both equal-area). */
static void test_dim_area_twin(void **state)
{
    (void)state;
    json_object *g = FT_TEST_RUN_JSON("dim", "area", US_LONLAT, "--json");
    json_object *p = FT_TEST_RUN_JSON("dim", "area", US_ALBERS, "--json");
    double ag = ft_test_json_num(g, "area"), ap = ft_test_json_num(p, "area");
    print_message("  area lon/lat %.6g m2, Albers %.6g m2\n", ag, ap);
    assert_true(fabs(ag / ap - 1.0) < 1e-4);
    assert_string_equal(ft_test_json_str(g, "units"), "m");
    assert_non_null(strstr(ft_test_json_str(ft_test_json_key(g, "geographic"), "projection"), "equal-area"));
    json_object_put(g);
    json_object_put(p);
}

/* The Luxembourg DEM in lon/lat and its gdalwarp to UTM 32N: variogram D over 1.5-12 km within 0.02. */
static void test_dim_surface_twin(void **state)
{
    (void)state;
    json_object *g = NULL, *p = NULL;
    double dd = twin_d("surface", NULL, LUX_LONLAT, LUX_UTM, "1500", "12000", &g, &p);
    print_message("  variogram D lon/lat %.4f, UTM %.4f\n", ft_test_json_num(g, "D"), ft_test_json_num(p, "D"));
    assert_true(dd < 0.02);
    assert_non_null(strstr(ft_test_json_str(ft_test_json_key(g, "geographic"), "projection"), "Transverse Mercator"));
    json_object_put(g);
    json_object_put(p);
}

/* Clarke's model of the lon/lat DEM: the three strongest harmonics' waves (wavelength in metres, direction
 * from true north) are those of the UTM twin within 2% and 1 degree. The twins' grids differ in extent and
 * orientation (78 x 113 cells of 746 m in a local TM against 81 x 115 of 743 m in UTM 32N, whose grid north is
 * 2.19 degrees off true north here), so their modes (k, l) differ: each wave is matched to the twin's nearest. */
static double direction_gap(double a, double b)
{
    double d = fabs(a - b);
    return d > 90.0 ? 180.0 - d : d;
}

static void test_model_fit_twin(void **state)
{
    (void)state;
    json_object *g = FT_TEST_RUN_JSON("model", "fit", LUX_LONLAT, "--json");
    json_object *p = FT_TEST_RUN_JSON("model", "fit", LUX_UTM, "--json");
    assert_string_equal(ft_test_json_str(g, "units"), "m");
    json_object *hg = ft_test_json_key(g, "harmonics"), *hp = ft_test_json_key(p, "harmonics");
    assert_string_equal(ft_test_json_str(hg, "direction_from"), "true north");
    assert_string_equal(ft_test_json_str(hp, "direction_from"), "true north");
    assert_true(fabs(ft_test_json_num(hp, "grid_north_azimuth") - 2.19) < 0.02); /* UTM 32N at 6.1E 49.8N */
    json_object *lg = ft_test_json_key(hg, "list"), *lp = ft_test_json_key(hp, "list");
    assert_true(json_object_array_length(lg) >= 3);
    for (size_t i = 0; i < 3; i++) {
        json_object *a = ft_test_json_at(lg, i);
        double da = ft_test_json_num(a, "direction"), wa = ft_test_json_num(a, "wavelength");
        double best = INFINITY, db = NAN, wb = NAN;
        for (size_t j = 0; j < json_object_array_length(lp); j++) {
            json_object *b = ft_test_json_at(lp, j);
            double d = ft_test_json_num(b, "direction"), w = ft_test_json_num(b, "wavelength");
            double cost = direction_gap(da, d) + 100.0 * fabs(log(wa / w)); /* 1 deg ~ 1% */
            if (cost < best) {
                best = cost;
                db = d;
                wb = w;
            }
        }
        print_message("  harmonic (%d,%d): direction %.2f / %.2f deg, wavelength %.0f / %.0f m\n",
                      (int)ft_test_json_int(a, "k"), (int)ft_test_json_int(a, "l"), da, db, wa, wb);
        assert_true(direction_gap(da, db) < 1.0);
        assert_true(fabs(wa / wb - 1.0) < 0.02);
    }
    double b1g = ft_test_json_num(ft_test_json_key(g, "trend"), "beta1");
    double b1p = ft_test_json_num(ft_test_json_key(p, "trend"), "beta1");
    assert_true(fabs(b1g / b1p - 1.0) < 0.1); /* m of height per m east, not per degree */
    json_object_put(g);
    json_object_put(p);
}

/* dim map on lon/lat writes its D map in the local projection it measured in. */
static void test_dim_map(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("dmap.tif");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "dim", "map", LUX_LONLAT, out, "--window", "16", NULL), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    ft_grid *g = NULL;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_read_grid(out, &ro, &g), FT_OK);
    ft_crs_info crs;
    assert_int_equal(ft_io_crs_info(g->crs_wkt, &crs), FT_OK);
    assert_false(crs.geographic);
    assert_string_equal(crs.scale_unit, "m");
    ft_grid_free(g);
}

/* Scattered lon/lat elevations: lags in metres. */
static void test_dim_points(void **state)
{
    (void)state;
    char *text = malloc(200000);
    size_t n = (size_t)snprintf(text, 200000, "{\"type\":\"FeatureCollection\",\"features\":[");
    uint32_t u = 7u;
    for (int i = 0; i < 400; i++) {
        u = u * 1664525u + 1013904223u;
        double lon = 6.0 + 0.2 * (u >> 8) / 16777216.0;
        u = u * 1664525u + 1013904223u;
        double lat = 49.5 + 0.2 * (u >> 8) / 16777216.0;
        double z = 300.0 + 200.0 * sin(lon * 40.0) * cos(lat * 30.0);
        n += (size_t)snprintf(text + n, 200000 - n, "%s{\"type\":\"Feature\",\"properties\":{},\"geometry\":{"
                              "\"type\":\"Point\",\"coordinates\":[%.6f,%.6f,%.3f]}}", i ? "," : "", lon, lat, z);
    }
    snprintf(text + n, 200000 - n, "]}");
    const char *path = ft_test_tmp_text("pts.geojson", text);
    free(text);
    json_object *o = FT_TEST_RUN_JSON("dim", "points", path, "--json");
    assert_string_equal(ft_test_json_str(o, "units"), "m");
    assert_non_null(strstr(ft_test_json_str(ft_test_json_key(o, "geographic"), "projection"), "Transverse Mercator"));
    json_object *t = ft_test_json_key(o, "table");
    double s0 = ft_test_json_num(ft_test_json_at(t, 0), "scale");
    assert_true(s0 > 100.0 && s0 < 10000.0); /* 400 points over ~14 x 22 km: lags of hundreds of metres */
    json_object_put(o);
}

/* The line editors take metres on lon/lat input, edit in a local LAEA and write lon/lat back: weeding at
 * 500 m leaves about as many vertices as on the Albers twin, and the output is in WGS 84 again. */
static void test_line_editors(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("weeded.geojson"), *out2 = ft_test_tmp("weeded_albers.geojson");
    json_object *g = FT_TEST_RUN_JSON("weed", US_LONLAT, out, "--min-segment", "500", "--json");
    json_object *p = FT_TEST_RUN_JSON("weed", US_ALBERS, out2, "--min-segment", "500", "--json");
    double vg = (double)ft_test_json_int(g, "vertices_out"), vp = (double)ft_test_json_int(p, "vertices_out");
    print_message("  weed 500 m: %g vertices (lon/lat), %g (Albers)\n", vg, vp);
    assert_true(fabs(vg / vp - 1.0) < 0.02);
    assert_true(vg < 0.9 * (double)ft_test_json_int(g, "vertices_in"));
    assert_non_null(ft_test_json_key(g, "geographic"));
    ft_layer *l = ft_test_read_layer(out);
    ft_crs_info crs;
    assert_int_equal(ft_io_crs_info(l->crs_wkt, &crs), FT_OK);
    assert_true(crs.geographic);
    double x0, y0, x1, y1;
    assert_int_equal(ft_layer_bbox(l, &x0, &y0, &x1, &y1), FT_OK);
    assert_true(x0 > -115.0 && x1 < -70.0 && y0 > 30.0 && y1 < 45.0);
    ft_layer_free(l);
    json_object_put(g);
    json_object_put(p);
    static const char *const cmds[][6] = {
        {"simplify", "--tolerance", "1000", NULL, NULL, NULL},
        {"smooth", "--st", "5000", NULL, NULL, NULL},
        {"enhance", "--sd", "1.3", "--st", "5000", NULL},
        {"boundary", "--dim", "1.3", "--max", "5000", NULL},
    };
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        const char *o2 = ft_test_tmp("edited.geojson");
        json_object *r = FT_TEST_RUN_JSON(cmds[i][0], US_LONLAT, o2, cmds[i][1], cmds[i][2], "--json",
                                          cmds[i][3] ? cmds[i][3] : "--json", cmds[i][4] ? cmds[i][4] : "--json");
        assert_non_null(strstr(ft_test_json_str(ft_test_json_key(r, "geographic"), "projection"), "equal-area"));
        json_object_put(r);
        unlink(o2);
    }
}

/* Commands that cannot measure lon/lat say why and how to reproject, exit 1, write nothing. */
static void test_refusals(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("recon.tif");
    const char *pts = ft_test_tmp_text(
        "pts.geojson", "{\"type\":\"FeatureCollection\",\"features\":["
                       "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[6.0,49.5,300]}},"
                       "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[6.1,49.5,320]}},"
                       "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[6.0,49.6,310]}},"
                       "{\"type\":\"Feature\",\"properties\":{},\"geometry\":{\"type\":\"Point\",\"coordinates\":[6.1,49.6,330]}}]}");
    FT_TEST_EXPECT_FAILURE(1, "reconstruct", "longitude/latitude (WGS 84)", "reconstruct", pts, out, "--cell",
                           "100");
    assert_int_equal(access(out, F_OK), -1);
    /* voids of a lon/lat DEM are filled in its cells, with a warning giving their ground size */
    ft_run_result r;
    assert_int_equal(ft_run(&r, "reconstruct", LUX_LONLAT, out, NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "on the ground, and the voids are filled as if they were square"));
    ft_run_free(&r);
    FT_TEST_EXPECT_FAILURE(1, "mountain", "geographic CRS (WGS 84)", "mountain", US_LONLAT,
                           ft_test_tmp("m.geojson"));
}

/* fill of a lon/lat DEM fills in its own cells and says so with their ground size; model simulate of a model
 * fitted on lon/lat writes its grid in the local transverse Mercator it was fitted in, in metres. */
static void test_fill_and_simulate(void **state)
{
    (void)state;
    const char *filled = ft_test_tmp("fill.tif"), *model = ft_test_tmp("lux-model.json");
    const char *sim = ft_test_tmp("lux-sim.tif");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "fill", LUX_LONLAT, filled, NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.err, "its cells are 600 m x 927 m on the ground, and the voids are filled as if they "
                                  "were square"));
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "model", "fit", LUX_LONLAT, "-o", model, NULL), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "model", "simulate", model, sim, "--seed", "3", NULL), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    ft_grid *g = NULL;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_read_grid(sim, &ro, &g), FT_OK);
    ft_crs_info crs;
    assert_int_equal(ft_io_crs_info(g->crs_wkt, &crs), FT_OK);
    assert_false(crs.geographic);
    assert_non_null(strstr(crs.name, "Transverse Mercator centred on"));
    assert_true(fabs(g->gt[1] - 745.57) < 1.0); /* the geometric mean of the 600 m x 927 m ground cells */
    ft_grid_free(g);
}

/* hillshade of a lon/lat DEM takes the ellipsoid's metres per degree of latitude at its centre as scale:
 * the same image as --scale 111229 (the textbook length of a degree of latitude at 50 N), within one grey
 * level, and not the image of --scale 1 (degrees taken as metres). */
static void test_hillshade(void **state)
{
    (void)state;
    const char *scales[3] = {NULL, "111229", "1"};
    ft_grid *g[3] = {NULL, NULL, NULL};
    for (int i = 0; i < 3; i++) {
        const char *out = ft_test_tmp(i == 0 ? "s0.tif" : i == 1 ? "s1.tif" : "s2.tif");
        ft_run_result r;
        if (scales[i])
            assert_int_equal(ft_run(&r, "hillshade", LUX_LONLAT, out, "--scale", scales[i], NULL), 0);
        else
            assert_int_equal(ft_run(&r, "hillshade", LUX_LONLAT, out, NULL), 0);
        assert_int_equal(r.status, 0);
        ft_run_free(&r);
        ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
        assert_int_equal(ft_io_read_grid(out, &ro, &g[i]), FT_OK);
    }
    double d1 = 0.0, d2 = 0.0;
    for (size_t k = 0; k < g[0]->nx * g[0]->ny; k++) {
        d1 = fmax(d1, fabs(g[0]->z[k] - g[1]->z[k]));
        d2 = fmax(d2, fabs(g[0]->z[k] - g[2]->z[k]));
    }
    print_message("  max grey difference: %g against --scale 111229, %g against --scale 1\n", d1, d2);
    assert_true(d1 <= 1.0);
    assert_true(d2 > 20.0);
    for (int i = 0; i < 3; i++)
        ft_grid_free(g[i]);
}

/* info says what the measuring commands will do, and a lon/lat grid's ground cells: 30" at 49.8 N are about
 * 600 m x 927 m (a degree of longitude is 71 696 m at 50 N, of latitude 111 229 m: textbook values). */
static void test_info(void **state)
{
    (void)state;
    json_object *o = FT_TEST_RUN_JSON("info", LUX_LONLAT, "--json");
    json_object *crs = ft_test_json_key(o, "crs");
    assert_true(json_object_get_boolean(ft_test_json_key(crs, "geographic")));
    assert_string_equal(ft_test_json_str(crs, "ellipsoid"), "WGS 84");
    json_object *g = ft_test_json_key(o, "ground_cell_size");
    assert_true(fabs(json_object_get_double(json_object_array_get_idx(g, 0)) / (71696.0 / 120.0) - 1.0) < 0.01);
    assert_true(fabs(json_object_get_double(json_object_array_get_idx(g, 1)) / (111229.0 / 120.0) - 1.0) < 0.001);
    json_object_put(o);
}

/* urban table of the lon/lat states: areas in square metres, equal to the Albers twin's. */
static void test_urban_table(void **state)
{
    (void)state;
    const char *t1 = ft_test_tmp("t1.json"), *t2 = ft_test_tmp("t2.json");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "urban", "table", US_LONLAT, "--class", "code", "-o", t1, NULL), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "urban", "table", US_ALBERS, "--class", "code", "-o", t2, NULL), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    json_object *a = json_object_from_file(t1), *b = json_object_from_file(t2);
    assert_non_null(a);
    assert_non_null(b);
    double aa = ft_test_json_num(ft_test_json_at(ft_test_json_key(a, "rows"), 0), "area");
    double ab = ft_test_json_num(ft_test_json_at(ft_test_json_key(b, "rows"), 0), "area");
    assert_true(fabs(aa / ab - 1.0) < 1e-4);
    json_object_put(a);
    json_object_put(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dim_line_twin),
        cmocka_unit_test(test_dim_line_native_lonlat),
        cmocka_unit_test(test_antimeridian),
        cmocka_unit_test(test_fill_and_simulate),    cmocka_unit_test(test_dim_line_box_projection),
        cmocka_unit_test(test_dim_line_rulers_too_long), cmocka_unit_test(test_dim_area_twin),
        cmocka_unit_test(test_dim_surface_twin), cmocka_unit_test(test_model_fit_twin),
        cmocka_unit_test(test_dim_map),          cmocka_unit_test(test_dim_points),
        cmocka_unit_test(test_line_editors),     cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_hillshade),        cmocka_unit_test(test_info),
        cmocka_unit_test(test_urban_table),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
