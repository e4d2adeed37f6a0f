/* fracterra — src/contour/polygon_set.c: polygon sets (the contour(s) of one elevation: islands, each with
 * holes): creation, copy, appending with reorientation (outer rings counter-clockwise, holes clockwise,
 * y up), area, vertex count, the polygons of a layer, GEOS validity and containment.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ft_polygon_set *ft_polygon_set_create(void)
{
    return ft_calloc(1, sizeof(ft_polygon_set));
}

static void polygon_clear(ft_polygon *p)
{
    ft_chain_free(p->outer);
    for (size_t k = 0; k < p->nholes; k++)
        ft_chain_free(p->holes[k]);
    free(p->holes);
    *p = (ft_polygon){0};
}

void ft_polygon_set_free(ft_polygon_set *s)
{
    if (s == NULL)
        return;
    for (size_t i = 0; i < s->n; i++)
        polygon_clear(&s->polys[i]);
    free(s->polys);
    free(s);
}

size_t ft_polygon_set_ring_count(const ft_polygon_set *s)
{
    size_t n = 0;
    for (size_t i = 0; s != NULL && i < s->n; i++)
        n += 1 + s->polys[i].nholes;
    return n;
}

const ft_chain *ft_polygon_set_ring(const ft_polygon_set *s, size_t k)
{
    for (size_t i = 0; s != NULL && i < s->n; i++) {
        if (k == 0)
            return s->polys[i].outer;
        if (k <= s->polys[i].nholes)
            return s->polys[i].holes[k - 1];
        k -= 1 + s->polys[i].nholes;
    }
    return NULL;
}

ft_polygon_set *ft_polygon_set_copy(const ft_polygon_set *s)
{
    if (s == NULL) {
        ft_error(FT_E_INVALID, "ft_polygon_set_copy: NULL set");
        return NULL;
    }
    ft_polygon_set *d = ft_polygon_set_create();
    if (d == NULL)
        return NULL;
    if (s->n > 0 && (d->polys = ft_calloc(s->n, sizeof *d->polys)) == NULL)
        goto fail;
    d->cap = s->n;
    for (size_t i = 0; i < s->n; i++) {
        const ft_polygon *p = &s->polys[i];
        ft_polygon *q = &d->polys[i];
        d->n = i + 1;
        if ((q->outer = ft_chain_copy(p->outer)) == NULL)
            goto fail;
        if (p->nholes == 0)
            continue;
        if ((q->holes = ft_calloc(p->nholes, sizeof *q->holes)) == NULL)
            goto fail;
        for (size_t k = 0; k < p->nholes; k++) {
            if ((q->holes[k] = ft_chain_copy(p->holes[k])) == NULL)
                goto fail;
            q->nholes = k + 1;
        }
    }
    return d;
fail:
    ft_polygon_set_free(d);
    return NULL;
}

/* Checks a ring given to ft_polygon_set_add: present, finite, at least 3 vertices once a repeated
 * closing vertex is set aside. */
static int check_added_ring(const ft_chain *c, const char *what, size_t index)
{
    if (c == NULL)
        return ft_error(FT_E_INVALID, "ft_polygon_set_add: %s %zu is NULL", what, index);
    size_t n = c->n;
    if (n >= 2 && c->x[0] == c->x[n - 1] && c->y[0] == c->y[n - 1])
        n--;
    if (n < 3)
        return ft_error(FT_E_INVALID, "ft_polygon_set_add: %s %zu has %zu vertices, a ring needs at least 3",
                        what, index, n);
    for (size_t i = 0; i < c->n; i++)
        if (!isfinite(c->x[i]) || !isfinite(c->y[i]))
            return ft_error(FT_E_INVALID, "ft_polygon_set_add: %s %zu vertex %zu is not finite (x=%g, y=%g)",
                            what, index, i, c->x[i], c->y[i]);
    return FT_OK;
}

/* Marks the chain as a ring, drops a repeated closing vertex and orients it (sign +1 counter-clockwise,
 * -1 clockwise) by its signed area. */
static void normalize_ring(ft_chain *c, int sign)
{
    c->closed = 1;
    if (c->n >= 2 && c->x[0] == c->x[c->n - 1] && c->y[0] == c->y[c->n - 1])
        c->n--;
    double a = ft_chain_signed_area(c);
    if (a * sign < 0.0)
        ft_chain_reverse(c);
}

