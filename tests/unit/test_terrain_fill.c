/* fracterra — unit tests of terrain/fill*.c (ft_terrain_fill): bad options and data named in the error,
 * a flat DEM (the kriging of a constant is that constant), valid cells bit for bit and reproducibility,
 * --max-void and the validity mask, voids on the edge, realizations (mean, sd), and on exact fBm of
 * D = 2.2, 2.5, 2.8 with 16 voids of 48 x 48 cells: the D of the filled cells (lag 1-8 variogram written
 * here) within 0.05 of the true D, increments across the void borders like the truth's, and the RMSE of
 * the kriging mean no worse than GDAL's FillNodata (max distance unbounded, no smoothing) on the same
 * voids.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <gdal.h>
#include <gdal_alg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/terrain.h"
#include "ft_test_assert.h"

static ft_grid *fbm(size_t n, double D, uint64_t seed)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = FT_SYNTH_EXACT;
    o.dim = D;
    o.sigma = 100.0;
    o.seed = seed;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(n, n, &o, &g), 0);
    return g;
}

/* Marks a w x h void at (x0, y0): mask 0. */
static void punch(ft_grid *g, size_t x0, size_t y0, size_t w, size_t h)
{
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    for (size_t y = y0; y < y0 + h; y++)
        for (size_t x = x0; x < x0 + w; x++)
            g->mask[y * g->nx + x] = 0;
}

/* D = 3 - slope / 2 of log mean (dz)² on log lag, lags 1..8 along rows and columns, pairs with both
 * cells selected (an estimator independent of the library's). */
static double variogram_D(const float *z, const uint8_t *sel, size_t nx, size_t ny)
{
    double lx[8], ly[8];
    for (size_t h = 1; h <= 8; h++) {
        double s = 0.0, c = 0.0;
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++) {
                size_t i = y * nx + x;
                if (!sel[i])
                    continue;
                if (x + h < nx && sel[i + h]) {
                    s += ((double)z[i + h] - z[i]) * ((double)z[i + h] - z[i]);
                    c++;
                }
                if (y + h < ny && sel[i + h * nx]) {
                    s += ((double)z[i + h * nx] - z[i]) * ((double)z[i + h * nx] - z[i]);
                    c++;
                }
            }
        assert_true(c > 0.0);
        lx[h - 1] = log((double)h);
        ly[h - 1] = log(s / c);
    }
    double mx = 0.0, my = 0.0, sxy = 0.0, sxx = 0.0;
    for (int i = 0; i < 8; i++) {
        mx += lx[i] / 8.0;
        my += ly[i] / 8.0;
    }
    for (int i = 0; i < 8; i++) {
        sxy += (lx[i] - mx) * (ly[i] - my);
        sxx += (lx[i] - mx) * (lx[i] - mx);
    }
    return 3.0 - sxy / sxx / 2.0;
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_grid *g = fbm(32, 2.5, 1), *out = NULL;
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    o.max_void = -1.0;
    assert_error_names(ft_terrain_fill(g, NULL, &o, &out, NULL, NULL), FT_E_INVALID, "max_void");
    o = (ft_fill_opts)FT_FILL_OPTS_DEFAULT;
    o.realizations = 0;
    assert_error_names(ft_terrain_fill(g, NULL, &o, &out, NULL, NULL), FT_E_INVALID, "realizations");
    o = (ft_fill_opts)FT_FILL_OPTS_DEFAULT;
    o.mean = 1;
    o.realizations = 4;
    assert_error_names(ft_terrain_fill(g, NULL, &o, &out, NULL, NULL), FT_E_INVALID, "mean");
    o = (ft_fill_opts)FT_FILL_OPTS_DEFAULT;
    o.dim = 3.2;
    assert_error_names(ft_terrain_fill(g, NULL, &o, &out, NULL, NULL), FT_E_INVALID, "3.2");
    o = (ft_fill_opts)FT_FILL_OPTS_DEFAULT;
    o.ring = 1;
    assert_error_names(ft_terrain_fill(g, NULL, &o, &out, NULL, NULL), FT_E_INVALID, "ring");
    assert_error_names(ft_terrain_fill(NULL, NULL, NULL, &out, NULL, NULL), FT_E_INVALID, "NULL");
    punch(g, 0, 0, 32, 32);
    assert_error_names(ft_terrain_fill(g, NULL, NULL, &out, NULL, NULL), FT_E_EMPTY, "no valid cell");
    assert_null(out);
    ft_grid_free(g);
    /* a 3 x 3 DEM with one void: no lag has enough pairs anywhere */
    ft_grid *t = ft_grid_create(3, 3);
    for (size_t i = 0; i < 9; i++)
        t->z[i] = (float)(i * i);
    punch(t, 1, 1, 1, 1);
    assert_error_names(ft_terrain_fill(t, NULL, NULL, &out, NULL, NULL), FT_E_EMPTY, "too few valid");
    ft_grid_free(t);
}

