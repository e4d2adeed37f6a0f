/* fracterra — line/edit_internal.h: helpers shared by the chain editing operations of Dutton (1981)
 * (enhancement, smoothing, weeding, Douglas-Peucker, loop removal): input checks with messages that name
 * the value, the [SM, ST) segment window, and the three-vertex fallback that keeps rings rings.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_EDIT_INTERNAL_H
#define FRACTERRA_LINE_EDIT_INTERNAL_H

#include <math.h>
#include <stddef.h>

#include "fracterra/core.h"
#include "internal.h"

/** A chain an operation can read: ft_chain_check_operand (src/internal.h), shared with Contour's operators. */
static inline int ft_edit_check_chain(const char *op, const ft_chain *in, ft_chain **out)
{
    return ft_chain_check_operand(op, in, out);
}

/** The arguments of a weeding (weed.c, weed_shape.c): a readable chain and 0 <= min_seg finite. */
static inline int ft_edit_check_weed(const ft_chain *in, double min_seg, ft_chain **out)
{
    int rc = ft_edit_check_chain("weed", in, out);
    if (rc == FT_OK && (!(min_seg >= 0.0) || !isfinite(min_seg)))
        rc = ft_error(FT_E_INVALID, "weeding length (sm) must be finite and >= 0, got %g", min_seg);
    return rc;
}

/** The segment window of Dutton's tolerances: st > 0 (may be INFINITY), 0 <= sm finite, sm <= st. */
static inline int ft_edit_check_window(double st, double sm)
{
    if (!(sm >= 0.0) || !isfinite(sm))
        return ft_error(FT_E_INVALID, "sm must be finite and >= 0, got %g", sm);
    if (!(st > 0.0))
        return ft_error(FT_E_INVALID, "st must be > 0, got %g", st);
    if (st < sm)
        return ft_error(FT_E_INVALID, "st must be >= sm, got st = %g and sm = %g", st, sm);
    return FT_OK;
}

/** Squared tolerances for the window test on squared lengths. */
typedef struct {
    double st2, sm2;
} ft_edit_window;

static inline ft_edit_window ft_edit_window_make(double st, double sm)
{
    ft_edit_window w = {st * st, sm * sm};
    return w;
}

/** 1 if a segment of squared length len2 is in [sm, st): shorter than ST and not shorter than SM. */
static inline int ft_edit_in_window(ft_edit_window w, double len2)
{
    return len2 < w.st2 && len2 >= w.sm2;
}

static inline double ft_edit_dist2(const ft_chain *c, size_t i, size_t j)
{
    double dx = c->x[j] - c->x[i], dy = c->y[j] - c->y[i];
    return dx * dx + dy * dy;
}

/** The vertex farthest from vertex 0 (ties: the lowest index). Needs n >= 2. */
static inline size_t ft_edit_farthest_from_first(const ft_chain *c)
{
    size_t f = 1;
    double best = -1.0;
    for (size_t k = 1; k < c->n; k++) {
        double d = ft_edit_dist2(c, 0, k);
        if (d > best) {
            best = d;
            f = k;
        }
    }
    return f;
}

/** The three vertices a collapsing ring keeps: vertex 0, the vertex f farthest from it, and the vertex
 *  farthest from the line through both (ties: the lowest index). i[0] < i[1] < i[2] in ring order.
 *  Needs n >= 3. */
static inline void ft_edit_ring_triangle(const ft_chain *c, size_t i[3])
{
    size_t f = ft_edit_farthest_from_first(c), g = f == 1 ? 2 : 1;
    double ux = c->x[f] - c->x[0], uy = c->y[f] - c->y[0], best = -1.0;
    for (size_t k = 1; k < c->n; k++) {
        if (k == f)
            continue;
        double d = fabs(ux * (c->y[k] - c->y[0]) - uy * (c->x[k] - c->x[0]));
        if (d > best) {
            best = d;
            g = k;
        }
    }
    i[0] = 0;
    i[1] = f < g ? f : g;
    i[2] = f < g ? g : f;
}

/** ft_line_run_passes (guarded_passes.c) from chains the caller keeps: out[c] receives chain c's result (left
 *  untouched on failure); the first pass reads in[c] itself, so nothing is copied. */
int ft_line_run_passes_into(const ft_chain *const *in, size_t n, ft_line_pass_fn pass, const void *ctx, int passes,
                            int guard, ft_line_guard_stats *stats, ft_chain **out);

#endif /* FRACTERRA_LINE_EDIT_INTERNAL_H */
