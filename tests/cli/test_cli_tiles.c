/* fracterra — tests/cli/test_cli_tiles.c: `dim map` and `dim surface` stripe by stripe (--tile-rows, and
 * automatically beyond --max-memory) and on two MPI ranks give what the whole-raster run gives: every cell of
 * the map (across the stripe seams, nodata included) and the whole JSON report; so do `hillshade` and `fill`. Refusals: random pairs,
 * methods that do not decompose, geographic DEMs, formats other than GeoTIFF, commands that do not run on
 * ranks. The mpiexec tests run when the CLI was built with MPI (FT_TEST_MPIEXEC) and not under the
 * sanitizers (Open MPI's own allocations are reported as leaks there); they are skipped otherwise.
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
#include <stdlib.h>
#include <dirent.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define LUX_UTM FT_TEST_DATA "/dem_luxembourg_utm32n.tif" /* 81 x 115, half nodata */
#define LUX_LONLAT FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"

static size_t hole_cells; /* cells of the synthetic DEM's nodata hole */
#define NOISE_SD 0.05  /* m: white noise on the noisy DEM's z (its relief has sd 1 m: 26 dB) */

/* A 230 x 190 D = 2.4 surface in UTM 33N with a nodata hole, as GeoTIFF. */
static const char *synthetic_dem_noise(double noise_sd, const char *name);

static const char *synthetic_dem(void)
{
    return synthetic_dem_noise(0.0, "dem.tif");
}

/* The synthetic DEM with white N(0, noise_sd²) noise on z (metres) when noise_sd > 0, written to name. */
static const char *synthetic_dem_noise(double noise_sd, const char *name)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = 2.4;
    so.cell = 25.0;
    so.origin_x = 400000.0;
    so.origin_y = 5000000.0;
    so.seed = 5;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(230, 190, &so, &g), FT_OK);
    char *wkt = NULL;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:32633", &wkt), FT_OK);
    assert_int_equal(ft_grid_set_crs(g, wkt), FT_OK);
    free(wkt);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    hole_cells = 0;
    for (size_t i = 0; i < g->ny; i++)
        for (size_t j = 0; j < g->nx; j++)
            if (hypot((double)j - 150.0, (double)i - 70.0) < 20.0) {
                g->mask[i * g->nx + j] = 0;
                hole_cells++;
            }
    ft_rng *r = ft_rng_create(7, 0);
    for (size_t i = 0; noise_sd > 0.0 && i < g->nx * g->ny; i++)
        g->z[i] += (float)ft_rng_gaussian(r, noise_sd);
    ft_rng_free(r);
    const char *path = ft_test_tmp(name);
    assert_int_equal(ft_io_write_grid(path, g, NULL), FT_OK);
    ft_grid_free(g);
    return path;
}

/* stdout of a successful run (malloc'd). */
static char *run_out(const char *const *argv)
{
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    if (r.status != 0)
        print_error("status %d, stderr: %s\n", r.status, r.err);
    assert_int_equal(r.status, 0);
    char *out = strdup(r.out);
    ft_run_free(&r);
    return out;
}
#define RUN_OUT(...) run_out((const char *const[]){__VA_ARGS__, NULL})

/* Band `band` (0: the first) of two rasters into *x and *y, asserting the same size and geotransform. */
static void read_same_frame(const char *a, const char *b, int band, ft_grid **x, ft_grid **y)
{
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    if (band > 0)
        o.band = band;
    *x = *y = NULL;
    assert_int_equal(ft_io_read_grid(a, &o, x), FT_OK);
    assert_int_equal(ft_io_read_grid(b, &o, y), FT_OK);
    assert_int_equal((*x)->nx, (*y)->nx);
    assert_int_equal((*x)->ny, (*y)->ny);
    for (int k = 0; k < 6; k++)
        assert_true((*x)->gt[k] == (*y)->gt[k]);
}

/* Band `band` of two rasters, cell for cell (nodata where the other has nodata), and their georeferencing;
 * returns the number of valid cells compared (*cells, if not NULL: all cells). */
static size_t assert_same_band_cells(const char *a, const char *b, int band, size_t *cells)
{
    ft_grid *x, *y;
    read_same_frame(a, b, band, &x, &y);
    ft_test_assert_same_crs(x->crs_wkt, y->crs_wkt);
    size_t valid = 0;
    for (size_t i = 0; i < x->nx * x->ny; i++) {
        int vx = x->mask == NULL || x->mask[i], vy = y->mask == NULL || y->mask[i];
        assert_int_equal(vx, vy);
        if (vx) {
            assert_memory_equal(&x->z[i], &y->z[i], sizeof(float));
            valid++;
        }
    }
    if (cells != NULL)
        *cells = x->nx * x->ny;
    ft_grid_free(x);
    ft_grid_free(y);
    return valid;
}

