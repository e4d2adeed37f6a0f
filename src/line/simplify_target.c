/* fracterra — src/line/simplify_target.c: the Douglas-Peucker tolerance that leaves a layer at most a given
 * number of vertices (Dutton 1981 simplified the Newfoundland coast to "158 points"): the smallest tolerance
 * found by bisection between 0 and the layer's bounding-box diagonal, each step a simplification of a copy.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/line.h"

#define BISECTION_STEPS 60

/* Vertices left in a copy of l after simplifying it with tolerance tol. */
static int count_after(const ft_layer *l, double tol, int coverage, size_t *n)
{
    ft_layer *c = ft_layer_copy(l);
    if (c == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : FT_E_NOMEM;
    int rc = ft_line_apply_layer(c, ft_line_op_simplify, &tol, coverage);
    *n = ft_layer_vertex_count(c);
    ft_layer_free(c);
    return rc;
}

int ft_line_simplify_tolerance_for(const ft_layer *l, size_t target, int coverage, double *tolerance,
                                   size_t *vertices)
{
    if (l == NULL || tolerance == NULL || vertices == NULL)
        return ft_error(FT_E_INVALID, "ft_line_simplify_tolerance_for: NULL argument");
    double x0, y0, x1, y1, lo = 0.0;
    size_t n = ft_layer_vertex_count(l);
    *tolerance = 0.0;
    *vertices = n;
    if (n <= target)
        return FT_OK;
    int rc = ft_layer_bbox(l, &x0, &y0, &x1, &y1);
    double hi = hypot(x1 - x0, y1 - y0);
    if (rc == FT_OK)
        rc = count_after(l, hi, coverage, &n);
    if (rc != FT_OK)
        return rc;
    if (n > target)
        return ft_error(FT_E_INVALID, "cannot simplify to %zu vertices: Douglas-Peucker keeps at least %zu", target,
                        n);
    *vertices = n;
    for (int i = 0; i < BISECTION_STEPS && hi - lo > 1e-12 * hi; i++) {
        double mid = 0.5 * (lo + hi);
        size_t m = 0;
        if ((rc = count_after(l, mid, coverage, &m)) != FT_OK)
            return rc;
        if (m <= target) {
            hi = mid;
            *vertices = m;
        } else {
            lo = mid;
        }
    }
    *tolerance = hi;
    return FT_OK;
}
