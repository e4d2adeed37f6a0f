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

/* Why a straight run may not give the dimension (loglog_admit.c). */
typedef enum {
    FT_LL_ADMITTED = 0,  /* qualifies */
    FT_LL_FEW_ROWS,      /* fewer than min_points rows */
    FT_LL_SHORT,         /* spans a scale factor under min_span */
    FT_LL_OUT_OF_BOUNDS  /* D outside [d_min, d_max] by more than bounds_tol */
} ft_ll_verdict;

/* 1 if the map carries bounds (not d_min == d_max == 0). */
int ft_ll_bounded(const ft_dim_map *m);
/* 1 if D lies in [d_min - tol, d_max + tol], or the map has no bounds. */
int ft_ll_in_bounds(const ft_dim_map *m, double D, double tol);
/* Whether rows [first, last] of the window, whose least-squares dimension is D, may give the result. */
ft_ll_verdict ft_ll_admit(const ft_ll_data *d, const ft_loglog_opts *o, size_t first, size_t last, double D);
/* The allocated warning of a whole-window fallback whose dimension is D; NULL if out of memory. */
char *ft_ll_whole_range_warning(const ft_ll_data *d, const ft_loglog_opts *o, double D);

/* ILS over the window, the tolerance it used in *tol. *admitted = 1: [*first, *last] is the longest
 * qualifying converged run; 0: no converged run qualifies ([*first, *last] is the longest of them).
 * Fails if no converged run has min_points rows. */
int ft_ll_ils(const ft_ll_data *d, const ft_loglog_opts *o, size_t *first, size_t *last, double *tol,
              int *admitted);

/* Minimax segmentation of the window: the segments by increasing scale, the index of the longest
 * (first chosen) and the width used. */
int ft_ll_minimax(const ft_ll_data *d, const ft_loglog_opts *o, ft_loglog_segment **segs, size_t *nsegs,
                  size_t *longest, double *width);

/* Curvature test of rows [first, last] (loglog_regimes.c): 1 if curved; *dD the change of D across the
 * rows from the quadratic term, *tq its t statistic. */
int ft_ll_curved(const ft_ll_data *d, const ft_loglog_opts *o, size_t first, size_t last, double *dD, double *tq);

/* The regimes (straight runs by the curvature test) of the window by increasing scale and the
 * *nregimes - 1 break scales between them (NULL when fewer than 2 regimes). */
int ft_ll_regimes(const ft_ll_data *d, const ft_loglog_opts *o, ft_loglog_segment **regimes, size_t *nregimes,
                  double **breaks);

/* Fewest boxes, steps or pairs at a used row below which a count is called few (a warning). */
#define FT_LL_FEW_COUNTS 30

#endif /* FRACTERRA_LOGLOG_INTERNAL_H */
