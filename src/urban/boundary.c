/* fracterra — src/urban/boundary.c: the midpoint-subdivision fractal generator of Zhang, Yu & Fan (2008,
 * §2) that simulates an urban boundary at a larger scale with detail of dimension D.
 *
 * Generator (Fig. 3, Eqs. 6-9): a segment B -> C of length r becomes the two legs B -> N -> C, each of length
 * r / (2 cos a), where a is the base angle of the isosceles triangle B N C. One step multiplies the number of
 * segments by 2 and divides their length by 2 cos a, so by Eq. 6, D = ln(N_{n+1}/N_n) / ln(r_n/r_{n+1}) =
 * ln 2 / ln(2 cos a) (Eqs. 7-8), and a = acos(e^{(1 - D) ln 2 / D}) = acos(2^(1/D - 1)) (Eq. 9). The apex N
 * sits at the perpendicular distance L = (r/2) tan a from the midpoint of B C.
 *
 * Apex (Eq. 10): X_N = (X_B + X_C)/2 - J L sin(beta) + R_x, Y_N = (Y_B + Y_C)/2 + J L cos(beta) + R_y, with
 * beta the azimuth of B -> C (from the x axis: sin(beta) = dy / r, cos(beta) = dx / r), J = +1 (N left of
 * B -> C) or -1 (right), drawn per segment. The printed equation adds one symbol R to both coordinates and
 * says R scatters N "in the dashed rectangle" of Fig. 5; one shared value would move N along a diagonal
 * line, not within a rectangle, so R_x and R_y are two independent draws, uniform in [-jitter L, jitter L]:
 * the rectangle is the square of half-side jitter L centred on the exact apex, sides parallel to the map
 * axes (the equation adds R to map coordinates). Scaling it with L keeps every level a scaled copy of the
 * previous one (statistical self-similarity) and vanishes with D -> 1.
 *
 * Thresholds (§2.2.3): a segment is replaced while min < r <= max; legs are replaced in turn until they
 * are no longer than min ("this process will be continued towards the minimum threshold"); an input
 * segment longer than max is kept as it is (the wall of a regular parcel). max defaults to the average
 * chord length d_avg of Eqs. 11-13: d_i = [(x_{i+1} - x_i)^2 + (y_{i+1} - y_i)^2]^(1/2) (the scan prints a
 * "+" inside the first square, a distance needs "-"), s = sum d_i, d_avg = s / (n - 1) for n nodes, i.e.
 * the length over the number of segments (a ring counts its closing segment). A segment equal to d_avg
 * within a relative 1e-12 counts as not longer (all-equal segments average to their common length up to
 * rounding).
 *
 * Termination: with jitter below ft_urban_jitter_max(D) every leg is at most q r with q = 1/(2 cos a) +
 * (sqrt 2 / 2) jitter tan a < 1 (the apex square's corner is sqrt 2 jitter L from the exact apex), so the
 * depth is at most log(max / min) / log(1 / q). Segments are subdivided depth-first on an explicit stack
 * (no recursion), emitting the legs' vertices in chain order.
 *
 * Randomness: each input segment's key is ft_rng_mix chained over (seed, stream, its end points in
 * lexicographic order); a segment with key k draws J from ft_rng_mix(k, 0), R_x and R_y from
 * ft_rng_mix(k, 1) and ft_rng_mix(k, 2), and its legs get the keys ft_rng_mix(k, 3) and ft_rng_mix(k, 4).
 * Every segment is generated from its canonical end (the lexicographically smaller one) and the new
 * vertices reversed if the chain walks it the other way: the output depends on the segment alone, not on
 * processing order, direction, or which chain or arc holds it.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/urban.h"
#include "internal.h"
#include "urban/urban_internal.h"

#define PI_4 0.78539816339744830962
#define SQRT1_2 0.70710678118654752440
#define AVG_REL_TOL 1e-12

double ft_urban_angle_for_dim(double D)
{
    if (!(D >= 1.0 && D <= 2.0))
        return NAN;
    return acos(pow(2.0, 1.0 / D - 1.0)); /* Eq. 9 */
}

double ft_urban_dim_for_angle(double a)
{
    if (!(a >= 0.0 && a <= PI_4))
        return NAN;
    return a == 0.0 ? 1.0 : log(2.0) / log(2.0 * cos(a)); /* Eq. 8 */
}

double ft_urban_jitter_max(double D)
{
    if (!(D > 1.0 && D < 2.0))
        return NAN;
    double a = ft_urban_angle_for_dim(D);
    double j = (1.0 - 1.0 / (2.0 * cos(a))) * 2.0 * SQRT1_2 / tan(a);
    return j < SQRT1_2 ? j : SQRT1_2;
}

double ft_urban_chord_avg(const ft_chain *c)
{
    if (c == NULL)
        return 0.0;
    size_t nseg = ft_chain_segments(c);
    return nseg > 0 ? ft_chain_length(c) / (double)nseg : 0.0; /* Eqs. 11-13 */
}

