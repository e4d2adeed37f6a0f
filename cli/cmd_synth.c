/* fracterra — cli/cmd_synth.c: `fracterra synth OUT.tif --dim D --size NxM`: a fractional Brownian surface
 * of dimension D (ft_terrain_synth: spectral, successive random addition, midpoint displacement or exact
 * circulant embedding; docs/terrain-synthesis.md), written as a georeferenced raster.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain_cli.h"

#include "cli_ranks.h"
#include "tile_cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define SYNTH_MAX_SIDE 65536

typedef struct {
    ft_synth_opts so;
    size_t nx, ny;
    int have_dim, have_size, json;
    const char *crs, *driver;
} synth_args;

/* "NxM" (columns x rows), each in [1, SYNTH_MAX_SIDE]. */
static int parse_size(const cli_command *cmd, const char *arg, size_t *nx, size_t *ny)
{
    char *end = NULL;
    unsigned long a = 0, b = 0;
    int ok = arg[0] >= '0' && arg[0] <= '9';
    if (ok) {
        a = strtoul(arg, &end, 10);
        ok = (*end == 'x' || *end == 'X') && end[1] >= '0' && end[1] <= '9';
    }
    if (ok) {
        b = strtoul(end + 1, &end, 10);
        ok = *end == '\0' && a >= 1 && b >= 1 && a <= SYNTH_MAX_SIDE && b <= SYNTH_MAX_SIDE;
    }
    if (!ok)
        return cli_usage_error(cmd, "--size must be NxM (columns x rows, each in [1,%d]), got '%s'", SYNTH_MAX_SIDE,
                               arg);
    *nx = a;
    *ny = b;
    return CLI_CONTINUE;
}

