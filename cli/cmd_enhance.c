/* fracterra — cli/cmd_enhance.c: `fracterra enhance INPUT OUTPUT`: Dutton's fractal enhancement of the
 * lines and polygon boundaries of a layer, then optionally weeding, roundness smoothing and loop repair,
 * in that order (Dutton 1981: fractalize, weed segments shorter than SM, smooth).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"

#include <math.h>

#define MAX_ITERATIONS 16
#define MAX_PASSES 16

enum { OPT_TARGET_DIM = 0x300 }; /* long-only option codes, clear of line_edit.h's */

typedef struct {
    line_io io;
    ft_dutton_opts dutton;
    ft_smooth_opts smooth;
    int weed, repair, roundness_given;
} enhance_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    enhance_args *a = ctx;
    if (line_io_option(opt, arg, &a->io) == CLI_CONTINUE)
        return CLI_CONTINUE;
    switch (opt) {
    case 'd': return cli_parse_double(cmd, "--sd", arg, 1.0, 2.0, CLI_CLOSED, &a->dutton.sd);
    case 'u': return cli_parse_double(cmd, "--uc", arg, -1.0, 1.0, CLI_CLOSED, &a->dutton.uc);
    case 't': return cli_parse_double(cmd, "--st", arg, 0.0, INFINITY, CLI_OPEN_LO | CLI_ALLOW_INF, &a->dutton.st);
    case 'm': return cli_parse_double(cmd, "--sm", arg, 0.0, INFINITY, CLI_CLOSED, &a->dutton.sm);
    case 'i': return cli_parse_int(cmd, "--iterations", arg, 0, MAX_ITERATIONS, &a->dutton.iterations);
    case OPT_TARGET_DIM: /* calibrated mode: the apex angle from the dimension wanted, --sd ignored */
        return cli_parse_double(cmd, "--target-dim", arg, 1.0, ft_dutton_steady_dimension(FT_DUTTON_APEX_MIN),
                                CLI_CLOSED, &a->dutton.target_dim);
    case 's': return cli_parse_int(cmd, "--smooth", arg, 0, MAX_PASSES, &a->smooth.passes);
    case 'r':
        a->roundness_given = 1;
        return cli_parse_double(cmd, "--roundness", arg, 0.0, 1.0, CLI_OPEN_LO, &a->smooth.roundness);
    case 'W': a->weed = 1; return CLI_CONTINUE;
    case 'R': a->repair = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int check_args(const cli_command *cmd, enhance_args *a)
{
    if (a->dutton.sm >= a->dutton.st)
        return cli_usage_error(cmd, "--sm %g must be below --st %g: no segment could be altered", a->dutton.sm,
                               a->dutton.st);
    if (a->weed && a->dutton.sm <= 0.0)
        return cli_usage_error(cmd, "--weed drops segments shorter than --sm: give --sm > 0");
    if (a->roundness_given && a->smooth.passes == 0)
        a->smooth.passes = 1; /* --roundness alone asks for one pass */
    a->smooth.st = a->dutton.st;
    a->smooth.sm = a->dutton.sm;
    return CLI_CONTINUE;
}

static json_object *params_json(const enhance_args *a)
{
    json_object *p = json_object_new_object();
    json_object_object_add(p, "sd", cli_json_double(a->dutton.sd));
    json_object_object_add(p, "uc", cli_json_double(a->dutton.uc));
    json_object_object_add(p, "st", cli_json_double(a->dutton.st)); /* null: no limit */
    json_object_object_add(p, "sm", cli_json_double(a->dutton.sm));
    json_object_object_add(p, "iterations", json_object_new_int(a->dutton.iterations));
    if (a->dutton.target_dim != 0.0) {
        json_object_object_add(p, "target_dim", cli_json_double(a->dutton.target_dim));
        json_object_object_add(p, "apex_deg", cli_json_double(ft_dutton_apex_for_dimension(a->dutton.target_dim) *
                                                              180.0 / 3.14159265358979323846));
    }
    json_object_object_add(p, "weed", json_object_new_boolean(a->weed));
    json_object_object_add(p, "smooth", json_object_new_int(a->smooth.passes));
    json_object_object_add(p, "roundness", cli_json_double(a->smooth.roundness));
    json_object_object_add(p, "repair", json_object_new_boolean(a->repair));
    return p;
}

static int run_enhance(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"sd", required_argument, NULL, 'd'},        {"uc", required_argument, NULL, 'u'},
        {"st", required_argument, NULL, 't'},        {"sm", required_argument, NULL, 'm'},
        {"iterations", required_argument, NULL, 'i'}, {"smooth", required_argument, NULL, 's'},
        {"roundness", required_argument, NULL, 'r'}, {"weed", no_argument, NULL, 'W'},
        {"repair", no_argument, NULL, 'R'},          {"target-dim", required_argument, NULL, OPT_TARGET_DIM},
        LINE_IO_LONGOPTS,
        CLI_OPT_HELP,                                CLI_OPT_END,
    };
    enhance_args a = {LINE_IO_DEFAULT, FT_DUTTON_OPTS_DEFAULT, FT_SMOOTH_OPTS_DEFAULT, 0, 0, 0};
    a.smooth.passes = 0;
    int first = 0;
    int rc = line_edit_parse(cmd, argc, argv, longopts, "d:u:t:m:i:s:r:" LINE_IO_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = check_args(cmd, &a);
    if (rc != CLI_CONTINUE)
        return rc;
    line_step steps[4];
    size_t n = 0;
    if (a.dutton.iterations > 0) {
        steps[n] = (line_step){"fractalize", ft_line_op_enhance, &a.dutton, ldexp(1.0, a.dutton.iterations), ""};
        snprintf(steps[n++].option, sizeof steps[0].option, "--iterations %d", a.dutton.iterations);
    }
    if (a.weed)
        steps[n++] = (line_step){"weed", ft_line_op_weed, &a.dutton.sm, 0.0, ""};
    if (a.smooth.passes > 0) {
        steps[n] = (line_step){"smooth", ft_line_op_smooth, &a.smooth, ldexp(1.0, a.smooth.passes), ""};
        snprintf(steps[n++].option, sizeof steps[0].option, "--smooth %d", a.smooth.passes);
    }
    if (a.repair)
        steps[n++] = (line_step){"repair", ft_line_op_remove_loops, NULL, 0.0, ""};
    return line_edit_run(cmd, argv[first], argv[first + 1], &a.io, steps, n, NULL, NULL, params_json(&a));
}

