/* fracterra — contour/midpoint_displace.c: random midpoint displacement of the segments of a contour
 * (Misawa, Chiba & Saito, "Simulation of natural scenes: procedure modeling for mountains", §4.1, Fig. 13).
 *
 * Every segment longer than max_seg (the paper's 2 d0, d0 the seed contour's mean segment length) is split
 * at its midpoint, which moves perpendicularly to the segment, to a random side, by
 *     min{ d'', |l tan theta| },   2l the segment's length, theta uniform in [theta_min, theta_max]
 * (the paper: "the displacement is min{d'', |l tan theta|}, its direction random"), and both halves are
 * treated the same way until every segment is at most max_seg. The paper insists this is not the fractal
 * midpoint displacement of Voss (no scaling law): only "move the midpoint at random".
 *
 * Termination: a half has length l sqrt(1 + tan^2 theta) = l / cos theta, shorter than its parent 2l only
 * for theta < 60 degrees. The displacement is therefore also capped at l sqrt(4 q^2 - 1) with q = 0.9
 * (theta = 56.3 degrees), so every split shortens the segments by at least 10 %; below that angle (the
 * paper's settings go to 40 degrees) the cap never acts.
 *
 * Random draws: one xoshiro stream per call from (seed, stream); the splits are made depth first along
 * the chain, each drawing theta then the side, so the same (seed, stream) gives the same chain.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/contour.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define HALF_CAP 1.4966629547095765 /* sqrt(4 * 0.9^2 - 1): halves at most 0.9 of their parent */
#define MAX_VERTICES ((size_t)1 << 25)
#define MAX_DEPTH 2000

typedef struct {
    ft_chain *out;
    ft_rng_fast rng;
    double max_seg2, max_offset, tan_min, tan_max, theta_min, theta_max;
} displacer;

/* Uniform in [0, 1) from the top 53 bits. */
static double uniform01(ft_rng_fast *r)
{
    return (double)(ft_rng_fast_next(r) >> 11) * 0x1p-53;
}

/* Splits the segment a -> b (a already pushed, b pushed by the caller) until its pieces are short. */
static int split(displacer *s, double ax, double ay, double bx, double by, int depth)
{
    double dx = bx - ax, dy = by - ay, len2 = dx * dx + dy * dy;
    if (!(len2 > s->max_seg2))
        return FT_OK;
    if (depth > MAX_DEPTH)
        return ft_error(FT_E_NUMERIC, "midpoint displacement: a segment of length %g does not converge",
                        sqrt(len2));
    double len = sqrt(len2), l = 0.5 * len;
    double theta = s->theta_min + (s->theta_max - s->theta_min) * uniform01(&s->rng);
    double side = uniform01(&s->rng) < 0.5 ? 1.0 : -1.0;
    double off = fmin(s->max_offset, fabs(l * tan(theta * PI / 180.0))); /* §4.1: min{d'', |l tan theta|} */
    off = fmin(off, l * HALF_CAP);
    /* left normal of a -> b */
    double nx = -dy / len, ny = dx / len;
    double mx = 0.5 * (ax + bx) + side * off * nx, my = 0.5 * (ay + by) + side * off * ny;
    int rc = split(s, ax, ay, mx, my, depth + 1);
    if (rc != FT_OK)
        return rc;
    if (s->out->n >= MAX_VERTICES)
        return ft_error(FT_E_INVALID,
                        "midpoint displacement: max_seg = %g would make more than %zu vertices; use a larger one",
                        sqrt(s->max_seg2), MAX_VERTICES);
    rc = ft_chain_push(s->out, mx, my);
    if (rc != FT_OK)
        return rc;
    return split(s, mx, my, bx, by, depth + 1);
}

static int check_opts(const ft_midpoint_opts *o)
{
    if (o == NULL)
        return ft_error(FT_E_INVALID, "midpoint displacement: options are required (max_seg must be > 0)");
    if (!(o->max_seg > 0.0) || !isfinite(o->max_seg))
        return ft_error(FT_E_INVALID, "max_seg must be finite and > 0, got %g", o->max_seg);
    if (!(o->max_offset >= 0.0) || !isfinite(o->max_offset))
        return ft_error(FT_E_INVALID, "max_offset must be finite and >= 0, got %g", o->max_offset);
    if (!(o->theta_min >= 0.0 && o->theta_min < 90.0))
        return ft_error(FT_E_INVALID, "theta_min must be in [0,90) degrees, got %g", o->theta_min);
    if (!(o->theta_max >= o->theta_min && o->theta_max < 90.0))
        return ft_error(FT_E_INVALID, "theta_max must be in [theta_min,90) = [%g,90) degrees, got %g",
                        o->theta_min, o->theta_max);
    return FT_OK;
}

int ft_contour_midpoint_displace(const ft_chain *in, const ft_midpoint_opts *opts, uint64_t seed,
                                 uint64_t stream, ft_chain **out)
{
    ft_midpoint_opts taken = FT_MIDPOINT_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_midpoint_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    int rc = ft_chain_check_operand("midpoint displacement", in, out);
    if (rc != FT_OK)
        return rc;
    rc = check_opts(opts);
    if (rc != FT_OK)
        return rc;

    /* every piece is at most max_seg and the pieces are at least as long as their segment together */
    size_t nseg = ft_chain_segments(in);
    double least = (double)in->n;
    for (size_t i = 0; i < nseg; i++) {
        size_t j = (i + 1) % in->n;
        least += floor(hypot(in->x[j] - in->x[i], in->y[j] - in->y[i]) / opts->max_seg);
    }
    if (least > (double)MAX_VERTICES)
        return ft_error(FT_E_INVALID,
                        "midpoint displacement: max_seg = %g would make more than %zu vertices; use a larger one",
                        opts->max_seg, MAX_VERTICES);

    displacer s;
    s.max_seg2 = opts->max_seg * opts->max_seg;
    s.max_offset = opts->max_offset;
    s.theta_min = opts->theta_min;
    s.theta_max = opts->theta_max;
    ft_rng_fast_init(&s.rng, seed, stream);
    s.out = ft_chain_create(in->n * 2, in->closed);
    if (s.out == NULL)
        return FT_E_NOMEM;

    rc = ft_chain_push(s.out, in->x[0], in->y[0]);
    for (size_t i = 0; i < nseg && rc == FT_OK; i++) {
        size_t j = (i + 1) % in->n;
        rc = split(&s, in->x[i], in->y[i], in->x[j], in->y[j], 0);
        if (rc == FT_OK && j != 0)
            rc = ft_chain_push(s.out, in->x[j], in->y[j]);
    }
    if (rc != FT_OK) {
        ft_chain_free(s.out);
        return rc;
    }
    *out = s.out;
    return FT_OK;
}