static int parse_origin(const cli_command *cmd, const char *arg, double *x, double *y)
{
    char *end = NULL;
    *x = strtod(arg, &end);
    int ok = end != arg && *end == ',' && isfinite(*x);
    if (ok) {
        const char *s = end + 1;
        *y = strtod(s, &end);
        ok = end != s && *end == '\0' && isfinite(*y);
    }
    return ok ? CLI_CONTINUE : cli_usage_error(cmd, "--origin must be X,Y (two numbers), got '%s'", arg);
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    synth_args *a = ctx;
    switch (opt) {
    case 'd':
        a->have_dim = 1;
        return cli_parse_double(cmd, "--dim", arg, 2.0, 3.0, CLI_OPEN_LO | CLI_OPEN_HI, &a->so.dim);
    case 's':
        a->have_size = 1;
        return parse_size(cmd, arg, &a->nx, &a->ny);
    case 'm':
        return ft_synth_method_parse(arg, &a->so.method) == FT_OK
                   ? CLI_CONTINUE
                   : cli_usage_error(cmd, "--method must be fft, sra, midpoint, exact, sra-raw or midpoint-raw, got '%s'", arg);
    case 'c': return cli_parse_double(cmd, "--cell", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->so.cell);
    case 'o': return parse_origin(cmd, arg, &a->so.origin_x, &a->so.origin_y);
    case 'r': a->crs = arg; return CLI_CONTINUE;
    /* Elevations are stored as float: a few sigmas must stay far below FLT_MAX (3.4e38). */
    case 'g': return cli_parse_double(cmd, "--sigma", arg, 0.0, 1e30, CLI_CLOSED, &a->so.sigma);
    case 'p': a->so.periodic = 1; return CLI_CONTINUE;
    case 'S': return terrain_parse_seed(cmd, arg, &a->so.seed);
    case 'f': a->driver = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* g: the grid (its figures computed here), or with st the header of a surface written by the ranks. */
static int report(const cli_command *cmd, const synth_args *a, const char *out, const ft_grid *g,
                  const ft_grid_stats *st)
{
    if (!a->json) {
        printf("wrote %s: %zu x %zu cells, D = %g (%s), seed %llu\n", out, a->nx, a->ny, a->so.dim,
               ft_synth_method_name(a->so.method), (unsigned long long)a->so.seed);
        return CLI_OK;
    }
    json_object *o = json_object_new_object();
    json_object_object_add(o, "output", json_object_new_string(out));
    json_object_object_add(o, "method", json_object_new_string(ft_synth_method_name(a->so.method)));
    json_object_object_add(o, "D", cli_json_double(a->so.dim));
    json_object_object_add(o, "D_param", cli_json_double(ft_synth_raw_dim(a->so.method, a->so.dim, a->nx, a->ny)));
    json_object_object_add(o, "seed", json_object_new_uint64(a->so.seed));
    json_object_object_add(o, "sigma", cli_json_double(a->so.sigma));
    json_object_object_add(o, "cell", cli_json_double(a->so.cell));
    json_object *origin = json_object_new_array();
    json_object_array_add(origin, cli_json_double(a->so.origin_x));
    json_object_array_add(origin, cli_json_double(a->so.origin_y));
    json_object_object_add(o, "origin", origin);
    json_object_object_add(o, "periodic", json_object_new_boolean(a->so.periodic));
    if (st != NULL)
        terrain_add_grid_json_of(o, g, st);
    else
        terrain_add_grid_json(o, g);
    return cli_print_json(cmd, o);
}

static int synthesize(const cli_command *cmd, synth_args *a, const char *out)
{
    char *wkt = NULL;
    if (a->crs && ft_io_crs_to_wkt(a->crs, &wkt) != FT_OK) {
        cli_error(cmd, "--crs: %s", ft_last_error());
        return CLI_USAGE;
    }
    if (ft_io_check_writable(out) != FT_OK) {
        free(wkt);
        return cli_fail(cmd);
    }
    ft_grid *g = NULL;
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    wo.driver = a->driver;
    a->so.progress = cli_progress();
    int rc = ft_terrain_synth(a->nx, a->ny, &a->so, &g);
    if (rc == FT_OK)
        rc = ft_grid_set_crs(g, wkt);
    if (rc == FT_OK)
        rc = ft_io_write_grid(out, g, &wo);
    free(wkt);
    int status = rc == FT_OK ? report(cmd, a, out, g, NULL) : cli_fail(cmd);
    ft_grid_free(g);
    return status;
}

#ifdef FT_HAVE_FFTW_MPI
/* Under mpiexec: the fft surface on the ranks (tile_synth.c), rank 0 writing one GeoTIFF. */
static int synthesize_ranks(const cli_command *cmd, synth_args *a, const char *out)
{
    char *wkt = NULL;
    int ok = !a->crs || ft_io_crs_to_wkt(a->crs, &wkt) == FT_OK;
    if (!ok)
        cli_error(cmd, "--crs: %s", ft_last_error());
    else if (cli_rank() == 0 && ft_io_check_writable(out) != FT_OK)
        ok = (cli_fail(cmd), 0);
    if (!cli_ranks_all_ok(ok)) {
        free(wkt);
        return a->crs && wkt == NULL ? CLI_USAGE : CLI_FAIL;
    }
    ft_grid_stats st;
    int rc = tile_synth(cmd, a->nx, a->ny, &a->so, wkt, out, a->json ? &st : NULL);
    if (rc == CLI_OK && cli_rank() == 0) {
        ft_grid hdr = {.nx = a->nx, .ny = a->ny, .crs_wkt = wkt,
                       .gt = {a->so.origin_x, a->so.cell, 0.0, a->so.origin_y, 0.0, -a->so.cell}};
        rc = report(cmd, a, out, &hdr, a->json ? &st : NULL);
    }
    free(wkt);
    return rc;
}
#endif

static int run_synth(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"dim", required_argument, NULL, 'd'},    {"size", required_argument, NULL, 's'},
        {"method", required_argument, NULL, 'm'}, {"cell", required_argument, NULL, 'c'},
        {"origin", required_argument, NULL, 'o'}, {"crs", required_argument, NULL, 'r'},
        {"sigma", required_argument, NULL, 'g'},  {"periodic", no_argument, NULL, 'p'},
        {"seed", required_argument, NULL, 'S'},   {"format", required_argument, NULL, 'f'},
        {"json", no_argument, NULL, 'j'},         CLI_OPT_HELP,
        CLI_OPT_END};
    static const char *const names[] = {"OUT"};
    synth_args a = {.so = FT_SYNTH_OPTS_DEFAULT};
    a.so.seed = TERRAIN_DEFAULT_SEED;
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "f:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE && !a.have_dim)
        rc = cli_usage_error(cmd, "missing --dim D (the fractal dimension, in (2,3))");
    if (rc == CLI_CONTINUE && !a.have_size)
        rc = cli_usage_error(cmd, "missing --size NxM (columns x rows)");
    if (rc == CLI_CONTINUE && a.so.periodic && a.so.method != FT_SYNTH_FFT)
        rc = cli_usage_error(cmd, "--periodic is for --method fft (only its tile wraps), got --method %s",
                             ft_synth_method_name(a.so.method));
    if (rc == CLI_CONTINUE && cli_ranks_joined() && a.so.method != FT_SYNTH_FFT)
        rc = cli_usage_error(cmd, "under mpiexec only --method fft runs (on FFTW's distributed transform), got "
                             "--method %s", ft_synth_method_name(a.so.method));
    if (rc == CLI_CONTINUE && cli_ranks_joined() && a.driver && strcasecmp(a.driver, "GTiff") != 0)
        rc = cli_usage_error(cmd, "under mpiexec the surface is written as GeoTIFF (one file, or one part a rank "
                             "under OUT.vrt), got -f %s", a.driver);
    if (rc == CLI_CONTINUE && !cli_ranks_joined() && tile_is_mosaic(argv[first]))
        rc = cli_usage_error(cmd, "'%s': a .vrt mosaic of parts is written under mpiexec only (one part a rank); "
                             "one process writes one raster: give OUT.tif", argv[first]);
    if (rc != CLI_CONTINUE)
        return rc;
    /* float output, a padded FFT grid of doubles and its complex spectrum: about 32 bytes a cell */
    double cells = (double)a.nx * (double)a.ny / (double)cli_nranks(); /* each rank holds a slab */
    char what[96];
    snprintf(what, sizeof what, "--size %zux%zu (%.3g cells)", a.nx, a.ny, cells);
    if (ft_check_memory(32.0 * cells, what) != FT_OK ||
        ft_check_work(cells * fmax(1.0, log2(fmax((double)a.nx, (double)a.ny))), what) != FT_OK)
        return cli_fail(cmd);
#ifdef FT_HAVE_FFTW_MPI
    if (cli_ranks_joined())
        return synthesize_ranks(cmd, &a, argv[first]);
#endif
    return synthesize(cmd, &a, argv[first]);
}

