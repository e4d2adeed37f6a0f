/* fracterra — surface/points_counters.c: Arakawa & Krotkov §2.4 step 1 for scattered elevations: the
 * lags Δd_i, the tolerance ε, the counters A_i = Σ|z - z'|, B_i = Σ(z - z')², C_i = pairs over every pair
 * with |d - Δd_i| <= ε (all pairs through the grid, all pairs i < j, or P random pairs), and per lag the
 * method's statistic (§2.3):
 *
 *   Yokoya   E_Δd = A_i / C_i                                  (the mean of |Δz|)
 *   Pentland S_Δd = sqrt((B_i - A_i² / C_i) / (C_i - 1))       (the sample standard deviation of |Δz|)
 *
 * with the noise model for independent N(0, σ²) noise on z (docs/surface-points.md): the observed
 * differences have E Δz² = v + 2σ² where v is the noise-free E Δz², and for Gaussian increments
 * E|Δz| = sqrt(2/π) sqrt(v + 2σ²), so  E_Δd² - 4σ²/π  and  S_Δd² - 2σ²(1 - 2/π)  are the noise-free
 * squares. A lag with fewer than min_pairs pairs (the paper's threshold), with no noise-free statistic left,
 * or with a zero statistic is kept in the counters with its status and left out of the table.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "internal.h"
#include "points_internal.h"

#define DEFAULT_MIN_LAG 0.5 /* x the mean spacing (docs/surface-points.md, "Defaults and evidence") */
#define DEFAULT_MAX_LAG 4.0
#define MAX_LAGS 1000

const char *ft_points_method_name(ft_points_method m)
{
    return m == FT_POINTS_PENTLAND ? "pentland" : "yokoya";
}

int ft_points_method_parse(const char *name, ft_points_method *m)
{
    if (name != NULL && strcasecmp(name, "yokoya") == 0)
        *m = FT_POINTS_YOKOYA;
    else if (name != NULL && strcasecmp(name, "pentland") == 0)
        *m = FT_POINTS_PENTLAND;
    else
        return ft_error(FT_E_INVALID, "method must be yokoya or pentland, got '%s'", name ? name : "(null)");
    return FT_OK;
}

void ft_points_counters_free(ft_points_counters *c)
{
    if (c == NULL)
        return;
    free(c->lags);
    free(c);
}

