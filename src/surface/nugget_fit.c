/* fracterra — surface/nugget_fit.c: white noise on the elevations seen by the lag estimators (the nugget
 * of geostatistics; Matheron 1962, Cressie 1993 §2.3.1) and its removal. docs/surface-noise.md.
 *
 * With independent N(0, σ²) noise on z, every pair's difference gains 2σ² of variance, so the structure
 * functions of a fractional Brownian surface (variance a' r^(2H) of the noise-free increments) become,
 * with Gaussian increments (E|X| = sqrt(2/π) sd X):
 *
 *   mean Δz²            γ(r)  = 2σ² + a' r^(2H)                 (variogram)
 *   (mean |Δz|)²        E(r)² = (2/π)(2σ² + a' r^(2H))          (Yokoya; Arakawa & Krotkov §2.3)
 *   (sd of |Δz|)²       S(r)² = (1 - 2/π)(2σ² + a' r^(2H))      (Pentland)
 *
 * i.e. q(r) = value^power = c0 + a r^(2H) with power 1 or 2: a constant (the nugget c0) plus a power
 * law. On the log-log plot the noise flattens the curve toward the small lags and pushes D up, most at
 * low D. The fit profiles the exponent e = 2H over [0.01, 2] (a grid of 0.1, then golden section):
 * for each e, c0 >= 0 and a > 0 by weighted linear least squares with weights 1/q² (equal relative
 * errors, what a log-log fit assumes); the pure power law (c0 = 0) is profiled the same way and the F
 * statistic of the extra parameter, F = (RSS0 - RSS1) / (RSS1 / (n - 3)), with the share of c0 in the
 * smallest lag's q, decides whether a nugget is there. The test reads only the lags within 4 x the
 * smallest: one realization's sample variogram bends smoothly over its larger lags (the estimates of
 * nearby lags share their pairs and are strongly correlated, so the residuals understate that error), a
 * bend the free exponent turns into a nugget; white noise is a constant that shows at the smallest lags.
 *
 * Position noise (errors on x and y) is handled by the same constant: a pair observed at distance d has
 * its elevations at a true distance |d + δ|, δ ~ N(0, 2σ_p² I); to second order E q = q(d) + σ_p² (2H)²
 * a d^(2H-2), a term nearly constant in d for smooth surfaces (H near 1) and absorbed by c0, fast
 * vanishing for rough ones. The fit range starts where the power law exceeds the nugget (the floor).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "surface/grid_internal.h"

#define E_MIN 0.01
#define E_MAX 2.0
#define E_STEP 0.1
#define DETECT_P 0.05     /* level of the F test of the nugget against the pure power law, F(1, n - 3) */
#define DETECT_SHARE 0.05 /* and c0 at least this share of q at the smallest lag */
#define FLOOR_RATIO 1.0  /* the fit starts where a r^(2H) >= FLOOR_RATIO c0 */
#define NUGGET_SPAN 4.0  /* the nugget is fitted over the lags up to 4 x the smallest ... */
#define NUGGET_ROWS 4    /* ... or the smallest 4 lags, whichever are more */
#define XY_FLOOR 3.0     /* with position noise sd σ_p given, lags below XY_FLOOR σ_p are left out */

/* σ² of white noise on z per unit of c0 (the factor k in c0 = k σ²). */
static double noise_factor(ft_structure_stat stat)
{
    return stat == FT_STRUCT_MEAN_SQ ? 2.0 : stat == FT_STRUCT_MEAN_ABS ? 4.0 / M_PI : 2.0 * (1.0 - 2.0 / M_PI);
}

typedef struct {
    const double *lr, *q, *w; /* log scale, q, weight */
    size_t n;
    double c0_fixed;          /* >= 0: c0 held at this value; < 0: fitted (>= 0) */
    double *x;                /* scratch: r^e per row, then the grid step r^E_STEP per row */
    double emin, emax;        /* the exponents searched */
} profile_data;

