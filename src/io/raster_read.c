/* fracterra — io/raster_read.c: one raster band into an ft_grid (float cells + nodata mask).
 *
 * Cells are read as Float32 in blocks of whole rows (a multiple of the band's block height), so large
 * rasters stream through GDAL's block cache without per-cell calls. The mask comes from GDAL's mask
 * band whenever it is not "all valid": it compares the nodata value in the band's own type (e.g. Int16
 * -32768) and covers per-dataset masks and alpha bands; NaN and infinite cells are nodata too. A band
 * with a scale or offset is returned in physical units (raw * scale + offset). A grid whose cells are
 * all nodata is read successfully: ft_grid_count_valid() tells the caller.
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

typedef struct {
    const char *path;
    GDALRasterBandH band;
    GDALRasterBandH mask;  /* NULL when GDAL says every cell is valid */
    ft_grid *g;            /* the whole band, or one strip of it (summaries) */
    int row_base;          /* band row held in g's row 0 */
    uint8_t *mbuf;         /* one block of mask rows */
    double scale, offset;
} grid_reader;

static int check_band(GDALDatasetH ds, const char *path, int band)
{
    int count = GDALGetRasterCount(ds);
    if (count == 0) {
        char **sub = GDALGetMetadata(ds, "SUBDATASETS");
        const char *first = CSLFetchNameValue(sub, "SUBDATASET_1_NAME");
        if (first != NULL)
            return ft_error(FT_E_FORMAT, "'%s' has no band of its own; it holds subdatasets such as '%s'", path,
                            first);
        return ft_error(FT_E_FORMAT, "'%s' has no raster band", path);
    }
    if (band < 1 || band > count)
        return ft_error(FT_E_FORMAT, "band %d requested but '%s' has %d band%s", band, path, count,
                        count == 1 ? "" : "s");
    return FT_OK;
}

/* GDAL reads whole blocks, and a pixel-interleaved GeoTIFF one block of every band at once: a small file
 * may declare a block far larger than the band (found by fuzzing: 31,232 bands of 36,352-cell rows, a
 * 2.3 GB buffer for one row), which must be refused, not allocated. */
static int check_block(GDALDatasetH ds, GDALRasterBandH band, const char *path)
{
    int bx = 0, by = 0, nb = GDALGetRasterCount(ds);
    GDALGetBlockSize(band, &bx, &by);
    double bytes = (double)bx * (double)by * GDALGetDataTypeSizeBytes(GDALGetRasterDataType(band)) * (nb > 0 ? nb : 1);
    char what[PATH_MAX + 96];
    snprintf(what, sizeof what, "reading '%s' (one block of %d x %d cells in %d bands)", path, bx, by, nb);
    return ft_check_memory(bytes, what);
}

/* The grid of the dataset's size, georeferencing and CRS; with header_only its cells are one (nx and ny
 * still say the dataset's size), for a caller that keeps only the header. */
static int grid_from_dataset(GDALDatasetH ds, const char *path, int header_only, ft_grid **out)
{
    int nx = GDALGetRasterXSize(ds), ny = GDALGetRasterYSize(ds);
    if (nx <= 0 || ny <= 0)
        return ft_error(FT_E_FORMAT, "'%s' has an empty raster (%d x %d)", path, nx, ny);
    char what[PATH_MAX + 64];
    snprintf(what, sizeof what, "reading '%s' (%d x %d cells)", path, nx, ny);
    /* float elevations and a byte mask per cell (the memory bound, --max-memory, is the one that matters
     * for reading: GDAL reads a cell in nanoseconds, so no work bound applies here) */
    if (!header_only && ft_check_memory((double)nx * (double)ny * (sizeof(float) + 1.0), what) != FT_OK)
        return FT_E_NOMEM;
    ft_grid *g = header_only ? ft_grid_create(1, 1) : ft_grid_create((size_t)nx, (size_t)ny);
    if (g == NULL)
        return FT_E_NOMEM;
    g->nx = (size_t)nx;
    g->ny = (size_t)ny;
    double gt[6];
    if (GDALGetGeoTransform(ds, gt) == CE_None)
        memcpy(g->gt, gt, sizeof gt);
    else
        memcpy(g->gt, (double[6]){0, 1, 0, 0, 0, 1}, sizeof gt);
    char *wkt = ft_io_srs_to_wkt(GDALGetSpatialRef(ds));
    int rc = wkt ? ft_grid_set_crs(g, wkt) : FT_OK;
    free(wkt);
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}

/* Marks cell i invalid, creating the mask on the first invalid cell. */
static int set_invalid(ft_grid *g, size_t i)
{
    if (g->mask == NULL && ft_grid_ensure_mask(g) != FT_OK)
        return FT_E_NOMEM;
    g->mask[i] = 0;
    return FT_OK;
}

