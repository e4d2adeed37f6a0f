/* fracterra — core/loglog_fit.c: the dimension from a log-log table, step 3 of Arakawa & Krotkov §2.4
 * ("estimate fractal dimension from the slope of linear segments"): a least-squares line over the
 * chosen rows (a user range, the longest qualifying iterative least-squares run or minimax segment, or
 * the whole window when no straight run qualifies: loglog_admit.c), D = a + b * slope by the
 * estimator's map, and a result that keeps the table with its used rows and every segment found, so
 * that users can judge the straightness themselves.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int ft_ll_opts_check(const ft_loglog_opts *opts, ft_loglog_opts *o)
{
    *o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(*o, opts, ft_loglog_opts) != FT_OK)
        return FT_E_INVALID;
    if (o->method != FT_LOGLOG_ILS && o->method != FT_LOGLOG_MINIMAX && o->method != FT_LOGLOG_REGIMES)
        return ft_error(FT_E_INVALID, "log-log segmentation: unknown method %d (0 = ILS, 1 = minimax, "
                        "2 = regimes)", (int)o->method);
    if (!isfinite(o->tol) || !(o->tol > 0.0))
        return ft_error(FT_E_INVALID, "log-log segmentation: tol must be > 0 (log10 units), got %g", o->tol);
    if (!isfinite(o->width) || !(o->width > 0.0))
        return ft_error(FT_E_INVALID, "log-log segmentation: width must be > 0 (log10 units), got %g", o->width);
    if (!isfinite(o->tol_sigma) || o->tol_sigma < 0.0)
        return ft_error(FT_E_INVALID, "log-log segmentation: tol_sigma must be >= 0, got %g", o->tol_sigma);
    if (o->min_points < 2)
        return ft_error(FT_E_INVALID, "log-log segmentation: min_points must be >= 2, got %zu", o->min_points);
    if (o->max_iter < 1)
        return ft_error(FT_E_INVALID, "log-log segmentation: max_iter must be >= 1, got %d", o->max_iter);
    if (!isfinite(o->min_span) || !(o->min_span >= 1.0))
        return ft_error(FT_E_INVALID, "log-log segmentation: min_span must be >= 1 (a scale factor), got %g",
                        o->min_span);
    if (!isfinite(o->bounds_tol) || !(o->bounds_tol >= 0.0))
        return ft_error(FT_E_INVALID, "log-log segmentation: bounds_tol must be >= 0, got %g", o->bounds_tol);
    if (!isfinite(o->curve_dD) || !(o->curve_dD > 0.0))
        return ft_error(FT_E_INVALID, "log-log segmentation: curve_dD must be > 0, got %g", o->curve_dD);
    if (!(o->curve_alpha > 0.0 && o->curve_alpha < 1.0))
        return ft_error(FT_E_INVALID, "log-log segmentation: curve_alpha must be in (0, 1), got %g",
                        o->curve_alpha);
    if (o->regime < 0)
        return ft_error(FT_E_INVALID, "log-log segmentation: regime must be >= 0 (0 = the widest), got %d",
                        o->regime);
    return FT_OK;
}

int ft_ll_describe(const ft_ll_data *d, size_t first, size_t last, ft_loglog_segment *seg)
{
    ft_fit fit;
    int rc = ft_fit_line(d->lx, d->ly, first, last, &fit);
    if (rc != FT_OK)
        return rc;
    double ms, mc, err;
    ft_ll_chebyshev(d->lx + first, d->ly + first, last - first + 1, d->work, &ms, &mc, &err);
    seg->first = first;
    seg->last = last;
    seg->n = last - first + 1;
    seg->scale_lo = d->t->rows[first].scale;
    seg->scale_hi = d->t->rows[last].scale;
    seg->slope = fit.slope;
    seg->intercept = fit.intercept;
    seg->D = d->map.a + d->map.b * fit.slope;
    seg->r2 = fit.r2;
    seg->stderr_D = fabs(d->map.b) * fit.stderr_slope;
    seg->max_err = err;
    seg->D_minimax = d->map.a + d->map.b * ms;
    return FT_OK;
}

void ft_loglog_segments_free(ft_loglog_segment *s)
{
    free(s);
}

void ft_dim_result_free(ft_dim_result *r)
{
    if (r == NULL)
        return;
    ft_loglog_free(r->table);
    free(r->segments);
    free(r->regimes);
    free(r->breaks);
    for (size_t i = 0; i < r->nwarnings; i++)
        free(r->warnings[i]);
    free(r->warnings);
    free(r);
}

/* Takes ownership of msg (NULL: allocation failed) and appends it to r's warnings. */
static int add_warning(ft_dim_result *r, char *msg)
{
    if (msg == NULL)
        return ft_error(FT_E_NOMEM, "log-log fit: out of memory for a warning");
    char **w = realloc(r->warnings, (r->nwarnings + 1) * sizeof *w);
    if (w == NULL) {
        free(msg);
        return ft_error(FT_E_NOMEM, "log-log fit: out of memory for a warning");
    }
    w[r->nwarnings++] = msg;
    r->warnings = w;
    return FT_OK;
}

