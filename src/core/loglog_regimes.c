/* fracterra — core/loglog_regimes.c: when a run of a log-log table is straight, and the regimes (straight
 * runs) and breaks of a table.
 *
 * Curvature test. Arakawa & Krotkov's tolerance bands (§2.4) call a run straight when its points lie
 * within a fixed distance of a line; a smoothly curving divider plot (Andrle 1992; Klinkenberg 1994, the
 * fine end of a digitized line) passes such a band while its local slope doubles. Here the data decide:
 * over rows [f, l] fit the quadratic y = c + s u + q u^2 by least squares (y = log10 value, u = log10
 * scale minus its mean over the rows). The quadratic term changes the slope by 2 q (u_l - u_f) across the
 * rows, i.e. D by dD = |b| 2 q (u_l - u_f) for the map D = a + b slope. Its t statistic t = q / se(q)
 * uses the rows' own residual scatter about the quadratic, sigma^2 = SSE / (m - 3), and
 * Var q = sigma^2 [(X'X)^-1]_qq (ordinary regression; e.g. Draper & Smith, Applied Regression Analysis,
 * ch. 12, the extra-term t test). The run is curved when both |dD| > curve_dD (a change of D that matters)
 * and |t| > t_{1 - alpha/2, m - 3} (the change is not scatter). Fewer than 4 rows cannot be tested.
 *
 * Regimes. Greedy, longest first: the run with the most rows (ties: the smaller residual rms) that has
 * at least max(min_points, 3) rows, spans a scale factor of at least min_span and is not curved is a
 * regime; the search repeats on the rows left of it and right of it (each may share the regime's end row,
 * so a break row belongs to both sides). Two touching regimes then have their common boundary moved to
 * the row that minimises their summed squared residuals (both sides still straight and long enough): the
 * least-squares break point of a two-phase regression. A regime whose D differs from a neighbour's by
 * curve_dD or less is not a regime of its own (the tail of a circle's divider plot beside its D = 1
 * run): the narrower of the two is dropped. A regime between two others whose D lies between theirs and
 * which is no wider than either of them and narrower than a decade is the transition between them, not
 * a regime: the rounded corner of a plot whose slope changes over a factor of a few in scale (box counts of one to
 * three times the length where a generator changes). It is dropped; its rows belong to no regime.
 *
 * Breaks. The break between neighbouring regimes is the join point of a continuous two-phase (hinge)
 * regression over their rows and the transition rows between them, y = c + s1 min(x - xb, 0) +
 * s2 max(x - xb, 0), with xb free between the two regimes: for a fixed xb the model is linear, and xb
 * minimises the profile residual sum of squares (Hudson 1966, "Fitting segmented curves whose join points
 * have to be estimated", JASA 61, 1097-1129; the least-squares and Gaussian maximum-likelihood join
 * point). It is
 * where the two asymptotes of a rounded corner meet; the regimes' D stay the fits of their own straight
 * rows, which leave out the transition.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Quadratic least squares over rows [f, l] (m >= 4): curvature statistics. */
