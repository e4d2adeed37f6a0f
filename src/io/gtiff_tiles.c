/* fracterra — io/gtiff_tiles.c: the tiles of a one-band Float32 GeoTIFF compressed on fracterra's threads.
 *
 * GDAL writes the file's header (size, tiling, ZSTD + floating-point predictor tags, georeferencing,
 * nodata) with no tile in it (SPARSE_OK: every tile offset 0); libtiff then opens that file for update,
 * the tiles are predicted and ZSTD-compressed on the OpenMP threads, appended in their order with
 * TIFFWriteRawTile as they finish, and libtiff rewrites the tile offset and byte-count arrays in place on
 * flush (the directory stays where GDAL put it). The bytes of a tile are those libtiff's
 * encoder would produce before ZSTD: the floating-point predictor of Adobe's TIFF Technical Note 3
 * (Ritter, 2005; libtiff's fpDiff) turns each row of w floats into 4 planes of w bytes, most significant
 * byte first, then replaces every byte of the row but the first by its difference with the previous one
 * (mod 256). The partial tiles at the right and bottom edges are padded with their last column and row.
 * The cells written are the grid's, invalid ones as the nodata value, as GDAL's path writes them; any
 * reader of ZSTD GeoTIFFs (GDAL, libtiff) decodes the same floats.
 *
 * This replaces GDAL's block cache, its copy of the rows and its compression at GDALClose (one thread
 * writing while the others compress): 2048² cells written in ~0.6x the time and CPU (docs/bench.md).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tiffio.h>
#include <zstd.h>

#include "internal.h"
#include "io/io_internal.h"

/* ---- libtiff on a file descriptor whose failures keep errno ------------------------------------ */

typedef struct {
    int fd;
    int err;       /* first errno of a failed read/write/seek/close */
    char msg[256]; /* libtiff's last error message */
} tiff_file;

static tmsize_t file_io(thandle_t h, void *buf, tmsize_t n, int writing)
{
    tiff_file *f = (tiff_file *)h;
    unsigned char *p = buf;
    tmsize_t done = 0;
    while (done < n) {
        size_t want = (size_t)(n - done) > (size_t)INT_MAX ? (size_t)INT_MAX : (size_t)(n - done);
        ssize_t r = writing ? write(f->fd, p + done, want) : read(f->fd, p + done, want);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0 || (r == 0 && writing)) {
            if (f->err == 0)
                f->err = r < 0 ? errno : EIO;
            return -1;
        }
        if (r == 0)
            break;
        done += r;
    }
    return done;
}

static tmsize_t file_read(thandle_t h, void *buf, tmsize_t n)
{
    return file_io(h, buf, n, 0);
}

static tmsize_t file_write(thandle_t h, void *buf, tmsize_t n)
{
    return file_io(h, buf, n, 1);
}

static toff_t file_seek(thandle_t h, toff_t off, int whence)
{
    tiff_file *f = (tiff_file *)h;
    off_t r = lseek(f->fd, (off_t)off, whence);
    if (r < 0 && f->err == 0)
        f->err = errno;
    return r < 0 ? (toff_t)-1 : (toff_t)r;
}

static int file_close(thandle_t h)
{
    (void)h; /* the descriptor is closed by its opener, which checks close() */
    return 0;
}

static toff_t file_size(thandle_t h)
{
    struct stat st;
    return fstat(((tiff_file *)h)->fd, &st) == 0 ? (toff_t)st.st_size : 0;
}

static int file_map(thandle_t h, void **base, toff_t *size)
{
    (void)h;
    (void)base;
    (void)size;
    return 0; /* no mapping: reads go through file_read */
}

static void file_unmap(thandle_t h, void *base, toff_t size)
{
    (void)h;
    (void)base;
    (void)size;
}

#if TIFFLIB_VERSION >= 20221213 /* libtiff 4.5: handlers per TIFF, the process-wide ones left alone */
static int keep_error(TIFF *tif, void *user, const char *module, const char *fmt, va_list ap)
{
    (void)tif;
    (void)module;
    tiff_file *f = user;
    vsnprintf(f->msg, sizeof f->msg, fmt, ap);
    return 1;
}

static int drop_warning(TIFF *tif, void *user, const char *module, const char *fmt, va_list ap)
{
    (void)tif;
    (void)user;
    (void)module;
    (void)fmt;
    (void)ap;
    return 1;
}
#endif