static void assert_same_band(const char *a, const char *b, int band)
{
    assert_same_band_cells(a, b, band, NULL);
}

/* Both bands of two maps, cell for cell, measured windows and nodata ones both present. */
static void assert_same_map(const char *a, const char *b)
{
    for (int band = 1; band <= 2; band++) {
        size_t cells = 0, valid = assert_same_band_cells(a, b, band, &cells);
        assert_true(valid > 0 && valid < cells);
    }
}

/* The "output" member differs; everything else of two dim map reports must be equal. */
static void assert_same_report(const char *a, const char *b, const char *out_a, const char *out_b)
{
    const char *pa = strstr(a, out_a), *pb = strstr(b, out_b);
    assert_non_null(pa);
    assert_non_null(pb);
    assert_int_equal(pa - a, pb - b);
    assert_memory_equal(a, b, (size_t)(pa - a));
    assert_string_equal(pa + strlen(out_a), pb + strlen(out_b));
}

static void test_dim_map_tiled_equals_whole(void **state)
{
    (void)state;
    const char *dem = synthetic_dem();
    const char *whole = ft_test_tmp("whole.tif"), *t1 = ft_test_tmp("t1.tif"), *t2 = ft_test_tmp("t2.tif");
    char *a = RUN_OUT("dim", "map", dem, whole, "--window", "32", "--step", "8", "--min-valid", "0.9", "--json");
    /* stripes of 8 lattice rows, of 1 (every seam), and automatic ones under a 1 MB memory bound */
    char *b = RUN_OUT("dim", "map", dem, t1, "--window", "32", "--step", "8", "--min-valid", "0.9", "--json",
                      "--tile-rows", "64");
    char *c = RUN_OUT("dim", "map", dem, t2, "--window", "32", "--step", "8", "--min-valid", "0.9", "--json",
                      "--tile-rows", "1");
    assert_same_map(whole, t1);
    assert_same_map(whole, t2);
    assert_same_report(a, b, "whole.tif", "t1.tif");
    assert_same_report(a, c, "whole.tif", "t2.tif");
    const char *t3 = ft_test_tmp("t3.tif");
    char *d = RUN_OUT("--max-memory", "1M", "dim", "map", dem, t3, "--window", "32", "--step", "8", "--min-valid",
                      "0.9", "--json");
    assert_same_map(whole, t3);
    assert_same_report(a, d, "whole.tif", "t3.tif");
    /* a DEM with nodata over half its cells (Int16), window 16 step 4 */
    const char *lw = ft_test_tmp("lw.tif"), *lt = ft_test_tmp("lt.tif");
    free(RUN_OUT("dim", "map", LUX_UTM, lw, "--window", "16", "--step", "4"));
    free(RUN_OUT("dim", "map", LUX_UTM, lt, "--window", "16", "--step", "4", "--tile-rows", "10"));
    assert_same_map(lw, lt);
    free(a);
    free(b);
    free(c);
    free(d);
}

static void test_dim_surface_tiled_equals_whole(void **state)
{
    (void)state;
    const char *dem = synthetic_dem();
    const char *methods[] = {"variogram", "yokoya", "pentland"};
    for (int k = 0; k < 3; k++) {
        char *a = RUN_OUT("dim", "surface", dem, "--method", methods[k], "--pairs", "0", "--json");
        char *b = RUN_OUT("dim", "surface", dem, "--method", methods[k], "--tile-rows", "7", "--json");
        assert_string_equal(a, b); /* D, table, fit, warnings, cells_valid: the whole report */
        if (k == 0) { /* automatic stripes under a 1 MB memory bound */
            char *c = RUN_OUT("--max-memory", "1M", "dim", "surface", dem, "--method", methods[k], "--json");
            assert_string_equal(a, c);
            free(c);
        }
        json_object *o = json_tokener_parse(a);
        double D = ft_test_json_num(o, "D");
        assert_true(D > 2.2 && D < 2.6);
        assert_int_equal(ft_test_json_int(o, "cells_valid"), 230 * 190 - (int64_t)hole_cells);
        json_object_put(o);
        free(a);
        free(b);
    }
}

/* dim map's noise count: white noise on z is found in windows of the noisy DEM, the same count stripe by
 * stripe (the whole report compared) and none with --noise-model off. */
