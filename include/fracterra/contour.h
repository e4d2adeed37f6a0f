/* fracterra — contour.h: the seed-contour mountain generator (Misawa, Chiba & Saito):
 * polygon shrinking with three corner joins and the paper's d' join, random midpoint displacement,
 * P-type Fourier descriptor phase randomization, the improved method, contour stacks and the DEM they
 * define.
 *
 * Conventions: a polygon's outer ring is counter-clockwise, its holes clockwise (y up, as map
 * coordinates are); rings are ft_chain with closed = 1 and no repeated closing vertex.
 * docs/contour-mountain.md holds the equations, parameters and figures.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CONTOUR_H
#define FRACTERRA_CONTOUR_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------------
 * Polygon sets: the contour(s) of one elevation, possibly several islands, each possibly with holes.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    ft_chain *outer;   /**< counter-clockwise ring */
    ft_chain **holes;  /**< clockwise rings inside outer */
    size_t nholes;
} ft_polygon;

typedef struct {
    ft_polygon *polys;
    size_t n, cap;
} ft_polygon_set;

FT_API ft_polygon_set *ft_polygon_set_create(void);
FT_API ft_polygon_set *ft_polygon_set_copy(const ft_polygon_set *s);
FT_API void ft_polygon_set_free(ft_polygon_set *s);
/** Appends a polygon, taking ownership of outer and holes (holes array included; may be NULL when
 *  nholes == 0). Rings are reoriented to the convention. On failure nothing is taken. */
FT_API int ft_polygon_set_add(ft_polygon_set *s, ft_chain *outer, ft_chain **holes, size_t nholes);
/** Total area (outer areas minus hole areas), ground units². */
FT_API double ft_polygon_set_area(const ft_polygon_set *s);
/** Total vertices over every ring. */
FT_API size_t ft_polygon_set_vertices(const ft_polygon_set *s);
/** The polygons of a layer: polygon features (outer + inner parts), or line features whose parts are
 *  closed rings (the first and last vertices equal, or the chain flagged closed), each ring one outer.
 *  FT_E_EMPTY if there is none; FT_E_FORMAT naming the feature for an open line. */
FT_API int ft_polygon_set_from_layer(const ft_layer *l, ft_polygon_set **out);

/** 1 if every ring is simple (no self-intersection), outer rings are counter-clockwise with a positive
 *  area, holes clockwise inside their outer ring, and no two polygons overlap (GEOS validity);
 *  0 otherwise, with the reason in *why (thread-local text, may be NULL); 2 if the question could not be
 *  decided (NULL set, GEOS context or check failure: ft_last_error() says why), as GEOS's predicates. */
FT_API int ft_polygon_set_is_valid(const ft_polygon_set *s, const char **why);

/** 1 if every polygon of inner lies inside outer (GEOS covers), 0 otherwise, 2 if it could not be decided
 *  (NULL set, rings GEOS rejects, GEOS failure: ft_last_error() says why), as GEOS's predicates. */
FT_API int ft_polygon_set_within(const ft_polygon_set *inner, const ft_polygon_set *outer);

/* ------------------------------------------------------------------------------------------------
 * Polygon shrinking (§2–3): offset every edge inward by d, join the corners, node, keep the faces
 * the offset curve winds around counter-clockwise, drop tiny faces. d < 0 grows the polygons
 * (the mountain's foot); grown polygons that meet are merged.
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_JOIN_DPRIME = 0, /**< the paper's join: one point on the angle bisector at distance d' from the
                             vertex, or the intersection of the extended offset lines, whichever is
                             nearer to the vertex (default) */
    FT_JOIN_MITRE = 1,  /**< extension lines: the intersection of the extended offset lines */
    FT_JOIN_BEVEL = 2,  /**< a straight connection between the offset edges' ends */
    FT_JOIN_ROUND = 3   /**< an arc of radius d: the exact set of points at distance d (GEOS buffer) */
} ft_contour_join;