/* Reads rows [row0, row0 + rows) of columns [col0, col0 + g->nx) of cells and mask, then masks and scales
 * them. */
static int read_window_rows(grid_reader *r, int col0, int row0, int rows)
{
    ft_grid *g = r->g;
    size_t nx = g->nx, base = (size_t)(row0 - r->row_base) * nx, n = (size_t)rows * nx;
    int inx = (int)nx;
    ft_io_gdal_reset();
    if (GDALRasterIO(r->band, GF_Read, col0, row0, inx, rows, g->z + base, inx, rows, GDT_Float32, 0, 0) != CE_None)
        return ft_io_fail(FT_E_IO, "cannot read rows %d-%d of '%s'", row0, row0 + rows - 1, r->path);
    if (r->mask != NULL &&
        GDALRasterIO(r->mask, GF_Read, col0, row0, inx, rows, r->mbuf, inx, rows, GDT_Byte, 0, 0) != CE_None)
        return ft_io_fail(FT_E_IO, "cannot read the mask of rows %d-%d of '%s'", row0, row0 + rows - 1, r->path);
    int scaled = r->scale != 1.0 || r->offset != 0.0;
    for (size_t k = 0; k < n; k++) {
        float *z = &g->z[base + k];
        if ((r->mask != NULL && r->mbuf[k] == 0) || !isfinite(*z)) {
            if (set_invalid(g, base + k) != FT_OK)
                return FT_E_NOMEM;
        } else if (scaled) {
            *z = (float)(*z * r->scale + r->offset);
        }
    }
    return FT_OK;
}

static int read_rows(grid_reader *r, int row0, int rows)
{
    return read_window_rows(r, 0, row0, rows);
}

/* Rows per read: whole blocks, about `cells` cells at a time. */
static int rows_per_chunk(GDALRasterBandH band, size_t nx, size_t cells)
{
    int bx, by;
    GDALGetBlockSize(band, &bx, &by);
    if (by < 1)
        by = 1;
    size_t want = cells / (nx ? nx : 1);
    size_t blocks = want / (size_t)by;
    if (blocks < 1)
        blocks = 1;
    size_t rows = blocks * (size_t)by;
    return rows > INT_MAX ? INT_MAX : (int)rows;
}

/* The band's nodata value, scale and offset into g and r. */
static void band_header(grid_reader *r)
{
    ft_grid *g = r->g;
    int flags = GDALGetMaskFlags(r->band);
    r->mask = (flags & GMF_ALL_VALID) ? NULL : GDALGetMaskBand(r->band);
    int ok = 0;
    double v = GDALGetRasterNoDataValue(r->band, &ok);
    g->has_nodata = ok != 0;
    g->nodata_value = ok ? v : 0.0;
    r->scale = GDALGetRasterScale(r->band, &ok);
    if (!ok || r->scale == 0.0)
        r->scale = 1.0;
    r->offset = GDALGetRasterOffset(r->band, &ok);
    if (!ok)
        r->offset = 0.0;
}

static int read_band(grid_reader *r)
{
    ft_grid *g = r->g;
    band_header(r);
    int chunk = rows_per_chunk(r->band, g->nx, (size_t)1 << 22), ny = (int)g->ny;
    if (r->mask != NULL && (r->mbuf = ft_malloc((size_t)chunk * g->nx)) == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (int row = 0; rc == FT_OK && row < ny; row += chunk)
        rc = read_rows(r, row, row + chunk <= ny ? chunk : ny - row);
    return rc;
}

static int read_grid(const char *path, const ft_read_grid_opts *opts, ft_grid **out)
{
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_read_grid_opts) != FT_OK)
        return FT_E_INVALID;
    *out = NULL;
    GDALDatasetH ds;
    int rc = ft_io_open(path, GDAL_OF_RASTER, &ds);
    if (rc != FT_OK)
        return rc;
    rc = ft_io_read_grid_ds(ds, path, &o, out);
    GDALClose(ds);
    return rc;
}

int ft_io_read_grid(const char *path, const ft_read_grid_opts *opts, ft_grid **out)
{
    ft_io_enter();
    return ft_io_leave(read_grid(path, opts, out));
}

int ft_io_read_grid_ds(GDALDatasetH ds, const char *path, const ft_read_grid_opts *opts, ft_grid **out)
{
    ft_read_grid_opts o = *opts;
    *out = NULL;
    grid_reader r = {.path = path};
    int rc = check_band(ds, path, o.band);
    if (rc == FT_OK)
        rc = grid_from_dataset(ds, path, 0, &r.g);
    if (rc == FT_OK) {
        r.band = GDALGetRasterBand(ds, o.band);
        rc = check_block(ds, r.band, path);
    }
    if (rc == FT_OK)
        rc = read_band(&r);
    free(r.mbuf);
    if (rc != FT_OK) {
        ft_grid_free(r.g);
        return rc;
    }
    *out = r.g;
    return FT_OK;
}

