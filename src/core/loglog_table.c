/* fracterra — core/loglog_table.c: the log-log table every estimator returns (scale, value, count,
 * local slope, used), its checks, and its view in log10 space for the segmentations of Arakawa &
 * Krotkov §2.4 ("plot the points in log-log space and identify linear segments").
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

ft_loglog *ft_loglog_create(size_t cap)
{
    ft_loglog *t = ft_calloc(1, sizeof *t);
    if (t == NULL)
        return NULL;
    if (cap > 0) {
        t->rows = ft_realloc_array(NULL, cap, sizeof *t->rows);
        if (t->rows == NULL) {
            free(t);
            return NULL;
        }
        t->cap = cap;
    }
    return t;
}

void ft_loglog_free(ft_loglog *t)
{
    if (t == NULL)
        return;
    free(t->rows);
    free(t);
}

ft_loglog *ft_loglog_copy(const ft_loglog *t)
{
    if (t == NULL) {
        ft_error(FT_E_INVALID, "log-log table: NULL table to copy");
        return NULL;
    }
    ft_loglog *c = ft_loglog_create(t->n);
    if (c == NULL)
        return NULL;
    if (t->n > 0)
        memcpy(c->rows, t->rows, t->n * sizeof *t->rows);
    c->n = t->n;
    return c;
}

/* Local slope at row i: centred difference between the neighbours, one-sided at the ends. */
static double local_slope(const ft_loglog *t, size_t i)
{
    if (t->n < 2)
        return NAN;
    size_t lo = i > 0 ? i - 1 : 0, hi = i + 1 < t->n ? i + 1 : i;
    double dx = log10(t->rows[hi].scale) - log10(t->rows[lo].scale);
    double dy = log10(t->rows[hi].value) - log10(t->rows[lo].value);
    return dy / dx;
}

void ft_loglog_update_slopes(ft_loglog *t)
{
    if (t == NULL)
        return;
    for (size_t i = 0; i < t->n; i++)
        t->rows[i].slope = local_slope(t, i);
}

/* Row-level checks shared by push and check; `row` is the index reported in messages. */
static int check_row(size_t row, double scale, double value, double count)
{
    if (!isfinite(scale))
        return ft_error(FT_E_NUMERIC, "log-log table: row %zu scale = %g is not finite", row, scale);
    if (!(scale > 0.0))
        return ft_error(FT_E_INVALID, "log-log table: row %zu scale = %g must be > 0", row, scale);
    if (!isfinite(value))
        return ft_error(FT_E_NUMERIC, "log-log table: row %zu value = %g is not finite", row, value);
    if (!(value > 0.0))
        return ft_error(FT_E_INVALID, "log-log table: row %zu value = %g must be > 0", row, value);
    if (!isfinite(count))
        return ft_error(FT_E_NUMERIC, "log-log table: row %zu count = %g is not finite", row, count);
    if (count < 0.0)
        return ft_error(FT_E_INVALID, "log-log table: row %zu count = %g must be >= 0", row, count);
    return FT_OK;
}

int ft_loglog_push(ft_loglog *t, double scale, double value, double count)
{
    if (t == NULL)
        return ft_error(FT_E_INVALID, "log-log table: NULL table");
    int rc = check_row(t->n, scale, value, count);
    if (rc != FT_OK)
        return rc;
    if (t->n == t->cap) {
        size_t cap = t->cap ? 2 * t->cap : 16;
        ft_loglog_row *rows = ft_realloc_array(t->rows, cap, sizeof *rows);
        if (rows == NULL)
            return FT_E_NOMEM;
        t->rows = rows;
        t->cap = cap;
    }
    t->rows[t->n++] = (ft_loglog_row){scale, value, count, NAN, 0};
    for (size_t i = t->n >= 2 ? t->n - 2 : 0; i < t->n; i++)
        t->rows[i].slope = local_slope(t, i);
    return FT_OK;
}

static int by_scale(const void *pa, const void *pb)
{
    double a = ((const ft_loglog_row *)pa)->scale, b = ((const ft_loglog_row *)pb)->scale;
    return (a > b) - (a < b);
}

int ft_loglog_sort(ft_loglog *t)
{
    if (t == NULL)
        return ft_error(FT_E_INVALID, "log-log table: NULL table");
    if (t->n > 1)
        qsort(t->rows, t->n, sizeof *t->rows, by_scale);
    ft_loglog_update_slopes(t);
    return FT_OK;
}

