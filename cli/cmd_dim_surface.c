/* fracterra — cli/cmd_dim_surface.c: `fracterra dim surface DEM`: the fractal dimension of an elevation grid
 * by the variogram, Yokoya's and Pentland's increments, the power spectrum, Clarke's triangular prisms or
 * cube counting (ft_surface_dim; docs/surface-grid.md), printed by the shared dimension printer
 * (dim_output.h). Also the helpers of surface_cli.h, shared with `dim map`.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "dim_output.h"
#include "surface_cli.h"
#include "terrain_cli.h"
#include "tile_cli.h"
#include "cli_ranks.h"

#include <stdio.h>
#include <string.h>

typedef struct {
    cli_dim_opts dim;
    const char *method;
    int band;
    long pairs; /* -1: automatic */
    uint64_t seed;
    ft_noise_opts noise;
    long tile_rows; /* 0: automatic */
} surface_args;

/* ---- shared with dim map (surface_cli.h) ---- */

int surface_read_dem(const cli_command *cmd, const char *path, int band, ft_grid **out, ft_crs_info *crs)
{
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = band;
    if (ft_io_read_grid(path, &ro, out) != FT_OK)
        return cli_fail(cmd);
    if (cli_check_grid_work(cmd, path, *out) != CLI_CONTINUE) {
        ft_grid_free(*out);
        *out = NULL;
        return CLI_FAIL;
    }
    return cli_geo_grid_ground(cmd, path, out, crs);
}

int surface_parse_methods(const cli_command *cmd, const char *text, int allow_all, ft_surface_method *ms, int *n)
{
    *n = 0;
    if (allow_all && strcmp(text, "all") == 0) {
        for (int i = 0; i < FT_SURFACE_NMETHODS; i++)
            ms[(*n)++] = (ft_surface_method)i;
        return CLI_CONTINUE;
    }
    char buf[256];
    snprintf(buf, sizeof buf, "%s", text);
    int ok = strlen(text) < sizeof buf;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); ok && tok; tok = strtok_r(NULL, ",", &save)) {
        ft_surface_method m;
        ok = *n < FT_SURFACE_NMETHODS && ft_surface_method_parse(tok, &m) == FT_OK;
        for (int i = 0; ok && i < *n; i++)
            ok = ms[i] != m;
        if (ok)
            ms[(*n)++] = m;
    }
    ft_clear_error();
    if (ok && *n > 0 && (allow_all || *n == 1))
        return CLI_CONTINUE;
    return cli_usage_error(cmd, "--method must be variogram, yokoya, pentland, spectrum, prism or cubes%s; got '%s'",
                           allow_all ? ", a comma-separated list of them, or all" : "", text);
}

int surface_parse_pairs(const cli_command *cmd, const char *arg, long *pairs)
{
    int v = 0, rc = cli_parse_int(cmd, "--pairs", arg, 0, 100000000, &v);
    *pairs = v;
    return rc;
}

size_t surface_pairs(long pairs, const ft_grid *g)
{
    if (pairs >= 0)
        return (size_t)pairs;
    return g->nx * g->ny > SURFACE_EXHAUSTIVE_CELLS ? SURFACE_DEFAULT_PAIRS : 0;
}

/* ---- the command ---- */

