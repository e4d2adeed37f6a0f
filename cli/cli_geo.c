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

int cli_geo_local_crs(const cli_command *cmd, const char *wkt, ft_local_projection kind, double lon0, double lat0,
                      char **local)
{
    if (ft_io_local_crs(wkt, kind, lon0, lat0, local) == FT_OK)
        return CLI_CONTINUE;
    return cli_fail(cmd);
}

/* Longitudes and latitudes seen so far: the plain longitude range and the one with negative longitudes moved
 * by 360 degrees, which is the narrower for data crossing the antimeridian. */
typedef struct {
    double lo, hi, lo360, hi360, ylo, yhi;
} lonlat_range;

#define LONLAT_RANGE_EMPTY {INFINITY, -INFINITY, INFINITY, -INFINITY, INFINITY, -INFINITY}

static void lonlat_range_add(lonlat_range *r, const double *x, const double *y, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double x360 = x[i] < 0.0 ? x[i] + 360.0 : x[i];
        r->lo = fmin(r->lo, x[i]);
        r->hi = fmax(r->hi, x[i]);
        r->lo360 = fmin(r->lo360, x360);
        r->hi360 = fmax(r->hi360, x360);
        r->ylo = fmin(r->ylo, y[i]);
        r->yhi = fmax(r->yhi, y[i]);
    }
}

/* The centre of the data for a local projection: on the antimeridian side if that range is the narrower.
 * Data spanning more than 180 degrees of longitude either way are refused (no local projection holds them). */
static int lonlat_range_centre(const cli_command *cmd, const char *what, const lonlat_range *r, double *lon0,
                               double *lat0)
{
    double plain = r->hi - r->lo, across = r->hi360 - r->lo360;
    int wrap = across < plain;
    double span = wrap ? across : plain;
    if (!(span <= 180.0)) {
        cli_error(cmd, "%s spans %.1f degrees of longitude (%.4g to %.4g), %s: no local projection holds it; split "
                  "it or reproject it to a projected CRS first (ogr2ogr -t_srs)", what, span, r->lo, r->hi,
                  wrap ? "even across the antimeridian" : "and as much across the antimeridian");
        return CLI_FAIL;
    }
    double c = wrap ? 0.5 * (r->lo360 + r->hi360) : 0.5 * (r->lo + r->hi);
    *lon0 = c > 180.0 ? c - 360.0 : c;
    *lat0 = 0.5 * (r->ylo + r->yhi);
    return CLI_CONTINUE;
}

static int layer_centre(const cli_command *cmd, const char *what, const ft_layer *l, double *lon0, double *lat0)
{
    lonlat_range r = LONLAT_RANGE_EMPTY;
    for (size_t p = 0; p < l->nparts; p++)
        if (l->parts[p].chain)
            lonlat_range_add(&r, l->parts[p].chain->x, l->parts[p].chain->y, l->parts[p].chain->n);
    if (l->topology)
        for (size_t a = 0; a < l->topology->narcs; a++)
            lonlat_range_add(&r, l->topology->arcs[a]->x, l->topology->arcs[a]->y, l->topology->arcs[a]->n);
    if (!(r.lo <= r.hi)) {
        cli_error(cmd, "%s has no vertex to centre a local projection on", what);
        return CLI_FAIL;
    }
    return lonlat_range_centre(cmd, what, &r, lon0, lat0);
}

int cli_geo_layer_local(const cli_command *cmd, const char *path, const ft_layer *l, ft_local_projection kind,
                        ft_layer **out)
{
    double lon0, lat0;
    char *wkt = NULL;
    *out = NULL;
    int rc = layer_centre(cmd, path, l, &lon0, &lat0);
    if (rc == CLI_CONTINUE)
        rc = cli_geo_local_crs(cmd, l->crs_wkt, kind, lon0, lat0, &wkt);
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
    double lon0, lat0;
    char *wkt = NULL;
    if ((rc = layer_centre(cmd, path, l, &lon0, &lat0)) != CLI_CONTINUE ||
        (rc = cli_geo_local_crs(cmd, l->crs_wkt, kind, lon0, lat0, &wkt)) != CLI_CONTINUE)
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
    lonlat_range r = LONLAT_RANGE_EMPTY;
    lonlat_range_add(&r, p->x, p->y, p->n);
    double lon0, lat0;
    char *wkt = NULL;
    if ((rc = lonlat_range_centre(cmd, path, &r, &lon0, &lat0)) != CLI_CONTINUE ||
        (rc = cli_geo_local_crs(cmd, p->crs_wkt, FT_LOCAL_TMERC, lon0, lat0, &wkt)) != CLI_CONTINUE)
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
    /* a grid's columns are continuous in longitude (179.5 .. 180.5 across the antimeridian; GDAL's warp
     * reads such a source), so its centre is the middle of its extent */
    if (!(x1 - x0 <= 180.0)) {
        cli_error(cmd, "the grid spans %.1f degrees of longitude (%.4g to %.4g): no local projection holds it; "
                  "cut it or warp it to a projected CRS first (gdalwarp -t_srs)", x1 - x0, x0, x1);
        return CLI_FAIL;
    }
    int rc = cli_geo_local_crs(cmd, g->crs_wkt, FT_LOCAL_TMERC, 0.5 * (x0 + x1), 0.5 * (y0 + y1), &wkt);
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

void cli_geo_warn_square_cells(const cli_command *cmd, const char *path, const ft_grid *g, const ft_crs_info *crs)
{
    double per_lon, per_lat, x0, y0, x1, y1;
    ft_grid_extent(g, &x0, &y0, &x1, &y1);
    ft_ellipsoid_metres_per_degree(&crs->ellipsoid, 0.5 * (y0 + y1), &per_lon, &per_lat);
    cli_warn(cmd, "%s is in longitude/latitude (%s): its cells are %.0f m x %.0f m on the ground, and the voids "
                  "are filled as if they were square (reproject it first for an isotropic model)",
             path, crs->name, fabs(g->gt[1]) * per_lon, fabs(g->gt[5]) * per_lat);
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
