/* fracterra — contour/mountain.c: the contour generation method of Misawa, Chiba & Saito ("Simulation of
 * natural scenes: procedure modeling for mountains"): every contour of a mountain from seed contour(s).
 *
 * One level from the level below it (P), going up (shrinking by the spacing d) — §3 and §4:
 *   simple   (§3)   thin(shrink(P, d))
 *   midpoint (§4.1) clean(midpoint(thin(shrink(P, d))))
 *   fourier  (§4.2) clean(fourier(shrink(P, d)))
 *   improved (§4.3) clean(midpoint(clean(collinear(fourier(shrink(P, d))))))
 * shrink: ft_contour_shrink with the d' join (or the join asked for); midpoint: every ring's segments
 * longer than 2 d0 (d0 the seed's mean segment length) split with displacements min(d'', |l tan theta|),
 * d'' = dsecond d (§4.1); fourier: every ring resampled to n points, its P-type descriptor's phases
 * randomized from f0 up (§4.2); collinear: nearly collinear vertices removed (§4.3); clean (§4.4): the
 * faces the rings wind around positively (twists and loops removed), faces smaller than shrink.min_area d^2
 * dropped, as the shrinking does; thin: Douglas-Peucker at 0.01 d (GEOS's topology-preserving one for the
 * simple method, whose result must stay valid), because the d' joins add vertices at every reflex corner
 * (one shrink of a smooth 2,000-vertex ring returns about 3,700), which the next levels would carry on.
 * The midpoint displacement comes last: §4.1 applies it to "the generated polygons", §4.3 step 1.0 to
 * the contours of P before they are shrunk; both mean that every generated contour carries its
 * displacement, and so it does here (the seed is kept as given). Measured, this is also what keeps the
 * contours' divider dimension near the seed's: displaced before the shrink and the phase randomization,
 * the detail is rounded off again (§4.2 notes that phase randomization alone rounds the contours).
 * Below the seed (levels_down) the same steps grow by d instead (shrink(., -d)), and grown contours that
 * meet merge (the paper's future work: several seed contours of one range).
 *
 * Theta from the seed's dimension (match_dim = 1, the default; improved method only). §5 proposes to set
 * theta from the seed's fractal dimension. The paper's fixed 20-40 degrees give every seed about the same
 * roughness (divider D 1.08-1.16 over d0 .. 4 d0, measured): a smooth seed (D 1.01) gets contours of
 * D 1.04-1.16. The rule: D* = the seed's divider dimension (all its rings, rulers d0 .. 4 d0, the whole
 * range fitted, ft_line_dim); every ring is displaced with theta uniform in s [theta_min, theta_max],
 * s chosen for that ring by bisection on [0, 56 / theta_max] (56 degrees: the displacement's own cap) so
 * that the displaced ring's divider D over the same rulers is D*, the random draws being the same at
 * every s. A halving at angle theta multiplies a segment's length by 1 / cos theta, so a full cascade
 * would give D = 1 - log2(cos theta) (Nakajima's relation, the paper's [中嶋85]); here only the segments
 * longer than 2 d0 are split, one cascade per level, and the shrink and the phase randomization change
 * the rest, so the angle is found by measurement instead of that formula (for the Luxembourg contour of
 * D 1.13, where the formula gives 24 degrees, s comes out mostly 0.9-1.1, the paper's range; for the
 * smooth Maunga Whau contour mostly 0). When
 * even s = 0 leaves a ring rougher than D* (small summit contours, whose outline counts at the largest
 * rulers) or the ring is shorter than four of the largest rulers, the ring is left as it is (splitting
 * with no displacement would only add collinear vertices); when s at its cap leaves it smoother (d''
 * limits the offsets), the cap is used. The largest ruler is 4 d0 so that a contour of 50 vertices is
 * still walked in a dozen steps. match_dim = 0 keeps [theta_min, theta_max] as given. Cost: up to 9
 * displacements and divider walks per ring (2,000-vertex seed, 60 levels: 0.21 s on one core against
 * 0.29 s with the fixed range, which splits more).
 *
 * Collinear removal, default (collinear_deg = 0): §4.3 removes nearly collinear points so that "the
 * segments of length 2 d0 or more are about 20 % of all"; the threshold angle is found per ring by
 * bisection on [0, 90] degrees as the smallest that leaves 20 % of the segments longer than 2 d0 (none is
 * removed if they already are). collinear_deg > 0 fixes the angle instead.
 *
 * Crossing guard (issue 15; allow_crossings = 0, the default). The midpoint displacement and the phase
 * randomization each move vertices from a base (the undisplaced ring with the added vertices on it; the
 * resampled ring the randomization starts from) to the drawn positions; contour/guard_displace.c moves every
 * vertex all, half, a quarter of the way or not at all, as far as it touches no other ring of the level and
 * no ring of the level below (line/move_guard.c, FT_GUARD_REDUCE). The counts go to the stack
 * (guard_moves, guard_reduced, guard_dropped). The cleaning and nesting below still run: they catch what
 * the guard cannot see (rings that touch before the move, the collinear removal after the randomization).
 *
 * Nesting. The stochastic steps may push a contour out of the one below it. Every new level is therefore
 * kept as it is if it lies inside the level below eroded by eps = 0.02 d (a GEOS buffer; a prepared
 * covers test), and otherwise replaced by its intersection with it; going down, it must cover the level
 * above dilated by eps, or becomes its union with it. So a contour never comes closer than eps to its
 * neighbour, and containment (ft_polygon_set_within) holds with that margin whatever the rounding.
 * Polygons left smaller than shrink.min_area d^2 by an intersection are dropped (holes are kept: filling
 * one could cross the level below). The levels go up until levels_up, or until nothing is left.
 *
 * Defaults (0 in the options struct): spacing d = sqrt(seed area) / 40, so a round seed gives about 20
 * levels above it; d' = 3 d for improved (§4.3's best), 1.2 d for the others (§2, Fig. 7: the paper's
 * Fig. 10, 12 and 15 also use 1.4 d, "the most real" for the simple method; pass it explicitly);
 * collinear_deg as above. levels_up = -1 stops when the contour vanishes,
 * after at most 10000 levels.
 *
 * Random streams: the ring operators draw from stream (level, ring, operator) of opts->seed, level
 * counted from the seed (+k above, -k below), ring the index of the ring in its set (outer rings and
 * their holes, polygon by polygon), so the stack is reproducible and independent of evaluation order.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"
#include "fracterra/line.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_LEVELS 10000
#define NEST_EPS 0.02            /* nesting margin, a fraction of d */
#define SIMPLIFY_TOL 0.01        /* vertex thinning tolerance, a fraction of d */
#define DEFAULT_SPACING_DIV 40.0 /* d = sqrt(area) / 40 */
#define LONG_SHARE 0.2           /* default collinear removal: 20 % of the segments longer than 2 d0 */
#define COLLINEAR_BISECTIONS 12
#define BUFFER_QUADSEGS 2
#define MATCH_RULERS 4.0     /* the dimension is measured over rulers d0 .. 4 d0 */
#define MATCH_MIN_STEPS 4.0  /* a ring is measured if its perimeter is >= 4 of the largest rulers */
#define MATCH_THETA_CAP 56.0 /* degrees: the displacement's own cap (midpoint_displace.c, 56.3) */
#define MATCH_BISECTIONS 7

