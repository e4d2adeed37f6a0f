/* fracterra — contour/contour_stack.c: contour stacks (the levels of a mountain, Misawa, Chiba & Saito
 * §3–4.3) to and from vector layers.
 *
 * To a layer: a real field `elev` (as gdal_contour -p -amin elev names it); one polygon feature per
 * polygon of each level (its outer ring and holes), or, with as_lines, one line feature per ring (outer
 * rings counter-clockwise, holes clockwise, each written closed). A level is the region at or above its
 * elevation, so the polygons of a stack overlap (each inside the one below).
 *
 * From a layer: the levels are the distinct values of the field, sorted. The region of a level is the
 * union of every polygon whose value is at or above it, so both our own nested regions and the bands of
 * gdal_contour -p (the area between a level and the next one up) give the same nested stack. Polygon
 * features bring their outer rings and holes; closed rings of line features bring the area inside an
 * odd number of the level's line rings (even-odd rule, so a hole written as a line stays a hole whatever
 * its orientation). The union is taken from the top down as the positive-winding region of the rings
 * (contour_internal.h), which also repairs self-intersecting input. The stack's interval is the median
 * step between consecutive levels (0 for one level); its spacing is 0 (not known).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

void ft_contour_stack_free(ft_contour_stack *s)
{
    if (s == NULL)
        return;
    for (size_t i = 0; i < s->n; i++)
        ft_polygon_set_free(s->levels[i].polys);
    free(s->levels);
    free(s);
}

/* ---- to a layer ------------------------------------------------------------------------------ */

static int add_ring_part(ft_layer *l, const ft_chain *ring, ft_part_role role)
{
    ft_chain *c = ft_chain_copy(ring);
    if (c == NULL)
        return FT_E_NOMEM;
    c->closed = 1;
    return ft_layer_add_part(l, c, role, 0); /* takes c, even on failure */
}

static int add_line_feature(ft_layer *l, size_t field, double elev, const ft_chain *ring)
{
    int64_t f = ft_layer_add_feature(l, (int64_t)l->nfeatures, FT_GEOM_LINE, 0);
    if (f < 0)
        return (int)f;
    int rc = ft_layer_set_real(l, (size_t)f, field, elev);
    return rc == FT_OK ? add_ring_part(l, ring, FT_ROLE_LINE) : rc;
}