static void test_dim_map_noise_count(void **state)
{
    (void)state;
    const char *dem = synthetic_dem_noise(NOISE_SD, "noisy.tif");
    const char *whole = ft_test_tmp("nw.tif"), *t1 = ft_test_tmp("nt.tif"), *off = ft_test_tmp("noff.tif");
    char *a = RUN_OUT("dim", "map", dem, whole, "--window", "32", "--step", "16", "--json");
    char *b = RUN_OUT("dim", "map", dem, t1, "--window", "32", "--step", "16", "--json", "--tile-rows", "1");
    assert_same_map(whole, t1);
    assert_same_report(a, b, "nw.tif", "nt.tif");
    json_object *o = json_tokener_parse(a), *noise = NULL, *w = NULL;
    assert_true(json_object_object_get_ex(o, "noise", &noise));
    int64_t n = ft_test_json_int(noise, "windows_with_nugget"), m = ft_test_json_int(noise, "windows");
    print_message("  noisy DEM: %lld of %lld windows with a nugget\n", (long long)n, (long long)m);
    assert_int_equal(m, ft_test_json_int(o, "windows_measured"));
    assert_true(n >= m / 10); /* measured 26 of 126; the 5 % F test alone would flag about 6 */
    assert_true(json_object_object_get_ex(o, "warnings", &w));
    assert_int_equal(json_object_array_length(w), 1);
    assert_non_null(strstr(json_object_get_string(json_object_array_get_idx(w, 0)), "noise detected in"));
    json_object_put(o);
    char *c = RUN_OUT("dim", "map", dem, off, "--window", "32", "--step", "16", "--json", "--noise-model", "off");
    o = json_tokener_parse(c);
    assert_true(json_object_object_get_ex(o, "noise", &noise));
    assert_int_equal(ft_test_json_int(noise, "windows_with_nugget"), 0);
    assert_true(json_object_object_get_ex(o, "warnings", &w));
    assert_int_equal(json_object_array_length(w), 0);
    json_object_put(o);
    free(a);
    free(b);
    free(c);
}

/* Byte cells of two hillshades, every one, and their georeferencing. */
static void assert_same_shade(const char *a, const char *b)
{
    ft_grid *x, *y;
    read_same_frame(a, b, 0, &x, &y);
    size_t lit = 0;
    for (size_t i = 0; i < x->nx * x->ny; i++) {
        float vx = x->mask == NULL || x->mask[i] ? x->z[i] : 0.0f, vy = y->mask == NULL || y->mask[i] ? y->z[i] : 0.0f;
        assert_true(vx == vy);
        lit += vx > 0.0f;
    }
    assert_true(lit > 0 && lit < x->nx * x->ny); /* shaded cells and the nodata hole both compared */
    ft_grid_free(x);
    ft_grid_free(y);
}

static void test_hillshade_tiled_equals_whole(void **state)
{
    (void)state;
    const char *dem = synthetic_dem(), *whole = ft_test_tmp("hw.tif"), *t = ft_test_tmp("ht.tif");
    free(RUN_OUT("hillshade", dem, whole, "--z-factor", "3"));
    free(RUN_OUT("hillshade", dem, t, "--z-factor", "3", "--tile-rows", "13"));
    assert_same_shade(whole, t);
    FT_TEST_EXPECT_FAILURE(1, "hillshade", "--color", "hillshade", dem, ft_test_tmp("c.tif"), "--color",
                           "--tile-rows", "13");
    FT_TEST_EXPECT_FAILURE(1, "hillshade", "must be a GeoTIFF", "hillshade", dem, ft_test_tmp("c.png"),
                           "--tile-rows", "13");
    assert_int_equal(ft_test_dir_count(), 3); /* the DEM and the two shades */
}

/* The same bytes in two files. */
static void assert_same_file(const char *a, const char *b)
{
    size_t na = 0, nb = 0;
    char *x = ft_test_read_file(a, &na), *y = ft_test_read_file(b, &nb);
    assert_non_null(x);
    assert_non_null(y);
    if (na != nb || memcmp(x, y, na) != 0)
        fail_msg("%s (%zu bytes) differs from %s (%zu bytes)", a, na, b, nb);
    free(x);
    free(y);
}

/* One process shades a DEM beyond half of --max-memory (14 bytes per cell used to send it to the stripes)
 * through the streaming engine, in chunks cut to the bound: the very bytes of the unbounded run, as GeoTIFF
 * (the stripes write another file) in chunks of 58 rows, PNG and --color (which the stripes refuse). Below
 * one decoded block (256 x 256 Float32) the DEM is refused, naming --max-memory, and nothing is left (the
 * 2-row chunk's refusal is in unit/test_io_hillshade). */
