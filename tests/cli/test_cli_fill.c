/* fracterra — tests/cli/test_cli_fill.c: `fracterra fill` end to end on real DEMs: the volcano with punched
 * voids (valid cells bit for bit, voids filled, JSON per void, D of the filled windows near the original's),
 * Luxembourg whose outside is nodata (--max-void keeps it nodata, the voids inside are filled), --max-void
 * in ground units, --mask (gdal_fillnodata's validity convention), --mean, --realizations (two bands),
 * reproducibility, and bad input (exit code, message naming the culprit, nothing written).
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
#include <string.h>

#include "fracterra/fracterra.h"
#include "ft_test_assert.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"

/* The volcano with 6 x 6 voids centred in every 16 x 16 window (cols 5..10 of each window), written to
 * ft_test_tmp("holed.tif"). */
static const char *holed_volcano(ft_grid **orig)
{
    ft_grid *g = ft_test_read_band(VOLCANO, 1);
    *orig = ft_grid_copy(g);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t y = 0; y < g->ny; y++)
        for (size_t x = 0; x < g->nx; x++)
            if (x / 16 < g->nx / 16 && y / 16 < g->ny / 16 && x % 16 >= 5 && x % 16 < 11 && y % 16 >= 5 &&
                y % 16 < 11)
                g->mask[y * g->nx + x] = 0;
    const char *path = ft_test_tmp("holed.tif");
    assert_int_equal(ft_io_write_grid(path, g, NULL), FT_OK);
    ft_grid_free(g);
    return path;
}

/* D of a window by the variogram over lags 1..8 (ft_surface_dim_map, one window per 16 x 16 block). */
static ft_grid *dmap(const ft_grid *g)
{
    ft_surface_dim_opts so = FT_SURFACE_DIM_OPTS_DEFAULT;
    so.fit_whole_range = 1;
    so.min_scale = fabs(g->gt[1]);
    so.max_scale = 8.0 * fabs(g->gt[1]);
    so.min_valid = 1.0;
    ft_grid *D = NULL;
    assert_int_equal(ft_surface_dim_map(g, 16, 16, FT_SURFACE_VARIOGRAM, &so, &D, NULL), FT_OK);
    return D;
}

static void test_volcano(void **state)
{
    (void)state;
    ft_grid *orig = NULL;
    const char *in = holed_volcano(&orig);
    const char *out = ft_test_tmp("filled.tif");
    json_object *o = FT_TEST_RUN_JSON("fill", in, out, "--json", "--seed", "3");
    /* 3 x 5 windows of 16 in 61 x 87 */
    assert_int_equal(ft_test_json_int(o, "voids_found"), 15);
    assert_int_equal(ft_test_json_int(o, "voids_filled"), 15);
    assert_int_equal(ft_test_json_int(o, "cells_filled"), 15 * 36);
    assert_int_equal(ft_test_json_int(o, "cells_left"), 0);
    assert_int_equal(ft_test_json_int(o, "seed"), 3);
    json_object *v = ft_test_json_at(ft_test_json_key(o, "voids"), 0);
    assert_int_equal(ft_test_json_int(v, "cells"), 36);
    assert_true(json_object_get_boolean(ft_test_json_key(v, "filled")));
    double D = ft_test_json_num(v, "D");
    assert_true(D > 2.0 && D < 2.5);
    assert_true(ft_test_json_num(v, "amplitude") > 0.0);
    assert_string_equal(ft_test_json_str(v, "D_source"), "ring");
    json_object_put(o);
    ft_grid *f = ft_test_read_band(out, 1);
    assert_int_equal(f->nx, orig->nx);
    for (size_t i = 0; i < f->nx * f->ny; i++) {
        assert_true(f->mask == NULL || f->mask[i]);
        size_t x = i % f->nx, y = i / f->nx;
        int hole = x / 16 < f->nx / 16 && y / 16 < f->ny / 16 && x % 16 >= 5 && x % 16 < 11 && y % 16 >= 5 &&
                   y % 16 < 11;
        if (!hole)
            assert_memory_equal(&f->z[i], &orig->z[i], sizeof(float));
    }
    /* the windows' D, filled against original: within 0.05 on average over the 15 windows */
    ft_grid *D0 = dmap(orig), *D1 = dmap(f);
    double s = 0.0;
    for (size_t i = 0; i < D0->nx * D0->ny; i++)
        s += D1->z[i] - D0->z[i];
    print_message("volcano: mean D of the 15 windows, filled - original = %+.3f\n", s / 15.0);
    assert_true(fabs(s / 15.0) <= 0.05);
    /* the same seed gives the same cells */
    const char *out2 = ft_test_tmp("again.tif");
    json_object_put(FT_TEST_RUN_JSON("fill", in, out2, "--json", "--seed", "3"));
    ft_grid *f2 = ft_test_read_band(out2, 1);
    assert_memory_equal(f->z, f2->z, f->nx * f->ny * sizeof(float));
    ft_grid_free(f2);
    ft_grid_free(D0);
    ft_grid_free(D1);
    ft_grid_free(f);
    ft_grid_free(orig);
}

