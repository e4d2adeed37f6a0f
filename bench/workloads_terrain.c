/* fracterra — workloads_terrain.c: terrain synthesis and variogram workloads of `make bench`.
 *
 *  - terrain.synth.fft.4096: ft_terrain_synth, method fft (padded and cropped, the default), 4096², D = 2.3,
 *    ONE thread, against its floor in the same run: one bare in-place FFTW complex-to-real transform of
 *    4096² (plan made beforehand, one thread) as the in-process peer, so ours/peer is the multiple of the
 *    c2r floor (the target: at most 1.5, peak memory under 300 MB);
 *  - terrain.synth.fft.4096.threads: the same on OMP_NUM_THREADS threads (same cells, bit for bit);
 *  - terrain.synth.fft.4096.reuse: the same synthesis through ft_terrain_synth_into with a workspace and
 *    grid made (and every page touched) untimed, as the floor's buffer is: like against like, no page
 *    fault in either timed region (issue 17: the allocating call's slow runs are the first touch of
 *    fresh memory, docs/bench.md);
 *  - terrain.synth.sra.4096: the same with method sra, one thread (target: under 1.5 s); no in-process peer
 *    (r.surf.fractal is a whole GRASS session: cli.synth.sra.4096 compares like with like);
 *  - terrain.fftw.c2r.4096: the c2r transform alone;
 *  - cli.synth.fft.4096 / .2048 / .4096.envi, cli.synth.sra.4096: the whole `fracterra synth` process
 *    against the whole GRASS session running r.surf.fractal (spectral synthesis) at the same size, through
 *    `grass --tmp-location XY --exec` (GRASS 8.2 and 8.4 accept it) when grass is on PATH;
 *  - cli.hillshade.4096: `fracterra hillshade` of a 4096² fft surface (10 m cells, made once, untimed) to a
 *    GeoTIFF, whole process, against `gdaldem hillshade -compute_edges` of the same file (the engine's oracle);
 *  - surface.variogram.32k: ft_surface_dim_variogram with 32,000 random points (Mark & Aronson) on a 4096²
 *    fft surface prepared untimed (target: under 0.5 s).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>

#include "fft/fft.h"
#include "fracterra/fracterra.h"

#define SYNTH_N 4096
#define SYNTH_DIM 2.3
#define BENCH_SEED UINT64_C(20240501)
#define VARIOGRAM_POINTS 32000

static ft_grid *held_grid;      /* in the child only */
static fftw_complex *held_spec; /* in the child only */

static int grass_peer_n(ft_bench_case *c, double dim, int n)
{
    char *script = ft_bench_strf("g.region rows=%d cols=%d && r.surf.fractal output=fracterra_bench "
                                 "dimension=%g --overwrite --quiet", n, n, dim);
    if (script == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    const char *args[] = {"grass", "--tmp-location", "XY", "--exec", "sh", "-c", script};
    for (size_t i = 0; i < sizeof args / sizeof args[0]; i++)
        if ((c->peer_argv[i] = i == 6 ? script : ft_bench_strdup(args[i])) == NULL)
            return ft_error(FT_E_NOMEM, "out of memory");
    return FT_OK;
}

static int one_thread(ft_bench_case *c)
{
    (void)c;
    omp_set_num_threads(1);
    return FT_OK;
}

static int synth(ft_synth_method m)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.method = m;
    o.dim = SYNTH_DIM;
    o.seed = BENCH_SEED;
    ft_grid *g = NULL;
    int rc = ft_terrain_synth(SYNTH_N, SYNTH_N, &o, &g);
    ft_grid_free(g);
    return rc;
}

static int c2r_prepare(ft_bench_case *c);
static int c2r_run(ft_bench_case *c);

static ft_synth_workspace *held_ws; /* in the child only */

/* In process: the fft synthesis against the bare c2r transform of the same size (its floor). */
static int synth_setup(ft_bench_case *c)
{
    c->work = (double)SYNTH_N * SYNTH_N;
    c->peer_prepare = c2r_prepare;
    c->peer_run = c2r_run;
    c->peer_label = "one in-place FFTW c2r transform of 4096x4096, one thread (the floor of the fft synthesis)";
    c->min_repeat = 12; /* the target holds on every run: the spread line shows min and max */
    return FT_OK;
}

static int synth_sra_setup(ft_bench_case *c)
{
    c->work = (double)SYNTH_N * SYNTH_N;
    c->peer_none = "none in process: GRASS r.surf.fractal runs as a whole session (cli.synth.sra.4096)";
    return FT_OK;
}

static int synth_fft_run(ft_bench_case *c)
{
    (void)c;
    return synth(FT_SYNTH_FFT);
}

static int synth_sra_run(ft_bench_case *c)
{
    (void)c;
    return synth(FT_SYNTH_SRA);
}

/* terrain.synth.fft.4096.reuse: one synthesis untimed (workspace and grid touched, plans made), then the
 * timed one into the same memory. */