static void test_hillshade_beyond_memory_streams(void **state)
{
    (void)state;
    char *dem = strdup(synthetic_dem()); /* 230 x 190: 14 bytes per cell = 598 KiB */
    const char *ext[] = {"tif", "png", "tif"}, *limit[] = {"300K", "300K", "1M"};
    for (int k = 0; k < 3; k++) {
        char w[32], b[32];
        snprintf(w, sizeof w, "hw%d.%s", k, ext[k]);
        snprintf(b, sizeof b, "hb%d.%s", k, ext[k]);
        char *ww = strdup(ft_test_tmp(w)), *bb = strdup(ft_test_tmp(b));
        const char *colour = k == 2 ? "--color" : "--band", *cv = k == 2 ? "--json" : "1"; /* --color k = 2 */
        free(RUN_OUT("hillshade", dem, ww, "--z-factor", "3", colour, cv));
        free(RUN_OUT("--max-memory", limit[k], "hillshade", dem, bb, "--z-factor", "3", colour, cv));
        assert_same_file(ww, bb);
        free(ww);
        free(bb);
    }
    FT_TEST_EXPECT_FAILURE(1, "hillshade", "--max-memory", "--max-memory", "8K", "hillshade", dem,
                           ft_test_tmp("refused.tif"));
    FT_TEST_EXPECT_FAILURE(1, "hillshade", "--max-memory", "--max-memory", "100K", "hillshade", dem,
                           ft_test_tmp("refused.png"));
    free(dem);
    assert_int_equal(ft_test_dir_count(), 7); /* the DEM and the six shades */
}

static void test_tiled_refusals(void **state)
{
    (void)state;
    const char *dem = synthetic_dem();
    FT_TEST_EXPECT_FAILURE(2, "dim map", "random pairs", "dim", "map", dem, ft_test_tmp("m.tif"), "--window", "32",
                           "--pairs", "100", "--tile-rows", "40");
    FT_TEST_EXPECT_FAILURE(2, "dim surface", "random pairs", "dim", "surface", dem, "--pairs", "100", "--tile-rows",
                           "40");
    FT_TEST_EXPECT_FAILURE(2, "dim surface", "got --method spectrum", "dim", "surface", dem, "--method", "spectrum",
                           "--tile-rows", "40");
    FT_TEST_EXPECT_FAILURE(2, "dim surface", "--tile-rows", "dim", "surface", dem, "--tile-rows", "0");
    FT_TEST_EXPECT_FAILURE(1, "dim surface", "longitude/latitude", "dim", "surface", LUX_LONLAT, "--tile-rows",
                           "40");
    FT_TEST_EXPECT_FAILURE(1, "dim map", "longitude/latitude", "dim", "map", LUX_LONLAT, ft_test_tmp("m.tif"),
                           "--window", "16", "--tile-rows", "40");
    FT_TEST_EXPECT_FAILURE(1, "dim map", "must be a GeoTIFF", "dim", "map", dem, ft_test_tmp("m.asc"), "--window",
                           "32", "--tile-rows", "40");
    FT_TEST_EXPECT_FAILURE(1, "dim map", "larger than the 230x190 grid", "dim", "map", dem, ft_test_tmp("m.tif"),
                           "--window", "200", "--tile-rows", "40");
    assert_int_equal(ft_test_dir_count(), 1); /* the DEM: no map, no temporary left behind */
}

/* ---- fill ---- */

/* The synthetic DEM with 60 rectangular voids of 1-20 cells a side scattered over it (many across any
 * stripe border), a 1 x 60 void (longer than --max-void 40: left nodata, across several stripes) and the
 * round hole (40 cells wide: filled), as GeoTIFF. */
static const char *voids_dem(void)
{
    ft_grid *g = NULL;
    assert_int_equal(ft_io_read_grid(synthetic_dem(), NULL, &g), FT_OK);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    ft_rng *r = ft_rng_create(11, 0);
    for (int k = 0; k < 60; k++) {
        size_t w = 1 + (size_t)(ft_rng_uniform(r) * 20.0), h = 1 + (size_t)(ft_rng_uniform(r) * 20.0);
        size_t x0 = (size_t)(ft_rng_uniform(r) * (double)(g->nx - w)), y0 = (size_t)(ft_rng_uniform(r) * (double)(g->ny - h));
        for (size_t y = y0; y < y0 + h; y++)
            for (size_t x = x0; x < x0 + w; x++)
                g->mask[y * g->nx + x] = 0;
    }
    ft_rng_free(r);
    for (size_t y = 100; y < 160; y++)
        g->mask[y * g->nx + 20] = 0;
    const char *path = ft_test_tmp("voids.tif");
    assert_int_equal(ft_io_write_grid(path, g, NULL), FT_OK);
    ft_grid_free(g);
    return path;
}