static int add_level(ft_layer *l, size_t field, const ft_contour_level *lev, int as_lines)
{
    const ft_polygon_set *s = lev->polys;
    for (size_t i = 0; s != NULL && i < s->n; i++) {
        const ft_polygon *p = &s->polys[i];
        int rc;
        if (as_lines) {
            rc = add_line_feature(l, field, lev->elev, p->outer);
            for (size_t k = 0; rc == FT_OK && k < p->nholes; k++)
                rc = add_line_feature(l, field, lev->elev, p->holes[k]);
            if (rc != FT_OK)
                return rc;
            continue;
        }
        int64_t f = ft_layer_add_feature(l, (int64_t)l->nfeatures, FT_GEOM_POLYGON, 0);
        if (f < 0)
            return (int)f;
        rc = ft_layer_set_real(l, (size_t)f, field, lev->elev);
        if (rc == FT_OK)
            rc = add_ring_part(l, p->outer, FT_ROLE_OUTER);
        for (size_t k = 0; rc == FT_OK && k < p->nholes; k++)
            rc = add_ring_part(l, p->holes[k], FT_ROLE_INNER);
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

int ft_contour_stack_to_layer(const ft_contour_stack *s, int as_lines, const char *crs_wkt, ft_layer **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_stack_to_layer: NULL output pointer");
    *out = NULL;
    if (s == NULL || (s->n > 0 && s->levels == NULL))
        return ft_error(FT_E_INVALID, "ft_contour_stack_to_layer: NULL contour stack");
    ft_layer *l = ft_layer_create("contours", crs_wkt);
    if (l == NULL)
        return FT_E_NOMEM;
    int rc = ft_layer_add_field(l, "elev", FT_FIELD_REAL, -1, 0, 0);
    if (rc >= 0) {
        size_t field = (size_t)rc;
        rc = FT_OK;
        for (size_t i = 0; rc == FT_OK && i < s->n; i++) {
            if (!isfinite(s->levels[i].elev))
                rc = ft_error(FT_E_NUMERIC, "contour level %zu has a non-finite elevation (%g)", i,
                              s->levels[i].elev);
            else
                rc = add_level(l, field, &s->levels[i], as_lines);
        }
    }
    if (rc != FT_OK) {
        ft_layer_free(l);
        return rc;
    }
    *out = l;
    return FT_OK;
}

/* ---- from a layer ---------------------------------------------------------------------------- */

typedef struct {
    ft_chain **rings;
    size_t n, cap;
} ring_list;

static void ring_list_clear(ring_list *r)
{
    for (size_t i = 0; i < r->n; i++)
        ft_chain_free(r->rings[i]);
    r->n = 0;
}

/* Appends c (taken, even on failure). */
static int ring_list_push(ring_list *r, ft_chain *c)
{
    if (c == NULL)
        return FT_E_NOMEM;
    if (r->n == r->cap) {
        size_t cap = r->cap < 16 ? 16 : 2 * r->cap;
        ft_chain **p = ft_realloc_array(r->rings, cap, sizeof *p);
        if (p == NULL) {
            ft_chain_free(c);
            return FT_E_NOMEM;
        }
        r->rings = p;
        r->cap = cap;
    }
    r->rings[r->n++] = c;
    return FT_OK;
}

/* Crossing-number test: 1 if (x, y) is inside the ring. */
static int inside_ring(const ft_chain *r, double x, double y)
{
    int in = 0;
    for (size_t i = 0, j = r->n - 1; i < r->n; j = i++) {
        if ((r->y[i] > y) != (r->y[j] > y) &&
            x < (r->x[j] - r->x[i]) * (y - r->y[i]) / (r->y[j] - r->y[i]) + r->x[i])
            in = !in;
    }
    return in;
}

/* Orients the line rings by the even-odd rule: a ring inside an even number of the
 * others turns counter-clockwise (adds), inside an odd number clockwise (removes). */
static void orient_even_odd(ring_list *lines)
{
    for (size_t i = 0; i < lines->n; i++) {
        ft_chain *r = lines->rings[i];
        size_t depth = 0;
        for (size_t j = 0; j < lines->n; j++)
            if (j != i && inside_ring(lines->rings[j], r->x[0], r->y[0]))
                depth++;
        double a = ft_chain_signed_area(r);
        if ((depth % 2 == 0) != (a > 0.0))
            ft_chain_reverse(r);
    }
}

/* The rings of feature f: polygon outer rings counter-clockwise and holes clockwise into polys, closed
 * line parts as they are into lines. */
static int feature_rings(const ft_layer *l, size_t f, ring_list *polys, ring_list *lines)
{
    const ft_feature *ft = &l->features[f];
    for (size_t p = ft->first; p < ft->first + ft->count; p++) {
        ft_chain *r = NULL;
        int rc = ft_contour_ring_of_part(l, p, 1, &r);
        if (rc != FT_OK)
            return rc;
        if (r == NULL)
            continue;
        if (ft->type == FT_GEOM_LINE || l->parts[p].role == FT_ROLE_LINE) {
            rc = ring_list_push(lines, r);
        } else {
            double a = ft_chain_signed_area(r);
            int want = l->parts[p].role == FT_ROLE_INNER ? -1 : 1;
            if (a * want < 0.0)
                ft_chain_reverse(r);
            rc = ring_list_push(polys, r);
        }
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The value of feature f in field k as a double; FT_E_FORMAT naming the feature if null or not finite. */
static int feature_value(const ft_layer *l, size_t f, size_t k, double *v)
{
    const ft_value *val = &l->features[f].values[k];
    if (val->is_null)
        return ft_error(FT_E_FORMAT, "feature %" PRId64 " has no value in field '%s'", l->features[f].fid,
                        l->fields[k].name);
    *v = l->fields[k].type == FT_FIELD_INT ? (double)val->i : val->r;
    if (!isfinite(*v))
        return ft_error(FT_E_FORMAT, "feature %" PRId64 ": field '%s' is not finite (%g)", l->features[f].fid,
                        l->fields[k].name, *v);
    return FT_OK;
}

/* The distinct values of the features with geometry, sorted, into *levels (malloc'd). */
static int distinct_levels(const ft_layer *l, size_t k, double **levels, size_t *n)
{
    double *v = ft_malloc((l->nfeatures > 0 ? l->nfeatures : 1) * sizeof *v);
    if (v == NULL)
        return FT_E_NOMEM;
    size_t m = 0;
    for (size_t f = 0; f < l->nfeatures; f++) {
        if (l->features[f].type == FT_GEOM_NONE || l->features[f].count == 0)
            continue;
        int rc = feature_value(l, f, k, &v[m]);
        if (rc != FT_OK) {
            free(v);
            return rc;
        }
        m++;
    }
    qsort(v, m, sizeof *v, cmp_double);
    size_t d = 0;
    for (size_t i = 0; i < m; i++)
        if (d == 0 || v[i] != v[d - 1])
            v[d++] = v[i];
    *levels = v;
    *n = d;
    return FT_OK;
}

static double median_step(const double *levels, size_t n)
{
    if (n < 2)
        return 0.0;
    double *d = ft_malloc((n - 1) * sizeof *d);
    if (d == NULL)
        return levels[n - 1] - levels[0];
    for (size_t i = 0; i + 1 < n; i++)
        d[i] = levels[i + 1] - levels[i];
    qsort(d, n - 1, sizeof *d, cmp_double);
    double m = (n - 1) % 2 ? d[(n - 1) / 2] : 0.5 * (d[(n - 1) / 2 - 1] + d[(n - 1) / 2]);
    free(d);
    return m;
}

/* rings += the rings of set s (copies). */
static int push_set_rings(ring_list *rings, const ft_polygon_set *s)
{
    for (size_t i = 0; i < s->n; i++) {
        int rc = ring_list_push(rings, ft_chain_copy(s->polys[i].outer));
        for (size_t k = 0; rc == FT_OK && k < s->polys[i].nholes; k++)
            rc = ring_list_push(rings, ft_chain_copy(s->polys[i].holes[k]));
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

/* The region of level `elev`: the union of the level above (`above`, may be NULL) and the features whose
 * value is elev. */
static int level_region(ft_geos *g, const ft_layer *l, size_t k, double elev, const ft_polygon_set *above,
                        ft_polygon_set **out)
{
    ring_list polys = {0}, lines = {0};
    int rc = above ? push_set_rings(&polys, above) : FT_OK;
    for (size_t f = 0; rc == FT_OK && f < l->nfeatures; f++) {
        double v;
        if (l->features[f].type == FT_GEOM_NONE || l->features[f].count == 0)
            continue;
        rc = feature_value(l, f, k, &v);
        if (rc == FT_OK && v == elev)
            rc = feature_rings(l, f, &polys, &lines);
    }
    if (rc == FT_OK) {
        orient_even_odd(&lines);
        for (size_t i = 0; i < lines.n; i++) {
            if (rc == FT_OK)
                rc = ring_list_push(&polys, lines.rings[i]); /* takes the ring, even on failure */
            else
                ft_chain_free(lines.rings[i]);
            lines.rings[i] = NULL;
        }
        lines.n = 0;
    }
    ft_polygon_set *s = NULL;
    if (rc == FT_OK && (s = ft_polygon_set_create()) == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = ft_contour_positive_region(g, polys.rings, polys.n, 0.0, 0.0, s);
    ring_list_clear(&polys);
    ring_list_clear(&lines);
    free(polys.rings);
    free(lines.rings);
    if (rc != FT_OK) {
        ft_polygon_set_free(s);
        return rc;
    }
    *out = s;
    return FT_OK;
}

int ft_contour_stack_from_layer(const ft_layer *l, const char *field, ft_contour_stack **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_stack_from_layer: NULL output pointer");
    *out = NULL;
    if (l == NULL || field == NULL)
        return ft_error(FT_E_INVALID, "ft_contour_stack_from_layer: NULL %s", l ? "field name" : "layer");
    int k = ft_layer_field_index(l, field);
    if (k < 0)
        return ft_error(FT_E_FORMAT, "layer '%s' has no field '%s'", l->name ? l->name : "", field);
    if (l->fields[k].type != FT_FIELD_INT && l->fields[k].type != FT_FIELD_REAL)
        return ft_error(FT_E_FORMAT, "field '%s' of layer '%s' is not numeric", field, l->name ? l->name : "");
    double *levels = NULL;
    size_t n = 0;
    int rc = distinct_levels(l, (size_t)k, &levels, &n);
    if (rc != FT_OK)
        return rc;
    if (n == 0) {
        free(levels);
        return ft_error(FT_E_EMPTY, "layer '%s' has no feature with a geometry", l->name ? l->name : "");
    }
    ft_contour_stack *s = ft_calloc(1, sizeof *s);
    if (s == NULL || (s->levels = ft_calloc(n, sizeof *s->levels)) == NULL) {
        free(s);
        free(levels);
        return FT_E_NOMEM;
    }
    s->n = n;
    s->interval = median_step(levels, n);
    s->spacing = 0.0;
    s->dprime = 0.0;
    ft_geos g;
    rc = ft_geos_open(&g);
    for (size_t i = n; rc == FT_OK && i-- > 0;) {
        s->levels[i].elev = levels[i];
        rc = level_region(&g, l, (size_t)k, levels[i], i + 1 < n ? s->levels[i + 1].polys : NULL,
                          &s->levels[i].polys);
        if (rc == FT_OK && s->levels[i].polys->n == 0)
            rc = ft_error(FT_E_FORMAT, "field '%s': the polygons of level %g enclose no area", field, levels[i]);
    }
    ft_geos_close(&g);
    free(levels);
    if (rc != FT_OK) {
        ft_contour_stack_free(s);
        return rc;
    }
    *out = s;
    return FT_OK;
}
