/* fracterra — unit tests of surface/prism.c (Clarke's triangular prisms): a plane's surface over
 * planimetric area is sqrt(1 + a² + b²) at every square size (D = 2), squares with a nodata corner are
 * skipped, the automatic elevation scale, and bad options named in the error.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "fracterra/surface.h"

static ft_grid *plane(size_t n, double a, double b)
{
    ft_grid *g = ft_grid_create(n, n);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            g->z[i * n + j] = (float)(a * (double)j + b * (double)i);
    return g;
}

static void test_plane_area(void **state)
{
    (void)state;
    ft_grid *g = plane(65, 0.75, 0.5);
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    o.zscale = 1.0;
    o.max_size = 16;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_prism(g, &o, &r), 0);
    assert_string_equal(r->method, "prism");
    assert_int_equal(r->table->n, 5); /* 1, 2, 4, 8, 16 */
    for (size_t k = 0; k < r->table->n; k++) {
        double s = r->table->rows[k].scale;
        assert_true(fabs(r->table->rows[k].value - sqrt(1.0 + 0.5625 + 0.25)) < 1e-6);
        assert_true(fabs(r->table->rows[k].count - (64.0 / s) * (64.0 / s)) < 1e-9);
    }
    assert_true(fabs(r->D - 2.0) < 1e-6);
    ft_dim_result_free(r);
    /* a corner masked: the one square of side 1 touching it, and so on at each size, are skipped */
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    g->mask[0] = 0;
    assert_int_equal(ft_surface_dim_prism(g, &o, &r), 0);
    assert_true(fabs(r->table->rows[0].count - (64.0 * 64.0 - 1.0)) < 1e-9);
    assert_true(fabs(r->D - 2.0) < 1e-6);
    ft_dim_result_free(r);
    ft_grid_free(g);
}

/* A saw-tooth ridge z = |x mod 2 - 1| seen at square size 1 (steep) and 2 (flat): the area falls. */
static void test_roughness_lost_at_coarse_sizes(void **state)
{
    (void)state;
    size_t n = 33;
    ft_grid *g = ft_grid_create(n, n);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            g->z[i * n + j] = (float)(j % 2);
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    o.zscale = 1.0;
    o.max_size = 4;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_prism(g, &o, &r), 0);
    /* size 1: every square has corners 0, 1, 0, 1, centre 0.5: four triangles of area sqrt(1.25) / 4 ... */
    double tri = 0.5 * sqrt(0.25 * 1.0 + 1.0 * 0.25 + 0.0); /* |(1,0,1) x (0.5,0.5,0.5)| / 2 */
    double side = 0.5 * sqrt(0.25 + 0.0 + 0.25);            /* |(0,1,0) x (0.5,0.5,0.5)| / 2 */
    assert_true(fabs(r->table->rows[0].value - (2.0 * tri + 2.0 * side)) < 1e-6);
    assert_true(fabs(r->table->rows[1].value - 1.0) < 1e-9); /* size 2 sees a flat surface */
    assert_true(r->D > 2.0);
    ft_dim_result_free(r);
    ft_grid_free(g);
}

static void test_bad_options(void **state)
{
    (void)state;
    ft_grid *g = plane(40, 1.0, 0.0);
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    ft_dim_result *r = NULL;
    o.zscale = -1;
    assert_int_equal(ft_surface_dim_prism(g, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "zscale"));
    o = (ft_dyadic_opts)FT_DYADIC_OPTS_DEFAULT;
    o.max_size = 100;
    assert_int_equal(ft_surface_dim_prism(g, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "100"));
    o.max_size = 1;
    assert_int_equal(ft_surface_dim_prism(g, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "two powers of two"));
    assert_null(r);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_plane_area),
        cmocka_unit_test(test_roughness_lost_at_coarse_sizes),
        cmocka_unit_test(test_bad_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
