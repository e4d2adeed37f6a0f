/* fracterra — cli/dim_output.c: the shared scale options and the one printer of dimension results (JSON,
 * table, log-log plots) used by every estimator command; see dim_output.h for the JSON shapes.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "dim_output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

typedef struct {
    ft_dim_result *r;
    const char *xlabel, *ylabel;
    char *plot; /* the plot written for it, or NULL */
} dim_item;

typedef struct {
    int is_feature;
    json_object *id;
    char *label;
    json_object *info;
    char *error;
    dim_item *items;
    size_t n, cap;
} dim_group;

struct cli_dim_report {
    const char *input;
    dim_group *groups;
    size_t n, cap;
};

/* ---- options ---- */

int cli_dim_option(const cli_command *cmd, int opt, const char *arg, cli_dim_opts *o)
{
    switch (opt) {
    case CLI_DIM_OPT_MIN_SCALE:
        return cli_parse_double(cmd, "--min-scale", arg, 0.0, INFINITY, CLI_OPEN_LO, &o->min_scale);
    case CLI_DIM_OPT_MAX_SCALE:
        return cli_parse_double(cmd, "--max-scale", arg, 0.0, INFINITY, CLI_OPEN_LO, &o->max_scale);
    case CLI_DIM_OPT_SCALES: return cli_parse_int(cmd, "--scales", arg, 3, CLI_DIM_MAX_SCALES, &o->nscales);
    case CLI_DIM_OPT_SEGMENTS: o->segments = 1; return CLI_CONTINUE;
    case CLI_DIM_OPT_PLOT: o->plot = arg; return CLI_CONTINUE;
    case CLI_DIM_OPT_REGIME: return cli_parse_int(cmd, "--regime", arg, 1, CLI_DIM_MAX_SCALES, &o->regime);
    case 'j': o->json = 1; return CLI_CONTINUE;
    default: return CLI_DIM_NOT_SHARED;
    }
}

int cli_dim_input_option(const cli_command *cmd, int opt, const char *arg, cli_dim_opts *o, const char **method,
                         const char **layer)
{
    switch (opt) {
    case 'm': *method = arg; return CLI_CONTINUE;
    case 'l': *layer = arg; return CLI_CONTINUE;
    default: return cli_dim_option(cmd, opt, arg, o);
    }
}

static int has_plot_extension(const char *path)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(slash ? slash : path, '.');
    return dot && (strcasecmp(dot, ".svg") == 0 || strcasecmp(dot, ".png") == 0 || strcasecmp(dot, ".pdf") == 0);
}

int cli_dim_check(const cli_command *cmd, const cli_dim_opts *o)
{
    if (o->min_scale > 0.0 && o->max_scale > 0.0 && o->min_scale >= o->max_scale)
        return cli_usage_error(cmd, "--min-scale %g must be below --max-scale %g", o->min_scale, o->max_scale);
    if (o->regime > 0 && o->min_scale > 0.0 && o->max_scale > 0.0)
        return cli_usage_error(cmd, "--regime picks a regime of the automatic fit; it cannot be combined with a "
                               "range (--min-scale and --max-scale)");
    if (o->plot && !has_plot_extension(o->plot))
        return cli_usage_error(cmd, "--plot file must end in .svg, .png or .pdf, got '%s'", o->plot);
    return CLI_CONTINUE;
}

/* ---- collecting ---- */

cli_dim_report *cli_dim_report_create(const char *input)
{
    cli_dim_report *rep = calloc(1, sizeof *rep);
    if (rep)
        rep->input = input;
    return rep;
}

void cli_dim_report_free(cli_dim_report *rep)
{
    if (rep == NULL)
        return;
    for (size_t g = 0; g < rep->n; g++) {
        dim_group *gr = &rep->groups[g];
        for (size_t i = 0; i < gr->n; i++) {
            ft_dim_result_free(gr->items[i].r);
            free(gr->items[i].plot);
        }
        free(gr->items);
        json_object_put(gr->id);
        json_object_put(gr->info);
        free(gr->label);
        free(gr->error);
    }
    free(rep->groups);
    free(rep);
}

