/* fracterra — cli/cmd_mountain.c: `fracterra mountain SEED OUT`: every contour of a mountain grown from one
 * seed contour (Misawa, Chiba & Saito: polygon shrinking, random midpoint displacement, Fourier descriptor
 * phase randomization, the improved method; ft_mountain_generate), written as a contour layer
 * (ft_contour_stack_to_layer, field `elev`), optionally with its DEM (ft_contour_stack_to_dem, as GRASS
 * r.surf.contour) and a bird's-eye view of it (ft_render_perspective). docs/contour-mountain.md.
 *
 * Every output is first written under a temporary name beside its destination; they are renamed together
 * once all are complete, so a failure leaves none of them behind.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define SEED_ELEV_FIELD "elev"

enum {
    OPT_INTERVAL = 0x300,
    OPT_SPACING,
    OPT_SEED_ELEV,
    OPT_UP,
    OPT_DOWN,
    OPT_METHOD,
    OPT_JOIN,
    OPT_DPRIME,
    OPT_DSECOND,
    OPT_THETA,
    OPT_F0,
    OPT_N,
    OPT_SEED,
    OPT_LINES,
    OPT_DEM,
    OPT_CELL,
    OPT_SUMMIT,
    OPT_VIEW,
    OPT_MAP,
    OPT_ALLOW_CROSSINGS,
};

typedef struct {
    ft_mountain_opts mo;
    ft_contour_dem_opts dem;
    const char *layer, *where, *driver;
    const char *dem_path, *view_path, *map_path;
    int lines, json;
    int have_seed_elev, have_cell, have_theta, have_f0, have_n;
} mountain_args;

/* "MIN,MAX" in degrees, 0 <= MIN <= MAX < 90. */
static int parse_theta(const cli_command *cmd, const char *arg, double *lo, double *hi)
{
    char *end = NULL;
    errno = 0;
    *lo = strtod(arg, &end);
    int ok = end != arg && *end == ',';
    if (ok) {
        const char *s = end + 1;
        *hi = strtod(s, &end);
        ok = end != s && *end == '\0';
    }
    if (!ok || !(*lo >= 0.0 && *lo <= *hi && *hi < 90.0))
        return cli_usage_error(cmd, "--theta must be MIN,MAX in degrees with 0 <= MIN <= MAX < 90, got '%s'", arg);
    return CLI_CONTINUE;
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    mountain_args *a = ctx;
    ft_mountain_opts *m = &a->mo;
    switch (opt) {
    case OPT_INTERVAL: return cli_parse_double(cmd, "--interval", arg, 0.0, INFINITY, CLI_OPEN_LO, &m->interval);
    case OPT_SPACING: return cli_parse_double(cmd, "--spacing", arg, 0.0, INFINITY, CLI_OPEN_LO, &m->spacing);
    case OPT_SEED_ELEV:
        a->have_seed_elev = 1;
        return cli_parse_double(cmd, "--seed-elevation", arg, -INFINITY, INFINITY, CLI_OPEN_LO | CLI_OPEN_HI,
                                &m->seed_elevation);
    case OPT_UP: return cli_parse_int(cmd, "--levels-up", arg, 0, 10000, &m->levels_up);
    case OPT_DOWN: return cli_parse_int(cmd, "--levels-down", arg, 0, 10000, &m->levels_down);
    case OPT_METHOD:
        return ft_mountain_method_parse(arg, &m->method) == FT_OK
                   ? CLI_CONTINUE
                   : cli_usage_error(cmd, "--method must be simple, midpoint, fourier or improved, got '%s'", arg);
    case OPT_JOIN:
        return ft_contour_join_parse(arg, &m->shrink.join) == FT_OK
                   ? CLI_CONTINUE
                   : cli_usage_error(cmd, "--join must be dprime, mitre, bevel or round, got '%s'", arg);
    case OPT_DPRIME: return cli_parse_double(cmd, "--dprime", arg, 1.0, INFINITY, CLI_CLOSED, &m->shrink.dprime);
    case OPT_DSECOND: return cli_parse_double(cmd, "--dsecond", arg, 0.0, INFINITY, CLI_CLOSED, &m->dsecond);
    case OPT_THETA: /* an explicit range is used as is: no matching of the seed's dimension */
        a->have_theta = 1;
        m->match_dim = 0;
        return parse_theta(cmd, arg, &m->theta_min, &m->theta_max);
    case OPT_F0: a->have_f0 = 1; return cli_parse_int(cmd, "--f0", arg, 1, 1 << 20, &m->fourier.f0);
    case OPT_N: a->have_n = 1; return cli_parse_int(cmd, "--n", arg, 8, 1 << 21, &m->fourier.n);
    case OPT_SEED: return terrain_parse_seed(cmd, arg, &m->seed);
    case OPT_LINES: a->lines = 1; return CLI_CONTINUE;
    case OPT_DEM: a->dem_path = arg; return CLI_CONTINUE;
    case OPT_CELL:
        a->have_cell = 1;
        return cli_parse_double(cmd, "--cell", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->dem.cell);
    case OPT_SUMMIT: return cli_parse_double(cmd, "--summit", arg, 0.0, INFINITY, CLI_CLOSED, &a->dem.summit);
    case OPT_VIEW: a->view_path = arg; return CLI_CONTINUE;
    case OPT_MAP: a->map_path = arg; return CLI_CONTINUE;
    case OPT_ALLOW_CROSSINGS: m->allow_crossings = 1; return CLI_CONTINUE;
    case 'l': a->layer = arg; return CLI_CONTINUE;
    case 'w': a->where = arg; return CLI_CONTINUE;
    case 'f': a->driver = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* 1 if path ends in one of the extensions of list ("svg png pdf"), case-insensitively. */
static int has_ext(const char *path, const char *list)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (dot == NULL || (slash != NULL && dot < slash) || dot[1] == '\0')
        return 0;
    size_t n = strlen(dot + 1);
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, " ");
        if (len == n && strncasecmp(p, dot + 1, n) == 0)
            return 1;
        p += len + (p[len] == ' ');
    }
    return 0;
}

