/* fracterra — bench/accuracy/accuracy.c: `make accuracy`, the experiment of Arakawa & Krotkov §2.5 and
 * Table 1 run on fracterra's estimator: keep a random 5% of the cells of 512² fractional Brownian surfaces
 * of known D = 2.1 ... 2.8, estimate D from the scattered points with Yokoya's method (§2.4), and print per
 * D the mean signed error, its standard deviation and the worst error in % of D over the surfaces, beside
 * the paper's Table 1; optionally with independent Gaussian noise on x, y and z at a signal-to-noise ratio
 * SNR = 20 log10(σ_S / σ_N) dB, σ_S the largest of the standard deviations of x, y and z.
 *
 *   fracterra_accuracy [--surfaces N] [--size N] [--fraction F] [--synth stein,exact,sra,fft] [--dims LIST]
 *                      [--snr LIST] [--noisy-only] [--z-only] [--jitter] [--method yokoya|pentland]
 *                      [--min-lag K] [--max-lag K] [--nlags N] [--eps E] [--fit-auto] [--noise-model]
 *                      [--no-nugget] [--zsd S] [--seed N]
 *
 * --synth stein (the default) is Stein's exact circulant embedding written here (fbm_circulant.c),
 * independent of fracterra's synthesis; --noisy-only skips the no-noise table; --z-only puts the noise
 * on z alone; --noise-model gives the estimator the true σ (x, y and z); --no-nugget turns its noise
 * model off. A row beats the paper when |mean error| minus one standard error of the mean is below the
 * paper's.
 *
 * Lags are given in multiples of the mean point spacing (the library's default unit); surfaces are
 * generated with standard deviation --zsd in cell units (default: size / sqrt(12), the standard deviation
 * of x and y over the grid, so that x, y and z share the largest standard deviation of the SNR).
 * docs/surface-points.md reports the runs.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fracterra/fracterra.h"

#include "accuracy_util.h"
#include "fbm_circulant.h"

#define MAX_DIMS 32
#define MAX_LIST 8

/* Table 1 of Arakawa & Krotkov: estimation error without noise, % of D, for D = 2.1 ... 2.8. */
static const double paper_error[8] = {8.00, 5.18, 3.17, 1.54, 0.28, 0.65, 1.48, 2.29};
/* With noise on x, y and z: mean error % at SNR 30, 25, 20 dB. */
static const double paper_snr[3][8] = {
    {8.15, 5.38, 3.20, 1.52, 0.27, 0.68, 1.47, 2.28},
    {9.16, 5.96, 3.50, 1.67, 0.35, 0.63, 1.42, 2.24},
    {13.59, 9.02, 5.42, 2.75, 0.88, 0.38, 1.31, 2.17},
};
/* The independent generator (fbm_circulant.c) in the synthesizer list. */
#define SYNTH_STEIN ((ft_synth_method)-1)

typedef struct {
    int surfaces, size, jitter, nlags, fit_auto, noise_model, z_only, no_nugget, noisy_only;
    double fraction, min_lag, max_lag, eps, zsd;
    uint64_t seed;
    ft_points_method method;
    ft_synth_method synth[MAX_LIST];
    int nsynth;
    double dims[MAX_DIMS];
    int ndims;
    double snr[MAX_LIST];
    int nsnr;
} args;

