/* fracterra — recon_perturb.c: the fractal reconstruction as an exact sample of the posterior (Arakawa &
 * Krotkov §3.2, eqs. 9-10: the Gibbs distribution exp(-E / (lambda T)) of the regularization energy) by
 * perturbation and optimization (Papandreou & Yuille 2010, "Gaussian sampling by local perturbations";
 * Gilavert, Moussaoui & Idier 2015).
 *
 * The prior energy is a sum of squared local differences, E_p(u) = sum_j w_j/2 (g_j' u)², with
 * (recon_stencil.c) g_j = u_xx at every node whose two x-neighbours exist and u_yy likewise (w = tp),
 * u_xy of every 2 x 2 block (w = 2 tp), and the forward differences along x and y (w = mem), so
 * A = sum_j w_j g_j g_j'. Perturbing each term's target, E~(u) = sum_j w_j/2 (g_j' u - e_j)² with
 * e_j ~ N(0, lambda T / w_j) independent, its minimizer over the free nodes (fixed nodes at 0) solves
 * A_ff delta = eta_f, eta = sum_j w_j e_j g_j, Cov(eta_f) = lambda T A_ff, so
 * Cov(delta) = lambda T A_ff^-1: delta is an exact draw of the prior conditioned on the data (the
 * posterior minus its mean u*), at equilibrium, not the state of a Gibbs chain after a few sweeps.
 * The reconstruction is u = u* + delta. The solve is the T = 0 solver's (conjugate gradients with the
 * multigrid V-cycle, recon_multigrid.c), stopped at FT_RECON_SAMPLE_TOL of the initial residual. As A is
 * linear, u itself solves A_ff u_f = (c d)_f + eta_f with u = d at the fixed nodes: one realization needs
 * no separate u*, and one solve from u*'s initial guess, stopped at the tighter of u*'s threshold
 * (FT_RECON_TOL of its initial residual) and delta's, replaces the two (12 iterations instead of 12 + 6
 * on the 1024² benchmark).
 *
 * The deviates of term type t anchored on row y come from the stream (seed, t, y) of ft_rng_fast and eta
 * is gathered node by node, so the sample is the same on any thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

enum { TERM_XX, TERM_YY, TERM_XY, TERM_MX, TERM_MY, NTERMS };

/* 1 if the term of type t anchored at (x, y) exists on an nx x ny grid (the terms of recon_stencil.c):
 * xx centred at x, yy centred at y, xy the block (x..x+1, y..y+1), mx (x, x+1), my (y, y+1). */
static int term_exists(int t, long x, long y, long nx, long ny)
{
    if (x < 0 || y < 0 || x >= nx || y >= ny)
        return 0;
    switch (t) {
    case TERM_XX: return x >= 1 && x + 1 < nx;
    case TERM_YY: return y >= 1 && y + 1 < ny;
    case TERM_XY: return x + 1 < nx && y + 1 < ny;
    case TERM_MX: return x + 1 < nx;
    default: return y + 1 < ny;
    }
}

/* Standard normal deviates e[t][y nx + x] of every existing term (0 elsewhere), scaled by sqrt(w_t). */
static void draw_terms(const ft_recon_level *L, uint64_t seed, int level, float *const e[NTERMS], int nthreads)
{
    size_t nx = L->nx, ny = L->ny;
    const double w[NTERMS] = {L->tp, L->tp, 2.0 * L->tp, L->mem, L->mem};
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nx * ny)) schedule(static)
    for (size_t y = 0; y < ny; y++)
        for (int t = 0; t < NTERMS; t++) {
            float *row = e[t] + y * nx;
            ft_rng_fast g;
            ft_rng_fast_init(&g, seed, ft_rng_mix(FT_RECON_STREAM_PERTURB + (uint64_t)(16 * level + t), (uint64_t)y));
            ft_rng_fast_normals(&g, row, nx);
            double s = sqrt(w[t]);
            for (size_t x = 0; x < nx; x++)
                row[x] = term_exists(t, (long)x, (long)y, (long)nx, (long)ny) ? (float)(s * row[x]) : 0.0f;
        }
}

/* eta_i = sum_j sqrt(w_j) xi_j g_ji over the terms that hold node (x, y) (xi already scaled). */
static double gather(float *const e[NTERMS], size_t nx, size_t ny, size_t x, size_t y)
{
#define E(t, a, b) ((double)e[t][(size_t)(b) * nx + (size_t)(a)])
    long X = (long)x, Y = (long)y, NX = (long)nx, NY = (long)ny;
    double s = 0.0;
    /* u_xx centred at x-1, x, x+1 (absent terms hold 0) */
    for (long c = X - 1; c <= X + 1; c++)
        if (c >= 0 && c < NX)
            s += (c == X ? -2.0 : 1.0) * E(TERM_XX, c, Y);
    for (long c = Y - 1; c <= Y + 1; c++)
        if (c >= 0 && c < NY)
            s += (c == Y ? -2.0 : 1.0) * E(TERM_YY, X, c);
    /* u_xy of the blocks with corner (cx, cy): + at (cx, cy) and (cx+1, cy+1), - at the other two */
    for (long cx = X - 1; cx <= X; cx++)
        for (long cy = Y - 1; cy <= Y; cy++)
            if (cx >= 0 && cy >= 0)
                s += (((cx == X) == (cy == Y)) ? 1.0 : -1.0) * E(TERM_XY, cx, cy);
    /* membrane: u(x+1) - u(x) holds x with -1 and x+1 with +1 */
    s -= E(TERM_MX, X, Y);
    if (X >= 1)
        s += E(TERM_MX, X - 1, Y);
    s -= E(TERM_MY, X, Y);
    if (Y >= 1)
        s += E(TERM_MY, X, Y - 1);
#undef E
    return s;
}

