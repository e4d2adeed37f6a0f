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
#include "terrain.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Registers GDAL/OGR drivers once (thread-safe, idempotent); every reader and writer calls it.
 *
 *  GDAL's messages: fracterra never replaces the process's GDAL error handler. Each io function pushes its
 *  own handler on the calling thread's GDAL handler stack for the time of the call and pops it before
 *  returning, so a host's handler (CPLSetErrorHandler or CPLPushErrorHandler) stays in place. GDAL's
 *  failures and warnings raised inside a fracterra call do not reach the host's handler: they are returned
 *  in ft_last_error() ("cannot open 'x.tif': <GDAL's reason>"). Debug messages (CPL_DEBUG) pass through
 *  to the host's handler. */
FT_API void ft_io_init(void);
/** Releases GDAL's global state (call at program exit; optional). */
FT_API void ft_io_cleanup(void);

/* What a path holds, as far as fracterra is concerned. */
typedef enum {
    FT_KIND_UNKNOWN = 0,
    FT_KIND_GRID = 1,         /**< a raster GDAL opens */
    FT_KIND_CHAINS = 2,       /**< a vector layer of lines or polygons, or GMT text chains */
    FT_KIND_POINTS = 3,       /**< a vector layer of points, CSV or XYZ text */
} ft_file_kind;

/** Decides what a file holds without reading it all. FT_E_IO if it cannot be opened, FT_E_FORMAT if
 *  it is neither a raster nor a vector nor a known text format. layer may be NULL (first layer). */
FT_API int ft_io_probe(const char *path, const char *layer, ft_file_kind *kind);

/** What a file held, as read by ft_io_read_any: exactly one of grid, layer, points is set. */
typedef struct {
    ft_file_kind kind;
    ft_grid *grid;
    ft_layer *layer;
    ft_points *points;
} ft_data;

/** 1 if the path names a plain-text chain file by its extension (.gmt, .xy, .txt). */
FT_API int ft_io_is_text_chains(const char *path);
/** 1 if the path names a plain-text point file by its extension (.csv, .xyz). */
FT_API int ft_io_is_text_points(const char *path);

/* ------------------------------------------------------------------------------------------------
 * Chains and polygons
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_read_layer_opts); see FT_OPTS in core.h */
    const char *layer;   /**< layer name; NULL = the first layer */
    const char *where;   /**< OGR attribute filter (SQL WHERE clause); NULL = all features */
    const char *fields;  /**< comma-separated field names to keep; NULL = all, "" = none */
} ft_read_layer_opts;
#define FT_READ_LAYER_OPTS_DEFAULT                                                                                   \
    {.struct_size = sizeof(ft_read_layer_opts), .layer = NULL, .where = NULL, .fields = NULL}

/** Reads lines, multilines, polygons (with holes) and multipolygons of a layer, or GMT text chains
 *  (by extension). Rings lose their repeated closing vertex. Errors: FT_E_IO (missing/unreadable),
 *  FT_E_FORMAT (a raster, a point layer, unknown layer or field), FT_E_EMPTY (no chain at all),
 *  FT_E_NUMERIC (NaN/Inf coordinate, named). Chains with fewer than 2 vertices are kept. */
FT_API int ft_io_read_layer(const char *path, const ft_read_layer_opts *opts, ft_layer **out);

typedef struct {
    size_t struct_size; /**< sizeof(ft_write_layer_opts); see FT_OPTS in core.h */
    const char *driver;      /**< OGR driver short name; NULL = from the extension */
    const char *layer;       /**< layer name to write; NULL = the layer's name or the file's stem */
    const char *const *lco;  /**< NULL-terminated layer creation options, or NULL */
} ft_write_layer_opts;
#define FT_WRITE_LAYER_OPTS_DEFAULT                                                                                  \
    {.struct_size = sizeof(ft_write_layer_opts), .driver = NULL, .layer = NULL, .lco = NULL}

/** Writes a layer (geometry type per feature, fields, CRS) through OGR, or as GMT text (by extension or
 *  driver "GMT-text"). Replaces an existing file only when the whole write succeeded. */
FT_API int ft_io_write_layer(const char *path, const ft_layer *layer, const ft_write_layer_opts *opts);

/** GMT-style text: `x y` per line (extra columns ignored), `>` lines separate segments, `#` comments.
 *  A segment whose last vertex equals its first becomes a ring. "-" reads stdin / writes stdout. */