static int synth_reuse_prepare(ft_bench_case *c)
{
    one_thread(c);
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.dim = SYNTH_DIM;
    o.seed = BENCH_SEED + 1;
    held_grid = ft_grid_create(SYNTH_N, SYNTH_N);
    if (held_grid == NULL)
        return FT_E_NOMEM;
    int rc = ft_synth_workspace_create(SYNTH_N, SYNTH_N, &o, &held_ws);
    return rc == FT_OK ? ft_terrain_synth_into(&o, held_ws, held_grid) : rc;
}

static int synth_reuse_run(ft_bench_case *c)
{
    (void)c;
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.dim = SYNTH_DIM;
    o.seed = BENCH_SEED;
    return ft_terrain_synth_into(&o, held_ws, held_grid);
}

/* terrain.fftw.c2r.4096: the spectrum is filled and the plan made untimed. */
static int c2r_setup(ft_bench_case *c)
{
    c->work = (double)SYNTH_N * SYNTH_N;
    c->peer_none = "none: the yardstick of terrain.synth.fft.4096";
    return FT_OK;
}

static void fill_spectrum(fftw_complex *s, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        s[i][0] = 1.0 / (double)(1 + i % 977);
        s[i][1] = 0.5 / (double)(1 + i % 613);
    }
}

static int c2r_prepare(ft_bench_case *c)
{
    one_thread(c);
    size_t n = (size_t)SYNTH_N * (SYNTH_N / 2 + 1);
    held_spec = ft_fft_alloc_complex(n);
    if (held_spec == NULL)
        return FT_E_NOMEM;
    fill_spectrum(held_spec, n);
    int rc = ft_fft_c2r_2d(SYNTH_N, SYNTH_N, held_spec, (double *)held_spec); /* makes the plan */
    fill_spectrum(held_spec, n);
    return rc;
}

static int c2r_run(ft_bench_case *c)
{
    (void)c;
    return ft_fft_c2r_2d(SYNTH_N, SYNTH_N, held_spec, (double *)held_spec);
}

/* cli.synth.fft.*: the built `fracterra synth` program, whole process (start-up, synthesis, the GeoTIFF
 * written with the default creation options, or raw ENVI), against the whole GRASS session that runs
 * r.surf.fractal into its own raster store. */
static int cli_synth_setup(ft_bench_case *c, int n, const char *ext, const char *driver, const char *method)
{
    const char *prog = ft_bench_fracterra_program();
    if (prog == NULL)
        return ft_error(FT_E_IO, "no fracterra program beside fracterra_bench (build the target fracterra_cli)");
    char *name = ft_bench_strf("synth_out.%s", ext);
    c->scratch = name ? ft_bench_path(name) : NULL;
    free(name);
    char *size = ft_bench_strf("%dx%d", n, n), *seed = ft_bench_strf("%llu", (unsigned long long)BENCH_SEED);
    const char *args[] = {prog, "synth", c->scratch, "--dim", "2.3", "--size", size, "--seed", seed,
                          "-f", driver, "--method", method};
    int rc = c->scratch && size && seed ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
    for (size_t i = 0; rc == FT_OK && i < sizeof args / sizeof args[0]; i++)
        if ((c->argv[i] = ft_bench_strdup(args[i])) == NULL)
            rc = ft_error(FT_E_NOMEM, "out of memory");
    free(size);
    free(seed);
    c->work = (double)n * n;
    return rc == FT_OK ? grass_peer_n(c, SYNTH_DIM, n) : rc;
}

static int cli_synth_4096(ft_bench_case *c)
{
    return cli_synth_setup(c, 4096, "tif", "GTiff", "fft");
}

static int cli_synth_2048(ft_bench_case *c)
{
    return cli_synth_setup(c, 2048, "tif", "GTiff", "fft");
}

static int cli_synth_4096_envi(ft_bench_case *c)
{
    return cli_synth_setup(c, 4096, "envi", "ENVI", "fft");
}

static int cli_synth_sra_4096(ft_bench_case *c)
{
    return cli_synth_setup(c, 4096, "tif", "GTiff", "sra");
}

/* cli.hillshade.4096: the DEM is written once, in a child (the harness stays small). */
static int write_hillshade_dem(void *arg)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.dim = SYNTH_DIM;
    o.seed = BENCH_SEED;
    o.cell = 10.0;
    o.sigma = 200.0;
    ft_grid *g = NULL;
    int rc = ft_terrain_synth(SYNTH_N, SYNTH_N, &o, &g);
    if (rc == FT_OK)
        rc = ft_io_write_grid(arg, g, NULL);
    ft_grid_free(g);
    return rc;
}

