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
 * keep_vertices (one pass only): the input's vertices stay, and each new midpoint M of P N goes where it is
 * relative to its neighbours in the pass above: M - (dP + dN) / 2, dP and dN the moves P and N get there (0
 * for a vertex that does not move). The pass's output minus its input vertices' moves, interpolated
 * linearly along each segment: the same small-scale shape, but the scales of the input's segments and
 * above, which the divider's coarse rulers see, are the input's own (issue 15: Dutton's first pass moves
 * the 158 vertices of the Newfoundland outline and lowers D at 2-8 of its segments by 0.04).
 * By default theta is calibrated (dutton_calibrate.c) so that the chain's divider D over the scales the
 * enhancement generates is the target D_in + UC (SD - D_in) (SD itself at UC = 1), D_in the input's divider
 * dimension; literal_sd takes theta from SD by the relation above, which measures well below SD (1.12 for
 * 1.3). A pass proposes base positions (the input's vertices and midpoints) and raw ones (the moved
 * vertices); unless allow_crossings, the crossing guard (move_guard.c) keeps the moves that cross nothing
 * (run fused into the pass by dutton_guarded.c). Both passes compute the raw positions of ft_dutton_raw_vertex
 * a run of vertices at a time (ft_dutton_raw_run, dutton_raw.c: in vector registers, with the same bits).
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
#include <stdio.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define PARALLEL_MIN 32768     /* vertices below which a pass runs on one thread */
#define MAX_ITERATIONS 64
#define RAW_RUN 256          /* vertices whose raw positions are computed together (ft_dutton_raw_run) */
#define DENSIFY_RATIO 3.0 /* calibrated mode: segments this many times the input's mean segment are cut first */

double ft_dutton_apex_angle(double sd)
{
    if (!(sd >= 1.0 && sd <= 2.0))
        return NAN;
    return PI - 2.0 * acos(pow(2.0, 1.0 / sd - 1.0));
}

static int check_opts(const ft_dutton_opts *o)
{
    if (o == NULL)
        return ft_error(FT_E_INVALID, "enhance: NULL options");
    if (o->sd == 0.0 && (o->literal_sd || o->uc <= 0.0))
        return ft_error(FT_E_INVALID, "sd 0 (the input's own dimension) needs the calibrated mode and uc > 0, got "
                        "%s and uc %g", o->literal_sd ? "literal_sd" : "calibrated", o->uc);
    if (!(o->sd >= 1.0 && o->sd <= 2.0) && o->sd != 0.0)
        return ft_error(FT_E_INVALID, "sd must be in [1,2], got %g", o->sd); /* or 0: the input's own D */
    if (!(o->uc >= -1.0 && o->uc <= 1.0))
        return ft_error(FT_E_INVALID, "uc must be in [-1,1], got %g", o->uc);
    if (o->target_dim != 0.0 && !(o->target_dim >= 1.0 && o->target_dim <= 2.0))
        return ft_error(FT_E_INVALID, "target_dim must be 0 (from sd) or in [1,2], got %g", o->target_dim);
    if (o->input_dim != 0.0 && !(o->input_dim >= 1.0 && o->input_dim <= 2.0))
        return ft_error(FT_E_INVALID, "input_dim must be 0 (measured) or in [1,2], got %g", o->input_dim);
    if (o->iterations < 1 || o->iterations > MAX_ITERATIONS)
        return ft_error(FT_E_INVALID, "iterations must be in [1,%d], got %d", MAX_ITERATIONS, o->iterations);
    if (o->keep_vertices && o->iterations != 1)
        return ft_error(FT_E_INVALID, "keep_vertices keeps the input's vertices in one pass: iterations must be 1, "
                        "got %d", o->iterations);
    return ft_edit_check_window(o->st, o->sm);
}