static void quad_stats(const double *x, const double *y, size_t f, size_t l, double b, double *dD, double *tq,
                       double *df)
{
    size_t m = l - f + 1;
    double xm = 0.0;
    for (size_t i = f; i <= l; i++)
        xm += x[i];
    xm /= (double)m;
    double s2 = 0.0, s3 = 0.0, s4 = 0.0, ty = 0.0, tuy = 0.0, tu2y = 0.0;
    for (size_t i = f; i <= l; i++) {
        double u = x[i] - xm, u2 = u * u;
        s2 += u2;
        s3 += u2 * u;
        s4 += u2 * u2;
        ty += y[i];
        tuy += u * y[i];
        tu2y += u2 * y[i];
    }
    /* normal equations [[m, 0, s2], [0, s2, s3], [s2, s3, s4]] (c, s, q)' = (ty, tuy, tu2y)' */
    double M = (double)m;
    double det = M * (s2 * s4 - s3 * s3) - s2 * s2 * s2;
    *df = (double)m - 3.0;
    if (!(fabs(det) > 0.0) || !(s2 > 0.0)) {
        *dD = 0.0;
        *tq = 0.0;
        return;
    }
    /* Cramer's rule */
    double c = (ty * (s2 * s4 - s3 * s3) + s2 * (tuy * s3 - s2 * tu2y)) / det;
    double q = (M * (s2 * tu2y - s3 * tuy) - s2 * s2 * ty) / det;
    double s = (tuy - s3 * q) / s2;
    double sse = 0.0;
    for (size_t i = f; i <= l; i++) {
        double u = x[i] - xm, r = y[i] - (c + s * u + q * u * u);
        sse += r * r;
    }
    double var_q = sse / *df * (M * s2) / det;
    *dD = b * 2.0 * q * (x[l] - x[f]);
    *tq = var_q > 0.0 ? q / sqrt(var_q) : (q != 0.0 ? copysign(INFINITY, q) : 0.0);
}

/* 1 if rows [f, l] of the log10 data are curved under o (see the file comment). */
static int curved_rows(const double *x, const double *y, size_t f, size_t l, double b, const ft_loglog_opts *o,
                       double *dD, double *tq)
{
    *dD = 0.0;
    *tq = 0.0;
    if (l < f + 3)
        return 0;
    double df;
    quad_stats(x, y, f, l, b, dD, tq, &df);
    if (!(fabs(*dD) > o->curve_dD))
        return 0;
    return fabs(*tq) > gsl_cdf_tdist_Qinv(0.5 * o->curve_alpha, df);
}

static int end_outlier(const ft_ll_data *d, const ft_loglog_opts *o, size_t f, size_t l, size_t e);

int ft_ll_curved(const ft_ll_data *d, const ft_loglog_opts *o, size_t first, size_t last, double *dD, double *tq)
{
    if (curved_rows(d->lx, d->ly, first, last, d->map.b, o, dD, tq))
        return 1;
    return last >= first + 4 && (end_outlier(d, o, first, last, first) || end_outlier(d, o, first, last, last));
}

int ft_loglog_curved(const ft_loglog *t, size_t first, size_t last, const ft_loglog_opts *opts,
                     const ft_dim_map *map, double *dD, double *tq)
{
    ft_loglog_opts o;
    int rc = ft_ll_opts_check(opts, &o);
    if (rc != FT_OK)
        return rc;
    if (map == NULL || dD == NULL || tq == NULL)
        return ft_error(FT_E_INVALID, "ft_loglog_curved: NULL map or output");
    ft_ll_data d;
    rc = ft_ll_data_init(&d, t, 0.0, 0.0, map, 2);
    if (rc != FT_OK)
        return rc;
    if (first > last || last >= t->n) {
        ft_ll_data_free(&d);
        return ft_error(FT_E_INVALID, "ft_loglog_curved: rows [%zu, %zu] outside the table's %zu rows", first,
                        last, t->n);
    }
    int curved = ft_ll_curved(&d, &o, first, last, dD, tq);
    ft_ll_data_free(&d);
    return curved;
}

/* Residual sum of squares of the least-squares line over rows [f, l] (INFINITY if it cannot be fitted). */
static double line_sse(const ft_ll_data *d, size_t f, size_t l)
{
    ft_fit fit;
    if (ft_fit_line(d->lx, d->ly, f, l, &fit) != FT_OK)
        return INFINITY;
    double sse = 0.0;
    for (size_t i = f; i <= l; i++) {
        double r = d->ly[i] - (fit.intercept + fit.slope * d->lx[i]);
        sse += r * r;
    }
    return sse;
}

/* 1 if end row e of rows [f, l] (e == f or e == l, m >= 5 rows) is an outlier of the line through the
 * others: its prediction residual exceeds the t quantile of the others' scatter (Draper & Smith ch. 2,
 * the prediction interval of a new observation) and bends the slope to its neighbour by more than
 * curve_dD in D. The quadratic test misses a single bent end row (the equipaced polygon below the vertex
 * spacing), this test catches it. */
