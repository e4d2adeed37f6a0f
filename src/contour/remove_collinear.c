/* fracterra — contour/remove_collinear.c: removal of nearly collinear vertices, the last step of the
 * improved contour generation method (Misawa, Chiba & Saito, §4.3, step 1.2: "points almost on one
 * straight line are removed to reduce the number of segments", so that the midpoint displacement of the
 * next level keeps finding segments longer than 2 d0).
 *
 * Greedy along the chain: with P the last vertex kept and N the next input vertex, a vertex V whose
 * turning angle, the angle between P -> V and V -> N, is below the threshold is dropped (a vertex on top
 * of P or N turns by 0). Measuring from the last kept vertex bounds the drift: a run of small turns is
 * cut once the chord from P has turned by the threshold. An open chain keeps its end points; a ring
 * starts from its vertex of largest turning angle (always kept) and keeps at least 3 vertices. The kept
 * vertices stay in input order.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/contour.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

/* Turning angle (radians, in [0, pi]) at v between p -> v and v -> n; 0 for a zero-length side. */
static double turning_angle(const ft_chain *c, size_t p, size_t v, size_t n)
{
    double ax = c->x[v] - c->x[p], ay = c->y[v] - c->y[p];
    double bx = c->x[n] - c->x[v], by = c->y[n] - c->y[v];
    if ((ax == 0.0 && ay == 0.0) || (bx == 0.0 && by == 0.0))
        return 0.0;
    return fabs(atan2(ax * by - ay * bx, ax * bx + ay * by));
}

int ft_contour_remove_collinear(const ft_chain *in, double angle_deg, ft_chain **out)
{
    int rc = ft_chain_check_operand("collinear removal", in, out);
    if (rc != FT_OK)
        return rc;
    if (!(angle_deg >= 0.0) || !isfinite(angle_deg))
        return ft_error(FT_E_INVALID, "collinear angle must be finite and >= 0 degrees, got %g", angle_deg);
    double thr = angle_deg * PI / 180.0;
    size_t n = in->n;
    unsigned char *keep = ft_calloc(n, 1);
    if (keep == NULL)
        return FT_E_NOMEM;

    size_t start = 0, nkept = 1;
    if (in->closed) {
        double best = -1.0;
        for (size_t i = 0; i < n; i++) {
            double a = turning_angle(in, (i + n - 1) % n, i, (i + 1) % n);
            if (a > best) {
                best = a;
                start = i;
            }
        }
    }
    keep[start] = 1;
    size_t last = start;
    /* candidates: the n - 1 vertices after start (a ring) or the interior ones (open chain) */
    size_t ncand = in->closed ? n - 1 : n - 2, min_keep = in->closed ? 3 : 2;
    for (size_t t = 1; t <= ncand; t++) {
        size_t v = (start + t) % n, next = (v + 1) % n;
        size_t remaining = ncand - t; /* candidates after v */
        int can_drop = nkept + remaining + (in->closed ? 0 : 1) >= min_keep;
        if (can_drop && turning_angle(in, last, v, next) < thr)
            continue;
        keep[v] = 1;
        nkept++;
        last = v;
    }
    if (!in->closed)
        keep[n - 1] = 1;

    ft_chain *res = ft_chain_create(n, in->closed);
    if (res == NULL) {
        free(keep);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < n; i++)
        if (keep[i])
            ft_chain_push(res, in->x[i], in->y[i]); /* within capacity: cannot fail */
    free(keep);
    *out = res;
    return FT_OK;
}
