/* fracterra — src/contour/clean.c: the faces a set of closed curves winds around positively, and with them
 * the removal of twists and loops (Misawa, Chiba & Saito, §2 steps 3-4 and §4.4 method 1).
 *
 * The region is {p : w(p) > 0}, w the winding number of all the curves together: "the counter-clockwise
 * faces" of §2 step 4. For a counter-clockwise outer ring and its clockwise holes this is the polygon's
 * side; a clockwise loop of an outer ring (a twist) winds -1 and goes; overlapping islands wind twice and
 * merge. Two ways compute it, with the same result:
 *  - depth (the usual one): GEOS's buffer engine at distance 0 nodes the curves robustly (snap-rounding when
 *    floating noding fails) and gives every face its depth, +1 inside each polygon shell and -1 inside each
 *    hole, a ring's sides taken from its orientation; handing it every counter-clockwise curve as a shell
 *    and every clockwise one as a hole makes the depth the winding number, and it returns depth >= 1 (when
 *    every curve is clockwise, a frame given as shell and hole, of net depth 0, holds them);
 *  - faces (when a curve's orientation is too close to zero area to tell, or the buffer engine fails): the
 *    curves are noded by a unary union snap-rounded to a fine grid (ft_contour_grid: 1e-9 of the caller's
 *    scale, or 1e-12 of the extent; floating noding can leave near-coincident nodes the polygonizer cannot
 *    close rings through), polygonized, and each face kept if the winding number at an interior point
 *    (GEOSPointOnSurface) is positive, counted over the raw curves with Sunday's crossing rule ("Inclusion
 *    of a point in a polygon", 2001) in horizontal bands; the kept faces are a coverage (one noded
 *    arrangement), merged by a coverage union. Its cost grows with the number of faces.
 * Then polygons enclosing less than min_area and holes smaller than min_area are dropped (§4.4 method 1
 * drops faces with few segments; an area is the scale-free equivalent).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- winding numbers ------------------------------------------------------------------------- */

typedef struct {
    double x0, y0, x1, y1;
} segment;

typedef struct {
    segment *seg;
    size_t nseg;
    double ymin, ymax, band_h;
    size_t nbands;
    size_t *start; /* nbands + 1 offsets into idx */
    size_t *idx;   /* segment indices per band */
} winding_index;

static void winding_index_free(winding_index *w)
{
    free(w->seg);
    free(w->start);
    free(w->idx);
    *w = (winding_index){0};
}

static size_t band_of(const winding_index *w, double y)
{
    if (!(y > w->ymin))
        return 0;
    double b = (y - w->ymin) / w->band_h;
    if (!(b < (double)w->nbands))
        return w->nbands - 1;
    return (size_t)b;
}

/* Total band registrations with nbands bands. */
static size_t count_entries(winding_index *w)
{
    size_t total = 0;
    for (size_t i = 0; i < w->nseg; i++) {
        const segment *s = &w->seg[i];
        total += band_of(w, fmax(s->y0, s->y1)) - band_of(w, fmin(s->y0, s->y1)) + 1;
    }
    return total;
}

