/* fracterra — cli/terrain_cli.h: what the terrain commands (synth, model, hillshade, render) share: seeds,
 * reading a DEM with messages that name the file, and the figures of a grid for their JSON.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_TERRAIN_H
#define FRACTERRA_CLI_TERRAIN_H

#include <stdint.h>

#include "cli.h"

#define TERRAIN_DEFAULT_SEED 1

/** Parses --seed (a decimal integer in [0, 2^64 - 1]): CLI_CONTINUE, or CLI_USAGE naming the value. */
int terrain_parse_seed(const cli_command *cmd, const char *arg, uint64_t *seed);
/** --dim D: a number in (2,3), or "auto" (*dim = 0: estimated from the data), for fill and reconstruct. */
int terrain_parse_dim(const cli_command *cmd, const char *arg, double *dim);
/** Reads band 1 of a DEM: CLI_CONTINUE, or CLI_FAIL with "fracterra: CMD: <message naming the file>". */
int terrain_read_dem(const cli_command *cmd, const char *path, ft_grid **out);
/** Without --json, prints "wrote OUT" and returns NULL; with it, a new object {"input", "output"} for the
 *  command to complete and print (cli_print_json). */
json_object *terrain_report_start(int json, const char *in, const char *out);
/** {"size": [nx, ny], "mean", "sd", "min", "max"} of the valid cells. */
json_object *terrain_grid_figures(const ft_grid *g);
/** Adds "geotransform" (6 numbers), "crs" (WKT or null) and "grid" (terrain_grid_figures) to o. */
void terrain_add_grid_json(json_object *o, const ft_grid *g);
/** The same with the figures given (a grid written stripe by stripe: g is its header). */
json_object *terrain_grid_figures_of(const ft_grid *g, const ft_grid_stats *st);
void terrain_add_grid_json_of(json_object *o, const ft_grid *g, const ft_grid_stats *st);

#endif /* FRACTERRA_CLI_TERRAIN_H */
