/* fracterra — terrain/clarke/clarke_spectrum.c: the fractal noise F of Clarke's model as the DEM's measured
 * radially averaged spectrum, and the regimes (straight runs with a break) of that spectrum.
 *
 * Clarke (1987, eqs. ix-xv) gives F one power law, the log-log regression of harmonic power on wavelength.
 * Real DEMs bend: on the 3" Jacksboro DEM one law gives D = 1.85 while the DEM's variogram reads 2.21 at 1-8
 * cells and 2.53 at 4-32, so a simulation from the one law has the wrong roughness at both
 * scales. Here F keeps the spectrum it was measured with:
 *  - every wave of the (tapered, normalised) periodogram of z - T - H (clarke_fit.c removes H's grid modes
 *    before the taper, so the strong waves' leakage does not count as noise) is put in a ring of a quarter octave of frequency (rings from the grid's longest wavelength down);
 *    a ring's power is the mean power of its waves (the radially averaged spectrum, e.g. Turcotte 1997,
 *    Fractals and Chaos in Geology and Geophysics, §7.7: the spectral estimate of D of a surface from the
 *    radial average), its wavelength the geometric mean of theirs. Averaging over a ring is the smoothing;
 *  - the simulation gives a wave of wavelength w the power of the log-log interpolation of the rings at w,
 *    the longest ring's power beyond it, and below the shortest ring the finest regime's power law;
 *  - the rings of at least min_wavelength cells, as (frequency, power) rows, go through the project's
 *    log-log regime search (src/core/loglog_regimes.c: curvature test, two-phase break point, Hudson 1966);
 *    each regime is reported as a power law in wavelength with its D = (8 - slope) / 2 and its range, and
 *    the breaks as wavelengths.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/clarke/clarke_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"

#define RINGS_PER_OCTAVE 4.0

typedef struct {
    double power, logwl, count;
} ring_sum;

/* Ring index of a wave of frequency f (cycles per ground unit) above the lowest frequency f0. */
static size_t ring_of(double f, double f0)
{
    double r = floor(RINGS_PER_OCTAVE * log2(f / f0));
    return r > 0.0 ? (size_t)r : 0;
}

static int store_rings(ft_clarke_model *m, const ring_sum *rings, size_t nrings)
{
    size_t n = 0;
    for (size_t i = 0; i < nrings; i++)
        n += rings[i].count > 0.0;
    m->spectrum_wavelength = ft_malloc((n ? n : 1) * sizeof(double));
    m->spectrum_power = ft_malloc((n ? n : 1) * sizeof(double));
    m->spectrum_count = ft_malloc((n ? n : 1) * sizeof(double));
    if (!m->spectrum_wavelength || !m->spectrum_power || !m->spectrum_count)
        return ft_last_error_code();
    m->nspectrum = 0;
    for (size_t i = nrings; i-- > 0;) { /* highest frequency first: increasing wavelength */
        if (!(rings[i].count > 0.0))
            continue;
        m->spectrum_wavelength[m->nspectrum] = pow(10.0, rings[i].logwl / rings[i].count);
        m->spectrum_power[m->nspectrum] = rings[i].power / rings[i].count;
        m->spectrum_count[m->nspectrum++] = rings[i].count;
    }
    return FT_OK;
}

int clarke_measure_spectrum(ft_clarke_model *m, const clarke_frame *fr, const double *wave_power)
{
    size_t nx = m->nx, ny = m->ny, hx = nx / 2 + 1;
    double f0 = 1.0 / fmax(fr->lx, fr->ly) * (1.0 - 1e-9), fmaxv = 0.0;
    for (size_t ky = 0; ky < ny; ky++)
        for (size_t kx = 0; kx < hx; kx++)
            if (isfinite(wave_power[ky * hx + kx]))
                fmaxv = fmax(fmaxv, 1.0 / clarke_wavelength(fr, (int)kx, clarke_signed_l(ky, ny)));
    if (!(fmaxv > 0.0))
        return ft_error(FT_E_EMPTY, "Clarke model: the residual has no wave of non-zero power to measure F from");
    size_t nrings = ring_of(fmaxv, f0) + 1;
    ring_sum *rings = ft_calloc(nrings, sizeof *rings);
    if (rings == NULL)
        return ft_last_error_code();
    for (size_t ky = 0; ky < ny; ky++) { /* in order: the same sums on any thread count */
        for (size_t kx = 0; kx < hx; kx++) {
            double p = wave_power[ky * hx + kx];
            if (!isfinite(p))
                continue;
            double wl = clarke_wavelength(fr, (int)kx, clarke_signed_l(ky, ny));
            ring_sum *r = &rings[ring_of(1.0 / wl, f0)];
            r->power += p;
            r->logwl += log10(wl);
            r->count += 1.0;
        }
    }
    int rc = store_rings(m, rings, nrings);
    free(rings);
    return rc;
}

/* The regimes of the rings of at least min_wl (ground units) by the log-log regime search. None found
 * (too few rings, no straight run) is not an error: the model then has nregimes = 0. */
