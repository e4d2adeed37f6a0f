/* fracterra — surface/points_dim.c: the fractal dimension of scattered elevations, Arakawa & Krotkov §2.4
 * steps 2 and 3: the kept lags' statistic (Yokoya's E_Δd or Pentland's S_Δd, points_counters.c) against
 * the mean separation of their pairs in log-log space, a straight line through them, D = 3 - H with H the
 * slope (§2.3: E|Δz| and the standard deviation of |Δz| both grow as d^H; FT_DIM_MAP_INCREMENT_SURFACE).
 *
 * The table's scale is the mean separation of the pairs counted on a lag, not the nominal Δd_i: when the
 * pairs do not spread evenly over the annulus (points on a lattice have only the separations
 * sqrt(i² + j²) cells), the nominal lag misplaces the row by up to ε. By default D comes from least
 * squares over every kept lag (the range, chosen from the Table 1 experiment, is the lag range:
 * docs/surface-points.md); fit_auto uses the shared segmentation instead. In sample mode the standard
 * error of D from the sampling is the least-squares slope's sensitivity to each row's standard error.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "internal.h"
#include "points_internal.h"

/* "0.5 (12 pairs), 0.7 (40 pairs)" for the lags that are not kept, into buf. */
static void list_dropped(const ft_points_counters *c, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (size_t k = 0; k < c->n && used + 1 < size; k++) {
        const ft_points_lag *l = &c->lags[k];
        if (l->status == FT_LAG_KEPT)
            continue;
        const char *sep = used ? ", " : "";
        int w = l->status == FT_LAG_NOISE  ? snprintf(buf + used, size - used, "%s%g (noise exceeds it)", sep, l->lag)
                : l->status == FT_LAG_ZERO ? snprintf(buf + used, size - used, "%s%g (no difference)", sep, l->lag)
                : c->sample ? snprintf(buf + used, size - used, "%s%g (%llu drawn pairs)", sep, l->lag,
                                       (unsigned long long)l->drawn)
                            : snprintf(buf + used, size - used, "%s%g (%.0f pairs)", sep, l->lag, l->C);
        if (w < 0)
            break;
        used += (size_t)w < size - used ? (size_t)w : size - used - 1;
    }
}

static int build_table(const ft_points_counters *c, ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create(c->n);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t k = 0; k < c->n && rc == FT_OK; k++)
        if (c->lags[k].status == FT_LAG_KEPT)
            rc = ft_loglog_push(t, c->lags[k].dist, c->lags[k].value, c->lags[k].C);
    if (rc == FT_OK)
        rc = ft_loglog_sort(t);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

/* Sampling standard error of D: slope = Σ w_k y_k over the used rows, y_k = log10 value_k, with
 * var y_k = (se_k / (value_k ln 10))² and the rows independent (disjoint draws). */
static double sample_se(const ft_points_counters *c, const ft_dim_result *r)
{
    const ft_loglog *t = r->table;
    double sx = 0.0, n = 0.0;
    for (size_t i = 0; i < t->n; i++)
        if (t->rows[i].used) {
            sx += log10(t->rows[i].scale);
            n += 1.0;
        }
    double mx = sx / n, sxx = 0.0, var = 0.0;
    for (size_t i = 0; i < t->n; i++)
        if (t->rows[i].used)
            sxx += pow(log10(t->rows[i].scale) - mx, 2.0);
    for (size_t i = 0; i < t->n; i++) {
        if (!t->rows[i].used)
            continue;
        for (size_t k = 0; k < c->n; k++)
            if (c->lags[k].status == FT_LAG_KEPT && c->lags[k].dist == t->rows[i].scale) {
                double w = (log10(t->rows[i].scale) - mx) / sxx;
                double sy = c->lags[k].value_se / (c->lags[k].value * M_LN10);
                var += w * w * sy * sy;
                break;
            }
    }
    return fabs(r->map.b) * sqrt(var);
}

int ft_surface_dim_points(const ft_points *p, const ft_points_dim_opts *opts, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "scattered points: output pointer is NULL");
    *out = NULL;
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    if (opts != NULL)
        o = *opts;
    if (o.counters != NULL)
        *o.counters = NULL;
    ft_points_counters *c = NULL;
    ft_loglog *t = NULL;
    int rc = ft_surface_points_counters(p, &o, &c);
    size_t need = o.fit.min_points > 2 ? o.fit.min_points : 2;
    if (rc == FT_OK && c->kept < need) {
        char list[2048];
        list_dropped(c, list, sizeof list);
        rc = ft_error(FT_E_EMPTY, "scattered points: too few lags: %zu of %zu kept, %zu needed; dropped lags: %s "
                      "(min_pairs %zu, eps %g; lower the pair threshold, widen eps or use larger lags)",
                      c->kept, c->n, need, list, c->min_pairs, c->eps);
    }
    if (rc == FT_OK)
        rc = build_table(c, &t);
    ft_dim_map map = FT_DIM_MAP_INCREMENT_SURFACE;
    if (rc == FT_OK)
        rc = o.fit_auto ? ft_loglog_fit_auto(t, 0.0, 0.0, &o.fit, &map, out)
                        : ft_loglog_fit_range(t, 0.0, 0.0, &map, out);
    if (rc == FT_OK && !o.fit_auto && t->n >= 2) {
        /* The minimax segments are reported with the whole-range fit too (--segments). */
        ft_dim_result *r = *out;
        rc = ft_loglog_segment_minimax(t, &o.fit, &map, &r->segments, &r->nsegments);
        for (size_t k = 0; rc == FT_OK && k < r->nsegments; k++)
            if (r->segments[k].first == r->fit.first && r->segments[k].last == r->fit.last)
                r->best = k;
        if (rc != FT_OK) {
            ft_dim_result_free(r);
            *out = NULL;
        }
    }
    if (rc == FT_OK) {
        (*out)->method = ft_points_method_name(o.method);
        if (c->sample > 0)
            c->D_sample_se = sample_se(c, *out);
        rc = ft_progress(o.progress, o.progress_arg, 1.0, "dim points");
        if (rc != FT_OK) {
            ft_dim_result_free(*out);
            *out = NULL;
        }
    }
    if (rc == FT_OK && o.counters != NULL) {
        *o.counters = c;
        c = NULL;
    }
    ft_points_counters_free(c);
    ft_loglog_free(t);
    return rc;
}
