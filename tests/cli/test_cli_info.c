/* fracterra — tests/cli/test_cli_info.c: `fracterra info` on every file of tests/data, figures checked
 * against tests/data/README.md, plus large generated inputs (a 1,000,000-vertex GeoJSON line and a
 * 4096 x 4096 GeoTIFF) whose counts are known by construction.
 *
 * Vertex counts: `vertices` counts rings without their repeated closing vertex (as fracterra stores
 * them), `file_vertices` with it (as the file and ogrinfo do): Newfoundland has 64,193 and 64,194.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <gdal.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ft_test_util.h"

#define DATA(f) FT_TEST_DATA "/" f

static double at(json_object *a, size_t i)
{
    return json_object_get_double(json_object_array_get_idx(a, i));
}

static void assert_crs(json_object *o, const char *name, int epsg)
{
    json_object *crs = ft_test_json_key(o, "crs");
    assert_non_null(crs);
    assert_string_equal(ft_test_json_str(crs, "name"), name);
    assert_int_equal(ft_test_json_int(crs, "epsg"), epsg);
}

static void test_newfoundland(void **state)
{
    json_object *o = FT_TEST_RUN_JSON("info", "--json", DATA("gshhg_newfoundland_utm21n.geojson"));
    assert_string_equal(ft_test_json_str(o, "kind"), "chains");
    assert_string_equal(ft_test_json_str(o, "driver"), "GeoJSON");
    assert_int_equal(ft_test_json_int(o, "features"), 1);
    assert_int_equal(ft_test_json_int(o, "parts"), 1);
    assert_int_equal(ft_test_json_int(o, "rings"), 1);
    assert_int_equal(ft_test_json_int(o, "lines"), 0);
    assert_int_equal(ft_test_json_int(o, "vertices"), 64193);
    assert_int_equal(ft_test_json_int(o, "file_vertices"), 64194);
    assert_int_equal(ft_test_json_int(o, "short_chains"), 0);
    json_object *e = ft_test_json_key(o, "extent");
    assert_int_equal(json_object_array_length(e), 4);
    assert_true(fabs(at(e, 0) - 319701.72) < 0.01 && fabs(at(e, 3) - 5720600.84) < 0.01);
    assert_crs(o, "WGS 84 / UTM zone 21N", 32621);
    assert_false(json_object_object_get_ex(o, "warnings", NULL));
    json_object_put(o);
}

static void test_us_states(void **state)
{
    json_object *o = FT_TEST_RUN_JSON("info", "--json", DATA("dcw_us_states_small_albers5070.geojson"));
    assert_string_equal(ft_test_json_str(o, "kind"), "chains");
    assert_int_equal(ft_test_json_int(o, "features"), 4);
    assert_true(ft_test_json_int(o, "rings") >= 4);
    assert_int_equal(ft_test_json_int(o, "lines"), 0);
    assert_int_equal(ft_test_json_int(o, "file_vertices"),
                     ft_test_json_int(o, "vertices") + ft_test_json_int(o, "rings"));
    assert_crs(o, "NAD83 / Conus Albers", 5070);
    json_object *fields = ft_test_json_key(o, "fields");
    int have_code = 0;
    for (size_t i = 0; i < json_object_array_length(fields); i++)
        have_code |= strcmp(ft_test_json_str(json_object_array_get_idx(fields, i), "name"), "code") == 0;
    assert_true(have_code);
    json_object_put(o);
}

static void test_volcano(void **state)
{
    json_object *o = FT_TEST_RUN_JSON("info", "--json", DATA("dem_volcano_maunga_whau_10m.tif"));
    assert_string_equal(ft_test_json_str(o, "kind"), "grid");
    assert_string_equal(ft_test_json_str(o, "driver"), "GTiff");
    json_object *size = ft_test_json_key(o, "size");
    assert_int_equal(at(size, 0), 61);
    assert_int_equal(at(size, 1), 87);
    assert_int_equal(ft_test_json_int(o, "cells"), 5307);
    assert_int_equal(ft_test_json_int(o, "valid"), 5307);
    assert_int_equal(ft_test_json_int(o, "nodata"), 0);
    json_object *z = ft_test_json_key(o, "z_range");
    assert_true(at(z, 0) == 94.0 && at(z, 1) == 195.0); /* R's volcano: range 94..195 m */
    json_object *cs = ft_test_json_key(o, "cell_size");
    assert_true(at(cs, 0) == 10.0 && at(cs, 1) == 10.0);
    json_object *e = ft_test_json_key(o, "extent");
    assert_true(fabs((at(e, 2) - at(e, 0)) - 610.0) < 1e-6 && fabs((at(e, 3) - at(e, 1)) - 870.0) < 1e-6);
    assert_crs(o, "NZGD49 / New Zealand Map Grid", 27200);
    json_object_put(o);
}

