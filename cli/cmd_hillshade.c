/* fracterra — cli/cmd_hillshade.c: `fracterra hillshade DEM OUT`: shaded relief by the library's engine
 * (cell for cell gdaldem hillshade -compute_edges), optionally times a hypsometric colour relief.
 * The library side is ft_io_hillshade (src/io/dem_processing.c).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain_cli.h"
#include "tile_cli.h"
#include "cli_ranks.h"

#include <math.h>
#include <stdio.h>

typedef struct {
    ft_io_hillshade_opts ho;
    int json;
    long tile_rows; /* 0: automatic */
} hillshade_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    hillshade_args *a = ctx;
    switch (opt) {
    case 'a': return cli_parse_double(cmd, "--azimuth", arg, 0.0, 360.0, CLI_CLOSED, &a->ho.azimuth);
    case 'H': return cli_parse_double(cmd, "--altitude", arg, 0.0, 90.0, CLI_OPEN_LO, &a->ho.altitude);
    case 'z': return cli_parse_double(cmd, "--z-factor", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->ho.z_factor);
    case 's': return cli_parse_double(cmd, "--scale", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->ho.scale);
    case 'b': return cli_parse_int(cmd, "--band", arg, 1, 65535, &a->ho.band);
    case 'c': a->ho.color = 1; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    case 'T': return tile_parse_rows(cmd, arg, &a->tile_rows);
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int report(const cli_command *cmd, const hillshade_args *a, const char *in, const char *out)
{
    json_object *o = terrain_report_start(a->json, in, out);
    if (o == NULL)
        return CLI_OK;
    json_object_object_add(o, "azimuth", cli_json_double(a->ho.azimuth));
    json_object_object_add(o, "altitude", cli_json_double(a->ho.altitude));
    json_object_object_add(o, "z_factor", cli_json_double(a->ho.z_factor));
    double scale = 0.0;
    if (ft_io_hillshade_scale(in, &a->ho, &scale) != FT_OK) {
        json_object_put(o);
        return cli_fail(cmd);
    }
    json_object_object_add(o, "scale", cli_json_double(scale));
    json_object_object_add(o, "scale_from", json_object_new_string(a->ho.scale > 0.0 ? "--scale" : "automatic"));
    json_object_object_add(o, "band", json_object_new_int(a->ho.band));
    json_object_object_add(o, "color", json_object_new_boolean(a->ho.color));
    return cli_print_json(cmd, o);
}

static int run_hillshade(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"azimuth", required_argument, NULL, 'a'}, {"altitude", required_argument, NULL, 'H'},
        {"z-factor", required_argument, NULL, 'z'}, {"scale", required_argument, NULL, 's'},
        {"band", required_argument, NULL, 'b'},     {"color", no_argument, NULL, 'c'},
        {"colour", no_argument, NULL, 'c'},         {"json", no_argument, NULL, 'j'},
        {"tile-rows", required_argument, NULL, 'T'},
        CLI_OPT_HELP,                               CLI_OPT_END};
    static const char *const names[] = {"DEM", "OUT"};
    hillshade_args a = {.ho = FT_IO_HILLSHADE_OPTS_DEFAULT};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "OUT", argv[first + 1], argv[first], (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    /* Stripes only when asked for or on MPI ranks: one process streams any DEM within --max-memory. */
    if (a.tile_rows > 0 || cli_ranks_joined()) {
        rc = tile_hillshade(cmd, argv[first], argv[first + 1], &a.ho, a.tile_rows);
        return rc == CLI_OK && cli_rank() == 0 ? report(cmd, &a, argv[first], argv[first + 1]) : rc;
    }
    if (ft_io_hillshade(argv[first], argv[first + 1], &a.ho) != FT_OK)
        return cli_fail(cmd);
    return report(cmd, &a, argv[first], argv[first + 1]);
}

const cli_command cli_cmd_hillshade = {
    "hillshade",
    "shaded relief of a DEM (as gdaldem hillshade), optionally with colour relief",
    "fracterra hillshade DEM OUT.png|OUT.tif [--azimuth A] [--altitude H] [--z-factor Z] [--scale S]\n"
    "       [--color] [--band N] [--tile-rows N] [--json]\n"
    "       mpiexec -n N fracterra hillshade DEM OUT.tif [...]",
    "Shades a DEM with the library's hillshade (Horn's slope, edges computed, 0 = nodata), written as\n"
    "gdaldem hillshade -compute_edges writes it (within 1 grey level). With --color, a hypsometric\n"
    "colour relief (gdaldem color-relief, built-in ramp from green lowlands to white summits, nodata\n"
    "transparent) is multiplied by the shade. The output format\n"
    "follows the extension (PNG, GeoTIFF with the DEM's georeferencing, ...); it is written under a\n"
    "temporary name and renamed when complete. Without --color, a format GDAL can create (GeoTIFF, ...)\n"
    "is written chunk by chunk as it is shaded (memory: a few chunks of about 1 M cells, fewer rows under\n"
    "a small --max-memory, not the DEM), so a DEM of any size within the work bound is shaded in one\n"
    "process; a DEM whose 2-row chunk exceeds --max-memory is refused. PNG and --color hold the whole\n"
    "image (2 and 10 bytes per cell) and are refused beyond --max-memory.\n"
    "With --tile-rows, or under mpiexec, the DEM is shaded in stripes of rows (each with one row above\n"
    "and below) into a Byte GeoTIFF (.tif), cell for cell the whole-DEM run's; the ranks share the\n"
    "stripes and rank 0 writes (docs/tiling.md). Not with --color.\n\n"
    "Options:\n"
    "  --azimuth A    light direction, degrees clockwise from north, in [0,360] (default 315)\n"
    "  --altitude H   light elevation, degrees, in (0,90] (default 45)\n"
    "  --z-factor Z   vertical exaggeration, > 0 (default 1)\n"
    "  --scale S      ground units of the DEM's horizontal coordinates per elevation unit,\n"
    "                 as gdaldem -s (default: metres per degree of latitude on the ellipsoid\n"
    "                 at the centre for a DEM in degrees, else 1)\n"
    "  --color        multiply a hypsometric colour relief by the shade (RGBA output)\n"
    "  --band N       band of the DEM (default 1)\n"
    "  --tile-rows N  shade N rows per stripe into a GeoTIFF (default: no stripes; under mpiexec,\n"
    "                 stripes of a quarter of --max-memory)\n"
    "  -j, --json     print {\"input\", \"output\", \"azimuth\", \"altitude\", \"z_factor\", \"scale\" (the one\n"
    "                 used), \"scale_from\", \"band\", \"color\"}\n"
    "  -h, --help     print this help\n\n"
    "Example:\n"
    "  fracterra hillshade dem.tif relief.png --z-factor 2 --color\n",
    run_hillshade,
};
