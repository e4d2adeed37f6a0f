/* fracterra — recon_conditional.c: conditional simulation of a fractional Brownian surface (beyond
 * Arakawa & Krotkov: the classical geostatistical construction, e.g. Journel & Huijbregts 1978, ch. VII;
 * Chilès & Delfiner, "Geostatistics", §7.3), with the thin-plate/membrane interpolator in place of kriging.
 *
 *     u = s + S(d - s)
 * s an unconditional fBm of exponent H = 3 - D (ft_terrain_synth: Stein's exact circulant embedding up to
 * EXACT_MAX nodes per side, spectral synthesis above, where the embedding's torus would not fit in
 * memory), scaled so that its one-cell increments have the RMS `amp` measured on the data
 * (recon_temperature.c); S the T = 0 solution operator with the data's weights (recon_multigrid.c).
 * S is linear, so S(d - s) = u* - S(s) with u* = S(d) computed once for all realizations. At fixed
 * data nodes u = s + d - s = d: the data are honoured exactly; between them u has the roughness of s.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define EXACT_MAX 1536

/* RMS of the one-node differences along rows and columns (rows summed in order). */
static double rms_step(const float *z, size_t nx, size_t ny)
{
    double s = 0.0, n = 0.0;
    for (size_t y = 0; y < ny; y++) {
        double r = 0.0;
        for (size_t x = 0; x < nx; x++) {
            double v = z[y * nx + x];
            if (x + 1 < nx) {
                double d = (double)z[y * nx + x + 1] - v;
                r += d * d;
            }
            if (y + 1 < ny) {
                double d = (double)z[(y + 1) * nx + x] - v;
                r += d * d;
            }
        }
        s += r;
    }
    n = (double)(nx - 1) * (double)ny + (double)nx * (double)(ny - 1);
    return n > 0.0 ? sqrt(s / n) : 0.0;
}

int ft_recon_conditional(const ft_recon_problem *p, const float *ustar, double H, double amp, uint64_t seed,
                         float *u, const ft_recon_progress *prog)
{
    size_t nx = p->nx, ny = p->ny, n = nx * ny;
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.method = (nx > EXACT_MAX || ny > EXACT_MAX) ? FT_SYNTH_FFT : FT_SYNTH_EXACT;
    so.dim = 3.0 - H;
    so.sigma = 0.0;
    so.seed = seed;
    ft_grid *s = NULL;
    int rc = ft_terrain_synth(nx > 1 ? nx : 2, ny > 1 ? ny : 2, &so, &s);
    if (rc != FT_OK)
        return rc;
    rc = ft_recon_report(prog, 0.3, "reconstruct: unconditional fBm");
    if (rc != FT_OK) {
        ft_grid_free(s);
        return rc;
    }
    /* ft_terrain_synth made at least 2 x 2 nodes: use the nx x ny corner */
    float *sz = ft_malloc(n * sizeof *sz), *rhs = ft_malloc(n * sizeof *rhs);
    if (sz == NULL || rhs == NULL) {
        ft_grid_free(s);
        free(sz);
        free(rhs);
        return FT_E_NOMEM;
    }
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++)
            sz[y * nx + x] = s->z[y * s->nx + x];
    ft_grid_free(s);
    const ft_recon_level *L = &p->lev[0];
    for (size_t i = 0; i < n; i++) {
        u[i] = L->fixed[i] ? sz[i] : 0.0f;
        rhs[i] = L->fixed[i] ? 0.0f : (float)((double)L->c[i] * (double)sz[i]);
    }
    ft_recon_progress sub = ft_progress_range_sub(prog, 0.3, 1.0);
    rc = ft_recon_solve_rhs(p, rhs, u, prog ? &sub : NULL, NULL);
    if (rc == FT_OK) {
        /* e = s - S(s), then u = u* + kappa e with kappa² = (amp² - V(u*)) / V(e), V = mean squared
         * one-node difference: the result's one-cell increments get the data's variance */
        for (size_t i = 0; i < n; i++)
            sz[i] = L->fixed[i] ? 0.0f : (float)((double)sz[i] - (double)u[i]);
        double ve = rms_step(sz, nx, ny), vs = rms_step(ustar, nx, ny);
        ve *= ve;
        vs *= vs;
        double kappa = ve > 0.0 && amp * amp > vs ? sqrt((amp * amp - vs) / ve) : 0.0;
        for (size_t i = 0; i < n; i++)
            u[i] = L->fixed[i] ? ustar[i] : (float)((double)ustar[i] + kappa * (double)sz[i]);
    }
    free(sz);
    free(rhs);
    return rc;
}