const cli_command cli_cmd_synth = {
    "synth",
    "synthesize a fractional Brownian terrain of dimension D (fft, sra, midpoint, exact)",
    "fracterra synth OUT.tif --dim D --size NxM [--method fft|sra|midpoint|exact|sra-raw|midpoint-raw]\n"
    "       [--cell SIZE] [--origin X,Y] [--crs EPSG:n|WKT] [--sigma S] [--periodic] [--seed N] [-f DRIVER]\n"
    "       [--json]",
    "Writes a fractional Brownian surface of dimension D = 3 - H as a one-band Float32 raster (GeoTIFF\n"
    "unless the extension or -f says otherwise), north-up with the given cell size, origin and CRS.\n"
    "A GeoTIFF is tiled and compressed losslessly with ZSTD (FRACTERRA_GTIFF_COMPRESS=DEFLATE for\n"
    "readers without ZSTD; fracterra(1), ENVIRONMENT).\n"
    "The same options and seed give identical cells on any machine and thread count.\n"
    "Under mpiexec -n N (built with FFTW's MPI transforms) --method fft runs on the N ranks, each holding\n"
    "about 1/N of the padded grid: the cells of the one-process run to the transform's rounding\n"
    "(docs/tiling.md). OUT.tif: rank 0 writes one GeoTIFF. OUT.vrt: each rank writes its rows, in\n"
    "parallel, as OUT's stem + .part-NNNN.tif beside it, then rank 0 the VRT mosaic (GDAL reads it as one\n"
    "raster; it names its parts relative to itself: move them together); on an error nothing is left.\n"
    "Each rank compresses with its share of the cores (GDAL_NUM_THREADS, else OMP_NUM_THREADS, else\n"
    "cores / ranks on the node).\n\n"
    "Options:\n"
    "  --dim D          fractal dimension, in (2,3) (required)\n"
    "  --size NxM       columns x rows (required), each up to 65536\n"
    "  --method NAME    fft (default): spectral synthesis on a padded grid, cropped;\n"
    "                   sra: successive random addition (Voss); midpoint: diamond-square (creases);\n"
    "                   both calibrated so that the variogram over lags 1-16 cells reads D;\n"
    "                   exact: circulant embedding (Stein 2002), exact fBm increments;\n"
    "                   sra-raw, midpoint-raw: the papers' algorithms at H = 3 - D, uncalibrated\n"
    "  --cell SIZE      cell size in CRS units (default 1)\n"
    "  --origin X,Y     upper-left corner (default 0,0)\n"
    "  --crs CRS        EPSG:n, WKT or a PROJ string (default none)\n"
    "  --sigma S        standard deviation of the output (default 1; 0 = as generated)\n"
    "  --periodic       fft: keep the periodic tile (wraps seamlessly)\n"
    "  --seed N         random seed (default 1; printed in the JSON)\n"
    "  -f, --format DRV GDAL driver of the output (default from the extension)\n"
    "  -j, --json       print {\"output\", \"method\", \"D\", \"D_param\" (the D the algorithm ran at),\n"
    "                   \"seed\", \"sigma\", \"cell\", \"periodic\",\n"
    "                   \"geotransform\", \"crs\", \"grid\": {\"size\", \"mean\", \"sd\", \"min\", \"max\"}}\n"
    "  -h, --help       print this help\n\n"
    "Example:\n"
    "  fracterra synth hills.tif --dim 2.3 --size 1024x768 --cell 10 --origin 500000,4600000 \\\n"
    "      --crs EPSG:32632 --sigma 80 --seed 42\n",
    run_synth,
};
