/* fracterra — tests/unit/test_terrain_clarke.c: Clarke's scale-based model (Clarke 1987, z = T + cF + H).
 *
 * The synthetic DEM is a plane + three plane waves of known wavelength and amplitude + a fractional
 * Brownian surface of D = 2.3 (ft_terrain_synth, fft method, 512 x 512 cells of 10 m), for several seeds:
 *  - fit: trend coefficients within 1 %, exactly those three significant harmonics at the right
 *    wavelengths, D within 0.1;
 *  - simulate from that model: mean and standard deviation within 2 % of the original, the same
 *    significant harmonics, and D measured (by fitting the simulated grid) within 0.1 of the model's;
 *  - bad input: all-nodata grid, 1 x 1 grid, cutoff out of range, bad simulation options.
 * The waves are cosines even about the grid's centre, so that they are orthogonal to the plane.
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

#define N 512
#define CELL 10.0
#define X0 (-2560.0) /* the grid centred on the map origin: beta0 is the centre's elevation */
#define Y0 2560.0
#define BETA1 0.2
#define BETA2 (-0.12)
#define Z_CENTRE 800.0
#define FBM_SIGMA 2.0
#define FBM_D 2.3

typedef struct {
    int k, l;
    double amplitude;
} wave;

/* Three waves (k cycles across the columns, l down the rows). */
static const wave waves[3] = {{3, 1, 30.0}, {1, -4, 20.0}, {7, 5, 12.0}};
static const uint64_t seeds[] = {1, 7, 2024};

static double wave_length(const wave *w)
{
    double L = N * CELL;
    return 1.0 / hypot(w->k / L, w->l / L);
}

/* Azimuth (degrees clockwise from north, in [0, 180)) of wave (u, v) cycles across the columns and down
 * the rows of a north-up grid of square cells: the wave vector is (u, -v) / L in (east, north). */
static double wave_direction(double u, double v)
{
    return fmod(atan2(u, -v) * 180.0 / M_PI + 360.0, 180.0);
}

/* The plane's beta0 in map coordinates (its value at x = y = 0). */
static double beta0(void)
{
    double xc = X0 + 0.5 * N * CELL, yc = Y0 - 0.5 * N * CELL;
    return Z_CENTRE - BETA1 * xc - BETA2 * yc;
}

/* A fractional Brownian surface of dimension FBM_D and sd FBM_SIGMA (spectral synthesis, padded). */
static ft_grid *fbm(uint64_t seed)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = FBM_D;
    so.sigma = FBM_SIGMA;
    so.cell = CELL;
    so.origin_x = X0;
    so.origin_y = Y0;
    so.seed = seed;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(N, N, &so, &g), FT_OK);
    return g;
}

static ft_grid *synthetic_dem(uint64_t seed)
{
    ft_grid *g = fbm(seed);
    double gt[6] = {X0, CELL, 0.0, Y0, 0.0, -CELL};
    memcpy(g->gt, gt, sizeof gt);
    for (size_t r = 0; r < N; r++) {
        for (size_t c = 0; c < N; c++) {
            double u = (double)c + 0.5 - 0.5 * N, v = (double)r + 0.5 - 0.5 * N;
            double x = X0 + (c + 0.5) * CELL, y = Y0 - (r + 0.5) * CELL;
            double z = beta0() + BETA1 * x + BETA2 * y;
            for (int i = 0; i < 3; i++)
                z += waves[i].amplitude * cos(2.0 * M_PI * (waves[i].k * u + waves[i].l * v) / N);
            g->z[r * N + c] += (float)z;
        }
    }
    return g;
}

static ft_clarke_model *fit(const ft_grid *g)
{
    ft_clarke_model *m = NULL;
    assert_int_equal(ft_clarke_fit(g, NULL, &m), FT_OK);
    assert_non_null(m);
    return m;
}

