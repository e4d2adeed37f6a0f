/* fracterra — io/contour_generate.c: contour polygons of a DEM through GDAL's contour generator
 * (GDALContourGenerateEx with POLYGONIZE=YES), as `gdal_contour -p -amin elev` writes them.
 *
 * The grid goes into an in-memory raster (its geotransform and CRS; masked and non-finite cells get a
 * sentinel below every valid cell, passed as NODATA so GDAL leaves them out), the bands between levels
 * base + i x interval go into an in-memory OGR layer (one MultiPolygon per band), and the layer is read
 * into an ft_layer with one real field `elev`. GDAL 3.6 writes 0 as the lower level of the lowest band
 * (it has no level below the DEM's minimum); `elev` is therefore taken from the band's upper level,
 * which GDAL always writes, minus one interval: the band's true lower level.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_string.h>
#include <gdal_alg.h>

#include "internal.h"
#include "io/io_internal.h"

#define CONTOUR_MAX_BANDS 100000.0
#define CONTOUR_LAYER "contour"
#define FIELD_ID "ID"
#define FIELD_LOW "elev"
#define FIELD_HIGH "elev_max"

static int cell_valid(const ft_grid *g, size_t i)
{
    return (g->mask == NULL || g->mask[i] != 0) && isfinite(g->z[i]);
}

static int check_args(const ft_grid *dem, double interval, double base, ft_layer **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "contours: no output pointer given");
    *out = NULL;
    if (dem == NULL || dem->z == NULL)
        return ft_error(FT_E_INVALID, "contours: no grid given");
    if (dem->nx < 2 || dem->ny < 2 || dem->nx > INT32_MAX || dem->ny > INT32_MAX)
        return ft_error(FT_E_INVALID, "contours: the grid must have at least 2 x 2 cells (and fewer than 2^31 a "
                                      "side), got %zu x %zu",
                        dem->nx, dem->ny);
    if (!isfinite(interval) || interval <= 0.0)
        return ft_error(FT_E_INVALID, "contours: interval must be finite and > 0, got %g", interval);
    if (!isfinite(base))
        return ft_error(FT_E_INVALID, "contours: base level must be finite, got %g", base);
    for (int i = 0; i < 6; i++)
        if (!isfinite(dem->gt[i]))
            return ft_error(FT_E_INVALID, "contours: geotransform coefficient %d is not finite (%g)", i, dem->gt[i]);
    return FT_OK;
}

/* Range of the valid cells and whether some cell is not valid. FT_E_EMPTY if none is valid. */
static int valid_range(const ft_grid *g, double *zmin, double *zmax, int *any_invalid)
{
    size_t n = g->nx * g->ny, nvalid = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        if (!cell_valid(g, i))
            continue;
        nvalid++;
        lo = fmin(lo, g->z[i]);
        hi = fmax(hi, g->z[i]);
    }
    if (nvalid == 0)
        return ft_error(FT_E_EMPTY, "contours: the grid has no valid cell");
    *zmin = lo;
    *zmax = hi;
    *any_invalid = nvalid < n;
    return FT_OK;
}

int ft_io_grid_mem_raster(const ft_grid *g, float nodata, GDALDatasetH *out)
{
    *out = NULL;
    GDALDriverH mem = GDALGetDriverByName("MEM");
    ft_io_gdal_reset();
    GDALDatasetH ds = mem ? GDALCreate(mem, "", (int)g->nx, (int)g->ny, 1, GDT_Float32, NULL) : NULL;
    if (ds == NULL)
        return ft_io_fail(FT_E_NOMEM, "cannot hold a %zu x %zu grid in memory", g->nx, g->ny);
    double gt[6];
    memcpy(gt, g->gt, sizeof gt);
    GDALSetGeoTransform(ds, gt);
    float *row = ft_malloc(g->nx * sizeof *row);
    int rc = row ? FT_OK : FT_E_NOMEM;
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    for (size_t r = 0; r < g->ny && rc == FT_OK; r++) {
        for (size_t c = 0; c < g->nx; c++)
            row[c] = cell_valid(g, r * g->nx + c) ? g->z[r * g->nx + c] : nodata;
        if (GDALRasterIO(band, GF_Write, 0, (int)r, (int)g->nx, 1, row, (int)g->nx, 1, GDT_Float32, 0, 0) != CE_None)
            rc = ft_io_fail(FT_E_IO, "cannot fill row %zu of the in-memory raster", r);
    }
    free(row);
    if (rc != FT_OK) {
        GDALClose(ds);
        return rc;
    }
    *out = ds;
    return FT_OK;
}

