/* fracterra — recon_voids.c: ft_reconstruct_voids, filling the nodata cells of a DEM with the
 * reconstruction methods (Arakawa & Krotkov §3; docs/terrain-reconstruct.md).
 *
 * Valid cells are fixed nodes (Dirichlet) and keep their values bit for bit; only the voids are unknowns.
 * Every term of the energy (recon_stencil.c) spans at most 2 nodes from any of its nodes, so a void
 * interacts only with the cells within 2 of it: the voids are grouped into components of their mask
 * dilated by 2 cells (8-connected), and each component is solved on its own box (the bounding box of its
 * dilated cells), exactly the same problem as on the whole grid. Voids of other components inside a box
 * are fixed there (no term joins them to this component's voids). Component k's random streams come
 * from ft_rng_mix(seed, k), its realization r from that + r. D and sigma0 are measured on all the valid
 * cells (grid estimators with their default ranges).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define MARGIN 2

typedef struct {
    size_t x0, y0, x1, y1; /* inclusive box */
    size_t voids;
} component;

static int is_void(const ft_grid *g, size_t i)
{
    return (g->mask && !g->mask[i]) || !isfinite(g->z[i]);
}

/* Labels the components of the void mask dilated by MARGIN (8-connected): label[i] = component + 1 on
 * the dilated cells, 0 elsewhere. */
static int label_components(const ft_grid *g, uint32_t *label, component **comps, size_t *ncomp)
{
    size_t nx = g->nx, ny = g->ny, n = nx * ny;
    uint8_t *dil = ft_calloc(n, 1);
    size_t *stack = ft_malloc(n * sizeof *stack);
    if (dil == NULL || stack == NULL) {
        free(dil);
        free(stack);
        return FT_E_NOMEM;
    }
    /* separable dilation by MARGIN: rows, then columns */
    uint8_t *tmp = ft_calloc(n, 1);
    if (tmp == NULL) {
        free(dil);
        free(stack);
        return FT_E_NOMEM;
    }
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++)
            if (is_void(g, y * nx + x))
                for (size_t a = x >= MARGIN ? x - MARGIN : 0; a <= x + MARGIN && a < nx; a++)
                    tmp[y * nx + a] = 1;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++)
            if (tmp[y * nx + x])
                for (size_t b = y >= MARGIN ? y - MARGIN : 0; b <= y + MARGIN && b < ny; b++)
                    dil[b * nx + x] = 1;
    free(tmp);
    size_t cap = 16, nc = 0;
    component *c = ft_malloc(cap * sizeof *c);
    int rc = c ? FT_OK : FT_E_NOMEM;
    for (size_t s = 0; s < n && rc == FT_OK; s++) {
        if (!dil[s] || label[s])
            continue;
        if (nc == cap) {
            component *c2 = ft_realloc_array(c, cap * 2, sizeof *c);
            if (c2 == NULL) {
                rc = FT_E_NOMEM;
                break;
            }
            c = c2;
            cap *= 2;
        }
        component *k = &c[nc++];
        *k = (component){s % nx, s / nx, s % nx, s / nx, 0};
        size_t top = 0;
        stack[top++] = s;
        label[s] = (uint32_t)nc;
        while (top > 0) {
            size_t i = stack[--top], x = i % nx, y = i / nx;
            k->voids += (size_t)is_void(g, i);
            k->x0 = x < k->x0 ? x : k->x0;
            k->x1 = x > k->x1 ? x : k->x1;
            k->y0 = y < k->y0 ? y : k->y0;
            k->y1 = y > k->y1 ? y : k->y1;
            for (long dy = -1; dy <= 1; dy++)
                for (long dx = -1; dx <= 1; dx++) {
                    long a = (long)x + dx, b = (long)y + dy;
                    if (a < 0 || b < 0 || a >= (long)nx || b >= (long)ny)
                        continue;
                    size_t j = (size_t)b * nx + (size_t)a;
                    if (dil[j] && !label[j]) {
                        label[j] = (uint32_t)nc;
                        stack[top++] = j;
                    }
                }
        }
    }
    free(dil);
    free(stack);
    if (rc != FT_OK) {
        free(c);
        return rc;
    }
    *comps = c;
    *ncomp = nc;
    return FT_OK;
}

