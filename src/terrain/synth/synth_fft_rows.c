/* fracterra — synth_fft_rows.c: the fft synthesis (synth_fft.c, Voss 1985 / Saupe 1988) cut into slabs of
 * rows, for a caller that runs the 2-D inverse transform across processes (FFTW's MPI transforms: the CLI's
 * `mpiexec -n N fracterra synth --method fft`, cli/tile_synth.c; docs/tiling.md). Each spectrum row ky is
 * drawn from its own stream, so a slab's rows are those of ft_terrain_synth whatever the slab; the plane,
 * the crop and the rescale to sigma use the whole surface's figures (per-row sums reduced in row order, as
 * synth.c's rescale sums them), so the cells differ from ft_terrain_synth's by the transform's rounding
 * only.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth/synth_internal.h"

#include <math.h>
#include <stdint.h>

#include "fracterra/core.h"
#include "internal.h"

static int take_opts(size_t nx, size_t ny, const ft_synth_opts *opts, ft_synth_opts *o)
{
    ft_synth_opts d = FT_SYNTH_OPTS_DEFAULT;
    *o = d;
    if (FT_OPTS_TAKE(*o, opts, ft_synth_opts) != FT_OK)
        return FT_E_INVALID;
    if (nx == 0 || ny == 0)
        return ft_error(FT_E_INVALID, "synth: size must be at least 1x1, got %zux%zu", nx, ny);
    if (o->method != FT_SYNTH_FFT)
        return ft_error(FT_E_INVALID, "synth: slabs of rows are for method fft, got %s",
                        ft_synth_method_name(o->method));
    if (!(o->dim > 2.0 && o->dim < 3.0))
        return ft_error(FT_E_INVALID, "synth: dimension D must be in (2, 3), got %g", o->dim);
    return FT_OK;
}

int ft_synth_fft_grid_size(size_t nx, size_t ny, const ft_synth_opts *opts, size_t *px, size_t *py)
{
    ft_synth_opts o;
    int rc = take_opts(nx, ny, opts, &o);
    if (rc != FT_OK)
        return rc;
    *px = ft_synth_fft_padded(nx, o.periodic);
    *py = ft_synth_fft_padded(ny, o.periodic);
    if (*px == 0 || *py == 0 || *px > INT32_MAX || *py > INT32_MAX)
        return ft_error(FT_E_INVALID, "synth: fft grid for %zu x %zu is too large", nx, ny);
    return FT_OK;
}

int ft_synth_fft_spectrum_rows(size_t nx, size_t ny, const ft_synth_opts *opts, size_t row0, size_t nrows,
                               float *spec)
{
    size_t px, py;
    int rc = ft_synth_fft_grid_size(nx, ny, opts, &px, &py);
    if (rc != FT_OK)
        return rc;
    if (spec == NULL || row0 > py || nrows > py - row0)
        return ft_error(FT_E_INVALID, "synth: spectrum rows %zu + %zu outside the %zu rows of the fft grid", row0,
                        nrows, py);
    ft_synth_opts o;
    take_opts(nx, ny, opts, &o);
    return ft_synth_fft_fill_rows(py, px, 3.0 - o.dim, o.seed, row0, nrows, (fftwf_complex *)spec);
}

int ft_synth_fft_surface_rows(size_t nx, size_t ny, const ft_synth_opts *opts, size_t row0, size_t nrows,
                              float *rows, double *row_sums)
{
    size_t px, py;
    int rc = ft_synth_fft_grid_size(nx, ny, opts, &px, &py);
    if (rc != FT_OK)
        return rc;
    if (rows == NULL || row0 > py || nrows > py - row0)
        return ft_error(FT_E_INVALID, "synth: surface rows %zu + %zu outside the %zu rows of the fft grid", row0,
                        nrows, py);
    ft_synth_opts o;
    take_opts(nx, ny, opts, &o);
    double ax, ay;
    if ((rc = ft_synth_fft_plane(px, py, 3.0 - o.dim, &o, &ax, &ay)) != FT_OK)
        return rc;
    size_t rs = ft_fft_real_stride(px), nout = row0 >= ny ? 0 : (ny - row0 < nrows ? ny - row0 : nrows);
    /* crop and plane in place as ft_synth_fft_make's crop_in_place (same expression, global row index) */
    for (size_t k = 0; k < nout; k++) {
        const float *src = rows + k * rs;
        float *dst = rows + k * nx;
        double i = (double)(row0 + k), s = 0.0, s2 = 0.0;
        for (size_t j = 0; j < nx; j++) {
            dst[j] = (float)((double)src[j] + ax * (double)j + ay * i);
            double v = dst[j];
            s += v;
            s2 += v * v;
        }
        if (row_sums != NULL) {
            row_sums[2 * k] = s;
            row_sums[2 * k + 1] = s2;
        }
    }
    return FT_OK;
}

int ft_synth_rescale_rows(size_t nx, size_t ny, const ft_synth_opts *opts, const double *row_sums, size_t nrows,
                          float *rows)
{
    ft_synth_opts o;
    int rc = take_opts(nx, ny, opts, &o);
    if (rc != FT_OK)
        return rc;
    if (!(o.sigma > 0.0))
        return FT_OK;
    if (row_sums == NULL || (nrows > 0 && rows == NULL) || nrows > ny)
        return ft_error(FT_E_INVALID, "synth: rescale needs the %zu rows' sums and at most %zu rows", ny, ny);
    /* synth.c's rescale: the rows' sums added in row order, mean 0 and standard deviation sigma */
    double s = 0.0, s2 = 0.0, n = (double)nx * (double)ny;
    for (size_t i = 0; i < ny; i++) {
        s += row_sums[2 * i];
        s2 += row_sums[2 * i + 1];
    }
    double mean = s / n, var = s2 / n - mean * mean;
    double k = var > 0.0 ? o.sigma / sqrt(var) : 0.0;
    for (size_t i = 0; i < nx * nrows; i++)
        rows[i] = (float)(((double)rows[i] - mean) * k);
    return FT_OK;
}
