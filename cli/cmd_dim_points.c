/* fracterra — cli/cmd_dim_points.c: `fracterra dim points POINTS`: the fractal dimension of scattered
 * elevations (CSV, XYZ or an OGR point layer) by Yokoya's or Pentland's method on irregularly sampled
 * points (Arakawa & Krotkov §2.4; ft_surface_dim_points, docs/surface-points.md).
 *
 * Lags whose pair count falls below --min-pairs are dropped: the JSON lists them in "dropped_lags"
 * ({"lag", "pairs", "reason", "method"}), the table output names them in a warning on stderr, and when too
 * few lags remain the command fails with a message listing every dropped lag.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"
#include "dim_output.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_USER_LAGS 1000

typedef struct {
    cli_dim_opts dim;
    const char *method, *lags, *layer, *zfield;
    ft_read_points_opts read;
    ft_points_dim_opts est;
    int seed_given;
    const ft_crs_info *crs; /* of the input, once read */
} points_args;

enum {
    OPT_EPS = 0x200,
    OPT_MIN_PAIRS,
    OPT_LAGS,
    OPT_EXACT,
    OPT_SAMPLE,
    OPT_NOISE,
    OPT_NOISE_MODEL,
    OPT_SEED,
    OPT_X,
    OPT_Y,
    OPT_Z,
    OPT_LAYER,
    OPT_ZFIELD,
};

/* "all" or a comma-separated list of methods into ms; the count, 0 on a bad or repeated name. */
static int parse_methods(const char *text, ft_points_method *ms)
{
    if (strcmp(text, "all") == 0) {
        ms[0] = FT_POINTS_YOKOYA;
        ms[1] = FT_POINTS_PENTLAND;
        return 2;
    }
    int n = 0;
    char buf[64];
    snprintf(buf, sizeof buf, "%s", text);
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        ft_points_method m;
        if (n == 2 || ft_points_method_parse(tok, &m) != FT_OK || (n == 1 && ms[0] == m))
            return 0;
        ms[n++] = m;
    }
    ft_clear_error();
    return n;
}

