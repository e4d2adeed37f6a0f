/* fracterra — spectrum.c: the power-spectrum dimension of an elevation grid (Clarke 1987, "Scale-based
 * simulation of topography", eqs. vi-viii; Voss 1985; Welch 1967 for averaged periodograms;
 * prewhitening by first differences: Blackman & Tukey 1958, Percival & Walden 1993 ch. 6).
 *
 * For an isotropic fractional Brownian surface the radially averaged power falls as P(f) ~ f^-beta with
 * beta = 2H + 2, so D = 3 - H = (8 - beta) / 2 (FT_DIM_MAP_SPECTRUM_SURFACE, the table's scale being the
 * frequency). Clarke's eq. viii, f = 3 - beta/2, is the variogram relation and is not used (seeds/README).
 *
 * Two estimators of P, on square tiles of `tile` cells overlapping by about half (Welch), spread evenly
 * from edge to edge (automatic tile: min(nx, ny), one tile on a square grid; sizes 2·3·5·7-smooth):
 *
 *  - differences (default): the first differences along rows and columns, in elevation per ground unit,
 *    gx = (z(i, j+1) - z(i, j)) / cx and gy = (z(i+1, j) - z(i, j)) / cy, each kept only where both of
 *    its cells are valid (nodata never read, never filled), minus their mean over the tile (the plane);
 *    the periodogram of each, |Gx(k)|² / Nx with Nx its number of valid differences (the power of the
 *    0/1 mask that multiplies it), and P(k) = (|Gx|² / Nx + |Gy|² / Ny) / (4 sin²(pi kx / T) / cx² +
 *    4 sin²(pi ky / T) / cy²), the differencing gain divided out (white noise of variance s² gives P = s²
 *    at every frequency). Differencing flattens the steep fBm spectrum (f^-beta becomes f^(2 - beta)), so
 *    the tile's edges and the nodata holes, which multiply the field by a sharp 0/1 mask, leak almost no
 *    power from the strong low frequencies into the fitted band: no taper is needed, and without one
 *    every cell counts fully (a Hann taper keeps about a quarter of the degrees of freedom of a 2-D
 *    periodogram, which doubled the scatter of D). A tile is measured if at least half of its
 *    differences are valid; the automatic tile is halved while none is.
 *  - elevations (opts->elevations = 1): the periodogram of the tile's elevations after removing the
 *    least-squares plane (Clarke's trend T, eq. xii), with the 2-D Hann taper w(i) w(j),
 *    w(i) = sin²(pi (i + 1/2) / T) (window = 1), |F(k)|² / Σw²; only tiles free of nodata, the automatic
 *    tile halved while none is.
 *
 * Radial average: frequencies f = |(kx / (T cx), ky / (T cy))| (cycles per ground unit) in log-spaced bins
 * between 1 / max_wavelength and 1 / min_wavelength (defaults 8 cells, below which aliasing flattens the
 * spectrum, and T / 8); each bin's value is the mean power of its frequencies (every frequency of the
 * plane once) over every tile, each tile weighted by its number of valid differences, its scale their
 * mean f. log P against log f is fitted as every estimator (ft_loglog_fit_auto or the whole range), after
 * a white-noise floor P = N0 + A f^-beta is detected and removed (spectrum_floor.c).
 *
 * The transforms are pruned to what the band needs: every row of a tile is transformed (src/fft/fft.h,
 * 1-D complex: gx + i gy, or the elevations), only the columns |kx| <= T / min_wavelength are kept and
 * transformed, and only their rows |ky| <= T / min_wavelength are binned; the two real fields are
 * separated from the one complex transform by Hermitian symmetry. Rows and columns run in parallel
 * (OpenMP) within a tile, or whole tiles in parallel when there are many; partial bin sums are added in
 * a fixed order, so the result has the same bits on any thread count.
 * Degenerate surfaces fail plainly: a plane (after removing it only float rounding is left) and a
 * surface smoother than any fBm (D < 1.9, beta > 4.2). docs/surface-grid.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "fft/fft.h"
#include "internal.h"
#include "surface/grid_internal.h"

#define NAME "spectrum"
#define MIN_TILE 8
#define AUTO_MIN_TILE 16
#define DEFAULT_MIN_WAVELENGTH 8.0
#define DEFAULT_MAX_WAVELENGTH_DIV 8.0
#define DEGENERATE_D 1.9
#define MIN_VALID_DIFFERENCES 0.5 /* differences mode: the fraction of a tile's differences that must be valid */
#define COL_BLOCK 8               /* columns gathered and transformed together (64-byte runs of a row) */

typedef struct {
    size_t tile;
    size_t *x0, *y0; /* upper-left cells of the measured tiles */
    double *valid;   /* their valid differences (differences mode) or cells */
    size_t ntiles;
} tiling;

