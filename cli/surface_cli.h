/* fracterra — cli/surface_cli.h: what `dim surface` and `dim map` share (cmd_dim_surface.c): reading a band
 * of a DEM, the --method list and the default pairing of the lag methods.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_SURFACE_H
#define FRACTERRA_CLI_SURFACE_H

#include "cli.h"

/* Grids with more cells than this are measured by the lag methods from 32,000 random points (Mark &
 * Aronson) unless --pairs says otherwise; smaller ones exhaustively. */
#define SURFACE_EXHAUSTIVE_CELLS ((size_t)1024 * 1024)
#define SURFACE_DEFAULT_PAIRS 32000

/** Reads band `band` of a DEM: CLI_CONTINUE, or CLI_FAIL with a message naming the file. */
int surface_read_dem(const cli_command *cmd, const char *path, int band, ft_grid **out, ft_crs_info *crs);
/** Parses "all" (when allow_all) or a comma-separated list of distinct methods into ms (room for
 *  FT_SURFACE_NMETHODS): CLI_CONTINUE with *n set, or CLI_USAGE naming the text. */
int surface_parse_methods(const cli_command *cmd, const char *text, int allow_all, ft_surface_method *ms, int *n);
/** Parses --pairs N (0 .. 100,000,000) into *pairs: CLI_CONTINUE, or CLI_USAGE naming the value. */
int surface_parse_pairs(const cli_command *cmd, const char *arg, long *pairs);
/** The --pairs in force: `pairs` if given (>= 0), else 0 (exhaustive) up to SURFACE_EXHAUSTIVE_CELLS cells
 *  and SURFACE_DEFAULT_PAIRS above. */
size_t surface_pairs(long pairs, const ft_grid *g);

#endif /* FRACTERRA_CLI_SURFACE_H */
