/* fracterra — recon_binding.c: scattered elevations -> the nodes of the reconstruction grid (Arakawa &
 * Krotkov §3.2: the data compatibility term E_d = sum c_i/2 (u_i - d_i)², eq. 6).
 *
 * The nodes are the cell centres of the target grid. A point goes to the node of the cell it falls in
 * (the nearest centre); a point outside the grid is counted and ignored. Several points on one node
 * become their confidence-weighted mean d = sum c d / sum c with confidence sum c. With sigma = 0 and no
 * per-point weights the data nodes are fixed (Dirichlet): the data are honoured exactly. Otherwise
 * c = w² with w = 1/sigma or the point's own weight (its confidence 1/sigma_i); the problem then also
 * records the number of points bound and their weighted scatter about their node's datum (the part of
 * chi² that no surface can remove), for the discrepancy principle (recon_discrepancy.c).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

ft_recon_problem *ft_recon_problem_create(size_t nx, size_t ny, int nthreads)
{
    ft_recon_problem *p = ft_calloc(1, sizeof *p);
    if (p == NULL)
        return NULL;
    size_t n = nx * ny;
    p->nx = nx;
    p->ny = ny;
    p->nthreads = nthreads > 0 ? nthreads : 1;
    p->d = ft_calloc(n, sizeof *p->d);
    p->lev = ft_calloc(1, sizeof *p->lev);
    if (p->d == NULL || p->lev == NULL) {
        ft_recon_problem_free(p);
        return NULL;
    }
    p->nlev = 1;
    p->lev[0].nx = nx;
    p->lev[0].ny = ny;
    p->lev[0].c = ft_calloc(n, sizeof *p->lev[0].c);
    p->lev[0].fixed = ft_calloc(n, 1);
    if (p->lev[0].c == NULL || p->lev[0].fixed == NULL) {
        ft_recon_problem_free(p);
        return NULL;
    }
    return p;
}

void ft_recon_level_free_arrays(ft_recon_level *L)
{
    free(L->c);
    free(L->fixed);
    free(L->x);
    free(L->b);
    free(L->r);
    free(L->chol);
    free(L->chol_idx);
}

void ft_recon_problem_free(ft_recon_problem *p)
{
    if (p == NULL)
        return;
    for (int l = 0; p->lev && l < p->nlev; l++)
        ft_recon_level_free_arrays(&p->lev[l]);
    free(p->lev);
    ft_recon_prior_levels_free(p);
    free(p->d);
    free(p);
}

/* Inverse of the target's geotransform: pixel coordinates (col, row) of a map position. */
static int inverse_gt(const double *gt, double *inv)
{
    double det = gt[1] * gt[5] - gt[2] * gt[4];
    if (!(fabs(det) > 0.0) || !isfinite(det))
        return ft_error(FT_E_INVALID, "the target grid's geotransform is degenerate "
                        "(pixel size %g x %g)", gt[1], gt[5]);
    inv[0] = gt[5] / det;
    inv[1] = -gt[2] / det;
    inv[2] = -gt[4] / det;
    inv[3] = gt[1] / det;
    return FT_OK;
}

/* 1 if the data nodes are not all on one line (node coordinates). */
static int not_collinear(const ft_recon_problem *p, const double *wsum, size_t *count)
{
    size_t nx = p->nx, n = nx * p->ny, k = 0;
    long ax = 0, ay = 0, bx = 0, by = 0;
    int have_b = 0, ok = 0;
    for (size_t i = 0; i < n; i++) {
        if (!(wsum[i] > 0.0))
            continue;
        long x = (long)(i % nx), y = (long)(i / nx);
        if (k == 0) {
            ax = x;
            ay = y;
        } else if (!have_b) {
            bx = x;
            by = y;
            have_b = 1;
        } else if (!ok && (bx - ax) * (y - ay) - (by - ay) * (x - ax) != 0) {
            ok = 1;
        }
        k++;
    }
    *count = k;
    return ok;
}

