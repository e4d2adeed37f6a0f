/* fracterra — io/points_read.c: scattered points from CSV / XYZ text (by extension, "-" = XYZ on
 * stdin) or from an OGR layer of points or multipoints, z taken from the geometry or from a field.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "io/io_internal.h"

typedef struct {
    const char *path;
    OGRLayerH ogr;
    int zfield, wfield;  /* OGR field indices, -1 if unused */
    const char *zname, *wname;
    ft_points *p;
    double *w;
    size_t wcap;
} point_reader;

static int field_index(point_reader *r, const char *name, int *index)
{
    *index = -1;
    if (name == NULL)
        return FT_OK;
    *index = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(r->ogr), name);
    if (*index < 0)
        return ft_error(FT_E_FORMAT, "no field '%s' in layer '%s' of '%s'", name, OGR_L_GetName(r->ogr), r->path);
    return FT_OK;
}

static int field_number(point_reader *r, OGRFeatureH f, int i, const char *name, double *v)
{
    if (!OGR_F_IsFieldSetAndNotNull(f, i))
        return ft_error(FT_E_FORMAT, "feature %lld of '%s' has no value in field '%s'", (long long)OGR_F_GetFID(f),
                        r->path, name);
    *v = OGR_F_GetFieldAsDouble(f, i);
    return FT_OK;
}

static int push_weight(point_reader *r, double w)
{
    if (r->p->n > r->wcap) {
        size_t cap = r->wcap ? 2 * r->wcap : 256;
        double *nw = ft_realloc_array(r->w, cap, sizeof *nw);
        if (nw == NULL)
            return FT_E_NOMEM;
        r->w = nw;
        r->wcap = cap;
    }
    r->w[r->p->n - 1] = w;
    return FT_OK;
}

/* Adds one Point geometry of feature f. */
static int add_point(point_reader *r, OGRFeatureH f, OGRGeometryH pt)
{
    long long fid = (long long)OGR_F_GetFID(f);
    double x = OGR_G_GetX(pt, 0), y = OGR_G_GetY(pt, 0), z = 0, w = 1;
    int rc = FT_OK;
    if (r->zfield >= 0)
        rc = field_number(r, f, r->zfield, r->zname, &z);
    else if (OGR_G_Is3D(pt))
        z = OGR_G_GetZ(pt, 0);
    else
        rc = ft_error(FT_E_FORMAT, "feature %lld of '%s' has no Z coordinate; name a z field", fid, r->path);
    if (rc == FT_OK && r->wfield >= 0)
        rc = field_number(r, f, r->wfield, r->wname, &w);
    if (rc != FT_OK)
        return rc;
    if (!isfinite(x) || !isfinite(y) || !isfinite(z) || !isfinite(w))
        return ft_error(FT_E_NUMERIC, "feature %lld of '%s' has a non-finite value (%g, %g, %g, weight %g)", fid,
                        r->path, x, y, z, w);
    if (ft_points_push(r->p, x, y, z) != FT_OK)
        return FT_E_NOMEM;
    return r->wfield >= 0 ? push_weight(r, w) : FT_OK;
}

