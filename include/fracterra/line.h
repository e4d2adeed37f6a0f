/* fracterra — line.h: the fractal dimension of chains, and Dutton's fractal enhancement of generalized lines
 * with the companion operations (Douglas-Peucker simplification, weeding, roundness smoothing).
 *
 * Papers: Dutton (1981) "Fractal enhancement of cartographic line detail" (seeds 000); Clarke (1987) walking
 * dividers (seeds 004); Zhang, Yu & Fan (2008) line methods (seeds 002); Arakawa & Krotkov §2.4 log-log
 * segmentation (seeds 003). docs/line-*.md hold the equations and limits.
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
    double min_scale;       /**< smallest ruler/box; 0 = automatic (from the vertex spacing) */
    double max_scale;       /**< largest ruler/box; 0 = automatic (from the extent) */
    int nscales;            /**< scales in the geometric series; 0 = the method's default (16; box 12) */
    int both_ends;          /**< divider/hybrid on open chains: average walks from both ends; default 1 */
    int box_offsets;        /**< box counting: grid offsets per size (n x n); default 4 */
    ft_loglog_opts fit;     /**< segmentation of the log-log table */
    int fit_whole_range;    /**< 1: fit every scale between min and max, no segmentation; default 0 */
    ft_progress_fn progress;
    void *progress_arg;
} ft_line_dim_opts;
#define FT_LINE_DIM_OPTS_DEFAULT {0.0, 0.0, 0, 1, 4, FT_LOGLOG_OPTS_DEFAULT, 0, NULL, NULL}

/** Dimension of a set of chains (n >= 1; chains with fewer than 2 vertices are skipped and counted in the
 *  error message if none is left). *out is allocated; free with ft_dim_result_free. */
int ft_line_dim(const ft_chain *const *chains, size_t n, ft_line_method method, const ft_line_dim_opts *opts,
                ft_dim_result **out);
/** The method's name as used by the CLI and the JSON ("divider", "equipaced", "hybrid", "box", "box-min"). */
const char *ft_line_method_name(ft_line_method m);
/** Parses a method name; FT_E_INVALID naming it otherwise. */
int ft_line_method_parse(const char *name, ft_line_method *m);

/** One divider walk with a fixed ruler from the start (from_end = 0) or the end (1) of a chain: the walked
 *  length including the fractional last step, and the number of whole steps. */
int ft_line_divider_walk(const ft_chain *c, double ruler, int from_end, double *length, size_t *steps);
/** Number of grid cells of side `size`, with origin (ox, oy), crossed by the chain's segments (exact cell
 *  traversal). */
int ft_line_box_count(const ft_chain *const *chains, size_t n, double size, double ox, double oy,
                      uint64_t *count);

/* ------------------------------------------------------------------------------------------------
 * Dutton's fractal enhancement and its companions. Chain-level functions take a chain and allocate a new
 * one; layer-level functions apply them to every part of a layer in place, and on polygon layers (coverages)
 * work on the arc-node topology so that shared boundaries stay identical on both sides.
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double sd;       /**< sinuosity dimension in [1, 2]; default 1.3 */
    double uc;       /**< uniformity coefficient in [-1, 1]; default 1 */
    double st;       /**< straightness tolerance: vertices are altered only if both segments are shorter;
                          default INFINITY */
    double sm;       /**< smoothness tolerance: ... and not shorter than this; default 0 */
    int iterations;  /**< default 1 */
    double target_dim; /**< calibrated mode: 0 (default) = off, the apex angle comes from sd by the literal
                            relation; else the dimension wanted, in [1, ft_dutton_steady_dimension(
                            FT_DUTTON_APEX_MIN)] (about 1.777): sd is ignored and the apex angle is
                            ft_dutton_apex_for_dimension(target_dim), so that with uc = 1 the enhanced chain's
                            divider dimension is target_dim (docs/line-enhance.md) */
} ft_dutton_opts;
#define FT_DUTTON_OPTS_DEFAULT {1.3, 1.0, INFINITY, 0.0, 1, 0.0}