enum { OP_MIDPOINT = 0, OP_FOURIER = 1 };

static const char *const METHOD_NAMES[] = {"simple", "midpoint", "fourier", "improved"};

const char *ft_mountain_method_name(ft_mountain_method m)
{
    if ((int)m < 0 || (int)m > FT_MOUNTAIN_IMPROVED)
        return "unknown";
    return METHOD_NAMES[m];
}

/* Misawa et al.: d' = 3 d for the improved method (§4.3); d' = 1.4 d "nearly like the real ones" for
 * the polygon shrinking with midpoint displacement and Fourier descriptors (Figs. 10, 12, 15). */
double ft_mountain_default_dprime(ft_mountain_method m)
{
    switch (m) {
    case FT_MOUNTAIN_IMPROVED: return 3.0;
    case FT_MOUNTAIN_SIMPLE: return 1.2;
    default: return 1.4;
    }
}

int ft_mountain_method_parse(const char *name, ft_mountain_method *m)
{
    if (m == NULL)
        return ft_error(FT_E_INVALID, "ft_mountain_method_parse: NULL output");
    for (int i = 0; name != NULL && i <= FT_MOUNTAIN_IMPROVED; i++)
        if (strcmp(name, METHOD_NAMES[i]) == 0) {
            *m = (ft_mountain_method)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "unknown mountain method '%s' (simple, midpoint, fourier, improved)",
                    name ? name : "(null)");
}

/* ---- the generator's state ------------------------------------------------------------------- */

typedef struct {
    ft_mountain_method method;
    double d, eps, simplify, min_area;
    ft_shrink_opts shrink;
    ft_midpoint_opts mid;
    ft_fourier_opts fourier;
    double collinear;
    uint64_t seed;
    int match;                /* theta scaled ring by ring to match dim_target */
    double dim_target;        /* the seed's divider dimension over d0 .. 4 d0 */
    ft_line_dim_opts dim_opts;
    int guard;                /* the displacements and randomizations guarded against crossings */
    ft_line_guard_stats stats; /* what the guard did, over every level */
    ft_geos g;
} generator;

static uint64_t stream_id(int level, size_t ring, int op)
{
    return ((uint64_t)(level + (1 << 20)) << 40) | ((uint64_t)ring << 2) | (uint64_t)op;
}

typedef struct {
    ft_chain **c;
    size_t n;
} rings;