static int end_outlier(const ft_ll_data *d, const ft_loglog_opts *o, size_t f, size_t l, size_t e)
{
    size_t a = e == f ? f + 1 : f, b = e == f ? l : l - 1, nb = e == f ? f + 1 : l - 1;
    ft_fit fit;
    if (ft_fit_line(d->lx, d->ly, a, b, &fit) != FT_OK)
        return 0;
    size_t m = b - a + 1;
    double xm = 0.0, sxx = 0.0, sse = 0.0;
    for (size_t i = a; i <= b; i++)
        xm += d->lx[i];
    xm /= (double)m;
    for (size_t i = a; i <= b; i++) {
        double r = d->ly[i] - (fit.intercept + fit.slope * d->lx[i]);
        sxx += (d->lx[i] - xm) * (d->lx[i] - xm);
        sse += r * r;
    }
    double re = d->ly[e] - (fit.intercept + fit.slope * d->lx[e]);
    double dx = fabs(d->lx[nb] - d->lx[e]);
    if (!(dx > 0.0) || !(fabs(d->map.b) * fabs(re) / dx > o->curve_dD))
        return 0;
    double df = (double)m - 2.0;
    double se = sqrt(sse / df * (1.0 + 1.0 / (double)m + (d->lx[e] - xm) * (d->lx[e] - xm) / sxx));
    if (!(se > 0.0))
        return 1;
    return fabs(re) / se > gsl_cdf_tdist_Qinv(0.5 * o->curve_alpha, df);
}

/* Sums of a run for O(1) line fits of its sub-runs. */
typedef struct {
    double n, x, y, xx, xy, yy;
} sums;

static double sums_sse(const sums *a)
{
    double sxx = a->xx - a->x * a->x / a->n, sxy = a->xy - a->x * a->y / a->n, syy = a->yy - a->y * a->y / a->n;
    double sse = sxx > 0.0 ? syy - sxy * sxy / sxx : syy;
    return sse > 0.0 ? sse : 0.0;
}

static double sums_slope(const sums *a)
{
    double sxx = a->xx - a->x * a->x / a->n, sxy = a->xy - a->x * a->y / a->n;
    return sxx > 0.0 ? sxy / sxx : 0.0;
}

/* 1 if rows [f, l] hold a break: two lines, split between rows j and j + 1 with at least a quarter of the
 * rows (and 3) on each side, fit significantly better than one (F test of the two extra parameters at
 * curve_alpha; Draper & Smith ch. 6) and their slopes differ by more than curve_dD in D. A kink that the
 * quadratic term does not follow (a regime's end taken into a longer run) is found this way. */
static int has_break(const ft_ll_data *d, const ft_loglog_opts *o, size_t f, size_t l)
{
    size_t m = l - f + 1, side = m / 4 > 3 ? m / 4 : 3;
    if (m < 2 * side || m < 8)
        return 0;
    double x0 = d->lx[f], y0 = d->ly[f];
    sums all = {0, 0, 0, 0, 0, 0};
    for (size_t i = f; i <= l; i++) {
        double x = d->lx[i] - x0, y = d->ly[i] - y0;
        all = (sums){all.n + 1, all.x + x, all.y + y, all.xx + x * x, all.xy + x * y, all.yy + y * y};
    }
    double sse1 = sums_sse(&all), best = INFINITY, ds = 0.0;
    sums left = {0, 0, 0, 0, 0, 0};
    for (size_t j = f; j + side <= l; j++) {
        double x = d->lx[j] - x0, y = d->ly[j] - y0;
        left = (sums){left.n + 1, left.x + x, left.y + y, left.xx + x * x, left.xy + x * y, left.yy + y * y};
        if (j - f + 1 < side)
            continue;
        sums right = {all.n - left.n, all.x - left.x, all.y - left.y, all.xx - left.xx, all.xy - left.xy,
                      all.yy - left.yy};
        double sse2 = sums_sse(&left) + sums_sse(&right);
        if (sse2 < best) {
            best = sse2;
            ds = sums_slope(&left) - sums_slope(&right);
        }
    }
    if (!(fabs(d->map.b) * fabs(ds) > o->curve_dD))
        return 0;
    double df = (double)m - 4.0;
    if (!(best > 0.0))
        return sse1 > 0.0;
    double F = (sse1 - best) / 2.0 / (best / df);
    return F > gsl_cdf_fdist_Qinv(o->curve_alpha, 2.0, df);
}

