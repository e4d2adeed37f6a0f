/* fracterra — cli/cmd_dim_map.c: `fracterra dim map DEM OUT --window W`: a local fractal-dimension
 * (roughness) map, D of every window of a moving window (ft_surface_dim_map), written as a two-band raster
 * aligned with the DEM: band 1 D, band 2 the r² of each window's log-log fit, nodata where a window could
 * not be measured. docs/surface-grid.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "surface_cli.h"
#include "dim_output.h"
#include "terrain_cli.h"
#include "tile_cli.h"
#include "cli_ranks.h"

#include <math.h>
#include <stdio.h>

typedef struct {
    const char *method, *driver;
    int band, window, step, json;
    long pairs; /* -1: automatic */
    long tile_rows; /* 0: automatic */
    uint64_t seed;
    double min_scale, max_scale, min_valid;
    int nscales;
    int noise_mode; /* ft_noise_opts.mode: 0 auto, -1 off */
} map_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    map_args *a = ctx;
    switch (opt) {
    case 'm': a->method = arg; return CLI_CONTINUE;
    case 'f': a->driver = arg; return CLI_CONTINUE;
    case 'w': return cli_parse_int(cmd, "--window", arg, 4, 1000000, &a->window);
    case 'S': return cli_parse_int(cmd, "--step", arg, 1, 1000000, &a->step);
    case 'b': return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->band);
    case 'p': return surface_parse_pairs(cmd, arg, &a->pairs);
    case 's': return terrain_parse_seed(cmd, arg, &a->seed);
    case 'v': return cli_parse_double(cmd, "--min-valid", arg, 0.0, 1.0, CLI_OPEN_LO, &a->min_valid);
    case 1: return cli_parse_double(cmd, "--min-scale", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->min_scale);
    case 2: return cli_parse_double(cmd, "--max-scale", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->max_scale);
    case 3: return cli_parse_int(cmd, "--scales", arg, 3, 1000, &a->nscales);
    case 4: return tile_parse_rows(cmd, arg, &a->tile_rows);
    case 5: return cli_parse_noise_model(cmd, arg, &a->noise_mode);
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* The figures of the measured windows, summed in row order, and the windows with a noise flag N
 * (tile_cli.h's tile_map_stats). */
static tile_map_stats map_stats(const ft_grid *D, const ft_grid *N)
{
    tile_map_stats st = {D->nx, D->ny, ft_grid_count_valid(D), NAN, NAN, 0.0, 0};
    if (st.measured)
        ft_grid_minmax(D, &st.lo, &st.hi);
    for (size_t i = 0; i < D->nx * D->ny; i++)
        if (D->mask == NULL || D->mask[i]) {
            st.sum += D->z[i];
            st.nugget += N->z[i] > 0.5f;
        }
    return st;
}

/* The warning of a map where some windows' noise model removed white noise (docs/surface-noise.md). */
static void noise_warning(const tile_map_stats *st, ft_surface_method m, char *buf, size_t size)
{
    snprintf(buf, size,
             "noise detected in %zu of %zu measured windows: their log-log plot flattens toward the small %s "
             "(white noise on z); it was removed and those windows fitted past it, so their D is less certain "
             "than their neighbours'",
             st->nugget, st->measured, m == FT_SURFACE_SPECTRUM ? "wavelengths" : "lags");
}

static int report(const cli_command *cmd, const map_args *a, const char *in, const char *out,
                  const tile_map_stats *st, ft_surface_method m)
{
    double lo = st->measured ? st->lo : NAN, hi = st->measured ? st->hi : NAN;
    char warning[512] = "";
    if (st->nugget > 0)
        noise_warning(st, m, warning, sizeof warning);
    json_object *o = terrain_report_start(a->json, in, out);
    if (o == NULL) {
        printf("%zu of %zu windows measured, D %.3f .. %.3f\n", st->measured, st->nox * st->noy, lo, hi);
        if (st->nugget > 0)
            cli_warn(cmd, "%s", warning);
        return CLI_OK;
    }
    json_object *size = json_object_new_array();
    json_object_array_add(size, json_object_new_int64((int64_t)st->nox));
    json_object_array_add(size, json_object_new_int64((int64_t)st->noy));
    json_object_object_add(o, "method", json_object_new_string(ft_surface_method_name(m)));
    json_object_object_add(o, "window", json_object_new_int(a->window));
    json_object_object_add(o, "step", json_object_new_int(a->step));
    json_object_object_add(o, "pairs", json_object_new_int64(a->pairs > 0 ? (int64_t)a->pairs : 0));
    if (a->pairs > 0) /* the seed draws the random points */
        json_object_object_add(o, "seed", json_object_new_uint64(a->seed));
    json_object_object_add(o, "min_valid", cli_json_double(a->min_valid));
    json_object_object_add(o, "noise_model", json_object_new_string(a->noise_mode == 0 ? "auto" : "off"));
    json_object_object_add(o, "size", size);
    json_object_object_add(o, "bands", json_object_new_string("1: D, 2: r2"));
    json_object_object_add(o, "windows", json_object_new_int64((int64_t)(st->nox * st->noy)));
    json_object_object_add(o, "windows_measured", json_object_new_int64((int64_t)st->measured));
    json_object_object_add(o, "D_min", cli_json_double(lo));
    json_object_object_add(o, "D_max", cli_json_double(hi));
    json_object_object_add(o, "D_mean", cli_json_double(st->measured ? st->sum / (double)st->measured : NAN));
    json_object *noise = json_object_new_object();
    json_object_object_add(noise, "windows_with_nugget", json_object_new_int64((int64_t)st->nugget));
    json_object_object_add(noise, "windows", json_object_new_int64((int64_t)st->measured));
    json_object_object_add(o, "noise", noise);
    json_object *w = json_object_new_array();
    if (st->nugget > 0)
        json_object_array_add(w, json_object_new_string(warning));
    json_object_object_add(o, "warnings", w);
    return cli_print_json(cmd, o);
}

/* The map stripe by stripe (--tile-rows, a DEM beyond half of --max-memory, or MPI ranks). */
static int run_tiled(const cli_command *cmd, map_args *a, const ft_surface_dim_opts *o, ft_surface_method m,
                     size_t step, const char *in, const char *out)
{
    if (o->pairs != 0) {
        cli_error(cmd, "--pairs %zu: random pairs are not available stripe by stripe (--tile-rows, large DEMs, "
                  "MPI); use --pairs 0", o->pairs);
        return CLI_USAGE;
    }
    tile_map_job job = {(size_t)a->window, step, m, *o, a->band, a->driver, a->tile_rows};
    job.opts.progress = NULL;
    tile_map_stats st;
    int rc = tile_dim_map(cmd, in, out, &job, &st);
    return rc == CLI_OK && cli_rank() == 0 ? report(cmd, a, in, out, &st, m) : rc;
}

static int run_dim_map(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"window", required_argument, NULL, 'w'},  {"step", required_argument, NULL, 'S'},
        {"method", required_argument, NULL, 'm'},  {"band", required_argument, NULL, 'b'},
        {"pairs", required_argument, NULL, 'p'},   {"seed", required_argument, NULL, 's'},
        {"min-valid", required_argument, NULL, 'v'}, {"min-scale", required_argument, NULL, 1},
        {"max-scale", required_argument, NULL, 2}, {"scales", required_argument, NULL, 3},
        {"format", required_argument, NULL, 'f'},  {"json", no_argument, NULL, 'j'},
        {"tile-rows", required_argument, NULL, 4}, {"noise-model", required_argument, NULL, 5}, CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"DEM", "OUT"};
    map_args a = {"variogram", NULL, 1, 0, 0, 0, -1, 0, 1, 0.0, 0.0, 0.5, 0, 0};
    ft_surface_method m;
    int first = 0, nm = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "w:S:m:b:p:s:v:f:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "OUT", argv[first + 1], argv[first], (const char *)NULL);
    if (rc == CLI_CONTINUE && a.window == 0)
        rc = cli_usage_error(cmd, "--window W is required (cells, >= 4)");
    if (rc == CLI_CONTINUE && a.min_scale > 0.0 && a.max_scale > 0.0 && !(a.max_scale > a.min_scale))
        rc = cli_usage_error(cmd, "--max-scale %g must exceed --min-scale %g", a.max_scale, a.min_scale);
    if (rc == CLI_CONTINUE)
        rc = surface_parse_methods(cmd, a.method, 0, &m, &nm);
    if (rc != CLI_CONTINUE)
        return rc;
    const char *in = argv[first], *out = argv[first + 1];
    if (ft_io_check_writable(out) != FT_OK)
        return cli_fail(cmd);
    size_t nx = 0, ny = 0;
    if ((rc = tile_band_size(cmd, in, a.band, &nx, &ny)) != CLI_CONTINUE)
        return rc;
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.min_scale = a.min_scale;
    o.max_scale = a.max_scale;
    o.nscales = a.nscales;
    o.fit_whole_range = 1; /* every window over the same range: the map compares like with like */
    o.pairs = a.pairs >= 0 ? (size_t)a.pairs : 0;
    o.seed = a.seed;
    o.min_valid = a.min_valid;
    o.noise.mode = a.noise_mode;
    o.progress = cli_progress();
    size_t step = a.step > 0 ? (size_t)a.step : ((size_t)a.window / 4 > 0 ? (size_t)a.window / 4 : 1);
    a.step = (int)step;
    if (tile_wanted(a.tile_rows, nx, ny, 18.0))
        return run_tiled(cmd, &a, &o, m, step, in, out);
    ft_grid *g = NULL, *D = NULL, *r2 = NULL, *N = NULL;
    ft_crs_info crs;
    if ((rc = surface_read_dem(cmd, in, a.band, &g, &crs)) != CLI_CONTINUE) {
        ft_grid_free(g);
        return rc;
    }
    rc = ft_surface_dim_map_noise(g, (size_t)a.window, step, m, &o, &D, &r2, &N) == FT_OK ? CLI_OK : cli_fail(cmd);
    if (rc == CLI_OK) {
        ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
        wo.driver = a.driver;
        const ft_grid *bands[2] = {D, r2};
        tile_map_stats st = map_stats(D, N);
        rc = ft_io_write_grids(out, bands, 2, &wo) == FT_OK ? report(cmd, &a, in, out, &st, m) : cli_fail(cmd);
    }
    ft_grid_free(D);
    ft_grid_free(r2);
    ft_grid_free(N);
    ft_grid_free(g);
    return rc;
}

