/* fracterra — unit tests of surface/dim_map.c: a surface made of two halves of different D shows the
 * difference, the output lies on the window-centre lattice of the input (geotransform, CRS), holes make
 * nodata windows, the same map on 1 and 2 threads, the lag methods' block-sum map equal to the estimator
 * run on every window, and bad input (all nodata, window larger than the grid, step 0, unknown method, a
 * scale range the window cannot hold) named in the error.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <omp.h>
#include <string.h>

#include "fracterra/surface.h"
#include "fracterra/terrain.h"
#include "ft_test_assert.h"

/* 512 x 256 cells: columns 0-255 of a D = 2.2 surface, columns 256-511 of a D = 2.8 one. */
static ft_grid *two_halves(void)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = FT_SYNTH_EXACT;
    ft_grid *a = NULL, *b = NULL, *g = ft_grid_create(512, 256);
    o.dim = 2.2;
    o.seed = 4;
    assert_int_equal(ft_terrain_synth(256, 256, &o, &a), 0);
    o.dim = 2.8;
    assert_int_equal(ft_terrain_synth(256, 256, &o, &b), 0);
    for (size_t i = 0; i < 256; i++)
        for (size_t j = 0; j < 256; j++) {
            g->z[i * 512 + j] = a->z[i * 256 + j];
            g->z[i * 512 + 256 + j] = b->z[i * 256 + j];
        }
    ft_grid_free(a);
    ft_grid_free(b);
    g->gt[0] = 1000.0;
    g->gt[1] = 10.0;
    g->gt[3] = 5000.0;
    g->gt[5] = -10.0;
    assert_int_equal(ft_grid_set_crs(g, "EPSG:32633"), 0);
    return g;
}

static int progress_calls;
static int count_progress(double frac, const char *msg, void *arg)
{
    (void)msg;
    (void)arg;
    assert_true(frac >= 0.0 && frac <= 1.0);
    progress_calls++;
    return 1;
}

static void test_two_halves(void **state)
{
    (void)state;
    ft_grid *g = two_halves(), *D = NULL, *r2 = NULL;
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.fit_whole_range = 1;
    o.progress = count_progress;
    assert_int_equal(ft_surface_dim_map(g, 64, 32, FT_SURFACE_VARIOGRAM, &o, &D, &r2), 0);
    assert_true(progress_calls >= 2);
    assert_int_equal(D->nx, (512 - 64) / 32 + 1);
    assert_int_equal(D->ny, (256 - 64) / 32 + 1);
    /* output cell (0, 0) is centred on window (0, 0)'s centre, 32 cells from the corner */
    assert_true(fabs(D->gt[0] - (1000.0 + (64 - 32) / 2 * 10.0)) < 1e-9);
    assert_true(fabs(D->gt[3] - (5000.0 - (64 - 32) / 2 * 10.0)) < 1e-9);
    assert_true(fabs(D->gt[1] - 320.0) < 1e-9 && fabs(D->gt[5] + 320.0) < 1e-9);
    assert_non_null(D->crs_wkt);
    double left = 0.0, right = 0.0;
    int nl = 0, nr = 0;
    for (size_t i = 0; i < D->ny; i++)
        for (size_t j = 0; j < D->nx; j++) {
            size_t k = i * D->nx + j;
            assert_true(D->mask[k] && r2->mask[k]);
            assert_true(r2->z[k] > 0.5f && r2->z[k] <= 1.0f);
            if (j * 32 + 64 <= 256) {
                left += D->z[k];
                nl++;
            } else if (j * 32 >= 256) {
                right += D->z[k];
                nr++;
            }
        }
    left /= nl;
    right /= nr;
    print_message("mean D: left %.3f (2.2), right %.3f (2.8)\n", left, right);
    assert_true(fabs(left - 2.2) < 0.1 && fabs(right - 2.8) < 0.1);
    assert_true(right - left > 0.45);
    /* the same bits on one thread */
    ft_grid *D1 = NULL;
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    o.progress = NULL;
    assert_int_equal(ft_surface_dim_map(g, 64, 32, FT_SURFACE_VARIOGRAM, &o, &D1, NULL), 0);
    omp_set_num_threads(nt);
    assert_memory_equal(D->z, D1->z, D->nx * D->ny * sizeof(float));
    ft_grid_free(D1);
    ft_grid_free(D);
    ft_grid_free(r2);
    ft_grid_free(g);
}

