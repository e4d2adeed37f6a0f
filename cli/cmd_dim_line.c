/* fracterra — cli/cmd_dim_line.c: `fracterra dim line INPUT`: the fractal dimension of the chains of a
 * vector layer (OGR) or GMT text file, by walking divider, equipaced polygon, hybrid walk or box counting.
 *
 * By default the whole layer is one set: every part of every feature (lines, outer rings and holes) is
 * measured together, the values at each scale summed over the chains (ft_line_dim). `--by FIELD` gives
 * one result per distinct value of FIELD (features sharing a value are measured together, in order of
 * first appearance, a null value being a value of its own); `--by fid` gives one result per feature when
 * the layer has no field called fid. A feature group that cannot be measured (too small for the scales)
 * is reported with an "error" and a warning; the command fails only if no group could be measured.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "dim_output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define NMETHODS 5

typedef struct {
    cli_dim_opts dim;
    const char *method, *layer, *where, *by;
    int starts; /* --starts: divider walks round each ring (Andrle 1992); 1 = one walk from vertex 0 */
} line_args;

/* A set of features measured together. */
typedef struct {
    size_t *features, n;
    json_object *id;
    char *label;
} line_group;

/* A feature's --by key, for sorting features into groups. */
typedef struct {
    size_t feature;
    int is_null;
    char *key;
} feature_key;

/* ---- methods ---- */

/* Parses "all" or a comma-separated list of method names into ms; returns the count, 0 on a bad name. */
static int parse_methods(const char *text, ft_line_method *ms)
{
    if (strcmp(text, "all") == 0) {
        for (int i = 0; i < NMETHODS; i++)
            ms[i] = (ft_line_method)i;
        return NMETHODS;
    }
    int n = 0;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", text);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        ft_line_method m;
        if (n == NMETHODS || ft_line_method_parse(tok, &m) != FT_OK)
            return 0;
        for (int i = 0; i < n; i++)
            if (ms[i] == m)
                return 0;
        ms[n++] = m;
    }
    ft_clear_error();
    return n;
}

static void axis_labels(ft_line_method m, const char **x, const char **y)
{
    int box = m == FT_LINE_BOX || m == FT_LINE_BOX_MIN;
    *x = box ? "box side" : m == FT_LINE_EQUIPACED ? "spacing" : "ruler";
    *y = box ? (m == FT_LINE_BOX ? "boxes crossed (mean over offsets)" : "boxes crossed (fewest)") : "length";
}

/* ---- groups ---- */

static void groups_free(line_group *g, size_t n)
{
    for (size_t i = 0; g && i < n; i++) {
        free(g[i].features);
        json_object_put(g[i].id);
        free(g[i].label);
    }
    free(g);
}

static int cmp_key(const void *a, const void *b)
{
    const feature_key *p = a, *q = b;
    if (p->is_null != q->is_null)
        return p->is_null - q->is_null;
    int c = p->is_null ? 0 : strcmp(p->key, q->key);
    return c ? c : (p->feature > q->feature) - (p->feature < q->feature);
}

static int same_key(const feature_key *p, const feature_key *q)
{
    return p->is_null == q->is_null && (p->is_null || strcmp(p->key, q->key) == 0);
}

static int cmp_group_first(const void *a, const void *b)
{
    const line_group *p = a, *q = b;
    return (p->features[0] > q->features[0]) - (p->features[0] < q->features[0]);
}

/* Feature f's key for field `field` (-1: the feature id), as text, and its JSON id. */
static int make_key(const ft_layer *l, size_t f, int field, feature_key *k, json_object **id)
{
    char buf[64];
    const ft_value *v = field >= 0 ? &l->features[f].values[field] : NULL;
    k->feature = f;
    k->is_null = v && v->is_null;
    *id = NULL;
    if (v == NULL) {
        snprintf(buf, sizeof buf, "%lld", (long long)l->features[f].fid);
        *id = json_object_new_int64(l->features[f].fid);
    } else if (k->is_null) {
        buf[0] = '\0';
    } else if (l->fields[field].type == FT_FIELD_INT) {
        snprintf(buf, sizeof buf, "%lld", (long long)v->i);
        *id = json_object_new_int64(v->i);
    } else if (l->fields[field].type == FT_FIELD_REAL) {
        snprintf(buf, sizeof buf, "%.17g", v->r);
        *id = cli_json_double(v->r);
    } else {
        *id = json_object_new_string(v->s ? v->s : "");
    }
    const char *text = v && !k->is_null && l->fields[field].type == FT_FIELD_STRING ? (v->s ? v->s : "") : buf;
    k->key = strdup(text);
    return k->key ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
}

