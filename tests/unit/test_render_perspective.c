/* fracterra — tests/unit/test_render_perspective.c: the perspective (bird's-eye) view: a PNG of plausible
 * size, a peak drawn above a flat plain, nodata holes, bad options rejected.
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
#include <string.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

#define N 101

/* A flat plain of 10 m cells, with a Gaussian peak of height h in the middle. */
static ft_grid *plain(double h)
{
    ft_grid *g = ft_grid_create(N, N);
    assert_non_null(g);
    double gt[6] = {1000.0, 10.0, 0.0, 5000.0, 0.0, -10.0};
    memcpy(g->gt, gt, sizeof gt);
    for (size_t r = 0; r < N; r++)
        for (size_t c = 0; c < N; c++) {
            double dx = (double)c - N / 2, dy = (double)r - N / 2;
            g->z[r * N + c] = (float)(100.0 + h * exp(-(dx * dx + dy * dy) / 50.0));
        }
    return g;
}

/* The topmost opaque row of column x (-1 if none). */
static int top_row(cairo_surface_t *s, int x)
{
    int h = cairo_image_surface_get_height(s), stride = cairo_image_surface_get_stride(s);
    const unsigned char *d = cairo_image_surface_get_data(s);
    for (int y = 0; y < h; y++)
        if (((const uint32_t *)(const void *)(d + (size_t)y * stride))[x] >> 24 > 128)
            return y;
    return -1;
}

static cairo_surface_t *render(const ft_grid *g, const char *name, int sky)
{
    ft_perspective_opts o = FT_PERSPECTIVE_OPTS_DEFAULT;
    o.azimuth = 0.0;
    o.elevation = 20.0;
    o.exaggeration = 1.0;
    o.width = 400;
    o.sky = sky;
    const char *path = ft_test_tmp(name);
    assert_int_equal(ft_render_perspective(g, path, &o), FT_OK);
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    return s;
}

static void test_png_size(void **state)
{
    ft_grid *g = plain(200.0);
    cairo_surface_t *s = render(g, "view.png", 1);
    int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
    assert_int_equal(w, 400);
    assert_true(h >= 140 && h <= 600);
    assert_int_equal(top_row(s, 0), 0); /* the sky is opaque */
    cairo_surface_destroy(s);
    assert_int_equal(ft_test_dir_count(), 1); /* no temporary file left */
    ft_grid_free(g);
}

static void test_peak_above_plain(void **state)
{
    ft_grid *flat = plain(0.0), *peak = plain(300.0);
    cairo_surface_t *a = render(flat, "flat.png", 0), *b = render(peak, "peak.png", 0);
    int w = cairo_image_surface_get_width(a);
    /* flat: the far edge is one horizontal line; peak: the summit rises above the far edge */
    int flat_mid = top_row(a, w / 2), flat_side = top_row(a, w / 2 - w / 8);
    assert_true(flat_mid >= 0 && abs(flat_mid - flat_side) <= 2);
    int peak_mid = top_row(b, w / 2), peak_side = top_row(b, w / 2 - w / 3);
    assert_true(peak_mid >= 0 && peak_side >= 0);
    assert_true(peak_mid + 10 < peak_side);
    cairo_surface_destroy(a);
    cairo_surface_destroy(b);
    ft_grid_free(flat);
    ft_grid_free(peak);
}

/* The bottom-most opaque row of column x (-1 if none). */
static int bottom_row(cairo_surface_t *s, int x)
{
    int h = cairo_image_surface_get_height(s), stride = cairo_image_surface_get_stride(s);
    const unsigned char *d = cairo_image_surface_get_data(s);
    for (int y = h - 1; y >= 0; y--)
        if (((const uint32_t *)(const void *)(d + (size_t)y * stride))[x] >> 24 > 128)
            return y;
    return -1;
}

static uint32_t alpha_at(cairo_surface_t *s, int x, int y)
{
    const unsigned char *d = cairo_image_surface_get_data(s);
    return ((const uint32_t *)(const void *)(d + (size_t)y * cairo_image_surface_get_stride(s)))[x] >> 24;
}

/* A hole of nodata in the middle of the plain shows the background. */
static void test_nodata(void **state)
{
    ft_grid *g = plain(0.0);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t r = N / 2 - 20; r < N / 2 + 20; r++)
        for (size_t c = N / 2 - 20; c < N / 2 + 20; c++)
            g->mask[r * N + c] = 0;
    cairo_surface_t *s = render(g, "hole.png", 0);
    int x = cairo_image_surface_get_width(s) / 2, top = top_row(s, x), bottom = bottom_row(s, x);
    assert_true(top >= 0 && bottom > top + 20);
    assert_true(alpha_at(s, x, (top + bottom) / 2) < 16);
    assert_true(alpha_at(s, x, top + 2) > 200 && alpha_at(s, x, bottom - 2) > 200);
    cairo_surface_destroy(s);
    memset(g->mask, 0, N * N);
    assert_int_equal(ft_render_perspective(g, ft_test_tmp("none.png"), NULL), FT_E_EMPTY);
    ft_grid_free(g);
}

static void test_bad_options(void **state)
{
    ft_grid *g = plain(10.0);
    const char *path = ft_test_tmp("bad.png");
    ft_perspective_opts o = FT_PERSPECTIVE_OPTS_DEFAULT;
    o.elevation = 2.0;
    assert_int_equal(ft_render_perspective(g, path, &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "elevation"));
    o = (ft_perspective_opts)FT_PERSPECTIVE_OPTS_DEFAULT;
    o.width = 10;
    assert_int_equal(ft_render_perspective(g, path, &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "width"));
    o = (ft_perspective_opts)FT_PERSPECTIVE_OPTS_DEFAULT;
    o.exaggeration = -1.0;
    assert_int_equal(ft_render_perspective(g, path, &o), FT_E_INVALID);
    o.exaggeration = NAN;
    assert_int_equal(ft_render_perspective(g, path, &o), FT_E_INVALID);
    assert_int_equal(ft_render_perspective(g, ft_test_tmp("bad.svg"), NULL), FT_E_INVALID);
    assert_int_equal(ft_render_perspective(g, ft_test_tmp("missing/x.png"), NULL), FT_E_IO);
    assert_int_equal(ft_render_perspective(NULL, path, NULL), FT_E_INVALID);
    ft_grid *one = ft_grid_create(1, 1);
    assert_int_equal(ft_render_perspective(one, path, NULL), FT_E_INVALID);
    ft_grid_free(one);
    assert_int_equal(ft_test_dir_count(), 0);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_png_size),
        cmocka_unit_test(test_peak_above_plain),
        cmocka_unit_test(test_nodata),
        cmocka_unit_test(test_bad_options),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