/* The options together: CLI_CONTINUE or CLI_USAGE. */
static int check_args(const cli_command *cmd, const mountain_args *a, const char *out)
{
    const ft_mountain_opts *m = &a->mo;
    if (a->have_cell && a->dem_path == NULL && a->view_path == NULL)
        return cli_usage_error(cmd, "--cell sets the DEM's cell size: give --dem OUT.tif or --view OUT.png with it");
    if (m->fourier.f0 > m->fourier.n / 2)
        return cli_usage_error(cmd, "--f0 must be at most --n / 2 = %d, got %d", m->fourier.n / 2, m->fourier.f0);
    if ((a->have_f0 || a->have_n) && (m->method == FT_MOUNTAIN_SIMPLE || m->method == FT_MOUNTAIN_MIDPOINT))
        return cli_usage_error(cmd, "--f0 and --n set the Fourier descriptor step: they need --method fourier or "
                                    "improved, not %s",
                               ft_mountain_method_name(m->method));
    if (a->have_theta && (m->method == FT_MOUNTAIN_SIMPLE || m->method == FT_MOUNTAIN_FOURIER))
        return cli_usage_error(cmd, "--theta sets the midpoint displacement: it needs --method midpoint or improved, "
                                    "not %s",
                               ft_mountain_method_name(m->method));
    if (strcmp(out, "-") == 0)
        return cli_usage_error(cmd, "OUT must be a file: the contour layer is not written to stdout");
    if (a->view_path && !has_ext(a->view_path, "png"))
        return cli_usage_error(cmd, "--view writes a PNG: its name must end in .png, got '%s'", a->view_path);
    if (a->map_path && !has_ext(a->map_path, "svg png pdf"))
        return cli_usage_error(cmd, "--map must end in .svg, .png or .pdf, got '%s'", a->map_path);
    /* The outputs are staged under temporary names whose driver is found from the real name's extension. */
    const char *dot = strrchr(out, '.');
    if (a->driver == NULL && (dot == NULL || strchr(dot, '/') != NULL || dot[1] == '\0'))
        return cli_usage_error(cmd, "OUT '%s' has no extension: end it in .geojson, .gpkg, .shp or .gmt, or name "
                               "a driver with -f", out);
    dot = a->dem_path ? strrchr(a->dem_path, '.') : NULL;
    if (a->dem_path && (dot == NULL || strchr(dot, '/') != NULL || dot[1] == '\0'))
        return cli_usage_error(cmd, "--dem '%s' has no extension: end it in .tif (or another raster format's)",
                               a->dem_path);
    const char *paths[4] = {out, a->dem_path, a->view_path, a->map_path};
    static const char *const names[4] = {"OUT", "--dem", "--view", "--map"};
    for (int i = 0; i < 4; i++)
        for (int j = i + 1; j < 4; j++)
            if (paths[i] && paths[j] && strcmp(paths[i], paths[j]) == 0)
                return cli_usage_error(cmd, "%s and %s name the same file '%s'", names[i], names[j], paths[i]);
    return CLI_CONTINUE;
}

