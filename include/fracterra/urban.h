/* fracterra — urban.h: urban morphology. Box-counting dimension of polygon layers (land-use classes) and of
 * classified rasters, the regression of ln(area) on D across years, and the midpoint-subdivision generator
 * that simulates a boundary with detail of a given dimension.
 *
 * Paper: Zhang Yi, Yu Jie, Fan Wei (2008), "Fractal features of urban morphology and simulation of urban
 * boundary", Geo-spatial Information Science 11(2): box counting §1.1 (Eqs. 1-4), the
 * regression §1.2 (Eq. 5), the generator §2 (Eqs. 6-13). docs/urban-boxcount.md and docs/urban-boundary.md
 * hold the equations, the readings of the garbled passages and the limits.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_URBAN_H
#define FRACTERRA_URBAN_H

#include <stddef.h>
#include <stdint.h>

#include "core.h"
#include "line.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------------
 * Box-counting dimension of polygons (§1.1, Eqs. 1-4: N(r) ~ r^-D, D = -slope of log N on log r).
 * Counts are exact from the vector geometry (no rasterization at a resolution of its own). Cells are
 * half-open squares [x0 + i r, x0 + (i+1) r) x [y0 + j r, y0 + (j+1) r), as in ft_line_box_count.
 *  - FT_AREA_BOUNDARY: cells holding a point of a ring (outer or inner), counted by ft_line_box_count's
 *    exact cell traversal;
 *  - FT_AREA_AREA: cells touching the polygons' interior = the cells whose inside (the open square) a
 *    ring passes through, plus the cells whose centre is inside (even-odd over the polygon's rings), found
 *    by a scanline through the centres of each row of cells: a cell no ring passes through lies wholly
 *    inside or wholly outside, so its centre decides. A cell that only touches a polygon along its edge
 *    or at a corner is not counted (a filled square aligned with the grid covers exactly (side / r)²
 *    cells); overlapping polygons count their cells once.
 * At each box side r the count is the mean (default; unbiased for a randomly placed grid) or the fewest
 * (fewest = 1; biased upward where the largest boxes hold few counts) over offsets x offsets grid origins
 * shifted by multiples of r / offsets from the lower-left corner of the polygons' bounding box.
 * The log-log table (one row per size) is fitted by the shared module (ft_loglog_fit_auto within the
 * size range, or ft_loglog_fit_range over all of it), so the result carries the whole table.
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_AREA_BOUNDARY = 0, /**< boxes crossed by the boundary (the rings) */
    FT_AREA_AREA = 1      /**< boxes touching the polygons' interior */
} ft_area_what;

/** "boundary" or "area" (the CLI's --what and the JSON's "what"); "unknown" otherwise. */
FT_API const char *ft_area_what_name(ft_area_what w);
/** Parses "boundary" or "area" (case-insensitive); FT_E_INVALID naming the word otherwise. */
FT_API int ft_area_what_parse(const char *name, ft_area_what *w);

typedef struct {
    size_t struct_size; /**< sizeof(ft_area_dim_opts); see FT_OPTS in core.h */
    ft_area_what what;   /**< default FT_AREA_BOUNDARY */
    const double *cells; /**< explicit box sides in map units (ncells > 0): every one is counted (any
                              order, duplicates an error); NULL = a geometric series */
    size_t ncells;
    double min_cell;     /**< series: smallest box side; 0 = automatic (docs/urban-boxcount.md) */
    double max_cell;     /**< series: largest box side; 0 = automatic */
    int nscales;         /**< series: number of sizes, [3, 1000]; 0 = default 12 */
    int offsets;         /**< grid origins per axis (offsets x offsets), [1, 16]; default 4 */
    ft_loglog_opts fit;  /**< segmentation of the log-log table */
    int fit_whole_range; /**< 1: fit every size, no segmentation; default 0 */
    int fewest;          /**< 1: the fewest count over the origins; 0 (default): their mean */
    ft_progress_fn progress;
    void *progress_arg;
} ft_area_dim_opts;
#define FT_AREA_DIM_OPTS_DEFAULT                                                                                     \
    {.struct_size = sizeof(ft_area_dim_opts), .what = FT_AREA_BOUNDARY, .cells = NULL, .ncells = 0, .min_cell = 0.0, \
     .max_cell = 0.0, .nscales = 0, .offsets = 4, .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_whole_range = 0, .fewest = 0,  \
     .progress = NULL, .progress_arg = NULL}

