/* fracterra — core/layer.c: vector layers (ft_layer): fields, features with attribute values, parts
 * (chains with a role), deep copy, bounding box and finiteness checks.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Grows *arr (elements of elsize) so that it holds at least need elements, by half again each time. */
static int grow(void **arr, size_t *cap, size_t need, size_t elsize)
{
    if (need <= *cap)
        return FT_OK;
    size_t ncap = *cap < 8 ? 8 : *cap + *cap / 2;
    if (ncap < need)
        ncap = need;
    void *p = ft_realloc_array(*arr, ncap, elsize);
    if (p == NULL)
        return FT_E_NOMEM;
    *arr = p;
    *cap = ncap;
    return FT_OK;
}

ft_layer *ft_layer_create(const char *name, const char *crs_wkt)
{
    ft_layer *l = ft_calloc(1, sizeof *l);
    if (l == NULL)
        return NULL;
    if ((name != NULL && (l->name = ft_strdup(name)) == NULL) ||
        (crs_wkt != NULL && (l->crs_wkt = ft_strdup(crs_wkt)) == NULL)) {
        ft_layer_free(l);
        return NULL;
    }
    return l;
}

static void free_values(ft_value *v, size_t n)
{
    if (v == NULL)
        return;
    for (size_t i = 0; i < n; i++)
        free(v[i].s);
    free(v);
}

void ft_layer_free(ft_layer *l)
{
    if (l == NULL)
        return;
    for (size_t i = 0; i < l->nfields; i++)
        free(l->fields[i].name);
    free(l->fields);
    for (size_t f = 0; f < l->nfeatures; f++)
        free_values(l->features[f].values, l->nfields);
    free(l->features);
    for (size_t p = 0; p < l->nparts; p++)
        ft_chain_free(l->parts[p].chain);
    free(l->parts);
    ft_topology_free(l->topology);
    free(l->name);
    free(l->crs_wkt);
    free(l);
}

/* ---- deep copy ------------------------------------------------------------------------------- */

static int copy_fields(ft_layer *d, const ft_layer *l)
{
    if (l->nfields == 0)
        return FT_OK;
    d->fields = ft_calloc(l->nfields, sizeof *d->fields);
    if (d->fields == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < l->nfields; i++) {
        d->fields[i] = l->fields[i];
        d->fields[i].name = NULL;
        d->nfields = i + 1;
        if ((d->fields[i].name = ft_strdup(l->fields[i].name)) == NULL)
            return FT_E_NOMEM;
    }
    return FT_OK;
}

static ft_value *copy_values(const ft_value *v, size_t n)
{
    ft_value *d = ft_calloc(n, sizeof *d);
    if (d == NULL)
        return NULL;
    for (size_t i = 0; i < n; i++) {
        d[i] = v[i];
        d[i].s = NULL;
        if (v[i].s != NULL && (d[i].s = ft_strdup(v[i].s)) == NULL) {
            free_values(d, n);
            return NULL;
        }
    }
    return d;
}

static int copy_features(ft_layer *d, const ft_layer *l)
{
    if (l->nfeatures == 0)
        return FT_OK;
    d->features = ft_calloc(l->nfeatures, sizeof *d->features);
    if (d->features == NULL)
        return FT_E_NOMEM;
    d->features_cap = l->nfeatures;
    for (size_t f = 0; f < l->nfeatures; f++) {
        d->features[f] = l->features[f];
        d->features[f].values = NULL;
        d->nfeatures = f + 1;
        if ((d->features[f].values = copy_values(l->features[f].values, l->nfields)) == NULL)
            return FT_E_NOMEM;
    }
    return FT_OK;
}

static int copy_parts(ft_layer *d, const ft_layer *l)
{
    if (l->nparts == 0)
        return FT_OK;
    d->parts = ft_calloc(l->nparts, sizeof *d->parts);
    if (d->parts == NULL)
        return FT_E_NOMEM;
    d->parts_cap = l->nparts;
    for (size_t p = 0; p < l->nparts; p++) {
        d->parts[p] = l->parts[p];
        d->parts[p].chain = NULL;
        d->nparts = p + 1;
        if ((d->parts[p].chain = ft_chain_copy(l->parts[p].chain)) == NULL)
            return FT_E_NOMEM;
    }
    return FT_OK;
}