static void rings_free(rings *r)
{
    for (size_t i = 0; i < r->n; i++)
        ft_chain_free(r->c[i]);
    free(r->c);
    r->c = NULL;
    r->n = 0;
}

/* The region the rings wind around positively, small faces dropped: the loop removal of §4.4. */
static int clean_rings(generator *gen, rings *r, ft_polygon_set **out)
{
    ft_polygon_set *s = ft_polygon_set_create();
    if (s == NULL)
        return FT_E_NOMEM;
    int rc = ft_contour_positive_region(&gen->g, r->c, r->n, gen->d, gen->min_area, s);
    if (rc != FT_OK) {
        ft_polygon_set_free(s);
        return rc;
    }
    *out = s;
    return FT_OK;
}

/* Divider dimension of a set of rings over the seed's rulers d0 .. 4 d0; NAN when they are too short to
 * walk (perimeter below MATCH_MIN_STEPS of the largest ruler) or the fit fails (no error is left set). */
static double rings_dim(const generator *gen, const ft_chain *const *c, size_t n)
{
    double len = 0.0;
    for (size_t i = 0; i < n; i++)
        len += ft_chain_length(c[i]);
    if (!(len >= MATCH_MIN_STEPS * gen->dim_opts.max_scale))
        return NAN;
    ft_dim_result *r = NULL;
    if (ft_line_dim(c, n, FT_LINE_DIVIDER, &gen->dim_opts, &r) != FT_OK) {
        ft_clear_error();
        return NAN;
    }
    double D = r->D;
    ft_dim_result_free(r);
    return isfinite(D) ? D : NAN;
}

/* The ring displaced with the angle range scaled by s: theta uniform in s [theta_min, theta_max]. */
static int displace_scaled(const generator *gen, const ft_chain *ring, double s, uint64_t stream, ft_chain **out)
{
    ft_midpoint_opts m = gen->mid;
    m.theta_min *= s;
    m.theta_max *= s;
    return ft_contour_midpoint_displace(ring, &m, gen->seed, stream, out);
}

/* Midpoint displacement of one ring; with match_dim (§5: theta from the fractal dimension), the scale s of
 * the angle range whose displaced ring has the seed's divider dimension, by bisection on
 * [0, MATCH_THETA_CAP / theta_max] with the same random draws at every s (the dimension grows with s: a
 * halving at angle theta lengthens a segment by 1 / cos theta). A ring too short to be measured (and any
 * ring whose best scale is 0) is left as it is: splitting without displacement adds only collinear
 * vertices. */
static int displace_ring(generator *gen, const ft_chain *ring, uint64_t stream, ft_chain **out)
{
    if (!gen->match || !(gen->mid.theta_max > 0.0))
        return ft_contour_midpoint_displace(ring, &gen->mid, gen->seed, stream, out);
    if (!(ft_chain_length(ring) >= MATCH_MIN_STEPS * gen->dim_opts.max_scale))
        return (*out = ft_chain_copy(ring)) != NULL ? FT_OK : FT_E_NOMEM; /* too short: nothing to match */
    double target = gen->dim_target, lo = 0.0, hi = MATCH_THETA_CAP / gen->mid.theta_max;
    ft_chain *best = NULL;
    double best_err = INFINITY, best_s = 0.0;
    /* the ends first: at hi the ring may still be smoother than the seed (d'' caps the offsets), at 0 (no
     * displacement) it may already be rougher (small summit contours) */
    double probe[2] = {hi, 0.0};
    for (int it = 0; it < 2 + MATCH_BISECTIONS; it++) {
        double s = it < 2 ? probe[it] : 0.5 * (lo + hi);
        ft_chain *c = NULL;
        int rc = displace_scaled(gen, ring, s, stream, &c);
        if (rc != FT_OK) {
            ft_chain_free(best);
            return rc;
        }
        double D = rings_dim(gen, (const ft_chain *const *)&c, 1);
        if (isnan(D)) { /* the fit failed: nothing to match */
            ft_chain_free(c);
            ft_chain_free(best);
            best = NULL;
            best_s = 0.0;
            break;
        }
        double err = fabs(D - target);
        if (err < best_err) {
            ft_chain_free(best);
            best = c;
            best_err = err;
            best_s = s;
        } else {
            ft_chain_free(c);
        }
        if ((it == 0 && D <= target) || (it == 1 && D >= target))
            break; /* the whole range is on one side of the target: its end */
        if (it >= 2) {
            if (D < target)
                lo = s;
            else
                hi = s;
        }
    }
    if (best_s == 0.0) { /* no displacement: splitting would only add collinear vertices */
        ft_chain_free(best);
        best = ft_chain_copy(ring);
        if (best == NULL)
            return FT_E_NOMEM;
    }
    *out = best;
    return FT_OK;
}

