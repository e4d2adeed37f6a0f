/* fracterra — src/contour/shrink.c: polygon shrinking (and growing) by a distance d with the corner joins of
 * Misawa, Chiba & Saito (§2, Fig. 5-7).
 *
 * Every edge of every ring is moved by d to the polygon's side (the left of a counter-clockwise outer ring
 * and of a clockwise hole, so holes grow when the polygon shrinks; d < 0 moves it the other way). At a
 * vertex where the moved edges leave a gap (a reflex vertex when shrinking, a convex one when growing) a
 * join closes it:
 *   - mitre, "extension lines" (Fig. 5a): the moved lines extended to their intersection;
 *   - bevel, "a straight connection" (Fig. 5b);
 *   - round, "an arc of radius d" (Fig. 5c): the exact set of points at distance d from the boundary;
 *   - d' (Fig. 7): ONE point on the angle bisector at distance min(d', d / cos(a/2)) from the vertex, a
 *     the angle between the edges' normals, d / cos(a/2) being where the extended lines meet; it is joined to
 *     the moved edges' ends.
 * Where the moved edges overlap (the other kind of vertex) the curve is closed by the chord from the end
 * of one moved edge to the start of the next: the chord of the arc the moving normal sweeps there. The raw
 * curve with such arcs at every vertex winds positively exactly around the offset region (Chen & McMains,
 * "Polygon offsetting by computing winding numbers", ASME IDETC 2005); the chord changes the winding
 * number only between itself and the arc, inside the disc of radius d about the vertex, lowering it where
 * shrinking excludes every point and raising it where growing includes every point. So the winding rule
 * cuts the moved edges at their intersection, and a part narrower than 2d turns inside out and goes. The
 * curves of all rings are then noded together and the region they wind around positively kept (§2 steps
 * 3-4, ft_contour_positive_region in clean.c); growing polygons that meet merge because their overlap
 * winds twice, holes grow because their curves wind negatively.
 *
 * Speed: a rough ring shrunk by several of its edge lengths makes a raw curve whose moved edges cross their
 * neighbours thousands of times. When shrinking, an overlap corner whose moved edges meet within both (at
 * m, k = d tan(phi/2) from their ends b and a, phi the turn) is cut short at m, as GEOS's offset curve
 * does. This adds +1 to the winding number inside the triangle (m, b, a) only, which lies within d of
 * the corner's edges; the region computed with the cuts is kept if it enters no such triangle (it then
 * equals the region without them), otherwise it is computed again with every corner closed by its chord.
 * Before offsetting, the vertices within 1e-6 d of the segment joining their neighbours are dropped:
 * nodes a previous shrink left a few grid cells apart would otherwise give tiny edges pointing anywhere,
 * and joins at random angles.
 *
 * Mitre, bevel and round go through GEOS's buffer (GEOSBufferWithStyle with distance -d, the robust
 * offset, which builds the same raw curves and keeps the same side): mitre with a mitre-ratio limit of
 * FT_SHRINK_MITRE_LIMIT, round with quad_segs chords per quarter circle (vertices on the arc). GEOS
 * simplifies its input curve by 1% of d before offsetting (BufferInputLineSimplifier), so its result lies
 * within 0.01 d of the exact offset. The d' join is built here. Islands and holes smaller than
 * min_area * d^2 are dropped in both cases.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/** Vertices closer than this many d to the line through their neighbours do not count (ring_vertices). */
#define FT_SHRINK_VERTEX_TOL 1e-6

/** Overlap corners are cut short at the moved edges' intersection only when it lies at least this many d
 *  from the moved ends (smaller corners add no crossing worth saving); the check that the region stays
 *  out of the cut triangles pulls their sides in by FT_SHRINK_CUT_MARGIN of their size. */
#define FT_SHRINK_CUT_MIN 1e-4
#define FT_SHRINK_CUT_MARGIN 1e-3