/* The largest 2·3·5·7-smooth size <= n. */
static size_t smooth_floor(size_t n)
{
    while (n > 1 && ft_fft_good_size(n) != n)
        n--;
    return n;
}

/* Tile origins along one axis: from 0 to len - tile, steps of about tile / 2. */
static size_t origins(size_t len, size_t tile, size_t *out)
{
    if (len == tile) {
        out[0] = 0;
        return 1;
    }
    size_t half = tile / 2 > 0 ? tile / 2 : 1, m = (len - tile + half - 1) / half + 1;
    for (size_t k = 0; k < m; k++)
        out[k] = (size_t)llround((double)k * (double)(len - tile) / (double)(m - 1));
    return m;
}

/* The validity of every cell (not masked, finite) and the range of the valid elevations; FT_E_EMPTY if
 * no cell is valid. */
static int valid_cells(const ft_grid *g, uint8_t **valid, double *zmin, double *zmax)
{
    size_t nx = g->nx, ny = g->ny;
    uint8_t *v = ft_malloc(nx * ny);
    double *lo = ft_malloc(ny * sizeof *lo), *hi = ft_malloc(ny * sizeof *hi);
    if (v == NULL || lo == NULL || hi == NULL) {
        free(v);
        free(lo);
        free(hi);
        return FT_E_NOMEM;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < ny; i++) {
        double a = INFINITY, b = -INFINITY;
        for (size_t j = 0; j < nx; j++) {
            size_t k = i * nx + j;
            int ok = ft_surface_cell_ok(g, k);
            v[k] = (uint8_t)ok;
            if (ok) {
                a = fmin(a, (double)g->z[k]);
                b = fmax(b, (double)g->z[k]);
            }
        }
        lo[i] = a;
        hi[i] = b;
    }
    *zmin = INFINITY;
    *zmax = -INFINITY;
    for (size_t i = 0; i < ny; i++) {
        *zmin = fmin(*zmin, lo[i]);
        *zmax = fmax(*zmax, hi[i]);
    }
    free(lo);
    free(hi);
    if (!(*zmin <= *zmax)) {
        free(v);
        return ft_error(FT_E_EMPTY, NAME ": the %zux%zu grid has no valid cell (all nodata)", nx, ny);
    }
    *valid = v;
    return FT_OK;
}

/* The t x t tile at (x0, y0) of a grid nx cells wide: its number of valid differences (differences
 * mode) or cells (elevations mode), or -1 if it cannot be measured: not free of nodata (elevations), or
 * with fewer than MIN_VALID_DIFFERENCES of its 2 t (t - 1) differences valid (differences). */
static double tile_valid(const uint8_t *valid, size_t nx, size_t x0, size_t y0, size_t t, int elevations)
{
    size_t count = 0;
    for (size_t i = y0; i < y0 + t; i++) {
        const uint8_t *v = valid + i * nx + x0, *vb = v + nx;
        unsigned row = 0;
        if (elevations) {
            for (size_t j = 0; j < t; j++)
                row += v[j];
            if (row < t)
                return -1.0;
        } else {
            for (size_t j = 0; j + 1 < t; j++)
                row += (unsigned)(v[j] & v[j + 1]);
            if (i + 1 < y0 + t)
                for (size_t j = 0; j < t; j++)
                    row += (unsigned)(v[j] & vb[j]);
        }
        count += row;
    }
    if (!elevations && (double)count < MIN_VALID_DIFFERENCES * 2.0 * (double)t * (double)(t - 1))
        return -1.0;
    return (double)count;
}

static void tiling_free(tiling *tl)
{
    free(tl->x0);
    free(tl->y0);
    free(tl->valid);
    tl->x0 = tl->y0 = NULL;
    tl->valid = NULL;
}

/* The usable tiles of side t; FT_OK with ntiles possibly 0. */
static int find_tiles(const ft_grid *g, const uint8_t *vcell, size_t t, int elevations, tiling *tl)
{
    size_t half = t / 2 > 0 ? t / 2 : 1;
    size_t *ox = ft_malloc((g->nx / half + 2) * sizeof *ox), *oy = ft_malloc((g->ny / half + 2) * sizeof *oy);
    if (ox == NULL || oy == NULL) {
        free(ox);
        free(oy);
        return FT_E_NOMEM;
    }
    size_t mx = origins(g->nx, t, ox), my = origins(g->ny, t, oy);
    tl->tile = t;
    tl->ntiles = 0;
    tl->x0 = ft_malloc(mx * my * sizeof *tl->x0);
    tl->y0 = ft_malloc(mx * my * sizeof *tl->y0);
    tl->valid = ft_malloc(mx * my * sizeof *tl->valid);
    double *valid = ft_malloc(mx * my * sizeof *valid);
    int rc = tl->x0 && tl->y0 && tl->valid && valid ? FT_OK : FT_E_NOMEM;
    if (rc == FT_OK) {
#pragma omp parallel for schedule(dynamic, 1)
        for (size_t k = 0; k < mx * my; k++)
            valid[k] = tile_valid(vcell, g->nx, ox[k % mx], oy[k / mx], t, elevations);
        for (size_t k = 0; k < mx * my; k++)
            if (valid[k] >= 0.0) {
                tl->x0[tl->ntiles] = ox[k % mx];
                tl->y0[tl->ntiles] = oy[k / mx];
                tl->valid[tl->ntiles++] = valid[k];
            }
    }
    free(valid);
    free(ox);
    free(oy);
    return rc;
}

