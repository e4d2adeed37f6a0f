/* fracterra — tests/cli/test_cli_urban.c: the urban commands end to end, through the built binary: `dim area`
 * (a filled square has D = 2 by area and 1 by boundary, one result per class with --class, a classified
 * raster class by class, plots), `urban table` and `urban regress` (a table written as CSV and JSON and read
 * back; the paper's Table 2 gives r = 0.954), `boundary` (output GDAL reads with CRS and attributes, shared
 * boundaries kept identical, segments longer than --max unchanged, same seed same bytes), bad input for
 * every command, and --help.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cpl_conv.h>
#include <gdal.h>
#include <math.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define US_STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"
#define CRS_UTM21N "\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"urn:ogc:def:crs:EPSG::32621\"}},"

/* ---- fixtures ---- */

/* A GeoJSON square ring [x, x + s] x [y, y + s] (closed, counter-clockwise). */
static void square_coords(char *buf, size_t size, double x, double y, double s)
{
    snprintf(buf, size, "[[[%g,%g],[%g,%g],[%g,%g],[%g,%g],[%g,%g]]]", x, y, x + s, y, x + s, y + s, x, y + s, x, y);
}

/* A polygon layer of n squares (x, y, side) with the land use `use` of each, EPSG:32621. */
static const char *write_squares(const char *name, const double (*sq)[3], const char *const *use, size_t n)
{
    char *text = malloc(512 * (n + 1)), ring[256];
    assert_non_null(text);
    size_t len = (size_t)sprintf(text, "{\"type\":\"FeatureCollection\"," CRS_UTM21N "\"features\":[");
    for (size_t i = 0; i < n; i++) {
        square_coords(ring, sizeof ring, sq[i][0], sq[i][1], sq[i][2]);
        len += (size_t)sprintf(text + len,
                               "%s{\"type\":\"Feature\",\"properties\":{\"use\":\"%s\",\"n\":%zu},"
                               "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":%s}}",
                               i ? "," : "", use[i], i, ring);
    }
    sprintf(text + len, "]}\n");
    const char *path = ft_test_tmp_text(name, text);
    free(text);
    return path;
}

/* One filled square of side 1000. */
static const char *write_square(const char *name)
{
    static const double sq[1][3] = {{500000.0, 5000000.0, 1000.0}};
    static const char *const use[1] = {"residential"};
    return write_squares(name, sq, use, 1);
}

/* Three squares: two residential (sides 400 and 300) and one industrial (side 500). */
static const char *write_landuse(const char *name)
{
    static const double sq[3][3] = {{0.0, 0.0, 400.0}, {1000.0, 0.0, 300.0}, {0.0, 1000.0, 500.0}};
    static const char *const use[3] = {"residential", "residential", "industrial"};
    return write_squares(name, sq, use, 3);
}

/* Appends the vertices of a Koch island of `level` levels on a triangle of side `side` (clockwise, bumps
 * outward), starting at (x0, y0): 3 * 4^level vertices, as GeoJSON pairs. */
static size_t put_koch_island(char *text, int level, double side, double x0, double y0)
{
    size_t steps = 1, len = 0;
    for (int i = 0; i < level; i++)
        steps *= 4;
    double step = side / pow(3.0, level), x = x0, y = y0;
    for (int e = 0; e < 3; e++)
        for (size_t k = 0; k < steps; k++) {
            int turn = 0;
            for (size_t q = k; q > 0; q /= 4)
                turn += (q % 4 == 1) ? 1 : (q % 4 == 2) ? -1 : 0;
            double a = (turn * 60.0 - e * 120.0) * M_PI / 180.0;
            len += (size_t)sprintf(text + len, "[%.6f,%.6f],", x, y);
            x += step * cos(a);
            y += step * sin(a);
        }
    return len + (size_t)sprintf(text + len, "[%.6f,%.6f]", x0, y0);
}

/* A year's map: a residential Koch island whose level (detail, D and area) grows with the year, and a fixed
 * industrial square. */
static const char *write_year(const char *name, int level)
{
    char *text = malloc(64 * 3 * 256 + 2048), ring[256];
    assert_non_null(text);
    size_t len = (size_t)sprintf(text, "{\"type\":\"FeatureCollection\"," CRS_UTM21N "\"features\":["
                                       "{\"type\":\"Feature\",\"properties\":{\"use\":\"residential\"},"
                                       "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[");
    len += put_koch_island(text + len, level, 2700.0, 0.0, 3000.0);
    square_coords(ring, sizeof ring, 5000.0, 0.0, 800.0);
    sprintf(text + len, "]]}},{\"type\":\"Feature\",\"properties\":{\"use\":\"industrial\"},"
                        "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":%s}}]}\n",
            ring);
    const char *path = ft_test_tmp_text(name, text);
    free(text);
    return path;
}

