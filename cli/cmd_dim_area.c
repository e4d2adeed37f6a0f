/* fracterra — cli/cmd_dim_area.c: `fracterra dim area INPUT`: the box-counting dimension of the polygons of a
 * vector layer, or of the classes of a classified raster (Zhang, Yu & Fan 2008, Eqs. 1-4), counted exactly
 * from the geometry: boxes crossed by the boundary (--what boundary) or touching the interior (--what area).
 *
 * A vector layer gives one result for the whole layer; with --class FIELD, the whole layer and then one
 * result per value of FIELD ({"features": [{"id": null, "scope": "layer", ...}, {"id": "residential",
 * "scope": "class", ...}]}). A raster gives one result per distinct cell value. A set that cannot be measured
 * (too small for the box sizes) is reported with an "error" and a warning; the command fails only if none
 * could be measured. The printing, JSON and plots are dim_output's, shared with `dim line`.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "dim_output.h"
#include "urban_cli.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    cli_dim_opts dim;
    urban_box_args box;
    const char *layer, *where, *cls;
} area_args;

typedef struct {
    const cli_command *cmd;
    cli_dim_report *rep;
    int classes; /* 1 when every set is a feature group (--class, or a raster) */
    const char *what;
    ft_crs_info crs; /* of the input */
} area_ctx;

/* ---- collecting ---- */

/* Adds one measured set to the report. */
static int add_set(const urban_set *s, ft_dim_result *r, void *arg)
{
    area_ctx *c = arg;
    json_object *info = json_object_new_object();
    if (c->classes)
        json_object_object_add(info, "scope", json_object_new_string(s->label ? "class" : "layer"));
    json_object_object_add(info, "what", json_object_new_string(c->what));
    json_object *figures = urban_set_info(s);
    json_object_object_foreach(figures, key, val) json_object_object_add(info, key, json_object_get(val));
    json_object_put(figures);
    char label[256];
    snprintf(label, sizeof label, "%s", s->label ? s->label : "whole layer");
    int rc = cli_dim_report_group(c->rep, c->classes, json_object_get(s->id), label, info);
    if (rc == FT_OK && r == NULL)
        cli_dim_report_group_failed(c->cmd, c->rep);
    else if (rc == FT_OK) {
        cli_geo_units(r, &c->crs);
        rc = cli_dim_report_add(c->rep, r, "box side", "boxes");
    }
    else
        ft_dim_result_free(r);
    return rc;
}

static void set_scales(const area_args *a, ft_area_dim_opts *o)
{
    *o = a->box.dim;
    o->min_cell = a->dim.min_scale;
    o->max_cell = a->dim.max_scale;
    o->nscales = a->dim.nscales;
    o->fit_whole_range = o->ncells > 0 || (a->dim.min_scale > 0.0 && a->dim.max_scale > 0.0);
    o->fit.regime = a->dim.regime;
    o->progress = cli_progress();
}

/* Reads INPUT: a vector layer, or a raster when no --layer is named. CLI_CONTINUE, CLI_USAGE (a bad --where
 * filter, --class or --where on a raster) or CLI_FAIL; messages printed. */
static int read_input(const cli_command *cmd, const char *path, const area_args *a, ft_data *d)
{
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    lo.layer = a->layer;
    lo.where = a->where;
    int rc = ft_io_read_any(path, &lo, NULL, NULL, d);
    if (rc == FT_E_INVALID)
        return cli_usage_error(cmd, "%s", ft_last_error());
    if (rc == FT_OK && d->kind == FT_KIND_POINTS)
        rc = ft_error(FT_E_FORMAT, "%s holds points: dim area measures polygons or a classified raster", path);
    if (rc == FT_OK && d->layer)
        rc = ft_layer_check_finite(d->layer);
    if (rc != FT_OK)
        return cli_fail(cmd);
    if (d->grid && cli_check_grid_work(cmd, path, d->grid) != CLI_CONTINUE)
        return CLI_FAIL;
    if (d->grid && (a->cls || a->where))
        return cli_usage_error(cmd, "%s is a raster: its classes are its cell values (--class and --where are for "
                                    "vector layers)",
                               path);
    return CLI_CONTINUE;
}

