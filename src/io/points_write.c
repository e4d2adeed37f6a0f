/* fracterra — io/points_write.c: scattered points as CSV (`x,y,z[,w]` with a header), XYZ text
 * (`x y z [w]`; "-" writes it to stdout) or any OGR vector format as Point Z features (weight in a field
 * "w"), always through a temporary file renamed on success.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_string.h>

#include "internal.h"
#include "io/io_internal.h"

static void put_points(FILE *f, const ft_points *p, int csv)
{
    char sep = csv ? ',' : ' ';
    if (csv)
        fputs(p->w ? "x,y,z,w\n" : "x,y,z\n", f);
    for (size_t i = 0; i < p->n; i++) {
        ft_io_put_double(f, p->x[i]);
        fputc(sep, f);
        ft_io_put_double(f, p->y[i]);
        fputc(sep, f);
        ft_io_put_double(f, p->z[i]);
        if (p->w) {
            fputc(sep, f);
            ft_io_put_double(f, p->w[i]);
        }
        fputc('\n', f);
    }
}

static int put_csv(FILE *f, const void *p)
{
    put_points(f, p, 1);
    return FT_OK;
}

static int put_xyz(FILE *f, const void *p)
{
    put_points(f, p, 0);
    return FT_OK;
}

static int write_features(const char *path, OGRLayerH layer, const ft_points *p)
{
    OGRFeatureDefnH defn = OGR_L_GetLayerDefn(layer);
    for (size_t i = 0; i < p->n; i++) {
        OGRFeatureH f = OGR_F_Create(defn);
        OGRGeometryH g = OGR_G_CreateGeometry(wkbPoint25D);
        OGR_G_SetPoint(g, 0, p->x[i], p->y[i], p->z[i]);
        OGR_F_SetGeometryDirectly(f, g);
        if (p->w)
            OGR_F_SetFieldDouble(f, 0, p->w[i]);
        ft_io_gdal_reset();
        OGRErr e = OGR_L_CreateFeature(layer, f);
        OGR_F_Destroy(f);
        if (e != OGRERR_NONE)
            return ft_io_fail(FT_E_IO, "cannot write point %zu to '%s'", i, path);
    }
    return FT_OK;
}

static int create_layer(const char *path, GDALDatasetH ds, GDALDriverH drv, const ft_points *p, OGRLayerH *layer)
{
    OGRSpatialReferenceH srs;
    int rc = ft_io_srs_from_wkt(p->crs_wkt, &srs);
    if (rc != FT_OK)
        return rc;
    char *stem = ft_io_stem(path);
    char **lco = NULL;
    if (EQUAL(GDALGetDriverShortName(drv), "GeoJSON"))
        lco = CSLSetNameValue(CSLSetNameValue(lco, "RFC7946", "NO"), "SIGNIFICANT_FIGURES", "17");
    ft_io_gdal_reset();
    *layer = GDALDatasetCreateLayer(ds, stem ? stem : "points", srs, wkbPoint25D, lco);
    CSLDestroy(lco);
    free(stem);
    if (srs)
        OSRDestroySpatialReference(srs);
    if (*layer == NULL)
        return ft_io_fail(FT_E_IO, "cannot create a layer in '%s'", path);
    if (p->w) {
        OGRFieldDefnH fd = OGR_Fld_Create("w", OFTReal);
        OGRErr e = OGR_L_CreateField(*layer, fd, TRUE);
        OGR_Fld_Destroy(fd);
        if (e != OGRERR_NONE)
            return ft_io_fail(FT_E_IO, "cannot create field 'w' in '%s'", path);
    }
    return FT_OK;
}

static int write_ogr(const char *path, GDALDriverH drv, const char *tmp, const ft_points *p)
{
    int rc;
    ft_io_gdal_reset();
    GDALDatasetH ds = GDALCreate(drv, tmp, 0, 0, 0, GDT_Unknown, NULL);
    if (ds == NULL)
        return ft_io_fail(FT_E_IO, "cannot create '%s' (%s)", path, GDALGetDriverShortName(drv));
    OGRLayerH layer;
    rc = create_layer(path, ds, drv, p, &layer);
    int txn = rc == FT_OK && GDALDatasetTestCapability(ds, ODsCTransactions) &&
              GDALDatasetStartTransaction(ds, FALSE) == OGRERR_NONE;
    if (rc == FT_OK)
        rc = write_features(path, layer, p);
    if (txn && rc == FT_OK && GDALDatasetCommitTransaction(ds) != OGRERR_NONE)
        rc = ft_io_fail(FT_E_IO, "cannot commit the points of '%s'", path);
    ft_io_gdal_reset();
    GDALClose(ds);
    if (rc == FT_OK && ft_io_gdal_failed())
        rc = ft_io_fail(FT_E_IO, "cannot finish writing '%s'", path);
    return rc;
}

static int write_points(const char *path, const ft_points *p)
{
    if (p == NULL)
        return ft_error(FT_E_INVALID, "no points to write to '%s'", path ? path : "(null)");
    int rc = ft_io_check_writable(path);
    if (rc != FT_OK)
        return rc;
    if (ft_io_is_stdio(path)) {
        put_points(stdout, p, 0);
        if (fflush(stdout) != 0 || ferror(stdout))
            return ft_error(FT_E_IO, "cannot write to stdout: %s", strerror(errno));
        return FT_OK;
    }
    ft_io_init();
    if (ft_io_ext_in(path, "csv"))
        return ft_io_atomic_write(path, put_csv, p);
    if (ft_io_ext_in(path, "xyz"))
        return ft_io_atomic_write(path, put_xyz, p);
    GDALDriverH drv;
    ft_io_stage st;
    rc = ft_io_find_driver(path, NULL, GDAL_DCAP_VECTOR, &drv);
    if (rc == FT_OK)
        rc = ft_io_stage_begin(path, drv, 0.0, &st);
    if (rc != FT_OK)
        return rc;
    rc = write_ogr(path, drv, st.target, p);
    int end = ft_io_stage_end(&st, rc == FT_OK);
    return rc != FT_OK ? rc : end;
}

int ft_io_write_points(const char *path, const ft_points *p)
{
    ft_io_enter();
    return ft_io_leave(write_points(path, p));
}