/* ---- summaries: the band strip by strip (about 1 M cells, whole blocks) through one strip-sized grid ---- */

/* Adds the valid cells of the strip's first `rows` rows to s. */
static void add_strip(ft_grid *strip, size_t rows, ft_grid_summary *s)
{
    size_t full = strip->ny;
    strip->ny = rows;
    s->valid += ft_grid_count_valid(strip);
    double lo, hi;
    if (ft_grid_minmax(strip, &lo, &hi) == FT_OK) {
        s->zmin = lo < s->zmin ? lo : s->zmin;
        s->zmax = hi > s->zmax ? hi : s->zmax;
    }
    strip->ny = full;
    if (strip->mask != NULL)
        memset(strip->mask, 1, strip->nx * strip->ny);
}

static int summarize_band(grid_reader *r, const ft_grid *header, ft_grid_summary *s)
{
    int ny = (int)header->ny;
    int chunk = rows_per_chunk(r->band, header->nx, (size_t)1 << 20);
    if (chunk > ny)
        chunk = ny;
    r->g = ft_grid_create(header->nx, (size_t)chunk);
    if (r->g == NULL)
        return FT_E_NOMEM;
    band_header(r);
    s->header.has_nodata = r->g->has_nodata;
    s->header.nodata_value = r->g->nodata_value;
    if (r->mask != NULL && (r->mbuf = ft_malloc((size_t)chunk * header->nx)) == NULL)
        return FT_E_NOMEM;
    s->valid = 0;
    s->zmin = INFINITY;
    s->zmax = -INFINITY;
    int rc = FT_OK;
    for (int row = 0; rc == FT_OK && row < ny; row += chunk) {
        int rows = row + chunk <= ny ? chunk : ny - row;
        r->row_base = row;
        rc = read_rows(r, row, rows);
        if (rc == FT_OK)
            add_strip(r->g, (size_t)rows, s);
        /* the strip's blocks are not needed again: GDAL's cache keeps no more than one strip */
        GDALFlushRasterCache(r->band);
        if (r->mask != NULL)
            GDALFlushRasterCache(r->mask);
    }
    if (s->valid == 0)
        s->zmin = s->zmax = NAN;
    return rc;
}

int ft_io_summarize_grid_ds(GDALDatasetH ds, const char *path, const ft_read_grid_opts *opts,
                            ft_grid_summary *out)
{
    memset(out, 0, sizeof *out);
    ft_grid *header = NULL;
    grid_reader r = {.path = path};
    int rc = check_band(ds, path, opts->band);
    if (rc == FT_OK)
        rc = grid_from_dataset(ds, path, 1, &header);
    if (rc == FT_OK) {
        out->header = *header;
        out->header.z = NULL;
        out->header.mask = NULL;
        header->crs_wkt = NULL; /* now the summary's */
        r.band = GDALGetRasterBand(ds, opts->band);
        rc = summarize_band(&r, header, out);
    }
    ft_grid_free(header);
    ft_grid_free(r.g);
    free(r.mbuf);
    if (rc != FT_OK)
        ft_grid_summary_clear(out);
    return rc;
}

static int summarize_grid(const char *path, const ft_read_grid_opts *opts, ft_grid_summary *out)
{
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_read_grid_opts) != FT_OK)
        return FT_E_INVALID;
    memset(out, 0, sizeof *out);
    GDALDatasetH ds;
    int rc = ft_io_open(path, GDAL_OF_RASTER, &ds);
    if (rc != FT_OK)
        return rc;
    rc = ft_io_summarize_grid_ds(ds, path, &o, out);
    GDALClose(ds);
    return rc;
}

int ft_io_summarize_grid(const char *path, const ft_read_grid_opts *opts, ft_grid_summary *out)
{
    ft_io_enter();
    return ft_io_leave(summarize_grid(path, opts, out));
}

void ft_grid_summary_clear(ft_grid_summary *s)
{
    if (s == NULL)
        return;
    free(s->header.crs_wkt);
    memset(s, 0, sizeof *s);
}

/* ---- windows: a band read piece by piece (a stripe or block plus its halo) in bounded memory ---- */

struct ft_grid_reader {
    char *path;
    GDALDatasetH ds;
    grid_reader r;  /* band, mask, scale and offset; r.g is the window being read */
    ft_grid *header; /* size, georeferencing, CRS and nodata of the band; one cell */
};

static void grid_reader_close(ft_grid_reader *gr)
{
    if (gr == NULL)
        return;
    if (gr->ds != NULL)
        GDALClose(gr->ds);
    ft_grid_free(gr->header);
    free(gr->path);
    free(gr);
}