/* A 200 x 200 classified raster of 10 m cells: class 1 on the left half, 2 on the right, EPSG:32621. */
static const char *write_classes_tif(const char *name)
{
    ft_grid *g = ft_grid_create(200, 200);
    assert_non_null(g);
    for (size_t r = 0; r < 200; r++)
        for (size_t c = 0; c < 200; c++)
            g->z[r * 200 + c] = c < 100 ? 1.0f : 2.0f;
    double gt[6] = {500000.0, 10.0, 0.0, 5002000.0, 0.0, -10.0};
    memcpy(g->gt, gt, sizeof gt);
    char *wkt = NULL;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:32621", &wkt), FT_OK);
    assert_int_equal(ft_grid_set_crs(g, wkt), FT_OK);
    free(wkt);
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    const char *path = ft_test_tmp(name);
    assert_int_equal(ft_io_write_grid(path, g, &wo), FT_OK);
    ft_grid_free(g);
    return path;
}

/* Two squares sharing a zigzag boundary x = 10 + (i % 2) * 0.5, y = i (i = 0..10), EPSG:32621. */
static const char *write_coverage(const char *name)
{
    char text[4096];
    size_t len = (size_t)sprintf(text, "{\"type\":\"FeatureCollection\"," CRS_UTM21N "\"features\":["
                                       "{\"type\":\"Feature\",\"properties\":{\"name\":\"west\",\"code\":1},"
                                       "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[0,0]");
    for (int i = 0; i <= 10; i++)
        len += (size_t)sprintf(text + len, ",[%g,%d]", 10.0 + (i % 2) * 0.5, i);
    len += (size_t)sprintf(text + len, ",[0,10],[0,0]]]}},{\"type\":\"Feature\",\"properties\":{\"name\":\"east\","
                                       "\"code\":2},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[20,0],"
                                       "[20,10]");
    for (int i = 10; i >= 0; i--)
        len += (size_t)sprintf(text + len, ",[%g,%d]", 10.0 + (i % 2) * 0.5, i);
    sprintf(text + len, ",[20,0]]]}}]}\n");
    return ft_test_tmp_text(name, text);
}

/* The members every estimator prints (DESIGN.md "JSON results"). */
static void assert_result_shape(json_object *r)
{
    assert_non_null(ft_test_json_str(r, "method"));
    assert_true(isfinite(ft_test_json_num(r, "D")) && ft_test_json_num(r, "r2") >= 0.0 &&
                ft_test_json_num(r, "r2") <= 1.0 && ft_test_json_num(r, "stderr") >= 0.0);
    assert_int_equal(json_object_array_length(ft_test_json_key(r, "range")), 2);
    json_object *t = ft_test_json_key(r, "table");
    assert_true(json_object_array_length(t) >= 3);
    for (size_t i = 0; i < json_object_array_length(t); i++) {
        json_object *row = ft_test_json_at(t, i);
        assert_true(ft_test_json_num(row, "scale") > 0.0 && ft_test_json_num(row, "value") > 0.0 &&
                    ft_test_json_num(row, "count") >= 0.0);
        ft_test_json_key(row, "slope");
        ft_test_json_key(row, "used");
    }
}

/* ---- dim area ---- */

/* The accuracy case: a filled square gives 2 +- 0.02 by area and 1 +- 0.02 by boundary. */
static void test_dim_area_filled_square(void **state)
{
    const char *sq = write_square("square.geojson");
    json_object *a = FT_TEST_RUN_JSON("dim", "area", sq, "--what", "area", "--json");
    json_object *b = FT_TEST_RUN_JSON("dim", "area", sq, "--json");
    assert_result_shape(a);
    assert_result_shape(b);
    fprintf(stderr, "filled square: area D = %.4f, boundary D = %.4f\n", ft_test_json_num(a, "D"), ft_test_json_num(b,
            "D"));
    assert_true(fabs(ft_test_json_num(a, "D") - 2.0) <= 0.02);
    assert_true(fabs(ft_test_json_num(b, "D") - 1.0) <= 0.02);
    assert_string_equal(ft_test_json_str(a, "what"), "area");
    assert_string_equal(ft_test_json_str(b, "what"), "boundary");
    assert_string_equal(ft_test_json_str(a, "method"), "box-area");
    assert_true(fabs(ft_test_json_num(a, "area") - 1e6) < 1e-6);
    assert_int_equal(ft_test_json_int(a, "polygons"), 1);
    assert_true(fabs(ft_test_json_num(a, "perimeter") - 4000.0) < 1e-9);
    json_object_put(a);
    json_object_put(b);

    /* explicit box sides: every one counted, D fitted over all of them */
    json_object *c = FT_TEST_RUN_JSON("dim", "area", sq, "--what", "area", "--cell", "10,20", "--cell", "40",
                                      "--fewest-boxes", "--json");
    json_object *t = ft_test_json_key(c, "table");
    assert_int_equal(json_object_array_length(t), 3);
    for (size_t i = 0; i < 3; i++)
        assert_true(json_object_get_boolean(ft_test_json_key(ft_test_json_at(t, i), "used")));
    assert_true(fabs(ft_test_json_num(ft_test_json_at(t, 0), "value") - 10000.0) < 0.5); /* (1000 / 10)^2 boxes */
    assert_true(fabs(ft_test_json_num(c, "D") - 2.0) <= 0.02);
    json_object_put(c);
}

