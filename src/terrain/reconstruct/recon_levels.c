/* fracterra — recon_levels.c: the fractal method's multilevel prior (Szeliski 1990, "Bayesian modeling of
 * uncertainty in low-level vision", the fractal prior; Arakawa & Krotkov 1996 eqs. 7-8: the energy of every
 * layer of the multiresolution pyramid, with weights that depend on D).
 *
 * The prior energy of the fractal method is a sum over the levels l = 0 .. L of the pyramid,
 *     E_p(u) = sum_l w_l [tp E_tp(R_l u) + g^l mem E_mem(R_l u)],   w_l = 2^(-2 H l),   H = 3 - D,
 * where E_tp and E_mem are the thin-plate and membrane energies of recon_stencil.c on level l's own nodes
 * (spacing 2^l fine nodes, h = 1 there; tp and mem are level 0's, lambda (1 - tau) and lambda tau),
 * g = FT_RECON_LEVEL_MEMBRANE, and R_l = r o ... o r (l times) the restriction to level l: r is full
 * weighting normalized to a weighted mean, separable, (1/2, 1, 1/2) / (the sum of the weights inside the
 * grid); level l has the nodes 2I <= n - 1 of level l - 1. The matrix is A = sum_l R_l' A_l R_l (R_0 = I).
 * Why these weights: a smooth component of wavenumber k (fine units) costs 4^-l (2^l k)^4 per fine node
 * in level l's thin plate, and the levels that see it are those with 2^l k < 1; with w_l = 2^(-2Hl)
 * their sum grows like k^(2 + 2H), the fBm's precision (spectrum k^-(8 - 2D)), one octave per level
 * (the level weights of Szeliski's fractal prior, Arakawa & Krotkov eq. 8). A membrane level costs
 * 4^-l (2^l k)² = k² whatever l, so no weighting of membrane levels can follow k^(2 + 2H): the membrane
 * is the finest level's roughener (Szeliski's eq. 7 blend, tau), and its coarser copies decay by g per
 * level (measured: g = 1 leaves a dip of the structure function at 6-16 cells at D = 2.8, g = 0 an
 * excess at 2-4 cells). A single level (the blend of session 5) follows the law near one wavelength
 * only; its top octave is at best a membrane's, S(2)/S(1) = 1.21 > 2^H at D > 2.6.
 *
 * The levels keep their own nodes; applying A costs one restriction and one transposed restriction per
 * level (1/3 of a fine grid in all) and one stencil per level. The multigrid preconditioner of
 * recon_multigrid.c adds w_l E_l to its level l (the rediscretized operator of its coarse levels).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

/* Nodes of the level below a level of n nodes: 2I <= n - 1. */
static size_t coarser(size_t n)
{
    return (n - 1) / 2 + 1;
}

/* The weight of fine node x in coarse node I (0 unless |x - 2I| <= 1), normalized by the weights of I's
 * fine nodes inside [0, nf). */
static double rweight(size_t I, long x, size_t nf)
{
    long d = x - 2 * (long)I;
    if (d < -1 || d > 1 || x < 0 || x >= (long)nf)
        return 0.0;
    double sum = 1.0 + (2 * (long)I - 1 >= 0 ? 0.5 : 0.0) + (2 * (long)I + 1 < (long)nf ? 0.5 : 0.0);
    return (d == 0 ? 1.0 : 0.5) / sum;
}

void ft_recon_prior_levels_free(ft_recon_problem *p)
{
    for (int l = 0; l < p->npl; l++) {
        free(p->pl[l].c);
        free(p->pl[l].x);
        free(p->pl[l].b);
        free(p->pl[l].r);
    }
    free(p->pl);
    p->pl = NULL;
    p->npl = 0;
}

int ft_recon_prior_levels(ft_recon_problem *p, double H)
{
    ft_recon_prior_levels_free(p);
    if (!(H > 0.0))
        return FT_OK;
    const ft_recon_level *L0 = &p->lev[0];
    int n = 0;
    for (size_t nx = p->nx, ny = p->ny; n < 40; n++) {
        nx = coarser(nx);
        ny = coarser(ny);
        if (nx < 3 || ny < 3)
            break;
    }
    if (n == 0)
        return FT_OK;
    p->pl = ft_calloc((size_t)n, sizeof *p->pl);
    if (p->pl == NULL)
        return FT_E_NOMEM;
    p->npl = n;
    size_t nx = p->nx, ny = p->ny;
    for (int l = 0; l < n; l++) {
        ft_recon_level *P = &p->pl[l];
        size_t above_ny = ny; /* the restriction's work rows: this level's columns x the level above's rows */
        nx = coarser(nx);
        ny = coarser(ny);
        double w = pow(2.0, -2.0 * H * (l + 1));
        P->nx = nx;
        P->ny = ny;
        P->tp = w * L0->tp;
        P->mem = w * pow(FT_RECON_LEVEL_MEMBRANE, l + 1) * L0->mem;
        P->c = ft_calloc(nx * ny, sizeof *P->c);
        P->x = ft_calloc(nx * ny, sizeof *P->x);
        P->b = ft_calloc(nx * ny, sizeof *P->b);
        P->r = ft_calloc(nx * above_ny, sizeof *P->r);
        if (!P->c || !P->x || !P->b || !P->r) {
            ft_recon_prior_levels_free(p);
            return FT_E_NOMEM;
        }
    }
    return FT_OK;
}