/** The apex angle (radians) that a sinuosity dimension implies: pi - 2a with cos a = 2^(1/sd - 1). */
double ft_dutton_apex_angle(double sd);

/** The smallest apex angle of calibrated mode, 60 degrees: below it the enhanced chain overlaps itself and
 *  its measured dimension stops rising. */
#define FT_DUTTON_APEX_MIN (3.14159265358979323846 / 3.0)
/** The divider dimension that iterating the enhancement with apex angle `apex` (radians, uc = 1, no
 *  tolerances) converges to: ln 2 / ln(2 / f), f the steady-state length growth per iteration, computed on
 *  a canonical junction (deterministic; a few hundred microseconds). Decreasing in apex; 1 at pi. NaN
 *  outside [FT_DUTTON_APEX_MIN, pi]. SD's literal angle gives ft_dutton_steady_dimension(
 *  ft_dutton_apex_angle(1.3)) = 1.12, not 1.3. */
double ft_dutton_steady_dimension(double apex);
/** Calibrated mode: the apex angle (radians) whose steady-state divider dimension is target_dim (the
 *  inverse of ft_dutton_steady_dimension, by bisection). NaN outside [1, ft_dutton_steady_dimension(
 *  FT_DUTTON_APEX_MIN)]. */
double ft_dutton_apex_for_dimension(double target_dim);
/** Dutton enhancement of one chain. End points of open chains never move. */
int ft_line_enhance(const ft_chain *in, const ft_dutton_opts *opts, ft_chain **out);

typedef struct {
    int passes;        /**< corner-cutting passes; default 1 */
    double roundness;  /**< R in (0, 1]: V is replaced by V + R(M1 - V) and V + R(M2 - V); default 0.5 */
    double st, sm;     /**< only segments within [sm, st] are cut; defaults INFINITY and 0 */
} ft_smooth_opts;
#define FT_SMOOTH_OPTS_DEFAULT {1, 0.5, INFINITY, 0.0}

/** Roundness smoothing (corner cutting; R = 0.5 is Chaikin's quarter points). */
int ft_line_smooth(const ft_chain *in, const ft_smooth_opts *opts, ft_chain **out);
/** Weeding: drops vertices so that no segment is shorter than min_seg (end points of open chains kept). */
int ft_line_weed(const ft_chain *in, double min_seg, ft_chain **out);
/** Douglas-Peucker simplification with a distance tolerance (rings keep at least 3 vertices). */
int ft_line_simplify(const ft_chain *in, double tolerance, ft_chain **out);

/** Number of proper self-intersections of a chain (pairs of non-adjacent segments that cross). */
int ft_line_count_self_intersections(const ft_chain *c, size_t *count);
/** Removes the loops that self-intersections make (keeps the part of the chain that does not loop back). */
int ft_line_remove_loops(const ft_chain *in, ft_chain **out);

/** A chain operation, for the layer-level driver: reads in, allocates *out. */
typedef int (*ft_line_op)(const ft_chain *in, const void *opts, ft_chain **out);

/** Applies op to every part of the layer. If the layer has rings and coverage is nonzero, builds the
 *  arc-node topology, applies op to each arc once (arc end points, the nodes, are kept in place) and
 *  rebuilds the rings from the edited arcs, so adjacent polygons stay coincident. */
int ft_line_apply_layer(ft_layer *l, ft_line_op op, const void *opts, int coverage);

/* The chain operations as ft_line_op, for ft_line_apply_layer: opts points to what the operation takes.
 * Each keeps the end points of open chains, so on a coverage the nodes stay in place. */
int ft_line_op_enhance(const ft_chain *in, const void *opts /* const ft_dutton_opts * */, ft_chain **out);
int ft_line_op_smooth(const ft_chain *in, const void *opts /* const ft_smooth_opts * */, ft_chain **out);
int ft_line_op_weed(const ft_chain *in, const void *opts /* const double *min_seg */, ft_chain **out);
int ft_line_op_simplify(const ft_chain *in, const void *opts /* const double *tolerance */, ft_chain **out);
int ft_line_op_remove_loops(const ft_chain *in, const void *opts /* ignored, may be NULL */, ft_chain **out);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_LINE_H */