/* --class: the whole layer, then one entry per class (sorted), typed ids, the figures of each. */
static void test_dim_area_classes(void **state)
{
    const char *in = write_landuse("landuse.geojson");
    json_object *o = FT_TEST_RUN_JSON("dim", "area", in, "--class", "use", "--what", "area", "--json");
    assert_string_equal(ft_test_json_str(o, "class"), "use");
    json_object *f = ft_test_json_key(o, "features");
    assert_int_equal(json_object_array_length(f), 3);
    assert_null(ft_test_json_key(ft_test_json_at(f, 0), "id"));
    assert_string_equal(ft_test_json_str(ft_test_json_at(f, 0), "scope"), "layer");
    assert_string_equal(ft_test_json_str(ft_test_json_at(f, 1), "id"), "industrial");
    assert_string_equal(ft_test_json_str(ft_test_json_at(f, 2), "id"), "residential");
    assert_string_equal(ft_test_json_str(ft_test_json_at(f, 2), "scope"), "class");
    assert_int_equal(ft_test_json_int(ft_test_json_at(f, 0), "polygons"), 3);
    assert_int_equal(ft_test_json_int(ft_test_json_at(f, 1), "polygons"), 1);
    assert_int_equal(ft_test_json_int(ft_test_json_at(f, 2), "polygons"), 2);
    assert_true(fabs(ft_test_json_num(ft_test_json_at(f, 2), "area") - (400.0 * 400.0 + 300.0 * 300.0)) < 1e-6);
    for (size_t i = 0; i < 3; i++) {
        assert_result_shape(ft_test_json_at(f, i));
        assert_true(ft_test_json_num(ft_test_json_at(f, i), "D") > 1.8 &&
                    ft_test_json_num(ft_test_json_at(f, i), "D") < 2.05);
    }
    json_object_put(o);

    /* integer field: ids are numbers; --plot writes one file per set */
    o = FT_TEST_RUN_JSON("dim", "area", in, "--class", "n", "--plot", ft_test_tmp("p.svg"), "--json");
    f = ft_test_json_key(o, "features");
    assert_int_equal(json_object_array_length(f), 4);
    assert_true(json_object_is_type(ft_test_json_key(ft_test_json_at(f, 1), "id"), json_type_int));
    for (size_t i = 0; i < 4; i++)
        free(ft_test_read_svg(ft_test_json_str(ft_test_json_at(f, i), "plot"), NULL));
    json_object_put(o);
}

/* A human table, and a --where filter. */
static void test_dim_area_table_and_where(void **state)
{
    const char *in = write_landuse("landuse.geojson");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "dim", "area", in, "--class", "use", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "whole layer"));
    assert_non_null(strstr(r.out, "industrial"));
    assert_non_null(strstr(r.out, "box-boundary D = "));
    ft_run_free(&r);
    json_object *o = FT_TEST_RUN_JSON("dim", "area", in, "--where", "use = 'industrial'", "--json");
    assert_int_equal(ft_test_json_int(o, "features"), 1);
    assert_true(fabs(ft_test_json_num(o, "area") - 250000.0) < 1e-6);
    json_object_put(o);
}

/* A classified raster: one result per cell value; each half of the grid is a filled rectangle of 1000 x
 * 2000 m, so boxes of 10 to 100 m (1 to 10 cells) count (1000 / s) (2000 / s). */
static void test_dim_area_raster(void **state)
{
    const char *tif = write_classes_tif("classes.tif");
    json_object *o = FT_TEST_RUN_JSON("dim", "area", tif, "--what", "area", "--cell", "10,20,50,100", "--json");
    json_object *f = ft_test_json_key(o, "features");
    assert_int_equal(json_object_array_length(f), 2);
    for (size_t i = 0; i < 2; i++) {
        json_object *g = ft_test_json_at(f, i);
        assert_true(ft_test_json_num(g, "id") == (double)(i + 1));
        assert_int_equal(ft_test_json_int(g, "cells"), 20000);
        assert_true(fabs(ft_test_json_num(g, "area") - 2e6) < 1e-6);
        assert_result_shape(g);
        assert_true(fabs(ft_test_json_num(g, "D") - 2.0) < 0.02);
        assert_true(ft_test_json_num(ft_test_json_at(ft_test_json_key(g, "table"), 0), "value") == 20000.0);
    }
    json_object_put(o);
}

