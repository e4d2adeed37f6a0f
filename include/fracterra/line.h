/* fracterra — line.h: the fractal dimension of chains, and Dutton's fractal enhancement of generalized lines
 * with the companion operations (Douglas-Peucker simplification, weeding, roundness smoothing).
 *
 * Papers: Dutton (1981) "Fractal enhancement of cartographic line detail"; Clarke (1987) walking
 * dividers; Zhang, Yu & Fan (2008) line methods; Arakawa & Krotkov §2.4 log-log
 * segmentation. docs/line-*.md hold the equations and limits.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_H
#define FRACTERRA_LINE_H

#include <math.h>

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------------------------------------
 * Dimension of chains. Every estimator measures a SET of chains (one feature's parts, or a whole layer):
 * the value at each scale is summed over the chains, then one log-log table is fitted with the shared
 * module (ft_loglog_fit_auto), so the result carries the whole table, the range and every segment.
 * --------------------------------------------------------------------------------------------- */

typedef enum {
    FT_LINE_DIVIDER = 0,   /**< walking divider (Richardson): length against ruler, D = 1 - slope */
    FT_LINE_EQUIPACED = 1, /**< equipaced polygon: resample at arc-length spacing s, length against s */
    FT_LINE_HYBRID = 2,    /**< hybrid walk (Clarke & Schweizer): divider restricted to vertices */
    FT_LINE_BOX = 3,       /**< box counting: exact cells crossed, mean over grid offsets, D = -slope */
    FT_LINE_BOX_MIN = 4    /**< box counting, fewest cells over grid offsets (biased upward where the
                                largest boxes hold few counts; kept for comparison with the literature) */
} ft_line_method;

typedef struct {
    size_t struct_size; /**< sizeof(ft_line_dim_opts); see FT_OPTS in core.h */
    double min_scale;       /**< smallest ruler/box; 0 = automatic (from the vertex spacing) */
    double max_scale;       /**< largest ruler/box; 0 = automatic (from the extent) */
    int nscales;            /**< scales in the geometric series; 0 = the method's default (16; box 12) */
    int both_ends;          /**< divider/hybrid on open chains: average walks from both ends; default 1 */
    int box_offsets;        /**< box counting: grid offsets per size (n x n); default 4 */
    ft_loglog_opts fit;     /**< segmentation of the log-log table */
    int fit_whole_range;    /**< 1: fit every scale between min and max, no segmentation; default 0 */
    ft_progress_fn progress;
    void *progress_arg;
    const ft_ellipsoid *ellipsoid; /**< NULL (default): planar chains, scales in their own unit. Else x =
                                        longitude, y = latitude in degrees on this ellipsoid: the walks step
                                        by straight 3-D chords between Earth-centred points, scales and
                                        lengths are metres (docs/geographic.md); box counting refuses
                                        (project the chains to an equal-area CRS first) */
    double min_r2;          /**< 0 (default): off; else a fit with r² below it fails (the CLI uses
                                 FT_LINE_R2_FLOOR), unless D is pinned anyway (see FT_LINE_R2_FLOOR) */
    int starts;             /**< divider on rings: L(r) is the mean of this many walks, walk k starting at the
                                 first vertex at or after arc length k L / starts from vertex 0 (Andrle 1992:
                                 the start moves a ring's D); 1 (default): one walk from vertex 0. Open chains
                                 keep both_ends. Other methods: 1 only */
    int only_start;         /**< -1 (default): the mean of the starts; k in [0, starts): walk k alone (the
                                 spread of D over the starts, docs/line-dimension.md) */
} ft_line_dim_opts;
#define FT_LINE_DIM_OPTS_DEFAULT                                                                                     \
    {.struct_size = sizeof(ft_line_dim_opts), .min_scale = 0.0, .max_scale = 0.0, .nscales = 0, .both_ends = 1,      \
     .box_offsets = 4, .fit = FT_LOGLOG_OPTS_DEFAULT, .fit_whole_range = 0, .progress = NULL, .progress_arg = NULL,  \
     .ellipsoid = NULL, .min_r2 = 0.0, .starts = 1, .only_start = -1}