int ft_polygon_set_add(ft_polygon_set *s, ft_chain *outer, ft_chain **holes, size_t nholes)
{
    if (s == NULL)
        return ft_error(FT_E_INVALID, "ft_polygon_set_add: NULL set");
    if (nholes > 0 && holes == NULL)
        return ft_error(FT_E_INVALID, "ft_polygon_set_add: %zu holes announced but the array is NULL", nholes);
    int rc = check_added_ring(outer, "outer ring", s->n);
    for (size_t k = 0; rc == FT_OK && k < nholes; k++)
        rc = check_added_ring(holes[k], "hole", k);
    if (rc != FT_OK)
        return rc;
    if (s->n == s->cap) {
        size_t cap = s->cap < 4 ? 4 : s->cap + s->cap / 2;
        ft_polygon *p = ft_realloc_array(s->polys, cap, sizeof *p);
        if (p == NULL)
            return FT_E_NOMEM;
        s->polys = p;
        s->cap = cap;
    }
    normalize_ring(outer, 1);
    for (size_t k = 0; k < nholes; k++)
        normalize_ring(holes[k], -1);
    if (nholes == 0) {
        free(holes); /* the array is taken too, even when it holds nothing */
        holes = NULL;
    }
    s->polys[s->n++] = (ft_polygon){outer, holes, nholes};
    return FT_OK;
}

double ft_polygon_set_area(const ft_polygon_set *s)
{
    double a = 0.0;
    if (s == NULL)
        return 0.0;
    for (size_t i = 0; i < s->n; i++) {
        a += fabs(ft_chain_signed_area(s->polys[i].outer));
        for (size_t k = 0; k < s->polys[i].nholes; k++)
            a -= fabs(ft_chain_signed_area(s->polys[i].holes[k]));
    }
    return a;
}

size_t ft_polygon_set_vertices(const ft_polygon_set *s)
{
    size_t n = 0;
    if (s == NULL)
        return 0;
    for (size_t i = 0; i < s->n; i++) {
        n += s->polys[i].outer ? s->polys[i].outer->n : 0;
        for (size_t k = 0; k < s->polys[i].nholes; k++)
            n += s->polys[i].holes[k] ? s->polys[i].holes[k]->n : 0;
    }
    return n;
}

int ft_contour_check_ring(const ft_chain *ring, const char *what)
{
    if (ring == NULL)
        return ft_error(FT_E_INVALID, "%s is NULL", what);
    for (size_t i = 0; i < ring->n; i++)
        if (!isfinite(ring->x[i]) || !isfinite(ring->y[i]))
            return ft_error(FT_E_INVALID, "%s: vertex %zu is not finite (x=%g, y=%g)", what, i, ring->x[i],
                            ring->y[i]);
    /* distinct vertices: consecutive repeats (and a repeated closing vertex) do not count */
    size_t distinct = 0;
    for (size_t i = 0; i < ring->n; i++) {
        size_t j = i + 1 == ring->n ? 0 : i + 1;
        if (ring->n == 1 || ring->x[i] != ring->x[j] || ring->y[i] != ring->y[j])
            distinct++;
    }
    if (distinct < 3)
        return ft_error(FT_E_INVALID, "%s has %zu distinct vertices, at least 3 needed", what, distinct);
    double xmin, ymin, xmax, ymax;
    ft_chain_bbox(ring, &xmin, &ymin, &xmax, &ymax);
    double w = xmax - xmin, h = ymax - ymin;
    double a = ft_chain_signed_area(ring);
    if (!(fabs(a) > 1e-12 * (w * w + h * h)))
        return ft_error(FT_E_INVALID, "%s has zero area (%g over a %g x %g extent)", what, a, w, h);
    return FT_OK;
}

/* ---- from a layer ------------------------------------------------------------------------------ */