int clarke_spectrum_regimes(ft_clarke_model *m, double min_wl)
{
    ft_loglog *t = ft_loglog_create(m->nspectrum);
    if (t == NULL)
        return ft_last_error_code();
    int rc = FT_OK;
    for (size_t i = m->nspectrum; i-- > 0 && rc == FT_OK;) /* increasing frequency */
        if (m->spectrum_wavelength[i] >= min_wl && m->spectrum_power[i] > 0.0)
            rc = ft_loglog_push(t, 1.0 / m->spectrum_wavelength[i], m->spectrum_power[i], m->spectrum_count[i]);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    ft_loglog_opts lo = FT_LOGLOG_OPTS_DEFAULT;
    lo.method = FT_LOGLOG_REGIMES;
    const ft_dim_map map = {4.0, 0.5, 0.0, 0.0}; /* FT_DIM_MAP_SPECTRUM_SURFACE without bounds: D is reported */
    ft_dim_result *res = NULL;
    if (t->n >= 3 && ft_loglog_fit_auto(t, 0.0, 0.0, &lo, &map, &res) == FT_OK && res->nregimes > 0) {
        size_t n = res->nregimes;
        m->regimes = ft_calloc(n, sizeof *m->regimes);
        m->breaks = n > 1 ? ft_calloc(n - 1, sizeof *m->breaks) : NULL;
        if (m->regimes == NULL || (n > 1 && m->breaks == NULL)) {
            rc = ft_last_error_code();
        } else {
            for (size_t i = 0; i < n; i++) { /* frequency order reversed: increasing wavelength */
                const ft_loglog_segment *s = &res->regimes[n - 1 - i];
                ft_clarke_regime *g = &m->regimes[i];
                g->wavelength_lo = 1.0 / s->scale_hi;
                g->wavelength_hi = 1.0 / s->scale_lo;
                g->slope = -s->slope;
                g->intercept = s->intercept;
                g->D = (8.0 - g->slope) / 2.0;
                g->r2 = s->r2;
                g->stderr_D = s->stderr_D;
                g->bins = s->n;
            }
            for (size_t i = 0; i + 1 < n; i++)
                m->breaks[i] = 1.0 / res->breaks[n - 2 - i];
            m->nregimes = n;
        }
    }
    ft_dim_result_free(res);
    ft_loglog_free(t);
    return rc;
}

int clarke_ring_bracket(const ft_clarke_model *m, double wavelength, size_t *lo, double *t)
{
    size_t n = m->nspectrum;
    const double *w = m->spectrum_wavelength;
    if (wavelength >= w[n - 1])
        return 1;
    if (wavelength <= w[0])
        return -1;
    size_t a = 0, b = n - 1;
    while (b - a > 1) {
        size_t mid = a + (b - a) / 2;
        if (w[mid] <= wavelength)
            a = mid;
        else
            b = mid;
    }
    *lo = a;
    *t = log(wavelength / w[a]) / log(w[b] / w[a]);
    return 0;
}

double clarke_noise_power(const ft_clarke_model *m, double wavelength)
{
    size_t n = m->nspectrum;
    if (m->noise != FT_CLARKE_NOISE_SPECTRUM || n < 2)
        return clarke_power(m, wavelength);
    const double *w = m->spectrum_wavelength, *p = m->spectrum_power;
    size_t lo = 0;
    double t = 0.0;
    int where = clarke_ring_bracket(m, wavelength, &lo, &t);
    if (where > 0)
        return p[n - 1];
    if (where < 0) { /* finer than the DEM's rings: the finest regime's law through the finest ring */
        double slope = m->nregimes > 0 ? m->regimes[0].slope : m->slope;
        return p[0] * pow(wavelength / w[0], slope);
    }
    return exp((1.0 - t) * log(p[lo]) + t * log(p[lo + 1]));
}

int clarke_check_spectrum(const ft_clarke_model *m)
{
    if (m->noise != FT_CLARKE_NOISE_POWER_LAW && m->noise != FT_CLARKE_NOISE_SPECTRUM)
        return ft_error(FT_E_INVALID, "Clarke model: noise must be power-law (0) or spectrum (1), got %d",
                        (int)m->noise);
    if (m->nspectrum > 0 && (!m->spectrum_wavelength || !m->spectrum_power || !m->spectrum_count))
        return ft_error(FT_E_INVALID, "Clarke model: %zu spectrum bins announced, none given", m->nspectrum);
    if (m->noise == FT_CLARKE_NOISE_SPECTRUM && m->nspectrum < 2)
        return ft_error(FT_E_INVALID, "Clarke model: the measured-spectrum noise needs at least 2 bins, got %zu",
                        m->nspectrum);
    for (size_t i = 0; i < m->nspectrum; i++) {
        double w = m->spectrum_wavelength[i], p = m->spectrum_power[i];
        if (!(isfinite(w) && w > 0.0) || (i > 0 && !(w > m->spectrum_wavelength[i - 1])))
            return ft_error(FT_E_INVALID, "Clarke model: spectrum wavelength %zu (%g) must be finite, > 0 and "
                            "larger than the one before", i, w);
        if (!(isfinite(p) && p > 0.0))
            return ft_error(FT_E_INVALID, "Clarke model: spectrum power %zu (%g) must be finite and > 0", i, p);
    }
    if (m->nregimes > 0 && m->regimes == NULL)
        return ft_error(FT_E_INVALID, "Clarke model: %zu regimes announced, none given", m->nregimes);
    for (size_t i = 0; i < m->nregimes; i++)
        if (!isfinite(m->regimes[i].slope))
            return ft_error(FT_E_INVALID, "Clarke model: regime %zu has a non-finite slope", i);
    return FT_OK;
}
