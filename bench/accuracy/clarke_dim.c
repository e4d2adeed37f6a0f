/* fracterra — bench/accuracy/clarke_dim.c: does a simulation from Clarke's model of a real DEM have the DEM's
 * roughness? (issue 14 item 4; docs/terrain-clarke.md, "Measured accuracy").
 *
 * For each DEM given: fit the model with F the measured spectrum (the default) and with Clarke's one power
 * law, simulate several seeds from each, and measure the variogram D = 3 - slope / 2 of the least-squares
 * line of log gamma(h) on log h over every whole lag h of 1-8 and of 4-32 cells, along rows and columns,
 * pairs of cells valid in the DEM only (a simulation is measured on the DEM's footprint): an estimator written here, independent of the library's. Prints one row per
 * DEM: the DEM's D, and the median, min and max over the seeds of each model's simulations.
 *
 *   fracterra_accuracy_clarke [--seeds N] [--no-taper] DEM...
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accuracy_util.h"
#include "fracterra/fracterra.h"

#define MAX_SEEDS 64

static int use_taper = 1; /* --no-taper: the raw periodogram */

/* gamma(h) = half the mean squared difference of the pairs h cells apart along rows and columns whose both
 * cells are valid in v (a grid of g's size: the original DEM, so a simulation is measured on its footprint). */
static double variogram_at(const ft_grid *g, const ft_grid *v, size_t h)
{
    double s = 0.0, c = 0.0;
    for (size_t y = 0; y < g->ny; y++)
        for (size_t x = 0; x < g->nx; x++) {
            if (!ft_grid_is_valid(v, x, y))
                continue;
            double z = g->z[y * g->nx + x];
            if (x + h < g->nx && ft_grid_is_valid(v, x + h, y)) {
                double d = g->z[y * g->nx + x + h] - z;
                s += d * d;
                c++;
            }
            if (y + h < g->ny && ft_grid_is_valid(v, x, y + h)) {
                double d = g->z[(y + h) * g->nx + x] - z;
                s += d * d;
                c++;
            }
        }
    return c > 0 ? 0.5 * s / c : NAN;
}

/* D from every whole lag in [lo, hi]. */
static double variogram_dim(const ft_grid *g, const ft_grid *v, size_t lo, size_t hi)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
    for (size_t h = lo; h <= hi; h++) {
        double gam = variogram_at(g, v, h);
        if (!(gam > 0.0))
            return NAN;
        double x = log((double)h), y = log(gam);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
        n++;
    }
    return 3.0 - (n * sxy - sx * sy) / (n * sxx - sx * sx) / 2.0;
}

static void summary(double *v, int n, double out[3])
{
    qsort(v, (size_t)n, sizeof *v, accuracy_cmp_double);
    out[0] = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    out[1] = v[0];
    out[2] = v[n - 1];
}

/* Median [min, max] of the simulations' D at both lag ranges for one kind of noise. */
static int simulate_dims(const ft_grid *g, ft_clarke_noise noise, int seeds, double fine[3], double coarse[3],
                         double *model_D)
{
    ft_clarke_opts co = FT_CLARKE_OPTS_DEFAULT;
    co.noise = noise;
    co.taper = use_taper;
    ft_clarke_model *m = NULL;
    if (ft_clarke_fit(g, &co, &m) != FT_OK)
        return -1;
    *model_D = m->D;
    double a[MAX_SEEDS], b[MAX_SEEDS];
    for (int s = 0; s < seeds; s++) {
        ft_clarke_sim_opts so = FT_CLARKE_SIM_OPTS_DEFAULT;
        ft_grid *sim = NULL;
        so.seed = (uint64_t)(1000 + s);
        if (ft_clarke_simulate(m, &so, &sim) != FT_OK) {
            ft_clarke_model_free(m);
            return -1;
        }
        a[s] = variogram_dim(sim, g, 1, 8);
        b[s] = variogram_dim(sim, g, 4, 32);
        ft_grid_free(sim);
    }
    if (noise == FT_CLARKE_NOISE_SPECTRUM)
        for (size_t i = 0; i < m->nregimes; i++)
        {
            printf("#   regime %zu: D %.3f over wavelengths %.4g-%.4g (%.1f-%.1f cells of %g)\n", i + 1,
                   m->regimes[i].D, m->regimes[i].wavelength_lo, m->regimes[i].wavelength_hi,
                   m->regimes[i].wavelength_lo / fabs(g->gt[1]), m->regimes[i].wavelength_hi / fabs(g->gt[1]),
                   fabs(g->gt[1]));
            if (i + 1 < m->nregimes)
                printf("#   break at wavelength %.4g (%.1f cells)\n", m->breaks[i], m->breaks[i] / fabs(g->gt[1]));
        }
    ft_clarke_model_free(m);
    summary(a, seeds, fine);
    summary(b, seeds, coarse);
    return 0;
}

static int measure(const char *path, int seeds)
{
    ft_grid *g = NULL;
    if (ft_io_read_grid(path, NULL, &g) != FT_OK) {
        fprintf(stderr, "%s: %s\n", path, ft_last_error());
        return 1;
    }
    const char *base = strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    printf("# %s: %zu x %zu cells\n", base, g->nx, g->ny);
    double d18 = variogram_dim(g, g, 1, 8), d432 = variogram_dim(g, g, 4, 32);
    double sf[3], sc[3], pf[3], pc[3], Ds, Dp;
    if (simulate_dims(g, FT_CLARKE_NOISE_SPECTRUM, seeds, sf, sc, &Ds) != 0 ||
        simulate_dims(g, FT_CLARKE_NOISE_POWER_LAW, seeds, pf, pc, &Dp) != 0) {
        fprintf(stderr, "%s: %s\n", path, ft_last_error());
        ft_grid_free(g);
        return 1;
    }
    printf("%-28s %5zu %5zu %5.3f | %6.3f %5.3f [%5.3f %5.3f] %+6.3f | %6.3f %5.3f [%5.3f %5.3f] %+6.3f |"
           " %5.3f [%5.3f %5.3f] %5.3f [%5.3f %5.3f]\n",
           base, g->nx, g->ny, Dp, d18, sf[0], sf[1], sf[2], sf[0] - d18, d432, sc[0], sc[1], sc[2], sc[0] - d432,
           pf[0], pf[1], pf[2], pc[0], pc[1], pc[2]);
    ft_grid_free(g);
    return 0;
}

int main(int argc, char **argv)
{
    int seeds = 8, first = 1;
    for (; first < argc && argv[first][0] == '-'; first++) {
        if (strcmp(argv[first], "--seeds") == 0 && first + 1 < argc)
            seeds = atoi(argv[++first]);
        else if (strcmp(argv[first], "--no-taper") == 0)
            use_taper = 0;
        else
            seeds = 0; /* unknown option: usage */
    }
    if (first >= argc || seeds < 1 || seeds > MAX_SEEDS) {
        fprintf(stderr, "usage: %s [--seeds N (1-%d)] [--no-taper] DEM...\n", argv[0], MAX_SEEDS);
        return 2;
    }
    printf("# variogram D (own estimator, every whole lag, rows and columns), %d seeds: median [min max]\n", seeds);
    printf("# DEM nx ny D_one_law | D_dem(1-8) spectrum-sim [range] diff | D_dem(4-32) spectrum-sim [range] diff |"
           " power-law-sim 1-8 [range], 4-32 [range]\n");
    int rc = 0;
    for (int i = first; i < argc; i++)
        rc |= measure(argv[i], seeds);
    return rc;
}
