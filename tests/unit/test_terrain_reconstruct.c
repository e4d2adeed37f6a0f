/* fracterra — unit tests of terrain/reconstruct/reconstruct.c and recon_*.c: bad options and data named in the error,
 * method names, reproducibility (same seed, other seed, 1 and 2 threads), the smooth method on a plane
 * (the thin plate's null space: exact) and a paraboloid (close), data fidelity (within sigma with soft
 * data by the discrepancy principle, per-point sigmas, several points per node; exact with sigma = 0, for
 * the conditional method and for voids), realizations (mean and sd),
 * info, cancellation, void filling of a real DEM (known cells bit-identical), and the structure function
 * of the conditional reconstruction (mean |dz| at lags 1-32 within 5% of the original's) with the blend
 * of Szeliski's eq. 7.
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

#include "fracterra/io.h"
#include "fracterra/surface.h"
#include "fracterra/terrain.h"
#include "ft_test_assert.h"

/* A 64 x 64 grid with cells of 10 ground units, upper-left corner (1000, 2000). */
static ft_grid *target(size_t nx, size_t ny)
{
    ft_grid *g = ft_grid_create(nx, ny);
    assert_non_null(g);
    double gt[6] = {1000.0, 10.0, 0.0, 2000.0, 0.0, -10.0};
    memcpy(g->gt, gt, sizeof gt);
    return g;
}

/* A fractional Brownian surface of dimension D on a target-like grid, standard deviation 100. */
static ft_grid *fbm(size_t n, double D, uint64_t seed)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = FT_SYNTH_EXACT;
    o.dim = D;
    o.sigma = 100.0;
    o.seed = seed;
    o.cell = 10.0;
    o.origin_x = 1000.0;
    o.origin_y = 2000.0;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(n, n, &o, &g), 0);
    return g;
}

/* Every `every`-th cell centre of g in each direction (offset 1), with the cell's value. */
static ft_points *lattice_points(const ft_grid *g, size_t every)
{
    ft_points *p = ft_points_create(0);
    assert_non_null(p);
    for (size_t y = 1; y < g->ny; y += every)
        for (size_t x = 1; x < g->nx; x += every) {
            double cx, cy;
            ft_grid_cell_center(g, (double)x, (double)y, &cx, &cy);
            assert_int_equal(ft_points_push(p, cx, cy, g->z[y * g->nx + x]), 0);
        }
    return p;
}

static ft_points *sample(const ft_grid *g, double fraction, uint64_t seed)
{
    ft_grid_sample_opts o = FT_GRID_SAMPLE_OPTS_DEFAULT;
    o.fraction = fraction;
    o.seed = seed;
    ft_points *p = NULL;
    assert_int_equal(ft_surface_points_from_grid(g, &o, &p), 0);
    return p;
}

static ft_grid *recon(const ft_points *p, const ft_grid *t, const ft_recon_opts *o, ft_recon_info *info)
{
    ft_grid *out = NULL;
    int rc = ft_reconstruct_points(p, t, o, &out, NULL, info);
    if (rc != 0)
        print_error("reconstruct: %s\n", ft_last_error());
    assert_int_equal(rc, 0);
    assert_non_null(out);
    return out;
}

static void test_names(void **state)
{
    (void)state;
    for (int m = 0; m < 3; m++) {
        ft_recon_method got;
        assert_int_equal(ft_recon_method_parse(ft_recon_method_name((ft_recon_method)m), &got), 0);
        assert_int_equal((int)got, m);
    }
    ft_recon_method got;
    assert_int_equal(ft_recon_method_parse("FRACTAL", &got), 0);
    assert_int_equal(got, FT_RECON_FRACTAL);
    assert_error_names(ft_recon_method_parse("kriging", &got), FT_E_INVALID, "kriging");
    assert_string_equal(ft_recon_method_name((ft_recon_method)9), "unknown");
    assert_true(FT_RECON_K_DEFAULT > 0.0);
}

static void expect_bad(const ft_points *p, const ft_grid *t, const ft_recon_opts *o, int code, const char *text)
{
    ft_grid *out = (ft_grid *)1, *sd = (ft_grid *)1;
    assert_error_names(ft_reconstruct_points(p, t, o, &out, &sd, NULL), code, text);
    assert_null(out);
    assert_null(sd);
}

