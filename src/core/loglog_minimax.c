/* fracterra — core/loglog_minimax.c: minimax polyline segmentation of a log-log table, the first of the
 * two segmentations of Arakawa & Krotkov §2.4 (after Kurozumi): the points are split into sets that lie
 * within narrow bands ("rectangles") of a given width around lines, and the cardinality of the sets
 * tells which one gives the dimension.
 *
 * Exact minimax line. For points with increasing x, the line minimising max |y_i - c - s x_i| has
 * error (U(s) - L(s)) / 2 with U(s) = max (y_i - s x_i) over the upper convex hull and L(s) = min over
 * the lower hull; f(s) = U(s) - L(s) is convex and piecewise linear with its kinks at the slopes of the
 * hull edges, so its minimum is at one of them. f sampled at the edge slopes of one hull, in order, is
 * unimodal, so a binary search on each hull finds it in O(k + h log h).
 *
 * Segmentation. Rows are covered longest run first: among all runs of >= 2 rows within the half-width
 * of their minimax line that cover at least one uncovered row (and may share their end rows with
 * segments already chosen), take the one with the most rows, ties to the smaller error, then to the
 * smaller scales; repeat until every row is covered. The first segment is thus the longest straight
 * run of the table. The error of a run can only grow as it extends, so for each start the longest run
 * is found by a two-pointer sweep.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Upper (upper = 1) or lower convex hull of points with increasing x (Andrew's monotone chain). */
static size_t half_hull(const double *x, const double *y, size_t k, int upper, size_t *h)
{
    size_t m = 0;
    for (size_t i = 0; i < k; i++) {
        while (m >= 2) {
            size_t p = h[m - 2], q = h[m - 1];
            double cross = (x[q] - x[p]) * (y[i] - y[p]) - (y[q] - y[p]) * (x[i] - x[p]);
            if (upper ? cross < 0.0 : cross > 0.0)
                break;
            m--;
        }
        h[m++] = i;
    }
    return m;
}

typedef struct {
    const double *x, *y;
    const size_t *up, *lo; /* hull vertex indices */
    size_t nup, nlo;
} hulls;

/* Vertical width of the thinnest band of slope s holding every point; *mid is its centre line's
 * intercept. */
static double band(const hulls *hs, double s, double *mid)
{
    double U = -INFINITY, L = INFINITY;
    for (size_t i = 0; i < hs->nup; i++) {
        double v = hs->y[hs->up[i]] - s * hs->x[hs->up[i]];
        U = v > U ? v : U;
    }
    for (size_t i = 0; i < hs->nlo; i++) {
        double v = hs->y[hs->lo[i]] - s * hs->x[hs->lo[i]];
        L = v < L ? v : L;
    }
    *mid = 0.5 * (U + L);
    return U - L;
}

static double edge_slope(const hulls *hs, const size_t *h, size_t e)
{
    return (hs->y[h[e + 1]] - hs->y[h[e]]) / (hs->x[h[e + 1]] - hs->x[h[e]]);
}

/* Binary search for the smallest band among the edge slopes of hull h (m >= 2 vertices). */
static double best_on_hull(const hulls *hs, const size_t *h, size_t m, double *s)
{
    size_t lo = 0, hi = m - 2;
    double c;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (band(hs, edge_slope(hs, h, mid), &c) <= band(hs, edge_slope(hs, h, mid + 1), &c))
            hi = mid;
        else
            lo = mid + 1;
    }
    *s = edge_slope(hs, h, lo);
    return band(hs, *s, &c);
}

void ft_ll_chebyshev(const double *x, const double *y, size_t k, size_t *work, double *s, double *c,
                     double *err)
{
    if (k < 2) {
        *s = 0.0;
        *c = k ? y[0] : 0.0;
        *err = 0.0;
        return;
    }
    hulls hs = {x, y, work, work + k, 0, 0};
    hs.nup = half_hull(x, y, k, 1, work);
    hs.nlo = half_hull(x, y, k, 0, work + k);
    double su, sl;
    double wu = best_on_hull(&hs, hs.up, hs.nup, &su), wl = best_on_hull(&hs, hs.lo, hs.nlo, &sl);
    *s = wu <= wl ? su : sl;
    double w = band(&hs, *s, c);
    *err = 0.5 * (w > 0.0 ? w : 0.0);
}