/* Reads INPUT and measures it into the report. */
static int measure_input(const cli_command *cmd, const char *path, const area_args *a, area_ctx *c,
                         json_object *extra)
{
    ft_data d = {0};
    ft_area_dim_opts o;
    set_scales(a, &o);
    int rc = read_input(cmd, path, a, &d);
    if (rc == CLI_CONTINUE && d.layer) /* lon/lat polygons: boxes in a local equal-area projection */
        rc = cli_geo_layer_ground(cmd, path, d.layer, FT_LOCAL_LAEA, &c->crs);
    else if (rc == CLI_CONTINUE && (rc = cli_geo_crs(cmd, path, d.grid->crs_wkt, &c->crs)) == CLI_CONTINUE &&
             c->crs.geographic)
        rc = cli_geo_refuse(cmd, path, &c->crs, "its cells are not squares on the ground, and a classified raster "
                            "cannot be resampled", "gdalwarp -t_srs EPSG:3035 -r near in.tif out.tif");
    if (rc == CLI_CONTINUE && c->crs.geographic)
        json_object_object_add(extra, "geographic", cli_geo_json(&c->crs, d.layer->crs_wkt));
    if (rc == CLI_CONTINUE) {
        c->classes = a->cls != NULL || d.grid != NULL;
        json_object_object_add(extra, "layer", d.layer && d.layer->name ? json_object_new_string(d.layer->name)
                                                                         : NULL);
        int mrc = d.grid ? urban_measure_grid(d.grid, &o, add_set, c)
                         : urban_measure_layer(d.layer, a->cls, 1, &o, add_set, c);
        rc = mrc == FT_OK ? CLI_OK : cli_fail(cmd);
    }
    ft_data_clear(&d);
    return rc;
}

/* ---- the command ---- */

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    area_args *a = ctx;
    int rc = cli_dim_option(cmd, opt, arg, &a->dim);
    if (rc == CLI_DIM_NOT_SHARED)
        rc = urban_box_option(cmd, opt, arg, &a->box);
    if (rc != URBAN_NOT_SHARED)
        return rc;
    switch (opt) {
    case 'c': a->cls = arg; return CLI_CONTINUE;
    case 'l': a->layer = arg; return CLI_CONTINUE;
    case 'w': a->where = arg; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int check_args(const cli_command *cmd, const area_args *a)
{
    int rc = cli_dim_check(cmd, &a->dim);
    if (rc == CLI_CONTINUE && a->box.dim.ncells > 0 && a->box.dim.ncells < 3)
        rc = cli_usage_error(cmd, "--cell: give at least 3 box sides to fit a line, got %zu", a->box.dim.ncells);
    if (rc == CLI_CONTINUE && a->box.dim.ncells > 0 && (a->dim.min_scale > 0.0 || a->dim.max_scale > 0.0 ||
                                                        a->dim.nscales > 0))
        rc = cli_usage_error(cmd, "--cell gives the box sides: it cannot go with --min-scale, --max-scale or "
                                  "--scales");
    if (rc == CLI_CONTINUE && a->dim.plot && ft_io_check_writable(a->dim.plot) != FT_OK)
        rc = cli_fail(cmd);
    return rc;
}

static int run_dim_area(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"class", required_argument, NULL, 'c'}, {"layer", required_argument, NULL, 'l'},
        {"where", required_argument, NULL, 'w'}, URBAN_BOX_LONGOPTS,
        CLI_DIM_LONGOPTS,                        CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"INPUT"};
    area_args a = {.dim = CLI_DIM_OPTS_DEFAULT};
    urban_box_init(&a.box);
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "c:l:w:" CLI_DIM_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE)
        rc = check_args(cmd, &a);
    if (rc != CLI_CONTINUE)
        return rc;
    const char *path = argv[first];
    area_ctx c = {cmd, cli_dim_report_create(path), 0, ft_area_what_name(a.box.dim.what), {0}};
    json_object *extra = json_object_new_object();
    json_object_object_add(extra, "file", json_object_new_string(path));
    if (a.cls)
        json_object_object_add(extra, "class", json_object_new_string(a.cls));
    json_object_object_add(extra, "offsets", json_object_new_int(a.box.dim.offsets));
    json_object_object_add(extra, "fewest_boxes", json_object_new_boolean(a.box.dim.fewest));
    rc = c.rep ? measure_input(cmd, path, &a, &c, extra) : (ft_error(FT_E_NOMEM, "out of memory"), cli_fail(cmd));
    if (rc == CLI_OK && cli_dim_report_count(c.rep) == 0) {
        cli_error(cmd, "nothing in '%s' could be measured", path);
        rc = CLI_FAIL;
    }
    if (rc == CLI_OK)
        rc = cli_dim_report_print(cmd, c.rep, &a.dim, json_object_get(extra));
    json_object_put(extra);
    cli_dim_report_free(c.rep);
    return rc;
}

