/* fracterra — surface/points_pairs_sample.c: the counters of Arakawa & Krotkov §2.4 step 1 estimated from
 * P random pairs instead of all of them.
 *
 * A draw picks a point i uniformly among the N, then a partner j uniformly among the K_i other points of
 * the grid cells around i that can hold a partner on some lag (the candidates: a superset of the points
 * within max lag + ε). An ordered pair is thus drawn with probability 1 / (N K_i), and weighting the draw
 * by w = K_i makes every weighted sum an unbiased (Horvitz-Thompson) estimate of the sum over all
 * pairs: Σ_pairs f = N / (2P) · Σ_draws w f. The statistics are ratios of such sums (Σ w |Δz| / Σ w, ...),
 * whose standard errors follow by linearisation (points_counters.c). Draws come in blocks of BLOCK, each
 * with its own RNG stream (seed, block), and block sums are added in block order: the same seed gives
 * the same counters on any thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "points_internal.h"

#define BLOCK 4096
#define CELLS_PER_LAG 2
#define STREAM_POINTS_SAMPLE UINT64_C(0x5053000000000000)

/* The cell holding sorted point i: the last cell whose start is <= i. */
static size_t cell_of_index(const pts_grid *g, size_t i)
{
    size_t lo = 0, hi = g->nx * g->ny;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (g->start[mid] <= i)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The candidate cells of cell c: their indices into cells[], their total point count (point i excluded). */
static size_t candidates(const pts_grid *g, const pts_offsets *s, size_t c, size_t *cells, size_t *ncells)
{
    long cx = (long)(c % g->nx), cy = (long)(c / g->nx);
    size_t k = 0, total = 0;
    for (size_t m = 0; m < s->n; m++) {
        long bx = cx + s->ox[m], by = cy + s->oy[m];
        if (bx < 0 || by < 0 || bx >= (long)g->nx || by >= (long)g->ny)
            continue;
        size_t b = (size_t)by * g->nx + (size_t)bx;
        size_t cnt = g->start[b + 1] - g->start[b];
        if (cnt == 0)
            continue;
        cells[k++] = b;
        total += cnt;
    }
    *ncells = k;
    return total - 1;
}

/* The r-th candidate (0 <= r < K), skipping point i itself. */
static size_t pick(const pts_grid *g, const size_t *cells, size_t ncells, size_t i, size_t r)
{
    for (size_t m = 0; m < ncells; m++) {
        size_t b0 = g->start[cells[m]], cnt = g->start[cells[m] + 1] - b0;
        int has_i = i >= b0 && i < b0 + cnt;
        size_t avail = cnt - (size_t)has_i;
        if (r < avail) {
            size_t j = b0 + r;
            return has_i && j >= i ? j + 1 : j;
        }
        r -= avail;
    }
    return i; /* not reached: r < K */
}

/* Adds a draw of weight w to every lag whose annulus holds it (the exact test of pts_add_pair). */
static void add_draw(const pts_lags *L, pts_wsum *ws, double d2, double dz, double w)
{
    size_t b = pts_bin(L, d2);
    if (!L->bin_hit[b])
        return;
    double a = fabs(dz), d = sqrt(d2), w2 = w * w;
    for (size_t k = L->bin_first[b]; k < L->bin_first[b] + L->bin_count[b]; k++)
        if (d2 >= L->lo2[k] && d2 <= L->hi2[k]) {
            pts_wsum *s = &ws[k];
            s->w += w;
            s->wa += w * a;
            s->wa2 += w * a * a;
            s->wd += w * d;
            double t = w2;
            for (int e = 0; e < 5; e++, t *= a)
                s->v[e] += t;
            s->drawn++;
        }
}

static int sample_block(const pts_grid *g, const pts_offsets *s, const pts_lags *L, size_t block, size_t ndraw,
                        uint64_t seed, pts_wsum *ws, size_t *cells)
{
    ft_rng *r = ft_rng_create(seed, STREAM_POINTS_SAMPLE + block);
    if (r == NULL)
        return FT_E_NOMEM;
    size_t n = g->start[g->nx * g->ny];
    for (size_t t = 0; t < ndraw; t++) {
        size_t i = (size_t)ft_rng_uint(r, n), ncells = 0;
        size_t K = candidates(g, s, cell_of_index(g, i), cells, &ncells);
        if (K == 0)
            continue;
        size_t j = pick(g, cells, ncells, i, (size_t)ft_rng_uint(r, K));
        double dx = g->x[j] - g->x[i], dy = g->y[j] - g->y[i];
        add_draw(L, ws, dx * dx + dy * dy, g->z[j] - g->z[i], (double)K);
    }
    ft_rng_free(r);
    return FT_OK;
}

int pts_pairs_sample(const ft_points *p, const pts_lags *L, size_t sample, uint64_t seed, pts_wsum *ws,
                     ft_progress_fn fn, void *arg)
{
    pts_grid g;
    pts_offsets s = {NULL, NULL, 0};
    size_t nblocks = (sample + BLOCK - 1) / BLOCK;
    pts_wsum *part = ft_calloc(nblocks * L->n, sizeof *part);
    int rc = part ? pts_grid_build(&g, p, L->rmax / CELLS_PER_LAG) : FT_E_NOMEM;
    if (rc != FT_OK) {
        free(part);
        return rc;
    }
    rc = pts_grid_offsets(&g, L, 0, &s);
    int failed = 0;
    if (rc == FT_OK) {
#pragma omp parallel reduction(| : failed)
        {
            size_t *cells = malloc((s.n ? s.n : 1) * sizeof *cells);
            failed |= cells == NULL;
#pragma omp for schedule(dynamic, 1)
            for (size_t b = 0; b < nblocks; b++) {
                size_t nd = (b + 1) * BLOCK <= sample ? BLOCK : sample - b * BLOCK;
                if (cells != NULL)
                    failed |= sample_block(&g, &s, L, b, nd, seed, part + b * L->n, cells) != FT_OK;
            }
            free(cells);
        }
        if (failed)
            rc = ft_error(FT_E_NOMEM, "scattered points: out of memory while sampling pairs");
    }
    for (size_t b = 0; rc == FT_OK && b < nblocks; b++)
        for (size_t k = 0; k < L->n; k++) {
            const pts_wsum *q = &part[b * L->n + k];
            ws[k].w += q->w;
            ws[k].wa += q->wa;
            ws[k].wa2 += q->wa2;
            ws[k].wd += q->wd;
            for (int e = 0; e < 5; e++)
                ws[k].v[e] += q->v[e];
            ws[k].drawn += q->drawn;
        }
    if (rc == FT_OK)
        rc = ft_progress(fn, arg, 1.0, "pairs");
    pts_offsets_free(&s);
    free(part);
    pts_grid_free(&g);
    return rc;
}
