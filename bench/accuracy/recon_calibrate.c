/* fracterra — bench/accuracy/recon_calibrate.c: the eq. 11 calibration of k and the Table 4 experiment of
 * Arakawa & Krotkov §3.3-3.4 for ft_reconstruct_points (docs/terrain-reconstruct.md).
 *
 *   Syn(D): ft_terrain_synth, SRA, N x N, unit standard deviation, seed s
 *   Sub:    every 4th cell in each direction plus a random 5% of the cells (cell centres, exact values)
 *   Rec:    ft_reconstruct_points on the same grid, method fractal / conditional / smooth, D given
 *           (--dim-from data: D estimated from the sample, the library's default when D is unknown; the
 *           raw SRA's parameter D is not its dimension: D* is 2.35 at D = 2.2, 2.77 at 2.8;
 *           --sigma0 surface: the fractal method's T rescaled by (sigma0 of every cell / sigma0 of the data)²,
 *           what a perfect amplitude estimator would give; the row prints the mean sigma0_data/sigma0_surface)
 *   Est:    ft_surface_dim with method yokoya over its default range, lags 1 .. N/8 cells, least squares over
 *           the whole range (fit_whole_range: the ILS segmentation would fit different sub-ranges on the
 *           original and on the reconstruction, and on a smooth one drop exactly the too-steep small lags
 *           that eq. 11 is about)
 * prints D, D* = Est(Syn(D)), D^ = Est(Rec(Sub(Syn(D)))) and |D* - D^| per method, averaged over seeds.
 * With --scan K0,K1,... it repeats the fractal rows for each k (the calibration: the k that minimizes the
 * mean |D* - D^| at D = 2.4).
 *
 * Built by CMake (not run by make accuracy: it takes long); run from the source tree:
 *   build/fracterra_accuracy_recon_calibrate --size 256 --seeds 8 --dims 2.2,2.3,2.4,2.5,2.6,2.7,2.8
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fracterra/fracterra.h"
#include "accuracy_util.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double est_max_lag; /* --max-lag: Est's largest lag in cells (0 = its default, N/8) */

static double yokoya(const ft_grid *g)
{
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.fit_whole_range = 1;
    o.max_scale = est_max_lag * fabs(g->gt[1]);
    o.noise.mode = -1; /* the paper's estimator on noise-free surfaces: no nugget model */
    ft_dim_result *r = NULL;
    if (ft_surface_dim(g, FT_SURFACE_YOKOYA, &o, &r) != FT_OK) {
        fprintf(stderr, "yokoya: %s\n", ft_last_error());
        exit(1);
    }
    double D = r->D;
    ft_dim_result_free(r);
    return D;
}