/** Mitre join: the extension lines meet at most this many d from the vertex (a reflex angle within
 *  0.12 degrees of 360); beyond, GEOS cuts the corner square at that distance. */
#define FT_SHRINK_MITRE_LIMIT 1000.0

const char *ft_contour_join_name(ft_contour_join j)
{
    switch (j) {
    case FT_JOIN_DPRIME: return "dprime";
    case FT_JOIN_MITRE: return "mitre";
    case FT_JOIN_BEVEL: return "bevel";
    case FT_JOIN_ROUND: return "round";
    }
    return "unknown";
}

int ft_contour_join_parse(const char *name, ft_contour_join *j)
{
    if (name == NULL || j == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_join_parse: NULL %s", name == NULL ? "name" : "output");
    static const struct {
        const char *name;
        ft_contour_join join;
    } names[] = {{"dprime", FT_JOIN_DPRIME}, {"mitre", FT_JOIN_MITRE}, {"miter", FT_JOIN_MITRE},
                 {"bevel", FT_JOIN_BEVEL},   {"round", FT_JOIN_ROUND}};
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        if (strcasecmp(name, names[k].name) == 0) {
            *j = names[k].join;
            return FT_OK;
        }
    }
    return ft_error(FT_E_INVALID, "unknown join '%s' (expected dprime, mitre, bevel or round)", name);
}

/* ---- the d' raw offset curve ------------------------------------------------------------------ */

/* Distance from (px, py) to the segment (ax, ay)-(bx, by). */
static double segment_distance(double px, double py, double ax, double ay, double bx, double by)
{
    double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
    double t = l2 > 0.0 ? ((px - ax) * ex + (py - ay) * ey) / l2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    return hypot(px - ax - t * ex, py - ay - t * ey);
}

/* The vertices of a ring that matter at the scale of tol, in the order that makes its signed area's sign
 * equal to sign: walking from the lowest-leftmost vertex (on the convex hull), a vertex is dropped when it
 * lies within tol of the segment from the last kept vertex to the next one. This merges the nodes a
 * previous noding left a few grid cells apart, whose tiny edges would otherwise point anywhere and give
 * joins at random angles, and the vertices of straight runs. Returns the count kept (ring->n at most). */
static size_t ring_vertices(const ft_chain *ring, int sign, double tol, double *x, double *y)
{
    size_t n = ring->n, start = 0, m = 0;
    for (size_t i = 1; i < n; i++)
        if (ring->y[i] < ring->y[start] || (ring->y[i] == ring->y[start] && ring->x[i] < ring->x[start]))
            start = i;
    for (size_t k = 0; k < n; k++) {
        size_t i = (start + k) % n, j = (i + 1) % n;
        double px = ring->x[i], py = ring->y[i];
        if (k > 0 && segment_distance(px, py, x[m - 1], y[m - 1], ring->x[j], ring->y[j]) <= tol)
            continue;
        x[m] = px;
        y[m] = py;
        m++;
    }
    while (m > 2 && segment_distance(x[m - 1], y[m - 1], x[m - 2], y[m - 2], x[0], y[0]) <= tol)
        m--;
    double a = ft_chain_signed_area(ring);
    if (a * sign < 0.0) {
        for (size_t i = 0, k = m - 1; m > 0 && i < k; i++, k--) {
            double t = x[i];
            x[i] = x[k];
            x[k] = t;
            t = y[i];
            y[i] = y[k];
            y[k] = t;
        }
    }
    return m;
}

/* The triangles (m, b, a) of the overlap corners cut short at the moved edges' intersection m: 6
 * coordinates each. */
typedef struct {
    double *v;
    size_t n, cap;
} corner_cuts;

static int cuts_push(corner_cuts *t, double mx, double my, double bx, double by, double ax, double ay)
{
    if (t->n == t->cap) {
        size_t cap = t->cap < 64 ? 64 : 2 * t->cap;
        double *v = ft_realloc_array(t->v, cap, 6 * sizeof *v);
        if (v == NULL)
            return FT_E_NOMEM;
        t->v = v;
        t->cap = cap;
    }
    double *q = t->v + 6 * t->n++;
    q[0] = mx, q[1] = my, q[2] = bx, q[3] = by, q[4] = ax, q[5] = ay;
    return FT_OK;
}

