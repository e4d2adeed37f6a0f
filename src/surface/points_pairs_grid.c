/* fracterra — surface/points_pairs_grid.c: the counters of Arakawa & Krotkov §2.4 step 1 over every pair
 * of points, found through a uniform grid instead of the paper's O(N²) loop over all pairs.
 *
 * The points are sorted into square cells of side (max lag + ε) / CELLS_PER_LAG. A pair can fall on a lag
 * only if its separation is at most max lag + ε, so each cell is paired with itself (i < j inside it) and
 * with the cells at the offsets of one half-plane (oy > 0, or oy = 0 and ox > 0) whose range of possible
 * separations meets some annulus [Δd_i - ε, Δd_i + ε]: every such pair of points is visited exactly once,
 * pairs that cannot fall on a lag are never visited. The per-pair test and the fixed-point sums are the
 * exact enumeration's (points_internal.h), so the counters are bit-identical to it. Cost: O(N k), k the
 * points within max lag + ε of a point. OpenMP over cells, one set of counters per thread, merged as
 * integers (order-free, so the result does not depend on the thread count).
 *
 * Most pairs lie far apart, where an offset's range of separations meets one to three annuli (they are
 * spaced by a fixed ratio, the cells are small). Such an offset's pairs are screened against just those
 * annuli: with AVX-512, sixteen pairs per instruction in float (d² - lo from |q|² - lo, |p|² and two fused
 * multiply-adds, against annuli widened beyond the float roundings: float_annuli), the pairs kept listed
 * and then tested exactly eight at a time (lane_body_avx512f, candidates_body); where the processor has
 * VBMI2 and cells hold at most 256 points, two rows at a time with 16-bit indices (lane_body_avx512w: one
 * compress and one store per two rows); with AVX2, four pairs per instruction in double; else plain C.
 * The exact test is always the scalar one's arithmetic: d² = dx² + dy² with each product rounded (no fused
 * multiply-add), the same bounds, the same rounded integer terms. Cells are copied with their point counts padded to the
 * lane width with NaN coordinates (a NaN d² lies in no annulus). Without AVX-512, offsets near the
 * origin, meeting more annuli, keep the lookup-table screen. A pair meets the same annuli whichever screen
 * runs, so the counters do not depend on it (tests/unit/test_surface_points.c compares each with the
 * exact enumeration).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "points_internal.h"

/* Cells across the largest annulus radius: finer cells cut the area scanned around each point from
 * (3 (max lag + ε))² towards π (max lag + ε)² (about 1.2 times it with 16) and let whole cells between
 * two annuli be skipped. */
#define CELLS_PER_LAG 16
#define MIN_PER_CELL 32.0
#define CHUNKS 64
#define FEW_MAX 8 /* offsets meeting at most this many annuli take a lane screen (vector copies) */
#define RANGE_SLACK 1e-9 /* relative widening of an offset's range when listing the annuli it meets */

/* The grid's points again, each cell padded with NaN points to a multiple of the screen's lanes. */
typedef struct {
    size_t *start;  /* ncell + 1 offsets */
    double *x, *y, *z;
    float *fx, *fy; /* x, y less the cell's corner, as floats (the float screen only) */
    float *fa, *fb, *fm; /* -2 fx, -2 fy, fx² + fy² */
    size_t lanes;   /* cells padded to a multiple of this */
} padded_cells;

/* An offset with the consecutive annuli [k0, k0 + nk) its range of separations meets, and its
 * displacement as floats. */
typedef struct {
    long ox, oy;
    uint32_t k0, nk;
    float fx, fy;
} lane_offset;

/* The screens this run may use (tests only: pts_pairs_grid_isa). */
enum { ISA_BEST = 0, ISA_AVX2 = 1, ISA_GENERIC = 2, ISA_AVX512_IDS32 = 3 };
static int isa_limit;

void pts_pairs_grid_isa(int limit)
{
    isa_limit = limit;
}

static int pad_cells(const pts_grid *g, size_t lanes, padded_cells *p)
{
    size_t ncell = g->nx * g->ny;
    p->lanes = lanes;
    p->start = ft_malloc((ncell + 1) * sizeof *p->start);
    if (p->start == NULL)
        return FT_E_NOMEM;
    p->start[0] = 0;
    for (size_t c = 0; c < ncell; c++) {
        size_t n = g->start[c + 1] - g->start[c];
        p->start[c + 1] = p->start[c] + (n + lanes - 1) / lanes * lanes;
    }
    size_t total = p->start[ncell];
    p->x = ft_malloc((total ? total : 1) * sizeof *p->x);
    p->y = ft_malloc((total ? total : 1) * sizeof *p->y);
    p->z = ft_malloc((total ? total : 1) * sizeof *p->z);
    p->fx = ft_malloc((total ? total : 1) * sizeof *p->fx);
    p->fy = ft_malloc((total ? total : 1) * sizeof *p->fy);
    p->fa = ft_malloc((total ? total : 1) * sizeof *p->fa);
    p->fb = ft_malloc((total ? total : 1) * sizeof *p->fb);
    p->fm = ft_malloc((total ? total : 1) * sizeof *p->fm);
    if (p->x == NULL || p->y == NULL || p->z == NULL || p->fx == NULL || p->fy == NULL || p->fa == NULL ||
        p->fb == NULL || p->fm == NULL)
        return FT_E_NOMEM;
    for (size_t c = 0; c < ncell; c++) {
        size_t at = p->start[c];
        double cx = g->x0 + (double)(c % g->nx) * g->cell, cy = g->y0 + (double)(c / g->nx) * g->cell;
        for (size_t i = g->start[c]; i < g->start[c + 1]; i++, at++) {
            p->x[at] = g->x[i];
            p->y[at] = g->y[i];
            p->z[at] = g->z[i];
            p->fx[at] = (float)(g->x[i] - cx);
            p->fy[at] = (float)(g->y[i] - cy);
            p->fa[at] = -2.0f * p->fx[at];
            p->fb[at] = -2.0f * p->fy[at];
            p->fm[at] = p->fx[at] * p->fx[at] + p->fy[at] * p->fy[at];
        }
        for (; at < p->start[c + 1]; at++) {
            p->x[at] = p->y[at] = p->z[at] = NAN;
            p->fx[at] = p->fy[at] = p->fa[at] = p->fb[at] = p->fm[at] = NAN;
        }
    }
    return FT_OK;
}

