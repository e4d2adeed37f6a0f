/* fracterra — line/dutton.c: Dutton's fractal enhancement of a chain (Dutton 1981, "Fractal enhancement
 * of cartographic line detail", section "Parametric Fractalization of Digitized Curves": Sinuosity
 * Dimension SD, Uniformity Coefficient UC, Straightness ST and Smoothness SM tolerances).
 *
 * One iteration, from the input positions only (every vertex is computed independently, so the result
 * does not depend on the thread count):
 *  1. a segment is split at its midpoint iff its length L is in the window SM <= L < ST (Dutton: "both
 *     segments ... must be less than ST", SM "the smallest segment allowed to be modified"); other
 *     segments pass through unchanged and unsplit;
 *  2. an interior vertex V with neighbours P and N moves iff both of its segments are split; the end
 *     points of an open chain never move, a ring has none;
 *  3. the moved vertex goes to V + UC (V* - V), where V* is V's standard position: the apex of the
 *     triangle on the base M1 M2 (M1, M2 the midpoints of PV and VN) whose apex angle is
 *     theta = pi - 2 alpha with cos alpha = 2^(1/SD - 1) (the midpoint generator of Zhang et al. 2008
 *     Eq. 9, D = ln 2 / ln(2 cos alpha); SD = 1 gives theta = pi, SD = 2 a right angle), whose legs keep
 *     V's proportions, |M1 V*| / |V* M2| = |PV| / |VN|, and which lies on V's side of M1 M2.
 *     Negative UC moves V the opposite way by the same amount (Dutton's exaggeration).
 * So one iteration with ST = inf and SM = 0 turns an open chain of n vertices into 2n - 1 (a ring: 2n).
 * Calibrated mode (opts->target_dim != 0) takes theta from ft_dutton_apex_for_dimension instead of SD: the
 * literal relation gives a measured dimension well below SD (dutton_calibrate.c derives why and by how much).
 *
 * Where V* is (Dutton: "solving trigonometric identities involving the law of sines, law of cosines").
 * Let a = |PV|, c = |VN|, b = |M1 M2| = |PN| / 2 and p = |M1 V*|, q = |V* M2| with p / q = a / c.
 * V* lies on the circular arc through M1 and M2 that sees the base under theta (on V's side), at its
 * intersection with the Apollonius circle of ratio a / c. The law of cosines in M1 V* M2,
 *     b^2 = p^2 + q^2 - 2 p q cos theta,   with p = (a / c) q,
 * gives p = b a / E and q = b c / E, E^2 = a^2 + c^2 - 2 a c cos theta (E > 0: theta >= pi/2, so
 * cos theta <= 0). With u = M2 - M1 (|u| = b) and u' = u turned +90 degrees, V* = M1 + s u + sigma h u',
 * where s is the foot of the apex along the base and h its height, both as fractions of b:
 *     s = (p^2 - q^2 + b^2) / (2 b^2) = (1 + (a^2 - c^2) / E^2) / 2,
 *     h = p q sin theta / b^2          = a c sin theta / E^2        (twice the area over the base),
 * and sigma = +1 if V is left of the directed line P -> N, -1 if right. One square root per vertex
 * (a c = sqrt(a^2 c^2)). Checks: theta = pi gives V* on M1 M2 dividing it as a : c; a junction that
 * already has the angle theta is its own standard position (the triangle on the midline of P V N
 * with the same apex angle and leg ratio is P V N's own apex), so iterating never disturbs it.
 * A junction with no side — V on the line P N (turn below 1e-12 rad: a straight run or a reversal) or a
 * zero-length segment — is left in place: Dutton treats straightness as intentional, and picking a side
 * would invent a direction the data does not have. Its segments are still split by the window rule.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "line/dutton_internal.h"
#include "line/edit_internal.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define PARALLEL_MIN 32768     /* vertices below which a pass runs on one thread */
#define MAX_ITERATIONS 64

double ft_dutton_apex_angle(double sd)
{
    if (!(sd >= 1.0 && sd <= 2.0))
        return NAN;
    return PI - 2.0 * acos(pow(2.0, 1.0 / sd - 1.0));
}

/* Calibrated mode (target_dim != 0) ignores sd; its target must be one ft_dutton_apex_for_dimension reaches. */
static int check_angle_opts(const ft_dutton_opts *o)
{
    if (o->target_dim != 0.0) {
        if (!isnan(ft_dutton_apex_for_dimension(o->target_dim))) /* cached: one bisection per target */
            return FT_OK;
        double dmax = ft_dutton_steady_dimension(FT_DUTTON_APEX_MIN);
        return ft_error(FT_E_INVALID,
                        "target_dim must be 0 (off) or in [1,%.3f], got %g: the enhanced chain's dimension stops "
                        "rising below a 60 degree apex angle, where it overlaps itself",
                        floor(dmax * 1000.0) / 1000.0, o->target_dim);
    }
    if (!(o->sd >= 1.0 && o->sd <= 2.0))
        return ft_error(FT_E_INVALID, "sd must be in [1,2], got %g", o->sd);
    return FT_OK;
}