static size_t min_rows(const ft_loglog_opts *o)
{
    return o->min_points > 3 ? o->min_points : 3;
}

/* 1 if rows [f, l] may form a regime: enough rows, a wide enough span, not curved. */
static int regime_ok(const ft_ll_data *d, const ft_loglog_opts *o, size_t f, size_t l)
{
    double dD, tq;
    if (l - f + 1 < min_rows(o) || d->lx[l] - d->lx[f] < log10(o->min_span) - 1e-9)
        return 0;
    return !ft_ll_curved(d, o, f, l, &dD, &tq) && !has_break(d, o, f, l);
}

typedef struct {
    size_t *first, *last;
    size_t n;
} run_list;

/* The longest regime within rows [a, b] into *f, *l; 0 if none. */
static int longest_regime(const ft_ll_data *d, const ft_loglog_opts *o, size_t a, size_t b, size_t *f, size_t *l)
{
    size_t k = min_rows(o);
    if (b < a || b - a + 1 < k)
        return 0;
    for (size_t len = b - a + 1; len >= k; len--) {
        double best = INFINITY;
        int found = 0;
        for (size_t i = a; i + len - 1 <= b; i++) {
            size_t j = i + len - 1;
            if (!regime_ok(d, o, i, j))
                continue;
            double sse = line_sse(d, i, j);
            if (!found || sse < best) {
                best = sse;
                *f = i;
                *l = j;
                found = 1;
            }
        }
        if (found)
            return 1;
    }
    return 0;
}

static void search(const ft_ll_data *d, const ft_loglog_opts *o, size_t a, size_t b, run_list *rl)
{
    size_t f, l;
    if (!longest_regime(d, o, a, b, &f, &l))
        return;
    rl->first[rl->n] = f;
    rl->last[rl->n] = l;
    rl->n++;
    if (f > a)
        search(d, o, a, f, rl);
    if (l < b)
        search(d, o, l, b, rl);
}

/* Moves the boundary between touching regimes k and k + 1 to the least-squares break row. */
static void refine(const ft_ll_data *d, const ft_loglog_opts *o, run_list *rl, size_t k)
{
    size_t F = rl->first[k], L = rl->last[k + 1];
    if (rl->first[k + 1] > rl->last[k] + 1)
        return;
    double best = INFINITY;
    size_t bj = 0;
    for (size_t j = F + 1; j < L; j++) {
        if (!regime_ok(d, o, F, j) || !regime_ok(d, o, j, L))
            continue;
        double sse = line_sse(d, F, j) + line_sse(d, j, L);
        if (sse < best) {
            best = sse;
            bj = j;
        }
    }
    if (bj != 0) {
        rl->last[k] = bj;
        rl->first[k + 1] = bj;
    }
}

static void sort_runs(run_list *rl)
{
    for (size_t i = 1; i < rl->n; i++)
        for (size_t j = i; j > 0 && rl->first[j] < rl->first[j - 1]; j--) {
            size_t tf = rl->first[j], tl = rl->last[j];
            rl->first[j] = rl->first[j - 1];
            rl->last[j] = rl->last[j - 1];
            rl->first[j - 1] = tf;
            rl->last[j - 1] = tl;
        }
}