double ft_nugget_wls(const double *x, const double *q, const double *w, size_t n, double c0_fixed, double *c0_out,
                     double *a_out)
{
    double S = 0.0, Sx = 0.0, Sxx = 0.0, Sq = 0.0, Sxq = 0.0;
    for (size_t i = 0; i < n; i++) {
        S += w[i];
        Sx += w[i] * x[i];
        Sxx += w[i] * x[i] * x[i];
        Sq += w[i] * q[i];
        Sxq += w[i] * x[i] * q[i];
    }
    double c0, a;
    if (c0_fixed >= 0.0) {
        c0 = c0_fixed;
        a = (Sxq - c0 * Sx) / Sxx;
    } else {
        double det = S * Sxx - Sx * Sx;
        a = det > 0.0 ? (S * Sxq - Sx * Sq) / det : 0.0;
        c0 = (Sq - a * Sx) / S;
        if (!(c0 >= 0.0)) {
            c0 = 0.0;
            a = Sxq / Sxx;
        }
    }
    if (!(a > 0.0) || !isfinite(a))
        return INFINITY;
    double rss = 0.0;
    for (size_t i = 0; i < n; i++) {
        double r = q[i] - c0 - a * x[i];
        rss += w[i] * r * r;
    }
    *c0_out = c0;
    *a_out = a;
    return rss;
}

/* Weighted LS of q on (1, r^e) at one exponent (ft_nugget_wls): RSS, c0 and a (INFINITY when a <= 0). */
static double rss_at(const profile_data *p, double e, double *c0_out, double *a_out)
{
    for (size_t i = 0; i < p->n; i++)
        p->x[i] = exp(e * p->lr[i]);
    return ft_nugget_wls(p->x, p->q, p->w, p->n, p->c0_fixed, c0_out, a_out);
}

/* The exponent e minimising the RSS: a grid, then golden section around the best grid point. On the
 * grid r^e is stepped by a product (r^(e + E_STEP) = r^e r^E_STEP; n exp calls per profile instead of one
 * per row and exponent), the golden section stops at a bracket of GOLDEN_TOL in e and ends with one
 * parabolic step (Brent 1973, ch. 5). */
#define GOLDEN_TOL 1e-4
static double profile(const profile_data *p, double *e_out, double *c0, double *a)
{
    double best = INFINITY, eb = NAN, cc, aa;
    double *x = p->x, *step = p->x + p->n;
    for (size_t i = 0; i < p->n; i++) {
        x[i] = exp(p->emin * p->lr[i]);
        step[i] = exp(E_STEP * p->lr[i]);
    }
    int ne = (int)floor((p->emax - p->emin) / E_STEP + 1e-9);
    for (int j = 0; j <= ne; j++) {
        if (j > 0)
            for (size_t i = 0; i < p->n; i++)
                x[i] *= step[i];
        double r = ft_nugget_wls(x, p->q, p->w, p->n, p->c0_fixed, &cc, &aa);
        if (r < best) {
            best = r;
            eb = p->emin + (double)j * E_STEP;
        }
    }
    if (!isfinite(best))
        return INFINITY;
    double lo = fmax(p->emin, eb - E_STEP), hi = fmin(p->emax, eb + E_STEP), g = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = rss_at(p, x1, &cc, &aa), f2 = rss_at(p, x2, &cc, &aa);
    while (hi - lo > GOLDEN_TOL) {
        if (f1 < f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = rss_at(p, x1, &cc, &aa);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = rss_at(p, x2, &cc, &aa);
        }
    }
    double e = 0.5 * (lo + hi), r = rss_at(p, e, &cc, &aa);
    /* one parabolic step through (x1, f1), (e, r), (x2, f2): the RSS is quadratic near its minimum */
    double u = (e - x1) * (r - f2), v = (e - x2) * (r - f1), den = u - v;
    if (den != 0.0) {
        double xp = e - 0.5 * ((e - x1) * u - (e - x2) * v) / den;
        if (xp > lo && xp < hi) {
            double rp = rss_at(p, xp, &cc, &aa);
            if (rp < r) {
                e = xp;
                r = rp;
            } else {
                rss_at(p, e, &cc, &aa);
            }
        }
    }
    if (!(r <= best)) {
        e = eb;
        r = rss_at(p, e, &cc, &aa);
    }
    *e_out = e;
    *c0 = cc;
    *a = aa;
    return r;
}

double ft_nugget_profile(const double *lr, const double *q, const double *w, size_t n, double c0_fixed, double emin,
                         double emax, double *scratch, double *e, double *c0, double *a)
{
    profile_data p = {lr, q, w, n, c0_fixed, scratch, emin, emax};
    return profile(&p, e, c0, a);
}

