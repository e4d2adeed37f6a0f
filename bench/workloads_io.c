/* fracterra — workloads_io.c: I/O workloads of `make bench`.
 *
 * Inputs, generated once (deterministically, seed 20240501) in the bench folder and removed at the end:
 *  - grid4096.tif: 4096 x 4096 Float32 GeoTIFF in UTM 32N (EPSG:32632), 10 m cells, a smooth relief plus
 *    Gaussian noise, with a nodata disk of radius 300 cells; written through ft_io_write_grid;
 *  - line1m.geojson: one LineString of 1,000,000 vertices (a correlated random walk with 5 m steps),
 *    EPSG:32632, written through ft_io_write_layer.
 * Peers: gdal_translate, ogr2ogr, gdalinfo, ogrinfo (GDAL's command-line tools), doing the same work.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_conv.h>
#include <ogr_srs_api.h>

#include "fracterra/fracterra.h"

#define GRID_N 4096
#define LINE_N 1000000
#define BENCH_SEED UINT64_C(20240501)
#define BENCH_EPSG 32632

/* Creation options of the GeoTIFFs the copy workloads write, ours and the peer's alike (DEFLATE level 6,
 * the codec every reader has), spelt out so that both sides do the same work; io.geotiff.write.default
 * measures ft_io_write_grid's own defaults. */
#define TIF_CO_TEXT "TILED=YES COMPRESS=DEFLATE PREDICTOR=3 BIGTIFF=IF_SAFER NUM_THREADS=ALL_CPUS"
static const char *const tif_co[] = {"TILED=YES", "COMPRESS=DEFLATE", "PREDICTOR=3", "BIGTIFF=IF_SAFER",
                                     "NUM_THREADS=ALL_CPUS", NULL};

static const double pi = 3.14159265358979323846;

/* ------------------------------------------------------------------------------------------------
 * Inputs
 * --------------------------------------------------------------------------------------------- */

static char *tif_path;   /* NULL until generated */
static char *line_path;

