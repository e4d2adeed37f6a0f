/* fracterra — line/simplify_dp.c: Douglas-Peucker simplification (Douglas & Peucker 1973, the
 * "bandwidth-tolerance" filter Dutton 1981 uses to generalize the DIME state boundaries to 1,055 points
 * and Newfoundland to 158 before enhancing them).
 *
 * Between two kept vertices i < j, the vertex k of i..j farthest from the segment [v_i, v_j] is kept if its
 * distance exceeds the tolerance, and both halves are examined in turn; otherwise the vertices between i
 * and j are dropped. The ranges wait on an explicit stack (at most n entries), so a million-vertex chain
 * needs no recursion. Distances are to the segment, not to its line (a spike beyond an end point counts),
 * compared squared. An open chain keeps its end points. A ring is cut at vertex 0 and the vertex f farthest
 * from it, both kept, and each half is simplified as an open chain; if only those two remain, the vertex
 * farthest from their line is kept too, so a ring keeps at least three vertices.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "edit_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    size_t first, last;
} range;

/* The vertex of (i, j) farthest from the segment [v_i, v_j] and its squared distance in *best. */
static size_t farthest(const double *x, const double *y, size_t i, size_t j, double *best)
{
    double ax = x[i], ay = y[i], dx = x[j] - ax, dy = y[j] - ay;
    double len2 = dx * dx + dy * dy, inv = len2 > 0.0 ? 1.0 / len2 : 0.0;
    double bd = -1.0;
    size_t bk = i;
    for (size_t k = i + 1; k < j; k++) {
        double px = x[k] - ax, py = y[k] - ay;
        double t = (px * dx + py * dy) * inv;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        double ex = px - t * dx, ey = py - t * dy;
        double d = ex * ex + ey * ey;
        if (d > bd) {
            bd = d;
            bk = k;
        }
    }
    *best = bd;
    return bk;
}

/* Marks keep[k] for the vertices of [first, last] that Douglas-Peucker keeps (first and last included). */
static void dp_range(const double *x, const double *y, size_t first, size_t last, double tol2,
                     unsigned char *keep, range *stack)
{
    size_t top = 0;
    keep[first] = keep[last] = 1;
    stack[top++] = (range){first, last};
    while (top > 0) {
        range r = stack[--top];
        if (r.last - r.first < 2)
            continue;
        double d;
        size_t k = farthest(x, y, r.first, r.last, &d);
        if (d <= tol2)
            continue;
        keep[k] = 1;
        stack[top++] = (range){k, r.last};
        stack[top++] = (range){r.first, k};
    }
}

static ft_chain *gather(const ft_chain *in, const unsigned char *keep)
{
    size_t m = 0;
    for (size_t i = 0; i < in->n; i++)
        m += keep[i];
    ft_chain *c = ft_chain_create(m, in->closed);
    if (c == NULL)
        return NULL;
    for (size_t i = 0; i < in->n; i++) {
        if (keep[i]) {
            c->x[c->n] = in->x[i];
            c->y[c->n] = in->y[i];
            c->n++;
        }
    }
    return c;
}

/* A ring as the open chain v_0 .. v_{n-1}, v_0, cut at v_0 and the vertex farthest from it; keep has
 * n + 1 entries (the last stands for v_0 again). */
static int dp_ring(const ft_chain *in, double tol2, unsigned char *keep, range *stack)
{
    size_t n = in->n;
    double *x = ft_realloc_array(NULL, n + 1, sizeof *x), *y = ft_realloc_array(NULL, n + 1, sizeof *y);
    if (x == NULL || y == NULL) {
        free(x);
        free(y);
        return FT_E_NOMEM;
    }
    memcpy(x, in->x, n * sizeof *x);
    memcpy(y, in->y, n * sizeof *y);
    x[n] = in->x[0];
    y[n] = in->y[0];
    size_t f = ft_edit_farthest_from_first(in);
    dp_range(x, y, 0, f, tol2, keep, stack);
    dp_range(x, y, f, n, tol2, keep, stack);
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        m += keep[i];
    if (m < 3) {
        size_t t[3];
        ft_edit_ring_triangle(in, t);
        keep[t[0]] = keep[t[1]] = keep[t[2]] = 1;
    }
    free(x);
    free(y);
    return FT_OK;
}

int ft_line_simplify(const ft_chain *in, double tolerance, ft_chain **out)
{
    int rc = ft_edit_check_chain("simplify", in, out);
    if (rc != FT_OK)
        return rc;
    if (!(tolerance >= 0.0) || !isfinite(tolerance))
        return ft_error(FT_E_INVALID, "simplify tolerance must be finite and >= 0, got %g", tolerance);
    size_t n = in->n;
    unsigned char *keep = ft_calloc(n + 1, 1);
    range *stack = ft_realloc_array(NULL, n + 2, sizeof *stack);
    if (keep == NULL || stack == NULL) {
        free(keep);
        free(stack);
        return FT_E_NOMEM;
    }
    double tol2 = tolerance * tolerance;
    if (in->closed)
        rc = dp_ring(in, tol2, keep, stack);
    else
        dp_range(in->x, in->y, 0, n - 1, tol2, keep, stack);
    ft_chain *c = rc == FT_OK ? gather(in, keep) : NULL;
    free(keep);
    free(stack);
    if (rc != FT_OK)
        return rc;
    if (c == NULL)
        return FT_E_NOMEM;
    *out = c;
    return FT_OK;
}
