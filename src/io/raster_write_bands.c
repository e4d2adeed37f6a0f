/* fracterra — io/raster_write_bands.c: several grids as the bands of one raster (a local D map and its
 * r², for instance). Checks that the grids agree, then writes them through raster_write.c's writer
 * (ft_io_write_bands), atomically, as ft_io_write_grid writes one.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "io/io_internal.h"
#include "internal.h"

static int write_grids(const char *path, const ft_grid *const *bands, size_t n, const ft_write_grid_opts *opts)
{
    if (bands == NULL || n == 0)
        return ft_error(FT_E_INVALID, "no band to write to '%s'", path ? path : "(null)");
    if (n > 65535)
        return ft_error(FT_E_INVALID, "%zu bands are too many for '%s'", n, path ? path : "(null)");
    for (size_t k = 0; k < n; k++) {
        const ft_grid *g = bands[k];
        if (g == NULL || g->z == NULL)
            return ft_error(FT_E_INVALID, "band %zu of '%s' is NULL", k + 1, path ? path : "(null)");
        if (g->nx != bands[0]->nx || g->ny != bands[0]->ny)
            return ft_error(FT_E_INVALID, "band %zu of '%s' has %zux%zu cells, band 1 has %zux%zu", k + 1,
                            path ? path : "(null)", g->nx, g->ny, bands[0]->nx, bands[0]->ny);
        for (int i = 0; i < 6; i++)
            if (!(fabs(g->gt[i] - bands[0]->gt[i]) <= 1e-9 * fmax(1.0, fabs(bands[0]->gt[i]))))
                return ft_error(FT_E_INVALID, "band %zu of '%s' has geotransform[%d] = %.17g, band 1 has %.17g",
                                k + 1, path ? path : "(null)", i, g->gt[i], bands[0]->gt[i]);
    }
    return ft_io_write_bands(path, bands, n, opts);
}

int ft_io_write_grids(const char *path, const ft_grid *const *bands, size_t n, const ft_write_grid_opts *opts)
{
    ft_io_enter();
    return ft_io_leave(write_grids(path, bands, n, opts));
}