/* Exactly the three waves, each once, with the right wavelength and amplitude. */
static void assert_three_waves(const ft_clarke_model *m)
{
    if (m->nharmonics != 3)
        for (size_t i = 0; i < m->nharmonics; i++)
            fprintf(stderr, "harmonic %zu: (%d,%d) share %.4f\n", i, m->harmonics[i].k, m->harmonics[i].l,
                    m->harmonics[i].share);
    assert_int_equal(m->nharmonics, 3);
    for (int i = 0; i < 3; i++) {
        const ft_clarke_harmonic *h = &m->harmonics[i]; /* by decreasing share: the waves' order */
        assert_int_equal(h->k, waves[i].k);
        assert_int_equal(h->l, waves[i].l);
        /* the reported wave is the continuous-frequency fit near the mode: the fBm moves it a little */
        fprintf(stderr, "wave %d: wavelength %.2f (true %.2f), direction %.3f (true %.3f)\n", i, h->wavelength,
                wave_length(&waves[i]), h->direction, wave_direction(waves[i].k, waves[i].l));
        assert_true(fabs(h->wavelength / wave_length(&waves[i]) - 1.0) < 0.005);
        assert_true(fabs(h->direction - wave_direction(waves[i].k, waves[i].l)) < 0.3);
        assert_true(fabs(hypot(h->a, h->b) - waves[i].amplitude) < 0.05 * waves[i].amplitude);
        assert_true(h->share > 0.025 && h->share < 1.0);
        assert_true(h->direction >= 0.0 && h->direction < 180.0);
    }
}

static void test_fit_synthetic(void **state)
{
    for (size_t s = 0; s < sizeof seeds / sizeof seeds[0]; s++) {
        ft_grid *g = synthetic_dem(seeds[s]);
        ft_clarke_model *m = fit(g);
        assert_true(fabs(m->beta1 / BETA1 - 1.0) < 0.01);
        assert_true(fabs(m->beta2 / BETA2 - 1.0) < 0.01);
        assert_true(fabs(m->beta0 / beta0() - 1.0) < 0.01);
        assert_true(m->trend_r2 > 0.9 && m->trend_r2 <= 1.0);
        assert_three_waves(m);
        fprintf(stderr, "seed %llu: beta %.4f %.5f %.5f, D %.3f (eq. viii %.3f), r2 %.3f, c %.3f\n",
                (unsigned long long)seeds[s], m->beta0, m->beta1, m->beta2, m->D, m->D_clarke_eq8, m->r2, m->c);
        assert_true(fabs(m->D - FBM_D) < 0.1);
        assert_true(fabs(m->D_clarke_eq8 - (3.0 - m->slope / 2.0)) < 1e-12);
        assert_int_equal(m->nx, N);
        assert_int_equal(m->nodata_filled, 0);
        assert_true(m->npairs > 10000 && m->npairs < (N * N - 4) / 2 + 3); /* the waves of 4 cells or more */
        assert_true(m->c > 0.0);
        ft_clarke_model_free(m);
        ft_grid_free(g);
    }
}

static void grid_stats(const ft_grid *g, double *mean, double *sd)
{
    double s = 0.0, ss = 0.0;
    size_t n = g->nx * g->ny;
    for (size_t i = 0; i < n; i++)
        s += g->z[i];
    *mean = s / n;
    for (size_t i = 0; i < n; i++)
        ss += (g->z[i] - *mean) * (g->z[i] - *mean);
    *sd = sqrt(ss / n);
}

static void test_simulate_synthetic(void **state)
{
    for (size_t s = 0; s < sizeof seeds / sizeof seeds[0]; s++) {
        ft_grid *g = synthetic_dem(seeds[s]), *sim = NULL;
        ft_clarke_model *m = fit(g);
        ft_clarke_sim_opts so = FT_CLARKE_SIM_OPTS_DEFAULT;
        double c = -1.0, mean0, sd0, mean1, sd1;
        so.seed = 99 + s;
        so.c_used = &c;
        assert_int_equal(ft_clarke_simulate(m, &so, &sim), FT_OK);
        assert_int_equal(sim->nx, N);
        assert_int_equal(sim->ny, N);
        assert_memory_equal(sim->gt, g->gt, sizeof g->gt);
        grid_stats(g, &mean0, &sd0);
        grid_stats(sim, &mean1, &sd1);
        assert_true(fabs(mean1 - mean0) < 0.02 * fabs(mean0));
        assert_true(fabs(sd1 / sd0 - 1.0) < 0.02);
        assert_true(c > 0.0);
        ft_clarke_model *m2 = fit(sim);
        assert_three_waves(m2);
        fprintf(stderr, "seed %llu: simulated D %.3f (model %.3f), c %.3f (model %.3f)\n",
                (unsigned long long)seeds[s], m2->D, m->D, c, m->c);
        assert_true(fabs(m2->D - m->D) < 0.1);
        ft_clarke_model_free(m2);
        ft_clarke_model_free(m);
        ft_grid_free(sim);
        ft_grid_free(g);
    }
}

