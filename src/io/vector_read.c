/* fracterra — io/vector_read.c: lines and polygons of an OGR layer into an ft_layer.
 *
 * LineString / MultiLineString / Polygon (outer ring then holes) / MultiPolygon, their Z and M variants
 * (z and m dropped), curves (linearized by OGR) and homogeneous geometry collections. Ring vertices are
 * copied in bulk and lose their repeated closing vertex. Features without geometry are kept with
 * FT_GEOM_NONE so their attributes survive a read/write cycle.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_conv.h>
#include <cpl_string.h>

#include "internal.h"
#include "io/io_internal.h"

typedef struct {
    const char *path;
    OGRLayerH ogr;
    ft_layer *out;
    int *src;       /* OGR field index of each kept field */
    size_t nkeep;
    int64_t fid;    /* feature being read */
} reader;

/* ---- fields ------------------------------------------------------------------------------------ */

static ft_field_type value_type(OGRFieldType t)
{
    if (t == OFTInteger || t == OFTInteger64)
        return FT_FIELD_INT;
    return t == OFTReal ? FT_FIELD_REAL : FT_FIELD_STRING;
}

static int field_list_error(reader *r, const char *name)
{
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(r->ogr);
    char list[1024] = "";
    size_t used = 0;
    for (int i = 0; i < OGR_FD_GetFieldCount(defn) && used < sizeof list - 1; i++) {
        int k = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "",
                         OGR_Fld_GetNameRef(OGR_FD_GetFieldDefn(defn, i)));
        if (k < 0)
            break;
        used += (size_t)k;
    }
    return ft_error(FT_E_FORMAT, "no field '%s' in layer '%s' of '%s' (fields: %s)", name,
                    OGR_L_GetName(r->ogr), r->path, used ? list : "none");
}

/* Which OGR fields to keep: all (NULL), none (""), or the named ones in the given order. */
static int select_fields(reader *r, const char *fields)
{
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(r->ogr);
    int nf = OGR_FD_GetFieldCount(defn);
    char **names = fields ? CSLTokenizeString2(fields, ",", CSLT_STRIPLEADSPACES | CSLT_STRIPENDSPACES) : NULL;
    size_t want = fields ? (size_t)CSLCount(names) : (size_t)nf;
    r->src = ft_calloc(want ? want : 1, sizeof *r->src);
    if (r->src == NULL) {
        CSLDestroy(names);
        return FT_E_NOMEM;
    }
    int rc = FT_OK;
    for (size_t k = 0; k < want && rc == FT_OK; k++) {
        int i = fields ? OGR_FD_GetFieldIndex(defn, names[k]) : (int)k;
        if (i < 0) {
            rc = field_list_error(r, names[k]);
            break;
        }
        OGRFieldDefnH fd = OGR_FD_GetFieldDefn(defn, i);
        OGRFieldType t = OGR_Fld_GetType(fd);
        int idx = ft_layer_add_field(r->out, OGR_Fld_GetNameRef(fd), value_type(t), (int)t, OGR_Fld_GetWidth(fd),
                                     OGR_Fld_GetPrecision(fd));
        if (idx < 0)
            rc = idx;
        else
            r->src[r->nkeep++] = i;
    }
    CSLDestroy(names);
    return rc;
}