/* Starts a group at keys[i] (its first feature) with the label "FIELD=value". */
static int start_group(line_group *g, const feature_key *k, const char *by, json_object *id, size_t cap)
{
    size_t size = strlen(by) + strlen(k->key) + 8;
    g->features = malloc(cap * sizeof *g->features);
    g->label = malloc(size);
    g->id = id;
    g->n = 0;
    if (g->features == NULL || g->label == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    snprintf(g->label, size, "%s=%s", by, k->is_null ? "null" : k->key);
    return FT_OK;
}

/* Sorts the features by key and makes one group per run of equal keys, ordered by first feature. */
static int group_keys(feature_key *keys, json_object **ids, size_t n, const char *by, line_group **out,
                      size_t *nout)
{
    qsort(keys, n, sizeof *keys, cmp_key);
    line_group *g = calloc(n ? n : 1, sizeof *g);
    size_t ng = 0;
    int rc = g ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
    for (size_t i = 0, run = 0; rc == FT_OK && i < n; i = run) {
        for (run = i + 1; run < n && same_key(&keys[i], &keys[run]); run++)
            ;
        rc = start_group(&g[ng], &keys[i], by, json_object_get(ids[keys[i].feature]), run - i);
        for (size_t k = i; rc == FT_OK && k < run; k++)
            g[ng].features[g[ng].n++] = keys[k].feature;
        ng++;
    }
    if (rc != FT_OK) {
        groups_free(g, ng);
        return rc;
    }
    qsort(g, ng, sizeof *g, cmp_group_first);
    *out = g;
    *nout = ng;
    return FT_OK;
}

/* The groups of --by FIELD (or fid), NULL-free on success. */
static int group_by(const ft_layer *l, const char *path, const char *by, line_group **out, size_t *nout)
{
    int field = ft_layer_field_index(l, by);
    if (field < 0 && strcasecmp(by, "fid") != 0)
        return ft_error(FT_E_FORMAT, "--by: no field '%s' in '%s'", by, path);
    feature_key *keys = calloc(l->nfeatures ? l->nfeatures : 1, sizeof *keys);
    json_object **ids = calloc(l->nfeatures ? l->nfeatures : 1, sizeof *ids);
    int rc = keys && ids ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
    for (size_t f = 0; rc == FT_OK && f < l->nfeatures; f++)
        rc = make_key(l, f, field, &keys[f], &ids[f]);
    if (rc == FT_OK)
        rc = group_keys(keys, ids, l->nfeatures, by, out, nout);
    for (size_t f = 0; keys && ids && f < l->nfeatures; f++) {
        free(keys[f].key);
        json_object_put(ids[f]);
    }
    free(keys);
    free(ids);
    return rc;
}

/* ---- measuring ---- */

/* The chains (2 or more vertices) of a group's features, or of the whole layer (g == NULL). */
static int group_chains(const ft_layer *l, const line_group *g, const ft_chain ***out, size_t *n,
                        size_t *vertices)
{
    const ft_chain **c = malloc((l->nparts ? l->nparts : 1) * sizeof *c);
    if (c == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    *n = *vertices = 0;
    size_t nf = g ? g->n : l->nfeatures;
    for (size_t i = 0; i < nf; i++) {
        const ft_feature *f = &l->features[g ? g->features[i] : i];
        for (size_t p = f->first; p < f->first + f->count; p++) {
            const ft_chain *ch = l->parts[p].chain;
            if (ch && ch->n >= 2) {
                c[(*n)++] = ch;
                *vertices += ch->n;
            }
        }
    }
    *out = c;
    return FT_OK;
}

static json_object *group_info(size_t features, size_t chains, size_t vertices)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "features", json_object_new_int64((int64_t)features));
    json_object_object_add(o, "chains", json_object_new_int64((int64_t)chains));
    json_object_object_add(o, "vertices", json_object_new_int64((int64_t)vertices));
    return o;
}