static void test_bad_options(void **state)
{
    (void)state;
    ft_grid *t = target(32, 32), *g = fbm(32, 2.5, 1);
    ft_points *p = lattice_points(g, 4);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.dim = 3.5;
    expect_bad(p, t, &o, FT_E_INVALID, "3.5");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.realizations = 0;
    expect_bad(p, t, &o, FT_E_INVALID, "realizations");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.lambda = 0.0;
    expect_bad(p, t, &o, FT_E_INVALID, "lambda");
    o.lambda = -2.0;
    expect_bad(p, t, &o, FT_E_INVALID, "-2");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.tension = 1.5;
    expect_bad(p, t, &o, FT_E_INVALID, "tension");
    o.tension = -0.1;
    expect_bad(p, t, &o, FT_E_INVALID, "-0.1");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.sigma = NAN;
    expect_bad(p, t, &o, FT_E_INVALID, "sigma");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.k = -1.0;
    expect_bad(p, t, &o, FT_E_INVALID, "k must");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.method = (ft_recon_method)7;
    expect_bad(p, t, &o, FT_E_INVALID, "method");
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    expect_bad(p, NULL, &o, FT_E_INVALID, "target");

    /* fewer than 3 points, collinear points, a NaN datum, a bad weight */
    o.method = FT_RECON_SMOOTH;
    ft_points *two = ft_points_create(0);
    ft_points_push(two, 1005.0, 1995.0, 1.0);
    ft_points_push(two, 1105.0, 1895.0, 2.0);
    expect_bad(two, t, &o, FT_E_EMPTY, "at least 3");
    ft_points_push(two, 1205.0, 1795.0, 3.0); /* nodes (0, 0), (10, 10), (20, 20): one line */
    expect_bad(two, t, &o, FT_E_INVALID, "line");
    ft_points_push(two, 5000.0, 5000.0, 3.0); /* outside: still on a line inside */
    expect_bad(two, t, &o, FT_E_INVALID, "line");
    ft_points_push(two, 1015.0, 1805.0, NAN);
    expect_bad(two, t, &o, FT_E_NUMERIC, "point 4");
    two->z[4] = 1.0;
    assert_int_equal(ft_points_ensure_weights(two), 0);
    two->w[1] = 0.0;
    expect_bad(two, t, &o, FT_E_INVALID, "point 1");
    ft_points_free(two);

    /* all-nodata DEM */
    ft_grid *v = ft_grid_copy(g);
    assert_int_equal(ft_grid_ensure_mask(v), 0);
    memset(v->mask, 0, v->nx * v->ny);
    ft_grid *out = (ft_grid *)1;
    assert_error_names(ft_reconstruct_voids(v, NULL, &out, NULL, NULL), FT_E_EMPTY, "no valid cell");
    assert_null(out);
    o = (ft_recon_opts)FT_RECON_OPTS_DEFAULT;
    o.dim = 1.5;
    assert_error_names(ft_reconstruct_voids(g, &o, &out, NULL, NULL), FT_E_INVALID, "1.5");
    ft_grid_free(v);
    ft_points_free(p);
    ft_grid_free(g);
    ft_grid_free(t);
}

/* Same seed: bit-identical; another seed: different; 1 and 2 threads: bit-identical. */
static void test_reproducible(void **state)
{
    (void)state;
    ft_grid *g = fbm(96, 2.5, 3);
    ft_points *p = sample(g, 0.05, 4);
    for (int m = 0; m < 2; m++) {
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = (ft_recon_method)m;
        o.dim = 2.5;
        o.seed = 11;
        o.threads = 1;
        ft_grid *a = recon(p, g, &o, NULL);
        o.threads = 2;
        ft_grid *b = recon(p, g, &o, NULL);
        o.seed = 12;
        ft_grid *c = recon(p, g, &o, NULL);
        size_t n = g->nx * g->ny;
        assert_memory_equal(a->z, b->z, n * sizeof *a->z);
        assert_true(memcmp(a->z, c->z, n * sizeof *a->z) != 0);
        ft_grid_free(a);
        ft_grid_free(b);
        ft_grid_free(c);
    }
    ft_points_free(p);
    ft_grid_free(g);
}

/* The thin plate (tension 0) has the planes as its null space: points of a plane give the plane. */
static void test_smooth_plane(void **state)
{
    (void)state;
    ft_grid *g = target(50, 40);
    for (size_t y = 0; y < g->ny; y++)
        for (size_t x = 0; x < g->nx; x++)
            g->z[y * g->nx + x] = (float)(300.0 + 2.0 * (double)x - 1.5 * (double)y);
    ft_points *p = sample(g, 0.03, 2);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = FT_RECON_SMOOTH;
    o.tension = 0.0;
    ft_recon_info info;
    ft_grid *out = recon(p, g, &o, &info);
    double worst = 0.0;
    for (size_t i = 0; i < g->nx * g->ny; i++)
        worst = fmax(worst, fabs((double)out->z[i] - (double)g->z[i]));
    print_message("plane: largest error %.3g (range 100 .. 460)\n", worst);
    assert_true(worst < 1e-4 * 460.0); /* float cells and the solver's tolerance */
    assert_int_equal(info.data_used, p->n);
    assert_int_equal(info.data_outside, 0);
    assert_int_equal(info.filled, g->nx * g->ny - p->n);
    assert_true(info.levels >= 3);
    ft_grid_free(out);
    ft_points_free(p);
    ft_grid_free(g);
}

/* A paraboloid (biharmonic: it satisfies the thin plate's equation inside) from 5% of its cells: close,
 * the error coming from the natural boundary conditions near the edges. */
static void test_smooth_paraboloid(void **state)
{
    (void)state;
    ft_grid *g = target(64, 64);
    double zmin = INFINITY, zmax = -INFINITY;
    for (size_t y = 0; y < g->ny; y++)
        for (size_t x = 0; x < g->nx; x++) {
            double dx = (double)x - 30.0, dy = (double)y - 35.0;
            double z = 500.0 - 0.2 * (dx * dx + dy * dy);
            g->z[y * g->nx + x] = (float)z;
            zmin = fmin(zmin, z);
            zmax = fmax(zmax, z);
        }
    ft_points *p = sample(g, 0.05, 5);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = FT_RECON_SMOOTH;
    o.tension = 0.0;
    ft_grid *out = recon(p, g, &o, NULL);
    double s = 0.0;
    for (size_t i = 0; i < g->nx * g->ny; i++)
        s += pow((double)out->z[i] - (double)g->z[i], 2);
    double rmse = sqrt(s / (double)(g->nx * g->ny));
    print_message("paraboloid: RMSE %.4f over a range of %.1f\n", rmse, zmax - zmin);
    assert_true(rmse < 0.005 * (zmax - zmin));
    ft_grid_free(out);
    ft_points_free(p);
    ft_grid_free(g);
}

/* Data fidelity: exact with sigma = 0 (smooth, fractal, conditional), within sigma with soft data (the
 * discrepancy principle lowers the default lambda = 1 until chi² = sum (u - d)² / sigma² is within
 * [(1 - 0.06) N, N]). The stochastic methods keep the data nodes at the smooth solution's values. */
