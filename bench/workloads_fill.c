/* fracterra — workloads_fill.c: void filling (ft_terrain_fill, docs/terrain-fill.md) in
 * `make bench`, against GDAL's FillNodata (GDALFillNodata: inverse-distance interpolation from the void's
 * edges, max search distance larger than any void, no smoothing passes) as the in-process peer on the same
 * voids.
 *
 *  - fill.voids100.1024: a 1024² exact fBm (D = 2.5, sd 100) with 100 rectangular voids of 8..38 cells a
 *    side at seeded positions (about 5% of the cells), one conditional realization, ONE thread (the
 *    issue's target: under 1 s);
 *  - fill.mean.1024: the same voids, the kriging mean (--mean);
 *  - fill.voids1pct.4096: a 4096² spectral fBm (D = 2.5) with 100 voids of 16..66 cells a side (about 1%),
 *    one realization, ONE thread (target: under 5 s).
 * Setup (in a child, untimed) also fills the 1024² voids once with each side and prints the accuracy: the
 * D of the filled cells and of the truth in the same cells (variogram over lags 1-8 cells, pairs inside
 * the voids) and the RMSE of the kriging mean and of GDAL's fill against the truth.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <gdal.h>
#include <gdal_alg.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"

#define FILL_SEED UINT64_C(20261125)
#define FILL_DIM 2.5
#define NVOIDS 100

static ft_grid *held_truth, *held_dem; /* in the child only */
static float *held_band;               /* the peer's input/output buffer */

/* The n x n surface and its voids: 100 rectangles with sides in [lo, hi] at seeded positions. */
static int make_input(size_t n, ft_grid **truth, ft_grid **dem)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.method = n <= 1024 ? FT_SYNTH_EXACT : FT_SYNTH_FFT;
    so.dim = FILL_DIM;
    so.sigma = 100.0;
    so.seed = FILL_SEED;
    int rc = ft_terrain_synth(n, n, &so, truth);
    if (rc != FT_OK)
        return rc;
    if ((*dem = ft_grid_copy(*truth)) == NULL || ft_grid_ensure_mask(*dem) != FT_OK)
        return FT_E_NOMEM;
    size_t lo = n <= 1024 ? 8 : 16, hi = n <= 1024 ? 38 : 66;
    ft_rng *r = ft_rng_create(FILL_SEED, 14);
    if (r == NULL)
        return FT_E_NOMEM;
    for (int k = 0; k < NVOIDS; k++) {
        size_t w = lo + ft_rng_uint(r, hi - lo + 1), h = lo + ft_rng_uint(r, hi - lo + 1);
        size_t x0 = 4 + ft_rng_uint(r, n - w - 8), y0 = 4 + ft_rng_uint(r, n - h - 8);
        for (size_t y = y0; y < y0 + h; y++)
            memset((*dem)->mask + y * n + x0, 0, w);
    }
    ft_rng_free(r);
    return FT_OK;
}

static int prepare_n(ft_bench_case *c, size_t n)
{
    omp_set_num_threads(1);
    int rc = make_input(n, &held_truth, &held_dem);
    c->work = (double)n * (double)n;
    return rc;
}

static int prepare_1024(ft_bench_case *c)
{
    return prepare_n(c, 1024);
}

static int prepare_4096(ft_bench_case *c)
{
    return prepare_n(c, 4096);
}

static int fill(int mean, ft_grid **out)
{
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    o.mean = mean;
    o.seed = FILL_SEED + 1;
    return ft_terrain_fill(held_dem, NULL, &o, out, NULL, NULL);
}

static int run_real(ft_bench_case *c)
{
    (void)c;
    ft_grid *out = NULL;
    int rc = fill(0, &out);
    ft_grid_free(out);
    return rc;
}

static int run_mean(ft_bench_case *c)
{
    (void)c;
    ft_grid *out = NULL;
    int rc = fill(1, &out);
    ft_grid_free(out);
    return rc;
}

/* ---- the peer: GDALFillNodata on a MEM band ---- */

static GDALDatasetH peer_ds;

static int peer_prepare_n(ft_bench_case *c, size_t n)
{
    int rc = prepare_n(c, n);
    if (rc != FT_OK)
        return rc;
    GDALAllRegister();
    peer_ds = GDALCreate(GDALGetDriverByName("MEM"), "", (int)n, (int)n, 1, GDT_Float32, NULL);
    held_band = malloc(n * n * sizeof *held_band);
    if (peer_ds == NULL || held_band == NULL)
        return ft_error(FT_E_NOMEM, "GDAL MEM dataset of %zu x %zu", n, n);
    for (size_t i = 0; i < n * n; i++)
        held_band[i] = held_dem->mask[i] ? held_dem->z[i] : -9999.0f;
    GDALRasterBandH b = GDALGetRasterBand(peer_ds, 1);
    if (GDALRasterIO(b, GF_Write, 0, 0, (int)n, (int)n, held_band, (int)n, (int)n, GDT_Float32, 0, 0) != CE_None ||
        GDALSetRasterNoDataValue(b, -9999.0) != CE_None)
        return ft_error(FT_E_IO, "GDAL: %s", CPLGetLastErrorMsg());
    return FT_OK;
}

static int peer_prepare_1024(ft_bench_case *c)
{
    return peer_prepare_n(c, 1024);
}

static int peer_prepare_4096(ft_bench_case *c)
{
    return peer_prepare_n(c, 4096);
}