/* Luxembourg (30", hills): a 10 x 10 void in the centre of every complete 16 x 16 window, filled with
 * seeds 1..3 (--max-void 10: the outside stays nodata); the windows' D (lags 1-8), filled against
 * original, within 0.05 on average. */
static void test_luxembourg_windows(void **state)
{
    (void)state;
    ft_grid *orig = ft_test_read_band(LUXEMBOURG, 1), *D0 = dmap(orig), *g = ft_grid_copy(orig);
    size_t nwin = 0;
    for (size_t wy = 0; wy < D0->ny; wy++)
        for (size_t wx = 0; wx < D0->nx; wx++) {
            if (!ft_grid_is_valid(D0, wx, wy))
                continue;
            nwin++;
            for (size_t y = wy * 16 + 3; y < wy * 16 + 13; y++)
                for (size_t x = wx * 16 + 3; x < wx * 16 + 13; x++)
                    g->mask[y * g->nx + x] = 0;
        }
    assert_true(nwin >= 6);
    const char *in = ft_test_tmp("lux_holes.tif"), *out = ft_test_tmp("lux_win.tif");
    assert_int_equal(ft_io_write_grid(in, g, NULL), FT_OK);
    double s = 0.0;
    const char *seeds[3] = {"1", "2", "3"};
    for (int k = 0; k < 3; k++) {
        json_object *o = FT_TEST_RUN_JSON("fill", in, out, "--max-void", "10", "--seed", seeds[k], "--json");
        assert_int_equal(ft_test_json_int(o, "cells_filled"), (int64_t)(nwin * 100));
        json_object_put(o);
        ft_grid *f = ft_test_read_band(out, 1), *D1 = dmap(f);
        for (size_t i = 0; i < D0->nx * D0->ny; i++)
            if (ft_grid_is_valid(D0, i % D0->nx, i / D0->nx)) {
                assert_true(ft_grid_is_valid(D1, i % D0->nx, i / D0->nx));
                s += D1->z[i] - D0->z[i];
            }
        ft_grid_free(D1);
        ft_grid_free(f);
    }
    print_message("Luxembourg: mean D of %zu windows x 3 seeds, filled - original = %+.3f\n", nwin,
                  s / (3.0 * (double)nwin));
    assert_true(fabs(s / (3.0 * (double)nwin)) <= 0.05);
    ft_grid_free(g);
    ft_grid_free(D0);
    ft_grid_free(orig);
}

static void test_luxembourg_outside_stays(void **state)
{
    (void)state;
    ft_grid *g = ft_test_read_band(LUXEMBOURG, 1);
    size_t outside = g->nx * g->ny - ft_grid_count_valid(g);
    /* a 5 x 4 void inside the country */
    for (size_t y = 40; y < 44; y++)
        for (size_t x = 45; x < 50; x++) {
            assert_true(g->mask[y * g->nx + x]);
            g->mask[y * g->nx + x] = 0;
        }
    const char *in = ft_test_tmp("lux.tif"), *out = ft_test_tmp("lux_filled.tif");
    assert_int_equal(ft_io_write_grid(in, g, NULL), FT_OK);
    json_object *o = FT_TEST_RUN_JSON("fill", in, out, "--max-void", "20", "--json");
    assert_int_equal(ft_test_json_int(o, "cells_filled"), 20);
    assert_int_equal(ft_test_json_int(o, "cells_left"), (int64_t)outside);
    json_object_put(o);
    ft_grid *f = ft_test_read_band(out, 1);
    assert_int_equal(f->nx * f->ny - ft_grid_count_valid(f), outside);
    for (size_t i = 0; i < f->nx * f->ny; i++)
        assert_int_equal(f->mask[i], g->mask[i] || ((i / g->nx) >= 40 && (i / g->nx) < 44 && (i % g->nx) >= 45 &&
                                                     (i % g->nx) < 50));
    ft_grid_free(f);
    ft_grid_free(g);
}

