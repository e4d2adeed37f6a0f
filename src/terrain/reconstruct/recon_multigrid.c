/* fracterra — recon_multigrid.c: the level hierarchy of a reconstruction (Szeliski's multiresolution
 * representation, Arakawa & Krotkov §3.2) and the T = 0 solver: the minimum u* = A^-1 b of the quadratic
 * energy (eq. 9), found by conjugate gradients preconditioned with one symmetric multigrid V-cycle.
 *
 * Level l has nodes at every 2^l-th fine node: nx_l = nx_{l-1} / 2 + 1 (the last coarse node may lie
 * just beyond the fine grid). Coarse operators are rediscretized: the thin-plate coefficient is divided
 * by 4 per level (the energy sum (u_xx)² of a smooth surface at spacing 2h is 4 times that at h over a
 * quarter of the nodes), the membrane's is kept (scale-free in 2-D), and the data weights are lumped,
 * c_I = sum_i P_iI c_i (the row sums of the Galerkin product P'CP). A coarse node is fixed if the fine
 * node under it is; a fixed fine node elsewhere contributes P_iI times the fine prior diagonal, so coarse
 * corrections avoid it. Restriction is P' (full weighting without the 1/4), prolongation bilinear.
 * The V-cycle: 2 forward 5-colour Gauss-Seidel sweeps, restriction of the residual, the coarser cycle,
 * correction, 2 backward sweeps; on the coarsest level (at most FT_RECON_COARSEST nodes per side) a
 * dense Cholesky solve. Forward-then-backward sweeps and R = P' make the cycle a symmetric positive
 * definite preconditioner. CG stops when |r| <= FT_RECON_TOL |r_0| (r on the free nodes) or after
 * FT_RECON_MAX_ITER iterations. Dot products are summed per row in double and the rows in order, so the
 * iterates do not depend on the thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define PRE_SWEEPS 2

static double bilinear_weight(long d)
{
    return d == 0 ? 1.0 : 0.5;
}

/* Builds level `l` from level `l - 1`. */
static int coarsen(ft_recon_problem *p, int l)
{
    const ft_recon_level *F = &p->lev[l - 1];
    ft_recon_level *C = &p->lev[l];
    memset(C, 0, sizeof *C);
    C->nx = F->nx / 2 + 1;
    C->ny = F->ny / 2 + 1;
    C->tp = F->tp / 4.0;
    C->mem = F->mem;
    if (l <= p->npl) {
        /* the multilevel prior's level l, on this level's spacing (recon_levels.c) */
        C->tp += p->pl[l - 1].tp;
        C->mem += p->pl[l - 1].mem;
    }
    size_t n = C->nx * C->ny;
    C->c = ft_calloc(n, sizeof *C->c);
    C->fixed = ft_calloc(n, 1);
    C->x = ft_calloc(n, sizeof *C->x);
    C->b = ft_calloc(n, sizeof *C->b);
    C->r = ft_calloc(n, sizeof *C->r);
    if (!C->c || !C->fixed || !C->x || !C->b || !C->r)
        return FT_E_NOMEM;
    double pen = ft_recon_prior_diag(F);
#pragma omp parallel for num_threads(ft_recon_threads(p->nthreads, n)) schedule(static)
    for (size_t J = 0; J < C->ny; J++)
        for (size_t I = 0; I < C->nx; I++) {
            size_t ci = J * C->nx + I;
            long fx = 2 * (long)I, fy = 2 * (long)J;
            if (fx < (long)F->nx && fy < (long)F->ny && F->fixed[(size_t)fy * F->nx + (size_t)fx]) {
                C->fixed[ci] = 1;
                continue;
            }
            double s = 0.0;
            for (long dy = -1; dy <= 1; dy++)
                for (long dx = -1; dx <= 1; dx++) {
                    long x = fx + dx, y = fy + dy;
                    if (x < 0 || y < 0 || x >= (long)F->nx || y >= (long)F->ny)
                        continue;
                    size_t fi = (size_t)y * F->nx + (size_t)x;
                    s += bilinear_weight(dx) * bilinear_weight(dy) * (F->fixed[fi] ? pen : (double)F->c[fi]);
                }
            C->c[ci] = (float)s;
        }
    return FT_OK;
}