static int copy_values(reader *r, OGRFeatureH f, size_t fi)
{
    for (size_t k = 0; k < r->nkeep; k++) {
        int i = r->src[k];
        if (!OGR_F_IsFieldSetAndNotNull(f, i))
            continue;
        int rc;
        switch (r->out->fields[k].type) {
        case FT_FIELD_INT: rc = ft_layer_set_int(r->out, fi, k, OGR_F_GetFieldAsInteger64(f, i)); break;
        case FT_FIELD_REAL: rc = ft_layer_set_real(r->out, fi, k, OGR_F_GetFieldAsDouble(f, i)); break;
        default: rc = ft_layer_set_string(r->out, fi, k, OGR_F_GetFieldAsString(f, i)); break;
        }
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

/* ---- geometry ---------------------------------------------------------------------------------- */

/* Kind of a (linear) geometry: FT_GEOM_LINE / FT_GEOM_POLYGON with multi, FT_GEOM_NONE if unsupported. */
static ft_geom_type geom_kind(OGRGeometryH g, int *multi)
{
    OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
    *multi = 0;
    switch (t) {
    case wkbLineString:
    case wkbLinearRing: return FT_GEOM_LINE;
    case wkbPolygon:
    case wkbTriangle: return FT_GEOM_POLYGON;
    case wkbMultiLineString: *multi = 1; return FT_GEOM_LINE;
    case wkbMultiPolygon: *multi = 1; return FT_GEOM_POLYGON;
    case wkbGeometryCollection: {
        ft_geom_type kind = FT_GEOM_NONE;
        int sub;
        for (int i = 0; i < OGR_G_GetGeometryCount(g); i++) {
            ft_geom_type k = geom_kind(OGR_G_GetGeometryRef(g, i), &sub);
            if (k == FT_GEOM_NONE || (kind != FT_GEOM_NONE && k != kind))
                return FT_GEOM_NONE;
            kind = k;
        }
        *multi = 1;
        return kind;
    }
    default: return FT_GEOM_NONE;
    }
}

/* Copies a LineString or LinearRing; a ring (closed) loses its repeated closing vertex. */
static int add_chain(reader *r, OGRGeometryH g, int closed, ft_part_role role, int polygon)
{
    int n = OGR_G_GetPointCount(g);
    ft_chain *c = ft_chain_create(n > 0 ? (size_t)n : 1, closed);
    if (c == NULL)
        return FT_E_NOMEM;
    if (n > 0)
        OGR_G_GetPoints(g, c->x, (int)sizeof(double), c->y, (int)sizeof(double), NULL, 0);
    c->n = (size_t)(n > 0 ? n : 0);
    size_t part = r->out->nfeatures ? r->out->features[r->out->nfeatures - 1].count : 0;
    for (size_t i = 0; i < c->n; i++) {
        if (!isfinite(c->x[i]) || !isfinite(c->y[i])) {
            int rc = ft_error(FT_E_NUMERIC, "feature %lld of '%s': vertex %zu of part %zu is not finite (%g, %g)",
                              (long long)r->fid, r->path, i, part, c->x[i], c->y[i]);
            ft_chain_free(c);
            return rc;
        }
    }
    if (closed && c->n >= 2 && c->x[0] == c->x[c->n - 1] && c->y[0] == c->y[c->n - 1])
        c->n--;
    return ft_layer_add_part(r->out, c, role, polygon);
}

static int add_polygon(reader *r, OGRGeometryH g, int polygon)
{
    int nrings = OGR_G_GetGeometryCount(g);
    for (int i = 0; i < nrings; i++) {
        int rc = add_chain(r, OGR_G_GetGeometryRef(g, i), 1, i == 0 ? FT_ROLE_OUTER : FT_ROLE_INNER, polygon);
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

/* Adds the parts of g (lines or polygons, single, multi or collection); *polygon counts polygons. */
static int add_parts(reader *r, OGRGeometryH g, int *polygon)
{
    OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
    if (t == wkbLineString || t == wkbLinearRing)
        return add_chain(r, g, 0, FT_ROLE_LINE, 0);
    if (t == wkbPolygon || t == wkbTriangle)
        return add_polygon(r, g, (*polygon)++);
    for (int i = 0; i < OGR_G_GetGeometryCount(g); i++) {
        int rc = add_parts(r, OGR_G_GetGeometryRef(g, i), polygon);
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

static int points_error(reader *r)
{
    return ft_error(FT_E_FORMAT, "layer '%s' of '%s' holds points, not lines or polygons (feature %lld); "
                    "read it as points", OGR_L_GetName(r->ogr), r->path, (long long)r->fid);
}

static int add_feature(reader *r, OGRFeatureH f, int64_t index)
{
    r->fid = OGR_F_GetFID(f) == OGRNullFID ? index : (int64_t)OGR_F_GetFID(f);
    OGRGeometryH g = OGR_F_GetGeometryRef(f), lin = NULL;
    if (g != NULL && OGR_G_IsEmpty(g))
        g = NULL;
    if (g != NULL && OGR_GT_IsNonLinear(OGR_G_GetGeometryType(g)))
        g = lin = OGR_G_GetLinearGeometry(g, 0.0, NULL);
    int multi = 0, rc = FT_OK;
    ft_geom_type kind = g ? geom_kind(g, &multi) : FT_GEOM_NONE;
    if (g != NULL && kind == FT_GEOM_NONE) {
        OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
        if (t == wkbPoint || t == wkbMultiPoint)
            rc = points_error(r);
        else
            rc = ft_error(FT_E_FORMAT, "feature %lld of '%s' is a %s; only lines and polygons are read",
                          (long long)r->fid, r->path, OGRGeometryTypeToName(t));
    }
    int64_t fi = rc == FT_OK ? ft_layer_add_feature(r->out, r->fid, kind, multi) : rc;
    if (fi < 0)
        rc = (int)fi;
    int polygon = 0;
    if (rc == FT_OK && g != NULL)
        rc = add_parts(r, g, &polygon);
    if (rc == FT_OK)
        rc = copy_values(r, f, (size_t)fi);
    if (lin != NULL)
        OGR_G_DestroyGeometry(lin);
    return rc;
}

/* ---- the layer --------------------------------------------------------------------------------- */

static int read_features(reader *r)
{
    int rc = FT_OK;
    int64_t index = 0;
    OGRFeatureH f;
    OGR_L_ResetReading(r->ogr);
    ft_io_gdal_reset();
    while (rc == FT_OK && (f = OGR_L_GetNextFeature(r->ogr)) != NULL) {
        rc = add_feature(r, f, index++);
        OGR_F_Destroy(f);
    }
    if (rc == FT_OK && ft_io_gdal_failed())
        rc = ft_io_fail(FT_E_IO, "error reading layer '%s' of '%s'", OGR_L_GetName(r->ogr), r->path);
    return rc;
}

static int read_ogr_layer(reader *r, const ft_read_layer_opts *o)
{
    OGRwkbGeometryType t = wkbFlatten(OGR_L_GetGeomType(r->ogr));
    if (t == wkbPoint || t == wkbMultiPoint)
        return ft_error(FT_E_FORMAT, "layer '%s' of '%s' holds points, not lines or polygons; read it as points",
                        OGR_L_GetName(r->ogr), r->path);
    if (o->where != NULL) {
        ft_io_gdal_reset();
        if (OGR_L_SetAttributeFilter(r->ogr, o->where) != OGRERR_NONE)
            return ft_io_fail(FT_E_INVALID, "bad filter '%s' on '%s'", o->where, r->path);
    }
    char *wkt = ft_io_srs_to_wkt(OGR_L_GetSpatialRef(r->ogr));
    r->out = ft_layer_create(OGR_L_GetName(r->ogr), wkt);
    free(wkt);
    if (r->out == NULL)
        return FT_E_NOMEM;
    int rc = select_fields(r, o->fields);
    if (rc == FT_OK)
        rc = read_features(r);
    if (rc == FT_OK && r->out->nparts == 0)
        rc = ft_error(FT_E_EMPTY, "layer '%s' of '%s' holds no line or polygon%s%s%s", OGR_L_GetName(r->ogr),
                      r->path, o->where ? " matching '" : "", o->where ? o->where : "", o->where ? "'" : "");
    return rc;
}

static int read_layer(const char *path, const ft_read_layer_opts *opts, ft_layer **out)
{
    ft_read_layer_opts o = FT_READ_LAYER_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_read_layer_opts) != FT_OK)
        return FT_E_INVALID;
    *out = NULL;
    if (ft_io_is_text_chains(path)) {
        if (o.where != NULL || (o.fields != NULL && o.fields[0] != '\0'))
            return ft_error(FT_E_UNSUPPORTED, "'%s' is GMT text: it has no attributes to filter or select", path);
        return ft_io_read_text_chains(path, out);
    }
    GDALDatasetH ds;
    int rc = ft_io_open(path, GDAL_OF_VECTOR, &ds);
    if (rc != FT_OK)
        return rc;
    rc = ft_io_read_layer_ds(ds, path, &o, out);
    GDALClose(ds);
    return rc;
}

int ft_io_read_layer(const char *path, const ft_read_layer_opts *opts, ft_layer **out)
{
    ft_io_enter();
    return ft_io_leave(read_layer(path, opts, out));
}

int ft_io_read_layer_ds(GDALDatasetH ds, const char *path, const ft_read_layer_opts *o, ft_layer **out)
{
    *out = NULL;
    reader r = {.path = path};
    int rc = ft_io_get_layer(ds, path, o->layer, &r.ogr);
    if (rc == FT_OK)
        rc = read_ogr_layer(&r, o);
    free(r.src);
    if (rc != FT_OK) {
        ft_layer_free(r.out);
        return rc;
    }
    *out = r.out;
    return FT_OK;
}
