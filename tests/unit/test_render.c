/* fracterra — tests/unit/test_render.c: hillshade (hand-checkable planes, nodata, options), grid images
 * and vector maps.
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
#include "ft_test_util.h"

#define N 7
#define CELL 10.0

/* An N x N north-up grid of 10 m cells with z = a * x + b * y (x east, y north, in metres). */
static ft_grid *plane(double a, double b)
{
    ft_grid *g = ft_grid_create(N, N);
    assert_non_null(g);
    double gt[6] = {1000.0, CELL, 0.0, 2000.0, 0.0, -CELL};
    memcpy(g->gt, gt, sizeof gt);
    for (size_t r = 0; r < N; r++)
        for (size_t c = 0; c < N; c++)
            g->z[r * N + c] = (float)(a * (c + 0.5) * CELL + b * -((double)r + 0.5) * CELL);
    return g;
}

static double shade_at_centre(const ft_grid *dem, const ft_hillshade_opts *o)
{
    ft_grid *hs = NULL;
    assert_int_equal(ft_render_hillshade(dem, o, &hs), FT_OK);
    assert_int_equal(hs->nx, dem->nx);
    assert_int_equal(hs->ny, dem->ny);
    assert_true(ft_grid_is_valid(hs, N / 2, N / 2));
    double v = hs->z[(N / 2) * N + N / 2];
    ft_grid_free(hs);
    return v;
}

static void test_flat_plane(void **state)
{
    ft_grid *g = plane(0.0, 0.0);
    ft_grid *hs = NULL;
    assert_int_equal(ft_render_hillshade(g, NULL, &hs), FT_OK);
    double expect = 255.0 * sin(45.0 * M_PI / 180.0); /* 180.31 */
    for (size_t r = 0; r < N; r++)
        for (size_t c = 0; c < N; c++) { /* the edges too: extrapolated, as gdaldem -compute_edges */
            assert_true(ft_grid_is_valid(hs, c, r));
            assert_true(fabs(hs->z[r * N + c] - expect) < 1e-3);
        }
    assert_true(fabs(expect - 180.31) < 0.01);
    ft_hillshade_opts o = FT_HILLSHADE_OPTS_DEFAULT;
    o.altitude = 90.0;
    assert_true(fabs(shade_at_centre(g, &o) - 255.0) < 1e-3);
    ft_grid_free(hs);
    ft_grid_free(g);
}

/* Light from the north-west (315): a slope facing north-west (falling towards it) is lit, the opposite
 * one (facing south-east) is in shade; the ordering follows cos(azimuth - aspect). */
static void test_slopes_towards_and_away_from_light(void **state)
{
    ft_grid *towards = plane(0.3, -0.3); /* rises to the east and south: faces north-west */
    ft_grid *away = plane(-0.3, 0.3);    /* faces south-east */
    ft_grid *side = plane(0.3, 0.3);     /* faces south-west: across the light */
    double t = shade_at_centre(towards, NULL), a = shade_at_centre(away, NULL), s = shade_at_centre(side, NULL);
    assert_true(t > 180.31);
    assert_true(a < 180.31);
    assert_true(t > s && s > a);
    /* exact: slope = atan(0.3 sqrt 2), facing the light: 255 cos(zenith - slope) */
    double slope = atan(0.3 * sqrt(2.0));
    assert_true(fabs(t - 255.0 * cos(M_PI / 4 - slope)) < 1e-3);
    /* on a plane the linear extrapolation beyond the edges is exact: the edges shade as the centre; the four
     * corners, whose window gdaldem clamps along the row, see half the east-west gradient */
    ft_grid *hs = NULL;
    assert_int_equal(ft_render_hillshade(towards, NULL, &hs), FT_OK);
    for (size_t r = 0; r < N; r++)
        for (size_t c = 0; c < N; c++) {
            int corner = (r == 0 || r == N - 1) && (c == 0 || c == N - 1);
            assert_true((fabs(hs->z[r * N + c] - t) < 1e-3) == !corner);
        }
    ft_grid *half = plane(0.15, -0.3);
    assert_true(fabs(hs->z[0] - shade_at_centre(half, NULL)) < 1e-3);
    ft_grid_free(half);
    ft_grid_free(hs);
    /* moving the light to the south-east swaps them */
    ft_hillshade_opts o = FT_HILLSHADE_OPTS_DEFAULT;
    o.azimuth = 135.0;
    assert_true(shade_at_centre(away, &o) > shade_at_centre(towards, &o));
    /* a steeper z_factor darkens the slope facing away */
    o = (ft_hillshade_opts)FT_HILLSHADE_OPTS_DEFAULT;
    o.z_factor = 3.0;
    assert_true(shade_at_centre(away, &o) < a);
    ft_grid_free(towards);
    ft_grid_free(away);
    ft_grid_free(side);
}