int ft_urban_boundary_check(const ft_boundary_opts *o)
{
    if (!(o->dim > 1.0 && o->dim < 2.0))
        return ft_error(FT_E_INVALID, "boundary: dim must be in (1, 2) (the dimension of the boundary), got %g",
                        o->dim);
    if (!(o->min > 0.0) || !isfinite(o->min))
        return ft_error(FT_E_INVALID, "boundary: min must be finite and > 0 (the shortest segment to replace, "
                        "in map units), got %g", o->min);
    if (!(o->max >= 0.0) || !isfinite(o->max))
        return ft_error(FT_E_INVALID, "boundary: max must be finite and >= min (0 = the average chord length), "
                        "got %g", o->max);
    if (o->max > 0.0 && o->max < o->min)
        return ft_error(FT_E_INVALID, "boundary: max (%g) must not be less than min (%g)", o->max, o->min);
    double jmax = ft_urban_jitter_max(o->dim);
    if (!(o->jitter >= 0.0 && o->jitter < jmax))
        return ft_error(FT_E_INVALID, "boundary: jitter must be in [0, %.4g) at dim %g (beyond it a leg could be "
                        "as long as its segment), got %g", jmax, o->dim, o->jitter);
    return FT_OK;
}

/* ---- generation ---------------------------------------------------------------------------------- */

typedef struct {
    double x0, y0, x1, y1;
    uint64_t key;
} seg;

typedef struct {
    double half_tan;  /* tan(a) / 2: L = half_tan * r */
    double min, min2; /* min and min² */
    double jitter;
    seg *stack;
    size_t top, cap;
    ft_chain *out;
} generator;

static uint64_t coord_bits(double v)
{
    uint64_t b;
    v = v == 0.0 ? 0.0 : v; /* -0 and +0 are one coordinate */
    memcpy(&b, &v, sizeof b);
    return b;
}

/* Uniform in [-1, 1) from a 64-bit word. */
static double sym_uniform(uint64_t u)
{
    return (double)(u >> 11) * 0x1p-52 - 1.0;
}

static int stack_push(generator *g, double x0, double y0, double x1, double y1, uint64_t key)
{
    if (g->top == g->cap) {
        size_t cap = g->cap ? 2 * g->cap : 64;
        seg *s = ft_realloc_array(g->stack, cap, sizeof *s);
        if (s == NULL)
            return FT_E_NOMEM;
        g->stack = s;
        g->cap = cap;
    }
    g->stack[g->top++] = (seg){x0, y0, x1, y1, key};
    return FT_OK;
}

static int emit(generator *g, double x, double y)
{
    if (g->out->n >= FT_BOUNDARY_MAX_VERTICES)
        return ft_error(FT_E_INVALID, "boundary: the output would have more than %zu vertices; raise min (%g)",
                        (size_t)FT_BOUNDARY_MAX_VERTICES, g->min);
    return ft_chain_push(g->out, x, y);
}

/* Appends the vertices that replace the inside of segment (x0, y0) -> (x1, y1) (key k), in order, end
 * points excluded. */
static int subdivide(generator *g, double x0, double y0, double x1, double y1, uint64_t key)
{
    g->top = 0;
    int rc = stack_push(g, x0, y0, x1, y1, key);
    while (rc == FT_OK && g->top > 0) {
        seg s = g->stack[--g->top];
        double dx = s.x1 - s.x0, dy = s.y1 - s.y0, r2 = dx * dx + dy * dy;
        if (!(r2 > g->min2)) { /* final: its end is the next vertex (the last one is x1, y1) */
            if (g->top > 0)
                rc = emit(g, s.x1, s.y1);
            continue;
        }
        /* Eq. 10 with L sin(beta) = half_tan dy and L cos(beta) = half_tan dx */
        double J = (ft_rng_mix(s.key, 0) >> 63) ? 1.0 : -1.0;
        double xn = 0.5 * (s.x0 + s.x1) - J * g->half_tan * dy;
        double yn = 0.5 * (s.y0 + s.y1) + J * g->half_tan * dx;
        if (g->jitter > 0.0) {
            double R = g->jitter * g->half_tan * sqrt(r2);
            xn += R * sym_uniform(ft_rng_mix(s.key, 1));
            yn += R * sym_uniform(ft_rng_mix(s.key, 2));
        }
        rc = stack_push(g, xn, yn, s.x1, s.y1, ft_rng_mix(s.key, 4)); /* second leg, done after the first */
        if (rc == FT_OK)
            rc = stack_push(g, s.x0, s.y0, xn, yn, ft_rng_mix(s.key, 3));
    }
    return rc;
}

/* Reverses the vertices from index `from` to the end, through a view of that tail. */
static void reverse_tail(ft_chain *c, size_t from)
{
    ft_chain tail = {c->x + from, c->y + from, c->n - from, c->n - from, 0};
    ft_chain_reverse(&tail);
}

