/* fracterra — src/line/equipaced.c: the equipaced polygon (Zhang, Yu & Fan 2008, "Equipaced
 * Polygon method", after Kaye and Clark): the chain is resampled at points equally spaced by s along its
 * arc length, s_k = k s (k = 0, 1, ...), and the length of the polygon through those points, closed by
 * the chain's end point (vertex 0 again for a ring), is L(s). As for the divider, L(s) ~ s^(1 - D),
 * D = 1 - slope of log L on log s. Unlike the divider, the spacing is measured along the chain, so the
 * polygon's sides are chords of at most s and the walk never skips a loop of the chain. O(n + L/s).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/line.h"
#include "line/line_dim_internal.h"

FT_WALK_INLINE void equipaced_impl(const ft_walk_src *wp, double s, double *length, double *steps, int d3)
{
    const ft_walk_src w = *wp;
    double a[3], q[3];
    ft_walk_vertex3(&w, 0, &a[0], &a[1], &a[2], d3);
    q[0] = a[0];
    q[1] = a[1];
    q[2] = a[2];
    double len = 0.0, need = s; /* arc length still to go to the next sample */
    size_t nsteps = 0;
    for (size_t k = 1; k < w.m; k++) {
        double b[3];
        ft_walk_vertex3(&w, k, &b[0], &b[1], &b[2], d3);
        double seg = ft_walk_dist(b[0] - a[0], b[1] - a[1], b[2] - a[2]), pos = 0.0;
        while (seg - pos >= need) {
            pos += need;
            double t = pos / seg, sp[3];
            for (int i = 0; i < 3; i++)
                sp[i] = a[i] + t * (b[i] - a[i]);
            len += ft_walk_dist(sp[0] - q[0], sp[1] - q[1], sp[2] - q[2]);
            q[0] = sp[0];
            q[1] = sp[1];
            q[2] = sp[2];
            nsteps++;
            need = s;
        }
        need -= seg - pos;
        a[0] = b[0];
        a[1] = b[1];
        a[2] = b[2];
    }
    *length = len + ft_walk_dist(a[0] - q[0], a[1] - q[1], a[2] - q[2]);
    *steps = (double)nsteps;
}

void ft_line_equipaced_length(const ft_chain *c, const double *z, double s, double *length, double *steps)
{
    ft_walk_src w;
    ft_walk_src_init(&w, c, 0);
    w.z = z;
    if (z)
        equipaced_impl(&w, s, length, steps, 1);
    else
        equipaced_impl(&w, s, length, steps, 0);
}