/* D_in: the divider dimension of the input chains over their automatic range. */
static int measure_input_dim(const ft_chain *const *chains, size_t n, double *d)
{
    ft_line_dim_opts lo = FT_LINE_DIM_OPTS_DEFAULT;
    ft_dim_result *r = NULL;
    int rc = ft_line_dim(chains, n, FT_LINE_DIVIDER, &lo, &r);
    if (rc != FT_OK) {
        char msg[400];
        snprintf(msg, sizeof msg, "%s", ft_last_error());
        return ft_error(FT_E_INVALID,
                        "enhance: uc < 1 needs the input's dimension D_in and it cannot be measured (%s); give "
                        "input_dim (--input-dim), a target_dim, or uc = 1",
                        msg);
    }
    *d = fmin(fmax(r->D, 1.0), 2.0);
    ft_dim_result_free(r);
    return FT_OK;
}

/* The mean segment length of the chains (0 if none): a scale for densify(), so a square root per segment
 * (hypot's overflow guard is not needed for it, and costs twice the pass's arithmetic on a 10^6-vertex chain). */
static double mean_segment(const ft_chain *const *chains, size_t n)
{
    double len = 0.0;
    size_t nseg = 0;
    for (size_t c = 0; c < n; c++) {
        const ft_chain *ch = chains[c];
        size_t ns = ft_chain_segments(ch);
        for (size_t i = 0; i < ns; i++)
            len += sqrt(ft_edit_dist2(ch, i, i + 1 < ch->n ? i + 1 : 0));
        nseg += ns;
    }
    return nseg > 0 ? len / (double)nseg : 0.0;
}

int ft_dutton_plan_make(const ft_chain *const *chains, size_t n, const ft_dutton_opts *o, ft_dutton_plan *p)
{
    ft_dutton_opts taken = FT_DUTTON_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (o != NULL) {
        if (FT_OPTS_TAKE(taken, o, ft_dutton_opts) != FT_OK)
            return FT_E_INVALID;
        o = &taken;
    }
    if (p == NULL)
        return ft_error(FT_E_INVALID, "enhance: NULL plan");
    int rc = check_opts(o);
    if (rc != FT_OK)
        return rc;
    *p = (ft_dutton_plan){ft_dutton_apex_angle(o->sd), NAN, NAN, o->uc, o->st, o->sm, 0.0, o->keep_vertices != 0};
    if (o->literal_sd || o->uc <= 0.0)
        return FT_OK; /* literal reading; uc = 0 moves nothing, uc < 0 exaggerates: no dimension target */
    double target = o->target_dim;
    if (target == 0.0 && o->sd == 0.0) { /* SD is the input's own D (Dutton's Newfoundland): D_in whatever uc */
        double din = o->input_dim;
        if (din == 0.0 && (rc = measure_input_dim(chains, n, &din)) != FT_OK)
            return rc;
        p->input_dim = din;
        target = din;
    } else if (target == 0.0 && o->uc == 1.0) {
        target = o->sd;
    } else if (target == 0.0) {
        double din = o->input_dim;
        if (din == 0.0 && (rc = measure_input_dim(chains, n, &din)) != FT_OK)
            return rc;
        p->input_dim = din;
        target = ft_dutton_target_dimension(o->sd, o->uc, din);
    }
    double apex = ft_dutton_apex_for_target(target, o->uc);
    if (isnan(apex)) {
        double dmax = ft_dutton_max_dimension(o->uc);
        return ft_error(FT_E_INVALID,
                        "enhance: a target dimension of %.3f is out of reach with uc = %g: the enhanced chain's "
                        "dimension stops rising at %.3f (a 60 degree apex angle, where it overlaps itself)",
                        target, o->uc, floor(dmax * 1000.0) / 1000.0);
    }
    p->apex = apex;
    p->target_dim = target;
    p->densify = mean_segment(chains, n);
    return FT_OK;
}

typedef ft_dutton_pass_params pass_params;