const cli_command cli_cmd_dim_map = {
    "dim map",
    "local fractal-dimension (roughness) map of an elevation grid",
    "fracterra dim map DEM OUT --window W [--step S] [--method M] [--pairs N] [--seed N] [--band N]\n"
    "                          [--min-scale S] [--max-scale S] [--scales N] [--min-valid F] [-f DRIVER]\n"
    "                          [--noise-model auto|off] [--tile-rows N] [--json]\n"
    "       mpiexec -n N fracterra dim map DEM OUT.tif --window W [...]",
    "Measures D in every window of W x W cells whose corner moves by S cells, and writes a raster aligned\n"
    "with the DEM (same CRS; one cell of S x S DEM cells centred on each window's centre): band 1 holds D,\n"
    "band 2 the r\xc2\xb2 of the window's log-log fit. A window with fewer valid cells than --min-valid of its\n"
    "area, or that the method cannot measure (flat), is nodata. Every window is fitted over the same scale\n"
    "range (the method's default for W, or --min-scale/--max-scale), so the map compares like with like.\n"
    "Windows run in parallel (OMP_NUM_THREADS); the map is the same on any thread count.\n"
    "A DEM larger than half of --max-memory, or any DEM with --tile-rows, is read in stripes of rows with\n"
    "a halo of W - S rows and the map written stripe by stripe into a tiled GeoTIFF: peak memory follows\n"
    "the stripe, every cell is the whole-DEM run's. Under mpiexec the ranks share the stripes and rank 0\n"
    "writes the map (docs/tiling.md). Stripes need every pair (--pairs 0) and a projected DEM.\n"
    "Each window's estimator detects and removes white noise on z (a nugget; spectrum: a floor) as dim\n"
    "surface does; the number of windows where it did is reported, with a warning (docs/surface-noise.md).\n\n"
    "Options:\n"
    "  -w, --window W       window side, cells (>= 4; required)\n"
    "  -S, --step S         distance between windows, cells (default W / 4)\n"
    "  -m, --method M       variogram (default), yokoya, pentland, spectrum, prism or cubes\n"
    "                       (docs/surface-grid.md; lag methods use lags 1 .. W/8 cells by default)\n"
    "  -p, --pairs N        lag methods: N random points per window (default 0: every pair)\n"
    "  -s, --seed N         seed of the random points (default 1)\n"
    "  -b, --band N         band of the DEM (default 1)\n"
    "      --min-scale S    smallest lag, side or wavelength in map units (default: the method's)\n"
    "      --max-scale S    largest (default: the method's for a W x W grid)\n"
    "      --scales N       lags or frequency bins (3..1000)\n"
    "  -v, --min-valid F    fewest valid cells of a window, as a fraction in (0, 1] (default 0.5)\n"
    "      --noise-model M  auto (default): every window's estimator detects and removes white noise on z;\n"
    "                       off: none (variogram, yokoya, pentland, spectrum; docs/surface-noise.md)\n"
    "  -f, --format DRIVER  GDAL driver of OUT (default: from the extension, GeoTIFF)\n"    "      --tile-rows N    compute N rows of the DEM per stripe (default: whole DEM when it fits half\n"
    "                       of --max-memory, else stripes filling a quarter of it)\n"
    "  -j, --json           print {\"input\", \"output\", \"method\", \"window\", \"step\", \"size\", \"windows\",\n"
    "                       \"windows_measured\", \"D_min\", \"D_max\", \"D_mean\", \"noise\": {\"windows_with_nugget\",\n"
    "                       \"windows\"}, \"warnings\"}\n"
    "  -h, --help           print this help\n\n"
    "Example:\n"
    "  fracterra dim map dem.tif roughness.tif --window 64 --step 16\n",
    run_dim_map,
};