const cli_command cli_cmd_dim_area = {
    "dim area",
    "box-counting dimension of polygon layers and classified rasters",
    "fracterra dim area INPUT [--class FIELD] [--what boundary|area] [--cell SIZE ...] [--offsets K]\n"
    "                         [--layer NAME] [--where SQL] [--min-scale S] [--max-scale S] [--scales N]\n"
    "                         [--segments] [--plot FILE] [--json]",
    "Measures the box-counting dimension D of the polygons of INPUT, N(r) ~ r^-D (Zhang, Yu & Fan 2008,\n"
    "Eqs. 1-4), counting boxes exactly from the vector geometry: with --what boundary the boxes a ring passes\n"
    "through, with --what area the boxes touching the polygons' interior (a filled square gives 2, its\n"
    "outline 1). At each box side the count is the mean over K x K shifted grid origins (--fewest-boxes: the\n"
    "fewest, the literature's). D is read from the straightest run of the log-log plot (docs/loglog.md) and\n"
    "the whole table is reported, as `dim line` does. Method: docs/urban-boxcount.md.\n\n"
    "INPUT is an OGR polygon layer, or a classified raster (one class per cell value: land use coded 1, 2,\n"
    "3...), measured value by value on its cells (box sides rounded to whole cells).\n\n"
    "Options:\n"
    "  -c, --class FIELD    also one result per value of FIELD (residential, industrial, water, ...)\n"
    "  -l, --layer NAME     the vector layer to read (default: the first)\n"
    "  -w, --where SQL      only the features matching this OGR attribute filter\n" URBAN_BOX_HELP
    CLI_DIM_OPTIONS_HELP
    "  -h, --help           print this help\n"
    "Default sizes: 12 sides from the median segment length (at most 1/16 of the largest) to 1/48 of the\n"
    "extent's diagonal. With --cell, or both --min-scale and --max-scale, D is fitted over every size.\n\n"
    "JSON: {\"file\", \"layer\", \"what\", \"features\", \"polygons\", \"holes\", \"area\", \"perimeter\",\n"
    "\"method\", \"D\", \"r2\", \"stderr\", \"range\", \"segmentation\", \"max_err\", \"table\": [{\"scale\",\n"
    "\"value\", \"count\", \"slope\", \"used\"}]}. With --class, \"features\": [{\"id\", \"scope\", ...}]: the\n"
    "whole layer first (id null, scope \"layer\"), then each class (scope \"class\"); a raster gives one entry\n"
    "per cell value, with \"cells\" for \"features\" and \"holes\".\n\n"
    "Examples:\n"
    "  fracterra dim area landuse-1997.gpkg --class use --what area --plot d1997.svg\n"
    "  fracterra dim area tests/data/dcw_us_states_small_albers5070.geojson --class code --json | jq "
    "'.features[].D'\n",
    run_dim_area,
};