/* A deep copy of a topology, arcs included (they may hold edits not yet applied to the rings). */
static ft_topology *copy_topology(const ft_topology *t)
{
    ft_topology *d = ft_calloc(1, sizeof *d);
    if (d == NULL)
        return NULL;
    d->narcs = t->narcs;
    d->nparts = t->nparts;
    d->arcs = ft_calloc(t->narcs, sizeof *d->arcs);
    d->arc_left = ft_calloc(t->narcs, sizeof *d->arc_left);
    d->arc_right = ft_calloc(t->narcs, sizeof *d->arc_right);
    d->rings = ft_calloc(t->nparts, sizeof *d->rings);
    d->nrings = ft_calloc(t->nparts, sizeof *d->nrings);
    if (!d->arcs || !d->arc_left || !d->arc_right || !d->rings || !d->nrings)
        goto fail;
    for (size_t a = 0; a < t->narcs; a++) {
        if ((d->arcs[a] = ft_chain_copy(t->arcs[a])) == NULL)
            goto fail;
        d->arc_left[a] = t->arc_left[a];
        d->arc_right[a] = t->arc_right[a];
    }
    for (size_t p = 0; p < t->nparts; p++) {
        if (t->nrings[p] == 0)
            continue;
        d->rings[p] = ft_calloc(t->nrings[p], sizeof *d->rings[p]);
        if (d->rings[p] == NULL)
            goto fail;
        memcpy(d->rings[p], t->rings[p], t->nrings[p] * sizeof *d->rings[p]);
        d->nrings[p] = t->nrings[p];
    }
    return d;
fail:
    ft_topology_free(d);
    return NULL;
}

ft_layer *ft_layer_copy(const ft_layer *l)
{
    if (l == NULL) {
        ft_error(FT_E_INVALID, "ft_layer_copy: NULL layer");
        return NULL;
    }
    ft_layer *d = ft_layer_create(l->name, l->crs_wkt);
    if (d == NULL)
        return NULL;
    if (copy_fields(d, l) != FT_OK || copy_features(d, l) != FT_OK || copy_parts(d, l) != FT_OK)
        goto fail;
    if (l->topology != NULL && (d->topology = copy_topology(l->topology)) == NULL)
        goto fail;
    return d;
fail:
    ft_layer_free(d);
    return NULL;
}

/* ---- fields and features --------------------------------------------------------------------- */

/* Existing features get a null value for the new field. */
int ft_layer_add_field(ft_layer *l, const char *name, ft_field_type type, int native_type, int width,
                       int precision)
{
    if (l == NULL || name == NULL)
        return ft_error(FT_E_INVALID, "ft_layer_add_field: NULL %s", l ? "field name" : "layer");
    if (type != FT_FIELD_INT && type != FT_FIELD_REAL && type != FT_FIELD_STRING)
        return ft_error(FT_E_INVALID, "field '%s': unknown field type %d", name, (int)type);
    if (ft_layer_field_index(l, name) >= 0)
        return ft_error(FT_E_INVALID, "field '%s' already exists", name);
    if (l->nfields >= INT_MAX)
        return ft_error(FT_E_INVALID, "too many fields (%zu)", l->nfields);
    size_t n = l->nfields + 1;
    for (size_t f = 0; f < l->nfeatures; f++) {
        ft_value *v = ft_realloc_array(l->features[f].values, n, sizeof *v);
        if (v == NULL)
            return FT_E_NOMEM;
        memset(&v[n - 1], 0, sizeof *v);
        v[n - 1].is_null = 1;
        l->features[f].values = v;
    }
    ft_field *fields = ft_realloc_array(l->fields, n, sizeof *fields);
    if (fields == NULL)
        return FT_E_NOMEM;
    l->fields = fields;
    ft_field *fd = &fields[n - 1];
    if ((fd->name = ft_strdup(name)) == NULL)
        return FT_E_NOMEM;
    fd->type = type;
    fd->native_type = native_type;
    fd->width = width;
    fd->precision = precision;
    l->nfields = n;
    return (int)(n - 1);
}