/* The input as measured: the layer, its CRS, and for box counting of lon/lat data its copy in a local
 * equal-area projection (NULL otherwise). */
typedef struct {
    const ft_layer *l, *box_layer;
    const ft_crs_info *crs;
} line_input;

/* With --starts N, the divider's D from each start alone over the rulers the mean's fit used (r's range, the
 * same geometric series): "starts": {"n", "D_mean", "D_sd", "D_min", "D_max"} in info, and a line on
 * stderr. */
static int start_spread(const ft_chain *const *chains, size_t n, const ft_line_dim_opts *opts, const ft_dim_result *r,
                        json_object *info)
{
    ft_line_dim_opts o = *opts;
    o.min_scale = r->range[0];
    o.max_scale = r->range[1];
    o.nscales = (int)(r->fit.last - r->fit.first + 1);
    o.fit_whole_range = 1;
    o.min_r2 = 0.0;
    o.progress = NULL;
    double sum = 0.0, sum2 = 0.0, lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < o.starts; k++) {
        ft_dim_result *one = NULL;
        o.only_start = k;
        int rc = ft_line_dim(chains, n, FT_LINE_DIVIDER, &o, &one);
        if (rc != FT_OK)
            return rc;
        sum += one->D;
        sum2 += one->D * one->D;
        lo = one->D < lo ? one->D : lo;
        hi = one->D > hi ? one->D : hi;
        ft_dim_result_free(one);
    }
    double mean = sum / o.starts, var = (sum2 - sum * mean) / (o.starts - 1);
    json_object *s = json_object_new_object();
    json_object_object_add(s, "n", json_object_new_int(o.starts));
    json_object_object_add(s, "D_mean", json_object_new_double(mean));
    json_object_object_add(s, "D_sd", json_object_new_double(var > 0.0 ? sqrt(var) : 0.0));
    json_object_object_add(s, "D_min", json_object_new_double(lo));
    json_object_object_add(s, "D_max", json_object_new_double(hi));
    json_object_object_add(info, "starts", s);
    fprintf(stderr, "divider over %d starts: D %.4f of the mean lengths; one start alone: %.4f +- %.4f (sd), "
            "[%.4f, %.4f]\n", o.starts, r->D, mean, var > 0.0 ? sqrt(var) : 0.0, lo, hi);
    return FT_OK;
}

/* Measures one group (g == NULL: the whole layer) with every method into the report. Lon/lat chains are
 * walked on the ellipsoid, and box-counted in the equal-area copy. */
