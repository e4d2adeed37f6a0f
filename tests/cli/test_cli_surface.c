/* fracterra — tests/cli/test_cli_surface.c: `fracterra dim surface` and `fracterra dim map` end to end on
 * the DEMs of tests/data and a synthetic GeoTIFF: JSON keys and figures in range, every method, the plot,
 * the two-band map read back through GDAL with the DEM's CRS and aligned geotransform, and bad input
 * (unknown method, window larger than the grid, step 0, all-nodata DEM, missing file): a message naming
 * the value, a non-zero exit and nothing written.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"

/* Runs argv; checks the exit code, and on failure the "fracterra: CMD: " prefix, the needle on stderr and
 * an empty stdout. Returns stdout's JSON object on success (NULL when not asked for). */
static json_object *run(int code, const char *cmd, const char *needle, const char *const *argv, int json)
{
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    if (r.status != code || (needle && strstr(r.err, needle) == NULL))
        print_error("status %d, stderr: %s\n", r.status, r.err);
    assert_false(r.signaled);
    assert_int_equal(r.status, code);
    json_object *o = NULL;
    if (code != 0) {
        char prefix[64];
        snprintf(prefix, sizeof prefix, "fracterra: %s: ", cmd);
        assert_int_equal(r.out_len, 0);
        assert_true(strncmp(r.err, prefix, strlen(prefix)) == 0);
    } else if (json) {
        o = ft_run_json(&r);
        assert_non_null(o);
    }
    if (needle)
        assert_non_null(strstr(r.err, needle));
    ft_run_free(&r);
    return o;
}

/* A 256 x 256 D = 2.5 surface with a CRS, as GeoTIFF. */
static const char *synthetic_dem(void)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.method = FT_SYNTH_EXACT;
    so.dim = 2.5;
    so.cell = 30.0;
    so.origin_x = 500000.0;
    so.origin_y = 4000000.0;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(256, 256, &so, &g), 0);
    assert_int_equal(ft_grid_set_crs(g, "EPSG:32633"), 0);
    const char *path = ft_test_tmp("dem.tif");
    assert_int_equal(ft_io_write_grid(path, g, NULL), 0);
    ft_grid_free(g);
    return path;
}

static void test_dim_surface(void **state)
{
    (void)state;
    const char *dem = synthetic_dem();
    const char *a1[] = {"dim", "surface", dem, "--json", NULL};
    json_object *o = run(0, NULL, NULL, a1, 1);
    assert_string_equal(ft_test_json_str(o, "method"), "variogram");
    assert_true(fabs(ft_test_json_num(o, "D") - 2.5) < 0.08);
    assert_string_equal(ft_test_json_str(o, "pairs"), "exhaustive");
    assert_int_equal(ft_test_json_int(o, "cells_valid"), 256 * 256);
    assert_true(json_object_array_length(ft_test_json_key(o, "table")) >= 3);
    /* scales in map units: the first lag is one 30 m cell */
    json_object *row0 = json_object_array_get_idx(ft_test_json_key(o, "table"), 0);
    assert_true(fabs(ft_test_json_num(row0, "scale") - 30.0) < 1e-6);
    json_object_put(o);
    const char *plot = ft_test_tmp("p.svg");
    const char *a2[] = {"dim", "surface", dem, "--method", "all", "--pairs", "4000", "--plot", plot, "--json", NULL};
    o = run(0, NULL, NULL, a2, 1);
    json_object *res = ft_test_json_key(o, "results");
    assert_int_equal(json_object_array_length(res), FT_SURFACE_NMETHODS);
    for (size_t i = 0; i < FT_SURFACE_NMETHODS; i++) {
        json_object *ri = json_object_array_get_idx(res, i);
        assert_string_equal(ft_test_json_str(ri, "method"), ft_surface_method_name((ft_surface_method)i));
        double D = ft_test_json_num(ri, "D");
        assert_true(D > 2.2 && D < 2.7);
    }
    assert_int_equal(ft_test_json_int(o, "pairs"), 4000);
    json_object_put(o);
    assert_true(ft_test_dir_count() >= 1 + FT_SURFACE_NMETHODS); /* the DEM and one plot per method */
    /* the spectrum's white-noise floor, given: removed, said, the highest frequency fitted reported */
    const char *a5[] = {"dim", "surface", dem, "--method", "spectrum", "--noise-sigma", "0.01", "--json", NULL};
    o = run(0, NULL, NULL, a5, 1);
    json_object *noise = ft_test_json_key(o, "noise");
    assert_true(json_object_get_boolean(ft_test_json_key(noise, "removed")));
    assert_true(fabs(ft_test_json_num(noise, "nugget") - 1e-4) < 1e-12); /* N0 = sigma² */
    assert_true(ft_test_json_num(noise, "max_frequency") > 0.0);
    json_object *w = ft_test_json_key(o, "warnings");
    int said = 0;
    for (size_t i = 0; i < json_object_array_length(w); i++)
        said |= strstr(json_object_get_string(json_object_array_get_idx(w, i)), "white spectrum") != NULL;
    assert_true(said);
    json_object_put(o);
    /* the real DEMs: human table, D in [2, 3] */
    const char *a3[] = {"dim", "surface", VOLCANO, "--method", "yokoya", "--json", NULL};
    o = run(0, NULL, NULL, a3, 1);
    assert_true(ft_test_json_num(o, "D") >= 2.0 && ft_test_json_num(o, "D") < 2.5);
    json_object_put(o);
    const char *a4[] = {"dim", "surface", LUXEMBOURG, "--method", "prism", NULL};
    run(0, NULL, NULL, a4, 0);
}

