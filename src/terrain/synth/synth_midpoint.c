/* fracterra — synth_midpoint.c: diamond-square midpoint displacement (Fournier, Fussell & Carpenter 1982,
 * "Computer rendering of stochastic models"; Saupe 1988, MidPointFM2D).
 *
 * On the dyadic lattice of ft_synth_dyadic_plan (base corners N(0, delta_0^(2H))), each level with square
 * side s = 2h sets: (diamond) every square's centre to the mean of its 4 corners, (square) every edge
 * midpoint to the mean of its 4 (3 on the border) diamond neighbours, each plus an independent
 * N(0, d^(2H) (1 - 2^(2H-2))), d the distance to the parents (h sqrt 2, then h): the conditional
 * variance of an fBm midpoint between two points 2d apart. Earlier values are never revisited, which
 * leaves the known creases along the coarse lattice lines (docs/terrain-synthesis.md). One RNG stream
 * per (level, step, row); the lattice is cropped to the output.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/core.h"
#include "internal.h"

static uint64_t mp_stream(int level, int step, size_t row)
{
    return FT_SYNTH_STREAM_MIDPOINT + ((uint64_t)level << 27) + ((uint64_t)step << 26) + (uint64_t)row;
}

/* Diamond step, one row of square centres at y (odd multiple of h). */
static int diamond_row(double *g, size_t gx, size_t y, size_t h, double sd, uint64_t seed, uint64_t stream)
{
    ft_rng *r = ft_rng_create(seed, stream);
    if (r == NULL)
        return FT_E_NOMEM;
    const double *up = g + (y - h) * gx, *dn = g + (y + h) * gx;
    for (size_t x = h; x < gx; x += 2 * h)
        g[y * gx + x] = 0.25 * (up[x - h] + up[x + h] + dn[x - h] + dn[x + h]) + ft_rng_gaussian(r, sd);
    ft_rng_free(r);
    return FT_OK;
}

/* Square step, one row y (multiple of h): the nodes with x + y an odd multiple of h. */
static int square_row(double *g, size_t gx, size_t gy, size_t y, size_t h, double sd, uint64_t seed,
                      uint64_t stream)
{
    ft_rng *r = ft_rng_create(seed, stream);
    if (r == NULL)
        return FT_E_NOMEM;
    for (size_t x = ((y / h) % 2 == 0) ? h : 0; x < gx; x += 2 * h) {
        double s = 0.0;
        int n = 0;
        if (x >= h) { s += g[y * gx + x - h]; n++; }
        if (x + h < gx) { s += g[y * gx + x + h]; n++; }
        if (y >= h) { s += g[(y - h) * gx + x]; n++; }
        if (y + h < gy) { s += g[(y + h) * gx + x]; n++; }
        g[y * gx + x] = s / n + ft_rng_gaussian(r, sd);
    }
    ft_rng_free(r);
    return FT_OK;
}

static int mp_level(double *g, const ft_synth_dyadic *d, int level, double H, uint64_t seed)
{
    size_t h = (size_t)1 << (d->levels - level);
    double c = sqrt(1.0 - pow(2.0, 2.0 * H - 2.0));
    double sd_diamond = c * pow((double)h * M_SQRT2, H), sd_square = c * pow((double)h, H);
    int failed = 0;
    long nrows = (long)((d->gy - 1) / (2 * h));
#pragma omp parallel for schedule(static) reduction(| : failed)
    for (long k = 0; k < nrows; k++) {
        size_t y = (size_t)k * 2 * h + h;
        failed |= diamond_row(g, d->gx, y, h, sd_diamond, seed, mp_stream(level, 0, y)) != FT_OK;
    }
    long srows = (long)((d->gy - 1) / h + 1);
#pragma omp parallel for schedule(static) reduction(| : failed)
    for (long k = 0; k < srows; k++) {
        size_t y = (size_t)k * h;
        failed |= square_row(g, d->gx, d->gy, y, h, sd_square, seed, mp_stream(level, 1, y)) != FT_OK;
    }
    return failed ? ft_error(FT_E_NOMEM, "synth: midpoint: out of memory at level %d", level) : FT_OK;
}

int ft_synth_midpoint_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z)
{
    ft_synth_dyadic d;
    ft_synth_dyadic_plan(nx, ny, &d);
    double *g = ft_malloc(d.gx * d.gy * sizeof *g);
    if (g == NULL)
        return FT_E_NOMEM;
    size_t step = (size_t)1 << d.levels;
    double sd0 = pow((double)step, H);
    int rc = FT_OK;
    for (size_t y = 0; y < d.gy && rc == FT_OK; y += step) {
        ft_rng *r = ft_rng_create(o->seed, mp_stream(0, 0, y));
        if (r == NULL) {
            rc = FT_E_NOMEM;
            break;
        }
        for (size_t x = 0; x < d.gx; x += step)
            g[y * d.gx + x] = ft_rng_gaussian(r, sd0);
        ft_rng_free(r);
    }
    for (int l = 1; rc == FT_OK && l <= d.levels; l++) {
        rc = mp_level(g, &d, l, H, o->seed);
        if (rc == FT_OK)
            rc = ft_progress(o->progress, o->progress_arg, (double)l / d.levels, "midpoint: levels");
    }
    if (rc == FT_OK)
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++)
                z[y * nx + x] = (float)g[y * d.gx + x];
    free(g);
    return rc;
}
