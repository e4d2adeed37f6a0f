/* fracterra — terrain/clarke/clarke_peak.c: the wavelength and direction of a Clarke harmonic as a property of the
 * terrain, not of the grid.
 *
 * A harmonic of Clarke's model (Clarke 1987, eq. vi) is one of the grid's Fourier modes (k, l): its wavelength
 * 1 / |(k / Lx) ex + (l / Ly) ey| is the extent divided by an integer, so the same terrain on a grid of another
 * extent or orientation (a warp to another projection) reports other wavelengths and directions. Here each
 * significant mode is followed to the continuous frequency (u, v), in cycles across the grid, that maximizes
 * the variance one plane wave a cos(theta) + b sin(theta), theta = 2 pi (u col / nx + v row / ny), explains
 * in a least-squares fit to the detrended DEM over its valid cells — the single-sinusoid least-squares
 * frequency estimate (Walker 1971; for one wave in white noise the maximum of the periodogram, here with the
 * 2 x 2 normal equations of the cosine and sine so that long waves over few cycles and nodata are fitted
 * correctly). The search is a compass (pattern) search from the mode: the eight neighbours at step h
 * (0.25 cycle at first), a move to the best that improves, h halved when none does, until h < 2^-10 cycle;
 * it climbs to the local maximum the mode's energy belongs to, so two modes leaking one wave report the same
 * wave. Grids over 128 cells a side are fitted on blocks: the block mean of the residual at the centroid of
 * the block's valid cells, weighted by their count (a block mean of a wave of 8 blocks or more keeps its
 * frequency; shorter waves are fitted on finer blocks, down to single cells). Serial, so the same on any
 * thread count. Only the reported wavelength and direction change: the model keeps the mode's
 * coefficients, which the simulation places on the grid's modes.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/clarke/clarke_internal.h"

#include <math.h>
#include <stdlib.h>

#include "internal.h"

#define PEAK_MAX_BLOCKS 128       /* blocks along the longer side of a large grid */
#define PEAK_MIN_BLOCKS_PER_WAVE 8
#define PEAK_FIRST_STEP 0.25      /* cycles across the grid */
#define PEAK_LAST_STEP (1.0 / 1024.0)
#define PEAK_MAX_EVALS 600

typedef struct {
    double *col, *row, *r, *w; /* centroid (cell-index units), mean residual, valid cells */
    size_t n;
    size_t nx, ny;             /* of the grid, for the phase */
} peak_blocks;

static void blocks_free(peak_blocks *b)
{
    free(b->col);
    free(b->row);
    free(b->r);
    free(b->w);
    b->col = b->row = b->r = b->w = NULL;
    b->n = 0;
}

/* Aggregates the residual (row stride rs; valid cells by the DEM's mask and finite values) into s x s
 * blocks, keeping the blocks with a valid cell. */
static int blocks_make(const ft_grid *dem, const double *res, size_t rs, size_t s, peak_blocks *b)
{
    size_t bx = (dem->nx + s - 1) / s, by = (dem->ny + s - 1) / s, cap = bx * by;
    b->col = ft_malloc(cap * sizeof(double));
    b->row = ft_malloc(cap * sizeof(double));
    b->r = ft_malloc(cap * sizeof(double));
    b->w = ft_malloc(cap * sizeof(double));
    b->n = 0;
    b->nx = dem->nx;
    b->ny = dem->ny;
    if (!b->col || !b->row || !b->r || !b->w) {
        blocks_free(b);
        return ft_last_error_code();
    }
    for (size_t j = 0; j < by; j++) {
        for (size_t i = 0; i < bx; i++) {
            double w = 0.0, sc = 0.0, sr = 0.0, sz = 0.0;
            for (size_t row = j * s; row < (j + 1) * s && row < dem->ny; row++) {
                for (size_t col = i * s; col < (i + 1) * s && col < dem->nx; col++) {
                    double z = res[row * rs + col];
                    if (!ft_grid_is_valid(dem, col, row) || !isfinite(dem->z[row * dem->nx + col]))
                        continue;
                    w += 1.0;
                    sc += (double)col;
                    sr += (double)row;
                    sz += z;
                }
            }
            if (w > 0.0) {
                b->col[b->n] = sc / w;
                b->row[b->n] = sr / w;
                b->r[b->n] = sz / w;
                b->w[b->n++] = w;
            }
        }
    }
    return FT_OK;
}

