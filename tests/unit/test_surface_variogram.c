/* fracterra — unit tests of surface/variogram.c: a tilted plane has D = 2, nodata cells are skipped
 * (a NaN blob or a masked blob leaves D within 0.02), random-pair mode is reproducible per seed and close
 * to the exhaustive estimate, ground-unit lags, thread-count independence and bad input.
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

static ft_dim_result *run(const ft_grid *g, size_t pairs, uint64_t seed)
{
    ft_variogram_opts v = FT_VARIOGRAM_OPTS_DEFAULT;
    v.pairs = pairs;
    v.seed = seed;
    v.min_lag = 1;
    v.max_lag = 32;
    v.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim_variogram(g, &v, &r);
    if (rc != 0)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, 0);
    assert_string_equal(r->method, "variogram");
    return r;
}

static void test_tilted_plane(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(300, 200);
    for (size_t i = 0; i < 200; i++)
        for (size_t j = 0; j < 300; j++)
            g->z[i * 300 + j] = (float)(0.3 * (double)j - 0.7 * (double)i + 100.0);
    ft_dim_result *r = run(g, 0, 1);
    assert_near(r->D, 2.0, 0.02);
    ft_dim_result_free(r);
    r = run(g, 32000, 1);
    assert_near(r->D, 2.0, 0.02);
    ft_dim_result_free(r);
    /* default options: automatic lags and segmentation */
    assert_int_equal(ft_surface_dim_variogram(g, NULL, &r), 0);
    assert_near(r->D, 2.0, 0.02);
    ft_dim_result_free(r);
    ft_grid_free(g);
}

static ft_grid *surface(double D)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = FT_SYNTH_EXACT;
    o.dim = D;
    o.seed = 11;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(256, 256, &o, &g), 0);
    return g;
}

/* A blob of about 10% of the cells, as NaN or as masked cells with garbage values. */
static void test_nodata_skipped(void **state)
{
    (void)state;
    ft_grid *g = surface(2.5);
    ft_dim_result *ref = run(g, 0, 1);
    ft_grid *nan_g = ft_grid_copy(g), *mask_g = ft_grid_copy(g);
    assert_int_equal(ft_grid_ensure_mask(mask_g), 0);
    size_t holes = 0;
    for (size_t i = 0; i < 256; i++)
        for (size_t j = 0; j < 256; j++)
            if (hypot((double)i - 90.0, (double)j - 150.0) < 46.0) {
                nan_g->z[i * 256 + j] = NAN;
                mask_g->z[i * 256 + j] = -9999.0f;
                mask_g->mask[i * 256 + j] = 0;
                holes++;
            }
    assert_true(holes > 6000 && holes < 7500);
    ft_dim_result *a = run(nan_g, 0, 1), *b = run(mask_g, 0, 1);
    assert_near(a->D, ref->D, 0.02);
    assert_near(b->D, ref->D, 0.02);
    assert_true(a->D == b->D);
    ft_dim_result *c = run(mask_g, 32000, 3);
    assert_true(isfinite(c->D));
    assert_near(c->D, ref->D, 0.05);
    ft_dim_result_free(ref);
    ft_dim_result_free(a);
    ft_dim_result_free(b);
    ft_dim_result_free(c);
    ft_grid_free(nan_g);
    ft_grid_free(mask_g);
    ft_grid_free(g);
}

static void test_random_pairs_reproducible(void **state)
{
    (void)state;
    ft_grid *g = surface(2.4);
    ft_dim_result *a = run(g, 5000, 42), *b = run(g, 5000, 42), *c = run(g, 5000, 43), *e = run(g, 0, 1);
    assert_int_equal(a->table->n, b->table->n);
    assert_memory_equal(a->table->rows, b->table->rows, a->table->n * sizeof a->table->rows[0]);
    assert_true(a->D == b->D);
    assert_true(a->D != c->D);
    assert_near(a->D, e->D, 0.05);
    /* same answer on one thread */
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    ft_dim_result *d = run(g, 5000, 42), *f = run(g, 0, 1);
    omp_set_num_threads(nt);
    assert_memory_equal(a->table->rows, d->table->rows, a->table->n * sizeof a->table->rows[0]);
    assert_memory_equal(e->table->rows, f->table->rows, e->table->n * sizeof e->table->rows[0]);
    ft_dim_result_free(a);
    ft_dim_result_free(b);
    ft_dim_result_free(c);
    ft_dim_result_free(d);
    ft_dim_result_free(e);
    ft_dim_result_free(f);
    ft_grid_free(g);
}

/* Lags are in ground units: a 30 m grid has scales 30, 60, ... and the same D. */
static void test_ground_units(void **state)
{
    (void)state;
    ft_grid *g = surface(2.6);
    ft_dim_result *a = run(g, 0, 1);
    g->gt[1] = 30.0;
    g->gt[5] = -30.0;
    ft_dim_result *b = run(g, 0, 1);
    assert_near(b->table->rows[0].scale, 30.0, 1e-9);
    assert_near(b->range[1], 960.0, 1e-6);
    assert_near(a->D, b->D, 1e-9);
    ft_dim_result_free(a);
    ft_dim_result_free(b);
    ft_grid_free(g);
}

/* Lags longer than the grid's width but within its height (a 61 x 87 grid, lags up to 70 cells): only
 * column pairs reach them; rows contribute nothing at any lag instead of a negative count (this read far
 * past the rows before). A tilted plane still gives D = 2. */
static void test_lags_beyond_the_short_side(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(61, 87);
    for (size_t i = 0; i < 87; i++)
        for (size_t j = 0; j < 61; j++)
            g->z[i * 61 + j] = (float)(0.3 * (double)j - 0.7 * (double)i + 100.0);
    ft_variogram_opts v = FT_VARIOGRAM_OPTS_DEFAULT;
    v.min_lag = 2;
    v.max_lag = 70;
    v.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_variogram(g, &v, &r), 0);
    assert_near(r->D, 2.0, 0.02);
    ft_dim_result_free(r);
    ft_grid_free(g);
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_dim_result *r = (ft_dim_result *)1;
    assert_int_equal(ft_surface_dim_variogram(NULL, NULL, &r), FT_E_INVALID);
    assert_null(r);
    ft_grid *g = ft_grid_create(64, 64);
    ft_variogram_opts v = FT_VARIOGRAM_OPTS_DEFAULT;
    assert_int_equal(ft_surface_dim_variogram(g, &v, &r), FT_E_EMPTY); /* flat */
    v.min_lag = -2;
    assert_int_equal(ft_surface_dim_variogram(g, &v, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "-2"));
    v = (ft_variogram_opts)FT_VARIOGRAM_OPTS_DEFAULT;
    v.max_lag = 500;
    assert_int_equal(ft_surface_dim_variogram(g, &v, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "500"));
    v.max_lag = 1;
    assert_int_equal(ft_surface_dim_variogram(g, &v, &r), FT_E_INVALID);
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    memset(g->mask, 0, 64 * 64);
    assert_int_equal(ft_surface_dim_variogram(g, NULL, &r), FT_E_EMPTY); /* nodata only */
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tilted_plane),
        cmocka_unit_test(test_nodata_skipped),
        cmocka_unit_test(test_random_pairs_reproducible),
        cmocka_unit_test(test_ground_units),
        cmocka_unit_test(test_lags_beyond_the_short_side),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
