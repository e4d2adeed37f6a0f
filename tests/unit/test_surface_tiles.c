/* fracterra — tests of the surface estimators on stripes (docs/tiling.md): the exhaustive lag estimators
 * accumulated stripe by stripe (ft_surface_lag_stripes_*) give the whole grid's D and table bit for bit for any
 * stripe height, and a local D map computed on stripes whose first row is a multiple of the step holds the
 * whole map's cells across the stripe seams.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/surface.h"
#include "fracterra/terrain.h"

/* An fBm surface of D = 2.4 with oblong cells and nodata holes (so that masks cross the seams). */
static ft_grid *holed_surface(size_t nx, size_t ny)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = 2.4;
    so.seed = 7;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(nx, ny, &so, &g), FT_OK);
    g->gt[1] = 10.0;
    g->gt[5] = -7.0;
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t i = 0; i < ny; i++)
        for (size_t j = 0; j < nx; j++)
            if (hypot((double)j - 0.3 * (double)nx, (double)i - 0.5 * (double)ny) < 9.0 || (i * nx + j) % 89 == 0) {
                g->mask[i * nx + j] = 0;
                g->z[i * nx + j] = NAN;
            }
    return g;
}

/* Rows [r0, r1) of g as a stripe of its own (cells, mask and georeferencing). */
static ft_grid *stripe_of(const ft_grid *g, size_t r0, size_t r1)
{
    ft_grid *s = ft_grid_create(g->nx, r1 - r0);
    assert_non_null(s);
    memcpy(s->z, g->z + r0 * g->nx, g->nx * (r1 - r0) * sizeof *s->z);
    if (g->mask != NULL) {
        assert_int_equal(ft_grid_ensure_mask(s), FT_OK);
        memcpy(s->mask, g->mask + r0 * g->nx, g->nx * (r1 - r0));
    }
    memcpy(s->gt, g->gt, sizeof s->gt);
    s->gt[3] = g->gt[3] + (double)r0 * g->gt[5];
    return s;
}

/* D of g by stripes of h rows, as one process would add them. */
static ft_dim_result *by_stripes(const ft_grid *g, ft_surface_method m, const ft_surface_dim_opts *o, size_t h)
{
    ft_lag_stripes *ls = NULL;
    assert_int_equal(ft_surface_lag_stripes_create(g, m, o, &ls), FT_OK);
    size_t halo = ft_surface_lag_stripes_halo(ls), ns = ft_surface_lag_stripes_nsums(ls);
    assert_true(halo >= 1 && ns >= 8);
    double *sums = malloc(h * ns * sizeof *sums);
    assert_non_null(sums);
    for (size_t r0 = 0; r0 < g->ny; r0 += h) {
        size_t r1 = r0 + h < g->ny ? r0 + h : g->ny, hi = r1 + halo < g->ny ? r1 + halo : g->ny;
        ft_grid *s = stripe_of(g, r0, hi);
        assert_int_equal(ft_surface_lag_stripes_rows(ls, s, r0, r0, r1, sums), FT_OK);
        assert_int_equal(ft_surface_lag_stripes_add(ls, r0, r1, sums), FT_OK);
        ft_grid_free(s);
    }
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_lag_stripes_fit(ls, &r), FT_OK);
    free(sums);
    ft_surface_lag_stripes_free(ls);
    return r;
}

/* ft_rows_fn over a grid in memory; counts the windows asked for. */
typedef struct {
    const ft_grid *g;
    size_t reads;
} mem_rows;

static int read_mem_rows(void *arg, size_t row0, size_t nrows, ft_grid **out)
{
    mem_rows *m = arg;
    assert_true(nrows >= 1 && row0 + nrows <= m->g->ny);
    *out = stripe_of(m->g, row0, row0 + nrows);
    m->reads++;
    return FT_OK;
}

/* D of g by stripes of h rows through ft_surface_lag_stripes_rows_read with the lags up to near from the
 * stripe's own window; *reads: the windows read. */
static ft_dim_result *by_rolling(const ft_grid *g, const ft_surface_dim_opts *o, size_t h, size_t near, size_t *reads)
{
    ft_lag_stripes *ls = NULL;
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_VARIOGRAM, o, &ls), FT_OK);
    size_t ns = ft_surface_lag_stripes_nsums(ls);
    double *sums = malloc(h * ns * sizeof *sums);
    assert_non_null(sums);
    mem_rows m = {g, 0};
    for (size_t r0 = 0; r0 < g->ny; r0 += h) {
        size_t r1 = r0 + h < g->ny ? r0 + h : g->ny;
        assert_int_equal(ft_surface_lag_stripes_rows_read(ls, read_mem_rows, &m, r0, r1, near, sums), FT_OK);
        assert_int_equal(ft_surface_lag_stripes_add(ls, r0, r1, sums), FT_OK);
    }
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_lag_stripes_fit(ls, &r), FT_OK);
    free(sums);
    ft_surface_lag_stripes_free(ls);
    *reads = m.reads;
    return r;
}