#define PEAK_CHUNKS 64 /* partial sums per chunk of blocks, reduced in order (an evaluation is ~1 ms of work at
                          most: a parallel region per evaluation costs more than it saves on a loaded machine) */

/* Variance explained by the best plane wave at (u, v) cycles across the grid (times the weight sum):
 * v' G^-1 v with G the Gram matrix of the cosine and sine over the blocks. 0 where they are collinear. */
static double explained(const peak_blocks *b, double u, double v)
{
    double part[PEAK_CHUNKS][5];
    double fu = 2.0 * M_PI * u / (double)b->nx, fv = 2.0 * M_PI * v / (double)b->ny;
    for (int k = 0; k < PEAK_CHUNKS; k++) {
        double cc = 0.0, ss = 0.0, cs = 0.0, rc = 0.0, rsn = 0.0;
        for (size_t i = b->n * (size_t)k / PEAK_CHUNKS; i < b->n * (size_t)(k + 1) / PEAK_CHUNKS; i++) {
            double th = fu * b->col[i] + fv * b->row[i], c = cos(th), s = sin(th), w = b->w[i];
            cc += w * c * c;
            ss += w * s * s;
            cs += w * c * s;
            rc += w * b->r[i] * c;
            rsn += w * b->r[i] * s;
        }
        part[k][0] = cc;
        part[k][1] = ss;
        part[k][2] = cs;
        part[k][3] = rc;
        part[k][4] = rsn;
    }
    double t[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < PEAK_CHUNKS; k++)
        for (int j = 0; j < 5; j++)
            t[j] += part[k][j];
    double cc = t[0], ss = t[1], cs = t[2], rc = t[3], rsn = t[4];
    double det = cc * ss - cs * cs;
    if (!(det > 1e-9 * (cc + ss) * (cc + ss)))
        return 0.0;
    return (rc * rc * ss - 2.0 * rc * rsn * cs + rsn * rsn * cc) / det;
}

/* Compass search from (*u, *v) to the local maximum of explained(). */
static void climb(const peak_blocks *b, double *u, double *v)
{
    static const int du[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dv[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    double best = explained(b, *u, *v), h = PEAK_FIRST_STEP;
    int evals = 1;
    while (h >= PEAK_LAST_STEP && evals < PEAK_MAX_EVALS) {
        int arg = -1;
        double top = best;
        for (int d = 0; d < 8; d++) {
            double e = explained(b, *u + h * du[d], *v + h * dv[d]);
            evals++;
            if (e > top) {
                top = e;
                arg = d;
            }
        }
        if (arg < 0) {
            h *= 0.5;
            continue;
        }
        *u += h * du[arg];
        *v += h * dv[arg];
        best = top;
    }
}

/* Block side for a wave of this many cells' wavelength: at most PEAK_MAX_BLOCKS blocks along the longer
 * side, at least PEAK_MIN_BLOCKS_PER_WAVE blocks per wavelength. */
static size_t block_side(size_t nx, size_t ny, double wavelength_cells)
{
    size_t n = nx > ny ? nx : ny;
    size_t coarse = (n + PEAK_MAX_BLOCKS - 1) / PEAK_MAX_BLOCKS;
    double fine = floor(wavelength_cells / PEAK_MIN_BLOCKS_PER_WAVE);
    size_t s = fine < (double)coarse ? (size_t)fine : coarse;
    return s < 1 ? 1 : s;
}

int clarke_refine_harmonics(const ft_grid *dem, const double *res, size_t rs, const clarke_frame *fr,
                            ft_clarke_harmonic *h, size_t n)
{
    peak_blocks b = {0};
    size_t side = 0;
    double cell = fmin(fr->lx / (double)dem->nx, fr->ly / (double)dem->ny);
    for (size_t i = 0; i < n; i++) {
        size_t s = block_side(dem->nx, dem->ny, clarke_wavelength(fr, h[i].k, h[i].l) / cell);
        if (s != side) {
            blocks_free(&b);
            int rc = blocks_make(dem, res, rs, s, &b);
            if (rc != FT_OK)
                return rc;
            side = s;
        }
        double u = h[i].k, v = h[i].l;
        climb(&b, &u, &v);
        clarke_wave_geometry_at(fr, u, v, &h[i].wavelength, &h[i].direction);
    }
    blocks_free(&b);
    return FT_OK;
}
