/* fracterra — core/loglog_ils.c: iterative least-squares segmentation of a log-log table, the second of
 * the two segmentations of Arakawa & Krotkov §2.4: "construct a set of points that lie within a
 * specified distance of the line", which they found insensitive to the threshold.
 *
 * One start, from a run S of rows: fit y = c + s x by least squares over S; mark every row of the
 * window whose vertical distance |y_i - c - s x_i| is at most tol (this drops rows of S and takes in
 * rows outside it); S' = the longest contiguous run of marked rows (ties: the smaller scales); stop
 * when S' = S, otherwise continue from S'. A converged run is a maximal straight run: its rows are all
 * within tol of their own least-squares line and the rows beside it are not.
 * The paper notes that a single start "selects only the first linear part"; to keep the longest
 * straight run instead, starts are made from the whole window and from every run of min_points rows,
 * and the converged run with the most rows among those that qualify (loglog_admit.c: enough rows, a
 * scale factor of min_span, D within the map's bounds) wins (ties: the smaller residual rms, then the
 * earlier start). tol = max(opts.tol, opts.tol_sigma * ft_loglog_noise(window)).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <math.h>

/* The longest run of window rows within tol of y = c + s x (ties: the first); its length, 0 if none. */
static size_t inlier_run(const ft_ll_data *d, double s, double c, double tol, size_t *first, size_t *last)
{
    size_t best = 0, start = 0, len = 0;
    for (size_t i = d->a; i <= d->b; i++) {
        if (fabs(d->ly[i] - (c + s * d->lx[i])) <= tol + FT_LL_SLACK) {
            if (len++ == 0)
                start = i;
            if (len > best) {
                best = len;
                *first = start;
                *last = i;
            }
        } else {
            len = 0;
        }
    }
    return best;
}

/* Runs one start from rows [f, l]; 1 with the converged run in [*rf, *rl], 0 if it did not converge
 * or shrank below 2 rows. */
static int ils_start(const ft_ll_data *d, size_t f, size_t l, double tol, int max_iter, size_t *rf,
                     size_t *rl)
{
    for (int it = 0; it < max_iter; it++) {
        ft_fit fit;
        if (ft_fit_line(d->lx, d->ly, f, l, &fit) != FT_OK)
            return 0;
        size_t nf = f, nl = l;
        if (inlier_run(d, fit.slope, fit.intercept, tol, &nf, &nl) < 2)
            return 0;
        if (nf == f && nl == l) {
            *rf = f;
            *rl = l;
            return 1;
        }
        f = nf;
        l = nl;
    }
    return 0;
}

/* Root mean square of the least-squares residuals over rows [f, l] and the dimension of their slope. */
static double ls_rms(const ft_ll_data *d, size_t f, size_t l, double *D)
{
    ft_fit fit;
    *D = NAN;
    if (ft_fit_line(d->lx, d->ly, f, l, &fit) != FT_OK)
        return INFINITY;
    double sse = 0.0;
    for (size_t i = f; i <= l; i++) {
        double r = d->ly[i] - (fit.intercept + fit.slope * d->lx[i]);
        sse += r * r;
    }
    *D = d->map.a + d->map.b * fit.slope;
    return sqrt(sse / (double)(l - f + 1));
}

typedef struct {
    size_t first, last;
    double rms;
    int found;
} ils_best;

/* Keeps run [f, l] in *b if it is longer than *b's (or as long and straighter). */
static void keep_better(ils_best *b, size_t f, size_t l, double rms)
{
    if (b->found && (l - f < b->last - b->first || (f == b->first && l == b->last)))
        return;
    if (b->found && l - f == b->last - b->first && !(rms < b->rms))
        return;
    *b = (ils_best){f, l, rms, 1};
}

/* The longest converged run of any start (`any`) and the longest that qualifies (`admitted`). */
typedef struct {
    ils_best any, admitted;
} ils_choice;

/* Runs start [f, l] and offers its converged run to both choices. */
static void try_start(const ft_ll_data *d, const ft_loglog_opts *o, size_t f, size_t l, double tol, ils_choice *c)
{
    size_t rf, rl;
    if (!ils_start(d, f, l, tol, o->max_iter, &rf, &rl))
        return;
    double D, rms = ls_rms(d, rf, rl, &D);
    keep_better(&c->any, rf, rl, rms);
    if (ft_ll_admit(d, o, rf, rl, D) == FT_LL_ADMITTED)
        keep_better(&c->admitted, rf, rl, rms);
}

int ft_ll_ils(const ft_ll_data *d, const ft_loglog_opts *o, size_t *first, size_t *last, double *tol,
              int *admitted)
{
    double t = o->tol, t_noise = o->tol_sigma * ft_loglog_noise(d->t, d->a, d->b);
    t = t_noise > t ? t_noise : t;
    ils_choice c = {{0, 0, INFINITY, 0}, {0, 0, INFINITY, 0}};
    size_t k = o->min_points;
    try_start(d, o, d->a, d->b, t, &c);
    for (size_t i = d->a; i + k - 1 <= d->b; i++)
        try_start(d, o, i, i + k - 1, t, &c);
    *tol = t;
    if (!c.any.found || c.any.last - c.any.first + 1 < k)
        return ft_error(FT_E_NUMERIC,
                        "iterative least squares: no run of %zu or more rows lies within %g (log10 units) of "
                        "its least-squares line; raise the tolerance or check the table",
                        k, t);
    const ils_best *b = c.admitted.found ? &c.admitted : &c.any;
    *first = b->first;
    *last = b->last;
    *admitted = c.admitted.found;
    return FT_OK;
}
