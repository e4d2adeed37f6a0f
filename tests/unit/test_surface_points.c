/* fracterra — unit tests of the scattered-point estimator (src/surface/points_*.c, Arakawa & Krotkov §2.4):
 * the grid and the exact O(N²) enumeration give bit-identical counters A, B, C on 20,000 irregular points,
 * and so do 1 and 2 threads and each pair screen (AVX-512 floats in two rows or one, AVX2 doubles, plain C),
 * also with a cell of hundreds of points; a plane gives D = 2 with both methods; hand-counted pairs on a small lattice;
 * lags below min_pairs are dropped and reported (and too few lags is a clear error); sample mode is
 * reproducible per seed, differs between seeds and agrees with all pairs within its standard error; the
 * noise model moves D back towards the noise-free value; bad input is refused with the value named.
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
#include "surface/points_internal.h"

static void expect_ok(int rc)
{
    if (rc != 0)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, 0);
}

/* About n irregular points (jittered cells, z interpolated) of an fft surface of dimension D. */
static ft_points *surface_points(double D, size_t side, double fraction, uint64_t seed, double noise_z)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = D;
    so.seed = seed;
    ft_grid *g = NULL;
    expect_ok(ft_terrain_synth(side, side, &so, &g));
    ft_grid_sample_opts go = FT_GRID_SAMPLE_OPTS_DEFAULT;
    go.fraction = fraction;
    go.jitter = 1;
    go.noise_z = noise_z;
    go.seed = seed;
    ft_points *p = NULL;
    expect_ok(ft_surface_points_from_grid(g, &go, &p));
    ft_grid_free(g);
    return p;
}

static ft_points_counters *counters(const ft_points *p, int exact)
{
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    o.exact = exact;
    ft_points_counters *c = NULL;
    expect_ok(ft_surface_points_counters(p, &o, &c));
    return c;
}

static void assert_same_counters(const ft_points_counters *a, const ft_points_counters *b)
{
    assert_int_equal(a->n, b->n);
    assert_true(a->eps == b->eps);
    for (size_t k = 0; k < a->n; k++) {
        const ft_points_lag *x = &a->lags[k], *y = &b->lags[k];
        assert_true(x->C == y->C);
        assert_memory_equal(&x->A, &y->A, sizeof x->A);
        assert_memory_equal(&x->B, &y->B, sizeof x->B);
        assert_memory_equal(&x->dist, &y->dist, sizeof x->dist);
        assert_int_equal(x->status, y->status);
    }
}

static void test_exact_equals_grid(void **state)
{
    (void)state;
    ft_points *p = surface_points(2.4, 632, 0.05, 3, 0.0);
    assert_in_range(p->n, 19900, 20100);
    ft_points_counters *g = counters(p, 0), *e = counters(p, 1);
    assert_string_equal(g->pairs, "grid");
    assert_string_equal(e->pairs, "exact");
    size_t total = 0;
    for (size_t k = 0; k < g->n; k++)
        total += (size_t)g->lags[k].C;
    assert_true(total > 100000);
    assert_same_counters(g, e);
    /* the same on one thread */
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    ft_points_counters *one = counters(p, 0);
    omp_set_num_threads(nt);
    assert_same_counters(g, one);
    ft_points_counters_free(one);
    /* the same through every pair screen this processor has: AVX2 doubles, plain C, AVX-512 floats with
     * 32-bit candidates */
    for (int isa = 1; isa <= 3; isa++) {
        pts_pairs_grid_isa(isa);
        ft_points_counters *s = counters(p, 0);
        pts_pairs_grid_isa(0);
        assert_same_counters(s, e);
        ft_points_counters_free(s);
    }
    ft_points_counters_free(g);
    ft_points_counters_free(e);
    /* far from the origin (projected coordinates: the float screen works relative to each cell), on the
     * first 6,000 points (a band) to keep the exact enumeration short */
    p->n = 6000;
    for (size_t i = 0; i < p->n; i++) {
        p->x[i] += 500000.25;
        p->y[i] += 5000000.125;
    }
    g = counters(p, 0);
    e = counters(p, 1);
    assert_same_counters(g, e);
    ft_points_counters_free(g);
    ft_points_counters_free(e);
    ft_points_free(p);
}

/* A dense cluster: `crowd` of 3,000 points within a 3 x 3 square, so that one cell holds hundreds of points
 * (the AVX-512 exact test gathers them instead of permuting a table; over 256 the two-row screen's 16-bit
 * candidates cannot index them): every screen == exact. */
