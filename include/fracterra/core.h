/* fracterra — fractal geometry of maps.
 * core.h: core types (chains, layers, grids, points), errors, progress, RNG, least-squares fits.
 *
 * Conventions (see docs/api.md):
 *  - functions return int: 0 (FT_OK) on success, a negative FT_E_* code on failure, and then
 *    ft_last_error() holds a thread-local message naming the bad value;
 *  - the caller owns what it passes in; a function allocates what it returns; ft_*_free releases it;
 *    ft_*_free(NULL) is a no-op;
 *  - geometry is double; grids are float cells with a separate nodata mask.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CORE_H
#define FRACTERRA_CORE_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define FT_VERSION_MAJOR 0
#define FT_VERSION_MINOR 1
#define FT_VERSION_PATCH 0
#define FT_VERSION_STRING "0.1.0"

/** The library's version string, e.g. "0.1.0". */
const char *ft_version(void);

/* ------------------------------------------------------------------------------------------------
 * Errors
 * --------------------------------------------------------------------------------------------- */

enum {
    FT_OK = 0,
    FT_E_INVALID = -1,     /**< an argument or option is out of range or inconsistent */
    FT_E_NOMEM = -2,       /**< out of memory */
    FT_E_IO = -3,          /**< a file cannot be opened, read or written */
    FT_E_FORMAT = -4,      /**< a file's content is not what was expected (format, kind, field) */
    FT_E_EMPTY = -5,       /**< no data: empty layer, all-nodata grid, no points */
    FT_E_CANCELLED = -6,   /**< the progress callback asked to stop */
    FT_E_NUMERIC = -7,     /**< NaN/Inf or a numerically degenerate case */
    FT_E_UNSUPPORTED = -8  /**< a valid request this build cannot serve */
};

/** The message of the last error set on this thread ("" if none). */
const char *ft_last_error(void);
/** The code of the last error set on this thread (FT_OK if none). */
int ft_last_error_code(void);
/** A short generic description of an FT_E_* code. */
const char *ft_strerror(int code);
/** Sets the thread-local error (printf-style) and returns code, so that `return ft_error(...)` reads well. */
int ft_error(int code, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/** Clears the thread-local error. */
void ft_clear_error(void);

/* ------------------------------------------------------------------------------------------------
 * Progress: GDAL's GDALProgressFunc signature, so GDALTermProgress plugs in directly.
 * --------------------------------------------------------------------------------------------- */

/** Called with frac in [0,1]; returning 0 asks the caller to stop (it then fails with FT_E_CANCELLED). */
typedef int (*ft_progress_fn)(double frac, const char *msg, void *arg);

/** Reports progress if fn is not NULL. Returns FT_OK, or FT_E_CANCELLED (error set) if fn returned 0. */
int ft_progress(ft_progress_fn fn, void *arg, double frac, const char *msg);

/* ------------------------------------------------------------------------------------------------
 * Resource bounds: every long or large computation estimates its memory and work before it starts and
 * refuses what cannot fit, naming the option that drives it and the size it would reach.
 * --------------------------------------------------------------------------------------------- */

/** The memory bound in bytes: ft_set_memory_limit's value, else half the machine's physical memory. */
size_t ft_memory_limit(void);
/** Sets the process-wide memory bound (the CLI's --max-memory); 0 restores the default. */
void ft_set_memory_limit(size_t bytes);
/** The work bound in elementary steps (a pair, a cell visit, a vertex move): ft_set_work_limit's value,
 *  else FT_WORK_LIMIT_DEFAULT (a ruler placement, a pair or a cell visit each: well under a minute). */
double ft_work_limit(void);
#define FT_WORK_LIMIT_DEFAULT 1e9
/** Sets the process-wide work bound (the CLI's --max-work); 0 restores the default. */
void ft_set_work_limit(double steps);
/** FT_OK if an estimate of `bytes` (may be huge or infinite) fits ft_memory_limit(); else FT_E_NOMEM with
 *  "<what> would need 12.5 GB of memory, more than the 11.6 GB limit (--max-memory)". what names the
 *  option or data that drive the size, e.g. "--size 20000x20000 (4e+08 cells)". */
int ft_check_memory(double bytes, const char *what);
/** The same for work: FT_E_UNSUPPORTED (a valid request beyond the bound) with "<what> would take 3e+12 steps, more than the 2e+11 limit
 *  (--max-work)" when steps exceeds ft_work_limit(). */
int ft_check_work(double steps, const char *what);

/* ------------------------------------------------------------------------------------------------
 * Chains: open polylines and rings. A ring is stored WITHOUT repeating its first vertex
 * (closed = 1); readers drop the closing vertex, writers add it back.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double *x;   /**< n x coordinates */
    double *y;   /**< n y coordinates */
    size_t n;    /**< number of vertices */
    size_t cap;  /**< allocated capacity of x and y */
    int closed;  /**< 1 for a ring (last vertex joins the first), 0 for an open chain */
} ft_chain;

