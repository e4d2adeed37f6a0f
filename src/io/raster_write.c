/* fracterra — io/raster_write.c: ft_grids as the bands of one raster, atomically (ft_io_write_grid writes
 * one band; raster_write_bands.c checks and writes several through ft_io_write_bands below).
 *
 * The driver comes from the extension (.tif/.tiff GeoTIFF tiled + ZSTD or DEFLATE, .asc Arc/Info ASCII,
 * others looked up among GDAL's drivers, no extension = GeoTIFF) or is named by the caller. Drivers that can
 * only CreateCopy (AAIGrid and others) get a copy of an in-memory dataset. Masked and non-finite cells
 * are written as the grid's nodata value, else NaN for float types, -9999 for signed integers and the
 * type's maximum for unsigned ones. Rows are written in blocks through a double buffer, so the nodata
 * value reaches the file exactly whatever the output type. Each band has its own nodata value; the
 * geotransform and CRS are the first grid's. A one-band Float32 GeoTIFF with the default codec has its
 * tiles compressed on fracterra's threads (gtiff_tiles.c), GDAL writing only its header. The file (and
 * siblings such as .prj) is written under a temporary name and renamed on success.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_conv.h>
#include <cpl_string.h>

#include "internal.h"
#include "io/io_internal.h"

#define ROWS_PER_WRITE_CELLS ((size_t)1 << 20)

typedef struct {
    const char *path;
    const ft_grid *const *bands;
    size_t nbands;
    GDALDataType type;
    int *use_nodata; /* per band */
    double *nodata;  /* per band */
} grid_writer;

static int is_float(GDALDataType t)
{
    return t == GDT_Float32 || t == GDT_Float64;
}

double ft_io_default_nodata(GDALDataType t)
{
    switch (t) {
    case GDT_Float32:
    case GDT_Float64: return NAN;
    case GDT_Byte: return 255.0;
    case GDT_UInt16: return 65535.0;
    case GDT_UInt32: return 4294967295.0;
    default: return -9999.0;
    }
}

static int cell_invalid(const ft_grid *g, size_t i)
{
    return (g->mask != NULL && g->mask[i] == 0) || !isfinite(g->z[i]);
}

/* Whether a cell is masked out or not finite. Without a mask the cells are checked a block at a time by
 * a loop without an exit, which vectorizes (|z| <= FLT_MAX is false for NaN and the infinities). */
#define INVALID_SCAN_BLOCK 4096

static int any_invalid(const ft_grid *g)
{
    size_t n = g->nx * g->ny;
    if (g->mask != NULL) {
        for (size_t i = 0; i < n; i++)
            if (cell_invalid(g, i))
                return 1;
        return 0;
    }
    const float *z = g->z;
    for (size_t i0 = 0; i0 < n; i0 += INVALID_SCAN_BLOCK) {
        size_t i1 = n - i0 < INVALID_SCAN_BLOCK ? n : i0 + INVALID_SCAN_BLOCK;
        int bad = 0;
#pragma omp simd reduction(| : bad)
        for (size_t i = i0; i < i1; i++)
            bad |= !(fabsf(z[i]) <= FLT_MAX);
        if (bad)
            return 1;
    }
    return 0;
}

int ft_io_output_type(int requested, GDALDataType *t)
{
    *t = requested == 0 ? GDT_Float32 : (GDALDataType)requested;
    if (requested < 0 || requested >= GDT_TypeCount || *t == GDT_Unknown)
        return ft_error(FT_E_INVALID, "unknown raster data type code %d", requested);
    if (GDALDataTypeIsComplex(*t))
        return ft_error(FT_E_UNSUPPORTED, "complex data type %s cannot hold a grid", GDALGetDataTypeName(*t));
    return FT_OK;
}

/* The GeoTIFF codec of a write that names none: FRACTERRA_GTIFF_COMPRESS (environment or GDAL config option)
 * when set, else ZSTD when this GDAL's GeoTIFF driver has it, else DEFLATE. */
