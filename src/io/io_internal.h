/* fracterra — private helpers of the I/O module (src/io/), not installed.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_IO_INTERNAL_H
#define FRACTERRA_IO_INTERNAL_H

#include <stdio.h>

#include <gdal.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include "fracterra/io.h"

/* GDAL messages (init.c). Every public function that reaches GDAL runs its work between ft_io_enter (registers
 * the drivers once, pushes the module's handler on this thread's GDAL handler stack) and ft_io_leave (pops it,
 * returns rc), so the host's own handler is back on return:
 *     int ft_io_read_x(...) { ft_io_enter(); return ft_io_leave(read_x(...)); }
 * The pushed handler keeps the last message of this thread instead of printing it. */
void ft_io_enter(void);
int ft_io_leave(int rc);
void ft_io_gdal_reset(void);       /* forgets the stored message and failure flag */
const char *ft_io_gdal_msg(void);  /* last failure message (else last warning) since the reset, "" if none */
int ft_io_gdal_failed(void);       /* 1 if GDAL reported a failure since the reset */

/* Sets the error like ft_error(), appending ": <GDAL message>" when GDAL said something. */
int ft_io_fail(int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* GDAL's worker threads (common.c): between begin and end, this thread's GDAL calls may use every core
 * for (de)compression (GDAL_NUM_THREADS=ALL_CPUS, thread-local), unless the user set GDAL_NUM_THREADS.
 * begin returns what end restores (the previous thread-local value, or NULL). */
char *ft_io_threads_begin(void);
void ft_io_threads_end(char *prev);

/* Paths (common.c). */
const char *ft_io_ext(const char *path);             /* extension after the last dot of the file name, "" if none */
int ft_io_ext_in(const char *path, const char *list); /* 1 if the extension is one of the space-separated list */
char *ft_io_stem(const char *path);                  /* malloc'd file name without folder and extension */
int ft_io_is_stdio(const char *path);                 /* 1 for "-" */
/* FT_E_IO "cannot open 'path': reason" when path is missing or unreadable; FT_OK if it can be read. */
int ft_io_check_readable(const char *path);

/* Opening (common.c): a dataset of the wanted kind (GDAL_OF_VECTOR or GDAL_OF_RASTER), with the errors
 * of the module: FT_E_IO for a missing/unreadable file, FT_E_FORMAT for the other kind or an unknown format. */
int ft_io_open(const char *path, unsigned int kind, GDALDatasetH *ds);
/* The named layer (or the first); FT_E_FORMAT naming it and listing the layers when absent. */
int ft_io_get_layer(GDALDatasetH ds, const char *path, const char *name, OGRLayerH *layer);

/* Readers working on an open dataset (vector_read.c, points_read.c, raster_read.c), so that a file is opened
 * (and, for GeoJSON, parsed) once when its kind is probed and its content read (ft_io_read_any). */
int ft_io_read_layer_ds(GDALDatasetH ds, const char *path, const ft_read_layer_opts *o, ft_layer **out);
int ft_io_read_points_ds(GDALDatasetH ds, const char *path, const ft_read_points_opts *o, ft_points **out);
int ft_io_read_grid_ds(GDALDatasetH ds, const char *path, const ft_read_grid_opts *o, ft_grid **out);
int ft_io_summarize_grid_ds(GDALDatasetH ds, const char *path, const ft_read_grid_opts *o, ft_grid_summary *out);
/* What an open dataset holds (probe.c): a grid unless a layer is named, else the kind of the layer. */
int ft_io_dataset_kind(GDALDatasetH ds, const char *path, const char *layer, ft_file_kind *kind);

/* Drivers (common.c): opts driver name, else from the extension among drivers that can create files of
 * that kind (GDAL_DCAP_VECTOR or GDAL_DCAP_RASTER). FT_E_FORMAT naming the extension or driver otherwise. */
int ft_io_find_driver(const char *path, const char *name, const char *cap, GDALDriverH *drv);

/* CRS (common.c). */
char *ft_io_srs_to_wkt(OGRSpatialReferenceH srs);    /* malloc'd WKT2 (or WKT1), NULL if srs is NULL */
int ft_io_srs_from_wkt(const char *wkt, OGRSpatialReferenceH *srs); /* *srs NULL for NULL/empty wkt */

/* A one-band Float32 MEM raster holding the grid and its geotransform (not its CRS), nodata cells set to
 * `nodata` (contour_generate.c). */
int ft_io_grid_mem_raster(const ft_grid *g, float nodata, GDALDatasetH *out);

/* Text (common.c). */
void ft_io_format_double(char *buf, size_t size, double v); /* shortest text that reads back to exactly v */
void ft_io_put_double(FILE *f, double v);            /* the same, written to f */
int ft_io_parse_double(const char *s, double *v);    /* 1 if s is one whole number (spaces around allowed) */
FILE *ft_io_fopen_read(const char *path);            /* stdin for "-" */

/* Rasters (raster_write.c): grids of the same size as the bands of one file, atomically; the geotransform
 * and CRS are the first grid's, each band has its grid's nodata. No checks across the grids. */
int ft_io_write_bands(const char *path, const ft_grid *const *bands, size_t n, const ft_write_grid_opts *opts);
/* The pieces of that writer the tile writer (raster_tile_write.c) shares: the band type of a request (0 =
 * Float32), the nodata value of a type when the grid has none, the creation options (GeoTIFF defaults plus
 * the caller's, into *out: CSLDestroy them; FT_E_INVALID for a bad FRACTERRA_GTIFF_COMPRESS), a band's
 * nodata in its type, and FT_E_UNSUPPORTED when drv cannot store the type. */
int ft_io_output_type(int requested, GDALDataType *t);
double ft_io_default_nodata(GDALDataType t);
int ft_io_creation_options(GDALDriverH drv, const char *const *co, GDALDataType t, char ***out);
void ft_io_set_nodata(GDALRasterBandH b, GDALDataType t, double v);
int ft_io_check_type(const char *path, GDALDriverH drv, GDALDataType type);

/* GDAL writers through the atomic service (atomic_write.c). ft_io_stage_begin picks where GDAL writes
 * (target): the on-disk temporary for a GTiff/COG beyond 256 MB (libtiff reports failed writes), else a
 * /vsimem/ folder whose files are copied to the temporary with every write checked. ft_io_stage_end(s, ok) commits
 * when ok (FT_E_IO naming the path if a byte could not be written), discards otherwise, and frees s. */
typedef struct {
    const char *path; /* the destination */
    char *tmp;        /* its on-disk temporary */
    char *target;     /* the name GDAL writes */
    char *mem_dir;    /* the /vsimem/ folder of target, or NULL */
} ft_io_stage;
/* The tiles of a one-band Float32 GeoTIFF (gtiff_tiles.c): file is the on-disk GeoTIFF of g's size GDAL wrote
 * tiled, ZSTD + predictor 3 and without tiles (SPARSE_OK); its tiles are compressed at ZSTD level on the
 * OpenMP threads and appended, invalid cells as nodata when use_nodata. *done is 0 (and nothing written)
 * when the file's layout is not that one; errors name path. */
int ft_io_gtiff_tiles_fill(const char *path, const char *file, const ft_grid *g, int use_nodata, float nodata,
                           int level, int *done);

int ft_io_stage_begin(const char *path, GDALDriverH drv, double bytes, ft_io_stage *s); /* bytes: a size hint */
int ft_io_stage_end(ft_io_stage *s, int ok);

/* Text points (points_text.c): CSV with a header row, whitespace XYZ ("-" = stdin). */
int ft_io_read_points_csv(const char *path, const ft_read_points_opts *o, ft_points **out);
int ft_io_read_points_xyz(const char *path, const ft_read_points_opts *o, ft_points **out);

#endif /* FRACTERRA_IO_INTERNAL_H */
