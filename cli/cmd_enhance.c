/* fracterra — cli/cmd_enhance.c: `fracterra enhance INPUT OUTPUT`: Dutton's fractal enhancement of the
 * lines and polygon boundaries of a layer, then optionally weeding, roundness smoothing and loop repair,
 * in that order (Dutton 1981: fractalize, weed segments shorter than SM, smooth).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"

#include <math.h>
#include <string.h>

#define MAX_ITERATIONS 16
#define MAX_PASSES 16

enum { /* long-only option codes, clear of line_edit.h's */
    OPT_TARGET_DIM = 0x300,
    OPT_INPUT_DIM,
    OPT_LITERAL_SD,
    OPT_ALLOW_CROSSINGS,
    OPT_KEEP_SHAPE,
    OPT_KEEP_VERTICES
};

typedef struct {
    line_io io;
    ft_dutton_opts dutton;
    ft_smooth_opts smooth;
    int weed, repair, roundness_given, keep_shape;
    json_object *params; /* the report's parameters: the plan is added once the layer is read */
} enhance_args;

/* The fractalize step: the whole layer at once (one plan, one crossing guard), the plan into the report. */
static int enhance_layer_step(ft_layer *l, void *ctx, int coverage, ft_line_guard_stats *stats)
{
    enhance_args *a = ctx;
    ft_dutton_plan plan;
    int rc = ft_line_enhance_layer(l, &a->dutton, coverage, &plan, stats);
    if (rc != FT_OK)
        return rc;
    json_object_object_add(a->params, "apex_deg", cli_json_double(plan.apex * 180.0 / 3.14159265358979323846));
    json_object_object_add(a->params, "target_dim", cli_json_double(plan.target_dim)); /* null: literal/uc <= 0 */
    json_object_object_add(a->params, "input_dim", cli_json_double(plan.input_dim));   /* null: not used */
    return FT_OK;
}

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    enhance_args *a = ctx;
    if (line_io_option(opt, arg, &a->io) == CLI_CONTINUE)
        return CLI_CONTINUE;
    switch (opt) {
    case 'd':
        if (strcmp(arg, "input") == 0) {
            a->dutton.sd = 0.0; /* the library's "SD is D_in" */
            return CLI_CONTINUE;
        }
        return cli_parse_double(cmd, "--sd", arg, 1.0, 2.0, CLI_CLOSED, &a->dutton.sd);
    case 'u': return cli_parse_double(cmd, "--uc", arg, -1.0, 1.0, CLI_CLOSED, &a->dutton.uc);
    case 't': return cli_parse_double(cmd, "--st", arg, 0.0, INFINITY, CLI_OPEN_LO | CLI_ALLOW_INF, &a->dutton.st);
    case 'm': return cli_parse_double(cmd, "--sm", arg, 0.0, INFINITY, CLI_CLOSED, &a->dutton.sm);
    case 'i': return cli_parse_int(cmd, "--iterations", arg, 0, MAX_ITERATIONS, &a->dutton.iterations);
    case OPT_TARGET_DIM: /* the dimension wanted, whatever --uc; --sd ignored */
        return cli_parse_double(cmd, "--target-dim", arg, 1.0, ft_dutton_steady_dimension(FT_DUTTON_APEX_MIN),
                                CLI_CLOSED, &a->dutton.target_dim);
    case OPT_INPUT_DIM:
        return cli_parse_double(cmd, "--input-dim", arg, 1.0, 2.0, CLI_CLOSED, &a->dutton.input_dim);
    case OPT_LITERAL_SD: a->dutton.literal_sd = 1; return CLI_CONTINUE;
    case OPT_ALLOW_CROSSINGS: a->dutton.allow_crossings = a->smooth.allow_crossings = 1; return CLI_CONTINUE;
    case 's': return cli_parse_int(cmd, "--smooth", arg, 0, MAX_PASSES, &a->smooth.passes);
    case 'r':
        a->roundness_given = 1;
        return cli_parse_double(cmd, "--roundness", arg, 0.0, 1.0, CLI_OPEN_LO, &a->smooth.roundness);
    case 'W': a->weed = 1; return CLI_CONTINUE;
    case OPT_KEEP_SHAPE: a->keep_shape = 1; return CLI_CONTINUE;
    case OPT_KEEP_VERTICES: a->dutton.keep_vertices = 1; return CLI_CONTINUE;
    case 'R': a->repair = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int check_args(const cli_command *cmd, enhance_args *a)
{
    if (a->dutton.sm >= a->dutton.st)
        return cli_usage_error(cmd, "--sm %g must be below --st %g: no segment could be altered", a->dutton.sm,
                               a->dutton.st);
    if (a->dutton.keep_vertices && a->dutton.iterations != 1)
        return cli_usage_error(cmd, "--keep-vertices keeps the input's vertices in one pass: --iterations must be 1, "
                               "got %d", a->dutton.iterations);
    if (a->keep_shape && !a->weed)
        return cli_usage_error(cmd, "--keep-shape chooses how --weed drops vertices: give --weed");
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
    json_object_object_add(p, "sd", a->dutton.sd == 0.0 ? json_object_new_string("input") : cli_json_double(a->dutton.sd));
    json_object_object_add(p, "uc", cli_json_double(a->dutton.uc));
    json_object_object_add(p, "st", cli_json_double(a->dutton.st)); /* null: no limit */
    json_object_object_add(p, "sm", cli_json_double(a->dutton.sm));
    json_object_object_add(p, "iterations", json_object_new_int(a->dutton.iterations));
    json_object_object_add(p, "literal_sd", json_object_new_boolean(a->dutton.literal_sd));
    json_object_object_add(p, "allow_crossings", json_object_new_boolean(a->dutton.allow_crossings));
    json_object_object_add(p, "keep_vertices", json_object_new_boolean(a->dutton.keep_vertices));
    json_object_object_add(p, "weed", json_object_new_boolean(a->weed));
    json_object_object_add(p, "keep_shape", json_object_new_boolean(a->keep_shape));
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
        {"input-dim", required_argument, NULL, OPT_INPUT_DIM}, {"literal-sd", no_argument, NULL, OPT_LITERAL_SD},
        {"allow-crossings", no_argument, NULL, OPT_ALLOW_CROSSINGS}, {"keep-shape", no_argument, NULL, OPT_KEEP_SHAPE},
        {"keep-vertices", no_argument, NULL, OPT_KEEP_VERTICES},
        LINE_IO_LONGOPTS,
        CLI_OPT_HELP,                                CLI_OPT_END,
    };
    enhance_args a = {LINE_IO_DEFAULT, FT_DUTTON_OPTS_DEFAULT, FT_SMOOTH_OPTS_DEFAULT, 0, 0, 0, 0, NULL};
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
        steps[n] = (line_step){"fractalize", ft_line_op_enhance, &a.dutton, enhance_layer_step, &a,
                               ldexp(1.0, a.dutton.iterations), ""};
        snprintf(steps[n++].option, sizeof steps[0].option, "--iterations %d", a.dutton.iterations);
    }
    if (a.weed)
        steps[n++] = (line_step){"weed", a.keep_shape ? ft_line_op_weed_shape : ft_line_op_weed, &a.dutton.sm, NULL,
                                 NULL, 0.0, ""};
    if (a.smooth.passes > 0) {
        steps[n] = (line_step){"smooth", ft_line_op_smooth, &a.smooth, line_smooth_layer_step, &a.smooth,
                               ldexp(1.0, a.smooth.passes), ""};
        snprintf(steps[n++].option, sizeof steps[0].option, "--smooth %d", a.smooth.passes);
    }
    if (a.repair)
        steps[n++] = (line_step){"repair", ft_line_op_remove_loops, NULL, NULL, NULL, 0.0, ""};
    a.params = params_json(&a);
    return line_edit_run(cmd, argv[first], argv[first + 1], &a.io, steps, n, NULL, NULL, a.params);
}