static void padded_free(padded_cells *p)
{
    free(p->start);
    free(p->x);
    free(p->y);
    free(p->z);
    free(p->fx);
    free(p->fy);
    free(p->fa);
    free(p->fb);
    free(p->fm);
}

/* The offset (ox, oy) with the annuli its range of separations meets. */
static lane_offset lane_offset_of(const pts_grid *g, long ox, long oy, const pts_lags *L)
{
    double dmin2, dmax2;
    pts_grid_offset_range(g, ox, oy, &dmin2, &dmax2);
    dmin2 *= 1.0 - RANGE_SLACK;
    dmax2 *= 1.0 + RANGE_SLACK;
    size_t first = 0;
    while (first < L->n && L->hi2[first] < dmin2)
        first++;
    size_t end = first;
    while (end < L->n && L->lo2[end] <= dmax2)
        end++;
    return (lane_offset){ox, oy, (uint32_t)first, (uint32_t)(end - first), (float)((double)ox * g->cell),
                         (float)((double)oy * g->cell)};
}

/* The offsets of o with the annuli each meets. */
static lane_offset *lane_offsets(const pts_grid *g, const pts_offsets *o, const pts_lags *L)
{
    lane_offset *lo = ft_malloc((o->n ? o->n : 1) * sizeof *lo);
    if (lo == NULL)
        return NULL;
    for (size_t k = 0; k < o->n; k++)
        lo[k] = lane_offset_of(g, o->ox[k], o->oy[k], L);
    return lo;
}

/* The bits of a float. */
static inline uint32_t float_bits(float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    return u;
}

/* x rounded to a float not above (dir < 0) or not below (dir > 0) it. */
static float float_toward(double x, int dir)
{
    float f = (float)x;
    if (dir < 0 && (double)f > x)
        f = nextafterf(f, -INFINITY);
    if (dir > 0 && (double)f < x)
        f = nextafterf(f, INFINITY);
    return f;
}

/* The annuli for the float screen, which takes d² = |q|² + |p|² - 2 q·p (p a point relative to its cell's
 * corner, q the other moved by the offset, both rounded to float) less the annulus' lower bound lo, and
 * keeps the pair when 0 <= that <= span, compared as unsigned bits (a NaN or negative float is above any
 * span). With B = (max lag + ε + 5 cells)², every term and partial sum is below 3B, so the dozen float
 * roundings (2^-24 each) and those of the coordinates and the double cell corners (2^-48 of the largest
 * coordinate) move d² by less than E = 2^-17 B + 2^-44 (largest coordinate)(max lag + ε + 5 cells): lo is
 * the annulus' (Δd - ε)² less E rounded down, span its (Δd + ε)² plus E less lo rounded up, so a pair
 * inside an annulus always passes; the exact test follows. */
static int float_annuli(const pts_grid *g, const pts_lags *L, float **lo, float **span)
{
    double big = fmax(fmax(fabs(g->x0), fabs(g->y0)),
                      fmax(fabs(g->x0 + (double)g->nx * g->cell), fabs(g->y0 + (double)g->ny * g->cell)));
    double reach = L->rmax + 5.0 * g->cell, e = ldexp(reach * reach, -17) + ldexp(big, -44) * reach;
    *lo = ft_malloc(L->n * sizeof **lo);
    *span = ft_malloc(L->n * sizeof **span);
    if (*lo == NULL || *span == NULL)
        return FT_E_NOMEM;
    for (size_t k = 0; k < L->n; k++) {
        (*lo)[k] = float_toward(L->lo2[k] - e, -1);
        (*span)[k] = float_toward(L->hi2[k] + e - (double)(*lo)[k], 1);
    }
    return FT_OK;
}

static void cell_self(const pts_grid *g, size_t c, const pts_lags *L, pts_acc *acc)
{
    for (size_t i = g->start[c]; i < g->start[c + 1]; i++)
        for (size_t j = i + 1; j < g->start[c + 1]; j++) {
            double dx = g->x[j] - g->x[i], dy = g->y[j] - g->y[i];
            pts_add_pair(L, acc, dx * dx + dy * dy, g->z[j] - g->z[i]);
        }
}

/* Every point of cell a against every point of cell b: the squared separations and their bins for a
 * whole row first (a loop the compiler vectorises), then the rare pairs whose bin an annulus meets. */
static void cell_pair(const pts_grid *g, size_t a, size_t b, const pts_lags *L, pts_acc *acc, double *d2,
                      int32_t *bin)
{
    size_t b0 = g->start[b], nb = g->start[b + 1] - b0;
    const double *restrict xb = g->x + b0, *restrict yb = g->y + b0, *restrict zb = g->z + b0;
    const double cap = L->bin_cap, scale = L->bin_scale;
    const uint8_t *hit = L->bin_hit;
    for (size_t i = g->start[a]; i < g->start[a + 1]; i++) {
        double xi = g->x[i], yi = g->y[i];
        for (size_t j = 0; j < nb; j++) {
            double dx = xb[j] - xi, dy = yb[j] - yi, q = dx * dx + dy * dy;
            d2[j] = q;
            bin[j] = (int32_t)((q < cap ? q : cap) * scale);
        }
        for (size_t j = 0; j < nb; j++)
            if (hit[bin[j]])
                pts_add_binned(L, acc, d2[j], zb[j] - g->z[i], (size_t)bin[j]);
    }
}

/* One pair of the lane screen that lies in an annulus of [k0, k0 + nk): the exact test of
 * pts_add_binned over those annuli (they hold every annulus the pair can be in). Point i of cell a and
 * point j of cell b, in the padded arrays. */
static inline __attribute__((always_inline)) void add_lane_pair(const pts_lags *L, pts_acc *acc,
                                                                 const padded_cells *p, size_t i, size_t j,
                                                                 uint32_t k0, const uint32_t nk)
{
    double dx = p->x[j] - p->x[i], dy = p->y[j] - p->y[i], d2 = dx * dx + dy * dy, dz = p->z[j] - p->z[i];
    double adz = dz < 0.0 ? -dz : dz;
    int64_t ta = (int64_t)(adz * L->qa + 0.5), tb = (int64_t)(adz * adz * L->qb + 0.5);
    int64_t ts = (int64_t)(sqrt(d2) * L->qs + 0.5);
    /* the annulus (or annuli) holding the pair without a branch: its terms are added, others get 0 */
    for (uint32_t k = 0; k < nk; k++) {
        int64_t in = (d2 >= L->lo2[k0 + k]) & (d2 <= L->hi2[k0 + k]);
        pts_acc *q = &acc[k];
        q->a += (pts_i128)(ta & -in);
        q->b += (pts_i128)(tb & -in);
        q->s += (pts_i128)(ts & -in);
        q->c += (uint64_t)in;
    }
}