/* The tile size asked for, or the automatic one, and its usable tiles. */
static int choose_tiles(const ft_grid *g, const uint8_t *valid, size_t asked, int elevations, tiling *tl)
{
    size_t small = g->nx < g->ny ? g->nx : g->ny;
    size_t t = asked ? asked : smooth_floor(small);
    for (;;) {
        int rc = find_tiles(g, valid, t, elevations, tl);
        if (rc != FT_OK || tl->ntiles > 0)
            return rc;
        tiling_free(tl);
        if (asked || t / 2 < AUTO_MIN_TILE) {
            if (elevations)
                return ft_error(FT_E_EMPTY, NAME ": no tile of %zux%zu cells is free of nodata on the %zux%zu grid%s",
                                t, t, g->nx, g->ny, asked ? "; try a smaller tile" : "");
            return ft_error(FT_E_EMPTY, NAME ": no tile of %zux%zu cells has half of its differences valid on the "
                            "%zux%zu grid%s", t, t, g->nx, g->ny, asked ? "; try a smaller tile" : "");
        }
        t = smooth_floor(t / 2);
    }
}

/* Per-tile sums of one bin: power, frequency, count. */
typedef struct {
    double p, f, n;
} bin_acc;

/* What every tile shares: the tile side, the mode, the kept frequencies and the radial bins. */
typedef struct {
    const ft_grid *g;
    const uint8_t *valid; /* the grid's cells: 1 valid */
    size_t t;
    int elevations;
    const double *w;     /* elevations mode: the 1-D taper, or NULL */
    double w2;           /* elevations mode: Σ of the 2-D taper squared */
    double cx, cy;
    size_t kpos, kneg;   /* kept transform indices 0 .. kpos and t - kneg .. t - 1 */
    size_t nk;           /* kpos + 1 + kneg */
    long *freq;          /* nk signed frequency indices */
    size_t *mirror;      /* nk: the kept index of -k */
    double *gain_x, *gain_y; /* nk: 4 sin²(pi k / t) / c² (differences mode) */
    double flo, fhi;     /* the band, cycles per ground unit */
    size_t nbins;
} spec_plan;

static void plan_free(spec_plan *p)
{
    free(p->freq);
    free(p->mirror);
    free(p->gain_x);
    free(p->gain_y);
}

/* The kept indices: |k| <= kmax, each frequency once (for an even t and kmax = t / 2 the Nyquist index
 * t / 2 is kept once, as +t / 2). */
static int make_plan(spec_plan *p, size_t kmax, int nbins)
{
    size_t t = p->t;
    p->kpos = kmax;
    p->kneg = kmax < t - 1 - kmax ? kmax : t - 1 - kmax;
    p->nk = p->kpos + 1 + p->kneg;
    p->freq = ft_malloc(p->nk * sizeof *p->freq);
    p->mirror = ft_malloc(p->nk * sizeof *p->mirror);
    p->gain_x = ft_malloc(p->nk * sizeof *p->gain_x);
    p->gain_y = ft_malloc(p->nk * sizeof *p->gain_y);
    if (p->freq == NULL || p->mirror == NULL || p->gain_x == NULL || p->gain_y == NULL)
        return FT_E_NOMEM;
    for (size_t q = 0; q < p->nk; q++) {
        size_t m = q <= p->kpos ? q : t - p->kneg + (q - p->kpos - 1); /* transform index */
        p->freq[q] = m <= t / 2 ? (long)m : (long)m - (long)t;
        size_t mm = (t - m) % t; /* index of -k */
        p->mirror[q] = mm <= p->kpos ? mm : p->kpos + 1 + (mm - (t - p->kneg));
        double s = sin(M_PI * (double)p->freq[q] / (double)t);
        p->gain_x[q] = 4.0 * s * s / (p->cx * p->cx);
        p->gain_y[q] = 4.0 * s * s / (p->cy * p->cy);
    }
    if (nbins <= 0)
        nbins = (int)ceil(4.0 * log2(p->fhi / p->flo));
    p->nbins = (size_t)(nbins < 2 ? 2 : nbins);
    return FT_OK;
}

