/* fracterra — io/raster_tile_write.c: one raster written piece by piece (stripes or blocks of the bands, in
 * any order), so that a grid far larger than memory is written with the memory of one piece.
 *
 * The output is a tiled GeoTIFF (the GeoTIFF defaults of raster_write.c: tiled, ZSTD or DEFLATE, predictor, BigTIFF
 * when needed) created at its full size under the atomic service's on-disk temporary name; each piece goes
 * through GDALRasterIO at its global offset, GDAL's block cache gathering the pieces of a tile row, and
 * commit closes the file (the last blocks are written) and renames it onto the destination. Masked and
 * non-finite cells are written as the header's nodata value, else the type's (NaN for float types), and
 * every band carries that value as its nodata (a piece cannot know whether a later one has nodata).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_string.h>

#include "internal.h"
#include "io/io_internal.h"

struct ft_grid_writer {
    char *path;
    ft_io_stage stage;
    int staged;          /* 1 between ft_io_stage_begin and ft_io_stage_end */
    GDALDatasetH ds;
    size_t nx, ny, nbands;
    GDALDataType type;
    double nodata;
};

static void grid_writer_abort(ft_grid_writer *w);

static int set_georef(ft_grid_writer *w, const ft_grid *h)
{
    double gt[6];
    memcpy(gt, h->gt, sizeof gt);
    ft_io_gdal_reset();
    if (GDALSetGeoTransform(w->ds, gt) != CE_None)
        return ft_io_fail(FT_E_IO, "cannot set the geotransform of '%s'", w->path);
    if (h->crs_wkt == NULL || h->crs_wkt[0] == '\0')
        return FT_OK;
    OGRSpatialReferenceH srs;
    int rc = ft_io_srs_from_wkt(h->crs_wkt, &srs);
    if (rc != FT_OK)
        return rc;
    CPLErr e = GDALSetSpatialRef(w->ds, srs);
    OSRDestroySpatialReference(srs);
    return e == CE_None ? FT_OK : ft_io_fail(FT_E_IO, "cannot set the CRS of '%s'", w->path);
}

static int create_dataset(ft_grid_writer *w, const ft_grid *h, const ft_write_grid_opts *o)
{
    GDALDriverH drv;
    int rc = ft_io_find_driver(w->path, o->driver, GDAL_DCAP_RASTER, &drv);
    if (rc != FT_OK)
        return rc;
    if (!EQUAL(GDALGetDriverShortName(drv), "GTiff"))
        return ft_error(FT_E_UNSUPPORTED, "'%s': a raster written piece by piece must be a GeoTIFF (.tif), not %s",
                        w->path, GDALGetDriverShortName(drv));
    if ((rc = ft_io_check_type(w->path, drv, w->type)) != FT_OK)
        return rc;
    /* an on-disk temporary whatever the size: the pieces must not gather in memory */
    if ((rc = ft_io_stage_begin(w->path, drv, INFINITY, &w->stage)) != FT_OK)
        return rc;
    w->staged = 1;
    char **co = NULL;
    if ((rc = ft_io_creation_options(drv, o->co, w->type, &co)) != FT_OK)
        return rc;
    co = CSLSetNameValue(co, "BIGTIFF", "IF_SAFER");
    ft_io_gdal_reset();
    w->ds = GDALCreate(drv, w->stage.target, (int)w->nx, (int)w->ny, (int)w->nbands, w->type, co);
    CSLDestroy(co);
    if (w->ds == NULL)
        return ft_io_fail(FT_E_IO, "cannot create '%s'", w->path);
    if ((rc = set_georef(w, h)) != FT_OK)
        return rc;
    for (size_t b = 0; b < w->nbands; b++)
        ft_io_set_nodata(GDALGetRasterBand(w->ds, (int)b + 1), w->type, w->nodata);
    return FT_OK;
}

