/* fracterra — src/line/equipaced.c: the equipaced polygon (Zhang, Yu & Fan 2008, seeds 002, "Equipaced
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

void ft_line_equipaced_length(const ft_chain *c, double s, double *length, double *steps)
{
    ft_walk_src w;
    ft_walk_src_init(&w, c, 0);
    double ax, ay, qx, qy;
    ft_walk_vertex(&w, 0, &ax, &ay);
    qx = ax;
    qy = ay;
    double len = 0.0, need = s; /* arc length still to go to the next sample */
    size_t nsteps = 0;
    for (size_t k = 1; k < w.m; k++) {
        double bx, by;
        ft_walk_vertex(&w, k, &bx, &by);
        double seg = hypot(bx - ax, by - ay), pos = 0.0;
        while (seg - pos >= need) {
            pos += need;
            double t = pos / seg, sx = ax + t * (bx - ax), sy = ay + t * (by - ay);
            len += hypot(sx - qx, sy - qy);
            qx = sx;
            qy = sy;
            nsteps++;
            need = s;
        }
        need -= seg - pos;
        ax = bx;
        ay = by;
    }
    *length = len + hypot(ax - qx, ay - qy);
    *steps = (double)nsteps;
}