int ft_dim_result_warn(ft_dim_result *r, const char *fmt, ...)
{
    if (r == NULL || fmt == NULL)
        return ft_error(FT_E_INVALID, "ft_dim_result_warn: NULL result or format");
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return add_warning(r, ft_strdup(msg));
}

const char *ft_dim_result_find_warning(const ft_dim_result *r, const char *substr)
{
    for (size_t i = 0; r != NULL && i < r->nwarnings; i++)
        if (substr == NULL || strstr(r->warnings[i], substr) != NULL)
            return r->warnings[i];
    return NULL;
}

void ft_dim_result_set_units(ft_dim_result *r, const char *units)
{
    if (r == NULL)
        return;
    snprintf(r->units, sizeof r->units, "%s", units != NULL ? units : "");
}

/* A new result holding a copy of the table with no row used. */
static int result_new(const ft_ll_data *d, const char *name, ft_dim_result **out)
{
    ft_dim_result *r = ft_calloc(1, sizeof *r);
    if (r == NULL)
        return FT_E_NOMEM;
    r->table = ft_loglog_copy(d->t);
    if (r->table == NULL) {
        free(r);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < r->table->n; i++)
        r->table->rows[i].used = 0;
    ft_loglog_update_slopes(r->table);
    r->method = r->segmentation = name;
    r->map = d->map;
    r->best = FT_LOGLOG_NONE;
    r->regime = FT_LOGLOG_NONE;
    r->noise = ft_loglog_noise(d->t, d->a, d->b);
    *out = r;
    return FT_OK;
}

/* Fits D over rows [first, last] and marks them used. */
static int result_fit(ft_dim_result *r, const ft_ll_data *d, size_t first, size_t last)
{
    ft_loglog_segment seg;
    int rc = ft_ll_describe(d, first, last, &seg);
    if (rc != FT_OK)
        return rc;
    rc = ft_fit_line(d->lx, d->ly, first, last, &r->fit);
    if (rc != FT_OK)
        return rc;
    r->D = seg.D;
    r->r2 = seg.r2;
    r->stderr_D = seg.stderr_D;
    r->max_err = seg.max_err;
    r->range[0] = seg.scale_lo;
    r->range[1] = seg.scale_hi;
    for (size_t i = first; i <= last; i++)
        r->table->rows[i].used = 1;
    return FT_OK;
}

/* Common tail: on failure frees the result and the data, on success hands the result out. */
static int finish(int rc, ft_ll_data *d, ft_dim_result *r, ft_dim_result **out)
{
    ft_ll_data_free(d);
    if (rc != FT_OK) {
        ft_dim_result_free(r);
        return rc;
    }
    *out = r;
    return FT_OK;
}

static int check_out(ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "log-log fit: NULL result pointer");
    *out = NULL;
    return FT_OK;
}

/* The regimes of d's window into r (once). */
static int find_regimes(ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o)
{
    if (r->regimes != NULL || r->nregimes > 0)
        return FT_OK;
    return ft_ll_regimes(d, o, &r->regimes, &r->nregimes, &r->breaks);
}

/* Warns when the count behind the value at the largest used scale is below FT_LL_FEW_COUNTS. */
static int warn_few_counts(ft_dim_result *r)
{
    const ft_loglog_row *row = &r->table->rows[r->fit.last];
    if (!(row->count > 0.0) || row->count >= FT_LL_FEW_COUNTS)
        return FT_OK;
    return ft_dim_result_warn(r, "few counts: %g boxes, steps or pairs behind the value at the largest scale "
                              "used (%g), fewer than %d: so few counts bias the slope; lower the largest "
                              "scale (--max-scale)", row->count, row->scale, FT_LL_FEW_COUNTS);
}

