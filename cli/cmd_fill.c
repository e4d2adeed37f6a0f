/* fracterra — cli/cmd_fill.c: `fracterra fill DEM OUT.tif`: the nodata voids of a DEM filled with terrain
 * as rough as the terrain around each void (ft_terrain_fill; docs/terrain-fill.md). The command a
 * gdal_fillnodata user looks for: nodata from the file, --mask, --max-void; valid cells kept bit for bit.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "cli_ranks.h"
#include "terrain_cli.h"
#include "tile_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FILL_MAX_REALIZATIONS 10000

typedef struct {
    ft_fill_opts fo;
    double max_void;    /* as given */
    int max_void_ground; /* 1: in ground units (suffix m) */
    const char *mask, *driver;
    int band, json;
    long tile_rows; /* 0: automatic */
} fill_args;

enum {
    OPT_MAX_VOID = 0x300,
    OPT_MASK,
    OPT_MEAN,
    OPT_RING,
    OPT_BAND,
    OPT_TILE_ROWS,
};
/* Bytes per cell of a whole-DEM fill (the DEM, its filled copy, void flags and labels, the sd band): beyond
 * half of --max-memory the DEM is filled stripe by stripe. */
#define FILL_WHOLE_BYTES_PER_CELL 20.0

/* --max-void N (cells) or Nm (ground units of the CRS): N >= 0, 0 = no limit. */
static int parse_max_void(const cli_command *cmd, const char *arg, fill_args *a)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(arg, &end);
    int ground = end != arg && strcmp(end, "m") == 0;
    if (end == arg || (*end != '\0' && !ground) || errno != 0 || !(v >= 0.0) || !isfinite(v))
        return cli_usage_error(cmd, "--max-void must be a number of cells >= 0 (0 = no limit) or a length in "
                               "ground units with the suffix m (e.g. 3000m), got '%s'", arg);
    a->max_void = v;
    a->max_void_ground = ground;
    return CLI_CONTINUE;
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    fill_args *a = ctx;
    switch (opt) {
    case OPT_MAX_VOID: return parse_max_void(cmd, arg, a);
    case OPT_MASK: a->mask = arg; return CLI_CONTINUE;
    case OPT_MEAN: a->fo.mean = 1; return CLI_CONTINUE;
    case 'n': return cli_parse_int(cmd, "--realizations", arg, 1, FILL_MAX_REALIZATIONS, &a->fo.realizations);
    case 'd': return terrain_parse_dim(cmd, arg, &a->fo.dim);
    case OPT_RING: return cli_parse_int(cmd, "--ring", arg, 2, 100000, &a->fo.ring);
    case 'S': return terrain_parse_seed(cmd, arg, &a->fo.seed);
    case OPT_BAND: return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->band);
    case OPT_TILE_ROWS: return tile_parse_rows(cmd, arg, &a->tile_rows);
    case 'f': a->driver = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* max_void in cells from --max-void (ground units: over the larger cell side). */
static int resolve_max_void(const cli_command *cmd, fill_args *a, const ft_grid *g, const char *in)
{
    if (!a->max_void_ground) {
        a->fo.max_void = a->max_void;
        return CLI_CONTINUE;
    }
    ft_crs_info crs;
    if (ft_io_crs_info(g->crs_wkt, &crs) == FT_OK && crs.geographic) {
        cli_error(cmd, "--max-void %gm: %s has a geographic CRS (cells in degrees); give --max-void in cells",
                  a->max_void, in);
        return CLI_USAGE;
    }
    double cx = hypot(g->gt[1], g->gt[4]), cy = hypot(g->gt[2], g->gt[5]);
    double cell = cx > cy ? cx : cy;
    if (!(cell > 0.0)) {
        cli_error(cmd, "--max-void %gm: %s has no cell size in its geotransform", a->max_void, in);
        return CLI_USAGE;
    }
    a->fo.max_void = floor(a->max_void / cell + 1e-9);
    if (a->max_void > 0.0 && a->fo.max_void < 1.0) {
        cli_error(cmd, "--max-void %gm is less than one cell of %s (%g); nothing would be filled", a->max_void,
                  in, cell);
        return CLI_USAGE;
    }
    return CLI_CONTINUE;
}