/** The least r² the CLI accepts (opts.min_r2; docs/line-dimension.md): below it ft_line_dim fails
 *  (FT_E_INVALID) naming the range, rather than return a D read from a table that is not a straight line.
 *  Exempt are fits whose values vary by less than FT_LINE_R2_MIN_SPREAD in log10 (lengths within 1.2%: a
 *  straight line, D = 1, leaves r² nothing to explain) and fits whose D has a standard error below
 *  FT_LINE_R2_MAX_STDERR (a smooth curve's slope near 0 is pinned even when r² is low). */
#define FT_LINE_R2_FLOOR 0.5
#define FT_LINE_R2_MIN_SPREAD 0.005
#define FT_LINE_R2_MAX_STDERR 0.01

/** Dimension of a set of chains (n >= 1; chains with fewer than 2 vertices are skipped and counted in the
 *  error message if none is left). *out is allocated; free with ft_dim_result_free. Rows where the chains
 *  are shorter than one ruler (no whole step: the value is only the chord) are not used; fewer than 3 usable
 *  rows, or a fit with r² below opts.min_r2, fail with FT_E_INVALID naming the range and the chains'
 *  length and extent in the same unit. */
FT_API int ft_line_dim(const ft_chain *const *chains, size_t n, ft_line_method method, const ft_line_dim_opts *opts,
                ft_dim_result **out);
/** The method's name as used by the CLI and the JSON ("divider", "equipaced", "hybrid", "box", "box-min"). */
FT_API const char *ft_line_method_name(ft_line_method m);
/** Parses a method name; FT_E_INVALID naming it otherwise. */
FT_API int ft_line_method_parse(const char *name, ft_line_method *m);

/** One divider walk with a fixed ruler from the start (from_end = 0) or the end (1) of a chain: the walked
 *  length including the fractional last step, and the number of whole steps. */
FT_API int ft_line_divider_walk(const ft_chain *c, double ruler, int from_end, double *length, size_t *steps);
/** Number of grid cells of side `size`, with origin (ox, oy), crossed by the chain's segments (exact cell
 *  traversal). */
FT_API int ft_line_box_count(const ft_chain *const *chains, size_t n, double size, double ox, double oy,
                      uint64_t *count);

/* ------------------------------------------------------------------------------------------------
 * Dutton's fractal enhancement and its companions. Chain-level functions take a chain and allocate a new
 * one; layer-level functions apply them to every part of a layer in place, and on polygon layers (coverages)
 * work on the arc-node topology so that shared boundaries stay identical on both sides.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_dutton_opts); see FT_OPTS in core.h */
    double sd;       /**< sinuosity dimension in [1, 2]: the divider dimension the enhanced chain measures over
                          the scales the enhancement generates when uc = 1 (unless literal_sd); default 1.3;
                          0: the input's own D_in (input_dim), the target whatever uc (not with literal_sd) */
    double uc;       /**< uniformity coefficient in [-1, 1]; default 1. For uc in (0, 1] the target dimension
                          is D_in + uc (sd - D_in), D_in the input's divider dimension (input_dim); uc = 0
                          moves nothing; uc < 0 (exaggeration) uses the literal apex angle of sd */
    double st;       /**< straightness tolerance: vertices are altered only if both segments are shorter;
                          default INFINITY */
    double sm;       /**< smoothness tolerance: ... and not shorter than this; default 0 */
    int iterations;  /**< default 1 */
    double target_dim; /**< 0 (default): the target comes from sd and uc as above; else the divider dimension
                            wanted, whatever uc (sd and input_dim are ignored), up to ft_dutton_max_dimension(uc) */
    double input_dim;  /**< D_in for uc in (0, 1): 0 (default) = measured, the walking divider over the input's
                            automatic range (ft_line_dim, all chains together); else given */
    int literal_sd;    /**< 1: Dutton's literal reading, the apex angle pi - 2a with cos a = 2^(1/sd - 1), no
                            calibration (it measures well below sd: 1.12 for 1.3); default 0 */
    int allow_crossings; /**< 1: the raw algorithm; 0 (default): a move that would make a segment cross or
                              touch another one of the chain (or layer) is halved, then dropped */
    int keep_vertices; /**< 1: the input's vertices stay where they are; each new midpoint takes the place it
                            has relative to its neighbours in Dutton's pass (Dutton's position minus the mean
                            of its two neighbours' moves, same apex and uc). One pass only (iterations = 1).
                            Default 0: Dutton's pass, which moves the input's vertices */
} ft_dutton_opts;
#define FT_DUTTON_OPTS_DEFAULT                                                                                       \
    {.struct_size = sizeof(ft_dutton_opts), .sd = 1.3, .uc = 1.0, .st = INFINITY, .sm = 0.0, .iterations = 1,        \
     .target_dim = 0.0, .input_dim = 0.0, .literal_sd = 0, .allow_crossings = 0, .keep_vertices = 0}

