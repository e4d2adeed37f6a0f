/* fracterra — surface/spectrum_floor.c: white noise on the elevations seen by the power spectrum, a flat
 * floor under the power law (docs/surface-noise.md).
 *
 * Independent N(0, σ²) noise on z has a flat spectrum: with the normalisations of spectrum.c (the
 * differencing gain divided out, or the periodogram divided by the taper's Σw²) its power is σ² at every
 * frequency. The radially averaged spectrum of a noisy fractional Brownian surface is then
 *
 *   P(f) = A f^-β + N0,   N0 = σ²                 (e.g. Percival & Walden 1993 §10; Voss 1985)
 *
 * which flattens toward the high frequencies and lowers β, so pushes D = (8 - β) / 2 up. With r = 1/f
 * this is the grids' nugget model q = c0 + a r^e (nugget_fit.c), fitted the same way: the exponent
 * profiled (here β in [1, 5]), N0 >= 0 and A by weighted least squares with weights count / P² (the
 * bins' periodogram ordinates are nearly independent, each bin's relative variance about 1/count), over
 * the bins within 4 x the highest frequency (at least 4). The floor is detected when the F statistic of
 * N0 against the pure power law exceeds the 5% point of F(1, n - 3) and N0 is at least 5% of the power
 * of the highest bin; then N0 is removed from every bin (bins with nothing left are dropped) and the fit
 * keeps the frequencies up to where the power law falls to N0, f_N = (A / N0)^(1/β). When fewer bins than
 * the fit needs lie below f_N (white noise alone: a flat spectrum) the floor is reported, not removed.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <gsl/gsl_cdf.h>
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "surface/grid_internal.h"

#define BETA_MIN 1.0
#define BETA_MAX 5.0
#define HEAD_SPAN 1e9     /* the floor is fitted over the bins within 4 x the highest frequency ... */
#define HEAD_ROWS 4       /* ... or the highest 4, whichever are more */
#define DETECT_P 0.05     /* level of the F test of N0 against the pure power law, F(1, n - 3) */
#define DETECT_SHARE 0.05 /* and N0 at least this share of the highest bin's power */

static int fit_below(const ft_loglog *t, double hi, int whole, const ft_loglog_opts *fit, const ft_dim_map *map,
                     ft_dim_result **out)
{
    return whole ? ft_loglog_fit_range(t, 0.0, hi, map, out) : ft_loglog_fit_auto(t, 0.0, hi, fit, map, out);
}

/* P = N0 + A f^-beta over the highest-frequency bins of t (sorted by f): the model in m (c0 = N0, a = A,
 * H = (beta - 2) / 2, F, sigma_z = sqrt N0); FT_E_NUMERIC when no decreasing power law fits. */
static int fit_floor(const ft_loglog *t, double sigma_z, ft_noise_model *m, size_t *nhead)
{
    size_t first = t->n > HEAD_ROWS ? t->n - HEAD_ROWS : 0;
    while (first > 0 && t->rows[first - 1].scale * HEAD_SPAN >= t->rows[t->n - 1].scale)
        first--;
    size_t n = t->n - first;
    double *buf = ft_malloc(5 * n * sizeof *buf);
    if (buf == NULL)
        return FT_E_NOMEM;
    double *lr = buf, *q = buf + n, *w = buf + 2 * n, *scratch = buf + 3 * n;
    for (size_t i = 0; i < n; i++) {
        const ft_loglog_row *r = &t->rows[first + i];
        lr[i] = -log(r->scale);
        q[i] = r->value;
        w[i] = (r->count > 0.0 ? r->count : 1.0) / (r->value * r->value);
    }
    double beta = NAN, n0 = 0.0, A = 0.0, F = 0.0;
    double rss1 = ft_nugget_profile(lr, q, w, n, sigma_z > 0.0 ? sigma_z * sigma_z : -1.0, BETA_MIN, BETA_MAX,
                                    scratch, &beta, &n0, &A);
    if (isfinite(rss1) && sigma_z == 0.0 && n > 3) {
        double b0, c00, a0;
        double rss0 = ft_nugget_profile(lr, q, w, n, 0.0, BETA_MIN, BETA_MAX, scratch, &b0, &c00, &a0);
        F = rss1 > 0.0 ? (rss0 - rss1) / (rss1 / (double)(n - 3)) : (rss0 > 0.0 ? INFINITY : 0.0);
    }
    free(buf);
    if (!isfinite(rss1))
        return ft_error(FT_E_NUMERIC, "spectrum floor: no decreasing power law fits the %zu highest bins", n);
    *m = (ft_noise_model){0};
    m->fitted = 1;
    m->power = 1.0;
    m->c0 = n0;
    m->a = A;
    m->H = 0.5 * (beta - 2.0);
    m->F = F;
    m->sigma_z = sqrt(n0);
    *nhead = n;
    return FT_OK;
}

