/* fracterra — core/chain.c: polylines and rings (ft_chain): creation, growth, length, area, checks.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

ft_chain *ft_chain_create(size_t cap, int closed)
{
    ft_chain *c = ft_calloc(1, sizeof *c);
    if (c == NULL)
        return NULL;
    c->closed = closed ? 1 : 0;
    if (cap > 0 && ft_chain_reserve(c, cap) != FT_OK) {
        free(c);
        return NULL;
    }
    return c;
}

ft_chain *ft_chain_from_arrays(const double *x, const double *y, size_t n, size_t stride, int closed)
{
    if (n > 0 && (x == NULL || y == NULL)) {
        ft_error(FT_E_INVALID, "ft_chain_from_arrays: NULL coordinate array for %zu vertices", n);
        return NULL;
    }
    if (stride == 0) {
        ft_error(FT_E_INVALID, "ft_chain_from_arrays: stride must be >= 1, got 0");
        return NULL;
    }
    if (n > 0 && n - 1 > SIZE_MAX / stride) {
        ft_error(FT_E_INVALID, "ft_chain_from_arrays: %zu vertices with stride %zu overflow", n, stride);
        return NULL;
    }
    ft_chain *c = ft_chain_create(n, closed);
    if (c == NULL)
        return NULL;
    for (size_t i = 0; i < n; i++) {
        c->x[i] = x[i * stride];
        c->y[i] = y[i * stride];
    }
    c->n = n;
    return c;
}

ft_chain *ft_chain_copy(const ft_chain *c)
{
    if (c == NULL) {
        ft_error(FT_E_INVALID, "ft_chain_copy: NULL chain");
        return NULL;
    }
    ft_chain *d = ft_chain_create(c->n, c->closed);
    if (d == NULL)
        return NULL;
    if (c->n > 0) {
        memcpy(d->x, c->x, c->n * sizeof *d->x);
        memcpy(d->y, c->y, c->n * sizeof *d->y);
    }
    d->n = c->n;
    return d;
}

void ft_chain_free(ft_chain *c)
{
    if (c == NULL)
        return;
    free(c->x);
    free(c->y);
    free(c);
}

/* On failure the chain keeps its old capacity (an array that did grow simply has spare room). */
int ft_chain_reserve(ft_chain *c, size_t cap)
{
    if (c == NULL)
        return ft_error(FT_E_INVALID, "ft_chain_reserve: NULL chain");
    if (cap <= c->cap)
        return FT_OK;
    double *nx = ft_realloc_array(c->x, cap, sizeof *nx);
    if (nx == NULL)
        return FT_E_NOMEM;
    c->x = nx;
    double *ny = ft_realloc_array(c->y, cap, sizeof *ny);
    if (ny == NULL)
        return FT_E_NOMEM;
    c->y = ny;
    c->cap = cap;
    return FT_OK;
}

int ft_chain_push(ft_chain *c, double x, double y)
{
    if (c == NULL)
        return ft_error(FT_E_INVALID, "ft_chain_push: NULL chain");
    if (c->n == c->cap) {
        size_t cap = c->cap < 8 ? 8 : c->cap + c->cap / 2;
        if (cap <= c->cap)
            return ft_error(FT_E_NOMEM, "chain capacity overflows at %zu vertices", c->cap);
        int rc = ft_chain_reserve(c, cap);
        if (rc != FT_OK)
            return rc;
    }
    c->x[c->n] = x;
    c->y[c->n] = y;
    c->n++;
    return FT_OK;
}

void ft_chain_reverse(ft_chain *c)
{
    if (c == NULL || c->n < 2)
        return;
    for (size_t i = 0, j = c->n - 1; i < j; i++, j--) {
        double t = c->x[i];
        c->x[i] = c->x[j];
        c->x[j] = t;
        t = c->y[i];
        c->y[i] = c->y[j];
        c->y[j] = t;
    }
}

size_t ft_chain_segments(const ft_chain *c)
{
    if (c == NULL || c->n < 2)
        return 0;
    return c->closed ? c->n : c->n - 1;
}

double ft_chain_length(const ft_chain *c)
{
    size_t nseg = ft_chain_segments(c);
    double len = 0.0;
    for (size_t i = 0; i < nseg; i++) {
        size_t j = (i + 1 == c->n) ? 0 : i + 1;
        len += hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
    }
    return len;
}

/* Shoelace formula on coordinates relative to the first vertex, which keeps precision far from the
 * origin (projected coordinates in the millions). */
double ft_chain_signed_area(const ft_chain *c)
{
    if (c == NULL || !c->closed || c->n < 3)
        return 0.0;
    double x0 = c->x[0], y0 = c->y[0], twice = 0.0;
    for (size_t i = 1; i + 1 < c->n; i++)
        twice += (c->x[i] - x0) * (c->y[i + 1] - y0) - (c->x[i + 1] - x0) * (c->y[i] - y0);
    return 0.5 * twice;
}

int ft_chain_bbox(const ft_chain *c, double *xmin, double *ymin, double *xmax, double *ymax)
{
    if (c == NULL || c->n == 0)
        return ft_error(FT_E_EMPTY, "bounding box of a chain without vertices");
    double x0 = c->x[0], x1 = c->x[0], y0 = c->y[0], y1 = c->y[0];
    for (size_t i = 1; i < c->n; i++) {
        x0 = fmin(x0, c->x[i]);
        x1 = fmax(x1, c->x[i]);
        y0 = fmin(y0, c->y[i]);
        y1 = fmax(y1, c->y[i]);
    }
    if (xmin) *xmin = x0;
    if (ymin) *ymin = y0;
    if (xmax) *xmax = x1;
    if (ymax) *ymax = y1;
    return FT_OK;
}

int ft_chain_check_finite(const ft_chain *c)
{
    if (c == NULL)
        return ft_error(FT_E_INVALID, "ft_chain_check_finite: NULL chain");
    for (size_t i = 0; i < c->n; i++)
        if (!isfinite(c->x[i]) || !isfinite(c->y[i]))
            return ft_error(FT_E_NUMERIC, "vertex %zu is not finite (x=%g, y=%g)", i, c->x[i], c->y[i]);
    return FT_OK;
}

int ft_chain_check_min_vertices(const ft_chain *c, size_t min_vertices)
{
    size_t n = c ? c->n : 0;
    if (n < min_vertices)
        return ft_error(FT_E_INVALID, "%s has %zu vertices, at least %zu needed",
                        c && c->closed ? "ring" : "chain", n, min_vertices);
    return FT_OK;
}
