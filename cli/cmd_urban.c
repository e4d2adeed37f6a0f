/* fracterra — cli/cmd_urban.c: `fracterra urban SUBCOMMAND ...`: urban morphology across years (Zhang, Yu &
 * Fan 2008): the per-year table of box-counting dimensions per land-use class (urban_table.c) and the
 * regression of area on dimension (urban_regress.c). Each subcommand is a command of its own, named
 * "urban <name>" so that its messages read "fracterra: urban table: ...".
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"

static const cli_command *const subcommands[] = {
    &cli_cmd_urban_table,
    &cli_cmd_urban_regress,
};

static int run_urban(const cli_command *cmd, int argc, char **argv)
{
    return cli_run_subcommand(cmd, subcommands, sizeof subcommands / sizeof subcommands[0], argc, argv);
}

const cli_command cli_cmd_urban = {
    "urban",
    "land-use classes across years: table of D, area and polygons; regression of area on D",
    "fracterra urban SUBCOMMAND [OPTIONS] ARGS...",
    "Follows how complex each land-use class of a city becomes as it grows (Zhang, Yu & Fan 2008).\n\n"
    "Subcommands:\n"
    "  table     one row per land-use map (year): D, area and polygons of each class; CSV or JSON, chart\n"
    "  regress   least squares of one table column on another, e.g. ln(area) on D (Eq. 5), with r\n\n"
    "Run 'fracterra urban SUBCOMMAND --help' for its options. The box-counting dimension of one layer:\n"
    "'fracterra dim area'; a boundary simulated with detail of a dimension: 'fracterra boundary'.\n\n"
    "Example:\n"
    "  fracterra urban table lu1959.gpkg lu1997.gpkg --class use --label 1959 --label 1997 -o t.csv\n"
    "  fracterra urban regress t.csv --class residential --x D --y area --log-y\n",
    run_urban,
};
