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
#include <omp.h>
#include <pthread.h>

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

/* gdaldem's Byte value of the engine's shade s in [0, 255]: 1 + 254 s / 255 rounded (the argument is
 * positive, so the truncation is the floor); 0 (nodata) where valid is 0 (the engine's nodata shade is
 * -9999: the product stays in int). Without a branch, so that a row of them is vectorised. */
static inline unsigned char shade_byte(float s, uint8_t valid)
{
    return (unsigned char)((int)(1.0 + 254.0 * (double)s / 255.0 + 0.5) * (int)valid);
}

/* The engine's shade of dem with the options of o at the given scale (as gdaldem's Byte values when bytes is
 * set: then in a float grid whose nodata value is 0). */
static int shade_engine(const ft_grid *dem, const ft_io_hillshade_opts *o, double scale, int bytes, ft_grid **out)
{
    ft_hillshade_opts ro = FT_HILLSHADE_OPTS_DEFAULT;
    ro.azimuth = o->azimuth;
    ro.altitude = o->altitude;
    ro.z_factor = o->z_factor;
    ro.scale = scale;
    int rc = ft_render_hillshade(dem, &ro, out);
    if (rc != FT_OK || !bytes)
        return rc;
    ft_grid *g = *out;
    for (size_t k = 0; k < g->nx * g->ny; k++)
        g->z[k] = (float)shade_byte(g->z[k], g->mask[k]);
    g->nodata_value = 0.0;
    return FT_OK;
}

/* ---- the whole DEM streamed: chunks of whole blocks of rows, each shaded with the two rows above it ---- */

/* Receives rows [row0, row0 + nrows) of the shade as gdaldem's bytes. */
typedef int (*shade_sink)(void *ctx, size_t row0, size_t nrows, const unsigned char *px);

/* Bytes per cell of a streamed row: the window being shaded (z and mask: 5), the engine's shade of it (5), the
 * next chunk as read (z, mask and the reader's mask buffer: 6; GDAL's decoded cells: 4), the byte row (1) and
 * the output's cache (1). A window holds its chunk's rows and the two above them. */
#define STREAM_BYTES_PER_CELL 22.0

static double chunk_bytes(size_t nx, size_t rows)
{
    return STREAM_BYTES_PER_CELL * (double)nx * (double)(rows + 2);
}

/* Rows per read (*rows): whole blocks of the band, about 1 M cells, as many as the memory bound leaves beside
 * `held` bytes (the whole image, when one is kept); fewer rows than a block when no block fits, never fewer
 * than 2 (the engine's smallest grid). A DEM whose 2-row chunk does not fit is refused, naming --max-memory. */
static int chunk_rows(ft_grid_reader *r, const char *path, double held, size_t *rows)
{
    const ft_grid *h = ft_io_grid_reader_header(r);
    size_t nx = h->nx, ny = h->ny, by = 1, want = ((size_t)1 << 20) / nx;
    char what[PATH_MAX + 96];
    snprintf(what, sizeof what, "shading '%s' (%zu x %zu cells) in chunks of 2 rows", path, nx, ny);
    if (ft_check_memory(held + chunk_bytes(nx, 2), what) != FT_OK)
        return FT_E_NOMEM;
    ft_io_grid_reader_block(r, NULL, &by);
    by = by > 0 ? by : 1;
    double fit = ((double)ft_memory_limit() - held) / (STREAM_BYTES_PER_CELL * (double)nx) - 2.0;
    size_t cap = fit >= (double)ny ? ny : (size_t)fit; /* >= 2: checked above */
    size_t n = (want / by > 0 ? want / by : 1) * by;
    if (n > cap)
        n = cap >= by ? cap / by * by : cap;
    n = n < 2 ? 2 : n;
    *rows = n < ny ? n : ny;
    return FT_OK;
}

/* Appends the chunk c (rows of the band, nx wide) to the window win, which holds `held` rows and has room
 * for `cap`; the window gets a mask (all valid so far) on the first chunk that has one. */
static int window_append(ft_grid *win, size_t held, size_t cap, const ft_grid *c)
{
    size_t nx = win->nx, n = nx * c->ny;
    if (c->mask != NULL && win->mask == NULL) {
        win->ny = cap;
        if (ft_grid_ensure_mask(win) != FT_OK)
            return FT_E_NOMEM;
    }
    memcpy(win->z + held * nx, c->z, n * sizeof *c->z);
    if (win->mask != NULL) {
        if (c->mask != NULL)
            memcpy(win->mask + held * nx, c->mask, n);
        else
            memset(win->mask + held * nx, 1, n);
    }
    win->ny = held + c->ny;
    return FT_OK;
}