static int default_codec(GDALDriverH drv, const char **codec)
{
    const char *list = GDALGetMetadataItem(drv, GDAL_DMD_CREATIONOPTIONLIST, NULL);
    int have_zstd = list != NULL && strstr(list, "<Value>ZSTD</Value>") != NULL;
    const char *want = CPLGetConfigOption("FRACTERRA_GTIFF_COMPRESS", NULL);
    *codec = have_zstd ? "ZSTD" : "DEFLATE";
    if (want == NULL || want[0] == '\0')
        return FT_OK;
    if (EQUAL(want, "DEFLATE") || (EQUAL(want, "ZSTD") && have_zstd)) {
        *codec = EQUAL(want, "ZSTD") ? "ZSTD" : "DEFLATE";
        return FT_OK;
    }
    if (EQUAL(want, "ZSTD"))
        return ft_error(FT_E_UNSUPPORTED, "FRACTERRA_GTIFF_COMPRESS=ZSTD: this GDAL's GeoTIFF driver has no ZSTD");
    return ft_error(FT_E_INVALID, "FRACTERRA_GTIFF_COMPRESS='%s': expected ZSTD or DEFLATE", want);
}

/* GeoTIFF defaults, overridden by the caller's: tiled, BigTIFF when needed, compressed on every core
 * (NUM_THREADS) with the floating-point or integer predictor and ZSTD level 1 (DEFLATE level 1 where GDAL
 * has no ZSTD, or when FRACTERRA_GTIFF_COMPRESS=DEFLATE asks for it, for readers on a libtiff without
 * ZSTD). Measured on 4096² Float32 fBm surfaces (docs/bench.md): ZSTD-1 + predictor 3 gives the file size
 * of DEFLATE-1 + predictor 3 (47.6 against 47.4 MB) for ~0.55x its CPU time; predictor 2 is 12 % larger,
 * LZW 29 % larger and slower. A caller's ZLEVEL alone asks for DEFLATE at that level. */
int ft_io_creation_options(GDALDriverH drv, const char *const *co, GDALDataType t, char ***out)
{
    char **o = NULL;
    *out = NULL;
    int gtiff = EQUAL(GDALGetDriverShortName(drv), "GTiff");
    int caller_codec = 0, caller_zlevel = 0;
    for (size_t i = 0; co != NULL && co[i] != NULL; i++) {
        char *key = NULL;
        CPLParseNameValue(co[i], &key);
        caller_codec |= key != NULL && EQUAL(key, "COMPRESS");
        caller_zlevel |= key != NULL && EQUAL(key, "ZLEVEL");
        CPLFree(key);
    }
    const char *codec = NULL;
    if (gtiff && !caller_codec) {
        int rc = FT_OK;
        if (caller_zlevel)
            codec = "DEFLATE"; /* at the caller's level */
        else
            rc = default_codec(drv, &codec);
        if (rc != FT_OK)
            return rc;
    }
    if (gtiff) {
        o = CSLSetNameValue(o, "TILED", "YES");
        o = CSLSetNameValue(o, "PREDICTOR", is_float(t) ? "3" : "2");
        o = CSLSetNameValue(o, "BIGTIFF", "IF_SAFER");
        o = CSLSetNameValue(o, "NUM_THREADS", "ALL_CPUS");
        if (codec != NULL) {
            o = CSLSetNameValue(o, "COMPRESS", codec);
            o = CSLSetNameValue(o, EQUAL(codec, "ZSTD") ? "ZSTD_LEVEL" : "ZLEVEL", "1");
        }
    }
    for (size_t i = 0; co != NULL && co[i] != NULL; i++) {
        char *key = NULL;
        const char *val = CPLParseNameValue(co[i], &key);
        if (key != NULL && val != NULL)
            o = CSLSetNameValue(o, key, val);
        CPLFree(key);
    }
    *out = o;
    return FT_OK;
}

void ft_io_set_nodata(GDALRasterBandH b, GDALDataType t, double v)
{
    if (t == GDT_Int64)
        GDALSetRasterNoDataValueAsInt64(b, (int64_t)v);
    else if (t == GDT_UInt64)
        GDALSetRasterNoDataValueAsUInt64(b, (uint64_t)v);
    else
        GDALSetRasterNoDataValue(b, v);
}

/* Float32 output whose nodata value a float holds exactly (or none is needed): the rows go to GDAL as
 * floats, straight from the grid where a chunk has no invalid cell, else through a float copy with the
 * nodata value in the invalid cells; the same cells as the double path, without its two conversions. */
