/* fracterra — io.h: reading and writing chains, polygons, grids and points.
 *
 * Vector layers go through OGR (GeoJSON, Shapefile, GeoPackage, any OGR driver), rasters through GDAL,
 * plus GMT-style plain text chains (`x y` per line, `>` between segments), CSV and whitespace XYZ points.
 * Every writer writes to a temporary name in the destination folder and renames on success, so a
 * failed write leaves no file behind. CRS and geotransform are carried through.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_IO_H
#define FRACTERRA_IO_H

#include <stdio.h>

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Registers GDAL/OGR drivers once (thread-safe, idempotent); every reader and writer calls it. */
void ft_io_init(void);
/** Releases GDAL's global state (call at program exit; optional). */
void ft_io_cleanup(void);

/* What a path holds, as far as fracterra is concerned. */
typedef enum {
    FT_KIND_UNKNOWN = 0,
    FT_KIND_GRID = 1,         /**< a raster GDAL opens */
    FT_KIND_CHAINS = 2,       /**< a vector layer of lines or polygons, or GMT text chains */
    FT_KIND_POINTS = 3,       /**< a vector layer of points, CSV or XYZ text */
} ft_file_kind;

/** Decides what a file holds without reading it all. FT_E_IO if it cannot be opened, FT_E_FORMAT if
 *  it is neither a raster nor a vector nor a known text format. layer may be NULL (first layer). */
int ft_io_probe(const char *path, const char *layer, ft_file_kind *kind);

/** What a file held, as read by ft_io_read_any: exactly one of grid, layer, points is set. */
typedef struct {
    ft_file_kind kind;
    ft_grid *grid;
    ft_layer *layer;
    ft_points *points;
} ft_data;

/** 1 if the path names a plain-text chain file by its extension (.gmt, .xy, .txt). */
int ft_io_is_text_chains(const char *path);
/** 1 if the path names a plain-text point file by its extension (.csv, .xyz). */
int ft_io_is_text_points(const char *path);

/* ------------------------------------------------------------------------------------------------
 * Chains and polygons
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    const char *layer;   /**< layer name; NULL = the first layer */
    const char *where;   /**< OGR attribute filter (SQL WHERE clause); NULL = all features */
    const char *fields;  /**< comma-separated field names to keep; NULL = all, "" = none */
} ft_read_layer_opts;
#define FT_READ_LAYER_OPTS_DEFAULT {NULL, NULL, NULL}

/** Reads lines, multilines, polygons (with holes) and multipolygons of a layer, or GMT text chains
 *  (by extension). Rings lose their repeated closing vertex. Errors: FT_E_IO (missing/unreadable),
 *  FT_E_FORMAT (a raster, a point layer, unknown layer or field), FT_E_EMPTY (no chain at all),
 *  FT_E_NUMERIC (NaN/Inf coordinate, named). Chains with fewer than 2 vertices are kept. */
int ft_io_read_layer(const char *path, const ft_read_layer_opts *opts, ft_layer **out);

typedef struct {
    const char *driver;      /**< OGR driver short name; NULL = from the extension */
    const char *layer;       /**< layer name to write; NULL = the layer's name or the file's stem */
    const char *const *lco;  /**< NULL-terminated layer creation options, or NULL */
} ft_write_layer_opts;
#define FT_WRITE_LAYER_OPTS_DEFAULT {NULL, NULL, NULL}

/** Writes a layer (geometry type per feature, fields, CRS) through OGR, or as GMT text (by extension or
 *  driver "GMT-text"). Replaces an existing file only when the whole write succeeded. */
int ft_io_write_layer(const char *path, const ft_layer *layer, const ft_write_layer_opts *opts);

/** GMT-style text: `x y` per line (extra columns ignored), `>` lines separate segments, `#` comments.
 *  A segment whose last vertex equals its first becomes a ring. "-" reads stdin / writes stdout. */
int ft_io_read_text_chains(const char *path, ft_layer **out);
int ft_io_write_text_chains(const char *path, const ft_layer *layer);

/* ------------------------------------------------------------------------------------------------
 * Grids
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    int band;  /**< 1-based band number; default 1 */
} ft_read_grid_opts;
#define FT_READ_GRID_OPTS_DEFAULT {1}

/** Reads one band as float with its geotransform, CRS and nodata mask (the band's nodata value, its
 *  mask band, and NaN cells are nodata). FT_E_FORMAT for a vector file or a bad band number. */
int ft_io_read_grid(const char *path, const ft_read_grid_opts *opts, ft_grid **out);

typedef struct {
    const char *driver;       /**< GDAL driver short name; NULL = from the extension (GTiff default) */
    const char *const *co;    /**< NULL-terminated creation options, or NULL (GeoTIFF: tiled, DEFLATE) */
    int type;                 /**< GDALDataType of the output band; 0 = Float32 */
} ft_write_grid_opts;
#define FT_WRITE_GRID_OPTS_DEFAULT {NULL, NULL, 0}

/** Writes a grid with its geotransform, CRS and nodata (masked cells get nodata_value, or NaN/-9999
 *  chosen for the type if the grid has none). Drivers without Create use CreateCopy from memory. */
int ft_io_write_grid(const char *path, const ft_grid *g, const ft_write_grid_opts *opts);
/** Writes n >= 1 grids as bands 1 .. n of one raster (e.g. a D map and its r²): every grid must have the
 *  first's size and geotransform (the error names the band at fault); CRS from the first grid, nodata per
 *  band as ft_io_write_grid. */