static void test_dim_map(void **state)
{
    (void)state;
    const char *dem = synthetic_dem(), *out = ft_test_tmp("map.tif");
    const char *a1[] = {"dim", "map", dem, out, "--window", "64", "--step", "32", "--json", NULL};
    json_object *o = run(0, NULL, NULL, a1, 1);
    assert_int_equal(ft_test_json_int(o, "windows"), 7 * 7);
    assert_int_equal(ft_test_json_int(o, "windows_measured"), 7 * 7);
    assert_true(fabs(ft_test_json_num(o, "D_mean") - 2.5) < 0.1);
    json_object_put(o);
    ft_grid *D = NULL, *r2 = NULL;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_read_grid(out, &ro, &D), 0);
    ro.band = 2;
    assert_int_equal(ft_io_read_grid(out, &ro, &r2), 0);
    assert_int_equal(D->nx, 7);
    assert_int_equal(D->ny, 7);
    assert_true(fabs(D->gt[0] - (500000.0 + 16 * 30.0)) < 1e-6); /* (64 - 32) / 2 cells in */
    assert_true(fabs(D->gt[1] - 32 * 30.0) < 1e-9);
    ft_test_assert_crs_epsg(D->crs_wkt, 32633);
    for (size_t i = 0; i < 49; i++)
        assert_true(D->z[i] > 2.2f && D->z[i] < 2.8f && r2->z[i] > 0.5f && r2->z[i] <= 1.0f);
    ft_grid_free(D);
    ft_grid_free(r2);
}

static void test_bad_input(void **state)
{
    (void)state;
    const char *dem = synthetic_dem(), *out = ft_test_tmp("never.tif");
    const char *a1[] = {"dim", "surface", dem, "--method", "fractalish", NULL};
    run(2, "dim surface", "fractalish", a1, 0);
    const char *a2[] = {"dim", "map", dem, out, "--window", "300", NULL};
    run(1, "dim map", "300", a2, 0);
    const char *a3[] = {"dim", "map", dem, out, "--window", "64", "--step", "0", NULL};
    run(2, "dim map", "--step", a3, 0);
    const char *a4[] = {"dim", "map", dem, out, NULL};
    run(2, "dim map", "--window", a4, 0);
    const char *a5[] = {"dim", "map", dem, out, "--window", "64", "--method", "all", NULL};
    run(2, "dim map", "all", a5, 0);
    const char *n1[] = {"dim", "surface", dem, "--noise-sigma", "1,2", NULL}; /* no XY for a grid */
    run(2, "dim surface", "--noise-sigma", n1, 0);
    const char *n2[] = {"dim", "surface", dem, "--noise-sigma", "-0.5", NULL};
    run(2, "dim surface", "-0.5", n2, 0);
    const char *n3[] = {"dim", "surface", dem, "--noise-model", "on", NULL};
    run(2, "dim surface", "--noise-model", n3, 0);
    const char *a6[] = {"dim", "surface", ft_test_tmp("missing.tif"), NULL};
    run(1, "dim surface", "missing.tif", a6, 0);
    /* an all-nodata DEM */
    ft_grid *g = ft_grid_create(32, 32);
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    memset(g->mask, 0, 32 * 32);
    const char *empty = ft_test_tmp("empty.tif");
    assert_int_equal(ft_io_write_grid(empty, g, NULL), 0);
    ft_grid_free(g);
    const char *a7[] = {"dim", "surface", empty, NULL};
    run(1, "dim surface", "nodata", a7, 0);
    const char *a8[] = {"dim", "map", empty, out, "--window", "16", NULL};
    run(1, "dim map", "nodata", a8, 0);
    assert_int_equal(ft_test_dir_count(), 2); /* dem.tif and empty.tif: no output left behind */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dim_surface),
        cmocka_unit_test(test_dim_map),
        cmocka_unit_test(test_bad_input),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
