/* fracterra — src/line/hybrid_walk.c: the hybrid walk of Clarke & Schweizer (1991, "Measuring the
 * fractal dimension of natural surfaces using a robust fractal estimator"; listed by Zhang, Yu & Fan
 * 2008, beside the structured walk and the equipaced polygon).
 *
 * Reading of the method used here: it is the walking divider (divider.c) restricted to the chain's
 * vertices. From the current vertex P the walk moves to the first following vertex V at distance
 * |V - P| >= d (no circle-segment intersection: every divider point is a digitized point, which is what
 * makes the walk cheap and independent of how segments are interpolated). Such a step overshoots d, so
 * each step is counted by interpolation as |V - P| / d steps rather than as one: N(d) = sum |V - P| / d,
 * and L(d) = N(d) d is the length of the vertex polygon of the walk, last partial step (to the end, or to
 * vertex 0 for a ring) included. D = 1 - slope of log L on log d, as for the divider. Open chains are
 * walked from both ends and averaged, like the divider. O(n) per ruler.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/line.h"
#include "line/line_dim_internal.h"

FT_WALK_INLINE double hybrid_walk_impl(const ft_walk_src *w, double r, int d3)
{
    const double r2 = r * r;
    double p[3];
    ft_walk_vertex3(w, 0, &p[0], &p[1], &p[2], d3);
    double len = 0.0;
    for (size_t k = 1; k < w->m; k++) {
        double b[3];
        ft_walk_vertex3(w, k, &b[0], &b[1], &b[2], d3);
        double dx = b[0] - p[0], dy = b[1] - p[1], dz = b[2] - p[2], d2 = dx * dx + dy * dy + dz * dz;
        if (d2 >= r2) {
            len += sqrt(d2);
            p[0] = b[0];
            p[1] = b[1];
            p[2] = b[2];
        }
    }
    double e[3];
    ft_walk_vertex3(w, w->m - 1, &e[0], &e[1], &e[2], d3);
    return len + ft_walk_dist(e[0] - p[0], e[1] - p[1], e[2] - p[2]);
}

static double hybrid_walk(const ft_walk_src *w, double r)
{
    return w->z ? hybrid_walk_impl(w, r, 1) : hybrid_walk_impl(w, r, 0);
}

void ft_line_hybrid_length(const ft_chain *c, const double *z, double r, int both_ends, double *length,
                           double *steps)
{
    ft_walk_src w;
    ft_walk_src_init(&w, c, 0);
    w.z = z;
    double len = hybrid_walk(&w, r);
    if (!c->closed && both_ends) {
        ft_walk_src_init(&w, c, 1);
        w.z = z;
        len = 0.5 * (len + hybrid_walk(&w, r));
    }
    *length = len;
    *steps = len / r;
}
