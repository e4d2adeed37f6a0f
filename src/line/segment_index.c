/* fracterra — line/segment_index.c: an index of the segments of a set of chains whose vertices move during
 * a guarded pass (move_guard.c), and the contact test between two segments.
 *
 * Every vertex of a guarded pass ends on the straight line through its base and raw positions: somewhere
 * from base to raw (move_guard.c only shortens moves) or, in mirror mode, at base - (raw - base). So a
 * segment's every possible position lies in the bounding box of its two end points' base, raw (and mirror)
 * positions, its swept box, widened by 1e-9 of its largest coordinate against rounding. The segments are cut
 * into blocks of FT_SEGMENT_BLOCK consecutive segments of a chain (a chain is spatially coherent, so a
 * block's box is small) and every block b lists the blocks whose boxes meet its reach, the union of its box
 * and the next block's: a uniform grid over the block boxes (counting pass, prefix sums, filling pass), each
 * pair found once, in the lowest cell the two share. A vertex whose segments lie in b and the next block
 * sweeps only points of that reach, so every segment it may touch is in b's list: where a chain runs clear of
 * others, three or four blocks. Indexing blocks instead of segments makes the grid FT_SEGMENT_BLOCK times
 * smaller, and the guard then scans short runs of consecutive segments, in memory order.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "line/segment_index.h"

#include <math.h>
#include <stdlib.h>

#define MAX_SPAN 1048576.0          /* cells along an axis: at most 2^20 */
#define MAX_CELLS_PER_BLOCK 4.0     /* the grid has at most about 4 nblock cells */
#define NEAR_SLOTS 8               /* near blocks kept per block in the first join pass */
#define WIDEN 1e-9                  /* swept boxes widened by this fraction of their largest coordinate */

static inline double dmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

/* ---- the block index ----------------------------------------------------------------------------- */

static void box_add(double box[4], double x, double y)
{
    box[0] = dmin(box[0], x);
    box[1] = dmin(box[1], y);
    box[2] = dmax(box[2], x);
    box[3] = dmax(box[3], y);
}

void ft_segment_box_widen(double box[4])
{
    double m = dmax(dmax(fabs(box[0]), fabs(box[1])), dmax(fabs(box[2]), fabs(box[3])));
    double w = WIDEN * m + 1e-300;
    box[0] -= w;
    box[1] -= w;
    box[2] += w;
    box[3] += w;
}

/* The widened swept box of block b. */
static void block_box(const ft_segment_blocks *g, const ft_chain *const *base, const ft_chain *const *raw, size_t b,
                      int mirror, double box[4])
{
    const ft_chain *bc = base[g->chain[b]], *rc = raw[g->chain[b]];
    size_t n = bc->n, v0 = g->first[b], v1 = v0 + g->count[b];
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (size_t v = v0; v <= v1; v++) {
        size_t i = v < n ? v : v - n; /* a ring's last segment ends at vertex 0 */
        double bx = bc->x[i], by = bc->y[i], rx = rc->x[i], ry = rc->y[i];
        box_add(box, bx, by);
        box_add(box, rx, ry);
        if (mirror)
            box_add(box, bx - (rx - bx), by - (ry - by));
    }
    ft_segment_box_widen(box);
}

/* The block after b along its chain (a ring's last: its first), or b itself at an open chain's end. */
static size_t next_block(const ft_segment_blocks *g, const ft_chain *const *base, size_t b)
{
    uint32_t c = g->chain[b];
    if (b + 1 < g->chain_block[c + 1])
        return b + 1;
    return base[c]->closed ? g->chain_block[c] : b;
}

typedef struct {
    double x0, y0, inv;
    size_t nx, ny;
    uint32_t *start, *ids, *range; /* range: the cell range of every block, 4 per block */
} block_grid;

static inline size_t clamp_cell(double v, size_t n)
{
    if (!(v > 0.0))
        return 0;
    return v >= (double)(n - 1) ? n - 1 : (size_t)v;
}

