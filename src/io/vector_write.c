/* fracterra — io/vector_write.c: an ft_layer through OGR, atomically.
 *
 * The file is written under a temporary name beside the target and renamed only when everything, the
 * driver's final flush included, succeeded; on any failure the temporary files are removed. The layer's
 * geometry type is the common type of its features (Multi* if any is multi, Unknown if lines and
 * polygons mix); each feature keeps its own type. Rings get their closing vertex back. Fields are
 * created with the reader's native OGR type, width and precision when those fit the held values.
 * GeoJSON is written with 17 significant digits and without RFC 7946 (so the CRS stays in the file);
 * Shapefile with UTF-8 attributes. Note that the Shapefile driver rewinds rings (outer clockwise,
 * holes counter-clockwise); GeoJSON and GeoPackage keep the vertex order as given.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdlib.h>
#include <string.h>

#include <cpl_conv.h>
#include <cpl_string.h>

#include "internal.h"
#include "io/io_internal.h"

typedef struct {
    const char *path;      /* final name, for messages */
    const ft_layer *l;
    GDALDatasetH ds;
    OGRLayerH ogr;
} writer;

/* ---- layer definition -------------------------------------------------------------------------- */

static OGRwkbGeometryType layer_geom_type(const ft_layer *l)
{
    ft_geom_type kind = FT_GEOM_NONE;
    int multi = 0;
    for (size_t i = 0; i < l->nfeatures; i++) {
        const ft_feature *f = &l->features[i];
        if (f->type == FT_GEOM_NONE)
            continue;
        if (kind != FT_GEOM_NONE && f->type != kind)
            return wkbUnknown;
        kind = f->type;
        multi |= f->multi;
    }
    if (kind == FT_GEOM_LINE)
        return multi ? wkbMultiLineString : wkbLineString;
    if (kind == FT_GEOM_POLYGON)
        return multi ? wkbMultiPolygon : wkbPolygon;
    return wkbUnknown;
}

/* The reader's native type when it holds values of the field's kind, else the plain type of the kind. */
static OGRFieldType ogr_field_type(const ft_field *f)
{
    int n = f->native_type;
    int is_int = n == OFTInteger || n == OFTInteger64;
    switch (f->type) {
    case FT_FIELD_INT: return is_int ? (OGRFieldType)n : OFTInteger64;
    case FT_FIELD_REAL: return OFTReal;
    default: return (n >= 0 && n <= OFTMaxType && !is_int && n != OFTReal) ? (OGRFieldType)n : OFTString;
    }
}

static int create_fields(writer *w)
{
    for (size_t k = 0; k < w->l->nfields; k++) {
        const ft_field *f = &w->l->fields[k];
        OGRFieldDefnH fd = OGR_Fld_Create(f->name ? f->name : "field", ogr_field_type(f));
        if (f->width > 0)
            OGR_Fld_SetWidth(fd, f->width);
        if (f->precision > 0)
            OGR_Fld_SetPrecision(fd, f->precision);
        OGRErr e = OGR_L_CreateField(w->ogr, fd, TRUE);
        OGR_Fld_Destroy(fd);
        if (e != OGRERR_NONE)
            return ft_io_fail(FT_E_IO, "cannot create field '%s' in '%s'", f->name, w->path);
    }
    if ((size_t)OGR_FD_GetFieldCount(OGR_L_GetLayerDefn(w->ogr)) != w->l->nfields)
        return ft_io_fail(FT_E_IO, "'%s' did not take all %zu fields", w->path, w->l->nfields);
    return FT_OK;
}

/* Driver defaults that keep data intact, unless the caller set the same option. */
static char **layer_options(GDALDriverH drv, const char *const *lco)
{
    char **o = CSLDuplicate((char **)lco);
    const char *name = GDALGetDriverShortName(drv);
    if (EQUAL(name, "GeoJSON")) {
        if (CSLFetchNameValue(o, "RFC7946") == NULL)
            o = CSLSetNameValue(o, "RFC7946", "NO");
        if (CSLFetchNameValue(o, "COORDINATE_PRECISION") == NULL &&
            CSLFetchNameValue(o, "SIGNIFICANT_FIGURES") == NULL)
            o = CSLSetNameValue(o, "SIGNIFICANT_FIGURES", "17");
    } else if (EQUAL(name, "ESRI Shapefile")) {
        if (CSLFetchNameValue(o, "ENCODING") == NULL)
            o = CSLSetNameValue(o, "ENCODING", "UTF-8");
    }
    return o;
}