/* Midpoint displacement of every ring of P (§4.1), guarded against the rings of P and of the level below
 * (unless allow_crossings), cleaned; with thin, each ring is first thinned by Douglas-Peucker at the
 * thinning tolerance (the shrink's joins multiply vertices). */
static int displaced(generator *gen, const ft_polygon_set *p, const ft_polygon_set *below, int level, int thin,
                     ft_polygon_set **out)
{
    size_t nr = ft_polygon_set_ring_count(p);
    rings r = {ft_calloc(nr + 1, sizeof(ft_chain *)), 0};
    ft_chain **used = ft_calloc(nr + 1, sizeof *used); /* the rings displaced: thinned copies or NULL */
    if (r.c == NULL || used == NULL) {
        free(r.c);
        free(used);
        return FT_E_NOMEM;
    }
    int rc = FT_OK;
    for (size_t k = 0; rc == FT_OK && k < nr; k++) {
        const ft_chain *ring = ft_polygon_set_ring(p, k);
        if (thin && (rc = ft_line_simplify(ring, gen->simplify, &used[k])) == FT_OK)
            ring = used[k];
        if (rc == FT_OK)
            rc = displace_ring(gen, ring, stream_id(level, k, OP_MIDPOINT), &r.c[r.n]);
        r.n += rc == FT_OK;
    }
    if (rc == FT_OK && gen->guard) {
        const ft_chain **ring = ft_calloc(nr + 1, sizeof *ring);
        if (ring == NULL)
            rc = FT_E_NOMEM;
        for (size_t k = 0; rc == FT_OK && k < nr; k++)
            ring[k] = used[k] != NULL ? used[k] : ft_polygon_set_ring(p, k);
        if (rc == FT_OK)
            rc = ft_contour_guard_displaced(r.c, ring, r.n, below, &gen->stats);
        free(ring);
    }
    if (rc == FT_OK)
        rc = clean_rings(gen, &r, out);
    for (size_t k = 0; k < nr; k++)
        ft_chain_free(used[k]);
    free(used);
    rings_free(&r);
    return rc;
}

/* Fraction of the ring's segments longer than max_seg. */
static double long_fraction(const ft_chain *c, double max_seg)
{
    size_t n = 0, nseg = ft_chain_segments(c);
    for (size_t i = 0; i < nseg; i++) {
        size_t j = (i + 1) % c->n;
        n += hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]) > max_seg;
    }
    return nseg ? (double)n / (double)nseg : 0.0;
}

/* Collinear removal (§4.3): with a fixed threshold, or (collinear_deg = 0) with the smallest one that
 * leaves LONG_SHARE of the segments longer than 2 d0, found by bisection on [0, 90] degrees. */
static int collinear_removed(generator *gen, const ft_chain *f, ft_chain **out)
{
    if (gen->collinear > 0.0)
        return ft_contour_remove_collinear(f, gen->collinear, out);
    if (long_fraction(f, gen->mid.max_seg) >= LONG_SHARE)
        return ft_contour_remove_collinear(f, 0.0, out);
    double lo = 0.0, hi = 90.0;
    ft_chain *best = NULL;
    for (int it = 0; it < COLLINEAR_BISECTIONS; it++) {
        double a = 0.5 * (lo + hi);
        ft_chain *c = NULL;
        int rc = ft_contour_remove_collinear(f, a, &c);
        if (rc != FT_OK) {
            ft_chain_free(best);
            return rc;
        }
        if (long_fraction(c, gen->mid.max_seg) >= LONG_SHARE) {
            hi = a;
            ft_chain_free(best);
            best = c;
        } else {
            lo = a;
            ft_chain_free(c);
        }
    }
    if (best == NULL)
        return ft_contour_remove_collinear(f, hi, out);
    *out = best;
    return FT_OK;
}

/* Phase randomization of every ring of S (§4.2), guarded against the rings of S and of the level below
 * (unless allow_crossings: each vertex moves from its place on the resampled ring towards its randomized
 * one only as far as it crosses nothing), then collinear removal (§4.3, improved), cleaned. */
static int randomized(generator *gen, const ft_polygon_set *s, const ft_polygon_set *below, int level,
                      ft_polygon_set **out)
{
    size_t nr = ft_polygon_set_ring_count(s);
    rings r = {ft_calloc(nr + 1, sizeof(ft_chain *)), 0};
    ft_chain **base = ft_calloc(nr + 1, sizeof *base); /* the resampled rings (guarded) */
    int rc = r.c != NULL && base != NULL ? FT_OK : FT_E_NOMEM;
    for (size_t k = 0; rc == FT_OK && k < nr; k++) {
        rc = ft_contour_fourier_randomize_paired(ft_polygon_set_ring(s, k), &gen->fourier, gen->seed,
                                                 stream_id(level, k, OP_FOURIER), gen->guard ? &base[k] : NULL,
                                                 &r.c[r.n]);
        r.n += rc == FT_OK;
    }
    if (rc == FT_OK && gen->guard)
        rc = ft_contour_guard_rings(r.c, base, r.n, below, &gen->stats); /* takes the bases */
    for (size_t k = 0; rc == FT_OK && gen->method == FT_MOUNTAIN_IMPROVED && k < r.n; k++) {
        ft_chain *c = NULL;
        rc = collinear_removed(gen, r.c[k], &c);
        if (rc == FT_OK) {
            ft_chain_free(r.c[k]);
            r.c[k] = c;
        }
    }
    if (rc == FT_OK)
        rc = clean_rings(gen, &r, out);
    for (size_t k = 0; base != NULL && k < nr; k++)
        ft_chain_free(base[k]);
    free(base);
    rings_free(&r);
    return rc;
}