/* An error for a D outside its domain by more than slack, naming the reason; a D outside it by less is
 * reported as the bound, with a warning. */
static int check_domain(ft_dim_result *r, double slack)
{
    const ft_dim_map *m = &r->map;
    if (!ft_ll_bounded(m) || (r->D >= m->d_min && r->D <= m->d_max))
        return FT_OK;
    double bound = r->D < m->d_min ? m->d_min : m->d_max;
    if (fabs(r->D - bound) < 5e-5) { /* rounding: prints as the bound */
        r->D = bound;
        return FT_OK;
    }
    if (fabs(r->D - bound) <= slack + 1e-12) {
        int rc = ft_dim_result_warn(r, "D = %.4f estimated, %g reported: the estimate lies outside [%g, %g] by "
                                    "no more than %g", r->D, bound, m->d_min, m->d_max, slack);
        r->D = bound;
        return rc;
    }
    double span = r->range[1] / r->range[0];
    return ft_error(FT_E_NUMERIC,
                    "D = %.4f lies outside [%g, %g], the interval of this estimator, over scales %g to %g "
                    "(%zu rows, a factor %.3g): not a result; %s%s",
                    r->D, m->d_min, m->d_max, r->range[0], r->range[1], r->fit.n, span,
                    r->D < m->d_min ? "the data are smoother than any fractal over these scales (degenerate for "
                                      "this estimator)"
                                    : "the data are rougher than any fractal over these scales (noise, or too few "
                                      "scales)",
                    span < 10.0 ? "; the band is narrower than a decade: widen it (more data, a larger grid or "
                                  "other scale limits)"
                                : "; look at the table's regimes (--plot) or give another range");
}

/* What every fit ends with, whatever chose its rows: the regimes of the window, which of them gave D, the
 * warnings of docs/loglog.md (curved rows, few counts, a band under a decade, fewer than 5 scales) and
 * the domain of D. */
static int conclude(ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o)
{
    int rc = find_regimes(r, d, o);
    for (size_t k = 0; rc == FT_OK && k < r->nregimes; k++)
        if (r->regimes[k].first == r->fit.first && r->regimes[k].last == r->fit.last)
            r->regime = k;
    double dD, tq;
    if (rc == FT_OK && ft_ll_curved(d, o, r->fit.first, r->fit.last, &dD, &tq))
        rc = ft_dim_result_warn(r, "curved: the log-log plot curves over the fitted scales %g to %g (D changes "
                                "by %+.3f across them, quadratic term t = %.1f): no single dimension holds "
                                "there; see \"regimes\" or --plot", r->range[0], r->range[1], dD, tq);
    if (rc == FT_OK)
        rc = warn_few_counts(r);
    if (rc == FT_OK && r->range[1] / r->range[0] < 10.0)
        rc = ft_dim_result_warn(r, "narrow band: the fit spans a factor %.3g of scales (%g to %g), less than a "
                                "decade", r->range[1] / r->range[0], r->range[0], r->range[1]);
    if (rc == FT_OK && r->fit.n < 5)
        rc = ft_dim_result_warn(r, "few scales: the fit uses %zu scales, fewer than 5", r->fit.n);
    if (rc == FT_OK)
        rc = check_domain(r, o->bounds_tol);
    return rc;
}

int ft_loglog_fit_range(const ft_loglog *t, double lo, double hi, const ft_dim_map *map, ft_dim_result **out)
{
    int rc = check_out(out);
    if (rc != FT_OK)
        return rc;
    const ft_loglog_opts defaults = FT_LOGLOG_OPTS_DEFAULT;
    ft_ll_data d;
    ft_dim_result *r = NULL;
    rc = ft_ll_data_init(&d, t, lo, hi, map, 2);
    if (rc == FT_OK)
        rc = result_new(&d, "range", &r);
    if (rc == FT_OK)
        rc = result_fit(r, &d, d.a, d.b);
    if (rc == FT_OK) {
        r->choice = "range asked for";
        rc = conclude(r, &d, &defaults);
    }
    return finish(rc, &d, r, out);
}

