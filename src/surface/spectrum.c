/* fracterra — spectrum.c: the power-spectrum dimension of an elevation grid (Clarke 1987, "Scale-based
 * simulation of topography", eqs. vi-viii, seeds 004; Voss 1985; Welch 1967 for the averaged tapered
 * periodograms).
 *
 * For an isotropic fractional Brownian surface the radially averaged power falls as P(f) ~ f^-beta with
 * beta = 2H + 2, so D = 3 - H = (8 - beta) / 2 (FT_DIM_MAP_SPECTRUM_SURFACE, the table's scale being the
 * frequency). Clarke's eq. viii, f = 3 - beta/2, is the variogram relation and is not used (seeds/README).
 *
 * Steps:
 *  1. Tiles: squares of `tile` cells, overlapping by about half (Welch), spread evenly from edge to edge;
 *     a tile holding a nodata or non-finite cell is skipped (never filled). Automatic tile: min(nx, ny)
 *     (one tile on a square grid), halved while no tile is free of nodata; sizes are 2·3·5·7-smooth.
 *  2. Each tile: the least-squares plane removed (Clarke's trend T, eq. xii), then the 2-D Hann taper
 *     w(i) w(j), w(i) = sin²(pi (i + 1/2) / tile), against the leakage of the tile's edges; its periodogram
 *     |F(kx, ky)|² / Σw² through src/fft/fft.h.
 *  3. Radial average: frequencies f = |(kx / (tile cx), ky / (tile cy))| (cycles per ground unit) in
 *     log-spaced bins between 1 / max_wavelength and 1 / min_wavelength (defaults 8 cells, below which
 *     aliasing flattens the spectrum, and tile / 8, above which the taper and the plane bend it); each
 *     bin's value is the mean power of its frequencies over every tile (both halves of the spectrum
 *     counted), its scale their mean f.
 *  4. log P against log f, fitted as every estimator (ft_loglog_fit_auto or the whole range).
 * Degenerate surfaces fail plainly: a plane (the detrended tiles hold only float rounding) and a surface
 * smoother than any fBm (D < 1.9, beta > 4.2: a smooth bowl's tapered spectrum falls as f^-6).
 * Tiles run in parallel (OpenMP) with per-tile bin sums added in order: the same bits on any thread count.
 * docs/surface-grid.md.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>

#include "fft/fft.h"
#include "internal.h"
#include "surface/grid_internal.h"

#define NAME "spectrum"
#define MIN_TILE 8
#define AUTO_MIN_TILE 16
#define DEFAULT_MIN_WAVELENGTH 8.0
#define DEFAULT_MAX_WAVELENGTH_DIV 8.0
#define DEGENERATE_D 1.9

typedef struct {
    size_t tile;
    size_t *x0, *y0; /* upper-left cells of the valid tiles */
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

static int tile_valid(const ft_grid *g, size_t x0, size_t y0, size_t t)
{
    for (size_t i = y0; i < y0 + t; i++)
        for (size_t j = x0; j < x0 + t; j++)
            if (!ft_surface_cell_ok(g, i * g->nx + j))
                return 0;
    return 1;
}

/* The valid tiles of side t; FT_OK with ntiles possibly 0. */
static int find_tiles(const ft_grid *g, size_t t, tiling *tl)
{
    size_t *ox = ft_malloc((g->nx / (t / 2 > 0 ? t / 2 : 1) + 2) * sizeof *ox);
    size_t *oy = ft_malloc((g->ny / (t / 2 > 0 ? t / 2 : 1) + 2) * sizeof *oy);
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
    int rc = tl->x0 && tl->y0 ? FT_OK : FT_E_NOMEM;
    for (size_t b = 0; rc == FT_OK && b < my; b++)
        for (size_t a = 0; a < mx; a++)
            if (tile_valid(g, ox[a], oy[b], t)) {
                tl->x0[tl->ntiles] = ox[a];
                tl->y0[tl->ntiles++] = oy[b];
            }
    free(ox);
    free(oy);
    return rc;
}

