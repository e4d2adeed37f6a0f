/* fracterra — surface/profile_dim.c: the fractal dimension of a profile by the power-variation estimators
 * of Gneiting, Sevcikova & Percival (2012, Statistical Science 27(2), 247-277, §3.2, Eq. 8-9): with
 *   V_p(l) = 1 / (2 (n - l)) sum_{i=1}^{n-l} |z_{i+l} - z_i|^p,
 *   D = 2 - (log V_p(2) - log V_p(1)) / (p log 2),
 * p = 2 the variogram estimator, p = 1 the madogram. For a self-affine profile E V_p(l) ~ l^(p H), and
 * lags 1 and 2 are the paper's choice: the shortest lags carry the most information about the local
 * roughness and their estimates are nearly unbiased for Gaussian profiles (their Table 2, measured in
 * docs/profile.md). The table (two rows) goes through the shared log-log module for its result, domain
 * check and JSON; its "few scales" and "narrow band" warnings are dropped, two neighbouring lags being the
 * method itself.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/surface.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const names[] = {"variogram", "madogram"};

const char *ft_profile_method_name(ft_profile_method m)
{
    return (unsigned)m < 2 ? names[m] : "?";
}

int ft_profile_method_parse(const char *name, ft_profile_method *m)
{
    if (name == NULL || m == NULL)
        return ft_error(FT_E_INVALID, "ft_profile_method_parse: NULL argument");
    for (int i = 0; i < 2; i++)
        if (strcasecmp(name, names[i]) == 0) {
            *m = (ft_profile_method)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "unknown profile method '%s' (variogram or madogram)", name);
}

/* V_p(lag) over the profile. */
static double power_variation(const double *z, size_t n, size_t lag, double p)
{
    double s = 0.0;
    for (size_t i = 0; i + lag < n; i++) {
        double d = fabs(z[i + lag] - z[i]);
        s += p == 2.0 ? d * d : d;
    }
    return s / (2.0 * (double)(n - lag));
}

/* Removes the warnings a two-lag estimator always earns. */
static void drop_design_warnings(ft_dim_result *r)
{
    size_t k = 0;
    for (size_t i = 0; i < r->nwarnings; i++) {
        if (strncmp(r->warnings[i], "few scales", 10) == 0 || strncmp(r->warnings[i], "narrow band", 11) == 0)
            free(r->warnings[i]);
        else
            r->warnings[k++] = r->warnings[i];
    }
    r->nwarnings = k;
}

int ft_profile_dim(const double *z, size_t n, double spacing, ft_profile_method m, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "profile dimension: NULL output");
    *out = NULL;
    if ((unsigned)m >= 2)
        return ft_error(FT_E_INVALID, "profile dimension: method must be 0 (variogram) or 1 (madogram), got %d",
                        (int)m);
    if (z == NULL || n < 3)
        return ft_error(FT_E_EMPTY, "profile dimension: needs at least 3 elevations, got %zu", z ? n : (size_t)0);
    if (!(spacing > 0.0) || !isfinite(spacing))
        return ft_error(FT_E_INVALID, "profile dimension: spacing must be finite and > 0, got %g", spacing);
    for (size_t i = 0; i < n; i++)
        if (!isfinite(z[i]))
            return ft_error(FT_E_NUMERIC, "profile dimension: elevation %zu is not finite (%g)", i, z[i]);
    double p = m == FT_PROFILE_VARIOGRAM ? 2.0 : 1.0;
    double v1 = power_variation(z, n, 1, p), v2 = power_variation(z, n, 2, p);
    if (!(v1 > 0.0) || !(v2 > 0.0))
        return ft_error(FT_E_NUMERIC, "profile dimension: the profile is constant at lag %d (no roughness to "
                        "measure)", v1 > 0.0 ? 2 : 1);
    ft_loglog *t = ft_loglog_create(2);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = ft_loglog_push(t, spacing, v1, (double)(n - 1));
    if (rc == FT_OK)
        rc = ft_loglog_push(t, 2.0 * spacing, v2, (double)(n - 2));
    const ft_dim_map vario = FT_DIM_MAP_VARIOGRAM_PROFILE, mado = FT_DIM_MAP_INCREMENT_PROFILE;
    if (rc == FT_OK)
        rc = ft_loglog_fit_range(t, 0.0, 0.0, m == FT_PROFILE_VARIOGRAM ? &vario : &mado, out);
    ft_loglog_free(t);
    if (rc != FT_OK)
        return rc;
    drop_design_warnings(*out);
    (*out)->method = names[m];
    (*out)->segmentation = "lags 1 and 2";
    (*out)->choice = "lags 1 and 2 (Gneiting, Sevcikova & Percival 2012)";
    (*out)->stderr_D = NAN; /* two lags leave no residual: the spread of D is the paper's (docs/profile.md) */
    return FT_OK;
}