/* A copy of a part as a ring (contour_internal.h). */
int ft_contour_ring_of_part(const ft_layer *l, size_t p, int degenerate_ok, ft_chain **out)
{
    const ft_part *part = &l->parts[p];
    const ft_chain *c = part->chain;
    int64_t fid = l->features[part->feature].fid;
    size_t index = p - l->features[part->feature].first;
    *out = NULL;
    if (c == NULL || c->n == 0)
        return ft_error(FT_E_FORMAT, "feature %" PRId64 " part %zu has no vertex", fid, index);
    int closed = c->closed || (c->n >= 2 && c->x[0] == c->x[c->n - 1] && c->y[0] == c->y[c->n - 1]);
    if (!closed)
        return ft_error(FT_E_FORMAT,
                        "feature %" PRId64 " part %zu is an open line (first and last vertices differ), not a ring",
                        fid, index);
    for (size_t i = 0; i < c->n; i++)
        if (!isfinite(c->x[i]) || !isfinite(c->y[i]))
            return ft_error(FT_E_FORMAT, "feature %" PRId64 " part %zu: vertex %zu is not finite (x=%g, y=%g)",
                            fid, index, i, c->x[i], c->y[i]);
    ft_chain *r = ft_chain_copy(c);
    if (r == NULL)
        return FT_E_NOMEM;
    r->closed = 1;
    if (r->n >= 2 && r->x[0] == r->x[r->n - 1] && r->y[0] == r->y[r->n - 1])
        r->n--;
    if (degenerate_ok && (r->n < 3 || ft_chain_signed_area(r) == 0.0)) {
        ft_chain_free(r); /* a degenerate ring encloses nothing */
        return FT_OK;
    }
    if (r->n < 3) {
        ft_chain_free(r);
        return ft_error(FT_E_FORMAT, "feature %" PRId64 " part %zu: a ring of %zu vertices, at least 3 needed",
                        fid, index, c->n);
    }
    *out = r;
    return FT_OK;
}

/* Adds the polygon made of parts [first, end) (an outer ring then its holes) to s. */
static int add_polygon_parts(const ft_layer *l, size_t first, size_t end, ft_polygon_set *s)
{
    ft_chain *outer = NULL;
    ft_chain **holes = NULL;
    size_t nholes = 0;
    int rc = ft_contour_ring_of_part(l, first, 0, &outer);
    if (rc == FT_OK && end - first > 1 && (holes = ft_calloc(end - first - 1, sizeof *holes)) == NULL)
        rc = FT_E_NOMEM;
    for (size_t p = first + 1; rc == FT_OK && p < end; p++) {
        rc = ft_contour_ring_of_part(l, p, 0, &holes[nholes]);
        if (rc == FT_OK)
            nholes++;
    }
    if (rc == FT_OK)
        rc = ft_polygon_set_add(s, outer, holes, nholes);
    if (rc != FT_OK) {
        ft_chain_free(outer);
        for (size_t k = 0; k < nholes; k++)
            ft_chain_free(holes[k]);
        free(holes);
    }
    return rc;
}

static int add_feature(const ft_layer *l, size_t f, ft_polygon_set *s)
{
    const ft_feature *ft = &l->features[f];
    if (ft->type == FT_GEOM_LINE) {
        for (size_t p = ft->first; p < ft->first + ft->count; p++) {
            int rc = add_polygon_parts(l, p, p + 1, s);
            if (rc != FT_OK)
                return rc;
        }
        return FT_OK;
    }
    if (ft->type != FT_GEOM_POLYGON)
        return FT_OK;
    size_t p = ft->first, end = ft->first + ft->count;
    while (p < end) {
        if (l->parts[p].role != FT_ROLE_OUTER)
            return ft_error(FT_E_FORMAT, "feature %" PRId64 " part %zu: an inner ring without its outer ring",
                            ft->fid, p - ft->first);
        size_t q = p + 1;
        while (q < end && l->parts[q].role == FT_ROLE_INNER && l->parts[q].polygon == l->parts[p].polygon)
            q++;
        int rc = add_polygon_parts(l, p, q, s);
        if (rc != FT_OK)
            return rc;
        p = q;
    }
    return FT_OK;
}

int ft_polygon_set_from_layer(const ft_layer *l, ft_polygon_set **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_polygon_set_from_layer: NULL output");
    *out = NULL;
    if (l == NULL)
        return ft_error(FT_E_INVALID, "ft_polygon_set_from_layer: NULL layer");
    ft_polygon_set *s = ft_polygon_set_create();
    if (s == NULL)
        return FT_E_NOMEM;
    for (size_t f = 0; f < l->nfeatures; f++) {
        int rc = add_feature(l, f, s);
        if (rc != FT_OK) {
            ft_polygon_set_free(s);
            return rc;
        }
    }
    if (s->n == 0) {
        ft_polygon_set_free(s);
        return ft_error(FT_E_EMPTY, "layer '%s' has no polygon and no closed ring (%zu features)",
                        l->name ? l->name : "", l->nfeatures);
    }
    *out = s;
    return FT_OK;
}

/* ---- validity and containment ----------------------------------------------------------------- */

static _Thread_local char tl_why[256];