/* Holes: a window mostly nodata is nodata; the other methods run too. */
static void test_holes_and_methods(void **state)
{
    (void)state;
    ft_grid *g = two_halves(), *D = NULL;
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    for (size_t i = 0; i < 128; i++)
        for (size_t j = 0; j < 128; j++)
            g->mask[i * 512 + j] = 0; /* the upper-left 128 x 128 cells */
    assert_int_equal(ft_surface_dim_map(g, 64, 64, FT_SURFACE_PRISM, NULL, &D, NULL), 0);
    assert_int_equal(D->nx, 8);
    assert_int_equal(D->ny, 4);
    assert_false(D->mask[0]);
    assert_false(D->mask[1 * 8 + 1]);
    assert_true(isnan(D->z[0]));
    assert_true(D->mask[3 * 8 + 7]);
    ft_grid_free(D);
    for (int m = 0; m < FT_SURFACE_NMETHODS; m++) {
        ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
        o.fit_whole_range = 1;
        if (m == FT_SURFACE_SPECTRUM)
            o.min_scale = 40; /* 4 cells: a 128-cell window fits 4 .. 16 */
        assert_int_equal(ft_surface_dim_map(g, 128, 128, (ft_surface_method)m, &o, &D, NULL), 0);
        assert_true(ft_grid_count_valid(D) >= 6);
        ft_grid_free(D);
    }
    ft_grid_free(g);
}

/* The lag methods' map sums pair counters over blocks shared by the windows (dim_map_lags.c) instead of
 * measuring each window: it must equal ft_surface_dim on a copy of every window (the same windows
 * measured, D and r² within 1e-6), whatever the window, the step (dividing the window or not, larger than
 * it, 1), the holes, the fit and the scale options. */
static void check_against_windows(const ft_grid *g, size_t w, size_t s, ft_surface_method m,
                                  const ft_surface_dim_opts *o)
{
    ft_grid *D = NULL, *r2 = NULL, *win = ft_grid_create(w, w);
    assert_int_equal(ft_surface_dim_map(g, w, s, m, o, &D, &r2), 0);
    assert_int_equal(ft_grid_ensure_mask(win), 0);
    size_t measured = 0;
    for (size_t i = 0; i < D->ny; i++)
        for (size_t j = 0; j < D->nx; j++) {
            size_t valid = 0, k = i * D->nx + j;
            for (size_t a = 0; a < w; a++)
                for (size_t b = 0; b < w; b++) {
                    size_t src = (i * s + a) * g->nx + j * s + b;
                    int ok = (g->mask == NULL || g->mask[src]) && isfinite(g->z[src]);
                    win->z[a * w + b] = ok ? g->z[src] : 0.0f;
                    win->mask[a * w + b] = (uint8_t)ok;
                    valid += (size_t)ok;
                }
            memcpy(win->gt, g->gt, sizeof win->gt);
            ft_dim_result *r = NULL;
            int ok = (double)valid >= o->min_valid * (double)(w * w) && valid > 0 &&
                     ft_surface_dim(win, m, o, &r) == FT_OK;
            assert_int_equal(D->mask[k], ok);
            assert_int_equal(r2->mask[k], ok);
            if (ok) {
                assert_near(D->z[k], r->D, 1e-6);
                assert_near(r2->z[k], r->r2, 1e-6);
                measured++;
            }
            ft_dim_result_free(r);
        }
    assert_true(measured > 0);
    ft_grid_free(win);
    ft_grid_free(D);
    ft_grid_free(r2);
}

