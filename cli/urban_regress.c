/* fracterra — cli/urban_regress.c: `fracterra urban regress TABLE`: least squares of one column of a per-year
 * table on another (ft_urban_regress), as Zhang, Yu & Fan (2008, Eq. 5) relate ln(area) of the residential
 * class to its box-counting dimension across years: slope, intercept, r and their standard errors.
 *
 * TABLE is what `urban table` writes (CSV or JSON; --class picks a class's columns) or any CSV with the two
 * columns. Rows where either value is empty, NA or null are skipped and counted.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "urban_cli.h"

#include <math.h>
#include <stdio.h>

typedef struct {
    const char *x, *y, *cls;
    int log_y, json;
} regress_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    regress_args *a = ctx;
    switch (opt) {
    case 'x': a->x = arg; return CLI_CONTINUE;
    case 'y': a->y = arg; return CLI_CONTINUE;
    case 'c': a->cls = arg; return CLI_CONTINUE;
    case 'L': a->log_y = 1; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* "ln(area)" or "area", prefixed by the class: "ln(residential.area)". */
static void y_name(const regress_args *a, char *buf, size_t size)
{
    char col[256];
    urban_column_name(a->cls, a->y, col, sizeof col);
    if (a->log_y)
        snprintf(buf, size, "ln(%s)", col);
    else
        snprintf(buf, size, "%s", col);
}

/* "ln(residential.area) = -0.0188 + 8.72 residential.D". */
static void equation(const regress_args *a, const ft_urban_regression *r, char *buf, size_t size)
{
    char y[300], x[256];
    y_name(a, y, sizeof y);
    urban_column_name(a->cls, a->x, x, sizeof x);
    snprintf(buf, size, "%s = %.6g %s %.6g %s", y, r->intercept, r->slope < 0 ? "-" : "+", fabs(r->slope), x);
}

static json_object *report_json(const char *path, const regress_args *a, size_t skipped,
                                const ft_urban_regression *r)
{
    char y[300], eq[700], x[256];
    y_name(a, y, sizeof y);
    urban_column_name(a->cls, a->x, x, sizeof x);
    equation(a, r, eq, sizeof eq);
    json_object *o = json_object_new_object();
    json_object_object_add(o, "file", json_object_new_string(path));
    json_object_object_add(o, "class", a->cls ? json_object_new_string(a->cls) : NULL);
    json_object_object_add(o, "x", json_object_new_string(x));
    json_object_object_add(o, "y", json_object_new_string(y));
    json_object_object_add(o, "log_y", json_object_new_boolean(a->log_y));
    json_object_object_add(o, "n", json_object_new_int64((int64_t)r->n));
    json_object_object_add(o, "rows_skipped", json_object_new_int64((int64_t)skipped));
    json_object_object_add(o, "equation", json_object_new_string(eq));
    json_object_object_add(o, "slope", cli_json_double(r->slope));
    json_object_object_add(o, "intercept", cli_json_double(r->intercept));
    json_object_object_add(o, "r", cli_json_double(r->r));
    json_object_object_add(o, "r2", cli_json_double(r->r2));
    json_object_object_add(o, "stderr_slope", cli_json_double(r->stderr_slope));
    json_object_object_add(o, "stderr_intercept", cli_json_double(r->stderr_intercept));
    json_object_object_add(o, "stderr_r", cli_json_double(r->stderr_r));
    json_object_object_add(o, "t", cli_json_double(r->t));
    json_object_object_add(o, "p_value", cli_json_double(r->p_value));
    return o;
}

