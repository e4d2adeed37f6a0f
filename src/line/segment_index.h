/* fracterra — line/segment_index.h: the grid of swept segments and the segment contact test of
 * segment_index.c, used by the crossing guard (move_guard.c).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_SEGMENT_INDEX_H
#define FRACTERRA_LINE_SEGMENT_INDEX_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/core.h"

/** Segment ids run over the chains in order: chain c's segment i (vertex i to i + 1, a ring's last one back
 *  to 0) is chain_first[c] + i. Cell (cx, cy) is bucket k = ft_segment_grid_bucket(g, cx, cy) = cy nx + cx,
 *  which holds ids[start[k] .. start[k + 1]). */
typedef struct {
    double x0, y0, inv; /**< origin and 1 / cell side */
    size_t nx, ny, nseg, nbuckets; /**< nbuckets = nx ny */
    uint32_t *start; /**< nbuckets + 1 offsets into ids (at most 2^32 - 2 entries) */
    uint32_t *ids, *seg_chain, *chain_first;
} ft_segment_grid;

/** Files every segment of base[0..n) in the cells its swept box (base and raw end points) meets. raw[c] has
 *  base[c]'s vertex count. */
int ft_segment_grid_build(ft_segment_grid *g, const ft_chain *const *base, const ft_chain *const *raw, size_t n);
void ft_segment_grid_free(ft_segment_grid *g);
/** The bucket of cell (cx, cy). */
static inline size_t ft_segment_grid_bucket(const ft_segment_grid *g, size_t cx, size_t cy)
{
    return cy * g->nx + cx;
}

static inline size_t ft_segment_grid_clamp(double v, size_t n)
{
    if (!(v > 0.0))
        return 0;
    return v >= (double)(n - 1) ? n - 1 : (size_t)v;
}

/** The inclusive cell range c = {cx0, cy0, cx1, cy1} that box {x0, y0, x1, y1} meets (clamped to the grid). */
static inline void ft_segment_grid_cells(const ft_segment_grid *g, const double box[4], size_t c[4])
{
    c[0] = ft_segment_grid_clamp((box[0] - g->x0) * g->inv, g->nx);
    c[1] = ft_segment_grid_clamp((box[1] - g->y0) * g->inv, g->ny);
    c[2] = ft_segment_grid_clamp((box[2] - g->x0) * g->inv, g->nx);
    c[3] = ft_segment_grid_clamp((box[3] - g->y0) * g->inv, g->ny);
}

/** 1 if the closed segments a b and c d meet anywhere but at a shared end point (two segments from a
 *  shared end point meet only if they overlap: collinear, the same way). */
int ft_segment_contact(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy);

#endif /* FRACTERRA_LINE_SEGMENT_INDEX_H */