static int check_points(const ft_points *p, double *zrange, double *spacing)
{
    if (p == NULL || p->x == NULL || p->y == NULL || p->z == NULL)
        return ft_error(FT_E_INVALID, "scattered points: the points are NULL");
    if (p->n < 3)
        return ft_error(FT_E_EMPTY, "scattered points: needs at least 3 points, got %zu", p->n);
    for (size_t i = 0; i < p->n; i++) {
        const char *bad = !isfinite(p->x[i]) ? "x" : !isfinite(p->y[i]) ? "y" : !isfinite(p->z[i]) ? "z" : NULL;
        if (bad != NULL) {
            double v = bad[0] == 'x' ? p->x[i] : bad[0] == 'y' ? p->y[i] : p->z[i];
            return ft_error(FT_E_NUMERIC, "scattered points: point %zu has %s = %g, not a finite number", i + 1,
                            bad, v);
        }
    }
    double x0, y0, x1, y1, z0 = p->z[0], z1 = p->z[0];
    ft_points_bbox(p, &x0, &y0, &x1, &y1);
    for (size_t i = 1; i < p->n; i++) {
        z0 = fmin(z0, p->z[i]);
        z1 = fmax(z1, p->z[i]);
    }
    *zrange = z1 - z0;
    double w = x1 - x0, h = y1 - y0;
    if (!(w > 0.0) && !(h > 0.0))
        return ft_error(FT_E_INVALID, "scattered points: all %zu points are at the same position", p->n);
    /* Mean spacing: the side of the square each point would own in the bounding box (the box's length
     * per point if the points lie on a line parallel to an axis). */
    *spacing = w > 0.0 && h > 0.0 ? sqrt(w * h / (double)p->n) : (w + h) / (double)p->n;
    return FT_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The lags (malloc'd, increasing) and ε from the options. */
static int make_lags(const ft_points_dim_opts *o, double spacing, double **out, size_t *n, double *eps)
{
    double *lags = NULL;
    if (o->lags != NULL) {
        if (o->nuser_lags < 2 || o->nuser_lags > MAX_LAGS)
            return ft_error(FT_E_INVALID, "scattered points: needs 2 to %d lags, got %zu", MAX_LAGS, o->nuser_lags);
        *n = o->nuser_lags;
        if ((lags = ft_malloc(*n * sizeof *lags)) == NULL)
            return FT_E_NOMEM;
        for (size_t k = 0; k < *n; k++) {
            lags[k] = o->lags[k];
            if (!(lags[k] > 0.0) || !isfinite(lags[k])) {
                free(lags);
                return ft_error(FT_E_INVALID, "scattered points: lag %zu must be a positive distance, got %g", k + 1,
                                o->lags[k]);
            }
        }
        qsort(lags, *n, sizeof *lags, cmp_double);
        for (size_t k = 1; k < *n; k++)
            if (lags[k] == lags[k - 1]) {
                double twice = lags[k];
                free(lags);
                return ft_error(FT_E_INVALID, "scattered points: lag %g is given twice", twice);
            }
    } else {
        if (o->nlags != 0 && (o->nlags < 2 || o->nlags > MAX_LAGS))
            return ft_error(FT_E_INVALID, "scattered points: nlags must be 0 (automatic) or in [2, %d], got %d",
                            MAX_LAGS,
                            o->nlags);
        if (!(o->min_lag >= 0.0) || !isfinite(o->min_lag) || !(o->max_lag >= 0.0) || !isfinite(o->max_lag))
            return ft_error(FT_E_INVALID, "scattered points: min_lag and max_lag must be >= 0, got %g and %g",
                            o->min_lag,
                            o->max_lag);
        double lo = o->min_lag > 0.0 ? o->min_lag : DEFAULT_MIN_LAG * spacing;
        double hi = o->max_lag > 0.0 ? o->max_lag : DEFAULT_MAX_LAG * spacing;
        if (!(hi > lo))
            return ft_error(FT_E_INVALID, "scattered points: the largest lag (%g) must exceed the smallest (%g)", hi,
                            lo);
        *n = o->nlags > 0 ? (size_t)o->nlags : (size_t)(4.0 * ceil(log2(hi / lo) - 1e-9)) + 1;
        if (*n < 2)
            *n = 2;
        if ((lags = ft_malloc(*n * sizeof *lags)) == NULL)
            return FT_E_NOMEM;
        for (size_t k = 0; k < *n; k++)
            lags[k] = lo * pow(hi / lo, (double)k / (double)(*n - 1));
    }
    double gap = INFINITY;
    for (size_t k = 1; k < *n; k++)
        gap = fmin(gap, lags[k] - lags[k - 1]);
    *eps = o->eps > 0.0 ? o->eps : 0.5 * gap;
    if (!(o->eps >= 0.0) || !isfinite(o->eps) || !(*eps < lags[0])) {
        double smallest = lags[0];
        free(lags);
        return ft_error(FT_E_INVALID, "scattered points: eps must satisfy 0 < eps < the smallest lag (%g), got %g",
                        smallest,
                        o->eps);
    }
    *out = lags;
    return FT_OK;
}

static int check_opts(const ft_points_dim_opts *o)
{
    if (o->method != FT_POINTS_YOKOYA && o->method != FT_POINTS_PENTLAND)
        return ft_error(FT_E_INVALID, "scattered points: unknown method %d", (int)o->method);
    if (o->min_pairs < 1)
        return ft_error(FT_E_INVALID, "scattered points: min_pairs must be >= 1, got %zu", o->min_pairs);
    if (!(o->noise_sigma >= 0.0) || !isfinite(o->noise_sigma))
        return ft_error(FT_E_INVALID, "scattered points: noise_sigma must be >= 0, got %g", o->noise_sigma);
    if (o->exact && o->sample > 0)
        return ft_error(FT_E_INVALID, "scattered points: exact and sample (%zu pairs) exclude each other", o->sample);
    return FT_OK;
}

/* The statistic of the method from the means m1 = E|Δz|, m2 = E Δz² over n pairs, after the noise
 * model; *square receives the noise-free square (<= 0: nothing left). */
static double statistic(ft_points_method m, double m1, double m2, double n, double sigma, double *square)
{
    double s2 = sigma * sigma;
    if (m == FT_POINTS_YOKOYA)
        *square = m1 * m1 - 4.0 * s2 / M_PI;
    else
        *square = fmax(m2 - m1 * m1, 0.0) * n / (n - 1.0) - 2.0 * s2 * (1.0 - 2.0 / M_PI);
    return *square > 0.0 ? sqrt(*square) : 0.0;
}

static void set_status(ft_points_lag *l, const ft_points_dim_opts *o, double count, double value, double square)
{
    if (count < (double)o->min_pairs || count < 2.0)
        l->status = FT_LAG_FEW_PAIRS;
    else if (o->noise_sigma > 0.0 && !(square > 0.0))
        l->status = FT_LAG_NOISE;
    else if (!(value > 0.0))
        l->status = FT_LAG_ZERO;
    else
        l->status = FT_LAG_KEPT;
    l->value = l->status == FT_LAG_NOISE ? NAN : value;
}

static void from_sums(ft_points_counters *c, const pts_lags *L, const pts_acc *acc, const ft_points_dim_opts *o)
{
    for (size_t k = 0; k < L->n; k++) {
        ft_points_lag *l = &c->lags[k];
        l->lag = L->lag[k];
        l->C = (double)acc[k].c;
        l->drawn = acc[k].c;
        l->A = (double)acc[k].a / L->qa;
        l->B = (double)acc[k].b / L->qb;
        l->dist = acc[k].c ? (double)acc[k].s / L->qs / l->C : 0.0;
        double sq = 0.0, v = 0.0;
        if (l->C > 0.0)
            v = statistic(o->method, l->A / l->C, l->B / l->C, l->C, o->noise_sigma, &sq);
        set_status(l, o, l->C, v, sq);
    }
}

/* Sample mode: ratio estimates and their linearised standard errors (points_pairs_sample.c). */
static void from_weights(ft_points_counters *c, const pts_lags *L, const pts_wsum *ws, size_t npoints,
                         const ft_points_dim_opts *o)
{
    double scale = (double)npoints / (2.0 * (double)o->sample);
    for (size_t k = 0; k < L->n; k++) {
        ft_points_lag *l = &c->lags[k];
        const pts_wsum *s = &ws[k];
        l->lag = L->lag[k];
        l->drawn = s->drawn;
        l->A = scale * s->wa;
        l->B = scale * s->wa2;
        l->C = scale * s->w;
        l->dist = s->w > 0.0 ? s->wd / s->w : 0.0;
        double sq = 0.0, v = 0.0, se = 0.0;
        if (s->w > 0.0 && s->drawn >= 2) {
            double W = s->w, m1 = s->wa / W, m2 = s->wa2 / W, n = (double)s->drawn;
            const double *q = s->v;
            v = statistic(o->method, m1, m2, n, o->noise_sigma, &sq);
            if (o->method == FT_POINTS_YOKOYA) {
                double e2 = q[2] - 2.0 * m1 * q[1] + m1 * m1 * q[0];
                se = sqrt(fmax(e2, 0.0)) / W * (v > 0.0 ? m1 / v : 0.0);
            } else {
                double cc = 2.0 * m1 * m1 - m2;
                double e2 = q[4] - 4.0 * m1 * q[3] + (4.0 * m1 * m1 + 2.0 * cc) * q[2] - 4.0 * m1 * cc * q[1] +
                            cc * cc * q[0];
                se = v > 0.0 ? sqrt(fmax(e2, 0.0)) / W / (2.0 * v) : 0.0;
            }
        }
        set_status(l, o, (double)s->drawn, v, sq);
        l->value_se = se;
    }
}

int ft_surface_points_counters(const ft_points *p, const ft_points_dim_opts *opts, ft_points_counters **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "scattered points: output pointer is NULL");
    *out = NULL;
    ft_points_dim_opts o = FT_POINTS_DIM_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_points_dim_opts) != FT_OK)
        return FT_E_INVALID;
    double zrange = 0.0, spacing = 0.0, eps = 0.0, *lagv = NULL;
    size_t n = 0;
    int rc = check_opts(&o);
    if (rc == FT_OK)
        rc = check_points(p, &zrange, &spacing);
    if (rc == FT_OK)
        rc = make_lags(&o, spacing, &lagv, &n, &eps);
    if (rc != FT_OK)
        return rc;
    pts_lags L;
    rc = pts_lags_init(&L, lagv, n, eps, zrange);
    ft_points_counters *c = ft_calloc(1, sizeof *c);
    pts_acc *acc = ft_calloc(n, sizeof *acc);
    pts_wsum *ws = ft_calloc(n, sizeof *ws);
    if (c != NULL)
        c->lags = ft_calloc(n, sizeof *c->lags);
    if (rc == FT_OK && (c == NULL || c->lags == NULL || acc == NULL || ws == NULL))
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = ft_progress(o.progress, o.progress_arg, 0.0, "dim points");
    if (rc == FT_OK && o.sample > 0)
        rc = pts_pairs_sample(p, &L, o.sample, o.seed, ws, o.progress, o.progress_arg);
    else if (rc == FT_OK)
        rc = o.exact ? pts_pairs_exact(p, &L, acc, o.progress, o.progress_arg)
                     : pts_pairs_grid(p, &L, acc, o.progress, o.progress_arg);
    if (rc == FT_OK) {
        c->method = o.method;
        c->n = n;
        c->eps = eps;
        c->spacing = spacing;
        c->min_pairs = o.min_pairs;
        c->pairs = o.sample > 0 ? "sample" : o.exact ? "exact" : "grid";
        c->sample = o.sample;
        if (o.sample > 0)
            from_weights(c, &L, ws, p->n, &o);
        else
            from_sums(c, &L, acc, &o);
        for (size_t k = 0; k < n; k++)
            c->kept += c->lags[k].status == FT_LAG_KEPT;
        *out = c;
        c = NULL;
    }
    ft_points_counters_free(c);
    pts_lags_free(&L);
    free(acc);
    free(ws);
    return rc;
}