static int push_point(ft_chain *c, double x, double y)
{
    if (c->n > 0 && c->x[c->n - 1] == x && c->y[c->n - 1] == y)
        return FT_OK;
    return ft_chain_push(c, x, y);
}

/* The raw d' offset curve of one ring (oriented by sign: +1 outer, -1 hole) moved by s to its left;
 * vertices closer than tol count as one. With cuts != NULL an overlap corner whose moved edges meet
 * within both is cut short at their intersection m, and its triangle recorded. */
static int raw_offset_dprime(const ft_chain *ring, int sign, double s, double dprime, double tol, corner_cuts *cuts,
                             ft_chain **out)
{
    *out = NULL;
    double *x = ft_malloc(3 * ring->n * sizeof *x); /* x, y, then edge lengths */
    double *e = ft_malloc(2 * ring->n * sizeof *e); /* unit edge directions, interleaved */
    ft_chain *raw = ft_chain_create(3 * ring->n, 1);
    if (x == NULL || e == NULL || raw == NULL) {
        free(x);
        free(e);
        ft_chain_free(raw);
        return FT_E_NOMEM;
    }
    double *y = x + ring->n, *len = x + 2 * ring->n;
    size_t m = ring_vertices(ring, sign, tol, x, y);
    if (m < 3) /* the whole ring is smaller than tol: keep all its distinct vertices */
        m = ring_vertices(ring, sign, 0.0, x, y);
    for (size_t i = 0; i < m; i++) {
        size_t j = i + 1 == m ? 0 : i + 1;
        double dx = x[j] - x[i], dy = y[j] - y[i];
        len[i] = hypot(dx, dy);
        e[2 * i] = dx / len[i];
        e[2 * i + 1] = dy / len[i];
    }
    double as = fabs(s), sg = s > 0.0 ? 1.0 : -1.0, dp = dprime * as;
    int rc = FT_OK;
    for (size_t i = 0; rc == FT_OK && i < m; i++) {
        size_t p = i == 0 ? m - 1 : i - 1;
        double epx = e[2 * p], epy = e[2 * p + 1], eix = e[2 * i], eiy = e[2 * i + 1];
        /* left normals n = (-ey, ex); moved ends b (previous edge) and a (next edge) */
        double npx = -epy, npy = epx, nix = -eiy, niy = eix;
        double bx = x[i] + s * npx, by = y[i] + s * npy, ax = x[i] + s * nix, ay = y[i] + s * niy;
        double cross = epx * eiy - epy * eix, dot = epx * eix + epy * eiy;
        if (fabs(cross) <= 1e-12 && dot > 0.0) { /* straight on: the moved edges meet end to end */
            rc = push_point(raw, bx, by);
        } else if (fabs(cross) > 1e-12 && cross * s > 0.0) { /* overlap */
            /* the moved edges meet at m, k = d tan(phi/2) back from b along the previous edge and forward
             * from a along the next one (phi the turn) */
            double k = as * fabs(cross) / (1.0 + dot);
            if (cuts != NULL && k >= FT_SHRINK_CUT_MIN * as && k <= len[p] && k <= len[i]) {
                double mx = bx - k * epx, my = by - k * epy;
                rc = push_point(raw, mx, my);
                if (rc == FT_OK)
                    rc = cuts_push(cuts, mx, my, bx, by, ax, ay);
            } else { /* the chord of the reversed arc */
                rc = push_point(raw, bx, by);
                if (rc == FT_OK)
                    rc = push_point(raw, ax, ay);
            }
        } else { /* gap: the d' join (Fig. 7) */
            double ux = npx + nix, uy = npy + niy, ul = hypot(ux, uy);
            double t, px, py;
            if (ul > 1e-9) {
                /* the extended lines meet at d / cos(a/2) = 2 d / |n_p + n_i| along the bisector */
                t = fmin(dp, 2.0 * as / ul);
                px = x[i] + sg * t * ux / ul;
                py = y[i] + sg * t * uy / ul;
            } else { /* the ring turns back on itself: the bisector runs straight on past the tip */
                px = x[i] + dp * epx;
                py = y[i] + dp * epy;
            }
            rc = push_point(raw, bx, by);
            if (rc == FT_OK)
                rc = push_point(raw, px, py);
            if (rc == FT_OK)
                rc = push_point(raw, ax, ay);
        }
    }
    while (rc == FT_OK && raw->n > 1 && raw->x[raw->n - 1] == raw->x[0] && raw->y[raw->n - 1] == raw->y[0])
        raw->n--;
    free(x);
    free(e);
    if (rc != FT_OK) {
        ft_chain_free(raw);
        return rc;
    }
    *out = raw;
    return FT_OK;
}