static void tiling_free(tiling *tl)
{
    free(tl->x0);
    free(tl->y0);
    tl->x0 = tl->y0 = NULL;
}

/* Step 1: the tile size asked for, or the automatic one, and its valid tiles. */
static int choose_tiles(const ft_grid *g, size_t asked, tiling *tl)
{
    size_t small = g->nx < g->ny ? g->nx : g->ny;
    size_t t = asked ? asked : smooth_floor(small);
    for (;;) {
        int rc = find_tiles(g, t, tl);
        if (rc != FT_OK || tl->ntiles > 0)
            return rc;
        tiling_free(tl);
        if (asked || t / 2 < AUTO_MIN_TILE)
            return ft_error(FT_E_EMPTY, NAME ": no tile of %zux%zu cells is free of nodata on the %zux%zu grid%s", t,
                            t, g->nx, g->ny, asked ? "; try a smaller tile" : "");
        t = smooth_floor(t / 2);
    }
}

/* Radial bins of the half spectrum of a t x t tile: bin index (or -1) and weight of every (ky, kx). */
typedef struct {
    int *bin;
    double *f;       /* frequency, cycles per ground unit */
    size_t nh;       /* t / 2 + 1 */
    size_t nbins;
    double *edges;   /* nbins + 1 */
} radial;

static int make_radial(size_t t, double cx, double cy, double flo, double fhi, int nbins, radial *r)
{
    if (nbins <= 0)
        nbins = (int)ceil(4.0 * log2(fhi / flo));
    if (nbins < 2)
        nbins = 2;
    r->nh = t / 2 + 1;
    r->nbins = (size_t)nbins;
    r->bin = ft_malloc(t * r->nh * sizeof *r->bin);
    r->f = ft_malloc(t * r->nh * sizeof *r->f);
    r->edges = ft_malloc((r->nbins + 1) * sizeof *r->edges);
    if (r->bin == NULL || r->f == NULL || r->edges == NULL)
        return FT_E_NOMEM;
    for (size_t b = 0; b <= r->nbins; b++)
        r->edges[b] = flo * pow(fhi / flo, (double)b / (double)r->nbins);
    double lo = flo * (1.0 - 1e-9), hi = fhi * (1.0 + 1e-9);
    for (size_t ky = 0; ky < t; ky++) {
        double fy = (double)(ky <= t / 2 ? (long)ky : (long)ky - (long)t) / ((double)t * cy);
        for (size_t kx = 0; kx < r->nh; kx++) {
            double f = hypot((double)kx / ((double)t * cx), fy);
            size_t i = ky * r->nh + kx;
            r->f[i] = f;
            r->bin[i] = -1;
            if (f < lo || f > hi)
                continue;
            size_t b = (size_t)floor((double)r->nbins * log(f / flo) / log(fhi / flo));
            r->bin[i] = (int)(b >= r->nbins ? r->nbins - 1 : b);
        }
    }
    return FT_OK;
}

static void radial_free(radial *r)
{
    free(r->bin);
    free(r->f);
    free(r->edges);
}

/* Per-tile sums of one bin: power, frequency, count (weights 2 for the columns standing for both halves). */
typedef struct {
    double p, f, n;
} bin_acc;

/* Least-squares plane of a t x t tile (centred coordinates make the normal equations diagonal). */
static void detrend(double *a, size_t t, double *ss_before, double *ss_after)
{
    double n = (double)t * (double)t, c = 0.5 * (double)(t - 1), sxx = 0.0;
    double mean = 0.0, sx = 0.0, sy = 0.0;
    for (size_t i = 0; i < t; i++)
        sxx += ((double)i - c) * ((double)i - c);
    for (size_t i = 0; i < t; i++)
        for (size_t j = 0; j < t; j++) {
            double v = a[i * t + j];
            mean += v;
            sx += ((double)j - c) * v;
            sy += ((double)i - c) * v;
        }
    mean /= n;
    double bx = sx / (sxx * (double)t), by = sy / (sxx * (double)t), before = 0.0, after = 0.0;
    for (size_t i = 0; i < t; i++)
        for (size_t j = 0; j < t; j++) {
            double *v = &a[i * t + j];
            before += (*v - mean) * (*v - mean);
            *v -= mean + bx * ((double)j - c) + by * ((double)i - c);
            after += *v * *v;
        }
    *ss_before = before;
    *ss_after = after;
}