static int cli_hillshade_setup(ft_bench_case *c)
{
    const char *prog = ft_bench_fracterra_program();
    if (prog == NULL)
        return ft_error(FT_E_IO, "no fracterra program beside fracterra_bench (build the target fracterra_cli)");
    char *dem = ft_bench_path("hillshade_dem.tif");
    c->scratch = ft_bench_path("hillshade_out.tif");
    int rc = dem && c->scratch ? ft_bench_in_child(write_hillshade_dem, dem) : ft_error(FT_E_NOMEM, "out of memory");
    const char *args[] = {prog, "hillshade", dem, c->scratch};
    const char *peer[] = {"gdaldem", "hillshade", "-q", "-compute_edges", dem, c->scratch};
    for (size_t i = 0; rc == FT_OK && i < 4; i++)
        if ((c->argv[i] = ft_bench_strdup(args[i])) == NULL)
            rc = ft_error(FT_E_NOMEM, "out of memory");
    for (size_t i = 0; rc == FT_OK && i < 6; i++)
        if ((c->peer_argv[i] = ft_bench_strdup(peer[i])) == NULL)
            rc = ft_error(FT_E_NOMEM, "out of memory");
    free(dem);
    c->work = (double)SYNTH_N * SYNTH_N;
    return rc;
}

/* surface.variogram.32k */
static int variogram_setup(ft_bench_case *c)
{
    c->work = (double)SYNTH_N * SYNTH_N;
    c->peer_none = "none: Gwyddion's partitioning is compared in the surface suite";
    return FT_OK;
}

static int variogram_prepare(ft_bench_case *c)
{
    (void)c;
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.dim = SYNTH_DIM;
    o.seed = BENCH_SEED;
    return ft_terrain_synth(SYNTH_N, SYNTH_N, &o, &held_grid);
}

static int variogram_run(ft_bench_case *c)
{
    (void)c;
    ft_variogram_opts v = FT_VARIOGRAM_OPTS_DEFAULT;
    v.pairs = VARIOGRAM_POINTS;
    v.seed = BENCH_SEED;
    v.max_lag = SYNTH_N / 8;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim_variogram(held_grid, &v, &r);
    ft_dim_result_free(r);
    return rc;
}

static const ft_bench_workload terrain_workloads[] = {
    {"terrain.synth.fft.4096", "fft synthesis of a 4096x4096 D=2.3 surface (padded, cropped), one thread",
     FT_BENCH_CELLS, synth_setup, one_thread, synth_fft_run, NULL},
    {"terrain.synth.fft.4096.threads", "the same fft synthesis on OMP_NUM_THREADS threads", FT_BENCH_CELLS,
     synth_setup, NULL, synth_fft_run, NULL},
    {"terrain.synth.fft.4096.reuse", "the same fft synthesis into a reused grid and workspace "
     "(ft_terrain_synth_into, memory touched untimed like the floor's), one thread", FT_BENCH_CELLS, synth_setup,
     synth_reuse_prepare, synth_reuse_run, NULL},
    {"terrain.fftw.c2r.4096", "one in-place FFTW complex-to-real 4096x4096 transform, one thread",
     FT_BENCH_CELLS, c2r_setup, c2r_prepare, c2r_run, NULL},
    {"terrain.synth.sra.4096", "successive random addition, 4096x4096, D=2.3, one thread", FT_BENCH_CELLS,
     synth_sra_setup, one_thread, synth_sra_run, NULL},
    {"cli.synth.fft.4096", "fracterra synth out.tif --dim 2.3 --size 4096x4096, whole process (GeoTIFF defaults: ZSTD 1)",
     FT_BENCH_CELLS, cli_synth_4096, NULL, NULL, NULL},
    {"cli.synth.fft.2048", "fracterra synth out.tif --dim 2.3 --size 2048x2048, whole process (GeoTIFF defaults: ZSTD 1)",
     FT_BENCH_CELLS, cli_synth_2048, NULL, NULL, NULL},
    {"cli.synth.sra.4096", "fracterra synth out.tif --method sra, 4096x4096, whole process (GeoTIFF defaults: ZSTD 1)",
     FT_BENCH_CELLS, cli_synth_sra_4096, NULL, NULL, NULL},
    {"cli.synth.fft.4096.envi", "fracterra synth out.envi -f ENVI, 4096x4096, whole process (raw, no compression)",
     FT_BENCH_CELLS, cli_synth_4096_envi, NULL, NULL, NULL},
    {"cli.hillshade.4096", "fracterra hillshade of a 4096x4096 DEM to a GeoTIFF, whole process (peer: gdaldem "
     "hillshade -compute_edges)", FT_BENCH_CELLS, cli_hillshade_setup, NULL, NULL, NULL},
    {"surface.variogram.32k", "variogram D of a 4096x4096 grid from 32,000 random points, lags 1-512 cells",
     FT_BENCH_CELLS, variogram_setup, variogram_prepare, variogram_run, NULL},
};

const ft_bench_suite ft_bench_suite_terrain = {"terrain", terrain_workloads,
                                               sizeof terrain_workloads / sizeof terrain_workloads[0]};
