/* fracterra — io/dem_processing.c: the hillshade of a DEM file, optionally times a colour relief through
 * GDAL's own DEM processing (GDALDEMProcessing color-relief, the engine of gdaldem), and CRS strings to WKT
 * (OSRSetFromUserInput).
 *
 * The shade is the library's one engine, ft_render_hillshade (Horn's slope, edges computed and nodata
 * neighbours replaced by the centre, as gdaldem hillshade -compute_edges), written as gdaldem writes its
 * Byte output: 1 + 254 x shade / 255 rounded, 0 = nodata. A stripe of rows (ft_io_hillshade_rows) is shaded
 * by the same engine from the stripe plus one row above and below, so its cells are the whole run's.
 * `scale` is the engine's (ground units of the horizontal coordinates per elevation unit); 0 asks for the
 * metres of a degree of latitude on the DEM's ellipsoid at its centre for a DEM in degrees (CRS service),
 * as gdaldem's documentation advises (its 111120 is that figure at about 45 degrees), else 1.
 * With colour, gdaldem's "color-relief" maps the DEM through a built-in hypsometric ramp written to
 * /vsimem (stops at fractions of the DEM's range, "nv" transparent), and each colour is multiplied by
 * 0.25 + 0.75 * shade / 255 (an ambient term keeps shadows readable). The output (any GDAL raster driver
 * that can CreateCopy, chosen by extension: PNG, GeoTIFF, ...) is written under a temporary name and
 * renamed when complete. GDAL's auxiliary .aux.xml files are off during the call: neither the input's
 * folder nor the output's gets one.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <limits.h>
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal_utils.h>

#include "fracterra/render.h"
#include "internal.h"
#include "io/io_internal.h"

#define SHADE_AMBIENT 0.25

static atomic_ulong vsimem_counter;

/* Hypsometric tints from lowland green through tan and brown to white summits, as render/grid_image.c:
 * fraction of the DEM's range, red, green, blue. */
static const struct {
    double t;
    int r, g, b;
} ramp_stops[] = {{0.00, 61, 125, 69},   {0.20, 140, 181, 107}, {0.45, 232, 217, 148},
                  {0.70, 181, 138, 89},  {0.88, 140, 115, 102}, {1.00, 250, 250, 250}};

typedef struct {
    char cr[96], ramp[96]; /* /vsimem names of this call */
} vsimem_names;

static void names_init(vsimem_names *n)
{
    unsigned long id = atomic_fetch_add(&vsimem_counter, 1);
    snprintf(n->cr, sizeof n->cr, "/vsimem/fracterra_cr_%p_%lu.tif", (void *)n, id);
    snprintf(n->ramp, sizeof n->ramp, "/vsimem/fracterra_ramp_%p_%lu.txt", (void *)n, id);
}

static void names_release(const vsimem_names *n)
{
    VSIUnlink(n->cr);
    VSIUnlink(n->ramp);
}

static int check_opts(const ft_io_hillshade_opts *o)
{
    if (!isfinite(o->azimuth) || o->azimuth < 0.0 || o->azimuth > 360.0)
        return ft_error(FT_E_INVALID, "hillshade azimuth must be in [0,360] degrees, got %g", o->azimuth);
    if (!isfinite(o->altitude) || o->altitude <= 0.0 || o->altitude > 90.0)
        return ft_error(FT_E_INVALID, "hillshade altitude must be in (0,90] degrees, got %g", o->altitude);
    if (!isfinite(o->z_factor) || o->z_factor <= 0.0)
        return ft_error(FT_E_INVALID, "hillshade z-factor must be > 0, got %g", o->z_factor);
    if (!isfinite(o->scale) || o->scale < 0.0)
        return ft_error(FT_E_INVALID, "hillshade scale must be > 0 (0 = automatic), got %g", o->scale);
    if (o->band < 1)
        return ft_error(FT_E_INVALID, "hillshade band must be >= 1, got %d", o->band);
    return FT_OK;
}