/* GEOS's answer as a set (no area limit: holes are kept), polygons smaller than min_area dropped when
 * drop_small. Takes geom. */
static int set_of_geos(generator *gen, GEOSGeometry *geom, int drop_small, ft_polygon_set **out)
{
    ft_polygon_set *s = ft_polygon_set_create();
    int rc = s ? ft_geos_append_to_set(&gen->g, geom, 0.0, s) : FT_E_NOMEM;
    GEOSGeom_destroy_r(gen->g.h, geom);
    if (rc == FT_OK && drop_small) {
        size_t m = 0;
        for (size_t i = 0; i < s->n; i++) {
            ft_polygon *p = &s->polys[i];
            if (fabs(ft_chain_signed_area(p->outer)) >= gen->min_area) {
                s->polys[m++] = *p;
                continue;
            }
            ft_chain_free(p->outer);
            for (size_t k = 0; k < p->nholes; k++)
                ft_chain_free(p->holes[k]);
            free(p->holes);
        }
        s->n = m;
    }
    if (rc != FT_OK) {
        ft_polygon_set_free(s);
        return rc;
    }
    *out = s;
    return FT_OK;
}

/* The set thinned by GEOS's topology-preserving Douglas-Peucker at the thinning tolerance (still valid). */
static int thinned(generator *gen, const ft_polygon_set *c, ft_polygon_set **out)
{
    GEOSGeometry *a = ft_geos_from_set(&gen->g, c), *t = NULL;
    if (a == NULL)
        return ft_last_error_code();
    t = GEOSTopologyPreserveSimplify_r(gen->g.h, a, gen->simplify);
    GEOSGeom_destroy_r(gen->g.h, a);
    if (t == NULL)
        return ft_geos_fail(&gen->g, "thinning the level's vertices");
    return set_of_geos(gen, t, 1, out);
}

/* The new level c made to lie inside the level below, p eroded by eps (up), or to hold the level above,
 * p dilated by eps (down): c itself when it already does, else its intersection with (union with) it. */
static int nested(generator *gen, const ft_polygon_set *c, const ft_polygon_set *p, int up, ft_polygon_set **out)
{
    GEOSContextHandle_t h = gen->g.h;
    GEOSGeometry *a = ft_geos_from_set(&gen->g, c), *b = NULL, *buf = NULL, *r = NULL;
    if (a != NULL)
        b = ft_geos_from_set(&gen->g, p);
    if (b != NULL && (buf = GEOSBuffer_r(h, b, up ? -gen->eps : gen->eps, BUFFER_QUADSEGS)) == NULL)
        ft_geos_fail(&gen->g, up ? "eroding the level below" : "dilating the level above");
    char done = 0;
    if (buf != NULL) {
        const GEOSPreparedGeometry *pg = GEOSPrepare_r(h, up ? buf : a);
        done = pg ? GEOSPreparedCovers_r(h, pg, up ? a : buf) : 0;
        if (pg)
            GEOSPreparedGeom_destroy_r(h, pg);
    }
    if (buf != NULL && done != 1) {
        r = up ? GEOSIntersection_r(h, a, buf) : GEOSUnion_r(h, a, buf);
        if (r == NULL) /* a robustness failure of overlay: snap to a fine grid */
            r = up ? GEOSIntersectionPrec_r(h, a, buf, gen->eps * 1e-4) : GEOSUnionPrec_r(h, a, buf, gen->eps * 1e-4);
        if (r == NULL)
            ft_geos_fail(&gen->g, up ? "nesting a level in the one below" : "nesting a level around the one above");
    }
    int rc;
    if (done == 1)
        rc = (*out = ft_polygon_set_copy(c)) != NULL ? FT_OK : FT_E_NOMEM;
    else
        rc = r != NULL ? set_of_geos(gen, r, up, out) : ft_last_error_code();
    if (a)
        GEOSGeom_destroy_r(h, a);
    if (b)
        GEOSGeom_destroy_r(h, b);
    if (buf)
        GEOSGeom_destroy_r(h, buf);
    return rc;
}

