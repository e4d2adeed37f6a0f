/* fracterra — cli/cmd_weed.c: `fracterra weed INPUT OUTPUT --min-segment LEN`: drops vertices of the lines
 * and polygon boundaries of a layer so that no segment is shorter than LEN (Dutton's weeding step).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"

#include <math.h>

typedef struct {
    line_io io;
    double min_segment;
    int keep_shape;
} weed_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    weed_args *a = ctx;
    if (line_io_option(opt, arg, &a->io) == CLI_CONTINUE)
        return CLI_CONTINUE;
    if (opt == 'k') {
        a->keep_shape = 1;
        return CLI_CONTINUE;
    }
    if (opt == 'm')
        return cli_parse_double(cmd, "--min-segment", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->min_segment);
    return cli_usage_error(cmd, "unexpected option");
}

static int run_weed(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"min-segment", required_argument, NULL, 'm'}, {"keep-shape", no_argument, NULL, 'k'}, LINE_IO_LONGOPTS,
        CLI_OPT_HELP, CLI_OPT_END,
    };
    weed_args a = {LINE_IO_DEFAULT, 0.0, 0};
    int first = 0;
    int rc = line_edit_parse(cmd, argc, argv, longopts, "m:k" LINE_IO_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE && a.min_segment <= 0.0)
        rc = cli_usage_error(cmd, "missing --min-segment LEN");
    if (rc != CLI_CONTINUE)
        return rc;
    json_object *params = json_object_new_object();
    json_object_object_add(params, "min_segment", cli_json_double(a.min_segment));
    json_object_object_add(params, "keep_shape", json_object_new_boolean(a.keep_shape));
    line_step step = {"weed", a.keep_shape ? ft_line_op_weed_shape : ft_line_op_weed, &a.min_segment, NULL, NULL,
                      0.0, ""};
    return line_edit_run(cmd, argv[first], argv[first + 1], &a.io, &step, 1, NULL, NULL, params);
}

const cli_command cli_cmd_weed = {
    "weed",
    "drop vertices so that no segment is shorter than a length",
    "fracterra weed INPUT OUTPUT --min-segment LEN [--keep-shape] [--no-coverage] [--layer NAME] [--where SQL]\n"
    "                             [-f DRIVER] [--json]",
    "Weeds every line and ring of INPUT: walking along the chain, a vertex closer than LEN to the last one\n"
    "kept is dropped, so no segment is shorter than LEN (end points of open lines are kept). This is the\n"
    "step Dutton applies after fractalizing, with LEN = SM (his Newfoundland: about 10% of the vertices;\n"
    "after enhance --keep-vertices, at SM 7372 m: docs/line-newfoundland.md). With --keep-shape, of the\n"
    "two vertices of a short segment the one nearer to the chord of its neighbours is dropped (passes until\n"
    "no segment is short): the extreme points of bays and headlands stay (docs/line-newfoundland.md).\n"
    LINE_IO_COVERAGE_HELP "\n"
    "Options:\n"
    "  -m, --min-segment LEN  shortest segment kept, in map units (> 0)\n"
    "  -k, --keep-shape       drop the vertex of a short segment that carries less shape\n" LINE_IO_HELP "\n"
    "Example:\n"
    "  fracterra weed enhanced.geojson weeded.geojson --min-segment 5100\n",
    run_weed,
};
