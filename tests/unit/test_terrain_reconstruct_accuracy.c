/* fracterra — accuracy tests of the reconstruction (docs/terrain-reconstruct.md):
 *  - a reduced Table 4 of Arakawa & Krotkov (eq. 11): SRA surfaces of D = 2.3, 2.5, 2.7 (256², 3 seeds),
 *    the subset every 4th cell plus a random 5%, D* = Est(Syn(D)) and D^ = Est(Rec(Sub(Syn(D)))) with
 *    Est = Yokoya's grid estimator over its default lags (1 .. 32 cells, whole-range fit) and, for the
 *    fractal method, over lags 1 .. 16 too. Bounds, from the full runs in the docs: fractal mean
 *    |D* - D^| <= 0.02 at lags 1-16 and at lags 1-32 (sigma0 from the data's shortest lags: +0.000 /
 *    -0.001 / +0.000 and +0.007 / +0.009 / +0.003 here; with the default lag range, whose lags 4 and 8
 *    are SRA's coarse-lattice pairs, 1-32 read +0.018 .. +0.023 and failed 0.02 at D 2.5;
 *    docs/terrain-reconstruct.md);
 *    conditional <= 0.02 on exact fBm surfaces (D = 2.5 here; measured <= 0.011 over 2.2 .. 2.8) and <= 0.05 on SRA ones (measured
 *    <= 0.038: SRA is not an exact fBm and its lattice is the data's); smooth D^ < D* - 0.05 (the paper's
 *    effect; measured -0.08 .. -0.16);
 *  - void filling: 9 round holes up to 51 cells across (~10% of a 256² fBm of D = 2.5): the filled
 *    holes' D (Yokoya on each hole's square window, averaged) within 0.05 of the original's on the same
 *    windows for fractal and conditional, and no seam: the mean |one-cell difference| across the hole
 *    borders within a factor 1.25 of that inside the holes and of the terrain around them.
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

#include "fracterra/surface.h"
#include "fracterra/terrain.h"
#include "ft_test_assert.h"

static ft_grid *synth(ft_synth_method m, size_t n, double D, uint64_t seed)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = m;
    o.dim = D;
    o.seed = seed;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(n, n, &o, &g), 0);
    return g;
}

/* Est: Yokoya over the lags 1 .. max_lag cells (0: its default, N/8), least squares over all of them. */
static double est_to(const ft_grid *g, double max_lag)
{
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.fit_whole_range = 1;
    o.max_scale = max_lag * fabs(g->gt[1]);
    o.noise.mode = -1; /* the paper's estimator: these surfaces are noise-free, and a nugget "detected" on
                          one of them would move D* or D^ by the model, not by the reconstruction */
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim(g, FT_SURFACE_YOKOYA, &o, &r), 0);
    double D = r->D;
    ft_dim_result_free(r);
    return D;
}

static double est(const ft_grid *g)
{
    return est_to(g, 0.0);
}

/* Sub: every 4th cell in each direction plus a random 5% of the cells. */
static ft_points *subset(const ft_grid *g, uint64_t seed)
{
    ft_points *p = ft_points_create(0);
    ft_rng *r = ft_rng_create(seed, 77);
    for (size_t y = 0; y < g->ny; y++)
        for (size_t x = 0; x < g->nx; x++)
            if ((x % 4 == 0 && y % 4 == 0) | (ft_rng_uniform(r) < 0.05)) {
                double cx, cy;
                ft_grid_cell_center(g, (double)x, (double)y, &cx, &cy);
                assert_int_equal(ft_points_push(p, cx, cy, g->z[y * g->nx + x]), 0);
            }
    ft_rng_free(r);
    return p;
}

/* Mean over seeds of D^ - D* for one method, Est over lags 1-32 (and in *diff16, if not NULL, 1-16). */
static double table4_row(ft_synth_method syn, double D, ft_recon_method m, int nseeds, double *Dstar,
                         double *diff16)
{
    double diff = 0.0, ds = 0.0, d16 = 0.0;
    for (int s = 0; s < nseeds; s++) {
        ft_grid *g = synth(syn, 256, D, (uint64_t)(1000 + s));
        ft_points *p = subset(g, (uint64_t)(2000 + s));
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = m;
        o.dim = D;
        o.seed = (uint64_t)(3000 + s);
        ft_grid *out = NULL;
        int rc = ft_reconstruct_points(p, g, &o, &out, NULL, NULL);
        if (rc != 0)
            print_error("%s\n", ft_last_error());
        assert_int_equal(rc, 0);
        double a = est(g), b = est(out);
        ds += a;
        diff += b - a;
        if (diff16)
            d16 += est_to(out, 16.0) - est_to(g, 16.0);
        ft_grid_free(out);
        ft_points_free(p);
        ft_grid_free(g);
    }
    *Dstar = ds / nseeds;
    if (diff16)
        *diff16 = d16 / nseeds;
    return diff / nseeds;
}