/* The sums a tile needs before its transform: elevations mode: mean and the plane's slopes; differences
 * mode: the mean of each difference field and the number of valid ones. */
typedef struct {
    double mean, bx, by;   /* elevations: z ~ mean + bx (j - c) + by (i - c), c = (t - 1) / 2 */
    double mx, my, nx, ny; /* differences: means and counts of gx and gy */
} tile_stats;

/* Row i of the tile at (x0, y0): its sums (elevations: Σz, Σ(j - c) z, Σz (i - c) is formed by the
 * caller; differences: Σgx, count, Σgy, count), into s[0..3]. */
static void row_sums(const spec_plan *p, size_t x0, size_t y0, size_t i, double s[4])
{
    size_t t = p->t, nx = p->g->nx;
    const float *z = p->g->z + (y0 + i) * nx + x0, *zb = z + nx;
    const uint8_t *v = p->valid + (y0 + i) * nx + x0, *vb = v + nx;
    double c = 0.5 * (double)(t - 1), a = 0.0, b = 0.0, na = 0.0, nb = 0.0;
    if (p->elevations) {
        for (size_t j = 0; j < t; j++) {
            a += (double)z[j];
            b += ((double)j - c) * (double)z[j];
        }
        s[0] = a;
        s[1] = b;
        s[2] = s[3] = 0.0;
        return;
    }
    for (size_t j = 0; j + 1 < t; j++) {
        int ok = v[j] & v[j + 1];
        a += ok ? (double)z[j + 1] - (double)z[j] : 0.0;
        na += (double)ok;
    }
    if (i + 1 < t)
        for (size_t j = 0; j < t; j++) {
            int ok = v[j] & vb[j];
            b += ok ? (double)zb[j] - (double)z[j] : 0.0;
            nb += (double)ok;
        }
    s[0] = a / p->cx;
    s[1] = na;
    s[2] = b / p->cy;
    s[3] = nb;
}

static void tile_sums(const spec_plan *p, size_t x0, size_t y0, int inner, double *rows, tile_stats *st)
{
    size_t t = p->t;
#pragma omp parallel for if (inner) schedule(static)
    for (size_t i = 0; i < t; i++)
        row_sums(p, x0, y0, i, rows + 4 * i);
    double s[4] = {0.0, 0.0, 0.0, 0.0}, sy = 0.0, c = 0.5 * (double)(t - 1), sxx = 0.0;
    for (size_t i = 0; i < t; i++) {
        for (int k = 0; k < 4; k++)
            s[k] += rows[4 * i + k];
        sy += ((double)i - c) * rows[4 * i];
        sxx += ((double)i - c) * ((double)i - c);
    }
    memset(st, 0, sizeof *st);
    if (p->elevations) {
        /* least-squares plane on centred coordinates: the normal equations are diagonal */
        double n = (double)t * (double)t;
        st->mean = s[0] / n;
        st->bx = s[1] / (sxx * (double)t);
        st->by = sy / (sxx * (double)t);
    } else {
        st->nx = s[1];
        st->ny = s[3];
        st->mx = s[1] > 0.0 ? s[0] / s[1] : 0.0;
        st->my = s[3] > 0.0 ? s[2] / s[3] : 0.0;
    }
}

/* Row i of the tile as a complex sequence (differences: gx - mx + i (gy - my), zero where invalid;
 * elevations: the detrended, tapered elevations), its sums of squares before and after the plane was
 * removed into ss[0..1]. */
static void fill_row(const spec_plan *p, size_t x0, size_t y0, size_t i, const tile_stats *st, fftw_complex *row,
                     double ss[2])
{
    size_t t = p->t, nx = p->g->nx;
    const float *z = p->g->z + (y0 + i) * nx + x0, *zb = z + nx;
    const uint8_t *v = p->valid + (y0 + i) * nx + x0, *vb = v + nx;
    double c = 0.5 * (double)(t - 1), before = 0.0, after = 0.0;
    if (p->elevations) {
        for (size_t j = 0; j < t; j++) {
            double e = (double)z[j];
            double r = e - (st->mean + st->bx * ((double)j - c) + st->by * ((double)i - c));
            before += (e - st->mean) * (e - st->mean);
            after += r * r;
            row[j][0] = p->w != NULL ? r * p->w[i] * p->w[j] : r;
            row[j][1] = 0.0;
        }
        ss[0] = before;
        ss[1] = after;
        return;
    }
    double ix = 1.0 / p->cx, iy = 1.0 / p->cy;
    for (size_t j = 0; j < t; j++) {
        int okx = j + 1 < t && (v[j] & v[j + 1]), oky = i + 1 < t && (v[j] & vb[j]);
        double dx = okx ? ((double)z[j + 1] - (double)z[j]) * ix : 0.0;
        double dy = oky ? ((double)zb[j] - (double)z[j]) * iy : 0.0;
        double gx = okx ? dx - st->mx : 0.0, gy = oky ? dy - st->my : 0.0;
        before += dx * dx + dy * dy;
        after += gx * gx + gy * gy;
        row[j][0] = gx;
        row[j][1] = gy;
    }
    ss[0] = before;
    ss[1] = after;
}