static void assert_same_result(const ft_dim_result *a, const ft_dim_result *b)
{
    assert_memory_equal(&a->D, &b->D, sizeof a->D); /* the same bits, not only the same value */
    assert_memory_equal(&a->r2, &b->r2, sizeof a->r2);
    assert_int_equal(a->table->n, b->table->n);
    for (size_t i = 0; i < a->table->n; i++) {
        assert_memory_equal(&a->table->rows[i].scale, &b->table->rows[i].scale, sizeof(double));
        assert_memory_equal(&a->table->rows[i].value, &b->table->rows[i].value, sizeof(double));
        assert_memory_equal(&a->table->rows[i].count, &b->table->rows[i].count, sizeof(double));
    }
}

static void test_lag_stripes_equal_whole(void **state)
{
    (void)state;
    ft_grid *g = holed_surface(97, 131);
    const ft_surface_method ms[3] = {FT_SURFACE_VARIOGRAM, FT_SURFACE_YOKOYA, FT_SURFACE_PENTLAND};
    const size_t heights[4] = {1, 7, 64, 131};
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    for (int k = 0; k < 3; k++) {
        ft_dim_result *whole = NULL;
        assert_int_equal(ft_surface_dim(g, ms[k], &o, &whole), FT_OK);
        assert_true(whole->D > 2.2 && whole->D < 2.6); /* an fBm of D = 2.4: the estimate means something */
        for (int h = 0; h < 4; h++) {
            ft_dim_result *r = by_stripes(g, ms[k], &o, heights[h]);
            assert_same_result(whole, r);
            ft_dim_result_free(r);
        }
        ft_dim_result_free(whole);
    }
    /* a given lag range (longest lag 20 cells: a deep halo) */
    o.min_scale = 10.0;
    o.max_scale = 190.0;
    o.fit_whole_range = 1;
    ft_dim_result *whole = NULL, *r = NULL;
    assert_int_equal(ft_surface_dim(g, FT_SURFACE_VARIOGRAM, &o, &whole), FT_OK);
    r = by_stripes(g, FT_SURFACE_VARIOGRAM, &o, 5);
    assert_same_result(whole, r);
    ft_dim_result_free(r);
    ft_dim_result_free(whole);
    ft_grid_free(g);
}

/* The lags beyond `near` read from their partner rows: the same bits as the whole grid, and one more read
 * per stripe and longer lag. */
static void test_lag_stripes_rolling_equal_whole(void **state)
{
    (void)state;
    ft_grid *g = holed_surface(97, 131);
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.min_scale = 10.0;
    o.max_scale = 280.0; /* lags up to 40 cells (the cells are 7 ground units tall) */
    o.fit_whole_range = 1;
    ft_dim_result *whole = NULL;
    assert_int_equal(ft_surface_dim(g, FT_SURFACE_VARIOGRAM, &o, &whole), FT_OK);
    const size_t heights[3] = {1, 9, 64}, nears[3] = {0, 5, 1000};
    for (int h = 0; h < 3; h++)
        for (int n = 0; n < 3; n++) {
            size_t reads = 0;
            ft_dim_result *r = by_rolling(g, &o, heights[h], nears[n], &reads);
            assert_same_result(whole, r);
            size_t stripes = (g->ny + heights[h] - 1) / heights[h];
            if (nears[n] >= 1000)
                assert_int_equal(reads, stripes); /* every lag from the stripe's window */
            else
                assert_true(reads > stripes);
            ft_dim_result_free(r);
        }
    ft_dim_result_free(whole);
    ft_grid_free(g);
}

/* The running totals handed from one accumulator to another (what MPI ranks do) give the same D. */
static void test_lag_stripes_handover(void **state)
{
    (void)state;
    ft_grid *g = holed_surface(80, 90);
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    ft_dim_result *whole = NULL;
    assert_int_equal(ft_surface_dim(g, FT_SURFACE_VARIOGRAM, &o, &whole), FT_OK);
    ft_lag_stripes *first = NULL, *second = NULL;
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_VARIOGRAM, &o, &first), FT_OK);
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_VARIOGRAM, &o, &second), FT_OK);
    size_t ns = ft_surface_lag_stripes_nsums(first), split = 41;
    double *sums = malloc(g->ny * ns * sizeof *sums), *state_buf = malloc(ns * sizeof *state_buf);
    assert_int_equal(ft_surface_lag_stripes_rows(first, g, 0, 0, split, sums), FT_OK);
    assert_int_equal(ft_surface_lag_stripes_rows(second, g, 0, split, g->ny, sums + split * ns), FT_OK);
    assert_int_equal(ft_surface_lag_stripes_add(first, 0, split, sums), FT_OK);
    assert_int_equal(ft_surface_lag_stripes_state(first, state_buf), split);
    assert_int_equal(ft_surface_lag_stripes_resume(second, state_buf, split), FT_OK);
    assert_int_equal(ft_surface_lag_stripes_add(second, split, g->ny, sums + split * ns), FT_OK);
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_lag_stripes_fit(second, &r), FT_OK);
    assert_same_result(whole, r);
    ft_dim_result_free(r);
    ft_dim_result_free(whole);
    free(sums);
    free(state_buf);
    ft_surface_lag_stripes_free(first);
    ft_surface_lag_stripes_free(second);
    ft_grid_free(g);
}

