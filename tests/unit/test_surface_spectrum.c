/* fracterra — unit tests of surface/spectrum.c: a periodic surface whose power is exactly |k|^-beta
 * (random phases) gives D = (8 - beta) / 2; white noise is flat at its variance, with square and oblong
 * cells (the differencing gain divided out per axis); one nodata cell leaves the whole tile in use (the
 * differences touching it are left out) while the elevations mode falls back to smaller nodata-free
 * tiles; the same bits on 1 and 2 threads with one tile and with many; the degenerate cases said
 * plainly, and bad options named in the error.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/surface.h"
#include "fracterra/terrain.h"
#include "ft_test_assert.h"

static ft_grid *fft_surface(size_t n, double D, uint64_t seed)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = FT_SYNTH_FFT;
    o.dim = D;
    o.seed = seed;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(n, n, &o, &g), 0);
    return g;
}

/* A t x t periodic surface z = Σ_k |k|^(-beta/2) cos(2 pi k.x / t + phi_k) over every frequency k != 0
 * (in cycles per tile), phi uniform and odd in k so that z is real: its power is exactly |k|^-beta at
 * every frequency, so D = (8 - beta) / 2 with no sampling scatter. A direct separable inverse DFT. */
static ft_grid *power_law(size_t t, double beta, uint64_t seed)
{
    double *cr = calloc(t * t, sizeof *cr), *ci = calloc(t * t, sizeof *ci);
    double *yr = calloc(t * t, sizeof *yr), *yi = calloc(t * t, sizeof *yi);
    double *cs = malloc(t * sizeof *cs), *sn = malloc(t * sizeof *sn);
    ft_rng *rng = ft_rng_create(seed, 0);
    ft_grid *g = ft_grid_create(t, t);
    assert_true(cr && ci && yr && yi && cs && sn && rng && g);
    for (size_t ky = 0; ky < t; ky++)
        for (size_t kx = 0; kx < t; kx++) {
            size_t k = ky * t + kx, mk = ((t - ky) % t) * t + (t - kx) % t;
            long fx = kx <= t / 2 ? (long)kx : (long)kx - (long)t, fy = ky <= t / 2 ? (long)ky : (long)ky - (long)t;
            if (k == 0)
                continue;
            if (mk < k) { /* the conjugate of -k, drawn already */
                cr[k] = cr[mk];
                ci[k] = -ci[mk];
                continue;
            }
            double a = pow((double)(fx * fx + fy * fy), -beta / 4.0), ph = 2.0 * M_PI * ft_rng_uniform(rng);
            cr[k] = a * cos(ph);
            ci[k] = mk == k ? 0.0 : a * sin(ph);
        }
    for (size_t m = 0; m < t; m++) {
        cs[m] = cos(2.0 * M_PI * (double)m / (double)t);
        sn[m] = sin(2.0 * M_PI * (double)m / (double)t);
    }
    for (size_t ky = 0; ky < t; ky++)
        for (size_t j = 0; j < t; j++) {
            double sr = 0.0, si = 0.0;
            for (size_t kx = 0; kx < t; kx++) {
                size_t m = (kx * j) % t;
                double a = cr[ky * t + kx], b = ci[ky * t + kx];
                sr += a * cs[m] - b * sn[m];
                si += a * sn[m] + b * cs[m];
            }
            yr[ky * t + j] = sr;
            yi[ky * t + j] = si;
        }
    for (size_t i = 0; i < t; i++)
        for (size_t j = 0; j < t; j++) {
            double s = 0.0;
            for (size_t ky = 0; ky < t; ky++) {
                size_t m = (ky * i) % t;
                s += yr[ky * t + j] * cs[m] - yi[ky * t + j] * sn[m];
            }
            g->z[i * t + j] = (float)s;
        }
    free(cr);
    free(ci);
    free(yr);
    free(yi);
    free(cs);
    free(sn);
    ft_rng_free(rng);
    return g;
}

/* The differences' periodogram recoloured by the differencing gain recovers the exponent: only the
 * wrap-around differences are missing from the periodic surface, a leakage of a few thousandths on a
 * 256 tile (about 0.02 at D = 2.1 on a 128 one). */
