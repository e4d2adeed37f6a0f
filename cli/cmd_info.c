/* fracterra — cli/cmd_info.c: `fracterra info FILE`: what fracterra sees in a file.
 *
 * The file is read once by ft_io_read_any (grid, chains or points) through the library's readers, so the figures are
 * those every other command will work with: for grids the size, valid and nodata cells, z range, extent,
 * cell size and CRS; for chains the features, parts (rings and lines), vertices and fields; for points the
 * count, extent and z range. Rings are counted without their repeated closing vertex ("vertices", as
 * fracterra stores them) and with it ("file_vertices", as GeoJSON, Shapefile and ogrinfo count them).
 * An all-nodata grid and chains of fewer than 2 vertices are facts about the file: they are reported
 * with a warning on stderr and the command still succeeds.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"

#include <gdal.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    const char *layer;
    int band;
    int json;
} info_args;

static const char *kind_name(ft_file_kind k)
{
    switch (k) {
    case FT_KIND_GRID: return "grid";
    case FT_KIND_CHAINS: return "chains";
    case FT_KIND_POINTS: return "points";
    default: return "unknown";
    }
}

/* The reader that will handle the file: our own text readers by extension, else GDAL's driver. */
static const char *driver_name(const char *path)
{
    if (ft_io_is_text_chains(path))
        return "GMT text";
    if (ft_io_is_text_points(path))
        return strlen(path) >= 4 && strcmp(path + strlen(path) - 4, ".xyz") == 0 ? "XYZ text" : "CSV text";
    GDALDriverH d = GDALIdentifyDriverEx(path, GDAL_OF_RASTER | GDAL_OF_VECTOR, NULL, NULL);
    return d ? GDALGetDriverShortName(d) : NULL;
}

static json_object *json_extent(double xmin, double ymin, double xmax, double ymax)
{
    json_object *a = json_object_new_array();
    json_object_array_add(a, cli_json_double(xmin));
    json_object_array_add(a, cli_json_double(ymin));
    json_object_array_add(a, cli_json_double(xmax));
    json_object_array_add(a, cli_json_double(ymax));
    return a;
}

static json_object *json_pair(json_object *a, json_object *b)
{
    json_object *p = json_object_new_array();
    json_object_array_add(p, a);
    json_object_array_add(p, b);
    return p;
}

static json_object *json_crs(const char *wkt)
{
    char name[256];
    int epsg;
    if (ft_io_crs_name(wkt, name, sizeof name, &epsg) != FT_OK || (name[0] == '\0' && epsg == 0)) {
        ft_clear_error();
        return NULL;
    }
    json_object *o = json_object_new_object();
    json_object_object_add(o, "name", json_object_new_string(name));
    json_object_object_add(o, "epsg", epsg ? json_object_new_int(epsg) : NULL);
    ft_crs_info crs; /* what the measuring commands will make of it (docs/geographic.md) */
    if (ft_io_crs_info(wkt, &crs) == FT_OK) {
        json_object_object_add(o, "geographic", json_object_new_boolean(crs.geographic));
        json_object_object_add(o, "unit", json_object_new_string(crs.unit));
        json_object_object_add(o, "ellipsoid", json_object_new_string(crs.ellipsoid_name));
    }
    ft_clear_error();
    return o;
}

/* A lon/lat grid's cell size on the ground at its centre, metres (dx shrinks with cos(latitude)). */
static json_object *ground_cell(const ft_grid *g, double ymid)
{
    ft_crs_info crs;
    double per_lon, per_lat;
    if (ft_io_crs_info(g->crs_wkt, &crs) != FT_OK || !crs.geographic || !(fabs(ymid) <= 90.0)) {
        ft_clear_error();
        return NULL;
    }
    ft_ellipsoid_metres_per_degree(&crs.ellipsoid, ymid, &per_lon, &per_lat);
    return json_pair(cli_json_double(fabs(g->gt[1]) * per_lon), cli_json_double(fabs(g->gt[5]) * per_lat));
}

