/* fracterra — cli/line_edit.c: the driver shared by enhance, simplify, weed and smooth (line_edit.h):
 * read the layer, apply the steps through ft_line_apply_layer (coverage topology on polygon layers), count
 * self-intersections, write atomically through ft_io_write_layer, report as a table or JSON.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"
#include "cli_geo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* ---- options ---- */

int line_io_option(int opt, const char *arg, line_io *io)
{
    switch (opt) {
    case 'l': io->layer = arg; return CLI_CONTINUE;
    case 'w': io->where = arg; return CLI_CONTINUE;
    case 'f': io->driver = arg; return CLI_CONTINUE;
    case LINE_OPT_NO_COVERAGE: io->no_coverage = 1; return CLI_CONTINUE;
    case 'j': io->json = 1; return CLI_CONTINUE;
    default: return LINE_IO_NOT_SHARED;
    }
}

int line_edit_parse(const cli_command *cmd, int argc, char **argv, const struct option *longopts,
                    const char *shortopts, cli_opt_fn fn, void *ctx, int *first)
{
    static const char *const names[] = {"INPUT", "OUTPUT"};
    int rc = cli_parse_options(cmd, argc, argv, longopts, shortopts, fn, ctx, first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, *first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "OUTPUT", argv[*first + 1], argv[*first], (const char *)NULL);
    return rc;
}

/* ---- helpers ---- */

static int has_rings(const ft_layer *l)
{
    for (size_t i = 0; i < l->nparts; i++)
        if (l->parts[i].role != FT_ROLE_LINE)
            return 1;
    return 0;
}

/* Proper self-intersections summed over the layer's chains (each chain against itself). */
static int count_self_intersections(const ft_layer *l, size_t *total)
{
    *total = 0;
    for (size_t i = 0; i < l->nparts; i++) {
        size_t n = 0;
        if (l->parts[i].chain == NULL || l->parts[i].chain->n < 4)
            continue;
        int rc = ft_line_count_self_intersections(l->parts[i].chain, &n);
        if (rc != FT_OK)
            return rc;
        *total += n;
    }
    return FT_OK;
}

/* ---- the run ---- */

/* What an edit did, for the report. */
typedef struct {
    size_t vertices_in, vertices_out, intersections, before_repair;
    int coverage, repaired, guarded;
    ft_line_guard_stats guard;
    json_object *stages;
} edit_report;

int line_smooth_layer_step(ft_layer *l, void *ctx, int coverage, ft_line_guard_stats *stats)
{
    return ft_line_smooth_layer(l, ctx, coverage, stats);
}

static void add_stage(json_object *stages, const char *name, size_t vertices)
{
    json_object *s = json_object_new_object();
    json_object_object_add(s, "step", json_object_new_string(name));
    json_object_object_add(s, "vertices", json_object_new_int64((int64_t)vertices));
    json_object_array_add(stages, s);
}

/* Applies the steps to l in order, recording the vertices after each. */
static int apply_steps(ft_layer *l, const line_step *steps, size_t nsteps, edit_report *r)
{
    for (size_t i = 0; i < nsteps; i++) {
        if (steps[i].op == ft_line_op_remove_loops) {
            int rc = count_self_intersections(l, &r->before_repair);
            if (rc != FT_OK)
                return rc;
            r->repaired = 1;
        }
        int rc;
        if (steps[i].layer != NULL) {
            rc = steps[i].layer(l, steps[i].ctx, r->coverage, &r->guard);
            r->guarded = 1;
        } else {
            rc = ft_line_apply_layer(l, steps[i].op, steps[i].opts, r->coverage);
        }
        if (rc != FT_OK)
            return rc;
        add_stage(r->stages, steps[i].name, ft_layer_vertex_count(l));
    }
    r->vertices_out = ft_layer_vertex_count(l);
    return count_self_intersections(l, &r->intersections);
}

static void add_size(json_object *o, const char *key, size_t v)
{
    json_object_object_add(o, key, json_object_new_int64((int64_t)v));
}

static json_object *report_json(const char *input, const char *output, const ft_layer *l, const edit_report *r,
                                json_object *params)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "input", json_object_new_string(input));
    json_object_object_add(o, "output", json_object_new_string(output));
    json_object_object_add(o, "layer", l->name ? json_object_new_string(l->name) : NULL);
    add_size(o, "features", l->nfeatures);
    add_size(o, "parts", l->nparts);
    json_object_object_add(o, "coverage", json_object_new_boolean(r->coverage));
    json_object_object_foreach(params, key, val) json_object_object_add(o, key, json_object_get(val));
    json_object_object_add(o, "stages", json_object_get(r->stages));
    add_size(o, "vertices_in", r->vertices_in);
    add_size(o, "vertices_out", r->vertices_out);
    add_size(o, "self_intersections", r->intersections);
    if (r->guarded) {
        json_object *g = json_object_new_object();
        add_size(g, "moves", r->guard.moves);
        add_size(g, "reduced", r->guard.reduced);
        add_size(g, "dropped", r->guard.dropped);
        add_size(g, "redrawn", r->guard.redrawn);
        json_object_object_add(o, "crossing_guard", g);
    }
    if (r->repaired)
        add_size(o, "self_intersections_before_repair", r->before_repair);
    return o;
}

/* The parameters on one line: "sd 1.3, uc 0.7, st inf, ..." (null: no limit). */
static void print_params(json_object *params)
{
    const char *sep = "";
    printf("%-19s ", "parameters");
    json_object_object_foreach(params, key, val)
    {
        if (val == NULL)
            printf("%s%s inf", sep, key);
        else if (json_object_is_type(val, json_type_double))
            printf("%s%s %g", sep, key, json_object_get_double(val));
        else
            printf("%s%s %s", sep, key, json_object_get_string(val));
        sep = ", ";
    }
    putchar('\n');
}