/* Steps 2-3 for one tile of side t at (x0, y0): detrend, taper, transform, bin into acc (nbins).
 * buf holds t x t reals, spec t x (t/2+1) complex; ss receives the sums of squares before and after the
 * plane was removed. */
static int one_tile(const ft_grid *g, size_t t, size_t x0, size_t y0, const radial *r, const double *w,
                    double w2, double *buf, fftw_complex *spec, bin_acc *acc, double ss[2])
{
    for (size_t i = 0; i < t; i++)
        for (size_t j = 0; j < t; j++)
            buf[i * t + j] = (double)g->z[(y0 + i) * g->nx + x0 + j];
    detrend(buf, t, &ss[0], &ss[1]);
    if (w != NULL)
        for (size_t i = 0; i < t; i++)
            for (size_t j = 0; j < t; j++)
                buf[i * t + j] *= w[i] * w[j];
    int rc = ft_fft_r2c_2d(t, t, buf, spec);
    if (rc != FT_OK)
        return rc;
    for (size_t b = 0; b < r->nbins; b++)
        acc[b] = (bin_acc){0.0, 0.0, 0.0};
    for (size_t ky = 0; ky < t; ky++)
        for (size_t kx = 0; kx < r->nh; kx++) {
            size_t i = ky * r->nh + kx;
            if (r->bin[i] < 0)
                continue;
            /* columns 1 .. ceil(t/2)-1 stand for their conjugates in the other half too */
            double wt = kx == 0 || 2 * kx == t ? 1.0 : 2.0;
            double p = (spec[i][0] * spec[i][0] + spec[i][1] * spec[i][1]) / w2;
            bin_acc *a = &acc[r->bin[i]];
            a->p += wt * p;
            a->f += wt * r->f[i];
            a->n += wt;
        }
    return FT_OK;
}

/* The 1-D taper and Σw² of the 2-D one (1 without a taper). */
static double *make_taper(size_t t, int window, double *w2)
{
    *w2 = (double)t * (double)t;
    if (!window)
        return NULL;
    double *w = ft_malloc(t * sizeof *w), s = 0.0;
    if (w == NULL)
        return NULL;
    for (size_t i = 0; i < t; i++) {
        double v = sin(M_PI * ((double)i + 0.5) / (double)t);
        w[i] = v * v;
        s += w[i] * w[i];
    }
    *w2 = s * s;
    return w;
}

