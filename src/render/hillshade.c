/* fracterra — render/hillshade.c: analytical hillshading of a DEM, as gdaldem hillshade -compute_edges: the
 * library's one hillshade engine (ft_io_hillshade and its stripes shade files with it).
 *
 * Slope and aspect come from Horn's 3x3 finite differences:
 *   Horn, B. K. P. (1981). Hill shading and the reflectance map. Proceedings of the IEEE 69(1), 14-47.
 * With the window   a b c          dz/dx = ((c + 2f + i) - (a + 2d + g)) / (8 * ewres)   (east minus west)
 *                   d e f          dz/dy = ((g + 2h + i) - (a + 2b + c)) / (8 * nsres)   (south minus north)
 *                   g h i
 * slope = atan(z_factor * |grad z|), aspect = atan2(dz/dy, -dz/dx) (ESRI convention), and the shade is
 *   255 * (cos(zenith) cos(slope) + sin(zenith) sin(slope) cos(azimuth_math - aspect)), clamped at 0,
 * where zenith = 90 - altitude and azimuth_math = 90 - azimuth (counter-clockwise from east). A flat cell
 * therefore gets 255 * sin(altitude). `scale` divides both cell sizes: ground units of the horizontal
 * coordinates per elevation unit (1 when both are metres; the metres of a degree for a DEM in degrees).
 * As gdaldem -compute_edges: a nodata cell stays nodata; a nodata neighbour takes the centre's value; a
 * neighbour beyond the grid's edge is extrapolated linearly (2 z(edge) - z(next inside)), so the edge
 * cells get a shade too; in the first and last rows only the rows are extrapolated and the columns are
 * clamped (gdaldem's rule: the four corners see their own column repeated).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/render.h"
#include "internal.h"

#include <math.h>
#include <stdlib.h>

#define FT_HS_NODATA (-9999.0)
#define FT_HS_PARALLEL_CELLS 4.0e6

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
    if (dem->nx < 2 || dem->ny < 2)
        return ft_error(FT_E_INVALID, "hillshade needs a grid of at least 2 x 2 cells, got %zu x %zu", dem->nx,
                        dem->ny);
    if (!isfinite(dem->gt[1]) || !isfinite(dem->gt[5]) || dem->gt[1] == 0.0 || dem->gt[5] == 0.0)
        return ft_error(FT_E_INVALID, "hillshade needs a non-zero cell size, got %g x %g", dem->gt[1],
                        dem->gt[5]);
    return FT_OK;
}

/* z of cell (col, row) of the grid, NAN when it is nodata (masked or not finite). */
static double cell(const ft_grid *g, size_t col, size_t row)
{
    size_t k = row * g->nx + col;
    if (g->mask != NULL && !g->mask[k])
        return NAN;
    return isfinite(g->z[k]) ? (double)g->z[k] : NAN;
}

/* z at column col of row `row` (inside the grid), where col may be one step outside: then the linear
 * extrapolation 2 z(edge) - z(next inside), as gdaldem -compute_edges (NAN if either is nodata). */
static double along_row(const ft_grid *g, long col, size_t row)
{
    long nx = (long)g->nx;
    if (col < 0)
        return 2.0 * cell(g, 0, row) - cell(g, 1, row);
    if (col >= nx)
        return 2.0 * cell(g, g->nx - 1, row) - cell(g, g->nx - 2, row);
    return cell(g, (size_t)col, row);
}

/* z at (col, row), either of which may be one step outside the grid, for the window of a cell of row
 * `centre_row`. As gdaldem -compute_edges: in the first and last rows the columns are clamped to the grid
 * (the corner cells see their own column repeated) and the row beyond the edge is extrapolated from the
 * edge row and the next; in the other rows a column beyond the edge is extrapolated along the row. */