/* The validity mask of --mask (band 1, 0 = to fill), the size of the DEM. */
static int read_mask(const cli_command *cmd, const char *path, const ft_grid *dem, const char *in, uint8_t **out)
{
    ft_grid *m = NULL;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    if (ft_io_read_grid(path, &ro, &m) != FT_OK)
        return cli_fail(cmd);
    if (m->nx != dem->nx || m->ny != dem->ny) {
        cli_error(cmd, "--mask %s is %zu x %zu cells, the DEM %s %zu x %zu", path, m->nx, m->ny, in, dem->nx,
                  dem->ny);
        ft_grid_free(m);
        return CLI_FAIL;
    }
    uint8_t *v = malloc(m->nx * m->ny);
    if (v == NULL) {
        ft_grid_free(m);
        cli_error(cmd, "out of memory reading --mask %s", path);
        return CLI_FAIL;
    }
    /* gdal_fillnodata's -mask: zero (or nodata) is invalid, to be filled */
    for (size_t i = 0; i < m->nx * m->ny; i++)
        v[i] = (m->mask == NULL || m->mask[i]) && m->z[i] != 0.0f;
    ft_grid_free(m);
    *out = v;
    return CLI_CONTINUE;
}

static json_object *void_json(const ft_fill_void *v, size_t id)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "id", json_object_new_int64((int64_t)id));
    json_object *bb = json_object_new_array();
    json_object_array_add(bb, json_object_new_int64((int64_t)v->x0));
    json_object_array_add(bb, json_object_new_int64((int64_t)v->y0));
    json_object_array_add(bb, json_object_new_int64((int64_t)v->x1));
    json_object_array_add(bb, json_object_new_int64((int64_t)v->y1));
    json_object_object_add(o, "cells_box", bb);
    json_object_object_add(o, "cells", json_object_new_int64((int64_t)v->cells));
    json_object_object_add(o, "edge", json_object_new_boolean(v->edge));
    json_object_object_add(o, "filled", json_object_new_boolean(v->filled));
    if (v->filled) {
        int flat = v->source == FT_FILL_D_FLAT;
        json_object_object_add(o, "D", flat ? NULL : cli_json_double(v->D));
        json_object_object_add(o, "amplitude", flat ? cli_json_double(0.0) : cli_json_double(v->amplitude));
        json_object_object_add(o, "r2", isfinite(v->r2) ? cli_json_double(v->r2) : NULL);
        json_object_object_add(o, "D_source", json_object_new_string(ft_fill_d_source_name(v->source)));
        json_object_object_add(o, "ring_cells", json_object_new_int64((int64_t)v->ring_cells));
        json_object_object_add(o, "conditioning_cells", json_object_new_int64((int64_t)v->conditioning));
    }
    json_object *w = json_object_new_array();
    if (!v->filled)
        json_object_array_add(w, json_object_new_string("larger than --max-void: left nodata"));
    if (v->clamped)
        json_object_array_add(w, json_object_new_string("the ring's variogram slope gave D outside "
                                                        "[2.01, 2.99]: clamped"));
    if (v->filled && v->source == FT_FILL_D_DEM)
        json_object_array_add(w, json_object_new_string("too few valid pairs in the ring: D and amplitude "
                                                        "from the whole DEM"));
    if (v->filled && v->source == FT_FILL_D_FLAT)
        json_object_array_add(w, json_object_new_string("flat surroundings: filled with the kriging mean"));
    json_object_object_add(o, "warnings", w);
    return o;
}

