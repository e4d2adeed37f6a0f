/* fracterra — synth.c: ft_terrain_synth, the entry to the four fractional Brownian surface synthesizers
 * (synth_fft.c, synth_sra.c, synth_midpoint.c, synth_exact.c; docs/terrain-synthesis.md): validates the
 * options (messages name the bad value), allocates the grid, rescales the cells to mean 0 and standard
 * deviation sigma (sigma = 0 leaves each method's raw scale) and sets the north-up geotransform
 * {origin_x, cell, 0, origin_y, 0, -cell}. H = 3 - D, or for sra and midpoint 3 - the calibrated parameter
 * (synth_calibration.c); sra-raw and midpoint-raw run at H = 3 - D as the papers define them.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fracterra/core.h"
#include "internal.h"

static const char *const method_names[] = {"fft", "sra", "midpoint", "exact", "sra-raw", "midpoint-raw"};
#define N_METHODS (sizeof method_names / sizeof method_names[0])

const char *ft_synth_method_name(ft_synth_method m)
{
    return (unsigned)m < N_METHODS ? method_names[m] : "unknown";
}

int ft_synth_method_parse(const char *name, ft_synth_method *m)
{
    if (name == NULL || m == NULL)
        return ft_error(FT_E_INVALID, "synth: method name is NULL");
    for (size_t i = 0; i < N_METHODS; i++)
        if (strcasecmp(name, method_names[i]) == 0) {
            *m = (ft_synth_method)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "synth: unknown method '%s' (expected fft, sra, midpoint, exact, sra-raw or midpoint-raw)", name);
}

static int validate(size_t nx, size_t ny, const ft_synth_opts *o)
{
    if (nx == 0 || ny == 0)
        return ft_error(FT_E_INVALID, "synth: size must be at least 1x1, got %zux%zu", nx, ny);
    if (nx > SIZE_MAX / sizeof(float) / ny)
        return ft_error(FT_E_INVALID, "synth: size %zux%zu is too large", nx, ny);
    if ((unsigned)o->method >= N_METHODS)
        return ft_error(FT_E_INVALID, "synth: unknown method %d", (int)o->method);
    if (!(o->dim > 2.0 && o->dim < 3.0))
        return ft_error(FT_E_INVALID, "synth: dimension D must be in (2, 3), got %g", o->dim);
    if (!(o->sigma >= 0.0) || !isfinite(o->sigma))
        return ft_error(FT_E_INVALID, "synth: sigma must be >= 0 and finite, got %g", o->sigma);
    if (!(o->cell > 0.0) || !isfinite(o->cell))
        return ft_error(FT_E_INVALID, "synth: cell size must be > 0 and finite, got %g", o->cell);
    if (!isfinite(o->origin_x) || !isfinite(o->origin_y))
        return ft_error(FT_E_INVALID, "synth: origin must be finite, got (%g, %g)", o->origin_x, o->origin_y);
    return FT_OK;
}

/* The caller's options (or the defaults) in *o, checked for an nx x ny synthesis. */
static int take_opts(const ft_synth_opts *opts, size_t nx, size_t ny, ft_synth_opts *o)
{
    *o = (ft_synth_opts)FT_SYNTH_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(*o, opts, ft_synth_opts) != FT_OK)
        return FT_E_INVALID;
    return validate(nx, ny, o);
}

/* Mean 0 and standard deviation sigma; per-row sums in double reduced in row order (deterministic). */
static int rescale(float *z, size_t nx, size_t ny, double sigma)
{
    double *rows = ft_malloc(2 * ny * sizeof *rows);
    if (rows == NULL)
        return FT_E_NOMEM;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < ny; i++) {
        double s = 0.0, s2 = 0.0;
        for (size_t j = 0; j < nx; j++) {
            double v = z[i * nx + j];
            s += v;
            s2 += v * v;
        }
        rows[2 * i] = s;
        rows[2 * i + 1] = s2;
    }
    double s = 0.0, s2 = 0.0, n = (double)nx * (double)ny;
    for (size_t i = 0; i < ny; i++) {
        s += rows[2 * i];
        s2 += rows[2 * i + 1];
    }
    free(rows);
    double mean = s / n, var = s2 / n - mean * mean;
    double k = var > 0.0 ? sigma / sqrt(var) : 0.0;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < ny; i++)
        for (size_t j = 0; j < nx; j++)
            z[i * nx + j] = (float)(((double)z[i * nx + j] - mean) * k);
    return FT_OK;
}

/* An nx x ny grid around the cells z (malloc'd; freed here on failure). */
static ft_grid *grid_adopt(size_t nx, size_t ny, float *z)
{
    ft_grid *g = ft_grid_create(1, 1);
    if (g == NULL) {
        free(z);
        return NULL;
    }
    free(g->z);
    g->z = z;
    g->nx = nx;
    g->ny = ny;
    return g;
}

/* The cells of the methods that fill a given array (all but fft, whose cells come from its spectrum). */
static int fill_cells(const ft_synth_opts *o, size_t nx, size_t ny, double H, float *z)
{
    switch (o->method) {
    case FT_SYNTH_FFT: return FT_OK;
    case FT_SYNTH_SRA:
    case FT_SYNTH_SRA_RAW: return ft_synth_sra_fill(nx, ny, H, o, z);
    case FT_SYNTH_MIDPOINT:
    case FT_SYNTH_MIDPOINT_RAW: return ft_synth_midpoint_fill(nx, ny, H, o, z);
    case FT_SYNTH_EXACT: return ft_synth_exact_fill(nx, ny, H, o, z);
    }
    return ft_error(FT_E_INVALID, "synth: unknown method %d", (int)o->method);
}

