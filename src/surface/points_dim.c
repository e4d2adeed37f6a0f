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

#define FLOOR_RATIO 1.0 /* the fit starts where the power law exceeds FLOOR_RATIO x what the noise adds */
#define XY_FLOOR 3.0    /* and above XY_FLOOR x a given position-noise sd */

/* The method's statistic without the counters' z-noise correction. */
static double raw_value(const ft_points_lag *l, ft_points_method m)
{
    if (m == FT_POINTS_YOKOYA)
        return l->A / l->C;
    double ss = l->B - l->A * l->A / l->C;
    return ss > 0.0 && l->C > 1.0 ? sqrt(ss / (l->C - 1.0)) : 0.0;
}

/* The noise model of the kept lags (nugget_positions.c): fitted to the mean squared differences. */
static int fit_model(const ft_points_counters *c, const ft_points_dim_opts *o, ft_noise_model *m)
{
    double *d = ft_malloc(2 * c->n * sizeof *d);
    if (d == NULL)
        return FT_E_NOMEM;
    double *q = d + c->n;
    size_t n = 0;
    for (size_t k = 0; k < c->n; k++) {
        const ft_points_lag *l = &c->lags[k];
        if (l->status == FT_LAG_KEPT && l->B > 0.0 && (n == 0 || l->dist > d[n - 1])) {
            d[n] = l->dist;
            q[n++] = l->B / l->C;
        }
    }
    int rc = ft_nugget_fit_positions(d, q, n, o->noise_sigma, o->noise_sigma_xy, m);
    free(d);
    return rc;
}

/* The table with the noise removed. Position noise (s > 0): each kept lag's observed mean Δz² less the
 * modelled noise (model minus power law; exact in expectation, where a ratio on |Δz| would carry the Jensen
 * gap of the mixture over true distances), as the method's statistic of a Gaussian difference of that
 * variance: E|X| = sqrt(2/π v), sd|X| = sqrt((1 - 2/π) v). With deconvolve (z noise alone, s = 0) the
 * observed statistic itself is deconvolved instead: for a Gaussian increment X and independent noise N of
 * variance c0, E|X + N|² = (2/π)(var X + c0), so E|X|² = E|X + N|² - (2/π) c0 (sd|X|²: (1 - 2/π) c0), which
 * tends to the plain statistic as c0 -> 0; going through mean Δz² replaces the realization's own
 * |Δz|-to-rms ratio by the Gaussian one, +0.012 in D at D = 2.1 (docs/surface-noise.md). And the floor. */
static int corrected_table(const ft_points_counters *c, const ft_points_dim_opts *o, int deconvolve,
                           ft_noise_model *m, ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create(c->n);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    double floor = 0.0, gauss = o->method == FT_POINTS_YOKOYA ? 2.0 / M_PI : 1.0 - 2.0 / M_PI;
    for (size_t k = 0; k < c->n && rc == FT_OK; k++) {
        const ft_points_lag *l = &c->lags[k];
        double v = l->C > 0.0 ? raw_value(l, o->method) : 0.0;
        if (l->status != FT_LAG_KEPT && !(l->status == FT_LAG_NOISE && v > 0.0))
            continue;
        double signal = m->a * pow(l->dist, 2.0 * m->H), total = ft_nugget_model_value(m, l->dist);
        double clean = deconvolve ? v * v - gauss * m->c0 /* the noise-free square of the statistic */
                                  : gauss * (l->B / l->C - (total - signal)); /* mean Δz² less the noise */
        if (!(v > 0.0) || !(signal > 0.0) || !(total > 0.0) || !(clean > 0.0))
            continue;
        if (signal < FLOOR_RATIO * (total - signal))
            floor = l->dist * (1.0 + 1e-9);
        rc = ft_loglog_push(t, l->dist, sqrt(clean), l->C);
    }
    if (rc == FT_OK)
        rc = ft_loglog_sort(t);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    m->floor = fmax(floor, XY_FLOOR * o->noise_sigma_xy);
    m->applied = 1;
    *out = t;
    return FT_OK;
}

static int fit_plain(const ft_loglog *t, const ft_points_dim_opts *o, double lo, ft_dim_result **out)
{
    ft_dim_map map = FT_DIM_MAP_INCREMENT_SURFACE;
    int rc = o->fit_auto ? ft_loglog_fit_auto(t, lo, 0.0, &o->fit, &map, out)
                         : ft_loglog_fit_range(t, lo, 0.0, &map, out);
    if (rc == FT_OK && !o->fit_auto && (*out)->table->n >= 2) {
        /* The minimax segments are reported with the whole-range fit too (--segments). */
        ft_dim_result *r = *out;
        rc = ft_loglog_segment_minimax(r->table, &o->fit, &map, &r->segments, &r->nsegments);
        for (size_t k = 0; rc == FT_OK && k < r->nsegments; k++)
            if (r->segments[k].first == r->fit.first && r->segments[k].last == r->fit.last)
                r->best = k;
        if (rc != FT_OK) {
            ft_dim_result_free(r);
            *out = NULL;
        }
    }
    return rc;
}