static void axis_labels(ft_surface_method m, const char **x, const char **y)
{
    static const char *const xs[FT_SURFACE_NMETHODS] = {"lag", "lag", "lag", "frequency", "square side", "cube side"};
    static const char *const ys[FT_SURFACE_NMETHODS] = {"mean squared difference", "mean |dz|", "sd of |dz|",
                                                        "power", "surface area / planimetric area", "cubes"};
    *x = xs[m];
    *y = ys[m];
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    surface_args *a = ctx;
    int rc = cli_dim_option(cmd, opt, arg, &a->dim);
    if (rc != CLI_DIM_NOT_SHARED)
        return rc;
    switch (opt) {
    case 'm': a->method = arg; return CLI_CONTINUE;
    case 'b': return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->band);
    case 'p': return surface_parse_pairs(cmd, arg, &a->pairs);
    case 's': return terrain_parse_seed(cmd, arg, &a->seed);
    case 'N': {
        double xy;
        return cli_parse_noise_sigma(cmd, arg, 0, &xy, &a->noise.sigma_z);
    }
    case 'M': return cli_parse_noise_model(cmd, arg, &a->noise.mode);
    case 'T': return tile_parse_rows(cmd, arg, &a->tile_rows);
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* g: the grid measured (NULL when it was read stripe by stripe, then not geographic). */
static json_object *extra_members(const char *path, const surface_args *a, const ft_grid *g, size_t nx, size_t ny,
                                  uint64_t valid, size_t pairs, const ft_crs_info *crs)
{
    json_object *o = json_object_new_object(), *size = json_object_new_array();
    json_object_object_add(o, "file", json_object_new_string(path));
    if (crs->geographic && g != NULL) /* measured on its warp to a local transverse Mercator */
        json_object_object_add(o, "geographic", cli_geo_json(crs, g->crs_wkt));
    json_object_object_add(o, "band", json_object_new_int(a->band));
    json_object_array_add(size, json_object_new_int64((int64_t)nx));
    json_object_array_add(size, json_object_new_int64((int64_t)ny));
    json_object_object_add(o, "size", size);
    json_object_object_add(o, "cells_valid", json_object_new_int64((int64_t)valid));
    json_object_object_add(o, "pairs",
                           pairs ? json_object_new_int64((int64_t)pairs) : json_object_new_string("exhaustive"));
    if (pairs)
        json_object_object_add(o, "seed", json_object_new_int64((int64_t)a->seed));
    json_object_object_add(o, "noise_model", json_object_new_string(a->noise.mode == 0 ? "auto" : "off"));
    return o;
}

/* Every method into the report; a method failing among several is a warning, a lone one an error. */
static int measure(const cli_command *cmd, const ft_grid *g, const ft_crs_info *crs, const ft_surface_method *ms,
                   int nm, const ft_surface_dim_opts *o, cli_dim_report *rep)
{
    for (int i = 0; i < nm; i++) {
        ft_dim_result *r = NULL;
        if (ft_surface_dim(g, ms[i], o, &r) != FT_OK) {
            if (nm == 1 || ft_last_error_code() == FT_E_NOMEM || ft_last_error_code() == FT_E_CANCELLED)
                return cli_fail(cmd);
            cli_warn(cmd, "%s", ft_last_error());
            continue;
        }
        const char *xl, *yl;
        axis_labels(ms[i], &xl, &yl);
        cli_geo_units(r, crs);
        if (cli_dim_report_add(rep, r, xl, yl) != FT_OK)
            return cli_fail(cmd);
    }
    if (cli_dim_report_count(rep) == 0) {
        cli_error(cmd, "no method could measure the grid");
        return CLI_FAIL;
    }
    return CLI_OK;
}

/* One exhaustive lag method stripe by stripe (--tile-rows, a DEM beyond half of --max-memory, MPI ranks). */
static int run_tiled(const cli_command *cmd, const surface_args *a, const ft_surface_method *ms, int nm,
                     ft_surface_dim_opts *o, const char *path)
{
    if (nm != 1 || (ms[0] != FT_SURFACE_VARIOGRAM && ms[0] != FT_SURFACE_YOKOYA && ms[0] != FT_SURFACE_PENTLAND)) {
        cli_error(cmd, "stripe by stripe (--tile-rows, a DEM beyond half of --max-memory, MPI) only one of "
                  "variogram, yokoya or pentland can be measured; got --method %s", a->method);
        return CLI_USAGE;
    }
    if (a->pairs > 0) {
        cli_error(cmd, "--pairs %ld: random pairs are not available stripe by stripe; every pair is used",
                  a->pairs);
        return CLI_USAGE;
    }
    o->pairs = 0;
    o->progress = NULL;
    ft_dim_result *r = NULL;
    size_t nx = 0, ny = 0;
    uint64_t valid = 0;
    ft_crs_info crs;
    int rc = tile_dim_surface(cmd, path, a->band, ms[0], o, a->tile_rows, &r, &nx, &ny, &valid, &crs);
    if (rc != CLI_OK || cli_rank() != 0)
        return rc;
    const char *xl, *yl;
    axis_labels(ms[0], &xl, &yl);
    cli_geo_units(r, &crs);
    cli_dim_report *rep = cli_dim_report_create(path);
    int ok = rep != NULL && cli_dim_report_group(rep, 0, NULL, path, NULL) == FT_OK;
    if (!ok)
        ft_dim_result_free(r);
    if (!ok || cli_dim_report_add(rep, r, xl, yl) != FT_OK) { /* add frees r when it fails */
        rc = cli_fail(cmd);
    } else {
        rc = cli_dim_report_print(cmd, rep, &a->dim, extra_members(path, a, NULL, nx, ny, valid, 0, &crs));
    }
    cli_dim_report_free(rep);
    return rc;
}

static int run_dim_surface(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"method", required_argument, NULL, 'm'}, {"band", required_argument, NULL, 'b'},
        {"pairs", required_argument, NULL, 'p'},  {"seed", required_argument, NULL, 's'},
        {"noise-sigma", required_argument, NULL, 'N'}, {"noise-model", required_argument, NULL, 'M'},
        {"tile-rows", required_argument, NULL, 'T'},
        CLI_DIM_LONGOPTS,                          CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"DEM"};
    surface_args a = {CLI_DIM_OPTS_DEFAULT, "variogram", 1, -1, 1, FT_NOISE_OPTS_DEFAULT, 0};
    ft_surface_method ms[FT_SURFACE_NMETHODS];
    int first = 0, nm = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "m:b:p:s:N:M:" CLI_DIM_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE)
        rc = cli_dim_check(cmd, &a.dim);
    if (rc == CLI_CONTINUE)
        rc = surface_parse_methods(cmd, a.method, 1, ms, &nm);
    if (rc != CLI_CONTINUE)
        return rc;
    const char *path = argv[first];
    if (a.dim.plot && ft_io_check_writable(a.dim.plot) != FT_OK)
        return cli_fail(cmd);
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.min_scale = a.dim.min_scale;
    o.max_scale = a.dim.max_scale;
    o.nscales = a.dim.nscales;
    o.fit_whole_range = a.dim.min_scale > 0.0 && a.dim.max_scale > 0.0;
    o.fit.regime = a.dim.regime;
    o.seed = a.seed;
    o.noise = a.noise;
    o.progress = cli_progress();
    size_t nx = 0, ny = 0;
    if ((rc = tile_band_size(cmd, path, a.band, &nx, &ny)) != CLI_CONTINUE)
        return rc;
    if (tile_wanted(a.tile_rows, nx, ny, 13.0))
        return run_tiled(cmd, &a, ms, nm, &o, path);
    ft_grid *g = NULL;
    ft_crs_info crs;
    if ((rc = surface_read_dem(cmd, path, a.band, &g, &crs)) != CLI_CONTINUE) {
        ft_grid_free(g);
        return rc;
    }
    o.pairs = surface_pairs(a.pairs, g);
    cli_dim_report *rep = cli_dim_report_create(path);
    rc = rep && cli_dim_report_group(rep, 0, NULL, path, NULL) == FT_OK
             ? measure(cmd, g, &crs, ms, nm, &o, rep)
             : (ft_error(FT_E_NOMEM, "out of memory"), cli_fail(cmd));
    if (rc == CLI_OK)
        rc = cli_dim_report_print(cmd, rep, &a.dim, extra_members(path, &a, g, g->nx, g->ny, ft_grid_count_valid(g), o.pairs, &crs));
    cli_dim_report_free(rep);
    ft_grid_free(g);
    return rc;
}

