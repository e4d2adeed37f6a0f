/* fracterra — recon_discrepancy.c: the prior weight lambda for soft data by Morozov's discrepancy principle
 * (V. A. Morozov, "On the solution of functional equations by the method of regularization", Soviet Math.
 * Dokl. 7, 1966; Hansen, "Rank-deficient and discrete ill-posed problems", SIAM 1998, §7.2).
 *
 * Data with standard deviations sigma_i (weights c_i = 1/sigma_i²) are fitted, not interpolated: a
 * surface that misses them by less than their noise fits the noise, one that misses them by more ignores
 * them. The principle takes the lambda at which the misfit equals the noise,
 *     chi²(lambda) = sum_points c_i (u_lambda(x_i) - d_i)² = N,
 * i.e. the RMS of (u - d_i) / sigma_i is 1. chi² = R(lambda) + S, S the scatter of points that share a node
 * about their node's datum (recon_binding.c: no surface on the grid removes it), R = sum_nodes c_k (u_k -
 * d_k)². R increases with lambda and R / lambda² decreases (in the generalized eigenbasis of the data and
 * prior matrices every component of the residual is lambda mu_j / (1 + lambda mu_j) times a constant), so
 * ln R is increasing in ln lambda with slope in [0, 2]. opts.lambda is an upper bound: if chi² <= N there
 * already, nothing changes. Otherwise the search moves down in t = ln lambda toward R = N - S:
 *   - while no point below the target is known, a step with slope s: the secant slope of the last two
 *     points (clamped to [0.25, 2]), 2 for the first step (it cannot overshoot);
 *   - once the target is bracketed, regula falsi on ln R with the Illinois modification;
 * aiming at the middle of the acceptance band (1 - FT_RECON_CHI2_TOL) N <= chi² <= N and stopping in it.
 * Every step is one T = 0 solve warm-started from the previous solution and stopped early (SEARCH_TOL:
 * chi² to about 0.2%); the accepted solution is then solved to FT_RECON_TOL of the initial residual. If
 * the band is not reached in MAX_SOLVES solves the largest lambda found with chi² <= N is used, if none
 * the smallest lambda tried (at least opts.lambda / LAMBDA_RANGE). When the points that share nodes
 * scatter by more than their sigmas (S >= N) no lambda satisfies the principle: the search then aims at
 * R = 5e-7 N, the interpolation of the nodes' means. Cost: 1024² from 5% points, sigma 1 .. 20: 3-4 search solves,
 * 22-31 conjugate-gradient iterations in all against 15 for one solve with sigma = 0.
 * All decisions depend only on solves that are bit-identical on any thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define MAX_SOLVES 12
#define LAMBDA_RANGE 1e12
/* The search's solves stop when sum r² <= SEARCH_TOL sum_k c_k. At data nodes the error e of a solve
 * has r ~ c e (smooth error components: the prior is small on them; rough ones the multigrid cycle
 * removes), so sum c e² <~ SEARCH_TOL N and chi² is off by at most 2 sqrt(N sum c e²) ~ 0.2% of N. The
 * final solve stops at FT_RECON_TOL x the initial residual, as ft_recon_solve. */
#define SEARCH_TOL 1e-6

/* R = sum over data nodes of c_k (u_k - d_k)² (rows in order). */
static double node_misfit(const ft_recon_problem *p, const float *u)
{
    const ft_recon_level *L = &p->lev[0];
    double s = 0.0;
    for (size_t y = 0; y < p->ny; y++) {
        double r = 0.0;
        for (size_t x = 0; x < p->nx; x++) {
            size_t i = y * p->nx + x;
            if (L->c[i] > 0.0f) {
                double e = (double)u[i] - (double)p->d[i];
                r += (double)L->c[i] * e * e;
            }
        }
        s += r;
    }
    return s;
}

/* Progress of solve k of at most MAX_SOLVES + 2 (segments of 1 / (MAX_SOLVES + 1); the last one: the rest
 * of the range). */
static ft_recon_progress solve_progress(const ft_recon_progress *prog, int k, int last)
{
    double a = (double)k / (MAX_SOLVES + 1), b = last ? 1.0 : (double)(k + 1) / (MAX_SOLVES + 1);
    return ft_progress_range_sub(prog, a, b);
}