static int winding_index_build(winding_index *w, ft_chain *const *rings, size_t nrings)
{
    *w = (winding_index){0};
    size_t n = 0;
    for (size_t r = 0; r < nrings; r++)
        n += rings[r] && rings[r]->n >= 2 ? rings[r]->n : 0;
    if (n == 0)
        return FT_OK;
    if ((w->seg = ft_calloc(n, sizeof *w->seg)) == NULL)
        return FT_E_NOMEM;
    w->ymin = INFINITY;
    w->ymax = -INFINITY;
    for (size_t r = 0; r < nrings; r++) {
        const ft_chain *c = rings[r];
        if (c == NULL || c->n < 2)
            continue;
        for (size_t i = 0; i < c->n; i++) {
            size_t j = i + 1 == c->n ? 0 : i + 1;
            w->seg[w->nseg++] = (segment){c->x[i], c->y[i], c->x[j], c->y[j]};
            w->ymin = fmin(w->ymin, c->y[i]);
            w->ymax = fmax(w->ymax, c->y[i]);
        }
    }
    /* about 4 segments per band, fewer bands while long segments would register too often */
    w->nbands = w->nseg / 4 + 1;
    for (;;) {
        w->band_h = (w->ymax - w->ymin) / (double)w->nbands;
        if (!(w->band_h > 0.0)) {
            w->nbands = 1;
            w->band_h = 1.0;
            break;
        }
        if (w->nbands == 1 || count_entries(w) <= 16 * w->nseg)
            break;
        w->nbands /= 2;
    }
    size_t total = count_entries(w);
    w->start = ft_calloc(w->nbands + 1, sizeof *w->start);
    w->idx = ft_calloc(total, sizeof *w->idx);
    if (w->start == NULL || w->idx == NULL) {
        winding_index_free(w);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < w->nseg; i++) {
        const segment *s = &w->seg[i];
        for (size_t b = band_of(w, fmin(s->y0, s->y1)), e = band_of(w, fmax(s->y0, s->y1)); b <= e; b++)
            w->start[b + 1]++;
    }
    for (size_t b = 0; b < w->nbands; b++)
        w->start[b + 1] += w->start[b];
    size_t *fill = ft_calloc(w->nbands, sizeof *fill);
    if (fill == NULL) {
        winding_index_free(w);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < w->nseg; i++) {
        const segment *s = &w->seg[i];
        for (size_t b = band_of(w, fmin(s->y0, s->y1)), e = band_of(w, fmax(s->y0, s->y1)); b <= e; b++)
            w->idx[w->start[b] + fill[b]++] = i;
    }
    free(fill);
    return FT_OK;
}

/* Winding number of the indexed curves around (x, y): Sunday's rule, an upward crossing left of the point
 * counts +1, a downward crossing right of it -1 (half-open in y, so a vertex is counted once). */
static long winding_number(const winding_index *w, double x, double y)
{
    if (w->nseg == 0 || y < w->ymin || y > w->ymax)
        return 0;
    size_t b = band_of(w, y);
    long wn = 0;
    for (size_t k = w->start[b]; k < w->start[b + 1]; k++) {
        const segment *s = &w->seg[w->idx[k]];
        double left = (s->x1 - s->x0) * (y - s->y0) - (x - s->x0) * (s->y1 - s->y0);
        if (s->y0 <= y) {
            if (s->y1 > y && left > 0.0)
                wn++;
        } else if (s->y1 <= y && left < 0.0) {
            wn--;
        }
    }
    return wn;
}

/* ---- noding, polygonizing, face selection ------------------------------------------------------ */

double ft_contour_grid(ft_chain *const *rings, size_t nrings, double scale)
{
    double maxabs = 0.0, x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t r = 0; r < nrings; r++) {
        for (size_t i = 0; rings[r] != NULL && i < rings[r]->n; i++) {
            double x = rings[r]->x[i], y = rings[r]->y[i];
            maxabs = fmax(maxabs, fmax(fabs(x), fabs(y)));
            x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
        }
    }
    double grid = FT_CONTOUR_GRID_SCALE * fabs(scale);
    if (!(grid > 0.0) && x1 >= x0)
        grid = FT_CONTOUR_GRID_EXTENT * hypot(x1 - x0, y1 - y0);
    grid = fmax(grid, FT_CONTOUR_GRID_COORD * maxabs);
    return grid > 0.0 ? grid : FT_CONTOUR_GRID_SCALE;
}

/* The rings as one MultiLineString of closed lines. */
static GEOSGeometry *rings_linework(ft_geos *g, ft_chain *const *rings, size_t nrings)
{
    GEOSGeometry **lines = ft_calloc(nrings > 0 ? nrings : 1, sizeof *lines);
    if (lines == NULL)
        return NULL;
    size_t n = 0;
    for (size_t r = 0; r < nrings; r++) {
        if (rings[r] == NULL || rings[r]->n < 2)
            continue;
        if ((lines[n] = ft_geos_ring_line(g, rings[r])) == NULL) {
            for (size_t k = 0; k < n; k++)
                GEOSGeom_destroy_r(g->h, lines[k]);
            free(lines);
            return NULL;
        }
        n++;
    }
    GEOSGeometry *mls = GEOSGeom_createCollection_r(g->h, GEOS_MULTILINESTRING, lines, (unsigned)n);
    free(lines);
    if (mls == NULL)
        ft_geos_fail(g, "linework");
    return mls;
}

