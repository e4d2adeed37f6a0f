/* fracterra — cli/cli_geo.c: the commands' side of geographic input (cli_geo.h): the CRS, the units of the
 * results, and local projections centred on the data.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli_geo.h"

#include <math.h>
#include <stdlib.h>

int cli_geo_crs(const cli_command *cmd, const char *path, const char *wkt, ft_crs_info *crs)
{
    if (ft_io_crs_info(wkt, crs) == FT_OK)
        return CLI_CONTINUE;
    cli_error(cmd, "%s: %s", path, ft_last_error());
    return CLI_FAIL;
}

void cli_geo_units(ft_dim_result *r, const ft_crs_info *crs)
{
    if (r == NULL || r->units[0] != '\0')
        return;
    if (crs->scale_unit[0] != '\0')
        ft_dim_result_set_units(r, crs->scale_unit);
    else if (!crs->has_crs)
        ft_dim_result_warn(r, "the input has no CRS: scales are in its own coordinate unit, taken as planar");
}

int cli_geo_local_crs(const cli_command *cmd, const char *wkt, ft_local_projection kind, double xmin, double ymin,
                      double xmax, double ymax, char **local)
{
    if (ft_io_local_crs(wkt, kind, 0.5 * (xmin + xmax), 0.5 * (ymin + ymax), local) == FT_OK)
        return CLI_CONTINUE;
    return cli_fail(cmd);
}

int cli_geo_layer_local(const cli_command *cmd, const ft_layer *l, ft_local_projection kind, ft_layer **out)
{
    double x0, y0, x1, y1;
    char *wkt = NULL;
    *out = NULL;
    if (ft_layer_bbox(l, &x0, &y0, &x1, &y1) != FT_OK)
        return cli_fail(cmd);
    int rc = cli_geo_local_crs(cmd, l->crs_wkt, kind, x0, y0, x1, y1, &wkt);
    if (rc != CLI_CONTINUE)
        return rc;
    ft_layer *p = ft_layer_copy(l);
    if (p == NULL || ft_io_layer_reproject(p, wkt) != FT_OK) {
        ft_layer_free(p);
        free(wkt);
        return cli_fail(cmd);
    }
    free(wkt);
    *out = p;
    return CLI_CONTINUE;
}

int cli_geo_layer_ground(const cli_command *cmd, const char *path, ft_layer *l, ft_local_projection kind,
                         ft_crs_info *crs)
{
    int rc = cli_geo_crs(cmd, path, l->crs_wkt, crs);
    if (rc != CLI_CONTINUE || !crs->geographic)
        return rc;
    double x0, y0, x1, y1;
    char *wkt = NULL;
    if (ft_layer_bbox(l, &x0, &y0, &x1, &y1) != FT_OK)
        return cli_fail(cmd);
    if ((rc = cli_geo_local_crs(cmd, l->crs_wkt, kind, x0, y0, x1, y1, &wkt)) != CLI_CONTINUE)
        return rc;
    if (ft_io_layer_reproject(l, wkt) != FT_OK) {
        cli_error(cmd, "%s: %s", path, ft_last_error());
        rc = CLI_FAIL;
    }
    free(wkt);
    return rc;
}

int cli_geo_points_ground(const cli_command *cmd, const char *path, ft_points *p, ft_crs_info *crs)
{
    int rc = cli_geo_crs(cmd, path, p->crs_wkt, crs);
    if (rc != CLI_CONTINUE || !crs->geographic || p->n == 0)
        return rc;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t i = 0; i < p->n; i++) {
        x0 = fmin(x0, p->x[i]);
        x1 = fmax(x1, p->x[i]);
        y0 = fmin(y0, p->y[i]);
        y1 = fmax(y1, p->y[i]);
    }
    char *wkt = NULL;
    if ((rc = cli_geo_local_crs(cmd, p->crs_wkt, FT_LOCAL_TMERC, x0, y0, x1, y1, &wkt)) != CLI_CONTINUE)
        return rc;
    if (ft_io_points_reproject(p, wkt) != FT_OK) {
        cli_error(cmd, "%s: %s", path, ft_last_error());
        rc = CLI_FAIL;
    }
    free(wkt);
    return rc;
}

int cli_geo_grid_local(const cli_command *cmd, const ft_grid *g, ft_grid **out)
{
    ft_crs_info crs;
    double x0, y0, x1, y1;
    char *wkt = NULL;
    *out = NULL;
    if (ft_io_crs_info(g->crs_wkt, &crs) != FT_OK)
        return cli_fail(cmd);
    ft_grid_extent(g, &x0, &y0, &x1, &y1);
    int rc = cli_geo_local_crs(cmd, g->crs_wkt, FT_LOCAL_TMERC, x0, y0, x1, y1, &wkt);
    if (rc != CLI_CONTINUE)
        return rc;
    double per_lon, per_lat;
    ft_ellipsoid_metres_per_degree(&crs.ellipsoid, 0.5 * (y0 + y1), &per_lon, &per_lat);
    double cell = sqrt(fabs(g->gt[1]) * per_lon * fabs(g->gt[5]) * per_lat);
    rc = ft_io_grid_reproject(g, wkt, cell, out) == FT_OK ? CLI_CONTINUE : cli_fail(cmd);
    free(wkt);
    return rc;
}

int cli_geo_grid_ground(const cli_command *cmd, const char *path, ft_grid **g, ft_crs_info *crs)
{
    int rc = cli_geo_crs(cmd, path, (*g)->crs_wkt, crs);
    if (rc != CLI_CONTINUE || !crs->geographic)
        return rc;
    ft_grid *p = NULL;
    if ((rc = cli_geo_grid_local(cmd, *g, &p)) != CLI_CONTINUE)
        return rc;
    ft_grid_free(*g);
    *g = p;
    return CLI_CONTINUE;
}

json_object *cli_geo_json(const ft_crs_info *crs, const char *projection_wkt)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "crs", json_object_new_string(crs->name));
    json_object_object_add(o, "ellipsoid", json_object_new_string(crs->ellipsoid_name));
    ft_crs_info p;
    if (projection_wkt && ft_io_crs_info(projection_wkt, &p) == FT_OK)
        json_object_object_add(o, "projection", json_object_new_string(p.name));
    else
        json_object_object_add(o, "projection", NULL);
    return o;
}

int cli_geo_refuse(const cli_command *cmd, const char *path, const ft_crs_info *crs, const char *why,
                   const char *how)
{
    cli_error(cmd, "%s is in longitude/latitude (%s): %s; reproject it to a projected CRS first (%s)", path,
              crs->name, why, how);
    return CLI_FAIL;
}