/* Residual sum of squares of the hinge y = c + s1 min(x - xb, 0) + s2 max(x - xb, 0) over rows [f, l]
 * (least squares in c, s1, s2 for this xb; INFINITY if they are not determined). */
static double hinge_sse(const double *x, const double *y, size_t f, size_t l, double xb)
{
    double n = 0, su = 0, sv = 0, suu = 0, svv = 0, sy = 0, suy = 0, svy = 0, syy = 0;
    for (size_t i = f; i <= l; i++) {
        double t = x[i] - xb, u = t < 0.0 ? t : 0.0, v = t > 0.0 ? t : 0.0;
        n += 1.0;
        su += u;
        sv += v;
        suu += u * u;
        svv += v * v;
        sy += y[i];
        suy += u * y[i];
        svy += v * y[i];
        syy += y[i] * y[i];
    }
    /* normal equations [[n, su, sv], [su, suu, 0], [sv, 0, svv]] (c, s1, s2)' = (sy, suy, svy)'; u v = 0 */
    if (!(suu > 0.0) || !(svv > 0.0))
        return INFINITY;
    double det = n * suu * svv - su * su * svv - sv * sv * suu;
    if (!(det > 1e-12 * n * suu * svv))
        return INFINITY;
    double c = (sy * suu * svv - su * suy * svv - sv * svy * suu) / det;
    double s1 = (suy - su * c) / suu, s2 = (svy - sv * c) / svv;
    /* SSE = y'y - beta' X'y at the least-squares solution */
    double sse = syy - (c * sy + s1 * suy + s2 * svy);
    double scale = syy > 0.0 ? syy : 1.0;
    if (sse < 1e-15 * scale) { /* cancellation: sum the residuals directly */
        sse = 0.0;
        for (size_t i = f; i <= l; i++) {
            double t = x[i] - xb, r = y[i] - (c + s1 * (t < 0.0 ? t : 0.0) + s2 * (t > 0.0 ? t : 0.0));
            sse += r * r;
        }
    }
    return sse;
}

/* The least-squares join point xb (log10 scale) of a hinge over rows [f, l] (at least 4 rows), searched
 * between x[a] and x[b] (f + 1 <= a < b <= l - 1, so that each phase has two rows): a grid of HINGE_GRID
 * points per row interval, then golden-section refinement within the best grid cell's neighbours. */
#define HINGE_GRID 16
static double hinge_break(const double *x, const double *y, size_t f, size_t l, size_t a_row, size_t b_row)
{
    double lo = x[a_row], hi = x[b_row], bx = 0.5 * (lo + hi), best = INFINITY, step = 0.0;
    for (size_t i = a_row; i < b_row; i++) {
        double h = (x[i + 1] - x[i]) / HINGE_GRID;
        for (int k = 0; k <= HINGE_GRID; k++) {
            double xb = x[i] + k * h, e = hinge_sse(x, y, f, l, xb);
            if (e < best) {
                best = e;
                bx = xb;
                step = h;
            }
        }
    }
    if (!(best < INFINITY))
        return bx;
    double a = fmax(lo, bx - step), b = fmin(hi, bx + step);
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    double c = b - g * (b - a), e = a + g * (b - a), fc = hinge_sse(x, y, f, l, c), fe = hinge_sse(x, y, f, l, e);
    for (int it = 0; it < 40 && b - a > 1e-9; it++) {
        if (fc <= fe) {
            b = e;
            e = c;
            fe = fc;
            c = b - g * (b - a);
            fc = hinge_sse(x, y, f, l, c);
        } else {
            a = c;
            c = e;
            fc = fe;
            e = a + g * (b - a);
            fe = hinge_sse(x, y, f, l, e);
        }
    }
    double xm = 0.5 * (a + b);
    return hinge_sse(x, y, f, l, xm) <= best ? xm : bx;
}

/* The break scale between regimes p and q (p before q): the hinge join point over their rows and the
 * rows between them, searched between the regimes (from p's last row to q's first; touching regimes: the
 * row intervals on either side of the shared row). */
