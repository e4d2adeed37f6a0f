/* fracterra — cli/cmd_reconstruct.c: `fracterra reconstruct INPUT OUT.tif`: dense terrain from sparse
 * elevations, or the nodata voids of a DEM filled, by regularization with a fractal prior (Arakawa & Krotkov
 * §3 after Szeliski: the smooth solution plus Gibbs sampling at a temperature per multigrid level), by
 * conditional simulation of a fractional Brownian surface, or the smooth (T = 0) solution alone
 * (ft_reconstruct_points, ft_reconstruct_voids; docs/terrain-reconstruct.md).
 *
 * INPUT is scattered points (CSV, XYZ text or an OGR point layer; an optional confidence column 1/sigma)
 * with a target grid from --like, or --extent and --cell, or --cell alone (the points' bounding box snapped
 * outward to the cell); or a raster DEM, whose nodata cells are filled and whose valid cells are kept.
 * With --realizations N > 1 the output has two bands: the per-cell mean and standard deviation.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "terrain_cli.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RECON_MAX_SIDE 65536
#define RECON_MAX_CELLS ((double)(1u << 30))
/* The target and its multigrid pyramid (4/3 of it), the conditioning mask, the mean and sd bands, the
 * writer's copy: about 64 bytes a cell. */
#define RECON_BYTES_PER_CELL 64.0
#define RECON_MAX_REALIZATIONS 10000

typedef struct {
    ft_recon_opts ro;
    ft_read_points_opts po;
    int band;
    int have_extent, have_cell, have_band, have_temperature, have_k;
    double extent[4]; /* xmin, ymin, xmax, ymax */
    double cell;
    const char *like, *crs, *driver, *method_text;
    int json;
} recon_args;

enum {
    OPT_EXTENT = 0x200,
    OPT_LIKE,
    OPT_WEIGHT,
    OPT_TENSION,
    OPT_LAMBDA,
    OPT_TEMPERATURE,
    OPT_K,
    OPT_REALIZATIONS,
    OPT_THREADS,
    OPT_CRS,
    OPT_X,
    OPT_Y,
    OPT_Z,
    OPT_LAYER,
    OPT_ZFIELD,
    OPT_BAND,
};