/** What an enhancement will do, resolved once for a chain or a whole layer (ft_dutton_plan_make). */
typedef struct {
    double apex;       /**< the apex angle used, radians */
    double target_dim; /**< the divider dimension aimed at over the generated scales; NaN if literal_sd, uc <= 0 */
    double input_dim;  /**< D_in used by the uc < 1 rule; NaN if not used */
    double uc, st, sm;
    double densify;    /**< calibrated mode: before a pass, a segment of length L >= 3 densify (and < st) is cut
                            into ceil(L / densify) equal pieces: the input's mean segment; 0 (literal): none */
    int keep_vertices; /**< opts->keep_vertices: the pass moves only the new midpoints */
} ft_dutton_plan;

/** Resolves opts against the input chains (measures D_in if needed). FT_E_INVALID if the target cannot be
 *  reached (above ft_dutton_max_dimension(uc)) or D_in cannot be measured. */
FT_API int ft_dutton_plan_make(const ft_chain *const *chains, size_t n, const ft_dutton_opts *opts, ft_dutton_plan *plan);
/** The UC rule: D_in + uc (sd - D_in). */
FT_API double ft_dutton_target_dimension(double sd, double uc, double input_dim);
/** The steady-state divider dimension of the enhancement with apex `apex` and uniformity uc in (0, 1]; NaN
 *  outside. uc = 1 is ft_dutton_steady_dimension. */
FT_API double ft_dutton_steady_dimension_uc(double apex, double uc);
/** The largest dimension calibrated mode reaches with uniformity uc (at FT_DUTTON_APEX_MIN). */
FT_API double ft_dutton_max_dimension(double uc);
/** The apex angle whose steady-state dimension with uniformity uc is target_dim; NaN if out of reach. */
FT_API double ft_dutton_apex_for_target(double target_dim, double uc);

/** The apex angle (radians) that a sinuosity dimension implies: pi - 2a with cos a = 2^(1/sd - 1). */
FT_API double ft_dutton_apex_angle(double sd);

/** The smallest apex angle of calibrated mode, 60 degrees: below it the enhanced chain overlaps itself and
 *  its measured dimension stops rising. */
#define FT_DUTTON_APEX_MIN (3.14159265358979323846 / 3.0)
/** The divider dimension that iterating the enhancement with apex angle `apex` (radians, uc = 1, no
 *  tolerances) converges to: ln 2 / ln(2 / f), f the steady-state length growth per iteration, computed on
 *  a canonical junction (deterministic; a few hundred microseconds). Decreasing in apex; 1 at pi. NaN
 *  outside [FT_DUTTON_APEX_MIN, pi]. SD's literal angle gives ft_dutton_steady_dimension(
 *  ft_dutton_apex_angle(1.3)) = 1.12, not 1.3. */
FT_API double ft_dutton_steady_dimension(double apex);
/** Calibrated mode: the apex angle (radians) whose steady-state divider dimension is target_dim (the
 *  inverse of ft_dutton_steady_dimension, by bisection). NaN outside [1, ft_dutton_steady_dimension(
 *  FT_DUTTON_APEX_MIN)]. */
FT_API double ft_dutton_apex_for_dimension(double target_dim);
/** Dutton enhancement of one chain. End points of open chains never move. */
FT_API int ft_line_enhance(const ft_chain *in, const ft_dutton_opts *opts, ft_chain **out);

