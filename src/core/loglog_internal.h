/* fracterra — core/loglog_internal.h: what the log-log modules (loglog_*.c) share, not installed.
 * Arakawa & Krotkov §2.4: the table in log10 space, its search window and the exact minimax line fit.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LOGLOG_INTERNAL_H
#define FRACTERRA_LOGLOG_INTERNAL_H

#include "fracterra/core.h"

#include <stddef.h>

/* Slack on tolerance tests, in log10 units: rounding must not split an exact power law. */
#define FT_LL_SLACK 1e-12

/* A checked table in log10 space and the rows [a, b] a segmentation may use. */
typedef struct {
    const ft_loglog *t;
    double *lx, *ly; /* log10(scale), log10(value), t->n each (one allocation, owned by lx) */
    size_t *work;    /* 2 * t->n scratch indices for ft_ll_chebyshev */
    size_t a, b;
    ft_dim_map map;
} ft_ll_data;

/* Checks the table and the map, computes the logs and the window lo <= scale <= hi (0 = no limit);
 * fails unless the window holds at least min_rows rows. Release with ft_ll_data_free. */
int ft_ll_data_init(ft_ll_data *d, const ft_loglog *t, double lo, double hi, const ft_dim_map *map,
                    size_t min_rows);
void ft_ll_data_free(ft_ll_data *d);

/* Checks the segmentation options (NULL = defaults) into *o. */
int ft_ll_opts_check(const ft_loglog_opts *opts, ft_loglog_opts *o);

/* Exact minimax (Chebyshev) line y = c + s x through k >= 1 points with strictly increasing x: the
 * line minimising max |y_i - c - s x_i|, whose value is *err. work holds 2k size_t. */
void ft_ll_chebyshev(const double *x, const double *y, size_t k, size_t *work, double *s, double *c,
                     double *err);

/* Describes rows [first, last] (>= 2 rows) as a segment: least squares, minimax error, D. */
int ft_ll_describe(const ft_ll_data *d, size_t first, size_t last, ft_loglog_segment *seg);

/* ILS over the window: the converged run [*first, *last] and the tolerance it used. */
int ft_ll_ils(const ft_ll_data *d, const ft_loglog_opts *o, size_t *first, size_t *last, double *tol);

/* Minimax segmentation of the window: the segments by increasing scale, the index of the longest
 * (first chosen) and the width used. */
int ft_ll_minimax(const ft_ll_data *d, const ft_loglog_opts *o, ft_loglog_segment **segs, size_t *nsegs,
                  size_t *longest, double *width);

#endif /* FRACTERRA_LOGLOG_INTERNAL_H */