static int grid_reader_open(const char *path, const ft_read_grid_opts *opts, ft_grid_reader **out)
{
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_read_grid_opts) != FT_OK)
        return FT_E_INVALID;
    if (out == NULL)
        return ft_error(FT_E_INVALID, "grid reader: output pointer is NULL");
    *out = NULL;
    ft_grid_reader *gr = ft_calloc(1, sizeof *gr);
    if (gr == NULL || (gr->path = ft_strdup(path ? path : "")) == NULL) {
        free(gr);
        return FT_E_NOMEM;
    }
    int rc = ft_io_open(path, GDAL_OF_RASTER, &gr->ds);
    if (rc == FT_OK)
        rc = check_band(gr->ds, path, o.band);
    if (rc == FT_OK)
        rc = grid_from_dataset(gr->ds, path, 1, &gr->header);
    if (rc == FT_OK) {
        gr->r.path = gr->path;
        gr->r.band = GDALGetRasterBand(gr->ds, o.band);
        rc = check_block(gr->ds, gr->r.band, path);
    }
    if (rc == FT_OK) {
        gr->r.g = gr->header;
        band_header(&gr->r);
        gr->r.g = NULL;
        free(gr->header->z);
        gr->header->z = NULL;
    }
    if (rc != FT_OK) {
        grid_reader_close(gr);
        return rc;
    }
    *out = gr;
    return FT_OK;
}

const ft_grid *ft_io_grid_reader_header(const ft_grid_reader *gr)
{
    return gr ? gr->header : NULL;
}

void ft_io_grid_reader_block(const ft_grid_reader *gr, size_t *bx, size_t *by)
{
    int x = 1, y = 1;
    if (gr != NULL)
        GDALGetBlockSize(gr->r.band, &x, &y);
    if (bx != NULL)
        *bx = x > 0 ? (size_t)x : 1;
    if (by != NULL)
        *by = y > 0 ? (size_t)y : 1;
}

static int grid_reader_read(ft_grid_reader *gr, size_t col0, size_t row0, size_t ncols, size_t nrows, ft_grid **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "grid reader: output pointer is NULL");
    *out = NULL;
    if (gr == NULL)
        return ft_error(FT_E_INVALID, "grid reader is NULL");
    const ft_grid *h = gr->header;
    if (ncols == 0 || nrows == 0 || col0 >= h->nx || row0 >= h->ny || ncols > h->nx - col0 || nrows > h->ny - row0)
        return ft_error(FT_E_INVALID, "window of %zu x %zu cells at column %zu, row %zu leaves the %zu x %zu band of "
                        "'%s'", ncols, nrows, col0, row0, h->nx, h->ny, gr->path);
    char what[PATH_MAX + 96];
    snprintf(what, sizeof what, "reading a %zu x %zu window of '%s'", ncols, nrows, gr->path);
    if (ft_check_memory((double)ncols * (double)nrows * (sizeof(float) + 2.0), what) != FT_OK)
        return FT_E_NOMEM;
    ft_grid *g = ft_grid_create(ncols, nrows);
    if (g == NULL)
        return FT_E_NOMEM;
    memcpy(g->gt, h->gt, sizeof g->gt);
    g->gt[0] = h->gt[0] + (double)col0 * h->gt[1] + (double)row0 * h->gt[2];
    g->gt[3] = h->gt[3] + (double)col0 * h->gt[4] + (double)row0 * h->gt[5];
    g->has_nodata = h->has_nodata;
    g->nodata_value = h->nodata_value;
    int rc = ft_grid_set_crs(g, h->crs_wkt);
    grid_reader *r = &gr->r;
    r->g = g;
    r->row_base = (int)row0;
    if (rc == FT_OK && r->mask != NULL && (r->mbuf = ft_malloc(ncols * nrows)) == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = read_window_rows(r, (int)col0, (int)row0, (int)nrows);
    /* the window's blocks are not kept: GDAL's cache holds no more than the window being read */
    GDALFlushRasterCache(r->band);
    if (r->mask != NULL)
        GDALFlushRasterCache(r->mask);
    free(r->mbuf);
    r->mbuf = NULL;
    r->g = NULL;
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}

/* ---- public entry points: GDAL's messages kept by the module's handler (ft_io_enter) ---- */

int ft_io_grid_reader_open(const char *path, const ft_read_grid_opts *opts, ft_grid_reader **out)
{
    ft_io_enter();
    return ft_io_leave(grid_reader_open(path, opts, out));
}

int ft_io_grid_reader_read(ft_grid_reader *gr, size_t col0, size_t row0, size_t ncols, size_t nrows, ft_grid **out)
{
    ft_io_enter();
    return ft_io_leave(grid_reader_read(gr, col0, row0, ncols, nrows, out));
}

void ft_io_grid_reader_close(ft_grid_reader *gr)
{
    ft_io_enter();
    grid_reader_close(gr);
    ft_io_leave(FT_OK);
}
