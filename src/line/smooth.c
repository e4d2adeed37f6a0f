/* fracterra — line/smooth.c: Dutton's roundness smoothing (Dutton 1981, section "Smoothness", Fig. 7;
 * a generalization of Chaikin 1974): each vertex is "snipped off" between itself and the midpoints of
 * its two segments.
 *
 * A vertex V with neighbours P and N, M1 and M2 the midpoints of PV and VN, becomes the two vertices
 *     V + R (M1 - V)   and   V + R (M2 - V),      R in (0, 1] (the roundness),
 * so R = 0.5 gives Chaikin's quarter points (3V + P) / 4 and (3V + N) / 4, and R = 1 the midpoint polygon
 * (where the two cuts of one segment meet, the point is kept once). As in the enhancement, only vertices
 * whose two segments are in the window SM <= L < ST are cut, so a segment outside it keeps both of its
 * vertices; the end points of an open chain are kept. K passes repeat the cut.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "edit_internal.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#define MAX_PASSES 64

static int check_opts(const ft_smooth_opts *o)
{
    if (o == NULL)
        return ft_error(FT_E_INVALID, "smooth: NULL options");
    if (o->passes < 1 || o->passes > MAX_PASSES)
        return ft_error(FT_E_INVALID, "smoothing passes must be in [1,%d], got %d", MAX_PASSES, o->passes);
    if (!(o->roundness > 0.0 && o->roundness <= 1.0))
        return ft_error(FT_E_INVALID, "roundness must be in (0,1], got %g", o->roundness);
    return ft_edit_check_window(o->st, o->sm);
}

/* Appends (x, y) unless it repeats the last vertex written. */
static void put(ft_chain *c, double x, double y)
{
    if (c->n > 0 && c->x[c->n - 1] == x && c->y[c->n - 1] == y)
        return;
    c->x[c->n] = x;
    c->y[c->n] = y;
    c->n++;
}

static int smooth_pass(const ft_chain *in, double r, ft_edit_window w, ft_chain **out)
{
    size_t n = in->n;
    if (n > SIZE_MAX / 2)
        return ft_error(FT_E_NOMEM, "smooth: %zu vertices overflow", n);
    ft_chain *c = ft_chain_create(2 * n, in->closed);
    if (c == NULL)
        return FT_E_NOMEM;
    double h = 0.5 * r; /* V + R (M - V) = V + (R / 2) (neighbour - V) */
    for (size_t i = 0; i < n; i++) {
        int interior = in->closed || (i > 0 && i + 1 < n);
        size_t ip = i > 0 ? i - 1 : n - 1, in_ = i + 1 < n ? i + 1 : 0;
        double vx = in->x[i], vy = in->y[i];
        if (interior && ft_edit_in_window(w, ft_edit_dist2(in, ip, i)) &&
            ft_edit_in_window(w, ft_edit_dist2(in, i, in_))) {
            put(c, vx + h * (in->x[ip] - vx), vy + h * (in->y[ip] - vy));
            put(c, vx + h * (in->x[in_] - vx), vy + h * (in->y[in_] - vy));
        } else {
            put(c, vx, vy);
        }
    }
    if (c->closed && c->n > 1 && c->x[c->n - 1] == c->x[0] && c->y[c->n - 1] == c->y[0])
        c->n--;
    *out = c;
    return FT_OK;
}

int ft_line_smooth(const ft_chain *in, const ft_smooth_opts *opts, ft_chain **out)
{
    int rc = ft_edit_check_chain("smooth", in, out);
    if (rc == FT_OK)
        rc = check_opts(opts);
    if (rc != FT_OK)
        return rc;
    ft_edit_window w = ft_edit_window_make(opts->st, opts->sm);
    ft_chain *cur = NULL;
    for (int k = 0; k < opts->passes && rc == FT_OK; k++) {
        ft_chain *next = NULL;
        rc = smooth_pass(cur ? cur : in, opts->roundness, w, &next);
        ft_chain_free(cur);
        cur = next;
    }
    if (rc != FT_OK) {
        ft_chain_free(cur);
        return rc;
    }
    *out = cur;
    return FT_OK;
}