/* Grows *p (n used, *cap allocated, elements of size) to hold one more. */
static int grow(void **p, size_t n, size_t *cap, size_t size)
{
    if (n < *cap)
        return FT_OK;
    size_t c = *cap ? 2 * *cap : 4;
    void *q = realloc(*p, c * size);
    if (q == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    *p = q;
    *cap = c;
    return FT_OK;
}

int cli_dim_report_group(cli_dim_report *rep, int is_feature, json_object *id, const char *label,
                         json_object *info)
{
    char *copy = strdup(label ? label : "");
    if (copy == NULL || grow((void **)&rep->groups, rep->n, &rep->cap, sizeof *rep->groups) != FT_OK) {
        free(copy);
        json_object_put(id);
        json_object_put(info);
        return ft_error(FT_E_NOMEM, "out of memory");
    }
    rep->groups[rep->n++] = (dim_group){is_feature, id, copy, info, NULL, NULL, 0, 0};
    return FT_OK;
}

int cli_dim_report_add(cli_dim_report *rep, ft_dim_result *r, const char *xlabel, const char *ylabel)
{
    dim_group *g = rep->n ? &rep->groups[rep->n - 1] : NULL;
    if (g == NULL || grow((void **)&g->items, g->n, &g->cap, sizeof *g->items) != FT_OK) {
        ft_dim_result_free(r);
        return g ? FT_E_NOMEM : ft_error(FT_E_INVALID, "dim report: no group started");
    }
    g->items[g->n++] = (dim_item){r, xlabel, ylabel, NULL};
    return FT_OK;
}

void cli_dim_report_group_failed(const cli_command *cmd, cli_dim_report *rep)
{
    if (rep->n == 0)
        return;
    dim_group *g = &rep->groups[rep->n - 1];
    const char *msg = *ft_last_error() ? ft_last_error() : ft_strerror(ft_last_error_code());
    cli_warn(cmd, "%s: %s", g->label, msg);
    free(g->error);
    g->error = strdup(msg);
}

size_t cli_dim_report_count(const cli_dim_report *rep)
{
    size_t n = 0;
    for (size_t g = 0; g < rep->n; g++)
        n += rep->groups[g].error ? 0 : rep->groups[g].n;
    return n;
}

static int has_features(const cli_dim_report *rep)
{
    for (size_t g = 0; g < rep->n; g++)
        if (rep->groups[g].is_feature)
            return 1;
    return 0;
}

/* ---- plots ---- */

/* text with every character outside [A-Za-z0-9._-] replaced by '_', at most 64 characters, into buf. */
static int sanitize(const char *text, char *buf, size_t size)
{
    size_t n = 0;
    int changed = 0;
    for (const char *s = text; *s && n + 1 < size && n < 64; s++, n++) {
        int keep = (*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || (*s >= '0' && *s <= '9') ||
                   *s == '.' || *s == '_' || *s == '-';
        buf[n] = keep ? *s : '_';
        changed |= !keep;
    }
    buf[n] = '\0';
    return changed || text[n] != '\0';
}

/* The plot path of item i of group g: the --plot path itself when the report holds one result, otherwise
 * STEM[-ID][-METHOD].EXT (ID for feature groups, cleaned to [A-Za-z0-9._-] with the group's number added if
 * cleaning changed it; METHOD when the group has several results). */
static char *plot_path(const cli_dim_report *rep, const char *plot, size_t g, size_t i)
{
    const dim_group *gr = &rep->groups[g];
    if (cli_dim_report_count(rep) == 1)
        return strdup(plot);
    const char *slash = strrchr(plot, '/'), *dot = strrchr(slash ? slash : plot, '.');
    char label[80] = "", method[80] = "";
    if (gr->is_feature || rep->n > 1) {
        char clean[72];
        const char *tag = gr->id ? json_object_get_string(gr->id) : gr->is_feature ? "null" : gr->label;
        if (sanitize(tag, clean, sizeof clean))
            snprintf(label, sizeof label, "-%s-%zu", clean, g + 1); /* keep names apart after cleaning */
        else
            snprintf(label, sizeof label, "-%s", clean);
    }
    if (gr->n > 1) {
        char clean[72];
        sanitize(gr->items[i].r->method ? gr->items[i].r->method : "result", clean, sizeof clean);
        snprintf(method, sizeof method, "-%s", clean);
    }
    size_t size = strlen(plot) + strlen(label) + strlen(method) + 1;
    char *p = malloc(size);
    if (p)
        snprintf(p, size, "%.*s%s%s%s", (int)(dot - plot), plot, label, method, dot);
    return p;
}

static void remove_plots(cli_dim_report *rep)
{
    for (size_t g = 0; g < rep->n; g++) {
        for (size_t i = 0; i < rep->groups[g].n; i++) {
            dim_item *it = &rep->groups[g].items[i];
            if (it->plot)
                unlink(it->plot);
            free(it->plot);
            it->plot = NULL;
        }
    }
}

static int write_plot(const cli_dim_report *rep, const cli_dim_opts *o, size_t g, dim_item *it)
{
    const dim_group *gr = &rep->groups[g];
    const char *slash = strrchr(rep->input, '/'), *base = slash ? slash + 1 : rep->input;
    char title[256];
    if (gr->is_feature)
        snprintf(title, sizeof title, "%s, %s: %s", base, gr->label, it->r->method);
    else
        snprintf(title, sizeof title, "%s: %s", base, it->r->method);
    ft_plot_opts po = FT_PLOT_OPTS_DEFAULT;
    po.title = title;
    char xlabel[96], ylabel[96];
    const int unit = it->r->units[0] != '\0';
    if (unit && it->xlabel) /* the axis names the unit of its scales, and of lengths */
        snprintf(xlabel, sizeof xlabel, "%s (%s)", it->xlabel, it->r->units);
    if (unit && it->ylabel && strcmp(it->ylabel, "length") == 0)
        snprintf(ylabel, sizeof ylabel, "%s (%s)", it->ylabel, it->r->units);
    po.xlabel = unit && it->xlabel ? xlabel : it->xlabel;
    po.ylabel = unit && it->ylabel && strcmp(it->ylabel, "length") == 0 ? ylabel : it->ylabel;
    po.segments = o->segments;
    char *path = plot_path(rep, o->plot, g, (size_t)(it - gr->items));
    if (path == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    int rc = ft_render_loglog_plot(it->r, path, &po);
    if (rc == FT_OK)
        it->plot = path;
    else
        free(path);
    return rc;
}

static int write_plots(const cli_command *cmd, cli_dim_report *rep, const cli_dim_opts *o)
{
    for (size_t g = 0; o->plot && g < rep->n; g++) {
        for (size_t i = 0; rep->groups[g].error == NULL && i < rep->groups[g].n; i++) {
            if (write_plot(rep, o, g, &rep->groups[g].items[i]) != FT_OK) {
                remove_plots(rep);
                return cli_fail(cmd);
            }
        }
    }
    return CLI_OK;
}

/* ---- JSON ---- */

static json_object *json_count(double c)
{
    if (c == floor(c) && fabs(c) < 9007199254740992.0)
        return json_object_new_int64((int64_t)c);
    return cli_json_double(c);
}

static json_object *json_range(double lo, double hi)
{
    json_object *a = json_object_new_array();
    json_object_array_add(a, cli_json_double(lo));
    json_object_array_add(a, cli_json_double(hi));
    return a;
}

static json_object *json_table(const ft_loglog *t)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; t && i < t->n; i++) {
        const ft_loglog_row *row = &t->rows[i];
        json_object *o = json_object_new_object();
        json_object_object_add(o, "scale", cli_json_double(row->scale));
        json_object_object_add(o, "value", cli_json_double(row->value));
        json_object_object_add(o, "count", json_count(row->count));
        json_object_object_add(o, "slope", cli_json_double(row->slope));
        json_object_object_add(o, "used", json_object_new_boolean(row->used != 0));
        json_object_array_add(a, o);
    }
    return a;
}

static json_object *json_segments(const ft_dim_result *r)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < r->nsegments; i++) {
        const ft_loglog_segment *s = &r->segments[i];
        json_object *o = json_object_new_object();
        json_object_object_add(o, "range", json_range(s->scale_lo, s->scale_hi));
        json_object_object_add(o, "rows", json_object_new_int64((int64_t)s->n));
        json_object_object_add(o, "D", cli_json_double(s->D));
        json_object_object_add(o, "r2", cli_json_double(s->r2));
        json_object_object_add(o, "stderr", cli_json_double(s->stderr_D));
        json_object_object_add(o, "max_err", cli_json_double(s->max_err));
        json_object_object_add(o, "D_minimax", cli_json_double(s->D_minimax));
        json_object_object_add(o, "chosen", json_object_new_boolean(i == r->best));
        json_object_array_add(a, o);
    }
    return a;
}

