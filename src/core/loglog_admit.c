/* fracterra — core/loglog_admit.c: which straight runs of a log-log table may give the dimension, and
 * the warnings of the fits that had to do without one.
 *
 * Arakawa & Krotkov §2.4 read D from "the slope of linear segments" (step 3), taking the straight parts
 * the segmentation finds (step 2) at face value. A straight run is evidence of a power law only if
 *   1. it holds at least min_points rows (a residual, hence an r² and a standard error);
 *   2. it spans a scale factor of at least min_span (default 4): a deterministic self-similar set of
 *      lacunarity q (q = 2^(1/D) for a midpoint curve, 3 for Koch) gives a staircase table whose
 *      straight treads span less than one period q, so they are never taken for the trend, and no
 *      power law is asserted over less than 0.6 decades;
 *   3. its D lies in the estimator's physical interval [d_min, d_max] of the map, within bounds_tol
 *      (default 0.05): a chain has 1 <= D <= 2, a surface 2 <= D <= 3; a tread of a divider table
 *      (length proportional to the ruler) has D = 0, a flat tail of box counts D = 0.
 * When runs exist but none qualifies, fit_auto fits the whole window and says so (docs/loglog.md).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <math.h>
#include <stdio.h>

/* Slack on the span test, in log10 units: rows a factor min_span apart qualify whatever the rounding. */
#define SPAN_SLACK 1e-9

int ft_ll_bounded(const ft_dim_map *m)
{
    return !(m->d_min == 0.0 && m->d_max == 0.0);
}

int ft_ll_in_bounds(const ft_dim_map *m, double D, double tol)
{
    return !ft_ll_bounded(m) || (D >= m->d_min - tol && D <= m->d_max + tol);
}

ft_ll_verdict ft_ll_admit(const ft_ll_data *d, const ft_loglog_opts *o, size_t first, size_t last, double D)
{
    if (last - first + 1 < o->min_points)
        return FT_LL_FEW_ROWS;
    if (d->lx[last] - d->lx[first] < log10(o->min_span) - SPAN_SLACK)
        return FT_LL_SHORT;
    if (!ft_ll_in_bounds(&d->map, D, o->bounds_tol))
        return FT_LL_OUT_OF_BOUNDS;
    return FT_LL_ADMITTED;
}

/* ", D in [lo, hi]" for a bounded map, "" otherwise, into buf. */
static const char *bounds_clause(const ft_dim_map *m, char *buf, size_t size)
{
    if (!ft_ll_bounded(m))
        return "";
    snprintf(buf, size, ", D in [%g, %g]", m->d_min, m->d_max);
    return buf;
}

char *ft_ll_whole_range_warning(const ft_ll_data *d, const ft_loglog_opts *o, double D)
{
    char clause[64], msg[512];
    double lo = d->t->rows[d->a].scale, hi = d->t->rows[d->b].scale;
    int n = snprintf(msg, sizeof msg,
                     "no straight run of the log-log table qualifies (%zu rows or more over a scale factor of "
                     "%g or more%s); D = %.4f is the least-squares fit over the whole range %g to %g (a factor "
                     "of %.3g): look at the local slopes (--plot) or give a range",
                     o->min_points, o->min_span, bounds_clause(&d->map, clause, sizeof clause), D, lo, hi,
                     hi / lo);
    if (!ft_ll_in_bounds(&d->map, D, o->bounds_tol) && n > 0 && (size_t)n < sizeof msg)
        snprintf(msg + n, sizeof msg - (size_t)n, "; that D lies outside [%g, %g]: the table does not follow "
                 "such a power law over this range", d->map.d_min, d->map.d_max);
    return ft_strdup(msg);
}
