/* fracterra — src/urban/classes.c: the land-use classes of a layer (Zhang, Yu & Fan 2008, §1.2:
 * residential area, industrial area, vegetation, water system, each measured on its own), i.e. its polygon
 * features grouped by the value of one attribute field. Features are sorted by (value, index) and cut
 * into runs of equal values: integer and real fields compare numerically, strings by strcmp.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/urban.h"
#include "internal.h"

typedef struct {
    const ft_value *v;
    size_t feature;
    ft_field_type t; /* the field's type, carried for the comparison */
} keyed;

static int cmp_value(const ft_value *a, const ft_value *b, ft_field_type t)
{
    if (t == FT_FIELD_INT)
        return (a->i > b->i) - (a->i < b->i);
    if (t == FT_FIELD_REAL)
        return (a->r > b->r) - (a->r < b->r);
    return strcmp(a->s != NULL ? a->s : "", b->s != NULL ? b->s : "");
}

static int cmp_keyed(const void *x, const void *y)
{
    const keyed *a = x, *b = y;
    int c = cmp_value(a->v, b->v, a->t);
    return c != 0 ? c : (a->feature > b->feature) - (a->feature < b->feature);
}

static char *label_of(const ft_value *v, ft_field_type t)
{
    char buf[64];
    if (t == FT_FIELD_INT)
        snprintf(buf, sizeof buf, "%" PRId64, v->i);
    else if (t == FT_FIELD_REAL)
        snprintf(buf, sizeof buf, "%.15g", v->r);
    return ft_strdup(t == FT_FIELD_STRING ? (v->s != NULL ? v->s : "") : buf);
}

void ft_urban_classes_free(ft_urban_classes *c)
{
    if (c == NULL)
        return;
    for (size_t i = 0; i < c->n; i++) {
        free(c->classes[i].label);
        free(c->classes[i].features);
    }
    free(c->classes);
    free(c);
}

static int field_error(const ft_layer *l, const char *field)
{
    char names[512] = "";
    size_t len = 0;
    for (size_t i = 0; i < l->nfields && len + 1 < sizeof names; i++)
        len += (size_t)snprintf(names + len, sizeof names - len, "%s%s", i ? ", " : "", l->fields[i].name);
    return ft_error(FT_E_INVALID, "no field '%s' in layer %s (fields: %s)", field, l->name ? l->name : "",
                    l->nfields ? names : "none");
}

/* Cuts the sorted features into classes. */
static int make_classes(const keyed *k, size_t n, ft_field_type t, ft_urban_classes *c)
{
    for (size_t i = 0; i < n;) {
        size_t j = i + 1;
        while (j < n && cmp_value(k[i].v, k[j].v, t) == 0)
            j++;
        ft_urban_class *cl = &c->classes[c->n];
        cl->label = label_of(k[i].v, t);
        cl->features = ft_malloc((j - i) * sizeof *cl->features);
        c->n++;
        if (cl->label == NULL || cl->features == NULL)
            return FT_E_NOMEM;
        for (size_t m = i; m < j; m++)
            cl->features[cl->n++] = k[m].feature;
        i = j;
    }
    return FT_OK;
}

int ft_urban_classes_by_field(const ft_layer *l, const char *field, ft_urban_classes **out)
{
    if (out == NULL || l == NULL || field == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_classes_by_field: NULL %s",
                        out == NULL ? "out" : (l == NULL ? "layer" : "field"));
    *out = NULL;
    int fi = ft_layer_field_index(l, field);
    if (fi < 0)
        return field_error(l, field);
    const ft_field_type t = l->fields[fi].type;
    ft_urban_classes *c = ft_calloc(1, sizeof *c);
    keyed *k = ft_malloc((l->nfeatures ? l->nfeatures : 1) * sizeof *k);
    if (c != NULL)
        c->classes = ft_calloc(l->nfeatures ? l->nfeatures : 1, sizeof *c->classes);
    int rc = c != NULL && k != NULL && c->classes != NULL ? FT_OK : FT_E_NOMEM;
    size_t n = 0;
    for (size_t f = 0; rc == FT_OK && f < l->nfeatures; f++) {
        if (l->features[f].type != FT_GEOM_POLYGON)
            continue;
        const ft_value *v = &l->features[f].values[fi];
        if (v->is_null)
            c->nnull++;
        else
            k[n++] = (keyed){v, f, t};
    }
    if (rc == FT_OK) {
        qsort(k, n, sizeof *k, cmp_keyed);
        rc = make_classes(k, n, t, c);
    }
    free(k);
    if (rc != FT_OK) {
        ft_urban_classes_free(c);
        return rc;
    }
    *out = c;
    return FT_OK;
}