typedef struct {
    size_t struct_size; /**< sizeof(ft_shrink_opts); see FT_OPTS in core.h */
    ft_contour_join join;  /**< default FT_JOIN_DPRIME */
    double dprime;         /**< d' as a multiple of d, >= 1; default 1.2 (1.4 looked most real) */
    int quad_segs;         /**< round join: segments per quarter circle, >= 1; default 8 */
    double min_area;       /**< faces smaller than min_area x d² are dropped, >= 0; default 0.5 */
} ft_shrink_opts;
#define FT_SHRINK_OPTS_DEFAULT                                                                                       \
    {.struct_size = sizeof(ft_shrink_opts), .join = FT_JOIN_DPRIME, .dprime = 1.2, .quad_segs = 8, .min_area = 0.5}

FT_API const char *ft_contour_join_name(ft_contour_join j);
/** "dprime", "mitre" (or "miter"), "bevel", "round"; FT_E_INVALID naming the text otherwise. */
FT_API int ft_contour_join_parse(const char *name, ft_contour_join *j);

/** The polygons of `in` shrunk by d (> 0) or grown by -d (< 0); d must be finite and non-zero. The
 *  result may be empty (n == 0): the contour vanished. The result is valid (ft_polygon_set_is_valid). */
FT_API int ft_contour_shrink(const ft_polygon_set *in, double d, const ft_shrink_opts *opts, ft_polygon_set **out);

/** Twists and loops (§4.4): nodes the rings, keeps the faces of positive winding number (a
 *  counter-clockwise loop of an outer ring, a clockwise one of a hole), drops faces smaller than
 *  min_area (ground units², >= 0). The result is valid; it may be empty. */
FT_API int ft_contour_clean(const ft_polygon_set *in, double min_area, ft_polygon_set **out);

/* ------------------------------------------------------------------------------------------------
 * Shape operators on one ring (§4.1, §4.2) and their companion.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_midpoint_opts); see FT_OPTS in core.h */
    double max_seg;       /**< split segments longer than this (ground units, > 0): the paper's 2 d0 */
    double max_offset;    /**< d'': the largest displacement (ground units, >= 0) */
    double theta_min;     /**< degrees, 0 <= theta_min <= theta_max < 90; default 20 */
    double theta_max;     /**< default 40 */
} ft_midpoint_opts;
#define FT_MIDPOINT_OPTS_DEFAULT                                                                                     \
    {.struct_size = sizeof(ft_midpoint_opts), .max_seg = 0.0, .max_offset = 0.0, .theta_min = 20.0,                  \
     .theta_max = 40.0}

/** Random midpoint displacement (§4.1): every segment longer than max_seg (length 2l) is split at its
 *  midpoint, displaced perpendicularly to a random side by min(max_offset, |l tan theta|), theta uniform
 *  in [theta_min, theta_max], recursively until every segment is at most max_seg. Works on rings and
 *  open chains. The same (seed, stream) gives the same chain. */
FT_API int ft_contour_midpoint_displace(const ft_chain *in, const ft_midpoint_opts *opts, uint64_t seed,
                                 uint64_t stream, ft_chain **out);

typedef struct {
    size_t struct_size; /**< sizeof(ft_fourier_opts); see FT_OPTS in core.h */
    int n;        /**< resample the ring to n equal segments, >= 8; default 1024 */
    int f0;       /**< randomize the phases of the components with |k| >= f0, 1 <= f0 <= n/2;
                       default 256 */
} ft_fourier_opts;
#define FT_FOURIER_OPTS_DEFAULT {.struct_size = sizeof(ft_fourier_opts), .n = 1024, .f0 = 256}

/** P-type Fourier descriptor phase randomization (§4.2): resample the ring to n equal segments, take
 *  the DFT c(k) of the unit edge vectors w(j), give every component with |k| >= f0 a uniform random
 *  phase keeping its magnitude, invert and rebuild the closed ring with the original perimeter,
 *  centroid and orientation (the closure error is spread evenly). The result has n vertices; it may
 *  self-intersect (ft_contour_clean removes the loops). */