/* ---- urban table and regress ---- */

/* Three years of a growing residential square: table to CSV and JSON, read back by regress. */
static void test_table_regress_round_trip(void **state)
{
    const char *y1 = write_year("y1990.geojson", 1), *y2 = write_year("y2000.geojson", 2);
    const char *y3 = write_year("y2010.geojson", 4);
    const char *csv = ft_test_tmp("t.csv"), *js = ft_test_tmp("t.json"), *png = ft_test_tmp("d.png");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "urban", "table", y1, y2, y3, "--class", "use", "--label", "1990", "--label",
                            "2000", "--label", "2010", "-o", csv, "--chart", png, NULL),
                     0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "3 rows, 2 classes"));
    ft_run_free(&r);
    char *text = ft_test_read_file(csv, NULL), *png_bytes = NULL;
    assert_non_null(text);
    assert_true(strncmp(text, "label,file,D,stderr,area,polygons,industrial.D,industrial.stderr,industrial.area,"
                              "industrial.polygons,residential.D,",
                        110) == 0);
    assert_non_null(strstr(text, "\n2000,"));
    assert_non_null(strstr(text, ",640000,1,")); /* the industrial area and polygons */
    size_t size = 0;
    png_bytes = ft_test_read_file(png, &size);
    assert_true(png_bytes && size > 1000 && memcmp(png_bytes, "\x89PNG", 4) == 0);
    free(png_bytes);

    /* the same table on stdout */
    assert_int_equal(ft_run(&r, "urban", "table", y1, y2, y3, "--class", "use", "--label", "1990", "--label",
                            "2000", "--label", "2010", NULL),
                     0);
    assert_int_equal(r.status, 0);
    assert_string_equal(r.out, text);
    ft_run_free(&r);
    free(text);

    json_object *t = FT_TEST_RUN_JSON("urban", "table", y1, y2, y3, "--class", "use", "-o", js, "--json");
    assert_string_equal(ft_test_json_str(t, "output"), js);
    json_object *rows = ft_test_json_key(t, "rows");
    assert_int_equal(json_object_array_length(rows), 3);
    assert_string_equal(ft_test_json_str(ft_test_json_at(rows, 0), "label"), "y1990");
    json_object *res = ft_test_json_key(ft_test_json_key(ft_test_json_at(rows, 2), "classes"), "residential");
    double koch = sqrt(3.0) / 4.0 * 2700.0 * 2700.0 * (1.0 + 1.0 / 3.0 * (1.0 - pow(4.0 / 9.0, 4)) / (1.0 - 4.0 / 9.0));
    assert_true(fabs(ft_test_json_num(res, "area") - koch) < 1e-6 * koch); /* a Koch island of 4 levels */
    assert_int_equal(ft_test_json_int(res, "polygons"), 1);
    json_object_put(t);

    json_object *a = FT_TEST_RUN_JSON("urban", "regress", csv, "--class", "residential", "--x", "D", "--y", "area",
                                      "--log-y", "--json");
    json_object *b = FT_TEST_RUN_JSON("urban", "regress", js, "--class", "residential", "--x", "D", "--y", "area",
                                      "--log-y", "--json");
    assert_int_equal(ft_test_json_int(a, "n"), 3);
    assert_string_equal(ft_test_json_str(a, "y"), "ln(residential.area)");
    fprintf(stderr, "Koch islands: %s, r = %.4f\n", ft_test_json_str(a, "equation"), ft_test_json_num(a, "r"));
    assert_true(ft_test_json_num(a, "slope") > 0.0); /* more detail, more area */
    assert_true(fabs(ft_test_json_num(a, "slope") - ft_test_json_num(b, "slope")) < 1e-6 * fabs(ft_test_json_num(a,
                "slope")) + 1e-9);
    assert_true(fabs(ft_test_json_num(a, "r") - ft_test_json_num(b, "r")) < 1e-6); /* the CSV holds D to 10 digits */
    json_object_put(a);
    json_object_put(b);

    /* year against area of the whole layer (bare column names) */
    a = FT_TEST_RUN_JSON("urban", "regress", csv, "--x", "label", "--y", "area", "--json");
    assert_true(ft_test_json_num(a, "slope") > 0.0 && ft_test_json_num(a, "r") > 0.95);
    json_object_put(a);
}