static void test_flat(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(40, 40), *out = NULL;
    for (size_t i = 0; i < 1600; i++)
        g->z[i] = 123.5f;
    punch(g, 10, 12, 7, 5);
    ft_fill_result *r = NULL;
    assert_int_equal(ft_terrain_fill(g, NULL, NULL, &out, NULL, &r), 0);
    assert_int_equal(r->nvoids, 1);
    assert_int_equal(r->voids[0].source, FT_FILL_D_FLAT);
    assert_true(isnan(r->voids[0].D));
    for (size_t i = 0; i < 1600; i++) {
        assert_int_equal(out->mask[i], 1);
        assert_near(out->z[i], 123.5, 1e-3);
    }
    ft_fill_result_free(r);
    ft_grid_free(out);
    ft_grid_free(g);
}

static void test_exact_and_reproducible(void **state)
{
    (void)state;
    ft_grid *g = fbm(96, 2.4, 3);
    punch(g, 20, 30, 12, 9);
    punch(g, 60, 10, 5, 20);
    punch(g, 0, 80, 6, 16); /* on the edge */
    ft_grid *a = NULL, *b = NULL, *c = NULL;
    ft_fill_result *r = NULL;
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    o.seed = 9;
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &a, NULL, &r), 0);
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &b, NULL, NULL), 0);
    o.seed = 10;
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &c, NULL, NULL), 0);
    assert_int_equal(r->nvoids, 3);
    assert_int_equal(r->voids_filled, 3);
    assert_int_equal(r->cells_filled, 12 * 9 + 5 * 20 + 6 * 16);
    assert_int_equal(r->voids[2].edge, 1);
    assert_int_equal(r->voids[0].edge, 0);
    size_t differ = 0;
    for (size_t i = 0; i < 96 * 96; i++) {
        assert_int_equal(a->mask[i], 1);
        assert_true(isfinite(a->z[i]));
        if (g->mask[i])
            assert_memory_equal(&a->z[i], &g->z[i], sizeof(float));
        differ += a->z[i] != c->z[i];
    }
    assert_memory_equal(a->z, b->z, 96 * 96 * sizeof(float));
    assert_true(differ > 300);
    for (size_t k = 0; k < 3; k++) {
        assert_true(r->voids[k].D > 2.2 && r->voids[k].D < 2.6);
        assert_true(r->voids[k].conditioning > 0);
    }
    ft_fill_result_free(r);
    ft_grid_free(a);
    ft_grid_free(b);
    ft_grid_free(c);
    ft_grid_free(g);
}

static void test_max_void_and_mask(void **state)
{
    (void)state;
    ft_grid *g = fbm(128, 2.5, 4), *out = NULL;
    punch(g, 10, 10, 4, 4);    /* small */
    punch(g, 40, 40, 30, 12);  /* 30 cells long */
    punch(g, 100, 0, 28, 40);  /* "sea" on the edge, 40 long */
    uint8_t *valid = malloc(128 * 128);
    memset(valid, 1, 128 * 128);
    for (size_t y = 90; y < 93; y++)
        for (size_t x = 20; x < 25; x++)
            valid[y * 128 + x] = 0; /* a hole given by the mask only */
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    o.max_void = 30;
    ft_fill_result *r = NULL;
    assert_int_equal(ft_terrain_fill(g, valid, &o, &out, NULL, &r), 0);
    assert_int_equal(r->nvoids, 4);
    assert_int_equal(r->voids_filled, 3);
    assert_int_equal(r->cells_left, 28 * 40);
    for (size_t y = 0; y < 128; y++)
        for (size_t x = 0; x < 128; x++) {
            int sea = x >= 100 && y < 40;
            assert_int_equal(out->mask[y * 128 + x], !sea);
        }
    assert_true(out->z[91 * 128 + 22] != g->z[91 * 128 + 22]);
    ft_fill_result_free(r);
    ft_grid_free(out);
    o.max_void = 0; /* no limit: the sea too */
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &out, NULL, &r), 0);
    assert_int_equal(r->voids_filled, 3);
    assert_int_equal(r->cells_left, 0);
    ft_fill_result_free(r);
    ft_grid_free(out);
    free(valid);
    ft_grid_free(g);
}

static void test_realizations(void **state)
{
    (void)state;
    ft_grid *g = fbm(80, 2.5, 5), *m = NULL, *mean = NULL, *sd = NULL;
    punch(g, 30, 30, 16, 16);
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    o.mean = 1;
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &m, NULL, NULL), 0);
    o.mean = 0;
    o.realizations = 24;
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &mean, &sd, NULL), 0);
    /* the mean of realizations tends to the kriging mean; sd grows from the border to the centre */
    double sum_d = 0.0, sum_sd = 0.0;
    for (size_t y = 30; y < 46; y++)
        for (size_t x = 30; x < 46; x++) {
            size_t i = y * 80 + x;
            sum_d += fabs(mean->z[i] - m->z[i]);
            sum_sd += sd->z[i];
        }
    assert_true(sum_d / 256.0 < 0.5 * sum_sd / 256.0);
    assert_true(sd->z[38 * 80 + 38] > sd->z[30 * 80 + 30]);
    assert_near(sd->z[10 * 80 + 10], 0.0, 0.0);
    ft_grid_free(m);
    ft_grid_free(mean);
    ft_grid_free(sd);
    ft_grid_free(g);
}

