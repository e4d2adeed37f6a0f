/* fracterra — dim_map.c: a local fractal-dimension (roughness) map: one estimate of ft_surface_dim in
 * every window of a moving window over the grid.
 *
 * Windows are window x window cells with their upper-left cell at multiples of step along both axes,
 * wholly inside the grid. The outputs (D and r² of each window's log-log fit) are grids on the lattice of
 * the window centres: output cell (i, j) covers step x step input cells centred on the centre of window
 * (i, j), so its geotransform is the input's scaled by step and shifted by (window - step) / 2 cells, and
 * the map lies over the DEM in any GIS. A window with fewer valid cells than min_valid of its area, or
 * where the estimator fails on the data (flat, too many holes for two scales), is nodata; an error of the
 * options (a scale range the window cannot hold) fails the whole map with the estimator's message.
 * Windows run in parallel (OpenMP, each thread measuring a copy of its window with the nested estimator
 * single-threaded); each window's result depends only on its cells and the options (random pairs use the
 * same seed in every window), so the maps are the same on every thread count. The exhaustive lag methods
 * (variogram, yokoya, pentland with pairs = 0) do not run per window: src/surface/dim_map_lags.c sums
 * their pair counters over blocks of step x step cells shared by the overlapping windows and fits each
 * window's table as the estimator does (the same D within rounding, tested). ft_surface_dim_map_noise
 * also returns every window's noise flag (its estimator removed a nugget or a spectral floor), a third
 * lattice grid read from the same per-window result: the D cells do not depend on it. docs/surface-grid.md,
 * docs/surface-noise.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "surface/grid_internal.h"

#define NAME "dim map"
#define MIN_WINDOW 4

typedef struct {
    int code;        /* first error of the options met in a window, FT_OK if none */
    char msg[512];
    volatile int stop;
} map_failure;

static int check_args(const ft_grid *g, size_t w, size_t s, ft_surface_method m, const ft_surface_dim_opts *o)
{
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, NAME ": the grid is NULL or empty");
    if ((unsigned)m >= FT_SURFACE_NMETHODS)
        return ft_error(FT_E_INVALID, NAME ": unknown surface method %d", (int)m);
    if (w < MIN_WINDOW)
        return ft_error(FT_E_INVALID, NAME ": window must be at least %d cells, got %zu", MIN_WINDOW, w);
    if (w > g->nx || w > g->ny)
        return ft_error(FT_E_INVALID, NAME ": window %zu cells is larger than the %zux%zu grid", w, g->nx, g->ny);
    if (s < 1)
        return ft_error(FT_E_INVALID, NAME ": step must be at least 1 cell, got %zu", s);
    if (!(o->min_valid > 0.0 && o->min_valid <= 1.0))
        return ft_error(FT_E_INVALID, NAME ": min_valid must be in (0, 1], got %g", o->min_valid);
    if (ft_grid_count_valid(g) == 0)
        return ft_error(FT_E_EMPTY, NAME ": the %zux%zu grid has no valid cell (all nodata)", g->nx, g->ny);
    return FT_OK;
}

/* An output grid on the window-centre lattice, all nodata, with the input's CRS. */
static ft_grid *lattice_grid(const ft_grid *g, size_t w, size_t s, size_t nox, size_t noy)
{
    ft_grid *o = ft_grid_create(nox, noy);
    if (o == NULL || ft_grid_ensure_mask(o) != FT_OK || ft_grid_set_crs(o, g->crs_wkt) != FT_OK) {
        ft_grid_free(o);
        return NULL;
    }
    double a = 0.5 * ((double)w - (double)s);
    o->gt[0] = g->gt[0] + a * g->gt[1] + a * g->gt[2];
    o->gt[3] = g->gt[3] + a * g->gt[4] + a * g->gt[5];
    o->gt[1] = (double)s * g->gt[1];
    o->gt[2] = (double)s * g->gt[2];
    o->gt[4] = (double)s * g->gt[4];
    o->gt[5] = (double)s * g->gt[5];
    for (size_t i = 0; i < nox * noy; i++) {
        o->z[i] = NAN;
        o->mask[i] = 0;
    }
    return o;
}

/* Copies window (x0, y0) into win (w x w, mask allocated); returns its number of valid cells. */
static size_t copy_window(const ft_grid *g, size_t x0, size_t y0, size_t w, ft_grid *win)
{
    size_t valid = 0;
    for (size_t i = 0; i < w; i++)
        for (size_t j = 0; j < w; j++) {
            size_t src = (y0 + i) * g->nx + x0 + j, dst = i * w + j;
            int ok = ft_surface_cell_ok(g, src);
            win->z[dst] = ok ? g->z[src] : 0.0f;
            win->mask[dst] = (uint8_t)ok;
            valid += (size_t)ok;
        }
    for (int k = 0; k < 6; k++)
        win->gt[k] = g->gt[k];
    win->gt[0] = g->gt[0] + (double)x0 * g->gt[1] + (double)y0 * g->gt[2];
    win->gt[3] = g->gt[3] + (double)x0 * g->gt[4] + (double)y0 * g->gt[5];
    return valid;
}

static int is_fatal(int rc)
{
    return rc == FT_E_INVALID || rc == FT_E_NOMEM || rc == FT_E_UNSUPPORTED || rc == FT_E_CANCELLED;
}