const cli_command cli_cmd_enhance = {
    "enhance",
    "Dutton's fractal enhancement of generalized lines and polygon boundaries",
    "fracterra enhance INPUT OUTPUT [--sd D | --target-dim D] [--uc U] [--st LEN] [--sm LEN] [--iterations N]\n"
    "                                [--weed] [--smooth K] [--roundness R] [--repair] [--no-coverage] [--layer NAME]\n"
    "                                [--where SQL] [-f DRIVER] [--json]",
    "Puts self-similar detail back into generalized lines (Dutton 1981, docs/line-enhance.md): at each\n"
    "iteration every interior vertex V splits its two segments at their midpoints M1, M2 and moves so that\n"
    "the angle M1-V-M2 is the one the sinuosity dimension SD implies, keeping the ratio of the legs; UC\n"
    "scales that move. Only vertices whose two segments are shorter than ST and not shorter than SM are\n"
    "altered; end points of open lines never move. Then, in this order: --weed drops vertices so that no\n"
    "segment is shorter than SM, --smooth cuts corners K times, --repair removes the loops that\n"
    "self-intersections make. The report gives the vertices after each step and the self-intersections\n"
    "left (within each chain; negative UC and narrow features make them).\n" LINE_IO_COVERAGE_HELP "\n"
    "Options:\n"
    "  -d, --sd D           sinuosity dimension in [1,2] (1 keeps junctions straight, 2 right angles); default 1.3\n"
    "      --target-dim D   calibrated mode: the apex angle whose steady-state divider dimension is D, in\n"
    "                       [1,1.777] (SD's own angle gives less: SD 1.3 measures 1.12); --sd is ignored;\n"
    "                       exact for --uc 1 (docs/line-enhance.md)\n"
    "  -u, --uc U           uniformity coefficient in [-1,1]: the fraction of the move (negative: the opposite\n"
    "                       way, exaggerating); default 1\n"
    "  -t, --st LEN         straightness tolerance: only segments shorter than LEN are altered; default inf\n"
    "  -m, --sm LEN         smoothness tolerance: only segments of at least LEN are altered; default 0\n"
    "  -i, --iterations N   fractalizing iterations, 0..16 (each one about doubles the vertices); default 1\n"
    "      --weed           after fractalizing, drop vertices so that no segment is shorter than --sm\n"
    "  -s, --smooth K       then K passes of corner cutting (0..16); default 0\n"
    "  -r, --roundness R    corner cutting in (0,1]: V becomes V + R(M1-V) and V + R(M2-V) (0.5: Chaikin);\n"
    "                       default 0.5; alone, implies --smooth 1\n"
    "      --repair         finally remove the loops of self-intersecting chains\n" LINE_IO_HELP "\n"
    "Example (Dutton's Newfoundland: SM 1% of a 510 km wide map, ST very large):\n"
    "  fracterra simplify tests/data/gshhg_newfoundland_utm21n.geojson nf158.geojson --vertices 158\n"
    "  fracterra enhance nf158.geojson nf-enhanced.geojson --sd 1.3 --uc 0.7 --sm 5100 --weed --smooth 1\n",
    run_enhance,
};