static void cells_of(const block_grid *G, const double *box, size_t c[4])
{
    c[0] = clamp_cell((box[0] - G->x0) * G->inv, G->nx);
    c[1] = clamp_cell((box[1] - G->y0) * G->inv, G->ny);
    c[2] = clamp_cell((box[2] - G->x0) * G->inv, G->nx);
    c[3] = clamp_cell((box[3] - G->y0) * G->inv, G->ny);
}

static void grid_frame(block_grid *G, const double *box, size_t nb)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, side = 0.0;
    for (size_t b = 0; b < nb; b++) {
        const double *q = box + 4 * b;
        x0 = dmin(x0, q[0]);
        y0 = dmin(y0, q[1]);
        x1 = dmax(x1, q[2]);
        y1 = dmax(y1, q[3]);
        side += dmax(q[2] - q[0], q[3] - q[1]);
    }
    double w = x1 - x0, h = y1 - y0;
    side = dmax(side / (double)nb, sqrt(w * h / (MAX_CELLS_PER_BLOCK * (double)nb)));
    side = dmax(side, dmax(w, h) / MAX_SPAN);
    if (!(side > 0.0))
        side = dmax(dmax(w, h), 1.0);
    G->x0 = x0;
    G->y0 = y0;
    G->inv = 1.0 / side;
    G->nx = (size_t)(w / side) + 1;
    G->ny = (size_t)(h / side) + 1;
}

/* Files every block in the cells its box meets; entries of a cell in increasing block order. */
static int grid_build(block_grid *G, const double *box, size_t nb)
{
    grid_frame(G, box, nb);
    size_t ncell = G->nx * G->ny, total = 0;
    G->start = ft_calloc(ncell + 1, sizeof *G->start);
    G->range = ft_malloc(4 * nb * sizeof *G->range);
    if (G->start == NULL || G->range == NULL)
        return FT_E_NOMEM;
    for (size_t b = 0; b < nb; b++) {
        size_t r[4];
        cells_of(G, box + 4 * b, r);
        for (int q = 0; q < 4; q++)
            G->range[4 * b + q] = (uint32_t)r[q];
        total += (r[2] - r[0] + 1) * (r[3] - r[1] + 1);
        if (total >= UINT32_MAX)
            return ft_error(FT_E_NOMEM, "segment index: more than 2^32 - 2 cell entries (%zu blocks)", nb);
        for (size_t cy = r[1]; cy <= r[3]; cy++)
            for (size_t cx = r[0]; cx <= r[2]; cx++)
                G->start[cy * G->nx + cx + 1]++;
    }
    for (size_t k = 0; k < ncell; k++)
        G->start[k + 1] += G->start[k];
    uint32_t *next = ft_malloc(ncell * sizeof *next);
    G->ids = ft_malloc((total ? total : 1) * sizeof *G->ids);
    if (next == NULL || G->ids == NULL) {
        free(next);
        return FT_E_NOMEM;
    }
    for (size_t k = 0; k < ncell; k++)
        next[k] = G->start[k];
    for (size_t b = 0; b < nb; b++) {
        const uint32_t *r = G->range + 4 * b;
        for (size_t cy = r[1]; cy <= r[3]; cy++)
            for (size_t cx = r[0]; cx <= r[2]; cx++)
                G->ids[next[cy * G->nx + cx]++] = (uint32_t)b;
    }
    free(next);
    return FT_OK;
}

static void grid_free(block_grid *G)
{
    free(G->start);
    free(G->ids);
    free(G->range);
}

/* The blocks whose boxes meet reach (cell range rr), each once: in the lowest cell it shares with the reach.
 * The first cap of them are written to out, in increasing order; returns how many there are. */