/** A new empty chain with room for cap vertices (cap may be 0). NULL (error set) if out of memory. */
ft_chain *ft_chain_create(size_t cap, int closed);
/** A new chain copied from arrays, with strides in elements (1 for plain arrays, 2 for interleaved xy). */
ft_chain *ft_chain_from_arrays(const double *x, const double *y, size_t n, size_t stride, int closed);
/** A deep copy. */
ft_chain *ft_chain_copy(const ft_chain *c);
void ft_chain_free(ft_chain *c);
/** Appends a vertex. */
int ft_chain_push(ft_chain *c, double x, double y);
/** Ensures room for at least cap vertices. */
int ft_chain_reserve(ft_chain *c, size_t cap);
/** Reverses the vertex order in place. */
void ft_chain_reverse(ft_chain *c);
/** Length along the chain, including the closing segment of a ring. */
double ft_chain_length(const ft_chain *c);
/** Number of segments: n-1 for an open chain, n for a ring (0 if n < 2). */
size_t ft_chain_segments(const ft_chain *c);
/** Signed area by the shoelace formula (positive counter-clockwise); 0 for open chains. */
double ft_chain_signed_area(const ft_chain *c);
/** Bounding box; returns FT_E_EMPTY if the chain has no vertex. */
int ft_chain_bbox(const ft_chain *c, double *xmin, double *ymin, double *xmax, double *ymax);
/** FT_OK if every coordinate is finite; FT_E_NUMERIC naming the first bad vertex otherwise. */
int ft_chain_check_finite(const ft_chain *c);
/** FT_OK if the chain has at least min_vertices vertices; FT_E_INVALID with a message otherwise. */
int ft_chain_check_min_vertices(const ft_chain *c, size_t min_vertices);

/* ------------------------------------------------------------------------------------------------
 * Layers: a collection of chains grouped into features with attributes, as read from a vector file.
 * Parts of feature f are parts[features[f].first .. features[f].first + features[f].count - 1].
 * A polygon is an outer ring followed by its inner rings (holes), all with the same `polygon` index.
 * --------------------------------------------------------------------------------------------- */

typedef enum { FT_GEOM_NONE = 0, FT_GEOM_LINE = 1, FT_GEOM_POLYGON = 2 } ft_geom_type;
typedef enum { FT_ROLE_LINE = 0, FT_ROLE_OUTER = 1, FT_ROLE_INNER = 2 } ft_part_role;
typedef enum { FT_FIELD_INT = 0, FT_FIELD_REAL = 1, FT_FIELD_STRING = 2 } ft_field_type;

typedef struct {
    char *name;
    ft_field_type type;  /**< how values are held: int64, double or string */
    int native_type;     /**< the reader's own type code (OGRFieldType), -1 if none; used to write it back */
    int width, precision;
} ft_field;

typedef struct {
    int is_null;  /**< 1 if the value is unset or null */
    int64_t i;    /**< FT_FIELD_INT */
    double r;     /**< FT_FIELD_REAL */
    char *s;      /**< FT_FIELD_STRING (owned); also dates and other native types as text */
} ft_value;

typedef struct {
    ft_chain *chain;    /**< owned by the layer */
    size_t feature;     /**< index of the feature holding this part */
    int polygon;        /**< polygon index within a multipolygon (0 otherwise) */
    ft_part_role role;
} ft_part;

typedef struct {
    int64_t fid;         /**< the source's feature id, or the index if it had none */
    ft_geom_type type;   /**< FT_GEOM_NONE for a feature without geometry */
    int multi;           /**< 1 if the source geometry was a Multi* type */
    size_t first, count; /**< its parts */
    ft_value *values;    /**< nfields values (owned) */
} ft_feature;