/* The level next to p: above it (up) or below it, `level` steps from the seed. */
static int next_level(generator *gen, const ft_polygon_set *p, int level, int up, ft_polygon_set **out)
{
    *out = NULL;
    int displace = gen->method == FT_MOUNTAIN_MIDPOINT || gen->method == FT_MOUNTAIN_IMPROVED;
    int randomize = gen->method == FT_MOUNTAIN_FOURIER || gen->method == FT_MOUNTAIN_IMPROVED;
    const ft_polygon_set *cur = p;
    ft_polygon_set *step[3] = {NULL, NULL, NULL};
    int rc = ft_contour_shrink(cur, up ? gen->d : -gen->d, &gen->shrink, &step[0]);
    if (rc == FT_OK)
        cur = step[0];
    if (rc == FT_OK && cur->n > 0 && randomize && (rc = randomized(gen, cur, p, level, &step[1])) == FT_OK)
        cur = step[1];
    if (rc == FT_OK && cur->n > 0 && displace &&
        (rc = displaced(gen, cur, p, level, gen->method == FT_MOUNTAIN_MIDPOINT, &step[2])) == FT_OK)
        cur = step[2];
    if (rc == FT_OK && cur->n > 0 && gen->method == FT_MOUNTAIN_SIMPLE && (rc = thinned(gen, cur, &step[2])) == FT_OK)
        cur = step[2];
    if (rc == FT_OK) {
        if (cur->n == 0) { /* vanished */
            *out = ft_polygon_set_create();
            rc = *out ? FT_OK : FT_E_NOMEM;
        } else {
            rc = nested(gen, cur, p, up, out);
        }
    }
    for (int k = 0; k < 3; k++)
        ft_polygon_set_free(step[k]);
    return rc;
}

/* ---- checks ------------------------------------------------------------------------------------ */

static int check_opts(const ft_mountain_opts *o)
{
    if ((int)o->method < 0 || (int)o->method > FT_MOUNTAIN_IMPROVED)
        return ft_error(FT_E_INVALID, "mountain method must be 0..3, got %d", (int)o->method);
    if (!(o->interval > 0.0) || !isfinite(o->interval))
        return ft_error(FT_E_INVALID, "interval must be finite and > 0, got %g", o->interval);
    if (!(o->spacing >= 0.0) || !isfinite(o->spacing))
        return ft_error(FT_E_INVALID, "spacing must be finite and > 0 (0 = automatic), got %g", o->spacing);
    if (!isfinite(o->seed_elevation))
        return ft_error(FT_E_INVALID, "seed_elevation must be finite, got %g", o->seed_elevation);
    if (o->levels_up < -1 || o->levels_up > MAX_LEVELS)
        return ft_error(FT_E_INVALID, "levels_up must be in [0,%d] or -1 (until the contour vanishes), got %d",
                        MAX_LEVELS, o->levels_up);
    if (o->levels_down < 0 || o->levels_down > MAX_LEVELS)
        return ft_error(FT_E_INVALID, "levels_down must be in [0,%d], got %d", MAX_LEVELS, o->levels_down);
    if ((int)o->shrink.join < FT_JOIN_DPRIME || (int)o->shrink.join > FT_JOIN_ROUND)
        return ft_error(FT_E_INVALID, "shrink join must be 0..3, got %d", (int)o->shrink.join);
    if (!(o->shrink.dprime == 0.0 || (o->shrink.dprime >= 1.0 && isfinite(o->shrink.dprime))))
        return ft_error(FT_E_INVALID, "dprime must be >= 1 (a multiple of d) or 0 (the method's default), got %g",
                        o->shrink.dprime);
    if (o->shrink.quad_segs < 1)
        return ft_error(FT_E_INVALID, "quad_segs must be >= 1, got %d", o->shrink.quad_segs);
    if (!(o->shrink.min_area >= 0.0) || !isfinite(o->shrink.min_area))
        return ft_error(FT_E_INVALID, "min_area must be finite and >= 0, got %g", o->shrink.min_area);
    if (!(o->dsecond >= 0.0) || !isfinite(o->dsecond))
        return ft_error(FT_E_INVALID, "dsecond must be finite and >= 0, got %g", o->dsecond);
    if (!(o->theta_min >= 0.0 && o->theta_min < 90.0))
        return ft_error(FT_E_INVALID, "theta_min must be in [0,90) degrees, got %g", o->theta_min);
    if (!(o->theta_max >= o->theta_min && o->theta_max < 90.0))
        return ft_error(FT_E_INVALID, "theta_max must be in [theta_min,90) = [%g,90) degrees, got %g", o->theta_min,
                        o->theta_max);
    if (o->fourier.n < 8 || o->fourier.n > (1 << 24))
        return ft_error(FT_E_INVALID, "fourier n must be in [8,%d], got %d", 1 << 24, o->fourier.n);
    if (o->fourier.f0 < 1 || o->fourier.f0 > o->fourier.n / 2)
        return ft_error(FT_E_INVALID, "fourier f0 must be in [1,n/2] = [1,%d], got %d", o->fourier.n / 2,
                        o->fourier.f0);
    if (!(o->collinear_deg >= 0.0 && o->collinear_deg < 180.0))
        return ft_error(FT_E_INVALID, "collinear_deg must be in [0,180) degrees (0 = default), got %g",
                        o->collinear_deg);
    if (o->allow_crossings != 0 && o->allow_crossings != 1)
        return ft_error(FT_E_INVALID, "allow_crossings must be 0 (guarded) or 1 (the raw algorithm), got %d",
                        o->allow_crossings);
    if (o->match_dim != 0 && o->match_dim != 1)
        return ft_error(FT_E_INVALID, "match_dim must be 0 (theta as given) or 1 (theta from the seed's dimension), "
                        "got %d", o->match_dim);
    return FT_OK;
}

