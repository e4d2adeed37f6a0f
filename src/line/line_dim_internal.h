/* fracterra — src/line/line_dim_internal.h: what the chain-dimension estimators (divider.c, equipaced.c,
 * hybrid_walk.c, box_count.c) offer the dispatcher line_dim.c. Not installed.
 *
 * A walk source presents a chain as the vertex sequence a walk follows: an open chain forwards or
 * backwards, or a ring from vertex 0 round to vertex 0 again (the closing vertex repeated virtually).
 * The walks (divider, equipaced, hybrid) also walk 3-D chains: a geographic chain converted to Earth-centred
 * coordinates on its ellipsoid (x, y and a third array z), measured with straight 3-D chords.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_DIM_INTERNAL_H
#define FRACTERRA_LINE_DIM_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "fracterra/core.h"
#include "line/line_shared.h"

typedef struct {
    const double *x, *y; /**< the chain's arrays */
    const double *z;     /**< third coordinate (ECEF chains), NULL for a planar chain */
    size_t n;            /**< its vertices */
    size_t m;            /**< vertices of the walked sequence: n (open) or n + 1 (ring, closes on vertex 0) */
    int backward;        /**< 1: walk an open chain from its last vertex to its first */
    size_t off;          /**< a ring's walk starts (and closes) at its vertex off; 0 for open chains */
} ft_walk_src;

/** The walked sequence of c (n >= 2) from its start (from_end = 0) or its end (1; ignored for rings); planar
 *  (w->z = NULL). */
void ft_walk_src_init(ft_walk_src *w, const ft_chain *c, int from_end);

/** Vertex k (0 <= k < w->m) of the walked sequence. */
static inline void ft_walk_vertex(const ft_walk_src *w, size_t k, double *x, double *y)
{
    size_t i = w->backward ? w->n - 1 - k : k + w->off;
    if (i >= w->n) /* a ring: k + off wraps round (k = n closes on the start vertex) */
        i -= w->n;
    *x = w->x[i];
    *y = w->y[i];
}

/** Vertex k of the walked sequence in 3-D; d3 = 0 (a compile-time constant in the walks, which are
 *  specialised for planar and 3-D chains so the planar loop stays as lean as before) gives z = 0. */
#if defined(__GNUC__)
#define FT_WALK_INLINE static inline __attribute__((always_inline))
#else
#define FT_WALK_INLINE static inline
#endif
FT_WALK_INLINE void ft_walk_vertex3(const ft_walk_src *w, size_t k, double *x, double *y, double *z, int d3)
{
    size_t i = w->backward ? w->n - 1 - k : k + w->off;
    if (i >= w->n)
        i -= w->n;
    *x = w->x[i];
    *y = w->y[i];
    *z = d3 ? w->z[i] : 0.0;
}

/** |(dx, dy, dz)|: hypot in the plane (dz = 0), so planar results do not change in the last bit. */
static inline double ft_walk_dist(double dx, double dy, double dz)
{
    return dz == 0.0 ? hypot(dx, dy) : sqrt(dx * dx + dy * dy + dz * dz);
}

/* The walks below take z: NULL for a planar chain, else the third ECEF coordinate of each vertex of c. */

/** Divider length of one chain (n >= 2) at ruler r > 0: the walk from the start, or for an open chain with
 *  both_ends set the mean of the walks from either end. *steps gets the (mean) number of whole steps. */
void ft_line_divider_length(const ft_chain *c, const double *z, double r, int both_ends, double *length, double *steps);

/** The divider walk of a ring c (n >= 2) from its vertex off at ruler r: walked length and whole steps. */
void ft_line_divider_ring_from(const ft_chain *c, const double *z, size_t off, double r, double *length,
                               double *steps);

/** The vertices where nstarts walks round a ring c (n >= 2, z as below) start (Andrle 1992): for k = 0 ..
 *  nstarts - 1 the first vertex at or after arc length k L / nstarts from vertex 0 (L the ring's length);
 *  start[0] = 0. */
void ft_line_ring_starts(const ft_chain *c, const double *z, size_t nstarts, size_t *start);

/** Equipaced polygon length of one chain (n >= 2) at arc-length spacing s > 0; *steps gets the number of
 *  whole spacings (the polygon's sides of length s along the chain). */
void ft_line_equipaced_length(const ft_chain *c, const double *z, double s, double *length, double *steps);

/** Hybrid-walk length of one chain (n >= 2) at ruler r > 0 (both_ends as for the divider); *steps gets the
 *  (mean) interpolated step count, length / r. */
void ft_line_hybrid_length(const ft_chain *c, const double *z, double r, int both_ends, double *length, double *steps);

#endif /* FRACTERRA_LINE_DIM_INTERNAL_H */