static int measure(const line_input *in, const line_group *g, const ft_line_method *ms, int nm,
                   const ft_line_dim_opts *opts, cli_dim_report *rep, const char *label)
{
    const ft_layer *l = in->l;
    const ft_chain **chains = NULL, **box_chains = NULL;
    size_t n = 0, vertices = 0, nb = 0, vb = 0;
    int rc = group_chains(l, g, &chains, &n, &vertices);
    if (rc == FT_OK && in->box_layer)
        rc = group_chains(in->box_layer, g, &box_chains, &nb, &vb);
    if (rc != FT_OK) {
        free(chains);
        return rc;
    }
    json_object *id = g ? json_object_get(g->id) : NULL;
    json_object *info = group_info(g ? g->n : l->nfeatures, n, vertices); /* the report owns it */
    rc = cli_dim_report_group(rep, g != NULL, id, label, info);
    if (rc == FT_OK && n == 0)
        rc = ft_error(FT_E_EMPTY, "%s: no chain of 2 or more vertices to measure", label);
    for (int i = 0; rc == FT_OK && i < nm; i++) {
        ft_dim_result *r = NULL;
        ft_line_dim_opts o = *opts;
        int box = (ms[i] == FT_LINE_BOX || ms[i] == FT_LINE_BOX_MIN) && in->box_layer != NULL;
        o.ellipsoid = in->crs->geographic && !box ? &in->crs->ellipsoid : NULL;
        rc = ft_line_dim(box ? box_chains : chains, box ? nb : n, ms[i], &o, &r);
        if (rc != FT_OK) { /* the message names the line */
            char msg[512];
            snprintf(msg, sizeof msg, "%s", ft_last_error());
            rc = ft_error(rc, "%s, %s: %s", label, ft_line_method_name(ms[i]), msg);
            break;
        }
        r->method = ft_line_method_name(ms[i]);
        if (ms[i] == FT_LINE_DIVIDER && o.starts > 1 && (rc = start_spread(chains, n, &o, r, info)) != FT_OK) {
            ft_dim_result_free(r);
            break;
        }
        cli_geo_units(r, in->crs);
        const char *xl, *yl;
        axis_labels(ms[i], &xl, &yl);
        rc = cli_dim_report_add(rep, r, xl, yl);
    }
    free(chains);
    free(box_chains);
    return rc;
}

/* Scales checked against the data before any work: coordinates whose span cannot be squared in double
 * precision (near 1e-300) are refused, and so is a --min-scale that would walk more rulers or boxes than the
 * work bound allows (about length / min-scale steps per scale and method). */
static int check_scales(const cli_command *cmd, const ft_layer *l, const char *path, const line_args *a, int nm)
{
    double x0, y0, x1, y1, len = 0.0;
    if (ft_layer_bbox(l, &x0, &y0, &x1, &y1) != FT_OK)
        return CLI_CONTINUE; /* empty: measure() says so */
    double span = fmax(x1 - x0, y1 - y0);
    if (span > 0.0 && span < 1e-150) {
        cli_error(cmd, "%s: the lines span only %g units: too small to measure in double precision (rescale the "
                       "coordinates)", path, span);
        return CLI_FAIL;
    }
    for (size_t p = 0; p < l->nparts; p++)
        len += ft_chain_length(l->parts[p].chain);
    if (a->dim.min_scale > 0.0) {
        double nscales = a->dim.nscales > 0 ? a->dim.nscales : 20.0;
        double steps = (double)nm * nscales * len / a->dim.min_scale;
        char what[200];
        if (isfinite(steps))
            snprintf(what, sizeof what, "--min-scale %g on lines %.4g units long (about %.3g rulers)",
                     a->dim.min_scale, len, steps);
        else
            snprintf(what, sizeof what, "--min-scale %g on lines %.4g units long (more rulers than a double counts)",
                     a->dim.min_scale, len);
        if (ft_check_work(steps, what) != FT_OK)
            return cli_fail(cmd);
    }
    return CLI_CONTINUE;
}

static int measure_all(const cli_command *cmd, const line_input *in, const char *path, const line_args *a,
                       const ft_line_method *ms, int nm, cli_dim_report *rep)
{
    const ft_layer *l = in->l;
    if (check_scales(cmd, l, path, a, nm) != CLI_CONTINUE)
        return CLI_FAIL;
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = a->dim.min_scale;
    o.max_scale = a->dim.max_scale;
    o.nscales = a->dim.nscales;
    o.fit_whole_range = a->dim.min_scale > 0.0 && a->dim.max_scale > 0.0;
    o.min_r2 = FT_LINE_R2_FLOOR;
    o.fit.regime = a->dim.regime;
    o.progress = cli_progress();
    o.starts = a->starts;
    if (a->by == NULL)
        return measure(in, NULL, ms, nm, &o, rep, path) == FT_OK ? CLI_OK : cli_fail(cmd);
    line_group *groups = NULL;
    size_t ng = 0;
    if (group_by(l, path, a->by, &groups, &ng) != FT_OK)
        return cli_fail(cmd);
    int rc = CLI_OK;
    for (size_t i = 0; i < ng && rc == CLI_OK; i++) {
        int mrc = measure(in, &groups[i], ms, nm, &o, rep, groups[i].label);
        if (mrc == FT_E_NOMEM || mrc == FT_E_CANCELLED)
            rc = cli_fail(cmd);
        else if (mrc != FT_OK)
            cli_dim_report_group_failed(cmd, rep);
    }
    groups_free(groups, ng);
    if (rc == CLI_OK && cli_dim_report_count(rep) == 0) {
        cli_error(cmd, "no feature of '%s' could be measured", path);
        rc = CLI_FAIL;
    }
    return rc;
}