static void test_mask_mean_realizations(void **state)
{
    (void)state;
    ft_grid *g = ft_test_read_band(VOLCANO, 1);
    ft_grid *m = ft_grid_create(g->nx, g->ny);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        m->z[i] = 1.0f;
    for (size_t y = 30; y < 40; y++)
        for (size_t x = 20; x < 28; x++)
            m->z[y * g->nx + x] = 0.0f; /* zero: invalid, to fill */
    const char *mask = ft_test_tmp("mask.tif"), *out = ft_test_tmp("mean.tif"), *out2 = ft_test_tmp("r.tif");
    assert_int_equal(ft_io_write_grid(mask, m, NULL), FT_OK);
    json_object *o = FT_TEST_RUN_JSON("fill", VOLCANO, out, "--mask", mask, "--mean", "--json");
    assert_int_equal(ft_test_json_int(o, "cells_filled"), 80);
    assert_string_equal(ft_test_json_str(o, "method"), "kriging mean");
    json_object_put(o);
    o = FT_TEST_RUN_JSON("fill", VOLCANO, out2, "--mask", mask, "--realizations", "8", "--json");
    assert_string_equal(ft_test_json_str(o, "bands"), "1: mean, 2: sd");
    json_object_put(o);
    ft_grid *mean = ft_test_read_band(out, 1), *rm = ft_test_read_band(out2, 1), *sd = ft_test_read_band(out2, 2);
    size_t i = 35 * g->nx + 24;
    assert_true(mean->z[i] != g->z[i]);
    assert_true(sd->z[i] > 0.0f);
    assert_near(sd->z[5 * g->nx + 5], 0.0, 0.0);
    assert_true(fabs(rm->z[i] - mean->z[i]) < 3.0 * sd->z[i]);
    /* ground units: 10 m cells, a 10-cell void is 100 m long */
    o = FT_TEST_RUN_JSON("fill", VOLCANO, out, "--mask", mask, "--max-void", "90m", "--json");
    assert_int_equal(ft_test_json_int(o, "cells_filled"), 0);
    assert_int_equal(ft_test_json_int(o, "cells_left"), 80);
    json_object_put(o);
    ft_grid_free(mean);
    ft_grid_free(rm);
    ft_grid_free(sd);
    ft_grid_free(m);
    ft_grid_free(g);
}

static void test_bad_input(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("o.tif");
    FT_TEST_EXPECT_FAILURE(2, "fill", "--max-void", "fill", VOLCANO, out, "--max-void", "ten");
    FT_TEST_EXPECT_FAILURE(2, "fill", "--max-void", "fill", VOLCANO, out, "--max-void", "-3");
    FT_TEST_EXPECT_FAILURE(2, "fill", "--realizations", "fill", VOLCANO, out, "--realizations", "0");
    FT_TEST_EXPECT_FAILURE(2, "fill", "--mean", "fill", VOLCANO, out, "--mean", "--realizations", "4");
    FT_TEST_EXPECT_FAILURE(2, "fill", "--dim", "fill", VOLCANO, out, "--dim", "3.5");
    FT_TEST_EXPECT_FAILURE(2, "fill", "--ring", "fill", VOLCANO, out, "--ring", "1");
    FT_TEST_EXPECT_FAILURE(2, "fill", "OUT", "fill", VOLCANO);
    FT_TEST_EXPECT_FAILURE(2, "fill", "geographic", "fill", LUXEMBOURG, out, "--max-void", "3000m");
    FT_TEST_EXPECT_FAILURE(1, "fill", "nope.tif", "fill", "nope.tif", out);
    FT_TEST_EXPECT_FAILURE(1, "fill", "--mask", "fill", VOLCANO, out, "--mask", LUXEMBOURG);
    ft_grid *g = ft_grid_create(8, 8);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    memset(g->mask, 0, 64);
    g->has_nodata = 1;
    g->nodata_value = -9999.0;
    const char *empty = ft_test_tmp("empty.tif");
    assert_int_equal(ft_io_write_grid(empty, g, NULL), FT_OK);
    ft_grid_free(g);
    FT_TEST_EXPECT_FAILURE(1, "fill", "no valid cell", "fill", empty, out);
    assert_int_equal(ft_test_dir_count(), 1); /* the fixture, no output */
}

static void test_help(void **state)
{
    (void)state;
    ft_run_result r;
    assert_int_equal(ft_run(&r, "fill", "--help", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "Example"));
    assert_non_null(strstr(r.out, "--max-void"));
    ft_run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_volcano),
        cmocka_unit_test(test_luxembourg_windows),
        cmocka_unit_test(test_luxembourg_outside_stays),
        cmocka_unit_test(test_mask_mean_realizations),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_help),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
