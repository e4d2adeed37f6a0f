/* fracterra — cli/urban_table.c: `fracterra urban table LAYER...`: one row per input (a year's land-use
 * map), one group of columns per class of --class FIELD: the box-counting dimension D with its standard
 * error, the area of the class and its number of polygons (Zhang, Yu & Fan 2008, Tables 1 and 2), plus the
 * same for the whole layer. CSV or JSON, on stdout or to -o, and a chart of D per class against the rows.
 *
 * Classes are listed in the order they first appear (the first input's sorted, then the new ones of each
 * following input); a class absent from an input has empty cells (null in JSON), one that cannot be
 * measured an empty D and its "error" in the JSON. Outputs are written under temporary names; if one fails,
 * none is left behind.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "urban_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

typedef struct {
    urban_box_args box;
    const char *cls, *out, *chart, *layer, *where;
    const char **labels; /* --label values, in order */
    size_t nlabels;
    int json;
} table_args;

/* What one set of one input gave. */
typedef struct {
    int present;  /* the input has this class */
    double D, stderr_D, area;
    size_t polygons;
    char *error;  /* why D is missing */
} table_cell;

/* The table: rows x (whole layer + classes); cells[row * (1 + ncap) + 1 + class], class columns added as
 * classes appear (the matrix is regrown then). */
typedef struct {
    char **classes;
    size_t nclasses, ncap;
    size_t nrows;
    char **labels, **files; /* per row, labels owned */
    table_cell *cells;
    size_t row; /* the row being measured */
} urban_tab;

/* ---- the table in memory ---- */

static table_cell *cell_at(const urban_tab *t, size_t row, size_t col)
{
    return &t->cells[row * (1 + t->ncap) + col];
}

static void tab_free(urban_tab *t)
{
    for (size_t r = 0; t->cells && r < t->nrows; r++)
        for (size_t c = 0; c <= t->nclasses; c++)
            free(cell_at(t, r, c)->error);
    for (size_t i = 0; i < t->nclasses; i++)
        free(t->classes[i]);
    for (size_t r = 0; t->labels && r < t->nrows; r++)
        free(t->labels[r]);
    free(t->classes);
    free(t->labels);
    free(t->files);
    free(t->cells);
}

/* Doubles the class capacity, moving every row's cells to the wider layout. */
static int tab_widen(urban_tab *t)
{
    size_t ncap = t->ncap ? 2 * t->ncap : 8;
    table_cell *cells = calloc(t->nrows * (1 + ncap), sizeof *cells);
    char **classes = realloc(t->classes, ncap * sizeof *classes);
    if (cells == NULL || classes == NULL) {
        free(cells);
        t->classes = classes ? classes : t->classes;
        return ft_error(FT_E_NOMEM, "out of memory");
    }
    for (size_t r = 0; t->cells && r < t->nrows; r++)
        memcpy(&cells[r * (1 + ncap)], cell_at(t, r, 0), (1 + t->ncap) * sizeof *cells);
    free(t->cells);
    t->cells = cells;
    t->classes = classes;
    t->ncap = ncap;
    return FT_OK;
}

/* The column of a class (0 = the whole layer), added if new. */
static int tab_column(urban_tab *t, const char *label, size_t *col)
{
    if (label == NULL) {
        *col = 0;
        return FT_OK;
    }
    for (size_t i = 0; i < t->nclasses; i++)
        if (strcmp(t->classes[i], label) == 0) {
            *col = i + 1;
            return FT_OK;
        }
    if (t->nclasses == FT_URBAN_MAX_CLASSES)
        return ft_error(FT_E_INVALID, "more than %d classes: is --class a land-use field?", FT_URBAN_MAX_CLASSES);
    int rc = t->nclasses == t->ncap ? tab_widen(t) : FT_OK;
    char *copy = rc == FT_OK ? strdup(label) : NULL;
    if (copy == NULL)
        return rc != FT_OK ? rc : ft_error(FT_E_NOMEM, "out of memory");
    t->classes[t->nclasses++] = copy;
    *col = t->nclasses;
    return FT_OK;
}