static void test_fill_tiled_equals_whole(void **state)
{
    (void)state;
    char *dem = strdup(voids_dem()); /* ft_test_tmp's buffers are reused */
    const char *whole = ft_test_tmp("fw.tif"), *t7 = ft_test_tmp("f7.tif");
    char *a = RUN_OUT("fill", dem, whole, "--max-void", "40", "--seed", "3", "--json");
    json_object *o = json_tokener_parse(a);
    assert_non_null(o);
    assert_true(ft_test_json_int(o, "voids_filled") >= 40);
    assert_true(ft_test_json_int(o, "cells_left") >= 60); /* the 1 x 60 void, and merged rectangles */
    json_object_put(o);
    /* 13-row stripes: many voids cross a seam, the long one several */
    char *b = RUN_OUT("fill", dem, t7, "--max-void", "40", "--seed", "3", "--json", "--tile-rows", "13");
    assert_same_band(whole, t7, 1);
    assert_same_report(a, b, "fw.tif", "f7.tif");
    free(a);
    free(b);
    /* no --max-void: the halo grows until the long void lies whole in the window; the sd band too; and the
     * stripes chosen from --max-memory */
    const char *w0 = ft_test_tmp("fw0.tif"), *t0 = ft_test_tmp("ft0.tif"), *m0 = ft_test_tmp("fm0.tif");
    a = RUN_OUT("fill", dem, w0, "--max-void", "0", "-n", "2", "--json");
    b = RUN_OUT("fill", dem, t0, "--max-void", "0", "-n", "2", "--json", "--tile-rows", "29");
    assert_same_band(w0, t0, 1);
    assert_same_band(w0, t0, 2);
    assert_same_report(a, b, "fw0.tif", "ft0.tif");
    free(b);
    b = RUN_OUT("--max-memory", "1M", "fill", dem, m0, "--max-void", "0", "-n", "2", "--json");
    assert_same_band(w0, m0, 1);
    assert_same_report(a, b, "fw0.tif", "fm0.tif");
    free(a);
    free(b);
    FT_TEST_EXPECT_FAILURE(2, "fill", "GeoTIFF only", "fill", dem, ft_test_tmp("f.asc"), "-f", "AAIGrid",
                           "--tile-rows", "7");
    free(dem);
}

/* ft_terrain_fill_rows: a stripe outside its window, and a window too small for a void meeting it. */
static void test_fill_rows_errors(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(20, 10), *out = NULL;
    assert_non_null(g);
    for (size_t i = 0; i < 200; i++)
        g->z[i] = (float)((i * 7919) % 13);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    assert_int_equal(ft_terrain_fill_rows(g, NULL, 5, 100, 4, 8, NULL, &out, NULL, NULL), FT_E_INVALID);
    assert_int_equal(ft_terrain_fill_rows(g, NULL, 5, 100, 8, 8, NULL, &out, NULL, NULL), FT_E_INVALID);
    assert_int_equal(ft_terrain_fill_rows(g, NULL, 95, 100, 96, 99, NULL, &out, NULL, NULL), FT_E_INVALID);
    g->mask[9 * 20 + 10] = 0; /* on the window's last row, which is not the raster's */
    assert_int_equal(ft_terrain_fill_rows(g, NULL, 5, 100, 10, 15, NULL, &out, NULL, NULL), FT_E_UNSUPPORTED);
    assert_non_null(strstr(ft_last_error(), "beyond the window"));
    assert_null(out);
    ft_grid_free(g);
}

/* ---- MPI ---- */

#if defined(FT_TEST_MPIEXEC) && !defined(FT_TEST_SANITIZE)
/* Runs `mpiexec -n n FT_BIN args` with stdout into out_path; returns the exit status. */
static int mpirun_n(int n, const char *out_path, const char *args)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "%s -n %d --oversubscribe %s %s %s > %s 2> %s.err", FT_TEST_MPIEXEC, n,
             geteuid() == 0 ? "--allow-run-as-root" : "", FT_BIN, args, out_path, out_path);
    int rc = system(cmd);
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

static int mpirun2(const char *out_path, const char *args)
{
    return mpirun_n(2, out_path, args);
}

static char *slurp(const char *path)
{
    char *s = ft_test_read_file(path, NULL);
    assert_non_null(s);
    return s;
}
#endif

