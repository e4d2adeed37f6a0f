/* fracterra — src/urban/boundary_layer.c: the midpoint-subdivision generator (boundary.c; Zhang, Yu & Fan
 * 2008, §2.2.3) over a whole layer. Polygon layers are coverages: through ft_line_apply_layer
 * each arc of the arc-node topology is generated once with its nodes fixed, and the rings rebuilt from the
 * arcs, so the two sides of a shared boundary get the same detail. No stream bookkeeping is needed for
 * that: a segment's random stream is keyed by its own end points (boundary.c), so each arc's detail is the
 * same whatever the order in which the topology lists the arcs.
 *
 * The maximum threshold defaults to the average chord length of Eqs. 11-13 taken over the whole layer
 * (every chord of every part): the paper computes it over "the curve", the whole boundary being
 * simulated; taken per arc it would make every two-vertex arc its own average and replace it.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/line.h"
#include "fracterra/urban.h"
#include "internal.h"
#include "urban/urban_internal.h"

int ft_urban_op_boundary(const ft_chain *in, const void *opts, ft_chain **out)
{
    if (opts == NULL)
        return ft_error(FT_E_INVALID, "boundary: NULL options");
    return ft_urban_boundary(in, opts, out);
}

int ft_urban_layer_chord_avg(const ft_layer *l, double *avg)
{
    if (l == NULL || avg == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_layer_chord_avg: NULL %s", l == NULL ? "layer" : "avg");
    *avg = 0.0;
    double length = 0.0;
    size_t nseg = 0;
    for (size_t p = 0; p < l->nparts; p++) {
        const ft_chain *c = l->parts[p].chain;
        if (c == NULL)
            continue;
        length += ft_chain_length(c);
        nseg += ft_chain_segments(c);
    }
    if (nseg == 0)
        return ft_error(FT_E_EMPTY, "boundary: the layer has no segment (%zu part%s)", l->nparts,
                        l->nparts == 1 ? "" : "s");
    *avg = length / (double)nseg; /* Eqs. 11-13 */
    return FT_OK;
}

/* Input segments longer than max (kept unchanged), over every part. */
static size_t count_kept(const ft_layer *l, double max)
{
    const double keep_above = max * (1.0 + 1e-12);
    size_t kept = 0;
    for (size_t p = 0; p < l->nparts; p++) {
        const ft_chain *c = l->parts[p].chain;
        size_t nseg = c != NULL ? ft_chain_segments(c) : 0;
        for (size_t i = 0; i < nseg; i++) {
            size_t j = i + 1 == c->n ? 0 : i + 1;
            kept += hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]) > keep_above;
        }
    }
    return kept;
}

int ft_urban_boundary_layer(ft_layer *l, const ft_boundary_opts *o, int coverage, ft_boundary_info *info)
{
    ft_boundary_opts taken = FT_BOUNDARY_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (o != NULL) {
        if (FT_OPTS_TAKE(taken, o, ft_boundary_opts) != FT_OK)
            return FT_E_INVALID;
        o = &taken;
    }
    if (l == NULL || o == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_boundary_layer: NULL %s", l == NULL ? "layer" : "options");
    int rc = ft_urban_boundary_check(o);
    if (rc != FT_OK)
        return rc;
    rc = ft_layer_check_finite(l);
    if (rc != FT_OK)
        return rc;
    double avg = 0.0;
    rc = ft_urban_layer_chord_avg(l, &avg);
    if (rc != FT_OK)
        return rc;
    ft_boundary_opts run = *o;
    if (run.max == 0.0) {
        if (avg < o->min)
            return ft_error(FT_E_INVALID, "boundary: the layer's average chord length %g (the default max) is "
                            "less than min (%g): lower min or set max", avg, o->min);
        run.max = avg;
    }
    ft_boundary_info done = {ft_layer_vertex_count(l), 0, run.max, count_kept(l, run.max), {0, 0, 0, 0}};
    rc = o->allow_crossings ? ft_line_apply_layer(l, ft_urban_op_boundary, &run, coverage)
                            : ft_urban_boundary_guarded(l, o, run.max, coverage, &done.guard);
    if (rc != FT_OK)
        return rc;
    done.vertices_out = ft_layer_vertex_count(l);
    if (info != NULL)
        *info = done;
    return FT_OK;
}