/* For a DEM in degrees (ft_io_crs_info), the ground metres of a degree of latitude on its ellipsoid at its
 * centre; 1 otherwise, unless the caller set a scale. The engine takes one scale for both axes (as gdaldem),
 * so the shortening of a degree of longitude (cos latitude) is not applied. dem: the whole DEM's header. */
static double effective_scale(const ft_grid *dem, double scale)
{
    if (scale > 0.0)
        return scale;
    ft_crs_info crs;
    if (dem->crs_wkt == NULL || ft_io_crs_info(dem->crs_wkt, &crs) != FT_OK || !crs.geographic) {
        ft_clear_error();
        return 1.0;
    }
    double per_lat = 0.0;
    double lat = dem->gt[3] + 0.5 * (double)dem->nx * dem->gt[4] + 0.5 * (double)dem->ny * dem->gt[5];
    ft_ellipsoid_metres_per_degree(&crs.ellipsoid, fabs(lat) <= 90.0 ? lat : 0.0, NULL, &per_lat);
    return per_lat;
}

/* The engine's shade of dem with the options of o at the given scale, as gdaldem's Byte values in a float
 * grid: 1 + 254 s / 255 rounded for a shade s in [0, 255], 0 (the grid's nodata value) for nodata. */
static int shade_bytes(const ft_grid *dem, const ft_io_hillshade_opts *o, double scale, ft_grid **out)
{
    ft_hillshade_opts ro = FT_HILLSHADE_OPTS_DEFAULT;
    ro.azimuth = o->azimuth;
    ro.altitude = o->altitude;
    ro.z_factor = o->z_factor;
    ro.scale = scale;
    int rc = ft_render_hillshade(dem, &ro, out);
    if (rc != FT_OK)
        return rc;
    ft_grid *g = *out;
    for (size_t k = 0; k < g->nx * g->ny; k++)
        g->z[k] = g->mask[k] ? (float)floor(1.0 + 254.0 * (double)g->z[k] / 255.0 + 0.5) : 0.0f;
    g->nodata_value = 0.0;
    return FT_OK;
}

/* Runs GDALDEMProcessing(mode) from src to the /vsimem GeoTIFF dst; the result stays open in *out. */
static int dem_run(GDALDatasetH src, const char *mode, const char *dst, const char *color_file, char **argv,
                   GDALDatasetH *out)
{
    ft_io_gdal_reset();
    GDALDEMProcessingOptions *opts = GDALDEMProcessingOptionsNew(argv, NULL);
    if (opts == NULL)
        return ft_io_fail(FT_E_INVALID, "hillshade: GDAL rejected the %s options", mode);
    int usage_error = 0;
    *out = GDALDEMProcessing(dst, src, mode, color_file, opts, &usage_error);
    GDALDEMProcessingOptionsFree(opts);
    if (*out == NULL)
        return ft_io_fail(FT_E_IO, "hillshade: GDAL's %s failed", mode);
    return FT_OK;
}

/* The ramp at the DEM's own elevations (absolute values: no statistics pass, no message from GDAL). */
static int write_ramp(GDALDatasetH src, int band, const char *path)
{
    double mm[2];
    ft_io_gdal_reset();
    if (GDALComputeRasterMinMax(GDALGetRasterBand(src, band), FALSE, mm) != CE_None || ft_io_gdal_failed())
        return ft_io_fail(FT_E_EMPTY, "hillshade: the DEM has no valid cell to colour");
    VSILFILE *f = VSIFOpenL(path, "wb");
    if (f == NULL)
        return ft_error(FT_E_IO, "hillshade: cannot write the colour ramp %s", path);
    int ok = VSIFPrintfL(f, "nv 0 0 0 0\n") > 0;
    for (size_t i = 0; i < sizeof ramp_stops / sizeof ramp_stops[0]; i++)
        ok &= VSIFPrintfL(f, "%.17g %d %d %d\n", mm[0] + ramp_stops[i].t * (mm[1] - mm[0]), ramp_stops[i].r,
                          ramp_stops[i].g, ramp_stops[i].b) > 0;
    ok &= VSIFCloseL(f) == 0;
    return ok ? FT_OK : ft_error(FT_E_IO, "hillshade: cannot write the colour ramp %s", path);
}