/* Zhang, Yu & Fan (2008), Table 2: ln(area) on D over 1959-1997 gives r = 0.954 (the paper prints 0.9527
 * from its own data). */
static void test_regress_paper_table2(void **state)
{
    const char *csv = ft_test_tmp_text("table2.csv", "year,area,D\n1959,116442,1.3614\n1980,190456,1.3722\n"
                                                     "1989,285423,1.4414\n1997,413110,1.4872\n");
    json_object *o = FT_TEST_RUN_JSON("urban", "regress", csv, "--x", "D", "--y", "area", "--log-y", "--json");
    fprintf(stderr, "Table 2: ln(area) = %.4f + %.4f D, r = %.4f +- %.4f, p = %.4f\n", ft_test_json_num(o,
            "intercept"), ft_test_json_num(o, "slope"), ft_test_json_num(o, "r"), ft_test_json_num(o, "stderr_r"),
            ft_test_json_num(o, "p_value"));
    assert_int_equal(ft_test_json_int(o, "n"), 4);
    assert_true(fabs(ft_test_json_num(o, "r") - 0.954) < 0.0005);
    assert_true(fabs(ft_test_json_num(o, "slope") - 8.7229) < 0.001);
    assert_true(ft_test_json_num(o, "stderr_slope") > 0.0 && ft_test_json_num(o, "stderr_intercept") > 0.0 &&
                ft_test_json_num(o, "stderr_r") > 0.0);
    assert_true(json_object_get_boolean(ft_test_json_key(o, "log_y")));
    assert_non_null(strstr(ft_test_json_str(o, "equation"), "ln(area) = "));
    json_object_put(o);

    ft_run_result r;
    assert_int_equal(ft_run(&r, "urban", "regress", csv, "--log-y", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "r          0.9540"));
    ft_run_free(&r);

    /* missing values are skipped, quoted fields read */
    csv = ft_test_tmp_text("t2q.csv", "\"year\",\"area, m2\",D\n1959,116442,1.3614\n1970,NA,1.37\n1980,190456,"
                                      "1.3722\n\n1989,\"285423\",1.4414\n1997,413110,1.4872\n");
    o = FT_TEST_RUN_JSON("urban", "regress", csv, "--y", "area, m2", "--log-y", "--json");
    assert_int_equal(ft_test_json_int(o, "n"), 4);
    assert_int_equal(ft_test_json_int(o, "rows_skipped"), 1);
    assert_true(fabs(ft_test_json_num(o, "r") - 0.954) < 0.0005);
    json_object_put(o);

    /* the same table as a spreadsheet in a comma-decimal locale saves it: ';' separators, decimal commas */
    csv = ft_test_tmp_text("t2eu.csv", "year;area;D\r\n1959;116442;1,3614\r\n1980;190456;1,3722\r\n"
                                       "1989;285423;1,4414\r\n1997;413110;1,4872\r\n");
    o = FT_TEST_RUN_JSON("urban", "regress", csv, "--x", "D", "--y", "area", "--log-y", "--json");
    assert_int_equal(ft_test_json_int(o, "n"), 4);
    assert_true(fabs(ft_test_json_num(o, "slope") - 8.7229) < 0.001);
    json_object_put(o);
}

/* ---- boundary ---- */

/* The output as GDAL reads it: driver, 2 features, the attributes and the CRS of the input. */
static void assert_ogr_output(const char *path, const char *driver)
{
    GDALDatasetH ds = GDALOpenEx(path, GDAL_OF_VECTOR, NULL, NULL, NULL);
    assert_non_null(ds);
    assert_string_equal(GDALGetDriverShortName(GDALGetDatasetDriver(ds)), driver);
    OGRLayerH l = GDALDatasetGetLayer(ds, 0);
    assert_int_equal(OGR_L_GetFeatureCount(l, 1), 2);
    char *wkt = NULL;
    assert_non_null(OGR_L_GetSpatialRef(l));
    assert_int_equal(OSRExportToWkt(OGR_L_GetSpatialRef(l), &wkt), OGRERR_NONE);
    ft_test_assert_crs_epsg(wkt, 32621);
    CPLFree(wkt);
    OGR_L_ResetReading(l);
    OGRFeatureH f = OGR_L_GetNextFeature(l);
    assert_non_null(f);
    assert_string_equal(OGR_F_GetFieldAsString(f, OGR_F_GetFieldIndex(f, "name")), "west");
    assert_int_equal(OGR_F_GetFieldAsInteger(f, OGR_F_GetFieldIndex(f, "code")), 1);
    OGR_F_Destroy(f);
    GDALClose(ds);
}

