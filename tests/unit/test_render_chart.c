/* fracterra — unit tests of render/series_chart.c and of the map's view window (render/map.c): charts are
 * written as SVG, PNG and PDF, with a numeric or a category x axis and gaps, atomically; bad series, sizes and
 * windows are refused naming the value, and a failed write leaves nothing.
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
#include <unistd.h>

#include "fracterra/fracterra.h"
#include "ft_test_util.h"

static const double YEARS[4] = {1959.0, 1980.0, 1989.0, 1997.0};
static const double RES[4] = {1.3614, 1.3722, 1.4414, 1.4872};
static const double IND[4] = {1.5721, 1.5254, NAN, 1.5210}; /* a gap */

static void test_chart_formats(void **state)
{
    ft_series s[2] = {{"residential", YEARS, RES, 4}, {"industrial", YEARS, IND, 4}};
    ft_chart_opts o = FT_CHART_OPTS_DEFAULT;
    o.title = "D per class";
    o.xlabel = "year";
    o.ylabel = "D";
    assert_int_equal(ft_render_series_chart(s, 2, ft_test_tmp("c.svg"), &o), FT_OK);
    assert_int_equal(ft_render_series_chart(s, 2, ft_test_tmp("c.png"), NULL), FT_OK);
    assert_int_equal(ft_render_series_chart(s, 2, ft_test_tmp("c.PDF"), &o), FT_OK);
    char *svg = ft_test_read_svg(ft_test_tmp("c.svg"), NULL);
    free(svg);
    size_t size = 0;
    char *png = ft_test_read_file(ft_test_tmp("c.png"), &size);
    assert_true(png && size > 1000 && memcmp(png, "\x89PNG", 4) == 0);
    free(png);
    char *pdf = ft_test_read_file(ft_test_tmp("c.PDF"), NULL);
    assert_true(pdf && strncmp(pdf, "%PDF-", 5) == 0);
    free(pdf);
    assert_int_equal(ft_test_dir_count(), 3); /* no temporary left */
}

static void test_chart_categories(void **state)
{
    static const char *const labels[3] = {"early", "middle", "late"};
    const double x[3] = {0.0, 1.0, 2.0}, y[3] = {1.1, 1.2, 1.15};
    ft_series s = {NULL, x, y, 3}; /* unnamed: no legend */
    ft_chart_opts o = FT_CHART_OPTS_DEFAULT;
    o.xcategories = labels;
    o.ncategories = 3;
    assert_int_equal(ft_render_series_chart(&s, 1, ft_test_tmp("cat.svg"), &o), FT_OK);
    char *svg = ft_test_read_svg(ft_test_tmp("cat.svg"), NULL);
    free(svg);
    const double bad[3] = {0.0, 1.0, 3.0};
    s.x = bad;
    assert_int_equal(ft_render_series_chart(&s, 1, ft_test_tmp("bad.svg"), &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "x = 3"));
}

static void test_chart_errors(void **state)
{
    const double nan3[3] = {NAN, NAN, NAN};
    ft_series s = {"a", YEARS, nan3, 3};
    assert_int_equal(ft_render_series_chart(&s, 1, ft_test_tmp("e.svg"), NULL), FT_E_EMPTY);
    s.y = RES;
    assert_int_equal(ft_render_series_chart(NULL, 0, ft_test_tmp("e.svg"), NULL), FT_E_INVALID);
    assert_int_equal(ft_render_series_chart(&s, 1, ft_test_tmp("e.gif"), NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "e.gif"));
    ft_chart_opts o = FT_CHART_OPTS_DEFAULT;
    o.width = 50;
    assert_int_equal(ft_render_series_chart(&s, 1, ft_test_tmp("e.svg"), &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "50 x 540"));
    const double inf_x[2] = {1.0, INFINITY};
    ft_series t = {"b", inf_x, RES, 2};
    assert_int_equal(ft_render_series_chart(&t, 1, ft_test_tmp("e.svg"), NULL), FT_E_INVALID);
    assert_int_equal(ft_render_series_chart(&s, 1, ft_test_tmp("missing/e.png"), NULL), FT_E_IO);
    assert_int_equal(ft_test_dir_count(), 0);
}

/* A 10 x 10 square ring as a one-feature layer. */
static ft_layer *square_layer(void)
{
    ft_layer *l = ft_layer_create("sq", NULL);
    const double x[4] = {0, 10, 10, 0}, y[4] = {0, 0, 10, 10};
    assert_non_null(l);
    assert_true(ft_layer_add_feature(l, 1, FT_GEOM_POLYGON, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(x, y, 4, 1, 1), FT_ROLE_OUTER, 0), FT_OK);
    return l;
}

static void test_map_window(void **state)
{
    ft_layer *l = square_layer();
    ft_map_opts o = FT_MAP_OPTS_DEFAULT;
    const double w[4] = {8.0, 8.0, 12.0, 12.0}; /* a corner, zoomed */
    memcpy(o.window, w, sizeof w);
    assert_int_equal(ft_render_map(l, ft_test_tmp("zoom.svg"), &o), FT_OK);
    char *svg = ft_test_read_svg(ft_test_tmp("zoom.svg"), NULL);
    assert_non_null(strstr(svg, "clip"));
    free(svg);
    const double bad[4] = {5.0, 0.0, 5.0, 10.0};
    memcpy(o.window, bad, sizeof bad);
    assert_int_equal(ft_render_map(l, ft_test_tmp("bad.svg"), &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "window"));
    o.window[2] = NAN;
    assert_int_equal(ft_render_map(l, ft_test_tmp("bad.svg"), &o), FT_E_INVALID);
    assert_int_equal(ft_test_dir_count(), 1);
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_chart_formats),
        cmocka_unit_test(test_chart_categories),
        cmocka_unit_test(test_chart_errors),
        cmocka_unit_test(test_map_window),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
