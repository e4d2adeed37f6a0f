/* fracterra — surface/nugget_positions.c: noise on x, y and z of scattered elevations, an errors-in-
 * variables model of the mean squared difference (docs/surface-noise.md).
 *
 * Two points observed a distance d apart carry the elevations of a true separation d + δ, δ the
 * difference of their position errors, N(0, s² I₂) with s² = 2σ_p² (for points spread evenly, the true
 * separation given the observed one has this law too). With white N(0, σ_z²) noise on z and a fractional
 * Brownian surface of variogram a r^(2H):
 *
 *   E Δz²(d) = 2σ_z² + a E|d + δ|^(2H) = c0 + a s^(2H) 2^H Γ(1 + H) M(-H, 1, -d² / (2s²))
 *
 * (the moment of order H of the noncentral χ² with 2 degrees of freedom, M Kummer's function; it tends
 * to d^(2H) as s -> 0 and to the constant a s^(2H) 2^H Γ(1 + H) as d -> 0: position noise flattens
 * the plot toward small lags like a nugget, but fades with d). The fit profiles H and s on grids, c0 >= 0
 * and a by weighted linear least squares (weights 1/q²), and compares with the pure power law by an F
 * test on the two extra parameters. Of the two noise terms only those the data ask for are kept: the
 * z-only model (s = 0) unless s adds F >= XY_F, then, for H < XY_ONLY_H, the position-only model (c0 = 0)
 * unless c0 adds F >= XY_F (nested models, one parameter each): a free c0 trades against s and on rough
 * surfaces can take many times the z noise, over-correcting the lags near the floor.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "surface/grid_internal.h"

#define H_STEP 0.02
#define NS 28          /* position-noise sds tried, geometric between the smallest and a third of the largest lag */
#define DETECT_F 3.0
#define DETECT_SHARE 0.02
#define XY_ONLY_H 0.5  /* the position-only model is tried below this H only */
#define XY_F 4.0       /* the position noise is kept when it adds F >= XY_F to the z-only model */

/* The factor of the Kummer branch that depends on (H, s) only: s^2H 2^H Γ(1+H). */
static double eiv_scale(double H, double s)
{
    return pow(s, 2.0 * H) * pow(2.0, H) * tgamma(1.0 + H);
}

/* E|d + δ|^(2H), δ ~ N(0, s² I₂), with scale = eiv_scale(H, s) (computed once per (H, s) by the fits). */
static double eiv_moment_scaled(double H, double d, double s, double scale)
{
    if (!(s > 0.0))
        return pow(d, 2.0 * H);
    double x = d * d / (2.0 * s * s), m;
    if (x > 40.0) { /* asymptotic: x^H / Γ(1+H) Σ ((-H)_k)² / k! x^-k */
        double term = 1.0, sum = 1.0;
        for (int k = 1; k < 8; k++) {
            double p = (-H + (double)(k - 1));
            term *= p * p / ((double)k * x);
            sum += term;
        }
        return pow(d, 2.0 * H) * sum;
    }
    /* Kummer: M(-H, 1, -x) = e^-x M(1 + H, 1, x), positive terms */
    double term = 1.0, sum = 1.0;
    for (int k = 1; k < 400; k++) {
        term *= (H + (double)k) * x / ((double)k * (double)k);
        sum += term;
        if (term < 1e-17 * sum)
            break;
    }
    m = exp(-x) * sum;
    return scale * m;
}

/* E|d + δ|^(2H), δ ~ N(0, s² I₂). */
double ft_nugget_eiv_moment(double H, double d, double s)
{
    return eiv_moment_scaled(H, d, s, s > 0.0 ? eiv_scale(H, s) : 0.0);
}

typedef struct {
    const double *d, *q, *w;
    size_t n;
    double c0_fixed; /* >= 0: held */
    double *g;       /* scratch: the moments at the current (H, s) */
} eiv_data;