/* 1 if the region `set` overlaps the interior of a cut corner's triangle (its sides pulled in by a
 * relative FT_SHRINK_CUT_MARGIN), 0 if not, negative on error. */
static int cuts_overlap(ft_geos *g, const ft_polygon_set *set, const corner_cuts *cuts)
{
    if (set->n == 0 || cuts->n == 0)
        return 0;
    GEOSGeometry **tri = ft_calloc(cuts->n, sizeof *tri);
    GEOSGeometry *region = ft_geos_from_set(g, set), *coll = NULL;
    const GEOSPreparedGeometry *prep = region ? GEOSPrepare_r(g->h, region) : NULL;
    int result = -1;
    size_t nt = 0;
    if (tri == NULL || prep == NULL)
        goto done;
    for (; nt < cuts->n; nt++) {
        const double *q = cuts->v + 6 * nt;
        double cx = (q[0] + q[2] + q[4]) / 3.0, cy = (q[1] + q[3] + q[5]) / 3.0, f = 1.0 - FT_SHRINK_CUT_MARGIN;
        double px[4], py[4];
        for (int k = 0; k < 3; k++)
            px[k] = cx + f * (q[2 * k] - cx), py[k] = cy + f * (q[2 * k + 1] - cy);
        ft_chain c = {px, py, 3, 4, 1};
        GEOSGeometry *ring = ft_geos_ring(g, &c);
        if (ring == NULL || (tri[nt] = GEOSGeom_createPolygon_r(g->h, ring, NULL, 0)) == NULL) {
            if (ring != NULL)
                GEOSGeom_destroy_r(g->h, ring);
            goto done;
        }
    }
    coll = GEOSGeom_createCollection_r(g->h, GEOS_GEOMETRYCOLLECTION, tri, (unsigned)nt);
    if (coll == NULL)
        goto done;
    nt = 0; /* taken */
    char r = GEOSPreparedIntersects_r(g->h, prep, coll);
    result = r == 1 ? 1 : r == 0 ? 0 : -1;
done:
    for (size_t k = 0; k < nt; k++)
        GEOSGeom_destroy_r(g->h, tri[k]);
    free(tri);
    if (coll)
        GEOSGeom_destroy_r(g->h, coll);
    if (prep)
        GEOSPreparedGeom_destroy_r(g->h, prep);
    if (region)
        GEOSGeom_destroy_r(g->h, region);
    return result;
}

/* The d' shrink (or growth) of `in` into res (empty on entry). Shrinking first cuts the overlap corners
 * short (fewer crossings to node): that can only add to the region, and only inside the cut corners'
 * triangles, which lie within d of the edges; if the region enters one, it is computed again with every
 * corner closed by its chord. */