static int check_seed(const ft_polygon_set *seed)
{
    if (seed == NULL)
        return ft_error(FT_E_INVALID, "ft_mountain_generate: NULL seed contours");
    if (seed->n == 0)
        return ft_error(FT_E_EMPTY, "ft_mountain_generate: no seed contour");
    char what[64];
    for (size_t i = 0; i < seed->n; i++) {
        snprintf(what, sizeof what, "seed polygon %zu outer ring", i);
        int rc = ft_contour_check_ring(seed->polys[i].outer, what);
        for (size_t k = 0; rc == FT_OK && k < seed->polys[i].nholes; k++) {
            snprintf(what, sizeof what, "seed polygon %zu hole %zu", i, k);
            rc = ft_contour_check_ring(seed->polys[i].holes[k], what);
        }
        if (rc != FT_OK)
            return rc;
    }
    const char *why = NULL;
    int valid = ft_polygon_set_is_valid(seed, &why);
    if (valid == 2)
        return ft_last_error_code();
    if (valid == 0)
        return ft_error(FT_E_INVALID, "the seed contours are not a valid polygon set (%s); ft_contour_clean repairs it",
                        why ? why : "invalid");
    return FT_OK;
}

/* Mean segment length d0 over every ring of the seed. */
static double mean_segment(const ft_polygon_set *s)
{
    double len = 0.0;
    size_t nseg = 0;
    for (size_t k = 0, nr = ft_polygon_set_ring_count(s); k < nr; k++) {
        const ft_chain *c = ft_polygon_set_ring(s, k);
        len += ft_chain_length(c);
        nseg += ft_chain_segments(c);
    }
    return nseg ? len / (double)nseg : 0.0;
}

/* ---- the level loop ---------------------------------------------------------------------------- */

typedef struct {
    ft_contour_level *v;
    size_t n, cap;
} level_list;

static int push_level(level_list *l, double elev, ft_polygon_set *s)
{
    if (l->n == l->cap) {
        size_t cap = l->cap < 16 ? 16 : 2 * l->cap;
        ft_contour_level *v = ft_realloc_array(l->v, cap, sizeof *v);
        if (v == NULL)
            return FT_E_NOMEM;
        l->v = v;
        l->cap = cap;
    }
    l->v[l->n++] = (ft_contour_level){elev, s};
    return FT_OK;
}

static void level_list_free(level_list *l)
{
    for (size_t i = 0; i < l->n; i++)
        ft_polygon_set_free(l->v[i].polys);
    free(l->v);
}

static int report(const ft_mountain_opts *o, double frac, int level)
{
    char msg[64];
    snprintf(msg, sizeof msg, "mountain: level %+d", level);
    return ft_progress(o->progress, o->progress_arg, frac > 1.0 ? 1.0 : frac, msg);
}

