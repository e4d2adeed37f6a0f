/* fracterra — workloads_clarke.c: Clarke's scale-based model in `make bench` (speed target: a model fit of a
 * 4096² DEM under 3 s).
 *
 * Input, made in the child before the timed run (untimed): a 4096 x 4096 DEM of 10 m cells, a plane plus
 * two plane waves plus a fractional Brownian surface of D = 2.3 (ft_terrain_synth, fft, seed 20240501).
 * No peer tool fits this model.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/fracterra.h"

#define CLARKE_N 4096
#define CLARKE_SEED UINT64_C(20240501)

static ft_grid *dem; /* in the child only */
static ft_clarke_model *model;

static int clarke_setup(ft_bench_case *c)
{
    c->work = (double)CLARKE_N * CLARKE_N;
    c->peer_none = "no peer fits Clarke's model";
    return 0;
}

static int clarke_prepare(ft_bench_case *c)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.sigma = 20.0;
    so.cell = 10.0;
    so.seed = CLARKE_SEED;
    int rc = ft_terrain_synth(CLARKE_N, CLARKE_N, &so, &dem);
    if (rc != FT_OK)
        return rc;
    const double pi = 3.14159265358979323846;
    for (size_t r = 0; r < CLARKE_N; r++)
        for (size_t k = 0; k < CLARKE_N; k++)
            dem->z[r * CLARKE_N + k] += (float)(0.05 * k - 0.03 * r + 80.0 * cos(2.0 * pi * (3.0 * k + r) / CLARKE_N) +
                                                40.0 * cos(2.0 * pi * (7.0 * k - 5.0 * r) / CLARKE_N));
    return FT_OK;
}

static int clarke_fit_run(ft_bench_case *c)
{
    return ft_clarke_fit(dem, NULL, &model);
}

static const ft_bench_workload clarke_workloads[] = {
    {"terrain.clarke.fit", "ft_clarke_fit of a 4096 x 4096 DEM (plane + 2 waves + fBm D = 2.3), Hann-tapered regression",
     FT_BENCH_CELLS, clarke_setup, clarke_prepare, clarke_fit_run, NULL},
};

const ft_bench_suite ft_bench_suite_clarke = {"clarke", clarke_workloads,
                                              sizeof clarke_workloads / sizeof clarke_workloads[0]};