/* Scratch of one tile: the kept columns of every row transform (t x nk), the kept spectrum (nk x nk,
 * column q at q * nk), per-row sums. */
typedef struct {
    fftw_complex *rows, *cols;
    double *sums; /* 4 per row */
} tile_work;

static void work_free(tile_work *w)
{
    ft_fft_free(w->rows);
    ft_fft_free(w->cols);
    free(w->sums);
    memset(w, 0, sizeof *w);
}

static int work_alloc(const spec_plan *p, tile_work *w)
{
    w->rows = ft_fft_alloc_complex(p->t * p->nk);
    w->cols = ft_fft_alloc_complex(p->nk * p->nk);
    w->sums = ft_malloc(4 * p->t * sizeof *w->sums);
    if (w->rows == NULL || w->cols == NULL || w->sums == NULL) {
        work_free(w);
        return FT_E_NOMEM;
    }
    return FT_OK;
}

/* Index in the full transform of kept index q. */
static size_t full_index(const spec_plan *p, size_t q)
{
    return q <= p->kpos ? q : p->t - p->kneg + (q - p->kpos - 1);
}

/* The kept 2-D spectrum of one tile: row transforms, then the kept columns in blocks. */
static int transform_tile(const spec_plan *p, size_t x0, size_t y0, const tile_stats *st, int inner,
                          tile_work *w)
{
    size_t t = p->t, nk = p->nk;
    int failed = 0;
#pragma omp parallel if (inner) reduction(| : failed)
    {
        fftw_complex *buf = ft_fft_alloc_complex(COL_BLOCK * t);
        failed |= buf == NULL;
#pragma omp for schedule(static)
        for (size_t i = 0; i < t; i++) {
            if (failed)
                continue;
            fill_row(p, x0, y0, i, st, buf, w->sums + 4 * i);
            failed |= ft_fft_c2c_1d(t, buf, buf, FT_FFT_FORWARD) != FT_OK;
            for (size_t q = 0; q < nk; q++) {
                size_t m = full_index(p, q);
                w->rows[i * nk + q][0] = buf[m][0];
                w->rows[i * nk + q][1] = buf[m][1];
            }
        }
#pragma omp for schedule(static)
        for (size_t q0 = 0; q0 < nk; q0 += COL_BLOCK) {
            if (failed)
                continue;
            size_t nb = nk - q0 < COL_BLOCK ? nk - q0 : COL_BLOCK;
            for (size_t i = 0; i < t; i++)
                for (size_t b = 0; b < nb; b++) {
                    buf[b * t + i][0] = w->rows[i * nk + q0 + b][0];
                    buf[b * t + i][1] = w->rows[i * nk + q0 + b][1];
                }
            for (size_t b = 0; b < nb && !failed; b++) {
                fftw_complex *col = buf + b * t;
                failed |= ft_fft_c2c_1d(t, col, col, FT_FFT_FORWARD) != FT_OK;
                for (size_t r = 0; r < nk; r++) {
                    size_t m = full_index(p, r);
                    w->cols[(q0 + b) * nk + r][0] = col[m][0];
                    w->cols[(q0 + b) * nk + r][1] = col[m][1];
                }
            }
        }
        ft_fft_free(buf);
    }
    return failed ? (ft_last_error_code() ? ft_last_error_code() : ft_error(FT_E_NOMEM, NAME ": out of memory"))
                  : FT_OK;
}

