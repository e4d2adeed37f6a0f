/* fracterra — core/loglog_noise.c: a robust estimate of the scatter of a log-log table about a straight
 * line, which sets the noise-dependent part of the tolerances of the two segmentations of Arakawa &
 * Krotkov §2.4. Each interior point is compared with the chord through its two neighbours:
 *   d_i = y_i - (w_- y_{i-1} + w_+ y_{i+1}),  w_- = (x_{i+1} - x_i) / (x_{i+1} - x_{i-1}),  w_+ = 1 - w_-,
 * which is 0 on any straight line. For i.i.d. noise of sd sigma, Var d_i = sigma^2 (1 + w_-^2 + w_+^2),
 * so z_i = d_i / sqrt(1 + w_-^2 + w_+^2) has sd sigma, and sigma = 1.4826 * median |z_i - median z|.
 * A break in slope moves a single z_i and a steady curvature shifts them all alike: neither reaches
 * the median absolute deviation, so the estimate follows the noise, not the shape.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "loglog_internal.h"

#include <math.h>
#include <stdlib.h>

static int cmp_double(const void *pa, const void *pb)
{
    double a = *(const double *)pa, b = *(const double *)pb;
    return (a > b) - (a < b);
}

/* Median of v[0..n-1] (n >= 1), reordering v. */
static double median(double *v, size_t n)
{
    qsort(v, n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* Normalised distance of row i to the chord through rows i-1 and i+1. */
static double chord_residual(const ft_loglog *t, size_t i)
{
    double x0 = log10(t->rows[i - 1].scale), x1 = log10(t->rows[i].scale), x2 = log10(t->rows[i + 1].scale);
    double y0 = log10(t->rows[i - 1].value), y1 = log10(t->rows[i].value), y2 = log10(t->rows[i + 1].value);
    double wm = (x2 - x1) / (x2 - x0), wp = 1.0 - wm;
    return (y1 - (wm * y0 + wp * y2)) / sqrt(1.0 + wm * wm + wp * wp);
}

double ft_loglog_noise(const ft_loglog *t, size_t first, size_t last)
{
    if (t == NULL || last >= t->n || first > last || last - first < 2)
        return 0.0;
    size_t m = last - first - 1;
    double *z = malloc(m * sizeof *z);
    if (z == NULL) /* a few hundred bytes; without them the tolerances fall back to their absolute parts */
        return 0.0;
    for (size_t k = 0; k < m; k++)
        z[k] = chord_residual(t, first + 1 + k);
    double med = median(z, m);
    for (size_t k = 0; k < m; k++)
        z[k] = fabs(z[k] - med);
    double mad = median(z, m);
    free(z);
    return 1.4826 * mad;
}
