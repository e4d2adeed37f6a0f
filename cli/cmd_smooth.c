/* fracterra — cli/cmd_smooth.c: `fracterra smooth INPUT OUTPUT`: Dutton's roundness smoothing (corner
 * cutting; roundness 0.5 is Chaikin's quarter points) of the lines and polygon boundaries of a layer.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"

#include <math.h>

#define MAX_PASSES 16

typedef struct {
    line_io io;
    ft_smooth_opts smooth;
} smooth_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    smooth_args *a = ctx;
    if (line_io_option(opt, arg, &a->io) == CLI_CONTINUE)
        return CLI_CONTINUE;
    switch (opt) {
    case 'p': return cli_parse_int(cmd, "--passes", arg, 1, MAX_PASSES, &a->smooth.passes);
    case 'r': return cli_parse_double(cmd, "--roundness", arg, 0.0, 1.0, CLI_OPEN_LO, &a->smooth.roundness);
    case 't': return cli_parse_double(cmd, "--st", arg, 0.0, INFINITY, CLI_OPEN_LO | CLI_ALLOW_INF, &a->smooth.st);
    case 'm': return cli_parse_double(cmd, "--sm", arg, 0.0, INFINITY, CLI_CLOSED, &a->smooth.sm);
    case 'X': a->smooth.allow_crossings = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static json_object *params_json(const ft_smooth_opts *s)
{
    json_object *p = json_object_new_object();
    json_object_object_add(p, "passes", json_object_new_int(s->passes));
    json_object_object_add(p, "roundness", cli_json_double(s->roundness));
    json_object_object_add(p, "st", cli_json_double(s->st)); /* null: no limit */
    json_object_object_add(p, "sm", cli_json_double(s->sm));
    json_object_object_add(p, "allow_crossings", json_object_new_boolean(s->allow_crossings));
    return p;
}

static int run_smooth(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"passes", required_argument, NULL, 'p'}, {"roundness", required_argument, NULL, 'r'},
        {"st", required_argument, NULL, 't'},     {"sm", required_argument, NULL, 'm'},
        {"allow-crossings", no_argument, NULL, 'X'},
        LINE_IO_LONGOPTS,                         CLI_OPT_HELP,
        CLI_OPT_END,
    };
    smooth_args a = {LINE_IO_DEFAULT, FT_SMOOTH_OPTS_DEFAULT};
    int first = 0;
    int rc = line_edit_parse(cmd, argc, argv, longopts, "p:r:t:m:" LINE_IO_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE && a.smooth.sm >= a.smooth.st)
        rc = cli_usage_error(cmd, "--sm %g must be below --st %g: no corner could be cut", a.smooth.sm, a.smooth.st);
    if (rc != CLI_CONTINUE)
        return rc;
    line_step step = {"smooth", ft_line_op_smooth, &a.smooth, line_smooth_layer_step, &a.smooth,
                      ldexp(1.0, a.smooth.passes), ""};
    snprintf(step.option, sizeof step.option, "--passes %d", a.smooth.passes);
    return line_edit_run(cmd, argv[first], argv[first + 1], &a.io, &step, 1, NULL, NULL, params_json(&a.smooth));
}

const cli_command cli_cmd_smooth = {
    "smooth",
    "roundness smoothing (corner cutting) of lines and polygon boundaries",
    "fracterra smooth INPUT OUTPUT [--passes K] [--roundness R] [--st LEN] [--sm LEN] [--allow-crossings]\n"
    "                               [--no-coverage] [--layer NAME] [--where SQL] [-f DRIVER] [--json]",
    "Smooths every line and ring of INPUT by cutting corners (Dutton 1981; Chaikin 1974): each vertex V\n"
    "with segment midpoints M1, M2 is replaced by V + R(M1 - V) and V + R(M2 - V). Vertices whose segments\n"
    "are not within [SM, ST] keep their place; end points of open lines never move. No cut makes a line\n"
    "cross or touch itself or another feature of the layer: a cut that would is halved, quartered, or not\n"
    "made (the report counts them; docs/line-enhance.md).\n" LINE_IO_COVERAGE_HELP "\n"
    "Options:\n"
    "  -p, --passes K       smoothing passes, 1..16; default 1\n"
    "  -r, --roundness R    in (0,1]; 0.5 cuts at the quarter points (Chaikin); default 0.5\n"
    "  -t, --st LEN         only corners whose segments are shorter than LEN; default inf\n"
    "  -m, --sm LEN         only corners whose segments are at least LEN; default 0\n"
    "      --allow-crossings  the raw algorithm: cut every corner even where lines then cross\n" LINE_IO_HELP "\n"
    "Example:\n"
    "  fracterra smooth coast.geojson coast-round.geojson --passes 2 --roundness 0.25\n",
    run_smooth,
};