/* Z noise alone within these lags: the model keeps no position noise (s = 0, none given) and at least
 * ZONLY_ROWS kept lags lie where the power law exceeds the nugget. Such noise is removed on the lags
 * themselves (deconvolved from the statistic) and the default lags are not extended: over 32 spacings one
 * smooth realization's own bend passes for position noise (the extended model kept s on 37 of 100 z-only
 * surfaces at D = 2.1, 30 dB, σ_z then found 0-2 for 4.7) and moved D by +0.03. */
#define ZONLY_ROWS 6
static int z_noise_alone(const ft_points_counters *c, const ft_points_dim_opts *o, const ft_noise_model *m)
{
    if (!m->detected || m->s != 0.0 || !(m->c0 > 0.0) || o->noise_sigma_xy > 0.0)
        return 0;
    size_t above = 0, need = o->fit.min_points > ZONLY_ROWS ? o->fit.min_points : ZONLY_ROWS;
    for (size_t k = 0; k < c->n; k++) {
        const ft_points_lag *l = &c->lags[k];
        above += l->status == FT_LAG_KEPT && l->B > 0.0 && m->a * pow(l->dist, 2.0 * m->H) >= FLOOR_RATIO * m->c0;
    }
    return above >= need;
}

/* The fit with the noise model: noise on x, y and z detected (or given) in the mean squared differences,
 * removed from the statistic, the fit from the floor up; what was done in the warnings. pre: the model
 * already fitted to these counters (NULL: fitted here); own_lags: the model was fitted on the lags the
 * user or the defaults asked for (not an extension), and z noise alone (s = 0) is then deconvolved from
 * the statistic (corrected_table). */
static int fit_points(const ft_points_counters *c, const ft_loglog *t, const ft_points_dim_opts *o,
                      const ft_noise_model *pre, int own_lags, ft_dim_result **out)
{
    ft_noise_model m = {0};
    if (pre != NULL)
        m = *pre;
    if (o->noise_mode < 0 || (pre == NULL && fit_model(c, o, &m) != FT_OK) || !m.detected) {
        int rc = fit_plain(t, o, 0.0, out);
        if (rc == FT_OK)
            (*out)->nugget = m;
        return rc;
    }
    ft_loglog *ct = NULL;
    int deconvolve = own_lags && z_noise_alone(c, o, &m);
    int rc = corrected_table(c, o, deconvolve, &m, &ct);
    if (rc != FT_OK)
        return rc;
    size_t need = o->fit.min_points > 3 ? o->fit.min_points : 3, above = 0;
    for (size_t i = 0; i < ct->n; i++)
        above += ct->rows[i].scale >= m.floor;
    double lo = m.floor;
    if (ct->n < 2)
        rc = ft_error(FT_E_NUMERIC, "scattered points: the noise (sd %g on z, %g on x and y) exceeds the "
                      "elevation differences at every lag; use larger lags", m.sigma_z, m.sigma_xy);
    else if (above < need)
        lo = ct->rows[ct->n >= need ? ct->n - need : 0].scale;
    if (rc == FT_OK)
        rc = fit_plain(ct, o, lo, out);
    if (rc == FT_OK) {
        ft_dim_result *r = *out;
        r->nugget = m;
        int given = o->noise_sigma > 0.0 || o->noise_sigma_xy > 0.0;
        rc = ft_dim_result_warn(r, "noise %s: the log-log plot flattens toward the small lags; noise sd %.4g on z "
                                "and %.4g on x and y (%s); the noise terms were removed from the statistic "
                                "(F = %.3g%s) and the fit starts at lag %g, where the power law exceeds them",
                                given ? "model" : "detected", m.sigma_z, m.sigma_xy,
                                given ? "given or fitted" : "fitted", m.F,
                                deconvolve ? "; z noise alone, deconvolved from the statistic" : "", lo);
        if (rc == FT_OK && above < need)
            rc = ft_dim_result_warn(r, "noise dominates up to lag %g: only the %zu largest lags are fitted; use "
                                    "larger lags", m.floor, need);
        if (rc != FT_OK) {
            ft_dim_result_free(r);
            *out = NULL;
        }
    }
    ft_loglog_free(ct);
    return rc;
}

/* Counters and their table for the options o. */
static int count(const ft_points *p, const ft_points_dim_opts *o, ft_points_counters **c, ft_loglog **t)
{
    *t = NULL;
    int rc = ft_surface_points_counters(p, o, c);
    size_t need = o->fit.min_points > 2 ? o->fit.min_points : 2;
    if (rc == FT_OK && (*c)->kept < need) {
        char list[2048];
        list_dropped(*c, list, sizeof list);
        rc = ft_error(FT_E_EMPTY, "scattered points: too few lags: %zu of %zu kept, %zu needed; dropped lags: %s "
                      "(min_pairs %zu, eps %g; lower the pair threshold, widen eps or use larger lags)",
                      (*c)->kept, (*c)->n, need, list, (*c)->min_pairs, (*c)->eps);
    }
    if (rc == FT_OK)
        rc = build_table(*c, t);
    return rc;
}

