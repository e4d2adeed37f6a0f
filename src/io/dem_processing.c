/* fracterra — io/dem_processing.c: hillshade and colour relief through GDAL's own DEM processing
 * (GDALDEMProcessing, the engine of gdaldem), and CRS strings to WKT (OSRSetFromUserInput).
 *
 * The hillshade is gdaldem's (Horn's slope, -compute_edges so that the border cells get a value, 0 kept
 * for nodata). With colour, gdaldem's "color-relief" maps the DEM through a built-in hypsometric ramp
 * written to /vsimem (stops at fractions of the DEM's range, "nv" transparent), and each colour is
 * multiplied by 0.25 + 0.75 * shade / 255 (an ambient term keeps shadows readable). Intermediate
 * products live in /vsimem; the output (any GDAL raster driver that can CreateCopy, chosen by extension:
 * PNG, GeoTIFF, ...) is written under a temporary name and renamed when complete. A geographic DEM
 * (degrees) gets the ground metres of a degree of latitude at its centre (CRS service) unless the caller gives
 * a scale, as gdaldem's documentation advises (its 111120 is that figure at about 45 degrees). GDAL's
 * auxiliary .aux.xml files are off during the call: neither the input's folder nor the output's gets one.
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
    char hs[96], cr[96], ramp[96]; /* /vsimem names of this call */
} vsimem_names;

static void names_init(vsimem_names *n)
{
    unsigned long id = atomic_fetch_add(&vsimem_counter, 1);
    snprintf(n->hs, sizeof n->hs, "/vsimem/fracterra_hs_%p_%lu.tif", (void *)n, id);
    snprintf(n->cr, sizeof n->cr, "/vsimem/fracterra_cr_%p_%lu.tif", (void *)n, id);
    snprintf(n->ramp, sizeof n->ramp, "/vsimem/fracterra_ramp_%p_%lu.txt", (void *)n, id);
}

