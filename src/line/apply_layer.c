/* fracterra — line/apply_layer.c: a chain operation (Dutton 1981 enhancement, smoothing, weeding,
 * Douglas-Peucker, loop removal) applied to a whole layer, and on coverages through the arc-node
 * topology, so that Dutton's thematic maps of states keep their neighbours coincident.
 *
 * Plain mode: every part is processed on its own (rings as rings, lines as open chains).
 * Coverage mode (coverage != 0 and the layer has rings): ft_layer_build_topology(l, 0) stores each
 * boundary shared by adjacent rings once, as an arc from node to node; each open arc is processed once
 * as an open chain, whose end points (the nodes) every operation keeps — checked here, exactly — and a
 * closed arc (a ring with no node) as a ring; ft_layer_apply_topology then rebuilds every ring from its
 * arcs, so both sides of a shared boundary get the same vertices. A ring that would fall below three
 * vertices (two arcs simplified to straight segments) keeps its original arcs. Line parts of the layer
 * are processed as in plain mode. The topology is dropped afterwards.
 * Either way every result is computed before any part is replaced: on failure the layer is unchanged
 * and the error names the feature, part or arc.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "line/guard_schedule.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>

/* ---- the operations as ft_line_op ---------------------------------------------------------------- */

static int need_opts(const char *op, const void *opts)
{
    return opts != NULL ? FT_OK : ft_error(FT_E_INVALID, "%s: NULL options", op);
}

int ft_line_op_enhance(const ft_chain *in, const void *opts, ft_chain **out)
{
    int rc = need_opts("enhance", opts);
    return rc == FT_OK ? ft_line_enhance(in, opts, out) : rc;
}

int ft_line_op_smooth(const ft_chain *in, const void *opts, ft_chain **out)
{
    int rc = need_opts("smooth", opts);
    return rc == FT_OK ? ft_line_smooth(in, opts, out) : rc;
}

int ft_line_op_weed(const ft_chain *in, const void *opts, ft_chain **out)
{
    int rc = need_opts("weed", opts);
    return rc == FT_OK ? ft_line_weed(in, *(const double *)opts, out) : rc;
}

int ft_line_op_weed_shape(const ft_chain *in, const void *opts, ft_chain **out)
{
    int rc = need_opts("weed", opts);
    return rc == FT_OK ? ft_line_weed_shape(in, *(const double *)opts, out) : rc;
}

int ft_line_op_simplify(const ft_chain *in, const void *opts, ft_chain **out)
{
    int rc = need_opts("simplify", opts);
    return rc == FT_OK ? ft_line_simplify(in, *(const double *)opts, out) : rc;
}

int ft_line_op_remove_loops(const ft_chain *in, const void *opts, ft_chain **out)
{
    (void)opts;
    return ft_line_remove_loops(in, out);
}

/* ---- helpers ----------------------------------------------------------------------------------- */

static int is_ring(const ft_part *p)
{
    return p->role != FT_ROLE_LINE && p->chain != NULL && p->chain->closed;
}

/* Runs op; a failure's message is prefixed with what was processed (e.g. "feature 3, part 1"). */
static int run_op(ft_line_op op, const void *opts, const ft_chain *in, ft_chain **out, const char *what)
{
    *out = NULL;
    int rc = op(in, opts, out);
    if (rc == FT_OK && *out == NULL)
        rc = ft_error(FT_E_INVALID, "the operation returned no chain");
    if (rc != FT_OK) {
        char msg[512];
        snprintf(msg, sizeof msg, "%s", ft_last_error());
        ft_chain_free(*out);
        *out = NULL;
        return ft_error(rc, "%s: %s", what, msg);
    }
    return FT_OK;
}

static int64_t part_fid(const ft_layer *l, size_t p)
{
    return l->features[l->parts[p].feature].fid;
}

static void free_chains(ft_chain **c, size_t n)
{
    for (size_t i = 0; c != NULL && i < n; i++)
        ft_chain_free(c[i]);
    free(c);
}