/* Keeps the window's last two rows (the next chunk's rows above) at its start. */
static size_t window_keep_two(ft_grid *win)
{
    size_t nx = win->nx, keep = win->ny < 2 ? win->ny : 2, from = (win->ny - keep) * nx;
    memmove(win->z, win->z + from, keep * nx * sizeof *win->z);
    if (win->mask != NULL)
        memmove(win->mask, win->mask + from, keep * nx);
    return keep;
}

/* Shades the window win, whose row 0 is band row p, and hands rows [first, last) of the band to the sink. */
static int shade_window_rows(const ft_grid *win, size_t p, size_t first, size_t last, const ft_io_hillshade_opts *o,
                             double scale, unsigned char *px, shade_sink sink, void *ctx)
{
    ft_grid *sh = NULL;
    int rc = shade_engine(win, o, scale, 0, &sh);
    if (rc != FT_OK)
        return rc;
    size_t nx = win->nx, n = (last - first) * nx;
    const float *restrict z = sh->z + (first - p) * nx;
    const uint8_t *restrict valid = sh->mask + (first - p) * nx;
    unsigned char *restrict out = px;
    for (size_t k = 0; k < n; k++)
        out[k] = shade_byte(z[k], valid[k]);
    ft_grid_free(sh);
    return sink(ctx, first, last - first, px);
}

/* Reads rows [a, b) of the band of r into *c (none when a == b) and counts their valid cells into *valid. */
static int read_chunk(ft_grid_reader *r, size_t a, size_t b, ft_grid **c, size_t *valid)
{
    *c = NULL;
    if (a >= b)
        return FT_OK;
    int rc = ft_io_grid_reader_read(r, 0, a, ft_io_grid_reader_header(r)->nx, b - a, c);
    if (rc == FT_OK)
        *valid += ft_grid_count_valid(*c);
    return rc;
}

/* One window to shade and hand to the sink, on a thread of its own: its result and message (ft_error's and
 * GDAL's are per thread) come back here. */
typedef struct {
    const ft_grid *win;
    size_t p, first, last;
    const ft_io_hillshade_opts *o;
    double scale;
    unsigned char *px;
    shade_sink sink;
    void *ctx;
    int rc;
    char msg[1024];
} shade_step;

static void *shade_step_run(void *arg)
{
    shade_step *s = arg;
    ft_io_enter(); /* GDAL's messages of the sink's writes, caught as on the caller's thread */
    s->rc = s->last > s->first ? shade_window_rows(s->win, s->p, s->first, s->last, s->o, s->scale, s->px, s->sink,
                                                   s->ctx)
                               : FT_OK;
    if (s->rc != FT_OK)
        snprintf(s->msg, sizeof s->msg, "%s", ft_last_error());
    ft_io_leave(FT_OK);
    return NULL;
}

/* The shade of the band of r, chunk by chunk of whole blocks (so that no block is decoded twice): each chunk
 * is shaded in a window with the two rows above it, and the rows whose 3 x 3 window is complete (the last
 * row waits for the next chunk) go to the sink; the window's first and last rows are the band's edges only
 * where they are, so every cell is the whole-DEM engine's. With more than one OpenMP thread allowed the
 * steps overlap: this thread reads and decodes the next chunk while a second one (joined, not spinning)
 * shades the window and hands it to the sink. chunk: rows per read (chunk_rows); *valid: the band's valid
 * cells. */
static int stream_shade(ft_grid_reader *r, const ft_io_hillshade_opts *o, double scale, size_t chunk, shade_sink sink,
                        void *ctx, size_t *valid)
{
    const ft_grid *h = ft_io_grid_reader_header(r);
    size_t nx = h->nx, ny = h->ny, cap = chunk + 2;
    ft_grid *win = ft_grid_create(nx, cap), *next = NULL;
    unsigned char *px = ft_malloc(nx * (chunk + 1));
    int rc = win != NULL && px != NULL ? FT_OK : FT_E_NOMEM, overlap = omp_get_max_threads() > 1;
    *valid = 0;
    if (rc == FT_OK) {
        memcpy(win->gt, h->gt, sizeof win->gt);
        win->ny = 0;
        rc = read_chunk(r, 0, chunk, &next, valid);
    }
    for (size_t a = 0; rc == FT_OK && a < ny; a += chunk) {
        size_t b = a + chunk < ny ? a + chunk : ny, nb = b + chunk < ny ? b + chunk : ny;
        size_t held = window_keep_two(win);
        rc = window_append(win, held, cap, next);
        ft_grid_free(next);
        next = NULL;
        if (rc != FT_OK)
            break;
        shade_step st = {.win = win, .p = a - held, .first = a > 0 ? a - 1 : 0, .last = b < ny ? b - 1 : ny,
                         .o = o, .scale = scale, .px = px, .sink = sink, .ctx = ctx};
        pthread_t th;
        int threaded = overlap && pthread_create(&th, NULL, shade_step_run, &st) == 0;
        int read_rc = read_chunk(r, b, nb, &next, valid);
        if (threaded)
            pthread_join(th, NULL);
        else
            shade_step_run(&st);
        rc = st.rc != FT_OK ? ft_error(st.rc, "%s", st.msg) : read_rc;
    }
    ft_grid_free(next);
    if (win != NULL)
        win->ny = cap;
    ft_grid_free(win);
    free(px);
    return rc;
}