/* ---- the command ---- */

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    line_args *a = ctx;
    int rc = cli_dim_input_option(cmd, opt, arg, &a->dim, &a->method, &a->layer);
    if (rc != CLI_DIM_NOT_SHARED)
        return rc;
    switch (opt) {
    case 'w': a->where = arg; return CLI_CONTINUE;
    case 'b': a->by = arg; return CLI_CONTINUE;
    case 's': return cli_parse_int(cmd, "--starts", arg, 1, 1000, &a->starts);
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static json_object *extra_members(const char *path, const line_input *in, const char *by)
{
    const ft_layer *l = in->l;
    json_object *o = json_object_new_object();
    json_object_object_add(o, "file", json_object_new_string(path));
    json_object_object_add(o, "layer", l->name ? json_object_new_string(l->name) : NULL);
    if (in->crs->geographic) /* walks on the ellipsoid; boxes in the local equal-area projection */
        json_object_object_add(o, "geographic", cli_geo_json(in->crs, in->box_layer ? in->box_layer->crs_wkt : NULL));
    if (by)
        json_object_object_add(o, "by", json_object_new_string(by));
    return o;
}

static int run_dim_line(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"method", required_argument, NULL, 'm'}, {"layer", required_argument, NULL, 'l'},
        {"where", required_argument, NULL, 'w'},  {"by", required_argument, NULL, 'b'},
        {"starts", required_argument, NULL, 's'},
        CLI_DIM_LONGOPTS,                          CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"INPUT"};
    line_args a = {CLI_DIM_OPTS_DEFAULT, "divider", NULL, NULL, NULL, 1};
    ft_line_method ms[NMETHODS];
    int first = 0, nm = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "m:l:w:b:s:" CLI_DIM_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE)
        rc = cli_dim_check(cmd, &a.dim);
    if (rc == CLI_CONTINUE && (nm = parse_methods(a.method, ms)) == 0)
        rc = cli_usage_error(cmd, "--method must be divider, equipaced, hybrid, box, a comma-separated list of "
                                  "them, or all; got '%s'",
                             a.method);
    for (int i = 0; rc == CLI_CONTINUE && a.starts > 1 && i < nm; i++)
        if (ms[i] != FT_LINE_DIVIDER)
            rc = cli_usage_error(cmd, "--starts %d applies to the divider only, not to the %s", a.starts,
                                 ft_line_method_name(ms[i]));
    if (rc != CLI_CONTINUE)
        return rc;
    const char *path = argv[first];
    if (a.dim.plot && ft_io_check_writable(a.dim.plot) != FT_OK)
        return cli_fail(cmd);
    ft_layer *l = NULL, *box_layer = NULL;
    if ((rc = cli_read_layer(cmd, path, a.layer, a.where, &l)) != CLI_CONTINUE)
        return rc;
    ft_crs_info crs;
    rc = cli_geo_crs(cmd, path, l->crs_wkt, &crs);
    for (int i = 0; rc == CLI_CONTINUE && crs.geographic && i < nm; i++)
        if ((ms[i] == FT_LINE_BOX || ms[i] == FT_LINE_BOX_MIN) && box_layer == NULL)
            rc = cli_geo_layer_local(cmd, path, l, FT_LOCAL_LAEA, &box_layer);
    if (rc != CLI_CONTINUE) {
        ft_layer_free(l);
        return rc;
    }
    line_input in = {l, box_layer, &crs};
    cli_dim_report *rep = cli_dim_report_create(path);
    rc = rep ? measure_all(cmd, &in, path, &a, ms, nm, rep) : (ft_error(FT_E_NOMEM, "out of memory"), cli_fail(cmd));
    if (rc == CLI_OK)
        rc = cli_dim_report_print(cmd, rep, &a.dim, extra_members(path, &in, a.by));
    cli_dim_report_free(rep);
    ft_layer_free(box_layer);
    ft_layer_free(l);
    return rc;
}