/* --lags L1,L2,...: positive distances. */
static int parse_lags(const cli_command *cmd, const char *text, double *lags, size_t *n)
{
    *n = 0;
    const char *s = text;
    while (*s) {
        char *end = NULL;
        double v = strtod(s, &end);
        if (end == s || !(v > 0.0) || !isfinite(v) || (*end != ',' && *end != '\0'))
            return cli_usage_error(cmd, "--lags must be positive distances separated by commas, got '%s'", text);
        if (*n == MAX_USER_LAGS)
            return cli_usage_error(cmd, "--lags: at most %d lags", MAX_USER_LAGS);
        lags[(*n)++] = v;
        s = *end == ',' ? end + 1 : end;
    }
    if (*n < 2)
        return cli_usage_error(cmd, "--lags needs at least 2 lags, got '%s'", text);
    return CLI_CONTINUE;
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    points_args *a = ctx;
    int rc = cli_dim_option(cmd, opt, arg, &a->dim);
    if (rc != CLI_DIM_NOT_SHARED)
        return rc;
    int n = 0;
    switch (opt) {
    case 'm': a->method = arg; return CLI_CONTINUE;
    case OPT_EPS: return cli_parse_double(cmd, "--eps", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->est.eps);
    case OPT_MIN_PAIRS:
        rc = cli_parse_int(cmd, "--min-pairs", arg, 1, 1000000000L, &n);
        a->est.min_pairs = (size_t)n;
        return rc;
    case OPT_LAGS: a->lags = arg; return CLI_CONTINUE;
    case OPT_EXACT: a->est.exact = 1; return CLI_CONTINUE;
    case OPT_SAMPLE: {
        char *end = NULL;
        unsigned long long v = strtoull(arg, &end, 10);
        if (end == arg || *end != '\0' || arg[0] == '-' || v < 1 || v > 10000000000ULL)
            return cli_usage_error(cmd, "--sample must be a number of pairs in [1, 10000000000], got '%s'", arg);
        a->est.sample = (size_t)v;
        return CLI_CONTINUE;
    }
    case OPT_NOISE: return cli_parse_noise_sigma(cmd, arg, 1, &a->est.noise_sigma_xy, &a->est.noise_sigma);
    case OPT_NOISE_MODEL: return cli_parse_noise_model(cmd, arg, &a->est.noise_mode);
    case OPT_SEED: {
        char *end = NULL;
        unsigned long long v = strtoull(arg, &end, 10);
        if (end == arg || *end != '\0' || arg[0] == '-')
            return cli_usage_error(cmd, "--seed must be a non-negative integer, got '%s'", arg);
        a->est.seed = v;
        a->seed_given = 1;
        return CLI_CONTINUE;
    }
    case OPT_X: a->read.x = arg; return CLI_CONTINUE;
    case OPT_Y: a->read.y = arg; return CLI_CONTINUE;
    case OPT_Z: a->read.z = arg; return CLI_CONTINUE;
    case OPT_LAYER: a->read.layer = arg; return CLI_CONTINUE;
    case OPT_ZFIELD: a->read.zfield = arg; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static const char *reason_name(ft_lag_status s)
{
    return s == FT_LAG_NOISE ? "noise" : s == FT_LAG_ZERO ? "zero" : "pairs";
}

/* Appends the dropped lags of c to arr (JSON) and to the warning text. */
static void note_dropped(const ft_points_counters *c, json_object *arr, char *text, size_t size)
{
    for (size_t k = 0; k < c->n; k++) {
        const ft_points_lag *l = &c->lags[k];
        if (l->status == FT_LAG_KEPT)
            continue;
        double pairs = c->sample ? (double)l->drawn : l->C;
        json_object *o = json_object_new_object();
        json_object_object_add(o, "lag", cli_json_double(l->lag));
        json_object_object_add(o, "pairs", json_object_new_int64((int64_t)pairs));
        json_object_object_add(o, "reason", json_object_new_string(reason_name(l->status)));
        json_object_object_add(o, "method", json_object_new_string(ft_points_method_name(c->method)));
        json_object_array_add(arr, o);
        size_t used = strlen(text);
        if (used + 1 < size)
            snprintf(text + used, size - used, "%s%g (%s %.0f)", used ? ", " : "", l->lag,
                     l->status == FT_LAG_FEW_PAIRS ? "pairs" : reason_name(l->status), pairs);
    }
}

static json_object *group_info(const ft_points *p, const ft_points_counters *c)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "points", json_object_new_int64((int64_t)p->n));
    json_object_object_add(o, "spacing", cli_json_double(c->spacing));
    json_object_object_add(o, "eps", cli_json_double(c->eps));
    json_object_object_add(o, "min_pairs", json_object_new_int64((int64_t)c->min_pairs));
    json_object_object_add(o, "pairs", json_object_new_string(c->pairs));
    json_object_object_add(o, "lags", json_object_new_int64((int64_t)c->n));
    json_object_object_add(o, "lags_kept", json_object_new_int64((int64_t)c->kept));
    return o;
}

/* Runs every method on the points into the report; fills the extra members. */
static int measure(const cli_command *cmd, const ft_points *p, const points_args *a, const ft_points_method *ms,
                   int nm, cli_dim_report *rep, json_object *extra)
{
    json_object *dropped = json_object_new_array(), *sse = nm > 1 ? json_object_new_object() : NULL;
    char warn[2048] = "";
    int rc = FT_OK;
    for (int i = 0; rc == FT_OK && i < nm; i++) {
        ft_points_dim_opts o = a->est;
        ft_points_counters *c = NULL;
        ft_dim_result *r = NULL;
        o.method = ms[i];
        o.counters = &c;
        o.progress = cli_progress();
        rc = ft_surface_dim_points(p, &o, &r);
        if (rc == FT_OK && i == 0)
            rc = cli_dim_report_group(rep, 0, NULL, cmd->name, group_info(p, c));
        if (rc == FT_OK) {
            note_dropped(c, dropped, warn, sizeof warn);
            if (c->sample > 0 && sse)
                json_object_object_add(sse, ft_points_method_name(ms[i]), cli_json_double(c->D_sample_se));
            else if (c->sample > 0)
                json_object_object_add(extra, "sample_stderr", cli_json_double(c->D_sample_se));
            cli_geo_units(r, a->crs);
            rc = cli_dim_report_add(rep, r, "mean pair separation",
                                    ms[i] == FT_POINTS_YOKOYA ? "mean |dz|" : "sd of |dz|");
        } else {
            ft_dim_result_free(r);
        }
        ft_points_counters_free(c);
    }
    json_object_object_add(extra, "dropped_lags", dropped);
    if (sse)
        json_object_object_add(extra, "sample_stderr", sse);
    if (rc == FT_OK && warn[0] && !a->dim.json)
        cli_warn(cmd, "dropped lags (lag, reason, pairs): %s", warn);
    return rc == FT_OK ? CLI_OK : cli_fail(cmd);
}