/* The kept faces' union. Takes the faces (array and geometries). */
static GEOSGeometry *merge_faces(ft_geos *g, GEOSGeometry **faces, size_t n)
{
    GEOSGeometry *coll = GEOSGeom_createCollection_r(g->h, GEOS_GEOMETRYCOLLECTION, faces, (unsigned)n);
    if (coll == NULL) {
        for (size_t k = 0; k < n; k++)
            GEOSGeom_destroy_r(g->h, faces[k]);
        ft_geos_fail(g, "collecting faces");
        return NULL;
    }
    GEOSGeometry *u = GEOSCoverageUnion_r(g->h, coll);
    if (u == NULL)
        u = GEOSUnaryUnion_r(g->h, coll);
    GEOSGeom_destroy_r(g->h, coll);
    if (u == NULL)
        ft_geos_fail(g, "merging faces");
    return u;
}

/* The faces path: snap-rounded noding, polygonizing, one winding number per face, coverage union of the
 * kept faces. Robust for any curves, but its cost grows with the number of faces. Returns the region (an
 * empty collection if nothing is kept) or NULL (error set). */
static GEOSGeometry *faces_region(ft_geos *g, ft_chain *const *rings, size_t nrings, double grid)
{
    winding_index wi;
    if (winding_index_build(&wi, rings, nrings) != FT_OK)
        return NULL;
    GEOSGeometry *lines = NULL, *noded = NULL, *faces = NULL, *result = NULL;
    GEOSGeometry **kept = NULL;
    size_t nkept = 0;
    if ((lines = rings_linework(g, rings, nrings)) == NULL)
        goto done;
    /* snap-rounded noding on a grid: no two nodes closer than a grid cell, so every face closes */
    noded = GEOSUnaryUnionPrec_r(g->h, lines, grid);
    if (noded == NULL)
        noded = GEOSUnaryUnion_r(g->h, lines);
    if (noded == NULL) {
        ft_geos_fail(g, "noding the curves");
        goto done;
    }
    const GEOSGeometry *in[1] = {noded};
    if ((faces = GEOSPolygonize_r(g->h, in, 1)) == NULL) {
        ft_geos_fail(g, "polygonizing the curves");
        goto done;
    }
    int nfaces = GEOSGetNumGeometries_r(g->h, faces);
    if (nfaces < 0) {
        ft_geos_fail(g, "reading the faces");
        goto done;
    }
    if ((kept = ft_calloc(nfaces > 0 ? (size_t)nfaces : 1, sizeof *kept)) == NULL)
        goto done;
    for (int i = 0; i < nfaces; i++) {
        const GEOSGeometry *f = GEOSGetGeometryN_r(g->h, faces, i);
        GEOSGeometry *pt = f ? GEOSPointOnSurface_r(g->h, f) : NULL;
        double x = 0.0, y = 0.0;
        int ok = pt != NULL && GEOSGeomGetX_r(g->h, pt, &x) && GEOSGeomGetY_r(g->h, pt, &y);
        if (pt != NULL)
            GEOSGeom_destroy_r(g->h, pt);
        if (!ok) {
            ft_geos_fail(g, "an interior point of a face");
            goto done;
        }
        if (winding_number(&wi, x, y) <= 0)
            continue;
        if ((kept[nkept] = GEOSGeom_clone_r(g->h, f)) == NULL) {
            ft_geos_fail(g, "copying a face");
            goto done;
        }
        nkept++;
    }
    if (nkept == 0) {
        result = GEOSGeom_createEmptyCollection_r(g->h, GEOS_MULTIPOLYGON);
        if (result == NULL)
            ft_geos_fail(g, "an empty region");
    } else {
        result = merge_faces(g, kept, nkept);
        nkept = 0; /* taken */
    }
done:
    for (size_t k = 0; k < nkept; k++)
        GEOSGeom_destroy_r(g->h, kept[k]);
    free(kept);
    if (faces)
        GEOSGeom_destroy_r(g->h, faces);
    if (noded)
        GEOSGeom_destroy_r(g->h, noded);
    if (lines)
        GEOSGeom_destroy_r(g->h, lines);
    winding_index_free(&wi);
    return result;
}