/* One thread's counters and buffers. */
typedef struct {
    pts_acc *acc;
    double *d2;     /* cell_pair: a row of squared separations */
    int32_t *bin;   /* and their bins */
    uint32_t *cand; /* the float screen's candidate pairs (i << 16 | j, indices within their cells) */
    int64_t *wide;  /* the vector exact test's sums: per lag WIDE_FIELDS x 8 lanes (see wide_flush) */
    uint64_t pending; /* candidates through the vector exact test since wide was last flushed */
} scratch;

/* The vector exact test adds each pair's terms t (int64, rounded as add_lane_pair rounds them) split in
 * two, t mod 2^32 (field LO) and t >> 32 (arithmetic shift, field HI), into 64-bit lanes per lag: fewer
 * than WIDE_FLUSH additions cannot overflow a lane, and Σt = Σlo + 2^32 Σhi exactly. wide_flush moves
 * the lanes into the 128-bit sums: the same integers as the scalar test adds, so the same counters. */
enum { W_ALO, W_AHI, W_BLO, W_BHI, W_SLO, W_SHI, W_C, WIDE_FIELDS };
#define WIDE_LANES 8
#define WIDE_FLUSH ((uint64_t)1 << 31)

static void wide_flush(scratch *w, size_t nlags)
{
    const pts_i128 two32 = (pts_i128)1 << 32;
    for (size_t k = 0; k < nlags; k++) {
        int64_t *v = w->wide + k * WIDE_FIELDS * WIDE_LANES;
        pts_acc *q = &w->acc[k];
        for (size_t l = 0; l < WIDE_LANES; l++) {
            q->a += (pts_i128)(uint64_t)v[W_ALO * WIDE_LANES + l] + (pts_i128)v[W_AHI * WIDE_LANES + l] * two32;
            q->b += (pts_i128)(uint64_t)v[W_BLO * WIDE_LANES + l] + (pts_i128)v[W_BHI * WIDE_LANES + l] * two32;
            q->s += (pts_i128)(uint64_t)v[W_SLO * WIDE_LANES + l] + (pts_i128)v[W_SHI * WIDE_LANES + l] * two32;
            q->c += (uint64_t)v[W_C * WIDE_LANES + l];
        }
        for (size_t f = 0; f < WIDE_FIELDS * WIDE_LANES; f++)
            v[f] = 0;
    }
    w->pending = 0;
}

typedef struct pair_job pair_job;
typedef void (*lane_fn)(const pair_job *, size_t, size_t, const lane_offset *, scratch *);

struct pair_job {
    const pts_grid *g;
    const padded_cells *p;
    const lane_offset *off;
    size_t noff;
    const pts_lags *L;
    const float *flo, *fspan; /* the float screen's annuli (float_annuli) */
    uint32_t few;             /* offsets meeting at most this many annuli take the lane screen */
    lane_fn lane[FEW_MAX + 1];
    lane_fn many;             /* the others, or NULL: the lookup-table screen (cell_pair) */
    /* the pairs inside a cell through a screen, or NULL: cell_self */
    void (*self)(const pair_job *, size_t, const lane_offset *, scratch *);
    lane_offset self_off; /* the offset (0, 0) with its annuli */
};

/* The real points of cell c in the padded arrays. */
static inline size_t padded_end(const pair_job *jb, size_t c)
{
    return jb->p->start[c] + (jb->g->start[c + 1] - jb->g->start[c]);
}

/* The lane screen without vector instructions. */
static void lane_pair_generic(const pair_job *jb, size_t a, size_t b, const lane_offset *off, scratch *w)
{
    pts_acc *acc = w->acc;
    const padded_cells *p = jb->p;
    const double *lo2 = jb->L->lo2 + off->k0, *hi2 = jb->L->hi2 + off->k0;
    for (size_t i = p->start[a]; i < padded_end(jb, a); i++)
        for (size_t j = p->start[b]; j < padded_end(jb, b); j++) {
            double dx = p->x[j] - p->x[i], dy = p->y[j] - p->y[i], d2 = dx * dx + dy * dy;
            int in = 0;
            for (uint32_t k = 0; k < off->nk; k++)
                in |= (d2 >= lo2[k]) & (d2 <= hi2[k]);
            if (in)
                add_lane_pair(jb->L, acc + off->k0, p, i, j, off->k0, off->nk);
        }
}

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define HAVE_X86_COPIES 1
#include <immintrin.h>

/* The lane screen, four pairs per AVX2 instruction in double precision (no FMA: d² is rounded as in
 * lane_pair_generic), nk annuli (a constant once inlined). */
__attribute__((target("avx2"))) static inline __attribute__((always_inline)) void
lane_body_avx2(const pair_job *jb, size_t a, size_t b, const lane_offset *off, scratch *w, const uint32_t nk)
{
    pts_acc *acc = w->acc;
    const padded_cells *p = jb->p;
    __m256d lo[FEW_MAX], hi[FEW_MAX];
    for (uint32_t k = 0; k < nk; k++) {
        lo[k] = _mm256_set1_pd(jb->L->lo2[off->k0 + k]);
        hi[k] = _mm256_set1_pd(jb->L->hi2[off->k0 + k]);
    }
    size_t j0 = p->start[b], j1 = p->start[b + 1];
    for (size_t i = p->start[a]; i < padded_end(jb, a); i++) {
        __m256d vx = _mm256_set1_pd(p->x[i]), vy = _mm256_set1_pd(p->y[i]);
        for (size_t j = j0; j < j1; j += 4) {
            __m256d dx = _mm256_sub_pd(_mm256_loadu_pd(p->x + j), vx);
            __m256d dy = _mm256_sub_pd(_mm256_loadu_pd(p->y + j), vy);
            __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
            __m256d in = _mm256_and_pd(_mm256_cmp_pd(d2, lo[0], _CMP_GE_OQ), _mm256_cmp_pd(d2, hi[0], _CMP_LE_OQ));
            for (uint32_t k = 1; k < nk; k++)
                in = _mm256_or_pd(in, _mm256_and_pd(_mm256_cmp_pd(d2, lo[k], _CMP_GE_OQ),
                                                    _mm256_cmp_pd(d2, hi[k], _CMP_LE_OQ)));
            for (unsigned bits = (unsigned)_mm256_movemask_pd(in); bits; bits &= bits - 1)
                add_lane_pair(jb->L, acc + off->k0, p, i, j + (unsigned)__builtin_ctz(bits), off->k0, nk);
        }
    }
}