static void test_fidelity(void **state)
{
    (void)state;
    ft_grid *g = fbm(80, 2.4, 6);
    ft_points *p = sample(g, 0.05, 7);
    for (int m = 0; m < 3; m++) {
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = (ft_recon_method)m;
        o.dim = 2.4;
        ft_recon_info info;
        ft_grid *out = recon(p, g, &o, &info);
        print_message("%s, sigma 0: data RMS %.3g\n", ft_recon_method_name(o.method), info.data_rms);
        assert_true(info.data_rms <= 1e-4 * 100.0);
        ft_grid_free(out);
        o.sigma = 5.0;
        out = recon(p, g, &o, &info);
        print_message("%s, sigma 5: data RMS %.3g\n", ft_recon_method_name(o.method), info.data_rms);
        assert_true(info.data_rms >= sqrt(0.94) * 5.0 - 1e-3 && info.data_rms <= 5.0 + 1e-3);
        ft_grid_free(out);
    }
    ft_points_free(p);
    ft_grid_free(g);
}

/* RMS over the points of (u - z_i) / sigma_i (sigma_i = 1 / w_i, or `sigma`) with u the output's cell under
 * each point (the points below are cell centres, where the output's bilinear value is the cell's). */
static double chi_rms(const ft_grid *out, const ft_points *p, double sigma)
{
    double s = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        size_t col = (size_t)floor((p->x[i] - out->gt[0]) / out->gt[1]);
        size_t row = (size_t)floor((p->y[i] - out->gt[3]) / out->gt[5]);
        assert_true(col < out->nx && row < out->ny);
        double e = ((double)out->z[row * out->nx + col] - p->z[i]) * (p->w ? p->w[i] : 1.0 / sigma);
        s += e * e;
    }
    return sqrt(s / (double)p->n);
}

/* The discrepancy principle (Morozov; recon_discrepancy.c) on real and synthetic elevations: with the
 * default lambda the RMS of (u - d) / sigma at the data is in [sqrt(1 - 0.06), 1] (its acceptance band),
 * for sigma = 1 and 5, for every method (the stochastic ones keep the data nodes at the smooth values);
 * per-point sigmas (weights) are fitted in the same sense; several points on one node count with their
 * scatter about the node's mean (and when it alone exceeds N, the node means are interpolated); a lambda that already fits within sigma is kept (the data are then
 * fitted much more closely). On noisy samples of a smooth surface the fit is closer to the truth than the
 * data are. */