/* The inside of input segment P -> Q, generated from its canonical end. */
static int input_segment(generator *g, uint64_t base, double px, double py, double qx, double qy)
{
    int swap = qx < px || (qx == px && qy < py);
    double ax = swap ? qx : px, ay = swap ? qy : py, bx = swap ? px : qx, by = swap ? py : qy;
    uint64_t key = ft_rng_mix(ft_rng_mix(ft_rng_mix(ft_rng_mix(base, coord_bits(ax)), coord_bits(ay)),
                                         coord_bits(bx)), coord_bits(by));
    size_t from = g->out->n;
    int rc = subdivide(g, ax, ay, bx, by, key);
    if (rc == FT_OK && swap)
        reverse_tail(g->out, from);
    return rc;
}

static int check_input(const ft_chain *in)
{
    if (in == NULL)
        return ft_error(FT_E_INVALID, "boundary: NULL chain");
    if (in->n < (in->closed ? 3u : 2u))
        return ft_error(FT_E_INVALID, "boundary: a%s needs at least %d vertices, got %zu",
                        in->closed ? " ring" : "n open chain", in->closed ? 3 : 2, in->n);
    return ft_chain_check_finite(in);
}

/* Refuses up front an output that would pass FT_BOUNDARY_MAX_VERTICES: without jitter a segment of length
 * r replaced down to min gains 2^k - 1 vertices, k = ceil(ln(r / min) / ln(2 cos a)) (jitter moves the
 * count little; emit() still enforces the limit). */
static int check_size(const ft_chain *in, const ft_boundary_opts *o, double keep_above, size_t *estimate)
{
    const double lnq = log(2.0 * cos(ft_urban_angle_for_dim(o->dim)));
    const size_t nseg = ft_chain_segments(in);
    double total = (double)in->n;
    for (size_t i = 0; i < nseg; i++) {
        size_t j = i + 1 == in->n ? 0 : i + 1;
        double r = hypot(in->x[j] - in->x[i], in->y[j] - in->y[i]);
        if (r > o->min && r <= keep_above)
            total += exp2(ceil(log(r / o->min) / lnq)) - 1.0;
    }
    if (!(total <= (double)FT_BOUNDARY_MAX_VERTICES))
        return ft_error(FT_E_INVALID, "boundary: about %.3g vertices would be generated, more than %zu; raise min "
                        "(%g)", total, (size_t)FT_BOUNDARY_MAX_VERTICES, o->min);
    *estimate = (size_t)total;
    return FT_OK;
}

int ft_urban_boundary(const ft_chain *in, const ft_boundary_opts *o, ft_chain **out)
{
    ft_boundary_opts taken = FT_BOUNDARY_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (o != NULL) {
        if (FT_OPTS_TAKE(taken, o, ft_boundary_opts) != FT_OK)
            return FT_E_INVALID;
        o = &taken;
    }
    if (out == NULL || o == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_boundary: NULL %s", out == NULL ? "out" : "options");
    *out = NULL;
    int rc = ft_urban_boundary_check(o);
    if (rc == FT_OK)
        rc = check_input(in);
    if (rc != FT_OK)
        return rc;
    double max = o->max;
    if (max == 0.0) {
        max = ft_urban_chord_avg(in);
        if (max < o->min)
            return ft_error(FT_E_INVALID, "boundary: the average chord length %g (the default max) is less than "
                            "min (%g): lower min or set max", max, o->min);
    }
    const double keep_above = max * (1.0 + AVG_REL_TOL);
    size_t estimate = 0;
    rc = check_size(in, o, keep_above, &estimate);
    if (rc != FT_OK)
        return rc;
    generator g = {0.5 * tan(ft_urban_angle_for_dim(o->dim)), o->min, o->min * o->min, o->jitter, NULL, 0, 0, NULL};
    g.out = ft_chain_create(estimate, in->closed);
    if (g.out == NULL)
        return FT_E_NOMEM;
    const uint64_t base = ft_rng_mix(o->seed, o->stream);
    const size_t nseg = ft_chain_segments(in);
    rc = emit(&g, in->x[0], in->y[0]);
    for (size_t i = 0; rc == FT_OK && i < nseg; i++) {
        size_t j = i + 1 == in->n ? 0 : i + 1;
        double r = hypot(in->x[j] - in->x[i], in->y[j] - in->y[i]);
        if (r <= keep_above)
            rc = input_segment(&g, base, in->x[i], in->y[i], in->x[j], in->y[j]);
        if (rc == FT_OK && j != 0)
            rc = emit(&g, in->x[j], in->y[j]);
    }
    free(g.stack);
    if (rc != FT_OK) {
        ft_chain_free(g.out);
        return rc;
    }
    *out = g.out;
    return FT_OK;
}