/* RSS of the weighted LS of q on (1, g) with c0 >= 0 and a > 0 (INFINITY otherwise). */
static double eiv_rss(eiv_data *p, double H, double s, double *c0_out, double *a_out)
{
    double scale = s > 0.0 ? eiv_scale(H, s) : 0.0;
    for (size_t i = 0; i < p->n; i++)
        p->g[i] = eiv_moment_scaled(H, p->d[i], s, scale);
    return ft_nugget_wls(p->g, p->q, p->w, p->n, p->c0_fixed, c0_out, a_out);
}

/* Best (H, s) over the grids (s = 0 alone when s_fixed == 0, the given s when > 0, the grid when < 0),
 * then H refined by golden section at that s. */
static double eiv_profile(eiv_data *p, double s_fixed, double *H, double *s, double *c0, double *a)
{
    double dmin = p->d[0], dmax = p->d[p->n - 1], best = INFINITY, cc, aa;
    double slo = dmin / 4.0, shi = dmax / 3.0;
    int ns = s_fixed < 0.0 ? NS + 1 : 1;
    for (int j = 0; j < ns; j++) {
        double sj = s_fixed >= 0.0 ? s_fixed : j == 0 ? 0.0 : slo * pow(shi / slo, (double)(j - 1) / (NS - 1));
        for (double h = H_STEP / 2.0; h < 1.0; h += H_STEP) {
            double r = eiv_rss(p, h, sj, &cc, &aa);
            if (r < best) {
                best = r;
                *H = h;
                *s = sj;
            }
        }
    }
    if (!isfinite(best))
        return INFINITY;
    double lo = fmax(1e-3, *H - H_STEP), hi = fmin(0.999, *H + H_STEP), g = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = eiv_rss(p, x1, *s, &cc, &aa), f2 = eiv_rss(p, x2, *s, &cc, &aa);
    for (int it = 0; it < 30; it++) {
        if (f1 < f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - g * (hi - lo);
            f1 = eiv_rss(p, x1, *s, &cc, &aa);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + g * (hi - lo);
            f2 = eiv_rss(p, x2, *s, &cc, &aa);
        }
    }
    double h = 0.5 * (lo + hi), r = eiv_rss(p, h, *s, &cc, &aa);
    if (r <= best) {
        *H = h;
        best = r;
    }
    best = eiv_rss(p, *H, *s, c0, a);
    return best;
}