static void clustered_equals_exact(size_t crowd)
{
    ft_points *p = ft_points_create(3000);
    uint64_t s = 12345;
    for (size_t i = 0; i < 3000; i++) {
        double u[3];
        for (int k = 0; k < 3; k++) {
            s = s * UINT64_C(6364136223846793005) + UINT64_C(1442695040888963407);
            u[k] = (double)(s >> 11) * 0x1p-53;
        }
        double x = i < crowd ? 100.0 + 3.0 * u[0] : 300.0 * u[0], y = i < crowd ? 100.0 + 3.0 * u[1] : 300.0 * u[1];
        expect_ok(ft_points_push(p, x, y, sin(x / 7.0) + cos(y / 5.0) + 0.1 * u[2]));
    }
    ft_points_counters *e = counters(p, 1);
    for (int isa = 0; isa <= 3; isa++) {
        pts_pairs_grid_isa(isa);
        ft_points_counters *g = counters(p, 0);
        pts_pairs_grid_isa(0);
        assert_same_counters(g, e);
        ft_points_counters_free(g);
    }
    assert_true(e->lags[0].C > (double)crowd);
    ft_points_counters_free(e);
    ft_points_free(p);
}

static void test_exact_equals_grid_clustered(void **state)
{
    (void)state;
    clustered_equals_exact(600);
    clustered_equals_exact(150);
}

/* A 4 x 4 lattice of unit spacing, z = column: lag 1 (eps 0.1) holds the 24 neighbour pairs, 12 of them
 * along rows with |dz| = 1; lag 2 the 16 pairs two apart, 8 along rows with |dz| = 2. */
static void test_hand_counted(void **state)
{
    (void)state;
    ft_points *p = ft_points_create(16);
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++)
            ft_points_push(p, c, r, c);
    const double lags[] = {1.0, 2.0};
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    o.lags = lags;
    o.nuser_lags = 2;
    o.eps = 0.1;
    o.min_pairs = 1;
    for (int exact = 0; exact < 2; exact++) {
        ft_points_counters *c = NULL;
        o.exact = exact;
        expect_ok(ft_surface_points_counters(p, &o, &c));
        assert_true(c->lags[0].C == 24.0 && c->lags[0].A == 12.0 && c->lags[0].B == 12.0);
        assert_true(c->lags[1].C == 16.0 && c->lags[1].A == 16.0 && c->lags[1].B == 32.0);
        assert_true(c->lags[0].dist == 1.0 && c->lags[1].dist == 2.0);
        assert_near(c->lags[0].value, 0.5, 1e-15);
        ft_points_counters_free(c);
    }
    ft_points_free(p);
}

static void test_plane(void **state)
{
    (void)state;
    ft_points *p = ft_points_create(5000);
    ft_rng *r = ft_rng_create(5, 0);
    for (int i = 0; i < 5000; i++) {
        double x = 100.0 * ft_rng_uniform(r), y = 100.0 * ft_rng_uniform(r);
        ft_points_push(p, x, y, 0.3 * x - 0.7 * y + 5.0);
    }
    ft_rng_free(r);
    for (int m = 0; m < 2; m++) {
        ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
        o.method = (ft_points_method)m;
        ft_dim_result *res = NULL;
        expect_ok(ft_surface_dim_points(p, &o, &res));
        assert_string_equal(res->method, m ? "pentland" : "yokoya");
        assert_near(res->D, 2.0, 0.02);
        assert_true(res->table->n >= 10);
        ft_dim_result_free(res);
    }
    ft_points_free(p);
}

static void test_min_pairs_drops(void **state)
{
    (void)state;
    ft_points *p = surface_points(2.5, 80, 0.05, 2, 0.0); /* 320 points */
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    ft_points_counters *c = NULL;
    o.min_pairs = 1;
    expect_ok(ft_surface_points_counters(p, &o, &c));
    double cmin = INFINITY, cmax = 0.0;
    for (size_t k = 0; k < c->n; k++) {
        cmin = fmin(cmin, c->lags[k].C);
        cmax = fmax(cmax, c->lags[k].C);
    }
    ft_points_counters_free(c);
    assert_true(cmin < cmax);
    /* a threshold between the smallest and the largest count drops some lags, keeps the others */
    o.min_pairs = (size_t)(0.5 * (cmin + cmax));
    o.counters = &c;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim_points(p, &o, &r);
    if (rc == 0) {
        size_t dropped = 0;
        for (size_t k = 0; k < c->n; k++) {
            int kept = c->lags[k].status == FT_LAG_KEPT;
            assert_int_equal(kept, c->lags[k].C >= (double)o.min_pairs);
            dropped += !kept;
        }
        assert_true(dropped > 0);
        assert_int_equal(r->table->n, c->kept);
        ft_dim_result_free(r);
        ft_points_counters_free(c);
    } else {
        assert_int_equal(rc, FT_E_EMPTY);
        assert_null(c);
    }
    /* a threshold above every count: a clear error that lists the dropped lags */
    o.min_pairs = (size_t)cmax + 1;
    o.counters = NULL;
    assert_int_equal(ft_surface_dim_points(p, &o, &r), FT_E_EMPTY);
    assert_null(r);
    assert_non_null(strstr(ft_last_error(), "too few lags"));
    assert_non_null(strstr(ft_last_error(), "dropped lags"));
    assert_non_null(strstr(ft_last_error(), "pairs)"));
    ft_points_free(p);
}