/* The problem of component k (label k + 1) on its box. */
static int component_problem(const ft_grid *g, const uint32_t *label, size_t k, const component *c, int nthreads,
                             ft_recon_problem **out)
{
    size_t bw = c->x1 - c->x0 + 1, bh = c->y1 - c->y0 + 1;
    ft_recon_problem *p = ft_recon_problem_create(bw, bh, nthreads);
    if (p == NULL)
        return FT_E_NOMEM;
    size_t fixed = 0;
    long ax = -1, ay = -1, bx = -1, by = -1;
    int spread = 0;
    for (size_t y = 0; y < bh; y++)
        for (size_t x = 0; x < bw; x++) {
            size_t i = (c->y0 + y) * g->nx + c->x0 + x, j = y * bw + x;
            int mine = is_void(g, i) && label[i] == (uint32_t)(k + 1);
            if (mine)
                continue;
            p->lev[0].fixed[j] = 1;
            p->d[j] = is_void(g, i) ? 0.0f : g->z[i];
            if (is_void(g, i))
                continue;
            if (fixed == 0) {
                ax = (long)x;
                ay = (long)y;
            } else if (fixed == 1) {
                bx = (long)x;
                by = (long)y;
            } else if (!spread && (bx - ax) * ((long)y - ay) - (by - ay) * ((long)x - ax) != 0) {
                spread = 1;
            }
            fixed++;
        }
    if (!spread) {
        ft_recon_problem_free(p);
        return ft_error(FT_E_EMPTY, "the void at cells (%zu..%zu, %zu..%zu) has %zu valid cell(s) "
                        "around it, not 3 off a line", c->x0, c->x1, c->y0, c->y1, fixed);
    }
    *out = p;
    return FT_OK;
}

int ft_reconstruct_voids(const ft_grid *dem, const ft_recon_opts *opts, ft_grid **out, ft_grid **sd_out,
                         ft_recon_info *info)
{
    ft_recon_opts o;
    ft_recon_info inf;
    int rc = ft_recon_begin(opts, &o, &inf, out, sd_out);
    if (rc != FT_OK)
        return rc;
    if (dem == NULL || dem->z == NULL || dem->nx == 0 || dem->ny == 0)
        return ft_error(FT_E_INVALID, "the DEM is NULL or empty");
    size_t nx = dem->nx, ny = dem->ny, n = nx * ny, nvoid = 0;
    for (size_t i = 0; i < n; i++)
        nvoid += (size_t)is_void(dem, i);
    if (nvoid == n)
        return ft_error(FT_E_EMPTY, "the DEM (%zu x %zu) has no valid cell", nx, ny);
    rc = ft_recon_outputs(dem, sd_out != NULL, out, sd_out);
    if (rc != FT_OK)
        return rc;
    for (size_t i = 0; i < n; i++)
        (*out)->z[i] = is_void(dem, i) ? 0.0f : dem->z[i];
    inf.data_used = n - nvoid;
    inf.filled = nvoid;
    inf.lambda = o.lambda; /* known cells are fixed: no discrepancy search */
    inf.dim = o.dim;
    uint32_t *label = NULL;
    component *comps = NULL;
    size_t ncomp = 0;
    ft_recon_params par;
    if (nvoid > 0) {
        double gt1 = dem->gt[1], gt5 = dem->gt[5], gt2 = dem->gt[2], gt4 = dem->gt[4];
        double cell = sqrt(fabs(gt1 * gt5 - gt2 * gt4));
        rc = ft_recon_job_params(&o, NULL, dem, NULL, cell > 0.0 ? cell : 1.0, &par, &inf);
        label = rc == FT_OK ? ft_calloc(n, sizeof *label) : NULL;
        if (rc == FT_OK && label == NULL)
            rc = FT_E_NOMEM;
        if (rc == FT_OK)
            rc = label_components(dem, label, &comps, &ncomp);
    }
    size_t done = 0;
    for (size_t k = 0; k < ncomp && rc == FT_OK; k++) {
        const component *c = &comps[k];
        ft_recon_problem *p = NULL;
        rc = component_problem(dem, label, k, c, o.threads, &p);
        if (rc != FT_OK)
            break;
        size_t bw = p->nx, bh = p->ny;
        float *m = ft_malloc(bw * bh * sizeof *m), *s = sd_out ? ft_malloc(bw * bh * sizeof *s) : NULL;
        if (m == NULL || (sd_out && s == NULL)) {
            free(m);
            free(s);
            ft_recon_problem_free(p);
            rc = FT_E_NOMEM;
            break;
        }
        ft_recon_params cp = par;
        cp.seed = ft_rng_mix(o.seed, (uint64_t)k);
        ft_recon_progress prog = {o.progress, o.progress_arg, 0.02 + 0.98 * (double)done / (double)nvoid,
                                  0.98 * (double)c->voids / (double)nvoid};
        rc = ft_recon_run(p, o.lambda, cp.tension, &cp, m, s, bw, &prog);
        if (rc == FT_OK) {
            inf.levels = p->nlev > inf.levels ? p->nlev : inf.levels;
            for (size_t y = 0; y < bh; y++)
                for (size_t x = 0; x < bw; x++)
                    if (!p->lev[0].fixed[y * bw + x]) {
                        size_t i = (c->y0 + y) * nx + c->x0 + x;
                        (*out)->z[i] = m[y * bw + x];
                        if (s)
                            (*sd_out)->z[i] = s[y * bw + x];
                    }
        }
        done += c->voids;
        free(m);
        free(s);
        ft_recon_problem_free(p);
    }
    free(label);
    free(comps);
    if (rc == FT_OK)
        rc = ft_progress(o.progress, o.progress_arg, 1.0, "reconstruct: done");
    return ft_recon_end(rc, &inf, info, out, sd_out);
}
