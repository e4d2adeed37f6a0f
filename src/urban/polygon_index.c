/* fracterra — src/urban/polygon_index.c: an index of the polygons of a land-use layer (or of one class of
 * it) that the box counter and the class statistics measure (Zhang, Yu & Fan 2008, §1.2: residential,
 * industrial, vegetation and water layers as polygons). Not a polygon model of its own: the polygons are
 * the layer's (ft_layer parts: an outer ring followed by its inner rings with the same polygon index,
 * core.h); the index borrows their rings, copies nothing, and groups them by polygon so that the interior
 * of each polygon is decided by the even-odd rule over its own rings (docs/architecture.md, "Polygons").
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>

#include "internal.h"
#include "urban/urban_internal.h"

void ft_polygon_index_clear(ft_polygon_index *s)
{
    free(s->rings);
    free(s->inner);
    free(s->poly_first);
    *s = (ft_polygon_index){0};
}

static int check_feature(const ft_layer *l, size_t f, int strict, int *use)
{
    *use = 0;
    if (f >= l->nfeatures)
        return ft_error(FT_E_INVALID, "feature index %zu is out of range (the layer has %zu features)", f,
                        l->nfeatures);
    const ft_feature *ft = &l->features[f];
    if (ft->type == FT_GEOM_LINE && strict)
        return ft_error(FT_E_INVALID, "feature %" PRId64 " is a line, not a polygon", ft->fid);
    if (ft->type != FT_GEOM_POLYGON)
        return FT_OK;
    for (size_t p = ft->first; p < ft->first + ft->count; p++) {
        const ft_chain *c = l->parts[p].chain;
        if (c == NULL)
            continue;
        if (ft_chain_check_finite(c) != FT_OK) {
            char msg[256];
            snprintf(msg, sizeof msg, "%s", ft_last_error());
            return ft_error(FT_E_NUMERIC, "feature %" PRId64 ", part %zu: %s", ft->fid, p - ft->first, msg);
        }
    }
    *use = 1;
    return FT_OK;
}

static void add_feature(const ft_layer *l, size_t f, ft_polygon_index *s)
{
    const ft_feature *ft = &l->features[f];
    int last_polygon = -1;
    for (size_t p = ft->first; p < ft->first + ft->count; p++) {
        const ft_part *part = &l->parts[p];
        if (part->chain == NULL || part->chain->n == 0 || part->role == FT_ROLE_LINE)
            continue;
        if (part->polygon != last_polygon || part->role == FT_ROLE_OUTER)
            s->poly_first[s->npolys++] = s->nrings;
        last_polygon = part->polygon;
        s->inner[s->nrings] = part->role == FT_ROLE_INNER;
        s->rings[s->nrings++] = part->chain;
    }
    s->nfeatures++;
}

int ft_polygon_index_collect(const ft_layer *l, const size_t *features, size_t nfeatures, int strict, ft_polygon_index *s)
{
    *s = (ft_polygon_index){0};
    if (l == NULL)
        return ft_error(FT_E_INVALID, "polygons: NULL layer");
    size_t nf = features != NULL ? nfeatures : l->nfeatures, cap = 0;
    for (size_t i = 0; i < nf; i++) { /* checks, and room for the parts (a feature may be listed twice) */
        size_t f = features != NULL ? features[i] : i;
        int use = 0;
        int rc = check_feature(l, f, strict, &use);
        if (rc != FT_OK)
            return rc;
        cap += use ? l->features[f].count : 0;
    }
    s->rings = ft_malloc((cap ? cap : 1) * sizeof *s->rings);
    s->inner = ft_malloc(cap ? cap : 1);
    s->poly_first = ft_malloc((cap + 1) * sizeof *s->poly_first);
    if (s->rings == NULL || s->inner == NULL || s->poly_first == NULL) {
        ft_polygon_index_clear(s);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < nf; i++) {
        size_t f = features != NULL ? features[i] : i;
        if (l->features[f].type == FT_GEOM_POLYGON)
            add_feature(l, f, s);
    }
    s->poly_first[s->npolys] = s->nrings;
    return FT_OK;
}