/* Dense Cholesky factor of the coarsest level's matrix on its free nodes. A pivot that vanishes (a
 * direction no datum constrains) is replaced by the largest diagonal, which keeps the factor symmetric
 * positive definite (that direction is then left nearly unchanged by the preconditioner). */
static int factor_coarsest(ft_recon_level *L)
{
    size_t n = L->nx * L->ny, m = 0;
    for (size_t i = 0; i < n; i++)
        m += !L->fixed[i];
    L->nchol = m;
    if (m == 0)
        return FT_OK;
    L->chol = ft_calloc(m * m, sizeof *L->chol);
    L->chol_idx = ft_malloc(m * sizeof *L->chol_idx);
    size_t *pos = ft_malloc(n * sizeof *pos);
    float *e = ft_calloc(n, sizeof *e);
    if (!L->chol || !L->chol_idx || !pos || !e) {
        free(pos);
        free(e);
        return FT_E_NOMEM;
    }
    for (size_t i = 0, k = 0; i < n; i++) {
        pos[i] = (size_t)-1;
        if (!L->fixed[i]) {
            L->chol_idx[k] = i;
            pos[i] = k++;
        }
    }
    double *A = L->chol, dmax = 0.0;
    for (size_t k = 0; k < m; k++) {
        size_t j = L->chol_idx[k], jx = j % L->nx, jy = j / L->nx;
        e[j] = 1.0f;
        for (long dy = -2; dy <= 2; dy++)
            for (long dx = -2; dx <= 2; dx++) {
                long x = (long)jx + dx, y = (long)jy + dy;
                if (x < 0 || y < 0 || x >= (long)L->nx || y >= (long)L->ny)
                    continue;
                size_t i = (size_t)y * L->nx + (size_t)x;
                if (pos[i] == (size_t)-1)
                    continue;
                double a;
                A[pos[i] * m + k] = ft_recon_apply(L, e, (size_t)x, (size_t)y, &a);
            }
        e[j] = 0.0f;
        dmax = fmax(dmax, A[k * m + k]);
    }
    free(e);
    free(pos);
    if (!(dmax > 0.0))
        dmax = 1.0;
    for (size_t j = 0; j < m; j++) {
        double d = A[j * m + j];
        for (size_t k = 0; k < j; k++)
            d -= A[j * m + k] * A[j * m + k];
        if (!(d > 1e-10 * dmax))
            d = dmax;
        d = sqrt(d);
        A[j * m + j] = d;
        for (size_t i = j + 1; i < m; i++) {
            double s = A[i * m + j];
            for (size_t k = 0; k < j; k++)
                s -= A[i * m + k] * A[j * m + k];
            A[i * m + j] = s / d;
        }
    }
    return FT_OK;
}

static void solve_coarsest(const ft_recon_level *L, const float *b, float *x)
{
    size_t m = L->nchol, n = L->nx * L->ny;
    for (size_t i = 0; i < n; i++)
        x[i] = 0.0f;
    if (m == 0)
        return;
    double *y = malloc(m * sizeof *y);
    if (y == NULL)
        return; /* the correction is then 0: slower convergence, never a wrong answer */
    const double *A = L->chol;
    for (size_t i = 0; i < m; i++) {
        double s = b[L->chol_idx[i]];
        for (size_t k = 0; k < i; k++)
            s -= A[i * m + k] * y[k];
        y[i] = s / A[i * m + i];
    }
    for (size_t i = m; i-- > 0;) {
        double s = y[i];
        for (size_t k = i + 1; k < m; k++)
            s -= A[k * m + i] * y[k];
        y[i] = s / A[i * m + i];
    }
    for (size_t i = 0; i < m; i++)
        x[L->chol_idx[i]] = (float)y[i];
    free(y);
}