static int create_layer(writer *w, GDALDriverH drv, const ft_write_layer_opts *o)
{
    OGRSpatialReferenceH srs;
    int rc = ft_io_srs_from_wkt(w->l->crs_wkt, &srs);
    if (rc != FT_OK)
        return rc;
    char *stem = ft_io_stem(w->path);
    const char *name = o->layer ? o->layer : (w->l->name && w->l->name[0]) ? w->l->name : stem;
    char **lco = layer_options(drv, o->lco);
    ft_io_gdal_reset();
    w->ogr = GDALDatasetCreateLayer(w->ds, name ? name : "layer", srs, layer_geom_type(w->l), lco);
    CSLDestroy(lco);
    free(stem);
    if (srs)
        OSRDestroySpatialReference(srs);
    if (w->ogr == NULL)
        return ft_io_fail(FT_E_IO, "cannot create a layer in '%s'", w->path);
    return create_fields(w);
}

/* ---- geometry ---------------------------------------------------------------------------------- */

/* A LineString, or a LinearRing when ring; closed chains get their first vertex repeated at the end. */
static OGRGeometryH make_chain(const ft_chain *c, int ring)
{
    OGRGeometryH g = OGR_G_CreateGeometry(ring ? wkbLinearRing : wkbLineString);
    if (g == NULL || c->n == 0)
        return g;
    OGR_G_SetPoints(g, (int)c->n, c->x, (int)sizeof(double), c->y, (int)sizeof(double), NULL, 0);
    if (c->closed || ring)
        OGR_G_AddPoint_2D(g, c->x[0], c->y[0]);
    return g;
}

static OGRGeometryH make_lines(const ft_layer *l, const ft_feature *f)
{
    if (!f->multi && f->count == 1)
        return make_chain(l->parts[f->first].chain, 0);
    OGRGeometryH m = OGR_G_CreateGeometry(wkbMultiLineString);
    for (size_t p = f->first; p < f->first + f->count; p++)
        OGR_G_AddGeometryDirectly(m, make_chain(l->parts[p].chain, 0));
    return m;
}

static OGRGeometryH make_polygons(const ft_layer *l, const ft_feature *f)
{
    OGRGeometryH m = OGR_G_CreateGeometry(wkbMultiPolygon), poly = NULL;
    int npoly = 0;
    for (size_t p = f->first; p < f->first + f->count; p++) {
        const ft_part *part = &l->parts[p];
        int starts = poly == NULL || part->role == FT_ROLE_OUTER || part->polygon != l->parts[p - 1].polygon;
        if (starts) {
            if (poly != NULL)
                OGR_G_AddGeometryDirectly(m, poly);
            poly = OGR_G_CreateGeometry(wkbPolygon);
            npoly++;
        }
        OGR_G_AddGeometryDirectly(poly, make_chain(part->chain, 1));
    }
    if (poly != NULL && (f->multi || npoly != 1)) {
        OGR_G_AddGeometryDirectly(m, poly);
        return m;
    }
    OGR_G_DestroyGeometry(m);
    return poly ? poly : OGR_G_CreateGeometry(wkbPolygon);
}

static OGRGeometryH make_geometry(const ft_layer *l, const ft_feature *f)
{
    if (f->type == FT_GEOM_LINE)
        return f->count ? make_lines(l, f) : OGR_G_CreateGeometry(f->multi ? wkbMultiLineString : wkbLineString);
    if (f->type == FT_GEOM_POLYGON)
        return make_polygons(l, f);
    return NULL;
}

/* ---- features ---------------------------------------------------------------------------------- */