static size_t near_blocks(const block_grid *G, const double *box, const double *reach, const size_t rr[4],
                          uint32_t *out, size_t cap)
{
    size_t k = 0;
    for (size_t cy = rr[1]; cy <= rr[3]; cy++)
        for (size_t cx = rr[0]; cx <= rr[2]; cx++) {
            size_t cell = cy * G->nx + cx;
            for (uint32_t e = G->start[cell]; e < G->start[cell + 1]; e++) {
                uint32_t m = G->ids[e];
                const uint32_t *mr = G->range + 4 * (size_t)m;
                if (cx != (mr[0] > rr[0] ? mr[0] : rr[0]) || cy != (mr[1] > rr[1] ? mr[1] : rr[1]))
                    continue;
                const double *q = box + 4 * (size_t)m;
                if (q[2] < reach[0] || q[0] > reach[2] || q[3] < reach[1] || q[1] > reach[3])
                    continue;
                if (k < cap) {
                    size_t j = k;
                    while (j > 0 && out[j - 1] > m) {
                        out[j] = out[j - 1];
                        j--;
                    }
                    out[j] = m;
                }
                k++;
            }
        }
    return k;
}

static void reach_of(const ft_segment_blocks *g, const ft_chain *const *base, const double *box, size_t b,
                     double reach[4])
{
    const double *p = box + 4 * b, *q = box + 4 * next_block(g, base, b);
    reach[0] = dmin(p[0], q[0]);
    reach[1] = dmin(p[1], q[1]);
    reach[2] = dmax(p[2], q[2]);
    reach[3] = dmax(p[3], q[3]);
}

/* The near lists of every block, each block independently (any thread count gives the same lists): into
 * NEAR_SLOTS slots per block, then packed; the few blocks with more are listed again in their packed place. */
static int join(ft_segment_blocks *g, const ft_chain *const *base, const double *box)
{
    size_t nb = g->nblock;
    block_grid G = {0};
    int rc = grid_build(&G, box, nb);
    uint32_t *slots = rc == FT_OK ? ft_malloc(NEAR_SLOTS * nb * sizeof *slots) : NULL;
    g->near_start = slots != NULL ? ft_calloc(nb + 1, sizeof *g->near_start) : NULL;
    if (g->near_start == NULL) {
        free(slots);
        grid_free(&G);
        return rc == FT_OK ? FT_E_NOMEM : rc;
    }
    long long nbl = (long long)nb;
#pragma omp parallel for schedule(dynamic, 1024)
    for (long long b = 0; b < nbl; b++) {
        double reach[4];
        size_t rr[4];
        reach_of(g, base, box, (size_t)b, reach);
        cells_of(&G, reach, rr);
        g->near_start[b + 1] = (uint32_t)near_blocks(&G, box, reach, rr, slots + NEAR_SLOTS * b, NEAR_SLOTS);
    }
    size_t total = 0;
    for (size_t b = 0; b < nb; b++) {
        total += g->near_start[b + 1];
        if (total >= UINT32_MAX) {
            free(slots);
            grid_free(&G);
            return ft_error(FT_E_NOMEM, "segment index: more than 2^32 - 2 block pairs (%zu blocks)", nb);
        }
        g->near_start[b + 1] = (uint32_t)total;
    }
    g->near = ft_malloc((total ? total : 1) * sizeof *g->near);
    if (g->near == NULL) {
        free(slots);
        grid_free(&G);
        return FT_E_NOMEM;
    }
#pragma omp parallel for schedule(static)
    for (long long b = 0; b < nbl; b++) {
        size_t k = g->near_start[b + 1] - g->near_start[b];
        uint32_t *out = g->near + g->near_start[b];
        if (k <= NEAR_SLOTS) {
            for (size_t j = 0; j < k; j++)
                out[j] = slots[NEAR_SLOTS * b + j];
        } else {
            double reach[4];
            size_t rr[4];
            reach_of(g, base, box, (size_t)b, reach);
            cells_of(&G, reach, rr);
            near_blocks(&G, box, reach, rr, out, k);
        }
    }
    free(slots);
    grid_free(&G);
    return FT_OK;
}