static int run_color(GDALDatasetH src, const ft_io_hillshade_opts *o, const vsimem_names *n, GDALDatasetH *out)
{
    char band[16];
    snprintf(band, sizeof band, "%d", o->band);
    char *argv[] = {"-q", "-of", "GTiff", "-b", band, "-alpha", NULL};
    int rc = write_ramp(src, o->band, n->ramp);
    return rc == FT_OK ? dem_run(src, "color-relief", n->cr, n->ramp, argv, out) : rc;
}

/* Reads band b of ds as bytes. */
static int read_band(GDALDatasetH ds, int b, unsigned char *buf, int w, int h)
{
    GDALRasterBandH band = GDALGetRasterBand(ds, b);
    if (band == NULL || GDALRasterIO(band, GF_Read, 0, 0, w, h, buf, w, h, GDT_Byte, 0, 0) != CE_None)
        return ft_io_fail(FT_E_IO, "hillshade: cannot read band %d of an intermediate product", b);
    return FT_OK;
}

/* A MEM Byte dataset of `bands` bands (1: the shade, 0 = nodata; 4: RGBA) holding px band after band, with
 * the georeferencing of src. */
static int byte_image(GDALDatasetH src, int w, int h, int bands, unsigned char *px, GDALDatasetH *out)
{
    GDALDriverH mem = GDALGetDriverByName("MEM");
    *out = mem ? GDALCreate(mem, "", w, h, bands, GDT_Byte, NULL) : NULL;
    if (*out == NULL)
        return ft_io_fail(FT_E_NOMEM, "hillshade: cannot make a %d x %d image", w, h);
    double gt[6];
    if (GDALGetGeoTransform(src, gt) == CE_None)
        GDALSetGeoTransform(*out, gt);
    GDALSetProjection(*out, GDALGetProjectionRef(src));
    if (bands == 1) {
        GDALSetRasterNoDataValue(GDALGetRasterBand(*out, 1), 0.0);
    } else {
        static const GDALColorInterp ci[] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand, GCI_AlphaBand};
        for (int b = 0; b < 4; b++)
            GDALSetRasterColorInterpretation(GDALGetRasterBand(*out, b + 1), ci[b]);
    }
    if (GDALDatasetRasterIO(*out, GF_Write, 0, 0, w, h, px, w, h, GDT_Byte, bands, NULL, 0, 0, 0) != CE_None)
        return ft_io_fail(FT_E_IO, "hillshade: cannot fill the %d x %d image", w, h);
    return FT_OK;
}

/* RGBA = colour relief (cr) x shade (w x h bytes, 0 = nodata), in a MEM dataset with src's georeferencing. */
static int combine(GDALDatasetH src, const unsigned char *shade, GDALDatasetH cr, GDALDatasetH *out)
{
    int w = GDALGetRasterXSize(src), h = GDALGetRasterYSize(src);
    size_t n = (size_t)w * (size_t)h;
    unsigned char *px = ft_malloc(4 * n);
    if (px == NULL)
        return ft_last_error_code();
    int rc = FT_OK;
    for (int b = 1; b <= 4 && rc == FT_OK; b++)
        rc = read_band(cr, b, px + (size_t)(b - 1) * n, w, h);
    if (rc == FT_OK) {
        for (size_t i = 0; i < n; i++) {
            double f = SHADE_AMBIENT + (1.0 - SHADE_AMBIENT) * shade[i] / 255.0;
            for (int b = 0; b < 3; b++)
                px[(size_t)b * n + i] = (unsigned char)lround(px[(size_t)b * n + i] * f);
            if (shade[i] == 0)
                px[3 * n + i] = 0; /* nodata in the hillshade */
        }
        rc = byte_image(src, w, h, 4, px, out);
    }
    free(px);
    return rc;
}