/* Sink: the rows into a whole-DEM byte image. */
typedef struct {
    unsigned char *px;
    size_t nx;
} image_sink;

static int sink_image(void *ctx, size_t row0, size_t nrows, const unsigned char *px)
{
    image_sink *s = ctx;
    memcpy(s->px + row0 * s->nx, px, nrows * s->nx);
    return FT_OK;
}

/* Sink: the rows written to band 1 of a dataset being created, its blocks flushed at once (GDAL's cache
 * holds no more than a chunk of the output). */
typedef struct {
    GDALRasterBandH band;
    const char *path;
    size_t nx;
} dataset_sink;

static int sink_dataset(void *ctx, size_t row0, size_t nrows, const unsigned char *px)
{
    dataset_sink *s = ctx;
    ft_io_gdal_reset();
    if (GDALRasterIO(s->band, GF_Write, 0, (int)row0, (int)s->nx, (int)nrows, (void *)px, (int)s->nx, (int)nrows,
                     GDT_Byte, 0, 0) != CE_None ||
        GDALFlushRasterCache(s->band) != CE_None || ft_io_gdal_failed())
        return ft_io_fail(FT_E_IO, "cannot write rows %zu-%zu of %s", row0, row0 + nrows - 1, s->path);
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

/* The georeferencing of src on ds. */
static void set_georef(GDALDatasetH ds, GDALDatasetH src)
{
    double gt[6];
    if (GDALGetGeoTransform(src, gt) == CE_None)
        GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, GDALGetProjectionRef(src));
}

/* A MEM Byte dataset of `bands` bands (1: the shade, 0 = nodata; 4: RGBA) holding px band after band, with
 * the georeferencing of src. */