/* 1 if GEOS's buffer engine orients a ring by its signed area (GEOS >= 3.10), 0 if by its highest vertex
 * (older), -1 if the probe failed: a figure-eight whose larger lobe is counter-clockwise and whose highest
 * vertex lies on the smaller, clockwise lobe keeps the larger lobe under the area rule. Probed once. */
static int buffer_orients_by_area(ft_geos *g)
{
    static _Atomic int rule = -2;
    int r = rule;
    if (r != -2)
        return r;
    const double x[] = {0, 4, 4, 2, 1, 3, 2, 0}, y[] = {0, 0, 1, 2, 3, 3, 2, 1};
    ft_chain c = {(double *)x, (double *)y, 8, 8, 1};
    GEOSGeometry *ring = ft_geos_ring(g, &c);
    GEOSGeometry *poly = ring ? GEOSGeom_createPolygon_r(g->h, ring, NULL, 0) : NULL;
    GEOSGeometry *b = poly ? GEOSBuffer_r(g->h, poly, 0.0, 8) : NULL;
    double area = 0.0;
    r = b != NULL && GEOSArea_r(g->h, b, &area) ? (fabs(area - 6.0) < 1e-9 ? 1 : 0) : -1;
    if (b)
        GEOSGeom_destroy_r(g->h, b);
    if (poly)
        GEOSGeom_destroy_r(g->h, poly);
    else if (ring)
        GEOSGeom_destroy_r(g->h, ring);
    if (r >= 0)
        rule = r;
    return r;
}

/* A rectangle about the rings' extent with a margin, counter-clockwise (sign +1) or clockwise (sign -1). */
static GEOSGeometry *frame_ring(ft_geos *g, ft_chain *const *rings, size_t nrings, int sign)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t r = 0; r < nrings; r++) {
        for (size_t i = 0; rings[r] != NULL && i < rings[r]->n; i++) {
            x0 = fmin(x0, rings[r]->x[i]), x1 = fmax(x1, rings[r]->x[i]);
            y0 = fmin(y0, rings[r]->y[i]), y1 = fmax(y1, rings[r]->y[i]);
        }
    }
    double ext = fmax(x1 - x0, y1 - y0), m = ext > 0.0 ? 0.01 * ext : 1.0;
    x0 -= m, y0 -= m, x1 += m, y1 += m;
    double fx[4] = {x0, x1, x1, x0}, fy[4] = {y0, y0, y1, y1};
    if (sign < 0) {
        fx[1] = x0, fy[1] = y1, fx[3] = x1, fy[3] = y0;
    }
    ft_chain c = {fx, fy, 4, 4, 1};
    return ft_geos_ring(g, &c);
}

/* The depth path: GEOS's buffer engine with distance 0 nodes all rings together and labels every face with
 * its depth, the sum over the rings of +1 inside a polygon shell and -1 inside a hole, each ring's sides
 * chosen by its orientation (GEOS >= 3.10 decides it by the signed area, older versions by the highest
 * vertex), and returns the faces of depth >= 1. A ring whose signed winding is to count as is must
 * therefore be a shell if GEOS finds it counter-clockwise and a hole otherwise; then depth = winding
 * number. When the area is too small to trust its sign, or (older GEOS) the highest-vertex test disagrees
 * with it, *unsure is set and NULL returned without error. */
