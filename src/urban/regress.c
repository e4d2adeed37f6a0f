/* fracterra — src/urban/regress.c: the regression of Zhang, Yu & Fan (2008, §1.2, Eq. 5,
 * ln Areas = a + b D, their Fig. 2) relating a class's area to its box-counting dimension across years.
 *
 * Ordinary least squares y = intercept + slope x over n rows (y = ln of the input with log_y), by the
 * shared ft_fit_line (slope, intercept and their standard errors: s² = RSS / (n - 2), se(slope) =
 * sqrt(s² / Sxx), se(intercept) = sqrt(s² (1/n + mean(x)² / Sxx))). The correlation coefficient is
 * r = Sxy / sqrt(Sxx Syy), taken as the slope's sign times sqrt(r²), r² = 1 - RSS / Syy. Its standard
 * error is the one of the t test of rho = 0, se(r) = sqrt((1 - r²) / (n - 2)), so that t = r / se(r) =
 * slope / se(slope), with a two-sided p-value from Student's t with n - 2 degrees of freedom (GSL). The
 * paper prints r = 0.9527 from its own data; its Table 2 as printed (areas 116442, 190456, 285423, 413110
 * against D 1.3614, 1.3722, 1.4414, 1.4872) gives r = 0.954.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "fracterra/urban.h"
#include "internal.h"

static int check_rows(const double *x, const double *y, size_t n, int log_y)
{
    if (x == NULL || y == NULL)
        return ft_error(FT_E_INVALID, "regression: NULL %s", x == NULL ? "x" : "y");
    if (n < 3)
        return ft_error(FT_E_INVALID, "regression: needs at least 3 rows (standard errors use n - 2), got %zu", n);
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(x[i]))
            return ft_error(FT_E_NUMERIC, "regression: row %zu: x = %g is not finite", i + 1, x[i]);
        if (!isfinite(y[i]))
            return ft_error(FT_E_NUMERIC, "regression: row %zu: y = %g is not finite", i + 1, y[i]);
        if (log_y && !(y[i] > 0.0))
            return ft_error(FT_E_INVALID, "regression: row %zu: y = %g must be > 0 to take its logarithm", i + 1,
                            y[i]);
    }
    return FT_OK;
}

int ft_urban_regress(const double *x, const double *y, size_t n, int log_y, ft_urban_regression *out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_regress: NULL out");
    int rc = check_rows(x, y, n, log_y);
    if (rc != FT_OK)
        return rc;
    double *yy = ft_malloc(n * sizeof *yy);
    if (yy == NULL)
        return FT_E_NOMEM;
    int varies = 0;
    for (size_t i = 0; i < n; i++) {
        yy[i] = log_y ? log(y[i]) : y[i];
        varies |= yy[i] != yy[0];
    }
    if (!varies) {
        double y0 = yy[0];
        free(yy);
        return ft_error(FT_E_NUMERIC, "regression: every %s is the same (%g): no correlation is defined",
                        log_y ? "ln y" : "y", y0);
    }
    ft_fit fit;
    rc = ft_fit_line(x, yy, 0, n - 1, &fit);
    free(yy);
    if (rc != FT_OK) {
        char msg[256];
        snprintf(msg, sizeof msg, "%s", ft_last_error());
        return ft_error(rc, "regression: %s", msg);
    }
    /* r² = 1 - RSS / Syy = Sxy² / (Sxx Syy) for one regressor */
    const double r = copysign(sqrt(fit.r2), fit.slope), df = (double)(n - 2);
    *out = (ft_urban_regression){0};
    out->n = n;
    out->log_y = log_y != 0;
    out->slope = fit.slope;
    out->intercept = fit.intercept;
    out->r = r;
    out->r2 = fit.r2;
    out->stderr_slope = fit.stderr_slope;
    out->stderr_intercept = fit.stderr_intercept;
    out->stderr_r = sqrt((1.0 - fit.r2) / df);
    if (out->stderr_r > 0.0) {
        out->t = r / out->stderr_r;
        out->p_value = 2.0 * gsl_cdf_tdist_Q(fabs(out->t), df);
    } else {
        out->t = r > 0.0 ? INFINITY : -INFINITY;
        out->p_value = 0.0;
    }
    return FT_OK;
}