static void test_luxembourg(void **state)
{
    json_object *o = FT_TEST_RUN_JSON("info", "--json", DATA("dem_luxembourg_terra_30s.tif"));
    assert_string_equal(ft_test_json_str(o, "kind"), "grid");
    json_object *size = ft_test_json_key(o, "size");
    assert_int_equal(at(size, 0), 95);
    assert_int_equal(at(size, 1), 90);
    assert_int_equal(ft_test_json_int(o, "cells"), 8550);
    assert_int_equal(ft_test_json_int(o, "valid"), 4608);
    assert_int_equal(ft_test_json_int(o, "nodata"), 3942);
    assert_true(json_object_get_double(ft_test_json_key(o, "nodata_value")) == -32768.0);
    json_object *z = ft_test_json_key(o, "z_range");
    assert_true(at(z, 0) == 141.0 && at(z, 1) == 547.0);
    assert_crs(o, "WGS 84", 4326);
    json_object_put(o);
}

static void test_mass_points(void **state)
{
    json_object *o = FT_TEST_RUN_JSON("info", "--json", DATA("points_mass_topo_davis1973.csv"));
    assert_string_equal(ft_test_json_str(o, "kind"), "points");
    assert_int_equal(ft_test_json_int(o, "points"), 52);
    json_object *z = ft_test_json_key(o, "z_range");
    assert_true(at(z, 0) == 690.0 && at(z, 1) == 960.0); /* MASS::topo: z from 690 to 960 ft */
    json_object *e = ft_test_json_key(o, "extent");
    assert_true(at(e, 0) >= 0.0 && at(e, 2) <= 6.5 && at(e, 1) >= 0.0 && at(e, 3) <= 6.5);
    json_object_put(o);
}

static void test_human_table(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", DATA("gshhg_newfoundland_utm21n.geojson"), NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "chains"));
    assert_non_null(strstr(r.out, "64193"));
    assert_non_null(strstr(r.out, "64194"));
    assert_non_null(strstr(r.out, "WGS 84 / UTM zone 21N (EPSG:32621)"));
    assert_null(ft_run_json(&r)); /* a table, not JSON */
    ft_run_free(&r);

    assert_int_equal(ft_run(&r, "info", DATA("dem_volcano_maunga_whau_10m.tif"), NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "61 x 87 = 5307 cells"));
    assert_non_null(strstr(r.out, "NZGD49 / New Zealand Map Grid (EPSG:27200)"));
    ft_run_free(&r);
}

static void test_band_option(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", "--json", "--band", "1", DATA("dem_volcano_maunga_whau_10m.tif"), NULL), 0);
    assert_int_equal(r.status, 0);
    json_object *o = ft_run_json(&r);
    assert_non_null(o);
    assert_int_equal(ft_test_json_int(o, "band"), 1);
    json_object_put(o);
    ft_run_free(&r);
}

/* A 1,000,000-vertex GeoJSON LineString: counts must be exact (speed is measured in `make bench`). */
static void test_large_line(void **state)
{
    const size_t n = 1000000;
    const char *path = ft_test_tmp("long_line.geojson");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs("{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
          "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[",
          f);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%s[%zu.5,%zu]", i ? "," : "", i, (i * 7919) % 1000);
    fputs("]}}]}\n", f);
    assert_int_equal(fclose(f), 0);

    json_object *o = FT_TEST_RUN_JSON("info", "--json", path);
    assert_string_equal(ft_test_json_str(o, "kind"), "chains");
    assert_int_equal(ft_test_json_int(o, "lines"), 1);
    assert_int_equal(ft_test_json_int(o, "rings"), 0);
    assert_int_equal(ft_test_json_int(o, "vertices"), (int64_t)n);
    assert_int_equal(ft_test_json_int(o, "file_vertices"), (int64_t)n);
    json_object *e = ft_test_json_key(o, "extent");
    assert_true(at(e, 0) == 0.5 && at(e, 2) == (double)(n - 1) + 0.5);
    json_object_put(o);
}

/* A 4096 x 4096 Float32 GeoTIFF with a known nodata block. */
static void test_large_grid(void **state)
{
    const int side = 4096, hole = 100;
    const char *path = ft_test_tmp("big.tif");
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path, side, side, 1, GDT_Float32, NULL);
    assert_non_null(ds);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    GDALSetRasterNoDataValue(b, -9999.0);
    float *row = malloc(sizeof(float) * (size_t)side);
    assert_non_null(row);
    for (int y = 0; y < side; y++) {
        for (int x = 0; x < side; x++)
            row[x] = (x < hole && y < hole) ? -9999.0f : (float)(x + y);
        assert_int_equal(GDALRasterIO(b, GF_Write, 0, y, side, 1, row, side, 1, GDT_Float32, 0, 0), CE_None);
    }
    free(row);
    GDALClose(ds);

    json_object *o = FT_TEST_RUN_JSON("info", "--json", path);
    assert_int_equal(ft_test_json_int(o, "cells"), (int64_t)side * side);
    assert_int_equal(ft_test_json_int(o, "nodata"), hole * hole);
    assert_int_equal(ft_test_json_int(o, "valid"), (int64_t)side * side - hole * hole);
    json_object *z = ft_test_json_key(o, "z_range");
    assert_true(at(z, 0) == hole && at(z, 1) == 2.0 * (side - 1));
    json_object_put(o);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_newfoundland), cmocka_unit_test(test_us_states),   cmocka_unit_test(test_volcano),
        cmocka_unit_test(test_luxembourg),   cmocka_unit_test(test_mass_points), cmocka_unit_test(test_human_table),
        cmocka_unit_test(test_band_option),  FT_TEST_OWN_DIR(test_large_line),  FT_TEST_OWN_DIR(test_large_grid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