static int invalid(const char **why, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* Records the reason in the thread's buffer, points *why at it, returns 0. */
static int invalid(const char **why, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(tl_why, sizeof tl_why, fmt, ap);
    va_end(ap);
    if (why != NULL)
        *why = tl_why;
    return 0;
}

/* Ring checks GEOS does not make: counts, finiteness, orientation. */
static int check_orientation(const ft_polygon_set *s, const char **why)
{
    for (size_t i = 0; i < s->n; i++) {
        const ft_polygon *p = &s->polys[i];
        if (p->outer == NULL || p->outer->n < 3)
            return invalid(why, "polygon %zu: outer ring missing or with fewer than 3 vertices", i);
        if (ft_chain_check_finite(p->outer) != FT_OK)
            return invalid(why, "polygon %zu: outer ring has a non-finite vertex", i);
        if (!(ft_chain_signed_area(p->outer) > 0.0))
            return invalid(why, "polygon %zu: outer ring is not counter-clockwise with a positive area", i);
        if (p->nholes > 0 && p->holes == NULL)
            return invalid(why, "polygon %zu: %zu holes but no hole array", i, p->nholes);
        for (size_t k = 0; k < p->nholes; k++) {
            const ft_chain *h = p->holes[k];
            if (h == NULL || h->n < 3)
                return invalid(why, "polygon %zu hole %zu: missing or with fewer than 3 vertices", i, k);
            if (ft_chain_check_finite(h) != FT_OK)
                return invalid(why, "polygon %zu hole %zu: a non-finite vertex", i, k);
            if (!(ft_chain_signed_area(h) < 0.0))
                return invalid(why, "polygon %zu hole %zu: not clockwise", i, k);
        }
    }
    return 1;
}

int ft_polygon_set_is_valid(const ft_polygon_set *s, const char **why)
{
    if (why != NULL)
        *why = NULL;
    if (s == NULL) {
        ft_error(FT_E_INVALID, "ft_polygon_set_is_valid: NULL polygon set");
        return 2;
    }
    if (s->n > 0 && s->polys == NULL)
        return invalid(why, "%zu polygons but no polygon array", s->n);
    if (!check_orientation(s, why))
        return 0;
    if (s->n == 0)
        return 1;
    ft_geos g;
    if (ft_geos_open(&g) != FT_OK)
        return 2;
    int ok = 0;
    GEOSGeometry *mp = ft_geos_from_set(&g, s);
    if (mp == NULL) {
        snprintf(tl_why, sizeof tl_why, "GEOS rejects the rings: %.200s", g.msg[0] ? g.msg : ft_last_error());
        if (why != NULL)
            *why = tl_why;
    } else {
        char *reason = NULL;
        GEOSGeometry *where = NULL;
        char v = GEOSisValidDetail_r(g.h, mp, 0, &reason, &where);
        if (v == 1) {
            ok = 1;
        } else {
            double x = NAN, y = NAN;
            if (where != NULL) {
                GEOSGeomGetX_r(g.h, where, &x);
                GEOSGeomGetY_r(g.h, where, &y);
            }
            if (v == 0) {
                snprintf(tl_why, sizeof tl_why, "%s at (%.17g, %.17g)", reason ? reason : "invalid", x, y);
                if (why != NULL)
                    *why = tl_why;
            } else {
                ft_geos_fail(&g, "ft_polygon_set_is_valid");
                ok = 2;
            }
        }
        if (reason != NULL)
            GEOSFree_r(g.h, reason);
        if (where != NULL)
            GEOSGeom_destroy_r(g.h, where);
        GEOSGeom_destroy_r(g.h, mp);
    }
    ft_geos_close(&g);
    return ok;
}

int ft_polygon_set_within(const ft_polygon_set *inner, const ft_polygon_set *outer)
{
    if (inner == NULL || outer == NULL) {
        ft_error(FT_E_INVALID, "ft_polygon_set_within: NULL %s set", inner == NULL ? "inner" : "outer");
        return 2;
    }
    if (inner->n == 0)
        return 1;
    if (outer->n == 0)
        return 0;
    ft_geos g;
    if (ft_geos_open(&g) != FT_OK)
        return 2;
    int result = 2; /* GEOS rejecting either set's rings leaves the question undecided (error set) */
    GEOSGeometry *a = ft_geos_from_set(&g, outer);
    GEOSGeometry *b = a ? ft_geos_from_set(&g, inner) : NULL;
    if (a != NULL && b != NULL) {
        char c = GEOSCovers_r(g.h, a, b);
        if (c == 2)
            ft_geos_fail(&g, "ft_polygon_set_within");
        result = c == 2 ? 2 : c == 1;
    }
    if (a != NULL)
        GEOSGeom_destroy_r(g.h, a);
    if (b != NULL)
        GEOSGeom_destroy_r(g.h, b);
    ft_geos_close(&g);
    return result;
}