static int float_path(const grid_writer *w, size_t band)
{
    double v = w->nodata[band];
    return w->type == GDT_Float32 && (isnan(v) || (fabs(v) <= FLT_MAX && (double)(float)v == v));
}

static int write_rows(grid_writer *w, size_t band, GDALRasterBandH b, size_t row, size_t rows, void *buf,
                      GDALDataType t)
{
    const ft_grid *g = w->bands[band];
    ft_io_gdal_reset();
    if (GDALRasterIO(b, GF_Write, 0, (int)row, (int)g->nx, (int)rows, buf, (int)g->nx, (int)rows, t, 0, 0) != CE_None)
        return ft_io_fail(FT_E_IO, "cannot write rows %zu-%zu of band %zu of '%s'", row, row + rows - 1, band + 1,
                          w->path);
    return FT_OK;
}

static int write_cells(grid_writer *w, size_t band, GDALRasterBandH b)
{
    const ft_grid *g = w->bands[band];
    size_t chunk = ROWS_PER_WRITE_CELLS / g->nx;
    if (chunk < 1)
        chunk = 1;
    if (chunk > g->ny)
        chunk = g->ny;
    int as_float = float_path(w, band);
    void *buf = ft_malloc(chunk * g->nx * (as_float ? sizeof(float) : sizeof(double)));
    if (buf == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t row = 0; row < g->ny && rc == FT_OK; row += chunk) {
        size_t rows = row + chunk <= g->ny ? chunk : g->ny - row, base = row * g->nx, n = rows * g->nx;
        if (as_float) {
            size_t bad = 0; /* a band without nodata has no invalid cell (any_invalid said so) */
            for (size_t k = 0; w->use_nodata[band] && k < n; k++)
                bad += cell_invalid(g, base + k);
            float *f = buf, nd = (float)w->nodata[band];
            if (bad == 0) { /* GDAL only reads the buffer of a write: the grid itself */
                rc = write_rows(w, band, b, row, rows, g->z + base, GDT_Float32);
                continue;
            }
            for (size_t k = 0; k < n; k++)
                f[k] = cell_invalid(g, base + k) ? nd : g->z[base + k];
            rc = write_rows(w, band, b, row, rows, f, GDT_Float32);
        } else {
            double *d = buf;
            for (size_t k = 0; k < n; k++)
                d[k] = cell_invalid(g, base + k) ? w->nodata[band] : (double)g->z[base + k];
            rc = write_rows(w, band, b, row, rows, d, GDT_Float64);
        }
    }
    free(buf);
    return rc;
}

/* Geotransform, CRS and every band's nodata of ds. */
static int fill_header(grid_writer *w, GDALDatasetH ds)
{
    const ft_grid *g = w->bands[0];
    double gt[6];
    memcpy(gt, g->gt, sizeof gt);
    ft_io_gdal_reset();
    if (GDALSetGeoTransform(ds, gt) != CE_None)
        return ft_io_fail(FT_E_IO, "cannot set the geotransform of '%s'", w->path);
    if (g->crs_wkt != NULL && g->crs_wkt[0] != '\0') {
        OGRSpatialReferenceH srs;
        int rc = ft_io_srs_from_wkt(g->crs_wkt, &srs);
        if (rc != FT_OK)
            return rc;
        CPLErr e = GDALSetSpatialRef(ds, srs);
        OSRDestroySpatialReference(srs);
        if (e != CE_None)
            return ft_io_fail(FT_E_UNSUPPORTED, "the %s format of '%s' cannot store its CRS",
                              GDALGetDriverShortName(GDALGetDatasetDriver(ds)), w->path);
    }
    for (size_t k = 0; k < w->nbands; k++)
        if (w->use_nodata[k])
            ft_io_set_nodata(GDALGetRasterBand(ds, (int)k + 1), w->type, w->nodata[k]);
    return FT_OK;
}

/* Geotransform, CRS, nodata and cells of every band of ds. */
static int fill_dataset(grid_writer *w, GDALDatasetH ds)
{
    int rc = fill_header(w, ds);
    for (size_t k = 0; k < w->nbands && rc == FT_OK; k++)
        rc = write_cells(w, k, GDALGetRasterBand(ds, (int)k + 1));
    return rc;
}