/* Arc-node topology: each shared boundary of adjacent polygons is stored once as an arc; every ring
 * (part) is the ordered list of its arcs, each walked forward or backward. */
typedef struct {
    size_t arc;   /**< index into arcs */
    int reversed; /**< 1 if the ring walks the arc from its last vertex to its first */
} ft_arc_ref;

typedef struct {
    ft_chain **arcs;    /**< open chains from node to node (closed if a ring has no node) */
    size_t narcs;
    int *arc_left;      /**< per arc: part index on its left (-1 if none) */
    int *arc_right;     /**< per arc: part index on its right (-1 if none) */
    ft_arc_ref **rings; /**< per part: its arc references, in ring order */
    size_t *nrings;     /**< per part: number of arc references */
    size_t nparts;
} ft_topology;

typedef struct {
    char *name;          /**< layer name (may be NULL) */
    char *crs_wkt;       /**< CRS as WKT (may be NULL) */
    ft_field *fields;
    size_t nfields;
    ft_feature *features;
    size_t nfeatures, features_cap;
    ft_part *parts;
    size_t nparts, parts_cap;
    ft_topology *topology; /**< NULL unless ft_layer_build_topology was called */
} ft_layer;

ft_layer *ft_layer_create(const char *name, const char *crs_wkt);
void ft_layer_free(ft_layer *l);
ft_layer *ft_layer_copy(const ft_layer *l);
/** Adds a field; returns its index (>= 0) or a negative error code. */
int ft_layer_add_field(ft_layer *l, const char *name, ft_field_type type, int native_type, int width,
                       int precision);
/** Index of a field by name (case-insensitive), -1 if absent. */
int ft_layer_field_index(const ft_layer *l, const char *name);
/** Adds a feature (all values null); returns its index (>= 0) or a negative error code. */
int64_t ft_layer_add_feature(ft_layer *l, int64_t fid, ft_geom_type type, int multi);
/** Adds a part to the LAST feature; the layer takes ownership of chain (even on failure). */
int ft_layer_add_part(ft_layer *l, ft_chain *chain, ft_part_role role, int polygon);
/** Sets a value of feature f (string values are copied). */
int ft_layer_set_int(ft_layer *l, size_t f, size_t field, int64_t v);
int ft_layer_set_real(ft_layer *l, size_t f, size_t field, double v);
int ft_layer_set_string(ft_layer *l, size_t f, size_t field, const char *v);
/** Total number of vertices over all parts. */
size_t ft_layer_vertex_count(const ft_layer *l);
/** Bounding box of all parts; FT_E_EMPTY if there is no vertex. */
int ft_layer_bbox(const ft_layer *l, double *xmin, double *ymin, double *xmax, double *ymax);
/** FT_OK if every coordinate is finite; FT_E_NUMERIC naming the feature, part and vertex otherwise. */
int ft_layer_check_finite(const ft_layer *l);

/** Builds the arc-node topology of the layer's rings: vertices closer than tol (0 = exact match) are
 *  the same node; an arc runs between nodes (vertices where the boundary graph does not simply
 *  continue); a boundary shared by two rings becomes one arc. Replaces any previous topology. */
int ft_layer_build_topology(ft_layer *l, double tol);
/** Rebuilds every ring from its (possibly edited) arcs, so that shared boundaries stay identical. */
int ft_layer_apply_topology(ft_layer *l);
void ft_topology_free(ft_topology *t);

/* ------------------------------------------------------------------------------------------------
 * Grids: float cells, row-major, row 0 at the top (north), as GDAL stores them.
 * Cell (col, row) covers x = gt[0] + col*gt[1] + row*gt[2], y = gt[3] + col*gt[4] + row*gt[5] at its
 * upper-left corner. Nodata is a mask: mask[i] = 1 valid, 0 nodata; mask == NULL means all valid.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t nx, ny;   /**< columns, rows */
    float *z;        /**< nx*ny cells */
    uint8_t *mask;   /**< NULL (all valid) or nx*ny bytes, 1 = valid */
    double gt[6];    /**< GDAL geotransform; default {0,1,0,0,0,1} */
    char *crs_wkt;   /**< may be NULL */
    int has_nodata;  /**< 1 if nodata_value should be written back for masked cells */
    double nodata_value;
} ft_grid;