/* ---- the seed ---------------------------------------------------------------------------------- */

/* Without --seed-elevation: the seed layer's `elev` field when every feature holds the same number. */
static void seed_elevation_from_layer(const ft_layer *l, mountain_args *a)
{
    int k = ft_layer_field_index(l, SEED_ELEV_FIELD);
    if (a->have_seed_elev || k < 0 || l->fields[k].type == FT_FIELD_STRING || l->nfeatures == 0)
        return;
    double v = NAN;
    for (size_t f = 0; f < l->nfeatures; f++) {
        const ft_value *x = &l->features[f].values[k];
        double e = x->is_null ? NAN : (l->fields[k].type == FT_FIELD_INT ? (double)x->i : x->r);
        if (!isfinite(e) || (f > 0 && e != v))
            return;
        v = e;
    }
    a->mo.seed_elevation = v;
    a->have_seed_elev = 2; /* from the layer */
}

static int read_seed(const cli_command *cmd, const char *path, mountain_args *a, ft_layer **layer,
                     ft_polygon_set **seed)
{
    int rc = cli_read_layer(cmd, path, a->layer, a->where, layer);
    if (rc != CLI_CONTINUE)
        return rc;
    if (ft_polygon_set_from_layer(*layer, seed) != FT_OK) {
        cli_error(cmd, "%s: %s", path, ft_last_error());
        return CLI_FAIL;
    }
    seed_elevation_from_layer(*layer, a);
    ft_crs_info crs;
    if (ft_io_crs_info((*layer)->crs_wkt, &crs) != FT_OK)
        return cli_fail(cmd);
    if (crs.geographic) {
        cli_error(cmd, "%s is in a geographic CRS (%s): the spacing, the shrinking and the DEM's cells are lengths on "
                       "the ground, which degrees are not; reproject the seed to a projected CRS first (e.g. "
                       "ogr2ogr -t_srs EPSG:32632 seed_utm.gpkg %s)",
                  path, crs.name, path);
        return CLI_FAIL;
    }
    return CLI_CONTINUE;
}

/* ---- outputs, staged under temporary names ----------------------------------------------------- */

typedef struct {
    const char *path[4];
    char *tmp[4];
    size_t n;
} staged;

static const char *stage(staged *s, const char *path)
{
    char *tmp = ft_io_atomic_tmp(path);
    if (tmp == NULL)
        return NULL;
    s->path[s->n] = path;
    s->tmp[s->n++] = tmp;
    return tmp;
}

static int commit_all(staged *s)
{
    int rc = FT_OK;
    for (size_t i = 0; i < s->n && rc == FT_OK; i++) {
        rc = ft_io_atomic_commit(s->tmp[i], s->path[i]);
        if (rc == FT_OK) {
            free(s->tmp[i]);
            s->tmp[i] = NULL;
        }
    }
    return rc;
}

static void discard_all(staged *s)
{
    for (size_t i = 0; i < s->n; i++) {
        if (s->tmp[i] != NULL)
            ft_io_atomic_discard(s->tmp[i]);
        free(s->tmp[i]);
    }
    s->n = 0;
}

/* The layer name of OUT: its file name without the extension (as every other writer names it). */
static char *layer_name(const char *out)
{
    const char *base = strrchr(out, '/');
    base = base ? base + 1 : out;
    const char *dot = strrchr(base, '.');
    size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    char *s = malloc(n + 1);
    if (s != NULL) {
        memcpy(s, base, n);
        s[n] = '\0';
    }
    return s;
}

typedef struct {
    const ft_layer *seed_layer;
    ft_contour_stack *stack;
    ft_layer *contours;
    ft_grid *dem;
} mountain_result;