static int shrink_dprime(ft_geos *g, const ft_polygon_set *in, double d, const ft_shrink_opts *o,
                         ft_polygon_set *res)
{
    size_t nrings = 0;
    for (size_t i = 0; i < in->n; i++)
        nrings += 1 + in->polys[i].nholes;
    ft_chain **raw = ft_calloc(nrings, sizeof *raw);
    if (raw == NULL)
        return FT_E_NOMEM;
    size_t n = 0;
    for (size_t i = 0; i < in->n; i++) { /* the input rings first, for the noding grid */
        raw[n++] = in->polys[i].outer;
        for (size_t k = 0; k < in->polys[i].nholes; k++)
            raw[n++] = in->polys[i].holes[k];
    }
    double tol = fmax(ft_contour_grid(raw, n, d), FT_SHRINK_VERTEX_TOL * fabs(d));
    corner_cuts cuts = {0};
    int rc = FT_OK;
    for (int shortcut = d > 0.0; ; shortcut = 0) {
        n = 0;
        cuts.n = 0;
        for (size_t i = 0; rc == FT_OK && i < in->n; i++) {
            const ft_polygon *p = &in->polys[i];
            rc = raw_offset_dprime(p->outer, 1, d, o->dprime, tol, shortcut ? &cuts : NULL, &raw[n]);
            n += rc == FT_OK;
            for (size_t k = 0; rc == FT_OK && k < p->nholes; k++) {
                rc = raw_offset_dprime(p->holes[k], -1, d, o->dprime, tol, shortcut ? &cuts : NULL, &raw[n]);
                n += rc == FT_OK;
            }
        }
        ft_polygon_set *attempt = rc == FT_OK ? ft_polygon_set_create() : NULL;
        if (rc == FT_OK && attempt == NULL)
            rc = FT_E_NOMEM;
        if (rc == FT_OK)
            rc = ft_contour_positive_region(g, raw, n, d, o->min_area * d * d, attempt);
        for (size_t k = 0; k < n; k++)
            ft_chain_free(raw[k]);
        if (rc == FT_OK && shortcut && cuts_overlap(g, attempt, &cuts) != 0) {
            ft_polygon_set_free(attempt);
            ft_clear_error();
            continue;
        }
        if (rc == FT_OK) { /* res is empty: hand it the attempt's polygons */
            ft_polygon_set tmp = *res;
            *res = *attempt;
            *attempt = tmp;
        }
        ft_polygon_set_free(attempt);
        break;
    }
    free(cuts.v);
    free(raw);
    return rc;
}

/* ---- mitre, bevel, round: GEOS's buffer ---------------------------------------------------------- */

/* The input as a valid GEOS geometry: as is when GEOS finds it valid, otherwise the region its rings
 * wind around positively (self-intersecting rings, overlapping islands). */
static GEOSGeometry *valid_input(ft_geos *g, const ft_polygon_set *in)
{
    GEOSGeometry *geom = ft_geos_from_set(g, in);
    if (geom == NULL || GEOSisValid_r(g->h, geom) == 1)
        return geom;
    GEOSGeom_destroy_r(g->h, geom);
    ft_polygon_set *clean = NULL;
    if (ft_contour_clean(in, 0.0, &clean) != FT_OK)
        return NULL;
    geom = ft_geos_from_set(g, clean);
    ft_polygon_set_free(clean);
    return geom;
}

static int shrink_buffer(ft_geos *g, const ft_polygon_set *in, double d, const ft_shrink_opts *o,
                         ft_polygon_set *res)
{
    int style = o->join == FT_JOIN_ROUND ? GEOSBUF_JOIN_ROUND
                : o->join == FT_JOIN_MITRE ? GEOSBUF_JOIN_MITRE
                                           : GEOSBUF_JOIN_BEVEL;
    GEOSGeometry *geom = valid_input(g, in);
    if (geom == NULL)
        return ft_last_error_code();
    GEOSGeometry *buf = GEOSBufferWithStyle_r(g->h, geom, -d, o->quad_segs, GEOSBUF_CAP_ROUND, style,
                                              FT_SHRINK_MITRE_LIMIT);
    GEOSGeom_destroy_r(g->h, geom);
    if (buf == NULL)
        return ft_geos_fail(g, "offsetting the polygons");
    if (GEOSisValid_r(g->h, buf) != 1) {
        GEOSGeometry *v = GEOSMakeValid_r(g->h, buf);
        GEOSGeom_destroy_r(g->h, buf);
        if (v == NULL)
            return ft_geos_fail(g, "repairing the offset polygons");
        buf = v;
    }
    int rc = ft_geos_append_to_set(g, buf, o->min_area * d * d, res);
    GEOSGeom_destroy_r(g->h, buf);
    return rc;
}