/* Every tile in parallel; per-tile sums reduced in order into tot (nbins) and ss (before, after). */
static int all_tiles(const ft_grid *g, const tiling *tl, const radial *r, const double *w, double w2,
                     const ft_spectrum_opts *o, bin_acc *tot, double ss[2])
{
    size_t t = tl->tile, nb = r->nbins;
    bin_acc *part = ft_calloc(tl->ntiles * nb, sizeof *part);
    double *pss = ft_calloc(tl->ntiles * 2, sizeof *pss);
    if (part == NULL || pss == NULL) {
        free(part);
        free(pss);
        return FT_E_NOMEM;
    }
    int failed = 0;
    volatile int cancelled = 0;
#pragma omp parallel reduction(| : failed)
    {
        double *buf = ft_fft_alloc_real(t * t);
        fftw_complex *spec = ft_fft_alloc_complex(t * r->nh);
        failed |= buf == NULL || spec == NULL;
#pragma omp for schedule(dynamic, 1)
        for (size_t k = 0; k < tl->ntiles; k++) {
            if (failed || cancelled)
                continue;
            failed |= one_tile(g, t, tl->x0[k], tl->y0[k], r, w, w2, buf, spec, part + k * nb, pss + 2 * k) != FT_OK;
            if (omp_get_thread_num() == 0 &&
                ft_progress(o->progress, o->progress_arg, 0.95 * (double)(k + 1) / (double)tl->ntiles, NAME) != FT_OK)
                cancelled = 1;
        }
        ft_fft_free(buf);
        ft_fft_free(spec);
    }
    for (size_t b = 0; b < nb; b++)
        tot[b] = (bin_acc){0.0, 0.0, 0.0};
    ss[0] = ss[1] = 0.0;
    for (size_t k = 0; k < tl->ntiles; k++) {
        for (size_t b = 0; b < nb; b++) {
            const bin_acc *q = &part[k * nb + b];
            tot[b] = (bin_acc){tot[b].p + q->p, tot[b].f + q->f, tot[b].n + q->n};
        }
        ss[0] += pss[2 * k];
        ss[1] += pss[2 * k + 1];
    }
    free(part);
    free(pss);
    if (cancelled)
        return ft_error(FT_E_CANCELLED, NAME ": cancelled");
    return failed ? (ft_last_error_code() ? ft_last_error_code() : ft_error(FT_E_NOMEM, NAME ": out of memory"))
                  : FT_OK;
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

int ft_surface_dim_spectrum(const ft_grid *g, const ft_spectrum_opts *opts, ft_dim_result **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, NAME ": output pointer is NULL");
    *out = NULL;
    ft_spectrum_opts o = FT_SPECTRUM_OPTS_DEFAULT;
    if (opts != NULL)
        o = *opts;
    int rc = check_opts(g, &o);
    if (rc != FT_OK)
        return rc;
    double zmin, zmax, cx, cy, lo, hi, w2 = 1.0, ss[2] = {0.0, 0.0};
    if ((rc = ft_surface_valid_range(g, NAME, &zmin, &zmax)) != FT_OK)
        return rc;
    ft_surface_cell_size(g, &cx, &cy);
    tiling tl = {0, NULL, NULL, 0};
    radial r = {NULL, NULL, 0, 0, NULL};
    double *w = NULL;
    bin_acc *tot = NULL;
    ft_loglog *t = NULL;
    if ((rc = ft_progress(o.progress, o.progress_arg, 0.0, NAME)) != FT_OK ||
        (rc = choose_tiles(g, o.tile, &tl)) != FT_OK)
        goto done;
    if ((rc = wavelengths(&o, tl.tile, &lo, &hi)) != FT_OK)
        goto done;
    double c = sqrt(cx * cy);
    if ((rc = make_radial(tl.tile, cx, cy, 1.0 / (hi * c), 1.0 / (lo * c), o.nbins, &r)) != FT_OK)
        goto done;
    w = make_taper(tl.tile, o.window, &w2);
    tot = ft_malloc(r.nbins * sizeof *tot);
    if ((o.window && w == NULL) || tot == NULL) {
        rc = FT_E_NOMEM;
        goto done;
    }
    if ((rc = all_tiles(g, &tl, &r, w, w2, &o, tot, ss)) != FT_OK)
        goto done;
    /* a plane leaves only float rounding: rms below a few ulps of the elevations */
    double n = (double)tl.ntiles * (double)tl.tile * (double)tl.tile, big = fmax(fabs(zmin), fabs(zmax));
    double rms = sqrt(ss[1] / n);
    if (!(rms > 16.0 * FLT_EPSILON * big) || !(rms > 1e-9 * sqrt(ss[0] / n))) {
        rc = ft_error(FT_E_NUMERIC, NAME ": the surface is a plane (rms %g after removing it): degenerate for the "
                      "spectrum, whose D needs relief at every scale", rms);
        goto done;
    }
    ft_dim_map map = FT_DIM_MAP_SPECTRUM_SURFACE;
    if ((rc = build_table(tot, r.nbins, &t)) != FT_OK ||
        (rc = ft_surface_fit_table(t, o.fit_whole_range, &o.fit, &map, NAME, out)) != FT_OK)
        goto done;
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
    radial_free(&r);
    tiling_free(&tl);
    return rc;
}