int ft_segment_blocks_layout(ft_segment_blocks *g, const ft_chain *const *chains, size_t n, size_t per_block)
{
    *g = (ft_segment_blocks){0};
    size_t nseg = 0, nb = 0;
    for (size_t c = 0; c < n; c++) {
        size_t ns = ft_chain_segments(chains[c]);
        nseg += ns;
        nb += (ns + per_block - 1) / per_block;
    }
    if (nseg >= UINT32_MAX || n >= UINT32_MAX)
        return ft_error(FT_E_NOMEM, "segment index: %zu segments in %zu chains (at most 2^32 - 2)", nseg, n);
    g->nblock = nb;
    g->nchain = n;
    g->chain_block = ft_malloc((n + 1) * sizeof *g->chain_block);
    g->chain = ft_malloc((nb ? nb : 1) * sizeof *g->chain);
    g->first = ft_malloc((nb ? nb : 1) * sizeof *g->first);
    g->count = ft_malloc((nb ? nb : 1) * sizeof *g->count);
    g->box = ft_malloc((nb ? 4 * nb : 1) * sizeof *g->box);
    if (g->chain_block == NULL || g->chain == NULL || g->first == NULL || g->count == NULL || g->box == NULL) {
        ft_segment_blocks_free(g);
        return FT_E_NOMEM;
    }
    size_t b = 0;
    for (size_t c = 0; c < n; c++) {
        g->chain_block[c] = (uint32_t)b;
        for (size_t s = 0, ns = ft_chain_segments(chains[c]); s < ns; s += per_block, b++) {
            g->chain[b] = (uint32_t)c;
            g->first[b] = (uint32_t)s;
            g->count[b] = (uint8_t)(ns - s < per_block ? ns - s : per_block);
        }
    }
    g->chain_block[n] = (uint32_t)b;
    return FT_OK;
}

int ft_segment_blocks_join(ft_segment_blocks *g, const ft_chain *const *chains)
{
    int rc = g->nblock > 0 ? join(g, chains, g->box) : FT_OK;
    if (rc != FT_OK)
        ft_segment_blocks_free(g);
    return rc;
}

int ft_segment_blocks_build(ft_segment_blocks *g, const ft_chain *const *base, const ft_chain *const *raw, size_t n,
                            int mirror)
{
    int rc = ft_segment_blocks_layout(g, base, n, FT_SEGMENT_BLOCK);
    if (rc != FT_OK)
        return rc;
    long long nbl = (long long)g->nblock;
#pragma omp parallel for schedule(static)
    for (long long k = 0; k < nbl; k++)
        block_box(g, base, raw, (size_t)k, mirror, g->box + 4 * k);
    return ft_segment_blocks_join(g, base);
}

/* The owner of block m's first vertex: the block before it, or at a chain's start m itself (open) or the
 * chain's last block (ring). Every other vertex of m's segments is owned by m. */
static size_t first_vertex_owner(const ft_segment_blocks *g, const ft_chain *const *chains, size_t m)
{
    uint32_t c = g->chain[m];
    if (m > g->chain_block[c])
        return m - 1;
    return chains[c]->closed ? g->chain_block[c + 1] - 1 : m;
}

void ft_segment_blocks_mark_local(const ft_segment_blocks *g, const ft_chain *const *chains, unsigned char *local)
{
    long long nb = (long long)g->nblock;
#pragma omp parallel for schedule(static)
    for (long long b = 0; b < nb; b++) {
        size_t k = (size_t)b / FT_GUARD_CHUNK;
        unsigned char ok = 1;
        for (uint32_t e = g->near_start[b]; e < g->near_start[b + 1] && ok; e++) {
            size_t m = g->near[e];
            ok = m / FT_GUARD_CHUNK == k && first_vertex_owner(g, chains, m) / FT_GUARD_CHUNK == k;
        }
        local[b] = ok;
    }
}

void ft_segment_blocks_free(ft_segment_blocks *g)
{
    free(g->chain);
    free(g->first);
    free(g->chain_block);
    free(g->near_start);
    free(g->near);
    free(g->count);
    free(g->box);
    *g = (ft_segment_blocks){0};
}