/* --extent xmin,ymin,xmax,ymax: four finite numbers with xmin < xmax and ymin < ymax. */
static int parse_extent(const cli_command *cmd, const char *arg, double *e)
{
    const char *s = arg;
    for (int i = 0; i < 4; i++) {
        char *end = NULL;
        errno = 0;
        e[i] = strtod(s, &end);
        if (end == s || errno != 0 || !isfinite(e[i]) || *end != (i < 3 ? ',' : '\0'))
            return cli_usage_error(cmd, "--extent must be xmin,ymin,xmax,ymax (four numbers), got '%s'", arg);
        s = end + 1;
    }
    if (!(e[0] < e[2]))
        return cli_usage_error(cmd, "--extent: xmin %g must be less than xmax %g (in '%s')", e[0], e[2], arg);
    if (!(e[1] < e[3]))
        return cli_usage_error(cmd, "--extent: ymin %g must be less than ymax %g (in '%s')", e[1], e[3], arg);
    return CLI_CONTINUE;
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    recon_args *a = ctx;
    switch (opt) {
    case 'm':
        a->method_text = arg;
        return ft_recon_method_parse(arg, &a->ro.method) == FT_OK
                   ? CLI_CONTINUE
                   : cli_usage_error(cmd, "--method must be fractal, conditional or smooth, got '%s'", arg);
    case 'd': return terrain_parse_dim(cmd, arg, &a->ro.dim);
    case OPT_EXTENT: a->have_extent = 1; return parse_extent(cmd, arg, a->extent);
    case 'c': a->have_cell = 1; return cli_parse_double(cmd, "--cell", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->cell);
    case OPT_LIKE: a->like = arg; return CLI_CONTINUE;
    case 'g': return cli_parse_double(cmd, "--sigma", arg, 0.0, INFINITY, CLI_CLOSED, &a->ro.sigma);
    case OPT_WEIGHT: a->po.weight = arg; return CLI_CONTINUE;
    case OPT_TENSION: return cli_parse_double(cmd, "--tension", arg, 0.0, 1.0, CLI_CLOSED, &a->ro.tension);
    case OPT_LAMBDA: return cli_parse_double(cmd, "--lambda", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->ro.lambda);
    case OPT_TEMPERATURE:
        a->have_temperature = 1;
        return cli_parse_double(cmd, "--temperature", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->ro.temperature);
    case OPT_K: a->have_k = 1; return cli_parse_double(cmd, "--k", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->ro.k);
    case 'n':
    case OPT_REALIZATIONS:
        return cli_parse_int(cmd, "--realizations", arg, 1, RECON_MAX_REALIZATIONS, &a->ro.realizations);
    case 'S': return terrain_parse_seed(cmd, arg, &a->ro.seed);
    case OPT_THREADS: return cli_parse_int(cmd, "--threads", arg, 1, 4096, &a->ro.threads);
    case OPT_CRS: a->crs = arg; return CLI_CONTINUE;
    case OPT_X: a->po.x = arg; return CLI_CONTINUE;
    case OPT_Y: a->po.y = arg; return CLI_CONTINUE;
    case OPT_Z: a->po.z = arg; return CLI_CONTINUE;
    case OPT_LAYER: a->po.layer = arg; return CLI_CONTINUE;
    case OPT_ZFIELD: a->po.zfield = arg; return CLI_CONTINUE;
    case OPT_BAND: a->have_band = 1; return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->band);
    case 'f': a->driver = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* The options checked together, before any file is read. */
static int check_options(const cli_command *cmd, const recon_args *a)
{
    if (a->like && a->have_extent)
        return cli_usage_error(cmd, "--like and --extent exclude each other (--like %s gives the grid)", a->like);
    if (a->like && a->have_cell)
        return cli_usage_error(cmd, "--like and --cell exclude each other (--like %s gives the grid)", a->like);
    if (a->have_extent && !a->have_cell)
        return cli_usage_error(cmd, "--extent needs --cell C (the cell size)");
    const char *fractal_only = NULL;
    if (a->have_temperature)
        fractal_only = "--temperature";
    else if (a->have_k)
        fractal_only = "--k";
    if (fractal_only && a->ro.method != FT_RECON_FRACTAL)
        return cli_usage_error(cmd, "%s applies to --method fractal only (method is %s)", fractal_only,
                               ft_recon_method_name(a->ro.method));
    if (a->have_temperature && a->have_k)
        return cli_usage_error(cmd, "--temperature and --k exclude each other (--temperature sets T0 itself)");
    return CLI_CONTINUE;
}

/* The options that only make sense for one kind of input, once the kind is known. */
static int check_kind(const cli_command *cmd, const recon_args *a, const char *in, ft_file_kind kind)
{
    if (kind == FT_KIND_GRID) {
        const char *grid_opt = a->have_extent ? "--extent" : a->have_cell ? "--cell" : a->like ? "--like" : NULL;
        if (grid_opt)
            return cli_usage_error(cmd, "%s: %s is a raster, whose nodata voids are filled on its own grid; "
                                   "--extent, --cell and --like are for point input", grid_opt, in);
        const char *pt_opt = NULL;
        if (a->po.weight)
            pt_opt = "--weight";
        else if (a->po.x || a->po.y || a->po.z)
            pt_opt = "--x/--y/--z";
        else if (a->po.zfield)
            pt_opt = "--zfield";
        if (pt_opt)
            return cli_usage_error(cmd, "%s: %s is a raster; %s is for point input", pt_opt, in, pt_opt);
        return CLI_CONTINUE;
    }
    if (kind == FT_KIND_CHAINS) {
        cli_error(cmd, "%s holds lines or polygons: INPUT must be points (CSV, XYZ, an OGR point layer) or a "
                  "raster DEM", in);
        return CLI_FAIL;
    }
    if (a->have_band)
        return cli_usage_error(cmd, "--band: %s holds points; --band is for a raster DEM", in);
    if (!a->like && !a->have_cell)
        return cli_usage_error(cmd, "%s holds points: give the target grid with --like GRID, or --cell C "
                               "(with --extent, or over the points' bounding box)", in);
    return CLI_CONTINUE;
}

/* The target grid of point input: --like's shape and CRS, or --extent/--cell (upper-left corner at
 * xmin, ymax), or the points' bounding box snapped outward to multiples of the cell, with the points
 * strictly inside the right and bottom edges. CRS: --crs, else --like's, else the points'. */
static int target_grid(const cli_command *cmd, const recon_args *a, const ft_points *p, const char *wkt,
                       ft_grid **out)
{
    double x0, y0, x1, y1, c = a->cell;
    const char *crs = wkt ? wkt : p->crs_wkt;
    ft_grid *t = NULL;
    if (a->like) {
        ft_grid *like = NULL;
        ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
        if (ft_io_read_grid(a->like, &go, &like) != FT_OK)
            return cli_fail(cmd);
        if ((t = ft_grid_create(like->nx, like->ny)) != NULL) {
            memcpy(t->gt, like->gt, sizeof t->gt);
            if (ft_grid_set_crs(t, wkt ? wkt : like->crs_wkt) != FT_OK) {
                ft_grid_free(t);
                t = NULL;
            }
        }
        ft_grid_free(like);
        if (t == NULL)
            return cli_fail(cmd);
        *out = t;
        return CLI_CONTINUE;
    }
    if (a->have_extent) {
        x0 = a->extent[0];
        y0 = a->extent[1];
        x1 = a->extent[2];
        y1 = a->extent[3];
    } else {
        ft_points_bbox(p, &x0, &y0, &x1, &y1);
    }
    size_t nx = 0, ny = 0;
    double gt[6];
    if (ft_grid_shape_for_extent(x0, y0, x1, y1, c, !a->have_extent, &nx, &ny, gt) != FT_OK || nx > RECON_MAX_SIDE ||
        ny > RECON_MAX_SIDE || (double)nx * (double)ny > RECON_MAX_CELLS)
        return cli_usage_error(cmd, "--cell %g gives a grid of %.0f x %.0f cells over %g x %g; at most %d per side "
                               "and %.0f in all", c, ceil((x1 - x0) / c), ceil((y1 - y0) / c), x1 - x0, y1 - y0,
                               RECON_MAX_SIDE, RECON_MAX_CELLS);
    char what[200];
    snprintf(what, sizeof what, "--cell %g over %g x %g (%zu x %zu cells)", c, gt[1] * (double)nx,
             gt[1] * (double)ny, nx, ny);
    if (ft_check_memory((double)nx * (double)ny * RECON_BYTES_PER_CELL, what) != FT_OK)
        return cli_fail(cmd);
    if ((t = ft_grid_create(nx, ny)) == NULL)
        return cli_fail(cmd);
    memcpy(t->gt, gt, sizeof gt);
    if (ft_grid_set_crs(t, crs) != FT_OK) {
        ft_grid_free(t);
        return cli_fail(cmd);
    }
    *out = t;
    return CLI_CONTINUE;
}

static json_object *cell_json(const ft_grid *g)
{
    if (fabs(g->gt[1]) == fabs(g->gt[5]) && g->gt[2] == 0.0 && g->gt[4] == 0.0)
        return cli_json_double(fabs(g->gt[1]));
    json_object *c = json_object_new_array();
    json_object_array_add(c, cli_json_double(hypot(g->gt[1], g->gt[4])));
    json_object_array_add(c, cli_json_double(hypot(g->gt[2], g->gt[5])));
    return c;
}

static int report(const cli_command *cmd, const recon_args *a, const char *in, const char *out, ft_file_kind kind,
                  const ft_grid *g, const ft_recon_info *info)
{
    const int fractal = a->ro.method == FT_RECON_FRACTAL;
    /* the smooth method needs no D, and only the fractal one Pentland's sigma0: 0 = not computed */
    const int have_dim = info->dim > 0.0, have_sigma0 = info->sigma0 > 0.0;
    if (!a->json) {
        printf("wrote %s: %zu x %zu cells%s, method %s", out, g->nx, g->ny,
               a->ro.realizations > 1 ? " (band 1 mean, band 2 sd)" : "", ft_recon_method_name(a->ro.method));
        if (have_dim)
            printf(", D = %.4g (%s)", info->dim, info->dim_estimated ? "estimated" : "given");
        printf(", tension %.3g, seed %llu\n", info->tension, (unsigned long long)a->ro.seed);
        if (fractal)
            printf("  T0 = %.4g (g(D) k sigma0^2, k %.4g, sigma0 %.4g), %d levels\n", info->temperature, info->k,
                   info->sigma0, info->levels);
        printf("  %s %zu, filled %zu cells, data rms %.4g\n", kind == FT_KIND_GRID ? "known cells" : "data used",
               info->data_used, info->filled, info->data_rms);
        if (kind != FT_KIND_GRID && info->data_outside > 0)
            printf("  %zu points outside the grid ignored\n", info->data_outside);
        return CLI_OK;
    }
    json_object *o = terrain_report_start(1, in, out);
    json_object_object_add(o, "input_kind", json_object_new_string(kind == FT_KIND_GRID ? "grid" : "points"));
    json_object_object_add(o, "method", json_object_new_string(ft_recon_method_name(a->ro.method)));
    json_object_object_add(o, "dim", a->ro.dim > 0.0 ? cli_json_double(a->ro.dim) : json_object_new_string("auto"));
    json_object_object_add(o, "D", have_dim ? cli_json_double(info->dim) : NULL);
    json_object_object_add(o, "D_estimated", json_object_new_boolean(info->dim_estimated));
    json_object_object_add(o, "sigma0", have_sigma0 ? cli_json_double(info->sigma0) : NULL);
    json_object_object_add(o, "k", fractal ? cli_json_double(info->k) : NULL);
    json_object_object_add(o, "temperature", fractal ? cli_json_double(info->temperature) : NULL);
    json_object_object_add(o, "levels", json_object_new_int(info->levels));
    json_object_object_add(o, "data_used", json_object_new_int64((int64_t)info->data_used));
    json_object_object_add(o, "data_outside", json_object_new_int64((int64_t)info->data_outside));
    json_object_object_add(o, "filled", json_object_new_int64((int64_t)info->filled));
    json_object_object_add(o, "data_rms", cli_json_double(info->data_rms));
    json_object_object_add(o, "sigma", cli_json_double(a->ro.sigma));
    json_object_object_add(o, "lambda", cli_json_double(info->lambda));
    json_object_object_add(o, "tension", cli_json_double(info->tension));
    json_object_object_add(o, "realizations", json_object_new_int(a->ro.realizations));
    json_object_object_add(o, "seed", json_object_new_uint64(a->ro.seed));
    json_object_object_add(o, "bands", json_object_new_string(a->ro.realizations > 1 ? "1: mean, 2: sd" : "1: z"));
    json_object_object_add(o, "nx", json_object_new_int64((int64_t)g->nx));
    json_object_object_add(o, "ny", json_object_new_int64((int64_t)g->ny));
    json_object_object_add(o, "cell", cell_json(g));
    terrain_add_grid_json(o, g);
    return cli_print_json(cmd, o);
}

/* Reads INPUT (after the kind checks), reconstructs and writes OUT. */
static int reconstruct(const cli_command *cmd, recon_args *a, const char *in, const char *out, ft_file_kind kind,
                       const char *wkt)
{
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
    lo.layer = a->po.layer;
    go.band = a->band;
    ft_data d = {0};
    if (ft_io_read_any(in, &lo, &go, &a->po, &d) != FT_OK)
        return cli_fail(cmd);
    ft_grid *target = NULL, *z = NULL, *sd = NULL;
    ft_recon_info info;
    memset(&info, 0, sizeof info);
    int rc = CLI_CONTINUE;
    ft_crs_info crs;
    rc = cli_geo_crs(cmd, in, d.kind == FT_KIND_GRID ? d.grid->crs_wkt : d.points ? d.points->crs_wkt : NULL, &crs);
    if (rc == CLI_CONTINUE && crs.geographic && d.kind == FT_KIND_GRID) { /* voids: filled in place, in cells */
        cli_geo_warn_square_cells(cmd, in, d.grid, &crs);
    } else if (rc == CLI_CONTINUE && crs.geographic) {
        rc = cli_geo_refuse(cmd, in, &crs, "the target grid's cells and the fractal scaling of the lags are lengths "
                            "on the ground, which degrees are not", "ogr2ogr -t_srs EPSG:32632 out.gpkg in.gpkg");
    }
    if (rc == CLI_CONTINUE && d.kind == FT_KIND_POINTS && d.points->n < 3) {
        cli_error(cmd, "%s holds %zu point%s; a reconstruction needs at least 3 (not on a line)", in, d.points->n,
                  d.points->n == 1 ? "" : "s");
        rc = CLI_FAIL;
    }
    if (rc == CLI_CONTINUE && d.kind == FT_KIND_POINTS)
        rc = target_grid(cmd, a, d.points, wkt, &target);
    if (rc == CLI_CONTINUE && d.kind == FT_KIND_GRID) {
        char what[PATH_MAX + 64];
        snprintf(what, sizeof what, "reconstructing '%s' (%zu x %zu cells)", in, d.grid->nx, d.grid->ny);
        if (ft_check_memory((double)d.grid->nx * (double)d.grid->ny * RECON_BYTES_PER_CELL, what) != FT_OK)
            rc = cli_fail(cmd);
        else
            rc = cli_check_grid_work(cmd, in, d.grid);
    }
    if (rc == CLI_CONTINUE) {
        a->ro.progress = cli_progress();
        ft_grid **sd_out = a->ro.realizations > 1 ? &sd : NULL;
        int lib = d.kind == FT_KIND_GRID ? ft_reconstruct_voids(d.grid, &a->ro, &z, sd_out, &info)
                                         : ft_reconstruct_points(d.points, target, &a->ro, &z, sd_out, &info);
        if (lib == FT_OK && d.kind == FT_KIND_GRID && wkt)
            lib = ft_grid_set_crs(z, wkt);
        if (lib == FT_OK && sd) {
            memcpy(sd->gt, z->gt, sizeof sd->gt);
            lib = ft_grid_set_crs(sd, z->crs_wkt);
        }
        if (lib == FT_OK) {
            ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
            wo.driver = a->driver;
            const ft_grid *bands[2] = {z, sd};
            lib = sd ? ft_io_write_grids(out, bands, 2, &wo) : ft_io_write_grid(out, z, &wo);
        }
        rc = lib == FT_OK ? report(cmd, a, in, out, kind, z, &info) : cli_fail(cmd);
    }
    ft_grid_free(sd);
    ft_grid_free(z);
    ft_grid_free(target);
    ft_data_clear(&d);
    return rc;
}

static int run_reconstruct(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"method", required_argument, NULL, 'm'},
        {"dim", required_argument, NULL, 'd'},
        {"extent", required_argument, NULL, OPT_EXTENT},
        {"cell", required_argument, NULL, 'c'},
        {"like", required_argument, NULL, OPT_LIKE},
        {"sigma", required_argument, NULL, 'g'},
        {"weight", required_argument, NULL, OPT_WEIGHT},
        {"tension", required_argument, NULL, OPT_TENSION},
        {"lambda", required_argument, NULL, OPT_LAMBDA},
        {"temperature", required_argument, NULL, OPT_TEMPERATURE},
        {"k", required_argument, NULL, OPT_K},
        {"realizations", required_argument, NULL, OPT_REALIZATIONS},
        {"seed", required_argument, NULL, 'S'},
        {"threads", required_argument, NULL, OPT_THREADS},
        {"crs", required_argument, NULL, OPT_CRS},
        {"x", required_argument, NULL, OPT_X},
        {"y", required_argument, NULL, OPT_Y},
        {"z", required_argument, NULL, OPT_Z},
        {"layer", required_argument, NULL, OPT_LAYER},
        {"zfield", required_argument, NULL, OPT_ZFIELD},
        {"band", required_argument, NULL, OPT_BAND},
        {"format", required_argument, NULL, 'f'},
        {"json", no_argument, NULL, 'j'},
        CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"INPUT", "OUT"};
    recon_args a = {.ro = FT_RECON_OPTS_DEFAULT, .po = FT_READ_POINTS_OPTS_DEFAULT, .band = 1};
    a.ro.seed = TERRAIN_DEFAULT_SEED;
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "m:d:c:n:f:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = check_options(cmd, &a);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "OUT", argv[first + 1], argv[first], a.like ? a.like : "", (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    const char *in = argv[first], *out = argv[first + 1];
    char *wkt = NULL;
    if (a.crs && ft_io_crs_to_wkt(a.crs, &wkt) != FT_OK) {
        cli_error(cmd, "--crs: %s", ft_last_error());
        return CLI_USAGE;
    }
    ft_file_kind kind = FT_KIND_UNKNOWN;
    if (ft_io_probe(in, a.po.layer, &kind) != FT_OK || ft_io_check_writable(out) != FT_OK)
        rc = cli_fail(cmd);
    else
        rc = check_kind(cmd, &a, in, kind);
    if (rc == CLI_CONTINUE && a.ro.realizations > 1 && a.ro.method == FT_RECON_SMOOTH)
        cli_warn(cmd, "--realizations %d with --method smooth: the smooth solution is deterministic, band 2 (sd) "
                 "is zero", a.ro.realizations);
    if (rc == CLI_CONTINUE)
        rc = reconstruct(cmd, &a, in, out, kind, wkt);
    free(wkt);
    return rc;
}

