/* fracterra — unit tests of terrain/synth*.c: accuracy of the four synthesizers against the variogram
 * estimator (exact: D within 0.02 over lags 1-64 at 512², median of 20 seeds; fft and sra within 0.05
 * over lags 2-32 where docs/terrain-synthesis.md shows the method holds it), the fft spectrum slope,
 * reproducibility, sigma, odd sizes, georeferencing and bad input.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fft/fft.h"
#include "fracterra/surface.h"
#include "fracterra/terrain.h"
#include "ft_test_assert.h"

static ft_grid *synth(ft_synth_method m, double D, size_t nx, size_t ny, uint64_t seed)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = m;
    o.dim = D;
    o.seed = seed;
    ft_grid *g = NULL;
    int rc = ft_terrain_synth(nx, ny, &o, &g);
    if (rc != 0)
        print_error("synth %s D=%g: %s\n", ft_synth_method_name(m), D, ft_last_error());
    assert_int_equal(rc, 0);
    return g;
}

static double variogram_D(const ft_grid *g, double lo, double hi)
{
    ft_variogram_opts v = FT_VARIOGRAM_OPTS_DEFAULT;
    v.min_lag = lo;
    v.max_lag = hi;
    v.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_variogram(g, &v, &r), 0);
    double D = r->D;
    ft_dim_result_free(r);
    return D;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median over `nseeds` surfaces of the variogram D. */
static double median_D(ft_synth_method m, double D, size_t n, int nseeds, double lo, double hi)
{
    double d[32];
    for (int s = 0; s < nseeds; s++) {
        ft_grid *g = synth(m, D, n, n, (uint64_t)s + 1);
        d[s] = variogram_D(g, lo, hi);
        ft_grid_free(g);
    }
    qsort(d, (size_t)nseeds, sizeof d[0], cmp_double);
    return nseeds % 2 ? d[nseeds / 2] : 0.5 * (d[nseeds / 2 - 1] + d[nseeds / 2]);
}

static void check_method(ft_synth_method m, const double *dims, size_t nd, int nseeds, double lo, double hi,
                         double tol)
{
    int bad = 0;
    for (size_t i = 0; i < nd; i++) {
        double got = median_D(m, dims[i], 512, nseeds, lo, hi);
        print_message("%s D=%.2f: median variogram D over %d seeds %.4f\n", ft_synth_method_name(m), dims[i],
                      nseeds, got);
        bad += !(fabs(got - dims[i]) <= tol);
    }
    assert_int_equal(bad, 0);
}

/* Every other D of the 2.1 ... 2.8 (both embeddings: R = 2 below D = 2.25, R = 1 above), to keep the
 * test under a minute; docs/terrain-synthesis.md has the full table (40 seeds per D). */
static void test_exact_accuracy(void **state)
{
    (void)state;
    static const double dims[] = {2.2, 2.4, 2.6, 2.8};
    /* 20 seeds, not 10: one 512² surface's variogram D scatters by 0.04 (D = 2.1) to 0.008 (D = 2.8) with a
     * +0.01 bias at low D (log of a single realization's variogram); the median of 10 then lands within
     * 0.02 only ~80% of the time even though the synthesizer is exact (docs/terrain-synthesis.md). */
    check_method(FT_SYNTH_EXACT, dims, sizeof dims / sizeof dims[0], 20, 1, 64, 0.02);
}

static void test_fft_accuracy(void **state)
{
    (void)state;
    static const double dims[] = {2.1, 2.2, 2.3, 2.4, 2.5, 2.6, 2.7, 2.8};
    check_method(FT_SYNTH_FFT, dims, sizeof dims / sizeof dims[0], 10, 2, 32, 0.05);
}

static void test_sra_accuracy(void **state)
{
    (void)state;
    static const double dims[] = {2.5, 2.6, 2.7, 2.8}; /* Voss's raw SRA is biased upwards below (docs) */
    check_method(FT_SYNTH_SRA_RAW, dims, sizeof dims / sizeof dims[0], 10, 2, 32, 0.05);
}

/* The variogram D over lags 1-16 written here (not the library's estimator): mean squared difference along
 * rows and columns at every integer lag 1..16, least squares of its log on log lag, D = 3 - slope / 2. */
static double lags16_D(const ft_grid *g)
{
    size_t nx = g->nx, ny = g->ny;
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t h = 1; h <= 16; h++) {
        double s = 0.0, c = 0.0;
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++) {
                double v = g->z[y * nx + x];
                if (x + h < nx) {
                    s += (g->z[y * nx + x + h] - v) * (g->z[y * nx + x + h] - v);
                    c++;
                }
                if (y + h < ny) {
                    s += (g->z[(y + h) * nx + x] - v) * (g->z[(y + h) * nx + x] - v);
                    c++;
                }
            }
        double lx = log((double)h), ly = log(s / c);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return 3.0 - (16.0 * sxy - sx * sy) / (16.0 * sxx - sx * sx) / 2.0;
}