/* Least-squares slope of log value on log scale over the whole table (NaN with fewer than 2 rows). */
static double table_slope(const ft_loglog *t)
{
    double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (size_t i = 0; i < t->n; i++) {
        double x = log(t->rows[i].scale), y = log(t->rows[i].value);
        n += 1.0;
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    double det = n * sxx - sx * sx;
    return n >= 2.0 && det > 0.0 ? (n * sxy - sx * sy) / det : NAN;
}

/* Default lags and a nugget (or a position-noise floor) near the top of their range: the lags extended
 * to EXTEND_LAG x the mean spacing, at most a quarter of the bounding box's shorter side. Returns the new
 * largest lag, or 0 to keep the counters. A default-lag plot flatter than H = FLAT_H (its least-squares
 * slope) extends them too: noise covering every default lag (position noise wider than the largest) looks
 * like that, and a nugget model fitted to it can put all of it in c0 and miss the test. */
#define EXTEND_LAG 32.0
#define FLAT_H 0.15
static double extended_max_lag(const ft_points *p, const ft_points_dim_opts *o, const ft_points_counters *c,
                               const ft_loglog *t, ft_noise_model *m, int *fitted)
{
    *fitted = 0;
    if (o->noise_mode < 0 || o->lags != NULL || o->max_lag > 0.0)
        return 0.0;
    double top = c->lags[c->n - 1].lag;
    if (!(3.0 * o->noise_sigma_xy * 4.0 > top || table_slope(t) < FLAT_H)) {
        if (fit_model(c, o, m) != FT_OK || !(m->detected || m->H < FLAT_H))
            return 0.0;
        *fitted = 1; /* the model of the default lags, reused when they are kept */
        if (z_noise_alone(c, o, m))
            return 0.0;
    }
    /* the bounding box only once the extension is wanted: a pass over every point */
    double x0, y0, x1, y1;
    ft_points_bbox(p, &x0, &y0, &x1, &y1);
    double cap = 0.25 * fmin(x1 - x0, y1 - y0), hi = fmin(EXTEND_LAG * c->spacing, cap);
    return hi > 2.0 * top ? hi : 0.0;
}

/* The default lags are kept (returns 1) when the model fitted to the extended ones finds no noise there:
 * the extension only serves the noise fit. */
static int keep_default_lags(const ft_points_counters *ext, const ft_points_dim_opts *o)
{
    ft_noise_model m;
    return fit_model(ext, o, &m) != FT_OK || !m.detected;
}

int ft_surface_dim_points(const ft_points *p, const ft_points_dim_opts *opts, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "scattered points: output pointer is NULL");
    *out = NULL;
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_points_dim_opts) != FT_OK)
        return FT_E_INVALID;
    if (o.counters != NULL)
        *o.counters = NULL;
    if (!(o.noise_sigma_xy >= 0.0) || !isfinite(o.noise_sigma_xy))
        return ft_error(FT_E_INVALID, "scattered points: noise_sigma_xy must be >= 0, got %g", o.noise_sigma_xy);
    if (o.noise_mode != 0 && o.noise_mode != -1)
        return ft_error(FT_E_INVALID, "scattered points: noise_mode must be 0 or -1, got %d", o.noise_mode);
    ft_points_counters *c = NULL;
    ft_loglog *t = NULL;
    int rc = count(p, &o, &c, &t);
    ft_noise_model m_default = {0};
    int fitted = 0;
    double ext = rc == FT_OK ? extended_max_lag(p, &o, c, t, &m_default, &fitted) : 0.0;
    if (ext > 0.0) {
        ft_points_dim_opts o2 = o;
        o2.min_lag = o.min_lag > 0.0 ? o.min_lag : c->lags[0].lag;
        o2.max_lag = ext;
        ft_points_counters *c2 = NULL;
        ft_loglog *t2 = NULL;
        rc = count(p, &o2, &c2, &t2);
        if (rc == FT_OK && keep_default_lags(c2, &o)) {
            ext = 0.0;
            ft_points_counters_free(c2);
            ft_loglog_free(t2);
        } else {
            ft_points_counters_free(c);
            ft_loglog_free(t);
            c = c2;
            t = t2;
        }
    }
    if (rc == FT_OK)
        rc = fit_points(c, t, &o, ext > 0.0 || !fitted ? NULL : &m_default, ext == 0.0, out);
    if (rc == FT_OK && ext > 0.0)
        rc = ft_dim_result_warn(*out, "noise model: the default lags (to %g x the mean spacing) were extended to "
                                "%g (%g x the spacing %g) to fit past the noise", 4.0, ext, ext / c->spacing,
                                c->spacing);
    if (rc == FT_OK) {
        (*out)->method = ft_points_method_name(o.method);
        if (c->sample > 0)
            c->D_sample_se = sample_se(c, *out);
        rc = ft_progress(o.progress, o.progress_arg, 1.0, "dim points");
    }
    if (rc != FT_OK) {
        ft_dim_result_free(*out);
        *out = NULL;
    }
    if (rc == FT_OK && o.counters != NULL) {
        *o.counters = c;
        c = NULL;
    }
    ft_points_counters_free(c);
    ft_loglog_free(t);
    return rc;
}