/* st: the output's figures (NULL: computed from g). */
static int report(const cli_command *cmd, const fill_args *a, const char *in, const char *out, const ft_grid *g,
                  const ft_grid_stats *st, const ft_fill_result *r)
{
    const char *what = a->fo.mean ? "kriging mean"
                       : a->fo.realizations > 1 ? "mean and sd of conditional realizations"
                                                : "conditional realization";
    if (!a->json) {
        printf("wrote %s: %zu x %zu cells%s, %s, seed %llu\n", out, g->nx, g->ny,
               a->fo.realizations > 1 ? " (band 1 mean, band 2 sd)" : "", what, (unsigned long long)a->fo.seed);
        printf("  %zu voids, %zu filled (%zu cells), %zu left nodata (%zu cells)\n", r->nvoids, r->voids_filled,
               r->cells_filled, r->nvoids - r->voids_filled, r->cells_left);
        return CLI_OK;
    }
    json_object *o = terrain_report_start(1, in, out);
    json_object_object_add(o, "method", json_object_new_string(what));
    json_object_object_add(o, "model", json_object_new_string("power variogram E(dz^2) = amplitude^2 r^(6 - 2D) "
                                                              "fitted on a ring, lags 1-8 cells"));
    json_object_object_add(o, "units", json_object_new_string("cells (lags, boxes); elevation units (amplitude)"));
    json_object *mv = json_object_new_object();
    json_object_object_add(mv, "cells", a->fo.max_void > 0.0 ? cli_json_double(a->fo.max_void) : NULL);
    if (a->max_void_ground)
        json_object_object_add(mv, "ground", cli_json_double(a->max_void));
    json_object_object_add(o, "max_void", mv);
    json_object_object_add(o, "dim", a->fo.dim > 0.0 ? cli_json_double(a->fo.dim) : json_object_new_string("auto"));
    json_object_object_add(o, "seed", json_object_new_uint64(a->fo.seed));
    json_object_object_add(o, "realizations", json_object_new_int(a->fo.mean ? 0 : a->fo.realizations));
    json_object_object_add(o, "bands", json_object_new_string(a->fo.realizations > 1 ? "1: mean, 2: sd" : "1: z"));
    json_object_object_add(o, "voids_found", json_object_new_int64((int64_t)r->nvoids));
    json_object_object_add(o, "voids_filled", json_object_new_int64((int64_t)r->voids_filled));
    json_object_object_add(o, "cells_filled", json_object_new_int64((int64_t)r->cells_filled));
    json_object_object_add(o, "cells_left", json_object_new_int64((int64_t)r->cells_left));
    json_object *vs = json_object_new_array();
    size_t clamped = 0, dem = 0;
    for (size_t i = 0; i < r->nvoids; i++) {
        json_object_array_add(vs, void_json(&r->voids[i], i + 1));
        clamped += (size_t)r->voids[i].clamped;
        dem += (size_t)(r->voids[i].filled && r->voids[i].source == FT_FILL_D_DEM);
    }
    json_object_object_add(o, "voids", vs);
    json_object *w = json_object_new_array();
    if (r->nvoids == 0)
        json_object_array_add(w, json_object_new_string("no void: the output is a copy"));
    if (r->cells_left > 0)
        json_object_array_add(w, json_object_new_string("some voids are larger than --max-void and stay nodata"));
    if (clamped > 0)
        json_object_array_add(w, json_object_new_string("some voids' D was clamped to [2.01, 2.99]"));
    if (dem > 0)
        json_object_array_add(w, json_object_new_string("some voids' model comes from the whole DEM"));
    json_object_object_add(o, "warnings", w);
    if (st)
        terrain_add_grid_json_of(o, g, st);
    else
        terrain_add_grid_json(o, g);
    return cli_print_json(cmd, o);
}