/* No straight run qualified: D over the whole window, flagged and explained. */
static int fit_whole(ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o)
{
    int rc = result_fit(r, d, d->a, d->b);
    if (rc != FT_OK)
        return rc;
    r->segmentation = FT_LOGLOG_WHOLE_RANGE;
    r->choice = "whole range (no straight run qualifies)";
    return add_warning(r, ft_ll_whole_range_warning(d, o, r->D));
}

/* The longest qualifying ILS run of d's window into r; *chosen = 0 (r untouched but for the tolerance)
 * if no converged run qualifies. */
static int fit_ils(ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o, int *chosen)
{
    size_t first, last;
    int rc = ft_ll_ils(d, o, &first, &last, &r->tol, chosen);
    if (rc == FT_OK && *chosen) {
        rc = result_fit(r, d, first, last);
        r->choice = "longest iterative least-squares run";
    }
    return rc;
}

int ft_loglog_segment_ils(const ft_loglog *t, const ft_loglog_opts *opts, const ft_dim_map *map,
                          ft_dim_result **out)
{
    ft_loglog_opts o;
    int rc = check_out(out);
    if (rc == FT_OK)
        rc = ft_ll_opts_check(opts, &o);
    if (rc != FT_OK)
        return rc;
    ft_ll_data d;
    ft_dim_result *r = NULL;
    int chosen = 0;
    rc = ft_ll_data_init(&d, t, 0.0, 0.0, map, o.min_points);
    if (rc == FT_OK)
        rc = result_new(&d, "ils", &r);
    if (rc == FT_OK)
        rc = fit_ils(r, &d, &o, &chosen);
    if (rc == FT_OK && !chosen)
        rc = fit_whole(r, &d, &o);
    if (rc == FT_OK)
        rc = conclude(r, &d, &o);
    return finish(rc, &d, r, out);
}

int ft_loglog_segment_minimax(const ft_loglog *t, const ft_loglog_opts *opts, const ft_dim_map *map,
                              ft_loglog_segment **segments, size_t *nsegments)
{
    if (segments == NULL || nsegments == NULL)
        return ft_error(FT_E_INVALID, "minimax segmentation: NULL output pointer");
    *segments = NULL;
    *nsegments = 0;
    ft_loglog_opts o;
    int rc = ft_ll_opts_check(opts, &o);
    if (rc != FT_OK)
        return rc;
    ft_ll_data d;
    rc = ft_ll_data_init(&d, t, 0.0, 0.0, map, 2);
    size_t longest;
    double width;
    if (rc == FT_OK)
        rc = ft_ll_minimax(&d, &o, segments, nsegments, &longest, &width);
    ft_ll_data_free(&d);
    return rc;
}

/* Index of the qualifying segment with the most rows (ties: the smaller max_err, then the smaller
 * scales), or FT_LOGLOG_NONE. */
static size_t admitted_segment(const ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o)
{
    size_t best = FT_LOGLOG_NONE;
    for (size_t k = 0; k < r->nsegments; k++) {
        const ft_loglog_segment *s = &r->segments[k];
        if (ft_ll_admit(d, o, s->first, s->last, s->D) != FT_LL_ADMITTED)
            continue;
        if (best == FT_LOGLOG_NONE || s->n > r->segments[best].n ||
            (s->n == r->segments[best].n && s->max_err < r->segments[best].max_err))
            best = k;
    }
    return best;
}

/* Minimax segments of d's window into r and, for FT_LOGLOG_MINIMAX, D over the longest qualifying one;
 * *chosen = 0 if the method is ILS or no segment qualifies. */
static int fit_minimax(ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o, int *chosen)
{
    size_t longest;
    *chosen = 0;
    int rc = ft_ll_minimax(d, o, &r->segments, &r->nsegments, &longest, &r->width);
    if (rc != FT_OK || o->method != FT_LOGLOG_MINIMAX)
        return rc;
    const ft_loglog_segment *s = &r->segments[longest];
    if (s->n < o->min_points)
        return ft_error(FT_E_NUMERIC,
                        "minimax segmentation: the longest segment within width %g (log10 units) has %zu rows, "
                        "fewer than min_points = %zu; widen the width or check the table",
                        r->width, s->n, o->min_points);
    size_t k = admitted_segment(r, d, o);
    if (k == FT_LOGLOG_NONE)
        return FT_OK;
    *chosen = 1;
    s = &r->segments[k];
    r->choice = "longest minimax segment";
    return result_fit(r, d, s->first, s->last);
}