static TIFF *open_update(const char *name, tiff_file *f)
{
#if TIFFLIB_VERSION >= 20221213
    TIFFOpenOptions *oo = TIFFOpenOptionsAlloc();
    if (oo == NULL)
        return NULL;
    TIFFOpenOptionsSetErrorHandlerExtR(oo, keep_error, f);
    TIFFOpenOptionsSetWarningHandlerExtR(oo, drop_warning, f);
    TIFF *tif = TIFFClientOpenExt(name, "r+", (thandle_t)f, file_read, file_write, file_seek, file_close, file_size,
                                  file_map, file_unmap, oo);
    TIFFOpenOptionsFree(oo);
    return tif;
#else
    return TIFFClientOpen(name, "r+", (thandle_t)f, file_read, file_write, file_seek, file_close, file_size,
                          file_map, file_unmap);
#endif
}

/* ---- the layout GDAL wrote ----------------------------------------------------------------------- */

typedef struct {
    uint32_t tw, th;       /* tile size */
    uint32_t ntx, nty;     /* tiles across, down */
} tile_layout;

/* 1 when the file is the one-band tiled Float32 ZSTD + predictor 3 image of nx x ny cells this writer makes. */
static int layout_of(TIFF *tif, size_t nx, size_t ny, tile_layout *l)
{
    uint32_t w = 0, h = 0;
    uint16_t comp = 0, pred = 0, bps = 0, spp = 0, fmt = 0;
    if (!TIFFIsTiled(tif) || !TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &w) || !TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &h) ||
        !TIFFGetField(tif, TIFFTAG_TILEWIDTH, &l->tw) || !TIFFGetField(tif, TIFFTAG_TILELENGTH, &l->th) ||
        !TIFFGetField(tif, TIFFTAG_COMPRESSION, &comp) || !TIFFGetField(tif, TIFFTAG_PREDICTOR, &pred) ||
        !TIFFGetFieldDefaulted(tif, TIFFTAG_BITSPERSAMPLE, &bps) ||
        !TIFFGetFieldDefaulted(tif, TIFFTAG_SAMPLESPERPIXEL, &spp) ||
        !TIFFGetFieldDefaulted(tif, TIFFTAG_SAMPLEFORMAT, &fmt))
        return 0;
    if (w != nx || h != ny || l->tw == 0 || l->th == 0 || comp != COMPRESSION_ZSTD || pred != PREDICTOR_FLOATINGPOINT ||
        bps != 32 || spp != 1 || fmt != SAMPLEFORMAT_IEEEFP)
        return 0;
    l->ntx = (uint32_t)((nx + l->tw - 1) / l->tw);
    l->nty = (uint32_t)((ny + l->th - 1) / l->th);
    return TIFFNumberOfTiles(tif) == l->ntx * l->nty;
}

/* ---- one tile ------------------------------------------------------------------------------------ */

typedef struct {
    const ft_grid *g;
    int use_nodata;
    float nodata;
    tile_layout l;
    int level; /* ZSTD level */
} tile_job;

static float cell(const tile_job *j, size_t i)
{
    const ft_grid *g = j->g;
    float z = g->z[i];
    if (j->use_nodata && ((g->mask != NULL && g->mask[i] == 0) || !isfinite(z)))
        return j->nodata;
    return z;
}

/* The predicted bytes of tile (tx, ty) into out (tw * th * 4 bytes); scratch holds 8 * tw bytes (4-byte
 * aligned): a row's floats as bits, then its 4 byte planes. */
static void predict_tile(const tile_job *j, uint32_t tx, uint32_t ty, unsigned char *out, unsigned char *scratch)
{
    const ft_grid *g = j->g;
    size_t tw = j->l.tw, x0 = (size_t)tx * tw, y0 = (size_t)ty * j->l.th;
    size_t xs = g->nx - x0 < tw ? g->nx - x0 : tw; /* columns inside the raster */
    uint32_t *bits = (uint32_t *)(void *)scratch;   /* the row's floats as bits */
    unsigned char *planes = scratch + 4 * tw;
    for (size_t r = 0; r < j->l.th; r++) {
        size_t y = y0 + r < g->ny ? y0 + r : g->ny - 1; /* padding repeats the last row */
        const size_t base = y * g->nx + x0;
        if (!j->use_nodata) {
            memcpy(bits, g->z + base, xs * sizeof *bits);
        } else {
            for (size_t c = 0; c < xs; c++) {
                float v = cell(j, base + c);
                memcpy(&bits[c], &v, sizeof v);
            }
        }
        for (size_t c = xs; c < tw; c++) /* and the last column */
            bits[c] = bits[xs - 1];
#pragma omp simd
        for (size_t c = 0; c < tw; c++) {
            uint32_t b = bits[c];
            planes[c] = (unsigned char)(b >> 24);
            planes[tw + c] = (unsigned char)(b >> 16);
            planes[2 * tw + c] = (unsigned char)(b >> 8);
            planes[3 * tw + c] = (unsigned char)b;
        }
        unsigned char *row = out + r * tw * 4;
        row[0] = planes[0];
#pragma omp simd
        for (size_t k = 1; k < 4 * tw; k++)
            row[k] = (unsigned char)(planes[k] - planes[k - 1]);
    }
}