static json_object *extra_members(const char *path, const points_args *a)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "file", json_object_new_string(path));
    if (a->est.sample > 0)
        json_object_object_add(o, "seed", json_object_new_int64((int64_t)a->est.seed));
    if (a->est.noise_sigma > 0.0)
        json_object_object_add(o, "noise_sigma", cli_json_double(a->est.noise_sigma));
    if (a->est.noise_sigma_xy > 0.0)
        json_object_object_add(o, "noise_sigma_xy", cli_json_double(a->est.noise_sigma_xy));
    json_object_object_add(o, "noise_model", json_object_new_string(a->est.noise_mode == 0 ? "auto" : "off"));
    return o;
}

static int run_dim_points(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"method", required_argument, NULL, 'm'},      {"eps", required_argument, NULL, OPT_EPS},
        {"min-pairs", required_argument, NULL, OPT_MIN_PAIRS}, {"lags", required_argument, NULL, OPT_LAGS},
        {"exact", no_argument, NULL, OPT_EXACT},       {"sample", required_argument, NULL, OPT_SAMPLE},
        {"noise-sigma", required_argument, NULL, OPT_NOISE}, {"seed", required_argument, NULL, OPT_SEED},
        {"noise-model", required_argument, NULL, OPT_NOISE_MODEL},
        {"x", required_argument, NULL, OPT_X},         {"y", required_argument, NULL, OPT_Y},
        {"z", required_argument, NULL, OPT_Z},         {"layer", required_argument, NULL, OPT_LAYER},
        {"zfield", required_argument, NULL, OPT_ZFIELD}, CLI_DIM_LONGOPTS,
        CLI_OPT_HELP,                                   CLI_OPT_END,
    };
    static const char *const names[] = {"POINTS"};
    points_args a = {CLI_DIM_OPTS_DEFAULT, "yokoya", NULL, NULL, NULL, FT_READ_POINTS_OPTS_DEFAULT,
                     FT_POINTS_DIM_OPTS_DEFAULT, 0, NULL};
    ft_points_method ms[2];
    double lags[MAX_USER_LAGS];
    int first = 0, nm = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "m:" CLI_DIM_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc == CLI_CONTINUE)
        rc = cli_dim_check(cmd, &a.dim);
    if (rc == CLI_CONTINUE && (nm = parse_methods(a.method, ms)) == 0)
        rc = cli_usage_error(cmd, "--method must be yokoya, pentland or all; got '%s'", a.method);
    if (rc == CLI_CONTINUE && a.est.exact && a.est.sample)
        rc = cli_usage_error(cmd, "--exact and --sample exclude each other");
    if (rc == CLI_CONTINUE && a.lags && (a.dim.min_scale > 0.0 || a.dim.max_scale > 0.0 || a.dim.nscales))
        rc = cli_usage_error(cmd, "--lags and --min-scale/--max-scale/--scales exclude each other");
    if (rc == CLI_CONTINUE && a.lags)
        rc = parse_lags(cmd, a.lags, lags, &a.est.nuser_lags);
    if (rc != CLI_CONTINUE)
        return rc;
    if (a.lags)
        a.est.lags = lags;
    a.est.min_lag = a.dim.min_scale;
    a.est.max_lag = a.dim.max_scale;
    a.est.nlags = a.dim.nscales;
    a.est.fit.regime = a.dim.regime;
    const char *path = argv[first];
    if (a.dim.plot && ft_io_check_writable(a.dim.plot) != FT_OK)
        return cli_fail(cmd);
    ft_points *p = NULL;
    ft_crs_info crs;
    if (ft_io_read_points(path, &a.read, &p) != FT_OK)
        return cli_fail(cmd);
    if (cli_geo_points_ground(cmd, path, p, &crs) != CLI_CONTINUE) { /* lon/lat: lags in metres */
        ft_points_free(p);
        return CLI_FAIL;
    }
    cli_dim_report *rep = cli_dim_report_create(path);
    json_object *extra = extra_members(path, &a);
    a.crs = &crs;
    if (crs.geographic)
        json_object_object_add(extra, "geographic", cli_geo_json(&crs, p->crs_wkt));
    rc = rep ? measure(cmd, p, &a, ms, nm, rep, extra) : (ft_error(FT_E_NOMEM, "out of memory"), cli_fail(cmd));
    if (rc == CLI_OK) {
        rc = cli_dim_report_print(cmd, rep, &a.dim, extra);
        extra = NULL;
    }
    json_object_put(extra);
    cli_dim_report_free(rep);
    ft_points_free(p);
    return rc;
}

