/* fracterra — recon_gibbs.c: the fractal reconstruction, stochastic relaxation per level (Arakawa &
 * Krotkov §3.2-3.4; Szeliski 1990; Geman & Geman's Gibbs sampler).
 *
 * The energy is quadratic, E(u) = 1/2 (u - u*)' A (u - u*) + k (eq. 10), so the reconstruction is
 * u = u* + delta with delta drawn from the Gibbs distribution of 1/2 delta' A delta: the smooth solution
 * u* (recon_multigrid.c) plus a perturbation that is 0 at the fixed data nodes. Coarse to fine over the
 * levels l = L .. 0 of the multigrid hierarchy (spacing 2^l):
 *   1. delta_l = bilinear prolongation of delta_{l+1} (0 on the coarsest level): the coarser levels' noise
 *      is carried down as it is, like the interpolation step of successive random addition;
 *   2. FT_RECON_RELAX_SWEEPS Gauss-Seidel sweeps at T = 0 (relaxation toward the minimum: they smooth the
 *      prolongation's kinks, not the longer waves);
 *   3. `sweeps` Gibbs sweeps: delta_i ~ N(delta+_i, lambda T_l / (w_l a_ii)) (eq. 10's conditional, with
 *      delta+ the Gauss-Seidel update), at T_l = T_0 2^(2 H l) (eq. 12).
 * w_l = a^(0)/a^(l), the ratio of the fine and level-l interior prior diagonals, are the level weights
 * (the role of Szeliski's eqs. 7-8): a free node's conditional variance at level l is then lambda T_l /
 * a^(0) whatever the rediscretized operator's scale, so the per-level added variance follows the SRA
 * ratio 2^(2 H l) exactly. Temperatures are in units of the prior weight lambda (the Gibbs distribution
 * is exp(-E / (lambda T))): lambda moves the balance of data and prior, not the roughness.
 * Every data node is fixed for delta (with soft data, reconstruct.c fixes the data nodes at u*'s values
 * before sampling), so the noise never moves a datum's node.
 * Each (level, sweep, colour, row) draws from its own stream of ft_rng_fast, so the result is the same on
 * any thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <string.h>

#include "terrain/reconstruct/reconstruct_internal.h"

int ft_recon_fractal(const ft_recon_problem *p, const float *ustar, double T0, double H, int sweeps,
                     uint64_t seed, float *u, const ft_recon_progress *prog)
{
    int top = p->nlev - 1, rc = FT_OK;
    double lambda = p->lev[0].tp + p->lev[0].mem, a0 = ft_recon_prior_diag(&p->lev[0]);
    int total = p->nlev * (FT_RECON_RELAX_SWEEPS + sweeps), done = 0;
    for (int l = top; l >= 0 && rc == FT_OK; l--) {
        const ft_recon_level *L = &p->lev[l];
        float *x = l == 0 ? u : L->x;
        memset(x, 0, L->nx * L->ny * sizeof *x);
        if (l < top)
            ft_recon_prolong_add(L, &p->lev[l + 1], p->lev[l + 1].x, x, p->nthreads);
        for (int s = 0; s < FT_RECON_RELAX_SWEEPS && rc == FT_OK; s++, done++)
            rc = ft_recon_sweep(L, x, NULL, s & 1, NULL, p->nthreads);
        double wl = a0 / ft_recon_prior_diag(L);
        double Tl = ft_recon_temperature_level(T0, H, l);
        ft_recon_noise nz = {lambda * Tl / wl, seed, 0};
        for (int s = 0; s < sweeps && rc == FT_OK; s++, done++) {
            nz.stream = FT_RECON_STREAM_GIBBS + (((uint64_t)l << 20) + ((uint64_t)s << 4));
            rc = ft_recon_sweep(L, x, NULL, 0, &nz, p->nthreads);
            if (rc == FT_OK)
                rc = ft_recon_report(prog, (double)(done + 1) / total, "reconstruct: Gibbs sampling");
        }
    }
    if (rc != FT_OK)
        return rc;
    size_t n = p->nx * p->ny;
    for (size_t i = 0; i < n; i++)
        u[i] = (float)((double)ustar[i] + (double)u[i]);
    return FT_OK;
}