static void test_power_law(void **state)
{
    (void)state;
    for (int d = 0; d < 3; d++) {
        double D = 2.1 + 0.4 * d;
        ft_grid *g = power_law(256, 8.0 - 2.0 * D, (uint64_t)(d + 1));
        ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
        o.fit_whole_range = 1;
        ft_dim_result *r = NULL;
        assert_int_equal(ft_surface_dim_spectrum(g, &o, &r), 0);
        print_message("power law D %.1f: measured %.4f\n", D, r->D);
        assert_near(r->D, D, 0.01);
        assert_true(r->r2 > 0.999);
        ft_dim_result_free(r);
        ft_grid_free(g);
    }
}

/* White noise of variance 1: a flat spectrum (beta = 0, so D = (8 - 0) / 2 = 4 by the formula) at the
 * level of the variance: the difference along x has spectrum 4 sin²(pi kx / T) / cx² times the variance,
 * exactly what is divided out, so the level holds with oblong cells too. Measured at wavelengths of 2 to
 * 8 cells: the differences of white noise have a rising spectrum, which the untapered tile edges leak
 * into the lowest frequencies (an excess of about T / (2 pi² k²) at k cycles per tile, 20 % at k = 8 on
 * a 256 tile; an fBm's differences have a flat or falling spectrum and do not leak that way). */
static void check_white(double cx, double cy)
{
    size_t n = 256;
    ft_grid *g = ft_grid_create(n, n);
    g->gt[1] = cx;
    g->gt[5] = -cy;
    ft_rng *rng = ft_rng_create(3, 0);
    for (size_t i = 0; i < n * n; i++)
        g->z[i] = (float)ft_rng_gaussian(rng, 1.0);
    ft_rng_free(rng);
    ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
    o.min_wavelength = 2;
    o.max_wavelength = 8;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    /* white noise has a flat spectrum, beta = 0, D = 4: outside [2, 3], an error and not a result */
    assert_error_names(ft_surface_dim_spectrum(g, &o, &r), FT_E_NUMERIC, "outside [2, 3]");
    assert_non_null(strstr(ft_last_error(), "rougher than any fractal"));
    assert_null(r);
    ft_grid_free(g);
}

static void test_white_noise(void **state)
{
    (void)state;
    check_white(1.0, 1.0);
    check_white(2.0, 0.5);
}

static void assert_same_result(const ft_dim_result *a, const ft_dim_result *b)
{
    assert_int_equal(a->table->n, b->table->n);
    assert_memory_equal(a->table->rows, b->table->rows, a->table->n * sizeof a->table->rows[0]);
    assert_memory_equal(&a->D, &b->D, sizeof a->D);
}

/* The same bits on 1 and on every thread, with one tile (rows and columns in parallel) and with many
 * (whole tiles in parallel). */
static void check_threads(const ft_grid *g, const ft_spectrum_opts *o)
{
    ft_dim_result *a = NULL, *b = NULL;
    assert_int_equal(ft_surface_dim_spectrum(g, o, &a), 0);
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    assert_int_equal(ft_surface_dim_spectrum(g, o, &b), 0);
    omp_set_num_threads(nt);
    assert_same_result(a, b);
    ft_dim_result_free(a);
    ft_dim_result_free(b);
}

static void test_nodata_tiles_and_threads(void **state)
{
    (void)state;
    ft_grid *g = fft_surface(256, 2.5, 7), *h = ft_grid_copy(g);
    ft_dim_result *a = NULL, *b = NULL;
    assert_int_equal(ft_grid_ensure_mask(h), 0);
    h->mask[100 * 256 + 100] = 0;
    h->z[100 * 256 + 100] = NAN; /* never read */
    /* differences: the whole 256 tile stays in use (its band reaches 256 / 8 = 32 cells) and one hole
     * of 4 differences out of 130,560 barely moves D */
    assert_int_equal(ft_surface_dim_spectrum(g, NULL, &a), 0);
    assert_int_equal(ft_surface_dim_spectrum(h, NULL, &b), 0);
    assert_near(b->table->rows[0].scale, a->table->rows[0].scale, 1e-12);
    assert_true(a->table->rows[0].scale < 1.0 / 32.0 * 1.3);
    assert_near(b->D, a->D, 0.002);
    ft_dim_result_free(a);
    ft_dim_result_free(b);
    check_threads(h, NULL);
    ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
    o.tile = 32; /* 15 x 15 tiles: whole tiles in parallel */
    o.min_wavelength = 4;
    check_threads(h, &o);
    /* elevations: no 256 tile is free of nodata, so 128 tiles with half overlap, some whole */
    o = (ft_spectrum_opts)FT_SPECTRUM_OPTS_DEFAULT;
    o.elevations = 1;
    assert_int_equal(ft_surface_dim_spectrum(h, &o, &a), 0);
    assert_true(a->table->rows[0].scale > 1.0 / 16.0 * 0.99);
    ft_dim_result_free(a);
    check_threads(h, &o);
    o.tile = 256; /* asked for: no fallback */
    assert_error_names(ft_surface_dim_spectrum(h, &o, &a), FT_E_EMPTY, "256");
    assert_null(a);
    ft_grid_free(g);
    ft_grid_free(h);
}