int main(int argc, char **argv)
{
    size_t size = 256;
    int seeds = 4, every = 4, threads = 0, dim_from_data = 0, surface_sigma0 = 0;
    double dims[16] = {2.2, 2.3, 2.4, 2.5, 2.6, 2.7, 2.8}, ks[32] = {0.0}, frac = 0.05, tension = -1.0;
    int nd = 7, nk = 1;
    const char *methods = "fractal,conditional,smooth";
    ft_synth_method synth = FT_SYNTH_SRA_RAW; /* the paper's data: Voss's SRA at H = 3 - D */
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--size") && i + 1 < argc)
            size = (size_t)atol(argv[++i]);
        else if (!strcmp(argv[i], "--seeds") && i + 1 < argc)
            seeds = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--dims") && i + 1 < argc)
            nd = accuracy_parse_list(argv[++i], dims, 16);
        else if (!strcmp(argv[i], "--scan") && i + 1 < argc)
            nk = accuracy_parse_list(argv[++i], ks, 32);
        else if (!strcmp(argv[i], "--methods") && i + 1 < argc)
            methods = argv[++i];
        else if (!strcmp(argv[i], "--every") && i + 1 < argc)
            every = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--fraction") && i + 1 < argc)
            frac = atof(argv[++i]);
        else if (!strcmp(argv[i], "--synth") && i + 1 < argc) {
            if (ft_synth_method_parse(argv[++i], &synth) != FT_OK)
                return 2;
        } else if (!strcmp(argv[i], "--tension") && i + 1 < argc)
            tension = atof(argv[++i]);
        else if (!strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--max-lag") && i + 1 < argc)
            est_max_lag = atof(argv[++i]);
        else if (!strcmp(argv[i], "--dim-from") && i + 1 < argc &&
                 (!strcmp(argv[i + 1], "nominal") || !strcmp(argv[i + 1], "data")))
            dim_from_data = !strcmp(argv[++i], "data");
        else if (!strcmp(argv[i], "--sigma0") && i + 1 < argc &&
                 (!strcmp(argv[i + 1], "data") || !strcmp(argv[i + 1], "surface")))
            surface_sigma0 = !strcmp(argv[++i], "surface");
        else {
            fprintf(stderr, "usage: recon_calibrate [--size N] [--seeds S] [--dims a,b] [--scan k1,k2] "
                            "[--methods fractal,conditional,smooth] [--every 4] [--fraction 0.05] [--tension t] [--synth sra-raw|sra|exact|fft] [--threads n] [--max-lag cells] [--dim-from nominal|data] [--sigma0 data|surface]\n");
            return 2;
        }
    }
    static const double paper[] = {0.060, 0.044, 0.026, 0.018, 0.017, 0.035, 0.056};
    printf("size %zu, %d seeds, synth %s, subset every %d + %.0f%%, D %s\n", size, seeds, ft_synth_method_name(synth),
           every, 100 * frac, dim_from_data ? "estimated from the sample" : "given (the synthesis's)");
    printf("%-12s %5s %8s %8s %8s %8s %8s %10s %7s %7s\n", "method", "D", "k", "D*", "D^", "|D*-D^|", "max",
           "T0", "paper", "sec");
    for (int di = 0; di < nd; di++) {
        double D = dims[di];
        int pi = (int)lround((D - 2.2) * 10);
        for (int mi = 0; mi < 3; mi++) {
            ft_recon_method m = (ft_recon_method)mi;
            if (!strstr(methods, ft_recon_method_name(m)))
                continue;
            for (int ki = 0; ki < (m == FT_RECON_FRACTAL ? nk : 1); ki++) {
                double sd_star = 0, sd_hat = 0, sabs = 0, smax = 0, T0 = 0, secs = 0, sdiff = 0, bias = 0;
                for (int s = 0; s < seeds; s++) {
                    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
                    so.method = synth;
                    so.dim = D;
                    so.seed = (uint64_t)(1000 + s);
                    ft_grid *g = NULL;
                    if (ft_terrain_synth(size, size, &so, &g) != FT_OK)
                        return 1;
                    ft_points *p = accuracy_subsample(g, (uint64_t)(2000 + s), frac, every);
                    ft_recon_opts ro = FT_RECON_OPTS_DEFAULT;
                    ro.method = m;
                    ro.dim = dim_from_data && m != FT_RECON_SMOOTH ? 0.0 : D;
                    ro.k = ks[ki];
                    ro.threads = threads;
                    if (tension >= 0.0)
                        ro.tension = tension;
                    ro.seed = (uint64_t)(3000 + s);
                    ft_grid *out = NULL;
                    ft_recon_info info;
                    if (surface_sigma0 && m == FT_RECON_FRACTAL)
                        bias += accuracy_use_surface_sigma0(g, p, &ro);
                    double t0 = now();
                    if (ft_reconstruct_points(p, g, &ro, &out, NULL, &info) != FT_OK) {
                        fprintf(stderr, "reconstruct: %s\n", ft_last_error());
                        return 1;
                    }
                    secs += now() - t0;
                    double Ds = yokoya(g), Dh = yokoya(out);
                    sd_star += Ds;
                    sd_hat += Dh;
                    sdiff += Dh - Ds;
                    sabs += fabs(Ds - Dh);
                    smax = fmax(smax, fabs(Ds - Dh));
                    T0 += info.temperature;
                    ft_grid_free(out);
                    ft_points_free(p);
                    ft_grid_free(g);
                }
                printf("%-12s %5.2f %8.3g %8.4f %8.4f %8.4f %8.4f %10.3g %7.3f %7.2f  (mean D^-D* %+.4f)",
                       ft_recon_method_name(m), D, m == FT_RECON_FRACTAL ? (ks[ki] > 0 ? ks[ki] : FT_RECON_K_DEFAULT) : 0.0,
                       sd_star / seeds, sd_hat / seeds, fabs(sd_star - sd_hat) / seeds, smax, T0 / seeds,
                       pi >= 0 && pi < 7 ? paper[pi] : NAN, secs / seeds, sdiff / seeds);
                if (bias > 0.0)
                    printf("  sigma0 data/surface %.3f", bias / seeds);
                printf("\n");
                fflush(stdout);
            }
        }
    }
    return 0;
}