static int byte_image(GDALDatasetH src, int w, int h, int bands, unsigned char *px, GDALDatasetH *out)
{
    GDALDriverH mem = GDALGetDriverByName("MEM");
    *out = mem ? GDALCreate(mem, "", w, h, bands, GDT_Byte, NULL) : NULL;
    if (*out == NULL)
        return ft_io_fail(FT_E_NOMEM, "hillshade: cannot make a %d x %d image", w, h);
    set_georef(*out, src);
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

/* Refuses what `render` refuses of the same DEM (reader r of path): fewer than 2 x 2 cells, more cells than
 * the work bound allows; the image bytes held (`bytes` per cell) beyond the memory bound. A truncated file
 * fails when its rows are read, a DEM without a valid cell once it has been read. */
static int check_shadeable(ft_grid_reader *r, const char *path, double bytes)
{
    const ft_grid *g = ft_io_grid_reader_header(r);
    if (g->nx < 2 || g->ny < 2)
        return ft_error(FT_E_INVALID, "%s has %zu x %zu cells; a hillshade needs at least 2 x 2", path, g->nx,
                        g->ny);
    char what[PATH_MAX + 64];
    snprintf(what, sizeof what, "shading '%s' (%zu x %zu cells)", path, g->nx, g->ny);
    double cells = (double)g->nx * (double)g->ny;
    if (ft_check_work(4.0 * cells, what) != FT_OK) /* read, slope, shade, encode */
        return FT_E_NOMEM;
    return bytes > 0.0 ? ft_check_memory(bytes * cells, what) : FT_OK;
}

static int no_valid_cell(const char *path, const ft_grid *h)
{
    return ft_error(FT_E_EMPTY, "%s has no valid cell (all %zu are nodata): nothing to shade", path, h->nx * h->ny);
}

/* The shade streamed into a Byte dataset created by drv (which can Create) at out_path: no more than a chunk
 * of the DEM and of the shade in memory, as gdaldem, which works row by row. */
static int shade_streamed(GDALDatasetH src, ft_grid_reader *r, const char *dem_path, const ft_io_hillshade_opts *o,
                          size_t chunk, GDALDriverH drv, const char *out_path)
{
    const ft_grid *h = ft_io_grid_reader_header(r);
    /* The output staged in /vsimem (1 byte a cell) counts against the memory bound: beside the chunk beyond
     * it, a GeoTIFF is written straight to its temporary file (ft_io_stage_begin's rule for large ones). */
    double out_bytes = (double)h->nx * (double)h->ny;
    int direct = out_bytes + chunk_bytes(h->nx, chunk) > (double)ft_memory_limit();
    ft_io_stage st;
    int rc = ft_io_stage_begin(out_path, drv, direct ? INFINITY : out_bytes, &st);
    if (rc != FT_OK)
        return rc;
    ft_io_gdal_reset();
    GDALDatasetH ds = GDALCreate(drv, st.target, (int)h->nx, (int)h->ny, 1, GDT_Byte, NULL);
    size_t valid = 0;
    if (ds == NULL) {
        rc = ft_io_fail(FT_E_IO, "cannot create %s", out_path);
    } else {
        set_georef(ds, src);
        GDALSetRasterNoDataValue(GDALGetRasterBand(ds, 1), 0.0);
        dataset_sink sink = {GDALGetRasterBand(ds, 1), out_path, h->nx};
        rc = stream_shade(r, o, effective_scale(h, o->scale), chunk, sink_dataset, &sink, &valid);
        ft_io_gdal_reset();
        GDALClose(ds);
        if (rc == FT_OK && ft_io_gdal_failed())
            rc = ft_io_fail(FT_E_IO, "cannot write %s", out_path);
    }
    if (rc == FT_OK && valid == 0)
        rc = no_valid_cell(dem_path, h);
    int end = ft_io_stage_end(&st, rc == FT_OK);
    return rc == FT_OK ? end : rc;
}

/* The shade as one image (for a driver that can only CreateCopy, and for the colour relief, which needs
 * the whole DEM's range), times the colour relief with o->color, written to out_path. */
static int shade_whole(GDALDatasetH src, ft_grid_reader *r, const char *dem_path, const ft_io_hillshade_opts *o,
                       size_t chunk, const char *out_path, const vsimem_names *n)
{
    const ft_grid *h = ft_io_grid_reader_header(r);
    size_t nx = h->nx, ny = h->ny, valid = 0;
    image_sink sink = {ft_malloc(nx * ny), nx};
    if (sink.px == NULL)
        return ft_last_error_code();
    int rc = stream_shade(r, o, effective_scale(h, o->scale), chunk, sink_image, &sink, &valid);
    if (rc == FT_OK && valid == 0)
        rc = no_valid_cell(dem_path, h);
    GDALDatasetH cr = NULL, img = NULL;
    if (rc == FT_OK && o->color)
        rc = run_color(src, o, n, &cr);
    if (rc == FT_OK)
        rc = o->color ? combine(src, sink.px, cr, &img) : byte_image(src, (int)nx, (int)ny, 1, sink.px, &img);
    if (rc == FT_OK)
        rc = write_copy(img, out_path);
    if (img)
        GDALClose(img);
    if (cr)
        GDALClose(cr);
    free(sink.px);
    return rc;
}

/* Streams the shade into a driver that can Create; else one image (the shade, the MEM copy, and with
 * colour the relief's and the product's RGBA) is held and copied. */
static int shade_file(GDALDatasetH src, ft_grid_reader *r, const char *dem_path, const char *out_path,
                      const ft_io_hillshade_opts *o)
{
    GDALDriverH drv = NULL;
    int rc = ft_io_find_driver(out_path, NULL, GDAL_DCAP_RASTER, &drv);
    if (rc != FT_OK)
        return rc;
    int stream = !o->color && GDALGetMetadataItem(drv, GDAL_DCAP_CREATE, NULL) != NULL;
    double per_cell = stream ? 0.0 : o->color ? 10.0 : 2.0; /* the image held whole */
    const ft_grid *h = ft_io_grid_reader_header(r);
    size_t chunk = 0;
    if ((rc = check_shadeable(r, dem_path, per_cell)) != FT_OK ||
        (rc = chunk_rows(r, dem_path, per_cell * (double)h->nx * (double)h->ny, &chunk)) != FT_OK)
        return rc;
    if (stream)
        return shade_streamed(src, r, dem_path, o, chunk, drv, out_path);
    vsimem_names n;
    names_init(&n);
    rc = shade_whole(src, r, dem_path, o, chunk, out_path, &n);
    names_release(&n);
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
        ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
        go.band = o->band;
        ft_grid_reader *r = NULL;
        if ((rc = ft_io_grid_reader_open(dem_path, &go, &r)) == FT_OK)
            rc = shade_file(src, r, dem_path, out_path, o);
        ft_io_grid_reader_close(r);
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
        rc = shade_engine(win, o, effective_scale(h, o->scale), 1, &sh);
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