/* The contour map: the contours in brown, the seed contour(s) over them in red, a title naming the method. */
static int draw_map(const mountain_args *a, const mountain_result *r, const char *path)
{
    char title[160];
    const ft_mountain_opts *m = &a->mo;
    snprintf(title, sizeof title, "%s method, %s join, interval %g, spacing %.4g, seed %llu",
             ft_mountain_method_name(m->method), ft_contour_join_name(m->shrink.join), r->stack->interval,
             r->stack->spacing, (unsigned long long)m->seed);
    ft_map_layer layers[2] = {
        {r->contours, "#8a5a2b", NULL, 0.8, 0.0, "contours"},
        {r->seed_layer, "#c0392b", NULL, 1.6, 0.0, "seed contour"},
    };
    ft_map_opts mo = FT_MAP_OPTS_DEFAULT;
    mo.width = 640;
    mo.height = 640;
    mo.title = title;
    return ft_render_map_layers(layers, 2, path, &mo);
}

/* Writes every output under its temporary name, then renames them all; on failure *failed names the output
 * at fault (its final name) and nothing is left behind. */
static int write_outputs(const mountain_args *a, const char *out, const mountain_result *r, const char **failed)
{
    staged s = {{NULL}, {NULL}, 0};
    char *name = layer_name(out);
    const char *tmp = name ? stage(&s, out) : NULL;
    ft_write_layer_opts wo = FT_WRITE_LAYER_OPTS_DEFAULT;
    wo.driver = a->driver;
    wo.layer = name;
    int rc = tmp ? ft_io_write_layer(tmp, r->contours, &wo) : (name ? ft_last_error_code() : FT_E_NOMEM);
    *failed = out;
    if (rc == FT_OK && a->dem_path != NULL) {
        *failed = a->dem_path;
        ft_write_grid_opts go = FT_WRITE_GRID_OPTS_DEFAULT;
        tmp = stage(&s, a->dem_path);
        rc = tmp ? ft_io_write_grid(tmp, r->dem, &go) : ft_last_error_code();
    }
    if (rc == FT_OK && a->view_path != NULL) {
        *failed = a->view_path;
        ft_perspective_opts po = FT_PERSPECTIVE_OPTS_DEFAULT;
        tmp = stage(&s, a->view_path);
        rc = tmp ? ft_render_perspective(r->dem, tmp, &po) : ft_last_error_code();
    }
    if (rc == FT_OK && a->map_path != NULL) {
        *failed = a->map_path;
        tmp = stage(&s, a->map_path);
        rc = tmp ? draw_map(a, r, tmp) : ft_last_error_code();
    }
    if (rc == FT_OK) {
        *failed = NULL;
        rc = commit_all(&s);
    }
    discard_all(&s);
    free(name);
    return rc;
}

/* ---- report ------------------------------------------------------------------------------------ */

static json_object *level_array(const ft_contour_stack *st, int what)
{
    json_object *a = json_object_new_array();
    for (size_t k = 0; k < st->n; k++) {
        const ft_contour_level *lv = &st->levels[k];
        switch (what) {
        case 0: json_object_array_add(a, cli_json_double(lv->elev)); break;
        case 1: json_object_array_add(a, json_object_new_uint64(ft_polygon_set_vertices(lv->polys))); break;
        case 2: json_object_array_add(a, json_object_new_uint64(lv->polys ? lv->polys->n : 0)); break;
        default: json_object_array_add(a, cli_json_double(ft_polygon_set_area(lv->polys))); break;
        }
    }
    return a;
}

static size_t stack_vertices(const ft_contour_stack *st)
{
    size_t v = 0;
    for (size_t k = 0; k < st->n; k++)
        v += ft_polygon_set_vertices(st->levels[k].polys);
    return v;
}

static json_object *dem_figures(const mountain_args *a, const ft_grid *g)
{
    if (g == NULL)
        return NULL;
    json_object *o = json_object_new_object();
    json_object_object_add(o, "output", a->dem_path ? json_object_new_string(a->dem_path) : NULL);
    json_object_object_add(o, "cell", cli_json_double(g->gt[1]));
    json_object_object_add(o, "summit", cli_json_double(a->dem.summit));
    json_object *fig = terrain_grid_figures(g);
    json_object_object_foreach(fig, key, val) json_object_object_add(o, key, json_object_get(val));
    json_object_put(fig);
    return o;
}

