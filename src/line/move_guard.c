/* fracterra — line/move_guard.c: the crossing guard of the line operations: a pass of Dutton's
 * enhancement, of roundness smoothing, of Zhang et al.'s boundary generator or of a contour displacement
 * proposes, for every output vertex, a base position (where it is with no displacement: the input's own
 * geometry, e.g. a new midpoint on its segment) and a raw position (where the algorithm puts it). The guard
 * starts from the base geometry and visits the moved vertices chain by chain, in vertex order; vertex v goes
 * from V0 (its base) to V = V0 + t (raw - V0) with the first t of 1, 1/2, 1/4 for which the move sweeps
 * nothing: with A and C its neighbours' current positions, no other segment of any chain meets the new
 * segments A V, V C or the path V0 V (ft_segment_contact: a shared end point is allowed, an overlap is not)
 * or lies inside the triangles A V0 V and V0 V C (a small island the move would jump over); otherwise v
 * stays at V0. In FT_GUARD_MIRROR mode (midpoint displacements: Zhang et al.'s boundary) the mirror move
 * V0 - (raw - V0), the apex drawn on the other side with the same legs, is tried after the full move (the
 * index counts the mirror in a segment's swept box). Each accepted move is a continuous motion that touches
 * nothing, so the layer's topology (which side of which line every feature lies) is kept, not only its
 * simplicity. The segments are found in the near lists of the block index (segment_index.c), tested at
 * their current positions.
 *
 * Invariant: if the base geometry has no contact, every accepted move keeps it so (the only segments that
 * change are v's two, and they were just tested against all others, along the whole motion), and a refused
 * move changes nothing; hence the output has no self-intersection, no contact between chains and the
 * input's nesting, by construction. A contact
 * already in the base (an input that crosses itself) stays, and the moves that touch it are refused.
 * The visiting order is fixed and serial, so the result does not depend on the thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "line/segment_contact.h"
#include "line/segment_index.h"

#include <math.h>
#include <stdlib.h>


typedef struct {
    ft_chain *const *cur;
    const ft_segment_blocks *g;
} guard;

static inline double dmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

static int strictly_inside(const double *a, const double *b, const double *c, double px, double py)
{
    double o1 = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
    double o2 = (c[0] - b[0]) * (py - b[1]) - (c[1] - b[1]) * (px - b[0]);
    double o3 = (a[0] - c[0]) * (py - c[1]) - (a[1] - c[1]) * (px - c[0]);
    return (o1 > 0 && o2 > 0 && o3 > 0) || (o1 < 0 && o2 < 0 && o3 < 0);
}

/* 1 if moving vertex v of chain c from b0 to b (its segments sa: a b0 -> a b, sb: b0 c -> b c; a or c NULL
 * when absent, sa or sb then SIZE_MAX) would sweep another segment: contact with a b, b c or the path b0 b,
 * or an end point inside the triangles a b0 b, b0 b c. Every such segment is in the near list of block nb
 * (the block of sa, or of sb if there is no sa): the whole motion lies in that block's reach. */
static int blocked(const guard *G, size_t c, size_t nb, const double *a, const double *b0, const double *b,
                   const double *cc, size_t sa, size_t sb)
{
    double box[4] = {dmin(b[0], b0[0]), dmin(b[1], b0[1]), dmax(b[0], b0[0]), dmax(b[1], b0[1])};
    if (a) {
        box[0] = dmin(box[0], a[0]), box[1] = dmin(box[1], a[1]);
        box[2] = dmax(box[2], a[0]), box[3] = dmax(box[3], a[1]);
    }
    if (cc) {
        box[0] = dmin(box[0], cc[0]), box[1] = dmin(box[1], cc[1]);
        box[2] = dmax(box[2], cc[0]), box[3] = dmax(box[3], cc[1]);
    }
    const ft_segment_blocks *g = G->g;
    for (uint32_t e = g->near_start[nb]; e < g->near_start[nb + 1]; e++) {
        uint32_t m = g->near[e], mc = g->chain[m];
        const double *q = g->box + 4 * (size_t)m;
        if (q[2] < box[0] || q[0] > box[2] || q[3] < box[1] || q[1] > box[3])
            continue;
        const ft_chain *ch = G->cur[mc];
        size_t n = ch->n, s0 = g->first[m], s1 = s0 + g->count[m];
        const double *x = ch->x, *y = ch->y;
        for (size_t s = s0; s < s1; s++) {
            if (mc == c && (s == sa || s == sb))
                continue;
            size_t j = s + 1 < n ? s + 1 : 0;
            double p0 = x[s], p1 = y[s], p2 = x[j], p3 = y[j];
            if (dmax(p0, p2) < box[0] || dmin(p0, p2) > box[2] || dmax(p1, p3) < box[1] || dmin(p1, p3) > box[3])
                continue;
            if (a && ft_segment_contact(a[0], a[1], b[0], b[1], p0, p1, p2, p3))
                return 1;
            if (cc && ft_segment_contact(b[0], b[1], cc[0], cc[1], p0, p1, p2, p3))
                return 1;
            if (ft_segment_contact(b0[0], b0[1], b[0], b[1], p0, p1, p2, p3))
                return 1;
            if ((a && strictly_inside(a, b0, b, p0, p1)) || (cc && strictly_inside(b0, b, cc, p0, p1)))
                return 1;
        }
    }
    return 0;
}

