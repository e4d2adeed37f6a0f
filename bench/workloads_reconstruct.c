/* fracterra — workloads_reconstruct.c: reconstruction of dense terrain from sparse points (speed;
 * Arakawa & Krotkov §3) in `make bench`. The input of every workload is 5% of the cells of an n x n fft
 * surface of D = 2.3 (standard deviation 246, cell 1), each point at a uniform position inside its cell
 * with z interpolated (ft_surface_points_from_grid, jittered), reconstructed onto the surface's own grid
 * with D given (2.3: the estimate from the points is not timed here):
 *
 *  - reconstruct.<method>.1024: fractal, conditional and smooth, ONE thread (the target for
 *    fractal: under 10 s; the paper needed about 2 hours for 256² on a Sun 4/75);
 *  - reconstruct.<method>.4096: fractal and conditional, ONE thread (target for fractal: under 3 minutes);
 *  - reconstruct.<method>.1024.t2: fractal and conditional on 2 threads (scaling against .1024; the cells
 *    are the same bit for bit);
 *  - cli.reconstruct.smooth.512: the whole `fracterra reconstruct POINTS.csv OUT.tif --like GRID.tif
 *    --method smooth --threads 1` process on 512² from 5% points (13,107), against GRASS GIS v.surf.rst
 *    (regularized spline with tension, default parameters, nprocs=1) on the same points and grid, run as
 *    `grass --tmp-location XY --exec` (v.in.ascii, g.region, v.surf.rst) when grass is on PATH. Both sides
 *    are whole processes; GRASS's start-up (the temporary location) is in its figure and printed apart.
 * Inputs are generated untimed: in the child (prepare) for the in-process workloads, once in a child of
 * the harness (setup) for the command workload.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "fracterra/fracterra.h"

#define RECON_DIM 2.3
#define RECON_SD 246.0
#define RECON_FRACTION 0.05
#define BENCH_SEED UINT64_C(20240701)
#define PEER_N 512

static ft_points *held_points; /* in the child only */
static ft_grid *held_target;   /* in the child only */

/* An n x n fft surface of D = 2.3 and 5% of its cells as jittered points; the surface is kept as the target
 * grid (its cells are ignored by the reconstruction). */
static int make_input(size_t n, ft_grid **grid, ft_points **points)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = RECON_DIM;
    so.sigma = RECON_SD;
    so.seed = BENCH_SEED;
    ft_grid_sample_opts go = FT_GRID_SAMPLE_OPTS_DEFAULT;
    go.fraction = RECON_FRACTION;
    go.jitter = 1;
    go.seed = BENCH_SEED;
    int rc = ft_terrain_synth(n, n, &so, grid);
    if (rc == FT_OK)
        rc = ft_surface_points_from_grid(*grid, &go, points);
    return rc;
}

static int prepare(ft_bench_case *c, size_t n, int threads)
{
    omp_set_num_threads(threads);
    int rc = make_input(n, &held_target, &held_points);
    c->work = (double)n * (double)n;
    return rc;
}

static int reconstruct(ft_recon_method m, int threads)
{
    ft_recon_opts o = FT_RECON_OPTS_DEFAULT;
    o.method = m;
    o.dim = RECON_DIM;
    o.seed = BENCH_SEED + 1; /* not the surface's: the conditional method would draw the surface itself */
    o.threads = threads;
    ft_grid *out = NULL;
    int rc = ft_reconstruct_points(held_points, held_target, &o, &out, NULL, NULL);
    ft_grid_free(out);
    return rc;
}

static int setup_inprocess(ft_bench_case *c, size_t n)
{
    c->work = (double)n * (double)n;
    c->peer_none = "none: no installed tool reconstructs rough terrain (GRASS v.surf.rst: cli.reconstruct.smooth.512)";
    return FT_OK;
}

static int setup_1024(ft_bench_case *c)
{
    return setup_inprocess(c, 1024);
}

static int setup_4096(ft_bench_case *c)
{
    return setup_inprocess(c, 4096);
}

#define PREPARE(n, t)                                                                                        \
    static int prepare_##n##_t##t(ft_bench_case *c)                                                          \
    {                                                                                                        \
        return prepare(c, n, t);                                                                             \
    }
PREPARE(1024, 1)
PREPARE(1024, 2)
PREPARE(4096, 1)

#define RUN(name, m, t)                                                                                      \
    static int run_##name##_t##t(ft_bench_case *c)                                                           \
    {                                                                                                        \
        (void)c;                                                                                             \
        return reconstruct(m, t);                                                                            \
    }
RUN(fractal, FT_RECON_FRACTAL, 1)
RUN(conditional, FT_RECON_CONDITIONAL, 1)
RUN(smooth, FT_RECON_SMOOTH, 1)
RUN(fractal, FT_RECON_FRACTAL, 2)
RUN(conditional, FT_RECON_CONDITIONAL, 2)