/** A new zero-filled grid, all cells valid. */
ft_grid *ft_grid_create(size_t nx, size_t ny);
ft_grid *ft_grid_copy(const ft_grid *g);
void ft_grid_free(ft_grid *g);
/** Allocates the mask (all valid) if absent. */
int ft_grid_ensure_mask(ft_grid *g);
/** 1 if cell (col,row) is valid. */
static inline int ft_grid_is_valid(const ft_grid *g, size_t col, size_t row)
{
    return g->mask == NULL || g->mask[row * g->nx + col] != 0;
}
/** Number of valid cells. */
size_t ft_grid_count_valid(const ft_grid *g);
/** Minimum and maximum of valid cells; FT_E_EMPTY if none is valid. */
int ft_grid_minmax(const ft_grid *g, double *zmin, double *zmax);
/** Georeferenced centre of a cell. */
void ft_grid_cell_center(const ft_grid *g, double col, double row, double *x, double *y);
/** Extent of the grid (corners through the geotransform). */
void ft_grid_extent(const ft_grid *g, double *xmin, double *ymin, double *xmax, double *ymax);
/** Sets (copies) the CRS WKT; NULL clears it. */
int ft_grid_set_crs(ft_grid *g, const char *wkt);
/** Marks NaN and Inf cells as nodata; returns how many were found (>= 0). */
long ft_grid_mask_nonfinite(ft_grid *g);

/* ------------------------------------------------------------------------------------------------
 * Scattered points (x, y, z), with an optional per-point weight (confidence = 1/sigma).
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double *x, *y, *z;
    double *w;       /**< NULL or n weights */
    size_t n, cap;
    char *crs_wkt;   /**< may be NULL */
} ft_points;

ft_points *ft_points_create(size_t cap);
ft_points *ft_points_copy(const ft_points *p);
void ft_points_free(ft_points *p);
int ft_points_push(ft_points *p, double x, double y, double z);
/** Allocates the weights (all 1) if absent. */
int ft_points_ensure_weights(ft_points *p);
int ft_points_bbox(const ft_points *p, double *xmin, double *ymin, double *xmax, double *ymax);
int ft_points_set_crs(ft_points *p, const char *wkt);

/* ------------------------------------------------------------------------------------------------
 * Random numbers: a seeded generator built on GSL. Each stochastic call derives its own stream from
 * (seed, stream id) so that results do not depend on call order or thread count: give every row,
 * tile or feature its own stream id.
 * --------------------------------------------------------------------------------------------- */

typedef struct ft_rng ft_rng;

/** A generator for stream `stream` of `seed` (NULL, error set, if out of memory). */
ft_rng *ft_rng_create(uint64_t seed, uint64_t stream);
void ft_rng_free(ft_rng *r);
/** Uniform in [0, 1). */
double ft_rng_uniform(ft_rng *r);
/** Uniform integer in [0, n). */
uint64_t ft_rng_uint(ft_rng *r, uint64_t n);
/** Normal with mean 0 and standard deviation sigma. */
double ft_rng_gaussian(ft_rng *r, double sigma);
/** The underlying gsl_rng * (as void * so this header does not need GSL's). */
void *ft_rng_gsl(ft_rng *r);
/** SplitMix64 mixing of a seed and a stream id, the derivation used by ft_rng_create. */
uint64_t ft_rng_mix(uint64_t seed, uint64_t stream);

/** A small fast stream for bulk draws: xoshiro256++ (Blackman & Vigna, "Scrambled linear pseudorandom
 *  number generators", ACM TOMS 2021), held by value so a caller can keep one per row on its stack, its
 *  state filled by SplitMix64 from ft_rng_mix(seed, stream). Its numbers are not ft_rng's; the same
 *  (seed, stream) always gives the same sequence. */
typedef struct {
    uint64_t s[4];
} ft_rng_fast;
void ft_rng_fast_init(ft_rng_fast *r, uint64_t seed, uint64_t stream);
/** The next 64 random bits. */
uint64_t ft_rng_fast_next(ft_rng_fast *r);
/** Fills out[0 .. n-1] with independent standard normal deviates (256-layer ziggurat of Marsaglia &
 *  Tsang 2000, one 64-bit draw per deviate on the fast path, layer and value from disjoint bits). */