/* One window into D, r2 and its noise flag nug (cell k), or a recorded failure. */
static void one_window(const ft_grid *g, size_t x0, size_t y0, size_t w, ft_surface_method m,
                       const ft_surface_dim_opts *wo, ft_grid *win, float *D, float *r2, float *nug, uint8_t *ok,
                       map_failure *fail)
{
    size_t valid = copy_window(g, x0, y0, w, win);
    if ((double)valid < wo->min_valid * (double)(w * w) || valid == 0)
        return;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim(win, m, wo, &r);
    if (rc == FT_OK) {
        *D = (float)r->D;
        *r2 = (float)r->r2;
        *nug = (float)(r->nugget.applied != 0);
        *ok = 1;
    } else if (is_fatal(rc)) {
#pragma omp critical(ft_dim_map_failure)
        if (fail->code == FT_OK) {
            fail->code = rc;
            snprintf(fail->msg, sizeof fail->msg, "%s", ft_last_error());
        }
        fail->stop = 1;
    }
    ft_dim_result_free(r);
}

static int run_windows(const ft_grid *g, size_t w, size_t s, ft_surface_method m, const ft_surface_dim_opts *o,
                       size_t nox, size_t noy, ft_grid *D, ft_grid *r2, ft_grid *N)
{
    ft_surface_dim_opts wo = *o;
    wo.progress = NULL;
    wo.progress_arg = NULL;
    map_failure fail = {FT_OK, "", 0};
    size_t total = nox * noy;
    int nested = omp_get_max_active_levels();
    omp_set_max_active_levels(1);
#pragma omp parallel
    {
        ft_grid *win = ft_grid_create(w, w);
        if (win == NULL || ft_grid_ensure_mask(win) != FT_OK) {
#pragma omp critical(ft_dim_map_failure)
            if (fail.code == FT_OK) {
                fail.code = FT_E_NOMEM;
                snprintf(fail.msg, sizeof fail.msg, "out of memory");
            }
            fail.stop = 1;
        }
#pragma omp for schedule(dynamic, 16)
        for (size_t k = 0; k < total; k++) {
            if (fail.stop)
                continue;
            size_t i = k / nox, j = k % nox;
            one_window(g, j * s, i * s, w, m, &wo, win, &D->z[k], &r2->z[k], &N->z[k], &D->mask[k], &fail);
            r2->mask[k] = N->mask[k] = D->mask[k];
            if (omp_get_thread_num() == 0 && (k % 64) == 0 &&
                ft_progress(o->progress, o->progress_arg, (double)k / (double)total, NAME) != FT_OK) {
#pragma omp critical(ft_dim_map_failure)
                if (fail.code == FT_OK) {
                    fail.code = FT_E_CANCELLED;
                    snprintf(fail.msg, sizeof fail.msg, NAME ": cancelled");
                }
                fail.stop = 1;
            }
        }
        ft_grid_free(win);
    }
    omp_set_max_active_levels(nested);
    if (fail.code != FT_OK)
        return fail.code == FT_E_CANCELLED ? ft_error(FT_E_CANCELLED, "%s", fail.msg)
                                           : ft_error(fail.code, NAME ": window of %zu cells: %s", w, fail.msg);
    return ft_progress(o->progress, o->progress_arg, 1.0, NAME);
}

int ft_surface_dim_map_noise(const ft_grid *g, size_t window, size_t step, ft_surface_method m,
                             const ft_surface_dim_opts *opts, ft_grid **D_out, ft_grid **r2_out, ft_grid **nugget_out)
{
    ft_grid **outs[3] = {D_out, r2_out, nugget_out};
    for (int k = 0; k < 3; k++)
        if (outs[k] != NULL)
            *outs[k] = NULL;
    if (D_out == NULL && r2_out == NULL && nugget_out == NULL)
        return ft_error(FT_E_INVALID, NAME ": all output pointers are NULL");
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_surface_dim_opts) != FT_OK)
        return FT_E_INVALID;
    int rc = check_args(g, window, step, m, &o);
    if (rc != FT_OK)
        return rc;
    size_t nox = (g->nx - window) / step + 1, noy = (g->ny - window) / step + 1;
    ft_grid *grids[3];
    for (int k = 0; k < 3; k++)
        grids[k] = lattice_grid(g, window, step, nox, noy);
    rc = grids[0] && grids[1] && grids[2] ? ft_progress(o.progress, o.progress_arg, 0.0, NAME) : FT_E_NOMEM;
    int lag_method = m == FT_SURFACE_VARIOGRAM || m == FT_SURFACE_YOKOYA || m == FT_SURFACE_PENTLAND;
    if (rc == FT_OK && lag_method && o.pairs == 0) {
        rc = ft_surface_dim_map_lags(g, window, step, m, &o, grids[0], grids[1], grids[2]);
        if (rc == FT_OK)
            rc = ft_progress(o.progress, o.progress_arg, 1.0, NAME);
    } else if (rc == FT_OK) {
        rc = run_windows(g, window, step, m, &o, nox, noy, grids[0], grids[1], grids[2]);
    }
    for (int k = 0; k < 3; k++) {
        if (rc == FT_OK && outs[k] != NULL)
            *outs[k] = grids[k];
        else
            ft_grid_free(grids[k]);
    }
    return rc;
}

int ft_surface_dim_map(const ft_grid *g, size_t window, size_t step, ft_surface_method m,
                       const ft_surface_dim_opts *opts, ft_grid **D_out, ft_grid **r2_out)
{
    if (D_out == NULL && r2_out == NULL)
        return ft_error(FT_E_INVALID, NAME ": both output pointers are NULL");
    return ft_surface_dim_map_noise(g, window, step, m, opts, D_out, r2_out, NULL);
}
