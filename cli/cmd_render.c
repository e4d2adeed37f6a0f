/* fracterra — cli/cmd_render.c: `fracterra render DEM OUT.png --view perspective`: a bird's-eye view of a
 * DEM, lit and z-buffered (ft_render_perspective, src/render/perspective.c; docs/render-perspective.md).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain_cli.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

typedef struct {
    ft_perspective_opts po;
    int json;
} render_args;

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    render_args *a = ctx;
    switch (opt) {
    case 'v':
        return strcmp(arg, "perspective") == 0 ? CLI_CONTINUE
                                               : cli_usage_error(cmd, "--view must be perspective, got '%s'", arg);
    case 'a': return cli_parse_double(cmd, "--azimuth", arg, -360.0, 360.0, CLI_CLOSED, &a->po.azimuth);
    case 'e': return cli_parse_double(cmd, "--elevation", arg, 5.0, 90.0, CLI_CLOSED, &a->po.elevation);
    case 'x': return cli_parse_double(cmd, "--exaggeration", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->po.exaggeration);
    case 'w': return cli_parse_int(cmd, "--width", arg, 64, 8192, &a->po.width);
    case 'A': return cli_parse_double(cmd, "--light-azimuth", arg, -360.0, 360.0, CLI_CLOSED, &a->po.light_azimuth);
    case 'H': return cli_parse_double(cmd, "--light-altitude", arg, 0.0, 90.0, CLI_OPEN_LO, &a->po.light_altitude);
    case 's': return cli_parse_double(cmd, "--scale", arg, 0.0, INFINITY, CLI_OPEN_LO, &a->po.scale);
    case 'n': a->po.sky = 0; return CLI_CONTINUE;
    case 'j': a->json = 1; return CLI_CONTINUE;
    default: return cli_usage_error(cmd, "unexpected option");
    }
}

static int report(const cli_command *cmd, const render_args *a, const char *in, const char *out)
{
    json_object *o = terrain_report_start(a->json, in, out);
    if (o == NULL)
        return CLI_OK;
    json_object_object_add(o, "view", json_object_new_string("perspective"));
    json_object_object_add(o, "azimuth", cli_json_double(a->po.azimuth));
    json_object_object_add(o, "elevation", cli_json_double(a->po.elevation));
    json_object_object_add(o, "exaggeration",
                           a->po.exaggeration > 0.0 ? cli_json_double(a->po.exaggeration) : json_object_new_string("auto"));
    json_object_object_add(o, "width", json_object_new_int(a->po.width));
    json_object_object_add(o, "light_azimuth", cli_json_double(a->po.light_azimuth));
    json_object_object_add(o, "light_altitude", cli_json_double(a->po.light_altitude));
    return cli_print_json(cmd, o);
}

static int run_render(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {
        {"view", required_argument, NULL, 'v'},           {"azimuth", required_argument, NULL, 'a'},
        {"elevation", required_argument, NULL, 'e'},      {"exaggeration", required_argument, NULL, 'x'},
        {"width", required_argument, NULL, 'w'},          {"light-azimuth", required_argument, NULL, 'A'},
        {"light-altitude", required_argument, NULL, 'H'}, {"scale", required_argument, NULL, 's'},
        {"no-sky", no_argument, NULL, 'n'},               {"json", no_argument, NULL, 'j'},
        CLI_OPT_HELP,                                     CLI_OPT_END};
    static const char *const names[] = {"DEM", "OUT.png"};
    render_args a = {.po = FT_PERSPECTIVE_OPTS_DEFAULT};
    int first = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "j", on_option, &a, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 2);
    if (rc == CLI_CONTINUE)
        rc = cli_refuse_overwrite(cmd, "OUT.png", argv[first + 1], argv[first], (const char *)NULL);
    if (rc != CLI_CONTINUE)
        return rc;
    const char *in = argv[first], *out = argv[first + 1];
    if (ft_io_check_writable(out) != FT_OK)
        return cli_fail(cmd);
    ft_grid *g = NULL;
    if (terrain_read_dem(cmd, in, &g) != CLI_CONTINUE)
        return CLI_FAIL;
    rc = ft_render_perspective(g, out, &a.po) == FT_OK ? report(cmd, &a, in, out) : cli_fail(cmd);
    ft_grid_free(g);
    return rc;
}

const cli_command cli_cmd_render = {
    "render",
    "render a DEM as a lit perspective (bird's-eye) view to PNG",
    "fracterra render DEM OUT.png [--view perspective] [--azimuth A] [--elevation E] [--exaggeration V]\n"
    "       [--width W] [--light-azimuth A] [--light-altitude H] [--scale S] [--no-sky] [--json]",
    "Draws the DEM's surface in perspective, z-buffered: hypsometric tints times Lambert shading, a\n"
    "little aerial haze with distance, on a sky gradient; nodata cells leave holes.\n\n"
    "Options:\n"
    "  --view perspective    the only view so far (default)\n"
    "  --azimuth A           direction the viewer looks towards, degrees clockwise from north (default 20)\n"
    "  --elevation E         line of sight below the horizon, degrees in [5,90] (default 35)\n"
    "  --exaggeration V      vertical exaggeration, > 0 (default: automatic, at least 1)\n"
    "  --width W             image width in pixels, in [64,8192] (default 1200; height follows)\n"
    "  --light-azimuth A     sun direction (default 315)\n"
    "  --light-altitude H    sun elevation, degrees in (0,90] (default 40)\n"
    "  --scale S             ground units per elevation unit (default: metres per degree on the\n"
    "                        ellipsoid at the centre for a DEM in degrees, else 1)\n"
    "  --no-sky              transparent background\n"
    "  -j, --json            print {\"input\", \"output\", \"view\", \"azimuth\", \"elevation\",\n"
    "                        \"exaggeration\", \"width\", \"light_azimuth\", \"light_altitude\"}\n"
    "  -h, --help            print this help\n\n"
    "Example:\n"
    "  fracterra render dem.tif view.png --view perspective --azimuth 30 --elevation 30 --exaggeration 2\n",
    run_render,
};