int ft_mountain_generate(const ft_polygon_set *seed, const ft_mountain_opts *opts, ft_contour_stack **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_mountain_generate: NULL output pointer");
    *out = NULL;
    ft_mountain_opts o = FT_MOUNTAIN_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_mountain_opts) != FT_OK)
        return FT_E_INVALID;
    int rc = check_opts(&o);
    if (rc == FT_OK)
        rc = check_seed(seed);
    if (rc != FT_OK)
        return rc;

    generator gen;
    memset(&gen, 0, sizeof gen);
    gen.method = o.method;
    double area = ft_polygon_set_area(seed);
    gen.d = o.spacing > 0.0 ? o.spacing : sqrt(area) / DEFAULT_SPACING_DIV;
    if (!(gen.d > 0.0) || !isfinite(gen.d))
        return ft_error(FT_E_NUMERIC, "spacing: the seed's area %g gives no usable default", area);
    gen.eps = NEST_EPS * gen.d;
    gen.simplify = SIMPLIFY_TOL * gen.d;
    gen.shrink = o.shrink;
    if (gen.shrink.dprime == 0.0)
        gen.shrink.dprime = ft_mountain_default_dprime(o.method);
    gen.min_area = o.shrink.min_area * gen.d * gen.d;
    gen.mid = (ft_midpoint_opts)FT_MIDPOINT_OPTS_DEFAULT;
    gen.mid.max_seg = 2.0 * mean_segment(seed); /* §4.1: segments longer than 2 d0 */
    gen.mid.max_offset = o.dsecond * gen.d;
    gen.mid.theta_min = o.theta_min;
    gen.mid.theta_max = o.theta_max;
    gen.fourier = o.fourier;
    gen.collinear = o.collinear_deg;
    gen.seed = o.seed;
    gen.guard = !o.allow_crossings;
    if (o.match_dim && o.method == FT_MOUNTAIN_IMPROVED) {
        ft_line_dim_opts lo = FT_LINE_DIM_OPTS_DEFAULT;
        lo.min_scale = 0.5 * gen.mid.max_seg; /* d0 */
        lo.max_scale = MATCH_RULERS * lo.min_scale;
        lo.fit_whole_range = 1;
        gen.dim_opts = lo;
        size_t nr = ft_polygon_set_ring_count(seed);
        const ft_chain **rs = ft_calloc(nr, sizeof *rs);
        if (rs == NULL)
            return FT_E_NOMEM;
        for (size_t k = 0; k < nr; k++)
            rs[k] = ft_polygon_set_ring(seed, k);
        gen.dim_target = rings_dim(&gen, rs, nr);
        free(rs);
        gen.match = !isnan(gen.dim_target); /* a seed too short for the rulers: theta as given */
    }

    if ((rc = ft_geos_open(&gen.g)) != FT_OK)
        return rc;
    level_list below = {0}, above = {0};
    ft_polygon_set *cur = NULL;
    int up_max = o.levels_up < 0 ? MAX_LEVELS : o.levels_up;
    double known = (double)o.levels_down + (o.levels_up >= 0 ? (double)o.levels_up : 0.0);
    double w_down = o.levels_up >= 0 ? (known > 0 ? o.levels_down / known : 0.0)
                                     : (o.levels_down > 0 ? 0.5 : 0.0);

    rc = report(&o, 0.0, 0);
    /* below the seed: grown outward, merged where they meet */
    const ft_polygon_set *prev = seed;
    for (int k = 1; rc == FT_OK && k <= o.levels_down; k++) {
        rc = next_level(&gen, prev, -k, 0, &cur);
        if (rc == FT_OK)
            rc = push_level(&below, o.seed_elevation - k * o.interval, cur);
        if (rc != FT_OK) {
            ft_polygon_set_free(cur);
            break;
        }
        prev = cur;
        rc = report(&o, w_down * k / o.levels_down, -k);
    }
    /* the seed and above it, until up_max levels or until nothing is left */
    ft_polygon_set *seed_copy = rc == FT_OK ? ft_polygon_set_copy(seed) : NULL;
    if (rc == FT_OK && seed_copy == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK && (rc = push_level(&above, o.seed_elevation, seed_copy)) != FT_OK)
        ft_polygon_set_free(seed_copy);
    prev = seed;
    for (int k = 1; rc == FT_OK && k <= up_max; k++) {
        rc = next_level(&gen, prev, k, 1, &cur);
        if (rc != FT_OK)
            break;
        if (cur->n == 0) {
            ft_polygon_set_free(cur);
            break;
        }
        if ((rc = push_level(&above, o.seed_elevation + k * o.interval, cur)) != FT_OK) {
            ft_polygon_set_free(cur);
            break;
        }
        prev = cur;
        double frac_up = o.levels_up >= 0 ? (double)k / up_max : 1.0 - sqrt(ft_polygon_set_area(cur) / area);
        rc = report(&o, w_down + (1.0 - w_down) * frac_up, k);
    }
    ft_geos_close(&gen.g);

    ft_contour_stack *s = NULL;
    if (rc == FT_OK && (s = ft_calloc(1, sizeof *s)) != NULL &&
        (s->levels = ft_calloc(below.n + above.n, sizeof *s->levels)) == NULL) {
        free(s);
        s = NULL;
    }
    if (rc == FT_OK && s == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = report(&o, 1.0, (int)above.n - 1);
    if (rc != FT_OK) {
        if (s != NULL) {
            free(s->levels);
            free(s);
        }
        level_list_free(&below);
        level_list_free(&above);
        return rc;
    }
    for (size_t i = 0; i < below.n; i++) /* lowest first */
        s->levels[i] = below.v[below.n - 1 - i];
    for (size_t i = 0; i < above.n; i++)
        s->levels[below.n + i] = above.v[i];
    s->n = below.n + above.n;
    s->spacing = gen.d;
    s->dprime = gen.shrink.dprime;
    s->interval = o.interval;
    s->guard_moves = gen.stats.moves;
    s->guard_reduced = gen.stats.reduced;
    s->guard_dropped = gen.stats.dropped;
    free(below.v);
    free(above.v);
    *out = s;
    return FT_OK;
}
