/* fracterra — src/contour/contour_internal.h: what the contour module's files share (not installed).
 *
 * GEOS is used through its reentrant C API only (GEOS_USE_ONLY_R_API below): every function that needs it
 * opens its own context with ft_geos_open() on the stack and closes it before returning, so calls on
 * different threads never share GEOS state. The context routes GEOS's error messages into its msg buffer;
 * ft_geos_fail() turns them into an ft_error naming the operation.
 *
 *   ft_geos g;
 *   if (ft_geos_open(&g) != FT_OK) return ft_last_error_code();
 *   GEOSGeometry *mp = ft_geos_from_set(&g, set);          // NULL: error set
 *   ...  GEOSArea_r(g.h, mp, &a) ...
 *   GEOSGeom_destroy_r(g.h, mp);
 *   ft_geos_close(&g);
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CONTOUR_INTERNAL_H
#define FRACTERRA_CONTOUR_INTERNAL_H

#ifndef GEOS_USE_ONLY_R_API
#define GEOS_USE_ONLY_R_API
#endif
#include <geos_c.h>

#include "fracterra/contour.h"
#include "fracterra/line.h"

/* ---- GEOS bridge (geos_bridge.c) ------------------------------------------------------------- */

typedef struct {
    GEOSContextHandle_t h; /**< the reentrant context, NULL once closed */
    char msg[512];         /**< GEOS's last error message ("" if none) */
} ft_geos;

/** Opens a GEOS context whose error messages go to g->msg. FT_E_NOMEM (error set) on failure. */
int ft_geos_open(ft_geos *g);
/** Closes the context (no-op if already closed). */
void ft_geos_close(ft_geos *g);
/** Sets ft_error(FT_E_NUMERIC, "<what>: GEOS: <message>") and returns FT_E_NUMERIC. */
int ft_geos_fail(ft_geos *g, const char *what);

/** A GEOS LinearRing of a ring (the closing vertex added), as stored: orientation is kept. */
GEOSGeometry *ft_geos_ring(ft_geos *g, const ft_chain *ring);
/** A GEOS closed LineString of a ring (the closing vertex added). */
GEOSGeometry *ft_geos_ring_line(ft_geos *g, const ft_chain *ring);
/** A GEOS Polygon of one polygon of a set. */
GEOSGeometry *ft_geos_polygon(ft_geos *g, const ft_polygon *p);
/** A GEOS MultiPolygon of a set (empty for n == 0). NULL on failure (error set). */
GEOSGeometry *ft_geos_from_set(ft_geos *g, const ft_polygon_set *s);

/** Appends the polygons of a polygonal GEOS geometry (Polygon, MultiPolygon, or a collection holding
 *  them; other parts are ignored) to s: rings lose their closing vertex, outer rings are made
 *  counter-clockwise and holes clockwise; polygons whose outer ring encloses less than min_area and
 *  holes smaller than min_area are dropped (a dropped hole is filled). */
int ft_geos_append_to_set(ft_geos *g, const GEOSGeometry *geom, double min_area, ft_polygon_set *s);

/* ---- checks shared by the contour functions (polygon_set.c) ----------------------------------- */

/* The number of rings of a set (outer rings and their holes; 0 for NULL). */
size_t ft_polygon_set_ring_count(const ft_polygon_set *s);
/* Ring k of a set in set order (outer rings and their holes, polygon by polygon); NULL past the end. */
const ft_chain *ft_polygon_set_ring(const ft_polygon_set *s, size_t k);

/* A copy of layer part p as a ring (closing vertex dropped, closed = 1). FT_E_FORMAT naming the feature
 * and part for an open line, no vertex or a non-finite coordinate; a ring of fewer than 3 vertices is
 * FT_E_FORMAT too unless degenerate_ok, which then gives FT_OK with *out = NULL (also for zero area). */
int ft_contour_ring_of_part(const ft_layer *l, size_t p, int degenerate_ok, ft_chain **out);

/** FT_OK if the ring has finite coordinates, at least 3 distinct vertices and a non-zero area (relative
 *  to its extent); FT_E_INVALID naming `what` (e.g. "polygon 2 hole 1") and the fault otherwise. */
int ft_contour_check_ring(const ft_chain *ring, const char *what);

/* ---- winding-number faces (clean.c) ----------------------------------------------------------- */

/** The region {p : w(p) > 0}, w the winding number of all the closed rings together (orientation as
 *  given, closing vertex not repeated): computed by GEOS's buffer engine at distance 0 (counter-clockwise
 *  rings as shells, clockwise ones as holes, so that its face depth is w), or, when a ring's orientation
 *  cannot be told, by snap-rounded noding on the grid ft_contour_grid(scale), polygonizing and a winding
 *  number per face. Polygons enclosing less than min_area and holes smaller than min_area are dropped;
 *  the result (appended to out) is valid. scale is the length the fallback's grid is a fraction of: the
 *  shrink distance d, or 0 for 1e-12 of the rings' extent. This is the back half of the paper's polygon
 *  shrinking (§2, steps 3-4) and the loop removal of §4.4. */
int ft_contour_positive_region(ft_geos *g, ft_chain *const *rings, size_t nrings, double scale, double min_area,
                               ft_polygon_set *out);

/** The noding grid: FT_CONTOUR_GRID_SCALE x |scale|, or for scale == 0 FT_CONTOUR_GRID_EXTENT x the rings'
 *  extent; at least FT_CONTOUR_GRID_COORD x the largest |coordinate|, so that coordinates stay exact
 *  multiples of it in double precision. */
#define FT_CONTOUR_GRID_SCALE 1e-9
#define FT_CONTOUR_GRID_EXTENT 1e-12
#define FT_CONTOUR_GRID_COORD 1e-13
double ft_contour_grid(ft_chain *const *rings, size_t nrings, double scale);

/* ---- guarded midpoint displacement (guard_displace.c) ----------------------------------------- */

/** rings[0..nr): rings displaced by ft_contour_midpoint_displace from used[0..nr) (the same ring when not
 *  displaced), each replaced by its guarded version: every added vertex moves from its place on the
 *  undisplaced ring towards its displaced one only as far as it touches no other segment of the rings nor
 *  of the rings of below (may be NULL), which stay fixed. A ring whose undisplaced vertices are not found
 *  in order keeps its displaced positions. stats (may be NULL) is added to. */
int ft_contour_guard_displaced(ft_chain **rings, const ft_chain *const *used, size_t nr, const ft_polygon_set *below,
                               ft_line_guard_stats *stats);

/** rings[0..nr) moved from bases[0..nr) (vertex for vertex: same count and closedness), each replaced by its
 *  guarded version (FT_GUARD_REDUCE): every vertex moves from its base towards its place in the ring only as
 *  far as it touches no other segment of the rings nor of the rings of below (may be NULL), which stay
 *  fixed. Takes bases (freed, also on failure). stats (may be NULL) is added to. */
int ft_contour_guard_rings(ft_chain **rings, ft_chain **bases, size_t nr, const ft_polygon_set *below,
                           ft_line_guard_stats *stats);

/* ---- Fourier phase randomization with its base (fourier_descriptor.c) ---------------------------- */

/** ft_contour_fourier_randomize, and (base not NULL) *base: the resampled input ring (before the phases are
 *  randomized), vertex j of *base being where vertex j of *out was drawn from (reversed with it). */
int ft_contour_fourier_randomize_paired(const ft_chain *ring, const ft_fourier_opts *opts, uint64_t seed,
                                        uint64_t stream, ft_chain **base, ft_chain **out);

#endif /* FRACTERRA_CONTOUR_INTERNAL_H */
