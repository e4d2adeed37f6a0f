/* fracterra — cli/cmd_boundary.c: `fracterra boundary INPUT OUTPUT --dim D`: the midpoint-subdivision
 * generator of Zhang, Yu & Fan (2008, §2, Eqs. 9-13) run on the lines and polygon boundaries of a layer: each
 * segment between --min and --max becomes two legs whose apex sits at (r/2) tan a off its midpoint (cos a =
 * 2^(1/D - 1)), on a random side, jittered within a small square, and so on down to --min; longer segments
 * (walls of regular parcels) are kept. The read-edit-write driver is line_edit's (coverage topology on
 * polygon layers, atomic output, report), the step ft_urban_boundary_layer (guarded against crossings unless
 * --allow-crossings).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "line_edit.h"
#include "terrain_cli.h"

#include <math.h>

typedef struct {
    line_io io;
    ft_boundary_opts b;
    int repair;
} boundary_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    boundary_args *a = ctx;
    if (line_io_option(opt, arg, &a->io) == CLI_CONTINUE)
        return CLI_CONTINUE;
    switch (opt) {
    case 'd': return cli_parse_double(cmd, "--dim", arg, 1.0, 2.0, CLI_OPEN_LO | CLI_OPEN_HI, &a->b.dim);
    case 'm': return cli_parse_double(cmd, "--min", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->b.min);
    case 'M': return cli_parse_double(cmd, "--max", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->b.max);
    case 'r': return cli_parse_double(cmd, "--jitter", arg, 0.0, 1.0, CLI_CLOSED, &a->b.jitter);
    case 'S': return terrain_parse_seed(cmd, arg, &a->b.seed);
    case 'R': a->repair = 1; return CLI_CONTINUE;
    case 'X': a->b.allow_crossings = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

/* Checks the options together: CLI_CONTINUE or CLI_USAGE. */
static int check_args(const cli_command *cmd, const boundary_args *a)
{
    if (a->b.dim == 0.0)
        return cli_usage_error(cmd, "missing --dim D (the dimension of the detail, in (1,2))");
    double jmax = ft_urban_jitter_max(a->b.dim);
    if (a->b.jitter >= jmax)
        return cli_usage_error(cmd, "--jitter must be below %.4g for --dim %g (so that every leg is shorter than "
                                    "its segment), got %g",
                               jmax, a->b.dim, a->b.jitter);
    if (a->b.min > 0.0 && a->b.max > 0.0 && a->b.max < a->b.min)
        return cli_usage_error(cmd, "--max %g must be at least --min %g", a->b.max, a->b.min);
    return CLI_CONTINUE;
}

/* Once the layer is read: the default --max (the average chord, Eqs. 11-13) and --min (a tenth of it), and
 * the parameters echoed in the report. */
/* An upper bound of the vertices the subdivision makes: a segment of length r > min is halved about
 * D·log2(r/min) times (each leg is 2^(-1/D) of its parent), so it becomes about (r/min)^D legs; twice that
 * covers the rounding up of the levels. Refused beyond the memory bound, naming --min as the user gave it
 * or as it was defaulted. */
static int check_size(const ft_layer *l, const ft_boundary_opts *b, int min_given)
{
    double total = 0.0;
    for (size_t p = 0; p < l->nparts; p++) {
        const ft_chain *c = l->parts[p].chain;
        size_t nseg = ft_chain_segments(c);
        total += (double)c->n;
        for (size_t i = 0; i < nseg; i++) {
            size_t j = i + 1 == c->n ? 0 : i + 1;
            double r = hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
            if (r > b->min && r <= b->max)
                total += 2.0 * pow(r / b->min, b->dim);
        }
    }
    char what[200];
    if (min_given)
        snprintf(what, sizeof what, "--min %g (up to %.3g vertices)", b->min, total);
    else
        snprintf(what, sizeof what, "the default --min %g (a tenth of the average chord; up to %.3g vertices)",
                 b->min, total);
    return ft_check_memory(total * LINE_BYTES_PER_VERTEX, what);
}

static int prepare(const ft_layer *l, int coverage, void *ctx, json_object *params)
{
    boundary_args *a = ctx;
    ft_boundary_opts *b = &a->b;
    int min_given = b->min > 0.0;
    double avg = 0.0;
    int rc = ft_urban_layer_chord_avg(l, &avg);
    if (rc != FT_OK)
        return rc;
    if (!(avg > 0.0))
        return ft_error(FT_E_EMPTY, "no segment to subdivide: every chain has fewer than 2 distinct vertices");
    if (b->max == 0.0)
        b->max = b->min > avg ? b->min : avg;
    if (b->min == 0.0)
        b->min = fmin(FT_BOUNDARY_MIN_FRACTION * avg, b->max);
    if ((rc = check_size(l, b, min_given)) != FT_OK)
        return rc;
    json_object_object_add(params, "dim", cli_json_double(b->dim));
    json_object_object_add(params, "angle", cli_json_double(ft_urban_angle_for_dim(b->dim) * 180.0 / M_PI));
    json_object_object_add(params, "min", cli_json_double(b->min));
    json_object_object_add(params, "max", cli_json_double(b->max));
    json_object_object_add(params, "chord_avg", cli_json_double(avg));
    json_object_object_add(params, "jitter", cli_json_double(b->jitter));
    json_object_object_add(params, "seed", json_object_new_uint64(b->seed));
    json_object_object_add(params, "allow_crossings", json_object_new_boolean(b->allow_crossings));
    return FT_OK;
}