static double break_scale(const ft_ll_data *d, const ft_loglog_segment *p, const ft_loglog_segment *q)
{
    size_t f = p->first, l = q->last, a = p->last, b = q->first;
    if (b <= a) {
        a = b > 0 ? b - 1 : b;
        b = p->last + 1;
    }
    a = a < f + 1 ? f + 1 : a;
    b = b > l - 1 ? l - 1 : b;
    if (b <= a) { /* cannot happen with regimes of 3 rows or more; the whole admissible interval */
        a = f + 1;
        b = l - 1;
    }
    return pow(10.0, hinge_break(d->lx, d->ly, f, l, a, b));
}

/* Drops the transitions (see the file comment) from segs[0, *n): a regime between two others, its D
 * between theirs, no wider than either and narrower than a decade. */
static void drop_transitions(const ft_ll_data *d, ft_loglog_segment *segs, size_t *n)
{
    for (size_t k = 1; k + 1 < *n;) {
        const ft_loglog_segment *p = &segs[k - 1], *m = &segs[k], *q = &segs[k + 1];
        double wp = d->lx[p->last] - d->lx[p->first], wm = d->lx[m->last] - d->lx[m->first],
               wq = d->lx[q->last] - d->lx[q->first];
        int between = (m->D - p->D) * (q->D - m->D) > 0.0;
        if (between && wm <= wp + 1e-9 && wm <= wq + 1e-9 && wm < 1.0) {
            memmove(&segs[k], &segs[k + 1], (*n - k - 1) * sizeof *segs);
            (*n)--;
            k = 1;
            continue;
        }
        k++;
    }
}

int ft_ll_regimes(const ft_ll_data *d, const ft_loglog_opts *o, ft_loglog_segment **regimes, size_t *nregimes,
                  double **breaks)
{
    *regimes = NULL;
    *nregimes = 0;
    *breaks = NULL;
    size_t m = d->b - d->a + 1;
    run_list rl = {ft_malloc(m * sizeof(size_t)), ft_malloc(m * sizeof(size_t)), 0};
    if (rl.first == NULL || rl.last == NULL) {
        free(rl.first);
        free(rl.last);
        return FT_E_NOMEM;
    }
    search(d, o, d->a, d->b, &rl);
    sort_runs(&rl);
    for (size_t k = 0; k + 1 < rl.n; k++)
        refine(d, o, &rl, k);
    ft_loglog_segment *segs = rl.n ? ft_calloc(rl.n, sizeof *segs) : NULL;
    int rc = rl.n && segs == NULL ? FT_E_NOMEM : FT_OK;
    size_t n = 0;
    for (size_t k = 0; rc == FT_OK && k < rl.n; k++) {
        rc = ft_ll_describe(d, rl.first[k], rl.last[k], &segs[n]);
        if (rc != FT_OK)
            break;
        /* a regime indistinguishable from its left neighbour: keep the wider */
        if (n > 0 && fabs(segs[n].D - segs[n - 1].D) <= o->curve_dD) {
            double wn = d->lx[segs[n].last] - d->lx[segs[n].first];
            double wp = d->lx[segs[n - 1].last] - d->lx[segs[n - 1].first];
            if (wn > wp)
                segs[n - 1] = segs[n];
            continue;
        }
        n++;
    }
    free(rl.first);
    free(rl.last);
    if (rc == FT_OK)
        drop_transitions(d, segs, &n);
    double *br = n > 1 ? ft_malloc((n - 1) * sizeof *br) : NULL;
    if (rc == FT_OK && n > 1 && br == NULL)
        rc = FT_E_NOMEM;
    if (rc != FT_OK) {
        free(segs);
        free(br);
        return rc;
    }
    for (size_t k = 0; k + 1 < n; k++)
        br[k] = break_scale(d, &segs[k], &segs[k + 1]);
    *regimes = segs;
    *nregimes = n;
    *breaks = br;
    return FT_OK;
}
