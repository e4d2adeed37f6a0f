/* fracterra — bench/accuracy/accuracy_util.h: what the accuracy programs (accuracy.c, reconstruct.c) share:
 * comma-separated option lists and the row of a paper's table for a dimension.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_BENCH_ACCURACY_UTIL_H
#define FRACTERRA_BENCH_ACCURACY_UTIL_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/** Parses "a,b,c" into at most max doubles; returns how many were read. */
static inline int accuracy_parse_list(const char *s, double *v, int max)
{
    int n = 0;
    char buf[512];
    snprintf(buf, sizeof buf, "%s", s);
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t && n < max; t = strtok_r(NULL, ",", &save))
        v[n++] = atof(t);
    return n;
}

/** The row of a paper's table whose rows are D = first, first + 0.1, ... (nrows of them) holding D, or -1. */
static inline int accuracy_paper_row(double D, double first, int nrows)
{
    long k = lround((D - first) * 10.0);
    return k >= 0 && k < nrows && fabs(D - (first + 0.1 * (double)k)) < 1e-9 ? (int)k : -1;
}

#endif /* FRACTERRA_BENCH_ACCURACY_UTIL_H */
