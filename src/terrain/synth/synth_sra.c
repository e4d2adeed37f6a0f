/* fracterra — synth_sra.c: successive random addition (Voss 1985, "Random fractal forgeries"; Saupe 1988,
 * algorithm InterpolatedFM2D / "successive random additions"), the synthesizer Arakawa & Krotkov used for
 * their synthetic data (§2.5 and §3.4).
 *
 * A coarse lattice of bx x by squares (spacing delta_0 = 2^L cells) gets independent N(0, delta_0^(2H))
 * values. Each of the L levels halves the spacing (r = 1/2): the new lattice is the bilinear interpolation
 * of the old one, then EVERY node, old and new, receives an independent N(0, sigma_l^2) addition with
 * sigma_l^2 = delta_0^(2H) r^(2 H l) = delta_l^(2H), so the added variance falls by r^(2H) per level and
 * the increments over delta_l scale as delta_l^H (fBm with H = 3 - D). The last lattice is cropped to the
 * output. One RNG stream per (level, row).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/synth/synth_internal.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/core.h"
#include "internal.h"

void ft_synth_dyadic_plan(size_t nx, size_t ny, ft_synth_dyadic *d)
{
    size_t span = (nx > ny ? nx : ny) - 1, step = 1;
    int levels = 0;
    while (4 * step < span) {
        step *= 2;
        levels++;
    }
    d->levels = levels;
    d->bx = nx > 1 ? (nx - 1 + step - 1) / step : 1;
    d->by = ny > 1 ? (ny - 1 + step - 1) / step : 1;
    d->gx = d->bx * step + 1;
    d->gy = d->by * step + 1;
}

static uint64_t sra_stream(int level, size_t row)
{
    return FT_SYNTH_STREAM_SRA + ((uint64_t)level << 26) + (uint64_t)row;
}

/* Row r of the refined lattice (w2 = 2 w - 1 nodes wide): bilinear interpolation of the old lattice
 * `old` (w nodes wide), plus N(0, sd^2) at every node; the first `keep` nodes are written to out. */
static int refine_row(const double *old, size_t w, size_t r, double sd, uint64_t seed, uint64_t stream,
                      double *tmp, size_t keep, double *outd, float *outf)
{
    size_t w2 = 2 * w - 1;
    const double *a = old + (r / 2) * w, *b = (r % 2) ? a + w : a;
    for (size_t i = 0; i < w; i++)
        tmp[2 * i] = 0.5 * (a[i] + b[i]);
    for (size_t i = 0; i + 1 < w; i++)
        tmp[2 * i + 1] = 0.5 * (tmp[2 * i] + tmp[2 * i + 2]);
    ft_rng *g = ft_rng_create(seed, stream);
    if (g == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < w2; i++) {
        double v = tmp[i] + ft_rng_gaussian(g, sd);
        if (i < keep) {
            if (outd)
                outd[i] = v;
            else
                outf[i] = (float)v;
        }
    }
    ft_rng_free(g);
    return FT_OK;
}

/* Level l: from the (w x h) lattice `old` to (2w-1) x (2h-1), into next (doubles) or, on the last level,
 * cropped into z (nx x ny floats). */
static int sra_level(const double *old, size_t w, size_t h, int level, double sd, uint64_t seed, double *next,
                     float *z, size_t nx, size_t ny)
{
    size_t w2 = 2 * w - 1, h2 = 2 * h - 1, rows = next ? h2 : ny, keep = next ? w2 : nx;
    int failed = 0;
#pragma omp parallel reduction(| : failed)
    {
        double *tmp = malloc(w2 * sizeof *tmp);
        failed |= tmp == NULL;
#pragma omp for schedule(static)
        for (size_t r = 0; r < rows; r++) {
            if (tmp == NULL || refine_row(old, w, r, sd, seed, sra_stream(level, r), tmp, keep,
                                          next ? next + r * w2 : NULL, next ? NULL : z + r * nx) != FT_OK)
                failed = 1;
        }
        free(tmp);
    }
    return failed ? ft_error(FT_E_NOMEM, "synth: sra: out of memory at level %d", level) : FT_OK;
}

static int sra_base(double *base, size_t w, size_t h, double sd, uint64_t seed)
{
    for (size_t r = 0; r < h; r++) {
        ft_rng *g = ft_rng_create(seed, sra_stream(0, r));
        if (g == NULL)
            return FT_E_NOMEM;
        for (size_t i = 0; i < w; i++)
            base[r * w + i] = ft_rng_gaussian(g, sd);
        ft_rng_free(g);
    }
    return FT_OK;
}

int ft_synth_sra_fill(size_t nx, size_t ny, double H, const ft_synth_opts *o, float *z)
{
    ft_synth_dyadic d;
    ft_synth_dyadic_plan(nx, ny, &d);
    double delta0 = ldexp(1.0, d.levels);
    size_t w = d.bx + 1, h = d.by + 1;
    double *cur = ft_malloc(w * h * sizeof *cur);
    if (cur == NULL)
        return FT_E_NOMEM;
    int rc = sra_base(cur, w, h, pow(delta0, H), o->seed);
    if (rc == FT_OK && d.levels == 0) {
        for (size_t r = 0; r < ny; r++)
            for (size_t i = 0; i < nx; i++)
                z[r * nx + i] = (float)cur[r * w + i];
    }
    for (int l = 1; rc == FT_OK && l <= d.levels; l++) {
        int last = l == d.levels;
        double sd = pow(delta0 * ldexp(1.0, -l), H);
        double *next = last ? NULL : ft_malloc((2 * w - 1) * (2 * h - 1) * sizeof *next);
        if (!last && next == NULL) {
            rc = FT_E_NOMEM;
            break;
        }
        rc = sra_level(cur, w, h, l, sd, o->seed, next, z, nx, ny);
        free(cur);
        cur = next;
        w = 2 * w - 1;
        h = 2 * h - 1;
        if (rc == FT_OK)
            rc = ft_progress(o->progress, o->progress_arg, (double)l / d.levels, "sra: levels");
    }
    free(cur);
    return rc;
}