static int parse_args(int argc, char **argv, args *a)
{
    *a = (args){100, 512, 0, 0, 0, 0, 0, 0, 0, 0.05, 0.0, 0.0, 0.0, 0.0, 1, FT_POINTS_YOKOYA, {SYNTH_STEIN}, 1,
                {2.1, 2.2, 2.3, 2.4, 2.5, 2.6, 2.7, 2.8}, 8, {0}, 0};
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int takes = 1;
        if (strcmp(o, "--jitter") == 0) {
            a->jitter = 1;
            takes = 0;
        } else if (strcmp(o, "--fit-auto") == 0) {
            a->fit_auto = 1;
            takes = 0;
        } else if (strcmp(o, "--no-nugget") == 0) {
            a->no_nugget = 1;
            takes = 0;
        } else if (strcmp(o, "--noisy-only") == 0) {
            a->noisy_only = 1;
            takes = 0;
        } else if (strcmp(o, "--z-only") == 0) {
            a->z_only = 1;
            takes = 0;
        } else if (strcmp(o, "--noise-model") == 0) {
            a->noise_model = 1;
            takes = 0;
        } else if (v == NULL) {
            fprintf(stderr, "fracterra_accuracy: %s needs a value (see the header of bench/accuracy/accuracy.c)\n", o);
            return 2;
        } else if (strcmp(o, "--surfaces") == 0) {
            a->surfaces = atoi(v);
        } else if (strcmp(o, "--size") == 0) {
            a->size = atoi(v);
        } else if (strcmp(o, "--fraction") == 0) {
            a->fraction = atof(v);
        } else if (strcmp(o, "--min-lag") == 0) {
            a->min_lag = atof(v);
        } else if (strcmp(o, "--max-lag") == 0) {
            a->max_lag = atof(v);
        } else if (strcmp(o, "--nlags") == 0) {
            a->nlags = atoi(v);
        } else if (strcmp(o, "--eps") == 0) {
            a->eps = atof(v);
        } else if (strcmp(o, "--zsd") == 0) {
            a->zsd = atof(v);
        } else if (strcmp(o, "--seed") == 0) {
            a->seed = strtoull(v, NULL, 10);
        } else if (strcmp(o, "--dims") == 0) {
            a->ndims = accuracy_parse_list(v, a->dims, MAX_DIMS);
        } else if (strcmp(o, "--snr") == 0) {
            a->nsnr = accuracy_parse_list(v, a->snr, MAX_LIST);
        } else if (strcmp(o, "--method") == 0) {
            if (ft_points_method_parse(v, &a->method) != FT_OK) {
                fprintf(stderr, "fracterra_accuracy: %s\n", ft_last_error());
                return 2;
            }
        } else if (strcmp(o, "--synth") == 0) {
            char buf[128];
            snprintf(buf, sizeof buf, "%s", v);
            a->nsynth = 0;
            for (char *save = NULL, *t = strtok_r(buf, ",", &save); t && a->nsynth < MAX_LIST;
                 t = strtok_r(NULL, ",", &save))
                if (strcmp(t, "stein") == 0)
                    a->synth[a->nsynth++] = SYNTH_STEIN;
                else if (ft_synth_method_parse(t, &a->synth[a->nsynth++]) != FT_OK) {
                    fprintf(stderr, "fracterra_accuracy: %s\n", ft_last_error());
                    return 2;
                }
        } else {
            fprintf(stderr, "fracterra_accuracy: unknown option %s\n", o);
            return 2;
        }
        i += takes;
    }
    for (int k = 0; a->jitter && k < a->nsynth; k++)
        if (a->synth[k] == SYNTH_STEIN) {
            fprintf(stderr, "fracterra_accuracy: --jitter needs a fracterra synthesizer (--synth exact,sra,fft)\n");
            return 2;
        }
    if (!(a->zsd > 0.0))
        a->zsd = (double)a->size / sqrt(12.0);
    if (a->surfaces < 1 || a->size < 16 || !(a->fraction > 0.0 && a->fraction <= 1.0) || a->ndims < 1) {
        fprintf(stderr, "fracterra_accuracy: needs --surfaces >= 1, --size >= 16, --fraction in (0, 1]\n");
        return 2;
    }
    return 0;
}

static double sd_of(const double *v, size_t n)
{
    double m = 0.0, s = 0.0;
    for (size_t i = 0; i < n; i++)
        m += v[i];
    m /= (double)n;
    for (size_t i = 0; i < n; i++)
        s += (v[i] - m) * (v[i] - m);
    return sqrt(s / (double)n);
}

/* The estimate of one point set. NaN (message printed) on failure. */
static double estimate(const args *a, ft_points *p, double noise_xy, double noise_z, double D, int s)
{
    ft_points_dim_opts po = FT_POINTS_DIM_OPTS_DEFAULT;
    po.method = a->method;
    po.nlags = a->nlags;
    po.eps = a->eps;
    po.fit_auto = a->fit_auto;
    po.noise_sigma = a->noise_model ? noise_z : 0.0;
    po.noise_sigma_xy = a->noise_model ? noise_xy : 0.0;
    po.noise_mode = a->no_nugget ? -1 : 0;
    if (a->min_lag > 0.0 || a->max_lag > 0.0) {
        double x0, y0, x1, y1;
        ft_points_bbox(p, &x0, &y0, &x1, &y1);
        double spacing = sqrt((x1 - x0) * (y1 - y0) / (double)p->n);
        po.min_lag = a->min_lag * spacing;
        po.max_lag = a->max_lag * spacing;
    }
    ft_dim_result *r = NULL;
    double est = NAN;
    if (ft_surface_dim_points(p, &po, &r) == FT_OK) {
        est = r->D;
        if (getenv("FT_ACCURACY_VERBOSE") != NULL)
            fprintf(stderr, "D %.2f s %d: D %.4f range %.1f..%.1f nugget fitted %d applied %d c0 %.4g H %.3f "
                    "sigma_z %.3g xy %.3g F %.3g floor %.1f\n", D, s, r->D, r->range[0], r->range[1], r->nugget.fitted,
                    r->nugget.applied, r->nugget.c0, r->nugget.H, r->nugget.sigma_z, r->nugget.sigma_xy, r->nugget.F,
                    r->nugget.floor);
    }
    else
        fprintf(stderr, "fracterra_accuracy: D %.2f surface %d: %s\n", D, s, ft_last_error());
    ft_dim_result_free(r);
    return est;
}