static void test_mpi_two_ranks_equal_whole(void **state)
{
    (void)state;
#if defined(FT_TEST_MPIEXEC) && !defined(FT_TEST_SANITIZE)
    char *dem = strdup(synthetic_dem()); /* ft_test_tmp's buffers are reused */
    const char *whole = ft_test_tmp("whole.tif"), *m2 = ft_test_tmp("m2.tif");
    char *a = RUN_OUT("dim", "map", dem, whole, "--window", "32", "--step", "8", "--min-valid", "0.9", "--json");
    char args[2048];
    snprintf(args, sizeof args, "dim map %s %s --window 32 --step 8 --min-valid 0.9 --json --tile-rows 40", dem, m2);
    assert_int_equal(mpirun2(ft_test_tmp("map.out"), args), 0);
    assert_same_map(whole, m2);
    char *b = slurp(ft_test_tmp("map.out"));
    assert_same_report(a, b, "whole.tif", "m2.tif");
    free(a);
    free(b);
    /* the noise count is summed over the ranks: the noisy DEM's report equals the whole run's */
    char *noisy = strdup(synthetic_dem_noise(NOISE_SD, "noisy.tif"));
    const char *nw = ft_test_tmp("nw.tif"), *n2 = ft_test_tmp("n2.tif");
    a = RUN_OUT("dim", "map", noisy, nw, "--window", "32", "--step", "16", "--json");
    snprintf(args, sizeof args, "dim map %s %s --window 32 --step 16 --json --tile-rows 40", noisy, n2);
    assert_int_equal(mpirun2(ft_test_tmp("nmap.out"), args), 0);
    b = slurp(ft_test_tmp("nmap.out"));
    assert_non_null(strstr(a, "noise detected in"));
    assert_same_report(a, b, "nw.tif", "n2.tif");
    free(a);
    free(b);
    free(noisy);
    a = RUN_OUT("dim", "surface", dem, "--pairs", "0", "--json");
    snprintf(args, sizeof args, "dim surface %s --json", dem);
    assert_int_equal(mpirun2(ft_test_tmp("surface.out"), args), 0);
    b = slurp(ft_test_tmp("surface.out"));
    assert_string_equal(a, b); /* one report, from rank 0 only, equal to the whole run's */
    free(b);
    /* 9-row stripes: the lags beyond 9 cells read their partner rows, on both ranks */
    snprintf(args, sizeof args, "dim surface %s --json --tile-rows 9", dem);
    assert_int_equal(mpirun2(ft_test_tmp("surface9.out"), args), 0);
    b = slurp(ft_test_tmp("surface9.out"));
    assert_string_equal(a, b);
    free(a);
    free(b);
    const char *hw = ft_test_tmp("hw.tif"), *h2 = ft_test_tmp("h2.tif");
    free(RUN_OUT("hillshade", dem, hw));
    snprintf(args, sizeof args, "hillshade %s %s --tile-rows 30", dem, h2);
    assert_int_equal(mpirun2(ft_test_tmp("shade.out"), args), 0);
    assert_same_shade(hw, h2);
    /* fill: the stripes' voids and cells gathered on rank 0 */
    const char *vd = voids_dem(), *fw = ft_test_tmp("fw.tif"), *f2 = ft_test_tmp("f2.tif");
    a = RUN_OUT("fill", vd, fw, "--max-void", "40", "--json");
    snprintf(args, sizeof args, "fill %s %s --max-void 40 --json", vd, f2);
    assert_int_equal(mpirun2(ft_test_tmp("fill.out"), args), 0);
    assert_same_band(fw, f2, 1);
    b = slurp(ft_test_tmp("fill.out"));
    assert_same_report(a, b, "fw.tif", "f2.tif");
    free(a);
    free(b);
    /* a command that does not decompose is refused on every rank, nothing written */
    snprintf(args, sizeof args, "mountain %s --dim 2.3", ft_test_tmp("s.tif"));
    assert_int_equal(mpirun2(ft_test_tmp("mountain.out"), args), 2);
    char *err = slurp(ft_test_tmp("mountain.out.err"));
    assert_non_null(strstr(err, "fracterra: mountain: does not run on several MPI ranks"));
    free(err);
    assert_int_equal(access(ft_test_tmp("s.tif"), F_OK), -1);
#ifndef FT_TEST_FFTW_MPI
    /* without FFTW's MPI transforms synth keeps its refusal */
    snprintf(args, sizeof args, "synth %s --dim 2.3 --size 64x64", ft_test_tmp("s.tif"));
    assert_int_equal(mpirun2(ft_test_tmp("synth.out"), args), 2);
    err = slurp(ft_test_tmp("synth.out.err"));
    assert_non_null(strstr(err, "fracterra: synth: does not run on several MPI ranks"));
    free(err);
    assert_int_equal(access(ft_test_tmp("s.tif"), F_OK), -1);
#endif
    free(dem);
#else
    skip(); /* built without MPI, or under the sanitizers */
#endif
}