int ft_spectrum_fit_noise(const ft_loglog *t, const ft_noise_opts *no, int whole, const ft_loglog_opts *fit,
                          const ft_dim_map *map, ft_dim_result **out)
{
    *out = NULL;
    if (!(no->sigma_z >= 0.0) || !isfinite(no->sigma_z))
        return ft_error(FT_E_INVALID, "spectrum: noise sd must be finite and >= 0, got %g", no->sigma_z);
    int given = no->sigma_z > 0.0;
    ft_noise_model m = {0};
    size_t nhead = 0;
    if (no->mode < 0 || t->n < (given ? 3u : 4u) || fit_floor(t, no->sigma_z, &m, &nhead) != FT_OK)
        return fit_below(t, 0.0, whole, fit, map, out);
    double ptop = t->rows[t->n - 1].value;
    int detected = given || (nhead > 3 && m.F >= gsl_cdf_fdist_Qinv(DETECT_P, 1.0, (double)(nhead - 3)) &&
                             m.c0 >= DETECT_SHARE * ptop);
    if (!detected) {
        int rc = fit_below(t, 0.0, whole, fit, map, out);
        if (rc == FT_OK)
            (*out)->nugget = m;
        return rc;
    }
    /* the highest frequency fitted: where A f^-beta = N0 */
    double beta = 2.0 * m.H + 2.0;
    m.floor = m.c0 > 0.0 ? pow(m.a / m.c0, 1.0 / beta) : INFINITY;
    m.detected = 1;
    size_t need = fit->min_points > 3 ? fit->min_points : 3, below = 0;
    for (size_t i = 0; i < t->n; i++)
        below += t->rows[i].scale <= m.floor * (1.0 + 1e-9) && t->rows[i].value > m.c0;
    if (below < need) {
        /* the floor covers the band: nothing to fit without it; the plain fit says what the data are
         * (white noise alone is rougher than any fractal) */
        int rc = fit_below(t, 0.0, whole, fit, map, out);
        if (rc == FT_OK) {
            (*out)->nugget = m;
            rc = ft_dim_result_warn(*out, "noise: a white-noise floor (power %.3g, noise sd %.4g) exceeds the power "
                                    "law above frequency %g, leaving %zu frequencies below it (%zu needed): the "
                                    "floor was not removed and D is biased up; use longer wavelengths", m.c0,
                                    m.sigma_z, m.floor, below, need);
            if (rc != FT_OK) {
                ft_dim_result_free(*out);
                *out = NULL;
            }
        }
        return rc;
    }
    ft_loglog *c = ft_loglog_create(t->n);
    if (c == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t i = 0; i < t->n && rc == FT_OK; i++)
        if (t->rows[i].value - m.c0 > 0.0)
            rc = ft_loglog_push(c, t->rows[i].scale, t->rows[i].value - m.c0, t->rows[i].count);
    m.applied = 1;
    if (rc == FT_OK)
        rc = fit_below(c, isfinite(m.floor) ? m.floor : 0.0, whole, fit, map, out);
    if (rc == FT_OK) {
        ft_dim_result *r = *out;
        r->nugget = m;
        if (given)
            rc = ft_dim_result_warn(r, "noise model: the given noise sd %g on z (a white spectrum of power %g) "
                                    "was removed; the fit ends at frequency %g", no->sigma_z, m.c0, m.floor);
        else
            rc = ft_dim_result_warn(r, "noise detected: the spectrum flattens toward the high frequencies (a "
                                    "white-noise floor of power %.3g, %.0f%% of the highest bin's, F = %.3g); "
                                    "estimated noise sd on z %.4g; the floor was removed and the fit ends at "
                                    "frequency %g, where the power law falls to the noise", m.c0,
                                    100.0 * m.c0 / ptop, m.F, m.sigma_z, m.floor);
        if (rc != FT_OK) {
            ft_dim_result_free(r);
            *out = NULL;
        }
    }
    ft_loglog_free(c);
    return rc;
}
