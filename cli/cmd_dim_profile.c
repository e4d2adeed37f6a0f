/* fracterra — cli/cmd_dim_profile.c: `fracterra dim profile INPUT`: the fractal dimension of a 1-D elevation
 * profile (D = 2 - H, in [1, 2]) by the variogram and madogram estimators of Gneiting, Sevcikova & Percival
 * (2012) (ft_profile_dim; docs/profile.md). The profile is a 3-D line's z along its horizontal length, a
 * row of a DEM (--row) or a transect between two points across a DEM (--from X,Y --to X,Y), printed by
 * the shared dimension printer (dim_output.h).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "dim_output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    cli_dim_opts dim;
    const char *method, *layer;
    int band, row; /* row -1: not given */
    int has_from, has_to;
    double from[2], to[2];
    double spacing; /* 3-D line: 0 = the median segment */
} profile_args;

static int parse_point(const cli_command *cmd, const char *opt, const char *arg, double *xy)
{
    char *end = NULL;
    xy[0] = strtod(arg, &end);
    if (end == arg || *end != ',')
        return cli_usage_error(cmd, "%s must be X,Y, got '%s'", opt, arg);
    const char *second = end + 1;
    xy[1] = strtod(second, &end);
    if (end == second || *end != '\0' || !isfinite(xy[0]) || !isfinite(xy[1]))
        return cli_usage_error(cmd, "%s must be X,Y (two finite numbers), got '%s'", opt, arg);
    return CLI_CONTINUE;
}

enum { OPT_ROW = 0x400, OPT_FROM, OPT_TO, OPT_SPACING };

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    profile_args *a = ctx;
    int rc = cli_dim_input_option(cmd, opt, arg, &a->dim, &a->method, &a->layer);
    if (rc != CLI_DIM_NOT_SHARED)
        return rc;
    switch (opt) {
    case 'b': return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->band);
    case OPT_ROW: return cli_parse_int(cmd, "--row", arg, 0, 2147483647L, &a->row);
    case OPT_FROM: a->has_from = 1; return parse_point(cmd, "--from", arg, a->from);
    case OPT_TO: a->has_to = 1; return parse_point(cmd, "--to", arg, a->to);
    case OPT_SPACING: return cli_parse_double(cmd, "--spacing", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->spacing);
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int check_args(const cli_command *cmd, const profile_args *a)
{
    if (a->has_from != a->has_to)
        return cli_usage_error(cmd, "--from and --to go together");
    if (a->has_from && a->row >= 0)
        return cli_usage_error(cmd, "give either --row or --from/--to, not both");
    if (a->dim.min_scale > 0.0 || a->dim.max_scale > 0.0 || a->dim.nscales > 0 || a->dim.regime > 0)
        return cli_usage_error(cmd, "the estimators use lags 1 and 2 of the profile: --min-scale, --max-scale, "
                               "--scales and --regime do not apply (use --spacing on a 3-D line)");
    return CLI_CONTINUE;
}

/* The profile: a DEM row or transect, or a 3-D line. *source names it for the JSON. */
static int read_profile(const cli_command *cmd, const char *path, const profile_args *a, double **z, size_t *n,
                        double *spacing, const char **source)
{
    int rc;
    if (a->row >= 0 || a->has_from) {
        ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
        ro.band = a->band;
        ft_grid *g = NULL;
        if (ft_io_read_grid(path, &ro, &g) != FT_OK)
            return cli_fail(cmd);
        rc = a->row >= 0 ? ft_profile_from_grid_row(g, (size_t)a->row, z, n, spacing)
                         : ft_profile_transect(g, a->from[0], a->from[1], a->to[0], a->to[1], z, n, spacing);
        *source = a->row >= 0 ? "row" : "transect";
        ft_grid_free(g);
        return rc == FT_OK ? CLI_CONTINUE : cli_fail(cmd);
    }
    double *x = NULL, *y = NULL, *zz = NULL;
    size_t m = 0;
    rc = ft_io_read_line_z(path, a->layer, &x, &y, &zz, &m);
    if (rc == FT_OK)
        rc = ft_profile_resample(x, y, zz, m, a->spacing, z, n, spacing);
    free(x);
    free(y);
    free(zz);
    *source = "line";
    return rc == FT_OK ? CLI_CONTINUE : cli_fail(cmd);
}

static json_object *extra_members(const char *path, const profile_args *a, const char *source, size_t n,
                                  double spacing)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "file", json_object_new_string(path));
    json_object_object_add(o, "profile", json_object_new_string(source));
    if (a->row >= 0)
        json_object_object_add(o, "row", json_object_new_int(a->row));
    if (a->has_from) {
        json_object *f = json_object_new_array(), *t = json_object_new_array();
        json_object_array_add(f, cli_json_double(a->from[0]));
        json_object_array_add(f, cli_json_double(a->from[1]));
        json_object_array_add(t, cli_json_double(a->to[0]));
        json_object_array_add(t, cli_json_double(a->to[1]));
        json_object_object_add(o, "from", f);
        json_object_object_add(o, "to", t);
    }
    json_object_object_add(o, "samples", json_object_new_int64((int64_t)n));
    json_object_object_add(o, "spacing", cli_json_double(spacing));
    if (strcmp(a->method, "both") == 0) /* one method: its result names it */
        json_object_object_add(o, "method", json_object_new_string("both"));
    return o;
}