/* fresh[p] = op(part p) for every part (but rings when skip_rings: coverage mode does them by arcs). */
static int process_parts(const ft_layer *l, ft_line_op op, const void *opts, int skip_rings, ft_chain **fresh)
{
    for (size_t p = 0; p < l->nparts; p++) {
        if (l->parts[p].chain == NULL || (skip_rings && is_ring(&l->parts[p])))
            continue;
        char what[96];
        snprintf(what, sizeof what, "feature %" PRId64 ", part %zu", part_fid(l, p), p);
        int rc = run_op(op, opts, l->parts[p].chain, &fresh[p], what);
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

static void replace_parts(ft_layer *l, ft_chain **fresh)
{
    for (size_t p = 0; p < l->nparts; p++)
        if (fresh[p] != NULL) {
            ft_chain_free(l->parts[p].chain);
            l->parts[p].chain = fresh[p];
            fresh[p] = NULL;
        }
}

/* ---- coverage mode ------------------------------------------------------------------------------- */

static int same_ends(const ft_chain *a, const ft_chain *b)
{
    return b->n >= 2 && a->x[0] == b->x[0] && a->y[0] == b->y[0] && a->x[a->n - 1] == b->x[b->n - 1] &&
           a->y[a->n - 1] == b->y[b->n - 1];
}

/* edited[a] = op(arc a); open arcs must keep their end points. */
static int process_arcs(const ft_layer *l, ft_line_op op, const void *opts, ft_chain **edited)
{
    const ft_topology *t = l->topology;
    for (size_t a = 0; a < t->narcs; a++) {
        int side = t->arc_left[a] >= 0 ? t->arc_left[a] : t->arc_right[a];
        char what[128];
        if (side >= 0)
            snprintf(what, sizeof what, "arc %zu (boundary of feature %" PRId64 ")", a, part_fid(l, (size_t)side));
        else
            snprintf(what, sizeof what, "arc %zu", a);
        int rc = run_op(op, opts, t->arcs[a], &edited[a], what);
        if (rc != FT_OK)
            return rc;
        if (!t->arcs[a]->closed && (edited[a]->closed || !same_ends(t->arcs[a], edited[a])))
            return ft_error(FT_E_INVALID, "%s: the operation moved the arc's end points (nodes)", what);
    }
    return FT_OK;
}

static size_t ring_vertices(const ft_topology *t, size_t p, ft_chain *const *arcs)
{
    size_t nv = 0;
    for (size_t r = 0; r < t->nrings[p]; r++) {
        const ft_chain *c = arcs[t->rings[p][r].arc];
        nv += c->closed ? c->n : c->n - 1;
    }
    return nv;
}

/* A ring whose edited arcs would give it fewer than 3 vertices gets its original arcs back. */
static int restore_collapsed(const ft_topology *t, ft_chain **edited)
{
    unsigned char *restored = ft_calloc(t->narcs ? t->narcs : 1, 1);
    if (restored == NULL)
        return FT_E_NOMEM;
    int changed = 1;
    while (changed) {
        changed = 0;
        for (size_t p = 0; p < t->nparts; p++) {
            if (t->nrings[p] == 0 || ring_vertices(t, p, edited) >= 3)
                continue;
            for (size_t r = 0; r < t->nrings[p]; r++) {
                size_t a = t->rings[p][r].arc;
                if (restored[a])
                    continue;
                ft_chain *orig = ft_chain_copy(t->arcs[a]);
                if (orig == NULL) {
                    free(restored);
                    return FT_E_NOMEM;
                }
                ft_chain_free(edited[a]);
                edited[a] = orig;
                restored[a] = changed = 1;
            }
        }
    }
    free(restored);
    return FT_OK;
}

/* Coverage edits committed when rc is FT_OK: the edited arcs swapped into the topology, the rings rebuilt
 * from them, the other parts replaced by fresh. Frees what is left in both arrays; returns the outcome. */
static int commit_edits(ft_layer *l, ft_chain **edited, ft_chain **fresh, int rc)
{
    ft_topology *t = l->topology;
    if (rc == FT_OK) {
        for (size_t a = 0; a < t->narcs; a++) {
            ft_chain *old = t->arcs[a];
            t->arcs[a] = edited[a];
            edited[a] = old;
        }
        rc = ft_layer_apply_topology(l);
    }
    if (rc == FT_OK)
        replace_parts(l, fresh);
    free_chains(edited, edited ? t->narcs : 0);
    free_chains(fresh, fresh ? l->nparts : 0);
    return rc;
}

static int apply_coverage(ft_layer *l, ft_line_op op, const void *opts)
{
    int rc = ft_layer_build_topology(l, 0.0);
    if (rc != FT_OK)
        return rc;
    ft_topology *t = l->topology;
    ft_chain **edited = ft_calloc(t->narcs ? t->narcs : 1, sizeof *edited);
    ft_chain **fresh = ft_calloc(l->nparts ? l->nparts : 1, sizeof *fresh);
    if (edited == NULL || fresh == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = process_arcs(l, op, opts, edited);
    if (rc == FT_OK)
        rc = restore_collapsed(t, edited);
    if (rc == FT_OK)
        rc = process_parts(l, op, opts, 1, fresh);
    rc = commit_edits(l, edited, fresh, rc);
    ft_topology_free(l->topology);
    l->topology = NULL;
    return rc;
}

static int has_rings(const ft_layer *l)
{
    for (size_t p = 0; p < l->nparts; p++)
        if (is_ring(&l->parts[p]))
            return 1;
    return 0;
}

/* ---- pass-wise operations over one chain set (guarded_passes.c) ------------------------------------ */

/* The chain set of a layer: the arcs of its topology (coverage) then every other part, or every part.
 * who[k] = arc index (coverage, k < narcs) or part index. */
typedef struct {
    ft_chain **chains;
    size_t n, narcs, *who;
} chain_set;

static void set_free(chain_set *s)
{
    free_chains(s->chains, s->n);
    free(s->who);
}

static int set_collect(const ft_layer *l, int coverage, chain_set *s)
{
    const ft_topology *t = coverage ? l->topology : NULL;
    size_t cap = l->nparts + (t ? t->narcs : 0);
    *s = (chain_set){ft_calloc(cap ? cap : 1, sizeof(ft_chain *)), 0, 0, ft_malloc((cap ? cap : 1) * sizeof(size_t))};
    if (s->chains == NULL || s->who == NULL)
        return FT_E_NOMEM;
    for (size_t a = 0; t && a < t->narcs; a++) {
        if ((s->chains[s->n] = ft_chain_copy(t->arcs[a])) == NULL)
            return FT_E_NOMEM;
        s->who[s->n++] = a;
    }
    s->narcs = s->n;
    for (size_t p = 0; p < l->nparts; p++) {
        if (l->parts[p].chain == NULL || (t && is_ring(&l->parts[p])))
            continue;
        if ((s->chains[s->n] = ft_chain_copy(l->parts[p].chain)) == NULL)
            return FT_E_NOMEM;
        s->who[s->n++] = p;
    }
    return FT_OK;
}

/* Coverage: the edited arcs back into the topology, the rings rebuilt, the other parts replaced. */
static int set_commit_coverage(ft_layer *l, chain_set *s)
{
    ft_topology *t = l->topology;
    ft_chain **edited = ft_calloc(t->narcs ? t->narcs : 1, sizeof *edited);
    ft_chain **fresh = ft_calloc(l->nparts ? l->nparts : 1, sizeof *fresh);
    int rc = edited == NULL || fresh == NULL ? FT_E_NOMEM : FT_OK;
    for (size_t k = 0; k < s->n && rc == FT_OK; k++) {
        ft_chain **slot = k < s->narcs ? &edited[s->who[k]] : &fresh[s->who[k]];
        *slot = s->chains[k];
        s->chains[k] = NULL;
        size_t a = s->who[k];
        if (k < s->narcs && !t->arcs[a]->closed && (edited[a]->closed || !same_ends(t->arcs[a], edited[a])))
            rc = ft_error(FT_E_INVALID, "arc %zu: the operation moved the arc's end points (nodes)", a);
    }
    return commit_edits(l, edited, fresh, rc);
}

int ft_line_apply_layer_passes(ft_layer *l, ft_line_pass_fn pass, const void *ctx, int passes, int coverage,
                               int guard, ft_line_guard_stats *stats)
{
    if (l == NULL || pass == NULL)
        return ft_error(FT_E_INVALID, "apply to layer: NULL layer or pass");
    int rc = ft_layer_check_finite(l);
    if (rc != FT_OK)
        return rc;
    coverage = coverage && has_rings(l);
    if (coverage && (rc = ft_layer_build_topology(l, 0.0)) != FT_OK)
        return rc;
    chain_set s;
    rc = set_collect(l, coverage, &s);
    ft_line_guard_stats st = {0, 0, 0, 0};
    if (rc == FT_OK)
        rc = ft_line_run_passes(s.chains, s.n, pass, ctx, passes, guard, &st);
    if (rc == FT_OK && coverage) {
        rc = set_commit_coverage(l, &s);
    } else if (rc == FT_OK) {
        for (size_t k = 0; k < s.n; k++) {
            ft_chain_free(l->parts[s.who[k]].chain);
            l->parts[s.who[k]].chain = s.chains[k];
            s.chains[k] = NULL;
        }
    }
    set_free(&s);
    if (coverage) {
        ft_topology_free(l->topology);
        l->topology = NULL;
    }
    if (rc == FT_OK && stats)
        ft_line_guard_stats_add(stats, &st);
    return rc;
}

int ft_line_enhance_layer(ft_layer *l, const ft_dutton_opts *opts, int coverage, ft_dutton_plan *plan,
                          ft_line_guard_stats *stats)
{
    ft_dutton_opts taken = FT_DUTTON_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_dutton_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    if (l == NULL)
        return ft_error(FT_E_INVALID, "enhance: NULL layer");
    int rc = ft_layer_check_finite(l);
    if (rc != FT_OK)
        return rc;
    const ft_chain **parts = ft_malloc((l->nparts ? l->nparts : 1) * sizeof *parts);
    if (parts == NULL)
        return FT_E_NOMEM;
    size_t n = 0;
    for (size_t p = 0; p < l->nparts; p++)
        if (l->parts[p].chain != NULL)
            parts[n++] = l->parts[p].chain;
    ft_dutton_plan pl;
    rc = ft_dutton_plan_make(parts, n, opts, &pl);
    free(parts);
    if (rc == FT_OK)
        rc = ft_line_apply_layer_passes(l, ft_line_pass_enhance, &pl, opts->iterations, coverage,
                                        !opts->allow_crossings, stats);
    if (rc == FT_OK && plan)
        *plan = pl;
    return rc;
}

int ft_line_smooth_layer(ft_layer *l, const ft_smooth_opts *opts, int coverage, ft_line_guard_stats *stats)
{
    ft_smooth_opts taken = FT_SMOOTH_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_smooth_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    if (opts == NULL)
        return ft_error(FT_E_INVALID, "smooth: NULL options");
    return ft_line_apply_layer_passes(l, ft_line_pass_smooth, opts, opts->passes, coverage, !opts->allow_crossings,
                                      stats);
}

/* ---- entry ---------------------------------------------------------------------------------------- */

int ft_line_apply_layer(ft_layer *l, ft_line_op op, const void *opts, int coverage)
{
    if (l == NULL)
        return ft_error(FT_E_INVALID, "apply to layer: NULL layer");
    if (op == NULL)
        return ft_error(FT_E_INVALID, "apply to layer: NULL operation");
    int rc = ft_layer_check_finite(l);
    if (rc != FT_OK)
        return rc;
    if (coverage && has_rings(l))
        return apply_coverage(l, op, opts);
    ft_chain **fresh = ft_calloc(l->nparts ? l->nparts : 1, sizeof *fresh);
    if (fresh == NULL)
        return FT_E_NOMEM;
    rc = process_parts(l, op, opts, 0, fresh);
    if (rc == FT_OK)
        replace_parts(l, fresh);
    free_chains(fresh, l->nparts);
    return rc;
}
