/* fracterra — src/io/grid_reproject.c: a grid warped to another CRS with square cells of a given ground
 * size (GDALSuggestedWarpOutput2 for the extent, GDALReprojectImage with bilinear resampling), as
 * `gdalwarp -t_srs DST -tr cell cell -r bilinear` would. Nodata cells stay nodata; target cells outside
 * the source are nodata.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <gdalwarper.h>
#include <math.h>
#include <string.h>

#include "internal.h"
#include "io/io_internal.h"

/* The target extent from GDAL, snapped to whole cells of `cell`. */
static int target_frame(GDALDatasetH src, const char *src_wkt, const char *dst_wkt, double cell, double gt[6],
                        size_t *nx, size_t *ny)
{
    void *tr = GDALCreateGenImgProjTransformer(src, src_wkt, NULL, dst_wkt, FALSE, 0.0, 1);
    if (tr == NULL)
        return ft_io_fail(FT_E_FORMAT, "no transformation from the grid's CRS to the target CRS");
    double sgt[6], extent[4];
    int w = 0, h = 0;
    CPLErr err = GDALSuggestedWarpOutput2(src, GDALGenImgProjTransform, tr, sgt, &w, &h, extent, 0);
    GDALDestroyGenImgProjTransformer(tr);
    if (err != CE_None)
        return ft_io_fail(FT_E_FORMAT, "cannot find the grid's extent in the target CRS");
    double x0 = floor(extent[0] / cell) * cell, y1 = ceil(extent[3] / cell) * cell;
    double cols = ceil((extent[2] - x0) / cell), rows = ceil((y1 - extent[1]) / cell);
    if (!(cols >= 1.0 && rows >= 1.0) || cols * rows > 4.0e9)
        return ft_error(FT_E_INVALID, "reprojected grid of %g x %g cells of %g is not usable", cols, rows, cell);
    *nx = (size_t)cols;
    *ny = (size_t)rows;
    gt[0] = x0;
    gt[1] = cell;
    gt[2] = 0.0;
    gt[3] = y1;
    gt[4] = 0.0;
    gt[5] = -cell;
    return FT_OK;
}

/* Reads band 1 of ds into a new grid, NaN cells masked. */
static int read_back(GDALDatasetH ds, size_t nx, size_t ny, const double gt[6], const char *wkt, ft_grid **out)
{
    ft_grid *g = ft_grid_create(nx, ny);
    if (g == NULL)
        return FT_E_NOMEM;
    memcpy(g->gt, gt, sizeof g->gt);
    int rc = ft_grid_set_crs(g, wkt);
    if (rc == FT_OK && GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, (int)nx, (int)ny, g->z, (int)nx,
                                    (int)ny, GDT_Float32, 0, 0) != CE_None)
        rc = ft_io_fail(FT_E_IO, "cannot read the reprojected grid back");
    if (rc == FT_OK && ft_grid_mask_nonfinite(g) > 0) {
        g->has_nodata = 1;
        g->nodata_value = NAN;
    }
    if (rc == FT_OK && ft_grid_count_valid(g) == 0)
        rc = ft_error(FT_E_EMPTY, "the reprojected grid has no valid cell");
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}

static int grid_reproject(const ft_grid *g, const char *dst_wkt, double cell, ft_grid **out)
{
    if (g == NULL || out == NULL || dst_wkt == NULL)
        return ft_error(FT_E_INVALID, "ft_io_grid_reproject: NULL %s", g == NULL ? "grid" : out ? "CRS" : "out");
    *out = NULL;
    if (!(cell > 0.0) || !isfinite(cell))
        return ft_error(FT_E_INVALID, "reprojected cell size must be finite and > 0, got %g", cell);
    if (g->crs_wkt == NULL || g->crs_wkt[0] == '\0')
        return ft_error(FT_E_INVALID, "a grid without CRS cannot be reprojected");
    if (g->nx > INT32_MAX || g->ny > INT32_MAX)
        return ft_error(FT_E_INVALID, "grid of %zu x %zu cells is too large to reproject", g->nx, g->ny);
    ft_io_init();
    GDALDatasetH src = NULL, dst = NULL;
    int rc = ft_io_grid_mem_raster(g, NAN, &src);
    double gt[6];
    size_t nx = 0, ny = 0;
    if (rc == FT_OK) {
        GDALSetProjection(src, g->crs_wkt);
        GDALSetRasterNoDataValue(GDALGetRasterBand(src, 1), NAN);
        rc = target_frame(src, g->crs_wkt, dst_wkt, cell, gt, &nx, &ny);
    }
    if (rc == FT_OK) {
        GDALDriverH mem = GDALGetDriverByName("MEM");
        dst = mem ? GDALCreate(mem, "", (int)nx, (int)ny, 1, GDT_Float32, NULL) : NULL;
        if (dst == NULL)
            rc = ft_io_fail(FT_E_NOMEM, "cannot hold a %zu x %zu reprojected grid in memory", nx, ny);
    }
    if (rc == FT_OK) {
        GDALSetGeoTransform(dst, gt);
        GDALSetProjection(dst, dst_wkt);
        GDALRasterBandH b = GDALGetRasterBand(dst, 1);
        GDALSetRasterNoDataValue(b, NAN);
        GDALFillRaster(b, NAN, 0.0);
        ft_io_gdal_reset();
        if (GDALReprojectImage(src, g->crs_wkt, dst, dst_wkt, GRA_Bilinear, 0.0, 0.125, NULL, NULL, NULL) !=
            CE_None)
            rc = ft_io_fail(FT_E_FORMAT, "reprojecting the grid failed");
    }
    if (rc == FT_OK)
        rc = read_back(dst, nx, ny, gt, dst_wkt, out);
    if (src)
        GDALClose(src);
    if (dst)
        GDALClose(dst);
    return rc;
}

int ft_io_grid_reproject(const ft_grid *g, const char *dst_wkt, double cell, ft_grid **out)
{
    ft_io_enter();
    return ft_io_leave(grid_reproject(g, dst_wkt, cell, out));
}