int ft_nugget_fit(const ft_loglog *t, ft_structure_stat stat, double sigma_z, ft_noise_model *m)
{
    if (t == NULL || m == NULL)
        return ft_error(FT_E_INVALID, "nugget fit: the table or the model is NULL");
    if ((unsigned)stat > FT_STRUCT_SD_ABS)
        return ft_error(FT_E_INVALID, "nugget fit: unknown statistic %d", (int)stat);
    if (!(sigma_z >= 0.0) || !isfinite(sigma_z))
        return ft_error(FT_E_INVALID, "nugget fit: noise sigma must be >= 0, got %g", sigma_z);
    *m = (ft_noise_model){0};
    m->power = stat == FT_STRUCT_MEAN_SQ ? 1.0 : 2.0;
    size_t need = sigma_z > 0.0 ? 3 : 4;
    if (t->n < need)
        return ft_error(FT_E_EMPTY, "nugget fit: needs at least %zu rows, got %zu", need, t->n);
    double *buf = ft_malloc(5 * t->n * sizeof *buf);
    if (buf == NULL)
        return FT_E_NOMEM;
    profile_data p = {buf, buf + t->n, buf + 2 * t->n, t->n, -1.0, buf + 3 * t->n, E_MIN, E_MAX};
    for (size_t i = 0; i < t->n; i++) {
        double q = pow(t->rows[i].value, m->power);
        buf[i] = log(t->rows[i].scale);
        buf[t->n + i] = q;
        buf[2 * t->n + i] = 1.0 / (q * q);
    }
    double k = noise_factor(stat), e1 = NAN, c0 = 0.0, a = 0.0;
    if (sigma_z > 0.0)
        p.c0_fixed = k * sigma_z * sigma_z;
    double rss1 = profile(&p, &e1, &c0, &a);
    double F = 0.0;
    /* With c0 held at its bound 0 at the free optimum the pure power law fits as well: F = 0, no profile. */
    if (sigma_z == 0.0 && isfinite(rss1) && c0 > 0.0) {
        double e0, c00, a0;
        p.c0_fixed = 0.0;
        double rss0 = profile(&p, &e0, &c00, &a0);
        F = rss1 > 0.0 ? (rss0 - rss1) / (rss1 / (double)(t->n - 3)) : (rss0 > 0.0 ? INFINITY : 0.0);
    }
    free(buf);
    if (!isfinite(rss1))
        return ft_error(FT_E_NUMERIC, "nugget fit: no increasing power law fits the %zu rows", t->n);
    m->fitted = 1;
    m->c0 = c0;
    m->a = a;
    m->H = 0.5 * e1;
    m->F = F;
    m->sigma_z = sqrt(c0 / k);
    return FT_OK;
}

int ft_nugget_detected(const ft_noise_model *m, const ft_loglog *t)
{
    if (!m->fitted || !(m->c0 > 0.0) || t->n == 0)
        return 0;
    double q0 = pow(t->rows[0].value, m->power);
    return t->n > 3 && m->F >= gsl_cdf_fdist_Qinv(DETECT_P, 1.0, (double)(t->n - 3)) && m->c0 >= DETECT_SHARE * q0;
}

int ft_nugget_remove(const ft_loglog *t, ft_noise_model *m, double min_floor, ft_loglog **out)
{
    *out = NULL;
    ft_loglog *c = ft_loglog_create(t->n);
    if (c == NULL)
        return FT_E_NOMEM;
    /* The floor: where the fitted power law reaches FLOOR_RATIO times the nugget. */
    double floor = m->c0 > 0.0 && m->H > 0.0 ? pow(FLOOR_RATIO * m->c0 / m->a, 1.0 / (2.0 * m->H)) : 0.0;
    m->floor = fmax(floor, min_floor);
    m->applied = 1;
    int rc = FT_OK;
    for (size_t i = 0; i < t->n && rc == FT_OK; i++) {
        double q = pow(t->rows[i].value, m->power) - m->c0;
        if (q > 0.0)
            rc = ft_loglog_push(c, t->rows[i].scale, pow(q, 1.0 / m->power), t->rows[i].count);
    }
    if (rc != FT_OK) {
        ft_loglog_free(c);
        return rc;
    }
    *out = c;
    return FT_OK;
}

/* The fit of the rows with scale >= lo (whole range or the shared segmentation). */
static int fit_from(const ft_loglog *t, double lo, int whole, const ft_loglog_opts *fit, const ft_dim_map *map,
                    ft_dim_result **out)
{
    return whole ? ft_loglog_fit_range(t, lo, 0.0, map, out) : ft_loglog_fit_auto(t, lo, 0.0, fit, map, out);
}