/* ---- the writer ---------------------------------------------------------------------------------- */

typedef struct {
    unsigned char *data; /* its compressed bytes (compressBound allocated), freed once appended */
    size_t size;         /* compressed size; 0 until the tile is compressed */
} packed_tile;

/* Appends tiles in their order as they come out of the compressing threads (under a critical section). */
typedef struct {
    TIFF *tif;
    uint32_t next; /* the next tile to append */
    int failed;    /* 1 compression (or memory), 2 append */
} appender;

static void append_ready(appender *a, packed_tile *p, uint32_t ntiles)
{
    while (!a->failed && a->next < ntiles && p[a->next].size != 0) {
        packed_tile *q = &p[a->next];
        if (TIFFWriteRawTile(a->tif, a->next, q->data, (tmsize_t)q->size) != (tmsize_t)q->size) {
#pragma omp atomic write
            a->failed = 2;
            break;
        }
        free(q->data);
        q->data = NULL;
        a->next++;
    }
}

/* Compresses the tiles (row-major tile numbers, p[t] zeroed) on the OpenMP threads, each appended as soon as
 * it and those before it are done: only the tiles finished out of order wait in memory. */
static void pack_tiles(const tile_job *j, uint32_t ntiles, packed_tile *p, appender *a)
{
    size_t raw = (size_t)j->l.tw * j->l.th * 4, cap = ZSTD_compressBound(raw);
#pragma omp parallel
    {
        unsigned char *buf = malloc(raw + 8 * (size_t)j->l.tw); /* the tile, then predict_tile's scratch */
        ZSTD_CCtx *cc = ZSTD_createCCtx();
#pragma omp for schedule(dynamic, 1)
        for (uint32_t t = 0; t < ntiles; t++) {
            int stop;
#pragma omp atomic read
            stop = a->failed;
            if (stop)
                continue;
            unsigned char *dst = buf != NULL && cc != NULL ? malloc(cap) : NULL;
            size_t n = 0;
            if (dst != NULL) {
                predict_tile(j, t % j->l.ntx, t / j->l.ntx, buf, buf + raw);
                n = ZSTD_compressCCtx(cc, dst, cap, buf, raw, j->level);
            }
#pragma omp critical(ft_gtiff_append)
            {
                if (dst == NULL || ZSTD_isError(n) || n == 0) {
                    free(dst);
#pragma omp atomic write
                    a->failed = 1;
                } else {
                    p[t] = (packed_tile){dst, n};
                    append_ready(a, p, ntiles);
                }
            }
        }
        ZSTD_freeCCtx(cc);
        free(buf);
    }
    for (uint32_t t = 0; t < ntiles; t++) /* left by a failure */
        free(p[t].data);
}

static int write_tiles(TIFF *tif, tiff_file *f, const tile_job *j, const char *path)
{
    uint32_t ntiles = j->l.ntx * j->l.nty;
    packed_tile *p = ft_calloc(ntiles, sizeof *p);
    if (p == NULL)
        return FT_E_NOMEM;
    appender a = {.tif = tif};
    pack_tiles(j, ntiles, p, &a);
    free(p);
    if (a.failed == 1)
        return ft_error(FT_E_NOMEM, "cannot compress the tiles of '%s' (ZSTD level %d)", path, j->level);
    if (a.failed)
        return ft_error(FT_E_IO, "cannot write '%s': %s", path,
                        f->err ? strerror(f->err) : f->msg[0] ? f->msg : "libtiff failed");
    return FT_OK;
}

int ft_io_gtiff_tiles_fill(const char *path, const char *file, const ft_grid *g, int use_nodata, float nodata,
                           int level, int *done)
{
    *done = 0;
    tiff_file f = {.fd = open(file, O_RDWR | O_CLOEXEC)};
    if (f.fd < 0)
        return ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(errno));
    TIFF *tif = open_update(file, &f);
    tile_job j = {.g = g, .use_nodata = use_nodata, .nodata = nodata, .level = level};
    int rc = FT_OK;
    if (tif != NULL && layout_of(tif, g->nx, g->ny, &j.l)) {
        *done = 1;
        rc = write_tiles(tif, &f, &j, path);
        if (rc == FT_OK && !TIFFFlush(tif))
            rc = ft_error(FT_E_IO, "cannot write '%s': %s", path,
                          f.err ? strerror(f.err) : f.msg[0] ? f.msg : "libtiff could not rewrite the directory");
    } else if (tif == NULL && f.err != 0) {
        rc = ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(f.err));
    }
    if (tif != NULL)
        TIFFClose(tif);
    if (close(f.fd) != 0 && rc == FT_OK && *done)
        rc = ft_error(FT_E_IO, "cannot write '%s': %s", path, strerror(errno));
    return rc;
}