static double extended(const ft_grid *g, long col, long row, size_t centre_row)
{
    long nx = (long)g->nx, ny = (long)g->ny;
    if (centre_row == 0 || centre_row + 1 == g->ny)
        col = col < 0 ? 0 : col >= nx ? nx - 1 : col;
    if (row < 0)
        return 2.0 * cell(g, (size_t)col, 0) - cell(g, (size_t)col, 1);
    if (row >= ny)
        return 2.0 * cell(g, (size_t)col, g->ny - 1) - cell(g, (size_t)col, g->ny - 2);
    return along_row(g, col, (size_t)row);
}

/* The 3x3 window a..i centred on (col, row) into w[0..8]; 0 if the centre is nodata. A neighbour that is
 * nodata (or extrapolated from nodata) takes the centre's value, as gdaldem -compute_edges. */
static int gather(const ft_grid *g, size_t col, size_t row, double w[9])
{
    double centre = cell(g, col, row);
    if (isnan(centre))
        return 0;
    int inside = col > 0 && row > 0 && col + 1 < g->nx && row + 1 < g->ny;
    for (int dr = -1, k = 0; dr <= 1; dr++)
        for (int dc = -1; dc <= 1; dc++, k++) {
            double v = inside ? cell(g, (size_t)((long)col + dc), (size_t)((long)row + dr))
                              : extended(g, (long)col + dc, (long)row + dr, row);
            w[k] = isnan(v) ? centre : v;
        }
    return 1;
}

typedef struct {
    double kx, ky;           /* z_factor / (8 x cell size), signed so that x runs east and y runs south */
    double cos_zen, sin_zen; /* of the zenith angle */
    double cos_az, sin_az;   /* of the light direction counter-clockwise from east */
} shade_params;

/* Horn's gradient of the window and the shade, 255 * max(0, cos(incidence)). With slope = atan(z |grad|)
 * and aspect = atan2(dz/dy, -dz/dx), cos(incidence) = cos(zen) cos(slope) + sin(zen) sin(slope)
 * cos(az - aspect) = (cos(zen) + sin(zen) (zy sin(az) - zx cos(az))) / sqrt(1 + zx^2 + zy^2), where
 * zx, zy are the gradient times z_factor: one square root per cell and no trigonometry. */
static inline double shade_window(const double w[9], const shade_params *p)
{
    double zx = ((w[2] + 2.0 * w[5] + w[8]) - (w[0] + 2.0 * w[3] + w[6])) * p->kx;
    double zy = ((w[6] + 2.0 * w[7] + w[8]) - (w[0] + 2.0 * w[1] + w[2])) * p->ky;
    double v = (p->cos_zen + p->sin_zen * (zy * p->sin_az - zx * p->cos_az)) / sqrt(1.0 + zx * zx + zy * zy);
    return v > 0.0 ? 255.0 * v : 0.0;
}

/* The window of an inner cell of a grid without a mask, read straight from the rows above, at and below
 * (the same values, and so the same shade, as gather gives). 0 if the centre is not finite. */
static int gather_inner(const float *up, const float *mid, const float *dn, double w[9])
{
    w[0] = up[-1], w[1] = up[0], w[2] = up[1];
    w[3] = mid[-1], w[4] = mid[0], w[5] = mid[1];
    w[6] = dn[-1], w[7] = dn[0], w[8] = dn[1];
    if (!isfinite(w[4]))
        return 0;
    for (int k = 0; k < 9; k++)
        if (!isfinite(w[k]))
            w[k] = w[4];
    return 1;
}

static void put(ft_grid *hs, size_t k, double v)
{
    int ok = isfinite(v);
    hs->mask[k] = (uint8_t)ok;
    hs->z[k] = ok ? (float)v : (float)FT_HS_NODATA;
}