const cli_command cli_cmd_dim_surface = {
    "dim surface",
    "fractal dimension of an elevation grid",
    "fracterra dim surface DEM [--method variogram|yokoya|pentland|spectrum|prism|cubes|all] [--pairs N]\n"
    "                            [--seed N] [--band N] [--noise-sigma Z] [--noise-model auto|off]\n"
    "                            [--min-scale S] [--max-scale S] [--scales N]\n"
    "                            [--tile-rows N] [--segments] [--plot FILE] [--json]\n"
    "       mpiexec -n N fracterra dim surface DEM --pairs 0 [...]",
    "Measures the fractal dimension D (2..3) of a DEM (any raster GDAL reads). The quantity is measured at\n"
    "scales in a geometric series (powers of two for prism and cubes) and D is read from the widest\n"
    "regime (straight run) of the log-log plot (docs/loglog.md); regimes, breaks and the whole table are\n"
    "reported so the fit can be judged; a D outside [2, 3] is an error. Nodata cells are left out: pairs, tiles, squares and blocks touching them are\n"
    "skipped, never read as zero.\n\n"
    "Methods (docs/surface-grid.md):\n"
    "  variogram  mean squared difference against lag, D = 3 - slope/2 (Mark & Aronson; the default:\n"
    "             median error 0.01 on fBm surfaces of D = 2.1 ... 2.8)\n"
    "  yokoya     mean |dz| against lag, D = 3 - H (Arakawa & Krotkov)\n"
    "  pentland   standard deviation of |dz| against lag, D = 3 - H\n"
    "  spectrum   radially averaged power of Hann-tapered, detrended tiles, D = (8 - beta) / 2\n"
    "  prism      Clarke's triangular prism surface area against square side, D = 2 - slope\n"
    "  cubes      cube counting over each block's corners, D = -slope: BIASED low, by 0.01-0.02 on\n"
    "             exact fBm of D = 2.1-2.8 (measured; the JSON says so in \"warnings\")\n"
    "  all        every method above: {\"results\": [...]}\n\n"
    "Options:\n"
    "  -m, --method M       variogram (default), another method, a list such as yokoya,prism, or all\n"
    "  -p, --pairs N        lag methods: N random points in the inscribed circle, each paired at every lag\n"
    "                       (Mark & Aronson); 0 = every pair along rows and columns. Default: exhaustive\n"
    "                       up to 1024x1024 cells, 32000 points above\n"
    "  -s, --seed N         seed of the random points (default 1)\n"
    "  -b, --band N         band of the DEM (default 1)\n"
    "      --noise-sigma Z  variogram, yokoya, pentland, spectrum: known standard deviation of white\n"
    "                       noise on z; its nugget (spectrum: its flat floor Z^2) is removed\n"
    "      --noise-model M  auto (default): detect white noise (the plot flattening toward small lags or\n"
    "                       high frequencies), remove it and fit past it, said in \"warnings\"; off: none\n"
    "      --tile-rows N    read the DEM in stripes of N rows (plus up to N rows below; a longer lag reads\n"
    "                       its N partner rows): peak memory follows the stripe, not the largest lag, and\n"
    "                       D is the whole-DEM run's with --pairs 0, bit for\n"
    "                       bit. Automatic for a DEM beyond half of --max-memory and under mpiexec, where\n"
    "                       the ranks share the stripes (docs/tiling.md); variogram, yokoya or pentland\n"
    "                       with every pair, projected DEMs only\n"
    CLI_DIM_OPTIONS_HELP
    "  -h, --help           print this help\n"
    "Scales are lags, square or cube sides, or wavelengths, in map units. With both --min-scale and\n"
    "--max-scale, D is fitted over every scale between them.\n\n"
    "JSON: {\"file\", \"band\", \"size\", \"cells_valid\", \"pairs\", \"method\", \"D\", \"r2\", \"stderr\",\n"
    "\"range\": [lo, hi], \"segmentation\", \"max_err\", \"warnings\", \"noise\" (lag methods), \"table\": [{\"scale\", \"value\", \"count\", \"slope\",\n"
    "\"used\"}]} (and \"segments\" with --segments); several methods: \"results\": [...].\n\n"
    "Examples:\n"
    "  fracterra dim surface tests/data/dem_volcano_maunga_whau_10m.tif --plot volcano.svg\n"
    "  fracterra dim surface dem.tif --method all --json | jq '.results[] | {method, D}'\n",
    run_dim_surface,
};