/* c = r f along one axis: the rows of f (nrows x nf, row stride nf) to the rows of c (nrows x nc). */
static void restrict_rows(const float *f, size_t nf, float *c, size_t nc, size_t nrows, int nthreads)
{
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nf * nrows)) schedule(static)
    for (size_t y = 0; y < nrows; y++) {
        const float *fr = f + y * nf;
        float *cr = c + y * nc;
        for (size_t I = 0; I < nc; I++) {
            long x = 2 * (long)I;
            double s = rweight(I, x, nf) * (double)fr[x];
            if (x >= 1)
                s += rweight(I, x - 1, nf) * (double)fr[x - 1];
            if (x + 1 < (long)nf)
                s += rweight(I, x + 1, nf) * (double)fr[x + 1];
            cr[I] = (float)s;
        }
    }
}

/* f += r' c along one axis (rows of c: nc, rows of f: nf). */
static void restrict_rows_t(const float *c, size_t nc, float *f, size_t nf, size_t nrows, int nthreads)
{
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nf * nrows)) schedule(static)
    for (size_t y = 0; y < nrows; y++) {
        const float *cr = c + y * nc;
        float *fr = f + y * nf;
        for (size_t x = 0; x < nf; x++) {
            size_t I0 = x / 2, I1 = (x + 1) / 2;
            double s = rweight(I0, (long)x, nf) * (double)cr[I0];
            if (I1 != I0 && I1 < nc)
                s += rweight(I1, (long)x, nf) * (double)cr[I1];
            fr[x] += (float)s;
        }
    }
}

void ft_recon_restrict_mean(const float *f, size_t nfx, size_t nfy, float *c, size_t ncx, size_t ncy, float *tmp,
                            int nthreads)
{
    /* along x into tmp (nfy rows of ncx), then along y: row J = sum_dy w tmp row 2J + dy */
    restrict_rows(f, nfx, tmp, ncx, nfy, nthreads);
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nfx * nfy)) schedule(static)
    for (size_t J = 0; J < ncy; J++) {
        long y = 2 * (long)J;
        double w0 = rweight(J, y, nfy), wm = y >= 1 ? rweight(J, y - 1, nfy) : 0.0;
        double wp = y + 1 < (long)nfy ? rweight(J, y + 1, nfy) : 0.0;
        const float *r0 = tmp + (size_t)y * ncx, *rm = wm != 0.0 ? r0 - ncx : r0, *rp = wp != 0.0 ? r0 + ncx : r0;
        for (size_t I = 0; I < ncx; I++)
            c[J * ncx + I] = (float)(w0 * (double)r0[I] + wm * (double)rm[I] + wp * (double)rp[I]);
    }
}

void ft_recon_restrict_mean_t(const float *c, size_t ncx, size_t ncy, float *f, size_t nfx, size_t nfy, float *tmp,
                              int nthreads)
{
    /* along y into tmp (nfy rows of ncx), then along x added to f */
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nfx * nfy)) schedule(static)
    for (size_t y = 0; y < nfy; y++) {
        size_t J0 = y / 2, J1 = (y + 1) / 2;
        double w0 = rweight(J0, (long)y, nfy), w1 = J1 != J0 && J1 < ncy ? rweight(J1, (long)y, nfy) : 0.0;
        const float *a = c + J0 * ncx, *b = w1 != 0.0 ? c + J1 * ncx : a;
        float *t = tmp + y * ncx;
        for (size_t I = 0; I < ncx; I++)
            t[I] = (float)(w0 * (double)a[I] + w1 * (double)b[I]);
    }
    restrict_rows_t(tmp, ncx, f, nfx, nfy, nthreads);
}

/* y_l = A_l v_l on every node of prior level P (no data, no fixed nodes). */
static void apply_level(const ft_recon_level *P, const float *v, float *y, int nthreads)
{
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, P->nx * P->ny)) schedule(static)
    for (size_t r = 0; r < P->ny; r++)
        for (size_t c = 0; c < P->nx; c++) {
            double a;
            y[r * P->nx + c] = (float)ft_recon_apply(P, v, c, r, &a);
        }
}

void ft_recon_prior_levels_add(const ft_recon_problem *p, const float *x, float *y)
{
    if (p->npl == 0)
        return;
    int nt = p->nthreads;
    /* down: x_l = r x_(l-1) */
    const float *v = x;
    size_t nx = p->nx, ny = p->ny;
    for (int l = 0; l < p->npl; l++) {
        ft_recon_level *P = &p->pl[l];
        ft_recon_restrict_mean(v, nx, ny, P->x, P->nx, P->ny, P->r, nt);
        v = P->x;
        nx = P->nx;
        ny = P->ny;
    }
    /* up: b_l = A_l x_l + r' b_(l+1); y += r' b_1 */
    for (int l = p->npl - 1; l >= 0; l--) {
        ft_recon_level *P = &p->pl[l];
        float *acc = P->b;
        if (l == p->npl - 1)
            apply_level(P, P->x, acc, nt);
        else {
            apply_level(P, P->x, acc, nt);
            ft_recon_restrict_mean_t(p->pl[l + 1].b, p->pl[l + 1].nx, p->pl[l + 1].ny, acc, P->nx, P->ny,
                                     p->pl[l + 1].r, nt);
        }
    }
    ft_recon_restrict_mean_t(p->pl[0].b, p->pl[0].nx, p->pl[0].ny, y, p->nx, p->ny, p->pl[0].r, nt);
}