/* CreateCopy of ds to path through a temporary name. */
static int write_copy(GDALDatasetH ds, const char *path)
{
    GDALDriverH drv = NULL;
    int rc = ft_io_find_driver(path, NULL, GDAL_DCAP_RASTER, &drv);
    if (rc != FT_OK)
        return rc;
    if (GDALGetMetadataItem(drv, GDAL_DCAP_CREATECOPY, NULL) == NULL &&
        GDALGetMetadataItem(drv, GDAL_DCAP_CREATE, NULL) == NULL)
        return ft_error(FT_E_UNSUPPORTED, "hillshade: GDAL's %s driver cannot write %s", GDALGetDriverShortName(drv),
                        path);
    ft_io_stage st;
    if ((rc = ft_io_stage_begin(path, drv, 4.0 * GDALGetRasterXSize(ds) * GDALGetRasterYSize(ds), &st)) != FT_OK)
        return rc;
    ft_io_gdal_reset();
    GDALDatasetH out = GDALCreateCopy(drv, st.target, ds, FALSE, NULL, NULL, NULL);
    if (out != NULL)
        GDALClose(out);
    int ok = out != NULL && !ft_io_gdal_failed();
    if (!ok)
        rc = ft_io_fail(FT_E_IO, "cannot write %s", path);
    int end = ft_io_stage_end(&st, ok);
    return ok ? end : rc;
}

/* Reads the band through the grid reader, so that a hillshade is refused where `render` refuses the same
 * DEM: a truncated file (a read error, not a grid of zeros), fewer than 2 x 2 cells, no valid cell, or more
 * cells than the memory bound allows. */
static int read_shadeable(GDALDatasetH src, const char *path, int band, ft_grid **out)
{
    ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
    go.band = band;
    ft_grid *g = NULL;
    int rc = ft_io_read_grid_ds(src, path, &go, &g);
    if (rc == FT_OK && (g->nx < 2 || g->ny < 2))
        rc = ft_error(FT_E_INVALID, "%s has %zu x %zu cells; a hillshade needs at least 2 x 2", path, g->nx,
                      g->ny);
    if (rc == FT_OK) {
        char what[PATH_MAX + 64];
        snprintf(what, sizeof what, "shading '%s' (%zu x %zu cells)", path, g->nx, g->ny);
        rc = ft_check_work(4.0 * (double)g->nx * (double)g->ny, what); /* read, slope, shade, encode */
    }
    if (rc == FT_OK && ft_grid_count_valid(g) == 0)
        rc = ft_error(FT_E_EMPTY, "%s has no valid cell (all %zu are nodata): nothing to shade", path, g->nx * g->ny);
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}

/* The shade of dem (read from src; freed as soon as it is shaded, to halve the peak memory) as bytes, times
 * the colour relief with o->color, written to out_path. */
static int shade_and_write(GDALDatasetH src, ft_grid *dem, const ft_io_hillshade_opts *o, const char *out_path,
                           const vsimem_names *n)
{
    ft_grid *sh = NULL;
    size_t nx = dem->nx, ny = dem->ny, cells = nx * ny;
    int rc = shade_bytes(dem, o, effective_scale(dem, o->scale), &sh);
    ft_grid_free(dem);
    if (rc != FT_OK)
        return rc;
    unsigned char *px = ft_malloc(cells);
    GDALDatasetH cr = NULL, img = NULL;
    if (px == NULL)
        rc = ft_last_error_code();
    for (size_t k = 0; rc == FT_OK && k < cells; k++)
        px[k] = (unsigned char)sh->z[k];
    ft_grid_free(sh);
    if (rc == FT_OK && o->color)
        rc = run_color(src, o, n, &cr);
    if (rc == FT_OK)
        rc = o->color ? combine(src, px, cr, &img) : byte_image(src, (int)nx, (int)ny, 1, px, &img);
    if (rc == FT_OK)
        rc = write_copy(img, out_path);
    if (img)
        GDALClose(img);
    if (cr)
        GDALClose(cr);
    free(px);
    return rc;
}