void ft_dutton_mark_splits(const ft_chain *in, size_t nseg, ft_edit_window w, unsigned char *split)
{
    size_t n = in->n;
#pragma omp parallel for schedule(static) if (n >= PARALLEL_MIN)
    for (size_t i = 0; i < nseg; i++)
        split[i] = (unsigned char)ft_edit_in_window(w, ft_edit_dist2(in, i, i + 1 < n ? i + 1 : 0));
}

/* Writes vertex i at out[k] (at raw, its raw position, unless keep_vertices), then its segment's midpoint at
 * out[k + 1] if split. */
static size_t emit_vertex(const ft_chain *in, const unsigned char *split, size_t nseg, const pass_params *pp,
                          size_t i, const double *raw, ft_chain *out, ft_chain *base, size_t k)
{
    size_t in_ = i + 1 < in->n ? i + 1 : 0;
    out->x[k] = pp->keep_vertices ? in->x[i] : raw[0];
    out->y[k] = pp->keep_vertices ? in->y[i] : raw[1];
    if (base) {
        base->x[k] = in->x[i];
        base->y[k] = in->y[i];
    }
    k++;
    if (i < nseg && split[i]) {
        double mx = 0.5 * (in->x[i] + in->x[in_]), my = 0.5 * (in->y[i] + in->y[in_]);
        out->x[k] = mx;
        out->y[k] = my;
        if (pp->keep_vertices) { /* M - (dP + dN) / 2 */
            double px, py, nx, ny;
            (void)ft_dutton_raw_vertex(in, split, pp, i, &px, &py);
            (void)ft_dutton_raw_vertex(in, split, pp, in_, &nx, &ny);
            out->x[k] = mx - 0.5 * ((px - in->x[i]) + (nx - in->x[in_]));
            out->y[k] = my - 0.5 * ((py - in->y[i]) + (ny - in->y[in_]));
        }
        if (base) {
            base->x[k] = mx;
            base->y[k] = my;
        }
        k++;
    }
    return k;
}

/* Vertices [lo, hi) are written from out position lo + (splits before lo): each thread counts the splits
 * of its block, waits for the others, and writes its block after the blocks before it, RAW_RUN vertices at a
 * time. */
static void emit_all(const ft_chain *in, const unsigned char *split, size_t nseg, const pass_params *pp,
                     ft_chain *out, ft_chain *base, size_t *counts, int nthreads)
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
        double raw[2 * RAW_RUN];
        for (size_t r = lo; r < hi; r += RAW_RUN) {
            size_t e = hi - r > RAW_RUN ? r + RAW_RUN : hi;
            if (!pp->keep_vertices)
                ft_dutton_raw_run(in, split, pp, r, e, raw);
            for (size_t i = r; i < e; i++)
                k = emit_vertex(in, split, nseg, pp, i, &raw[2 * (i - r)], out, base, k);
        }
    }
}

static int enhance_pass(const ft_chain *in, const pass_params *pp, ft_chain **base, ft_chain **out)
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
    ft_dutton_mark_splits(in, nseg, pp->w, split);
    size_t extra = 0;
    for (size_t i = 0; i < nseg; i++)
        extra += split[i];
    int rc = FT_OK;
    ft_chain *c = n > SIZE_MAX / 2 ? NULL : ft_chain_create(n + extra, in->closed);
    ft_chain *b = c == NULL || base == NULL ? NULL : ft_chain_create(n + extra, in->closed);
    if (c == NULL || (base != NULL && b == NULL)) {
        rc = n > SIZE_MAX / 2 ? ft_error(FT_E_NOMEM, "enhance: %zu vertices overflow", n) : FT_E_NOMEM;
        ft_chain_free(c);
        c = NULL;
    } else {
        emit_all(in, split, nseg, pp, c, b, counts, nthreads);
        c->n = n + extra;
        if (b)
            b->n = n + extra;
    }
    free(split);
    free(counts);
    *out = c;
    if (base)
        *base = b;
    return rc;
}

/* Pieces a segment of squared length l2 is cut into before a pass: ceil(L / len) if L >= 3 len and the
 * segment is in the window (Dutton's ST keeps longer ones straight), no piece shorter than SM; else 1. */