static json_object *json_regimes(const ft_dim_result *r)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < r->nregimes; i++) {
        const ft_loglog_segment *s = &r->regimes[i];
        json_object *o = json_object_new_object();
        json_object_object_add(o, "min_scale", cli_json_double(s->scale_lo));
        json_object_object_add(o, "max_scale", cli_json_double(s->scale_hi));
        json_object_object_add(o, "D", cli_json_double(s->D));
        json_object_object_add(o, "se", cli_json_double(s->stderr_D));
        json_object_object_add(o, "r2", cli_json_double(s->r2));
        json_object_object_add(o, "rows", json_object_new_int64((int64_t)s->n));
        json_object_object_add(o, "chosen", json_object_new_boolean(i == r->regime));
        json_object_array_add(a, o);
    }
    return a;
}

static json_object *json_breaks(const ft_dim_result *r)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; r->breaks && i + 1 < r->nregimes; i++)
        json_object_array_add(a, cli_json_double(r->breaks[i]));
    return a;
}

/* The noise model of a lag estimator or the spectrum (docs/surface-noise.md): detected (or given) and
 * removed or not, the noise sds it implies, the fitted structure function and the floor of the fit (the
 * spectrum: the highest frequency fitted, "max_frequency"). */
static json_object *json_noise(const ft_noise_model *m, int spectrum)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "detected", json_object_new_boolean(m->detected || m->applied));
    json_object_object_add(o, "removed", json_object_new_boolean(m->applied));
    json_object_object_add(o, "sigma_z", cli_json_double(m->sigma_z));
    if (m->s > 0.0 || m->sigma_xy > 0.0)
        json_object_object_add(o, "sigma_xy", cli_json_double(m->sigma_xy));
    json_object_object_add(o, "nugget", cli_json_double(m->c0));
    json_object_object_add(o, "H", cli_json_double(m->H));
    json_object_object_add(o, "F", cli_json_double(m->F));
    json_object_object_add(o, spectrum ? "max_frequency" : "floor", cli_json_double(m->floor));
    return o;
}