const cli_command cli_cmd_enhance = {
    "enhance",
    "Dutton's fractal enhancement of generalized lines and polygon boundaries",
    "fracterra enhance INPUT OUTPUT [--sd D [--literal-sd] | --target-dim D] [--uc U] [--input-dim D] [--st LEN]\n"
    "                                [--sm LEN] [--iterations N | --keep-vertices] [--weed [--keep-shape]]\n"
    "                                [--smooth K] [--roundness R] [--repair] [--allow-crossings] [--no-coverage]\n"
    "                                [--layer NAME] [--where SQL] [-f DRIVER] [--json]",
    "Puts self-similar detail back into generalized lines (Dutton 1981, docs/line-enhance.md): at each\n"
    "iteration every interior vertex V splits its two segments at their midpoints M1, M2 and moves towards\n"
    "the apex of a triangle on M1 M2 with a fixed apex angle, keeping the ratio of the legs; UC scales that\n"
    "move. SD is the dimension you get: the apex angle is calibrated so that the divider dimension over the\n"
    "scales the enhancement generates is\n"
    "    D_target = D_in + UC (SD - D_in)       (UC in (0,1]; SD itself at UC = 1),\n"
    "D_in the input layer's walking-divider dimension over its automatic range (or --input-dim); UC = 0\n"
    "moves nothing, negative UC (exaggeration) and --literal-sd use Dutton's literal angle for SD. In the\n"
    "calibrated default, segments 3 times the input's mean segment or longer are first cut into pieces of\n"
    "about the mean and straight junctions bend too (to alternate sides), so that long straight borders get\n"
    "the same detail. Only vertices whose two segments are shorter than ST and not shorter than SM are\n"
    "altered; end points of open lines never move. No move makes a line cross or touch itself or another feature of the layer: a move\n"
    "that would is halved, quartered, or not made (the report counts them). Then, in this order: --weed\n"
    "drops vertices so that no segment is shorter than SM, --smooth cuts corners K times (guarded too),\n"
    "--repair removes the loops of self-intersections (only --allow-crossings makes new ones). The report\n"
    "gives the vertices after each step, the target and D_in, and the self-intersections left.\n"
    LINE_IO_COVERAGE_HELP "\n"
    "Options:\n"
    "  -d, --sd D           sinuosity dimension in [1,2]: the divider dimension of the result at UC = 1;\n"
    "                       default 1.3. At most 1.777 (UC = 1), 1.614 (UC = 0.7), 1.453 (UC = 0.5).\n"
    "                       'input': SD is the input's own D_in (Dutton's Newfoundland), the target\n"
    "                       whatever UC\n"
    "      --literal-sd     Dutton's literal reading: the apex angle pi - 2a, cos a = 2^(1/SD - 1), no\n"
    "                       calibration (it measures less than SD: SD 1.3 gives 1.12)\n"
    "      --target-dim D   the divider dimension wanted, whatever UC (--sd and D_in are then not used)\n"
    "      --input-dim D    D_in for UC < 1 instead of measuring it\n"
    "      --allow-crossings  the raw algorithm: every move made in full, even where lines then cross\n"
    "      --keep-vertices  one pass that leaves the input's vertices in place: a new midpoint M of P N goes\n"
    "                       to M - (dP + dN)/2, dP and dN the moves the pass above gives P and N (so M sits\n"
    "                       where it would relative to them); the input's large-scale shape, and its\n"
    "                       divider D at rulers of its own segments and above, are kept. --iterations 1\n"
    "  -u, --uc U           uniformity coefficient in [-1,1]: the fraction of the move (negative: the opposite\n"
    "                       way, exaggerating); default 1\n"
    "  -t, --st LEN         straightness tolerance: only segments shorter than LEN are altered; default inf\n"
    "  -m, --sm LEN         smoothness tolerance: only segments of at least LEN are altered; default 0.\n"
    "                       Dutton: \"roughly 1 percent of the width of the map window\"\n"
    "  -i, --iterations N   fractalizing iterations, 0..16 (each one about doubles the vertices); default 1\n"
    "      --weed           after fractalizing, drop vertices so that no segment is shorter than --sm\n"
    "      --keep-shape     with --weed: of a short segment's two vertices drop the one nearer to the chord\n"
    "                       of its neighbours (`weed --keep-shape`), not the next one\n"
    "  -s, --smooth K       then K passes of corner cutting (0..16); default 0\n"
    "  -r, --roundness R    corner cutting in (0,1]: V becomes V + R(M1-V) and V + R(M2-V) (0.5: Chaikin);\n"
    "                       default 0.5; alone, implies --smooth 1\n"
    "      --repair         finally remove the loops of self-intersecting chains\n" LINE_IO_HELP "\n"
    "Example (Dutton's Newfoundland: SM 1% of the island's 510 km width, ST very large):\n"
    "  fracterra simplify tests/data/gshhg_newfoundland_utm21n.geojson nf158.geojson --vertices 158\n"
    "  fracterra enhance nf158.geojson nf-enhanced.geojson --sd 1.3 --uc 0.7 --sm 5100 --weed --smooth 1\n"
    "  the same keeping D at each stage, SM 1% of a 4:3 map window holding the island (737 km wide; the\n"
    "  weeding then removes the paper's 10%: 158 -> 328 -> 293 -> 586 points, docs/line-newfoundland.md):\n"
    "  fracterra enhance nf158.geojson nf-d.geojson --sd 1.3 --uc 0.7 --sm 7372 --keep-vertices --weed --smooth 1\n",
    run_enhance,
};