FT_API int ft_contour_fourier_randomize(const ft_chain *ring, const ft_fourier_opts *opts, uint64_t seed,
                                 uint64_t stream, ft_chain **out);

/** Removes nearly collinear vertices: a vertex whose turning angle is below angle_deg (degrees, >= 0)
 *  is dropped, greedily along the ring, keeping at least 3 vertices of a ring. */
FT_API int ft_contour_remove_collinear(const ft_chain *in, double angle_deg, ft_chain **out);

/* ------------------------------------------------------------------------------------------------
 * The mountain: every contour from seed contour(s) (§3–4.3).
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_MOUNTAIN_SIMPLE = 0,   /**< repeated shrinking (and growing below the seed) */
    FT_MOUNTAIN_MIDPOINT = 1, /**< midpoint displacement then shrink, per level */
    FT_MOUNTAIN_FOURIER = 2,  /**< shrink then phase randomization, per level */
    FT_MOUNTAIN_IMPROVED = 3  /**< midpoint, shrink, phase randomization, collinear removal (§4.3) */
} ft_mountain_method;

typedef struct {
    size_t struct_size; /**< sizeof(ft_mountain_opts); see FT_OPTS in core.h */
    ft_mountain_method method;  /**< default FT_MOUNTAIN_IMPROVED */
    double interval;            /**< elevation step between contours, > 0; default 10 */
    double spacing;             /**< d: horizontal shrink per contour, > 0 (ground units); 0 (default) =
                                     the documented fraction of the seed's size */
    double seed_elevation;      /**< elevation of the seed contour(s); default 0 */
    int levels_up;              /**< contours above the seed, >= 0; -1 (default) = until they vanish
                                     (at most 10000) */
    int levels_down;            /**< contours below the seed (grown outward), >= 0; default 0 */
    ft_shrink_opts shrink;      /**< join and d' (dprime is a multiple of d); when shrink.dprime is 0 the
                                     method's default applies (ft_mountain_default_dprime) */
    double dsecond;             /**< d'' as a multiple of d, >= 0; default 0.5 */
    double theta_min, theta_max;/**< degrees; default 20, 40 */
    ft_fourier_opts fourier;    /**< default n = 1024, f0 = 256 */
    double collinear_deg;       /**< collinear removal threshold, degrees; default as documented */
    int match_dim;              /**< improved method: 1 (default) scales the angle range [theta_min,
                                     theta_max] ring by ring so that each displaced ring has the seed's
                                     divider dimension over rulers d0 .. 4 d0 (§5: theta from the fractal
                                     dimension; docs/contour-mountain.md); 0 uses the range as given (the
                                     paper's fixed angles) */
    int allow_crossings;        /**< 0 (default): the midpoint displacements and the phase randomizations
                                     are guarded (a move that would cross another ring of the level or the
                                     level below is reduced to half, a quarter or none); 1: the raw
                                     algorithm (crossings repaired afterwards by the clean and nesting
                                     steps only) */
    uint64_t seed;              /**< default 1 */
    ft_progress_fn progress;
    void *progress_arg;
} ft_mountain_opts;
#define FT_MOUNTAIN_OPTS_DEFAULT                                                                                     \
    {.struct_size = sizeof(ft_mountain_opts), .method = FT_MOUNTAIN_IMPROVED, .interval = 10.0, .spacing = 0.0,      \
     .seed_elevation = 0.0, .levels_up = -1, .levels_down = 0, .shrink = {.struct_size = sizeof(ft_shrink_opts),     \
     .join = FT_JOIN_DPRIME, .dprime = 0.0, .quad_segs = 8, .min_area = 0.5}, .dsecond = 0.5, .theta_min = 20.0,     \
     .theta_max = 40.0, .fourier = FT_FOURIER_OPTS_DEFAULT, .collinear_deg = 0.0, .match_dim = 1,                    \
     .allow_crossings = 0, .seed = 1, .progress = NULL, .progress_arg = NULL}

