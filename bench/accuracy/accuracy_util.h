/* fracterra — bench/accuracy/accuracy_util.h: what the accuracy programs share: comma-separated option lists,
 * the row of a paper's table for a dimension, the sample of a grid the reconstruction programs start from,
 * and the independent lag 1-16 variogram D the synthesis programs measure with.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_BENCH_ACCURACY_UTIL_H
#define FRACTERRA_BENCH_ACCURACY_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"

/** Parses "a,b,c" into at most max doubles; returns how many were read. */
static inline int accuracy_parse_list(const char *s, double *v, int max)
{
    int n = 0;
    char buf[512];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t && n < max; t = strtok_r(NULL, ",", &save))
        v[n++] = atof(t);
    return n;
}

/** The row of a paper's table whose rows are D = first, first + 0.1, ... (nrows of them) holding D, or -1. */
static inline int accuracy_paper_row(double D, double first, int nrows)
{
    long k = lround((D - first) * 10.0);
    return k >= 0 && k < nrows && fabs(D - (first + 0.1 * (double)k)) < 1e-9 ? (int)k : -1;
}

/** qsort order of doubles, increasing. */
static inline int accuracy_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/** Arakawa & Krotkov's sample of a grid (§3.3): every `every`-th cell in each direction (0 = none) plus a
 *  random fraction frac of the cells, valid cells only, at their centres with their exact values. */
static inline ft_points *accuracy_subsample(const ft_grid *g, uint64_t seed, double frac, int every)
{
    ft_points *p = ft_points_create(g->nx * g->ny / 8);
    ft_rng *r = ft_rng_create(seed, 77);
    for (size_t y = 0; y < g->ny; y++)
        for (size_t x = 0; x < g->nx; x++) {
            int take = (every > 0 && x % (size_t)every == 0 && y % (size_t)every == 0);
            take |= ft_rng_uniform(r) < frac;
            if (take && ft_grid_is_valid(g, x, y)) {
                double cx, cy;
                ft_grid_cell_center(g, (double)x, (double)y, &cx, &cy);
                ft_points_push(p, cx, cy, g->z[y * g->nx + x]);
            }
        }
    ft_rng_free(r);
    return p;
}

/** Pentland's points line at one cell (the reconstruction's sigma0: no nugget model) over lags lo .. hi
 *  ground units; exits with the library's message on failure. */
static inline double accuracy_pentland_at_one(const ft_points *p, double lo, double hi)
{
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    o.method = FT_POINTS_PENTLAND;
    o.noise_mode = -1;
    o.min_lag = lo;
    o.max_lag = hi;
    ft_dim_result *r = NULL;
    if (ft_surface_dim_points(p, &o, &r) != FT_OK) {
        fprintf(stderr, "pentland: %s\n", ft_last_error());
        exit(1);
    }
    double v = pow(10.0, r->fit.intercept);
    ft_dim_result_free(r);
    return v;
}

/** sigma0 of the sample p of g (cell 1) over sigma0 of every cell of g, both by Pentland's points estimator
 *  over the lags 0.5 .. top x the mean spacing of p (the reconstruction's sigma0: top = 1.5; the
 *  estimator's default range: 4): the bias of the data's amplitude. */
static inline double accuracy_sigma0_bias(const ft_grid *g, const ft_points *p, double top)
{
    double spacing = sqrt((double)(g->nx - 1) * (double)(g->ny - 1) / (double)p->n);
    ft_points *every_cell = accuracy_subsample(g, 1, 1.0, 1);
    double data = accuracy_pentland_at_one(p, 0.5 * spacing, top * spacing);
    double surface = accuracy_pentland_at_one(every_cell, 0.5 * spacing, top * spacing);
    ft_points_free(every_cell);
    return data / surface;
}

/** Sets ro->temperature to the temperature the fractal reconstruction of p on g would take with the
 *  sigma0 of every cell of g instead of the data's (T scales as sigma0^2): one reconstruction run to read
 *  T0, divided by the squared bias. Returns the bias (accuracy_sigma0_bias, top 1.5); exits with the
 *  library's message on failure. */
static inline double accuracy_use_surface_sigma0(const ft_grid *g, const ft_points *p, ft_recon_opts *ro)
{
    double ratio = accuracy_sigma0_bias(g, p, 1.5);
    ft_grid *out = NULL;
    ft_recon_info info;
    if (ft_reconstruct_points(p, g, ro, &out, NULL, &info) != FT_OK) {
        fprintf(stderr, "reconstruct: %s\n", ft_last_error());
        exit(1);
    }
    ft_grid_free(out);
    ro->temperature = info.temperature / (ratio * ratio);
    return ratio;
}

#define ACCURACY_LAGS 16

/** The variogram of an n x n grid at lags 1 .. ACCURACY_LAGS cells along rows and columns into v[1 ..]:
 *  an estimator written here, independent of the library's. */
static inline void accuracy_variogram16(const float *z, size_t n, double *v)
{
    for (size_t h = 1; h <= ACCURACY_LAGS; h++) {
        double s = 0.0, c = 0.0;
        for (size_t y = 0; y < n; y++)
            for (size_t x = 0; x < n; x++) {
                if (x + h < n) {
                    double d = (double)z[y * n + x + h] - z[y * n + x];
                    s += d * d;
                    c++;
                }
                if (y + h < n) {
                    double d = (double)z[(y + h) * n + x] - z[y * n + x];
                    s += d * d;
                    c++;
                }
            }
        v[h] = s / c;
    }
}

/** D = 3 - slope / 2 of the least-squares line of log v[h] on log h, h = 1 .. ACCURACY_LAGS. */
static inline double accuracy_fit_variogram16(const double *v)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int h = 1; h <= ACCURACY_LAGS; h++) {
        double x = log((double)h), y = log(v[h]);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    return 3.0 - (ACCURACY_LAGS * sxy - sx * sy) / (ACCURACY_LAGS * sxx - sx * sx) / 2.0;
}

#endif /* FRACTERRA_BENCH_ACCURACY_UTIL_H */
