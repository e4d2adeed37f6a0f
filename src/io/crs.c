/* fracterra — src/io/crs.c: the one CRS service. Everything else asks it whether coordinates are degrees
 * (geographic), what their linear unit is and how many metres it holds, and on which ellipsoid a
 * geographic CRS lives; nothing else in fracterra looks into a WKT.
 *
 * The WKT is resolved by OSR (GDAL's OGRSpatialReference over PROJ): a compound CRS is reduced to its
 * horizontal part (OSRStripVertical), and a WKT2 BOUNDCRS answers for its source CRS (OSR demotes it to
 * its base when asked IsGeographic, the units or the ellipsoid), so "EPSG:4326 + a TOWGS84 bound" and
 * "EPSG:4326 + EGM96 height" are both geographic.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "internal.h"
#include "io/io_internal.h"

static void copy_text(char *dst, size_t size, const char *src)
{
    if (size == 0)
        return;
    size_t n = src ? strlen(src) : 0;
    n = n < size - 1 ? n : size - 1;
    if (n)
        memcpy(dst, src, n);
    dst[n] = '\0';
}

/* "m", "ft", "US ft" for the usual units, else the unit's own name. */
static void short_unit(const char *name, double metres, char *out, size_t size)
{
    if (fabs(metres - 1.0) < 1e-12)
        copy_text(out, size, "m");
    else if (fabs(metres - 0.3048) < 1e-12)
        copy_text(out, size, "ft");
    else if (fabs(metres - 1200.0 / 3937.0) < 1e-12)
        copy_text(out, size, "US ft");
    else if (fabs(metres - 1000.0) < 1e-9)
        copy_text(out, size, "km");
    else
        copy_text(out, size, name);
}

static int crs_info(const char *wkt, ft_crs_info *out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_io_crs_info: NULL out");
    memset(out, 0, sizeof *out);
    if (wkt == NULL || wkt[0] == '\0')
        return FT_OK;
    ft_io_init();
    OGRSpatialReferenceH srs = NULL;
    int rc = ft_io_srs_from_wkt(wkt, &srs);
    if (rc != FT_OK)
        return rc;
    if (OSRIsCompound(srs))
        OSRStripVertical(srs);
    out->has_crs = 1;
    out->geographic = OSRIsGeographic(srs) != 0;
    copy_text(out->name, sizeof out->name, OSRGetName(srs));
    OGRErr err = OGRERR_NONE;
    double a = OSRGetSemiMajor(srs, &err);
    double invf = err == OGRERR_NONE ? OSRGetInvFlattening(srs, &err) : 0.0;
    if (err == OGRERR_NONE && a > 0.0) {
        out->ellipsoid.a = a;
        out->ellipsoid.f = invf > 0.0 ? 1.0 / invf : 0.0;
        const char *en = OSRGetAttrValue(srs, "SPHEROID", 0);
        copy_text(out->ellipsoid_name, sizeof out->ellipsoid_name, en ? en : OSRGetAttrValue(srs, "ELLIPSOID", 0));
    }
    if (out->geographic) {
        copy_text(out->unit, sizeof out->unit, "degree");
        copy_text(out->scale_unit, sizeof out->scale_unit, "m");
        out->metres_per_unit = 0.0;
        if (!(out->ellipsoid.a > 0.0)) {
            OSRDestroySpatialReference(srs);
            return ft_error(FT_E_FORMAT, "geographic CRS '%s' has no ellipsoid", out->name);
        }
    } else {
        char *uname = NULL;
        double m = OSRGetLinearUnits(srs, &uname);
        copy_text(out->unit, sizeof out->unit, uname);
        out->metres_per_unit = m > 0.0 ? m : 0.0;
        if (out->metres_per_unit > 0.0)
            short_unit(out->unit, m, out->scale_unit, sizeof out->scale_unit);
    }
    OSRDestroySpatialReference(srs);
    return FT_OK;
}

int ft_io_crs_info(const char *wkt, ft_crs_info *out)
{
    ft_io_enter();
    return ft_io_leave(crs_info(wkt, out));
}

/* ------------------------------------------------------------------------------------------------
 * Local projections of geographic data: metres, centred on the data, on the data's own datum.
 * --------------------------------------------------------------------------------------------- */