/* Vertices of ring a also in ring b (exact equality). */
static size_t common_vertices(const ft_chain *a, const ft_chain *b)
{
    size_t n = 0;
    for (size_t i = 0; i < a->n; i++)
        for (size_t k = 0; k < b->n; k++)
            if (a->x[i] == b->x[k] && a->y[i] == b->y[k]) {
                n++;
                break;
            }
    return n;
}

/* A coverage: the output keeps CRS and attributes, the shared zigzag gets the same detail on both sides. */
static void test_boundary_coverage(void **state)
{
    const char *in = write_coverage("cover.geojson"), *out = ft_test_tmp("b.gpkg");
    json_object *o = FT_TEST_RUN_JSON("boundary", in, out, "--dim", "1.3", "--min", "0.05", "--json");
    assert_string_equal(ft_test_json_str(o, "output"), out);
    assert_int_equal(ft_test_json_int(o, "seed"), 1);
    assert_int_equal(ft_test_json_int(o, "vertices_in"), 26);
    assert_true(ft_test_json_int(o, "vertices_out") > 4 * 26);
    assert_true(json_object_get_boolean(ft_test_json_key(o, "coverage")));
    assert_true(ft_test_json_num(o, "dim") == 1.3 && ft_test_json_num(o, "min") == 0.05 &&
                ft_test_json_num(o, "max") > 0.0);
    assert_true(fabs(ft_test_json_num(o, "angle") - 31.55) < 0.01); /* acos(2^(1/1.3 - 1)), Eq. 9 */
    ft_test_json_key(o, "self_intersections");
    json_object_put(o);
    assert_ogr_output(out, "GPKG");
    ft_layer *before = ft_test_read_layer(in), *after = ft_test_read_layer(out);
    size_t shared = common_vertices(after->parts[0].chain, after->parts[1].chain);
    fprintf(stderr, "coverage: shared boundary 11 -> %zu vertices on both sides\n", shared);
    assert_true(shared > 11);
    for (size_t p = 0; p < 2; p++) /* every input vertex kept */
        assert_int_equal(common_vertices(before->parts[p].chain, after->parts[p].chain), before->parts[p].chain->n);
    ft_layer_free(before);
    ft_layer_free(after);
}

/* --max: the segments longer than it come out unchanged, vertex for vertex; the short ones are subdivided. */
static void test_boundary_max_keeps_long_segments(void **state)
{
    /* long segments of 100, short ones of 2 */
    const char *in = ft_test_tmp_text("walls.gmt", "> walls\n0 0\n100 0\n102 0\n104 0\n104 100\n106 100\n"
                                                   "108 100\n208 100\n");
    const char *out = ft_test_tmp("walls-out.gmt");
    json_object *o = FT_TEST_RUN_JSON("boundary", in, out, "--dim", "1.5", "--min", "0.1", "--max", "10", "--json");
    assert_true(ft_test_json_num(o, "max") == 10.0);
    assert_false(json_object_get_boolean(ft_test_json_key(o, "coverage")));
    json_object_put(o);
    ft_layer *l = ft_test_read_layer(out);
    const ft_chain *c = l->parts[0].chain;
    static const double walls[3][4] = {{0, 0, 100, 0}, {104, 0, 104, 100}, {108, 100, 208, 100}};
    for (size_t w = 0; w < 3; w++) {
        int found = 0;
        for (size_t i = 0; i + 1 < c->n; i++)
            found |= c->x[i] == walls[w][0] && c->y[i] == walls[w][1] && c->x[i + 1] == walls[w][2] &&
                     c->y[i + 1] == walls[w][3];
        assert_true(found);
    }
    assert_true(c->n > 8 + 4 * 8); /* the four short segments, split at least down to 0.1 */
    ft_layer_free(l);

    /* --repair: the loops of a rough curve removed, as a second stage */
    o = FT_TEST_RUN_JSON("boundary", in, ft_test_tmp("r.gmt"), "--dim", "1.8", "--min", "0.5", "--max", "200",
                         "--repair", "--json");
    json_object *stages = ft_test_json_key(o, "stages");
    assert_int_equal(json_object_array_length(stages), 2);
    assert_string_equal(ft_test_json_str(ft_test_json_at(stages, 1), "step"), "repair");
    assert_true(ft_test_json_int(o, "self_intersections_before_repair") > 0);
    assert_int_equal(ft_test_json_int(o, "self_intersections"), 0);
    json_object_put(o);
}