/** The vertices (x, y, z) of the first line (LineString, or first part of a MultiLineString) of a vector
 *  layer (NULL = the first layer), for a profile along a 3-D line. A 2-D line is FT_E_FORMAT, fewer than 3
 *  vertices FT_E_EMPTY, a NaN/Inf coordinate FT_E_NUMERIC. x, y and z are allocated (free them). */
FT_API int ft_io_read_line_z(const char *path, const char *layer, double **x, double **y, double **z, size_t *n);
FT_API int ft_io_read_text_chains(const char *path, ft_layer **out);
FT_API int ft_io_write_text_chains(const char *path, const ft_layer *layer);

/* ------------------------------------------------------------------------------------------------
 * Grids
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_read_grid_opts); see FT_OPTS in core.h */
    int band;  /**< 1-based band number; default 1 */
} ft_read_grid_opts;
#define FT_READ_GRID_OPTS_DEFAULT {.struct_size = sizeof(ft_read_grid_opts), .band = 1}

/** Reads one band as float with its geotransform, CRS and nodata mask (the band's nodata value, its
 *  mask band, and NaN cells are nodata). FT_E_FORMAT for a vector file or a bad band number. */
FT_API int ft_io_read_grid(const char *path, const ft_read_grid_opts *opts, ft_grid **out);

/** A band's header and cell statistics, computed strip by strip without holding its cells (the memory of
 *  one strip of about 4 M cells): what ft_io_read_grid would give, then ft_grid_count_valid and
 *  ft_grid_minmax, without the grid. */
typedef struct {
    ft_grid header;   /**< size, geotransform, CRS and nodata of the band; z and mask are NULL */
    size_t valid;     /**< cells that are not nodata */
    double zmin, zmax;/**< range of the valid cells, in the band's physical units; NaN when valid is 0 */
} ft_grid_summary;

/** Summarizes band opts->band of a raster file (opts may be NULL). Same errors as ft_io_read_grid.
 *  Release with ft_grid_summary_clear. */
FT_API int ft_io_summarize_grid(const char *path, const ft_read_grid_opts *opts, ft_grid_summary *out);
/** Frees the summary's CRS and zeroes it; NULL is a no-op. */
FT_API void ft_grid_summary_clear(ft_grid_summary *s);

typedef struct {
    size_t struct_size; /**< sizeof(ft_write_grid_opts); see FT_OPTS in core.h */
    const char *driver;       /**< GDAL driver short name; NULL = from the extension (GTiff default) */
    const char *const *co;    /**< NULL-terminated creation options, or NULL (GeoTIFF: tiled, ZSTD-1 or DEFLATE-1) */
    int type;                 /**< GDALDataType of the output band; 0 = Float32 */
} ft_write_grid_opts;
#define FT_WRITE_GRID_OPTS_DEFAULT {.struct_size = sizeof(ft_write_grid_opts), .driver = NULL, .co = NULL, .type = 0}

/** Writes a grid with its geotransform, CRS and nodata (masked cells get nodata_value, or NaN/-9999
 *  chosen for the type if the grid has none). Drivers without Create use CreateCopy from memory. */
FT_API int ft_io_write_grid(const char *path, const ft_grid *g, const ft_write_grid_opts *opts);
/** Writes n >= 1 grids as bands 1 .. n of one raster (e.g. a D map and its r²): every grid must have the
 *  first's size and geotransform (the error names the band at fault); CRS from the first grid, nodata per
 *  band as ft_io_write_grid. */
FT_API int ft_io_write_grids(const char *path, const ft_grid *const *bands, size_t n, const ft_write_grid_opts *opts);

/* ------------------------------------------------------------------------------------------------
 * Grids piece by piece (raster_read.c, raster_tile_write.c): a raster larger than memory is read as windows
 * (a stripe or block of cells plus the halo its operator needs) and written as pieces, with the memory of
 * one window. docs/tiling.md.
 * --------------------------------------------------------------------------------------------- */

/** A raster band open for windowed reading. */
typedef struct ft_grid_reader ft_grid_reader;