int ft_surface_fit_noise(const ft_loglog *t, const ft_noise_opts *no, ft_structure_stat stat, int whole,
                         const ft_loglog_opts *fit, const ft_dim_map *map, ft_dim_result **out)
{
    ft_noise_opts taken = FT_NOISE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (no != NULL) {
        if (FT_OPTS_TAKE(taken, no, ft_noise_opts) != FT_OK)
            return FT_E_INVALID;
        no = &taken;
    }
    *out = NULL;
    ft_noise_model m = {0};
    int given = no->sigma_z > 0.0;
    if (!(no->sigma_z >= 0.0) || !isfinite(no->sigma_z) || !(no->sigma_xy >= 0.0) || !isfinite(no->sigma_xy))
        return ft_error(FT_E_INVALID, "noise sd must be finite and >= 0, got %g on z and %g on x, y", no->sigma_z,
                        no->sigma_xy);
    if (no->mode < 0 || (t->n < 4 && !given) || t->n < 3)
        return fit_from(t, 0.0, whole, fit, map, out);
    /* The nugget shows at the small lags; the large ones carry the realization's own curvature, which
     * the model would trade against c0: the fit uses the rows within NUGGET_SPAN x the smallest scale. */
    ft_loglog head = *t;
    while (head.n > NUGGET_ROWS && head.rows[head.n - 1].scale > NUGGET_SPAN * t->rows[0].scale)
        head.n--;
    int rc = ft_nugget_fit(&head, stat, no->sigma_z, &m);
    if (rc != FT_OK) /* no increasing power law: leave the table to the ordinary fit and its checks */
        return fit_from(t, 0.0, whole, fit, map, out);
    int detected = given || ft_nugget_detected(&m, &head);
    double min_floor = XY_FLOOR * no->sigma_xy;
    if (!detected && min_floor <= 0.0) {
        rc = fit_from(t, 0.0, whole, fit, map, out);
        if (rc == FT_OK)
            (*out)->nugget = m;
        return rc;
    }
    ft_loglog *owned = NULL;
    const ft_loglog *c = t;
    if (detected) {
        rc = ft_nugget_remove(t, &m, min_floor, &owned);
        if (rc != FT_OK)
            return rc;
        c = owned;
    } else {
        m.floor = min_floor;
    }
    size_t need = fit->min_points > 3 ? fit->min_points : 3, above = 0;
    for (size_t i = 0; i < c->n; i++)
        above += c->rows[i].scale >= m.floor * (1.0 - 1e-9);
    double lo = m.floor;
    int short_range = 0;
    if (c->n < 2) {
        rc = ft_error(FT_E_NUMERIC, "the noise (nugget %g, noise sd %g) exceeds the statistic at every lag but "
                      "%zu: no lag is left to fit; use larger lags", m.c0, m.sigma_z, c->n);
    } else if (above < need) {
        short_range = 1;
        lo = c->rows[c->n >= need ? c->n - need : 0].scale;
    }
    if (rc == FT_OK)
        rc = fit_from(c, lo, whole, fit, map, out);
    if (rc == FT_OK) {
        ft_dim_result *r = *out;
        r->nugget = m;
        r->nugget.applied = detected;
        r->nugget.detected = detected;
        if (detected && given)
            rc = ft_dim_result_warn(r, "noise model: the given noise sd %g on z (nugget %g) was removed from the "
                                    "statistic; the fit starts at scale %g", no->sigma_z, m.c0, lo);
        else if (detected)
            rc = ft_dim_result_warn(r, "noise detected: the log-log plot flattens toward the small lags (a nugget "
                                    "of %.3g, %.0f%% of the statistic at the smallest lag, F = %.3g); estimated "
                                    "noise sd on z %.4g; the nugget was removed and the fit starts at scale %g, "
                                    "where the power law exceeds the noise", m.c0,
                                    100.0 * m.c0 / pow(t->rows[0].value, m.power), m.F, m.sigma_z, lo);
        if (rc == FT_OK && min_floor > 0.0)
            rc = ft_dim_result_warn(r, "noise model: position noise sd %g on x and y: lags below %g left out",
                                    no->sigma_xy, min_floor);
        if (rc == FT_OK && short_range)
            rc = ft_dim_result_warn(r, "noise dominates up to scale %g: only the %zu largest lags (from %g) are "
                                    "fitted; use larger lags", m.floor, need, lo);
        if (rc != FT_OK) {
            ft_dim_result_free(r);
            *out = NULL;
        }
    }
    ft_loglog_free(owned);
    return rc;
}