int ft_recon_bind_points(const ft_points *p, const ft_grid *target, double sigma, int nthreads,
                         ft_recon_problem **out, size_t *outside)
{
    *out = NULL;
    *outside = 0;
    if (p == NULL || p->n == 0 || p->x == NULL || p->y == NULL || p->z == NULL)
        return ft_error(FT_E_EMPTY, "no points");
    for (size_t i = 0; i < p->n; i++) {
        if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->z[i]))
            return ft_error(FT_E_NUMERIC, "point %zu is not finite (x %g, y %g, z %g)", i, p->x[i],
                            p->y[i], p->z[i]);
        if (p->w && !(p->w[i] > 0.0 && isfinite(p->w[i])))
            return ft_error(FT_E_INVALID, "point %zu has weight (confidence 1/sigma) %g; it must "
                            "be > 0 and finite", i, p->w[i]);
    }
    double inv[4] = {0.0, 0.0, 0.0, 0.0};
    int rc = inverse_gt(target->gt, inv);
    if (rc != FT_OK)
        return rc;
    size_t nx = target->nx, ny = target->ny, n = nx * ny;
    ft_recon_problem *pr = ft_recon_problem_create(nx, ny, nthreads);
    double *wsum = ft_calloc(n, sizeof *wsum), *zsum = ft_calloc(n, sizeof *zsum);
    if (pr == NULL || wsum == NULL || zsum == NULL) {
        ft_recon_problem_free(pr);
        free(wsum);
        free(zsum);
        return FT_E_NOMEM;
    }
    int dirichlet = sigma == 0.0 && p->w == NULL;
    double c0 = sigma > 0.0 ? 1.0 / (sigma * sigma) : 1.0;
    for (size_t i = 0; i < p->n; i++) {
        double dx = p->x[i] - target->gt[0], dy = p->y[i] - target->gt[3];
        double col = inv[0] * dx + inv[1] * dy, row = inv[2] * dx + inv[3] * dy;
        if (!(col >= 0.0 && row >= 0.0 && col < (double)nx && row < (double)ny)) {
            (*outside)++;
            continue;
        }
        size_t k = (size_t)row * nx + (size_t)col;
        double c = dirichlet ? 1.0 : p->w ? p->w[i] * p->w[i] : c0;
        wsum[k] += c;
        zsum[k] += c * p->z[i];
    }
    size_t used = 0;
    if (!not_collinear(pr, wsum, &used)) {
        ft_recon_problem_free(pr);
        free(wsum);
        free(zsum);
        if (used < 3)
            return ft_error(FT_E_EMPTY, "%zu grid node(s) hold data (%zu of %zu points inside the "
                            "grid); at least 3 not on a line are needed", used, p->n - *outside, p->n);
        return ft_error(FT_E_INVALID, "the %zu data nodes are all on one line; at least 3 not on a "
                        "line are needed", used);
    }
    ft_recon_level *L = &pr->lev[0];
    for (size_t k = 0; k < n; k++) {
        if (!(wsum[k] > 0.0))
            continue;
        pr->d[k] = (float)(zsum[k] / wsum[k]);
        if (dirichlet)
            L->fixed[k] = 1;
        else
            L->c[k] = (float)wsum[k];
    }
    if (!dirichlet) {
        /* what the discrepancy principle needs: N and the misfit of the points about their node's datum */
        for (size_t i = 0; i < p->n; i++) {
            double dx = p->x[i] - target->gt[0], dy = p->y[i] - target->gt[3];
            double col = inv[0] * dx + inv[1] * dy, row = inv[2] * dx + inv[3] * dy;
            if (!(col >= 0.0 && row >= 0.0 && col < (double)nx && row < (double)ny))
                continue;
            size_t k = (size_t)row * nx + (size_t)col;
            double c = p->w ? p->w[i] * p->w[i] : c0, e = p->z[i] - (double)pr->d[k];
            pr->ndata++;
            pr->scatter += c * e * e;
        }
    }
    free(wsum);
    free(zsum);
    *out = pr;
    return FT_OK;
}