int ft_layer_field_index(const ft_layer *l, const char *name)
{
    if (l == NULL || name == NULL)
        return -1;
    for (size_t i = 0; i < l->nfields; i++)
        if (strcasecmp(l->fields[i].name, name) == 0)
            return (int)i;
    return -1;
}

int64_t ft_layer_add_feature(ft_layer *l, int64_t fid, ft_geom_type type, int multi)
{
    if (l == NULL)
        return ft_error(FT_E_INVALID, "ft_layer_add_feature: NULL layer");
    if (type != FT_GEOM_NONE && type != FT_GEOM_LINE && type != FT_GEOM_POLYGON)
        return ft_error(FT_E_INVALID, "feature %lld: unknown geometry type %d", (long long)fid, (int)type);
    if (grow((void **)&l->features, &l->features_cap, l->nfeatures + 1, sizeof *l->features) != FT_OK)
        return FT_E_NOMEM;
    ft_value *values = ft_calloc(l->nfields, sizeof *values);
    if (values == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < l->nfields; i++)
        values[i].is_null = 1;
    ft_feature *ft = &l->features[l->nfeatures];
    memset(ft, 0, sizeof *ft);
    ft->fid = fid;
    ft->type = type;
    ft->multi = multi ? 1 : 0;
    ft->first = l->nparts;
    ft->values = values;
    return (int64_t)l->nfeatures++;
}

/* Adding a part invalidates a previously built topology, which is therefore freed. */
int ft_layer_add_part(ft_layer *l, ft_chain *chain, ft_part_role role, int polygon)
{
    if (l == NULL || chain == NULL) {
        ft_chain_free(chain);
        return ft_error(FT_E_INVALID, "ft_layer_add_part: NULL %s", l ? "chain" : "layer");
    }
    if (l->nfeatures == 0) {
        ft_chain_free(chain);
        return ft_error(FT_E_INVALID, "ft_layer_add_part: the layer has no feature to add a part to");
    }
    if (role != FT_ROLE_LINE && role != FT_ROLE_OUTER && role != FT_ROLE_INNER) {
        ft_chain_free(chain);
        return ft_error(FT_E_INVALID, "feature %zu: unknown part role %d", l->nfeatures - 1, (int)role);
    }
    if (grow((void **)&l->parts, &l->parts_cap, l->nparts + 1, sizeof *l->parts) != FT_OK) {
        ft_chain_free(chain);
        return FT_E_NOMEM;
    }
    ft_part *p = &l->parts[l->nparts];
    p->chain = chain;
    p->feature = l->nfeatures - 1;
    p->polygon = polygon;
    p->role = role;
    l->nparts++;
    l->features[l->nfeatures - 1].count++;
    ft_topology_free(l->topology);
    l->topology = NULL;
    return FT_OK;
}

/* ---- attribute values ------------------------------------------------------------------------ */

static ft_value *value_at(ft_layer *l, size_t f, size_t field)
{
    if (l == NULL) {
        ft_error(FT_E_INVALID, "NULL layer");
        return NULL;
    }
    if (f >= l->nfeatures) {
        ft_error(FT_E_INVALID, "feature index %zu out of range (%zu features)", f, l->nfeatures);
        return NULL;
    }
    if (field >= l->nfields) {
        ft_error(FT_E_INVALID, "field index %zu out of range (%zu fields)", field, l->nfields);
        return NULL;
    }
    return &l->features[f].values[field];
}

static void value_reset(ft_value *v)
{
    free(v->s);
    memset(v, 0, sizeof *v);
}

/* An integer may go into an integer or a real field. */
int ft_layer_set_int(ft_layer *l, size_t f, size_t field, int64_t v)
{
    ft_value *val = value_at(l, f, field);
    if (val == NULL)
        return FT_E_INVALID;
    ft_field_type type = l->fields[field].type;
    if (type == FT_FIELD_STRING)
        return ft_error(FT_E_INVALID, "field '%s' holds strings, cannot set integer %lld",
                        l->fields[field].name, (long long)v);
    value_reset(val);
    if (type == FT_FIELD_INT)
        val->i = v;
    else
        val->r = (double)v;
    return FT_OK;
}