/* ---- cli.reconstruct.smooth.512 against GRASS v.surf.rst ---- */

typedef struct {
    const char *csv, *like;
} peer_files;

/* In a child of the harness: the points as CSV (x,y,z) and the target grid as a GeoTIFF. */
static int write_peer_files(void *arg)
{
    const peer_files *f = arg;
    ft_grid *g = NULL;
    ft_points *p = NULL;
    int rc = make_input(PEER_N, &g, &p);
    if (rc == FT_OK)
        rc = ft_io_write_points(f->csv, p);
    if (rc == FT_OK)
        rc = ft_io_write_grid(f->like, g, NULL);
    ft_points_free(p);
    ft_grid_free(g);
    return rc;
}

static int set_argv(char **dst, const char *const *src, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if ((dst[i] = ft_bench_strdup(src[i])) == NULL)
            return ft_error(FT_E_NOMEM, "out of memory");
    return FT_OK;
}

static int setup_cli_512(ft_bench_case *c)
{
    c->work = (double)PEER_N * PEER_N;
    const char *prog = ft_bench_fracterra_program();
    if (prog == NULL)
        return ft_error(FT_E_IO, "the fracterra program is not beside fracterra_bench");
    char *csv = ft_bench_path("recon512_points.csv"), *like = ft_bench_path("recon512_like.tif");
    int rc = csv && like ? FT_OK : FT_E_NOMEM;
    if (rc == FT_OK) {
        fprintf(stderr, "generating %s (5%% of a %dx%d surface) ...\n", csv, PEER_N, PEER_N);
        peer_files f = {csv, like};
        rc = ft_bench_in_child(write_peer_files, &f);
    }
    if (rc == FT_OK && (c->scratch = ft_bench_path("recon512_out.tif")) == NULL)
        rc = ft_last_error_code();
    if (rc == FT_OK) {
        const char *ours[] = {prog, "reconstruct", csv, c->scratch, "--like", like, "--method", "smooth",
                              "--dim", "2.3", "--threads", "1"};
        rc = set_argv(c->argv, ours, sizeof ours / sizeof ours[0]);
    }
    char *script = NULL;
    if (rc == FT_OK) {
        /* the synthesized grid is north-up from (0, 0) with cells of 1: x 0 .. n, y -n .. 0 */
        script = ft_bench_strf("g.region n=0 s=-%d w=0 e=%d res=1 && "
                               "v.in.ascii input=%s output=pts separator=comma skip=1 x=1 y=2 z=3 -z -t -b --quiet && "
                               "v.surf.rst input=pts layer=0 elevation=rst nprocs=1 --quiet",
                               PEER_N, PEER_N, csv);
        rc = script ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
    }
    if (rc == FT_OK) {
        const char *peer[] = {"grass", "--tmp-location", "XY", "--exec", "sh", "-c", script};
        rc = set_argv(c->peer_argv, peer, sizeof peer / sizeof peer[0]);
    }
    free(script);
    free(csv);
    free(like);
    return rc;
}

#define WL(name, n, what)                                                                                    \
    {"reconstruct." #name "." #n, what " of " #n "x" #n " from 5% points (D = 2.3 given), one thread",       \
     FT_BENCH_CELLS, setup_##n, prepare_##n##_t1, run_##name##_t1, NULL}
#define WL2(name, n, what)                                                                                   \
    {"reconstruct." #name "." #n ".t2", what " of " #n "x" #n " from 5% points (D = 2.3 given), 2 threads",  \
     FT_BENCH_CELLS, setup_##n, prepare_##n##_t2, run_##name##_t2, NULL}

static const ft_bench_workload reconstruct_workloads[] = {
    WL(fractal, 1024, "fractal reconstruction (smooth solution + exact posterior sample)"),
    WL(conditional, 1024, "conditional simulation (fBm + smooth interpolation of the residuals)"),
    WL(smooth, 1024, "smooth reconstruction (T = 0, multigrid)"),
    WL(fractal, 4096, "fractal reconstruction"),
    WL(conditional, 4096, "conditional simulation"),
    WL2(fractal, 1024, "fractal reconstruction"),
    WL2(conditional, 1024, "conditional simulation"),
    {"cli.reconstruct.smooth.512",
     "fracterra reconstruct --method smooth of 512x512 from 13,107 points (CSV, --like), one thread",
     FT_BENCH_CELLS, setup_cli_512, NULL, NULL, NULL},
};

const ft_bench_suite ft_bench_suite_reconstruct = {"reconstruct", reconstruct_workloads,
                                                   sizeof reconstruct_workloads / sizeof reconstruct_workloads[0]};