/* u* and delta in one solve: eta += c d (the T = 0 right-hand side), u = the T = 0 solver's initial guess,
 * and *stop (the sample's threshold) lowered to the T = 0 solve's, FT_RECON_TOL² times its initial
 * residual, so that the sum is solved at least as tightly as each part would be alone. */
static int add_data_rhs(const ft_recon_problem *p, float *eta, float *u, double *stop)
{
    size_t n = p->nx * p->ny;
    float *rhs = ft_malloc(n * sizeof *rhs);
    if (rhs == NULL)
        return FT_E_NOMEM;
    ft_recon_data_rhs(p, rhs, u);
    double rr0 = ft_recon_residual_norm2(p, rhs, u);
    for (size_t i = 0; i < n; i++)
        eta[i] = (float)((double)eta[i] + (double)rhs[i]);
    free(rhs);
    if (isnan(rr0))
        return FT_E_NOMEM;
    *stop = fmin(*stop, FT_RECON_TOL * FT_RECON_TOL * rr0);
    return FT_OK;
}

int ft_recon_fractal(const ft_recon_problem *p, const float *ustar, double T0, uint64_t seed, float *u,
                     const ft_recon_progress *prog)
{
    const ft_recon_level *L = &p->lev[0];
    size_t nx = p->nx, ny = p->ny, n = nx * ny;
    float *buf = ft_malloc(NTERMS * n * sizeof *buf), *eta = ft_malloc(n * sizeof *eta);
    if (buf == NULL || eta == NULL) {
        free(buf);
        free(eta);
        return FT_E_NOMEM;
    }
    float *e[NTERMS];
    /* the multilevel prior's terms (recon_levels.c), coarsest first: b_l = eta_l + r' b_(l+1) */
    for (int l = p->npl - 1; l >= 0; l--) {
        ft_recon_level *P = &p->pl[l];
        size_t m = P->nx * P->ny;
        for (int t = 0; t < NTERMS; t++)
            e[t] = buf + (size_t)t * m;
        draw_terms(P, seed, l + 1, e, p->nthreads);
#pragma omp parallel for num_threads(ft_recon_threads(p->nthreads, m)) schedule(static)
        for (size_t y = 0; y < P->ny; y++)
            for (size_t x = 0; x < P->nx; x++)
                P->b[y * P->nx + x] = (float)gather(e, P->nx, P->ny, x, y);
        if (l + 1 < p->npl)
            ft_recon_restrict_mean_t(p->pl[l + 1].b, p->pl[l + 1].nx, p->pl[l + 1].ny, P->b, P->nx, P->ny,
                                     p->pl[l + 1].r, p->nthreads);
    }
    for (int t = 0; t < NTERMS; t++)
        e[t] = buf + (size_t)t * n;
    draw_terms(L, seed, 0, e, p->nthreads);
    /* e_j ~ N(0, lambda T / w_j) and eta = sum w_j e_j g_j: the deviates above times sqrt(lambda T) */
    double s = sqrt(p->lambda * T0);
#pragma omp parallel for num_threads(ft_recon_threads(p->nthreads, n)) schedule(static)
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            size_t i = y * nx + x;
            eta[i] = (float)gather(e, nx, ny, x, y);
            u[i] = 0.0f;
        }
    free(buf);
    if (p->npl > 0)
        ft_recon_restrict_mean_t(p->pl[0].b, p->pl[0].nx, p->pl[0].ny, eta, nx, ny, p->pl[0].r, p->nthreads);
    for (size_t i = 0; i < n; i++)
        eta[i] = L->fixed[i] ? 0.0f : (float)(s * (double)eta[i]);
    int rc = ft_recon_report(prog, 0.1, "reconstruct: perturbed prior");
    double rr0 = 0.0;
    for (size_t i = 0; i < n; i++)
        rr0 += (double)eta[i] * (double)eta[i];
    double stop = FT_RECON_SAMPLE_TOL * FT_RECON_SAMPLE_TOL * rr0;
    if (rc == FT_OK && ustar == NULL)
        rc = add_data_rhs(p, eta, u, &stop);
    if (rc == FT_OK) {
        ft_recon_progress sp = ft_progress_range_sub(prog, 0.1, 1.0);
        rc = ft_recon_solve_to(p, eta, u, stop, &sp, NULL);
    }
    free(eta);
    if (rc != FT_OK || ustar == NULL)
        return rc;
    for (size_t i = 0; i < n; i++)
        u[i] = (float)((double)ustar[i] + (double)u[i]);
    return FT_OK;
}