/** Opens band opts->band (opts may be NULL) of a raster file; same errors as ft_io_read_grid. */
FT_API int ft_io_grid_reader_open(const char *path, const ft_read_grid_opts *opts, ft_grid_reader **out);
/** The band's size (nx, ny), geotransform, CRS and nodata; z and mask are NULL. Owned by the reader. */
FT_API const ft_grid *ft_io_grid_reader_header(const ft_grid_reader *r);
/** The band's block size in cells (a window whose rows start and end on block rows reads each block once). */
FT_API void ft_io_grid_reader_block(const ft_grid_reader *r, size_t *bx, size_t *by);
/** Cells [col0, col0 + ncols) x [row0, row0 + nrows) of the band as a grid whose geotransform puts its cell
 *  (0, 0) at the band's cell (col0, row0), masked and scaled as ft_io_read_grid does: the cells are those
 *  ft_io_read_grid gives there. FT_E_INVALID naming the window when it leaves the band; FT_E_NOMEM when it
 *  does not fit ft_memory_limit(). GDAL's block cache is flushed after each window. */
FT_API int ft_io_grid_reader_read(ft_grid_reader *r, size_t col0, size_t row0, size_t ncols, size_t nrows,
                                  ft_grid **out);
/** Closes the file; NULL is a no-op. */
FT_API void ft_io_grid_reader_close(ft_grid_reader *r);

/** A raster being written piece by piece. */
typedef struct ft_grid_writer ft_grid_writer;

/** Creates an nbands-band tiled GeoTIFF of header's size, geotransform and CRS under a temporary name beside
 *  path (nothing appears at path before ft_io_grid_writer_commit). Cells are opts->type (default Float32);
 *  every band's nodata is header's nodata_value when has_nodata, else the type's (NaN for float types).
 *  FT_E_UNSUPPORTED for another format than GeoTIFF. */
FT_API int ft_io_grid_writer_create(const char *path, const ft_grid *header, size_t nbands,
                                    const ft_write_grid_opts *opts, ft_grid_writer **out);
/** Writes the cells of piece into band (1-based) with its cell (0, 0) at the raster's (col0, row0); masked
 *  and non-finite cells become nodata. Pieces may come in any order. */
FT_API int ft_io_grid_writer_write(ft_grid_writer *w, size_t band, const ft_grid *piece, size_t col0, size_t row0);
/** Closes the file and renames it onto path; frees w whatever the outcome (on failure nothing is at path). */
FT_API int ft_io_grid_writer_commit(ft_grid_writer *w);
/** Removes the temporary file and frees w; NULL is a no-op. */
FT_API void ft_io_grid_writer_abort(ft_grid_writer *w);

/** Writes path (a name ending in .vrt) as a GDAL virtual raster that mosaics n one-band rasters holding
 *  consecutive stripes of whole rows: parts[0] is the top rows, parts[1] the rows below, ... (e.g. one part
 *  per MPI rank). parts are named relative to path's folder and written so (relativeToVRT), so the .vrt moves
 *  with its parts, not without them. header gives the mosaic's size, geotransform and CRS. Every part is
 *  opened and checked: header->nx columns, one band, the first part's data type and nodata, the heights
 *  adding up to header->ny (FT_E_FORMAT / FT_E_INVALID naming the part). Atomic, as every writer. */
FT_API int ft_io_write_mosaic_vrt(const char *path, const ft_grid *header, size_t n, const char *const *parts);

/* ------------------------------------------------------------------------------------------------
 * Points
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_read_points_opts); see FT_OPTS in core.h */
    const char *x, *y, *z;  /**< column names for CSV (defaults "x", "y", "z", case-insensitive) */
    const char *weight;     /**< optional confidence column/field (1/sigma); NULL = none */
    const char *layer;      /**< OGR layer; NULL = first */
    const char *zfield;     /**< OGR point layers: z from this field; NULL = from the geometry's Z */
} ft_read_points_opts;
#define FT_READ_POINTS_OPTS_DEFAULT                                                                                  \
    {.struct_size = sizeof(ft_read_points_opts), .x = NULL, .y = NULL, .z = NULL, .weight = NULL, .layer = NULL,     \
     .zfield = NULL}

/** Reads scattered points from CSV (header row; .csv), whitespace XYZ text (.xyz, `x y z` per line,
 *  `#` comments), or an OGR point layer. Errors name the file, line and column of a non-numeric or
 *  non-finite value, and a missing column. */
FT_API int ft_io_read_points(const char *path, const ft_read_points_opts *opts, ft_points **out);
/** Writes points as CSV (x,y,z[,w]) or XYZ text by extension, or through OGR otherwise. */
FT_API int ft_io_write_points(const char *path, const ft_points *p);

/* ---- CSV (csv_tokenizer.c): the one CSV reader behind ft_io_read_points, open to any caller ----
 * The header is the first line that is neither blank nor a # comment; the separator is the most frequent of
 * `,` `;` tab outside quotes in it. Fields may be double-quoted (RFC 4180: "" is a quote; a quoted field may
 * hold separators and line breaks); blanks around fields are dropped; blank and # comment lines are skipped;
 * a UTF-8 BOM and CR LF are accepted. "-" reads standard input. */