/* Stripe by stripe (--tile-rows, a DEM beyond half of --max-memory, mpiexec): tile_fill.c. */
static int run_fill_tiled(const cli_command *cmd, fill_args *a, const char *in, const char *out)
{
    if (a->driver != NULL && strcmp(a->driver, "GTiff") != 0)
        return cli_usage_error(cmd, "-f %s: a DEM filled stripe by stripe (--tile-rows, beyond half of "
                               "--max-memory, mpiexec) is written as GeoTIFF only", a->driver);
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = a->band;
    ft_grid_reader *r = NULL;
    if (ft_io_grid_reader_open(in, &ro, &r) != FT_OK)
        return cli_fail(cmd);
    const ft_grid *hdr = ft_io_grid_reader_header(r);
    int rc = resolve_max_void(cmd, a, hdr, in);
    ft_crs_info crs;
    if (rc == CLI_CONTINUE && (rc = cli_geo_crs(cmd, in, hdr->crs_wkt, &crs)) == CLI_CONTINUE && crs.geographic &&
        cli_rank() == 0)
        cli_geo_warn_square_cells(cmd, in, hdr, &crs);
    if (rc == CLI_CONTINUE) {
        tile_fill_job job = {.in = in, .out = out, .mask = a->mask, .fo = a->fo, .band = a->band,
                             .tile_rows = a->tile_rows};
        job.fo.progress = cli_rank() == 0 ? cli_progress() : NULL;
        ft_fill_result res;
        ft_grid_stats st;
        rc = tile_fill(cmd, &job, &res, &st);
        if (rc == CLI_OK && cli_rank() == 0)
            rc = report(cmd, a, in, out, hdr, &st, &res);
        if (rc == CLI_OK && cli_rank() == 0)
            free(res.voids);
    }
    ft_io_grid_reader_close(r);
    return rc;
}