static void test_discrepancy(void **state)
{
    (void)state;
    const double lo = sqrt(1.0 - 0.06) - 1e-4, hi = 1.0 + 1e-4;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ft_grid *volcano = NULL;
    assert_int_equal(ft_io_read_grid(FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", &ro, &volcano), 0);
    ft_grid *syn = fbm(128, 2.3, 21);
    const ft_grid *surf[2] = {volcano, syn};
    for (int k = 0; k < 2; k++) {
        ft_points *p = sample(surf[k], 0.08, 31);
        for (int si = 0; si < 2; si++) {
            double sigma = si == 0 ? 1.0 : 5.0;
            for (int m = 0; m < 3; m++) {
                ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
                o.method = (ft_recon_method)m;
                o.dim = 2.3;
                o.sigma = sigma;
                ft_recon_info info;
                ft_grid *out = recon(p, surf[k], &o, &info);
                double r = chi_rms(out, p, sigma);
                print_message("%s, %s, sigma %g: data RMS %.3f (RMS/sigma %.4f)\n", k ? "fBm" : "volcano",
                              ft_recon_method_name(o.method), sigma, info.data_rms, r);
                assert_true(r >= lo && r <= hi);
                assert_near(info.data_rms, r * sigma, 1e-3 * sigma);
                ft_grid_free(out);
            }
        }
        /* a lambda that fits already is kept: far inside sigma */
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = FT_RECON_SMOOTH;
        o.sigma = 1.0;
        o.lambda = 1e-4;
        ft_recon_info info;
        ft_grid *out = recon(p, surf[k], &o, &info);
        print_message("%s, smooth, sigma 1, lambda 1e-4: RMS/sigma %.4f\n", k ? "fBm" : "volcano",
                      chi_rms(out, p, 1.0));
        assert_true(chi_rms(out, p, 1.0) < 0.5);
        ft_grid_free(out);
        /* per-point sigmas 1 and 4 alternately */
        assert_int_equal(ft_points_ensure_weights(p), 0);
        for (size_t i = 0; i < p->n; i++)
            p->w[i] = i % 2 ? 0.25 : 1.0;
        out = recon(p, surf[k], &o, &info);
        print_message("%s, smooth, sigma 1 or 4: RMS/sigma %.4f\n", k ? "fBm" : "volcano", chi_rms(out, p, 1.0));
        ft_grid_free(out);
        o.lambda = 1.0;
        out = recon(p, surf[k], &o, &info);
        double r = chi_rms(out, p, 1.0);
        print_message("%s, smooth, sigma 1 or 4, default lambda: RMS/sigma %.4f\n", k ? "fBm" : "volcano", r);
        assert_true(r >= lo && r <= hi);
        ft_grid_free(out);
        ft_points_free(p);
    }
    /* two points on every data node, z +- 0.5 sigma: their scatter alone is chi² = N / 4 */
    ft_points *p = sample(syn, 0.08, 32), *q = ft_points_create(0);
    for (size_t i = 0; i < p->n; i++) {
        assert_int_equal(ft_points_push(q, p->x[i], p->y[i], p->z[i] + 2.5), 0);
        assert_int_equal(ft_points_push(q, p->x[i] + 1.0, p->y[i] - 1.0, p->z[i] - 2.5), 0);
    }
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = FT_RECON_SMOOTH;
    o.sigma = 5.0;
    ft_recon_info info;
    ft_grid *out = recon(q, syn, &o, &info);
    double r = chi_rms(out, q, 5.0);
    print_message("fBm, pairs z +- 2.5 on one node, sigma 5: RMS/sigma %.4f\n", r);
    assert_true(r >= lo && r <= hi);
    ft_grid_free(out);
    ft_points_free(q);
    /* z +- 1.5 sigma: the scatter alone is 2.25 N, no lambda satisfies the principle; the node means are
     * interpolated, so RMS / sigma = 1.5 */
    q = ft_points_create(0);
    for (size_t i = 0; i < p->n; i++) {
        assert_int_equal(ft_points_push(q, p->x[i], p->y[i], p->z[i] + 7.5), 0);
        assert_int_equal(ft_points_push(q, p->x[i] + 1.0, p->y[i] - 1.0, p->z[i] - 7.5), 0);
    }
    out = recon(q, syn, &o, &info);
    r = chi_rms(out, q, 5.0);
    print_message("fBm, pairs z +- 7.5 on one node, sigma 5: RMS/sigma %.5f\n", r);
    assert_near(r, 1.5, 1e-3);
    ft_grid_free(out);
    ft_points_free(q);
    ft_points_free(p);
    /* noisy samples (sd 5) of a smooth surface: the fit is nearer the truth than the data */
    ft_grid *smooth = fbm(128, 2.1, 22);
    ft_grid_sample_opts so = FT_GRID_SAMPLE_OPTS_DEFAULT;
    so.fraction = 0.08;
    so.seed = 33;
    so.noise_z = 5.0;
    p = NULL;
    assert_int_equal(ft_surface_points_from_grid(smooth, &so, &p), 0);
    out = recon(p, smooth, &o, &info);
    double et = 0.0, ed = 0.0;
    for (size_t i = 0; i < p->n; i++) {
        size_t col = (size_t)floor((p->x[i] - out->gt[0]) / out->gt[1]);
        size_t row = (size_t)floor((p->y[i] - out->gt[3]) / out->gt[5]), c = row * out->nx + col;
        et += pow((double)out->z[c] - (double)smooth->z[c], 2);
        ed += pow(p->z[i] - (double)smooth->z[c], 2);
    }
    et = sqrt(et / (double)p->n);
    ed = sqrt(ed / (double)p->n);
    print_message("D 2.1 + noise 5: RMS data - truth %.3f, fit - truth %.3f, data RMS %.3f\n", ed, et,
                  info.data_rms);
    assert_true(et < ed);
    ft_grid_free(out);
    ft_points_free(p);
    ft_grid_free(smooth);
    ft_grid_free(syn);
    ft_grid_free(volcano);
}

/* Realizations: the mean and the sd; sd is 0 at the data nodes and positive elsewhere; smooth has sd 0. */
static void test_realizations(void **state)
{
    (void)state;
    ft_grid *g = fbm(48, 2.5, 8);
    ft_points *p = sample(g, 0.15, 14);
    uint8_t *data = calloc(g->nx * g->ny, 1);
    for (size_t k = 0; k < p->n; k++) {
        size_t x = (size_t)((p->x[k] - 1000.0) / 10.0), y = (size_t)((2000.0 - p->y[k]) / 10.0);
        data[y * g->nx + x] = 1;
    }
    ft_points_push(p, 1e6, 1e6, 0.0); /* outside */
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.dim = 2.5;
    o.realizations = 5;
    ft_grid *mean = NULL, *sd = NULL;
    ft_recon_info info;
    int rc = ft_reconstruct_points(p, g, &o, &mean, &sd, &info);
    if (rc != 0)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, 0);
    assert_int_equal(info.data_outside, 1);
    assert_int_equal(info.data_used, p->n - 1);
    assert_near(info.k, FT_RECON_K_DEFAULT, 0.0);
    assert_true(info.temperature > 0.0 && info.sigma0 > 0.0);
    size_t free_nodes = 0, positive = 0;
    for (size_t i = 0; i < g->nx * g->ny; i++) {
        if (data[i]) {
            assert_near(sd->z[i], 0.0, 0.0);
            assert_near(mean->z[i], g->z[i], 1e-3);
        } else {
            free_nodes++;
            positive += sd->z[i] > 0.0f;
        }
    }
    assert_int_equal(positive, free_nodes);
    free(data);
    /* the mean of 5 runs is the mean of the 5 single runs with seeds seed .. seed + 4, to the solver's
     * tolerance: a single run solves u* and its sample in one solve, a batch solves u* once and each
     * sample apart (recon_perturb.c); 0.05 is 5e-4 of the surface's sd (measured 0.036; a realization of
     * another seed differs by metres) */
    double worst = 0.0;
    float *acc = calloc(g->nx * g->ny, sizeof *acc);
    for (int r = 0; r < 5; r++) {
        ft_recon_opts o1 = o;
        o1.realizations = 1;
        o1.seed = o.seed + (uint64_t)r;
        ft_grid *one = recon(p, g, &o1, NULL);
        for (size_t i = 0; i < g->nx * g->ny; i++)
            acc[i] += one->z[i] / 5.0f;
        ft_grid_free(one);
    }
    for (size_t i = 0; i < g->nx * g->ny; i++)
        worst = fmax(worst, fabs((double)acc[i] - (double)mean->z[i]));
    print_message("mean of 5 single runs - mean of a batch of 5: worst %.4f (sd 100)\n", worst);
    assert_true(worst < 0.05);
    free(acc);
    ft_grid_free(mean);
    ft_grid_free(sd);
    o.method = FT_RECON_SMOOTH;
    assert_int_equal(ft_reconstruct_points(p, g, &o, &mean, &sd, NULL), 0);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        assert_near(sd->z[i], 0.0, 0.0);
    ft_grid_free(mean);
    ft_grid_free(sd);
    ft_points_free(p);
    ft_grid_free(g);
}

/* Adds w g g' to the dense n x n matrix H for the difference g with coefficients cf at nodes idx. */
static void add_term(double *H, size_t n, const size_t *idx, const double *cf, int m, double w)
{
    for (int a = 0; a < m; a++)
        for (int b = 0; b < m; b++)
            H[idx[a] * n + idx[b]] += w * cf[a] * cf[b];
}

/* The Hessian of the prior energy of docs/terrain-reconstruct.md on an nx x ny grid, written from its
 * definition (not from the library's stencil): tp/2 [sum u_xx² + 2 sum u_xy² + sum u_yy²] + mem/2 sum of
 * the squared forward differences, only the differences that fit in the grid. */
static double *prior_hessian(size_t nx, size_t ny, double tp, double mem)
{
    size_t n = nx * ny;
    double *H = calloc(n * n, sizeof *H);
    assert_non_null(H);
    static const double second[3] = {1.0, -2.0, 1.0}, mixed[4] = {1.0, -1.0, -1.0, 1.0}, first[2] = {-1.0, 1.0};
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            size_t i = y * nx + x;
            if (x >= 1 && x + 1 < nx)
                add_term(H, n, (size_t[]){i - 1, i, i + 1}, second, 3, tp);
            if (y >= 1 && y + 1 < ny)
                add_term(H, n, (size_t[]){i - nx, i, i + nx}, second, 3, tp);
            if (x + 1 < nx && y + 1 < ny)
                add_term(H, n, (size_t[]){i, i + 1, i + nx, i + nx + 1}, mixed, 4, 2.0 * tp);
            if (x + 1 < nx)
                add_term(H, n, (size_t[]){i, i + 1}, first, 2, mem);
            if (y + 1 < ny)
                add_term(H, n, (size_t[]){i, i + nx}, first, 2, mem);
        }
    return H;
}