static void add_size(json_object *o, const char *key, size_t v)
{
    json_object_object_add(o, key, json_object_new_int64((int64_t)v));
}

/* Warnings are collected in a "warnings" array that cli_info_describe moves to the object's end. */
static void add_warning(json_object *o, const char *msg)
{
    json_object *w;
    if (!json_object_object_get_ex(o, "warnings", &w)) {
        w = json_object_new_array();
        json_object_object_add(o, "warnings", w);
    }
    json_object_array_add(w, json_object_new_string(msg));
}

static void warnings_last(json_object *o)
{
    json_object *w;
    if (json_object_object_get_ex(o, "warnings", &w)) {
        json_object_get(w);
        json_object_object_del(o, "warnings");
        json_object_object_add(o, "warnings", w);
    }
}

static int describe_grid(const ft_grid_summary *s, int band, json_object *o)
{
    const ft_grid *g = &s->header;
    size_t cells = g->nx * g->ny, valid = s->valid;
    double x0, y0, x1, y1;
    json_object_object_add(o, "band", json_object_new_int(band));
    json_object_object_add(o, "size", json_pair(json_object_new_int64((int64_t)g->nx),
                                                json_object_new_int64((int64_t)g->ny)));
    add_size(o, "cells", cells);
    add_size(o, "valid", valid);
    add_size(o, "nodata", cells - valid);
    json_object_object_add(o, "nodata_value", g->has_nodata ? cli_json_double(g->nodata_value) : NULL);
    if (valid > 0) {
        json_object_object_add(o, "z_range", json_pair(cli_json_double(s->zmin), cli_json_double(s->zmax)));
    } else {
        char msg[96];
        snprintf(msg, sizeof msg, "the grid has no valid cell: all %zu cells are nodata", cells);
        json_object_object_add(o, "z_range", NULL);
        add_warning(o, msg);
    }
    ft_grid_extent(g, &x0, &y0, &x1, &y1);
    json_object_object_add(o, "extent", json_extent(x0, y0, x1, y1));
    json_object_object_add(o, "cell_size",
                           json_pair(cli_json_double(fabs(g->gt[1])), cli_json_double(fabs(g->gt[5]))));
    json_object_object_add(o, "crs", json_crs(g->crs_wkt));
    json_object *ground = ground_cell(g, 0.5 * (y0 + y1));
    if (ground)
        json_object_object_add(o, "ground_cell_size", ground);
    return FT_OK;
}

static const char *field_type_name(ft_field_type t)
{
    return t == FT_FIELD_INT ? "integer" : t == FT_FIELD_REAL ? "real" : "string";
}

static json_object *json_fields(const ft_layer *l)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < l->nfields; i++) {
        json_object *f = json_object_new_object();
        json_object_object_add(f, "name", json_object_new_string(l->fields[i].name ? l->fields[i].name : ""));
        json_object_object_add(f, "type", json_object_new_string(field_type_name(l->fields[i].type)));
        json_object_array_add(a, f);
    }
    return a;
}