static int run_fill(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"max-void", required_argument, NULL, OPT_MAX_VOID},
        {"mask", required_argument, NULL, OPT_MASK},
        {"mean", no_argument, NULL, OPT_MEAN},
        {"realizations", required_argument, NULL, 'n'},
        {"dim", required_argument, NULL, 'd'},
        {"ring", required_argument, NULL, OPT_RING},
        {"seed", required_argument, NULL, 'S'},
        {"band", required_argument, NULL, OPT_BAND},
        {"format", required_argument, NULL, 'f'},
        {"json", no_argument, NULL, 'j'},
        {"tile-rows", required_argument, NULL, OPT_TILE_ROWS},
        CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"DEM", "OUT"};
    fill_args a = {.fo = FT_FILL_OPTS_DEFAULT, .max_void = 100.0, .band = 1};
    a.fo.seed = TERRAIN_DEFAULT_SEED;
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "n:d:f:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE) /* the output may be neither the DEM nor the mask */
        rc = cli_refuse_overwrite(cmd, "OUT", argv[first + 1], argv[first], a.mask, (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    if (a.fo.mean && a.fo.realizations > 1)
        return cli_usage_error(cmd, "--mean and --realizations %d exclude each other (--realizations N writes the "
                               "mean of N realizations and their sd)", a.fo.realizations);
    const char *in = argv[first], *out = argv[first + 1];
    if (ft_io_check_writable(out) != FT_OK)
        return cli_fail(cmd);
    size_t nx = 0, ny = 0;
    if ((rc = tile_band_size(cmd, in, a.band, &nx, &ny)) != CLI_CONTINUE)
        return rc;
    if (tile_wanted(a.tile_rows, nx, ny, FILL_WHOLE_BYTES_PER_CELL))
        return run_fill_tiled(cmd, &a, in, out);
    ft_grid *dem = NULL, *z = NULL, *sd = NULL;
    uint8_t *valid = NULL;
    ft_fill_result *res = NULL;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = a.band;
    if (ft_io_read_grid(in, &ro, &dem) != FT_OK)
        return cli_fail(cmd);
    rc = resolve_max_void(cmd, &a, dem, in);
    ft_crs_info crs;
    if (rc == CLI_CONTINUE && (rc = cli_geo_crs(cmd, in, dem->crs_wkt, &crs)) == CLI_CONTINUE && crs.geographic)
        cli_geo_warn_square_cells(cmd, in, dem, &crs); /* filled in place: resampling would alter valid cells */
    if (rc == CLI_CONTINUE && a.mask)
        rc = read_mask(cmd, a.mask, dem, in, &valid);
    if (rc == CLI_CONTINUE) {
        a.fo.progress = cli_progress();
        int lib = ft_terrain_fill(dem, valid, &a.fo, &z, a.fo.realizations > 1 ? &sd : NULL, &res);
        if (lib == FT_OK) {
            ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
            wo.driver = a.driver;
            const ft_grid *bands[2] = {z, sd};
            lib = sd ? ft_io_write_grids(out, bands, 2, &wo) : ft_io_write_grid(out, z, &wo);
        }
        rc = lib == FT_OK ? report(cmd, &a, in, out, z, NULL, res) : cli_fail(cmd);
    }
    ft_fill_result_free(res);
    ft_grid_free(sd);
    ft_grid_free(z);
    ft_grid_free(dem);
    free(valid);
    return rc;
}

const cli_command cli_cmd_fill = {
    "fill",
    "fill a DEM's nodata voids with terrain as rough as each void's surroundings",
    "fracterra fill DEM OUT.tif [--max-void N|Nm] [--mask FILE] [--mean | --realizations N] [--dim D|auto]\n"
    "       [--ring W] [--seed N] [--band N] [-f DRIVER] [--tile-rows N] [--json]\n"
    "       mpiexec -n N fracterra fill DEM OUT.tif [...]",
    "Fills the nodata voids of a DEM (gdal_fillnodata's job) with conditional simulation: each void gets a\n"
    "power variogram (D and amplitude) fitted on a ring of valid cells around it, then the intrinsic kriging\n"
    "of the valid cells within 2 cells of it plus an exact fBm of that variogram minus its own kriging. Every\n"
    "valid cell is kept bit for bit, increments across the void's border have the statistics of those\n"
    "inside it (no seam), and the fill is as rough as the terrain around it. See docs/terrain-fill.md.\n\n"
    "Options:\n"
    "      --max-void N|Nm  voids whose bounding box is longer than N cells (or N ground units of the CRS with\n"
    "                       the suffix m, e.g. 3000m) along either axis stay nodata: sea, the outside of a\n"
    "                       survey; 0 = fill every void. Default 100 cells (gdal_fillnodata -md's default)\n"
    "      --mask FILE      raster of the DEM's size whose zero (or nodata) cells are filled too (the\n"
    "                       validity-mask convention of gdal_fillnodata -mask); the DEM's nodata is always\n"
    "                       filled\n"
    "      --mean           write the kriging mean (the best linear prediction: smooth inside large voids)\n"
    "                       instead of a realization\n"
    "  -n, --realizations N write the per-cell mean (band 1) and standard deviation (band 2) of N\n"
    "                       realizations\n"
    "  -d, --dim D|auto     D in (2,3) for every void; auto (default): fitted on each void's ring\n"
    "      --ring W         width of the ring whose variogram is fitted, cells >= 2 (default: half the\n"
    "                       void's longer side, clamped to 10..64)\n"
    "      --seed N         random seed (default 1); same seed, same cells\n"
    "      --band N         band of DEM (default 1)\n"
    "  -f, --format DRIVER  GDAL driver of OUT (default: from the extension, GeoTIFF)\n"
    "      --tile-rows N    fill N rows per stripe, each read with a halo of --max-void + ring + 1 rows (grown\n"
    "                       when a void goes on beyond it); the cells and the report are the whole run's.\n"
    "                       Automatic for a DEM beyond half of --max-memory and under mpiexec, where the\n"
    "                       ranks share the stripes and rank 0 writes (GeoTIFF only; docs/tiling.md)\n"
    "  -j, --json           print {\"input\", \"output\", \"method\", \"model\", \"units\", \"max_void\", \"seed\",\n"
    "                       \"realizations\", \"bands\", \"voids_found\", \"voids_filled\", \"cells_filled\",\n"
    "                       \"cells_left\", \"voids\": [{\"id\", \"cells_box\": [col0, row0, col1, row1],\n"
    "                       \"cells\", \"edge\", \"filled\", \"D\", \"amplitude\", \"r2\", \"D_source\",\n"
    "                       \"ring_cells\", \"conditioning_cells\", \"warnings\"}], \"warnings\",\n"
    "                       \"geotransform\", \"crs\", \"grid\"}\n"
    "  -h, --help           print this help\n\n"
    "A void is a set of 8-connected nodata cells; voids touching the raster's edge are filled like the\n"
    "others when they are within --max-void.\n\n"
    "Examples:\n"
    "  fracterra fill srtm.tif filled.tif --max-void 200 --json\n"
    "  fracterra fill dem.tif mean.tif --mean --mask holes.tif\n"
    "  fracterra fill dem.tif fill_sd.tif --realizations 32 --seed 7\n",
    run_fill,
};