int ft_recon_hierarchy(ft_recon_problem *p, double lambda, double tension)
{
    for (int l = 1; l < p->nlev; l++)
        ft_recon_level_free_arrays(&p->lev[l]);
    free(p->lev[0].chol);
    free(p->lev[0].chol_idx);
    p->lev[0].chol = NULL;
    p->lev[0].chol_idx = NULL;
    p->nlev = 1;
    int nlev = 1;
    for (size_t nx = p->nx, ny = p->ny; (nx > FT_RECON_COARSEST || ny > FT_RECON_COARSEST) && nlev < 40; nlev++) {
        nx = nx / 2 + 1;
        ny = ny / 2 + 1;
    }
    ft_recon_level *lev = ft_realloc_array(p->lev, (size_t)nlev, sizeof *lev);
    if (lev == NULL)
        return FT_E_NOMEM;
    p->lev = lev;
    for (int l = 1; l < nlev; l++)
        memset(&lev[l], 0, sizeof lev[l]);
    lev[0].tp = lambda * (1.0 - tension);
    lev[0].mem = lambda * tension;
    p->nlev = nlev;
    p->lambda = lambda;
    int rc = ft_recon_prior_levels(p, p->prior_H);
    if (rc != FT_OK)
        return rc;
    for (int l = 1; l < nlev && rc == FT_OK; l++)
        rc = coarsen(p, l);
    if (rc != FT_OK)
        return rc;
    return factor_coarsest(&lev[nlev - 1]);
}

void ft_recon_prolong_add(const ft_recon_level *F, const ft_recon_level *C, const float *xc, float *xf,
                          int nthreads)
{
    size_t cnx = C->nx;
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, F->nx * F->ny)) schedule(static)
    for (size_t y = 0; y < F->ny; y++) {
        size_t J = y / 2, J2 = J + (y & 1);
        for (size_t x = 0; x < F->nx; x++) {
            size_t i = y * F->nx + x;
            if (F->fixed[i])
                continue;
            size_t I = x / 2, I2 = I + (x & 1);
            double v = 0.25 * ((double)xc[J * cnx + I] + xc[J * cnx + I2] + xc[J2 * cnx + I] + xc[J2 * cnx + I2]);
            xf[i] += (float)v;
        }
    }
}

/* b_c = P' r on the free coarse nodes. */
static void restrict_residual(const ft_recon_level *F, const float *r, const ft_recon_level *C, float *bc,
                              int nthreads)
{
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, F->nx * F->ny)) schedule(static)
    for (size_t J = 0; J < C->ny; J++)
        for (size_t I = 0; I < C->nx; I++) {
            size_t ci = J * C->nx + I;
            if (C->fixed[ci]) {
                bc[ci] = 0.0f;
                continue;
            }
            double s = 0.0;
            for (long dy = -1; dy <= 1; dy++)
                for (long dx = -1; dx <= 1; dx++) {
                    long x = 2 * (long)I + dx, y = 2 * (long)J + dy;
                    if (x >= 0 && y >= 0 && x < (long)F->nx && y < (long)F->ny)
                        s += bilinear_weight(dx) * bilinear_weight(dy) * (double)r[(size_t)y * F->nx + (size_t)x];
                }
            bc[ci] = (float)s;
        }
}

/* x = V-cycle approximation of A_l^-1 b on level l (x, b, r: that level's arrays). */
static int vcycle(const ft_recon_problem *p, int l, float *x, const float *b, float *r)
{
    const ft_recon_level *L = &p->lev[l];
    if (l == p->nlev - 1) {
        solve_coarsest(L, b, x);
        return FT_OK;
    }
    memset(x, 0, L->nx * L->ny * sizeof *x);
    int rc = FT_OK;
    for (int s = 0; s < PRE_SWEEPS && rc == FT_OK; s++)
        rc = ft_recon_sweep(L, x, b, 0, p->nthreads);
    if (rc != FT_OK)
        return rc;
    ft_recon_residual(L, x, b, r, p->nthreads);
    ft_recon_level *C = &p->lev[l + 1];
    restrict_residual(L, r, C, C->b, p->nthreads);
    rc = vcycle(p, l + 1, C->x, C->b, C->r);
    if (rc != FT_OK)
        return rc;
    ft_recon_prolong_add(L, C, C->x, x, p->nthreads);
    for (int s = 0; s < PRE_SWEEPS && rc == FT_OK; s++)
        rc = ft_recon_sweep(L, x, b, 1, p->nthreads);
    return rc;
}