/* Every method's last steps: the cells to sigma, the final progress, and the north-up geotransform. */
static int finish(const ft_synth_opts *o, size_t nx, size_t ny, float *z, double gt[6])
{
    int rc = o->sigma > 0.0 ? rescale(z, nx, ny, o->sigma) : FT_OK;
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 1.0, "synth: done");
    if (rc != FT_OK)
        return rc;
    const double north_up[6] = {o->origin_x, o->cell, 0.0, o->origin_y, 0.0, -o->cell};
    for (int i = 0; i < 6; i++)
        gt[i] = north_up[i];
    return FT_OK;
}

int ft_terrain_synth(size_t nx, size_t ny, const ft_synth_opts *opts, ft_grid **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "synth: output pointer is NULL");
    *out = NULL;
    ft_synth_opts o;
    int rc = take_opts(opts, nx, ny, &o);
    if (rc != FT_OK)
        return rc;
    double H = 3.0 - ft_synth_raw_dim(o.method, o.dim, nx, ny);
    /* fft: the grid takes the cells the synthesis made in its spectrum's memory (no second buffer) */
    float *cells = NULL;
    if (o.method == FT_SYNTH_FFT && (rc = ft_synth_fft_make(nx, ny, H, &o, &cells)) != FT_OK)
        return rc;
    ft_grid *g = cells != NULL ? grid_adopt(nx, ny, cells) : ft_grid_create(nx, ny);
    if (g == NULL)
        return FT_E_NOMEM;
    rc = fill_cells(&o, nx, ny, H, g->z);
    if (rc == FT_OK)
        rc = finish(&o, nx, ny, g->z, g->gt);
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}

/* ---- Repeated syntheses into the caller's grid (ft_synth_workspace) ---- */

struct ft_synth_workspace {
    size_t nx, ny;
    ft_synth_method method;
    int periodic;
    fftwf_complex *spec; /* fft: the padded half-spectrum, every page touched at creation */
};

int ft_synth_workspace_create(size_t nx, size_t ny, const ft_synth_opts *opts, ft_synth_workspace **ws)
{
    if (ws == NULL)
        return ft_error(FT_E_INVALID, "synth: workspace pointer is NULL");
    *ws = NULL;
    ft_synth_opts o;
    int rc = take_opts(opts, nx, ny, &o);
    if (rc != FT_OK)
        return rc;
    ft_synth_workspace *w = ft_calloc(1, sizeof *w);
    if (w == NULL)
        return FT_E_NOMEM;
    w->nx = nx;
    w->ny = ny;
    w->method = o.method;
    w->periodic = o.periodic;
    if (o.method == FT_SYNTH_FFT && (rc = ft_synth_fft_workspace(nx, ny, o.periodic, &w->spec)) != FT_OK) {
        free(w);
        return rc;
    }
    *ws = w;
    return FT_OK;
}

void ft_synth_workspace_free(ft_synth_workspace *ws)
{
    if (ws == NULL)
        return;
    free(ws->spec);
    free(ws);
}

/* The options and grid match the workspace they are run with. */
static int check_workspace(const ft_synth_workspace *ws, const ft_synth_opts *o, const ft_grid *out)
{
    if (ws->nx != out->nx || ws->ny != out->ny)
        return ft_error(FT_E_INVALID, "synth: the workspace is for %zu x %zu, the grid is %zu x %zu", ws->nx, ws->ny,
                        out->nx, out->ny);
    if (ws->method != o->method)
        return ft_error(FT_E_INVALID, "synth: the workspace is for method %s, the options ask for %s",
                        ft_synth_method_name(ws->method), ft_synth_method_name(o->method));
    if (ws->periodic != o->periodic)
        return ft_error(FT_E_INVALID, "synth: the workspace is for periodic = %d, the options have %d", ws->periodic,
                        o->periodic);
    return FT_OK;
}

int ft_terrain_synth_into(const ft_synth_opts *opts, ft_synth_workspace *ws, ft_grid *out)
{
    if (ws == NULL || out == NULL || out->z == NULL)
        return ft_error(FT_E_INVALID, "synth: %s is NULL", ws == NULL ? "the workspace" : "the output grid");
    ft_synth_opts o;
    int rc = take_opts(opts, out->nx, out->ny, &o);
    if (rc == FT_OK)
        rc = check_workspace(ws, &o, out);
    if (rc != FT_OK)
        return rc;
    size_t nx = out->nx, ny = out->ny;
    double H = 3.0 - ft_synth_raw_dim(o.method, o.dim, nx, ny);
    rc = o.method == FT_SYNTH_FFT ? ft_synth_fft_into(nx, ny, H, &o, ws->spec, out->z)
                                  : fill_cells(&o, nx, ny, H, out->z);
    if (rc == FT_OK)
        rc = finish(&o, nx, ny, out->z, out->gt);
    if (rc == FT_OK && out->mask != NULL) /* every cell is valid; the mask stays the caller's memory */
        memset(out->mask, 1, nx * ny);
    return rc;
}