typedef struct {
    size_t struct_size; /**< sizeof(ft_smooth_opts); see FT_OPTS in core.h */
    int passes;        /**< corner-cutting passes; default 1 */
    double roundness;  /**< R in (0, 1]: V is replaced by V + R(M1 - V) and V + R(M2 - V); default 0.5 */
    double st, sm;     /**< only segments within [sm, st] are cut; defaults INFINITY and 0 */
    int allow_crossings; /**< 1: the raw algorithm; 0 (default): cuts that would make a segment cross or touch
                              another are reduced (move_guard.c) */
} ft_smooth_opts;
#define FT_SMOOTH_OPTS_DEFAULT                                                                                       \
    {.struct_size = sizeof(ft_smooth_opts), .passes = 1, .roundness = 0.5, .st = INFINITY, .sm = 0.0,                \
     .allow_crossings = 0}

/** Roundness smoothing (corner cutting; R = 0.5 is Chaikin's quarter points). */
FT_API int ft_line_smooth(const ft_chain *in, const ft_smooth_opts *opts, ft_chain **out);
/** Weeding: drops vertices so that no segment is shorter than min_seg (end points of open chains kept). */
FT_API int ft_line_weed(const ft_chain *in, double min_seg, ft_chain **out);
/** Weeding that keeps the shape: no segment shorter than min_seg either, but of a short segment's two
 *  vertices the one nearer to the chord of its neighbours is dropped (weed_shape.c); open chains keep their
 *  end points, rings at least 3 vertices. */
FT_API int ft_line_weed_shape(const ft_chain *in, double min_seg, ft_chain **out);
/** Douglas-Peucker simplification with a distance tolerance (rings keep at least 3 vertices). */
FT_API int ft_line_simplify(const ft_chain *in, double tolerance, ft_chain **out);
/** The smallest Douglas-Peucker tolerance (to 1e-12 of the layer's diagonal, by bisection) that leaves the
 *  layer at most target vertices when simplified by ft_line_apply_layer (coverage as there), and the
 *  vertices it leaves. Tolerance 0 if the layer has no more than target already; FT_E_INVALID naming the
 *  least reachable count when target is below it. The layer is not changed. */
FT_API int ft_line_simplify_tolerance_for(const ft_layer *l, size_t target, int coverage, double *tolerance,
                                          size_t *vertices);

/** Number of proper self-intersections of a chain (pairs of non-adjacent segments that cross). */
FT_API int ft_line_count_self_intersections(const ft_chain *c, size_t *count);
/** Removes the loops that self-intersections make (keeps the part of the chain that does not loop back). */
FT_API int ft_line_remove_loops(const ft_chain *in, ft_chain **out);

/* ------------------------------------------------------------------------------------------------
 * The crossing guard (move_guard.c, segment_index.c): operations that move vertices work in passes; each pass
 * proposes a base chain (no displacement: the input's geometry with the new vertices on it) and a raw chain
 * (the algorithm's positions), vertex for vertex; the guard moves every vertex as far towards raw (all, half,
 * a quarter, or not at all) as keeps every segment clear of every other segment of the chain set.
 * --------------------------------------------------------------------------------------------- */

/** What the guard did (counts add up over passes and chains). */
typedef struct {
    size_t moves;   /**< vertices the raw algorithm moves */
    size_t reduced; /**< of which moved only half or a quarter of the way */
    size_t dropped; /**< of which left at their base position */
    size_t redrawn; /**< of which moved in full to the mirror position (FT_GUARD_MIRROR) */
} ft_line_guard_stats;

/** Guard modes of ft_line_run_passes and ft_line_apply_layer_passes. */
enum {
    FT_GUARD_OFF = 0,   /**< the raw positions */
    FT_GUARD_REDUCE = 1, /**< all, half, a quarter of the move, or none */
    FT_GUARD_MIRROR = 2  /**< first the full move, then its mirror through the base (2 base - raw: a midpoint
                              displacement drawn to the other side, same length), then as REDUCE */
};