/* sum a_i b_i per row in double, rows in order. */
static double dot(const float *a, const float *b, size_t nx, size_t ny, double *rows, int nthreads)
{
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nx * ny)) schedule(static)
    for (size_t y = 0; y < ny; y++) {
        double s = 0.0;
        for (size_t x = 0; x < nx; x++)
            s += (double)a[y * nx + x] * (double)b[y * nx + x];
        rows[y] = s;
    }
    double s = 0.0;
    for (size_t y = 0; y < ny; y++)
        s += rows[y];
    return s;
}

/* r = rhs - A u on the free nodes (0 on fixed ones), A with the multilevel prior's levels; returns sum r².
 * q (n floats) and rows (ny doubles) are work space. */
static double full_residual(const ft_recon_problem *p, const float *u, const float *rhs, float *r, float *q,
                            double *rows)
{
    const ft_recon_level *L = &p->lev[0];
    size_t nx = L->nx, ny = L->ny, n = nx * ny;
    int nt = ft_recon_threads(p->nthreads, n);
    double rr = ft_recon_residual(L, u, rhs, r, nt);
    if (p->npl == 0)
        return rr;
    /* the multilevel prior's share of A u (recon_levels.c) */
    memset(q, 0, n * sizeof *q);
    ft_recon_prior_levels_add(p, u, q);
    for (size_t i = 0; i < n; i++)
        r[i] = L->fixed[i] ? 0.0f : (float)((double)r[i] - (double)q[i]);
    return dot(r, r, nx, ny, rows, nt);
}

double ft_recon_residual_norm2(const ft_recon_problem *p, const float *rhs, const float *u)
{
    size_t n = p->nx * p->ny;
    float *r = ft_malloc(n * sizeof *r), *q = ft_malloc(n * sizeof *q);
    double *rows = ft_malloc(p->ny * sizeof *rows), rr = NAN;
    if (r && q && rows)
        rr = full_residual(p, u, rhs, r, q, rows);
    free(r);
    free(q);
    free(rows);
    return rr;
}