static int add_feature(point_reader *r, OGRFeatureH f)
{
    OGRGeometryH g = OGR_F_GetGeometryRef(f);
    if (g == NULL || OGR_G_IsEmpty(g))
        return FT_OK;
    OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
    if (t == wkbPoint)
        return add_point(r, f, g);
    if (t != wkbMultiPoint)
        return ft_error(FT_E_FORMAT, "feature %lld of '%s' is a %s, not a point", (long long)OGR_F_GetFID(f),
                        r->path, OGRGeometryTypeToName(t));
    for (int i = 0; i < OGR_G_GetGeometryCount(g); i++) {
        int rc = add_point(r, f, OGR_G_GetGeometryRef(g, i));
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

static int read_ogr_points(point_reader *r, const ft_read_points_opts *o)
{
    OGRwkbGeometryType t = wkbFlatten(OGR_L_GetGeomType(r->ogr));
    if (t != wkbPoint && t != wkbMultiPoint && t != wkbUnknown && t != wkbGeometryCollection)
        return ft_error(FT_E_FORMAT, "layer '%s' of '%s' holds %s geometries, not points", OGR_L_GetName(r->ogr), r->path,
                        OGRGeometryTypeToName(t));
    r->zname = o->zfield;
    r->wname = o->weight;
    int rc = field_index(r, o->zfield, &r->zfield);
    if (rc == FT_OK)
        rc = field_index(r, o->weight, &r->wfield);
    if (rc != FT_OK)
        return rc;
    char *wkt = ft_io_srs_to_wkt(OGR_L_GetSpatialRef(r->ogr));
    r->p = ft_points_create(256);
    if (r->p != NULL && wkt != NULL)
        rc = ft_points_set_crs(r->p, wkt);
    free(wkt);
    if (r->p == NULL || rc != FT_OK)
        return r->p == NULL ? FT_E_NOMEM : rc;
    OGRFeatureH f;
    OGR_L_ResetReading(r->ogr);
    ft_io_gdal_reset();
    while (rc == FT_OK && (f = OGR_L_GetNextFeature(r->ogr)) != NULL) {
        rc = add_feature(r, f);
        OGR_F_Destroy(f);
    }
    if (rc == FT_OK && ft_io_gdal_failed())
        rc = ft_io_fail(FT_E_IO, "error reading layer '%s' of '%s'", OGR_L_GetName(r->ogr), r->path);
    if (rc == FT_OK && r->p->n == 0)
        rc = ft_error(FT_E_EMPTY, "layer '%s' of '%s' holds no point", OGR_L_GetName(r->ogr), r->path);
    if (rc == FT_OK && r->w != NULL && (rc = ft_points_ensure_weights(r->p)) == FT_OK)
        memcpy(r->p->w, r->w, r->p->n * sizeof *r->w);
    return rc;
}

static int read_points(const char *path, const ft_read_points_opts *opts, ft_points **out)
{
    ft_read_points_opts o = FT_READ_POINTS_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_read_points_opts) != FT_OK)
        return FT_E_INVALID;
    *out = NULL;
    int text = path != NULL && (ft_io_ext_in(path, "csv xyz") || ft_io_is_stdio(path));
    if (text && (o.layer != NULL || o.zfield != NULL))
        return ft_error(FT_E_INVALID, "%s is a text file: a layer and a z field are for OGR point layers (name a "
                        "CSV's z column instead)", path);
    if (text && !ft_io_ext_in(path, "csv") && (o.x != NULL || o.y != NULL || o.z != NULL))
        return ft_error(FT_E_INVALID, "%s is XYZ text (x y z by position): column names are for CSV files", path);
    if (path != NULL && ft_io_ext_in(path, "csv"))
        return ft_io_read_points_csv(path, &o, out);
    if (path != NULL && (ft_io_ext_in(path, "xyz") || ft_io_is_stdio(path)))
        return ft_io_read_points_xyz(path, &o, out);
    GDALDatasetH ds;
    int rc = ft_io_open(path, GDAL_OF_VECTOR, &ds);
    if (rc != FT_OK)
        return rc;
    rc = ft_io_read_points_ds(ds, path, &o, out);
    GDALClose(ds);
    return rc;
}

int ft_io_read_points(const char *path, const ft_read_points_opts *opts, ft_points **out)
{
    ft_io_enter();
    return ft_io_leave(read_points(path, opts, out));
}

int ft_io_read_points_ds(GDALDatasetH ds, const char *path, const ft_read_points_opts *o, ft_points **out)
{
    *out = NULL;
    point_reader r = {.path = path, .zfield = -1, .wfield = -1};
    int rc = ft_io_get_layer(ds, path, o->layer, &r.ogr);
    if (rc == FT_OK)
        rc = read_ogr_points(&r, o);
    free(r.w);
    if (rc != FT_OK) {
        ft_points_free(r.p);
        return rc;
    }
    *out = r.p;
    return FT_OK;
}