void ft_rng_fast_normals(ft_rng_fast *r, float *out, size_t n);

/* ------------------------------------------------------------------------------------------------
 * Least-squares line fits (log-log regression of every estimator).
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double slope, intercept;
    double r2;               /**< coefficient of determination */
    double stderr_slope;     /**< standard error of the slope (0 when n == 2) */
    double stderr_intercept;
    size_t first, last;      /**< index range used, inclusive */
    size_t n;                /**< number of points used */
} ft_fit;

/** Ordinary least squares y = intercept + slope*x over indices [first, last] (inclusive). Needs at
 *  least 2 points, finite values and x not all equal. */
int ft_fit_line(const double *x, const double *y, size_t first, size_t last, ft_fit *fit);
/** Same on log10(scale), log10(value); every scale and value in range must be > 0. */
int ft_fit_loglog(const double *scale, const double *value, size_t first, size_t last, ft_fit *fit);

/* ------------------------------------------------------------------------------------------------
 * Log-log tables and their segmentation, shared by every dimension estimator (Arakawa & Krotkov,
 * "Fractal modeling of natural terrain", §2.4; docs/loglog.md). An estimator measures value(scale)
 * at several scales, pushes one row per scale, sorts the table if its scales were not increasing,
 * and calls ft_loglog_fit_auto with its physical scale limits and its slope-to-D map. The result
 * keeps the whole table (local slopes, used flags) and every linear segment found.
 * All distances to a line are vertical, in log10 units of value: 0.02 means a factor 10^0.02 = 1.047.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double scale;  /**< > 0: step length, box side, lag, frequency, ... */
    double value;  /**< > 0: length, box count, variogram, power, ... */
    double count;  /**< >= 0: pairs, boxes or samples behind value (0 when it does not apply) */
    double slope;  /**< local slope d log10(value) / d log10(scale): centred difference between the two
                        neighbouring rows, one-sided at the ends; NaN while the table has one row */
    int used;      /**< 1 if the row is in the fitted range */
} ft_loglog_row;

typedef struct {
    ft_loglog_row *rows;
    size_t n, cap;
} ft_loglog;

/** A new empty table with room for cap rows (cap may be 0). NULL (error set) if out of memory. */
ft_loglog *ft_loglog_create(size_t cap);
/** A deep copy (NULL in, NULL out with an error). */
ft_loglog *ft_loglog_copy(const ft_loglog *t);
void ft_loglog_free(ft_loglog *t);
/** Appends a row (used = 0) and updates the local slopes of the last two rows. scale and value must
 *  be finite and > 0, count finite and >= 0; the error names the bad value. */
int ft_loglog_push(ft_loglog *t, double scale, double value, double count);
/** Sorts the rows by increasing scale and recomputes every local slope. */
int ft_loglog_sort(ft_loglog *t);
/** Recomputes every row's local slope (after rows were edited directly). */
void ft_loglog_update_slopes(ft_loglog *t);
/** FT_OK if the table has >= 2 rows, scales and values finite and > 0, counts finite and >= 0 and
 *  scales strictly increasing; otherwise an error naming the row and the value. */
int ft_loglog_check(const ft_loglog *t);
/** Robust noise estimate of rows [first, last] of a checked table, in log10 units of value: each
 *  interior point's vertical distance to the chord through its two neighbours, scaled to unit
 *  variance for i.i.d. noise, then 1.4826 * median absolute deviation. A straight table gives 0; a
 *  break in slope moves one distance only, so it barely moves the median. 0 if fewer than 3 rows. */
double ft_loglog_noise(const ft_loglog *t, size_t first, size_t last);

/** How a slope becomes a dimension, D = a + b * slope, and the interval D can physically take. */
typedef struct {
    double a, b;
    double d_min, d_max; /**< the estimator's interval of D: [1, 2] for chains and profiles, [2, 3] for
                              surfaces. ft_loglog_fit_auto never chooses a run whose D lies outside it by
                              more than opts.bounds_tol. d_min == d_max == 0: no bounds (what a
                              two-member initializer {a, b} leaves) */
} ft_dim_map;
#define FT_DIM_MAP_DIVIDER {1.0, -1.0, 1.0, 2.0}  /**< chain length L(step) ~ step^(1 - D) */
#define FT_DIM_MAP_BOXCOUNT {0.0, -1.0, 1.0, 3.0} /**< boxes N(side) ~ side^-D over any set of
                                                       topological dimension >= 1 in the plane or space */