/* The members of one result (DESIGN.md "JSON results") added to o. */
static void add_result(json_object *o, const dim_item *it, int segments)
{
    const ft_dim_result *r = it->r;
    json_object_object_add(o, "method", json_object_new_string(r->method ? r->method : ""));
    json_object_object_add(o, "D", cli_json_double(r->D));
    json_object_object_add(o, "r2", cli_json_double(r->r2));
    json_object_object_add(o, "stderr", cli_json_double(r->stderr_D));
    json_object_object_add(o, "range", json_range(r->range[0], r->range[1]));
    json_object_object_add(o, "segmentation", json_object_new_string(r->segmentation ? r->segmentation : ""));
    json_object_object_add(o, "max_err", cli_json_double(r->max_err));
    json_object_object_add(o, "choice", json_object_new_string(r->choice ? r->choice : ""));
    json_object_object_add(o, "regime", r->regime == FT_LOGLOG_NONE ? NULL
                                                                     : json_object_new_int64((int64_t)r->regime + 1));
    json_object_object_add(o, "regimes", json_regimes(r));
    json_object_object_add(o, "breaks", json_breaks(r));
    if (r->units[0] != '\0')
        json_object_object_add(o, "units", json_object_new_string(r->units));
    json_object *w = json_object_new_array();
    for (size_t i = 0; i < r->nwarnings; i++)
        json_object_array_add(w, json_object_new_string(r->warnings[i]));
    json_object_object_add(o, "warnings", w);
    if (r->nugget.fitted)
        json_object_object_add(o, "noise",
                               json_noise(&r->nugget, r->method != NULL && strcmp(r->method, "spectrum") == 0));
    json_object_object_add(o, "table", json_table(r->table));
    if (segments)
        json_object_object_add(o, "segments", json_segments(r));
    if (it->plot)
        json_object_object_add(o, "plot", json_object_new_string(it->plot));
}