/* A real may go into a real field, or into an integer field if it is a representable integer. */
int ft_layer_set_real(ft_layer *l, size_t f, size_t field, double v)
{
    ft_value *val = value_at(l, f, field);
    if (val == NULL)
        return FT_E_INVALID;
    ft_field_type type = l->fields[field].type;
    if (type == FT_FIELD_STRING)
        return ft_error(FT_E_INVALID, "field '%s' holds strings, cannot set real %g", l->fields[field].name, v);
    if (type == FT_FIELD_INT && !(v == floor(v) && v >= -9223372036854775808.0 && v < 9223372036854775808.0))
        return ft_error(FT_E_INVALID, "field '%s' holds integers, cannot set %g", l->fields[field].name, v);
    value_reset(val);
    if (type == FT_FIELD_INT)
        val->i = (int64_t)v;
    else
        val->r = v;
    return FT_OK;
}

/* A NULL string sets the value to null. */
int ft_layer_set_string(ft_layer *l, size_t f, size_t field, const char *v)
{
    ft_value *val = value_at(l, f, field);
    if (val == NULL)
        return FT_E_INVALID;
    if (v == NULL) {
        value_reset(val);
        val->is_null = 1;
        return FT_OK;
    }
    if (l->fields[field].type != FT_FIELD_STRING)
        return ft_error(FT_E_INVALID, "field '%s' is numeric, cannot set string '%s'", l->fields[field].name, v);
    char *copy = ft_strdup(v);
    if (copy == NULL)
        return FT_E_NOMEM;
    value_reset(val);
    val->s = copy;
    return FT_OK;
}

/* ---- geometry summaries ---------------------------------------------------------------------- */

size_t ft_layer_vertex_count(const ft_layer *l)
{
    size_t n = 0;
    for (size_t p = 0; l != NULL && p < l->nparts; p++)
        n += l->parts[p].chain ? l->parts[p].chain->n : 0;
    return n;
}

int ft_layer_bbox(const ft_layer *l, double *xmin, double *ymin, double *xmax, double *ymax)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    int any = 0;
    for (size_t p = 0; l != NULL && p < l->nparts; p++) {
        double a, b, c, d;
        const ft_chain *ch = l->parts[p].chain;
        if (ch == NULL || ch->n == 0 || ft_chain_bbox(ch, &a, &b, &c, &d) != FT_OK)
            continue;
        x0 = fmin(x0, a);
        y0 = fmin(y0, b);
        x1 = fmax(x1, c);
        y1 = fmax(y1, d);
        any = 1;
    }
    if (!any)
        return ft_error(FT_E_EMPTY, "layer '%s' has no vertex", l && l->name ? l->name : "");
    if (xmin) *xmin = x0;
    if (ymin) *ymin = y0;
    if (xmax) *xmax = x1;
    if (ymax) *ymax = y1;
    return FT_OK;
}

/* The message gives the feature index (and its fid), the part index within the feature and the
 * vertex index within the part. */
int ft_layer_check_finite(const ft_layer *l)
{
    if (l == NULL)
        return ft_error(FT_E_INVALID, "ft_layer_check_finite: NULL layer");
    for (size_t f = 0; f < l->nfeatures; f++) {
        const ft_feature *ft = &l->features[f];
        for (size_t k = 0; k < ft->count; k++) {
            const ft_chain *c = l->parts[ft->first + k].chain;
            for (size_t i = 0; c != NULL && i < c->n; i++)
                if (!isfinite(c->x[i]) || !isfinite(c->y[i]))
                    return ft_error(FT_E_NUMERIC, "feature %zu (fid %lld), part %zu, vertex %zu is not finite "
                                    "(x=%g, y=%g)", f, (long long)ft->fid, k, i, c->x[i], c->y[i]);
        }
    }
    return FT_OK;
}