static int local_crs(const char *geo_wkt, ft_local_projection kind, double lon0, double lat0, char **wkt)
{
    if (wkt == NULL)
        return ft_error(FT_E_INVALID, "ft_io_local_crs: NULL wkt");
    *wkt = NULL;
    if (!isfinite(lon0) || !isfinite(lat0) || fabs(lat0) > 90.0)
        return ft_error(FT_E_INVALID, "local projection centre must be a longitude and a latitude, got %g, %g",
                        lon0, lat0);
    ft_io_init();
    OGRSpatialReferenceH geo = NULL;
    int rc = ft_io_srs_from_wkt(geo_wkt, &geo);
    if (rc != FT_OK)
        return rc;
    if (geo == NULL)
        return ft_error(FT_E_INVALID, "a local projection needs the geographic CRS it is based on");
    OGRSpatialReferenceH base = OSRCloneGeogCS(geo);
    OSRDestroySpatialReference(geo);
    OGRSpatialReferenceH p = OSRNewSpatialReference(NULL);
    if (base == NULL || p == NULL) {
        OSRDestroySpatialReference(base);
        OSRDestroySpatialReference(p);
        return ft_error(FT_E_FORMAT, "cannot take the geographic base of '%.60s'", geo_wkt);
    }
    char name[160];
    const char *gname = OSRGetName(base);
    snprintf(name, sizeof name, "%s centred on %.4f%c %.4f%c (%s)",
             kind == FT_LOCAL_LAEA ? "Lambert azimuthal equal-area" : "Transverse Mercator", fabs(lat0),
             lat0 < 0 ? 'S' : 'N', fabs(lon0), lon0 < 0 ? 'W' : 'E', gname ? gname : "?");
    OGRErr err = OSRCopyGeogCSFrom(p, base);
    if (err == OGRERR_NONE)
        err = OSRSetProjCS(p, name);
    if (err == OGRERR_NONE)
        err = kind == FT_LOCAL_LAEA ? OSRSetLAEA(p, lat0, lon0, 0.0, 0.0) : OSRSetTM(p, lat0, lon0, 1.0, 0.0, 0.0);
    if (err == OGRERR_NONE)
        err = OSRSetLinearUnits(p, SRS_UL_METER, 1.0);
    OSRDestroySpatialReference(base);
    if (err != OGRERR_NONE) {
        OSRDestroySpatialReference(p);
        return ft_error(FT_E_FORMAT, "cannot build the local projection '%s'", name);
    }
    *wkt = ft_io_srs_to_wkt(p);
    OSRDestroySpatialReference(p);
    return *wkt ? FT_OK : ft_error(FT_E_NOMEM, "out of memory");
}

int ft_io_local_crs(const char *geo_wkt, ft_local_projection kind, double lon0, double lat0, char **wkt)
{
    ft_io_enter();
    return ft_io_leave(local_crs(geo_wkt, kind, lon0, lat0, wkt));
}

/* A transformation src -> dst in traditional GIS order (x = longitude). */
static int make_transform(const char *src_wkt, const char *dst_wkt, OGRCoordinateTransformationH *ct)
{
    *ct = NULL;
    OGRSpatialReferenceH s = NULL, d = NULL;
    int rc = ft_io_srs_from_wkt(src_wkt, &s);
    if (rc == FT_OK)
        rc = ft_io_srs_from_wkt(dst_wkt, &d);
    if (rc == FT_OK && (s == NULL || d == NULL))
        rc = ft_error(FT_E_INVALID, "reprojection needs a source and a target CRS");
    if (rc == FT_OK) {
        ft_io_gdal_reset();
        *ct = OCTNewCoordinateTransformation(s, d);
        if (*ct == NULL)
            rc = ft_io_fail(FT_E_FORMAT, "no transformation from '%s' to '%s'", OSRGetName(s), OSRGetName(d));
    }
    OSRDestroySpatialReference(s);
    OSRDestroySpatialReference(d);
    return rc;
}

static int transform_xy(OGRCoordinateTransformationH ct, double *x, double *y, size_t n, const char *what)
{
    if (n == 0)
        return FT_OK;
    if (n > (size_t)INT32_MAX)
        return ft_error(FT_E_INVALID, "%s: too many vertices to reproject (%zu)", what, n);
    int *ok = ft_malloc(n * sizeof *ok);
    if (ok == NULL)
        return FT_E_NOMEM;
    int all = OCTTransformEx(ct, (int)n, x, y, NULL, ok);
    size_t bad = n;
    for (size_t i = 0; i < n && bad == n; i++)
        if (!ok[i] || !isfinite(x[i]) || !isfinite(y[i]))
            bad = i;
    free(ok);
    if (!all || bad < n)
        return ft_error(FT_E_NUMERIC, "%s: vertex %zu cannot be reprojected", what, bad < n ? bad : 0);
    return FT_OK;
}