static GEOSGeometry *depth_region(ft_geos *g, ft_chain *const *rings, size_t nrings, int *unsure)
{
    *unsure = 0;
    int by_area = buffer_orients_by_area(g);
    GEOSGeometry **shells = ft_calloc(nrings > 0 ? nrings : 1, sizeof *shells);
    GEOSGeometry **holes = ft_calloc(nrings + 1, sizeof *holes); /* + 1 for a frame */
    size_t ns = 0, nh = 0;
    GEOSGeometry *result = NULL;
    if (shells == NULL || holes == NULL)
        goto done;
    for (size_t r = 0; r < nrings; r++) {
        const ft_chain *c = rings[r];
        if (c == NULL || c->n < 3)
            continue;
        /* the signed area's terms relative to the first vertex, and their magnitude */
        double twice = 0.0, mag = 0.0;
        for (size_t i = 1; i + 1 < c->n; i++) {
            double t = (c->x[i] - c->x[0]) * (c->y[i + 1] - c->y[0]) - (c->x[i + 1] - c->x[0]) * (c->y[i] - c->y[0]);
            twice += t;
            mag += fabs(t);
        }
        if (!(fabs(twice) > 1e-9 * mag)) {
            *unsure = 1;
            goto done;
        }
        GEOSGeometry *ring = ft_geos_ring(g, c);
        if (ring == NULL)
            goto done;
        char ccw = twice > 0.0;
        if (by_area != 1) { /* the highest-vertex rule must agree with the area */
            const GEOSCoordSequence *seq = GEOSGeom_getCoordSeq_r(g->h, ring);
            if (seq == NULL || !GEOSCoordSeq_isCCW_r(g->h, seq, &ccw) || (ccw != 0) != (twice > 0.0)) {
                GEOSGeom_destroy_r(g->h, ring);
                *unsure = 1;
                goto done;
            }
        }
        if (ccw)
            shells[ns++] = ring;
        else
            holes[nh++] = ring;
    }
    if (ns == 0 && nh == 0) { /* no ring at all */
        result = GEOSGeom_createEmptyCollection_r(g->h, GEOS_MULTIPOLYGON);
        if (result == NULL)
            ft_geos_fail(g, "an empty region");
        goto done;
    }
    if (ns == 0) {
        /* Every ring is clockwise by area, yet w may still be positive somewhere: a hugely self-overlapping
         * offset curve whose inverted loops (w <= -1) outweigh its region (w >= 1) has a negative signed
         * area. The holes need a shell to belong to: a frame about them, given both as a shell and as a
         * hole, whose coincident edges the buffer engine merges with depth deltas +1 and -1 summing to 0. */
        if ((shells[0] = frame_ring(g, rings, nrings, 1)) == NULL)
            goto done;
        ns = 1;
        if ((holes[nh] = frame_ring(g, rings, nrings, -1)) == NULL)
            goto done;
        nh++;
    }
    /* every shell its own polygon; the holes go to the first (the buffer engine labels each ring on its own) */
    GEOSGeometry **polys = ft_calloc(ns, sizeof *polys);
    if (polys == NULL)
        goto done;
    size_t np = 0;
    for (; np < ns; np++) {
        polys[np] = GEOSGeom_createPolygon_r(g->h, shells[np], np == 0 ? holes : NULL, np == 0 ? (unsigned)nh : 0);
        if (polys[np] == NULL)
            break;
        shells[np] = NULL;
        if (np == 0)
            nh = 0; /* taken */
    }
    GEOSGeometry *coll = NULL;
    if (np == ns)
        coll = GEOSGeom_createCollection_r(g->h, GEOS_GEOMETRYCOLLECTION, polys, (unsigned)np);
    if (coll == NULL) {
        for (size_t k = 0; k < np; k++)
            GEOSGeom_destroy_r(g->h, polys[k]);
        free(polys);
        ft_geos_fail(g, "collecting the curves");
        goto done;
    }
    free(polys);
    result = GEOSBuffer_r(g->h, coll, 0.0, 8);
    GEOSGeom_destroy_r(g->h, coll);
    if (result == NULL)
        ft_geos_fail(g, "depth of the curves' faces");
done:
    for (size_t k = 0; shells != NULL && k < ns; k++)
        if (shells[k] != NULL)
            GEOSGeom_destroy_r(g->h, shells[k]);
    for (size_t k = 0; holes != NULL && k < nh; k++)
        GEOSGeom_destroy_r(g->h, holes[k]);
    free(shells);
    free(holes);
    return result;
}

