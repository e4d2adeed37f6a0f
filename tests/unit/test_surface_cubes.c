/* fracterra — unit tests of surface/cubes.c: a flat grid meets one cube per block (D = 2), a ramp rising
 * one cube side per block meets two, blocks touching nodata are skipped without bending the count, the
 * automatic elevation scale, a block's column between its corners only, and bad options.
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

static void test_flat_and_ramp(void **state)
{
    (void)state;
    size_t n = 65;
    ft_grid *g = ft_grid_create(n, n);
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    o.max_size = 16;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_cubes(g, &o, &r), 0); /* flat: one cube per block */
    assert_string_equal(r->method, "cubes");
    for (size_t k = 0; k < r->table->n; k++) {
        double s = r->table->rows[k].scale;
        assert_true(fabs(r->table->rows[k].value - 64.0 * 64.0 / (s * s)) < 1e-6);
    }
    assert_true(fabs(r->D - 2.0) < 1e-9);
    ft_dim_result_free(r);
    /* z = x (+0.5 so no cell sits on a cube face): a block of side s spans s vertically, two cubes */
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            g->z[i * n + j] = (float)j + 0.5f;
    o.zscale = 1.0;
    assert_int_equal(ft_surface_dim_cubes(g, &o, &r), 0);
    for (size_t k = 0; k < r->table->n; k++) {
        double s = r->table->rows[k].scale;
        assert_true(fabs(r->table->rows[k].value - 2.0 * 64.0 * 64.0 / (s * s)) < 1e-6);
    }
    assert_true(fabs(r->D - 2.0) < 1e-9);
    ft_dim_result_free(r);
    /* a nodata cell: the blocks holding it are skipped, the count per block is unchanged */
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    g->mask[10 * n + 10] = 0;
    assert_int_equal(ft_surface_dim_cubes(g, &o, &r), 0);
    assert_true(fabs(r->table->rows[0].count - (64.0 * 64.0 - 4.0)) < 1e-9);
    assert_true(fabs(r->table->rows[0].value - 2.0 * 64.0 * 64.0) < 1e-6);
    ft_dim_result_free(r);
    ft_grid_free(g);
}

/* The column of a block runs between its lowest and highest corner (the surface at the cubes'
 * resolution): a spike at an odd row and column is a corner of the blocks of side 1 only. */
static void test_corners(void **state)
{
    (void)state;
    size_t n = 65;
    ft_grid *g = ft_grid_create(n, n);
    g->z[33 * n + 33] = 100.0f;
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    o.max_size = 16;
    o.fit_whole_range = 1;
    o.zscale = 1.0;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_cubes(g, &o, &r), 0);
    assert_true(fabs(r->table->rows[0].scale - 1.0) < 1e-12);
    /* s = 1: the 4 blocks with the spike at a corner meet floor(100) + 1 cubes, the others 1 */
    assert_true(fabs(r->table->rows[0].value - (64.0 * 64.0 + 4.0 * 100.0)) < 1e-6);
    for (size_t k = 1; k < r->table->n; k++) {
        double s = r->table->rows[k].scale;
        assert_true(fabs(r->table->rows[k].value - 64.0 * 64.0 / (s * s)) < 1e-6);
    }
    ft_dim_result_free(r);
    ft_grid_free(g);
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(2, 50);
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_cubes(g, NULL, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "2x50"));
    ft_grid_free(g);
    g = ft_grid_create(50, 50);
    ft_dyadic_opts o = FT_DYADIC_OPTS_DEFAULT;
    o.min_size = -4;
    assert_int_equal(ft_surface_dim_cubes(g, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "-4"));
    assert_null(r);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flat_and_ramp),
        cmocka_unit_test(test_corners),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