/** Box-counting dimension of the polygons of features[0 .. nfeatures) of the layer (features == NULL: every
 *  feature; nfeatures is then ignored). Every selected feature must be a polygon (FT_GEOM_POLYGON) or
 *  have no geometry (skipped); coordinates must be finite. The result's method is "box-boundary" or
 *  "box-area"; each table row holds the side, the count (value and count) and the local slope.
 *  *out is allocated; free with ft_dim_result_free. */
FT_API int ft_urban_dim_area(const ft_layer *l, const size_t *features, size_t nfeatures, const ft_area_dim_opts *o,
                      ft_dim_result **out);

/** The same on a classified raster (one class per cell value): the set is the valid cells whose value
 *  equals class_value (compared as float, the grid's cell type); FT_AREA_AREA counts boxes holding a cell
 *  of the class, FT_AREA_BOUNDARY boxes holding a boundary cell of the class (a class cell with a
 *  4-neighbour outside the class: another value, nodata or off the grid). Box sides are whole numbers s
 *  of cells (the options' sides in map units are rounded to cells, duplicates after rounding dropped;
 *  automatic range: 1 cell to 1/48 (boundary) or 1/128 (area) of the class's bounding-box diagonal, at
 *  least 8 cells or a quarter of the diagonal); the
 *  table's scale is s times the
 *  cell side sqrt(|gt[1] gt[5] - gt[2] gt[4]|); offsets are multiples of s / offsets cells. */
FT_API int ft_urban_dim_area_grid(const ft_grid *classes, double class_value, const ft_area_dim_opts *o,
                           ft_dim_result **out);

/** What a class holds, for the per-year table (the paper's Tables 1 and 2). */
typedef struct {
    size_t nfeatures; /**< polygon features counted (vector); 0 for a grid */
    size_t npolygons; /**< polygons (outer rings); for a grid, 4-connected patches of class cells */
    size_t nholes;    /**< inner rings (vector); for a grid 0 */
    size_t ncells;    /**< class cells (grid); 0 for a vector layer */
    double area;      /**< outer ring areas minus inner ring areas (map units²); grid: cells x cell area */
    double perimeter; /**< total ring length; grid: length of the cell edges between class and non-class */
} ft_urban_stats;

/** Area, perimeter and counts of the polygons of features[0 .. nfeatures) (NULL = every feature); features
 *  that are not polygons are not counted. */
FT_API int ft_urban_layer_stats(const ft_layer *l, const size_t *features, size_t nfeatures, ft_urban_stats *out);
/** The same for the cells of one class of a classified raster. */
FT_API int ft_urban_grid_stats(const ft_grid *classes, double class_value, ft_urban_stats *out);

/** A classification's usual number of classes at most: a raster with more distinct values is continuous. */
#define FT_URBAN_MAX_CLASSES 1000
/** The classes of a classified raster: the distinct values of its valid cells, increasing, into *values
 *  (malloc'd, free()) and *n. FT_E_EMPTY if no cell is valid; FT_E_INVALID, saying it does not look like a
 *  classified raster, if a value is not a whole number or there are more than max_classes of them. */
FT_API int ft_urban_grid_classes(const ft_grid *g, size_t max_classes, float **values, size_t *n);

/** The features of a layer grouped by the value of one field (residential, industrial, ...). */
typedef struct {
    char *label;       /**< the value as text: strings as they are, integers "%lld", reals "%.15g" */
    size_t *features;  /**< indices into l->features, increasing */
    size_t n;
} ft_urban_class;

typedef struct {
    ft_urban_class *classes; /**< sorted by value: numerically for integer and real fields, else strcmp */
    size_t n;
    size_t nnull;            /**< polygon features whose value is null (in no class) */
} ft_urban_classes;

/** Groups the layer's polygon features (FT_GEOM_POLYGON) by the value of field `field` (name,
 *  case-insensitive; FT_E_INVALID naming it and listing the layer's fields if absent). Features of other
 *  types are left out. *out is allocated; free with ft_urban_classes_free. */
