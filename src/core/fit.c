/* fracterra — core/fit.c: ordinary least-squares line fits (the log-log regression of every estimator).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* Fits y = a + b x over n points; `base` is the caller's index of x[0] and `xname` names x in messages.
 * Two passes (means first, then centred sums) keep precision when x or y sit far from zero. */
static int fit_core(const double *x, const double *y, size_t n, size_t base, const char *xname, ft_fit *fit)
{
    double xm = 0.0, ym = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            return ft_error(FT_E_NUMERIC, "line fit: x[%zu] = %g is not finite", base + i, x[i]);
        if (!isfinite(y[i]))
            return ft_error(FT_E_NUMERIC, "line fit: y[%zu] = %g is not finite", base + i, y[i]);
        xm += x[i];
        ym += y[i];
    }
    xm /= (double)n;
    ym /= (double)n;
    double sxx = 0.0, sxy = 0.0, syy = 0.0;
    for (size_t i = 0; i < n; i++) {
        double dx = x[i] - xm, dy = y[i] - ym;
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    if (!(sxx > 0.0))
        return ft_error(FT_E_INVALID, "line fit: all %zu %s values are equal (%g)", n, xname, x[0]);
    double slope = sxy / sxx, intercept = ym - slope * xm, sse = 0.0;
    for (size_t i = 0; i < n; i++) {
        double r = y[i] - (intercept + slope * x[i]);
        sse += r * r;
    }
    if (!isfinite(slope) || !isfinite(intercept) || !isfinite(sse))
        return ft_error(FT_E_NUMERIC, "line fit: overflow in the sums over %zu points", n);
    double r2 = syy > 0.0 ? 1.0 - sse / syy : 1.0;
    fit->slope = slope;
    fit->intercept = intercept;
    fit->r2 = r2 < 0.0 ? 0.0 : (r2 > 1.0 ? 1.0 : r2);
    if (n > 2) {
        double s2 = sse / (double)(n - 2);
        fit->stderr_slope = sqrt(s2 / sxx);
        fit->stderr_intercept = sqrt(s2 * (1.0 / (double)n + xm * xm / sxx));
    }
    fit->n = n;
    return FT_OK;
}

/* Common argument checks; clears *fit and records the range. */
static int fit_prepare(const void *a, const void *b, size_t first, size_t last, ft_fit *fit)
{
    if (fit == NULL)
        return ft_error(FT_E_INVALID, "line fit: NULL result");
    memset(fit, 0, sizeof *fit);
    fit->first = first;
    fit->last = last;
    if (a == NULL || b == NULL)
        return ft_error(FT_E_INVALID, "line fit: NULL data array");
    if (first > last)
        return ft_error(FT_E_INVALID, "line fit: first index %zu is after last index %zu", first, last);
    if (last - first == SIZE_MAX)
        return ft_error(FT_E_INVALID, "line fit: index range [%zu, %zu] is too large", first, last);
    if (last - first < 1)
        return ft_error(FT_E_INVALID, "line fit: needs at least 2 points, got 1 (index %zu)", first);
    return FT_OK;
}

int ft_fit_line(const double *x, const double *y, size_t first, size_t last, ft_fit *fit)
{
    int rc = fit_prepare(x, y, first, last, fit);
    if (rc != FT_OK)
        return rc;
    return fit_core(x + first, y + first, last - first + 1, first, "x", fit);
}

/* log10 of one input value; NaN/Inf and values <= 0 are FT_E_NUMERIC naming the index and value. */
static int log_of(const char *what, const double *v, size_t i, double *out)
{
    if (!isfinite(v[i]))
        return ft_error(FT_E_NUMERIC, "log-log fit: %s[%zu] = %g is not finite", what, i, v[i]);
    if (!(v[i] > 0.0))
        return ft_error(FT_E_NUMERIC, "log-log fit: %s[%zu] = %g must be > 0", what, i, v[i]);
    *out = log10(v[i]);
    return FT_OK;
}

int ft_fit_loglog(const double *scale, const double *value, size_t first, size_t last, ft_fit *fit)
{
    int rc = fit_prepare(scale, value, first, last, fit);
    if (rc != FT_OK)
        return rc;
    size_t n = last - first + 1;
    double *lx = ft_realloc_array(NULL, n, 2 * sizeof *lx);
    if (lx == NULL)
        return FT_E_NOMEM;
    double *ly = lx + n;
    for (size_t i = 0; i < n && rc == FT_OK; i++) {
        rc = log_of("scale", scale, first + i, &lx[i]);
        if (rc == FT_OK)
            rc = log_of("value", value, first + i, &ly[i]);
    }
    if (rc == FT_OK)
        rc = fit_core(lx, ly, n, first, "log10(scale)", fit);
    free(lx);
    return rc;
}