/* Records one measured set of the current row. */
static int add_set(const urban_set *s, ft_dim_result *r, void *arg)
{
    urban_tab *t = arg;
    size_t col = 0;
    int rc = tab_column(t, s->label, &col);
    if (rc != FT_OK) {
        ft_dim_result_free(r);
        return rc;
    }
    table_cell *c = cell_at(t, t->row, col);
    *c = (table_cell){1, r ? r->D : NAN, r ? r->stderr_D : NAN, s->stats->area, s->stats->npolygons, NULL};
    if (r == NULL && (c->error = strdup(ft_last_error())) == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    ft_dim_result_free(r);
    return FT_OK;
}

/* "lu1959" for "data/lu1959.gpkg". */
static char *file_stem(const char *path)
{
    const char *slash = strrchr(path, '/'), *base = slash ? slash + 1 : path, *dot = strrchr(base, '.');
    size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    char *s = malloc(n + 1);
    if (s)
        snprintf(s, n + 1, "%.*s", (int)n, base);
    return s;
}

static int tab_init(urban_tab *t, char **inputs, size_t n, const table_args *a)
{
    memset(t, 0, sizeof *t);
    t->nrows = n;
    t->labels = calloc(n, sizeof *t->labels);
    t->files = calloc(n, sizeof *t->files);
    int rc = t->labels && t->files ? tab_widen(t) : ft_error(FT_E_NOMEM, "out of memory");
    for (size_t i = 0; rc == FT_OK && i < n; i++) {
        t->files[i] = inputs[i];
        t->labels[i] = a->nlabels ? strdup(a->labels[i]) : file_stem(inputs[i]);
        if (t->labels[i] == NULL)
            rc = ft_error(FT_E_NOMEM, "out of memory");
    }
    return rc;
}

/* ---- measuring ---- */

static int measure_row(const cli_command *cmd, urban_tab *t, const table_args *a)
{
    ft_layer *l = NULL;
    const char *path = t->files[t->row];
    int rc = cli_read_layer(cmd, path, a->layer, a->where, &l);
    if (rc != CLI_CONTINUE)
        return rc;
    size_t rings = 0;
    for (size_t i = 0; i < l->nparts; i++)
        rings += l->parts[i].role != FT_ROLE_LINE;
    if (rings == 0) {
        cli_error(cmd, "%s holds no polygon (%zu line part%s): urban table measures land-use polygons", path,
                  l->nparts, l->nparts == 1 ? "" : "s");
        ft_layer_free(l);
        return CLI_FAIL;
    }
    ft_crs_info crs; /* lon/lat: areas and boxes in a local equal-area projection, m and m² */
    if ((rc = cli_geo_layer_ground(cmd, path, l, FT_LOCAL_LAEA, &crs)) != CLI_CONTINUE) {
        ft_layer_free(l);
        return rc;
    }
    ft_area_dim_opts o = a->box.dim;
    o.fit_whole_range = o.ncells > 0;
    o.progress = cli_progress();
    if (urban_measure_layer(l, a->cls, 1, &o, add_set, t) != FT_OK)
        rc = cli_fail(cmd);
    else if (!cell_at(t, t->row, 0)->present || isnan(cell_at(t, t->row, 0)->D))
        cli_warn(cmd, "%s: the whole layer could not be measured: %s", path,
                 cell_at(t, t->row, 0)->error ? cell_at(t, t->row, 0)->error : "no polygon");
    ft_layer_free(l);
    return rc;
}

/* ---- CSV ---- */

/* ",v" with digits significant digits (areas with every digit, not in exponent form), or "," if missing. */
static void csv_number(FILE *f, double v, int digits)
{
    if (isfinite(v))
        fprintf(f, ",%.*g", digits, v);
    else
        fputc(',', f);
}

static void csv_cells(FILE *f, const table_cell *c)
{
    csv_number(f, c->present ? c->D : NAN, 10);
    csv_number(f, c->present ? c->stderr_D : NAN, 6);
    csv_number(f, c->present ? c->area : NAN, 15);
    csv_number(f, c->present ? (double)c->polygons : NAN, 15);
}

static int write_csv(FILE *f, const void *arg)
{
    const urban_tab *t = arg;
    static const char *const measures[] = URBAN_MEASURES;
    fputs("label,file", f);
    for (size_t k = 0; k <= t->nclasses; k++)
        for (size_t m = 0; m < URBAN_NMEASURES; m++) {
            char col[512];
            urban_column_name(k ? t->classes[k - 1] : NULL, measures[m], col, sizeof col);
            fputc(',', f);
            urban_csv_field(f, col);
        }
    fputc('\n', f);
    for (size_t r = 0; r < t->nrows; r++) {
        urban_csv_field(f, t->labels[r]);
        fputc(',', f);
        urban_csv_field(f, t->files[r]);
        for (size_t k = 0; k <= t->nclasses; k++)
            csv_cells(f, cell_at(t, r, k));
        fputc('\n', f);
    }
    return ferror(f) ? FT_E_IO : FT_OK;
}

/* ---- JSON ---- */

static json_object *cell_json(const table_cell *c)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "D", cli_json_double(c->D));
    json_object_object_add(o, "stderr", cli_json_double(c->stderr_D));
    json_object_object_add(o, "area", cli_json_double(c->area));
    json_object_object_add(o, "polygons", json_object_new_int64((int64_t)c->polygons));
    if (c->error)
        json_object_object_add(o, "error", json_object_new_string(c->error));
    return o;
}