/* Index of the segment spanning exactly the used rows, or FT_LOGLOG_NONE. */
static size_t matching_segment(const ft_dim_result *r)
{
    for (size_t k = 0; k < r->nsegments; k++)
        if (r->segments[k].first == r->fit.first && r->segments[k].last == r->fit.last)
            return k;
    return FT_LOGLOG_NONE;
}

/* 1 if regime p is a better headline than q: wider in log scale, then more rows, then smaller stderr. */
static int wider(const ft_ll_data *d, const ft_loglog_segment *p, const ft_loglog_segment *q)
{
    double wp = d->lx[p->last] - d->lx[p->first], wq = d->lx[q->last] - d->lx[q->first];
    if (fabs(wp - wq) > 1e-9)
        return wp > wq;
    if (p->n != q->n)
        return p->n > q->n;
    return p->stderr_D < q->stderr_D;
}

/* FT_LOGLOG_REGIMES: D from the regime opts->regime asks for, or else the widest regime whose D lies in
 * the map's bounds; *chosen = 0 if there is none. */
static int fit_regime(ft_dim_result *r, const ft_ll_data *d, const ft_loglog_opts *o, int *chosen)
{
    *chosen = 0;
    int rc = find_regimes(r, d, o);
    if (rc != FT_OK)
        return rc;
    size_t k = FT_LOGLOG_NONE;
    if (o->regime > 0) {
        if ((size_t)o->regime > r->nregimes)
            return ft_error(FT_E_INVALID, "regime %d asked for, but the log-log table has %zu regime%s (straight "
                            "runs)%s", o->regime, r->nregimes, r->nregimes == 1 ? "" : "s",
                            r->nregimes ? "" : ": give a scale range instead");
        k = (size_t)o->regime - 1;
        r->choice = "regime asked for";
    } else {
        for (size_t i = 0; i < r->nregimes; i++) {
            const ft_loglog_segment *s = &r->regimes[i];
            if (ft_ll_admit(d, o, s->first, s->last, s->D) != FT_LL_ADMITTED)
                continue;
            if (k == FT_LOGLOG_NONE || wider(d, s, &r->regimes[k]))
                k = i;
        }
        r->choice = r->nregimes == 1 ? "the only regime" : "widest regime";
    }
    if (k == FT_LOGLOG_NONE)
        return FT_OK;
    *chosen = 1;
    r->segmentation = "regimes";
    return result_fit(r, d, r->regimes[k].first, r->regimes[k].last);
}

int ft_loglog_fit_auto(const ft_loglog *t, double lo_limit, double hi_limit, const ft_loglog_opts *opts,
                       const ft_dim_map *map, ft_dim_result **out)
{
    ft_loglog_opts o;
    int rc = check_out(out);
    if (rc == FT_OK)
        rc = ft_ll_opts_check(opts, &o);
    if (rc != FT_OK)
        return rc;
    ft_ll_data d;
    ft_dim_result *r = NULL;
    const char *name = o.method == FT_LOGLOG_ILS ? "ils" : o.method == FT_LOGLOG_MINIMAX ? "minimax" : "regimes";
    int chosen = 0;
    rc = ft_ll_data_init(&d, t, lo_limit, hi_limit, map, o.min_points);
    if (rc == FT_OK)
        rc = result_new(&d, name, &r);
    if (rc == FT_OK)
        rc = fit_minimax(r, &d, &o, &chosen);
    if (rc == FT_OK && o.method == FT_LOGLOG_ILS)
        rc = fit_ils(r, &d, &o, &chosen);
    if (rc == FT_OK && o.method == FT_LOGLOG_REGIMES)
        rc = fit_regime(r, &d, &o, &chosen);
    if (rc == FT_OK && !chosen)
        rc = fit_whole(r, &d, &o);
    if (rc == FT_OK) {
        r->best = matching_segment(r);
        rc = conclude(r, &d, &o);
    }
    return finish(rc, &d, r, out);
}