/* The restriction of the multilevel prior written from its definition (docs/terrain-reconstruct.md): a
 * level of m nodes along one axis has (m - 1) / 2 + 1 coarse nodes, coarse node I the weighted mean of fine
 * nodes 2I - 1, 2I, 2I + 1 (weights 1/2, 1, 1/2, those inside the axis only). Returns the mc x m matrix. */
static double *restriction_1d(size_t m, size_t *mc)
{
    *mc = (m - 1) / 2 + 1;
    double *r = calloc(*mc * m, sizeof *r);
    assert_non_null(r);
    for (size_t I = 0; I < *mc; I++) {
        double w[3] = {0.5, 1.0, 0.5}, sum = 0.0;
        for (long d = -1; d <= 1; d++) {
            long x = 2 * (long)I + d;
            if (x >= 0 && x < (long)m)
                sum += w[d + 1];
        }
        for (long d = -1; d <= 1; d++) {
            long x = 2 * (long)I + d;
            if (x >= 0 && x < (long)m)
                r[I * m + (size_t)x] = w[d + 1] / sum;
        }
    }
    return r;
}

/* Hessian of the fractal method's multilevel prior on an N x N grid: sum over levels l (while a level has
 * >= 3 nodes per side) of R_l' A_l R_l, A_l the thin plate 2^(-2Hl) tp plus the membrane 2^(-2Hl) 2^-l mem
 * on level l's nodes, R_l = the 2-D restriction (r x r) applied l times. */
static double *multilevel_hessian(size_t N, double H, double tp, double mem)
{
    size_t n = N * N;
    double *A = prior_hessian(N, N, tp, mem);
    double *R = malloc(n * n * sizeof *R); /* R_l, rows: level-l nodes, columns: fine nodes */
    assert_non_null(R);
    for (size_t i = 0; i < n * n; i++)
        R[i] = i % (n + 1) == 0 ? 1.0 : 0.0;
    size_t m = N;
    for (int l = 1;; l++) {
        size_t mc;
        double *r = restriction_1d(m, &mc);
        if (mc < 3) {
            free(r);
            break;
        }
        /* R <- (r x r) R */
        double *Rn = calloc(mc * mc * n, sizeof *Rn);
        assert_non_null(Rn);
        for (size_t J = 0; J < mc; J++)
            for (size_t I = 0; I < mc; I++)
                for (size_t y = 0; y < m; y++)
                    for (size_t x = 0; x < m; x++) {
                        double w = r[J * m + y] * r[I * m + x];
                        if (w != 0.0)
                            for (size_t k = 0; k < n; k++)
                                Rn[(J * mc + I) * n + k] += w * R[(y * m + x) * n + k];
                    }
        free(R);
        free(r);
        R = Rn;
        m = mc;
        double w = pow(2.0, -2.0 * H * l);
        double *Al = prior_hessian(m, m, w * tp, w * pow(0.5, l) * mem);
        size_t nl = m * m;
        double *AR = calloc(nl * n, sizeof *AR);
        assert_non_null(AR);
        for (size_t a = 0; a < nl; a++)
            for (size_t b = 0; b < nl; b++)
                if (Al[a * nl + b] != 0.0)
                    for (size_t k = 0; k < n; k++)
                        AR[a * n + k] += Al[a * nl + b] * R[b * n + k];
        for (size_t a = 0; a < nl; a++)
            for (size_t i = 0; i < n; i++)
                if (R[a * n + i] != 0.0)
                    for (size_t k = 0; k < n; k++)
                        A[i * n + k] += R[a * n + i] * AR[a * n + k];
        free(Al);
        free(AR);
    }
    free(R);
    return A;
}

/* diag((A_ff)^-1) of the free nodes (keep[i] != 0) of the dense A (n x n), by Cholesky; out[i] = 0 on the
 * others. */