static int report(const cli_command *cmd, const mountain_args *a, const char *in, const char *out,
                  const ft_layer *seed_layer, const ft_polygon_set *seed, const mountain_result *r)
{
    const ft_mountain_opts *m = &a->mo;
    const ft_contour_stack *st = r->stack;
    if (!a->json) {
        printf("wrote %s: %zu contour level(s) from %g to %g (interval %g, spacing %g, %s method, seed %llu), "
               "%zu vertices\n",
               out, st->n, st->n ? st->levels[0].elev : NAN, st->n ? st->levels[st->n - 1].elev : NAN, st->interval,
               st->spacing, ft_mountain_method_name(m->method), (unsigned long long)m->seed, stack_vertices(st));
        if (!m->allow_crossings && m->method != FT_MOUNTAIN_SIMPLE)
            printf("crossing guard: %zu moves, %zu halved or quartered, %zu dropped\n", st->guard_moves,
                   st->guard_reduced, st->guard_dropped);
        if (a->dem_path)
            printf("wrote %s: %zu x %zu cells of %g\n", a->dem_path, r->dem->nx, r->dem->ny, r->dem->gt[1]);
        if (a->view_path)
            printf("wrote %s: bird's-eye view\n", a->view_path);
        if (a->map_path)
            printf("wrote %s: contour map\n", a->map_path);
        return CLI_OK;
    }
    json_object *o = json_object_new_object();
    json_object_object_add(o, "input", json_object_new_string(in));
    json_object_object_add(o, "layer", seed_layer->name ? json_object_new_string(seed_layer->name) : NULL);
    json_object_object_add(o, "output", json_object_new_string(out));
    json_object_object_add(o, "as_lines", json_object_new_boolean(a->lines));
    json_object_object_add(o, "method", json_object_new_string(ft_mountain_method_name(m->method)));
    json_object_object_add(o, "join", json_object_new_string(ft_contour_join_name(m->shrink.join)));
    json_object_object_add(o, "interval", cli_json_double(st->interval));
    json_object_object_add(o, "spacing", cli_json_double(st->spacing));
    json_object_object_add(o, "seed_elevation", cli_json_double(m->seed_elevation));
    json_object_object_add(o, "seed_elevation_from",
                           json_object_new_string(a->have_seed_elev == 2 ? "field elev"
                                                                         : (a->have_seed_elev ? "option" : "default")));
    json_object_object_add(o, "dprime", cli_json_double(st->dprime));
    if (m->method == FT_MOUNTAIN_MIDPOINT || m->method == FT_MOUNTAIN_IMPROVED) {
        json_object_object_add(o, "dsecond", cli_json_double(m->dsecond));
        json_object *th = json_object_new_array();
        json_object_array_add(th, cli_json_double(m->theta_min));
        json_object_array_add(th, cli_json_double(m->theta_max));
        json_object_object_add(o, "theta", th);
        json_object_object_add(o, "match_dim",
                               json_object_new_boolean(m->method == FT_MOUNTAIN_IMPROVED && m->match_dim));
    }
    if (m->method == FT_MOUNTAIN_FOURIER || m->method == FT_MOUNTAIN_IMPROVED) {
        json_object_object_add(o, "f0", json_object_new_int(m->fourier.f0));
        json_object_object_add(o, "n", json_object_new_int(m->fourier.n));
    }
    json_object_object_add(o, "seed", json_object_new_uint64(m->seed));
    json_object_object_add(o, "allow_crossings", json_object_new_boolean(m->allow_crossings));
    json_object *guard = NULL;
    if (!m->allow_crossings && m->method != FT_MOUNTAIN_SIMPLE) { /* simple moves no vertex */
        guard = json_object_new_object();
        json_object_object_add(guard, "moves", json_object_new_uint64(st->guard_moves));
        json_object_object_add(guard, "reduced", json_object_new_uint64(st->guard_reduced));
        json_object_object_add(guard, "dropped", json_object_new_uint64(st->guard_dropped));
    }
    json_object_object_add(o, "crossing_guard", guard);
    json_object_object_add(o, "levels", json_object_new_uint64(st->n));
    json_object_object_add(o, "elevations", level_array(st, 0));
    json_object_object_add(o, "vertices", level_array(st, 1));
    json_object_object_add(o, "polygons", level_array(st, 2));
    json_object_object_add(o, "areas", level_array(st, 3));
    json_object_object_add(o, "vertices_in", json_object_new_uint64(ft_polygon_set_vertices(seed)));
    json_object_object_add(o, "vertices_out", json_object_new_uint64(stack_vertices(st)));
    json_object_object_add(o, "features", json_object_new_uint64(r->contours->nfeatures));
    json_object_object_add(o, "dem", dem_figures(a, r->dem));
    json_object_object_add(o, "view", a->view_path ? json_object_new_string(a->view_path) : NULL);
    json_object_object_add(o, "map", a->map_path ? json_object_new_string(a->map_path) : NULL);
    json_object *outs = json_object_new_array();
    json_object_array_add(outs, json_object_new_string(out));
    if (a->dem_path)
        json_object_array_add(outs, json_object_new_string(a->dem_path));
    if (a->view_path)
        json_object_array_add(outs, json_object_new_string(a->view_path));
    if (a->map_path)
        json_object_array_add(outs, json_object_new_string(a->map_path));
    json_object_object_add(o, "outputs", outs);
    return cli_print_json(cmd, o);
}