/* sra and midpoint are calibrated (src/terrain/synth/synth_calibration.c): the median of 5 seeds of the lag 1-16
 * variogram D is the asked D within 0.03 at D = 2.1 ... 2.8, on 256² and on a 384 x 200 grid (another
 * number of levels for sra); the raw variants keep the papers' bias (sra-raw +0.1 at D = 2.2). */
static void test_calibrated_accuracy(void **state)
{
    (void)state;
    const ft_synth_method methods[2] = {FT_SYNTH_SRA, FT_SYNTH_MIDPOINT};
    const size_t sizes[2][2] = {{256, 256}, {384, 200}};
    int bad = 0;
    for (int m = 0; m < 2; m++)
        for (int sz = 0; sz < 2; sz++)
            for (int k = 1; k <= 8; k++) {
                double D = 2.0 + 0.1 * k, d[5];
                for (int s = 0; s < 5; s++) {
                    ft_grid *g = synth(methods[m], D, sizes[sz][0], sizes[sz][1], (uint64_t)s + 1);
                    d[s] = lags16_D(g);
                    ft_grid_free(g);
                }
                qsort(d, 5, sizeof d[0], cmp_double);
                if (!(fabs(d[2] - D) <= 0.03)) {
                    print_error("%s %zux%zu D=%.1f: median lag 1-16 D %.4f\n", ft_synth_method_name(methods[m]),
                                sizes[sz][0], sizes[sz][1], D, d[2]);
                    bad++;
                }
            }
    assert_int_equal(bad, 0);
    ft_grid *raw = synth(FT_SYNTH_SRA_RAW, 2.2, 256, 256, 1), *cal = synth(FT_SYNTH_SRA, 2.2, 256, 256, 1);
    assert_true(lags16_D(raw) > 2.27);
    assert_true(ft_synth_raw_dim(FT_SYNTH_SRA, 2.2, 256, 256) < 2.2);
    assert_near(ft_synth_raw_dim(FT_SYNTH_SRA_RAW, 2.2, 256, 256), 2.2, 0.0);
    assert_near(ft_synth_raw_dim(FT_SYNTH_EXACT, 2.2, 256, 256), 2.2, 0.0);
    ft_grid_free(raw);
    ft_grid_free(cal);
}

/* Radially averaged power spectrum of a periodic fft tile, fitted over 4 .. 64 cycles per tile:
 * P(f) ~ f^-(2H+2). */