typedef struct ft_io_csv ft_io_csv;
/** Opens path and reads its header. FT_E_IO if it cannot be read, FT_E_EMPTY if it has no header row,
 *  FT_E_FORMAT on bad quoting. Close with ft_io_csv_close. */
FT_API int ft_io_csv_open(const char *path, ft_io_csv **out);
/** The header's column names (owned by c) and their count. */
FT_API size_t ft_io_csv_header(const ft_io_csv *c, char *const **names);
/** The index of the column named name (case-insensitive); FT_E_FORMAT naming the file, the name and the
 *  columns there are otherwise. */
FT_API int ft_io_csv_find(const ft_io_csv *c, const char *name, size_t *col);
/** The next record's fields (owned by c, valid until the next call): 1, 0 at the end of the file, or a
 *  negative FT_E_* code (FT_E_FORMAT naming file:line on bad quoting or a NUL byte, FT_E_IO). */
FT_API int ft_io_csv_next(ft_io_csv *c, size_t *n, char *const **fields);
/** The line on which the last record read starts (1-based), for messages. */
FT_API long ft_io_csv_line(const ft_io_csv *c);
/** The separator found in the header: ',', ';' or '\t'. */
FT_API char ft_io_csv_separator(const ft_io_csv *c);
/** 1 if field is one whole number (blanks around allowed; inf and nan too: check isfinite), 0 otherwise.
 *  With ';' separators a single decimal comma reads as a point ("2,5" is 2.5). c may be NULL (no decimal
 *  comma). */
FT_API int ft_io_csv_number(const ft_io_csv *c, const char *field, double *v);
/** Closes the file and frees c; NULL is a no-op. */
FT_API void ft_io_csv_close(ft_io_csv *c);

/* ------------------------------------------------------------------------------------------------
 * Any kind
 * --------------------------------------------------------------------------------------------- */

/** Opens a file once and reads what it holds: a grid (band go->band) when it is a raster and no layer is
 *  named, else the layer's lines/polygons or points. Options may be NULL (defaults); the layer name is taken
 *  from lo, else po. Same errors as the single-kind readers. Release with ft_data_clear. */
FT_API int ft_io_read_any(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                   const ft_read_points_opts *po, ft_data *out);
/** As ft_io_read_any, except that a grid is summarized (ft_io_summarize_grid) into *summary instead of
 *  read: out->grid stays NULL. Clear both. */
FT_API int ft_io_read_any_summary(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                           const ft_read_points_opts *po, ft_data *out, ft_grid_summary *summary);
/** Frees what ft_io_read_any read and zeroes *d; NULL is a no-op. */
FT_API void ft_data_clear(ft_data *d);

/* ------------------------------------------------------------------------------------------------
 * Model files (clarke_model_json.c)
 * --------------------------------------------------------------------------------------------- */

/** Clarke's scale-based model (ft_clarke_fit, terrain.h) as the JSON object of a model file: "method",
 *  "model": "clarke1987", "D", "r2", "stderr", "range", "c", "D_clarke_eq8", "grid", "original", "trend",
 *  "harmonics", "regression" (docs/terrain-clarke.md). Numbers have the fewest digits that read back to the
 *  same double. malloc'd text (free()), NULL with FT_E_NOMEM. */
FT_API char *ft_io_clarke_model_to_json(const ft_clarke_model *m);
/** Writes that JSON to path through the atomic-write service. */
FT_API int ft_io_write_clarke_model(const char *path, const ft_clarke_model *m);
/** Reads a model file into *out (ft_clarke_model_free). FT_E_IO if it cannot be read; FT_E_FORMAT naming the
 *  file and the missing or malformed key, or the byte where the JSON breaks off, if it is not a model. A file
 *  written by ft_io_write_clarke_model reads back to the same model, bit for bit. */
FT_API int ft_io_read_clarke_model(const char *path, ft_clarke_model **out);

/* ------------------------------------------------------------------------------------------------
 * Files
 * --------------------------------------------------------------------------------------------- */

/** FT_OK if path can be created: its folder exists and is writable (FT_E_IO naming it otherwise). */
FT_API int ft_io_check_writable(const char *path);