static int check_opts(const ft_dutton_opts *o)
{
    if (o == NULL)
        return ft_error(FT_E_INVALID, "enhance: NULL options");
    int rc = check_angle_opts(o);
    if (rc != FT_OK)
        return rc;
    if (!(o->uc >= -1.0 && o->uc <= 1.0))
        return ft_error(FT_E_INVALID, "uc must be in [-1,1], got %g", o->uc);
    if (o->iterations < 1 || o->iterations > MAX_ITERATIONS)
        return ft_error(FT_E_INVALID, "iterations must be in [1,%d], got %d", MAX_ITERATIONS, o->iterations);
    return ft_edit_check_window(o->st, o->sm);
}

typedef struct {
    double cos_t, sin_t, uc;
    ft_edit_window w;
} pass_params;

/* split[i] = 1 if segment i (vertex i to i+1, cyclically on a ring) is in the window. */
static void mark_splits(const ft_chain *in, size_t nseg, ft_edit_window w, unsigned char *split)
{
    size_t n = in->n;
#pragma omp parallel for schedule(static) if (n >= PARALLEL_MIN)
    for (size_t i = 0; i < nseg; i++)
        split[i] = (unsigned char)ft_edit_in_window(w, ft_edit_dist2(in, i, i + 1 < n ? i + 1 : 0));
}

/* Writes vertex i (moved or not) at out[k], then its segment's midpoint at out[k + 1] if split. */
static size_t emit_vertex(const ft_chain *in, const unsigned char *split, size_t nseg, const pass_params *pp,
                          size_t i, ft_chain *out, size_t k)
{
    size_t n = in->n;
    int has_prev = in->closed || i > 0, has_next = in->closed || i + 1 < n;
    size_t ip = i > 0 ? i - 1 : n - 1, in_ = i + 1 < n ? i + 1 : 0;
    double x = in->x[i], y = in->y[i];
    if (has_prev && has_next && split[ip] && split[i])
        ft_dutton_move(in->x[ip], in->y[ip], x, y, in->x[in_], in->y[in_], pp->cos_t, pp->sin_t, pp->uc, &x, &y);
    out->x[k] = x;
    out->y[k] = y;
    k++;
    if (i < nseg && split[i]) {
        out->x[k] = 0.5 * (in->x[i] + in->x[in_]);
        out->y[k] = 0.5 * (in->y[i] + in->y[in_]);
        k++;
    }
    return k;
}

/* Vertices [lo, hi) are written from out position lo + (splits before lo): each thread counts the splits
 * of its block, waits for the others, and writes its block after the blocks before it. */
static void emit_all(const ft_chain *in, const unsigned char *split, size_t nseg, const pass_params *pp,
                     ft_chain *out, size_t *counts, int nthreads)
{
    size_t n = in->n;
#pragma omp parallel num_threads(nthreads) if (n >= PARALLEL_MIN)
    {
        size_t t = (size_t)omp_get_thread_num(), nt = (size_t)omp_get_num_threads();
        size_t lo = n / nt * t + (t < n % nt ? t : n % nt);
        size_t hi = lo + n / nt + (t < n % nt ? 1 : 0);
        size_t cnt = 0;
        for (size_t i = lo; i < hi && i < nseg; i++)
            cnt += split[i];
        counts[t] = cnt;
#pragma omp barrier
        size_t k = lo;
        for (size_t j = 0; j < t; j++)
            k += counts[j];
        for (size_t i = lo; i < hi; i++)
            k = emit_vertex(in, split, nseg, pp, i, out, k);
    }
}

static int enhance_pass(const ft_chain *in, const pass_params *pp, ft_chain **out)
{
    size_t n = in->n, nseg = ft_chain_segments(in);
    unsigned char *split = ft_malloc(nseg);
    int nthreads = omp_get_max_threads();
    size_t *counts = ft_calloc((size_t)nthreads, sizeof *counts);
    if (split == NULL || counts == NULL) {
        free(split);
        free(counts);
        return FT_E_NOMEM;
    }
    mark_splits(in, nseg, pp->w, split);
    size_t extra = 0;
    for (size_t i = 0; i < nseg; i++)
        extra += split[i];
    int rc = FT_OK;
    ft_chain *c = n > SIZE_MAX / 2 ? NULL : ft_chain_create(n + extra, in->closed);
    if (c == NULL) {
        rc = n > SIZE_MAX / 2 ? ft_error(FT_E_NOMEM, "enhance: %zu vertices overflow", n) : FT_E_NOMEM;
    } else {
        emit_all(in, split, nseg, pp, c, counts, nthreads);
        c->n = n + extra;
    }
    free(split);
    free(counts);
    *out = c;
    return rc;
}

int ft_line_enhance(const ft_chain *in, const ft_dutton_opts *opts, ft_chain **out)
{
    int rc = ft_edit_check_chain("enhance", in, out);
    if (rc == FT_OK)
        rc = check_opts(opts);
    if (rc != FT_OK)
        return rc;
    double theta = opts->target_dim != 0.0 ? ft_dutton_apex_for_dimension(opts->target_dim)
                                           : ft_dutton_apex_angle(opts->sd);
    pass_params pp = {cos(theta), sin(theta), opts->uc, ft_edit_window_make(opts->st, opts->sm)};
    ft_chain *cur = NULL;
    for (int it = 0; it < opts->iterations && rc == FT_OK; it++) {
        ft_chain *next = NULL;
        rc = enhance_pass(cur ? cur : in, &pp, &next);
        ft_chain_free(cur);
        cur = next;
    }
    if (rc != FT_OK) {
        ft_chain_free(cur);
        return rc;
    }
    *out = cur;
    return FT_OK;
}
