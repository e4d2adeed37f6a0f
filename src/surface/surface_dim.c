/* fracterra — surface_dim.c: one entry to every grid estimator (variogram, yokoya, pentland, spectrum,
 * prism, cubes), their names, and the translation of the shared options (scales in ground units) into
 * each method's own (scales in cells). docs/surface-grid.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <strings.h>

#include "internal.h"
#include "surface/grid_internal.h"

static const char *const method_names[FT_SURFACE_NMETHODS] = {"variogram", "yokoya", "pentland",
                                                              "spectrum",  "prism",  "cubes"};

const char *ft_surface_method_name(ft_surface_method m)
{
    return (unsigned)m < FT_SURFACE_NMETHODS ? method_names[m] : "?";
}

int ft_surface_method_parse(const char *name, ft_surface_method *m)
{
    for (int i = 0; name != NULL && i < FT_SURFACE_NMETHODS; i++)
        if (strcasecmp(name, method_names[i]) == 0) {
            *m = (ft_surface_method)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "unknown surface method '%s' (variogram, yokoya, pentland, spectrum, prism or "
                    "cubes)", name ? name : "(null)");
}

static int check_opts(const ft_surface_dim_opts *o)
{
    if (!(o->min_scale >= 0.0) || !isfinite(o->min_scale))
        return ft_error(FT_E_INVALID, "min_scale must be >= 0 ground units, got %g", o->min_scale);
    if (!(o->max_scale >= 0.0) || !isfinite(o->max_scale))
        return ft_error(FT_E_INVALID, "max_scale must be >= 0 ground units, got %g", o->max_scale);
    if (o->min_scale > 0.0 && o->max_scale > 0.0 && !(o->max_scale > o->min_scale))
        return ft_error(FT_E_INVALID, "max_scale %g must exceed min_scale %g", o->max_scale, o->min_scale);
    if (o->nscales < 0)
        return ft_error(FT_E_INVALID, "nscales must be >= 0, got %d", o->nscales);
    return FT_OK;
}

/* Ground-unit scales of o in cells of mean size sqrt(cx cy) (0 stays 0: the method's default). */
static void scales_in_cells(const ft_surface_dim_opts *o, double cx, double cy, double *lo, double *hi)
{
    double c = sqrt(cx * cy);
    *lo = o->min_scale > 0.0 && c > 0.0 ? o->min_scale / c : 0.0;
    *hi = o->max_scale > 0.0 && c > 0.0 ? o->max_scale / c : 0.0;
}

int ft_surface_lag_opts(const ft_surface_dim_opts *o, double cx, double cy, ft_variogram_opts *v)
{
    int rc = check_opts(o);
    if (rc != FT_OK)
        return rc;
    double lo, hi;
    scales_in_cells(o, cx, cy, &lo, &hi);
    *v = (ft_variogram_opts)FT_VARIOGRAM_OPTS_DEFAULT;
    v->min_lag = lo;
    v->max_lag = hi;
    v->nlags = o->nscales;
    v->pairs = o->pairs;
    v->seed = o->seed;
    v->fit = o->fit;
    v->fit_whole_range = o->fit_whole_range;
    v->progress = o->progress;
    v->progress_arg = o->progress_arg;
    v->noise = o->noise;
    return FT_OK;
}

int ft_surface_dim(const ft_grid *g, ft_surface_method m, const ft_surface_dim_opts *opts, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "surface dimension: output pointer is NULL");
    *out = NULL;
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_surface_dim_opts) != FT_OK)
        return FT_E_INVALID;
    int rc = check_opts(&o);
    if (rc != FT_OK)
        return rc;
    if ((unsigned)m >= FT_SURFACE_NMETHODS)
        return ft_error(FT_E_INVALID, "unknown surface method %d", (int)m);
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "%s: the grid is NULL or empty", method_names[m]);
    double cx, cy, lo, hi;
    ft_surface_cell_size(g, &cx, &cy);
    scales_in_cells(&o, cx, cy, &lo, &hi);
    switch (m) {
    case FT_SURFACE_VARIOGRAM:
    case FT_SURFACE_YOKOYA:
    case FT_SURFACE_PENTLAND: {
        ft_variogram_opts v;
        ft_surface_lag_opts(&o, cx, cy, &v); /* o was checked above */
        return m == FT_SURFACE_VARIOGRAM ? ft_surface_dim_variogram(g, &v, out)
               : m == FT_SURFACE_YOKOYA  ? ft_surface_dim_yokoya(g, &v, out)
                                         : ft_surface_dim_pentland(g, &v, out);
    }
    case FT_SURFACE_SPECTRUM: {
        ft_spectrum_opts s = {.struct_size = sizeof s, .min_wavelength = lo, .max_wavelength = hi,
                              .nbins = o.nscales, .tile = o.tile, .window = 1, .fit = o.fit,
                              .fit_whole_range = o.fit_whole_range, .progress = o.progress,
                              .progress_arg = o.progress_arg, .elevations = 0, .noise = o.noise};
        return ft_surface_dim_spectrum(g, &s, out);
    }
    default: {
        ft_dyadic_opts d = {.struct_size = sizeof d, .min_size = lo, .max_size = hi, .zscale = o.zscale,
                            .fit = o.fit, .fit_whole_range = o.fit_whole_range, .progress = o.progress,
                            .progress_arg = o.progress_arg};
        return m == FT_SURFACE_PRISM ? ft_surface_dim_prism(g, &d, out) : ft_surface_dim_cubes(g, &d, out);
    }
    }
}