#define FT_DIM_MAP_BOXCOUNT_LINE {0.0, -1.0, 1.0, 2.0}    /**< boxes over a chain, boundary or built-up
                                                               area in the plane */
#define FT_DIM_MAP_BOXCOUNT_SURFACE {0.0, -1.0, 2.0, 3.0} /**< cubes N(side) ~ side^-D over a surface */
#define FT_DIM_MAP_PRISM {2.0, -1.0, 2.0, 3.0}    /**< surface area A(step) ~ step^(2 - D) */
#define FT_DIM_MAP_VARIOGRAM_SURFACE {3.0, -0.5, 2.0, 3.0} /**< gamma(lag) ~ lag^(2H), D = 3 - H */
#define FT_DIM_MAP_INCREMENT_SURFACE {3.0, -1.0, 2.0, 3.0} /**< E|dz| or sd(dz) at distance d ~ d^H,
                                                                D = 3 - H */
#define FT_DIM_MAP_SPECTRUM_SURFACE {4.0, 0.5, 2.0, 3.0}   /**< radial power P(f) ~ f^-beta (scale =
                                                                frequency), D = (8 - beta) / 2 */
#define FT_DIM_MAP_VARIOGRAM_PROFILE {2.0, -0.5, 1.0, 2.0} /**< profile gamma(lag) ~ lag^(2H), D = 2 - H */
#define FT_DIM_MAP_INCREMENT_PROFILE {2.0, -1.0, 1.0, 2.0} /**< profile E|dz| or sd(dz) ~ d^H, D = 2 - H */
#define FT_DIM_MAP_SPECTRUM_PROFILE {2.5, 0.5, 1.0, 2.0}   /**< 1-D power P(f) ~ f^-beta of a profile,
                                                                beta = 2H + 1, D = (5 - beta) / 2 */

typedef enum {
    FT_LOGLOG_ILS = 0,    /**< iterative least squares: the longest run within tol of its LS line */
    FT_LOGLOG_MINIMAX = 1 /**< minimax polyline: the longest segment within width of its minimax line */
} ft_loglog_method;

typedef struct {
    ft_loglog_method method; /**< how ft_loglog_fit_auto chooses the range; default FT_LOGLOG_ILS */
    double tol;        /**< ILS: a point is on the line if its distance to it is at most
                            max(tol, tol_sigma * noise); > 0; default 0.02 */
    double width;      /**< minimax: every point of a segment lies within max(width / 2,
                            tol_sigma * noise) of the segment's minimax line; > 0; default 0.04 */
    double tol_sigma;  /**< multiple of ft_loglog_noise widening both tolerances on noisy tables;
                            >= 0 (0 = absolute tolerances only); default 3 */
    size_t min_points; /**< fewest rows in the chosen range; >= 2; default 3 */
    int max_iter;      /**< ILS: iterations per start; >= 1; default 50 */
    double min_span;   /**< fewest scale factor scale_hi / scale_lo a chosen run spans; >= 1 (1 = any);
                            default 4: a step of a staircase table is never taken for the trend */
    double bounds_tol; /**< how far outside [map.d_min, map.d_max] the D of a chosen run may lie; >= 0;
                            default 0.05 */
} ft_loglog_opts;
#define FT_LOGLOG_OPTS_DEFAULT {FT_LOGLOG_ILS, 0.02, 0.04, 3.0, 3, 50, 4.0, 0.05}

/** One linear segment of a log-log table. */
typedef struct {
    size_t first, last; /**< inclusive row range; neighbouring segments may share one row */
    size_t n;           /**< rows in the segment */
    double scale_lo, scale_hi;
    double slope, intercept; /**< least squares on (log10 scale, log10 value) */
    double D;           /**< map.a + map.b * slope */
    double r2;          /**< r² of the least-squares line */
    double stderr_D;    /**< |map.b| * standard error of the slope (0 for 2 rows) */
    double max_err;     /**< fitting error: half-width of the thinnest band holding the rows, i.e. the
                             largest distance to the minimax (Chebyshev) line, log10 units */
    double D_minimax;   /**< map applied to the slope of the minimax line */
} ft_loglog_segment;

