/* fracterra — workloads_tiles.c: `dim map` and `dim surface` stripe by stripe and on MPI ranks
 * (docs/tiling.md) in `make bench`.
 *
 * Input: an N x N Float32 GeoTIFF fBm (D = 2.4, seed 20240501, UTM 33N, 10 m cells) made once by the
 * library in a child; N = $FT_BENCH_TILES_SIZE, default 16384 (the size: a 1 GB file, and a whole-
 * raster `dim map` needs about 5 GB). Each workload is a whole `fracterra` process (or `mpiexec` with its
 * ranks: the peak RSS is then the largest process's), and its "peer" is the run it is compared with:
 *  - tiles.dim_map.tiled: `dim map --window 64 --step 16 --tile-rows 1024` against the whole-raster run
 *    (same cells): the ratio is the cost of tiling (target within 10%), the RSS columns the memory bound;
 *  - tiles.dim_map.2ranks / tiles.dim_surface.2ranks: `mpiexec -n 2` against `mpiexec -n 1`, one OpenMP
 *    thread per rank (-x OMP_NUM_THREADS=1): parallel efficiency = 1 / (2 x ratio) (target >= 80% on an idle
 *    2-core machine). dim surface is the exhaustive variogram (--pairs 0).
 *  - tiles.synth_fft.2ranks: `mpiexec -n 2 synth OUT.vrt --method fft` (FFTW's distributed transform, each rank
 *    writing its part, one thread a rank for its FFT and its GDAL compression) against `mpiexec -n 1`, on an
 *    N x N surface (target: 2 ranks >= 1.6x the 1-rank speed).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fracterra/fracterra.h"

#define TILES_SEED UINT64_C(20240501)

static char *held_dem; /* the input's path, made once */

static size_t tiles_size(void)
{
    const char *s = getenv("FT_BENCH_TILES_SIZE");
    long n = s ? strtol(s, NULL, 10) : 16384;
    return n >= 256 && n <= 65536 ? (size_t)n : 16384;
}

static int make_dem(void *arg)
{
    const char *path = arg;
    size_t n = tiles_size();
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = 2.4;
    so.seed = TILES_SEED;
    so.cell = 10.0;
    so.origin_x = 400000.0;
    so.origin_y = 5000000.0 + 10.0 * (double)n;
    ft_grid *g = NULL;
    int rc = ft_terrain_synth(n, n, &so, &g);
    char *wkt = NULL;
    if (rc == FT_OK && (rc = ft_io_crs_to_wkt("EPSG:32633", &wkt)) == FT_OK)
        rc = ft_grid_set_crs(g, wkt);
    if (rc == FT_OK)
        rc = ft_io_write_grid(path, g, NULL);
    free(wkt);
    ft_grid_free(g);
    return rc;
}

static const char *dem_path(void)
{
    if (held_dem != NULL)
        return held_dem;
    char *path = ft_bench_path("tiles_dem.tif");
    if (path == NULL || ft_bench_in_child(make_dem, path) != FT_OK) {
        free(path);
        return NULL;
    }
    return held_dem = path;
}

/* Copies args[0..n) into dst (NULL-terminated by the zeroed case). */
static int put_argv(char **dst, const char *const *args, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if ((dst[i] = ft_bench_strdup(args[i])) == NULL)
            return ft_error(FT_E_NOMEM, "out of memory");
    return FT_OK;
}

/* `[mpiexec -n ranks ...] fracterra ARGS` into dst; ranks 0 = no mpiexec. */
static int command(char **dst, int ranks, const char *const *args, size_t n)
{
    const char *prog = ft_bench_fracterra_program();
    if (prog == NULL)
        return ft_error(FT_E_IO, "no fracterra program beside fracterra_bench (build the target fracterra_cli)");
    const char *all[FT_BENCH_MAX_ARGV];
    size_t k = 0;
    char nr[16];
    snprintf(nr, sizeof nr, "%d", ranks);
    if (ranks > 0) {
        const char *mpi[] = {"mpiexec", "-n", nr, "--oversubscribe", "-x", "OMP_NUM_THREADS=1"};
        for (size_t i = 0; i < sizeof mpi / sizeof mpi[0]; i++)
            all[k++] = mpi[i];
        if (geteuid() == 0)
            all[k++] = "--allow-run-as-root";
    }
    all[k++] = prog;
    all[k++] = "--max-work"; /* an N x N grid beyond the default work bound is what this suite measures */
    all[k++] = "1e13";
    for (size_t i = 0; i < n && k + 1 < FT_BENCH_MAX_ARGV; i++)
        all[k++] = args[i];
    return put_argv(dst, all, k);
}