static json_object *row_json(const urban_tab *t, size_t r)
{
    json_object *o = cell_json(cell_at(t, r, 0)), *classes = json_object_new_object();
    json_object *head = json_object_new_object();
    json_object_object_add(head, "label", json_object_new_string(t->labels[r]));
    json_object_object_add(head, "file", json_object_new_string(t->files[r]));
    json_object_object_foreach(o, key, val) json_object_object_add(head, key, json_object_get(val));
    json_object_put(o);
    for (size_t k = 1; k <= t->nclasses; k++) {
        const table_cell *c = cell_at(t, r, k);
        json_object_object_add(classes, t->classes[k - 1], c->present ? cell_json(c) : NULL);
    }
    json_object_object_add(head, "classes", classes);
    return head;
}

static json_object *tab_json(const urban_tab *t, const table_args *a)
{
    json_object *o = json_object_new_object(), *classes = json_object_new_array(), *rows = json_object_new_array();
    json_object_object_add(o, "class", json_object_new_string(a->cls));
    json_object_object_add(o, "what", json_object_new_string(ft_area_what_name(a->box.dim.what)));
    json_object_object_add(o, "offsets", json_object_new_int(a->box.dim.offsets));
    json_object_object_add(o, "fewest_boxes", json_object_new_boolean(a->box.dim.fewest));
    for (size_t k = 0; k < t->nclasses; k++)
        json_object_array_add(classes, json_object_new_string(t->classes[k]));
    json_object_object_add(o, "classes", classes);
    for (size_t r = 0; r < t->nrows; r++)
        json_object_array_add(rows, row_json(t, r));
    json_object_object_add(o, "rows", rows);
    return o;
}

static int write_json(FILE *f, const void *arg)
{
    return cli_json_fput((json_object *)arg, f);
}

static int has_ext(const char *path, const char *ext)
{
    const char *slash = strrchr(path, '/'), *dot = strrchr(slash ? slash : path, '.');
    return dot && strcasecmp(dot, ext) == 0;
}

/* ---- chart ---- */

/* x of each row: the labels as numbers when they all are (years), else NULL (a category axis). */
static double *numeric_labels(const urban_tab *t)
{
    double *x = malloc(t->nrows * sizeof *x);
    for (size_t r = 0; x && r < t->nrows; r++) {
        char *end = NULL;
        x[r] = strtod(t->labels[r], &end);
        if (end == t->labels[r] || *end != '\0' || !isfinite(x[r])) {
            free(x);
            return NULL;
        }
    }
    return x;
}