/* Keeps the compiler from fusing the product v into a following addition (some compilers take AVX-512 to
 * imply FMA): each product is rounded on its own, as in the scalar test. */
#define NO_FUSE(v) __asm__("" : "+v"(v))

/* v[0..8) += x in the lanes of `in`. */
__attribute__((target("avx512f"))) static inline __attribute__((always_inline)) void
wide_add(int64_t *v, __mmask8 in, __m512i x)
{
    __m512i s = _mm512_loadu_si512(v);
    _mm512_storeu_si512(v, _mm512_mask_add_epi64(s, in, s, x));
}

/* One coordinate of the points of a cell, padded to at most 64: a table for permutes (no gathers, slow on
 * some processors). */
typedef struct {
    __m512d t[8];
} cell_table;

/* The table of a cell's npad values (npad <= 8 x rows, rows 2, 4 or 8; rows past npad are left as zeros). */
__attribute__((target("avx512f"))) static inline __attribute__((always_inline)) cell_table
table_load(const double *v, size_t npad, const int rows)
{
    cell_table c;
    for (int r = 0; r < 8; r++)
        c.t[r] = r < rows && (size_t)r * 8 < npad ? _mm512_loadu_pd(v + 8 * r) : _mm512_setzero_pd();
    return c;
}

/* The values at idx (< 8 x rows) of the table, or with rows = 0 gathered from v (masked to m). */
__attribute__((target("avx512f"))) static inline __attribute__((always_inline)) __m512d
table_get(const cell_table *c, const double *v, __m512i idx, __mmask8 m, const int rows)
{
    if (rows == 0)
        return _mm512_mask_i64gather_pd(_mm512_setzero_pd(), m, idx, v, 8);
    __m512d r = _mm512_permutex2var_pd(c->t[0], idx, c->t[1]);
    if (rows > 2) {
        __mmask8 b16 = _mm512_test_epi64_mask(idx, _mm512_set1_epi64(16));
        r = _mm512_mask_mov_pd(r, b16, _mm512_permutex2var_pd(c->t[2], idx, c->t[3]));
        if (rows > 4) {
            __m512d h = _mm512_permutex2var_pd(c->t[4], idx, c->t[5]);
            h = _mm512_mask_mov_pd(h, b16, _mm512_permutex2var_pd(c->t[6], idx, c->t[7]));
            r = _mm512_mask_mov_pd(r, _mm512_test_epi64_mask(idx, _mm512_set1_epi64(32)), h);
        }
    }
    return r;
}

/* The exact test of add_lane_pair on eight of the float screen's candidates cand[0..n) at once (i << 16 | j
 * as 32 bits, or with id16 i << 8 | j as 16 bits, within cells starting at i0 and j0, padded to at most
 * 8 x rows points, rows = 0: any size): the same d² = dx² + dy², the same annulus bounds, the same terms,
 * added into the thread's 64-bit lanes (wide_flush). */
__attribute__((target("avx512f,avx512dq"))) static inline __attribute__((always_inline)) void
candidates_body(const pts_lags *L, scratch *w, const padded_cells *p, size_t i0, size_t ni, size_t j0, size_t nj,
                const void *cand, size_t n, uint32_t k0, uint32_t nk, const int rows, const int id16)
{
    const __m512d qa = _mm512_set1_pd(L->qa), qb = _mm512_set1_pd(L->qb), qs = _mm512_set1_pd(L->qs);
    const __m512d half = _mm512_set1_pd(0.5);
    const __m512i low = _mm512_set1_epi64(0xffffffff), one = _mm512_set1_epi64(1);
    cell_table xa = {0}, ya = {0}, za = {0}, xb = {0}, yb = {0}, zb = {0};
    if (rows > 0) {
        xa = table_load(p->x + i0, ni, rows);
        ya = table_load(p->y + i0, ni, rows);
        za = table_load(p->z + i0, ni, rows);
        xb = table_load(p->x + j0, nj, rows);
        yb = table_load(p->y + j0, nj, rows);
        zb = table_load(p->z + j0, nj, rows);
    }
    for (size_t t = 0; t < n; t += 8) {
        /* lanes past n read stale entries of the buffer (it has sixteen to spare) and are masked off */
        __mmask8 m = n - t >= 8 ? (__mmask8)0xff : (__mmask8)((1u << (n - t)) - 1u);
        __m512i ii, jj;
        if (id16) {
            __m512i c = _mm512_cvtepu16_epi64(_mm_loadu_si128((const __m128i *)((const uint16_t *)cand + t)));
            ii = _mm512_srli_epi64(c, 8);
            jj = _mm512_and_si512(c, _mm512_set1_epi64(0xff));
        } else {
            __m512i c = _mm512_cvtepu32_epi64(_mm256_loadu_si256((const __m256i *)((const uint32_t *)cand + t)));
            ii = _mm512_srli_epi64(c, 16);
            jj = _mm512_and_si512(c, _mm512_set1_epi64(0xffff));
        }
        __m512d dx = _mm512_sub_pd(table_get(&xb, p->x + j0, jj, m, rows), table_get(&xa, p->x + i0, ii, m, rows));
        __m512d dy = _mm512_sub_pd(table_get(&yb, p->y + j0, jj, m, rows), table_get(&ya, p->y + i0, ii, m, rows));
        __m512d dz = _mm512_sub_pd(table_get(&zb, p->z + j0, jj, m, rows), table_get(&za, p->z + i0, ii, m, rows));
        __m512d sx = _mm512_mul_pd(dx, dx), sy = _mm512_mul_pd(dy, dy);
        NO_FUSE(sx);
        NO_FUSE(sy);
        __m512d d2 = _mm512_add_pd(sx, sy), adz = _mm512_abs_pd(dz);
        __m512d pa = _mm512_mul_pd(adz, qa), a2 = _mm512_mul_pd(adz, adz);
        NO_FUSE(pa);
        NO_FUSE(a2);
        __m512d pb = _mm512_mul_pd(a2, qb), ps = _mm512_mul_pd(_mm512_sqrt_pd(d2), qs);
        NO_FUSE(pb);
        NO_FUSE(ps);
        __m512i ta = _mm512_cvttpd_epi64(_mm512_add_pd(pa, half));
        __m512i tb = _mm512_cvttpd_epi64(_mm512_add_pd(pb, half));
        __m512i ts = _mm512_cvttpd_epi64(_mm512_add_pd(ps, half));
        __m512i alo = _mm512_and_si512(ta, low), ahi = _mm512_srai_epi64(ta, 32);
        __m512i blo = _mm512_and_si512(tb, low), bhi = _mm512_srai_epi64(tb, 32);
        __m512i slo = _mm512_and_si512(ts, low), shi = _mm512_srai_epi64(ts, 32);
        for (uint32_t k = 0; k < nk; k++) {
            __mmask8 in = _mm512_mask_cmp_pd_mask(
                _mm512_mask_cmp_pd_mask(m, d2, _mm512_set1_pd(L->lo2[k0 + k]), _CMP_GE_OQ), d2,
                _mm512_set1_pd(L->hi2[k0 + k]), _CMP_LE_OQ);
            int64_t *v = w->wide + (size_t)(k0 + k) * WIDE_FIELDS * WIDE_LANES;
            wide_add(v + W_ALO * WIDE_LANES, in, alo);
            wide_add(v + W_AHI * WIDE_LANES, in, ahi);
            wide_add(v + W_BLO * WIDE_LANES, in, blo);
            wide_add(v + W_BHI * WIDE_LANES, in, bhi);
            wide_add(v + W_SLO * WIDE_LANES, in, slo);
            wide_add(v + W_SHI * WIDE_LANES, in, shi);
            wide_add(v + W_C * WIDE_LANES, in, one);
        }
    }
    w->pending += n;
    if (w->pending >= WIDE_FLUSH)
        wide_flush(w, L->n);
}