static void test_table4(void **state)
{
    (void)state;
    static const double dims[] = {2.3, 2.5, 2.7};
    int bad = 0;
    for (size_t i = 0; i < 3; i++) {
        double Ds, f16, f = table4_row(FT_SYNTH_SRA_RAW, dims[i], FT_RECON_FRACTAL, 3, &Ds, &f16);
        double c = table4_row(FT_SYNTH_SRA_RAW, dims[i], FT_RECON_CONDITIONAL, 3, &Ds, NULL);
        double s = table4_row(FT_SYNTH_SRA_RAW, dims[i], FT_RECON_SMOOTH, 3, &Ds, NULL);
        double Dse = 0.0, ce = i == 1 ? table4_row(FT_SYNTH_EXACT, dims[i], FT_RECON_CONDITIONAL, 3, &Dse, NULL) : 0.0;
        print_message("D %.1f: SRA D* %.3f, D^ - D*: fractal %+.4f (lags 1-16 %+.4f) conditional %+.4f smooth "
                      "%+.4f; exact fBm D* %.3f, conditional %+.4f\n", dims[i], Ds, f, f16, c, s, Dse, ce);
        bad += !(fabs(f16) <= 0.02);
        bad += !(fabs(f) <= 0.02);
        bad += !(fabs(c) <= 0.05);
        bad += !(s < -0.05);
        bad += !(fabs(ce) <= 0.02);
    }
    assert_int_equal(bad, 0);
}

/* Yokoya D of the square window of side w centred at (cx, cy). */
static double window_D(const ft_grid *g, size_t cx, size_t cy, size_t w)
{
    ft_grid *s = ft_grid_create(w, w);
    for (size_t y = 0; y < w; y++)
        for (size_t x = 0; x < w; x++)
            s->z[y * w + x] = g->z[(cy - w / 2 + y) * g->nx + cx - w / 2 + x];
    double D = est(s);
    ft_grid_free(s);
    return D;
}

static void test_voids(void **state)
{
    (void)state;
    const size_t n = 256;
    static const int holes[9][3] = {{60, 60, 25}, {180, 70, 20}, {70, 180, 15}, {190, 190, 15}, {128, 128, 12},
                                    {30, 140, 10},  {140, 25, 10},  {225, 130, 12}, {120, 225, 8}};
    ft_grid *g = synth(FT_SYNTH_EXACT, n, 2.5, 21), *holed = ft_grid_copy(g);
    assert_int_equal(ft_grid_ensure_mask(holed), 0);
    size_t nvoid = 0;
    for (size_t y = 0; y < n; y++)
        for (size_t x = 0; x < n; x++)
            for (int h = 0; h < 9; h++) {
                double dx = (double)x - holes[h][0], dy = (double)y - holes[h][1];
                if (dx * dx + dy * dy <= holes[h][2] * holes[h][2] && holed->mask[y * n + x]) {
                    holed->mask[y * n + x] = 0;
                    nvoid++;
                }
            }
    print_message("voids: %zu cells (%.1f%%)\n", nvoid, 100.0 * (double)nvoid / (double)(n * n));
    assert_true(nvoid > n * n / 12 && nvoid < n * n / 8);
    double Dtruth = 0.0;
    for (int h = 0; h < 9; h++)
        Dtruth += window_D(g, (size_t)holes[h][0], (size_t)holes[h][1], 2 * (size_t)holes[h][2] + 1) / 9.0;
    for (int m = 0; m < 3; m++) {
        ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
        o.method = (ft_recon_method)m;
        ft_grid *out = NULL;
        ft_recon_info info;
        assert_int_equal(ft_reconstruct_voids(holed, &o, &out, NULL, &info), 0);
        double Dfill = 0.0;
        for (int h = 0; h < 9; h++)
            Dfill += window_D(out, (size_t)holes[h][0], (size_t)holes[h][1], 2 * (size_t)holes[h][2] + 1) / 9.0;
        /* one-cell differences: across the border (one cell a void), inside the voids, outside them */
        double s[3] = {0, 0, 0}, c[3] = {0, 0, 0};
        for (size_t y = 0; y + 1 < n; y++)
            for (size_t x = 0; x + 1 < n; x++)
                for (int dir = 0; dir < 2; dir++) {
                    size_t i = y * n + x, j = dir ? i + n : i + 1;
                    int k = holed->mask[i] != holed->mask[j] ? 0 : holed->mask[i] ? 2 : 1;
                    s[k] += fabs((double)out->z[j] - (double)out->z[i]);
                    c[k] += 1.0;
                }
        double border = s[0] / c[0], inside = s[1] / c[1], outside = s[2] / c[2];
        print_message("%s (D %.3f%s): filled windows' D %.3f, original %.3f; mean |dz| border %.3f inside %.3f "
                      "outside %.3f\n", ft_recon_method_name(o.method), info.dim, info.dim_estimated ? " estimated" : "",
                      Dfill, Dtruth, border, inside, outside);
        if (o.method != FT_RECON_SMOOTH) {
            assert_true(fabs(Dfill - Dtruth) <= 0.05);
            assert_true(border / inside <= 1.25 && inside / border <= 1.25);
            assert_true(border / outside <= 1.25 && outside / border <= 1.25);
        } else {
            assert_true(Dfill < Dtruth - 0.1); /* the smooth fill, for contrast */
        }
        ft_grid_free(out);
    }
    ft_grid_free(holed);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_table4),
        cmocka_unit_test(test_voids),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