#define FT_LOGLOG_NONE ((size_t)-1)
/** ft_dim_result.segmentation when no straight run qualified and D is the whole window's fit. */
#define FT_LOGLOG_WHOLE_RANGE "whole range (no straight segment)"

/** A dimension with everything needed to judge it and to print an estimator's JSON (docs/loglog.md). */
typedef struct {
    const char *method;       /**< static name, "range", "ils" or "minimax"; an estimator may point it
                                   at its own static name ("divider") for its JSON "method" */
    const char *segmentation; /**< static name of how the range was chosen: "range", "ils", "minimax",
                                   or FT_LOGLOG_WHOLE_RANGE (no run qualified: see warning) */
    double D;                 /**< map.a + map.b * fit.slope */
    double r2;                /**< r² of the least-squares fit over the used rows */
    double stderr_D;          /**< |map.b| * fit.stderr_slope */
    double range[2];          /**< scales of the first and last used rows */
    double max_err;           /**< fitting error of the used rows (see ft_loglog_segment.max_err) */
    double noise;             /**< ft_loglog_noise over the rows that were searched */
    double tol;               /**< tolerance ILS used (0 if ILS did not run) */
    double width;             /**< width minimax used, 2 x its half-width (0 if it did not run) */
    ft_fit fit;               /**< least squares of log10 value on log10 scale; fit.first..fit.last are
                                   the used rows */
    ft_dim_map map;
    ft_loglog *table;         /**< owned copy of the input table, used flags set */
    ft_loglog_segment *segments; /**< owned; minimax segments by increasing scale (NULL if none) */
    size_t nsegments;
    size_t best;              /**< index in segments of the one that gave D, or FT_LOGLOG_NONE */
    char *warning;            /**< owned; NULL, or one sentence for the user (the CLI prints it on
                                   stderr): why D is the whole window's fit, or that D lies outside the
                                   map's bounds */
} ft_dim_result;

void ft_dim_result_free(ft_dim_result *r);
void ft_loglog_segments_free(ft_loglog_segment *s);

/** Least squares over the rows with lo <= scale <= hi (0 = no limit on that side; limits are inclusive
 *  within a relative 1e-9, so a limit equal to a computed scale keeps that row); needs >= 2 rows. A D
 *  outside the map's bounds (by more than the default bounds_tol) is returned with a warning. */
int ft_loglog_fit_range(const ft_loglog *t, double lo, double hi, const ft_dim_map *map,
                        ft_dim_result **out);
/** Iterative least squares over the whole table: from the whole table and from every run of
 *  min_points rows, fit a line, keep the longest contiguous run of rows within the tolerance of it,
 *  refit, until the run stops changing; the longest qualifying converged run wins (ties: smaller rms;
 *  qualifying and the whole-table fallback as in ft_loglog_fit_auto). */
int ft_loglog_segment_ils(const ft_loglog *t, const ft_loglog_opts *opts, const ft_dim_map *map,
                          ft_dim_result **out);
/** Minimax polyline over the whole table: every row is covered by segments whose rows lie within the
 *  half-width of their minimax line, chosen longest first (ties: smaller max_err). Release the
 *  segments with ft_loglog_segments_free. */
int ft_loglog_segment_minimax(const ft_loglog *t, const ft_loglog_opts *opts, const ft_dim_map *map,
                              ft_loglog_segment **segments, size_t *nsegments);
/** The estimators' entry: restricts to lo_limit <= scale <= hi_limit (0 = no limit), segments those
 *  rows by minimax (all segments kept in the result), and fits D over the range opts->method picks:
 *  the longest qualifying ILS run, or the longest qualifying minimax segment (ties: smaller max_err).
 *  A run qualifies if it has >= min_points rows, spans a scale factor >= min_span and its D lies in
 *  [map.d_min, map.d_max] within bounds_tol. If straight runs exist but none qualifies, D is the
 *  least-squares fit over the whole window, segmentation = FT_LOGLOG_WHOLE_RANGE and warning says why. */
int ft_loglog_fit_auto(const ft_loglog *t, double lo_limit, double hi_limit, const ft_loglog_opts *opts,
                       const ft_dim_map *map, ft_dim_result **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_CORE_H */
