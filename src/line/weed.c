/* fracterra — line/weed.c: weeding, the step of Dutton's Newfoundland sequence (Dutton 1981, section
 * "Straightness and Smoothing Tolerances", Fig. 6C) that removes "all segments smaller than SM" after
 * fractalizing and before smoothing.
 *
 * Greedy from the first vertex: a vertex is kept when it lies at least min_seg from the last kept one.
 * The end of an open chain is always kept, so while the last segment is still too short the kept vertex
 * before it is dropped (never the first). A ring closes on its first vertex the same way. Afterwards no
 * segment is shorter than min_seg, except when the whole chain is: an open chain then keeps its two end
 * points, and a ring that would fall below three vertices keeps the triangle of ft_edit_ring_triangle
 * (vertex 0, the vertex farthest from it, the vertex farthest from their line).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "edit_internal.h"

#include <math.h>
#include <stdlib.h>

static double d2(const ft_chain *c, size_t i, double x, double y)
{
    double dx = c->x[i] - x, dy = c->y[i] - y;
    return dx * dx + dy * dy;
}

/* Keeps, in c (a copy being compacted in place), vertices at least sqrt(m2) apart; ex, ey is where the
 * chain must end (the last vertex of an open chain, the first of a ring), not written. */
static void weed_greedy(ft_chain *c, double m2, double ex, double ey)
{
    size_t n = c->n, k = 1;
    for (size_t i = 1; i < n; i++) {
        if (d2(c, k - 1, c->x[i], c->y[i]) >= m2) {
            c->x[k] = c->x[i];
            c->y[k] = c->y[i];
            k++;
        }
    }
    while (k > 1 && d2(c, k - 1, ex, ey) < m2)
        k--;
    c->n = k;
}

int ft_line_weed(const ft_chain *in, double min_seg, ft_chain **out)
{
    int rc = ft_edit_check_weed(in, min_seg, out);
    if (rc != FT_OK)
        return rc;
    ft_chain *c = ft_chain_copy(in);
    if (c == NULL)
        return FT_E_NOMEM;
    double m2 = min_seg * min_seg;
    if (c->closed) {
        weed_greedy(c, m2, in->x[0], in->y[0]);
        if (c->n < 3) {
            size_t t[3];
            ft_edit_ring_triangle(in, t);
            for (size_t j = 0; j < 3; j++) {
                c->x[j] = in->x[t[j]];
                c->y[j] = in->y[t[j]];
            }
            c->n = 3;
        }
    } else {
        c->n = in->n - 1; /* the greedy pass runs up to the vertex before the end */
        weed_greedy(c, m2, in->x[in->n - 1], in->y[in->n - 1]);
        c->x[c->n] = in->x[in->n - 1];
        c->y[c->n] = in->y[in->n - 1];
        c->n++;
    }
    *out = c;
    return FT_OK;
}