const cli_command cli_cmd_dim_line = {
    "dim line",
    "fractal dimension of lines and polygon boundaries",
    "fracterra dim line INPUT [--method divider|equipaced|hybrid|box|all] [--layer NAME] [--where SQL]\n"
    "                          [--by FIELD] [--starts N] [--min-scale S] [--max-scale S] [--scales N]\n"
    "                          [--segments] [--plot FILE] [--json]",
    "Measures the fractal dimension D of the chains (lines, polygon rings) of INPUT, any OGR vector layer\n"
    "or a GMT text file (.gmt, .xy, .txt). The quantity is measured at scales in a geometric series,\n"
    "summed over the chains, and D is read from the widest regime (straight run, by a curvature test) of\n"
    "the log-log plot (docs/loglog.md); every regime, the breaks between them, warnings (curved fit, few\n"
    "boxes or steps, a band under a decade, a chain that looks like a profile: use `dim profile`) and the\n"
    "whole table are reported so the fit can be judged. A D outside [1, 2] is an error (exit 1).\n\n"
    "Methods (docs/line-dimension.md):\n"
    "  divider    walking divider (Richardson): length L(r) ~ r^(1-D), walks from both ends averaged\n"
    "  equipaced  equipaced polygon: the chain resampled at arc-length spacing s, L(s) ~ s^(1-D)\n"
    "  hybrid     hybrid walk (Clarke & Schweizer): divider on the vertices, with interpolation\n"
    "  box        box counting: grid cells crossed N(s) ~ s^-D, mean count over 4 x 4 grid offsets\n"
    "  box-min    the same with the fewest count over the offsets (the literature's; biased upward\n"
    "             where the largest boxes hold few counts)\n"
    "  all        every method above: {\"results\": [...]}\n\n"
    "Options:\n"
    "  -m, --method M       divider (default), equipaced, hybrid, box, a list such as divider,box, or all\n"
    "  -l, --layer NAME     the vector layer to read (default: the first)\n"
    "  -w, --where SQL      only the features matching this OGR attribute filter\n"
    "  -b, --by FIELD       one result per value of FIELD (features sharing a value measured together);\n"
    "                       'fid' gives one result per feature. Default: the whole layer as one set\n"
    "  -s, --starts N       divider on rings: L(r) is the mean of N walks starting at vertices evenly\n"
    "                       spaced along each ring (the first at or after k/N of its length), so that D\n"
    "                       does not hang on the start (Andrle 1992); the JSON's \"starts\" and a line on\n"
    "                       stderr give the D of each start alone over the same rulers: mean, sd, range.\n"
    "                       Default 1: one walk from the first vertex. Open lines: walks from both ends\n"
    CLI_DIM_OPTIONS_HELP
    "  -h, --help           print this help\n"
    "With both --min-scale and --max-scale, D is fitted over every scale between them.\n\n"
    "JSON: {\"file\", \"layer\", \"features\", \"chains\", \"vertices\", \"method\", \"D\", \"r2\", \"stderr\",\n"
    "\"range\": [lo, hi], \"segmentation\", \"max_err\",\n"
    "\"table\": [{\"scale\", \"value\", \"count\", \"slope\", \"used\"}]} (and \"segments\" with --segments);\n"
    "several methods: \"results\": [...]; --by: \"features\": [{\"id\", ...}].\n\n"
    "Examples:\n"
    "  fracterra dim line tests/data/gshhg_newfoundland_utm21n.geojson --plot coast.svg\n"
    "  fracterra dim line states.geojson --by code --method all --json | jq '.features[].results[].D'\n",
    run_dim_line,
};