/* Creates file with drv and co, fills it (fill_dataset, or fill_header alone) and closes it. */
static int create_filled(grid_writer *w, GDALDriverH drv, const char *file, char **co,
                         int (*fill)(grid_writer *, GDALDatasetH))
{
    ft_io_gdal_reset();
    GDALDatasetH ds = GDALCreate(drv, file, (int)w->bands[0]->nx, (int)w->bands[0]->ny, (int)w->nbands, w->type, co);
    if (ds == NULL)
        return ft_io_fail(FT_E_IO, "cannot create '%s' (%s)", w->path, GDALGetDriverShortName(drv));
    int rc = fill(w, ds);
    ft_io_gdal_reset();
    GDALClose(ds);
    if (rc == FT_OK && ft_io_gdal_failed())
        rc = ft_io_fail(FT_E_IO, "cannot finish writing '%s'", w->path);
    return rc;
}

static int write_direct(grid_writer *w, GDALDriverH drv, const char *tmp, char **co)
{
    return create_filled(w, drv, tmp, co, fill_dataset);
}

/* One Float32 band with the default GeoTIFF codec (ZSTD + predictor 3, no caller creation option): its tiles
 * can be compressed on fracterra's threads (gtiff_tiles.c) instead of GDAL's. */
static int tiles_path(const grid_writer *w, GDALDriverH drv, const ft_write_grid_opts *o, char **co)
{
    const char *codec = CSLFetchNameValue(co, "COMPRESS"), *pred = CSLFetchNameValue(co, "PREDICTOR");
    return w->nbands == 1 && (o->co == NULL || o->co[0] == NULL) && float_path(w, 0) &&
           EQUAL(GDALGetDriverShortName(drv), "GTiff") && codec != NULL && EQUAL(codec, "ZSTD") && pred != NULL &&
           EQUAL(pred, "3") && CSLFetchNameValue(co, "ZSTD_LEVEL") != NULL;
}

/* GDAL writes the header of the file on disk with no tile (SPARSE_OK), then the tiles are appended; a file
 * whose layout is not the expected one (*done 0) is written again by write_direct. */
static int write_tiles(grid_writer *w, GDALDriverH drv, const char *file, char **co, int *done)
{
    *done = 0;
    char **hco = CSLSetNameValue(CSLDuplicate(co), "SPARSE_OK", "TRUE");
    hco = CSLSetNameValue(hco, "NUM_THREADS", NULL);
    int rc = create_filled(w, drv, file, hco, fill_header);
    CSLDestroy(hco);
    if (rc != FT_OK)
        return rc;
    return ft_io_gtiff_tiles_fill(w->path, file, w->bands[0], w->use_nodata[0], (float)w->nodata[0],
                                  atoi(CSLFetchNameValue(co, "ZSTD_LEVEL")), done);
}

static int write_copy(grid_writer *w, GDALDriverH drv, const char *tmp, char **co)
{
    GDALDriverH mem = GDALGetDriverByName("MEM");
    ft_io_gdal_reset();
    GDALDatasetH src =
        mem ? GDALCreate(mem, "", (int)w->bands[0]->nx, (int)w->bands[0]->ny, (int)w->nbands, w->type, NULL) : NULL;
    if (src == NULL)
        return ft_io_fail(FT_E_NOMEM, "cannot hold '%s' in memory", w->path);
    int rc = fill_dataset(w, src);
    if (rc == FT_OK) {
        ft_io_gdal_reset();
        GDALDatasetH ds = GDALCreateCopy(drv, tmp, src, FALSE, co, NULL, NULL);
        if (ds == NULL) {
            rc = ft_io_fail(FT_E_IO, "cannot write '%s' (%s)", w->path, GDALGetDriverShortName(drv));
        } else {
            GDALClose(ds);
            if (ft_io_gdal_failed())
                rc = ft_io_fail(FT_E_IO, "cannot finish writing '%s'", w->path);
        }
    }
    GDALClose(src);
    return rc;
}