static double sample_D(const ft_points *p, size_t pairs, uint64_t seed, double *se)
{
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    ft_points_counters *c = NULL;
    ft_dim_result *r = NULL;
    o.sample = pairs;
    o.seed = seed;
    o.counters = &c;
    expect_ok(ft_surface_dim_points(p, &o, &r));
    assert_string_equal(c->pairs, "sample");
    for (size_t k = 0; k < c->n; k++)
        if (c->lags[k].status == FT_LAG_KEPT)
            assert_true(c->lags[k].value_se > 0.0);
    *se = c->D_sample_se;
    double D = r->D;
    ft_points_counters_free(c);
    ft_dim_result_free(r);
    return D;
}

static void test_sample_mode(void **state)
{
    (void)state;
    ft_points *p = surface_points(2.3, 632, 0.05, 4, 0.0);
    ft_dim_result *all = NULL;
    expect_ok(ft_surface_dim_points(p, NULL, &all));
    double se1, se2, se3;
    double d1 = sample_D(p, 400000, 7, &se1), d2 = sample_D(p, 400000, 7, &se2), d3 = sample_D(p, 400000, 8, &se3);
    assert_true(d1 == d2 && se1 == se2);
    assert_true(d1 != d3);
    assert_true(se1 > 0.0005 && se1 < 0.05);
    assert_near(d1, all->D, 4.0 * se1);
    assert_near(d3, all->D, 4.0 * se3);
    /* the same on one thread */
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    double d4 = sample_D(p, 400000, 7, &se2);
    omp_set_num_threads(nt);
    assert_true(d4 == d1);
    ft_dim_result_free(all);
    ft_points_free(p);
}

/* Noise N(0, 0.1²) on z of a smooth unit-sd surface flattens the small lags: without the noise model D
 * rises; the default path detects the noise, says so, and brings D back towards the noise-free estimate;
 * a given noise_sigma does too. */
static void noise_case(ft_points_method m, const ft_points *clean, const ft_points *noisy)
{
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    o.method = m;
    ft_dim_result *a = NULL, *b = NULL, *c = NULL, *d = NULL;
    expect_ok(ft_surface_dim_points(clean, &o, &a));
    expect_ok(ft_surface_dim_points(noisy, &o, &d));
    o.noise_mode = -1;
    expect_ok(ft_surface_dim_points(noisy, &o, &b));
    o.noise_sigma = 0.1;
    expect_ok(ft_surface_dim_points(noisy, &o, &c));
    print_message("%s clean %.4f noisy %.4f given sigma %.4f automatic %.4f (noise sd %.4g)\n",
                  ft_points_method_name(m), a->D, b->D, c->D, d->D, d->nugget.sigma_z);
    assert_true(b->D > a->D + 0.02);
    assert_true(fabs(c->D - a->D) < 0.5 * fabs(b->D - a->D));
    assert_true(fabs(d->D - a->D) < 0.5 * fabs(b->D - a->D));
    assert_true(d->nugget.applied);
    assert_non_null(ft_dim_result_find_warning(d, "noise detected"));
    assert_near(d->nugget.sigma_z, 0.1, 0.03);
    assert_null(ft_dim_result_find_warning(b, "noise"));
    ft_dim_result_free(a);
    ft_dim_result_free(b);
    ft_dim_result_free(c);
    ft_dim_result_free(d);
}

static void test_noise_model(void **state)
{
    (void)state;
    ft_points *clean = surface_points(2.2, 400, 0.05, 6, 0.0), *noisy = surface_points(2.2, 400, 0.05, 6, 0.1);
    noise_case(FT_POINTS_YOKOYA, clean, noisy);
    noise_case(FT_POINTS_PENTLAND, clean, noisy);
    ft_points_free(clean);
    ft_points_free(noisy);
}