/* Moves every member of src (may be NULL) to the end of dst. */
static void add_members(json_object *dst, json_object *src)
{
    if (src == NULL)
        return;
    json_object_object_foreach(src, key, val) json_object_object_add(dst, key, json_object_get(val));
}

/* A group's members (info, then its result or "results", or "error") added to o. */
static void add_group(json_object *o, const dim_group *g, int segments)
{
    add_members(o, g->info);
    if (g->error) {
        json_object_object_add(o, "error", json_object_new_string(g->error));
    } else if (g->n == 1) {
        add_result(o, &g->items[0], segments);
    } else {
        json_object *a = json_object_new_array();
        for (size_t i = 0; i < g->n; i++) {
            json_object *r = json_object_new_object();
            add_result(r, &g->items[i], segments);
            json_object_array_add(a, r);
        }
        json_object_object_add(o, "results", a);
    }
}

static json_object *report_json(const cli_dim_report *rep, const cli_dim_opts *o, json_object *extra)
{
    json_object *top = json_object_new_object();
    add_members(top, extra);
    if (!has_features(rep)) {
        for (size_t g = 0; g < rep->n; g++)
            add_group(top, &rep->groups[g], o->segments);
        return top;
    }
    json_object *a = json_object_new_array();
    for (size_t g = 0; g < rep->n; g++) {
        json_object *f = json_object_new_object();
        json_object_object_add(f, "id", json_object_get(rep->groups[g].id));
        add_group(f, &rep->groups[g], o->segments);
        json_object_array_add(a, f);
    }
    json_object_object_add(top, "features", a);
    return top;
}

/* ---- table ---- */

static size_t used_rows(const ft_loglog *t)
{
    size_t n = 0;
    for (size_t i = 0; t && i < t->n; i++)
        n += t->rows[i].used != 0;
    return n;
}

static void print_summary(const dim_item *it)
{
    const ft_dim_result *r = it->r;
    printf("%-10s D = %.4f \xc2\xb1 %.4f   r\xc2\xb2 = %.4f   range %.6g .. %.6g%s%s (%zu of %zu scales)\n",
           r->method ? r->method : "", r->D, r->stderr_D, r->r2, r->range[0], r->range[1], r->units[0] ? " " : "",
           r->units, used_rows(r->table), r->table ? r->table->n : 0);
    if (r->choice)
        printf("%-10s D from: %s\n", "", r->choice);
    for (size_t i = 0; i < r->nregimes; i++) {
        const ft_loglog_segment *s = &r->regimes[i];
        printf("%-10s regime %zu%s: scales %.6g .. %.6g%s%s  D = %.4f \xc2\xb1 %.4f  r\xc2\xb2 = %.4f\n", "", i + 1,
               i == r->regime ? " (D)" : "", s->scale_lo, s->scale_hi, r->units[0] ? " " : "", r->units, s->D,
               s->stderr_D, s->r2);
        if (i + 1 < r->nregimes && r->breaks)
            printf("%-10s break at %.6g%s%s\n", "", r->breaks[i], r->units[0] ? " " : "", r->units);
    }
    if (r->nugget.applied)
        printf("%-10s noise removed: sd %.4g on z%s; fit %s %.6g\n", "", r->nugget.sigma_z,
               r->nugget.s > 0.0 ? " (and x, y: see --json)" : "",
               r->method != NULL && strcmp(r->method, "spectrum") == 0 ? "to frequency" : "from", r->nugget.floor);
    if (it->plot)
        printf("%-10s plot %s\n", "", it->plot);
}

static void print_table(const ft_loglog *t, const char *units)
{
    char head[48];
    snprintf(head, sizeof head, units[0] ? "scale (%s)" : "scale", units);
    printf("  %14s %14s %12s %9s  %s\n", head, "value", "count", "slope", "used");
    for (size_t i = 0; t && i < t->n; i++) {
        const ft_loglog_row *row = &t->rows[i];
        printf("  %14.6g %14.6g %12.6g %9.4f  %s\n", row->scale, row->value, row->count, row->slope,
               row->used ? "*" : "");
    }
}