static int describe_chains(const ft_layer *l, json_object *o)
{
    int rc = ft_layer_check_finite(l);
    if (rc != FT_OK)
        return rc;
    size_t rings = 0, holes = 0, lines = 0, shorts = 0;
    for (size_t i = 0; i < l->nparts; i++) {
        const ft_part *p = &l->parts[i];
        rings += p->role != FT_ROLE_LINE;
        holes += p->role == FT_ROLE_INNER;
        lines += p->role == FT_ROLE_LINE;
        shorts += p->chain == NULL || p->chain->n < 2;
    }
    size_t vertices = ft_layer_vertex_count(l);
    double x0, y0, x1, y1;
    json_object_object_add(o, "layer", l->name ? json_object_new_string(l->name) : NULL);
    add_size(o, "features", l->nfeatures);
    add_size(o, "parts", l->nparts);
    add_size(o, "rings", rings);
    add_size(o, "holes", holes);
    add_size(o, "lines", lines);
    add_size(o, "vertices", vertices);
    add_size(o, "file_vertices", vertices + rings);
    add_size(o, "short_chains", shorts);
    if (ft_layer_bbox(l, &x0, &y0, &x1, &y1) == FT_OK)
        json_object_object_add(o, "extent", json_extent(x0, y0, x1, y1));
    else
        json_object_object_add(o, "extent", NULL);
    json_object_object_add(o, "crs", json_crs(l->crs_wkt));
    json_object_object_add(o, "fields", json_fields(l));
    if (shorts > 0) {
        char msg[96];
        snprintf(msg, sizeof msg, "%zu %s fewer than 2 vertices", shorts, shorts == 1 ? "chain has" : "chains have");
        add_warning(o, msg);
    }
    return FT_OK;
}

static int describe_points(const ft_points *p, json_object *o)
{
    double x0, y0, x1, y1, zmin = INFINITY, zmax = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        if (isfinite(p->z[i])) {
            zmin = p->z[i] < zmin ? p->z[i] : zmin;
            zmax = p->z[i] > zmax ? p->z[i] : zmax;
        }
    }
    add_size(o, "points", p->n);
    if (ft_points_bbox(p, &x0, &y0, &x1, &y1) == FT_OK)
        json_object_object_add(o, "extent", json_extent(x0, y0, x1, y1));
    else
        json_object_object_add(o, "extent", NULL);
    json_object_object_add(o, "z_range", zmin <= zmax ? json_pair(cli_json_double(zmin), cli_json_double(zmax))
                                                      : NULL);
    json_object_object_add(o, "weights", json_object_new_boolean(p->w != NULL));
    json_object_object_add(o, "crs", json_crs(p->crs_wkt));
    return FT_OK;
}

int cli_info_describe(const char *path, const char *layer, int band, json_object **out)
{
    *out = NULL;
    if (layer && (ft_io_is_text_chains(path) || ft_io_is_text_points(path)))
        return ft_error(FT_E_INVALID, "--layer applies to vector files, but %s is a text file", path);
    /* One open and one parse of the file: the kind and the content come from the same read. */
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
    ft_data data;
    ft_grid_summary grid; /* a grid's statistics come strip by strip: the grid is never held */
    lo.layer = layer;
    if (band > 0)
        go.band = band;
    int rc = ft_io_read_any_summary(path, &lo, &go, NULL, &data, &grid);
    if (rc != FT_OK)
        return rc;
    ft_file_kind kind = data.kind;
    if (kind != FT_KIND_GRID && band > 0) {
        ft_data_clear(&data);
        ft_grid_summary_clear(&grid);
        return ft_error(FT_E_INVALID, "--band applies to grids, but %s holds %s", path, kind_name(kind));
    }

    json_object *o = json_object_new_object();
    const char *driver = driver_name(path);
    json_object_object_add(o, "file", json_object_new_string(path));
    json_object_object_add(o, "kind", json_object_new_string(kind_name(kind)));
    json_object_object_add(o, "driver", driver ? json_object_new_string(driver) : NULL);
    if (kind == FT_KIND_GRID)
        rc = describe_grid(&grid, go.band, o);
    else if (kind == FT_KIND_CHAINS)
        rc = describe_chains(data.layer, o);
    else
        rc = describe_points(data.points, o);
    ft_data_clear(&data);
    ft_grid_summary_clear(&grid);
    if (rc != FT_OK) {
        json_object_put(o);
        return rc;
    }
    warnings_last(o);
    *out = o;
    return FT_OK;
}

/* ---- human-readable table, made from the JSON object so that both outputs always agree ---- */

static json_object *get(json_object *o, const char *key)
{
    json_object *v = NULL;
    return json_object_object_get_ex(o, key, &v) ? v : NULL;
}

static double num_at(json_object *a, size_t i)
{
    return json_object_get_double(json_object_array_get_idx(a, i));
}