static double spectrum_slope(const ft_grid *g)
{
    size_t n = g->nx, ncx = n / 2 + 1, nb = n / 2;
    double *re = ft_fft_alloc_real(n * n);
    fftw_complex *sp = ft_fft_alloc_complex(n * ncx);
    assert_non_null(re);
    assert_non_null(sp);
    for (size_t i = 0; i < n * n; i++)
        re[i] = g->z[i];
    assert_int_equal(ft_fft_r2c_2d(n, n, re, sp), 0);
    double *pw = calloc(nb + 1, sizeof *pw), *cnt = calloc(nb + 1, sizeof *cnt);
    for (size_t ky = 0; ky < n; ky++)
        for (size_t kx = 0; kx < ncx; kx++) {
            double fy = ky <= n / 2 ? (double)ky : (double)ky - (double)n;
            size_t b = (size_t)lround(hypot((double)kx, fy));
            if (b == 0 || b > nb)
                continue;
            pw[b] += sp[ky * ncx + kx][0] * sp[ky * ncx + kx][0] + sp[ky * ncx + kx][1] * sp[ky * ncx + kx][1];
            cnt[b] += 1.0;
        }
    double sx = 0, sy = 0, sxx = 0, sxy = 0, k = 0;
    for (size_t b = 4; b <= 64; b++) {
        double x = log10((double)b), y = log10(pw[b] / cnt[b]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        k += 1.0;
    }
    free(pw);
    free(cnt);
    ft_fft_free(re);
    ft_fft_free(sp);
    return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

static void test_fft_spectrum_slope(void **state)
{
    (void)state;
    static const double dims[] = {2.2, 2.5, 2.8};
    for (size_t i = 0; i < 3; i++) {
        ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
        o.dim = dims[i];
        o.periodic = 1;
        /* One 512² tile's slope scatters by about 0.033 (sd over 200 seeds at D = 2.8), and the aliasing
         * correction puts the expected slope about 0.06 above -(2H+2) at high D: 16 tiles bring the mean's
         * scatter to 0.008, well inside the 0.1 tolerance. */
        double sum = 0.0;
        for (uint64_t s = 1; s <= 16; s++) {
            o.seed = s;
            ft_grid *g = NULL;
            assert_int_equal(ft_terrain_synth(512, 512, &o, &g), 0);
            sum += spectrum_slope(g);
            ft_grid_free(g);
        }
        double H = 3.0 - dims[i];
        assert_near(sum / 16.0, -(2.0 * H + 2.0), 0.1);
    }
}

static void test_reproducible(void **state)
{
    (void)state;
    for (int m = 0; m < 4; m++) {
        ft_grid *a = synth((ft_synth_method)m, 2.4, 130, 97, 7), *b = synth((ft_synth_method)m, 2.4, 130, 97, 7);
        ft_grid *c = synth((ft_synth_method)m, 2.4, 130, 97, 8);
        assert_memory_equal(a->z, b->z, 130 * 97 * sizeof(float));
        assert_true(memcmp(a->z, c->z, 130 * 97 * sizeof(float)) != 0);
        ft_grid_free(a);
        ft_grid_free(b);
        ft_grid_free(c);
    }
}

/* ft_terrain_synth_into: the cells of ft_terrain_synth bit for bit, for every method, reusing one
 * workspace and one grid over several seeds (periodic fft too); the grid's mask is set all valid and its
 * geotransform set; a workspace of another size, method or periodic flag is refused. */
static void test_synth_into(void **state)
{
    (void)state;
    for (int m = 0; m < 6; m++)
        for (int periodic = 0; periodic < 2; periodic++) {
            if (periodic && m != FT_SYNTH_FFT)
                continue;
            ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
            o.method = (ft_synth_method)m;
            o.periodic = periodic;
            o.dim = 2.45;
            o.cell = 10.0;
            ft_synth_workspace *ws = NULL;
            assert_int_equal(ft_synth_workspace_create(131, 97, &o, &ws), FT_OK);
            ft_grid *out = ft_grid_create(131, 97);
            assert_non_null(out);
            assert_int_equal(ft_grid_ensure_mask(out), FT_OK);
            out->mask[5] = 0;
            for (uint64_t seed = 3; seed < 6; seed++) {
                o.seed = seed;
                ft_grid *ref = NULL;
                assert_int_equal(ft_terrain_synth(131, 97, &o, &ref), FT_OK);
                assert_int_equal(ft_terrain_synth_into(&o, ws, out), FT_OK);
                assert_memory_equal(out->z, ref->z, 131 * 97 * sizeof(float));
                assert_non_null(out->mask);
                for (size_t c = 0; c < 131 * 97; c++)
                    assert_int_equal(out->mask[c], 1);
                for (int k = 0; k < 6; k++)
                    assert_true(out->gt[k] == ref->gt[k]);
                ft_grid_free(ref);
            }
            ft_synth_opts other = o;
            other.method = m == FT_SYNTH_FFT ? FT_SYNTH_SRA : FT_SYNTH_FFT;
            assert_int_equal(ft_terrain_synth_into(&other, ws, out), FT_E_INVALID);
            assert_non_null(strstr(ft_last_error(), "workspace is for method"));
            ft_grid *small = ft_grid_create(130, 97);
            assert_int_equal(ft_terrain_synth_into(&o, ws, small), FT_E_INVALID);
            assert_non_null(strstr(ft_last_error(), "131 x 97"));
            if (m == FT_SYNTH_FFT) {
                other = o;
                other.periodic = !periodic;
                assert_int_equal(ft_terrain_synth_into(&other, ws, out), FT_E_INVALID);
            }
            assert_int_equal(ft_terrain_synth_into(&o, NULL, out), FT_E_INVALID);
            o.dim = 3.5;
            assert_int_equal(ft_terrain_synth_into(&o, ws, out), FT_E_INVALID);
            ft_grid_free(small);
            ft_grid_free(out);
            ft_synth_workspace_free(ws);
        }
    ft_synth_workspace *ws = NULL;
    assert_int_equal(ft_synth_workspace_create(0, 10, NULL, &ws), FT_E_INVALID);
    assert_null(ws);
    ft_synth_workspace_free(NULL);
}

static void test_sigma_and_georef(void **state)
{
    (void)state;
    for (int m = 0; m < 6; m++) {
        ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
        o.method = (ft_synth_method)m;
        o.sigma = 25.0;
        o.cell = 30.0;
        o.origin_x = 500000.0;
        o.origin_y = 4200000.0;
        ft_grid *g = NULL;
        assert_int_equal(ft_terrain_synth(200, 150, &o, &g), 0);
        double s = 0.0, s2 = 0.0, n = 200.0 * 150.0;
        for (size_t i = 0; i < 200 * 150; i++) {
            s += g->z[i];
            s2 += (double)g->z[i] * g->z[i];
        }
        assert_near(s / n, 0.0, 1e-3);
        assert_near(sqrt(s2 / n - (s / n) * (s / n)), 25.0, 1e-3);
        const double gt[6] = {500000.0, 30.0, 0.0, 4200000.0, 0.0, -30.0};
        for (int k = 0; k < 6; k++)
            assert_true(g->gt[k] == gt[k]);
        assert_null(g->mask);
        ft_grid_free(g);
    }
}

static void test_odd_sizes(void **state)
{
    (void)state;
    static const size_t sizes[][2] = {{257, 130}, {1, 1}, {1, 17}, {33, 1}, {2, 3}, {131, 5}};
    for (int m = 0; m < 4; m++)
        for (size_t k = 0; k < sizeof sizes / sizeof sizes[0]; k++) {
            ft_grid *g = synth((ft_synth_method)m, 2.5, sizes[k][0], sizes[k][1], 3);
            assert_int_equal(g->nx, sizes[k][0]);
            assert_int_equal(g->ny, sizes[k][1]);
            for (size_t i = 0; i < g->nx * g->ny; i++)
                assert_true(isfinite(g->z[i]));
            ft_grid_free(g);
        }
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.periodic = 1;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(97, 61, &o, &g), 0); /* periodic tile of prime size */
    ft_grid_free(g);
}

static void expect_error(size_t nx, size_t ny, ft_synth_opts o, const char *needle)
{
    ft_grid *g = (ft_grid *)1;
    assert_int_equal(ft_terrain_synth(nx, ny, &o, &g), FT_E_INVALID);
    assert_null(g);
    if (strstr(ft_last_error(), needle) == NULL)
        print_error("'%s' does not name '%s'\n", ft_last_error(), needle);
    assert_non_null(strstr(ft_last_error(), needle));
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.dim = 3.0;
    expect_error(10, 10, o, "3");
    o.dim = 1.5;
    expect_error(10, 10, o, "1.5");
    o.dim = NAN;
    expect_error(10, 10, o, "nan");
    o = (ft_synth_opts)FT_SYNTH_OPTS_DEFAULT;
    expect_error(0, 10, o, "0x10");
    expect_error(10, 0, o, "10x0");
    o.sigma = -1.0;
    expect_error(10, 10, o, "-1");
    o = (ft_synth_opts)FT_SYNTH_OPTS_DEFAULT;
    o.cell = 0.0;
    expect_error(10, 10, o, "cell");
    o = (ft_synth_opts)FT_SYNTH_OPTS_DEFAULT;
    o.method = (ft_synth_method)9;
    expect_error(10, 10, o, "9");
    ft_synth_method m;
    assert_int_equal(ft_synth_method_parse("midpoint", &m), 0);
    assert_int_equal(m, FT_SYNTH_MIDPOINT);
    assert_int_equal(ft_synth_method_parse("EXACT", &m), 0);
    assert_int_equal(m, FT_SYNTH_EXACT);
    assert_int_equal(ft_synth_method_parse("fractal", &m), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "fractal"));
    assert_string_equal(ft_synth_method_name(FT_SYNTH_SRA), "sra");
    assert_int_equal(ft_synth_method_parse("sra-raw", &m), 0);
    assert_int_equal(m, FT_SYNTH_SRA_RAW);
    assert_string_equal(ft_synth_method_name(FT_SYNTH_MIDPOINT_RAW), "midpoint-raw");
    assert_int_equal(ft_terrain_synth(4, 4, NULL, NULL), FT_E_INVALID);
}

static int cancel_at_once(double frac, const char *msg, void *arg)
{
    (void)frac;
    (void)msg;
    (void)arg;
    return 0;
}

static void test_cancel(void **state)
{
    (void)state;
    for (int m = 0; m < 6; m++) {
        ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
        o.method = (ft_synth_method)m;
        o.progress = cancel_at_once;
        ft_grid *g = NULL;
        assert_int_equal(ft_terrain_synth(64, 64, &o, &g), FT_E_CANCELLED);
        assert_null(g);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input),      cmocka_unit_test(test_odd_sizes),
        cmocka_unit_test(test_reproducible),   cmocka_unit_test(test_synth_into),   cmocka_unit_test(test_sigma_and_georef),
        cmocka_unit_test(test_cancel),         cmocka_unit_test(test_fft_spectrum_slope),
        cmocka_unit_test(test_fft_accuracy),   cmocka_unit_test(test_sra_accuracy),
        cmocka_unit_test(test_exact_accuracy), cmocka_unit_test(test_calibrated_accuracy),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    ft_fft_cleanup();
    return rc;
}