/* ---- entry ----------------------------------------------------------------------------------- */

static int check_opts(const ft_shrink_opts *o)
{
    if (o->join != FT_JOIN_DPRIME && o->join != FT_JOIN_MITRE && o->join != FT_JOIN_BEVEL &&
        o->join != FT_JOIN_ROUND)
        return ft_error(FT_E_INVALID, "unknown join %d (expected FT_JOIN_DPRIME, _MITRE, _BEVEL or _ROUND)",
                        (int)o->join);
    if (o->join == FT_JOIN_DPRIME && !(isfinite(o->dprime) && o->dprime >= 1.0))
        return ft_error(FT_E_INVALID, "dprime (d' as a multiple of d) must be finite and >= 1, got %g", o->dprime);
    if (o->join == FT_JOIN_ROUND && o->quad_segs < 1)
        return ft_error(FT_E_INVALID, "quad_segs must be >= 1, got %d", o->quad_segs);
    if (!(isfinite(o->min_area) && o->min_area >= 0.0))
        return ft_error(FT_E_INVALID, "min_area must be finite and >= 0, got %g", o->min_area);
    return FT_OK;
}

static int check_input(const ft_polygon_set *in)
{
    if (in->n > 0 && in->polys == NULL)
        return ft_error(FT_E_INVALID, "polygon set holds %zu polygons but no array", in->n);
    char what[64];
    for (size_t i = 0; i < in->n; i++) {
        const ft_polygon *p = &in->polys[i];
        snprintf(what, sizeof what, "polygon %zu outer ring", i);
        int rc = ft_contour_check_ring(p->outer, what);
        if (rc == FT_OK && p->nholes > 0 && p->holes == NULL)
            rc = ft_error(FT_E_INVALID, "polygon %zu announces %zu holes but has no hole array", i, p->nholes);
        for (size_t k = 0; rc == FT_OK && k < p->nholes; k++) {
            snprintf(what, sizeof what, "polygon %zu hole %zu", i, k);
            rc = ft_contour_check_ring(p->holes[k], what);
        }
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

int ft_contour_shrink(const ft_polygon_set *in, double d, const ft_shrink_opts *opts, ft_polygon_set **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_shrink: NULL output");
    *out = NULL;
    if (in == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_shrink: NULL polygon set");
    ft_shrink_opts o = FT_SHRINK_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_shrink_opts) != FT_OK)
        return FT_E_INVALID;
    if (!isfinite(d) || d == 0.0)
        return ft_error(FT_E_INVALID, "shrink distance d must be finite and non-zero, got %g", d);
    int rc = check_opts(&o);
    if (rc == FT_OK)
        rc = check_input(in);
    if (rc != FT_OK)
        return rc;
    ft_polygon_set *res = ft_polygon_set_create();
    if (res == NULL)
        return FT_E_NOMEM;
    if (in->n > 0) {
        ft_geos g;
        rc = ft_geos_open(&g);
        if (rc == FT_OK) {
            rc = o.join == FT_JOIN_DPRIME ? shrink_dprime(&g, in, d, &o, res) : shrink_buffer(&g, in, d, &o, res);
            ft_geos_close(&g);
        }
    }
    if (rc != FT_OK) {
        ft_polygon_set_free(res);
        return rc;
    }
    *out = res;
    return FT_OK;
}
