/* fracterra — core/grid_stats.c: count, mean, standard deviation and range of a grid's valid, finite cells
 * (two passes with double accumulators: the mean first, then the squared deviations from it, which keeps
 * the variance of a high, flat DEM accurate where the one-pass sum of squares loses it).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/core.h"

static int counts(const ft_grid *g, size_t i)
{
    return (g->mask == NULL || g->mask[i]) && isfinite(g->z[i]);
}

int ft_grid_compute_stats(const ft_grid *g, ft_grid_stats *out)
{
    if (g == NULL || out == NULL)
        return ft_error(FT_E_INVALID, "ft_grid_compute_stats: NULL argument");
    size_t cells = g->nx * g->ny, n = 0;
    double s = 0.0, zmin = INFINITY, zmax = -INFINITY;
    for (size_t i = 0; i < cells; i++) {
        if (!counts(g, i))
            continue;
        double z = g->z[i];
        s += z;
        zmin = fmin(zmin, z);
        zmax = fmax(zmax, z);
        n++;
    }
    double mean = n ? s / (double)n : NAN, ss = 0.0;
    for (size_t i = 0; i < cells && n; i++)
        if (counts(g, i))
            ss += ((double)g->z[i] - mean) * ((double)g->z[i] - mean);
    out->n = n;
    out->mean = mean;
    out->sd = n ? sqrt(ss / (double)n) : NAN;
    out->min = n ? zmin : NAN;
    out->max = n ? zmax : NAN;
    return FT_OK;
}