/* Same seed, same bytes; another seed, another output. */
static void test_boundary_reproducible(void **state)
{
    const char *in = write_coverage("cover.geojson");
    const char *a = ft_test_tmp("a.geojson"), *b = ft_test_tmp("b.geojson"), *c = ft_test_tmp("c.geojson");
    json_object_put(FT_TEST_RUN_JSON("boundary", in, a, "--dim", "1.4", "--min", "0.02", "--jitter", "0.3", "--seed",
                                     "42", "--json"));
    json_object_put(FT_TEST_RUN_JSON("boundary", in, b, "--dim", "1.4", "--min", "0.02", "--jitter", "0.3", "--seed",
                                     "42", "--json"));
    json_object *o = FT_TEST_RUN_JSON("boundary", in, c, "--dim", "1.4", "--min", "0.02", "--jitter", "0.3", "--seed",
                                      "43", "--json");
    assert_int_equal(ft_test_json_int(o, "seed"), 43);
    json_object_put(o);
    size_t na = 0, nb = 0, nc = 0;
    char *ta = ft_test_read_file(a, &na), *tb = ft_test_read_file(b, &nb), *tc = ft_test_read_file(c, &nc);
    assert_true(ta && tb && tc && na > 1000);
    assert_true(na == nb && memcmp(ta, tb, na) == 0);
    assert_false(na == nc && memcmp(ta, tc, na) == 0);
    free(ta);
    free(tb);
    free(tc);
}

/* ---- bad input ---- */

static void test_bad_input_dim_area(void **state)
{
    const char *in = write_landuse("landuse.geojson");
    FT_TEST_EXPECT_FAILURE(1, "dim area", "/nonexistent/x.geojson", "dim", "area", "/nonexistent/x.geojson");
    FT_TEST_EXPECT_FAILURE(1, "dim area", "'nosuch'", "dim", "area", in, "--class", "nosuch");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "is a raster", "dim", "area", VOLCANO, "--class", "use");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "--what must be boundary or area, got 'edges'", "dim", "area", in, "--what",
                           "edges");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "--cell", "dim", "area", in, "--cell", "-1");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "at least 3", "dim", "area", in, "--cell", "10,20");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "given twice", "dim", "area", in, "--cell", "10,20,10");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "--cell gives the box sides", "dim", "area", in, "--cell", "1,2,4",
                           "--scales", "5");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "--offsets", "dim", "area", in, "--offsets", "17");
    FT_TEST_EXPECT_FAILURE(1, "dim area", "/nonexistent/folder", "dim", "area", in, "--plot",
                           "/nonexistent/folder/p.svg");
    FT_TEST_EXPECT_FAILURE(2, "dim area", "missing INPUT", "dim", "area");
    ft_grid *g = ft_grid_create(20, 20);
    assert_non_null(g);
    for (size_t i = 0; i < 400; i++)
        g->z[i] = 0.5f * (float)i;
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_write_grid(ft_test_tmp("dem.tif"), g, &wo), FT_OK);
    ft_grid_free(g);
    FT_TEST_EXPECT_FAILURE(1, "dim area", "not a whole number", "dim", "area", ft_test_tmp("dem.tif"));
    assert_int_equal(ft_test_dir_count(), 2);
}

static void test_bad_input_urban(void **state)
{
    const char *in = write_landuse("landuse.geojson");
    const char *csv = ft_test_tmp_text("t.csv", "year,area,D\n1959,116442,1.3614\n1980,190456,x\n");
    const char *two = ft_test_tmp_text("two.csv", "year,area,D\n1959,116442,1.3614\n1980,190456,1.3722\n");
    const char *out = ft_test_tmp("out.csv");
    FT_TEST_EXPECT_FAILURE(2, "urban", "missing SUBCOMMAND", "urban");
    FT_TEST_EXPECT_FAILURE(2, "urban", "unknown subcommand 'tabel'", "urban", "tabel", in);
    FT_TEST_EXPECT_FAILURE(1, "urban table", "/nonexistent/x.geojson", "urban", "table", in, "/nonexistent/x.geojson",
                           "--class", "use", "-o", out);
    FT_TEST_EXPECT_FAILURE(2, "urban table", "missing --class", "urban", "table", in, "-o", out);
    FT_TEST_EXPECT_FAILURE(1, "urban table", "'nosuch'", "urban", "table", in, "--class", "nosuch", "-o", out);
    FT_TEST_EXPECT_FAILURE(2, "urban table", "2 --label given for 1 inputs", "urban", "table", in, "--class", "use",
                           "--label", "1959", "--label", "1980");
    FT_TEST_EXPECT_FAILURE(2, "urban table", "-o file must end in .csv or .json", "urban", "table", in, "--class",
                           "use", "-o", ft_test_tmp("t.txt"));
    FT_TEST_EXPECT_FAILURE(1, "urban table", "/nonexistent/folder", "urban", "table", in, "--class", "use", "-o",
                           "/nonexistent/folder/t.csv");
    FT_TEST_EXPECT_FAILURE(1, "urban table", "/nonexistent/folder", "urban", "table", in, "--class", "use", "-o", out,
                           "--chart", "/nonexistent/folder/c.png");
    FT_TEST_EXPECT_FAILURE(1, "urban table", "dem_volcano_maunga_whau_10m.tif", "urban", "table", VOLCANO, "--class",
                           "use", "-o", out);
    FT_TEST_EXPECT_FAILURE(2, "urban table", "missing LAYER", "urban", "table", "--class", "use");
    FT_TEST_EXPECT_FAILURE(1, "urban regress", "/nonexistent/t.csv", "urban", "regress", "/nonexistent/t.csv");
    FT_TEST_EXPECT_FAILURE(1, "urban regress", "has no column 'residential.D'", "urban", "regress", two, "--class",
                           "residential");
    FT_TEST_EXPECT_FAILURE(1, "urban regress", "has no column 'population'", "urban", "regress", two, "--y",
                           "population");
    FT_TEST_EXPECT_FAILURE(1, "urban regress", "line 3, column 'D': 'x' is not a number", "urban", "regress", csv);
    FT_TEST_EXPECT_FAILURE(1, "urban regress", "at least 3", "urban", "regress", two);
    FT_TEST_EXPECT_FAILURE(2, "urban regress", "missing TABLE", "urban", "regress");
    assert_int_equal(ft_test_dir_count(), 3); /* the three inputs: nothing written */
}