/* A south-up grid (positive gt[5]) of the same terrain shades the same. */
static void test_south_up_grid(void **state)
{
    ft_grid *g = plane(0.3, -0.3), *flipped = ft_grid_copy(g);
    assert_non_null(flipped);
    for (size_t r = 0; r < N; r++)
        memcpy(flipped->z + r * N, g->z + (N - 1 - r) * N, N * sizeof(float));
    flipped->gt[3] = g->gt[3] - N * CELL;
    flipped->gt[5] = CELL;
    assert_true(fabs(shade_at_centre(g, NULL) - shade_at_centre(flipped, NULL)) < 1e-3);
    ft_grid_free(g);
    ft_grid_free(flipped);
}

static void test_nodata_propagation(void **state)
{
    ft_grid *g = plane(0.1, 0.2);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    g->mask[3 * N + 3] = 0;
    ft_grid *hs = NULL;
    assert_int_equal(ft_render_hillshade(g, NULL, &hs), FT_OK);
    /* only the nodata cell is nodata: its neighbours take their own value in its place (gdaldem -compute_edges) */
    for (size_t r = 0; r < N; r++)
        for (size_t c = 0; c < N; c++)
            assert_int_equal(ft_grid_is_valid(hs, c, r), !(r == 3 && c == 3));
    /* its west neighbour's window has the centre's z where the nodata cell was: dz/dx drops by a quarter */
    ft_grid *whole = plane(0.1, 0.2), *full = NULL;
    assert_int_equal(ft_render_hillshade(whole, NULL, &full), FT_OK);
    ft_grid_free(whole);
    assert_true(fabs(hs->z[3 * N + 2] - full->z[3 * N + 2]) > 0.01);
    assert_true(fabs(hs->z[0] - full->z[0]) < 1e-6);
    ft_grid_free(full);
    assert_int_equal(hs->has_nodata, 1);
    for (int k = 0; k < 6; k++)
        assert_true(hs->gt[k] == g->gt[k]);
    ft_grid_free(hs);
    ft_grid_free(g);
}

static void test_crs_kept(void **state)
{
    ft_grid *g = plane(0.1, 0.1), *hs = NULL;
    assert_int_equal(ft_grid_set_crs(g, "PROJCRS[\"test\"]"), FT_OK);
    assert_int_equal(ft_render_hillshade(g, NULL, &hs), FT_OK);
    assert_non_null(hs->crs_wkt);
    assert_string_equal(hs->crs_wkt, "PROJCRS[\"test\"]");
    ft_grid_free(hs);
    ft_grid_free(g);
}

static void expect_bad_option(const ft_grid *g, ft_hillshade_opts o, const char *needle)
{
    ft_grid *hs = (ft_grid *)1;
    assert_int_equal(ft_render_hillshade(g, &o, &hs), FT_E_INVALID);
    assert_null(hs);
    if (strstr(ft_last_error(), needle) == NULL)
        fprintf(stderr, "message: %s\n", ft_last_error());
    assert_non_null(strstr(ft_last_error(), needle));
}

static void test_bad_options(void **state)
{
    ft_grid *g = plane(0.0, 0.0);
    const ft_hillshade_opts d = FT_HILLSHADE_OPTS_DEFAULT;
    ft_hillshade_opts o = d;
    o.altitude = 95.0;
    expect_bad_option(g, o, "95");
    o = d;
    o.altitude = -1.0;
    expect_bad_option(g, o, "altitude");
    o = d;
    o.azimuth = 400.0;
    expect_bad_option(g, o, "400");
    o = d;
    o.z_factor = 0.0;
    expect_bad_option(g, o, "z_factor");
    o = d;
    o.scale = NAN;
    expect_bad_option(g, o, "scale");
    ft_grid *tiny = ft_grid_create(1, 5);
    expect_bad_option(tiny, d, "1 x 5");
    ft_grid_free(tiny);
    ft_grid *hs = NULL;
    assert_int_equal(ft_render_hillshade(NULL, NULL, &hs), FT_E_INVALID);
    ft_grid_free(g);
}

/* ---- images and maps ---- */

static void test_grid_png(void **state)
{
    ft_grid *g = plane(0.3, -0.2), *hs = NULL;
    assert_int_equal(ft_render_hillshade(g, NULL, &hs), FT_OK);
    const char *p = ft_test_tmp("g.png");
    ft_grid_image_opts o = FT_GRID_IMAGE_OPTS_DEFAULT;
    o.width = 70;
    o.colormap = 1;
    o.shade = hs;
    assert_int_equal(ft_render_grid_png(g, p, &o), FT_OK);
    size_t size = 0;
    unsigned char *b = (unsigned char *)ft_test_read_file(p, &size);
    assert_non_null(b);
    assert_true(size > 33);
    assert_memory_equal(b, "\x89PNG\r\n\x1a\n", 8);
    assert_int_equal(b[19], 70); /* width, big-endian in IHDR */
    assert_int_equal(b[23], 70); /* square cells, square grid */
    free(b);
    assert_int_equal(ft_test_dir_count(), 1); /* no temporary left */
    ft_grid_free(hs);
    ft_grid_free(g);
}