int ft_io_write_grids(const char *path, const ft_grid *const *bands, size_t n, const ft_write_grid_opts *opts);

/* ------------------------------------------------------------------------------------------------
 * Points
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    const char *x, *y, *z;  /**< column names for CSV (defaults "x", "y", "z", case-insensitive) */
    const char *weight;     /**< optional confidence column/field (1/sigma); NULL = none */
    const char *layer;      /**< OGR layer; NULL = first */
    const char *zfield;     /**< OGR point layers: z from this field; NULL = from the geometry's Z */
} ft_read_points_opts;
#define FT_READ_POINTS_OPTS_DEFAULT {NULL, NULL, NULL, NULL, NULL, NULL}

/** Reads scattered points from CSV (header row; .csv), whitespace XYZ text (.xyz, `x y z` per line,
 *  `#` comments), or an OGR point layer. Errors name the file, line and column of a non-numeric or
 *  non-finite value, and a missing column. */
int ft_io_read_points(const char *path, const ft_read_points_opts *opts, ft_points **out);
/** Writes points as CSV (x,y,z[,w]) or XYZ text by extension, or through OGR otherwise. */
int ft_io_write_points(const char *path, const ft_points *p);

/* ------------------------------------------------------------------------------------------------
 * Any kind
 * --------------------------------------------------------------------------------------------- */

/** Opens a file once and reads what it holds: a grid (band go->band) when it is a raster and no layer is
 *  named, else the layer's lines/polygons or points. Options may be NULL (defaults); the layer name is taken
 *  from lo, else po. Same errors as the single-kind readers. Release with ft_data_clear. */
int ft_io_read_any(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                   const ft_read_points_opts *po, ft_data *out);
/** Frees what ft_io_read_any read and zeroes *d; NULL is a no-op. */
void ft_data_clear(ft_data *d);

/* ------------------------------------------------------------------------------------------------
 * Files
 * --------------------------------------------------------------------------------------------- */

/** FT_OK if path can be created: its folder exists and is writable (FT_E_IO naming it otherwise). */
int ft_io_check_writable(const char *path);

/* ---- atomic output (atomic_write.c) ----
 * Every file the library writes goes through this service: the bytes go to a temporary name beside the
 * destination, every write, flush and close is checked, the files are synced to disk (fsync) and only then
 * renamed onto the destination. On any failure the temporaries are removed and an existing output is left
 * untouched. */

/** A temporary name beside path, "<dir>/.<stem>.ft-tmp-<pid>-<n><ext>" (malloc'd); NULL with FT_E_IO naming
 *  the folder when it is missing. Companion files a driver adds (.shx, .dbf, ...) share its stem. */
char *ft_io_atomic_tmp(const char *path);
/** Syncs tmp and its companions to disk and renames them onto path (path's stem + their suffixes). On
 *  failure removes them, leaves path as it was and returns FT_E_IO naming path and the system's reason. */
int ft_io_atomic_commit(const char *tmp, const char *path);
/** Removes tmp and its companions; keeps the thread's error message. NULL is a no-op. */
void ft_io_atomic_discard(const char *tmp);
/** Writes path through fn(f, arg) into a temporary file, checks every write, the flush and the close, and
 *  commits it. fn returns FT_OK or an FT_E_* code (with ft_error set). */
typedef int (*ft_io_write_fn)(FILE *f, const void *arg);
int ft_io_atomic_write(const char *path, ft_io_write_fn fn, const void *arg);
/** 1 if a and b name the same file: the same device and inode when both exist, else the same resolved path
 *  (folder symlinks followed). "-" (standard input/output) is never the same as anything. */
int ft_io_same_file(const char *a, const char *b);

/* ------------------------------------------------------------------------------------------------
 * DEM processing through GDAL (GDALDEMProcessing) and CRS definitions
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double azimuth;   /**< light direction, degrees clockwise from north, [0, 360]; default 315 */
    double altitude;  /**< light elevation above the horizon, degrees, (0, 90]; default 45 */
    double z_factor;  /**< vertical exaggeration, > 0; default 1 */
    double scale;     /**< horizontal units per vertical unit; 0 (default) = 111120 for a DEM in degrees,
                           1 otherwise */
    int color;        /**< 1: multiply a hypsometric colour relief (gdaldem color-relief) by the shade */
    int band;         /**< 1-based band of the DEM; default 1 */
} ft_io_hillshade_opts;
#define FT_IO_HILLSHADE_OPTS_DEFAULT {315.0, 45.0, 1.0, 0.0, 0, 1}

/** gdaldem's hillshade of a DEM file (edges computed, nodata 0), optionally times a colour relief (RGBA,
 *  nodata transparent), written through the driver of the output's extension (PNG, GeoTIFF, ...) under a
 *  temporary name renamed on success. */
int ft_io_hillshade(const char *dem_path, const char *out_path, const ft_io_hillshade_opts *opts);

/** Contour polygons of a DEM (GDALContourGenerateEx with POLYGONIZE=YES, as gdal_contour -p -amin elev):
 *  one polygon feature per band between two levels base + i x interval, with a real field `elev` holding
 *  its lower level; nodata cells are excluded. The layer carries the grid's CRS. */
int ft_io_contour_polygons(const ft_grid *dem, double interval, double base, ft_layer **out);

/** A CRS given as "EPSG:n", WKT, a PROJ string or anything OSRSetFromUserInput accepts, as malloc'd WKT
 *  (free()). FT_E_INVALID naming the input if GDAL does not know it. */
int ft_io_crs_to_wkt(const char *user_input, char **wkt);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_IO_H */