static void test_bad_input_boundary(void **state)
{
    const char *in = write_coverage("cover.geojson"), *out = ft_test_tmp("out.geojson");
    FT_TEST_EXPECT_FAILURE(1, "boundary", "/nonexistent/x.geojson", "boundary", "/nonexistent/x.geojson", out, "--dim",
                           "1.3");
    FT_TEST_EXPECT_FAILURE(1, "boundary", "dem_volcano_maunga_whau_10m.tif", "boundary", VOLCANO, out, "--dim", "1.3");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "--dim must be a number in (1,2), got '2.5'", "boundary", in, out, "--dim",
                           "2.5");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "--dim", "boundary", in, out, "--dim", "1");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "missing --dim", "boundary", in, out);
    FT_TEST_EXPECT_FAILURE(2, "boundary", "--min must be a number > 0, got '-1'", "boundary", in, out, "--dim", "1.3",
                           "--min", "-1");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "--max 1 must be at least --min 2", "boundary", in, out, "--dim", "1.3",
                           "--min", "2", "--max", "1");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "--jitter", "boundary", in, out, "--dim", "1.9", "--jitter", "0.6");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "--seed", "boundary", in, out, "--dim", "1.3", "--seed", "-4");
    FT_TEST_EXPECT_FAILURE(1, "boundary", "/nonexistent/folder", "boundary", in, "/nonexistent/folder/o.geojson",
                           "--dim", "1.3");
    FT_TEST_EXPECT_FAILURE(2, "boundary", "missing OUTPUT", "boundary", in, "--dim", "1.3");
    assert_int_equal(ft_test_dir_count(), 1); /* only the input: nothing written, no temporary left */
}

/* --help: the usage line, an example, exit 0, for each command. */
static void test_help(void **state)
{
    const char *const cmds[][3] = {{"dim", "area", "fracterra dim area INPUT"},
                                   {"urban", "table", "fracterra urban table LAYER"},
                                   {"urban", "regress", "fracterra urban regress TABLE"},
                                   {"urban", "--help", "fracterra urban SUBCOMMAND"},
                                   {"boundary", "--help", "fracterra boundary INPUT OUTPUT"}};
    for (size_t i = 0; i < sizeof cmds / sizeof cmds[0]; i++) {
        ft_run_result r;
        if (strcmp(cmds[i][1], "--help") == 0)
            assert_int_equal(ft_run(&r, cmds[i][0], "--help", NULL), 0);
        else
            assert_int_equal(ft_run(&r, cmds[i][0], cmds[i][1], "--help", NULL), 0);
        assert_int_equal(r.status, 0);
        assert_non_null(strstr(r.out, cmds[i][2]));
        assert_true(strstr(r.out, "Example:") || strstr(r.out, "Examples:"));
        ft_run_free(&r);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dim_area_filled_square),
        cmocka_unit_test(test_dim_area_classes),
        cmocka_unit_test(test_dim_area_table_and_where),
        cmocka_unit_test(test_dim_area_raster),
        cmocka_unit_test(test_table_regress_round_trip),
        cmocka_unit_test(test_regress_paper_table2),
        cmocka_unit_test(test_boundary_coverage),
        cmocka_unit_test(test_boundary_max_keeps_long_segments),
        cmocka_unit_test(test_boundary_reproducible),
        cmocka_unit_test(test_bad_input_dim_area),
        cmocka_unit_test(test_bad_input_urban),
        cmocka_unit_test(test_bad_input_boundary),
        cmocka_unit_test(test_help),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