static void inverse_diagonal(const double *A, const uint8_t *keep, size_t n, double *out)
{
    size_t m = 0, *id = malloc(n * sizeof *id);
    for (size_t i = 0; i < n; i++)
        if (keep[i])
            id[m++] = i;
    double *L = calloc(m * m, sizeof *L), *col = malloc(m * sizeof *col);
    assert_non_null(L);
    for (size_t j = 0; j < m; j++)
        for (size_t i = j; i < m; i++) {
            double s = A[id[i] * n + id[j]];
            for (size_t k = 0; k < j; k++)
                s -= L[i * m + k] * L[j * m + k];
            if (i == j) {
                assert_true(s > 0.0);
                L[j * m + j] = sqrt(s);
            } else {
                L[i * m + j] = s / L[j * m + j];
            }
        }
    memset(out, 0, n * sizeof *out);
    for (size_t c = 0; c < m; c++) { /* column c of A_ff^-1: L L' x = e_c */
        for (size_t i = 0; i < m; i++) {
            double s = i == c ? 1.0 : 0.0;
            for (size_t k = 0; k < i; k++)
                s -= L[i * m + k] * col[k];
            col[i] = s / L[i * m + i];
        }
        for (size_t i = m; i-- > 0;) {
            double s = col[i];
            for (size_t k = i + 1; k < m; k++)
                s -= L[k * m + i] * col[k];
            col[i] = s / L[i * m + i];
        }
        out[id[c]] = col[c];
    }
    free(id);
    free(L);
    free(col);
}

/* The fractal method samples the equilibrium of its prior conditioned on the data: over 600 realizations
 * the per-cell variance is lambda T (A_ff^-1)_ii, the posterior variance of the Gibbs distribution
 * exp(-E / (lambda T)) (Arakawa & Krotkov eq. 10), with A the multilevel prior's Hessian written out here
 * from the energy's definition (levels of 12², 6², 3² nodes; the single-level sampler of session 5 fails
 * it: its variance is that of level 0's energy alone). 24 x 24 nodes, data (fixed) on every 6th node, lambda 2, tension 0.4, T 3. The
 * sample variance of 600 draws has a relative error of about 6% per cell and 0.6% over the ~560 cells: the
 * test asks 2% on the mean ratio and 30% (5 sd) on every cell (measured 1.009 and 0.22). The old Gibbs sampler (1 relaxation + 2 Gibbs
 * sweeps per level) was not at equilibrium and fails it. */
static void test_fractal_equilibrium(void **state)
{
    (void)state;
    const size_t N = 24, n = N * N;
    const double lambda = 2.0, tau = 0.4, T = 3.0;
    ft_grid *g = fbm(N, 2.5, 21);
    ft_points *p = lattice_points(g, 6);
    uint8_t *keep = malloc(n);
    for (size_t y = 0; y < N; y++)
        for (size_t x = 0; x < N; x++)
            keep[y * N + x] = !(x % 6 == 1 && y % 6 == 1);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = FT_RECON_FRACTAL;
    o.dim = 2.5;
    o.tension = tau;
    o.lambda = lambda;
    o.temperature = T;
    o.realizations = 600;
    o.seed = 99;
    ft_grid *mean = NULL, *sd = NULL;
    int rc = ft_reconstruct_points(p, g, &o, &mean, &sd, NULL);
    if (rc != 0)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, 0);
    double *H = multilevel_hessian(N, 3.0 - o.dim, lambda * (1.0 - tau), lambda * tau);
    double *var = malloc(n * sizeof *var);
    inverse_diagonal(H, keep, n, var);
    double sum_s = 0.0, sum_e = 0.0, worst = 0.0;
    for (size_t i = 0; i < n; i++) {
        double s2 = (double)sd->z[i] * sd->z[i], e2 = lambda * T * var[i];
        if (!keep[i]) {
            assert_near(sd->z[i], 0.0, 0.0);
            continue;
        }
        sum_s += s2;
        sum_e += e2;
        worst = fmax(worst, fabs(s2 / e2 - 1.0));
    }
    print_message("fractal posterior variance, sampled / exact: mean %.4f, worst cell %.3f off\n", sum_s / sum_e,
                  worst);
    assert_true(fabs(sum_s / sum_e - 1.0) < 0.02);
    assert_true(worst < 0.3);
    free(H);
    free(var);
    free(keep);
    ft_grid_free(mean);
    ft_grid_free(sd);
    ft_points_free(p);
    ft_grid_free(g);
}

/* D estimated from the data when dim is 0; the output carries the target's georeferencing. */
static void test_dim_auto(void **state)
{
    (void)state;
    ft_grid *g = fbm(128, 2.5, 9);
    assert_int_equal(ft_grid_set_crs(g, "EPSG:32633"), 0);
    ft_points *p = sample(g, 0.1, 10);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = FT_RECON_CONDITIONAL;
    ft_recon_info info;
    ft_grid *out = recon(p, g, &o, &info);
    print_message("estimated D %.3f (true 2.5)\n", info.dim);
    assert_int_equal(info.dim_estimated, 1);
    assert_true(fabs(info.dim - 2.5) < 0.15);
    assert_memory_equal(out->gt, g->gt, sizeof g->gt);
    assert_non_null(out->crs_wkt);
    assert_null(out->mask);
    ft_grid_free(out);
    ft_points_free(p);
    ft_grid_free(g);
}

static int calls;
static int cancel_after_3(double frac, const char *msg, void *arg)
{
    (void)msg;
    (void)arg;
    assert_true(frac >= 0.0 && frac <= 1.0);
    return ++calls < 3;
}

