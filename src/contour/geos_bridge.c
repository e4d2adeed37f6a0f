/* fracterra — src/contour/geos_bridge.c: ft_polygon_set <-> GEOS geometries, and the reentrant GEOS context
 * (one per call, on the caller's stack) whose error messages become ft_error messages.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void geos_message(const char *message, void *userdata)
{
    ft_geos *g = userdata;
    snprintf(g->msg, sizeof g->msg, "%s", message ? message : "unknown error");
}

int ft_geos_open(ft_geos *g)
{
    g->msg[0] = '\0';
    g->h = GEOS_init_r();
    if (g->h == NULL)
        return ft_error(FT_E_NOMEM, "cannot create a GEOS context");
    GEOSContext_setErrorMessageHandler_r(g->h, geos_message, g);
    return FT_OK;
}

void ft_geos_close(ft_geos *g)
{
    if (g != NULL && g->h != NULL) {
        GEOS_finish_r(g->h);
        g->h = NULL;
    }
}

int ft_geos_fail(ft_geos *g, const char *what)
{
    return ft_error(FT_E_NUMERIC, "%s: GEOS: %s", what, g->msg[0] ? g->msg : "operation failed");
}

/* A coordinate sequence of the ring with its first vertex repeated at the end. */
static GEOSCoordSequence *ring_sequence(ft_geos *g, const ft_chain *ring)
{
    if (ring == NULL || ring->n == 0) {
        ft_error(FT_E_INVALID, "a ring without vertices cannot become a GEOS geometry");
        return NULL;
    }
    GEOSCoordSequence *seq = GEOSCoordSeq_create_r(g->h, (unsigned)(ring->n + 1), 2);
    if (seq == NULL) {
        ft_geos_fail(g, "coordinate sequence");
        return NULL;
    }
    for (size_t i = 0; i <= ring->n; i++) {
        size_t k = i == ring->n ? 0 : i;
        if (!GEOSCoordSeq_setXY_r(g->h, seq, (unsigned)i, ring->x[k], ring->y[k])) {
            GEOSCoordSeq_destroy_r(g->h, seq);
            ft_geos_fail(g, "coordinate sequence");
            return NULL;
        }
    }
    return seq;
}

GEOSGeometry *ft_geos_ring(ft_geos *g, const ft_chain *ring)
{
    GEOSCoordSequence *seq = ring_sequence(g, ring);
    if (seq == NULL)
        return NULL;
    GEOSGeometry *r = GEOSGeom_createLinearRing_r(g->h, seq); /* takes seq, even on failure */
    if (r == NULL)
        ft_geos_fail(g, "linear ring");
    return r;
}

GEOSGeometry *ft_geos_ring_line(ft_geos *g, const ft_chain *ring)
{
    GEOSCoordSequence *seq = ring_sequence(g, ring);
    if (seq == NULL)
        return NULL;
    GEOSGeometry *r = GEOSGeom_createLineString_r(g->h, seq);
    if (r == NULL)
        ft_geos_fail(g, "line string");
    return r;
}

GEOSGeometry *ft_geos_polygon(ft_geos *g, const ft_polygon *p)
{
    GEOSGeometry *shell = ft_geos_ring(g, p->outer);
    if (shell == NULL)
        return NULL;
    GEOSGeometry **holes = NULL;
    if (p->nholes > 0) {
        holes = ft_calloc(p->nholes, sizeof *holes);
        if (holes == NULL) {
            GEOSGeom_destroy_r(g->h, shell);
            return NULL;
        }
        for (size_t k = 0; k < p->nholes; k++) {
            if ((holes[k] = ft_geos_ring(g, p->holes[k])) == NULL) {
                for (size_t j = 0; j < k; j++)
                    GEOSGeom_destroy_r(g->h, holes[j]);
                free(holes);
                GEOSGeom_destroy_r(g->h, shell);
                return NULL;
            }
        }
    }
    GEOSGeometry *poly = GEOSGeom_createPolygon_r(g->h, shell, holes, (unsigned)p->nholes);
    free(holes);
    if (poly == NULL)
        ft_geos_fail(g, "polygon");
    return poly;
}

GEOSGeometry *ft_geos_from_set(ft_geos *g, const ft_polygon_set *s)
{
    if (s == NULL || s->n == 0) {
        GEOSGeometry *e = GEOSGeom_createEmptyCollection_r(g->h, GEOS_MULTIPOLYGON);
        if (e == NULL)
            ft_geos_fail(g, "empty multipolygon");
        return e;
    }
    GEOSGeometry **parts = ft_calloc(s->n, sizeof *parts);
    if (parts == NULL)
        return NULL;
    for (size_t i = 0; i < s->n; i++) {
        if ((parts[i] = ft_geos_polygon(g, &s->polys[i])) == NULL) {
            for (size_t j = 0; j < i; j++)
                GEOSGeom_destroy_r(g->h, parts[j]);
            free(parts);
            return NULL;
        }
    }
    GEOSGeometry *mp = GEOSGeom_createCollection_r(g->h, GEOS_MULTIPOLYGON, parts, (unsigned)s->n);
    free(parts);
    if (mp == NULL)
        ft_geos_fail(g, "multipolygon");
    return mp;
}