static void test_lag_stripes_refusals(void **state)
{
    (void)state;
    ft_grid *g = holed_surface(64, 64);
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    ft_lag_stripes *ls = NULL;
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_SPECTRUM, &o, &ls), FT_E_UNSUPPORTED);
    assert_non_null(strstr(ft_last_error(), "spectrum cannot be measured stripe by stripe"));
    o.pairs = 1000;
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_VARIOGRAM, &o, &ls), FT_E_UNSUPPORTED);
    assert_non_null(strstr(ft_last_error(), "random pairs"));
    o.pairs = 0;
    o.max_scale = 1e6; /* a lag longer than the grid: the whole run's own error */
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_VARIOGRAM, &o, &ls), FT_E_INVALID);
    assert_null(ls);
    o.max_scale = 0.0;
    assert_int_equal(ft_surface_lag_stripes_create(g, FT_SURFACE_VARIOGRAM, &o, &ls), FT_OK);
    size_t ns = ft_surface_lag_stripes_nsums(ls);
    double *sums = malloc(64 * ns * sizeof *sums);
    /* a stripe without its halo */
    ft_grid *s = stripe_of(g, 0, 20);
    assert_int_equal(ft_surface_lag_stripes_rows(ls, s, 0, 0, 20, sums), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "must be 64 cells wide and hold rows 0-"));
    ft_grid_free(s);
    /* rows out of order, and a fit before every row came */
    assert_int_equal(ft_surface_lag_stripes_rows(ls, g, 0, 10, 20, sums), FT_OK);
    assert_int_equal(ft_surface_lag_stripes_add(ls, 10, 20, sums), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "row order"));
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_lag_stripes_fit(ls, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "never added"));
    free(sums);
    ft_surface_lag_stripes_free(ls);
    ft_surface_lag_stripes_free(NULL);
    ft_grid_free(g);
}

/* A D map on stripes starting at multiples of the step, their windows' rows pasted together, is the whole
 * map, cell for cell, for the block-sum path (variogram) and the per-window path (prism). */
static void test_dim_map_stripes_equal_whole(void **state)
{
    (void)state;
    ft_grid *g = holed_surface(120, 150);
    const ft_surface_method ms[2] = {FT_SURFACE_VARIOGRAM, FT_SURFACE_PRISM};
    size_t w = 24, step = 6;
    for (int k = 0; k < 2; k++) {
        ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
        o.fit_whole_range = 1;
        o.min_valid = 0.9; /* windows over the hole are nodata */
        ft_grid *D = NULL, *r2 = NULL;
        assert_int_equal(ft_surface_dim_map(g, w, step, ms[k], &o, &D, &r2), FT_OK);
        size_t per = 4, measured = 0; /* lattice rows per stripe: stripes of 4 x 6 + 18 = 42 rows */
        for (size_t a = 0; a < D->ny; a += per) {
            size_t b = a + per < D->ny ? a + per : D->ny;
            ft_grid *s = stripe_of(g, a * step, (b - 1) * step + w), *Ds = NULL, *r2s = NULL;
            assert_int_equal(ft_surface_dim_map(s, w, step, ms[k], &o, &Ds, &r2s), FT_OK);
            assert_int_equal(Ds->nx, D->nx);
            assert_int_equal(Ds->ny, b - a);
            assert_true(Ds->gt[3] == g->gt[3] + (double)(a * step) * g->gt[5] + 0.5 * (double)(w - step) * g->gt[5]);
            for (size_t i = 0; i < (b - a) * D->nx; i++) {
                size_t at = a * D->nx + i;
                assert_int_equal(Ds->mask[i], D->mask[at]);
                if (D->mask[at]) {
                    assert_memory_equal(&Ds->z[i], &D->z[at], sizeof(float));
                    assert_memory_equal(&r2s->z[i], &r2->z[at], sizeof(float));
                    measured++;
                }
            }
            ft_grid_free(s);
            ft_grid_free(Ds);
            ft_grid_free(r2s);
        }
        assert_true(measured > D->nx * D->ny / 2); /* most windows measured: the comparison is not empty */
        assert_true(measured < D->nx * D->ny);     /* and the hole made some nodata */
        ft_grid_free(D);
        ft_grid_free(r2);
    }
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lag_stripes_equal_whole),
        cmocka_unit_test(test_lag_stripes_rolling_equal_whole),
        cmocka_unit_test(test_lag_stripes_handover),
        cmocka_unit_test(test_lag_stripes_refusals),
        cmocka_unit_test(test_dim_map_stripes_equal_whole),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
