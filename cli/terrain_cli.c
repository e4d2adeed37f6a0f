/* fracterra — cli/terrain_cli.c: helpers shared by the terrain commands (see terrain_cli.h).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain_cli.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int terrain_parse_seed(const cli_command *cmd, const char *arg, uint64_t *seed)
{
    char *end = NULL;
    errno = 0;
    unsigned long long v = strtoull(arg, &end, 10);
    if (errno != 0 || end == arg || *end != '\0' || arg[0] == '-' || arg[0] == '+')
        return cli_usage_error(cmd, "--seed must be an integer in [0,18446744073709551615], got '%s'", arg);
    *seed = (uint64_t)v;
    return CLI_CONTINUE;
}

int terrain_parse_dim(const cli_command *cmd, const char *arg, double *dim)
{
    if (strcmp(arg, "auto") == 0) {
        *dim = 0.0;
        return CLI_CONTINUE;
    }
    char *end = NULL;
    errno = 0;
    double v = strtod(arg, &end);
    if (end == arg || *end != '\0' || errno != 0 || !(v > 2.0 && v < 3.0))
        return cli_usage_error(cmd, "--dim must be a number in (2,3) or 'auto', got '%s'", arg);
    *dim = v;
    return CLI_CONTINUE;
}

int terrain_read_dem(const cli_command *cmd, const char *path, ft_grid **out)
{
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    if (ft_io_read_grid(path, &ro, out) != FT_OK)
        return cli_fail(cmd);
    if (cli_check_grid_work(cmd, path, *out) != CLI_CONTINUE) {
        ft_grid_free(*out);
        *out = NULL;
        return CLI_FAIL;
    }
    return CLI_CONTINUE;
}

json_object *terrain_report_start(int json, const char *in, const char *out)
{
    if (!json) {
        printf("wrote %s\n", out);
        return NULL;
    }
    json_object *o = json_object_new_object();
    json_object_object_add(o, "input", json_object_new_string(in));
    json_object_object_add(o, "output", json_object_new_string(out));
    return o;
}

json_object *terrain_grid_figures(const ft_grid *g)
{
    ft_grid_stats st;
    ft_grid_compute_stats(g, &st);
    return terrain_grid_figures_of(g, &st);
}

json_object *terrain_grid_figures_of(const ft_grid *g, const ft_grid_stats *st)
{
    json_object *o = json_object_new_object(), *size = json_object_new_array();
    json_object_array_add(size, json_object_new_int64((int64_t)g->nx));
    json_object_array_add(size, json_object_new_int64((int64_t)g->ny));
    json_object_object_add(o, "size", size);
    json_object_object_add(o, "mean", cli_json_double(st->mean));
    json_object_object_add(o, "sd", cli_json_double(st->sd));
    json_object_object_add(o, "min", cli_json_double(st->min));
    json_object_object_add(o, "max", cli_json_double(st->max));
    return o;
}

void terrain_add_grid_json(json_object *o, const ft_grid *g)
{
    ft_grid_stats st;
    ft_grid_compute_stats(g, &st);
    terrain_add_grid_json_of(o, g, &st);
}

void terrain_add_grid_json_of(json_object *o, const ft_grid *g, const ft_grid_stats *st)
{
    json_object *gt = json_object_new_array();
    for (int i = 0; i < 6; i++)
        json_object_array_add(gt, cli_json_double(g->gt[i]));
    json_object_object_add(o, "geotransform", gt);
    json_object_object_add(o, "crs", g->crs_wkt ? json_object_new_string(g->crs_wkt) : NULL);
    json_object_object_add(o, "grid", terrain_grid_figures_of(g, st));
}