/* ---- the command ------------------------------------------------------------------------------- */

/* Every output can be written (check_args has already checked their names and extensions). */
static int check_outputs(const cli_command *cmd, const mountain_args *a, const char *out)
{
    const char *paths[4] = {out, a->dem_path, a->view_path, a->map_path};
    for (int i = 0; i < 4; i++)
        if (paths[i] != NULL && ft_io_check_writable(paths[i]) != FT_OK)
            return cli_fail(cmd);
    return CLI_CONTINUE;
}

/* The sizes the options would reach on this seed, refused beyond the memory bound before any work: the
 * shrinking makes in all about 2·area/d² contour vertices (a disc of radius R: R/d
 * levels of 2πR/d vertices), and the DEM about bbox-area/cell² cells (float, mask and a double work copy). */
static int check_sizes(const cli_command *cmd, const mountain_args *a, const ft_polygon_set *seed)
{
    double area = ft_polygon_set_area(seed);
    char what[200];
    if (a->mo.spacing > 0.0 && area > 0.0) {
        double verts = 2.0 * area / (a->mo.spacing * a->mo.spacing);
        snprintf(what, sizeof what, "--spacing %g on a seed of %.4g square units (about %.3g contour vertices)",
                 a->mo.spacing, area, verts);
        if (ft_check_memory(verts * 48.0, what) != FT_OK)
            return cli_fail(cmd);
    }
    if (a->dem.cell > 0.0 && (a->dem_path || a->view_path) && area > 0.0) {
        double cells = 2.0 * area / (a->dem.cell * a->dem.cell);
        snprintf(what, sizeof what, "--cell %g over a seed of %.4g square units (about %.3g DEM cells)", a->dem.cell,
                 area, cells);
        if (ft_check_memory(cells * 13.0, what) != FT_OK)
            return cli_fail(cmd);
    }
    return CLI_CONTINUE;
}

static int grow(const cli_command *cmd, mountain_args *a, const char *in, const char *out)
{
    ft_layer *seed_layer = NULL;
    ft_polygon_set *seed = NULL;
    mountain_result r = {NULL, NULL, NULL, NULL};
    int status = check_outputs(cmd, a, out);
    if (status == CLI_CONTINUE)
        status = read_seed(cmd, in, a, &seed_layer, &seed);
    if (status == CLI_CONTINUE)
        status = check_sizes(cmd, a, seed);
    if (status == CLI_CONTINUE) {
        r.seed_layer = seed_layer;
        a->mo.progress = a->dem.progress = cli_progress();
        int rc = ft_mountain_generate(seed, &a->mo, &r.stack);
        if (rc == FT_OK)
            rc = ft_contour_stack_to_layer(r.stack, a->lines, seed_layer->crs_wkt, &r.contours);
        if (rc == FT_OK && (a->dem_path || a->view_path))
            rc = ft_contour_stack_to_dem(r.stack, &a->dem, seed_layer->crs_wkt, &r.dem);
        const char *failed = NULL;
        if (rc == FT_OK)
            rc = write_outputs(a, out, &r, &failed);
        if (rc == FT_OK)
            status = report(cmd, a, in, out, seed_layer, seed, &r);
        else if (failed != NULL)
            cli_error(cmd, "cannot write %s (nothing was written): %s", failed, ft_last_error());
        status = rc == FT_OK ? status : (failed != NULL ? CLI_FAIL : cli_fail(cmd));
    }
    ft_grid_free(r.dem);
    ft_layer_free(r.contours);
    ft_contour_stack_free(r.stack);
    ft_polygon_set_free(seed);
    ft_layer_free(seed_layer);
    return status;
}