/* The subdivide step: the whole layer at once (ft_urban_boundary_layer), with the options prepare resolved. */
static int boundary_layer_step(ft_layer *l, void *ctx, int coverage, ft_line_guard_stats *stats)
{
    ft_boundary_info info;
    int rc = ft_urban_boundary_layer(l, ctx, coverage, &info);
    if (rc == FT_OK) {
        stats->moves += info.guard.moves;
        stats->reduced += info.guard.reduced;
        stats->dropped += info.guard.dropped;
        stats->redrawn += info.guard.redrawn;
    }
    return rc;
}

static int run_boundary(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"dim", required_argument, NULL, 'd'},    {"min", required_argument, NULL, 'm'},
        {"max", required_argument, NULL, 'M'},    {"jitter", required_argument, NULL, 'r'},
        {"seed", required_argument, NULL, 'S'},   {"repair", no_argument, NULL, 'R'},
        {"allow-crossings", no_argument, NULL, 'X'},
        LINE_IO_LONGOPTS,                         CLI_OPT_HELP,
        CLI_OPT_END,
    };
    boundary_args a = {LINE_IO_DEFAULT, FT_BOUNDARY_OPTS_DEFAULT, 0};
    int first = 0;
    int rc = line_edit_parse(cmd, argc, argv, longopts, "d:" LINE_IO_SHORTOPTS, on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = check_args(cmd, &a);
    if (rc != CLI_CONTINUE)
        return rc;
    line_step steps[2] = {{"subdivide", ft_urban_op_boundary, &a.b, boundary_layer_step, &a.b, 0.0, ""},
                          {"repair", ft_line_op_remove_loops, NULL, NULL, NULL, 0.0, ""}};
    return line_edit_run(cmd, argv[first], argv[first + 1], &a.io, steps, a.repair ? 2 : 1, prepare, &a,
                         json_object_new_object());
}

const cli_command cli_cmd_boundary = {
    "boundary",
    "simulate a boundary with detail of a given dimension (midpoint-subdivision generator)",
    "fracterra boundary INPUT OUTPUT --dim D [--min LEN] [--max LEN] [--jitter R] [--seed N] [--allow-crossings]\n"
    "                                 [--repair] [--no-coverage] [--layer NAME] [--where SQL] [-f DRIVER] [--json]",
    "Adds detail of dimension D to the lines and polygon boundaries of INPUT with the midpoint-subdivision\n"
    "generator of Zhang, Yu & Fan (2008, \xc2\xa7" "2): a segment of length r becomes two legs whose apex sits\n"
    "at L = (r/2) tan a off its midpoint, cos a = 2^(1/D - 1) (Eq. 9), on a side drawn at random, moved by\n"
    "up to R L along each axis (Eq. 10); the legs are split in turn while longer than --min. Segments longer\n"
    "than --max are kept as they are (the walls of regular parcels); input vertices never move. The same\n"
    "seed gives the same output, byte for byte. By default the segments are split level by level and an apex\n"
    "whose legs would cross or touch another segment of the layer is moved half, a quarter or none of the\n"
    "way from the midpoint (the report counts them), so the output is simple; --allow-crossings runs the\n"
    "paper's depth-first generator unguarded. Method: docs/urban-boundary.md.\n" LINE_IO_COVERAGE_HELP "\n"
    "Options:\n"
    "  -d, --dim D          the dimension of the detail, in (1,2), e.g. one measured by 'dim area' (required)\n"
    "      --min LEN        segments no longer than LEN are not split (map units); default: a tenth of --max\n"
    "      --max LEN        segments longer than LEN are kept unchanged; default: the average chord length\n"
    "                       of the input (its length over its number of segments, Eqs. 11-13)\n"
    "      --jitter R       apex moved by up to R L along x and y, R in [0, limit(D)): 0.707 up to D 1.4,\n"
    "                       0.68 at 1.5, 0.54 at 1.7, 0.45 at 1.9; default 0: the exact generator\n"
    "      --seed N         random sides and jitter; default 1 (printed in the JSON)\n"
    "      --allow-crossings  the unguarded depth-first generator: legs of neighbouring segments may cross\n"
    "                       at high D\n"
    "      --repair         then remove the loops where a chain (on a coverage, an arc) crosses itself\n"
    "                       (needed only with --allow-crossings)\n" LINE_IO_HELP
    "JSON: {\"input\", \"output\", \"layer\", \"features\", \"parts\", \"coverage\", \"dim\", \"angle\" (a, degrees),\n"
    "\"min\", \"max\", \"chord_avg\", \"jitter\", \"seed\", \"stages\", \"vertices_in\", \"vertices_out\",\n"
    "\"self_intersections\", \"crossing_guard\" (with --repair also \"self_intersections_before_repair\")}.\n\n"
    "Example:\n"
    "  fracterra boundary city-1997.gpkg city-detail.gpkg --dim 1.23 --min 5 --seed 7\n",
    run_boundary,
};