/* One surface: synthesize, sample, add noise at snr (0 = none), estimate. NaN (message printed) on failure. */
static double one_fracterra(const args *a, ft_synth_method m, double D, int s, double snr)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.method = m;
    so.dim = D;
    so.sigma = a->zsd;
    so.seed = a->seed + (uint64_t)s;
    ft_grid *g = NULL;
    ft_points *p = NULL;
    double est = NAN;
    ft_grid_sample_opts go = FT_GRID_SAMPLE_OPTS_DEFAULT;
    go.fraction = a->fraction;
    go.jitter = a->jitter;
    go.seed = a->seed * 1000003u + (uint64_t)s;
    int rc = ft_terrain_synth((size_t)a->size, (size_t)a->size, &so, &g);
    if (rc == FT_OK && snr > 0.0) {
        /* σ_S: the largest standard deviation of x, y (uniform over the grid) and z (the surface's sd). */
        double sx = (double)a->size / sqrt(12.0), sz = a->zsd, sig = sx > sz ? sx : sz;
        go.noise_z = sig / pow(10.0, snr / 20.0);
        go.noise_xy = a->z_only ? 0.0 : go.noise_z;
    }
    if (rc == FT_OK)
        rc = ft_surface_points_from_grid(g, &go, &p);
    if (rc == FT_OK)
        est = estimate(a, p, go.noise_xy, go.noise_z, D, s);
    else
        fprintf(stderr, "fracterra_accuracy: D %.2f surface %d: %s\n", D, s, ft_last_error());
    ft_points_free(p);
    ft_grid_free(g);
    return est;
}


/* One surface of the independent generator: exact fBm (Stein), z scaled to sd zsd, fraction of the cells
 * (centres, cell units) drawn without replacement, N(0, σ_N²) on x, y and z (z only with --z-only). */
static double one_stein(const args *a, const fbm_embedding *e, double D, int s, double snr)
{
    size_t n = (size_t)a->size, nn = n * n, k = (size_t)llround(a->fraction * (double)nn);
    double *z = malloc(nn * sizeof *z);
    size_t *idx = malloc(nn * sizeof *idx);
    ft_points *p = ft_points_create(k);
    double est = NAN;
    uint64_t seed = a->seed * 1000003u + (uint64_t)s + 7919u * (uint64_t)llround(D * 100.0);
    if (z == NULL || idx == NULL || p == NULL || fbm_embedding_draw(e, seed, z) != 0) {
        fprintf(stderr, "fracterra_accuracy: out of memory\n");
        goto done;
    }
    double m = 0.0, v = 0.0;
    for (size_t i = 0; i < nn; i++)
        m += z[i];
    m /= (double)nn;
    for (size_t i = 0; i < nn; i++)
        v += (z[i] - m) * (z[i] - m);
    double scale = a->zsd / sqrt(v / (double)nn);
    double sx = (double)n / sqrt(12.0), sig = fmax(sx, a->zsd);
    double noise = snr > 0.0 ? sig / pow(10.0, snr / 20.0) : 0.0, noise_xy = a->z_only ? 0.0 : noise;
    fbm_rng r;
    fbm_rng_seed(&r, seed ^ 0xA5A5A5A5u);
    for (size_t i = 0; i < nn; i++)
        idx[i] = i;
    for (size_t i = 0; i < k; i++) { /* partial Fisher-Yates */
        size_t j = i + (size_t)(fbm_rng_uniform(&r) * (double)(nn - i));
        size_t t = idx[i];
        idx[i] = idx[j < nn ? j : nn - 1];
        idx[j < nn ? j : nn - 1] = t;
        size_t c = idx[i];
        double x = (double)(c % n) + 0.5, y = (double)(c / n) + 0.5, zz = (z[c] - m) * scale;
        if (noise > 0.0) {
            x += noise_xy * fbm_rng_normal(&r);
            y += noise_xy * fbm_rng_normal(&r);
            zz += noise * fbm_rng_normal(&r);
        }
        if (ft_points_push(p, x, y, zz) != FT_OK)
            goto done;
    }
    est = estimate(a, p, noise_xy, noise, D, s);
done:
    free(z);
    free(idx);
    ft_points_free(p);
    return est;
}

static int paper_row(double D)
{
    return accuracy_paper_row(D, 2.1, 8);
}