static void test_grid_png_errors(void **state)
{
    ft_grid *g = plane(0.0, 0.0);
    const char *p = ft_test_tmp("bad.png");
    ft_grid_image_opts o = FT_GRID_IMAGE_OPTS_DEFAULT;
    o.colormap = 7;
    assert_int_equal(ft_render_grid_png(g, p, &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "7"));
    o.colormap = 0;
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    memset(g->mask, 0, N * N);
    assert_int_equal(ft_render_grid_png(g, p, &o), FT_E_EMPTY);
    memset(g->mask, 1, N * N);
    assert_int_equal(ft_render_grid_png(g, "/nonexistent/fracterra/x.png", &o), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "/nonexistent/fracterra/x.png"));
    assert_false(ft_test_exists(p));
    ft_grid_free(g);
}

static ft_layer *square_layer(void)
{
    ft_layer *l = ft_layer_create("square", "PROJCRS[\"test\"]");
    assert_non_null(l);
    assert_true(ft_layer_add_feature(l, 0, FT_GEOM_POLYGON, 0) >= 0);
    double x[] = {0, 1000, 1000, 0}, y[] = {0, 0, 1000, 1000};
    double hx[] = {400, 600, 600, 400}, hy[] = {400, 400, 600, 600};
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(x, y, 4, 1, 1), FT_ROLE_OUTER, 0), FT_OK);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(hx, hy, 4, 1, 1), FT_ROLE_INNER, 0), FT_OK);
    return l;
}

static void test_map_svg(void **state)
{
    ft_layer *l = square_layer();
    const char *p = ft_test_tmp("square.svg");
    ft_map_opts o = FT_MAP_OPTS_DEFAULT;
    o.title = "A square with a hole";
    assert_int_equal(ft_render_map(l, p, &o), FT_OK);
    char *s = ft_test_read_svg(p, NULL);
    assert_non_null(strstr(s, "width=\"800"));
    assert_non_null(strstr(s, "evenodd"));
    free(s);
    ft_layer_free(l);
}

static void test_map_png_and_pdf(void **state)
{
    ft_layer *l = square_layer();
    const char *png = ft_test_tmp("square.PNG"), *pdf = ft_test_tmp("square.pdf");
    assert_int_equal(ft_render_map(l, png, NULL), FT_OK);
    assert_int_equal(ft_render_map(l, pdf, NULL), FT_OK);
    char *b = ft_test_read_file(png, NULL);
    assert_memory_equal(b, "\x89PNG", 4);
    free(b);
    b = ft_test_read_file(pdf, NULL);
    assert_memory_equal(b, "%PDF", 4);
    free(b);
    assert_int_equal(ft_test_dir_count(), 2);
    ft_layer_free(l);
}

static void test_map_errors(void **state)
{
    ft_layer *l = square_layer(), *empty = ft_layer_create("empty", NULL);
    const char *p = ft_test_tmp("m.svg"), *jpg = ft_test_tmp("m.jpg");
    assert_int_equal(ft_render_map(l, jpg, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "m.jpg"));
    ft_map_opts o = FT_MAP_OPTS_DEFAULT;
    o.stroke = "blue";
    assert_int_equal(ft_render_map(l, p, &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "blue"));
    assert_int_equal(ft_render_map(empty, p, NULL), FT_E_EMPTY);
    l->parts[0].chain->x[2] = NAN;
    assert_int_equal(ft_render_map(l, p, NULL), FT_E_NUMERIC);
    l->parts[0].chain->x[2] = 1000.0;
    assert_int_equal(ft_render_map(l, "/nonexistent/fracterra/m.svg", NULL), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "/nonexistent/fracterra/m.svg"));
    assert_int_equal(ft_test_dir_count(), 0);
    ft_layer_free(empty);
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flat_plane),
        cmocka_unit_test(test_slopes_towards_and_away_from_light),
        cmocka_unit_test(test_south_up_grid),
        cmocka_unit_test(test_nodata_propagation),
        cmocka_unit_test(test_crs_kept),
        cmocka_unit_test(test_bad_options),
        FT_TEST_OWN_DIR(test_grid_png),
        FT_TEST_OWN_DIR(test_grid_png_errors),
        FT_TEST_OWN_DIR(test_map_svg),
        FT_TEST_OWN_DIR(test_map_png_and_pdf),
        FT_TEST_OWN_DIR(test_map_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