static void test_cancel(void **state)
{
    (void)state;
    ft_grid *g = fbm(64, 2.5, 12);
    ft_points *p = sample(g, 0.05, 13);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.dim = 2.5;
    o.progress = cancel_after_3;
    for (int m = 0; m < 3; m++) {
        o.method = (ft_recon_method)m;
        calls = 0;
        ft_grid *out = (ft_grid *)1;
        assert_int_equal(ft_reconstruct_points(p, g, &o, &out, NULL, NULL), FT_E_CANCELLED);
        assert_null(out);
    }
    ft_points_free(p);
    ft_grid_free(g);
}

/* Voids of a real DEM: known cells bit-identical, voids filled, no mask; a DEM without voids is copied. */
static void test_voids_dem(void **state)
{
    (void)state;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ft_grid *dem = NULL;
    assert_int_equal(ft_io_read_grid(FT_TEST_DATA "/dem_luxembourg_terra_30s.tif", &ro, &dem), 0);
    ft_grid *holed = ft_grid_copy(dem);
    assert_int_equal(ft_grid_ensure_mask(holed), 0);
    size_t holes = 0, voids = 0; /* holes punched in valid cells; all voids (the DEM has nodata) */
    for (size_t y = 0; y < holed->ny; y++)
        for (size_t x = 0; x < holed->nx; x++) {
            size_t i = y * holed->nx + x;
            double a = (double)x - 40.0, b = (double)y - 45.0, c = (double)x - 60.0, d = (double)y - 60.0;
            if (ft_grid_is_valid(dem, x, y) && (a * a + b * b < 64.0 || c * c + d * d < 25.0 || (x == 30 && y == 50))) {
                holed->mask[i] = 0;
                holed->z[i] = -9999.0f;
                holes++;
            }
            voids += !holed->mask[i];
        }
    assert_true(holes > 200);
    for (int m = 0; m < 3; m++) {
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = (ft_recon_method)m;
        o.realizations = m == 0 ? 3 : 1;
        ft_grid *out = NULL, *sd = NULL;
        ft_recon_info info;
        int rc = ft_reconstruct_voids(holed, &o, &out, &sd, &info);
        if (rc != 0)
            print_error("%s\n", ft_last_error());
        assert_int_equal(rc, 0);
        assert_null(out->mask);
        assert_int_equal(info.filled, voids);
        assert_int_equal(info.data_used, holed->nx * holed->ny - voids);
        double zmin, zmax, err = 0.0;
        ft_grid_minmax(dem, &zmin, &zmax);
        size_t sd_pos = 0;
        for (size_t i = 0; i < dem->nx * dem->ny; i++) {
            if (holed->mask[i]) {
                assert_memory_equal(&out->z[i], &dem->z[i], sizeof(float));
                assert_near(sd->z[i], 0.0, 0.0);
            } else {
                sd_pos += sd->z[i] > 0.0f;
                if (dem->mask && !dem->mask[i])
                    continue;
                assert_true(out->z[i] > zmin - 0.5 * (zmax - zmin) && out->z[i] < zmax + 0.5 * (zmax - zmin));
                err += pow((double)out->z[i] - (double)dem->z[i], 2);
            }
        }
        print_message("%s: D %.3f (estimated %d), RMSE in the holes %.1f m (relief %.0f m)\n",
                      ft_recon_method_name(o.method), info.dim, info.dim_estimated, sqrt(err / (double)holes),
                      zmax - zmin);
        if (m == 0)
            assert_int_equal(sd_pos, voids);
        ft_grid_free(out);
        ft_grid_free(sd);
    }
    ft_grid *full = fbm(40, 2.5, 15), *out = NULL;
    ft_recon_info info;
    assert_int_equal(ft_reconstruct_voids(full, NULL, &out, NULL, &info), 0);
    assert_int_equal(info.filled, 0);
    assert_memory_equal(out->z, full->z, full->nx * full->ny * sizeof *full->z);
    ft_grid_free(out);
    ft_grid_free(full);
    ft_grid_free(holed);
    ft_grid_free(dem);
}

/* Mean |z(x + h) - z(x)| over the pairs h cells apart along rows and columns, h = 1 .. 32. */
static void mean_abs_increments(const ft_grid *g, double *s)
{
    for (size_t h = 1; h <= 32; h++) {
        double sum = 0.0, n = 0.0;
        for (size_t y = 0; y < g->ny; y++)
            for (size_t x = 0; x < g->nx; x++) {
                double z = g->z[y * g->nx + x];
                if (x + h < g->nx) {
                    sum += fabs(g->z[y * g->nx + x + h] - z);
                    n += 1.0;
                }
                if (y + h < g->ny) {
                    sum += fabs(g->z[(y + h) * g->nx + x] - z);
                    n += 1.0;
                }
            }
        s[h] += sum / n;
    }
}

/* Szeliski's eq. 7 blend, written out here: tau / (1 - tau) = 2 (D - 2) / (3 - D). */
static double eq7_tension(double D)
{
    double r = 2.0 * (D - 2.0) / (3.0 - D);
    return r / (1.0 + r);
}

/* Exact fBm plus white noise carrying `share` of the one-cell increment variance: a surface whose
 * structure function bends below its power law at the smallest lags (as SRA surfaces and real DEMs do). */
static ft_grid *fbm_nugget(size_t n, double D, uint64_t seed, double share)
{
    ft_grid *g = fbm(n, D, seed);
    double v = 0.0, c = 0.0;
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x + 1 < n; x++) {
            double a = g->z[y * n + x + 1] - g->z[y * n + x], b = g->z[(x + 1) * n + y] - g->z[x * n + y];
            v += a * a + b * b;
            c += 2.0;
        }
    double sd = sqrt(share * (v / c) / (2.0 * (1.0 - share)));
    ft_rng *r = ft_rng_create(seed, 9);
    for (size_t k = 0; k < n * n; k++)
        g->z[k] = (float)(g->z[k] + ft_rng_gaussian(r, sd));
    ft_rng_free(r);
    return g;
}

