/* fracterra — recon_conditional.c: conditional simulation of a fractional Brownian surface (beyond
 * Arakawa & Krotkov: the classical geostatistical construction, e.g. Journel & Huijbregts 1978, ch. VII;
 * Chilès & Delfiner, "Geostatistics", §7.3), with the thin-plate/membrane interpolator in place of kriging.
 *
 *     u = s + S(d - s)
 * s an unconditional fBm of exponent H = 3 - D (ft_terrain_synth: Stein's exact circulant embedding up to
 * EXACT_MAX nodes per side, spectral synthesis above, where the embedding's torus would not fit in
 * memory) plus white noise carrying the data's white share of the one-cell increment variance (a
 * nugget; recon_temperature.c, ft_recon_small_scales); S the T = 0 solution operator with the data's
 * weights (recon_multigrid.c). S is linear, so S(d - s) = u* - S(s) with u* = S(d) computed once for all
 * realizations. At fixed data nodes u = s + d - s = d: the data are honoured exactly; between them u has
 * the roughness of s. The scale of s - S(s) is then set so that u's mean |dz| at one cell is the data's
 * (what the interpolant u* already carries is not counted twice).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define EXACT_MAX 1536
/* kappa is found when u's mean |dz| at one cell is within this fraction of the data's (far below the
 * seeds' scatter), in at most KAPPA_MAX_STEPS false-position steps after its bracket. */
#define KAPPA_RTOL 1e-6
#define KAPPA_MAX_STEPS 60

/* Mean of |d + kappa e| over the one-node differences along rows and columns (rows summed in order). */
static double mean_abs_step(const float *d, const float *e, double kappa, size_t nx, size_t ny)
{
    double s = 0.0;
    for (size_t y = 0; y < ny; y++) {
        double r = 0.0;
        for (size_t x = 0; x < nx; x++) {
            size_t i = y * nx + x;
            double v = (double)d[i] + kappa * (double)e[i];
            if (x + 1 < nx)
                r += fabs((double)d[i + 1] + kappa * (double)e[i + 1] - v);
            if (y + 1 < ny)
                r += fabs((double)d[i + nx] + kappa * (double)e[i + nx] - v);
        }
        s += r;
    }
    double n = (double)(nx - 1) * (double)ny + (double)nx * (double)(ny - 1);
    return n > 0.0 ? s / n : 0.0;
}

/* The kappa >= 0 with mean_abs_step(ustar, e, kappa) = m1 (0 if ustar alone is already as rough). The
 * mean is convex in kappa and below m1 at 0, so it crosses m1 once for kappa > 0: bracket by doubling,
 * then the Illinois variant of false position (a handful of passes; bisection's guarantee kept by the
 * bracket) until the mean is within KAPPA_RTOL of m1. */
static double match_kappa(const float *ustar, const float *e, double m1, size_t nx, size_t ny)
{
    double flo = mean_abs_step(ustar, e, 0.0, nx, ny) - m1;
    if (!(flo < 0.0))
        return 0.0;
    double lo = 0.0, hi = 1.0, fhi = mean_abs_step(ustar, e, hi, nx, ny) - m1;
    for (int i = 0; i < 60 && fhi < 0.0; i++) {
        lo = hi;
        flo = fhi;
        hi *= 2.0;
        fhi = mean_abs_step(ustar, e, hi, nx, ny) - m1;
    }
    if (fhi < 0.0)
        return hi;
    int side = 0;
    for (int i = 0; i < KAPPA_MAX_STEPS; i++) {
        double k = (lo * fhi - hi * flo) / (fhi - flo);
        if (!(k > lo && k < hi))
            k = 0.5 * (lo + hi);
        double f = mean_abs_step(ustar, e, k, nx, ny) - m1;
        if (fabs(f) <= KAPPA_RTOL * m1)
            return k;
        if (f < 0.0) {
            lo = k;
            flo = f;
            if (side == -1)
                fhi *= 0.5;
            side = -1;
        } else {
            hi = k;
            fhi = f;
            if (side == 1)
                flo *= 0.5;
            side = 1;
        }
    }
    return 0.5 * (lo + hi);
}

/* s = sqrt(1 - nugget) f / rms(f) + sqrt(nugget / 2) w: the fBm f scaled to unit RMS one-node increments
 * plus white noise w ~ N(0, 1) (increment variance 2), so the white part carries the share `nugget` of
 * the one-node increment variance. w is drawn per row from its own stream: any thread count. */
static void add_white(float *s, size_t nx, size_t ny, double nugget, uint64_t seed)
{
    double rf = 0.0;
    for (size_t y = 0; y < ny; y++) {
        double r = 0.0;
        for (size_t x = 0; x < nx; x++) {
            size_t i = y * nx + x;
            if (x + 1 < nx)
                r += ((double)s[i + 1] - s[i]) * ((double)s[i + 1] - s[i]);
            if (y + 1 < ny)
                r += ((double)s[i + nx] - s[i]) * ((double)s[i + nx] - s[i]);
        }
        rf += r;
    }
    double n = (double)(nx - 1) * (double)ny + (double)nx * (double)(ny - 1);
    rf = n > 0.0 && rf > 0.0 ? sqrt(rf / n) : 1.0;
    double a = sqrt(1.0 - nugget) / rf, b = sqrt(nugget / 2.0);
    for (size_t y = 0; y < ny; y++) {
        float *row = s + y * nx;
        if (b > 0.0) {
            ft_rng_fast g;
            ft_rng_fast_init(&g, seed, ft_rng_mix(FT_RECON_STREAM_WHITE, (uint64_t)y));
            float w[256];
            for (size_t x0 = 0; x0 < nx; x0 += 256) {
                size_t m = nx - x0 < 256 ? nx - x0 : 256;
                ft_rng_fast_normals(&g, w, m);
                for (size_t j = 0; j < m; j++)
                    row[x0 + j] = (float)(a * row[x0 + j] + b * w[j]);
            }
        } else {
            for (size_t x = 0; x < nx; x++)
                row[x] = (float)(a * row[x]);
        }
    }
}

int ft_recon_conditional(const ft_recon_problem *p, const float *ustar, double H, double m1, double nugget,
                         uint64_t seed, float *u, const ft_recon_progress *prog)
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
    add_white(sz, nx, ny, nugget, seed);
    const ft_recon_level *L = &p->lev[0];
    for (size_t i = 0; i < n; i++) {
        u[i] = L->fixed[i] ? sz[i] : 0.0f;
        rhs[i] = L->fixed[i] ? 0.0f : (float)((double)L->c[i] * (double)sz[i]);
    }
    ft_recon_progress sub = ft_progress_range_sub(prog, 0.3, 1.0);
    rc = ft_recon_solve_rhs(p, rhs, u, prog ? &sub : NULL, NULL);
    if (rc == FT_OK) {
        /* e = s - S(s), then u = u* + kappa e with kappa such that u's mean |dz| at one node is the data's:
         * the result's one-cell increments get the data's, whatever u*'s share of them */
        for (size_t i = 0; i < n; i++)
            sz[i] = L->fixed[i] ? 0.0f : (float)((double)sz[i] - (double)u[i]);
        double kappa = match_kappa(ustar, sz, m1, nx, ny);
        for (size_t i = 0; i < n; i++)
            u[i] = L->fixed[i] ? ustar[i] : (float)((double)ustar[i] + kappa * (double)sz[i]);
    }
    free(sz);
    free(rhs);
    return rc;
}
