/* fracterra — line/weed_shape.c: weeding that keeps the shape: like Dutton's weeding (1981, Fig. 6C; weed.c)
 * no segment is left shorter than SM, but of the two end vertices of a short segment the one dropped is the
 * one that carries less of the line's shape: the nearer to the chord of its two neighbours (Visvalingam &
 * Whyatt 1993 rank vertices by the area they add; the distance to the chord is the height of that
 * triangle). Dutton's greedy pass drops the vertex after a short segment whatever it is; after an
 * enhancement that is often a vertex of the input (the extreme point of a bay or headland that
 * Douglas-Peucker kept), and the coarse rulers lose it (docs/line-newfoundland.md).
 *
 * Passes over the chain: every segment shorter than min_seg whose two ends are still free drops one of them
 * (never an end point of an open chain); the neighbours of a dropped vertex are not touched again in that
 * pass, so every decision sees the chain as it is. Passes repeat until no segment is short or none can drop
 * a vertex (an open chain of two vertices); each pass is O(n). A ring keeps at least three vertices (the
 * triangle of ft_edit_ring_triangle when it would fall below).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "edit_internal.h"

#include <math.h>
#include <stdlib.h>

/* Distance of vertex i of c (k vertices) to the chord of its neighbours; INFINITY for an open chain's ends. */
static double chord_distance(const ft_chain *c, size_t k, size_t i)
{
    if (!c->closed && (i == 0 || i + 1 == k))
        return INFINITY;
    size_t p = i > 0 ? i - 1 : k - 1, n = i + 1 < k ? i + 1 : 0;
    double ux = c->x[n] - c->x[p], uy = c->y[n] - c->y[p];
    double vx = c->x[i] - c->x[p], vy = c->y[i] - c->y[p];
    double len = hypot(ux, uy);
    return len > 0.0 ? fabs(ux * vy - uy * vx) / len : hypot(vx, vy);
}

/* One pass over c: marks in drop[] the vertices to remove; returns how many. */
static size_t weed_pass(const ft_chain *c, double m2, unsigned char *drop, unsigned char *lock)
{
    size_t k = c->n, nseg = c->closed ? k : k - 1, ndrop = 0;
    for (size_t i = 0; i < k; i++)
        drop[i] = lock[i] = 0;
    for (size_t s = 0; s < nseg && k - ndrop > (c->closed ? 3u : 2u); s++) {
        size_t a = s, b = s + 1 < k ? s + 1 : 0;
        double dx = c->x[b] - c->x[a], dy = c->y[b] - c->y[a];
        if (dx * dx + dy * dy >= m2 || lock[a] || lock[b])
            continue;
        double ha = chord_distance(c, k, a), hb = chord_distance(c, k, b);
        if (isinf(ha) && isinf(hb))
            continue; /* an open chain of two vertices */
        size_t v = ha <= hb ? a : b;
        drop[v] = lock[v] = 1;
        lock[v > 0 ? v - 1 : k - 1] = 1;
        lock[v + 1 < k ? v + 1 : 0] = 1;
        ndrop++;
    }
    return ndrop;
}

int ft_line_weed_shape(const ft_chain *in, double min_seg, ft_chain **out)
{
    int rc = ft_edit_check_weed(in, min_seg, out);
    if (rc != FT_OK)
        return rc;
    ft_chain *c = ft_chain_copy(in);
    unsigned char *drop = ft_malloc(in->n ? 2 * in->n : 1);
    if (c == NULL || drop == NULL) {
        ft_chain_free(c);
        free(drop);
        return FT_E_NOMEM;
    }
    double m2 = min_seg * min_seg;
    while (weed_pass(c, m2, drop, drop + in->n) > 0) {
        size_t k = 0;
        for (size_t i = 0; i < c->n; i++)
            if (!drop[i]) {
                c->x[k] = c->x[i];
                c->y[k] = c->y[i];
                k++;
            }
        c->n = k;
    }
    free(drop);
    *out = c;
    return FT_OK;
}
