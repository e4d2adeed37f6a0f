/* fracterra — line/guarded_passes.c: runs a vertex-moving operation (Dutton 1981 enhancement, roundness
 * smoothing) pass by pass over a set of chains, every pass through the crossing guard (move_guard.c) over
 * the whole set, so that no chain of the set crosses itself or another.
 *
 * A pass computes base and raw chains for every chain (independently, in chain order), then either guards
 * the moves of the whole set at once or takes the raw positions (guard = 0: the raw algorithm), then drops
 * repeated consecutive vertices (smoothing's uncut or halved-to-nothing corners; a ring's last vertex equal
 * to its first). The end points of an open chain are never dropped. A guarded pass of Dutton's enhancement
 * (ft_line_pass_enhance, FT_GUARD_REDUCE, a plan whose pass moves no midpoint: ft_dutton_plan_fusable) runs
 * with the guard fused into it (dutton_guarded.c): the same rule, no base or raw chain.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "line/dutton_internal.h"
#include "line/edit_internal.h"

#include <stdlib.h>

/* Removes vertices equal to the one before (an open chain keeps its last vertex, dropping the interior
 * copy before it). Never leaves fewer than 2 (open) or 3 (ring) vertices: then nothing is removed. */
static void drop_repeats(ft_chain *c)
{
    size_t n = c->n, k = 0;
    if (n < 2)
        return;
    size_t kept = 1;
    for (size_t i = 1; i < n; i++)
        kept += c->x[i] != c->x[i - 1] || c->y[i] != c->y[i - 1];
    if (c->closed && kept > 1 && c->x[n - 1] == c->x[0] && c->y[n - 1] == c->y[0])
        kept--;
    if (kept == n || kept < (c->closed ? 3u : 2u))
        return;
    for (size_t i = 0; i < n; i++) {
        if (k > 0 && c->x[i] == c->x[k - 1] && c->y[i] == c->y[k - 1]) {
            if (!c->closed && i == n - 1) { /* keep the end point: overwrite the copy before it */
                c->x[k - 1] = c->x[i];
                c->y[k - 1] = c->y[i];
            }
            continue;
        }
        c->x[k] = c->x[i];
        c->y[k] = c->y[i];
        k++;
    }
    if (c->closed && k > 3 && c->x[k - 1] == c->x[0] && c->y[k - 1] == c->y[0])
        k--;
    c->n = k;
}

static void free_set(ft_chain **c, size_t n)
{
    for (size_t i = 0; c != NULL && i < n; i++)
        ft_chain_free(c[i]);
    free(c);
}

/* One pass over the set: chains[c] replaced by the guarded (or raw) result; the chains it replaces are
 * freed when owned (not on the first pass, which reads the caller's). */
static int one_pass(ft_chain **chains, size_t n, ft_line_pass_fn pass, const void *ctx, int guard,
                    ft_line_guard_stats *stats, ft_dutton_carry *carry, int passes_left, int owned)
{
    ft_chain **base = ft_calloc(n ? n : 1, sizeof *base), **raw = ft_calloc(n ? n : 1, sizeof *raw);
    int rc = base == NULL || raw == NULL ? FT_E_NOMEM : FT_OK;
    int fused = pass == ft_line_pass_enhance && guard == FT_GUARD_REDUCE && ft_dutton_plan_fusable(ctx);
    if (rc == FT_OK && fused)
        rc = ft_dutton_pass_guarded((const ft_chain *const *)chains, n, ctx, base, stats, carry, passes_left);
    for (size_t c = 0; c < n && rc == FT_OK && !fused; c++)
        rc = pass(chains[c], ctx, guard ? &base[c] : NULL, &raw[c]);
    if (rc == FT_OK && guard && !fused)
        rc = ft_line_guard_moves(base, (const ft_chain *const *)raw, n, guard, stats);
    if (rc == FT_OK) {
        ft_chain **keep = guard ? base : raw;
        for (size_t c = 0; c < n; c++) {
            drop_repeats(keep[c]);
            if (owned)
                ft_chain_free(chains[c]);
            chains[c] = keep[c];
            keep[c] = NULL;
        }
    }
    free_set(base, n);
    free_set(raw, n);
    return rc;
}

int ft_line_run_passes_into(const ft_chain *const *in, size_t n, ft_line_pass_fn pass, const void *ctx, int passes,
                            int guard, ft_line_guard_stats *stats, ft_chain **out)
{
    if ((in == NULL && n > 0) || (out == NULL && n > 0) || pass == NULL)
        return ft_error(FT_E_INVALID, "passes: NULL chains or pass");
    if (passes < 0)
        return ft_error(FT_E_INVALID, "passes must be >= 0, got %d", passes);
    ft_chain **work = ft_calloc(n ? n : 1, sizeof *work);
    if (work == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t c = 0; c < n; c++) /* the first pass reads the caller's chains: no copy */
        work[c] = (ft_chain *)in[c];
    ft_dutton_carry *carry = NULL; /* the fused enhancement's index, from pass to pass */
    if (passes > 1 && pass == ft_line_pass_enhance && guard == FT_GUARD_REDUCE && ft_dutton_plan_fusable(ctx) &&
        (carry = ft_dutton_carry_create()) == NULL)
        rc = FT_E_NOMEM;
    for (int k = 0; k < passes && rc == FT_OK; k++)
        rc = one_pass(work, n, pass, ctx, guard, stats, carry, passes - k - 1, k > 0);
    ft_dutton_carry_free(carry);
    int owned = passes > 0 && rc == FT_OK;
    for (size_t c = 0; c < n && rc == FT_OK && !owned; c++) /* no pass: copies */
        if ((work[c] = ft_chain_copy(in[c])) == NULL)
            rc = FT_E_NOMEM;
    if (rc == FT_OK)
        for (size_t c = 0; c < n; c++) {
            out[c] = work[c];
            work[c] = NULL;
        }
    else
        for (size_t c = 0; c < n; c++)
            if (work[c] != in[c])
                ft_chain_free(work[c]);
    free(work);
    return rc;
}

int ft_line_run_passes(ft_chain **chains, size_t n, ft_line_pass_fn pass, const void *ctx, int passes, int guard,
                       ft_line_guard_stats *stats)
{
    if (chains == NULL && n > 0)
        return ft_error(FT_E_INVALID, "passes: NULL chains or pass");
    ft_chain **out = ft_calloc(n ? n : 1, sizeof *out);
    if (out == NULL)
        return FT_E_NOMEM;
    int rc = ft_line_run_passes_into((const ft_chain *const *)chains, n, pass, ctx, passes, guard, stats, out);
    if (rc == FT_OK)
        for (size_t c = 0; c < n; c++) {
            ft_chain_free(chains[c]);
            chains[c] = out[c];
        }
    free(out);
    return rc;
}