static int write_chart(const urban_tab *t, const table_args *a)
{
    ft_series *s = calloc(t->nclasses, sizeof *s);
    double *y = malloc(t->nclasses * t->nrows * sizeof *y), *x = numeric_labels(t);
    double *cat = x ? NULL : malloc(t->nrows * sizeof *cat);
    int rc = s && y && (x || cat) ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
    for (size_t r = 0; rc == FT_OK && cat && r < t->nrows; r++)
        cat[r] = (double)r;
    for (size_t k = 0; rc == FT_OK && k < t->nclasses; k++) {
        for (size_t r = 0; r < t->nrows; r++)
            y[k * t->nrows + r] = cell_at(t, r, k + 1)->present ? cell_at(t, r, k + 1)->D : NAN;
        s[k] = (ft_series){t->classes[k], x ? x : cat, y + k * t->nrows, t->nrows};
    }
    char title[300], ylabel[64];
    snprintf(title, sizeof title, "Box-counting dimension per class of %s", a->cls);
    snprintf(ylabel, sizeof ylabel, "D (%s)", ft_area_what_name(a->box.dim.what));
    ft_chart_opts o = FT_CHART_OPTS_DEFAULT;
    o.title = title;
    o.xlabel = x ? "year" : "input";
    o.ylabel = ylabel;
    o.xcategories = x ? NULL : (const char *const *)t->labels;
    o.ncategories = x ? 0 : t->nrows;
    if (rc == FT_OK)
        rc = ft_render_series_chart(s, t->nclasses, a->chart, &o);
    free(s);
    free(y);
    free(x);
    free(cat);
    return rc;
}

/* Writes the chart, then the table file; stdout gets the table (no -o), or the report. */
static int write_outputs(const cli_command *cmd, const urban_tab *t, const table_args *a)
{
    if (a->chart && t->nclasses > 0 && write_chart(t, a) != FT_OK)
        return cli_fail(cmd);
    json_object *o = tab_json(t, a);
    int rc = FT_OK;
    if (a->out)
        rc = has_ext(a->out, ".json") ? cli_write_file(a->out, write_json, o) : cli_write_file(a->out, write_csv, t);
    if (rc != FT_OK) {
        if (a->chart)
            unlink(a->chart);
        json_object_put(o);
        return cli_fail(cmd);
    }
    if (a->json) {
        json_object_object_add(o, "output", a->out ? json_object_new_string(a->out) : NULL);
        json_object_object_add(o, "chart", a->chart && t->nclasses ? json_object_new_string(a->chart) : NULL);
        return cli_print_json(cmd, o);
    }
    json_object_put(o);
    if (a->out == NULL && write_csv(stdout, t) != FT_OK) {
        cli_error(cmd, "cannot write to standard output: %s", strerror(errno));
        return CLI_FAIL;
    }
    if (a->out == NULL)
        return CLI_OK;
    printf("wrote %s: %zu rows, %zu classes of %s\n", a->out, t->nrows, t->nclasses, a->cls);
    if (a->chart && t->nclasses)
        printf("wrote %s\n", a->chart);
    return CLI_OK;
}