/* All rows of one synthesizer and noise level; returns the number of rows beating the paper. */
static int run_table(const args *a, ft_synth_method m, double snr, int snr_index)
{
    printf("\n%s surfaces %dx%d, %d per D, %.0f%% of cells%s, %s, %s\n",
           m == SYNTH_STEIN ? "stein (independent exact)" : ft_synth_method_name(m), a->size, a->size,
           a->surfaces, 100.0 * a->fraction, a->jitter ? " (jittered, z interpolated)" : " (cell centres)",
           ft_points_method_name(a->method), snr > 0.0 ? "noisy" : "no noise");
    if (snr > 0.0)
        printf("SNR %.0f dB, noise on %s%s\n", snr, a->z_only ? "z only" : "x, y and z",
               a->noise_model ? " (noise_sigma given to the estimator)" : "");
    printf("%-5s %10s %10s %8s %10s %10s %10s %8s %6s\n", "D", "paper[%]", "mean[%]", "sem[%]", "std(D)",
           "worst[%]", "medianD", "failed", "beats");
    double *est = malloc((size_t)a->surfaces * sizeof *est);
    int wins = 0, compared = 0;
    for (int d = 0; d < a->ndims; d++) {
        double D = a->dims[d];
        fbm_embedding e = {0};
        if (m == SYNTH_STEIN && fbm_embedding_init(&e, (size_t)a->size, 3.0 - D) != 0) {
            free(est);
            return -1;
        }
#pragma omp parallel for schedule(dynamic, 1)
        for (int s = 0; s < a->surfaces; s++)
            est[s] = m == SYNTH_STEIN ? one_stein(a, &e, D, s, snr) : one_fracterra(a, m, D, s, snr);
        fbm_embedding_free(&e);
        double sum = 0.0, worst = 0.0, ok[4096];
        size_t n = 0;
        for (int s = 0; s < a->surfaces; s++)
            if (isfinite(est[s]) && n < 4096) {
                ok[n++] = est[s];
                sum += est[s] - D;
                if (fabs(est[s] - D) > fabs(worst))
                    worst = est[s] - D;
            }
        int k = paper_row(D);
        double ref = k < 0 ? NAN : snr_index < 0 ? paper_error[k] : paper_snr[snr_index][k];
        double mean = n ? 100.0 * sum / (double)n / D : NAN;
        for (size_t i = 1; i < n; i++)
            for (size_t j = i; j > 0 && ok[j - 1] > ok[j]; j--) {
                double t = ok[j];
                ok[j] = ok[j - 1];
                ok[j - 1] = t;
            }
        double med = n ? (n % 2 ? ok[n / 2] : 0.5 * (ok[n / 2 - 1] + ok[n / 2])) : NAN;
        /* A row beats the paper when |mean error| minus one standard error of the mean is below it. */
        double sem = n > 1 ? 100.0 * sd_of(ok, n) * sqrt((double)n / (double)(n - 1)) / sqrt((double)n) / D : NAN;
        int beats = isfinite(ref) && isfinite(mean) && fabs(mean) - (isfinite(sem) ? sem : 0.0) < ref;
        if (isfinite(ref)) {
            compared++;
            wins += beats;
        }
        printf("%-5.2f %10.2f %+10.2f %8.2f %10.4f %+10.2f %10.4f %8zu %6s\n", D, ref, mean, sem, n ? sd_of(ok, n) : NAN,
               100.0 * worst / D, med, (size_t)a->surfaces - n, isfinite(ref) ? (beats ? "yes" : "NO") : "-");
        fflush(stdout);
    }
    printf("rows beating the paper: %d of %d\n", wins, compared);
    free(est);
    return wins;
}

int main(int argc, char **argv)
{
    args a;
    int rc = parse_args(argc, argv, &a);
    if (rc != 0)
        return rc;
    time_t t0 = time(NULL);
    printf("fracterra %s accuracy: Arakawa & Krotkov Table 1 (error = mean signed error of D in %% of D;\n"
           "the paper's errors are magnitudes). Lags %g..%g x mean spacing (0 = library default), %s fit, %d threads\n",
           ft_version(), a.min_lag, a.max_lag, a.fit_auto ? "ILS" : "whole-range", omp_get_max_threads());
    for (int m = 0; m < a.nsynth; m++) {
        if (!a.noisy_only || a.nsnr == 0)
            run_table(&a, a.synth[m], 0.0, -1);
        for (int k = 0; k < a.nsnr; k++) {
            int idx = a.snr[k] == 30.0 ? 0 : a.snr[k] == 25.0 ? 1 : a.snr[k] == 20.0 ? 2 : -3;
            run_table(&a, a.synth[m], a.snr[k], idx < 0 ? 2 : idx);
        }
    }
    printf("\nelapsed %.0f s\n", difftime(time(NULL), t0));
    return 0;
}