static int run_dim_profile(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"method", required_argument, NULL, 'm'}, {"layer", required_argument, NULL, 'l'},
        {"band", required_argument, NULL, 'b'},   {"row", required_argument, NULL, OPT_ROW},
        {"from", required_argument, NULL, OPT_FROM}, {"to", required_argument, NULL, OPT_TO},
        {"spacing", required_argument, NULL, OPT_SPACING}, CLI_DIM_LONGOPTS, CLI_OPT_HELP, CLI_OPT_END,
    };
    static const char *const names[] = {"INPUT"};
    profile_args a = {CLI_DIM_OPTS_DEFAULT, "both", NULL, 1, -1, 0, 0, {0, 0}, {0, 0}, 0.0};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "m:l:b:" CLI_DIM_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE)
        rc = cli_dim_check(cmd, &a.dim);
    if (rc == CLI_CONTINUE)
        rc = check_args(cmd, &a);
    ft_profile_method ms[2];
    int nm = 0;
    if (rc == CLI_CONTINUE && strcmp(a.method, "both") == 0) {
        ms[nm++] = FT_PROFILE_MADOGRAM;
        ms[nm++] = FT_PROFILE_VARIOGRAM;
    } else if (rc == CLI_CONTINUE) {
        if (ft_profile_method_parse(a.method, &ms[nm++]) != FT_OK)
            rc = cli_usage_error(cmd, "--method must be madogram, variogram or both, got '%s'", a.method);
    }
    if (rc != CLI_CONTINUE)
        return rc;
    const char *path = argv[first], *source = "";
    if (a.dim.plot && ft_io_check_writable(a.dim.plot) != FT_OK)
        return cli_fail(cmd);
    double *z = NULL, spacing = 0.0;
    size_t n = 0;
    if ((rc = read_profile(cmd, path, &a, &z, &n, &spacing, &source)) != CLI_CONTINUE)
        return rc;
    cli_dim_report *rep = cli_dim_report_create(path);
    rc = rep && cli_dim_report_group(rep, 0, NULL, path, NULL) == FT_OK ? CLI_OK
                                                                          : (ft_error(FT_E_NOMEM, "out of memory"), cli_fail(cmd));
    for (int i = 0; rc == CLI_OK && i < nm; i++) {
        ft_dim_result *r = NULL;
        if (ft_profile_dim(z, n, spacing, ms[i], &r) != FT_OK ||
            cli_dim_report_add(rep, r, "lag", ms[i] == FT_PROFILE_MADOGRAM ? "madogram" : "variogram") != FT_OK)
            rc = cli_fail(cmd);
    }
    if (rc == CLI_OK)
        rc = cli_dim_report_print(cmd, rep, &a.dim, extra_members(path, &a, source, n, spacing));
    cli_dim_report_free(rep);
    free(z);
    return rc;
}

const cli_command cli_cmd_dim_profile = {
    "dim profile",
    "fractal dimension of an elevation profile (madogram, variogram)",
    "fracterra dim profile INPUT [--row N | --from X,Y --to X,Y] [--method madogram|variogram|both]\n"
    "                            [--band N] [--layer NAME] [--spacing S] [--plot FILE] [--json]",
    "Measures the fractal dimension D (1..2) of a 1-D elevation profile, the graph of z against distance,\n"
    "which is self-affine: D = 2 - H. Dividers and boxes do not measure such a graph (`dim line` warns when\n"
    "it sees one). The estimators are those of Gneiting, Sevcikova & Percival (2012), from the power\n"
    "variation V_p(l) = 1/(2(n-l)) sum |z(i+l) - z(i)|^p at lags 1 and 2:\n"
    "D = 2 - (log V_p(2) - log V_p(1)) / (p log 2); madogram p = 1, variogram p = 2 (docs/profile.md;\n"
    "measured on exact fBm profiles: RMSE 0.03 at n = 1024, 0.015 at n = 4096, bias under 0.005).\n\n"
    "The profile is:\n"
    "  a 3-D line (any OGR vector file): z resampled along the horizontal length at --spacing S\n"
    "              (default: the median horizontal segment)\n"
    "  --row N     row N (0 = top) of a DEM, at the DEM's x cell size\n"
    "  --from X,Y --to X,Y   a transect across a DEM (map coordinates), bilinear at the smaller cell side\n\n"
    "Options:\n"
    "  -m, --method M       madogram, variogram or both (default: both)\n"
    "  -b, --band N         band of the DEM (default 1)\n"
    "  -l, --layer NAME     the vector layer holding the 3-D line (default: the first)\n"
    "      --spacing S      3-D line: sample spacing in map units\n"
    "      --plot FILE      draw the log-log plot (two lags) to FILE.svg, .png or .pdf\n"
    "  -j, --json           print one JSON object (file, profile, samples, spacing, results)\n"
    "  -h, --help           print this help\n\n"
    "Examples:\n"
    "  fracterra dim profile tests/data/dem_volcano_maunga_whau_10m.tif --row 30\n"
    "  fracterra dim profile dem.tif --from 2667400,6478700 --to 2667800,6479300 --method madogram --json\n",
    run_dim_profile,
};