static void row(const char *key, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void row(const char *key, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    printf("%-11s", key);
    vprintf(fmt, ap);
    putchar('\n');
    va_end(ap);
}

static void print_extent(json_object *o)
{
    json_object *e = get(o, "extent");
    if (e)
        row("extent", "%.10g %.10g %.10g %.10g (xmin ymin xmax ymax)", num_at(e, 0), num_at(e, 1), num_at(e, 2),
            num_at(e, 3));
    else
        row("extent", "none");
}

static void print_z_range(json_object *o)
{
    json_object *z = get(o, "z_range");
    if (z)
        row("z range", "%.10g .. %.10g", num_at(z, 0), num_at(z, 1));
    else
        row("z range", "none (no valid value)");
}

static void print_crs(json_object *o)
{
    json_object *c = get(o, "crs"), *epsg = c ? get(c, "epsg") : NULL;
    if (c == NULL)
        row("crs", "none");
    else if (epsg)
        row("crs", "%s (EPSG:%d)", json_object_get_string(get(c, "name")), json_object_get_int(epsg));
    else
        row("crs", "%s", json_object_get_string(get(c, "name")));
    json_object *geo = NULL;
    if (c && json_object_object_get_ex(c, "geographic", &geo) && json_object_get_boolean(geo))
        row("", "longitude/latitude on %s: measured in metres (docs/geographic.md)",
            json_object_get_string(get(c, "ellipsoid")));
}

static long long int_of(json_object *o, const char *key)
{
    return (long long)json_object_get_int64(get(o, key));
}

static void print_grid(json_object *o)
{
    json_object *size = get(o, "size"), *cs = get(o, "cell_size"), *nv = get(o, "nodata_value");
    row("band", "%lld", int_of(o, "band"));
    row("size", "%lld x %lld = %lld cells", (long long)json_object_get_int64(json_object_array_get_idx(size, 0)),
        (long long)json_object_get_int64(json_object_array_get_idx(size, 1)), int_of(o, "cells"));
    row("valid", "%lld", int_of(o, "valid"));
    if (nv)
        row("nodata", "%lld (value %.10g)", int_of(o, "nodata"), json_object_get_double(nv));
    else
        row("nodata", "%lld", int_of(o, "nodata"));
    print_z_range(o);
    print_extent(o);
    row("cell size", "%.10g x %.10g", num_at(cs, 0), num_at(cs, 1));
    json_object *ground = NULL;
    if (json_object_object_get_ex(o, "ground_cell_size", &ground))
        row("ground", "cells of %.1f m x %.1f m at the centre", num_at(ground, 0), num_at(ground, 1));
    print_crs(o);
}

static void print_fields(json_object *o)
{
    json_object *f = get(o, "fields");
    size_t n = f ? json_object_array_length(f) : 0;
    if (n == 0) {
        row("fields", "none");
        return;
    }
    printf("%-11s", "fields");
    for (size_t i = 0; i < n; i++) {
        json_object *fi = json_object_array_get_idx(f, i);
        printf("%s%s (%s)", i ? ", " : "", json_object_get_string(get(fi, "name")),
               json_object_get_string(get(fi, "type")));
    }
    putchar('\n');
}

static void print_chains(json_object *o)
{
    json_object *layer = get(o, "layer");
    if (layer)
        row("layer", "%s", json_object_get_string(layer));
    row("features", "%lld", int_of(o, "features"));
    row("parts", "%lld (rings %lld, of which holes %lld; lines %lld)", int_of(o, "parts"), int_of(o, "rings"),
        int_of(o, "holes"), int_of(o, "lines"));
    if (int_of(o, "rings") > 0)
        row("vertices", "%lld (%lld in the file, counting each ring's closing vertex again)", int_of(o, "vertices"),
            int_of(o, "file_vertices"));
    else
        row("vertices", "%lld", int_of(o, "vertices"));
    print_extent(o);
    print_crs(o);
    print_fields(o);
}

static void print_points(json_object *o)
{
    row("points", "%lld", int_of(o, "points"));
    print_extent(o);
    print_z_range(o);
    row("weights", "%s", json_object_get_boolean(get(o, "weights")) ? "yes" : "no");
    print_crs(o);
}

static void print_human(json_object *o)
{
    json_object *driver = get(o, "driver");
    const char *kind = json_object_get_string(get(o, "kind"));
    row("file", "%s", json_object_get_string(get(o, "file")));
    row("kind", "%s", kind);
    row("driver", "%s", driver ? json_object_get_string(driver) : "unknown");
    if (strcmp(kind, "grid") == 0)
        print_grid(o);
    else if (strcmp(kind, "chains") == 0)
        print_chains(o);
    else
        print_points(o);
}

/* ---- the command ---- */

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    info_args *a = ctx;
    switch (opt) {
    case 'l': a->layer = arg; return CLI_CONTINUE;
    case 'b': return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->band);
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int run_info(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"layer", required_argument, NULL, 'l'}, {"band", required_argument, NULL, 'b'},
        {"json", no_argument, NULL, 'j'}, CLI_OPT_HELP, CLI_OPT_END,
    };
    static const char *const names[] = {"FILE"};
    info_args a = {NULL, 0, 0};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "l:b:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc != CLI_CONTINUE)
        return rc;

    json_object *o = NULL;
    rc = cli_info_describe(argv[first], a.layer, a.band, &o);
    if (rc == FT_E_INVALID)
        return cli_usage_error(cmd, "%s", ft_last_error());
    if (rc != FT_OK)
        return cli_fail(cmd);
    json_object *w = get(o, "warnings");
    for (size_t i = 0; w && i < json_object_array_length(w); i++)
        cli_warn(cmd, "%s: %s", argv[first], json_object_get_string(json_object_array_get_idx(w, i)));
    if (a.json)
        return cli_print_json(cmd, o);
    print_human(o);
    json_object_put(o);
    return CLI_OK;
}