/* candidates_body for cells of `ni` and `nj` padded points: from permute tables when both hold at most 64,
 * else gathered. */
__attribute__((target("avx512f,avx512dq"))) static inline __attribute__((always_inline)) void
candidates_sized(const pts_lags *L, scratch *w, const padded_cells *p, size_t i0, size_t ni, size_t j0, size_t nj,
                 const void *cand, size_t n, uint32_t k0, uint32_t nk, const int id16)
{
    size_t most = ni > nj ? ni : nj;
    if (most <= 16)
        candidates_body(L, w, p, i0, ni, j0, nj, cand, n, k0, nk, 2, id16);
    else if (most <= 32)
        candidates_body(L, w, p, i0, ni, j0, nj, cand, n, k0, nk, 4, id16);
    else if (most <= 64)
        candidates_body(L, w, p, i0, ni, j0, nj, cand, n, k0, nk, 8, id16);
    else
        candidates_body(L, w, p, i0, ni, j0, nj, cand, n, k0, nk, 0, id16);
}

/* The exact test of the candidates of one pair of cells, held as 32-bit or (id16) 16-bit indices. */
__attribute__((target("avx512f,avx512dq"))) static void
add_candidates_avx512(const pts_lags *L, scratch *w, const padded_cells *p, size_t i0, size_t ni, size_t j0,
                      size_t nj, const void *cand, size_t n, uint32_t k0, uint32_t nk, int id16)
{
    if (n == 0)
        return;
    if (id16)
        candidates_sized(L, w, p, i0, ni, j0, nj, cand, n, k0, nk, 1);
    else
        candidates_sized(L, w, p, i0, ni, j0, nj, cand, n, k0, nk, 0);
}

/* The float screen's test of row t: the lanes (points q, moved by the offset) whose d² less the first
 * annulus' lower bound, (|q|² - lo) + |p|² - 2 qx px - 2 qy py with p the row's point, falls in one of the nk
 * widened annuli (float_annuli), each compared as unsigned bits against its span (step: from the first
 * annulus' lower bound to the k-th's). */
__attribute__((target("avx512f"))) static inline __attribute__((always_inline)) __mmask16
row_keep(__m512 q2, __m512 xv, __m512 yv, const float *sm, const float *sa, const float *sb, size_t t,
         const __m512 *step, const __m512i *span, const float *flo, const float *fspan, const uint32_t nk)
{
    __m512 r = _mm512_add_ps(q2, _mm512_set1_ps(sm[t]));
    r = _mm512_fmadd_ps(xv, _mm512_set1_ps(sa[t]), r);
    r = _mm512_fmadd_ps(yv, _mm512_set1_ps(sb[t]), r);
    __mmask16 in = _mm512_cmple_epu32_mask(_mm512_castps_si512(r), nk <= FEW_MAX ? span[0] :
                                           _mm512_set1_epi32((int)float_bits(fspan[0])));
    if (nk <= FEW_MAX)
        for (uint32_t k = 1; k < nk; k++)
            in |= _mm512_cmple_epu32_mask(_mm512_castps_si512(_mm512_sub_ps(r, step[k])), span[k]);
    else
        for (uint32_t k = 1; k < nk; k++)
            in |= _mm512_cmple_epu32_mask(_mm512_castps_si512(_mm512_sub_ps(r, _mm512_set1_ps(flo[k] - flo[0]))),
                                          _mm512_set1_epi32((int)float_bits(fspan[k])));
    return in;
}

/* What both AVX-512 screens of a pair of cells share: sixteen points of one cell in the lanes, the other's
 * points in turn as rows, the cheaper way round (cells are padded to sixteen). The lanes hold b's points
 * moved by the offset, or (swap) a's moved back by it. */
typedef struct {
    const float *flo, *fspan;
    const float *vx, *vy;     /* the lanes' points */
    const float *sa, *sb, *sm; /* the rows': -2 x, -2 y, x² + y² */
    size_t i0, ni, vi, j0, nj, vj; /* first point, real and padded counts of a and b */
    size_t nv, ns;            /* padded lane points, real rows */
    int swap;
    __m512 ox, oy;
    __m512 step[FEW_MAX];  /* from the first annulus' lower bound to the k-th's */
    __m512i span[FEW_MAX]; /* as unsigned bits */
} screen_setup;