static int map_setup(ft_bench_case *c, int mpi)
{
    const char *dem = dem_path();
    if (dem == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : ft_error(FT_E_IO, "cannot make the input DEM");
    c->scratch = ft_bench_path("tiles_map.tif");
    if (c->scratch == NULL)
        return FT_E_NOMEM;
    size_t n = tiles_size();
    c->work = (double)n * (double)n;
    const char *tiled[] = {"dim", "map", dem, c->scratch, "--window", "64", "--step", "16", "--tile-rows", "1024"};
    const char *whole[] = {"dim", "map", dem, c->scratch, "--window", "64", "--step", "16"};
    if (!mpi) {
        int rc = command(c->argv, 0, tiled, sizeof tiled / sizeof tiled[0]);
        return rc == FT_OK ? command(c->peer_argv, 0, whole, sizeof whole / sizeof whole[0]) : rc;
    }
    int rc = command(c->argv, 2, whole, sizeof whole / sizeof whole[0]);
    return rc == FT_OK ? command(c->peer_argv, 1, whole, sizeof whole / sizeof whole[0]) : rc;
}

static int map_tiled_setup(ft_bench_case *c)
{
    return map_setup(c, 0);
}

static int map_ranks_setup(ft_bench_case *c)
{
    return map_setup(c, 1);
}

static int surface_ranks_setup(ft_bench_case *c)
{
    const char *dem = dem_path();
    if (dem == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : ft_error(FT_E_IO, "cannot make the input DEM");
    size_t n = tiles_size();
    c->work = (double)n * (double)n;
    const char *args[] = {"dim", "surface", dem, "--pairs", "0", "--tile-rows", "1024", "--json"};
    int rc = command(c->argv, 2, args, sizeof args / sizeof args[0]);
    return rc == FT_OK ? command(c->peer_argv, 1, args, sizeof args / sizeof args[0]) : rc;
}

static int synth_ranks_setup(ft_bench_case *c)
{
    size_t n = tiles_size();
    c->work = (double)n * (double)n;
    /* OUT.vrt: each rank writes its own part (tiles_synth.part-000r.tif, registered for removal) */
    c->scratch = ft_bench_path("tiles_synth.vrt");
    if (c->scratch == NULL)
        return FT_E_NOMEM;
    for (int k = 0; k < 2; k++) {
        char name[64];
        snprintf(name, sizeof name, "tiles_synth.part-%04d.tif", k);
        char *part = ft_bench_path(name);
        if (part == NULL)
            return FT_E_NOMEM;
        free(part);
    }
    char size[64];
    snprintf(size, sizeof size, "%zux%zu", n, n);
    const char *args[] = {"synth", c->scratch, "--dim", "2.3", "--size", size, "--seed", "3"};
    int rc = command(c->argv, 2, args, sizeof args / sizeof args[0]);
    return rc == FT_OK ? command(c->peer_argv, 1, args, sizeof args / sizeof args[0]) : rc;
}

static void tiles_teardown(ft_bench_case *c)
{
    (void)c; /* the DEM stays for the next workload; the harness removes it at exit */
}

static const ft_bench_workload tiles_workloads[] = {
    {"tiles.dim_map.tiled", "dim map W 64 S 16 in stripes of 1024 rows (peer: the whole-raster run)", FT_BENCH_CELLS,
     map_tiled_setup, NULL, NULL, tiles_teardown},
    {"tiles.dim_map.2ranks", "dim map W 64 S 16 on 2 MPI ranks, 1 thread each (peer: 1 rank)", FT_BENCH_CELLS,
     map_ranks_setup, NULL, NULL, tiles_teardown},
    {"tiles.dim_surface.2ranks", "dim surface, exhaustive variogram, on 2 MPI ranks, 1 thread each (peer: 1 rank)",
     FT_BENCH_CELLS, surface_ranks_setup, NULL, NULL, tiles_teardown},
    {"tiles.synth_fft.2ranks",
     "synth --method fft (FFTW MPI) to a .vrt of per-rank parts on 2 MPI ranks, 1 thread each (peer: 1 rank)",
     FT_BENCH_CELLS, synth_ranks_setup, NULL, NULL, tiles_teardown},
};

const ft_bench_suite ft_bench_suite_tiles = {"tiles", tiles_workloads,
                                             sizeof tiles_workloads / sizeof tiles_workloads[0]};