/* Bins column q of the kept spectrum into acc (nbins), each power times the tile's weight. */
static void bin_column(const spec_plan *p, const tile_work *w, size_t q, const tile_stats *st, double weight,
                       bin_acc *acc)
{
    size_t nk = p->nk;
    double t = (double)p->t, fx = (double)p->freq[q] / (t * p->cx);
    double lo = p->flo * (1.0 - 1e-9), hi = p->fhi * (1.0 + 1e-9), span = log(p->fhi / p->flo);
    const fftw_complex *col = w->cols + q * nk, *mcol = w->cols + p->mirror[q] * nk;
    for (size_t r = 0; r < nk; r++) {
        double fy = (double)p->freq[r] / (t * p->cy), f = sqrt(fx * fx + fy * fy);
        if (f < lo || f > hi)
            continue;
        size_t b = (size_t)floor((double)p->nbins * log(f / p->flo) / span);
        if (b >= p->nbins)
            b = p->nbins - 1;
        double a = col[r][0], bi = col[r][1], power;
        if (p->elevations) {
            power = (a * a + bi * bi) / p->w2;
        } else {
            /* Gx = (C(k) + conj C(-k)) / 2, Gy = (C(k) - conj C(-k)) / 2i */
            double c = mcol[p->mirror[r]][0], d = mcol[p->mirror[r]][1];
            double gx2 = 0.25 * ((a + c) * (a + c) + (bi - d) * (bi - d));
            double gy2 = 0.25 * ((bi + d) * (bi + d) + (a - c) * (a - c));
            double px = st->nx > 0.0 ? gx2 / st->nx : 0.0, py = st->ny > 0.0 ? gy2 / st->ny : 0.0;
            power = (px + py) / (p->gain_x[q] + p->gain_y[r]);
        }
        acc[b].p += weight * power;
        acc[b].f += f;
        acc[b].n += 1.0;
    }
}

/* One tile: its spectrum binned into acc (nbins, zeroed here), its sums of squares into ss (before,
 * after, number of values). part is scratch of nk x nbins. */
static int one_tile(const spec_plan *p, size_t x0, size_t y0, double mean_count, int inner, tile_work *w,
                    bin_acc *part, bin_acc *acc, double ss[3])
{
    tile_stats st;
    tile_sums(p, x0, y0, inner, w->sums, &st);
    int rc = transform_tile(p, x0, y0, &st, inner, w);
    if (rc != FT_OK)
        return rc;
    size_t nk = p->nk, nb = p->nbins;
    double weight = p->elevations ? 1.0 : (st.nx + st.ny) / mean_count;
#pragma omp parallel for if (inner) schedule(static)
    for (size_t q = 0; q < nk; q++) {
        bin_acc *a = part + q * nb;
        for (size_t b = 0; b < nb; b++)
            a[b] = (bin_acc){0.0, 0.0, 0.0};
        bin_column(p, w, q, &st, weight, a);
    }
    for (size_t b = 0; b < nb; b++)
        acc[b] = (bin_acc){0.0, 0.0, 0.0};
    for (size_t q = 0; q < nk; q++)
        for (size_t b = 0; b < nb; b++) {
            const bin_acc *s = &part[q * nb + b];
            acc[b] = (bin_acc){acc[b].p + s->p, acc[b].f + s->f, acc[b].n + s->n};
        }
    ss[0] = ss[1] = 0.0;
    for (size_t i = 0; i < p->t; i++) {
        ss[0] += w->sums[4 * i];
        ss[1] += w->sums[4 * i + 1];
    }
    ss[2] = p->elevations ? (double)p->t * (double)p->t : st.nx + st.ny;
    return FT_OK;
}

/* The mean number of valid values per tile, the unit of the tiles' weights. */
static double mean_tile_count(const tiling *tl)
{
    double sum = 0.0;
    for (size_t k = 0; k < tl->ntiles; k++)
        sum += tl->valid[k];
    return sum / (double)tl->ntiles;
}

/* Every tile: in turn with rows and columns in parallel when tiles are few, or whole tiles in parallel
 * when there are at least two per thread; per-tile sums reduced in tile order into tot and ss. */
static int all_tiles(const spec_plan *p, const tiling *tl, const ft_spectrum_opts *o, bin_acc *tot, double ss[3])
{
    size_t nb = p->nbins, nt = tl->ntiles;
    bin_acc *acc = ft_calloc(nt * nb, sizeof *acc);
    double *pss = ft_calloc(nt * 3, sizeof *pss);
    if (acc == NULL || pss == NULL) {
        free(acc);
        free(pss);
        return FT_E_NOMEM;
    }
    double mean_count = mean_tile_count(tl);
    int outer = nt >= 2 * (size_t)omp_get_max_threads() && omp_get_max_threads() > 1, failed = 0;
    volatile int cancelled = 0;
#pragma omp parallel if (outer) reduction(| : failed)
    {
        tile_work w = {NULL, NULL, NULL};
        bin_acc *part = ft_malloc(p->nk * nb * sizeof *part);
        failed |= part == NULL || work_alloc(p, &w) != FT_OK;
#pragma omp for schedule(dynamic, 1)
        for (size_t k = 0; k < nt; k++) {
            if (failed || cancelled)
                continue;
            failed |= one_tile(p, tl->x0[k], tl->y0[k], mean_count, !outer, &w, part, acc + k * nb, pss + 3 * k) !=
                      FT_OK;
            if (omp_get_thread_num() == 0 &&
                ft_progress(o->progress, o->progress_arg, 0.95 * (double)(k + 1) / (double)nt, NAME) != FT_OK)
                cancelled = 1;
        }
        free(part);
        work_free(&w);
    }
    for (size_t b = 0; b < nb; b++)
        tot[b] = (bin_acc){0.0, 0.0, 0.0};
    ss[0] = ss[1] = ss[2] = 0.0;
    for (size_t k = 0; k < nt; k++) {
        for (size_t b = 0; b < nb; b++) {
            const bin_acc *q = &acc[k * nb + b];
            tot[b] = (bin_acc){tot[b].p + q->p, tot[b].f + q->f, tot[b].n + q->n};
        }
        for (int j = 0; j < 3; j++)
            ss[j] += pss[3 * k + j];
    }
    free(acc);
    free(pss);
    if (cancelled)
        return ft_error(FT_E_CANCELLED, NAME ": cancelled");
    return failed ? (ft_last_error_code() ? ft_last_error_code() : ft_error(FT_E_NOMEM, NAME ": out of memory"))
                  : FT_OK;
}