static void print_segments(const ft_dim_result *r)
{
    for (size_t i = 0; i < r->nsegments; i++) {
        const ft_loglog_segment *s = &r->segments[i];
        printf("  segment %zu%s: scales %.6g .. %.6g (%zu rows)  D = %.4f \xc2\xb1 %.4f  r\xc2\xb2 = %.4f  "
               "max err %.4f\n",
               i + 1, i == r->best ? " (chosen)" : "", s->scale_lo, s->scale_hi, s->n, s->D, s->stderr_D, s->r2,
               s->max_err);
    }
}

/* A group's figures on one line: "features 1, chains 1, vertices 158". */
static void print_info(json_object *info)
{
    if (info == NULL || json_object_object_length(info) == 0)
        return;
    const char *sep = "";
    json_object_object_foreach(info, key, val)
    {
        printf("%s%s %s", sep, key, json_object_get_string(val));
        sep = ", ";
    }
    putchar('\n');
}

static void print_human(const cli_dim_report *rep, const cli_dim_opts *o)
{
    int features = has_features(rep);
    for (size_t g = 0; g < rep->n; g++) {
        const dim_group *gr = &rep->groups[g];
        if (features)
            printf("%s%s\n", g ? "\n" : "", gr->label);
        print_info(gr->info);
        if (gr->error)
            printf("%-10s error: %s\n", "", gr->error);
        for (size_t i = 0; gr->error == NULL && i < gr->n; i++) {
            if (i > 0 && !features)
                putchar('\n');
            print_summary(&gr->items[i]);
            if (!features)
                print_table(gr->items[i].r->table, gr->items[i].r->units);
            if (o->segments)
                print_segments(gr->items[i].r);
        }
    }
}

/* The fit's own warnings (e.g. no straight segment: whole range fitted) on stderr, one per result. */
static void warn_fits(const cli_command *cmd, const cli_dim_report *rep)
{
    for (size_t g = 0; g < rep->n; g++) {
        const dim_group *gr = &rep->groups[g];
        for (size_t i = 0; gr->error == NULL && i < gr->n; i++) {
            const ft_dim_result *r = gr->items[i].r;
            for (size_t w = 0; w < r->nwarnings; w++)
                cli_warn(cmd, "%s%s%s: %s", gr->label ? gr->label : "", gr->label ? " " : "",
                         r->method ? r->method : "", r->warnings[w]);
        }
    }
}

int cli_dim_report_print(const cli_command *cmd, cli_dim_report *rep, const cli_dim_opts *o, json_object *extra)
{
    warn_fits(cmd, rep);
    int rc = write_plots(cmd, rep, o);
    if (rc != CLI_OK) {
        json_object_put(extra);
        return rc;
    }
    if (o->json) {
        rc = cli_print_json(cmd, report_json(rep, o, extra));
    } else {
        print_human(rep, o);
        rc = CLI_OK;
    }
    json_object_put(extra);
    if (rc != CLI_OK)
        remove_plots(rep);
    return rc;
}

int cli_parse_noise_sigma(const cli_command *cmd, const char *arg, int allow_xy, double *xy, double *z)
{
    char *end = NULL;
    double a = strtod(arg, &end), b = NAN;
    int two = end != arg && *end == ',';
    if (two) {
        const char *s = end + 1;
        b = strtod(s, &end);
        if (end == s)
            two = -1;
    }
    int ok = end != arg && *end == '\0' && two >= 0 && (allow_xy || !two) && a >= 0.0 && isfinite(a) &&
             (!two || (b >= 0.0 && isfinite(b)));
    if (!ok)
        return cli_usage_error(cmd, "--noise-sigma must be %s (standard deviations >= 0), got '%s'",
                               allow_xy ? "Z or XY,Z" : "Z", arg);
    *xy = two ? a : 0.0;
    *z = two ? b : a;
    return CLI_CONTINUE;
}

int cli_parse_noise_model(const cli_command *cmd, const char *arg, int *mode)
{
    if (strcmp(arg, "auto") == 0)
        *mode = 0;
    else if (strcmp(arg, "off") == 0)
        *mode = -1;
    else
        return cli_usage_error(cmd, "--noise-model must be auto or off, got '%s'", arg);
    return CLI_CONTINUE;
}