__attribute__((target("avx512f"))) static inline __attribute__((always_inline)) void
screen_begin(const pair_job *jb, size_t a, size_t b, const lane_offset *off, const uint32_t nk, screen_setup *s)
{
    const padded_cells *p = jb->p;
    s->flo = jb->flo + off->k0;
    s->fspan = jb->fspan + off->k0;
    for (uint32_t k = 0; k < nk && k < FEW_MAX; k++) {
        s->step[k] = _mm512_set1_ps(s->flo[k] - s->flo[0]);
        s->span[k] = _mm512_set1_epi32((int)float_bits(s->fspan[k]));
    }
    s->i0 = p->start[a];
    s->ni = padded_end(jb, a) - s->i0;
    s->j0 = p->start[b];
    s->nj = padded_end(jb, b) - s->j0;
    s->vi = p->start[a + 1] - s->i0; /* padded counts */
    s->vj = p->start[b + 1] - s->j0;
    int swap = s->nj * (s->vi / 16) < s->ni * (s->vj / 16);
    size_t lane0 = swap ? s->i0 : s->j0, row0 = swap ? s->j0 : s->i0;
    s->swap = swap;
    s->vx = p->fx + lane0;
    s->vy = p->fy + lane0;
    s->sa = p->fa + row0;
    s->sb = p->fb + row0;
    s->sm = p->fm + row0;
    s->nv = swap ? s->vi : s->vj;
    s->ns = swap ? s->nj : s->ni;
    s->ox = _mm512_set1_ps(swap ? -off->fx : off->fx);
    s->oy = _mm512_set1_ps(swap ? -off->fy : off->fy);
}

/* The float screen, sixteen pairs per AVX-512 instruction, against the widened annuli (float_annuli):
 * each sixteen points of one cell (moved by the offset) against every point of the other in turn, the
 * indices of the pairs it keeps packed into the thread's candidate list (i << 16 | j, 32 bits), which then
 * goes through the exact test (no branch per pair in the screen). */
__attribute__((target("avx512f"))) static inline __attribute__((always_inline)) void
lane_body_avx512f(const pair_job *jb, size_t a, size_t b, const lane_offset *off, scratch *w, const uint32_t nk)
{
    screen_setup s;
    screen_begin(jb, a, b, off, nk, &s);
    const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
    uint32_t *cand = w->cand;
    size_t n = 0;
    /* candidate = i << 16 | j, both within their cell (cells hold < 2^15 points here) */
    const __m512i lane_id = s.swap ? _mm512_slli_epi32(iota, 16) : iota;
    const __m512i next_s = _mm512_set1_epi32(s.swap ? 1 : 1 << 16);
    const __m512i next_v = _mm512_set1_epi32(s.swap ? 16 << 16 : 16);
    __m512i base = lane_id;
    for (size_t v = 0; v < s.nv; v += 16, base = _mm512_add_epi32(base, next_v)) {
        __m512 xv = _mm512_add_ps(_mm512_loadu_ps(s.vx + v), s.ox);
        __m512 yv = _mm512_add_ps(_mm512_loadu_ps(s.vy + v), s.oy);
        /* |q|² less the first annulus' lower bound, once per sixteen */
        __m512 q2 = _mm512_sub_ps(_mm512_fmadd_ps(xv, xv, _mm512_mul_ps(yv, yv)), _mm512_set1_ps(s.flo[0]));
        __m512i ij = base;
        for (size_t t = 0; t < s.ns; t++, ij = _mm512_add_epi32(ij, next_s)) {
            __mmask16 in = row_keep(q2, xv, yv, s.sm, s.sa, s.sb, t, s.step, s.span, s.flo, s.fspan, nk);
            _mm512_storeu_si512(cand + n, _mm512_maskz_compress_epi32(in, ij));
            n += (size_t)__builtin_popcount(in);
        }
    }
    add_candidates_avx512(jb->L, w, jb->p, s.i0, s.vi, s.j0, s.vj, cand, n, off->k0, nk, 0);
}

/* Lane l of a 32-word vector: l mod 16 (the point) and l / 16 (which of two rows). */
static const uint16_t lane_w[32] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,
                                    0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
static const uint16_t half_w[32] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
                                    1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};

/* The lanes l of sixteen from point v whose point v + l comes after point t of the same cell. */
static inline uint32_t lanes_after(size_t t, size_t v)
{
    size_t e = t + 1 > v ? t + 1 - v : 0;
    return e >= 16 ? 0u : (0xffffu << e) & 0xffffu;
}

/* The same screen two rows at a time with 16-bit candidates (i << 8 | j: cells of at most 256 points):
 * the two rows' masks joined, one 32-word compress and one store per two rows instead of one each per row
 * (AVX-512 BW and VBMI2). With self, a = b and off is (0, 0): only the pairs i < j of the cell. */