/* The 1-D Hann taper and Σw² of the 2-D one; without a taper NULL and Σw² = t². */
static int make_taper(size_t t, int window, double **w, double *w2)
{
    *w = NULL;
    *w2 = (double)t * (double)t;
    if (!window)
        return FT_OK;
    double *v = ft_malloc(t * sizeof *v), s = 0.0;
    if (v == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < t; i++) {
        double x = sin(M_PI * ((double)i + 0.5) / (double)t);
        v[i] = x * x;
        s += v[i] * v[i];
    }
    *w = v;
    *w2 = s * s;
    return FT_OK;
}

static int check_opts(const ft_grid *g, const ft_spectrum_opts *o)
{
    int rc = ft_surface_check_grid(g, NAME, MIN_TILE);
    if (rc != FT_OK)
        return rc;
    size_t small = g->nx < g->ny ? g->nx : g->ny;
    if (o->tile != 0 && (o->tile < MIN_TILE || o->tile > small))
        return ft_error(FT_E_INVALID, NAME ": tile must be 0 (automatic) or in [%d, %zu] cells, got %zu", MIN_TILE,
                        small, o->tile);
    if (!(o->min_wavelength == 0.0 || o->min_wavelength >= 2.0) || !isfinite(o->min_wavelength))
        return ft_error(FT_E_INVALID, NAME ": min_wavelength must be 0 (automatic) or >= 2 cells, got %g",
                        o->min_wavelength);
    if (!(o->max_wavelength >= 0.0) || !isfinite(o->max_wavelength))
        return ft_error(FT_E_INVALID, NAME ": max_wavelength must be >= 0 cells, got %g", o->max_wavelength);
    if (o->nbins != 0 && (o->nbins < 2 || o->nbins > 1000))
        return ft_error(FT_E_INVALID, NAME ": nbins must be 0 (automatic) or in [2, 1000], got %d", o->nbins);
    if (o->window != 0 && o->window != 1)
        return ft_error(FT_E_INVALID, NAME ": window must be 0 (none) or 1 (Hann), got %d", o->window);
    if (o->elevations != 0 && o->elevations != 1)
        return ft_error(FT_E_INVALID, NAME ": elevations must be 0 (differences) or 1 (elevations), got %d",
                        o->elevations);
    if (o->noise.mode != 0 && o->noise.mode != -1)
        return ft_error(FT_E_INVALID, NAME ": noise.mode must be 0 (automatic) or -1 (off), got %d", o->noise.mode);
    if (!(o->noise.sigma_z >= 0.0) || !isfinite(o->noise.sigma_z))
        return ft_error(FT_E_INVALID, NAME ": noise.sigma_z must be finite and >= 0, got %g", o->noise.sigma_z);
    return FT_OK;
}

/* The wavelength range in cells for tiles of side t. */
static int wavelengths(const ft_spectrum_opts *o, size_t t, double *lo, double *hi)
{
    *lo = o->min_wavelength > 0.0 ? o->min_wavelength : DEFAULT_MIN_WAVELENGTH;
    *hi = o->max_wavelength > 0.0 ? o->max_wavelength
                                  : fmin(0.5 * (double)t, fmax((double)t / DEFAULT_MAX_WAVELENGTH_DIV, 2.0 * *lo));
    if (*hi > (double)t)
        return ft_error(FT_E_INVALID, NAME ": max_wavelength %g cells exceeds the tile (%zu cells)", *hi, t);
    if (!(*hi >= 2.0 * *lo))
        return ft_error(FT_E_INVALID, NAME ": needs wavelengths spanning an octave, got %g to %g cells (tile %zu)",
                        *lo, *hi, t);
    return FT_OK;
}