int ft_nugget_fit_positions(const double *d, const double *q, size_t n, double sigma_z, double sigma_xy,
                            ft_noise_model *m)
{
    if (d == NULL || q == NULL || m == NULL)
        return ft_error(FT_E_INVALID, "position-noise fit: NULL argument");
    if (!(sigma_z >= 0.0) || !isfinite(sigma_z) || !(sigma_xy >= 0.0) || !isfinite(sigma_xy))
        return ft_error(FT_E_INVALID, "position-noise fit: noise sd must be finite and >= 0, got %g (z) and %g "
                        "(x, y)", sigma_z, sigma_xy);
    *m = (ft_noise_model){0};
    m->power = 1.0;
    if (n < 6)
        return ft_error(FT_E_EMPTY, "position-noise fit: needs at least 6 lags, got %zu", n);
    for (size_t i = 0; i < n; i++)
        if (!(d[i] > 0.0) || !(q[i] > 0.0) || (i > 0 && !(d[i] > d[i - 1])))
            return ft_error(FT_E_INVALID, "position-noise fit: lag %zu (distance %g, value %g) is not positive "
                            "and increasing", i + 1, d[i], q[i]);
    double *buf = ft_malloc(2 * n * sizeof *buf);
    if (buf == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < n; i++)
        buf[i] = 1.0 / (q[i] * q[i]);
    eiv_data p = {d, q, buf, n, sigma_z > 0.0 ? 2.0 * sigma_z * sigma_z : -1.0, buf + n};
    double H1 = NAN, s1 = 0.0, c0 = 0.0, a = 0.0;
    double rss1 = eiv_profile(&p, sigma_xy > 0.0 ? sqrt(2.0) * sigma_xy : -1.0, &H1, &s1, &c0, &a);
    double H0 = NAN, s0 = 0.0, c00, a0, c0_given = p.c0_fixed;
    p.c0_fixed = 0.0;
    double rss0 = eiv_profile(&p, 0.0, &H0, &s0, &c00, &a0);
    p.c0_fixed = c0_given;
    /* A full model that does not beat the pure power law (F < DETECT_F) is not detected, and neither is
     * any of its nested models: no choice to make. */
    int choose = isfinite(rss1) && rss1 > 0.0 && ((rss0 - rss1) / 2.0) / (rss1 / (double)(n - 4)) >= DETECT_F;
    /* Model choice: the z-only model (s = 0) unless the position noise reduces the RSS significantly
     * (F >= XY_F on its one parameter). White z noise alone is a constant the counters' default lags
     * can carry. */
    if (choose && s1 > 0.0 && !(sigma_xy > 0.0) && n > 5) {
        double Hz = NAN, sz = 0.0, c0z = 0.0, az = 0.0;
        double rssz = eiv_profile(&p, 0.0, &Hz, &sz, &c0z, &az);
        if (isfinite(rssz) && (rss1 <= 0.0 ? rssz <= 0.0 : (rssz - rss1) / (rss1 / (double)(n - 4)) < XY_F)) {
            rss1 = rssz;
            H1 = Hz;
            s1 = 0.0;
            c0 = c0z;
            a = az;
        }
    }
    /* And on rough surfaces (H < XY_ONLY_H) the position-only model (c0 = 0) unless the nugget reduces the
     * RSS by F >= XY_F: there a free c0 trades against s and can take far more than the z noise. On smooth
     * ones the position noise's excess, σ_p² (2H)² a d^(2H-2) to second order, is nearly a constant itself,
     * and a small s passes for white z noise (c0 would be dropped from z-only data). */
    if (choose && s1 > 0.0 && c0 > 0.0 && H1 < XY_ONLY_H && !(sigma_z > 0.0) && n > 5) {
        double Hx = NAN, sx = 0.0, c0x = 0.0, ax = 0.0;
        p.c0_fixed = 0.0;
        double rssx = eiv_profile(&p, sigma_xy > 0.0 ? sqrt(2.0) * sigma_xy : -1.0, &Hx, &sx, &c0x, &ax);
        p.c0_fixed = c0_given;
        if (isfinite(rssx) && sx > 0.0 &&
            (rss1 <= 0.0 ? rssx <= 0.0 : (rssx - rss1) / (rss1 / (double)(n - 4)) < XY_F)) {
            rss1 = rssx;
            H1 = Hx;
            s1 = sx;
            c0 = 0.0;
            a = ax;
        }
    }
    free(buf);
    if (!isfinite(rss1))
        return ft_error(FT_E_NUMERIC, "position-noise fit: no increasing power law fits the %zu lags", n);
    m->fitted = 1;
    m->positions = 1;
    m->c0 = c0;
    m->a = a;
    m->H = H1;
    m->s = s1;
    m->sigma_z = sqrt(c0 / 2.0);
    m->sigma_xy = s1 / sqrt(2.0);
    m->F = rss1 > 0.0 ? ((rss0 - rss1) / 2.0) / (rss1 / (double)(n - 4)) : (rss0 > 0.0 ? INFINITY : 0.0);
    double noise0 = q[0] - a * pow(d[0], 2.0 * H1); /* what the noise adds at the smallest lag */
    m->detected = sigma_z > 0.0 || sigma_xy > 0.0 || (m->F >= DETECT_F && noise0 >= DETECT_SHARE * q[0]);
    return FT_OK;
}

double ft_nugget_model_value(const ft_noise_model *m, double d)
{
    return m->c0 + m->a * ft_nugget_eiv_moment(m->H, d, m->s);
}