static void shade_params_init(const ft_grid *dem, const ft_hillshade_opts *o, shade_params *p)
{
    const double deg = M_PI / 180.0;
    double zenith = (90.0 - o->altitude) * deg, az_math = (90.0 - o->azimuth) * deg;
    /* A positive gt[1] runs east and a negative gt[5] runs south (north-up): both are the usual case;
     * the signs flip the differences for grids stored the other way round. */
    double ewres = fabs(dem->gt[1]) * o->scale * (dem->gt[1] > 0.0 ? 1.0 : -1.0);
    double nsres = fabs(dem->gt[5]) * o->scale * (dem->gt[5] < 0.0 ? 1.0 : -1.0);
    p->kx = o->z_factor / (8.0 * ewres);
    p->ky = o->z_factor / (8.0 * nsres);
    p->cos_zen = cos(zenith);
    p->sin_zen = sin(zenith);
    p->cos_az = cos(az_math);
    p->sin_az = sin(az_math);
}

/* 1 if every cell of the n floats is finite. */
static int all_finite(const float *z, size_t n)
{
    int bad = 0;
    for (size_t k = 0; k < n; k++)
        bad |= !isfinite(z[k]);
    return !bad;
}

/* The inner cells [1, nx - 1) of an inner row whose three rows (up, mid, dn) are all finite and unmasked:
 * shade_window's arithmetic, in the same order (the same bits), without the window copy, so that the
 * compiler can vectorise it. */
static void shade_inner_run(const float *restrict up, const float *restrict mid, const float *restrict dn, size_t nx,
                            const shade_params *p, float *restrict z, uint8_t *restrict mask)
{
    const double kx = p->kx, ky = p->ky, cz = p->cos_zen, sz = p->sin_zen, ca = p->cos_az, sa = p->sin_az;
#pragma omp simd
    for (size_t c = 1; c < nx - 1; c++) {
        double a = up[c - 1], b = up[c], cc = up[c + 1], d = mid[c - 1], f = mid[c + 1];
        double g = dn[c - 1], h = dn[c], i = dn[c + 1];
        double zx = ((cc + 2.0 * f + i) - (a + 2.0 * d + g)) * kx;
        double zy = ((g + 2.0 * h + i) - (a + 2.0 * b + cc)) * ky;
        double v = (cz + sz * (zy * sa - zx * ca)) / sqrt(1.0 + zx * zx + zy * zy);
        z[c] = (float)(v > 0.0 ? 255.0 * v : 0.0);
        mask[c] = 1;
    }
}

/* One row of the shade: the inner cells of an inner row of a grid without a mask by direct reads (in one
 * vectorised run when the three rows are finite), the others through gather (edges, masks). */
static void shade_row(const ft_grid *dem, size_t row, const shade_params *p, ft_grid *hs)
{
    size_t nx = dem->nx, k0 = row * nx;
    double w[9];
    int fast = dem->mask == NULL && row > 0 && row + 1 < dem->ny;
    const float *mid0 = dem->z + k0;
    if (fast && nx > 2 && all_finite(mid0 - nx, 3 * nx)) {
        shade_inner_run(mid0 - nx, mid0, mid0 + nx, nx, p, hs->z + k0, hs->mask + k0);
        put(hs, k0, gather(dem, 0, row, w) ? shade_window(w, p) : NAN);
        put(hs, k0 + nx - 1, gather(dem, nx - 1, row, w) ? shade_window(w, p) : NAN);
        return;
    }
    for (size_t col = 0; col < nx; col++) {
        if (fast && col > 0 && col + 1 < nx) {
            const float *mid = dem->z + k0 + col;
            put(hs, k0 + col, gather_inner(mid - nx, mid, mid + nx, w) ? shade_window(w, p) : NAN);
        } else {
            put(hs, k0 + col, gather(dem, col, row, w) ? shade_window(w, p) : NAN);
        }
    }
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
    /* The vectorised run shades a cell in a few nanoseconds: below FT_HS_PARALLEL_CELLS (a stripe of a
     * streamed file) a second thread costs more in start and spin-wait than it saves. */
    const int parallel = (double)dem->nx * (double)dem->ny > FT_HS_PARALLEL_CELLS;
#pragma omp parallel for schedule(static) if (parallel)
    for (long row = 0; row < ny; row++)
        shade_row(dem, (size_t)row, &p, hs);
    *out = hs;
    return FT_OK;
}