const cli_command cli_cmd_dim_points = {
    "dim points",
    "fractal dimension of scattered elevations (Yokoya, Pentland)",
    "fracterra dim points POINTS [--method yokoya|pentland|all] [--eps E] [--min-pairs N]\n"
    "                            [--lags L1,L2,...|--min-scale S --max-scale S --scales N] [--exact|--sample P]\n"
    "                            [--noise-sigma [XY,]Z] [--noise-model auto|off] [--seed N]\n"
    "                            [--x COL --y COL --z COL] [--layer NAME] [--zfield NAME] [--segments]\n"
    "                            [--plot FILE] [--json]",
    "Measures the fractal dimension D of irregularly sampled elevations (CSV with a header, XYZ text, or\n"
    "an OGR point layer), after Arakawa & Krotkov section 2.4: for every lag L and every pair of points\n"
    "whose separation d satisfies |d - L| <= eps, the counters A = sum |dz|, B = sum dz^2 and C = pairs;\n"
    "lags with fewer than --min-pairs pairs are dropped (and listed); D = 3 - H from the slope H of the\n"
    "statistic against the mean pair separation in log-log space, least squares over the kept lags.\n\n"
    "Methods (docs/surface-points.md):\n"
    "  yokoya    mean of |dz|, A / C (default)\n"
    "  pentland  sample standard deviation of |dz|, sqrt((B - A^2/C) / (C - 1))\n"
    "  all       both: {\"results\": [...]}\n\n"
    "Options:\n"
    "  -m, --method M       yokoya (default), pentland or all\n"
    "      --lags L,L,...   the lags, in map units (instead of the geometric series below)\n"
    "      --eps E          annulus half-width, 0 < E < the smallest lag; default: half the smallest gap\n"
    "                       between consecutive lags\n"
    "      --min-pairs N    fewest pairs a lag needs (>= 1); default 100\n"
    "      --exact          enumerate all N(N-1)/2 pairs (the paper's O(N^2)); same counters as the default\n"
    "                       grid search, which visits only pairs within the largest lag\n"
    "      --sample P       estimate from P random pairs within the largest lag (sampling stderr reported)\n"
    "      --seed N         seed of --sample (default 1)\n"
    "      --noise-sigma [XY,]Z  known standard deviations of Gaussian noise on x and y (XY, map units)\n"
    "                       and on z (Z): 2 Z^2 is removed from E dz^2 and lags below 3 XY are left out\n"
    "      --noise-model M  auto (default): detect noise on x, y and z (the plot flattening toward small\n"
    "                       lags), remove it (errors-in-variables fit) and fit past it, extending the\n"
    "                       default lags to 32 spacings unless z noise alone leaves 6 of them above it;\n"
    "                       off: none (docs/surface-noise.md)\n"
    "      --x/--y/--z COL  CSV column names (default x, y, z)\n"
    "      --layer NAME     OGR layer (default: the first); --zfield NAME: z from this field, not the geometry\n"
    CLI_DIM_OPTIONS_HELP
    "  -h, --help           print this help\n"
    "Scales are lags in map units; default lags: 0.5 to 4 times the mean point spacing sqrt(area / N),\n"
    "4 per octave.\n\n"
    "JSON: {\"file\", \"points\", \"spacing\", \"eps\", \"min_pairs\", \"pairs\", \"lags\", \"lags_kept\",\n"
    "\"dropped_lags\": [{\"lag\", \"pairs\", \"reason\", \"method\"}], \"method\", \"D\", \"r2\", \"stderr\",\n"
    "\"range\", \"warnings\", \"noise\": {\"detected\", \"removed\", \"sigma_z\", \"sigma_xy\", \"nugget\", \"H\", \"F\",\n"
    "\"floor\"}, \"table\": [...]} (\"sample_stderr\" and \"seed\" with --sample); several methods: \"results\": [...].\n\n"
    "Examples:\n"
    "  fracterra dim points scan.xyz --plot scan-dim.svg\n"
    "  fracterra dim points spots.csv --z elev --method all --json | jq '.results[].D'\n"
    "  fracterra dim points tests/data/points_mass_topo_davis1973.csv --lags 1,1.5,2,2.5,3 --eps 0.25 \\\n"
    "      --min-pairs 10\n",
    run_dim_points,
};