/* The largest |S_rec(h) / S_orig(h) - 1| over lags 1 .. 32 of the conditional reconstruction of 2 seeds of
 * exact fBm (share 0) or fBm plus white noise (256², every 4th cell plus a random 5%). */
static double structure_worst(ft_recon_method m, double D, double share, uint64_t seed0)
{
    double so[33] = {0}, sr[33] = {0};
    for (uint64_t s = 0; s < 2; s++) {
        ft_grid *g = share > 0.0 ? fbm_nugget(256, D, seed0 + s, share) : fbm(256, D, seed0 + s);
        ft_points *p = ft_points_create(0);
        ft_rng *r = ft_rng_create(800 + s, 1);
        for (size_t y = 0; y < g->ny; y++)
            for (size_t x = 0; x < g->nx; x++)
                if ((x % 4 == 0 && y % 4 == 0) | (ft_rng_uniform(r) < 0.05)) {
                    double cx, cy;
                    ft_grid_cell_center(g, (double)x, (double)y, &cx, &cy);
                    assert_int_equal(ft_points_push(p, cx, cy, g->z[y * g->nx + x]), 0);
                }
        ft_rng_free(r);
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = m;
        o.dim = D;
        o.seed = 0x5eed0000 + s;
        ft_recon_info info;
        ft_grid *out = recon(p, g, &o, &info);
        if (m == FT_RECON_CONDITIONAL)
            assert_true(fabs(info.tension - eq7_tension(D)) < 1e-12);
        mean_abs_increments(g, so);
        mean_abs_increments(out, sr);
        ft_grid_free(out);
        ft_points_free(p);
        ft_grid_free(g);
    }
    double worst = 0.0;
    size_t at = 0;
    for (size_t h = 1; h <= 32; h++)
        if (fabs(sr[h] / so[h] - 1.0) > worst) {
            worst = fabs(sr[h] / so[h] - 1.0);
            at = h;
        }
    print_message("%s D %.1f, white share %.2f: mean |dz| reconstruction / original: lag 1 %.3f, 2 %.3f, 4 %.3f, "
                  "32 %.3f, worst %.3f at lag %zu\n", ft_recon_method_name(m), D, share, sr[1] / so[1], sr[2] / so[2], sr[4] / so[4],
                  sr[32] / so[32], worst, at);
    return worst;
}

/* The fractal reconstruction (multilevel prior; 256², every 4th cell plus a random 5%) has the original's
 * mean |dz| within 5% at every lag from 1 to 32 cells (2 seeds) at D 2.2, 2.5 and 2.8 on exact fBm (the
 * single-level prior of session 5 read 0.138 at D 2.8: lags 2-8 at 1.11-1.14). The conditional
 * reconstruction (same design) has the original's mean |dz|
 * within 5% at every lag from 1 to 32 cells (2 seeds), with the blend D gives, on exact fBm and on fBm
 * whose one-cell increments carry a white share of 0.4 at D 2.5 and 2.8 (its amplitude and white share
 * come from the data's own pairs 1 and 2 cells apart; the Yokoya line extrapolated to one cell with a
 * pure fBm missed these by 0.065 and 0.083, worst lag); the smooth method's blend follows a given D (its
 * grids differ) and stays the fixed one without it. */
static void test_structure_function(void **state)
{
    (void)state;
    static const double dims[] = {2.2, 2.5, 2.8};
    int bad = 0;
    for (size_t i = 0; i < 3; i++) {
        bad += !(structure_worst(FT_RECON_CONDITIONAL, dims[i], 0.0, 700) <= 0.05);
        if (i > 0)
            bad += !(structure_worst(FT_RECON_CONDITIONAL, dims[i], 0.4, 710) <= 0.05);
    }
    for (size_t i = 0; i < 3; i++)
        bad += !(structure_worst(FT_RECON_FRACTAL, dims[i], 0.0, 700) <= 0.05);
    assert_int_equal(bad, 0);

    ft_grid *t = target(64, 64), *g = fbm(64, 2.5, 5);
    ft_points *p = lattice_points(g, 4);
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = FT_RECON_SMOOTH;
    ft_recon_info i0, i2, i8;
    ft_grid *a = recon(p, t, &o, &i0);
    o.dim = 2.2;
    ft_grid *b = recon(p, t, &o, &i2);
    o.dim = 2.8;
    ft_grid *c = recon(p, t, &o, &i8);
    assert_true(fabs(i0.tension - 0.1) < 1e-12);
    assert_true(fabs(i2.tension - eq7_tension(2.2)) < 1e-12 && fabs(i8.tension - eq7_tension(2.8)) < 1e-12);
    double diff = 0.0;
    for (size_t k = 0; k < 64 * 64; k++)
        diff = fmax(diff, fabs(b->z[k] - c->z[k]));
    assert_true(diff > 1.0); /* z sd 100: the blends of D 2.2 and 2.8 interpolate differently */
    ft_grid_free(a);
    ft_grid_free(b);
    ft_grid_free(c);
    ft_points_free(p);
    ft_grid_free(g);
    ft_grid_free(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names),          cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_reproducible),   cmocka_unit_test(test_smooth_plane),
        cmocka_unit_test(test_smooth_paraboloid), cmocka_unit_test(test_fidelity),
        cmocka_unit_test(test_discrepancy),
        cmocka_unit_test(test_realizations),   cmocka_unit_test(test_dim_auto),
        cmocka_unit_test(test_cancel),         cmocka_unit_test(test_voids_dem),
        cmocka_unit_test(test_structure_function), cmocka_unit_test(test_fractal_equilibrium),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