__attribute__((target("avx512f,avx512bw,avx512vbmi2"))) static inline __attribute__((always_inline)) void
lane_body_avx512w_pairs(const pair_job *jb, size_t a, size_t b, const lane_offset *off, scratch *w,
                        const uint32_t nk, const int self)
{
    screen_setup s;
    screen_begin(jb, a, b, off, nk, &s);
    uint16_t *cand = (uint16_t *)(void *)w->cand;
    size_t n = 0;
    const __m512i lw = _mm512_loadu_si512(lane_w), hw = _mm512_loadu_si512(half_w);
    /* lanes 0-15: row t, lanes 16-31: row t + 1 */
    __m512i base = s.swap ? _mm512_add_epi16(_mm512_slli_epi16(lw, 8), hw)
                          : _mm512_add_epi16(lw, _mm512_slli_epi16(hw, 8));
    const __m512i next_2s = _mm512_set1_epi16(s.swap ? 2 : 2 << 8);
    const __m512i next_v = _mm512_set1_epi16(s.swap ? 16 << 8 : 16);
    for (size_t v = 0; v < s.nv; v += 16, base = _mm512_add_epi16(base, next_v)) {
        __m512 xv = _mm512_add_ps(_mm512_loadu_ps(s.vx + v), s.ox);
        __m512 yv = _mm512_add_ps(_mm512_loadu_ps(s.vy + v), s.oy);
        __m512 q2 = _mm512_sub_ps(_mm512_fmadd_ps(xv, xv, _mm512_mul_ps(yv, yv)), _mm512_set1_ps(s.flo[0]));
        __m512i ij = base;
        size_t t = 0, ns = self && v + 15 < s.ns ? v + 15 : s.ns; /* self: rows past v + 14 have no j > i */
        for (; t + 1 < ns; t += 2, ij = _mm512_add_epi16(ij, next_2s)) {
            __mmask16 in0 = row_keep(q2, xv, yv, s.sm, s.sa, s.sb, t, s.step, s.span, s.flo, s.fspan, nk);
            __mmask16 in1 = row_keep(q2, xv, yv, s.sm, s.sa, s.sb, t + 1, s.step, s.span, s.flo, s.fspan, nk);
            if (self) {
                in0 &= (__mmask16)lanes_after(t, v);
                in1 &= (__mmask16)lanes_after(t + 1, v);
            }
            __mmask32 in = _mm512_kunpackw((__mmask32)in1, (__mmask32)in0);
            _mm512_storeu_si512(cand + n, _mm512_maskz_compress_epi16(in, ij));
            n += (size_t)__builtin_popcount(in);
        }
        if (t < ns) {
            __mmask32 in = row_keep(q2, xv, yv, s.sm, s.sa, s.sb, t, s.step, s.span, s.flo, s.fspan, nk);
            if (self)
                in &= lanes_after(t, v);
            _mm512_storeu_si512(cand + n, _mm512_maskz_compress_epi16(in, ij));
            n += (size_t)__builtin_popcount(in);
        }
    }
    add_candidates_avx512(jb->L, w, jb->p, s.i0, s.vi, s.j0, s.vj, cand, n, off->k0, nk, 1);
}

__attribute__((target("avx512f,avx512bw,avx512vbmi2"))) static inline __attribute__((always_inline)) void
lane_body_avx512w(const pair_job *jb, size_t a, size_t b, const lane_offset *off, scratch *w, const uint32_t nk)
{
    lane_body_avx512w_pairs(jb, a, b, off, w, nk, 0);
}

/* The pairs i < j inside cell c through the two-row screen (off: the offset (0, 0) with its annuli). */
__attribute__((target("avx512f,avx512bw,avx512vbmi2"))) static void
cell_self_avx512w(const pair_job *jb, size_t c, const lane_offset *off, scratch *w)
{
    lane_body_avx512w_pairs(jb, c, c, off, w, off->nk, 1);
}

#define LANE_FN(isa, tgt, n)                                                                                   \
    __attribute__((target(tgt))) static void lane_pair_##isa##_##n(const pair_job *jb, size_t a, size_t b,     \
                                                                   const lane_offset *off, scratch *w)          \
    {                                                                                                          \
        lane_body_##isa(jb, a, b, off, w, n);                                                                \
    }
#define LANE_TABLE(isa, tgt)                                                                                   \
    LANE_FN(isa, tgt, 1)                                                                                       \
    LANE_FN(isa, tgt, 2)                                                                                       \
    LANE_FN(isa, tgt, 3)                                                                                       \
    LANE_FN(isa, tgt, 4)                                                                                       \
    LANE_FN(isa, tgt, 5)                                                                                       \
    LANE_FN(isa, tgt, 6)                                                                                       \
    LANE_FN(isa, tgt, 7)                                                                                       \
    LANE_FN(isa, tgt, 8)                                                                                       \
    static const lane_fn lanes_##isa[FEW_MAX + 1] = {NULL,                 lane_pair_##isa##_1,                \
                                                     lane_pair_##isa##_2,  lane_pair_##isa##_3,                \
                                                     lane_pair_##isa##_4,  lane_pair_##isa##_5,                \
                                                     lane_pair_##isa##_6,  lane_pair_##isa##_7,                \
                                                     lane_pair_##isa##_8};
/* The float screen for offsets meeting more than FEW_MAX annuli (near the origin). */
#define LANE_MANY(isa, tgt)                                                                                    \
    __attribute__((target(tgt))) static void lane_pair_##isa##_many(const pair_job *jb, size_t a, size_t b,    \
                                                                    const lane_offset *off, scratch *w)         \
    {                                                                                                          \
        lane_body_##isa(jb, a, b, off, w, off->nk);                                                          \
    }
LANE_TABLE(avx2, "avx2")
LANE_TABLE(avx512f, "avx512f")
LANE_TABLE(avx512w, "avx512f,avx512bw,avx512vbmi2")
LANE_MANY(avx512f, "avx512f")
LANE_MANY(avx512w, "avx512f,avx512bw,avx512vbmi2")
#endif

/* The lane screen for this processor (and isa_limit) and cells of at most `most` points: its functions
 * per annulus count and the padding of its cells. */
static size_t pick_lanes(pair_job *jb, size_t most)
{
    for (int k = 0; k <= FEW_MAX; k++)
        jb->lane[k] = lane_pair_generic;
    jb->few = 4;
    jb->many = NULL;
    jb->self = NULL;
#ifdef HAVE_X86_COPIES
    const lane_fn *t = NULL;
    size_t pad = 1;
    /* the float screen's candidates hold indices within cells of at most `most` points as 15 bits, or as
     * 8 bits in the two-row screen */
    int avx512 = (isa_limit == ISA_BEST || isa_limit == ISA_AVX512_IDS32) && most + 16 < ((size_t)1 << 15) &&
                 __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
    if (avx512 && isa_limit == ISA_BEST && most <= 256 && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vbmi2")) {
        t = lanes_avx512w;
        jb->many = lane_pair_avx512w_many;
        jb->self = cell_self_avx512w;
        pad = 16;
    } else if (avx512) {
        t = lanes_avx512f;
        jb->many = lane_pair_avx512f_many;
        pad = 16;
    } else if ((isa_limit <= ISA_AVX2 || isa_limit == ISA_AVX512_IDS32) && __builtin_cpu_supports("avx2")) {
        t = lanes_avx2;
        pad = 4;
    }
    if (t != NULL) {
        for (int k = 1; k <= FEW_MAX; k++)
            jb->lane[k] = t[k];
        jb->few = FEW_MAX;
        return pad;
    }
#endif
    return 1;
}