int ft_loglog_check(const ft_loglog *t)
{
    if (t == NULL)
        return ft_error(FT_E_INVALID, "log-log table: NULL table");
    if (t->n == 0)
        return ft_error(FT_E_EMPTY, "log-log table is empty");
    if (t->n < 2)
        return ft_error(FT_E_INVALID, "log-log table needs at least 2 rows, got 1");
    for (size_t i = 0; i < t->n; i++) {
        const ft_loglog_row *r = &t->rows[i];
        int rc = check_row(i, r->scale, r->value, r->count);
        if (rc != FT_OK)
            return rc;
        if (i > 0 && !(r->scale > t->rows[i - 1].scale))
            return ft_error(FT_E_INVALID,
                            "log-log table: row %zu scale %g is not greater than row %zu scale %g "
                            "(sort the table with ft_loglog_sort; scales must be distinct)",
                            i, r->scale, i - 1, t->rows[i - 1].scale);
    }
    return FT_OK;
}

static int check_map(const ft_dim_map *map)
{
    if (map == NULL)
        return ft_error(FT_E_INVALID, "log-log fit: no slope-to-D map given");
    if (!isfinite(map->a) || !isfinite(map->b))
        return ft_error(FT_E_INVALID, "log-log fit: map D = a + b*slope needs finite a and b, got a = %g, b = %g",
                        map->a, map->b);
    if (map->b == 0.0)
        return ft_error(FT_E_INVALID, "log-log fit: map D = a + b*slope needs b != 0, got b = 0");
    if (!isfinite(map->d_min) || !isfinite(map->d_max) ||
        (!(map->d_min < map->d_max) && !(map->d_min == 0.0 && map->d_max == 0.0)))
        return ft_error(FT_E_INVALID, "log-log fit: map bounds need d_min < d_max (0, 0 = none), got [%g, %g]",
                        map->d_min, map->d_max);
    return FT_OK;
}

/* Relative slack on scale limits, so that a limit equal to a computed scale (2^k times a cell size)
 * keeps that row whatever its last bits. */
#define LIMIT_SLACK 1e-9

/* The rows [*a, *b] with lo <= scale <= hi (0 = no limit); fails if fewer than min_rows. */
static int find_window(const ft_loglog *t, double lo, double hi, size_t min_rows, size_t *a, size_t *b)
{
    if (!isfinite(lo) || lo < 0.0)
        return ft_error(FT_E_INVALID, "log-log fit: lower scale limit must be >= 0 (0 = none), got %g", lo);
    if (!isfinite(hi) || hi < 0.0)
        return ft_error(FT_E_INVALID, "log-log fit: upper scale limit must be >= 0 (0 = none), got %g", hi);
    if (lo > 0.0 && hi > 0.0 && lo > hi)
        return ft_error(FT_E_INVALID, "log-log fit: lower scale limit %g is above upper scale limit %g", lo, hi);
    size_t first = t->n, last = 0, k = 0;
    for (size_t i = 0; i < t->n; i++) {
        double s = t->rows[i].scale;
        if ((lo > 0.0 && s < lo * (1.0 - LIMIT_SLACK)) || (hi > 0.0 && s > hi * (1.0 + LIMIT_SLACK)))
            continue;
        if (first == t->n)
            first = i;
        last = i;
        k++;
    }
    if (k < min_rows)
        return ft_error(FT_E_EMPTY, "log-log fit: %zu row(s) with scale in [%g, %g], at least %zu needed", k, lo,
                        hi > 0.0 ? hi : INFINITY, min_rows);
    *a = first;
    *b = last;
    return FT_OK;
}

int ft_ll_data_init(ft_ll_data *d, const ft_loglog *t, double lo, double hi, const ft_dim_map *map,
                    size_t min_rows)
{
    memset(d, 0, sizeof *d);
    int rc = ft_loglog_check(t);
    if (rc == FT_OK)
        rc = check_map(map);
    if (rc == FT_OK)
        rc = find_window(t, lo, hi, min_rows < 2 ? 2 : min_rows, &d->a, &d->b);
    if (rc != FT_OK)
        return rc;
    d->lx = ft_realloc_array(NULL, t->n, 2 * sizeof *d->lx);
    if (d->lx == NULL)
        return FT_E_NOMEM;
    d->ly = d->lx + t->n;
    d->work = ft_realloc_array(NULL, t->n, 2 * sizeof *d->work);
    if (d->work == NULL) {
        ft_ll_data_free(d);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < t->n; i++) {
        d->lx[i] = log10(t->rows[i].scale);
        d->ly[i] = log10(t->rows[i].value);
    }
    d->t = t;
    d->map = *map;
    return FT_OK;
}

void ft_ll_data_free(ft_ll_data *d)
{
    free(d->lx);
    free(d->work);
    d->lx = d->ly = NULL;
    d->work = NULL;
}
