/* fracterra — src/urban/boundary_guarded.c: Zhang, Yu & Fan's (2008, §2) midpoint-subdivision
 * generator run level by level through the crossing guard (line/move_guard.c), so that the
 * simulated boundary is simple and crosses no other boundary of the layer.
 *
 * One level splits every segment whose length r is in the window min < r <= max (boundary.c's thresholds;
 * an input segment longer than max is never split, and legs are always shorter than max) at once: the base
 * position of the new vertex is the segment's midpoint, the raw one the apex of Eq. 10 (side J and jitter
 * R_x, R_y as in boundary.c). The guard (FT_GUARD_MIRROR) then puts each apex where drawn, or failing that
 * on the other side of the segment (J redrawn: the same legs, so the same dimension), or half or a quarter
 * of the way, or leaves it on the midpoint. A level with no segment in the window adds nothing; the number of levels is bounded by
 * ceil(ln(max / min) / ln(1 / q)) + 1, q = 1 / (2 cos a) + (sqrt 2 / 2) jitter tan a the largest leg ratio
 * (boundary.c's termination argument; a reduced apex gives shorter legs).
 *
 * Randomness: a segment's draws come from the key ft_rng_mix chained over (seed, stream, its end points in
 * lexicographic order), at every level, so the output depends on the segments alone, not on the order of
 * processing, a chain's direction or which arc holds a segment; it is a different realization from the
 * depth-first generator (whose legs inherit their parent's key), which --allow-crossings keeps.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <string.h>

#include "fracterra/line.h"
#include "fracterra/urban.h"
#include "internal.h"
#include "urban/urban_internal.h"

typedef struct {
    double half_tan, min2, max2, jitter;
    uint64_t base;
} level_ctx;

static uint64_t coord_bits(double v)
{
    uint64_t b;
    v = v == 0.0 ? 0.0 : v; /* -0 and +0 are one coordinate */
    memcpy(&b, &v, sizeof b);
    return b;
}

static double sym_uniform(uint64_t u)
{
    return (double)(u >> 11) * 0x1p-52 - 1.0;
}

/* The apex of segment P -> Q (Eq. 10), drawn from the segment's canonical key. */
static void apex(const level_ctx *L, double px, double py, double qx, double qy, double *xn, double *yn)
{
    int swap = qx < px || (qx == px && qy < py);
    double ax = swap ? qx : px, ay = swap ? qy : py, bx = swap ? px : qx, by = swap ? py : qy;
    uint64_t key = ft_rng_mix(ft_rng_mix(ft_rng_mix(ft_rng_mix(L->base, coord_bits(ax)), coord_bits(ay)),
                                         coord_bits(bx)), coord_bits(by));
    double dx = bx - ax, dy = by - ay;
    double J = (ft_rng_mix(key, 0) >> 63) ? 1.0 : -1.0;
    *xn = 0.5 * (ax + bx) - J * L->half_tan * dy;
    *yn = 0.5 * (ay + by) + J * L->half_tan * dx;
    if (L->jitter > 0.0) {
        double R = L->jitter * L->half_tan * hypot(dx, dy);
        *xn += R * sym_uniform(ft_rng_mix(key, 1));
        *yn += R * sym_uniform(ft_rng_mix(key, 2));
    }
}

static int in_window(const level_ctx *L, const ft_chain *c, size_t i, size_t j)
{
    double dx = c->x[j] - c->x[i], dy = c->y[j] - c->y[i], r2 = dx * dx + dy * dy;
    return r2 > L->min2 && r2 <= L->max2;
}

/* One level (ft_line_pass_fn): base = input vertices and midpoints, raw = input vertices and apexes. */
static int boundary_level(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw)
{
    const level_ctx *L = ctx;
    *raw = NULL;
    if (base)
        *base = NULL;
    size_t nseg = ft_chain_segments(in), add = 0;
    for (size_t i = 0; i < nseg; i++)
        add += (size_t)in_window(L, in, i, i + 1 < in->n ? i + 1 : 0);
    if (in->n + add > FT_BOUNDARY_MAX_VERTICES)
        return ft_error(FT_E_INVALID, "boundary: a chain would have more than %zu vertices; raise min",
                        (size_t)FT_BOUNDARY_MAX_VERTICES);
    ft_chain *b = base ? ft_chain_create(in->n + add, in->closed) : NULL, *r = ft_chain_create(in->n + add, in->closed);
    if ((base && b == NULL) || r == NULL) {
        ft_chain_free(b);
        ft_chain_free(r);
        return FT_E_NOMEM;
    }
    size_t k = 0;
    for (size_t i = 0; i < in->n; i++) {
        r->x[k] = in->x[i];
        r->y[k] = in->y[i];
        if (b) {
            b->x[k] = in->x[i];
            b->y[k] = in->y[i];
        }
        k++;
        size_t j = i + 1 < in->n ? i + 1 : 0;
        if (i < nseg && in_window(L, in, i, j)) {
            if (b) {
                b->x[k] = 0.5 * (in->x[i] + in->x[j]);
                b->y[k] = 0.5 * (in->y[i] + in->y[j]);
            }
            apex(L, in->x[i], in->y[i], in->x[j], in->y[j], &r->x[k], &r->y[k]);
            k++;
        }
    }
    r->n = k;
    if (b) {
        b->n = k;
        *base = b;
    }
    *raw = r;
    return FT_OK;
}

int ft_urban_boundary_guarded(ft_layer *l, const ft_boundary_opts *o, double max, int coverage,
                              ft_line_guard_stats *stats)
{
    double a = ft_urban_angle_for_dim(o->dim);
    double q = 1.0 / (2.0 * cos(a)) + 0.70710678118654752440 * o->jitter * tan(a);
    double keep_above = max * (1.0 + 1e-12); /* boundary.c's AVG_REL_TOL */
    int levels = max > o->min ? (int)ceil(log(max / o->min) / log(1.0 / q)) + 1 : 1;
    level_ctx L = {0.5 * tan(a), o->min * o->min, keep_above * keep_above, o->jitter, ft_rng_mix(o->seed, o->stream)};
    return ft_line_apply_layer_passes(l, boundary_level, &L, levels, coverage, FT_GUARD_MIRROR, stats);
}