const cli_command cli_cmd_info = {
    "info",
    "what fracterra sees in a grid, chain or point file",
    "fracterra info FILE [--layer NAME] [--band N] [--json]",
    "Reads FILE the way every fracterra command does and reports what it holds:\n"
    "  grids:  size, cell count, valid and nodata cells, z range, extent, cell size, CRS;\n"
    "  chains: features, parts (rings, holes, lines), vertices, extent, CRS, fields;\n"
    "  points: count, extent, z range, CRS.\n"
    "Rings are stored without their repeated closing vertex: \"vertices\" counts them that way,\n"
    "\"file_vertices\" as the file (and ogrinfo) does, with each closing vertex counted again.\n"
    "An all-nodata grid or chains of fewer than 2 vertices give a warning on stderr, not an error.\n\n"
    "Options:\n"
    "  -l, --layer NAME  vector layer to read (default: the first)\n"
    "  -b, --band N      raster band to read (default: 1)\n"
    "  -j, --json        print one JSON object on stdout instead of a table\n"
    "  -h, --help        print this help\n\n"
    "JSON keys: file, kind (grid|chains|points), driver, crs {name, epsg, geographic, unit, ellipsoid},\n"
    "  extent [xmin,ymin,xmax,ymax];\n"
    "  grids: band, size [nx,ny], cells, valid, nodata, nodata_value, z_range [min,max], cell_size [dx,dy],\n"
    "  ground_cell_size [dx,dy] in metres at the centre for a lon/lat grid;\n"
    "  chains: layer, features, parts, rings, holes, lines, vertices, file_vertices, short_chains, fields;\n"
    "  points: points, z_range, weights; and \"warnings\" [...] when there are any.\n\n"
    "Examples:\n"
    "  fracterra info dem.tif\n"
    "  fracterra info --json coast.geojson | jq .vertices\n",
    run_info,
};