static int cancel_at_once(double frac, const char *msg, void *arg)
{
    (void)frac;
    (void)msg;
    (void)arg;
    return 0;
}

static void test_cancel(void **state)
{
    (void)state;
    ft_grid *g = fbm(64, 2.5, 6), *out = NULL, *sd = NULL;
    punch(g, 10, 10, 8, 8);
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    o.progress = cancel_at_once;
    o.realizations = 2;
    ft_fill_result *r = NULL;
    assert_int_equal(ft_terrain_fill(g, NULL, &o, &out, &sd, &r), FT_E_CANCELLED);
    assert_null(out);
    assert_null(sd);
    assert_null(r);
    ft_grid_free(g);
}

/* GDAL's FillNodata on a copy of g (max distance unbounded, no smoothing); returns the filled cells. */
static float *gdal_fill(const ft_grid *g)
{
    GDALAllRegister();
    int n = (int)g->nx;
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("MEM"), "", n, n, 1, GDT_Float32, NULL);
    assert_non_null(ds);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    float *buf = malloc(g->nx * g->ny * sizeof *buf);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        buf[i] = g->mask[i] ? g->z[i] : -9999.0f;
    assert_int_equal(GDALRasterIO(b, GF_Write, 0, 0, n, n, buf, n, n, GDT_Float32, 0, 0), CE_None);
    assert_int_equal(GDALSetRasterNoDataValue(b, -9999.0), CE_None);
    assert_int_equal(GDALFillNodata(b, NULL, (double)n, 0, 0, NULL, NULL, NULL), CE_None);
    assert_int_equal(GDALRasterIO(b, GF_Read, 0, 0, n, n, buf, n, n, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
    return buf;
}

static void test_fbm_accuracy(void **state)
{
    (void)state;
    const size_t N = 384, V = 48;
    const double dims[3] = {2.2, 2.5, 2.8};
    for (int k = 0; k < 3; k++) {
        ft_grid *t = fbm(N, dims[k], 20 + (uint64_t)k), *g = ft_grid_copy(t), *real = NULL, *mean = NULL;
        uint8_t *sel = calloc(N * N, 1);
        for (size_t a = 0; a < 4; a++)
            for (size_t b = 0; b < 4; b++) {
                size_t x0 = a * 2 * V + V / 2, y0 = b * 2 * V + V / 2;
                punch(g, x0, y0, V, V);
                for (size_t y = y0; y < y0 + V; y++)
                    memset(sel + y * N + x0, 1, V);
            }
        ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
        o.seed = 7;
        assert_int_equal(ft_terrain_fill(g, NULL, &o, &real, NULL, NULL), 0);
        o.mean = 1;
        assert_int_equal(ft_terrain_fill(g, NULL, &o, &mean, NULL, NULL), 0);
        float *gd = gdal_fill(g);
        double D_fill = variogram_D(real->z, sel, N, N), D_truth = variogram_D(t->z, sel, N, N);
        double e_mean = 0.0, e_gdal = 0.0, cross_fill = 0.0, cross_true = 0.0;
        for (size_t y = 0; y < N; y++)
            for (size_t x = 0; x < N; x++) {
                size_t i = y * N + x;
                if (sel[i]) {
                    e_mean += ((double)mean->z[i] - t->z[i]) * ((double)mean->z[i] - t->z[i]);
                    e_gdal += ((double)gd[i] - t->z[i]) * ((double)gd[i] - t->z[i]);
                }
                /* one-cell increments across a void border */
                if (x + 1 < N && sel[i] != sel[i + 1]) {
                    cross_fill += pow((double)real->z[i + 1] - real->z[i], 2);
                    cross_true += pow((double)t->z[i + 1] - t->z[i], 2);
                }
                if (y + 1 < N && sel[i] != sel[i + N]) {
                    cross_fill += pow((double)real->z[i + N] - real->z[i], 2);
                    cross_true += pow((double)t->z[i + N] - t->z[i], 2);
                }
            }
        print_message("D %.1f: filled %.3f, truth in the voids %.3f; RMSE kriging mean %.2f, GDAL %.2f; "
                      "border increments fill/truth %.3f\n", dims[k], D_fill, D_truth, sqrt(e_mean / (16.0 * V * V)),
                      sqrt(e_gdal / (16.0 * V * V)), cross_fill / cross_true);
        assert_near(D_fill, dims[k], 0.05);
        assert_true(e_mean <= e_gdal);
        assert_true(cross_fill / cross_true > 0.8 && cross_fill / cross_true < 1.25);
        free(gd);
        free(sel);
        ft_grid_free(real);
        ft_grid_free(mean);
        ft_grid_free(g);
        ft_grid_free(t);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_flat),
        cmocka_unit_test(test_exact_and_reproducible),
        cmocka_unit_test(test_max_void_and_mask),
        cmocka_unit_test(test_realizations),
        cmocka_unit_test(test_cancel),
        cmocka_unit_test(test_fbm_accuracy),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