static void names_release(const vsimem_names *n)
{
    VSIUnlink(n->hs);
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
 * centre; 1 otherwise, unless the caller set a scale. gdaldem takes one scale for both axes, so the
 * shortening of a degree of longitude (cos latitude) is not applied. */
static double effective_scale(GDALDatasetH ds, double scale)
{
    if (scale > 0.0)
        return scale;
    ft_crs_info crs;
    if (ft_io_crs_info(GDALGetProjectionRef(ds), &crs) != FT_OK || !crs.geographic) {
        ft_clear_error();
        return 1.0;
    }
    double gt[6] = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0}, per_lat = 0.0;
    GDALGetGeoTransform(ds, gt);
    double lat = gt[3] + 0.5 * GDALGetRasterXSize(ds) * gt[4] + 0.5 * GDALGetRasterYSize(ds) * gt[5];
    ft_ellipsoid_metres_per_degree(&crs.ellipsoid, fabs(lat) <= 90.0 ? lat : 0.0, NULL, &per_lat);
    return per_lat;
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

static int run_hillshade(GDALDatasetH src, const ft_io_hillshade_opts *o, const char *dst, GDALDatasetH *out)
{
    char az[32], alt[32], z[32], s[32], band[16];
    snprintf(az, sizeof az, "%.17g", o->azimuth);
    snprintf(alt, sizeof alt, "%.17g", o->altitude);
    snprintf(z, sizeof z, "%.17g", o->z_factor);
    snprintf(s, sizeof s, "%.17g", effective_scale(src, o->scale));
    snprintf(band, sizeof band, "%d", o->band);
    char *argv[] = {"-q", "-of", "GTiff", "-b", band, "-az", az, "-alt", alt, "-z", z, "-s", s, "-compute_edges", NULL};
    return dem_run(src, "hillshade", dst, NULL, argv, out);
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

/* RGBA = colour relief x shade, in a MEM dataset with the DEM's georeferencing. */
static int combine(GDALDatasetH hs, GDALDatasetH cr, GDALDatasetH *out)
{
    int w = GDALGetRasterXSize(hs), h = GDALGetRasterYSize(hs);
    size_t n = (size_t)w * (size_t)h;
    unsigned char *px = ft_malloc(5 * n);
    if (px == NULL)
        return ft_last_error_code();
    int rc = read_band(hs, 1, px + 4 * n, w, h);
    for (int b = 1; b <= 4 && rc == FT_OK; b++)
        rc = read_band(cr, b, px + (size_t)(b - 1) * n, w, h);
    if (rc == FT_OK) {
        for (size_t i = 0; i < n; i++) {
            double f = SHADE_AMBIENT + (1.0 - SHADE_AMBIENT) * px[4 * n + i] / 255.0;
            for (int b = 0; b < 3; b++)
                px[(size_t)b * n + i] = (unsigned char)lround(px[(size_t)b * n + i] * f);
            if (px[4 * n + i] == 0)
                px[3 * n + i] = 0; /* nodata in the hillshade */
        }
        GDALDriverH mem = GDALGetDriverByName("MEM");
        *out = mem ? GDALCreate(mem, "", w, h, 4, GDT_Byte, NULL) : NULL;
        if (*out == NULL)
            rc = ft_io_fail(FT_E_NOMEM, "hillshade: cannot make a %d x %d RGBA image", w, h);
    }
    if (rc == FT_OK) {
        double gt[6];
        if (GDALGetGeoTransform(hs, gt) == CE_None)
            GDALSetGeoTransform(*out, gt);
        GDALSetProjection(*out, GDALGetProjectionRef(hs));
        static const GDALColorInterp ci[] = {GCI_RedBand, GCI_GreenBand, GCI_BlueBand, GCI_AlphaBand};
        for (int b = 0; b < 4; b++)
            GDALSetRasterColorInterpretation(GDALGetRasterBand(*out, b + 1), ci[b]);
        if (GDALDatasetRasterIO(*out, GF_Write, 0, 0, w, h, px, w, h, GDT_Byte, 4, NULL, 0, 0, 0) != CE_None)
            rc = ft_io_fail(FT_E_IO, "hillshade: cannot fill the RGBA image");
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

static int shade_and_write(GDALDatasetH src, const ft_io_hillshade_opts *o, const char *out_path,
                           const vsimem_names *n)
{
    GDALDatasetH hs = NULL, cr = NULL, rgba = NULL;
    int rc = run_hillshade(src, o, n->hs, &hs);
    if (rc == FT_OK && o->color)
        rc = run_color(src, o, n, &cr);
    if (rc == FT_OK && o->color)
        rc = combine(hs, cr, &rgba);
    if (rc == FT_OK)
        rc = write_copy(o->color ? rgba : hs, out_path);
    if (rgba)
        GDALClose(rgba);
    if (cr)
        GDALClose(cr);
    if (hs)
        GDALClose(hs);
    return rc;
}

/* Reads the band through the grid reader first, so that a hillshade is refused where `render` refuses the
 * same DEM: a truncated file (a read error, not a grid of zeros), fewer than 2 x 2 cells, no valid cell, or
 * more cells than the memory bound allows. */
static int check_shadeable(GDALDatasetH src, const char *path, int band)
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
    ft_grid_free(g);
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
    } else if ((rc = check_shadeable(src, dem_path, o->band)) == FT_OK) {
        vsimem_names n;
        names_init(&n);
        rc = shade_and_write(src, o, out_path, &n);
        names_release(&n);
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

/* ---- rows of the hillshade: a stripe plus one row of halo above and below (docs/tiling.md) ---- */

/* Rows [y0, y1) of band `band` of src as an in-memory VRT (GDALTranslate -srcwin): GDAL's DEM processing
 * then sees the window as a raster of its own. */
static int window_vrt(GDALDatasetH src, size_t y0, size_t y1, GDALDatasetH *out)
{
    char yo[32], w[32], h[32];
    snprintf(yo, sizeof yo, "%zu", y0);
    snprintf(w, sizeof w, "%d", GDALGetRasterXSize(src));
    snprintf(h, sizeof h, "%zu", y1 - y0);
    char *argv[] = {"-q", "-of", "VRT", "-srcwin", "0", yo, w, h, NULL};
    ft_io_gdal_reset();
    GDALTranslateOptions *to = GDALTranslateOptionsNew(argv, NULL);
    if (to == NULL)
        return ft_io_fail(FT_E_INVALID, "hillshade: GDAL rejected the window options");
    *out = GDALTranslate("", src, to, NULL);
    GDALTranslateOptionsFree(to);
    return *out != NULL ? FT_OK : ft_io_fail(FT_E_IO, "hillshade: cannot make a window of rows %zu-%zu", y0, y1 - 1);
}

/* The shade of rows [row0, row0 + nrows) of src (rows y0 .. y1 - 1 shaded as a raster of their own). */
static int shade_rows(GDALDatasetH src, const ft_io_hillshade_opts *o, size_t row0, size_t nrows, ft_grid **out)
{
    size_t nx = (size_t)GDALGetRasterXSize(src), ny = (size_t)GDALGetRasterYSize(src);
    size_t y0 = row0 > 0 ? row0 - 1 : 0, y1 = row0 + nrows + 1 < ny ? row0 + nrows + 1 : ny;
    ft_io_hillshade_opts wo = *o;
    wo.scale = effective_scale(src, o->scale); /* the whole DEM's centre, not the window's */
    GDALDatasetH win = NULL, hs = NULL;
    vsimem_names n;
    names_init(&n);
    int rc = window_vrt(src, y0, y1, &win);
    if (rc == FT_OK)
        rc = run_hillshade(win, &wo, n.hs, &hs);
    ft_grid *g = rc == FT_OK ? ft_grid_create(nx, nrows) : NULL;
    if (rc == FT_OK && g == NULL)
        rc = FT_E_NOMEM;
    ft_io_gdal_reset();
    if (rc == FT_OK && GDALRasterIO(GDALGetRasterBand(hs, 1), GF_Read, 0, (int)(row0 - y0), (int)nx, (int)nrows, g->z,
                                    (int)nx, (int)nrows, GDT_Float32, 0, 0) != CE_None)
        rc = ft_io_fail(FT_E_IO, "hillshade: cannot read the shade of rows %zu-%zu", row0, row0 + nrows - 1);
    if (rc == FT_OK) {
        double gt[6] = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
        GDALGetGeoTransform(src, gt);
        memcpy(g->gt, gt, sizeof gt);
        g->gt[0] = gt[0] + (double)row0 * gt[2];
        g->gt[3] = gt[3] + (double)row0 * gt[5];
        g->has_nodata = 1;
        g->nodata_value = 0.0; /* gdaldem's */
        char *wkt = ft_io_srs_to_wkt(GDALGetSpatialRef(src));
        rc = wkt ? ft_grid_set_crs(g, wkt) : FT_OK;
        free(wkt);
    }
    if (hs)
        GDALClose(hs);
    if (win)
        GDALClose(win);
    names_release(&n);
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
    GDALDatasetH src = NULL;
    if ((rc = ft_io_open(dem_path, GDAL_OF_RASTER, &src)) != FT_OK)
        return rc;
    size_t nx = (size_t)GDALGetRasterXSize(src), ny = (size_t)GDALGetRasterYSize(src);
    if (o->band > GDALGetRasterCount(src))
        rc = ft_error(FT_E_FORMAT, "%s has %d band(s), band %d was asked for", dem_path, GDALGetRasterCount(src),
                      o->band);
    else if (nx < 2 || ny < 2)
        rc = ft_error(FT_E_INVALID, "%s has %zu x %zu cells; a hillshade needs at least 2 x 2", dem_path, nx, ny);
    else if (nrows == 0 || row0 >= ny || nrows > ny - row0)
        rc = ft_error(FT_E_INVALID, "hillshade: rows %zu-%zu leave the %zu rows of %s", row0, row0 + nrows - 1, ny,
                      dem_path);
    if (rc == FT_OK) {
        const char *pam = CPLGetThreadLocalConfigOption("GDAL_PAM_ENABLED", NULL);
        char *saved = pam ? CPLStrdup(pam) : NULL;
        CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
        rc = shade_rows(src, o, row0, nrows, out);
        CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", saved);
        CPLFree(saved);
    }
    GDALClose(src);
    return rc;
}

int ft_io_hillshade_rows(const char *dem_path, const ft_io_hillshade_opts *opts, size_t row0, size_t nrows,
                         ft_grid **out)
{
    ft_io_enter();
    return ft_io_leave(hillshade_rows(dem_path, opts, row0, nrows, out));
}