const cli_command cli_cmd_reconstruct = {
    "reconstruct",
    "dense terrain from scattered elevations, or a DEM's voids filled (fractal, conditional, smooth)",
    "fracterra reconstruct INPUT OUT.tif [--method fractal|conditional|smooth] [--dim D|auto]\n"
    "       [--extent XMIN,YMIN,XMAX,YMAX] [--cell C] [--like GRID.tif] [--sigma S] [--weight FIELD]\n"
    "       [--tension T] [--lambda L] [--temperature T0 | --k K] [--realizations N] [--seed N]\n"
    "       [--threads N] [--crs CRS] [--x COL --y COL --z COL] [--layer NAME] [--zfield NAME] [--band N]\n"
    "       [-f DRIVER] [--json]",
    "Reconstructs a dense grid from scattered elevations (CSV with a header, XYZ text, or an OGR point\n"
    "layer), or fills the nodata voids of a raster DEM (its valid cells are kept exactly), with terrain as\n"
    "rough as the data: regularization with a fractal prior on a multigrid (Arakawa & Krotkov section 3,\n"
    "after Szeliski), see docs/terrain-reconstruct.md.\n\n"
    "Methods:\n"
    "  fractal      the paper's (default): the smooth solution plus an exact sample of Szeliski's\n"
    "               multilevel prior of D (thin plate weighted 2^(-2(3-D)l) on pyramid level l)\n"
    "               conditioned on the data (Gibbs distribution at T = g(D) k sigma0^2, g calibrated),\n"
    "               drawn by perturbation and optimization\n"
    "  conditional  an unconditional fBm surface of dimension D plus the smooth interpolation of its\n"
    "               residuals at the data: honours the data exactly; its one-cell roughness and white\n"
    "               share measured on data cells 1 and 2 cells apart (else Yokoya's line at one cell)\n"
    "  smooth       the T = 0 solution (thin plate / membrane): the interpolator, too smooth by design\n\n"
    "Target grid of point input (one of):\n"
    "      --like GRID      the shape, geotransform and CRS of a raster\n"
    "      --extent XMIN,YMIN,XMAX,YMAX --cell C\n"
    "                       north-up cells of C from (XMIN, YMAX); the last column and row may reach past\n"
    "                       XMAX and YMIN\n"
    "  -c, --cell C         alone: the points' bounding box snapped outward to multiples of C\n"
    "A raster INPUT is filled on its own grid (--extent, --cell and --like are refused).\n\n"
    "Options:\n"
    "  -m, --method M       fractal (default), conditional or smooth\n"
    "  -d, --dim D|auto     fractal dimension in (2,3); auto (default): estimated from the data (points:\n"
    "                       Yokoya's estimator; a DEM: its valid cells)\n"
    "  -g, --sigma S        standard deviation of a datum without a weight, elevation units (default 0:\n"
    "                       interpolate); the data are then fitted to within their sigmas\n"
    "      --weight FIELD   column or field holding each point's confidence 1/sigma\n"
    "      --tension T      prior: 0 thin plate .. 1 membrane (default: fractal, conditional, and smooth\n"
    "                       with --dim: from D; fractal: the multilevel prior's finest-level blend,\n"
    "                       0.2 at D 2.2, 0.4 at 2.5, 1 at 2.8; conditional and smooth: Szeliski's crossover,\n"
    "                       tau/(1-tau) = 2 (D-2)/(3-D): 0.33 at D 2.2, 0.67 at 2.5, 0.89 at 2.8;\n"
    "                       smooth without --dim: 0.1)\n"
    "      --lambda L       weight of the prior against the data, > 0 (default 1). With sigmas: the\n"
    "                       largest weight; lowered until the RMS of (z - datum)/sigma at the data is\n"
    "                       about 1 (Morozov's discrepancy principle) if it misses them by more\n"
    "      --temperature T  fractal: the temperature, instead of k sigma0^2\n"
    "      --k K            fractal: the constant of T = g(D) k sigma0^2 (default: the library's, 7.5;\n"
    "                       g(D) 1.13 at D 2.2, 1.55 at 2.5, 0.73 at 2.8, calibrated on the structure\n"
    "                       function)\n"
    "  -n, --realizations N write the per-cell mean (band 1) and standard deviation (band 2) of N runs\n"
    "                       (streams seed, seed+1, ...); default 1\n"
    "      --seed N         random seed (default 1; printed in the JSON); same seed, same cells\n"
    "      --threads N      OpenMP threads (default: OMP_NUM_THREADS); the cells do not depend on it\n"
    "      --crs CRS        assign the output's CRS (EPSG:n, WKT, PROJ); no reprojection. Default: --like's,\n"
    "                       else the input's\n"
    "      --x/--y/--z COL  CSV column names (default x, y, z)\n"
    "      --layer NAME     OGR layer (default: the first); --zfield NAME: z from this field\n"
    "      --band N         band of a raster INPUT (default 1)\n"
    "  -f, --format DRIVER  GDAL driver of OUT (default: from the extension, GeoTIFF)\n"
    "  -j, --json           print {\"input\", \"output\", \"input_kind\", \"method\", \"dim\" (as given or \"auto\"),\n"
    "                       \"D\" (used), \"D_estimated\", \"sigma0\", \"k\", \"temperature\", \"levels\", \"data_used\",\n"
    "                       \"data_outside\", \"filled\", \"data_rms\", \"sigma\", \"lambda\", \"tension\", \"realizations\", \"seed\", \"bands\",\n"
    "                       \"nx\", \"ny\", \"cell\", \"geotransform\", \"crs\",\n"
    "                       \"grid\": {\"size\", \"mean\", \"sd\", \"min\", \"max\"}}\n"
    "  -h, --help           print this help\n\n"
    "Points outside the grid are ignored and counted (\"data_outside\"); at least 3 must fall inside.\n"
    "A progress bar goes to stderr when it is a terminal.\n\n"
    "Examples:\n"
    "  fracterra reconstruct tests/data/points_mass_topo_davis1973.csv topo.tif --cell 0.1 --dim 2.3\n"
    "  fracterra reconstruct spots.gpkg dem.tif --like area.tif --method conditional --realizations 16 --seed 7\n"
    "  fracterra reconstruct dem_with_voids.tif filled.tif --method fractal --json\n",
    run_reconstruct,
};