#if defined(FT_TEST_MPIEXEC) && defined(FT_TEST_FFTW_MPI) && !defined(FT_TEST_SANITIZE)
/* max |a - b| over the cells of two one-band rasters of the same size, georeferencing and CRS; *sd: a's sd. */
static double max_abs_diff(const char *a, const char *b, double *sd)
{
    ft_grid *x, *y;
    read_same_frame(a, b, 0, &x, &y);
    if (x->crs_wkt != NULL || y->crs_wkt != NULL)
        ft_test_assert_same_crs(x->crs_wkt, y->crs_wkt);
    ft_grid_stats st;
    ft_grid_compute_stats(x, &st);
    assert_int_equal(st.n, x->nx * x->ny); /* every cell written */
    *sd = st.sd;
    double d = 0.0;
    for (size_t i = 0; i < x->nx * x->ny; i++) {
        assert_true(y->mask == NULL || y->mask[i]);
        d = fmax(d, fabs((double)x->z[i] - (double)y->z[i]));
    }
    ft_grid_free(x);
    ft_grid_free(y);
    return d;
}
#endif

/* `mpiexec -n 1|2|3 synth --method fft` (FFTW's distributed c2r) gives the one-process surface to FFT rounding:
 * max |delta| <= 1e-4 of its sd (issue 20), on odd and even sizes, padded and periodic, sigma 0 (raw scale). */
static void test_mpi_synth_fft_equals_serial(void **state)
{
    (void)state;
#if defined(FT_TEST_MPIEXEC) && defined(FT_TEST_FFTW_MPI) && !defined(FT_TEST_SANITIZE)
    static const char *const cases[] = {
        "--dim 2.3 --size 203x157 --seed 11 --sigma 2 --cell 30 --origin 500000,4600000 --crs EPSG:32632",
        "--dim 2.7 --size 96x64 --seed 4 --periodic --sigma 0",
        "--dim 2.15 --size 41x250 --seed 9",
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char *serial = strdup(ft_test_tmp("synth_serial.tif")), args[1024];
        snprintf(args, sizeof args, "%s synth %s %s", FT_BIN, serial, cases[c]);
        assert_int_equal(system(args), 0);
        for (int n = 1; n <= 3; n++) {
            const char *ranks = ft_test_tmp("synth_ranks.tif");
            unlink(ranks);
            snprintf(args, sizeof args, "synth %s %s --json", ranks, cases[c]);
            assert_int_equal(mpirun_n(n, ft_test_tmp("synth_ranks.out"), args), 0);
            double sd = 0.0, d = max_abs_diff(serial, ft_test_tmp("synth_ranks.tif"), &sd);
            assert_true(sd > 0.0);
            if (!(d <= 1e-4 * sd))
                print_error("%s on %d ranks: max |delta| %g, sd %g\n", cases[c], n, d, sd);
            assert_true(d <= 1e-4 * sd);
            char *rep = slurp(ft_test_tmp("synth_ranks.out")); /* one report, rank 0's */
            assert_non_null(strstr(rep, "\"grid\""));
            assert_null(strstr(strstr(rep, "\"grid\"") + 1, "\"grid\""));
            free(rep);
        }
        free(serial);
    }
    /* only fft runs on ranks, GeoTIFF only: usage errors, nothing written */
    const char *bad = ft_test_tmp("synth_bad.tif");
    char args[1024];
    snprintf(args, sizeof args, "synth %s --dim 2.3 --size 64x64 --method sra", bad);
    assert_int_equal(mpirun2(ft_test_tmp("synth_bad.out"), args), 2);
    char *err = slurp(ft_test_tmp("synth_bad.out.err"));
    assert_non_null(strstr(err, "under mpiexec only --method fft runs"));
    free(err);
    snprintf(args, sizeof args, "synth %s --dim 2.3 --size 64x64 -f AAIGrid", bad);
    assert_int_equal(mpirun2(ft_test_tmp("synth_bad.out"), args), 2);
    assert_int_equal(access(bad, F_OK), -1);
#else
    skip(); /* built without MPI or FFTW's MPI transforms, or under the sanitizers */
#endif
}

#if defined(FT_TEST_MPIEXEC) && defined(FT_TEST_FFTW_MPI) && !defined(FT_TEST_SANITIZE)
/* Files of the test folder whose name starts with prefix or with "." prefix (a temporary of the atomic
 * service). */
static int count_named(const char *prefix)
{
    char *dir = strdup(ft_test_tmp("x")), *slash = strrchr(dir, '/');
    *slash = '\0';
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        const char *name = e->d_name + (e->d_name[0] == '.');
        n += strncmp(name, prefix, strlen(prefix)) == 0;
    }
    closedir(d);
    free(dir);
    return n;
}
#endif

/* `mpiexec -n 1|2|3 synth OUT.vrt`: each rank writes its slab as OUT's stem + ".part-NNNN.tif" and rank 0 the VRT
 * over them; GDAL reads the .vrt as the one-process surface to FFT rounding (max |delta| <= 1e-4 sd), the
 * sources are named relative to the .vrt, and on an error nothing is left behind. */