static int run_mountain(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"interval", required_argument, NULL, OPT_INTERVAL},
        {"spacing", required_argument, NULL, OPT_SPACING},
        {"seed-elevation", required_argument, NULL, OPT_SEED_ELEV},
        {"levels-up", required_argument, NULL, OPT_UP},
        {"levels-down", required_argument, NULL, OPT_DOWN},
        {"method", required_argument, NULL, OPT_METHOD},
        {"join", required_argument, NULL, OPT_JOIN},
        {"dprime", required_argument, NULL, OPT_DPRIME},
        {"dsecond", required_argument, NULL, OPT_DSECOND},
        {"theta", required_argument, NULL, OPT_THETA},
        {"f0", required_argument, NULL, OPT_F0},
        {"n", required_argument, NULL, OPT_N},
        {"seed", required_argument, NULL, OPT_SEED},
        {"lines", no_argument, NULL, OPT_LINES},
        {"dem", required_argument, NULL, OPT_DEM},
        {"cell", required_argument, NULL, OPT_CELL},
        {"summit", required_argument, NULL, OPT_SUMMIT},
        {"view", required_argument, NULL, OPT_VIEW},
        {"map", required_argument, NULL, OPT_MAP},
        {"allow-crossings", no_argument, NULL, OPT_ALLOW_CROSSINGS},
        {"layer", required_argument, NULL, 'l'},
        {"where", required_argument, NULL, 'w'},
        {"format", required_argument, NULL, 'f'},
        {"json", no_argument, NULL, 'j'},
        CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"SEED", "OUT"};
    mountain_args a = {.mo = FT_MOUNTAIN_OPTS_DEFAULT, .dem = FT_CONTOUR_DEM_OPTS_DEFAULT};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "l:w:f:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = check_args(cmd, &a, argv[first + 1]);
    const char *outs[4][2] = {{"OUT", NULL}, {"--dem", a.dem_path}, {"--view", a.view_path}, {"--map", a.map_path}};
    for (int i = 0; i < 4 && rc == CLI_CONTINUE; i++)
        rc = cli_refuse_overwrite(cmd, outs[i][0], i == 0 ? argv[first + 1] : outs[i][1], argv[first], (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    return grow(cmd, &a, argv[first], argv[first + 1]);
}

const cli_command cli_cmd_mountain = {
    "mountain",
    "grow every contour of a mountain from one seed contour, with its DEM and a bird's-eye view",
    "fracterra mountain SEED OUT [--interval DZ] [--spacing D] [--seed-elevation Z] [--levels-up N]\n"
    "       [--levels-down N] [--method simple|midpoint|fourier|improved] [--join dprime|mitre|bevel|round]\n"
    "       [--dprime K] [--dsecond K] [--theta MIN,MAX] [--f0 F] [--n N] [--seed N] [--lines]\n"
    "       [--allow-crossings] [--dem OUT.tif] [--cell C] [--summit K] [--view OUT.png] [--map OUT.svg|png|pdf] [--layer NAME]\n"
    "       [--where SQL] [-f DRIVER] [--json]",
    "Grows every contour of a mountain from the seed contour(s) of SEED with the contour generation method of\n"
    "Misawa, Chiba & Saito: each contour is the one below it shrunk inward by the spacing d (offset edges,\n"
    "corners joined, loops and vanished islands removed), one interval higher; --levels-down contours grown\n"
    "outward form the mountain's foot (seeds that meet merge). The improved method (the default) injects\n"
    "randomness at every step: shrinking, randomized phases of the high-frequency P-type Fourier descriptors,\n"
    "removal of nearly collinear vertices, random midpoint displacement of long segments. Every vertex the\n"
    "midpoint displacement or the phase randomization moves goes all, half, a quarter of the way or not at\n"
    "all, as far as it crosses no contour of its level nor the contour below (the report counts the moves\n"
    "reduced and dropped); --allow-crossings makes every move in full, leaving the crossings to the loop\n"
    "removal and the clipping into the contour below. The same seed gives the same contours, byte for byte. Method, parameters and figures: docs/contour-mountain.md.\n\n"
    "SEED is any OGR layer of polygons, or of lines whose parts are closed rings (GMT text: a segment whose last\n"
    "vertex repeats its first). OUT is a contour layer, one polygon (outer ring and holes) per feature with the\n"
    "elevation in a real field `elev`, as `gdal_contour -p -amin elev` writes (with --lines one line per ring),\n"
    "in the seed's CRS. Every output is written under a temporary name and renamed when all are complete.\n\n"
    "Options:\n"
    "      --interval DZ      elevation step between contours, > 0 (default 10)\n"
    "      --spacing D        d: horizontal shrink per contour, ground units (default: sqrt(seed area) / 40)\n"
    "      --seed-elevation Z elevation of the seed contour (default: the seed layer's `elev` field when every\n"
    "                         feature has the same value, else 0)\n"
    "      --levels-up N      contours above the seed (default: until they vanish)\n"
    "      --levels-down N    contours grown below the seed (default 0)\n"
    "      --method NAME      simple: shrink only (\xc2\xa7" "3); midpoint: shrink, then random midpoint displacement\n"
    "                         (\xc2\xa7" "4.1); fourier: shrink, then phase randomization (\xc2\xa7" "4.2); improved (default):\n"
    "                         shrink, phase randomization, collinear removal, midpoint displacement (\xc2\xa7" "4.3)\n"
    "      --join NAME        corners: dprime (default: a point on the bisector at d' or the mitre point,\n"
    "                         whichever is nearer), mitre, bevel, round (the exact offset)\n"
    "      --dprime K         d' = K d, >= 1 (default 3 for improved, 1.4 for midpoint and fourier, 1.2 for\n"
    "                         simple: the paper's settings)\n"
    "      --dsecond K        midpoint, improved: d'' = K d, the largest midpoint displacement, >= 0\n"
    "                         (default 0.5)\n"
    "      --theta MIN,MAX    midpoint, improved: displacement angles, degrees, 0 <= MIN <= MAX < 90\n"
    "                         (default 20,40;\n"
    "                         improved scales the range per contour so that its divider D matches the\n"
    "                         seed's; an explicit --theta is used as is, the paper's fixed range)\n"
    "      --f0 F             fourier, improved: randomize the phases of the components |k| >= F,\n"
    "                         1 <= F <= N/2 (default 256)\n"
    "      --n N              fourier, improved: resample each contour to N segments for the descriptor,\n"
    "                         >= 8 (default 1024)\n"
    "      --seed N           random seed (default 1; printed in the JSON)\n"
    "      --allow-crossings  midpoint, fourier, improved: the raw algorithm, every move made in full even where\n"
    "                         contours then cross (repaired by loop removal and clipping only)\n"
    "      --lines            write each ring as a line feature instead of polygons\n"
    "      --dem OUT.tif      also write the DEM interpolated between the contours (as GRASS r.surf.contour)\n"
    "      --cell C           the DEM's cell size (default: the lowest contour's larger extent / 512)\n"
    "      --summit K         the summit rises K intervals above the top contour, >= 0 (default 0.5)\n"
    "      --view OUT.png     also render a bird's-eye view of the DEM (made in memory when --dem is absent)\n"
    "      --map OUT.svg      also draw the contour map (SVG, PNG or PDF by extension), the seed in red\n"
    "  -l, --layer NAME       the layer of SEED to read (default: the first)\n"
    "  -w, --where SQL        only the features of SEED matching this OGR attribute filter\n"
    "  -f, --format DRIVER    OGR driver of OUT (default: from its extension; .gmt/.xy/.txt: GMT text)\n"
    "  -j, --json             print {\"input\", \"output\", \"method\", \"join\", \"interval\", \"spacing\",\n"
    "                         \"seed_elevation\", \"dprime\", \"seed\", \"allow_crossings\",\n"
    "                         \"crossing_guard\": {\"moves\", \"reduced\", \"dropped\"} (null if unguarded), \"levels\", \"elevations\", \"vertices\",\n"
    "                         \"polygons\", \"areas\" (per level), \"vertices_in\", \"vertices_out\", \"dem\",\n"
    "                         \"view\", \"map\", \"outputs\", ...}\n"
    "  -h, --help             print this help\n\n"
    "Example:\n"
    "  fracterra mountain tests/data/seed_contour_volcano.geojson volcano_contours.gpkg --interval 5 \\\n"
    "      --levels-down 3 --seed 7 --dem volcano_mountain.tif --cell 2 --view volcano_mountain.png\n",
    run_mountain,
};
