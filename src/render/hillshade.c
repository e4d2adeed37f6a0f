/* fracterra — render/hillshade.c: analytical hillshading of a DEM, as gdaldem hillshade.
 *
 * Slope and aspect come from Horn's 3x3 finite differences:
 *   Horn, B. K. P. (1981). Hill shading and the reflectance map. Proceedings of the IEEE 69(1), 14-47.
 * With the window   a b c          dz/dx = ((c + 2f + i) - (a + 2d + g)) / (8 * ewres)   (east minus west)
 *                   d e f          dz/dy = ((g + 2h + i) - (a + 2b + c)) / (8 * nsres)   (south minus north)
 *                   g h i
 * slope = atan(z_factor * |grad z|), aspect = atan2(dz/dy, -dz/dx) (ESRI convention), and the shade is
 *   255 * (cos(zenith) cos(slope) + sin(zenith) sin(slope) cos(azimuth_math - aspect)), clamped at 0,
 * where zenith = 90 - altitude and azimuth_math = 90 - azimuth (counter-clockwise from east). A flat cell
 * therefore gets 255 * sin(altitude). Cells on the grid's edge, and cells whose window touches nodata,
 * are nodata in the output.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/render.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>

#define FT_HS_NODATA (-9999.0)

static int check_opts(const ft_grid *dem, const ft_hillshade_opts *o)
{
    if (!isfinite(o->altitude) || o->altitude < 0.0 || o->altitude > 90.0)
        return ft_error(FT_E_INVALID, "hillshade altitude must be in [0,90] degrees, got %g", o->altitude);
    if (!isfinite(o->azimuth) || o->azimuth < 0.0 || o->azimuth > 360.0)
        return ft_error(FT_E_INVALID, "hillshade azimuth must be in [0,360] degrees, got %g", o->azimuth);
    if (!isfinite(o->z_factor) || o->z_factor <= 0.0)
        return ft_error(FT_E_INVALID, "hillshade z_factor must be > 0, got %g", o->z_factor);
    if (!isfinite(o->scale) || o->scale <= 0.0)
        return ft_error(FT_E_INVALID, "hillshade scale must be > 0, got %g", o->scale);
    if (dem->nx < 3 || dem->ny < 3)
        return ft_error(FT_E_INVALID, "hillshade needs a grid of at least 3 x 3 cells, got %zu x %zu", dem->nx,
                        dem->ny);
    if (!isfinite(dem->gt[1]) || !isfinite(dem->gt[5]) || dem->gt[1] == 0.0 || dem->gt[5] == 0.0)
        return ft_error(FT_E_INVALID, "hillshade needs a non-zero cell size, got %g x %g", dem->gt[1],
                        dem->gt[5]);
    return FT_OK;
}

/* 1 if the 3x3 window centred on (col,row) is inside the grid and all valid. */
static int window_valid(const ft_grid *g, size_t col, size_t row)
{
    if (col == 0 || row == 0 || col + 1 >= g->nx || row + 1 >= g->ny)
        return 0;
    if (g->mask == NULL)
        return 1;
    for (size_t r = row - 1; r <= row + 1; r++)
        for (size_t c = col - 1; c <= col + 1; c++)
            if (!g->mask[r * g->nx + c])
                return 0;
    return 1;
}

typedef struct {
    double ewres, nsres;     /* signed so that dx runs east and dy runs south */
    double z_factor;
    double cos_zen, sin_zen; /* of the zenith angle */
    double az_math;          /* light direction, radians counter-clockwise from east */
} shade_params;

static double shade_cell(const ft_grid *g, size_t col, size_t row, const shade_params *p)
{
    const float *up = g->z + (row - 1) * g->nx + col;
    const float *mid = up + g->nx;
    const float *dn = mid + g->nx;
    double a = up[-1], b = up[0], c = up[1];
    double d = mid[-1], f = mid[1];
    double gg = dn[-1], h = dn[0], i = dn[1];
    double dzdx = ((c + 2.0 * f + i) - (a + 2.0 * d + gg)) / (8.0 * p->ewres);
    double dzdy = ((gg + 2.0 * h + i) - (a + 2.0 * b + c)) / (8.0 * p->nsres);
    double slope = atan(p->z_factor * sqrt(dzdx * dzdx + dzdy * dzdy));
    double aspect = atan2(dzdy, -dzdx);
    double v = p->cos_zen * cos(slope) + p->sin_zen * sin(slope) * cos(p->az_math - aspect);
    return v > 0.0 ? 255.0 * v : 0.0;
}

static void shade_params_init(const ft_grid *dem, const ft_hillshade_opts *o, shade_params *p)
{
    const double deg = M_PI / 180.0;
    double zenith = (90.0 - o->altitude) * deg;
    /* A positive gt[1] runs east and a negative gt[5] runs south (north-up): both are the usual case;
     * the signs flip the differences for grids stored the other way round. */
    p->ewres = fabs(dem->gt[1]) * o->scale * (dem->gt[1] > 0.0 ? 1.0 : -1.0);
    p->nsres = fabs(dem->gt[5]) * o->scale * (dem->gt[5] < 0.0 ? 1.0 : -1.0);
    p->z_factor = o->z_factor;
    p->cos_zen = cos(zenith);
    p->sin_zen = sin(zenith);
    p->az_math = (90.0 - o->azimuth) * deg;
}

int ft_render_hillshade(const ft_grid *dem, const ft_hillshade_opts *opts, ft_grid **out)
{
    ft_hillshade_opts taken = FT_HILLSHADE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_hillshade_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_hillshade_opts defaults = FT_HILLSHADE_OPTS_DEFAULT;
    const ft_hillshade_opts *o = opts ? opts : &defaults;
    if (out == NULL)
        return ft_error(FT_E_INVALID, "hillshade: no output grid pointer given");
    *out = NULL;
    if (dem == NULL || dem->z == NULL)
        return ft_error(FT_E_INVALID, "hillshade: no input grid given");
    int rc = check_opts(dem, o);
    if (rc != FT_OK)
        return rc;

    ft_grid *hs = ft_grid_create(dem->nx, dem->ny);
    if (hs == NULL)
        return ft_error(FT_E_NOMEM, "hillshade: out of memory for a %zu x %zu grid", dem->nx, dem->ny);
    for (int k = 0; k < 6; k++)
        hs->gt[k] = dem->gt[k];
    if ((rc = ft_grid_set_crs(hs, dem->crs_wkt)) != FT_OK || (rc = ft_grid_ensure_mask(hs)) != FT_OK) {
        ft_grid_free(hs);
        return rc;
    }
    hs->has_nodata = 1;
    hs->nodata_value = FT_HS_NODATA;

    shade_params p;
    shade_params_init(dem, o, &p);
    const long ny = (long)dem->ny;
#pragma omp parallel for schedule(static)
    for (long row = 0; row < ny; row++) {
        for (size_t col = 0; col < dem->nx; col++) {
            size_t k = (size_t)row * dem->nx + col;
            double v = window_valid(dem, col, (size_t)row) ? shade_cell(dem, col, (size_t)row, &p) : NAN;
            int ok = isfinite(v); /* NaN cells left unmasked by the caller also give nodata */
            hs->mask[k] = (uint8_t)ok;
            hs->z[k] = ok ? (float)v : (float)FT_HS_NODATA;
        }
    }
    *out = hs;
    return FT_OK;
}