static int open_and_shade(const char *dem_path, const char *out_path, const ft_io_hillshade_opts *o)
{
    GDALDatasetH src = NULL;
    int rc = ft_io_open(dem_path, GDAL_OF_RASTER, &src);
    if (rc != FT_OK)
        return rc;
    if (o->band > GDALGetRasterCount(src)) {
        rc = ft_error(FT_E_FORMAT, "%s has %d band(s), band %d was asked for", dem_path, GDALGetRasterCount(src),
                      o->band);
    } else {
        ft_grid *dem = NULL;
        if ((rc = read_shadeable(src, dem_path, o->band, &dem)) == FT_OK) {
            vsimem_names n;
            names_init(&n);
            rc = shade_and_write(src, dem, o, out_path, &n); /* frees dem */
            names_release(&n);
        }
    }
    GDALClose(src);
    return rc;
}

static int hillshade(const char *dem_path, const char *out_path, const ft_io_hillshade_opts *opts)
{
    ft_io_hillshade_opts taken = FT_IO_HILLSHADE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_io_hillshade_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_io_hillshade_opts defaults = FT_IO_HILLSHADE_OPTS_DEFAULT;
    const ft_io_hillshade_opts *o = opts ? opts : &defaults;
    if (dem_path == NULL || out_path == NULL || *out_path == '\0')
        return ft_error(FT_E_INVALID, "hillshade: no input or output path given");
    int rc = check_opts(o);
    if (rc == FT_OK)
        rc = ft_io_check_writable(out_path);
    if (rc != FT_OK)
        return rc;
    /* No .aux.xml beside the user's DEM nor beside the output. */
    const char *pam = CPLGetThreadLocalConfigOption("GDAL_PAM_ENABLED", NULL);
    char *saved = pam ? CPLStrdup(pam) : NULL;
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
    rc = open_and_shade(dem_path, out_path, o);
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", saved);
    CPLFree(saved);
    return rc;
}

int ft_io_hillshade(const char *dem_path, const char *out_path, const ft_io_hillshade_opts *opts)
{
    ft_io_enter();
    return ft_io_leave(hillshade(dem_path, out_path, opts));
}

static int crs_to_wkt(const char *user_input, char **wkt)
{
    if (wkt == NULL)
        return ft_error(FT_E_INVALID, "CRS: no output pointer given");
    *wkt = NULL;
    if (user_input == NULL || *user_input == '\0')
        return ft_error(FT_E_INVALID, "CRS: empty definition");
    ft_io_init();
    OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
    if (srs == NULL)
        return ft_error(FT_E_NOMEM, "CRS: out of memory");
    ft_io_gdal_reset();
    int rc = FT_OK;
    if (OSRSetFromUserInput(srs, user_input) != OGRERR_NONE)
        rc = ft_io_fail(FT_E_INVALID, "unknown CRS '%s' (give EPSG:n, a WKT string or a PROJ string)", user_input);
    else if ((*wkt = ft_io_srs_to_wkt(srs)) == NULL)
        rc = ft_error(FT_E_INVALID, "CRS '%s' cannot be written as WKT", user_input);
    OSRDestroySpatialReference(srs);
    return rc;
}

int ft_io_crs_to_wkt(const char *user_input, char **wkt)
{
    ft_io_enter();
    return ft_io_leave(crs_to_wkt(user_input, wkt));
}

static int hillshade_scale(const char *dem_path, const ft_io_hillshade_opts *opts, double *scale)
{
    ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (FT_OPTS_TAKE(o, opts, ft_io_hillshade_opts) != FT_OK)
        return FT_E_INVALID;
    if (scale == NULL || dem_path == NULL)
        return ft_error(FT_E_INVALID, "hillshade scale: no DEM path or output pointer given");
    int rc = check_opts(&o);
    if (rc != FT_OK)
        return rc;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = o.band;
    ft_grid_reader *r = NULL;
    if ((rc = ft_io_grid_reader_open(dem_path, &ro, &r)) != FT_OK)
        return rc;
    *scale = effective_scale(ft_io_grid_reader_header(r), o.scale);
    ft_io_grid_reader_close(r);
    return FT_OK;
}

int ft_io_hillshade_scale(const char *dem_path, const ft_io_hillshade_opts *opts, double *scale)
{
    ft_io_enter();
    return ft_io_leave(hillshade_scale(dem_path, opts, scale));
}