FT_API int ft_urban_classes_by_field(const ft_layer *l, const char *field, ft_urban_classes **out);
FT_API void ft_urban_classes_free(ft_urban_classes *c);

/* ------------------------------------------------------------------------------------------------
 * Regression across years (§1.2, Eq. 5: ln Area = a + b D): ordinary least squares of y (or ln y) on x.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t n;                /**< rows */
    int log_y;               /**< 1 if y was replaced by ln y */
    double slope, intercept; /**< y = intercept + slope * x */
    double r;                /**< Pearson correlation of x and (ln) y, signed like the slope */
    double r2;               /**< r² */
    double stderr_slope;     /**< sqrt(s² / Sxx), s² = residual sum of squares / (n - 2) */
    double stderr_intercept; /**< sqrt(s² (1/n + mean(x)² / Sxx)) */
    double stderr_r;         /**< sqrt((1 - r²) / (n - 2)), the standard error of r under rho = 0 (the
                                  denominator of the t test; equal to r / t) */
    double t;                /**< r sqrt((n - 2) / (1 - r²)) = slope / stderr_slope (INFINITY if r² = 1) */
    double p_value;          /**< two-sided P(|T| > |t|), T Student with n - 2 degrees of freedom */
} ft_urban_regression;

/** Fits y = intercept + slope * x over n >= 3 rows (log_y: ln y instead of y, every y > 0). x and y
 *  finite, x not all equal, y not all equal; errors name the row and the value. On the paper's Table 2
 *  (ln area on D) r = 0.954. */
FT_API int ft_urban_regress(const double *x, const double *y, size_t n, int log_y, ft_urban_regression *out);

/* ------------------------------------------------------------------------------------------------
 * Midpoint-subdivision generator (§2, Eqs. 6-13). A segment B -> C of length r is replaced by the two
 * legs B -> N -> C; N sits at the perpendicular offset L = (r/2) tan a from the midpoint, on the side
 * J = +1 (left of B -> C) or -1 (right) drawn at random per segment, with cos a = 2^(1/D - 1) (Eq. 9:
 * two legs of r / (2 cos a) each give D = ln 2 / ln(2 cos a), Eqs. 7-8). Eq. 10 places N at
 *   X_N = (X_B + X_C)/2 - J L sin(beta) + R_x,   Y_N = (Y_B + Y_C)/2 + J L cos(beta) + R_y
 * (beta the azimuth of B -> C measured from the x axis), R_x and R_y independent and uniform in
 * [-jitter L, +jitter L]: the apex moves within the square of half-side jitter L centred on its exact
 * place, sides parallel to the map axes. A segment is replaced while min < r <= max, and its legs in turn
 * (the iteration continues towards min); a segment longer than max is kept as it is (walls of regular
 * parcels). Input vertices never move, so open chains keep their end points and coverages their nodes.
 *
 * Randomness: every input segment draws from its own stream, keyed by (seed, stream, the segment's two
 * end points in canonical order), and each generated segment's draws derive from its parent's key
 * (ft_rng_mix). The output therefore does not depend on processing order, on the chain's direction or on
 * where the segment sits in the layer: the same segment in two rings (or an arc of a coverage) gets the
 * same detail, and the same seed gives bit-identical output.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_boundary_opts); see FT_OPTS in core.h */
    double dim;      /**< D in (1, 2); no default (0 is rejected): the measured dimension of the boundary
                          (the paper's Table 1 gives 1.19-1.23 for Wuhan's boundaries) */
    double min;      /**< > 0, map units: segments no longer than this are not replaced (the paper: set by
                          the change of map scale); no default (0 is rejected); see
                          FT_BOUNDARY_MIN_FRACTION */
    double max;      /**< >= min, map units: segments longer than this are kept unchanged; 0 = the input
                          chain's average chord length (Eqs. 11-13; ft_urban_boundary_layer uses the layer's) */
    double jitter;   /**< half-side of the apex square (Eq. 10's R) as a fraction of L, in
                          [0, ft_urban_jitter_max(dim)); default 0 (the exact generator) */
    uint64_t seed;   /**< default 1 */
    uint64_t stream; /**< an extra stream id mixed into every segment's key (give separate layers
                          separate ids if they must differ); default 0 */
    int allow_crossings; /**< ft_urban_boundary_layer only: 0 (default) generates level by level through the
                              crossing guard (boundary_guarded.c): no leg crosses or touches another segment
                              of the layer; 1: the raw depth-first generator (boundary.c) */
} ft_boundary_opts;
#define FT_BOUNDARY_OPTS_DEFAULT                                                                                     \
    {.struct_size = sizeof(ft_boundary_opts), .dim = 0.0, .min = 0.0, .max = 0.0, .jitter = 0.0, .seed = 1,          \
     .stream = 0, .allow_crossings = 0}