int ft_contour_positive_region(ft_geos *g, ft_chain *const *rings, size_t nrings, double scale, double min_area,
                               ft_polygon_set *out)
{
    int unsure = 0;
    GEOSGeometry *region = depth_region(g, rings, nrings, &unsure);
    if (region == NULL) /* an orientation GEOS might read otherwise, or the buffer engine failed: faces */
        region = faces_region(g, rings, nrings, ft_contour_grid(rings, nrings, scale));
    if (region == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : ft_geos_fail(g, "positive region");
    if (GEOSisValid_r(g->h, region) != 1) {
        GEOSGeometry *v = GEOSMakeValid_r(g->h, region);
        GEOSGeom_destroy_r(g->h, region);
        if (v == NULL)
            return ft_geos_fail(g, "repairing the region");
        region = v;
    }
    int rc = ft_geos_append_to_set(g, region, min_area, out);
    GEOSGeom_destroy_r(g->h, region);
    return rc;
}

/* ---- ft_contour_clean ---------------------------------------------------------------------------- */

/* A copy of a ring of the set, oriented by its signed area (sign +1 counter-clockwise, -1 clockwise;
 * a ring of zero area, such as a figure-eight of equal lobes, is kept as stored). */
static int oriented_copy(const ft_chain *c, int sign, const char *what, ft_chain **out)
{
    *out = NULL;
    if (c == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_clean: %s is NULL", what);
    if (ft_chain_check_finite(c) != FT_OK)
        return ft_error(FT_E_INVALID, "ft_contour_clean: %s: %s", what, ft_last_error());
    if (c->n < 3)
        return ft_error(FT_E_INVALID, "ft_contour_clean: %s has %zu vertices, at least 3 needed", what, c->n);
    ft_chain *d = ft_chain_copy(c);
    if (d == NULL)
        return FT_E_NOMEM;
    d->closed = 1;
    if (ft_chain_signed_area(d) * sign < 0.0)
        ft_chain_reverse(d);
    *out = d;
    return FT_OK;
}

static void free_rings(ft_chain **rings, size_t n)
{
    for (size_t k = 0; k < n; k++)
        ft_chain_free(rings[k]);
    free(rings);
}

int ft_contour_clean(const ft_polygon_set *in, double min_area, ft_polygon_set **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_clean: NULL output");
    *out = NULL;
    if (in == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_clean: NULL polygon set");
    if (!isfinite(min_area) || min_area < 0.0)
        return ft_error(FT_E_INVALID, "min_area must be finite and >= 0, got %g", min_area);
    size_t nrings = 0;
    for (size_t i = 0; i < in->n; i++)
        nrings += 1 + in->polys[i].nholes;
    ft_chain **rings = ft_calloc(nrings > 0 ? nrings : 1, sizeof *rings);
    if (rings == NULL)
        return FT_E_NOMEM;
    size_t n = 0;
    int rc = FT_OK;
    char what[64];
    for (size_t i = 0; rc == FT_OK && i < in->n; i++) {
        const ft_polygon *p = &in->polys[i];
        snprintf(what, sizeof what, "polygon %zu outer ring", i);
        rc = oriented_copy(p->outer, 1, what, &rings[n]);
        n += rc == FT_OK;
        for (size_t k = 0; rc == FT_OK && k < p->nholes; k++) {
            snprintf(what, sizeof what, "polygon %zu hole %zu", i, k);
            rc = oriented_copy(p->holes ? p->holes[k] : NULL, -1, what, &rings[n]);
            n += rc == FT_OK;
        }
    }
    ft_polygon_set *res = rc == FT_OK ? ft_polygon_set_create() : NULL;
    if (rc == FT_OK && res == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK) {
        ft_geos g;
        rc = ft_geos_open(&g);
        if (rc == FT_OK) {
            rc = ft_contour_positive_region(&g, rings, n, 0.0, min_area, res);
            ft_geos_close(&g);
        }
    }
    free_rings(rings, n);
    if (rc != FT_OK) {
        ft_polygon_set_free(res);
        return rc;
    }
    *out = res;
    return FT_OK;
}