/* An in-memory vector dataset with the (empty) contour layer: ID, lower and upper level. */
static int make_layer(const ft_grid *g, GDALDatasetH *vds, OGRLayerH *layer)
{
    *vds = NULL;
    OGRSpatialReferenceH srs = NULL;
    int rc = ft_io_srs_from_wkt(g->crs_wkt, &srs);
    if (rc != FT_OK)
        return rc;
    GDALDriverH drv = GDALGetDriverByName("Memory");
    ft_io_gdal_reset();
    GDALDatasetH ds = drv ? GDALCreate(drv, "", 0, 0, 0, GDT_Unknown, NULL) : NULL;
    OGRLayerH l = ds ? GDALDatasetCreateLayer(ds, CONTOUR_LAYER, srs, wkbMultiPolygon, NULL) : NULL;
    if (srs != NULL)
        OSRDestroySpatialReference(srs);
    static const struct {
        const char *name;
        OGRFieldType type;
    } fields[] = {{FIELD_ID, OFTInteger}, {FIELD_LOW, OFTReal}, {FIELD_HIGH, OFTReal}};
    for (size_t i = 0; l != NULL && i < sizeof fields / sizeof fields[0]; i++) {
        OGRFieldDefnH fd = OGR_Fld_Create(fields[i].name, fields[i].type);
        if (OGR_L_CreateField(l, fd, TRUE) != OGRERR_NONE)
            l = NULL;
        OGR_Fld_Destroy(fd);
    }
    if (l == NULL) {
        if (ds != NULL)
            GDALClose(ds);
        return ft_io_fail(FT_E_NOMEM, "contours: cannot make the in-memory contour layer");
    }
    *vds = ds;
    *layer = l;
    return FT_OK;
}

static int run_contours(GDALDatasetH raster, OGRLayerH layer, double interval, double base, int use_nodata,
                        float nodata)
{
    char buf[64];
    char **opts = NULL;
    snprintf(buf, sizeof buf, "%.17g", interval);
    opts = CSLSetNameValue(opts, "LEVEL_INTERVAL", buf);
    snprintf(buf, sizeof buf, "%.17g", base);
    opts = CSLSetNameValue(opts, "LEVEL_BASE", buf);
    opts = CSLSetNameValue(opts, "POLYGONIZE", "YES");
    opts = CSLSetNameValue(opts, "ID_FIELD", "0");
    opts = CSLSetNameValue(opts, "ELEV_FIELD_MIN", "1");
    opts = CSLSetNameValue(opts, "ELEV_FIELD_MAX", "2");
    if (use_nodata) {
        snprintf(buf, sizeof buf, "%.9g", (double)nodata);
        opts = CSLSetNameValue(opts, "NODATA", buf);
    }
    ft_io_gdal_reset();
    CPLErr e = GDALContourGenerateEx(GDALGetRasterBand(raster, 1), layer, (CSLConstList)opts, NULL, NULL);
    CSLDestroy(opts);
    if (e != CE_None || ft_io_gdal_failed())
        return ft_io_fail(FT_E_IO, "contours: GDAL's contour generator failed (interval %g, base %g)", interval, base);
    return FT_OK;
}

/* elev := the level below the band's upper level (see the header comment). */
static int set_lower_levels(OGRLayerH layer, double interval, double base)
{
    int high = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(layer), FIELD_HIGH);
    int low = OGR_FD_GetFieldIndex(OGR_L_GetLayerDefn(layer), FIELD_LOW);
    OGRFeatureH f;
    int rc = FT_OK;
    OGR_L_ResetReading(layer);
    while (rc == FT_OK && (f = OGR_L_GetNextFeature(layer)) != NULL) {
        double upper = OGR_F_GetFieldAsDouble(f, high);
        double k = nearbyint((upper - base) / interval);
        OGR_F_SetFieldDouble(f, low, base + (k - 1.0) * interval);
        ft_io_gdal_reset();
        if (OGR_L_SetFeature(layer, f) != OGRERR_NONE)
            rc = ft_io_fail(FT_E_IO, "contours: cannot update band %lld", (long long)OGR_F_GetFID(f));
        OGR_F_Destroy(f);
    }
    return rc;
}

static int contour_polygons(const ft_grid *dem, double interval, double base, ft_layer **out)
{
    int rc = check_args(dem, interval, base, out);
    double zmin = 0.0, zmax = 0.0;
    int any_invalid = 0;
    if (rc == FT_OK)
        rc = valid_range(dem, &zmin, &zmax, &any_invalid);
    if (rc != FT_OK)
        return rc;
    double bands = floor((zmax - base) / interval) - floor((zmin - base) / interval) + 1.0;
    if (!(bands <= CONTOUR_MAX_BANDS))
        return ft_error(FT_E_INVALID, "contours: interval %g over elevations %g to %g gives %.0f bands (at most %.0f)",
                        interval, zmin, zmax, bands, CONTOUR_MAX_BANDS);
    ft_io_init();
    /* Strictly below every valid cell, whatever their sign and magnitude (float precision included). */
    double below = zmin - 1.0 - 2.0 * fabs(zmin);
    float nodata = below > -FLT_MAX ? (float)below : -FLT_MAX;
    GDALDatasetH raster = NULL, vds = NULL;
    OGRLayerH layer = NULL;
    rc = ft_io_grid_mem_raster(dem, nodata, &raster);
    if (rc == FT_OK)
        rc = make_layer(dem, &vds, &layer);
    if (rc == FT_OK)
        rc = run_contours(raster, layer, interval, base, any_invalid, nodata);
    if (rc == FT_OK)
        rc = set_lower_levels(layer, interval, base);
    if (rc == FT_OK) {
        ft_read_layer_opts ro = FT_READ_LAYER_OPTS_DEFAULT;
        ro.layer = CONTOUR_LAYER;
        ro.fields = FIELD_LOW;
        rc = ft_io_read_layer_ds(vds, "the grid's contours", &ro, out);
    }
    if (vds != NULL)
        GDALClose(vds);
    if (raster != NULL)
        GDALClose(raster);
    return rc;
}

int ft_io_contour_polygons(const ft_grid *dem, double interval, double base, ft_layer **out)
{
    ft_io_enter();
    return ft_io_leave(contour_polygons(dem, interval, base, out));
}