static void one_cell(const pair_job *jb, size_t c, scratch *w)
{
    const pts_grid *g = jb->g;
    if (g->start[c] == g->start[c + 1])
        return;
    long cx = (long)(c % g->nx), cy = (long)(c / g->nx);
    if (pts_lags_meet(jb->L, 0.0, 2.0 * g->cell * g->cell * (1.0 + 1e-6))) {
        if (jb->self != NULL && jb->self_off.nk > 0)
            jb->self(jb, c, &jb->self_off, w);
        else
            cell_self(g, c, jb->L, w->acc);
    }
    for (size_t k = 0; k < jb->noff; k++) {
        const lane_offset *off = &jb->off[k];
        long bx = cx + off->ox, by = cy + off->oy;
        if (bx < 0 || by < 0 || bx >= (long)g->nx || by >= (long)g->ny)
            continue;
        size_t b = (size_t)by * g->nx + (size_t)bx;
        if (g->start[b] == g->start[b + 1])
            continue;
        if (off->nk <= jb->few)
            jb->lane[off->nk](jb, c, b, off, w);
        else if (jb->many != NULL)
            jb->many(jb, c, b, off, w);
        else
            cell_pair(g, c, b, jb->L, w->acc, w->d2, w->bin);
    }
}

/* Cell side: CELLS_PER_LAG cells across max lag + ε, but not so small that cells hold fewer than about
 * MIN_PER_CELL points on average. Every pair of cells has a fixed cost (dispatch, the screen's set-up, the
 * exact test's permute tables), which outweighs its rows: on 10^6 points 32 per cell ran about 8 % faster
 * than 16 (a quarter as many pairs of cells for 10 % more pairs screened), 24, 28 and 36 no better, 40
 * slower (cells over 64 points take gathers). */
static double cell_side(const ft_points *p, const pts_lags *L)
{
    double x0, y0, x1, y1;
    ft_points_bbox(p, &x0, &y0, &x1, &y1);
    double area = fmax(x1 - x0, 1e-300) * fmax(y1 - y0, 1e-300);
    double c = L->rmax / CELLS_PER_LAG, dense = sqrt(MIN_PER_CELL * area / (double)p->n);
    return c > dense ? c : fmin(dense, L->rmax);
}

static void scratch_free(scratch *w, int nt)
{
    for (int t = 0; w != NULL && t < nt; t++) {
        free(w[t].d2);
        free(w[t].bin);
        free(w[t].cand);
        free(w[t].wide);
    }
    free(w);
}

/* nt threads' buffers: rows of `most` points, candidate lists of most x (most padded to `lanes`) pairs
 * plus the sixteen a packed store may write past the last. */
static scratch *scratch_new(int nt, size_t most, size_t lanes, pts_acc *part, size_t nlags)
{
    scratch *w = ft_calloc((size_t)nt, sizeof *w);
    if (w == NULL)
        return NULL;
    size_t pairs = most * ((most + lanes - 1) / lanes * lanes) + 16;
    for (int t = 0; t < nt; t++) {
        w[t].acc = part + (size_t)t * nlags;
        w[t].d2 = ft_malloc(most * sizeof *w[t].d2);
        w[t].bin = ft_malloc(most * sizeof *w[t].bin);
        w[t].cand = ft_malloc(pairs * sizeof *w[t].cand);
        w[t].wide = ft_calloc(nlags * WIDE_FIELDS * WIDE_LANES, sizeof *w[t].wide);
        if (w[t].d2 == NULL || w[t].bin == NULL || w[t].cand == NULL || w[t].wide == NULL) {
            scratch_free(w, nt);
            return NULL;
        }
    }
    return w;
}

int pts_pairs_grid(const ft_points *p, const pts_lags *L, pts_acc *acc, ft_progress_fn fn, void *arg)
{
    pts_grid g;
    pts_offsets o = {NULL, NULL, 0};
    padded_cells pad = {0};
    pair_job jb = {0};
    lane_offset *off = NULL;
    float *flo = NULL, *fspan = NULL;
    scratch *w = NULL;
    int nt = omp_get_max_threads();
    pts_acc *part = ft_calloc((size_t)nt * L->n, sizeof *part);
    int rc = part ? pts_grid_build(&g, p, cell_side(p, L)) : FT_E_NOMEM;
    if (rc != FT_OK) {
        free(part);
        return rc;
    }
    size_t ncell = g.nx * g.ny, most = 1;
    for (size_t c = 0; c < ncell; c++)
        if (g.start[c + 1] - g.start[c] > most)
            most = g.start[c + 1] - g.start[c];
    size_t lanes = pick_lanes(&jb, most);
    rc = (w = scratch_new(nt, most, lanes, part, L->n)) != NULL ? pts_grid_offsets(&g, L, 1, &o) : FT_E_NOMEM;
    if (rc == FT_OK)
        rc = pad_cells(&g, lanes, &pad);
    if (rc == FT_OK)
        rc = float_annuli(&g, L, &flo, &fspan);
    if (rc == FT_OK && (off = lane_offsets(&g, &o, L)) == NULL)
        rc = FT_E_NOMEM;
    jb.g = &g;
    jb.self_off = lane_offset_of(&g, 0, 0, L);
    jb.p = &pad;
    jb.off = off;
    jb.noff = o.n;
    jb.L = L;
    jb.flo = flo;
    jb.fspan = fspan;
    for (size_t chunk = 0; rc == FT_OK && chunk < CHUNKS; chunk++) {
        size_t c0 = ncell * chunk / CHUNKS, c1 = ncell * (chunk + 1) / CHUNKS;
#pragma omp parallel for schedule(dynamic, 16)
        for (size_t c = c0; c < c1; c++)
            one_cell(&jb, c, &w[omp_get_thread_num()]);
        rc = ft_progress(fn, arg, (double)(chunk + 1) / CHUNKS, "pairs");
    }
    for (int t = 0; rc == FT_OK && t < nt; t++) {
        wide_flush(&w[t], L->n);
        pts_acc_merge(acc, part + (size_t)t * L->n, L->n);
    }
    pts_offsets_free(&o);
    padded_free(&pad);
    scratch_free(w, nt);
    free(off);
    free(flo);
    free(fspan);
    free(part);
    pts_grid_free(&g);
    return rc;
}