/** A suggested min when no target scale is known: this fraction of the average chord length. */
#define FT_BOUNDARY_MIN_FRACTION 0.1

/** The generator's base angle a (radians) for dimension D: acos(2^(1/D - 1)) (Eq. 9); 0 at D = 1, pi/4 at
 *  D = 2; NaN outside [1, 2]. */
FT_API double ft_urban_angle_for_dim(double D);
/** The inverse: D = ln 2 / ln(2 cos a) (Eq. 8), for a in [0, pi/4]; NaN outside. */
FT_API double ft_urban_dim_for_angle(double a);
/** The largest jitter (exclusive) for dimension D: below it every leg is shorter than its segment by a fixed
 *  factor whatever the draws, so the iteration ends: (1 - 1/(2 cos a)) sqrt(2) / tan a, capped at
 *  1/sqrt(2) (which keeps the apex on side J). NaN outside (1, 2). */
FT_API double ft_urban_jitter_max(double D);
/** The average chord length of a chain, Eqs. 11-13: its length over its number of segments (a ring's
 *  closing segment included); 0 if it has fewer than 2 vertices. */
FT_API double ft_urban_chord_avg(const ft_chain *c);
/** The average chord length over every part of the layer (every chord of every chain and ring). */
FT_API int ft_urban_layer_chord_avg(const ft_layer *l, double *avg);

/** Runs the generator on one chain (open or ring, >= 2 vertices, finite coordinates). *out is a new chain
 *  with the same closed flag; every input vertex is kept, in order. Fails with FT_E_INVALID naming the
 *  value for dim outside (1, 2), min <= 0, max < min, jitter outside [0, ft_urban_jitter_max(dim)), NaN,
 *  or output beyond FT_BOUNDARY_MAX_VERTICES. */
FT_API int ft_urban_boundary(const ft_chain *in, const ft_boundary_opts *o, ft_chain **out);

/** The most vertices one output chain may have (about 4 GB of coordinates). */
#define FT_BOUNDARY_MAX_VERTICES ((size_t)1 << 28)

/** ft_urban_boundary as an ft_line_op (opts: const ft_boundary_opts *), for ft_line_apply_layer: on a
 *  coverage it runs once per arc with the arc's end points (nodes) fixed; max = 0 means each arc's own
 *  average chord. */
FT_API int ft_urban_op_boundary(const ft_chain *in, const void *opts, ft_chain **out);

/** What ft_urban_boundary_layer did, for the CLI's JSON. */
typedef struct {
    size_t vertices_in, vertices_out;
    double max_used;  /**< the max applied (the layer's average chord if o->max was 0) */
    size_t segments_kept; /**< input segments longer than max, kept unchanged (over every part) */
    ft_line_guard_stats guard; /**< apexes the crossing guard moved only part of the way or not at all */
} ft_boundary_info;

/** Runs the generator on every part of the layer in place: with max = 0 the layer's average chord
 *  (ft_urban_layer_chord_avg) is the max of every part; with coverage != 0 and rings in the layer, on the
 *  arc-node topology, so adjacent polygons keep identical shared boundaries. Unless o->allow_crossings, level
 *  by level through the crossing guard (every segment in the window split at once, each apex reduced if its
 *  legs would cross: the output is simple and crosses no other part). On failure the layer is unchanged.
 *  info may be NULL. */
FT_API int ft_urban_boundary_layer(ft_layer *l, const ft_boundary_opts *o, int coverage, ft_boundary_info *info);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_URBAN_H */
