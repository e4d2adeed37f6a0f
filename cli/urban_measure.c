/* fracterra — cli/urban_measure.c: the shared part of `dim area` and `urban table` (urban_cli.h): the
 * box-counting options, measuring a polygon layer as a whole and class by class (ft_urban_classes_by_field,
 * ft_urban_dim_area, ft_urban_layer_stats), a classified raster value by value (ft_urban_dim_area_grid,
 * ft_urban_grid_stats), the figures of each set as JSON and the table's column names.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "urban_cli.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- options ---- */

void urban_box_init(urban_box_args *a)
{
    ft_area_dim_opts d = FT_AREA_DIM_OPTS_DEFAULT;
    a->dim = d;
}

/* Appends the sides of "10" or "10,20,40" to a->cells. */
static int add_cells(const cli_command *cmd, const char *arg, urban_box_args *a)
{
    char buf[4096];
    if (snprintf(buf, sizeof buf, "%s", arg) >= (int)sizeof buf)
        return cli_usage_error(cmd, "--cell list is too long");
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (a->dim.ncells == URBAN_MAX_CELLS)
            return cli_usage_error(cmd, "--cell: at most %d box sides", URBAN_MAX_CELLS);
        double v = 0.0;
        int rc = cli_parse_double(cmd, "--cell", tok, 0.0, INFINITY, CLI_OPEN_LO, &v);
        if (rc != CLI_CONTINUE)
            return rc;
        for (size_t i = 0; i < a->dim.ncells; i++)
            if (a->cells[i] == v)
                return cli_usage_error(cmd, "--cell %g is given twice", v);
        a->cells[a->dim.ncells++] = v;
        a->dim.cells = a->cells;
    }
    return CLI_CONTINUE;
}

int urban_box_option(const cli_command *cmd, int opt, const char *arg, urban_box_args *a)
{
    switch (opt) {
    case URBAN_OPT_WHAT:
        if (ft_area_what_parse(arg, &a->dim.what) != FT_OK)
            return cli_usage_error(cmd, "--what must be boundary or area, got '%s'", arg);
        return CLI_CONTINUE;
    case URBAN_OPT_CELL: return add_cells(cmd, arg, a);
    case URBAN_OPT_OFFSETS: return cli_parse_int(cmd, "--offsets", arg, 1, 16, &a->dim.offsets);
    case URBAN_OPT_FEWEST: a->dim.fewest = 1; return CLI_CONTINUE;
    default: return URBAN_NOT_SHARED;
    }
}

/* ---- measuring ---- */

/* Passes one set to fn with its result; a failed measurement is passed as NULL unless it must stop. */
static int measure_set(const urban_set *s, int rc, ft_dim_result *r, urban_set_fn fn, void *ctx)
{
    if (rc == FT_E_NOMEM || rc == FT_E_CANCELLED)
        return rc;
    return fn(s, rc == FT_OK ? r : NULL, ctx);
}

static int measure_features(const ft_layer *l, const size_t *features, size_t n, const ft_area_dim_opts *o,
                            urban_set *s, urban_set_fn fn, void *ctx)
{
    ft_urban_stats stats;
    ft_dim_result *r = NULL;
    int rc = ft_urban_layer_stats(l, features, n, &stats);
    if (rc != FT_OK)
        return rc;
    s->stats = &stats;
    rc = ft_urban_dim_area(l, features, n, o, &r);
    return measure_set(s, rc, r, fn, ctx);
}

/* The class label as JSON, typed like the field. */
static json_object *class_id(const ft_layer *l, int field, const char *label)
{
    if (l->fields[field].type == FT_FIELD_INT)
        return json_object_new_int64(strtoll(label, NULL, 10));
    if (l->fields[field].type == FT_FIELD_REAL)
        return cli_json_double(strtod(label, NULL));
    return json_object_new_string(label);
}

int urban_measure_layer(const ft_layer *l, const char *field, int whole, const ft_area_dim_opts *o,
                        urban_set_fn fn, void *ctx)
{
    urban_set s = {NULL, NULL, NULL, 0};
    ft_urban_classes *c = NULL;
    int rc = field ? ft_urban_classes_by_field(l, field, &c) : FT_OK;
    if (rc == FT_OK && whole)
        rc = measure_features(l, NULL, 0, o, &s, fn, ctx);
    int k = field ? ft_layer_field_index(l, field) : -1;
    for (size_t i = 0; rc == FT_OK && c && i < c->n; i++) {
        s.label = c->classes[i].label;
        s.id = class_id(l, k, s.label);
        rc = measure_features(l, c->classes[i].features, c->classes[i].n, o, &s, fn, ctx);
        json_object_put(s.id);
    }
    ft_urban_classes_free(c);
    return rc;
}

int urban_measure_grid(const ft_grid *g, const ft_area_dim_opts *o, urban_set_fn fn, void *ctx)
{
    float *values = NULL;
    size_t n = 0;
    int rc = ft_urban_grid_classes(g, FT_URBAN_MAX_CLASSES, &values, &n);
    for (size_t i = 0; rc == FT_OK && i < n; i++) {
        char label[32];
        ft_urban_stats stats;
        ft_dim_result *r = NULL;
        snprintf(label, sizeof label, "%.9g", (double)values[i]);
        rc = ft_urban_grid_stats(g, values[i], &stats);
        if (rc != FT_OK)
            break;
        urban_set s = {label, cli_json_double(values[i]), &stats, 1};
        rc = ft_urban_dim_area_grid(g, values[i], o, &r);
        rc = measure_set(&s, rc, r, fn, ctx);
        json_object_put(s.id);
    }
    free(values);
    return rc;
}

/* ---- output ---- */

static void add_count(json_object *o, const char *key, size_t v)
{
    json_object_object_add(o, key, json_object_new_int64((int64_t)v));
}

json_object *urban_set_info(const urban_set *s)
{
    json_object *o = json_object_new_object();
    if (s->is_grid) {
        add_count(o, "cells", s->stats->ncells);
    } else {
        add_count(o, "features", s->stats->nfeatures);
        add_count(o, "holes", s->stats->nholes);
    }
    add_count(o, "polygons", s->stats->npolygons);
    json_object_object_add(o, "area", cli_json_double(s->stats->area));
    json_object_object_add(o, "perimeter", cli_json_double(s->stats->perimeter));
    return o;
}

void urban_column_name(const char *cls, const char *measure, char *buf, size_t size)
{
    if (cls)
        snprintf(buf, size, "%s.%s", cls, measure);
    else
        snprintf(buf, size, "%s", measure);
}
