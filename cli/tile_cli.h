/* fracterra — cli/tile_cli.h: `dim map`, `dim surface`, `hillshade` and `fill` on a raster read stripe by stripe (bounded memory)
 * and, under mpiexec, on several ranks (tile_dim.c). The cells of a D map and the D of a surface are those of
 * the whole-raster run, bit for bit. docs/tiling.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_TILE_H
#define FRACTERRA_CLI_TILE_H

#include "cli.h"

/** Parses --tile-rows N (rows of input cells per stripe, 1 .. 10^8). */
int tile_parse_rows(const cli_command *cmd, const char *arg, long *rows);
/** 1 if a command must run stripe by stripe: --tile-rows given, started by mpiexec (any number of ranks, so
 *  that the result does not depend on it), or the band (nx x ny cells of bytes_per_cell bytes while
 *  measured) larger than half of --max-memory. */
int tile_wanted(long tile_rows, size_t nx, size_t ny, double bytes_per_cell);
/** The band's size without reading its cells: CLI_CONTINUE, or CLI_FAIL (printed). */
int tile_band_size(const cli_command *cmd, const char *path, int band, size_t *nx, size_t *ny);

/** GDAL's compression threads for a write under mpiexec, so that a rank keeps to its share of the cores as
 *  its OpenMP threads do: NUM_THREADS = GDAL_NUM_THREADS when the user set it, else cli_ranks_threads()
 *  (OMP_NUM_THREADS, else the node's cores / its ranks). Points wo->co at t's storage (t must outlive the
 *  write). Without mpiexec wo is left as it is (the library's default: every core). */
/** 1 if OUT names a mosaic (ends in .vrt): under mpiexec the ranks write parts beside it (tile_synth). */
int tile_is_mosaic(const char *out);

typedef struct {
    char opt[64];
    const char *co[2];
} tile_threads;
void tile_write_threads(ft_write_grid_opts *wo, tile_threads *t);

/** This rank's share [*a, *b) of n rows (the r-th of P nearly equal parts). */
void tile_rank_share(size_t n, size_t *a, size_t *b);

typedef struct {
    size_t window, step;
    ft_surface_method method;
    ft_surface_dim_opts opts;
    int band;
    const char *driver;
    long tile_rows;     /* 0: automatic */
} tile_map_job;

/** What `dim map` reports: the lattice size, the D of the measured windows, summed in row order, and how many
 *  of them had white noise removed (ft_surface_dim_map_noise's flag). */
typedef struct {
    size_t nox, noy, measured;
    double lo, hi, sum;
    size_t nugget;
} tile_map_stats;

/** The D map (band 1) and r² (band 2) of the DEM into OUT (GeoTIFF), stripe by stripe, ranks sharing the
 *  stripes; rank 0 writes. CLI_OK with *st on rank 0, or CLI_FAIL (printed). */
int tile_dim_map(const cli_command *cmd, const char *in, const char *out, const tile_map_job *job,
                 tile_map_stats *st);

/** D of the whole DEM by an exhaustive lag method, stripe by stripe, ranks adding their rows in order. On
 *  rank 0, CLI_OK with *out, the band's size, valid cells and CRS; other ranks CLI_OK with *out NULL. */
int tile_dim_surface(const cli_command *cmd, const char *in, int band, ft_surface_method m,
                     const ft_surface_dim_opts *o, long tile_rows, ft_dim_result **out, size_t *nx, size_t *ny,
                     uint64_t *valid, ft_crs_info *crs);

/** The hillshade of the DEM into OUT (a Byte GeoTIFF, 0 = nodata) stripe by stripe (tile_hillshade.c), ranks
 *  sharing the stripes, rank 0 writing: the cells of ft_io_hillshade's. CLI_OK or CLI_FAIL (printed). */
int tile_hillshade(const cli_command *cmd, const char *in, const char *out, const ft_io_hillshade_opts *o,
                   long tile_rows);

typedef struct {
    const char *in, *out, *mask; /* DEM, OUT (GeoTIFF), --mask (may be NULL) */
    ft_fill_opts fo;             /* max_void in cells */
    int band;
    long tile_rows;              /* 0: automatic */
} tile_fill_job;

/** `fill` stripe by stripe (tile_fill.c), ranks sharing the stripes, rank 0 writing OUT: the cells of
 *  ft_terrain_fill's. On rank 0, CLI_OK with *res (voids in raster order, totals; free res->voids) and *st
 *  (the output's band 1 figures, as ft_grid_compute_stats gives them); or CLI_FAIL (printed). */
int tile_fill(const cli_command *cmd, const tile_fill_job *job, ft_fill_result *res, ft_grid_stats *st);

/** The figures of band 1 of the raster at path, read `rows` rows at a time and summed in row order as
 *  ft_grid_compute_stats sums a whole grid (tile_fill.c). CLI_OK or CLI_FAIL (printed). */
int tile_output_stats(const cli_command *cmd, const char *path, size_t rows, ft_grid_stats *st);

#ifdef FT_HAVE_FFTW_MPI
/** `synth --method fft` on the MPI ranks with FFTW's distributed c2r (tile_synth.c): the nx x ny surface of so
 *  (wkt: its CRS or NULL) into OUT: a GeoTIFF written by rank 0, or (OUT.vrt) one GeoTIFF part per rank,
 *  OUT's stem + ".part-NNNN.tif", written in parallel, and the VRT over them. On rank 0, CLI_OK with *st (the
 *  output's figures, read back from OUT; st may be NULL); or CLI_FAIL (printed). Collective. */
int tile_synth(const cli_command *cmd, size_t nx, size_t ny, const ft_synth_opts *so, const char *wkt,
               const char *out, ft_grid_stats *st);
#endif

#endif /* FRACTERRA_CLI_TILE_H */