/* ---- rows of the hillshade: a stripe plus one row of halo above and below (docs/tiling.md) ---- */

/* The shade of rows [row0, row0 + nrows) of the DEM of reader r (header h): rows y0 .. y1 - 1, the stripe
 * and its halo, shaded by the engine at the whole DEM's scale; the engine's 3 x 3 window makes each output
 * cell the whole run's. */
static int shade_rows(ft_grid_reader *r, const ft_grid *h, const ft_io_hillshade_opts *o, size_t row0,
                      size_t nrows, ft_grid **out)
{
    size_t nx = h->nx, ny = h->ny;
    size_t y0 = row0 > 0 ? row0 - 1 : 0, y1 = row0 + nrows + 1 < ny ? row0 + nrows + 1 : ny;
    ft_grid *win = NULL, *sh = NULL;
    int rc = ft_io_grid_reader_read(r, 0, y0, nx, y1 - y0, &win);
    if (rc == FT_OK)
        rc = shade_bytes(win, o, effective_scale(h, o->scale), &sh);
    ft_grid_free(win);
    ft_grid *g = rc == FT_OK ? ft_grid_create(nx, nrows) : NULL;
    if (rc == FT_OK && (g == NULL || ft_grid_ensure_mask(g) != FT_OK))
        rc = FT_E_NOMEM;
    if (rc == FT_OK) {
        memcpy(g->z, sh->z + (row0 - y0) * nx, nx * nrows * sizeof *g->z);
        memcpy(g->mask, sh->mask + (row0 - y0) * nx, nx * nrows);
        memcpy(g->gt, h->gt, sizeof g->gt);
        g->gt[0] = h->gt[0] + (double)row0 * h->gt[2];
        g->gt[3] = h->gt[3] + (double)row0 * h->gt[5];
        g->has_nodata = 1;
        g->nodata_value = 0.0; /* gdaldem's */
        rc = ft_grid_set_crs(g, h->crs_wkt);
    }
    ft_grid_free(sh);
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}

static int hillshade_rows(const char *dem_path, const ft_io_hillshade_opts *opts, size_t row0, size_t nrows,
                          ft_grid **out)
{
    ft_io_hillshade_opts o_taken = FT_IO_HILLSHADE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (FT_OPTS_TAKE(o_taken, opts, ft_io_hillshade_opts) != FT_OK)
        return FT_E_INVALID;
    const ft_io_hillshade_opts *o = &o_taken;
    if (out == NULL)
        return ft_error(FT_E_INVALID, "hillshade: output pointer is NULL");
    *out = NULL;
    if (dem_path == NULL)
        return ft_error(FT_E_INVALID, "hillshade: no input path given");
    int rc = check_opts(o);
    if (rc != FT_OK)
        return rc;
    if (o->color)
        return ft_error(FT_E_UNSUPPORTED, "hillshade: a colour relief spans the whole DEM's elevation range and is "
                        "not made row by row; shade without colour");
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ro.band = o->band;
    ft_grid_reader *r = NULL;
    if ((rc = ft_io_grid_reader_open(dem_path, &ro, &r)) != FT_OK)
        return rc;
    const ft_grid *h = ft_io_grid_reader_header(r);
    if (h->nx < 2 || h->ny < 2)
        rc = ft_error(FT_E_INVALID, "%s has %zu x %zu cells; a hillshade needs at least 2 x 2", dem_path, h->nx,
                      h->ny);
    else if (nrows == 0 || row0 >= h->ny || nrows > h->ny - row0)
        rc = ft_error(FT_E_INVALID, "hillshade: rows %zu-%zu leave the %zu rows of %s", row0, row0 + nrows - 1,
                      h->ny, dem_path);
    if (rc == FT_OK)
        rc = shade_rows(r, h, o, row0, nrows, out);
    ft_io_grid_reader_close(r);
    return rc;
}

int ft_io_hillshade_rows(const char *dem_path, const ft_io_hillshade_opts *opts, size_t row0, size_t nrows,
                         ft_grid **out)
{
    ft_io_enter();
    return ft_io_leave(hillshade_rows(dem_path, opts, row0, nrows, out));
}