int ft_recon_discrepancy(ft_recon_problem *p, double tension, double *lambda, float *u,
                         const ft_recon_progress *prog, double *chi2)
{
    const ft_recon_level *L0 = &p->lev[0];
    size_t n = p->nx * p->ny;
    double N = (double)p->ndata;
    float *rhs = ft_malloc(n * sizeof *rhs), *best = ft_malloc(n * sizeof *best);
    if (rhs == NULL || best == NULL) {
        free(rhs);
        free(best);
        return FT_E_NOMEM;
    }
    /* start from the data's weighted mean, as ft_recon_solve; the prior vanishes on a constant, so the
     * initial residual c (d - mean) and the stopping thresholds do not depend on lambda */
    double sw = 0.0, swd = 0.0, rr0 = 0.0;
    for (size_t i = 0; i < n; i++) {
        sw += L0->c[i];
        swd += (double)L0->c[i] * (double)p->d[i];
    }
    double mean = sw > 0.0 ? swd / sw : 0.0;
    for (size_t i = 0; i < n; i++) {
        rhs[i] = (float)((double)L0->c[i] * (double)p->d[i]);
        u[i] = (float)mean;
        double r = (double)L0->c[i] * ((double)p->d[i] - mean);
        rr0 += r * r;
    }
    double tight = FT_RECON_TOL * FT_RECON_TOL * rr0, loose = fmax(SEARCH_TOL * sw, tight);
    ft_recon_progress sp = solve_progress(prog, 0, 0);
    int rc = ft_recon_solve_to(p, rhs, u, loose, &sp, NULL), k = 1, used = 1; /* used: progress segments */
    double R = node_misfit(p, u);
    if (rc == FT_OK && R + p->scatter > N) {
        /* the band in terms of R, and the aim: its middle (or a small R when S leaves no room) */
        double Rmax = N - p->scatter, Rmin = Rmax - FT_RECON_CHI2_TOL * N;
        double aim = Rmin > 0.0 ? 0.5 * (Rmin + Rmax) : 0.5 * fmax(Rmax, 1e-6 * N);
        double lnaim = log(aim), tmin = log(*lambda / LAMBDA_RANGE);
        /* hi: the lowest t with R above the band, lo: the highest t with R <= Rmax */
        double thi = log(*lambda), hhi = log(R) - lnaim, tprev = 0.0, hprev = 0.0, tlo = 0.0, hlo = 0.0;
        double tlast = thi;
        int have_prev = 0, have_lo = 0, side = 0;
        for (; k <= MAX_SOLVES && rc == FT_OK; k++) {
            double t;
            if (!have_lo) {
                double s = 2.0;
                if (have_prev && tprev != thi)
                    s = fmin(2.0, fmax(0.25, (hprev - hhi) / (tprev - thi)));
                t = fmax(thi - hhi / s, tmin);
            } else {
                t = (tlo * hhi - thi * hlo) / (hhi - hlo); /* regula falsi on h = ln R - ln aim */
            }
            if (!(t < thi) || t == tlast)
                break;
            rc = ft_recon_hierarchy(p, exp(t), tension);
            if (rc == FT_OK) {
                sp = solve_progress(prog, k, 0);
                rc = ft_recon_solve_to(p, rhs, u, loose, &sp, NULL);
            }
            if (rc != FT_OK)
                break;
            R = node_misfit(p, u);
            used = k + 1;
            tlast = t;
            double h = log(fmax(R, 1e-300)) - lnaim;
            if (R <= Rmax) {
                memcpy(best, u, n * sizeof *best);
                if (have_lo && side == -1)
                    hhi *= 0.5; /* Illinois: the same end moved twice */
                tlo = t;
                hlo = h;
                have_lo = 1;
                side = -1;
                if (R >= Rmin)
                    break;
            } else {
                tprev = thi;
                hprev = hhi;
                have_prev = 1;
                if (have_lo && side == 1)
                    hlo *= 0.5;
                thi = t;
                hhi = h;
                side = 1;
            }
            if (t <= tmin)
                break;
        }
        if (rc == FT_OK) {
            double t = tlast;
            if (have_lo && tlast != tlo) {
                memcpy(u, best, n * sizeof *u);
                t = tlo;
            }
            *lambda = exp(t);
            if (p->lambda != *lambda)
                rc = ft_recon_hierarchy(p, *lambda, tension);
        }
    }
    if (rc == FT_OK) {
        sp = solve_progress(prog, used, 1);
        rc = ft_recon_solve_to(p, rhs, u, tight, &sp, NULL);
    }
    if (rc == FT_OK && chi2)
        *chi2 = node_misfit(p, u) + p->scatter;
    free(rhs);
    free(best);
    return rc;
}
