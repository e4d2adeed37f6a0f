/* fracterra — line/smooth.c: Dutton's roundness smoothing (Dutton 1981, section "Smoothness", Fig. 7;
 * a generalization of Chaikin 1974): each vertex is "snipped off" between itself and the midpoints of
 * its two segments.
 *
 * A vertex V with neighbours P and N, M1 and M2 the midpoints of PV and VN, becomes the two vertices
 *     V + R (M1 - V)   and   V + R (M2 - V),      R in (0, 1] (the roundness),
 * so R = 0.5 gives Chaikin's quarter points (3V + P) / 4 and (3V + N) / 4, and R = 1 the midpoint polygon
 * (where the two cuts of one segment meet, the point is kept once). As in the enhancement, only vertices
 * whose two segments are in the window SM <= L < ST are cut, so a segment outside it keeps both of its
 * vertices; the end points of an open chain are kept. K passes repeat the cut. Unless allow_crossings, each
 * pass goes through the crossing guard (move_guard.c): a cut that would make a segment cross or touch another
 * is halved, then not made.
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

/* One pass: base (if wanted) has each cut vertex twice at V, raw the two cuts; the driver removes repeated
 * vertices. */
static int smooth_pass(const ft_chain *in, double r, ft_edit_window w, ft_chain **base, ft_chain **raw)
{
    size_t n = in->n;
    if (n > SIZE_MAX / 2)
        return ft_error(FT_E_NOMEM, "smooth: %zu vertices overflow", n);
    ft_chain *c = ft_chain_create(2 * n, in->closed), *b = base ? ft_chain_create(2 * n, in->closed) : NULL;
    if (c == NULL || (base && b == NULL)) {
        ft_chain_free(c);
        ft_chain_free(b);
        return FT_E_NOMEM;
    }
    double h = 0.5 * r; /* V + R (M - V) = V + (R / 2) (neighbour - V) */
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        int interior = in->closed || (i > 0 && i + 1 < n);
        size_t ip = i > 0 ? i - 1 : n - 1, in_ = i + 1 < n ? i + 1 : 0;
        double vx = in->x[i], vy = in->y[i];
        if (b) {
            b->x[k] = vx;
            b->y[k] = vy;
        }
        if (interior && ft_edit_in_window(w, ft_edit_dist2(in, ip, i)) &&
            ft_edit_in_window(w, ft_edit_dist2(in, i, in_))) {
            c->x[k] = vx + h * (in->x[ip] - vx);
            c->y[k] = vy + h * (in->y[ip] - vy);
            k++;
            if (b) {
                b->x[k] = vx;
                b->y[k] = vy;
            }
            c->x[k] = vx + h * (in->x[in_] - vx);
            c->y[k] = vy + h * (in->y[in_] - vy);
        } else {
            c->x[k] = vx;
            c->y[k] = vy;
        }
        k++;
    }
    c->n = k;
    if (b) {
        b->n = k;
        *base = b;
    }
    *raw = c;
    return FT_OK;
}

int ft_line_pass_smooth(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw)
{
    if (raw == NULL)
        return ft_error(FT_E_INVALID, "smooth: NULL output pointer");
    *raw = NULL;
    if (base)
        *base = NULL;
    const ft_smooth_opts *o = ctx;
    ft_chain *dummy = NULL;
    int rc = ft_edit_check_chain("smooth", in, &dummy);
    if (rc == FT_OK)
        rc = check_opts(o);
    if (rc != FT_OK)
        return rc;
    return smooth_pass(in, o->roundness, ft_edit_window_make(o->st, o->sm), base, raw);
}

int ft_line_smooth(const ft_chain *in, const ft_smooth_opts *opts, ft_chain **out)
{
    ft_smooth_opts taken = FT_SMOOTH_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_smooth_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    int rc = ft_edit_check_chain("smooth", in, out);
    if (rc == FT_OK)
        rc = check_opts(opts);
    if (rc == FT_OK)
        rc = ft_line_run_passes_into(&in, 1, ft_line_pass_smooth, opts, opts->passes, !opts->allow_crossings, NULL,
                                     out);
    return rc;
}