/* Moves vertex i of chain c towards raw as far as the guard allows; returns the t used (1, 0.5, 0.25, 0;
 * -1: the mirror, in full). */
static double guard_vertex(const guard *G, size_t c, size_t i, const ft_chain *raw, int mode)
{
    ft_chain *ch = G->cur[c];
    size_t n = ch->n;
    int has_prev = ch->closed || i > 0, has_next = ch->closed || i + 1 < n;
    size_t ip = i > 0 ? i - 1 : n - 1, in = i + 1 < n ? i + 1 : 0;
    size_t sa = has_prev ? ip : SIZE_MAX, sb = has_next ? i : SIZE_MAX;
    size_t nb = G->g->chain_block[c] + (has_prev ? ip : i) / FT_SEGMENT_BLOCK;
    double a[2], cc[2];
    if (has_prev)
        a[0] = ch->x[ip], a[1] = ch->y[ip];
    if (has_next)
        cc[0] = ch->x[in], cc[1] = ch->y[in];
    double bx = ch->x[i], by = ch->y[i], dx = raw->x[i] - bx, dy = raw->y[i] - by, b0[2] = {bx, by};
    static const double ts[] = {1.0, -1.0, 0.5, 0.25}; /* -1: the mirror, FT_GUARD_MIRROR only */
    for (int k = 0; k < 4; k++) {
        double t = ts[k];
        if (t < 0.0 && mode != FT_GUARD_MIRROR)
            continue;
        double b[2] = {bx + t * dx, by + t * dy};
        if (!blocked(G, c, nb, has_prev ? a : NULL, b0, b, has_next ? cc : NULL, sa, sb)) {
            ch->x[i] = b[0];
            ch->y[i] = b[1];
            return t;
        }
    }
    return 0.0;
}

static int check_pair(const ft_chain *b, const ft_chain *r, size_t c)
{
    if (b == NULL || r == NULL)
        return ft_error(FT_E_INVALID, "crossing guard: chain %zu is NULL", c);
    if (b->n != r->n || b->closed != r->closed)
        return ft_error(FT_E_INVALID, "crossing guard: chain %zu has %zu base and %zu raw vertices", c, b->n,
                        r->n);
    return FT_OK;
}

int ft_line_guard_moves(ft_chain *const *chains, const ft_chain *const *raw, size_t n, int mode,
                        ft_line_guard_stats *stats)
{
    if ((chains == NULL || raw == NULL) && n > 0)
        return ft_error(FT_E_INVALID, "crossing guard: NULL chains");
    for (size_t c = 0; c < n; c++) {
        int rc = check_pair(chains[c], raw[c], c);
        if (rc != FT_OK)
            return rc;
    }
    ft_segment_blocks g;
    int rc = ft_segment_blocks_build(&g, (const ft_chain *const *)chains, raw, n, mode == FT_GUARD_MIRROR);
    if (rc != FT_OK)
        return rc;
    guard G = {chains, &g};
    ft_line_guard_stats s = {0, 0, 0, 0};
    for (size_t c = 0; c < n; c++) {
        const ft_chain *r = raw[c];
        for (size_t i = 0; i < r->n; i++) {
            if (r->x[i] == chains[c]->x[i] && r->y[i] == chains[c]->y[i])
                continue;
            s.moves++;
            double t = guard_vertex(&G, c, i, r, mode);
            s.reduced += t > 0.0 && t < 1.0;
            s.dropped += t == 0.0;
            s.redrawn += t < 0.0;
        }
    }
    ft_segment_blocks_free(&g);
    if (stats) {
        stats->moves += s.moves;
        stats->reduced += s.reduced;
        stats->dropped += s.dropped;
        stats->redrawn += s.redrawn;
    }
    return FT_OK;
}