/* A grid mostly nodata: a tile needs half of its differences valid, the automatic one shrinks until one
 * has; when none can, the error says why. */
static void test_mostly_nodata(void **state)
{
    (void)state;
    ft_grid *g = fft_surface(256, 2.5, 3);
    assert_int_equal(ft_grid_ensure_mask(g), 0);
    for (size_t i = 0; i < 256; i++)
        for (size_t j = 0; j < 256; j++)
            g->mask[i * 256 + j] = (uint8_t)(i < 96 && j < 96); /* valid: the upper-left 96 x 96 cells */
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_spectrum(g, NULL, &r), 0);
    assert_true(r->table->rows[0].scale > 1.0 / 16.0 * 0.99); /* 128 tiles: band up to 16 cells */
    ft_dim_result_free(r);
    for (size_t i = 0; i < 256 * 256; i++)
        g->mask[i] = (uint8_t)(i % 3 == 0); /* a third of the cells, never two neighbours along a row */
    assert_error_names(ft_surface_dim_spectrum(g, NULL, &r), FT_E_EMPTY, "differences valid");
    assert_null(r);
    ft_grid_free(g);
}

/* A tilted plane has nothing left after removing it; a bowl is smoother than any fractal. */
static void test_degenerate(void **state)
{
    (void)state;
    size_t n = 128;
    ft_grid *plane = ft_grid_create(n, n), *bowl = ft_grid_create(n, n);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++) {
            double x = (double)j - 63.5, y = (double)i - 63.5;
            plane->z[i * n + j] = (float)(0.3 * (double)j - 0.7 * (double)i + 100.0);
            bowl->z[i * n + j] = (float)(0.01 * (x * x + y * y) + 50.0);
        }
    ft_dim_result *r = NULL;
    for (int el = 0; el < 2; el++) {
        ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
        o.elevations = el;
        assert_error_names(ft_surface_dim_spectrum(plane, &o, &r), FT_E_NUMERIC, "plane");
        assert_error_names(ft_surface_dim_spectrum(bowl, &o, &r), FT_E_NUMERIC, "degenerate");
        assert_null(r);
    }
    ft_grid_free(plane);
    ft_grid_free(bowl);
}

static void test_bad_options(void **state)
{
    (void)state;
    ft_grid *g = fft_surface(64, 2.5, 7);
    ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
    ft_dim_result *r = NULL;
    o.tile = 100;
    assert_error_names(ft_surface_dim_spectrum(g, &o, &r), FT_E_INVALID, "100");
    o = (ft_spectrum_opts)FT_SPECTRUM_OPTS_DEFAULT;
    o.min_wavelength = 1;
    assert_error_names(ft_surface_dim_spectrum(g, &o, &r), FT_E_INVALID, "min_wavelength");
    o = (ft_spectrum_opts)FT_SPECTRUM_OPTS_DEFAULT;
    o.nbins = 1;
    assert_int_equal(ft_surface_dim_spectrum(g, &o, &r), FT_E_INVALID);
    o = (ft_spectrum_opts)FT_SPECTRUM_OPTS_DEFAULT;
    o.max_wavelength = 9; /* 8 .. 9 cells: not an octave */
    assert_error_names(ft_surface_dim_spectrum(g, &o, &r), FT_E_INVALID, "octave");
    o = (ft_spectrum_opts)FT_SPECTRUM_OPTS_DEFAULT;
    o.elevations = 2;
    assert_error_names(ft_surface_dim_spectrum(g, &o, &r), FT_E_INVALID, "elevations");
    assert_null(r);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_power_law),
        cmocka_unit_test(test_white_noise),
        cmocka_unit_test(test_nodata_tiles_and_threads),
        cmocka_unit_test(test_mostly_nodata),
        cmocka_unit_test(test_degenerate),
        cmocka_unit_test(test_bad_options),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