/* Same seed => the same cells; refine 2 => twice the cells on the same extent, same mean and sd. */
static void test_simulate_seed_refine(void **state)
{
    ft_grid *g = synthetic_dem(5), *a = NULL, *b = NULL, *r = NULL;
    ft_clarke_model *m = fit(g);
    ft_clarke_sim_opts so = FT_CLARKE_SIM_OPTS_DEFAULT;
    so.seed = 3;
    assert_int_equal(ft_clarke_simulate(m, &so, &a), FT_OK);
    assert_int_equal(ft_clarke_simulate(m, &so, &b), FT_OK);
    assert_memory_equal(a->z, b->z, N * N * sizeof(float));
    so.refine = 2;
    assert_int_equal(ft_clarke_simulate(m, &so, &r), FT_OK);
    assert_int_equal(r->nx, 2 * N);
    assert_int_equal(r->ny, 2 * N);
    assert_true(fabs(r->gt[1] - CELL / 2) < 1e-12 && fabs(r->gt[5] + CELL / 2) < 1e-12);
    assert_true(r->gt[0] == X0 && r->gt[3] == Y0);
    double mean0, sd0, mean1, sd1;
    grid_stats(g, &mean0, &sd0);
    grid_stats(r, &mean1, &sd1);
    assert_true(fabs(mean1 - mean0) < 0.02 * fabs(mean0));
    assert_true(fabs(sd1 / sd0 - 1.0) < 0.02);
    ft_clarke_model *mr = fit(r);
    assert_int_equal(mr->nharmonics, 3);
    for (int i = 0; i < 3; i++) /* same waves: the same (k, l) over the same extent */
        assert_true(mr->harmonics[i].k == waves[i].k && mr->harmonics[i].l == waves[i].l);
    ft_clarke_model_free(mr);
    ft_grid_free(r);
    ft_grid_free(a);
    ft_grid_free(b);
    ft_clarke_model_free(m);
    ft_grid_free(g);
}

/* A DEM with nodata: the holes are filled with the trend and counted. */
static void test_fit_nodata(void **state)
{
    ft_grid *g = synthetic_dem(11);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t r = 0; r < 40; r++)
        for (size_t c = 0; c < 50; c++)
            g->mask[r * N + c] = 0;
    ft_clarke_model *m = fit(g);
    assert_int_equal(m->nodata_filled, 2000);
    assert_int_equal(m->valid, N * N - 2000);
    assert_true(fabs(m->beta1 / BETA1 - 1.0) < 0.01);
    assert_true(m->nharmonics >= 3);
    ft_clarke_model_free(m);
    ft_grid_free(g);
}

/* A wave of 5.37 x -2.61 cycles across a 128 x 96 grid with a nodata corner: the harmonic reports the wave's
 * own wavelength and direction, not those of its nearest grid mode (5, -3), 5.7 degrees away. */