/* ---- atomic output (atomic_write.c) ----
 * Every file the library writes goes through this service: the bytes go to a temporary name beside the
 * destination, every write, flush and close is checked, the files are synced to disk (fsync) and only then
 * renamed onto the destination. On any failure the temporaries are removed and an existing output is left
 * untouched. */

/** A temporary name beside path, "<dir>/.<stem>.ft-tmp-<pid>-<n><ext>" (malloc'd); NULL with FT_E_IO naming
 *  the folder when it is missing. Companion files a driver adds (.shx, .dbf, ...) share its stem. */
FT_API char *ft_io_atomic_tmp(const char *path);
/** Syncs tmp and its companions to disk and renames them onto path (path's stem + their suffixes). On
 *  failure removes them, leaves path as it was and returns FT_E_IO naming path and the system's reason. */
FT_API int ft_io_atomic_commit(const char *tmp, const char *path);
/** Removes tmp and its companions; keeps the thread's error message. NULL is a no-op. */
FT_API void ft_io_atomic_discard(const char *tmp);
/** Writes path through fn(f, arg) into a temporary file, checks every write, the flush and the close, and
 *  commits it. fn returns FT_OK or an FT_E_* code (with ft_error set). */
typedef int (*ft_io_write_fn)(FILE *f, const void *arg);
FT_API int ft_io_atomic_write(const char *path, ft_io_write_fn fn, const void *arg);
/** 1 if a and b name the same file: the same device and inode when both exist, else the same resolved path
 *  (folder symlinks followed). "-" (standard input/output) is never the same as anything. */
FT_API int ft_io_same_file(const char *a, const char *b);

/* ------------------------------------------------------------------------------------------------
 * The hillshade of a DEM file (the library's engine, ft_render_hillshade; colour relief through GDAL's
 * DEMProcessing) and CRS definitions
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_io_hillshade_opts); see FT_OPTS in core.h */
    double azimuth;   /**< light direction, degrees clockwise from north, [0, 360]; default 315 */
    double altitude;  /**< light elevation above the horizon, degrees, (0, 90]; default 45 */
    double z_factor;  /**< vertical exaggeration, > 0; default 1 */
    double scale;     /**< ft_hillshade_opts.scale (ground units of the horizontal coordinates per elevation
                           unit); 0 (default) = the metres of a degree of latitude on the ellipsoid at the
                           centre for a DEM in degrees, 1 otherwise */
    int color;        /**< 1: multiply a hypsometric colour relief (gdaldem color-relief) by the shade */
    int band;         /**< 1-based band of the DEM; default 1 */
} ft_io_hillshade_opts;
#define FT_IO_HILLSHADE_OPTS_DEFAULT                                                                                 \
    {.struct_size = sizeof(ft_io_hillshade_opts), .azimuth = 315.0, .altitude = 45.0, .z_factor = 1.0, .scale = 0.0, \
     .color = 0, .band = 1}

/** The hillshade of a DEM file by the library's engine (ft_render_hillshade), written as gdaldem hillshade
 *  -compute_edges writes it (Byte 1 + 254 x shade / 255, 0 = nodata; within 1 grey level of gdaldem's
 *  cells, tests/unit/test_io_hillshade.c), optionally times a colour relief (RGBA, nodata transparent),
 *  through the driver of the output's extension (PNG, GeoTIFF, ...) under a temporary name renamed on
 *  success. */
FT_API int ft_io_hillshade(const char *dem_path, const char *out_path, const ft_io_hillshade_opts *opts);

/** The scale ft_io_hillshade and ft_io_hillshade_rows use for this DEM file and opts (NULL = defaults):
 *  opts->scale when > 0, else the metres of a degree of latitude at the DEM's centre for a DEM in degrees,
 *  else 1. Reads the file's header only. */
FT_API int ft_io_hillshade_scale(const char *dem_path, const ft_io_hillshade_opts *opts, double *scale);

/** The hillshade of rows [row0, row0 + nrows) of a DEM file, as ft_io_hillshade gives them on the whole DEM
 *  (the same engine, edges computed, 0 = nodata, the automatic scale of the whole DEM's centre), from those rows and
 *  one row above and below: cells 0 .. 255 as floats (has_nodata, nodata_value 0), georeferenced at row0.
 *  FT_E_UNSUPPORTED with opts->color (the colour ramp spans the whole DEM). docs/tiling.md. */
FT_API int ft_io_hillshade_rows(const char *dem_path, const ft_io_hillshade_opts *opts, size_t row0, size_t nrows,
                                ft_grid **out);