/* ---- the command ---- */

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    table_args *a = ctx;
    int rc = urban_box_option(cmd, opt, arg, &a->box);
    if (rc != URBAN_NOT_SHARED)
        return rc;
    switch (opt) {
    case 'c': a->cls = arg; return CLI_CONTINUE;
    case 'L': a->labels[a->nlabels++] = arg; return CLI_CONTINUE;
    case 'o': a->out = arg; return CLI_CONTINUE;
    case 'C': a->chart = arg; return CLI_CONTINUE;
    case 'l': a->layer = arg; return CLI_CONTINUE;
    case 'w': a->where = arg; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int check_outputs(const cli_command *cmd, const table_args *a)
{
    if (a->out && !has_ext(a->out, ".csv") && !has_ext(a->out, ".json"))
        return cli_usage_error(cmd, "-o file must end in .csv or .json, got '%s'", a->out);
    if (a->chart && !has_ext(a->chart, ".png") && !has_ext(a->chart, ".svg") && !has_ext(a->chart, ".pdf"))
        return cli_usage_error(cmd, "--chart file must end in .png, .svg or .pdf, got '%s'", a->chart);
    if ((a->out && ft_io_check_writable(a->out) != FT_OK) || (a->chart && ft_io_check_writable(a->chart) != FT_OK))
        return cli_fail(cmd);
    return CLI_CONTINUE;
}

static int check_args(const cli_command *cmd, const table_args *a, int ninputs)
{
    if (ninputs < 1)
        return cli_usage_error(cmd, "missing LAYER");
    if (a->cls == NULL)
        return cli_usage_error(cmd, "missing --class FIELD");
    if (a->nlabels && a->nlabels != (size_t)ninputs)
        return cli_usage_error(cmd, "%zu --label given for %d inputs: give one per input, or none", a->nlabels,
                               ninputs);
    if (a->box.dim.ncells > 0 && a->box.dim.ncells < 3)
        return cli_usage_error(cmd, "--cell: give at least 3 box sides to fit a line, got %zu", a->box.dim.ncells);
    return check_outputs(cmd, a);
}

static int run_table(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"class", required_argument, NULL, 'c'}, {"label", required_argument, NULL, 'L'},
        {"output", required_argument, NULL, 'o'}, {"chart", required_argument, NULL, 'C'},
        {"layer", required_argument, NULL, 'l'}, {"where", required_argument, NULL, 'w'},
        {"json", no_argument, NULL, 'j'},        URBAN_BOX_LONGOPTS,
        CLI_OPT_HELP,                            CLI_OPT_END,
    };
    table_args a = {.labels = calloc((size_t)argc, sizeof(const char *))};
    urban_box_init(&a.box);
    urban_tab t = {0};
    int first = 0;
    int rc = a.labels ? cli_parse_options(cmd, argc, argv, longopts, "c:o:l:w:j", on_option, &a, &first) : CLI_FAIL;
    if (rc == CLI_CONTINUE)
        rc = check_args(cmd, &a, argc - first);
    if (rc == CLI_CONTINUE && tab_init(&t, argv + first, (size_t)(argc - first), &a) != FT_OK)
        rc = cli_fail(cmd);
    for (t.row = 0; rc == CLI_CONTINUE && t.row < t.nrows; t.row++)
        rc = measure_row(cmd, &t, &a);
    if (rc == CLI_CONTINUE)
        rc = write_outputs(cmd, &t, &a);
    tab_free(&t);
    free(a.labels);
    return rc;
}

const cli_command cli_cmd_urban_table = {
    "urban table",
    "per-year table of D, area and polygons per land-use class",
    "fracterra urban table LAYER... --class FIELD [--label L ...] [-o TABLE.csv|.json] [--chart FILE]\n"
    "                      [--what boundary|area] [--cell SIZE ...] [--offsets K] [--layer NAME] [--where SQL]\n"
    "                      [--json]",
    "Measures each LAYER (one land-use map per year, as Zhang, Yu & Fan 2008 do for Wuhan) class by class\n"
    "and writes one row per LAYER: its label and file, then D, its standard error, the area and the number of\n"
    "polygons of the whole layer, then the same for each class of FIELD (columns CLASS.D, CLASS.stderr,\n"
    "CLASS.area, CLASS.polygons). D is the box-counting dimension of `fracterra dim area` (the same options);\n"
    "areas are in squared map units. A class absent from a layer has empty cells. `fracterra urban regress`\n"
    "reads the table back. Method: docs/urban-boxcount.md.\n\n"
    "Options:\n"
    "  -c, --class FIELD    the land-use field (required)\n"
    "      --label L        the label of each LAYER, in order (a year); default: the file names' stems\n"
    "  -o, --output FILE    write the table to FILE.csv or FILE.json (default: CSV on stdout)\n"
    "      --chart FILE     draw D per class against the labels to FILE.png, .svg or .pdf\n"
    "  -l, --layer NAME     the vector layer to read in each file (default: the first)\n"
    "  -w, --where SQL      only the features matching this OGR attribute filter\n" URBAN_BOX_HELP
    "  -j, --json           print the table as JSON on stdout, with \"output\" and \"chart\":\n"
    "                       {\"class\", \"what\", \"classes\": [...], \"rows\": [{\"label\", \"file\",\n"
    "                       \"D\", \"stderr\", \"area\", \"polygons\", \"classes\": {CLASS: {\"D\",\n"
    "                       \"stderr\", \"area\", \"polygons\"}}}]}\n"
    "  -h, --help           print this help\n\n"
    "Example:\n"
    "  fracterra urban table lu1959.gpkg lu1980.gpkg lu1989.gpkg lu1997.gpkg --class use \\\n"
    "      --label 1959 --label 1980 --label 1989 --label 1997 -o wuhan.csv --chart wuhan-d.png\n",
    run_table,
};