static void test_mpi_synth_fft_vrt_parts(void **state)
{
    (void)state;
#if defined(FT_TEST_MPIEXEC) && defined(FT_TEST_FFTW_MPI) && !defined(FT_TEST_SANITIZE)
    static const char *const cases[] = {
        "--dim 2.3 --size 203x157 --seed 11 --sigma 2 --cell 30 --origin 500000,4600000 --crs EPSG:32632",
        "--dim 2.15 --size 41x250 --seed 9",
    };
    char args[1024];
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        char *serial = strdup(ft_test_tmp("vrt_serial.tif"));
        snprintf(args, sizeof args, "%s synth %s %s", FT_BIN, serial, cases[c]);
        assert_int_equal(system(args), 0);
        for (int n = 1; n <= 3; n++) {
            char *vrt = strdup(ft_test_tmp("mosaic.vrt"));
            snprintf(args, sizeof args, "synth %s %s --json", vrt, cases[c]);
            assert_int_equal(mpirun_n(n, ft_test_tmp("mosaic.out"), args), 0);
            double sd = 0.0, d = max_abs_diff(serial, vrt, &sd);
            assert_true(sd > 0.0);
            if (!(d <= 1e-4 * sd))
                print_error("%s on %d ranks, .vrt: max |delta| %g, sd %g\n", cases[c], n, d, sd);
            assert_true(d <= 1e-4 * sd);
            char *xml = slurp(vrt); /* one source a rank holding rows, named beside the .vrt */
            assert_non_null(strstr(xml, "<SourceFilename relativeToVRT=\"1\">mosaic.part-0000.tif<"));
            int sources = 0;
            for (const char *p = xml; (p = strstr(p, "<SimpleSource>")) != NULL; p++)
                sources++;
            assert_true(sources >= 1 && sources <= n);
            assert_int_equal(count_named("mosaic.part-"), sources);
            free(xml);
            char *rep = slurp(ft_test_tmp("mosaic.out")); /* one report, rank 0's, read from the mosaic */
            assert_non_null(strstr(rep, "\"grid\""));
            assert_null(strstr(strstr(rep, "\"grid\"") + 1, "\"grid\""));
            free(rep);
            for (int k = 0; k < 3; k++) {
                snprintf(args, sizeof args, "%.*s.part-%04d.tif", (int)(strlen(vrt) - 4), vrt, k);
                unlink(args);
            }
            unlink(vrt);
            free(vrt);
        }
        free(serial);
    }
    /* rank 1's part cannot be written (a folder has its name): every rank fails, no part, no VRT, no temporary */
    char *bad = strdup(ft_test_tmp("broken.vrt"));
    assert_int_equal(mkdir(ft_test_tmp("broken.part-0001.tif"), 0755), 0);
    snprintf(args, sizeof args, "synth %s --dim 2.3 --size 64x64", bad);
    assert_int_equal(mpirun2(ft_test_tmp("brk.out"), args), 1);
    char *err = slurp(ft_test_tmp("brk.out.err"));
    assert_non_null(strstr(err, "broken.part-0001.tif': it is a folder"));
    free(err);
    assert_int_equal(count_named("broken."), 1); /* the folder only */
    assert_int_equal(rmdir(ft_test_tmp("broken.part-0001.tif")), 0);
    /* -f other than GTiff, and a .vrt from one process: usage errors, nothing written */
    snprintf(args, sizeof args, "synth %s --dim 2.3 --size 64x64 -f AAIGrid", bad);
    assert_int_equal(mpirun2(ft_test_tmp("brk.out"), args), 2);
    snprintf(args, sizeof args, "%s synth %s --dim 2.3 --size 64x64 2>/dev/null", FT_BIN, bad);
    int st = system(args);
    assert_true(WIFEXITED(st) && WEXITSTATUS(st) == 2);
    assert_int_equal(count_named("broken."), 0);
    free(bad);
#else
    skip(); /* built without MPI or FFTW's MPI transforms, or under the sanitizers */
#endif
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dim_map_tiled_equals_whole),
        cmocka_unit_test(test_dim_map_noise_count),
        cmocka_unit_test(test_dim_surface_tiled_equals_whole),
        cmocka_unit_test(test_hillshade_tiled_equals_whole),
        cmocka_unit_test(test_hillshade_beyond_memory_streams),
        cmocka_unit_test(test_tiled_refusals),
        cmocka_unit_test(test_fill_tiled_equals_whole),
        cmocka_unit_test(test_fill_rows_errors),
        cmocka_unit_test(test_mpi_two_ranks_equal_whole),
        cmocka_unit_test(test_mpi_synth_fft_equals_serial),
        cmocka_unit_test(test_mpi_synth_fft_vrt_parts),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
