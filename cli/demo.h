/* fracterra — cli/demo.h: the demo's shared state, so that each capability adds its piece of the gallery
 * as a step in its own file (cli/demo_<domain>.c) listed in cmd_demo.c's `steps` array.
 *
 * A step reads its input from ctx->data (demo_join_path), registers each output with demo_add_output
 * BEFORE writing it (so a failed demo removes it), writes it, and records the `fracterra info` figures of
 * its inputs with demo_add_input. It returns FT_OK or an FT_E_* code with ft_error set.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_DEMO_H
#define FRACTERRA_CLI_DEMO_H

#include "cli.h"

#define DEMO_MAX_OUTPUTS 64
#define SOURCE_GSHHG "GSHHG 2.3.7 full resolution shoreline, Wessel &amp; Smith (1996); LGPL-3+"

typedef struct {
    char *path;          /* OUTDIR/file */
    const char *file;    /* name inside OUTDIR, as index.html links it */
    const char *title;   /* short title */
    const char *caption; /* what it shows (HTML) */
    int image;           /* 1 if index.html shows it with <img> */
} demo_output;

typedef struct {
    const cli_command *cmd;
    const char *data;    /* the data folder */
    const char *outdir;
    demo_output out[DEMO_MAX_OUTPUTS];
    size_t nout;
    json_object *inputs; /* array: `fracterra info` of each input, plus "source" */
    ft_grid *volcano;    /* shared by the volcano steps */
} demo_ctx;

typedef int (*demo_step_fn)(demo_ctx *ctx);

/** malloc'd "dir/file". */
char *demo_join_path(const char *dir, const char *file);
/** Registers an output that a step is about to write; returns its path (owned by ctx) or NULL (error set). */
const char *demo_add_output(demo_ctx *ctx, const char *file, const char *title, const char *caption, int image);
/** Records the `fracterra info` figures of an input file of the data folder, with its source (HTML). */
int demo_add_input(demo_ctx *ctx, const char *file, const char *source);

/* The steps defined outside cmd_demo.c (cli/demo_<domain>.c). */
int demo_step_lines(demo_ctx *ctx); /* Dutton's Newfoundland sequence: map and log-log plots */

int demo_step_terrain(demo_ctx *ctx); /* synthetic and volcano DEMs: hillshades, perspectives, Clarke model */

int demo_step_urban(demo_ctx *ctx); /* a boundary simulated with the midpoint-subdivision generator, two zooms */

int demo_step_mountain(demo_ctx *ctx); /* a mountain grown from one seed contour: contour map, perspective */

#endif /* FRACTERRA_CLI_DEMO_H */