static void test_lag_maps_equal_windows(void **state)
{
    (void)state;
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.method = FT_SYNTH_EXACT;
    so.dim = 2.4;
    so.seed = 11;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(150, 110, &so, &g), 0);
    g->gt[1] = 10.0;
    g->gt[5] = -7.0; /* oblong cells */
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    for (size_t i = 0; i < 110; i++)
        for (size_t j = 0; j < 150; j++)
            if (hypot((double)j - 40.0, (double)i - 30.0) < 14.0 || hypot((double)j - 110.0, (double)i - 80.0) < 9.0 ||
                (i * 150 + j) % 97 == 0) {
                g->mask[i * 150 + j] = 0;
                g->z[i * 150 + j] = 1e30f;
            }
    /* step 1 on a 50 x 40 corner holding the first hole (24-cell windows: lags 1 .. 3) */
    ft_grid *small = ft_grid_create(50, 40);
    assert_int_equal(ft_grid_ensure_mask(small), 0);
    for (size_t i = 0; i < 40; i++)
        for (size_t j = 0; j < 50; j++) {
            small->z[i * 50 + j] = g->z[i * 150 + j];
            small->mask[i * 50 + j] = g->mask[i * 150 + j];
        }
    memcpy(small->gt, g->gt, sizeof small->gt);
    static const size_t ws[][2] = {{32, 8}, {33, 7}, {24, 40}, {16, 6}, {24, 1}};
    for (int m = FT_SURFACE_VARIOGRAM; m <= FT_SURFACE_PENTLAND; m++)
        for (size_t c = 0; c < sizeof ws / sizeof ws[0]; c++) {
            ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
            o.fit_whole_range = (int)(c % 2) || ws[c][1] == 1;
            o.min_valid = 0.8;
            if (c == 1) {
                o.min_scale = 20.0; /* 2 .. 8 cells of sqrt(70) ground units */
                o.max_scale = 70.0;
                o.nscales = 5;
            }
            check_against_windows(ws[c][1] == 1 ? small : g, ws[c][0], ws[c][1], (ft_surface_method)m, &o);
        }
    ft_grid_free(small);
    ft_grid_free(g);
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(100, 80), *D = (ft_grid *)1;
    assert_int_equal(ft_surface_dim_map(g, 120, 10, FT_SURFACE_VARIOGRAM, NULL, &D, NULL), FT_E_INVALID);
    assert_null(D);
    assert_non_null(strstr(ft_last_error(), "120"));
    assert_int_equal(ft_surface_dim_map(g, 32, 0, FT_SURFACE_VARIOGRAM, NULL, &D, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "step"));
    assert_int_equal(ft_surface_dim_map(g, 32, 8, (ft_surface_method)17, NULL, &D, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "17"));
    assert_int_equal(ft_surface_dim_map(g, 32, 8, FT_SURFACE_VARIOGRAM, NULL, NULL, NULL), FT_E_INVALID);
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.min_valid = 1.5;
    assert_int_equal(ft_surface_dim_map(g, 32, 8, FT_SURFACE_VARIOGRAM, &o, &D, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "1.5"));
    /* a range the window cannot hold fails the map with the estimator's message */
    for (size_t i = 0; i < 100 * 80; i++)
        g->z[i] = (float)((i * 7919) % 101);
    o = (ft_surface_dim_opts)FT_SURFACE_DIM_OPTS_DEFAULT;
    o.max_scale = 500;
    assert_int_equal(ft_surface_dim_map(g, 32, 8, FT_SURFACE_YOKOYA, &o, &D, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "500"));
    assert_non_null(strstr(ft_last_error(), "window of 32"));
    /* all nodata */
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    memset(g->mask, 0, 100 * 80);
    assert_int_equal(ft_surface_dim_map(g, 32, 8, FT_SURFACE_VARIOGRAM, NULL, &D, NULL), FT_E_EMPTY);
    assert_non_null(strstr(ft_last_error(), "nodata"));
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_two_halves),
        cmocka_unit_test(test_holes_and_methods),
        cmocka_unit_test(test_lag_maps_equal_windows),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