FT_API const char *ft_mountain_method_name(ft_mountain_method m);
/** The d' (a multiple of d) ft_mountain_generate applies when shrink.dprime is 0: 3 for the improved
 *  method (Misawa et al. §4.3), 1.4 for midpoint and fourier (their Figs. 12 and 15), 1.2 for simple. */
FT_API double ft_mountain_default_dprime(ft_mountain_method m);
/** "simple", "midpoint", "fourier", "improved"; FT_E_INVALID naming the text otherwise. */
FT_API int ft_mountain_method_parse(const char *name, ft_mountain_method *m);

/** One contour level: its elevation and polygons. */
typedef struct {
    double elev;
    ft_polygon_set *polys;
} ft_contour_level;

/** Contour levels by increasing elevation; every level is valid and lies inside the level below it. */
typedef struct {
    ft_contour_level *levels;
    size_t n;
    double spacing;   /**< d used (ground units) */
    double interval;  /**< elevation step */
    double dprime;    /**< d' used, as a multiple of d (0 when no generator made the stack) */
    size_t guard_moves;   /**< vertices the generator's guarded steps moved (0 unguarded or not generated) */
    size_t guard_reduced; /**< of which the crossing guard moved only half or a quarter of the way */
    size_t guard_dropped; /**< of which it left at their base position */
} ft_contour_stack;

FT_API void ft_contour_stack_free(ft_contour_stack *s);

/** Grows the mountain from seed contour(s) at opts->seed_elevation: levels_down grown outward (merged
 *  where they meet), the seed level, and the levels above it until levels_up or until nothing is
 *  left. Same seed polygons, options and seed => identical stack. */
FT_API int ft_mountain_generate(const ft_polygon_set *seed, const ft_mountain_opts *opts, ft_contour_stack **out);

/** A contour layer: one feature per polygon (outer + holes) with a real field `elev` (as
 *  gdal_contour -p -amin elev), or with as_lines = 1 one line feature per ring. crs_wkt may be NULL. */
FT_API int ft_contour_stack_to_layer(const ft_contour_stack *s, int as_lines, const char *crs_wkt, ft_layer **out);

/** A contour stack from a layer of polygons with an elevation field (levels = the distinct values,
 *  sorted). FT_E_FORMAT naming the field if it is missing or not numeric. */
FT_API int ft_contour_stack_from_layer(const ft_layer *l, const char *field, ft_contour_stack **out);

/* ------------------------------------------------------------------------------------------------
 * The DEM of a contour stack (as GRASS r.surf.contour): a cell between the contour of its level and
 * the next one up gets z = z_lo + (z_hi - z_lo) d_lo / (d_lo + d_hi), d the distances to the two
 * contours; inside the top contour(s) the summit rises above the last level as documented; outside
 * the lowest contour cells are nodata.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_contour_dem_opts); see FT_OPTS in core.h */
    double cell;       /**< cell size (ground units, > 0); 0 (default) = the lowest level's larger
                            extent / 512 */
    double margin;     /**< ground units around the lowest level's extent, >= 0; default 0 (one cell) */
    double summit;     /**< rise of the summit above the top contour as a multiple of the interval,
                            >= 0; default 0.5 */
    ft_progress_fn progress;
    void *progress_arg;
} ft_contour_dem_opts;
#define FT_CONTOUR_DEM_OPTS_DEFAULT                                                                                  \
    {.struct_size = sizeof(ft_contour_dem_opts), .cell = 0.0, .margin = 0.0, .summit = 0.5, .progress = NULL,        \
     .progress_arg = NULL}

/** A north-up grid covering the lowest level (crs_wkt copied if not NULL). */
FT_API int ft_contour_stack_to_dem(const ft_contour_stack *s, const ft_contour_dem_opts *opts, const char *crs_wkt,
                            ft_grid **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_CONTOUR_H */