static size_t densify_pieces(double l2, double len, ft_edit_window w)
{
    if (!(l2 >= DENSIFY_RATIO * DENSIFY_RATIO * len * len) || !ft_edit_in_window(w, l2))
        return 1;
    double L = sqrt(l2), m = ceil(L / len);
    if (w.sm2 > 0.0)
        m = fmin(m, floor(L / sqrt(w.sm2)));
    return m > 1.0 ? (size_t)m : 1;
}

/* Calibrated mode: the segments much longer than the input's mean (a straight border drawn with two
 * vertices) cut into pieces of about the mean, new vertices on the segment, so that every part of the
 * chain is enhanced over the same scales (a long segment would otherwise carry its coarse, not yet steady
 * generations into the rulers). *out stays NULL when no segment needs it. */
static int densify(const ft_chain *in, double len, ft_edit_window w, ft_chain **out)
{
    size_t n = in->n, nseg = ft_chain_segments(in), extra = 0;
    for (size_t i = 0; i < nseg; i++)
        extra += densify_pieces(ft_edit_dist2(in, i, i + 1 < n ? i + 1 : 0), len, w) - 1;
    if (extra == 0)
        return FT_OK;
    ft_chain *d = ft_chain_create(n + extra, in->closed);
    if (d == NULL)
        return FT_E_NOMEM;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        d->x[k] = in->x[i];
        d->y[k] = in->y[i];
        k++;
        if (i >= nseg)
            continue;
        size_t j = i + 1 < n ? i + 1 : 0;
        size_t m = densify_pieces(ft_edit_dist2(in, i, j), len, w);
        for (size_t q = 1; q < m; q++) {
            double t = (double)q / (double)m;
            d->x[k] = in->x[i] + t * (in->x[j] - in->x[i]);
            d->y[k] = in->y[i] + t * (in->y[j] - in->y[i]);
            k++;
        }
    }
    d->n = k;
    *out = d;
    return FT_OK;
}

int ft_dutton_pass_prepare(const ft_chain *in, const ft_dutton_plan *p, ft_dutton_pass_params *pp, ft_chain **dense)
{
    *dense = NULL;
    if (p == NULL)
        return ft_error(FT_E_INVALID, "enhance: NULL plan");
    ft_chain *dummy = NULL;
    int rc = ft_edit_check_chain("enhance", in, &dummy);
    if (rc != FT_OK)
        return rc;
    *pp = (pass_params){cos(p->apex), sin(p->apex), p->uc, ft_edit_window_make(p->st, p->sm), !isnan(p->target_dim),
                        p->keep_vertices};
    if (p->densify > 0.0)
        rc = densify(in, p->densify, pp->w, dense);
    return rc;
}

int ft_line_pass_enhance(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw)
{
    if (raw == NULL)
        return ft_error(FT_E_INVALID, "enhance: NULL output pointer");
    *raw = NULL;
    if (base)
        *base = NULL;
    pass_params pp;
    ft_chain *dense = NULL;
    int rc = ft_dutton_pass_prepare(in, ctx, &pp, &dense);
    if (rc != FT_OK)
        return rc;
    rc = enhance_pass(dense ? dense : in, &pp, base, raw);
    ft_chain_free(dense);
    return rc;
}

int ft_line_enhance(const ft_chain *in, const ft_dutton_opts *opts, ft_chain **out)
{
    ft_dutton_opts taken = FT_DUTTON_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_dutton_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    int rc = ft_edit_check_chain("enhance", in, out);
    ft_dutton_plan plan;
    if (rc == FT_OK)
        rc = ft_dutton_plan_make(&in, 1, opts, &plan);
    if (rc == FT_OK)
        rc = ft_line_run_passes_into(&in, 1, ft_line_pass_enhance, &plan, opts->iterations, !opts->allow_crossings,
                                     NULL, out);
    return rc;
}