/** Contour polygons of a DEM (GDALContourGenerateEx with POLYGONIZE=YES, as gdal_contour -p -amin elev):
 *  one polygon feature per band between two levels base + i x interval, with a real field `elev` holding
 *  its lower level; nodata cells are excluded. The layer carries the grid's CRS. */
FT_API int ft_io_contour_polygons(const ft_grid *dem, double interval, double base, ft_layer **out);

/** A CRS given as "EPSG:n", WKT, a PROJ string or anything OSRSetFromUserInput accepts, as malloc'd WKT
 *  (free()). FT_E_INVALID naming the input if GDAL does not know it. */
FT_API int ft_io_crs_to_wkt(const char *user_input, char **wkt);

/* ------------------------------------------------------------------------------------------------
 * The CRS service (crs.c, grid_reproject.c): the one place that reads a CRS. Geographic data are measured
 * in metres on their ellipsoid (lines) or in a local projection centred on them (boxes, grids, points,
 * tolerances); docs/geographic.md.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    int has_crs;            /**< 0: no CRS; coordinates are taken as planar, in an unknown unit */
    int geographic;         /**< 1: x = longitude, y = latitude in degrees (compound and bound CRSs resolved) */
    char name[128];         /**< the CRS's name ("WGS 84", "NAD83 / UTM zone 21N") */
    char unit[48];          /**< unit of x and y: "metre", "US survey foot", ..., "degree" if geographic */
    char scale_unit[16];    /**< unit of measured scales: "m" (metres, and every geographic CRS), "ft", "US ft",
                                 "km", else the unit's name; "" without CRS */
    double metres_per_unit; /**< metres in one unit of x and y (0.3048 for feet); 0 if geographic or unknown */
    ft_ellipsoid ellipsoid; /**< a (m) and f; zero if unknown */
    char ellipsoid_name[64];
} ft_crs_info;

/** What a WKT (or anything OSRSetFromUserInput reads) says; NULL or "" gives has_crs = 0 and FT_OK.
 *  FT_E_INVALID for a CRS GDAL does not know, FT_E_FORMAT for a geographic CRS without an ellipsoid. */
FT_API int ft_io_crs_info(const char *wkt, ft_crs_info *out);
/** The CRS's name (OSR's, e.g. "WGS 84 / UTM zone 32N") into name (at most size bytes) and the EPSG code
 *  the WKT itself gives its root (ID["EPSG",...] / AUTHORITY["EPSG",...]; 0 if none: no lookup). A NULL or
 *  empty wkt gives "" and 0; FT_E_INVALID if the WKT cannot be parsed. (crs_name.c) */
FT_API int ft_io_crs_name(const char *wkt, char *name, size_t size, int *epsg);

typedef enum {
    FT_LOCAL_LAEA = 0,  /**< Lambert azimuthal equal-area: areas and box counts */
    FT_LOCAL_TMERC = 1, /**< transverse Mercator, scale 1 on the central meridian: conformal, for grids */
} ft_local_projection;

/** WKT (malloc'd) of a projection in metres centred on (lon0, lat0), on the datum of the geographic (or
 *  any) CRS geo_wkt; its name says what it is ("Lambert azimuthal equal-area centred on 49.6000N ..."). */
FT_API int ft_io_local_crs(const char *geo_wkt, ft_local_projection kind, double lon0, double lat0, char **wkt);
/** Grid azimuth of true north at map point (x, y) of the CRS wkt, degrees clockwise from the grid's north
 *  (the meridian convergence: -2.2 for UTM 32N at 49.8N 6.1E); 0 for a geographic CRS or no CRS. An azimuth
 *  measured from grid north is the true azimuth plus this. FT_E_NUMERIC if the point cannot be reprojected. */
FT_API int ft_io_crs_grid_north(const char *wkt, double x, double y, double *azimuth);
/** Reprojects every part (and topology arc) of the layer from its CRS to dst_wkt in place (OCT, x =
 *  longitude order) and sets its CRS. FT_E_NUMERIC naming a vertex that cannot be transformed. */
FT_API int ft_io_layer_reproject(ft_layer *l, const char *dst_wkt);
/** The same for points (x, y change; z and weights stay). */
FT_API int ft_io_points_reproject(ft_points *p, const char *dst_wkt);
/** The grid warped to dst_wkt with square cells of side `cell` (target units), bilinear, nodata kept
 *  (as `gdalwarp -t_srs -tr cell cell -r bilinear`). */
FT_API int ft_io_grid_reproject(const ft_grid *g, const char *dst_wkt, double cell, ft_grid **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_IO_H */