static int peer_run(ft_bench_case *c)
{
    (void)c;
    GDALRasterBandH b = GDALGetRasterBand(peer_ds, 1);
    int n = GDALGetRasterBandXSize(b);
    return GDALFillNodata(b, NULL, (double)n, 0, 0, NULL, NULL, NULL) == CE_None
               ? FT_OK
               : ft_error(FT_E_IO, "GDALFillNodata: %s", CPLGetLastErrorMsg());
}

/* ---- accuracy, printed once by setup ---- */

/* D = 3 - slope / 2 of log mean squared difference on log lag, lags 1..8 along rows and columns, both
 * cells in the voids. */
static double voids_D(const float *z, const uint8_t *mask, size_t n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t h = 1; h <= 8; h++) {
        double s = 0.0, c = 0.0;
        for (size_t y = 0; y < n; y++)
            for (size_t x = 0; x < n; x++) {
                size_t i = y * n + x;
                if (mask[i])
                    continue;
                if (x + h < n && !mask[i + h]) {
                    s += ((double)z[i + h] - z[i]) * ((double)z[i + h] - z[i]);
                    c++;
                }
                if (y + h < n && !mask[i + h * n]) {
                    s += ((double)z[i + h * n] - z[i]) * ((double)z[i + h * n] - z[i]);
                    c++;
                }
            }
        double lx = log((double)h), ly = log(s / c);
        sx += lx;
        sy += ly;
        sxx += lx * lx;
        sxy += lx * ly;
    }
    return 3.0 - (8.0 * sxy - sx * sy) / (8.0 * sxx - sx * sx) / 2.0;
}

static int report_accuracy(void *arg)
{
    (void)arg;
    ft_bench_case c;
    int rc = peer_prepare_n(&c, 1024);
    ft_grid *real = NULL, *mean = NULL;
    if (rc == FT_OK)
        rc = fill(0, &real);
    if (rc == FT_OK)
        rc = fill(1, &mean);
    if (rc == FT_OK)
        rc = peer_run(&c);
    GDALRasterBandH b = rc == FT_OK ? GDALGetRasterBand(peer_ds, 1) : NULL;
    if (b && GDALRasterIO(b, GF_Read, 0, 0, 1024, 1024, held_band, 1024, 1024, GDT_Float32, 0, 0) != CE_None)
        rc = ft_error(FT_E_IO, "GDAL: %s", CPLGetLastErrorMsg());
    if (rc == FT_OK) {
        const uint8_t *m = held_dem->mask;
        double em = 0.0, eg = 0.0, cnt = 0.0;
        for (size_t i = 0; i < 1024 * 1024; i++)
            if (!m[i]) {
                em += pow((double)mean->z[i] - held_truth->z[i], 2);
                eg += pow((double)held_band[i] - held_truth->z[i], 2);
                cnt++;
            }
        double Dt = voids_D(held_truth->z, m, 1024);
        fprintf(stderr, "fill 1024², %.0f void cells (%.1f%%), true D %.2f (%.3f in the voids): D of the fill "
                "%.3f (error %+.3f), of GDAL FillNodata %.3f (error %+.3f); RMSE of the kriging mean %.2f, of "
                "GDAL %.2f\n", cnt, 100.0 * cnt / (1024.0 * 1024.0), FILL_DIM, Dt, voids_D(real->z, m, 1024),
                voids_D(real->z, m, 1024) - FILL_DIM, voids_D(held_band, m, 1024),
                voids_D(held_band, m, 1024) - FILL_DIM, sqrt(em / cnt), sqrt(eg / cnt));
    }
    return rc;
}

static int setup_1024(ft_bench_case *c)
{
    c->work = 1024.0 * 1024.0;
    c->peer_prepare = peer_prepare_1024;
    c->peer_run = peer_run;
    c->peer_label = "GDALFillNodata (max distance 1024, no smoothing), in process";
    return ft_bench_in_child(report_accuracy, NULL);
}

static int setup_1024_mean(ft_bench_case *c)
{
    c->work = 1024.0 * 1024.0;
    c->peer_prepare = peer_prepare_1024;
    c->peer_run = peer_run;
    c->peer_label = "GDALFillNodata (max distance 1024, no smoothing), in process";
    return FT_OK;
}

static int setup_4096(ft_bench_case *c)
{
    c->work = 4096.0 * 4096.0;
    c->peer_prepare = peer_prepare_4096;
    c->peer_run = peer_run;
    c->peer_label = "GDALFillNodata (max distance 4096, no smoothing), in process";
    return FT_OK;
}

static const ft_bench_workload fill_workloads[] = {
    {"fill.voids100.1024", "fill 100 voids (about 5%) of a 1024x1024 fBm, one realization, one thread",
     FT_BENCH_CELLS, setup_1024, prepare_1024, run_real, NULL},
    {"fill.mean.1024", "the same voids, kriging mean, one thread", FT_BENCH_CELLS, setup_1024_mean, prepare_1024,
     run_mean, NULL},
    {"fill.voids1pct.4096", "fill 100 voids (about 1%) of a 4096x4096 fBm, one realization, one thread",
     FT_BENCH_CELLS, setup_4096, prepare_4096, run_real, NULL},
};

const ft_bench_suite ft_bench_suite_fill = {"fill", fill_workloads, sizeof fill_workloads / sizeof fill_workloads[0]};
