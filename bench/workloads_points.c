/* fracterra — workloads_points.c: the scattered-point estimator (ft_surface_dim_points, Arakawa & Krotkov
 * §2.4) in `make bench`, ONE thread each:
 *  - surface.points.yokoya.1m: Yokoya's D of 1,000,000 irregular points (5% of the cells of a 4472² fft
 *    surface, D = 2.3, each at a uniform position inside its cell with z interpolated), lags from half the
 *    mean spacing to 5% of the extent (the target: under 10 s; the paper took 5,500 s for 19,600
 *    points exhaustively);
 *  - surface.points.exact.20k: the paper's exhaustive O(N²) enumeration (--exact) on 20,000 such points
 *    (a 632² surface), lags up to 5% of the extent;
 *  - surface.points.grid.20k: the default grid enumeration on the same points: the same counters.
 * Throughput is in points per second (printed as Mvertices/s: one vertex = one point). Points are generated
 * untimed in the child (prepare).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <omp.h>

#include "fracterra/fracterra.h"

#define BIG_SIDE 4472   /* 5% of 4472² = 999,949 points */
#define SMALL_SIDE 632  /* 5% of 632² = 19,971 points */
#define NOISE_SIDE 1414 /* 5% of 1414² = 99,970 points */
#define POINTS_DIM 2.3
#define BENCH_SEED UINT64_C(20240501)

static ft_points *held; /* in the child only */

static int make_points(size_t side)
{
    omp_set_num_threads(1);
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = POINTS_DIM;
    so.seed = BENCH_SEED;
    ft_grid *g = NULL;
    ft_grid_sample_opts go = FT_GRID_SAMPLE_OPTS_DEFAULT;
    go.jitter = 1;
    go.seed = BENCH_SEED;
    int rc = ft_terrain_synth(side, side, &so, &g);
    if (rc == FT_OK)
        rc = ft_surface_points_from_grid(g, &go, &held);
    ft_grid_free(g);
    return rc;
}

static int big_prepare(ft_bench_case *c)
{
    int rc = make_points(BIG_SIDE);
    if (rc == FT_OK)
        c->work = (double)held->n;
    return rc;
}

static int small_prepare(ft_bench_case *c)
{
    int rc = make_points(SMALL_SIDE);
    if (rc == FT_OK)
        c->work = (double)held->n;
    return rc;
}

static int big_setup(ft_bench_case *c)
{
    c->work = 0.05 * BIG_SIDE * BIG_SIDE;
    c->peer_none = "none: no installed tool estimates D from scattered points";
    return FT_OK;
}

static int small_setup(ft_bench_case *c)
{
    c->work = 0.05 * SMALL_SIDE * SMALL_SIDE;
    c->peer_none = "none: the grid enumeration of the same pairs is surface.points.grid.20k";
    return FT_OK;
}

/* Yokoya with lags from half the mean spacing to 5% of the extent. */
static int estimate(int exact)
{
    double x0, y0, x1, y1;
    ft_points_bbox(held, &x0, &y0, &x1, &y1);
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    o.min_lag = 0.5 * sqrt((x1 - x0) * (y1 - y0) / (double)held->n);
    o.max_lag = 0.05 * fmax(x1 - x0, y1 - y0);
    o.exact = exact;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim_points(held, &o, &r);
    ft_dim_result_free(r);
    return rc;
}

static int run_grid(ft_bench_case *c)
{
    (void)c;
    return estimate(0);
}

static int run_exact(ft_bench_case *c)
{
    (void)c;
    return estimate(1);
}

/* The noise model's cost: the default path on 100,000 points, with and without it. */
static int noise_prepare(ft_bench_case *c)
{
    int rc = make_points(NOISE_SIDE);
    if (rc == FT_OK)
        c->work = (double)held->n;
    return rc;
}

static int noise_setup(ft_bench_case *c)
{
    c->work = 0.05 * NOISE_SIDE * NOISE_SIDE;
    c->peer_none = "none: the same without the noise model is surface.points.nonoise.100k";
    return FT_OK;
}

static int run_default(int noise_mode)
{
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    o.noise_mode = noise_mode;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim_points(held, &o, &r);
    ft_dim_result_free(r);
    return rc;
}

static int run_noise(ft_bench_case *c)
{
    (void)c;
    return run_default(0);
}

static int run_nonoise(ft_bench_case *c)
{
    (void)c;
    return run_default(-1);
}

static const ft_bench_workload points_workloads[] = {
    {"surface.points.noise.100k", "dim points defaults (noise model on) on 100,000 irregular points, one thread",
     FT_BENCH_VERTICES, noise_setup, noise_prepare, run_noise, NULL},
    {"surface.points.nonoise.100k", "the same with --noise-model off", FT_BENCH_VERTICES, noise_setup,
     noise_prepare, run_nonoise, NULL},
    {"surface.points.yokoya.1m", "Yokoya D of 1,000,000 irregular points, lags up to 5% of the extent, one thread",
     FT_BENCH_VERTICES, big_setup, big_prepare, run_grid, NULL},
    {"surface.points.exact.20k", "the same on 20,000 points enumerating all pairs (--exact, O(N^2)), one thread",
     FT_BENCH_VERTICES, small_setup, small_prepare, run_exact, NULL},
    {"surface.points.grid.20k", "the same 20,000 points through the grid (the default), one thread",
     FT_BENCH_VERTICES, small_setup, small_prepare, run_grid, NULL},
};

const ft_bench_suite ft_bench_suite_points = {"points", points_workloads,
                                              sizeof points_workloads / sizeof points_workloads[0]};