/** chains[c] holds the base positions and receives the result; raw[c] the raw ones (same vertex count and
 *  closedness). If the base geometry has no contact between segments (but shared end points), neither has
 *  the result. The moves are visited in a fixed order (chunks of the chains walked in parallel, then the
 *  moves whose tests reach other chunks, serially): the same result on any thread count. stats (may be NULL)
 *  is added to. */
FT_API int ft_line_guard_moves(ft_chain *const *chains, const ft_chain *const *raw, size_t n, int mode,
                        ft_line_guard_stats *stats);

/** One pass of a vertex-moving operation: allocates *base and *raw (same vertex count); base may be NULL
 *  (unguarded: only raw is wanted). */
typedef int (*ft_line_pass_fn)(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw);
/** A pass of Dutton's enhancement; ctx is a const ft_dutton_plan *. */
FT_API int ft_line_pass_enhance(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw);
/** A pass of roundness smoothing; ctx is a const ft_smooth_opts * (passes ignored). Duplicate consecutive
 *  vertices are left in: ft_line_run_passes removes them. */
FT_API int ft_line_pass_smooth(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw);
/** `passes` passes over the chain set chains[0..n) (replaced in place; on failure unchanged), guarded in
 *  mode `guard` (FT_GUARD_*; FT_GUARD_OFF takes the raw positions); consecutive duplicate vertices are removed
 *  after each. */
FT_API int ft_line_run_passes(ft_chain **chains, size_t n, ft_line_pass_fn pass, const void *ctx, int passes, int guard,
                       ft_line_guard_stats *stats);
/** ft_line_run_passes over a whole layer: every part, or on coverages (coverage != 0 and rings) every arc of
 *  the arc-node topology once and the line parts, all in one chain set, so no part crosses another. */
FT_API int ft_line_apply_layer_passes(ft_layer *l, ft_line_pass_fn pass, const void *ctx, int passes, int coverage,
                               int guard, ft_line_guard_stats *stats);
/** Dutton's enhancement of a layer: one plan for the whole layer (D_in measured over all its parts), then
 *  opts->iterations guarded passes (unless opts->allow_crossings). plan and stats may be NULL. */
FT_API int ft_line_enhance_layer(ft_layer *l, const ft_dutton_opts *opts, int coverage, ft_dutton_plan *plan,
                          ft_line_guard_stats *stats);
/** Roundness smoothing of a layer, guarded unless opts->allow_crossings. stats may be NULL. */
FT_API int ft_line_smooth_layer(ft_layer *l, const ft_smooth_opts *opts, int coverage, ft_line_guard_stats *stats);

/** A chain operation, for the layer-level driver: reads in, allocates *out. */
typedef int (*ft_line_op)(const ft_chain *in, const void *opts, ft_chain **out);

/** Applies op to every part of the layer. If the layer has rings and coverage is nonzero, builds the
 *  arc-node topology, applies op to each arc once (arc end points, the nodes, are kept in place) and
 *  rebuilds the rings from the edited arcs, so adjacent polygons stay coincident. */
FT_API int ft_line_apply_layer(ft_layer *l, ft_line_op op, const void *opts, int coverage);

/* The chain operations as ft_line_op, for ft_line_apply_layer: opts points to what the operation takes.
 * Each keeps the end points of open chains, so on a coverage the nodes stay in place. */
FT_API int ft_line_op_enhance(const ft_chain *in, const void *opts /* const ft_dutton_opts * */, ft_chain **out);
FT_API int ft_line_op_smooth(const ft_chain *in, const void *opts /* const ft_smooth_opts * */, ft_chain **out);
FT_API int ft_line_op_weed(const ft_chain *in, const void *opts /* const double *min_seg */, ft_chain **out);
FT_API int ft_line_op_weed_shape(const ft_chain *in, const void *opts /* const double *min_seg */, ft_chain **out);
FT_API int ft_line_op_simplify(const ft_chain *in, const void *opts /* const double *tolerance */, ft_chain **out);
FT_API int ft_line_op_remove_loops(const ft_chain *in, const void *opts /* ignored, may be NULL */, ft_chain **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_LINE_H */