typedef struct {
    size_t first, last;
    double err;
    int longest; /* 1 for the first run chosen */
} run;

static double run_err(const ft_ll_data *d, size_t i, size_t j)
{
    double s, c, e;
    ft_ll_chebyshev(d->lx + i, d->ly + i, j - i + 1, d->work, &s, &c, &e);
    return e;
}

/* 1 if candidate r beats best: more rows, then smaller error (earlier scales win remaining ties,
 * because candidates come in increasing order). */
static int better(const run *r, const run *best)
{
    size_t nr = r->last - r->first, nb = best->last - best->first;
    return nr > nb || (nr == nb && r->err < best->err);
}

/* Improves *best with the longest run within half of its minimax line inside rows [wa, wb]. */
static void longest_in(const ft_ll_data *d, size_t wa, size_t wb, double half, run *best)
{
    size_t j = wa + 1;
    for (size_t i = wa; i < wb; i++) {
        if (j < i + 1)
            j = i + 1;
        while (j < wb && run_err(d, i, j + 1) <= half + FT_LL_SLACK)
            j++;
        run r = {i, j, 0.0, 0};
        if (j - i < best->last - best->first)
            continue;
        r.err = run_err(d, i, j);
        if (better(&r, best))
            *best = r;
    }
}

/* The best run over every gap of uncovered rows in the window; 0 if every row is covered. A gap's
 * search may take in the covered row on each side of it, so that neighbouring segments can share it. */
static int next_run(const ft_ll_data *d, const unsigned char *covered, double half, run *best)
{
    *best = (run){0, 0, INFINITY, 0};
    int found = 0;
    size_t i = d->a;
    while (i <= d->b) {
        if (covered[i - d->a]) {
            i++;
            continue;
        }
        size_t g0 = i;
        while (i <= d->b && !covered[i - d->a])
            i++;
        size_t wa = g0 > d->a ? g0 - 1 : g0, wb = i <= d->b ? i : d->b;
        longest_in(d, wa, wb, half, best);
        found = 1;
    }
    return found;
}

static int by_first(const void *pa, const void *pb)
{
    size_t a = ((const run *)pa)->first, b = ((const run *)pb)->first;
    return (a > b) - (a < b);
}

/* Covers the window with runs, longest first; *runs sorted by first row, *longest indexes the first
 * chosen. */
static int cover(const ft_ll_data *d, double half, run **runs, size_t *nruns, size_t *longest)
{
    size_t m = d->b - d->a + 1, n = 0;
    unsigned char *covered = ft_calloc(m, 1);
    run *rs = ft_realloc_array(NULL, m, sizeof *rs); /* each run covers >= 1 new row */
    if (covered == NULL || rs == NULL) {
        free(covered);
        free(rs);
        return FT_E_NOMEM;
    }
    run r;
    while (next_run(d, covered, half, &r)) {
        memset(covered + (r.first - d->a), 1, r.last - r.first + 1);
        r.longest = n == 0;
        rs[n++] = r;
    }
    free(covered);
    qsort(rs, n, sizeof *rs, by_first);
    for (size_t k = 0; k < n; k++)
        if (rs[k].longest)
            *longest = k;
    *runs = rs;
    *nruns = n;
    return FT_OK;
}

int ft_ll_minimax(const ft_ll_data *d, const ft_loglog_opts *o, ft_loglog_segment **segs, size_t *nsegs,
                  size_t *longest, double *width)
{
    double half = 0.5 * o->width, h_noise = o->tol_sigma * ft_loglog_noise(d->t, d->a, d->b);
    half = h_noise > half ? h_noise : half;
    run *rs = NULL;
    size_t n = 0;
    int rc = cover(d, half, &rs, &n, longest);
    if (rc != FT_OK)
        return rc;
    ft_loglog_segment *out = ft_calloc(n, sizeof *out);
    for (size_t k = 0; out != NULL && k < n && rc == FT_OK; k++)
        rc = ft_ll_describe(d, rs[k].first, rs[k].last, &out[k]);
    free(rs);
    if (out == NULL)
        return FT_E_NOMEM;
    if (rc != FT_OK) {
        free(out);
        return rc;
    }
    *segs = out;
    *nsegs = n;
    *width = 2.0 * half;
    return FT_OK;
}