static int layer_reproject(ft_layer *l, const char *dst_wkt)
{
    if (l == NULL)
        return ft_error(FT_E_INVALID, "ft_io_layer_reproject: NULL layer");
    ft_io_init();
    OGRCoordinateTransformationH ct = NULL;
    int rc = make_transform(l->crs_wkt, dst_wkt, &ct);
    char what[64];
    for (size_t p = 0; rc == FT_OK && p < l->nparts; p++) {
        snprintf(what, sizeof what, "part %zu", p);
        ft_chain *c = l->parts[p].chain;
        if (c)
            rc = transform_xy(ct, c->x, c->y, c->n, what);
    }
    if (l->topology)
        for (size_t a = 0; rc == FT_OK && a < l->topology->narcs; a++) {
            ft_chain *c = l->topology->arcs[a];
            rc = transform_xy(ct, c->x, c->y, c->n, "arc");
        }
    if (ct)
        OCTDestroyCoordinateTransformation(ct);
    if (rc == FT_OK) {
        char *w = ft_strdup(dst_wkt);
        if (w == NULL)
            return FT_E_NOMEM;
        free(l->crs_wkt);
        l->crs_wkt = w;
    }
    return rc;
}

int ft_io_layer_reproject(ft_layer *l, const char *dst_wkt)
{
    ft_io_enter();
    return ft_io_leave(layer_reproject(l, dst_wkt));
}

static int points_reproject(ft_points *pts, const char *dst_wkt)
{
    if (pts == NULL)
        return ft_error(FT_E_INVALID, "ft_io_points_reproject: NULL points");
    ft_io_init();
    OGRCoordinateTransformationH ct = NULL;
    int rc = make_transform(pts->crs_wkt, dst_wkt, &ct);
    if (rc == FT_OK)
        rc = transform_xy(ct, pts->x, pts->y, pts->n, "points");
    if (ct)
        OCTDestroyCoordinateTransformation(ct);
    return rc == FT_OK ? ft_points_set_crs(pts, dst_wkt) : rc;
}

/* The geographic base of a projected CRS as WKT (malloc'd), or NULL (error set). */
static char *geographic_base(const char *wkt)
{
    OGRSpatialReferenceH p = NULL;
    if (ft_io_srs_from_wkt(wkt, &p) != FT_OK || p == NULL)
        return NULL;
    OGRSpatialReferenceH g = OSRCloneGeogCS(p);
    OSRDestroySpatialReference(p);
    if (g == NULL) {
        ft_error(FT_E_FORMAT, "cannot take the geographic base of '%.60s'", wkt);
        return NULL;
    }
    char *out = ft_io_srs_to_wkt(g);
    OSRDestroySpatialReference(g);
    return out;
}

static int crs_grid_north(const char *wkt, double x, double y, double *azimuth)
{
    if (azimuth == NULL)
        return ft_error(FT_E_INVALID, "ft_io_crs_grid_north: NULL azimuth");
    *azimuth = 0.0;
    ft_crs_info info;
    int rc = crs_info(wkt, &info);
    if (rc != FT_OK || !info.has_crs || info.geographic)
        return rc;
    if (!isfinite(x) || !isfinite(y))
        return ft_error(FT_E_INVALID, "grid north: the point (%g, %g) is not finite", x, y);
    char *geo = geographic_base(wkt);
    if (geo == NULL)
        return ft_last_error_code();
    OGRCoordinateTransformationH to_geo = NULL, to_map = NULL;
    rc = make_transform(wkt, geo, &to_geo);
    if (rc == FT_OK)
        rc = make_transform(geo, wkt, &to_map);
    free(geo);
    double px[2] = {x, 0.0}, py[2] = {y, 0.0};
    if (rc == FT_OK)
        rc = transform_xy(to_geo, px, py, 1, "grid north");
    if (rc == FT_OK) { /* one arc-second north of the point, back on the map */
        double dlat = py[0] > 89.99 ? -1.0 / 3600.0 : 1.0 / 3600.0;
        px[1] = px[0];
        py[1] = py[0] + dlat;
        px[0] = x;
        py[0] = y;
        rc = transform_xy(to_map, px + 1, py + 1, 1, "grid north");
        if (rc == FT_OK)
            *azimuth = atan2(copysign(1.0, dlat) * (px[1] - x), copysign(1.0, dlat) * (py[1] - y)) * 180.0 / M_PI;
    }
    if (to_geo)
        OCTDestroyCoordinateTransformation(to_geo);
    if (to_map)
        OCTDestroyCoordinateTransformation(to_map);
    return rc;
}

int ft_io_crs_grid_north(const char *wkt, double x, double y, double *azimuth)
{
    ft_io_enter();
    return ft_io_leave(crs_grid_north(wkt, x, y, azimuth));
}

int ft_io_points_reproject(ft_points *pts, const char *dst_wkt)
{
    ft_io_enter();
    return ft_io_leave(points_reproject(pts, dst_wkt));
}