static void test_fit_off_grid_wave(void **state)
{
    (void)state;
    const size_t nx = 128, ny = 96;
    const double u = 5.37, v = -2.61, cell = 25.0;
    ft_grid *g = ft_grid_create(nx, ny);
    assert_non_null(g);
    double gt[6] = {1000.0, cell, 0.0, 9000.0, 0.0, -cell};
    memcpy(g->gt, gt, sizeof gt);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t r = 0; r < ny; r++)
        for (size_t c = 0; c < nx; c++) {
            double th = 2.0 * M_PI * (u * (c + 0.5) / nx + v * (r + 0.5) / ny);
            g->z[r * nx + c] = (float)(300.0 + 0.05 * c + 40.0 * cos(th + 0.7) + 3.0 * sin(0.37 * (double)(r * c)));
            g->mask[r * nx + c] = !(r < 20 && c < 30);
        }
    ft_clarke_model *m = fit(g);
    assert_true(m->nharmonics >= 1);
    const ft_clarke_harmonic *h = &m->harmonics[0];
    double wl = 1.0 / hypot(u / (nx * cell), v / (ny * cell));
    double az = fmod(atan2(u / (nx * cell), -v / (ny * cell)) * 180.0 / M_PI + 360.0, 180.0);
    fprintf(stderr, "off-grid wave: mode (%d,%d), wavelength %.3f (true %.3f), direction %.4f (true %.4f)\n", h->k,
            h->l, h->wavelength, wl, h->direction, az);
    assert_true(fabs(h->wavelength / wl - 1.0) < 1e-3);
    assert_true(fabs(h->direction - az) < 0.05);
    double mode_az = fmod(atan2(h->k / (nx * cell), -h->l / (ny * cell)) * 180.0 / M_PI + 360.0, 180.0);
    assert_true(fabs(mode_az - az) > 3.0); /* what the grid's mode alone would say */
    ft_clarke_model_free(m);
    ft_grid_free(g);
}

static void test_bad_input(void **state)
{
    ft_clarke_model *m = NULL;
    ft_clarke_opts o = FT_CLARKE_OPTS_DEFAULT;
    ft_grid *one = ft_grid_create(1, 1);
    assert_int_equal(ft_clarke_fit(one, NULL, &m), FT_E_INVALID);
    assert_null(m);
    assert_non_null(strstr(ft_last_error(), "1 x 1"));
    ft_grid_free(one);

    ft_grid *g = ft_grid_create(16, 16);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    memset(g->mask, 0, 16 * 16);
    assert_int_equal(ft_clarke_fit(g, NULL, &m), FT_E_EMPTY);
    assert_null(m);
    assert_non_null(strstr(ft_last_error(), "valid"));

    memset(g->mask, 1, 16 * 16);
    const double bad[] = {0.0, -1.0, 100.5, NAN};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        o.cutoff = bad[i];
        assert_int_equal(ft_clarke_fit(g, &o, &m), FT_E_INVALID);
        assert_non_null(strstr(ft_last_error(), "cutoff"));
    }
    o.cutoff = 2.5;
    assert_int_equal(ft_clarke_fit(g, &o, &m), FT_E_EMPTY); /* a flat grid: no power at all */
    assert_int_equal(ft_clarke_fit(NULL, &o, &m), FT_E_INVALID);
    assert_int_equal(ft_clarke_fit(g, &o, NULL), FT_E_INVALID);

    for (size_t i = 0; i < 256; i++)
        g->z[i] = (float)((i * 7919) % 31);
    o.cutoff = 0.5;
    assert_int_equal(ft_clarke_fit(g, &o, &m), FT_OK);
    assert_true(m->nharmonics > 0);
    ft_grid *sim = NULL;
    ft_clarke_sim_opts so = FT_CLARKE_SIM_OPTS_DEFAULT;
    so.refine = 0;
    assert_int_equal(ft_clarke_simulate(m, &so, &sim), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "refine"));
    so.refine = 1;
    so.extent = 100;
    assert_int_equal(ft_clarke_simulate(m, &so, &sim), FT_E_INVALID);
    so.extent = 1;
    m->harmonics[0].k = 99;
    assert_int_equal(ft_clarke_simulate(m, &so, &sim), FT_E_INVALID);
    assert_null(sim);
    assert_int_equal(ft_clarke_simulate(NULL, &so, &sim), FT_E_INVALID);
    ft_clarke_model_free(m);
    ft_clarke_model_free(NULL);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fit_synthetic),
        cmocka_unit_test(test_simulate_synthetic),
        cmocka_unit_test(test_simulate_seed_refine),
        cmocka_unit_test(test_fit_nodata),
        cmocka_unit_test(test_fit_off_grid_wave),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