static void print_human(const char *path, const regress_args *a, size_t skipped, const ft_urban_regression *r)
{
    char eq[700];
    equation(a, r, eq, sizeof eq);
    printf("%-10s %s: %zu rows", "table", path, r->n);
    if (skipped > 0)
        printf(" (%zu more skipped: a value missing)", skipped);
    printf("\n%-10s %s\n", "fit", eq);
    printf("%-10s %.6g \xc2\xb1 %.4g\n", "slope", r->slope, r->stderr_slope);
    printf("%-10s %.6g \xc2\xb1 %.4g\n", "intercept", r->intercept, r->stderr_intercept);
    printf("%-10s %.4f \xc2\xb1 %.4f   r\xc2\xb2 = %.4f   t = %.3f   p = %.4g\n", "r", r->r, r->stderr_r, r->r2, r->t,
           r->p_value);
}

static int run_regress(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"x", required_argument, NULL, 'x'},     {"y", required_argument, NULL, 'y'},
        {"class", required_argument, NULL, 'c'}, {"log-y", no_argument, NULL, 'L'},
        {"json", no_argument, NULL, 'j'},        CLI_OPT_HELP,
        CLI_OPT_END,
    };
    static const char *const names[] = {"TABLE"};
    regress_args a = {"D", "area", NULL, 0, 0};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "x:y:c:j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc != CLI_CONTINUE)
        return rc;
    const char *path = argv[first];
    const char *const measures[2] = {a.x, a.y};
    urban_columns c;
    ft_urban_regression r;
    if (urban_columns_read(path, a.cls, measures, &c) != FT_OK)
        return cli_fail(cmd);
    rc = ft_urban_regress(c.v[0], c.v[1], c.n, a.log_y, &r);
    urban_columns_free(&c);
    if (rc != FT_OK) {
        cli_error(cmd, "%s: %s", path, ft_last_error());
        return CLI_FAIL;
    }
    if (a.json)
        return cli_print_json(cmd, report_json(path, &a, c.skipped, &r));
    print_human(path, &a, c.skipped, &r);
    return CLI_OK;
}

const cli_command cli_cmd_urban_regress = {
    "urban regress",
    "least squares of one table column on another (ln area on D, Eq. 5)",
    "fracterra urban regress TABLE [--x COLUMN] [--y COLUMN] [--log-y] [--class NAME] [--json]",
    "Fits y = intercept + slope x by least squares over the rows of TABLE (with --log-y, ln y instead of\n"
    "y) and prints the slope and intercept with their standard errors, the correlation coefficient r with\n"
    "its standard error sqrt((1 - r\xc2\xb2)/(n - 2)), t and the two-sided p value (n - 2 degrees of freedom).\n"
    "Zhang, Yu & Fan (2008) relate the area of Wuhan's residential land to its box-counting dimension across\n"
    "four years this way (Eq. 5, r = 0.95). Method: docs/urban-boxcount.md.\n\n"
    "TABLE is the CSV or JSON that `fracterra urban table` writes, or any CSV with a header row (separated\n"
    "by commas, semicolons or tabs; with semicolons a decimal comma is read: 1,36 = 1.36). With\n"
    "--class NAME the columns are NAME.COLUMN (residential.D, residential.area), else COLUMN itself (the\n"
    "whole layer's, or any CSV's). Rows where a value is empty, NA or null are skipped; at least 3 are needed.\n\n"
    "Options:\n"
    "  -x, --x COLUMN     the explanatory column; default D\n"
    "  -y, --y COLUMN     the response column; default area\n"
    "      --log-y        regress ln y (every y > 0) instead of y\n"
    "  -c, --class NAME   use the columns of class NAME of an `urban table` table\n"
    "  -j, --json         print {\"file\", \"class\", \"x\", \"y\", \"log_y\", \"n\", \"rows_skipped\", \"equation\",\n"
    "                     \"slope\", \"intercept\", \"r\", \"r2\", \"stderr_slope\", \"stderr_intercept\",\n"
    "                     \"stderr_r\", \"t\", \"p_value\"}\n"
    "  -h, --help         print this help\n\n"
    "Examples:\n"
    "  fracterra urban table lu1959.gpkg lu1980.gpkg lu1997.gpkg --class use -o wuhan.csv\n"
    "  fracterra urban regress wuhan.csv --class residential --x D --y area --log-y\n",
    run_regress,
};