static int grid_writer_create(const char *path, const ft_grid *header, size_t nbands, const ft_write_grid_opts *opts,
                              ft_grid_writer **out)
{
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_write_grid_opts) != FT_OK)
        return FT_E_INVALID;
    if (out == NULL)
        return ft_error(FT_E_INVALID, "grid writer: output pointer is NULL");
    *out = NULL;
    if (path == NULL || header == NULL || header->nx == 0 || header->ny == 0)
        return ft_error(FT_E_INVALID, "grid writer: no path or an empty header");
    if (nbands == 0 || nbands > 65535)
        return ft_error(FT_E_INVALID, "grid writer: %zu bands requested for '%s' (1 .. 65535)", nbands, path);
    if (header->nx > (size_t)INT_MAX || header->ny > (size_t)INT_MAX)
        return ft_error(FT_E_UNSUPPORTED, "grid of %zu x %zu cells is too large for GDAL", header->nx, header->ny);
    ft_grid_writer *w = ft_calloc(1, sizeof *w);
    if (w == NULL || (w->path = ft_strdup(path)) == NULL) {
        free(w);
        return FT_E_NOMEM;
    }
    w->nx = header->nx;
    w->ny = header->ny;
    w->nbands = nbands;
    int rc = ft_io_check_writable(path);
    if (rc == FT_OK)
        rc = ft_io_output_type(o.type, &w->type);
    if (rc == FT_OK) {
        w->nodata = header->has_nodata ? header->nodata_value : ft_io_default_nodata(w->type);
        rc = create_dataset(w, header, &o);
    }
    if (rc != FT_OK) {
        grid_writer_abort(w);
        return rc;
    }
    *out = w;
    return FT_OK;
}

static int grid_writer_write(ft_grid_writer *w, size_t band, const ft_grid *piece, size_t col0, size_t row0)
{
    if (w == NULL || w->ds == NULL)
        return ft_error(FT_E_INVALID, "grid writer is NULL or closed");
    if (piece == NULL || piece->z == NULL || piece->nx == 0 || piece->ny == 0)
        return ft_error(FT_E_INVALID, "no piece to write to '%s'", w->path);
    if (band < 1 || band > w->nbands)
        return ft_error(FT_E_INVALID, "band %zu of '%s' requested, it has %zu", band, w->path, w->nbands);
    if (col0 >= w->nx || row0 >= w->ny || piece->nx > w->nx - col0 || piece->ny > w->ny - row0)
        return ft_error(FT_E_INVALID, "a %zu x %zu piece at column %zu, row %zu leaves the %zu x %zu raster '%s'",
                        piece->nx, piece->ny, col0, row0, w->nx, w->ny, w->path);
    size_t n = piece->nx * piece->ny;
    double *buf = ft_malloc(n * sizeof *buf);
    if (buf == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < n; i++) {
        int bad = (piece->mask != NULL && piece->mask[i] == 0) || !isfinite(piece->z[i]);
        buf[i] = bad ? w->nodata : (double)piece->z[i];
    }
    ft_io_gdal_reset();
    CPLErr e = GDALRasterIO(GDALGetRasterBand(w->ds, (int)band), GF_Write, (int)col0, (int)row0, (int)piece->nx,
                            (int)piece->ny, buf, (int)piece->nx, (int)piece->ny, GDT_Float64, 0, 0);
    free(buf);
    if (e != CE_None)
        return ft_io_fail(FT_E_IO, "cannot write rows %zu-%zu of band %zu of '%s'", row0, row0 + piece->ny - 1, band,
                          w->path);
    return FT_OK;
}

static int grid_writer_commit(ft_grid_writer *w)
{
    if (w == NULL || w->ds == NULL) {
        grid_writer_abort(w);
        return ft_error(FT_E_INVALID, "grid writer is NULL or closed");
    }
    ft_io_gdal_reset();
    GDALClose(w->ds);
    w->ds = NULL;
    int rc = ft_io_gdal_failed() ? ft_io_fail(FT_E_IO, "cannot finish writing '%s'", w->path) : FT_OK;
    int end = ft_io_stage_end(&w->stage, rc == FT_OK);
    w->staged = 0;
    if (rc == FT_OK)
        rc = end;
    grid_writer_abort(w);
    return rc;
}

static void grid_writer_abort(ft_grid_writer *w)
{
    if (w == NULL)
        return;
    if (w->ds != NULL)
        GDALClose(w->ds);
    if (w->staged)
        ft_io_stage_end(&w->stage, 0);
    free(w->path);
    free(w);
}

/* ---- public entry points: GDAL's messages kept by the module's handler (ft_io_enter) ---- */

int ft_io_grid_writer_create(const char *path, const ft_grid *header, size_t nbands, const ft_write_grid_opts *opts,
                             ft_grid_writer **out)
{
    ft_io_enter();
    return ft_io_leave(grid_writer_create(path, header, nbands, opts, out));
}

int ft_io_grid_writer_write(ft_grid_writer *w, size_t band, const ft_grid *piece, size_t col0, size_t row0)
{
    ft_io_enter();
    return ft_io_leave(grid_writer_write(w, band, piece, col0, row0));
}

int ft_io_grid_writer_commit(ft_grid_writer *w)
{
    ft_io_enter();
    return ft_io_leave(grid_writer_commit(w));
}

void ft_io_grid_writer_abort(ft_grid_writer *w)
{
    ft_io_enter();
    grid_writer_abort(w);
    ft_io_leave(FT_OK);
}