static int crs_wkt(int epsg, char **wkt_out)
{
    *wkt_out = NULL;
    OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
    if (srs == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    char *wkt = NULL;
    int rc = FT_OK;
    if (OSRImportFromEPSG(srs, epsg) != OGRERR_NONE || OSRExportToWkt(srs, &wkt) != OGRERR_NONE)
        rc = ft_error(FT_E_UNSUPPORTED, "cannot build the CRS EPSG:%d (is proj-data installed?)", epsg);
    else if ((*wkt_out = ft_bench_strdup(wkt)) == NULL)
        rc = ft_error(FT_E_NOMEM, "out of memory");
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    return rc;
}

/* Smooth relief (two long waves and a ridge system) plus N(0, 4 m) noise, one RNG stream per row. */
static int make_grid(void *arg)
{
    const char *path = arg;
    ft_grid *g = ft_grid_create(GRID_N, GRID_N);
    if (g == NULL)
        return ft_last_error_code();
    int rc = ft_grid_ensure_mask(g);
    char *wkt = NULL;
    if (rc == FT_OK)
        rc = crs_wkt(BENCH_EPSG, &wkt);
    if (rc == FT_OK)
        rc = ft_grid_set_crs(g, wkt);
    free(wkt);
    for (size_t row = 0; rc == FT_OK && row < GRID_N; row++) {
        ft_rng *rng = ft_rng_create(BENCH_SEED, row);
        if (rng == NULL) {
            rc = ft_last_error_code();
            break;
        }
        double v = (double)row / GRID_N;
        for (size_t col = 0; col < GRID_N; col++) {
            double u = (double)col / GRID_N;
            double z = 800.0 + 300.0 * sin(2.0 * pi * 1.5 * u) * cos(2.0 * pi * 1.2 * v) +
                       120.0 * sin(2.0 * pi * 5.9 * (u + 0.7 * v)) + 35.0 * cos(2.0 * pi * 17.3 * (u - v)) +
                       ft_rng_gaussian(rng, 4.0);
            size_t i = row * GRID_N + col;
            g->z[i] = (float)z;
            double dx = (double)col - 3000.0, dy = (double)row - 1000.0;
            g->mask[i] = dx * dx + dy * dy > 300.0 * 300.0;
        }
        ft_rng_free(rng);
    }
    if (rc == FT_OK) {
        const double gt[6] = {500000.0, 10.0, 0.0, 5200000.0, 0.0, -10.0};
        memcpy(g->gt, gt, sizeof gt);
        g->has_nodata = 1;
        g->nodata_value = -9999.0;
        ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
        o.co = tif_co; /* DEFLATE, the codec of the files users read most */
        rc = ft_io_write_grid(path, g, &o);
    }
    ft_grid_free(g);
    return rc;
}

/* A correlated random walk: the heading drifts by N(0, 0.25 rad) per step, 5 m steps. */
static int make_line(void *arg)
{
    const char *path = arg;
    char *wkt = NULL;
    int rc = crs_wkt(BENCH_EPSG, &wkt);
    if (rc != FT_OK)
        return rc;
    ft_layer *l = ft_layer_create("line1m", wkt);
    free(wkt);
    if (l == NULL)
        return ft_last_error_code();
    ft_chain *c = ft_chain_create(LINE_N, 0);
    ft_rng *rng = ft_rng_create(BENCH_SEED, 1);
    int field = ft_layer_add_field(l, "name", FT_FIELD_STRING, -1, 0, 0);
    int64_t f = ft_layer_add_feature(l, 1, FT_GEOM_LINE, 0);
    if (c == NULL || rng == NULL || field < 0 || f < 0) {
        rc = field < 0 ? field : f < 0 ? (int)f : ft_last_error_code();
        ft_chain_free(c);
    } else {
        double x = 520000.0, y = 5180000.0, heading = 0.0;
        for (size_t i = 0; rc == FT_OK && i < LINE_N; i++) {
            rc = ft_chain_push(c, x, y);
            heading += ft_rng_gaussian(rng, 0.25);
            x += 5.0 * cos(heading);
            y += 5.0 * sin(heading);
        }
        if (rc == FT_OK)
            rc = ft_layer_set_string(l, (size_t)f, (size_t)field, "bench random walk");
        if (rc == FT_OK)
            rc = ft_layer_add_part(l, c, FT_ROLE_LINE, 0);
        else
            ft_chain_free(c);
    }
    if (rc == FT_OK) {
        static const char *const lco[] = {"COORDINATE_PRECISION=3", NULL};
        ft_write_layer_opts o = FT_WRITE_LAYER_OPTS_DEFAULT;
        o.lco = lco;
        rc = ft_io_write_layer(path, l, &o);
    }
    ft_rng_free(rng);
    ft_layer_free(l);
    return rc;
}

static int need_input(char **path, const char *name, int (*make)(void *), const char *what)
{
    if (*path != NULL)
        return FT_OK;
    char *p = ft_bench_path(name);
    if (p == NULL)
        return ft_last_error_code();
    fprintf(stderr, "fracterra_bench: generating %s (%s)\n", name, what);
    int rc = ft_bench_in_child(make, p);
    if (rc != FT_OK) {
        free(p);
        return rc;
    }
    *path = p;
    return FT_OK;
}

static int need_grid(void)
{
    return need_input(&tif_path, "grid4096.tif", make_grid, "4096 x 4096 Float32 GeoTIFF");
}

static int need_line(void)
{
    return need_input(&line_path, "line1m.geojson", make_line, "GeoJSON LineString of 1,000,000 vertices");
}

/* ------------------------------------------------------------------------------------------------
 * Helpers
 * --------------------------------------------------------------------------------------------- */

/* Fills a NULL-terminated argv with copies of the strings given (NULL-terminated list). */
static int set_argv(char **argv, ...)
{
    va_list ap;
    va_start(ap, argv);
    int n = 0, rc = FT_OK;
    const char *s;
    while ((s = va_arg(ap, const char *)) != NULL) {
        if (n >= FT_BENCH_MAX_ARGV - 1) {
            rc = ft_error(FT_E_INVALID, "more than %d arguments", FT_BENCH_MAX_ARGV - 1);
            break;
        }
        if ((argv[n++] = ft_bench_strdup(s)) == NULL) {
            rc = ft_error(FT_E_NOMEM, "out of memory");
            break;
        }
    }
    va_end(ap);
    return rc;
}

static int check_grid(const ft_grid *g)
{
    if (g->nx != GRID_N || g->ny != GRID_N)
        return ft_error(FT_E_FORMAT, "expected a %d x %d grid, read %zu x %zu", GRID_N, GRID_N, g->nx, g->ny);
    return FT_OK;
}

static ft_grid *held_grid; /* a prepared grid, in the child only */

static ft_write_grid_opts tif_opts(void)
{
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.co = tif_co;
    return o;
}

/* ------------------------------------------------------------------------------------------------
 * io.geotiff.read
 * --------------------------------------------------------------------------------------------- */

static int geotiff_read_setup(ft_bench_case *c)
{
    int rc = need_grid();
    if (rc != FT_OK)
        return rc;
    c->work = (double)GRID_N * GRID_N;
    return set_argv(c->peer_argv, "gdal_translate", "-q", "-of", "MEM", tif_path, "mem", (const char *)NULL);
}

static int geotiff_read_run(ft_bench_case *c)
{
    ft_grid *g = NULL;
    int rc = ft_io_read_grid(tif_path, NULL, &g);
    if (rc == FT_OK)
        rc = check_grid(g);
    ft_grid_free(g);
    return rc;
}

/* ------------------------------------------------------------------------------------------------
 * io.geotiff.write
 * --------------------------------------------------------------------------------------------- */

static int geotiff_write_setup(ft_bench_case *c)
{
    int rc = need_grid();
    if (rc != FT_OK)
        return rc;
    c->work = (double)GRID_N * GRID_N;
    c->peer_none = "none: no command-line tool writes a GeoTIFF from memory (see io.geotiff.copy)";
    c->scratch = ft_bench_path("write_out.tif");
    return c->scratch ? FT_OK : ft_last_error_code();
}

static int geotiff_prepare(ft_bench_case *c)
{
    int rc = ft_io_read_grid(tif_path, NULL, &held_grid);
    return rc == FT_OK ? check_grid(held_grid) : rc;
}

static int geotiff_write_run(ft_bench_case *c)
{
    ft_write_grid_opts o = tif_opts();
    return ft_io_write_grid(c->scratch, held_grid, &o);
}

/* io.geotiff.write.default: ft_io_write_grid's GeoTIFF defaults (ZSTD level 1, predictor 3, all cores) */
static int geotiff_write_default_run(ft_bench_case *c)
{
    return ft_io_write_grid(c->scratch, held_grid, NULL);
}

/* io.geotiff.write.deflate1: the same defaults with DEFLATE level 1 (the default before ZSTD, and what
 * FRACTERRA_GTIFF_COMPRESS=DEFLATE gives): the cost of the codec every reader has */
static int geotiff_write_deflate1_run(ft_bench_case *c)
{
    static const char *const co[] = {"COMPRESS=DEFLATE", "ZLEVEL=1", NULL};
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.co = co;
    return ft_io_write_grid(c->scratch, held_grid, &o);
}

/* ------------------------------------------------------------------------------------------------
 * io.geotiff.copy: read + write, the work of gdal_translate
 * --------------------------------------------------------------------------------------------- */

static int geotiff_copy_setup(ft_bench_case *c)
{
    int rc = need_grid();
    if (rc != FT_OK)
        return rc;
    c->work = (double)GRID_N * GRID_N;
    c->scratch = ft_bench_path("copy_out.tif");
    if (c->scratch == NULL)
        return ft_last_error_code();
    return set_argv(c->peer_argv, "gdal_translate", "-q", "-of", "GTiff", "-co", tif_co[0], "-co", tif_co[1],
                    "-co", tif_co[2], "-co", tif_co[3], "-co", tif_co[4], tif_path, c->scratch, (const char *)NULL);
}

static int geotiff_copy_run(ft_bench_case *c)
{
    ft_grid *g = NULL;
    int rc = ft_io_read_grid(tif_path, NULL, &g);
    if (rc == FT_OK)
        rc = check_grid(g);
    if (rc == FT_OK) {
        ft_write_grid_opts o = tif_opts();
        rc = ft_io_write_grid(c->scratch, g, &o);
    }
    ft_grid_free(g);
    return rc;
}

/* ------------------------------------------------------------------------------------------------
 * io.geojson.read
 * --------------------------------------------------------------------------------------------- */

static int geojson_read_setup(ft_bench_case *c)
{
    int rc = need_line();
    if (rc != FT_OK)
        return rc;
    c->work = (double)LINE_N;
    return set_argv(c->peer_argv, "ogr2ogr", "-f", "Memory", "mem", line_path, (const char *)NULL);
}

static int geojson_read_run(ft_bench_case *c)
{
    ft_layer *l = NULL;
    int rc = ft_io_read_layer(line_path, NULL, &l);
    if (rc == FT_OK) {
        size_t n = ft_layer_vertex_count(l);
        c->work = (double)n;
        if (n != LINE_N)
            rc = ft_error(FT_E_FORMAT, "expected %d vertices, read %zu", LINE_N, n);
    }
    ft_layer_free(l);
    return rc;
}

/* ------------------------------------------------------------------------------------------------
 * cli.info.*: the built `fracterra info` program, whole process
 * --------------------------------------------------------------------------------------------- */

static int fracterra_argv(ft_bench_case *c, const char *path)
{
    const char *prog = ft_bench_fracterra_program();
    if (prog == NULL)
        return ft_error(FT_E_IO, "no fracterra program beside fracterra_bench (build the target fracterra_cli)");
    return set_argv(c->argv, prog, "info", path, (const char *)NULL);
}

static int info_geotiff_setup(ft_bench_case *c)
{
    int rc = need_grid();
    if (rc == FT_OK)
        rc = fracterra_argv(c, tif_path);
    if (rc == FT_OK)
        rc = set_argv(c->peer_argv, "gdalinfo", "-mm", tif_path, (const char *)NULL);
    c->work = (double)GRID_N * GRID_N;
    return rc;
}

static int info_geojson_setup(ft_bench_case *c)
{
    int rc = need_line();
    if (rc == FT_OK)
        rc = fracterra_argv(c, line_path);
    if (rc == FT_OK)
        rc = set_argv(c->peer_argv, "ogrinfo", "-ro", "-al", "-so", line_path, (const char *)NULL);
    c->work = (double)LINE_N;
    return rc;
}

/* ------------------------------------------------------------------------------------------------
 * The suite
 * --------------------------------------------------------------------------------------------- */

static const ft_bench_workload io_workloads[] = {
    {"io.geotiff.read", "ft_io_read_grid of grid4096.tif (4096 x 4096 Float32, DEFLATE, nodata disk)", FT_BENCH_CELLS,
     geotiff_read_setup, NULL, geotiff_read_run, NULL},
    {"io.geotiff.write", "ft_io_write_grid of that grid, " TIF_CO_TEXT, FT_BENCH_CELLS,
     geotiff_write_setup, geotiff_prepare, geotiff_write_run, NULL},
    {"io.geotiff.write.default", "ft_io_write_grid of that grid with its GeoTIFF defaults (ZSTD 1, predictor 3)",
     FT_BENCH_CELLS, geotiff_write_setup, geotiff_prepare, geotiff_write_default_run, NULL},
    {"io.geotiff.write.deflate1", "the same with COMPRESS=DEFLATE ZLEVEL=1 (FRACTERRA_GTIFF_COMPRESS=DEFLATE)",
     FT_BENCH_CELLS, geotiff_write_setup, geotiff_prepare, geotiff_write_deflate1_run, NULL},
    {"io.geotiff.copy", "ft_io_read_grid + ft_io_write_grid, " TIF_CO_TEXT, FT_BENCH_CELLS,
     geotiff_copy_setup, NULL, geotiff_copy_run, NULL},
    {"io.geojson.read", "ft_io_read_layer of line1m.geojson (one LineString, 1,000,000 vertices)",
     FT_BENCH_VERTICES, geojson_read_setup, NULL, geojson_read_run, NULL},
    {"cli.info.geotiff", "fracterra info grid4096.tif", FT_BENCH_CELLS, info_geotiff_setup, NULL, NULL, NULL},
    {"cli.info.geojson", "fracterra info line1m.geojson", FT_BENCH_VERTICES, info_geojson_setup, NULL, NULL,
     NULL},
};

const ft_bench_suite ft_bench_suite_io = {"io", io_workloads, sizeof io_workloads / sizeof io_workloads[0]};