static void expect_error(const ft_points *p, const ft_points_dim_opts *o, int code, const char *a, const char *b)
{
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_points(p, o, &r), code);
    assert_null(r);
    if (strstr(ft_last_error(), a) == NULL || strstr(ft_last_error(), b) == NULL)
        print_error("message '%s' lacks '%s' or '%s'\n", ft_last_error(), a, b);
    assert_non_null(strstr(ft_last_error(), a));
    assert_non_null(strstr(ft_last_error(), b));
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_points *p = ft_points_create(4);
    ft_points_push(p, 0, 0, 1);
    ft_points_push(p, 1, 0, 2);
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    expect_error(p, &o, FT_E_EMPTY, "at least 3 points", "got 2");
    ft_points_push(p, 0, 1, NAN);
    expect_error(p, &o, FT_E_NUMERIC, "point 3", "z = nan");
    p->z[2] = 3.0;
    o.eps = -1.0;
    expect_error(p, &o, FT_E_INVALID, "eps", "-1");
    o.eps = 0.0;
    o.min_pairs = 0;
    expect_error(p, &o, FT_E_INVALID, "min_pairs", "got 0");
    o.min_pairs = 1;
    const double lags[] = {0.5, 1.0, 0.5};
    o.lags = lags;
    o.nuser_lags = 3;
    expect_error(p, &o, FT_E_INVALID, "lag 0.5", "twice");
    o.nuser_lags = 2;
    o.eps = 0.7;
    expect_error(p, &o, FT_E_INVALID, "smallest lag (0.5)", "0.7");
    o.lags = NULL;
    o.eps = 0.0;
    o.noise_sigma = -2.0;
    expect_error(p, &o, FT_E_INVALID, "noise_sigma", "-2");
    o.noise_sigma = 0.0;
    o.exact = 1;
    o.sample = 10;
    expect_error(p, &o, FT_E_INVALID, "exact", "sample");
    ft_points_method m;
    assert_int_equal(ft_points_method_parse("lunar", &m), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "lunar"));
    /* all points at one position */
    ft_points *q = ft_points_create(3);
    for (int i = 0; i < 3; i++)
        ft_points_push(q, 1, 1, i);
    o = (ft_points_dim_opts)FT_POINTS_DIM_OPTS_DEFAULT;
    expect_error(q, &o, FT_E_INVALID, "same position", "3 points");
    ft_points_free(q);
    ft_points_free(p);
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_points(NULL, NULL, &r), FT_E_INVALID);
}

static void test_from_grid(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(20, 10);
    for (size_t i = 0; i < 200; i++)
        g->z[i] = (float)i;
    g->gt[0] = 100.0;
    g->gt[1] = 2.0;
    g->gt[3] = 50.0;
    g->gt[5] = -2.0;
    ft_grid_sample_opts o = FT_GRID_SAMPLE_OPTS_DEFAULT;
    o.fraction = 0.25;
    ft_points *p = NULL;
    expect_ok(ft_surface_points_from_grid(g, &o, &p));
    assert_int_equal(p->n, 50);
    for (size_t i = 0; i < p->n; i++) {
        /* the cell centre and the cell's value: z = 20 row + col */
        double col = (p->x[i] - 100.0) / 2.0 - 0.5, row = (50.0 - p->y[i]) / 2.0 - 0.5;
        assert_near(p->z[i], 20.0 * row + col, 1e-9);
    }
    ft_points_free(p);
    o.jitter = 1;
    expect_ok(ft_surface_points_from_grid(g, &o, &p));
    for (size_t i = 0; i < p->n; i++) {
        /* bilinear on a plane is exact away from the clamped border */
        double col = (p->x[i] - 100.0) / 2.0 - 0.5, row = (50.0 - p->y[i]) / 2.0 - 0.5;
        if (col > 0.0 && col < 19.0 && row > 0.0 && row < 9.0)
            assert_near(p->z[i], 20.0 * row + col, 1e-4);
    }
    ft_points_free(p);
    o.fraction = 1.5;
    assert_int_equal(ft_surface_points_from_grid(g, &o, &p), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "1.5"));
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_equals_grid), cmocka_unit_test(test_exact_equals_grid_clustered),
        cmocka_unit_test(test_hand_counted),
        cmocka_unit_test(test_plane),             cmocka_unit_test(test_min_pairs_drops),
        cmocka_unit_test(test_sample_mode),       cmocka_unit_test(test_noise_model),
        cmocka_unit_test(test_bad_input),         cmocka_unit_test(test_from_grid),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
