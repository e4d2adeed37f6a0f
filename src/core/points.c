/* fracterra — core/points.c: scattered (x, y, z) points with optional weights (ft_points).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Grows every coordinate array (and the weights if present) to cap; on failure the arrays that did
 * grow keep spare room and p->cap is unchanged. */
static int points_reserve(ft_points *p, size_t cap)
{
    if (cap <= p->cap)
        return FT_OK;
    double **arrays[4] = {&p->x, &p->y, &p->z, &p->w};
    for (int k = 0; k < 4; k++) {
        if (k == 3 && p->w == NULL)
            break;
        double *a = ft_realloc_array(*arrays[k], cap, sizeof *a);
        if (a == NULL)
            return FT_E_NOMEM;
        *arrays[k] = a;
    }
    p->cap = cap;
    return FT_OK;
}

ft_points *ft_points_create(size_t cap)
{
    ft_points *p = ft_calloc(1, sizeof *p);
    if (p == NULL)
        return NULL;
    if (points_reserve(p, cap) != FT_OK) {
        ft_points_free(p);
        return NULL;
    }
    return p;
}

ft_points *ft_points_copy(const ft_points *p)
{
    if (p == NULL) {
        ft_error(FT_E_INVALID, "ft_points_copy: NULL points");
        return NULL;
    }
    ft_points *d = ft_points_create(p->n);
    if (d == NULL)
        return NULL;
    if (p->w != NULL && ft_points_ensure_weights(d) != FT_OK)
        goto fail;
    if (p->n > 0) {
        memcpy(d->x, p->x, p->n * sizeof *d->x);
        memcpy(d->y, p->y, p->n * sizeof *d->y);
        memcpy(d->z, p->z, p->n * sizeof *d->z);
        if (p->w != NULL)
            memcpy(d->w, p->w, p->n * sizeof *d->w);
    }
    d->n = p->n;
    if (p->crs_wkt != NULL && (d->crs_wkt = ft_strdup(p->crs_wkt)) == NULL)
        goto fail;
    return d;
fail:
    ft_points_free(d);
    return NULL;
}

void ft_points_free(ft_points *p)
{
    if (p == NULL)
        return;
    free(p->x);
    free(p->y);
    free(p->z);
    free(p->w);
    free(p->crs_wkt);
    free(p);
}

/* A pushed point gets weight 1 when weights are present. */
int ft_points_push(ft_points *p, double x, double y, double z)
{
    if (p == NULL)
        return ft_error(FT_E_INVALID, "ft_points_push: NULL points");
    if (p->n == p->cap) {
        size_t cap = p->cap < 16 ? 16 : p->cap + p->cap / 2;
        if (cap <= p->cap)
            return ft_error(FT_E_NOMEM, "point capacity overflows at %zu points", p->cap);
        int rc = points_reserve(p, cap);
        if (rc != FT_OK)
            return rc;
    }
    p->x[p->n] = x;
    p->y[p->n] = y;
    p->z[p->n] = z;
    if (p->w != NULL)
        p->w[p->n] = 1.0;
    p->n++;
    return FT_OK;
}

int ft_points_ensure_weights(ft_points *p)
{
    if (p == NULL)
        return ft_error(FT_E_INVALID, "ft_points_ensure_weights: NULL points");
    if (p->w != NULL)
        return FT_OK;
    p->w = ft_malloc((p->cap ? p->cap : 1) * sizeof *p->w);
    if (p->w == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < p->cap; i++)
        p->w[i] = 1.0;
    return FT_OK;
}

int ft_points_bbox(const ft_points *p, double *xmin, double *ymin, double *xmax, double *ymax)
{
    if (p == NULL || p->n == 0)
        return ft_error(FT_E_EMPTY, "bounding box of an empty point set");
    double x0 = p->x[0], x1 = p->x[0], y0 = p->y[0], y1 = p->y[0];
    for (size_t i = 1; i < p->n; i++) {
        x0 = fmin(x0, p->x[i]);
        x1 = fmax(x1, p->x[i]);
        y0 = fmin(y0, p->y[i]);
        y1 = fmax(y1, p->y[i]);
    }
    if (xmin) *xmin = x0;
    if (ymin) *ymin = y0;
    if (xmax) *xmax = x1;
    if (ymax) *ymax = y1;
    return FT_OK;
}

int ft_points_set_crs(ft_points *p, const char *wkt)
{
    if (p == NULL)
        return ft_error(FT_E_INVALID, "ft_points_set_crs: NULL points");
    char *copy = NULL;
    if (wkt != NULL && (copy = ft_strdup(wkt)) == NULL)
        return FT_E_NOMEM;
    free(p->crs_wkt);
    p->crs_wkt = copy;
    return FT_OK;
}