static int build_table(const bin_acc *tot, size_t nb, ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create(nb);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t b = 0; b < nb && rc == FT_OK; b++)
        if (tot[b].n > 0.0 && tot[b].p > 0.0)
            rc = ft_loglog_push(t, tot[b].f / tot[b].n, tot[b].p / tot[b].n, tot[b].n);
    if (rc == FT_OK)
        rc = ft_loglog_sort(t);
    if (rc == FT_OK && t->n < 2)
        rc = ft_error(FT_E_EMPTY, NAME ": fewer than two frequency bins hold power");
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

/* A plane leaves only float rounding once removed: rms below a few ulps of the elevations (per cell for
 * the differences), or a billionth of what was there. */
static int is_plane(const spec_plan *p, const double ss[3], double zmin, double zmax)
{
    double big = fmax(fabs(zmin), fabs(zmax)), unit = p->elevations ? 1.0 : fmin(p->cx, p->cy);
    double rms = ss[2] > 0.0 ? sqrt(ss[1] / ss[2]) : 0.0, before = ss[2] > 0.0 ? sqrt(ss[0] / ss[2]) : 0.0;
    return !(rms > 16.0 * FLT_EPSILON * big / unit) || !(rms > 1e-9 * before);
}

int ft_surface_dim_spectrum(const ft_grid *g, const ft_spectrum_opts *opts, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, NAME ": output pointer is NULL");
    *out = NULL;
    ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_spectrum_opts) != FT_OK)
        return FT_E_INVALID;
    int rc = check_opts(g, &o);
    if (rc != FT_OK)
        return rc;
    double zmin, zmax, lo, hi, ss[3] = {0.0, 0.0, 0.0};
    uint8_t *valid = NULL;
    if ((rc = valid_cells(g, &valid, &zmin, &zmax)) != FT_OK)
        return rc;
    spec_plan p;
    memset(&p, 0, sizeof p);
    p.g = g;
    p.valid = valid;
    p.elevations = o.elevations;
    ft_surface_cell_size(g, &p.cx, &p.cy);
    tiling tl = {0, NULL, NULL, NULL, 0};
    double *w = NULL;
    bin_acc *tot = NULL;
    ft_loglog *t = NULL;
    if ((rc = ft_progress(o.progress, o.progress_arg, 0.0, NAME)) != FT_OK ||
        (rc = choose_tiles(g, valid, o.tile, o.elevations, &tl)) != FT_OK ||
        (rc = wavelengths(&o, tl.tile, &lo, &hi)) != FT_OK)
        goto done;
    p.t = tl.tile;
    double c = sqrt(p.cx * p.cy);
    p.flo = 1.0 / (hi * c);
    p.fhi = 1.0 / (lo * c);
    /* every index the band reaches along either axis: kx / (t cx) <= fhi = 1 / (lo c) */
    size_t kmax = (size_t)floor((double)p.t / lo * fmax(p.cx / c, p.cy / c) * (1.0 + 1e-9));
    if (kmax > p.t / 2)
        kmax = p.t / 2;
    if ((rc = make_plan(&p, kmax, o.nbins)) != FT_OK ||
        (o.elevations && (rc = make_taper(p.t, o.window, &w, &p.w2)) != FT_OK))
        goto done;
    p.w = w;
    tot = ft_malloc(p.nbins * sizeof *tot);
    if (tot == NULL) {
        rc = FT_E_NOMEM;
        goto done;
    }
    if ((rc = all_tiles(&p, &tl, &o, tot, ss)) != FT_OK)
        goto done;
    if (is_plane(&p, ss, zmin, zmax)) {
        rc = ft_error(FT_E_NUMERIC, NAME ": the surface is a plane (rms %g after removing it): degenerate for the "
                      "spectrum, whose D needs relief at every scale", ss[2] > 0.0 ? sqrt(ss[1] / ss[2]) : 0.0);
        goto done;
    }
    ft_dim_map map = FT_DIM_MAP_SPECTRUM_SURFACE;
    if ((rc = build_table(tot, p.nbins, &t)) != FT_OK ||
        (rc = ft_spectrum_fit_noise(t, &o.noise, o.fit_whole_range, &o.fit, &map, out)) != FT_OK)
        goto done;
    (*out)->method = NAME;
    if ((*out)->D < DEGENERATE_D) {
        rc = ft_error(FT_E_NUMERIC, NAME ": the surface is smoother than any fractal (beta = %.2f > 4.2, D = %.2f): "
                      "degenerate for the spectrum", 2.0 * (4.0 - (*out)->D), (*out)->D);
    } else {
        rc = ft_progress(o.progress, o.progress_arg, 1.0, NAME);
    }
    if (rc != FT_OK) {
        ft_dim_result_free(*out);
        *out = NULL;
    }
done:
    ft_loglog_free(t);
    free(tot);
    free(w);
    plan_free(&p);
    tiling_free(&tl);
    free(valid);
    return rc;
}