static void set_values(OGRFeatureH of, const ft_layer *l, const ft_feature *f)
{
    for (size_t k = 0; k < l->nfields; k++) {
        const ft_value *v = &f->values[k];
        int i = (int)k;
        if (v->is_null) {
            OGR_F_SetFieldNull(of, i);
            continue;
        }
        switch (l->fields[k].type) {
        case FT_FIELD_INT: OGR_F_SetFieldInteger64(of, i, v->i); break;
        case FT_FIELD_REAL: OGR_F_SetFieldDouble(of, i, v->r); break;
        default:
            if (v->s)
                OGR_F_SetFieldString(of, i, v->s);
            else
                OGR_F_SetFieldNull(of, i);
            break;
        }
    }
}

static int write_features(writer *w)
{
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(w->ogr);
    for (size_t i = 0; i < w->l->nfeatures; i++) {
        const ft_feature *f = &w->l->features[i];
        OGRFeatureH of = OGR_F_Create(defn);
        if (of == NULL)
            return ft_error(FT_E_NOMEM, "out of memory writing '%s'", w->path);
        set_values(of, w->l, f);
        OGRGeometryH g = make_geometry(w->l, f);
        if (g != NULL)
            OGR_F_SetGeometryDirectly(of, g);
        ft_io_gdal_reset();
        OGRErr e = OGR_L_CreateFeature(w->ogr, of);
        OGR_F_Destroy(of);
        if (e != OGRERR_NONE)
            return ft_io_fail(FT_E_IO, "cannot write feature %lld to '%s'", (long long)f->fid, w->path);
    }
    return FT_OK;
}

static int write_dataset(writer *w, GDALDriverH drv, const char *tmp, const ft_write_layer_opts *o)
{
    ft_io_gdal_reset();
    w->ds = GDALCreate(drv, tmp, 0, 0, 0, GDT_Unknown, NULL);
    if (w->ds == NULL)
        return ft_io_fail(FT_E_IO, "cannot create '%s' (%s)", w->path, GDALGetDriverShortName(drv));
    int rc = create_layer(w, drv, o);
    int txn = rc == FT_OK && GDALDatasetTestCapability(w->ds, ODsCTransactions) &&
              GDALDatasetStartTransaction(w->ds, FALSE) == OGRERR_NONE;
    if (rc == FT_OK)
        rc = write_features(w);
    if (txn && rc == FT_OK && GDALDatasetCommitTransaction(w->ds) != OGRERR_NONE)
        rc = ft_io_fail(FT_E_IO, "cannot commit the features of '%s'", w->path);
    ft_io_gdal_reset();
    GDALClose(w->ds);
    w->ds = NULL;
    if (rc == FT_OK && ft_io_gdal_failed())
        rc = ft_io_fail(FT_E_IO, "cannot finish writing '%s'", w->path);
    return rc;
}

static int write_layer(const char *path, const ft_layer *layer, const ft_write_layer_opts *opts)
{
    ft_write_layer_opts o = FT_WRITE_LAYER_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_write_layer_opts) != FT_OK)
        return FT_E_INVALID;
    if (layer == NULL)
        return ft_error(FT_E_INVALID, "no layer to write to '%s'", path ? path : "(null)");
    if (o.driver ? EQUAL(o.driver, "GMT-text") : ft_io_is_text_chains(path))
        return ft_io_write_text_chains(path, layer);
    GDALDriverH drv;
    int rc = ft_io_check_writable(path);
    if (rc == FT_OK)
        rc = ft_io_find_driver(path, o.driver, GDAL_DCAP_VECTOR, &drv);
    if (rc != FT_OK)
        return rc;
    if (!GDALGetMetadataItem(drv, GDAL_DCAP_CREATE, NULL))
        return ft_error(FT_E_UNSUPPORTED, "driver '%s' cannot create vector files", GDALGetDriverShortName(drv));
    ft_io_stage st;
    if ((rc = ft_io_stage_begin(path, drv, 0.0, &st)) != FT_OK)
        return rc;
    writer w = {.path = path, .l = layer};
    rc = write_dataset(&w, drv, st.target, &o);
    int end = ft_io_stage_end(&st, rc == FT_OK);
    return rc != FT_OK ? rc : end;
}

int ft_io_write_layer(const char *path, const ft_layer *layer, const ft_write_layer_opts *opts)
{
    ft_io_enter();
    return ft_io_leave(write_layer(path, layer, opts));
}