/* Conjugate gradients from u until sum r² <= rr_stop, or (rr_stop < 0) <= FT_RECON_TOL² x the initial one. */
static int solve_cg(const ft_recon_problem *p, const float *rhs, float *u, double rr_stop,
                    const ft_recon_progress *prog, int *iterations)
{
    const ft_recon_level *L = &p->lev[0];
    size_t nx = L->nx, ny = L->ny, n = nx * ny;
    int nt = ft_recon_threads(p->nthreads, n);
    float *r = ft_malloc(n * sizeof *r), *z = ft_malloc(n * sizeof *z);
    float *pp = ft_malloc(n * sizeof *pp), *q = ft_malloc(n * sizeof *q);
    double *rows = ft_malloc(ny * sizeof *rows);
    int rc = FT_OK, it = 0;
    if (!r || !z || !pp || !q || !rows) {
        rc = FT_E_NOMEM;
        goto done;
    }
    double rr = full_residual(p, u, rhs, r, q, rows);
    double rr0 = rr;
    if (!isfinite(rr)) {
        rc = ft_error(FT_E_NUMERIC, "the initial residual is not finite");
        goto done;
    }
    double stop = rr_stop >= 0.0 ? rr_stop : FT_RECON_TOL * FT_RECON_TOL * rr0;
    if (rr0 == 0.0 || rr0 <= stop)
        goto done;
    double span = rr_stop >= 0.0 ? log(rr0 / fmax(stop, 1e-300)) : log(1.0 / (FT_RECON_TOL * FT_RECON_TOL));
    rc = vcycle(p, 0, z, r, q);
    if (rc != FT_OK)
        goto done;
    memcpy(pp, z, n * sizeof *pp);
    double rz = dot(r, z, nx, ny, rows, nt);
    for (it = 1; it <= FT_RECON_MAX_ITER; it++) {
        /* q = A p on the free nodes (p is 0 on fixed ones) */
#pragma omp parallel for num_threads(nt) schedule(static)
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++) {
                size_t i = y * nx + x;
                double a;
                q[i] = L->fixed[i] ? 0.0f : (float)ft_recon_apply(L, pp, x, y, &a);
            }
        if (p->npl > 0) {
            ft_recon_prior_levels_add(p, pp, q);
            for (size_t i = 0; i < n; i++)
                if (L->fixed[i])
                    q[i] = 0.0f;
        }
        double pq = dot(pp, q, nx, ny, rows, nt);
        if (!(pq > 0.0) || !(rz > 0.0))
            break;
        double alpha = rz / pq;
#pragma omp parallel for num_threads(nt) schedule(static)
        for (size_t i = 0; i < n; i++) {
            u[i] = (float)((double)u[i] + alpha * (double)pp[i]);
            r[i] = (float)((double)r[i] - alpha * (double)q[i]);
        }
        rr = dot(r, r, nx, ny, rows, nt);
        if (prog) {
            double f = log(rr0 / fmax(rr, 1e-300)) / span;
            rc = ft_recon_report(prog, fmin(1.0, fmax(0.0, f)), "reconstruct: smooth solution");
            if (rc != FT_OK)
                goto done;
        }
        if (!isfinite(rr)) {
            rc = ft_error(FT_E_NUMERIC, "the solver diverged (residual not finite)");
            goto done;
        }
        if (rr <= stop)
            break;
        rc = vcycle(p, 0, z, r, q);
        if (rc != FT_OK)
            goto done;
        double rz1 = dot(r, z, nx, ny, rows, nt), beta = rz1 / rz;
        rz = rz1;
#pragma omp parallel for num_threads(nt) schedule(static)
        for (size_t i = 0; i < n; i++)
            pp[i] = (float)((double)z[i] + beta * (double)pp[i]);
    }
done:
    if (iterations)
        *iterations = it;
    free(r);
    free(z);
    free(pp);
    free(q);
    free(rows);
    return rc;
}

int ft_recon_solve_rhs(const ft_recon_problem *p, const float *rhs, float *u, const ft_recon_progress *prog,
                       int *iterations)
{
    return solve_cg(p, rhs, u, -1.0, prog, iterations);
}

int ft_recon_solve_to(const ft_recon_problem *p, const float *rhs, float *u, double rr_stop,
                      const ft_recon_progress *prog, int *iterations)
{
    return solve_cg(p, rhs, u, fmax(rr_stop, 0.0), prog, iterations);
}

void ft_recon_data_rhs(const ft_recon_problem *p, float *rhs, float *u)
{
    const ft_recon_level *L = &p->lev[0];
    size_t n = L->nx * L->ny;
    double sw = 0.0, swd = 0.0;
    for (size_t i = 0; i < n; i++) {
        double w = L->fixed[i] ? 1.0 : (double)L->c[i];
        sw += w;
        swd += w * (double)p->d[i];
    }
    float start = (float)(sw > 0.0 ? swd / sw : 0.0); /* the initial guess: the data's weighted mean */
    for (size_t i = 0; i < n; i++) {
        rhs[i] = L->fixed[i] ? 0.0f : (float)((double)L->c[i] * (double)p->d[i]);
        u[i] = L->fixed[i] ? p->d[i] : start;
    }
}

int ft_recon_solve(const ft_recon_problem *p, float *u, const ft_recon_progress *prog, int *iterations)
{
    size_t n = p->nx * p->ny;
    float *rhs = ft_malloc(n * sizeof *rhs);
    if (rhs == NULL)
        return FT_E_NOMEM;
    ft_recon_data_rhs(p, rhs, u);
    int rc = ft_recon_solve_rhs(p, rhs, u, prog, iterations);
    free(rhs);
    return rc;
}
