/* fracterra — cli/line_edit.h: what the line-editing commands (enhance, simplify, weed, smooth) share:
 * their I/O options, steps made of line.h's ft_line_op operations, and one driver that reads the input
 * layer, applies the steps (on the arc-node topology of polygon layers unless --no-coverage), counts
 * self-intersections, writes the output atomically and reports what it made.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_LINE_EDIT_H
#define FRACTERRA_CLI_LINE_EDIT_H

#include "cli.h"

/* The I/O options of every line-editing command. */
typedef struct {
    const char *layer, *where; /**< --layer NAME, --where SQL */
    const char *driver;        /**< -f DRIVER; NULL = from the output's extension */
    int no_coverage;           /**< --no-coverage: edit every ring on its own */
    int json;
} line_io;
#define LINE_IO_DEFAULT {NULL, NULL, NULL, 0, 0}

enum { LINE_OPT_NO_COVERAGE = 0x200 };
#define LINE_IO_LONGOPTS                                                                                     \
    {"layer", required_argument, NULL, 'l'}, {"where", required_argument, NULL, 'w'},                        \
        {"format", required_argument, NULL, 'f'}, {"no-coverage", no_argument, NULL, LINE_OPT_NO_COVERAGE},  \
        {"json", no_argument, NULL, 'j'}
#define LINE_IO_SHORTOPTS "l:w:f:j"
#define LINE_IO_HELP                                                                                         \
    "  -l, --layer NAME     the vector layer to read (default: the first)\n"                                    \
    "  -w, --where SQL      only the features matching this OGR attribute filter (the others are not written)\n" \
    "  -f, --format DRIVER  OGR driver of OUTPUT (default: from its extension; .gmt/.xy/.txt: GMT text)\n"      \
    "      --no-coverage    on polygon layers, edit each ring on its own instead of each shared boundary once\n" \
    "  -j, --json           print one JSON object (vertices_in, vertices_out, self_intersections, output, ...)\n" \
    "  -h, --help           print this help\n"
#define LINE_IO_COVERAGE_HELP                                                                                \
    "On a polygon layer the shared boundaries of adjacent polygons are edited once (arc-node topology, the\n"  \
    "nodes kept in place), so neighbours stay coincident: no gap, no overlap. Attributes and CRS are kept;\n"  \
    "OUTPUT is written under a temporary name and renamed when complete.\n"

/* Returned by line_io_option for an option that is not one of the shared ones. */
#define LINE_IO_NOT_SHARED (-101)

/** Handles a shared option: CLI_CONTINUE, or LINE_IO_NOT_SHARED. */
int line_io_option(int opt, const char *arg, line_io *io);
/** cli_parse_options, then exactly INPUT and OUTPUT: CLI_CONTINUE with *first set, or an exit code. */
int line_edit_parse(const cli_command *cmd, int argc, char **argv, const struct option *longopts,
                    const char *shortopts, cli_opt_fn fn, void *ctx, int *first);

/* A step applied to the whole layer at once (e.g. ft_line_enhance_layer, so that the crossing guard sees
 * every feature); adds what its guard did to *stats. FT_OK or an error code (error set). */
typedef int (*line_layer_fn)(ft_layer *l, void *ctx, int coverage, ft_line_guard_stats *stats);

/* One step of an edit: op applied chain by chain through ft_line_apply_layer, or layer (if not NULL). */
typedef struct {
    const char *name; /**< "fractalize", "weed", "smooth", "simplify", "repair" */
    ft_line_op op;    /**< ft_line_op_enhance, ft_line_op_weed, ... (line.h) */
    const void *opts;
    line_layer_fn layer; /**< a layer-level step (coverage, crossing guard) or NULL */
    void *ctx;
    double growth;    /**< at most this many vertices out per vertex in (0 or 1: no growth) */
    char option[48];  /**< the option that drives the growth, as the user gave it ("--iterations 16") */
} line_step;

/** The layer step of smoothing: ctx is an ft_smooth_opts *. */
int line_smooth_layer_step(ft_layer *l, void *ctx, int coverage, ft_line_guard_stats *stats);

/* Memory per output vertex of a line edit: x and y in the edited chain, its copy in the layer, the writer's
 * OGR geometry. */
#define LINE_BYTES_PER_VERTEX 48.0

/* Called once the input is read, before the steps (e.g. to choose a tolerance from the data); may add
 * members to params. FT_OK or an error code (error set). */
typedef int (*line_prepare_fn)(const ft_layer *l, int coverage, void *ctx, json_object *params);

/** Reads input, applies the steps in order, writes output and reports (JSON: "input", "output", "layer",
 *  "features", "parts", "coverage", the members of params (owned) echoing the parameters, "stages",
 *  "vertices_in", "vertices_out", "self_intersections", "crossing_guard" (moves, reduced, dropped: what the
 *  guard of the layer steps did; absent without one); with a repair step also
 *  "self_intersections_before_repair"). Returns the exit code; on failure nothing is written. */
int line_edit_run(const cli_command *cmd, const char *input, const char *output, const line_io *io,
                  const line_step *steps, size_t nsteps, line_prepare_fn prepare, void *ctx, json_object *params);

#endif /* FRACTERRA_CLI_LINE_EDIT_H */
