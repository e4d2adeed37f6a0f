/* fracterra — cli/cmd_simplify.c: `fracterra simplify INPUT OUTPUT`: Douglas-Peucker simplification of the
 * lines and polygon boundaries of a layer, with a distance tolerance or a target number of vertices (the
 * smallest tolerance leaving at most that many, found by bisection: Dutton's "158 points").
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"

#include <math.h>

typedef struct {
    line_io io;
    double tolerance; /* 0 until given or found */
    int vertices;     /* --vertices N, 0 if not given */
} simplify_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    simplify_args *a = ctx;
    if (line_io_option(opt, arg, &a->io) == CLI_CONTINUE)
        return CLI_CONTINUE;
    if (opt == 't')
        return cli_parse_double(cmd, "--tolerance", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->tolerance);
    if (opt == 'n')
        return cli_parse_int(cmd, "--vertices", arg, 2, 2000000000, &a->vertices);
    return cli_usage_error(cmd, "unexpected option");
}

/* --vertices N: the tolerance from the data, echoed with the target. */
static int choose_tolerance(const ft_layer *l, int coverage, void *ctx, json_object *params)
{
    simplify_args *a = ctx;
    size_t n = 0;
    int rc = ft_line_simplify_tolerance_for(l, (size_t)a->vertices, coverage, &a->tolerance, &n);
    if (rc == FT_OK)
        json_object_object_add(params, "tolerance", cli_json_double(a->tolerance));
    return rc;
}

static int run_simplify(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"tolerance", required_argument, NULL, 't'}, {"vertices", required_argument, NULL, 'n'}, LINE_IO_LONGOPTS,
        CLI_OPT_HELP, CLI_OPT_END,
    };
    simplify_args a = {LINE_IO_DEFAULT, 0.0, 0};
    int first = 0;
    int rc = line_edit_parse(cmd, argc, argv, longopts, "t:n:" LINE_IO_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE && (a.tolerance > 0.0) == (a.vertices > 0))
        rc = cli_usage_error(cmd, "give either --tolerance T or --vertices N");
    if (rc != CLI_CONTINUE)
        return rc;
    json_object *params = json_object_new_object();
    if (a.vertices > 0)
        json_object_object_add(params, "target_vertices", json_object_new_int(a.vertices));
    else
        json_object_object_add(params, "tolerance", cli_json_double(a.tolerance));
    line_step step = {"simplify", ft_line_op_simplify, &a.tolerance, NULL, NULL, 0.0, ""};
    return line_edit_run(cmd, argv[first], argv[first + 1], &a.io, &step, 1, a.vertices ? choose_tolerance : NULL,
                         &a, params);
}

const cli_command cli_cmd_simplify = {
    "simplify",
    "Douglas-Peucker simplification of lines and polygon boundaries",
    "fracterra simplify INPUT OUTPUT (--tolerance T | --vertices N) [--no-coverage] [--layer NAME]\n"
    "                                 [--where SQL] [-f DRIVER] [--json]",
    "Simplifies every line and ring of INPUT with Douglas-Peucker: a vertex is kept if it lies farther than\n"
    "the tolerance from the chord of the run it belongs to; end points of open lines are kept and rings keep\n"
    "at least 3 vertices. --vertices N picks the smallest tolerance that leaves at most N vertices in the\n"
    "whole layer (bisection) and reports it.\n" LINE_IO_COVERAGE_HELP "\n"
    "Options:\n"
    "  -t, --tolerance T    distance tolerance in map units (> 0)\n"
    "  -n, --vertices N     instead: at most N vertices in the output (N >= 2)\n" LINE_IO_HELP "\n"
    "Examples:\n"
    "  fracterra simplify tests/data/gshhg_newfoundland_utm21n.geojson nf158.geojson --vertices 158\n"
    "  fracterra simplify states.gpkg states-5km.gpkg --tolerance 5000 --json | jq .vertices_out\n",
    run_simplify,
};