/* ---- GEOS -> set ----------------------------------------------------------------------------- */

/* A ring of GEOS as an ft_chain without its closing vertex; NULL on failure (error set). */
static ft_chain *chain_of_ring(ft_geos *g, const GEOSGeometry *ring)
{
    const GEOSCoordSequence *seq = GEOSGeom_getCoordSeq_r(g->h, ring);
    unsigned size = 0;
    if (seq == NULL || !GEOSCoordSeq_getSize_r(g->h, seq, &size)) {
        ft_geos_fail(g, "reading a ring");
        return NULL;
    }
    ft_chain *c = ft_chain_create(size > 0 ? size : 1, 1);
    if (c == NULL)
        return NULL;
    if (size > 0 && !GEOSCoordSeq_copyToArrays_r(g->h, seq, c->x, c->y, NULL, NULL)) {
        ft_chain_free(c);
        ft_geos_fail(g, "reading a ring");
        return NULL;
    }
    c->n = size;
    if (c->n >= 2 && c->x[0] == c->x[c->n - 1] && c->y[0] == c->y[c->n - 1])
        c->n--;
    return c;
}

static int append_polygon(ft_geos *g, const GEOSGeometry *poly, double min_area, ft_polygon_set *s)
{
    if (GEOSisEmpty_r(g->h, poly) == 1)
        return FT_OK;
    const GEOSGeometry *shell = GEOSGetExteriorRing_r(g->h, poly);
    int nh = GEOSGetNumInteriorRings_r(g->h, poly);
    if (shell == NULL || nh < 0)
        return ft_geos_fail(g, "reading a polygon");
    ft_chain *outer = chain_of_ring(g, shell);
    if (outer == NULL)
        return ft_last_error_code();
    double a = ft_chain_signed_area(outer);
    if (outer->n < 3 || fabs(a) < min_area || a == 0.0) {
        ft_chain_free(outer);
        return FT_OK;
    }
    ft_chain **holes = NULL;
    size_t nholes = 0;
    if (nh > 0 && (holes = ft_calloc((size_t)nh, sizeof *holes)) == NULL) {
        ft_chain_free(outer);
        return FT_E_NOMEM;
    }
    int rc = FT_OK;
    for (int k = 0; k < nh; k++) {
        const GEOSGeometry *hr = GEOSGetInteriorRingN_r(g->h, poly, k);
        ft_chain *h = hr ? chain_of_ring(g, hr) : NULL;
        if (h == NULL) {
            rc = hr ? ft_last_error_code() : ft_geos_fail(g, "reading a hole");
            break;
        }
        double ha = ft_chain_signed_area(h);
        if (h->n < 3 || fabs(ha) < min_area || ha == 0.0) {
            ft_chain_free(h);
            continue;
        }
        holes[nholes++] = h;
    }
    if (rc == FT_OK && nholes == 0) {
        free(holes);
        holes = NULL;
    }
    if (rc == FT_OK)
        rc = ft_polygon_set_add(s, outer, holes, nholes); /* reorients; takes all on success */
    if (rc != FT_OK) {
        for (size_t k = 0; k < nholes; k++)
            ft_chain_free(holes[k]);
        free(holes);
        ft_chain_free(outer);
    }
    return rc;
}

int ft_geos_append_to_set(ft_geos *g, const GEOSGeometry *geom, double min_area, ft_polygon_set *s)
{
    if (geom == NULL)
        return ft_error(FT_E_INVALID, "ft_geos_append_to_set: NULL geometry");
    int type = GEOSGeomTypeId_r(g->h, geom);
    if (type == GEOS_POLYGON)
        return append_polygon(g, geom, min_area, s);
    if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
        int n = GEOSGetNumGeometries_r(g->h, geom);
        if (n < 0)
            return ft_geos_fail(g, "reading a collection");
        for (int i = 0; i < n; i++) {
            int rc = ft_geos_append_to_set(g, GEOSGetGeometryN_r(g->h, geom, i), min_area, s);
            if (rc != FT_OK)
                return rc;
        }
        return FT_OK;
    }
    if (type < 0)
        return ft_geos_fail(g, "reading a geometry");
    return FT_OK; /* points and lines have no area */
}