/* A driver that cannot store the band type would convert it on the way (PNG turns Float32 elevations
 * into a Byte image of their integer parts): refused instead of a silently different file. */
int ft_io_check_type(const char *path, GDALDriverH drv, GDALDataType type)
{
    const char *types = GDALGetMetadataItem(drv, GDAL_DMD_CREATIONDATATYPES, NULL);
    const char *name = GDALGetDataTypeName(type);
    if (types == NULL || name == NULL)
        return FT_OK;
    for (const char *s = strstr(types, name); s != NULL; s = strstr(s + 1, name))
        if ((s == types || s[-1] == ' ') && (s[strlen(name)] == ' ' || s[strlen(name)] == '\0'))
            return FT_OK;
    return ft_error(FT_E_UNSUPPORTED, "%s: GDAL's %s driver cannot store %s cells (it stores %s); write a GeoTIFF "
                    "(.tif), or make a picture with `fracterra hillshade` or `render`", path,
                    GDALGetDriverShortName(drv), name, types);
}

static int check_grid(const char *path, const ft_grid *g)
{
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "no grid to write to '%s'", path ? path : "(null)");
    if (g->nx > (size_t)INT32_MAX || g->ny > (size_t)INT32_MAX)
        return ft_error(FT_E_UNSUPPORTED, "grid of %zu x %zu cells is too large for GDAL", g->nx, g->ny);
    return FT_OK;
}

int ft_io_write_bands(const char *path, const ft_grid *const *bands, size_t n, const ft_write_grid_opts *opts)
{
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_write_grid_opts) != FT_OK)
        return FT_E_INVALID;
    grid_writer w = {.path = path, .bands = bands, .nbands = n};
    GDALDriverH drv;
    int rc = FT_OK;
    for (size_t k = 0; k < n && rc == FT_OK; k++)
        rc = check_grid(path, bands[k]);
    if (rc == FT_OK)
        rc = ft_io_check_writable(path);
    if (rc == FT_OK)
        rc = ft_io_output_type(o.type, &w.type);
    if (rc == FT_OK)
        rc = ft_io_find_driver(path, o.driver, GDAL_DCAP_RASTER, &drv);
    if (rc == FT_OK)
        rc = ft_io_check_type(path, drv, w.type);
    if (rc != FT_OK)
        return rc;
    w.use_nodata = ft_malloc(n * sizeof *w.use_nodata);
    w.nodata = ft_malloc(n * sizeof *w.nodata);
    ft_io_stage st;
    rc = w.use_nodata && w.nodata ? ft_io_stage_begin(path, drv, 8.0 * (double)n * (double)bands[0]->nx * (double)bands[0]->ny, &st) : FT_E_NOMEM;
    if (rc != FT_OK) {
        free(w.use_nodata);
        free(w.nodata);
        return rc;
    }
    for (size_t k = 0; k < n; k++) {
        w.use_nodata[k] = bands[k]->has_nodata || any_invalid(bands[k]);
        w.nodata[k] = bands[k]->has_nodata ? bands[k]->nodata_value : ft_io_default_nodata(w.type);
    }
    char **co = NULL;
    rc = ft_io_creation_options(drv, o.co, w.type, &co);
    int direct = GDALGetMetadataItem(drv, GDAL_DCAP_CREATE, NULL) != NULL;
    int done = 0;
    if (rc == FT_OK && direct && tiles_path(&w, drv, &o, co)) /* on the on-disk temporary: libtiff opens it */
        rc = write_tiles(&w, drv, st.tmp, co, &done);
    if (rc == FT_OK && !done)
        rc = direct ? write_direct(&w, drv, st.target, co) : write_copy(&w, drv, st.target, co);
    CSLDestroy(co);
    int end = ft_io_stage_end(&st, rc == FT_OK);
    if (rc == FT_OK)
        rc = end;
    free(w.use_nodata);
    free(w.nodata);
    return rc;
}

static int write_grid(const char *path, const ft_grid *g, const ft_write_grid_opts *opts)
{
    return ft_io_write_bands(path, &g, 1, opts);
}

int ft_io_write_grid(const char *path, const ft_grid *g, const ft_write_grid_opts *opts)
{
    ft_io_enter();
    return ft_io_leave(write_grid(path, g, opts));
}