static void print_human(const char *input, const char *output, const ft_layer *l, const edit_report *r,
                        json_object *params)
{
    printf("%-19s %s: %zu feature(s), %zu part(s), %zu vertices\n", "read", input, l->nfeatures, l->nparts,
           r->vertices_in);
    printf("%-19s %s\n", "coverage", r->coverage ? "yes: shared boundaries edited once" : "no");
    print_params(params);
    for (size_t i = 0; i < json_object_array_length(r->stages); i++) {
        json_object *s = json_object_array_get_idx(r->stages, i), *name = NULL, *n = NULL;
        json_object_object_get_ex(s, "step", &name);
        json_object_object_get_ex(s, "vertices", &n);
        printf("%-19s %lld vertices\n", json_object_get_string(name), (long long)json_object_get_int64(n));
    }
    if (r->repaired)
        printf("%-19s %zu before repair\n", "self-intersections", r->before_repair);
    printf("%-19s %zu\n", "self-intersections", r->intersections);
    if (r->guarded)
        printf("%-19s %zu moves: %zu redrawn on the other side, %zu halved or quartered, %zu dropped\n",
               "crossing guard", r->guard.moves, r->guard.redrawn, r->guard.reduced, r->guard.dropped);
    printf("%-19s %s: %zu -> %zu vertices\n", "wrote", output, r->vertices_in, r->vertices_out);
}

/* Refuses, before any work, steps whose output would not fit in memory, naming the option behind it. */
static int check_growth(const line_step *steps, size_t nsteps, size_t vertices_in)
{
    double est = (double)vertices_in;
    const char *why = NULL;
    for (size_t i = 0; i < nsteps; i++)
        if (steps[i].growth > 1.0) {
            est *= steps[i].growth;
            why = steps[i].option;
        }
    if (why == NULL)
        return FT_OK;
    char what[160];
    snprintf(what, sizeof what, "%s on %zu vertices (up to %.3g vertices out)", why, vertices_in, est);
    return ft_check_memory(est * LINE_BYTES_PER_VERTEX, what);
}

/* Everything after the input is read: prepare, edit, write, report. */
static int edit_and_write(const cli_command *cmd, const char *input, const char *output, const line_io *io,
                          ft_layer *l, const line_step *steps, size_t nsteps, line_prepare_fn prepare, void *ctx,
                          json_object *params, const char *geo_wkt)
{
    edit_report r = {0};
    r.coverage = !io->no_coverage && has_rings(l);
    r.vertices_in = ft_layer_vertex_count(l);
    if (prepare && prepare(l, r.coverage, ctx, params) != FT_OK)
        return ft_last_error_code() == FT_E_INVALID ? cli_usage_error(cmd, "%s", ft_last_error()) : cli_fail(cmd);
    if (check_growth(steps, nsteps, r.vertices_in) != FT_OK)
        return cli_fail(cmd);
    r.stages = json_object_new_array();
    ft_write_layer_opts wo = FT_WRITE_LAYER_OPTS_DEFAULT;
    wo.driver = io->driver;
    int rc = apply_steps(l, steps, nsteps, &r);
    if (rc == FT_OK && geo_wkt) /* back to longitude/latitude */
        rc = ft_io_layer_reproject(l, geo_wkt);
    if (rc == FT_OK)
        rc = ft_io_write_layer(output, l, &wo);
    if (rc != FT_OK) {
        json_object_put(r.stages);
        return cli_fail(cmd);
    }
    if (io->json) {
        rc = cli_print_json(cmd, report_json(input, output, l, &r, params));
    } else {
        print_human(input, output, l, &r, params);
        rc = CLI_OK;
    }
    json_object_put(r.stages);
    return rc;
}

/* A layer in longitude/latitude is edited in a local azimuthal equal-area projection centred on it, so that
 * every tolerance and length is in metres, then projected back (edit_and_write writes it in its input CRS). */
static int to_ground(const cli_command *cmd, const char *input, ft_layer *l, char **geo_wkt, json_object *params)
{
    ft_crs_info crs;
    *geo_wkt = NULL;
    if (l->crs_wkt && (*geo_wkt = strdup(l->crs_wkt)) == NULL)
        return ft_error(FT_E_NOMEM, "out of memory"), cli_fail(cmd);
    int rc = cli_geo_layer_ground(cmd, input, l, FT_LOCAL_LAEA, &crs);
    if (rc == CLI_CONTINUE && crs.geographic)
        json_object_object_add(params, "geographic", cli_geo_json(&crs, l->crs_wkt));
    if (rc != CLI_CONTINUE || !crs.geographic) {
        free(*geo_wkt);
        *geo_wkt = NULL;
    }
    return rc;
}

int line_edit_run(const cli_command *cmd, const char *input, const char *output, const line_io *io,
                  const line_step *steps, size_t nsteps, line_prepare_fn prepare, void *ctx, json_object *params)
{
    ft_layer *l = NULL;
    char *geo_wkt = NULL;
    int rc = ft_io_check_writable(output) != FT_OK ? cli_fail(cmd)
                                                   : cli_read_layer(cmd, input, io->layer, io->where, &l);
    if (rc == CLI_CONTINUE)
        rc = to_ground(cmd, input, l, &geo_wkt, params);
    if (rc == CLI_CONTINUE)
        rc = edit_and_write(cmd, input, output, io, l, steps, nsteps, prepare, ctx, params, geo_wkt);
    free(geo_wkt);
    ft_layer_free(l);
    json_object_put(params);
    return rc;
}
