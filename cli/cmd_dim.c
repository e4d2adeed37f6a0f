/* fracterra — cli/cmd_dim.c: `fracterra dim SUBCOMMAND ...`: the fractal dimension of what a file holds.
 *
 * Each subcommand is a command of its own (cmd_dim_<name>.c, named "dim <name>" so that its messages read
 * "fracterra: dim line: ..."), listed in the table below; a new estimator adds one entry here and one line
 * to the help text.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"

static const cli_command *const subcommands[] = {
    &cli_cmd_dim_line,
    &cli_cmd_dim_surface,
    &cli_cmd_dim_profile,
    &cli_cmd_dim_map,
    &cli_cmd_dim_area,
    &cli_cmd_dim_points,
};

static int run_dim(const cli_command *cmd, int argc, char **argv)
{
    return cli_run_subcommand(cmd, subcommands, sizeof subcommands / sizeof subcommands[0], argc, argv);
}

const cli_command cli_cmd_dim = {
    "dim",
    "fractal dimension of lines, polygon layers, elevation grids (also as a local map) and scattered points",
    "fracterra dim SUBCOMMAND [OPTIONS] INPUT",
    "Measures the fractal dimension of a file's content; every estimator reports D with r\xc2\xb2, its\n"
    "standard error, the scale range fitted and the whole log-log table (--json, --plot).\n\n"
    "Subcommands:\n"
    "  line   lines and polygon boundaries of a vector layer or GMT text file\n"
    "  surface an elevation grid: variogram, yokoya, pentland, spectrum, prism, cubes\n"
    "  profile an elevation profile (3-D line, DEM row or transect): madogram, variogram\n"
    "  map    a local D (roughness) map of an elevation grid, written as a raster\n"
    "  area   polygons (boundary or area box counting) of a layer, per class; classified rasters\n"
    "  points scattered elevations (CSV, XYZ, point layers): Yokoya, Pentland\n\n"
    "Run 'fracterra dim SUBCOMMAND --help' for its options.\n\n"
    "Example:\n"
    "  fracterra dim line coast.geojson --method divider --plot coast-dim.svg\n",
    run_dim,
};
