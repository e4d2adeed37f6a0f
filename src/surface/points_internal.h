/* fracterra — surface/points_internal.h: what the scattered-point estimator's files (points_*.c) share,
 * not installed. Arakawa & Krotkov §2.4 step 1: the lags Δd_i with their annuli |d - Δd_i| <= ε, and the
 * counters A_i = Σ|z - z'|, B_i = Σ(z - z')², C_i = pairs (plus Σd for the mean separation).
 *
 * The exact and grid enumerations add every pair's terms in 128-bit fixed point: each term is rounded once
 * to a multiple of a power of two chosen from the data (|Δz| to 2^-61 of the elevation range's power of
 * two, and so on), and integer sums do not depend on the order of addition. So both enumerations, on any
 * thread count, give bit-identical counters; the rounding of one term is at most 2^-62 of the range.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_SURFACE_POINTS_INTERNAL_H
#define FRACTERRA_SURFACE_POINTS_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "fracterra/surface.h"

__extension__ typedef __int128 pts_i128;

/* Fixed-point sums of one lag. */
typedef struct {
    pts_i128 a, b, s; /* Σ|Δz|·qa, Σ Δz²·qb, Σ d·qs, each term rounded to an integer */
    uint64_t c;       /* pairs */
} pts_acc;

/* The lags and their annuli in squared distance, with a lookup from d² to the lags it may hit. */
typedef struct {
    double *lag;        /* n lags, increasing */
    double *lo2, *hi2;  /* (max(0, lag - eps))², (lag + eps)² */
    size_t n;
    double eps;
    double rmin2, rmax2;   /* smallest lo2, largest hi2 */
    double rmax;           /* max lag + eps */
    double bin_scale;      /* d² -> bin: (size_t)(fmin(d², bin_cap) * bin_scale) */
    double bin_cap;        /* just above rmax2: larger d² fall in the empty bin nbins */
    size_t nbins;
    uint32_t *bin_first;   /* per bin: first lag whose annulus meets the bin */
    uint32_t *bin_count;   /* per bin: number of such lags (consecutive) */
    uint8_t *bin_hit;      /* nbins + 1 flags: 1 if some annulus meets the bin (0 for the last) */
    double qa, qb, qs;     /* fixed-point scales (powers of two) of |Δz|, Δz², d */
} pts_lags;

/* Builds the lookup and the fixed-point scales for lags (owned by L afterwards) over elevations of range
 * zrange. */
int pts_lags_init(pts_lags *L, double *lags, size_t n, double eps, double zrange);
void pts_lags_free(pts_lags *L);

/* The bin of a squared separation (nbins, an empty bin, beyond the largest annulus). */
static inline size_t pts_bin(const pts_lags *L, double d2)
{
    return (size_t)(fmin(d2, L->bin_cap) * L->bin_scale);
}

/* Step 1 of §2.4 for one pair whose bin has a hit: adds it (squared separation d2, elevation difference
 * dz) to every lag whose annulus holds it, |d - Δd_i| <= ε tested as (Δd_i - ε)² <= d² <= (Δd_i + ε)². */
static inline void pts_add_binned(const pts_lags *L, pts_acc *acc, double d2, double dz, size_t b)
{
    size_t k = L->bin_first[b], end = k + L->bin_count[b];
    for (; k < end; k++)
        if (d2 >= L->lo2[k] && d2 <= L->hi2[k]) {
            double adz = dz < 0.0 ? -dz : dz;
            acc[k].a += (pts_i128)(int64_t)(adz * L->qa + 0.5);
            acc[k].b += (pts_i128)(int64_t)(adz * adz * L->qb + 0.5);
            acc[k].s += (pts_i128)(int64_t)(sqrt(d2) * L->qs + 0.5);
            acc[k].c++;
        }
}

/* The same for any pair. */
static inline void pts_add_pair(const pts_lags *L, pts_acc *acc, double d2, double dz)
{
    size_t b = pts_bin(L, d2);
    if (L->bin_hit[b])
        pts_add_binned(L, acc, d2, dz, b);
}

/* Adds src into dst (n lags). */
void pts_acc_merge(pts_acc *dst, const pts_acc *src, size_t n);

/* The points sorted into a uniform grid of square cells (counting sort), coordinates copied cell by
 * cell. */
typedef struct {
    double x0, y0, cell;  /* origin (minimum x, y) and cell side */
    size_t nx, ny;
    size_t *start;        /* nx*ny + 1 offsets into x, y, z */
    double *x, *y, *z;
} pts_grid;

/* Sorts the n points into cells of side at least `cell`, enlarging it if the grid would have more than
 * max(4n, 4096) cells. */
int pts_grid_build(pts_grid *g, const ft_points *p, double cell);
void pts_grid_free(pts_grid *g);
/* Smallest and largest distance between a point of cell (0,0) and one of cell (ox, oy), with slack. */
void pts_grid_offset_range(const pts_grid *g, long ox, long oy, double *dmin2, double *dmax2);
/* 1 if some lag's annulus meets the squared-distance interval [dmin2, dmax2]. */
int pts_lags_meet(const pts_lags *L, double dmin2, double dmax2);

/* Cell offsets (ox, oy) whose range of separations can meet an annulus: all of them (with (0, 0)), or with
 * half = 1 those of one half-plane (oy > 0, or oy = 0 and ox > 0), so that each pair of cells is met once. */
typedef struct {
    long *ox, *oy;
    size_t n;
} pts_offsets;
int pts_grid_offsets(const pts_grid *g, const pts_lags *L, int half, pts_offsets *o);
void pts_offsets_free(pts_offsets *o);

/* Every pair i < j, O(N²) (points_pairs_exact.c). acc: n lags, zeroed by the caller. */
int pts_pairs_exact(const ft_points *p, const pts_lags *L, pts_acc *acc, ft_progress_fn fn, void *arg);
/* Every pair within the largest annulus through the grid (points_pairs_grid.c). */
int pts_pairs_grid(const ft_points *p, const pts_lags *L, pts_acc *acc, ft_progress_fn fn, void *arg);
/* Tests only: the screens pts_pairs_grid may use: 0 any (AVX-512 float where the processor has it, two rows
 * at a time with 16-bit candidates where it has VBMI2 and cells hold at most 256 points), 1 at most AVX2
 * (double), 2 none (plain C), 3 any but the two-row screen (AVX-512 float with 32-bit candidates). */
void pts_pairs_grid_isa(int limit);

/* Weighted sums of sample mode, per lag (points_pairs_sample.c): with w = the candidate count of the
 * drawn pair's first point, a = |Δz|: Σw, Σw·a, Σw·a², Σw·d, and for the standard errors Σw²·a^k,
 * k = 0..4. */
typedef struct {
    double w, wa, wa2, wd;
    double v[5];
    uint64_t drawn;
} pts_wsum;

/* `sample` random pairs within the largest annulus (points_pairs_sample.c). ws: n lags, zeroed. */
int pts_pairs_sample(const ft_points *p, const pts_lags *L, size_t sample, uint64_t seed, pts_wsum *ws,
                     ft_progress_fn fn, void *arg);

#endif /* FRACTERRA_SURFACE_POINTS_INTERNAL_H */
