/* fracterra — line/segment_index.c: an index of the segments of a set of chains whose vertices move during
 * a guarded pass (move_guard.c), and the contact test between two segments.
 *
 * Every vertex of a guarded pass ends on the straight line through its base and raw positions: somewhere
 * from base to raw (move_guard.c only shortens moves) or, in mirror mode, at base - (raw - base). So a
 * segment's every possible position lies in the bounding box of its two end points' base, raw (and mirror)
 * positions, its swept box, widened by 1e-9 of its largest coordinate against rounding. The segments are cut
 * into blocks of FT_SEGMENT_BLOCK consecutive segments of a chain (a chain is spatially coherent, so a
 * block's box is small) and every block b lists the blocks whose boxes meet its reach, the union of its box
 * and the next block's: a uniform grid over the block boxes (counting pass, prefix sums, filling pass from the
 * last block down); a query tests every entry of the cells its reach covers, branch-free, then sorts the few
 * found and drops the repeats of blocks filed in several of them. A vertex whose segments lie in b and the next block
 * sweeps only points of that reach, so every segment it may touch is in b's list: where a chain runs clear of
 * others, three or four blocks. Indexing blocks instead of segments makes the grid FT_SEGMENT_BLOCK times
 * smaller, and the guard then scans short runs of consecutive segments, in memory order. The fused
 * enhancement (dutton_guarded.c) makes the lists of its later passes from the pass before's instead
 * (ft_segment_blocks_join_carried: children of the parent's wide list, filtered; the same lists, no grid).
 *
 * Memory: the index is rebuilt every pass, and on a virtual machine fresh memory costs as much in the kernel
 * (page faults, clearing) as the joins in user time. So each thread writes the lists of a contiguous range of
 * blocks compactly into its own buffer, sized for the worst case but touched only as far as the lists go, and
 * the buffers are joined in block order (one thread: the buffer itself, shrunk): no per-block slots, no scratch
 * of every candidate, no second pass. The large arrays ask for transparent huge pages (ft_malloc_huge).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "line/segment_index.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define MAX_SPAN 1048576.0          /* cells along an axis: at most 2^20 */
#define MAX_CELLS_PER_BLOCK 4.0     /* the grid has at most about 4 nblock cells */

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

typedef struct {
    double x0, y0, inv;
    size_t nx, ny;
    uint32_t *start, *ids; /* the entries of cell k: ids[start[k] .. start[k + 1]) */
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

/* Files every block in the cells its box meets; entries of a cell in increasing block order (counted into
 * start[cell], summed to each cell's end, then filled from the last block down). */
static int grid_build(block_grid *G, const double *box, size_t nb)
{
    grid_frame(G, box, nb);
    size_t ncell = G->nx * G->ny, total = 0;
    G->start = ft_calloc_huge(ncell + 1, sizeof *G->start);
    if (G->start == NULL)
        return FT_E_NOMEM;
    for (size_t b = 0; b < nb; b++) {
        size_t r[4];
        cells_of(G, box + 4 * b, r);
        total += (r[2] - r[0] + 1) * (r[3] - r[1] + 1);
        if (total >= UINT32_MAX)
            return ft_error(FT_E_NOMEM, "segment index: more than 2^32 - 2 cell entries (%zu blocks)", nb);
        for (size_t cy = r[1]; cy <= r[3]; cy++)
            for (size_t cx = r[0]; cx <= r[2]; cx++)
                G->start[cy * G->nx + cx]++;
    }
    for (size_t k = 0; k < ncell; k++)
        G->start[k + 1] += G->start[k];
    G->ids = ft_malloc_huge((total ? total : 1) * sizeof *G->ids);
    if (G->ids == NULL)
        return FT_E_NOMEM;
    for (size_t b = nb; b-- > 0;) {
        size_t r[4];
        cells_of(G, box + 4 * b, r);
        for (size_t cy = r[1]; cy <= r[3]; cy++)
            for (size_t cx = r[0]; cx <= r[2]; cx++)
                G->ids[--G->start[cy * G->nx + cx]] = (uint32_t)b;
    }
    return FT_OK;
}

static void grid_free(block_grid *G)
{
    free(G->start);
    free(G->ids);
}

/* How many entries the cells rr hold: room for any query over them. */
static size_t cell_entries(const block_grid *G, const size_t rr[4])
{
    size_t k = 0;
    for (size_t cy = rr[1]; cy <= rr[3]; cy++)
        k += G->start[cy * G->nx + rr[2] + 1] - G->start[cy * G->nx + rr[0]];
    return k;
}

static inline int box_meets(const double *q, const double *r);

/* The blocks whose boxes meet reach (cell range rr), each once, in increasing order, written to out (room for
 * cell_entries); returns how many there are. Every entry of the cells is tested and appended branch-free (a
 * block filed in several of the cells comes once per cell), then the few found are sorted and the repeats
 * dropped. */
static size_t near_blocks(const block_grid *G, const double *box, const double *reach, const size_t rr[4],
                          uint32_t *out)
{
    size_t k = 0;
    for (size_t cy = rr[1]; cy <= rr[3]; cy++) {
        size_t row = cy * G->nx;
        for (uint32_t e = G->start[row + rr[0]], end = G->start[row + rr[2] + 1]; e < end; e++) {
            uint32_t m = G->ids[e];
            out[k] = m;
            k += (size_t)box_meets(box + 4 * (size_t)m, reach);
        }
    }
    for (size_t i = 1; i < k; i++) {
        uint32_t m = out[i];
        size_t j = i;
        for (; j > 0 && out[j - 1] > m; j--)
            out[j] = out[j - 1];
        out[j] = m;
    }
    size_t u = 0;
    for (size_t i = 0; i < k; i++)
        if (u == 0 || out[u - 1] != out[i])
            out[u++] = out[i];
    return u;
}

static inline void reach_of(const ft_segment_blocks *g, const ft_chain *const *base, const double *box, size_t b,
                            double reach[4])
{
    const double *p = box + 4 * b, *q = box + 4 * ft_segment_block_after(g, base, b);
    reach[0] = dmin(p[0], q[0]);
    reach[1] = dmin(p[1], q[1]);
    reach[2] = dmax(p[2], q[2]);
    reach[3] = dmax(p[3], q[3]);
}

static inline int box_meets(const double *q, const double *r)
{
    return !((q[2] < r[0]) | (q[0] > r[2]) | (q[3] < r[1]) | (q[1] > r[3])); /* near_blocks' test, no branch */
}

static void widen_by(double r[4], double s)
{
    r[0] -= s;
    r[1] -= s;
    r[2] += s;
    r[3] += s;
}

/* Packs per-block counts (start[b + 1]) into offsets; fails past 2^32 - 2 entries. */
static int pack_starts(uint32_t *start, size_t nb)
{
    size_t total = 0;
    for (size_t b = 0; b < nb; b++) {
        total += start[b + 1];
        if (total >= UINT32_MAX)
            return ft_error(FT_E_NOMEM, "segment index: more than 2^32 - 2 block pairs (%zu blocks)", nb);
        start[b + 1] = (uint32_t)total;
    }
    return FT_OK;
}

/* One thread's share of a join: blocks b0 .. b1, their near and wide lists back to back. */
typedef struct {
    size_t b0, b1;
    uint32_t *near, *wide;
    size_t nn, nw;
    int rc;
} list_part;

/* Inside a parallel region: this thread's part of blocks [0, nb), contiguous and in thread order; thread 0 sets
 * *nt to the threads running (fewer than asked: the others' parts stay empty). Returns the thread's number. */
static inline int thread_range(list_part *part, size_t nb, int *nt)
{
    int t = 0, used = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    used = omp_get_num_threads();
#endif
    if (t == 0)
        *nt = used;
    part[t].b0 = nb * (size_t)t / (size_t)used;
    part[t].b1 = nb * (size_t)(t + 1) / (size_t)used;
    return t;
}

/* The parts' lists joined into one array, in block order: the first part's buffer grown (no copy where the
 * allocator can remap it), the others copied after it. The parts' buffers are consumed. */
static uint32_t *lists_concat(list_part *part, int nt, int wide)
{
    size_t total = 0;
    for (int t = 0; t < nt; t++)
        total += wide ? part[t].nw : part[t].nn;
    uint32_t **buf0 = wide ? &part[0].wide : &part[0].near;
    uint32_t *all = ft_realloc_array(*buf0, total ? total : 1, sizeof *all);
    if (all == NULL)
        return NULL;
    *buf0 = NULL;
    size_t at = wide ? part[0].nw : part[0].nn;
    for (int t = 1; t < nt; t++) {
        uint32_t **buf = wide ? &part[t].wide : &part[t].near;
        size_t k = wide ? part[t].nw : part[t].nn;
        for (size_t j = 0; j < k; j++)
            all[at + j] = (*buf)[j];
        at += k;
        free(*buf);
        *buf = NULL;
    }
    return all;
}

/* Room for k more entries after at in *buf (capacity *cap), growing it by half again at least. */
static int list_room(uint32_t **buf, size_t *cap, size_t at, size_t k)
{
    if (at + k <= *cap)
        return FT_OK;
    size_t want = *cap + *cap / 2 > at + k ? *cap + *cap / 2 : at + k;
    uint32_t *p = ft_realloc_array(*buf, want, sizeof *p);
    if (p == NULL)
        return FT_E_NOMEM;
    *buf = p;
    *cap = want;
    return FT_OK;
}

/* The grid lists of blocks part->b0 .. b1 (reach widened by sigma), compactly into growing buffers: into
 * part->wide with want_wide (then part->near gets them filtered by the reach itself: the very lists of the
 * query with sigma = 0), else into part->near. The counts go to near_start / wide_start[b + 1]. */
static void join_range(const block_grid *G, const ft_segment_blocks *g, const ft_chain *const *base,
                       const double *box, double sigma, uint32_t *near_start, uint32_t *wide_start, list_part *part)
{
    size_t capn = 8 * (part->b1 - part->b0) + 64, capw = wide_start != NULL ? capn : 0, kn = 0, kw = 0;
    part->near = ft_malloc_huge(capn * sizeof *part->near);
    part->wide = wide_start != NULL ? ft_malloc_huge(capw * sizeof *part->wide) : NULL;
    if (part->near == NULL || (wide_start != NULL && part->wide == NULL)) {
        part->rc = FT_E_NOMEM;
        return;
    }
    for (size_t b = part->b0; b < part->b1; b++) {
        double reach[4], wr[4];
        size_t rr[4];
        reach_of(g, base, box, b, reach);
        for (int i = 0; i < 4; i++)
            wr[i] = reach[i];
        widen_by(wr, sigma);
        cells_of(G, wr, rr);
        size_t room = cell_entries(G, rr);
        uint32_t **qbuf = wide_start != NULL ? &part->wide : &part->near;
        size_t *qcap = wide_start != NULL ? &capw : &capn, *qk = wide_start != NULL ? &kw : &kn;
        if ((part->rc = list_room(qbuf, qcap, *qk, room)) != FT_OK)
            return;
        uint32_t *out = *qbuf + *qk;
        size_t k = near_blocks(G, box, wr, rr, out);
        *qk += k;
        if (wide_start == NULL) {
            near_start[b + 1] = (uint32_t)k;
            continue;
        }
        wide_start[b + 1] = (uint32_t)k;
        if ((part->rc = list_room(&part->near, &capn, kn, k + 1)) != FT_OK)
            return;
        out = part->wide + kw - k;
        size_t f = 0;
        for (size_t j = 0; j < k; j++) {
            part->near[kn + f] = out[j];
            f += (size_t)box_meets(box + 4 * (size_t)out[j], reach);
        }
        near_start[b + 1] = (uint32_t)f;
        kn += f;
    }
    part->nn = kn;
    part->nw = kw;
}

/* The near lists of every block, each block independently (any thread count gives the same lists), each
 * thread a contiguous range of blocks into its own buffers, joined in block order. With wide, the query is
 * the reach widened by sigma (wide's lists) and the near lists are those filtered by the reach itself. */
static int join(ft_segment_blocks *g, const ft_chain *const *base, const double *box, double sigma,
                ft_segment_wide *wide)
{
    size_t nb = g->nblock;
    block_grid G = {0};
    int rc = grid_build(&G, box, nb), nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    list_part *part = rc == FT_OK ? ft_calloc((size_t)nt, sizeof *part) : NULL;
    uint32_t *near_start = part != NULL ? ft_malloc_huge((nb + 1) * sizeof *near_start) : NULL;
    uint32_t *wide_start = near_start != NULL && wide != NULL ? ft_malloc_huge((nb + 1) * sizeof *wide_start) : NULL;
    if (rc == FT_OK && (near_start == NULL || (wide != NULL && wide_start == NULL)))
        rc = FT_E_NOMEM;
    if (rc == FT_OK) {
        near_start[0] = 0;
        if (wide_start != NULL)
            wide_start[0] = 0;
#pragma omp parallel num_threads(nt)
        {
            int t = thread_range(part, nb, &nt);
            join_range(&G, g, base, box, sigma, near_start, wide_start, &part[t]);
        }
        for (int t = 0; t < nt && rc == FT_OK; t++)
            rc = part[t].rc;
        if (rc != FT_OK)
            ft_error(FT_E_NOMEM, "segment index: out of memory for the near lists of %zu blocks", nb);
    }
    grid_free(&G);
    if (rc == FT_OK)
        rc = pack_starts(near_start, nb);
    if (rc == FT_OK && wide_start != NULL)
        rc = pack_starts(wide_start, nb);
    uint32_t *near = NULL, *wnear = NULL;
    if (rc == FT_OK && (near = lists_concat(part, nt, 0)) == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK && wide_start != NULL && (wnear = lists_concat(part, nt, 1)) == NULL)
        rc = FT_E_NOMEM;
    for (int t = 0; part != NULL && t < nt; t++) {
        free(part[t].near);
        free(part[t].wide);
    }
    free(part);
    g->near_start = near_start;
    g->near = near;
    if (wide != NULL) {
        wide->start = wide_start;
        wide->near = wnear;
        wide->sigma = sigma;
    }
    return rc;
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
    g->chain = ft_malloc_huge((nb ? nb : 1) * sizeof *g->chain);
    g->first = ft_malloc_huge((nb ? nb : 1) * sizeof *g->first);
    g->count = ft_malloc_huge((nb ? nb : 1) * sizeof *g->count);
    g->box = ft_malloc_huge((nb ? 4 * nb : 1) * sizeof *g->box);
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
    int rc = g->nblock > 0 ? join(g, chains, g->box, 0.0, NULL) : FT_OK;
    if (rc != FT_OK)
        ft_segment_blocks_free(g);
    return rc;
}

int ft_segment_blocks_join_wide(ft_segment_blocks *g, const ft_chain *const *chains, double sigma,
                                ft_segment_wide *wide)
{
    *wide = (ft_segment_wide){0};
    int rc = g->nblock > 0 ? join(g, chains, g->box, sigma, wide) : FT_OK;
    if (rc != FT_OK) {
        ft_segment_blocks_free(g);
        ft_segment_wide_free(wide);
    }
    return rc;
}

void ft_segment_wide_free(ft_segment_wide *w)
{
    free(w->start);
    free(w->near);
    *w = (ft_segment_wide){0};
}

/* ---- the near lists carried from the pass before --------------------------------------------------- */

/* Block b's parent: local block j of its chain comes from local block j / 2 of the same chain before. */
static inline size_t parent_of(const ft_segment_blocks *g, const ft_segment_blocks *prev, size_t b)
{
    uint32_t c = g->chain[b];
    return prev->chain_block[c] + (b - g->chain_block[c]) / 2;
}

/* How far any block's box sticks out of its parent's box (0 if inside), the largest over the blocks, and the
 * largest coordinate of any box (*m). */
static double largest_excess(const ft_segment_blocks *g, const ft_segment_blocks *prev, double *m)
{
    double e = 0.0, big = 0.0;
    long long nb = (long long)g->nblock;
#pragma omp parallel for schedule(static) reduction(max : e, big)
    for (long long b = 0; b < nb; b++) {
        const double *q = g->box + 4 * b, *p = prev->box + 4 * parent_of(g, prev, (size_t)b);
        double x = dmax(dmax(p[0] - q[0], p[1] - q[1]), dmax(q[2] - p[2], q[3] - p[3]));
        e = dmax(e, x);
        big = dmax(big, dmax(dmax(fabs(q[0]), fabs(q[1])), dmax(fabs(q[2]), fabs(q[3]))));
    }
    *m = big;
    return e;
}

/* A box against a reach, two lanes at a time: q meets r unless q0 > r2, q1 > r3, q2 < r0 or q3 < r1, the
 * last two as -q2 > -r0, -q3 > -r1 (negation is exact; NaN compares false either way): box_meets' test. */
#if defined(__GNUC__)
typedef double v2d __attribute__((vector_size(16)));
typedef long long v2l __attribute__((vector_size(16)));
typedef struct {
    v2d far, near; /* (r2, r3) and (-r0, -r1) */
} reach2;

static inline reach2 reach2_of(const double r[4])
{
    reach2 v = {{r[2], r[3]}, {-r[0], -r[1]}};
    return v;
}

static inline size_t meets2(v2d lo, v2d neg_hi, reach2 r)
{
    v2l m = (lo > r.far) | (neg_hi > r.near);
    return (size_t)((m[0] | m[1]) == 0);
}
#endif

/* The near lists (reach) and wide lists (reach widened by sigma, if wide is not NULL) of the k (1 or 2)
 * consecutive blocks b .. b + k - 1 of one parent, from the children of the parent's wide list, in increasing
 * order, in one scan of those children written branch-free: near and wide have room for cap = every child of
 * that list and one more per block; the second block's lists are written cap further on, then moved down to
 * follow the first's. Returns the counts. */
static void carried_lists(const ft_segment_blocks *g, const ft_chain *const *chains, const ft_segment_blocks *prev,
                          const ft_segment_wide *pw, double sigma, size_t b, size_t k, uint32_t *near,
                          uint32_t *wide, size_t nn[2], size_t nw[2])
{
    double reach[2][4], wr[2][4];
    for (size_t i = 0; i < k; i++) {
        reach_of(g, chains, g->box, b + i, reach[i]);
        for (int j = 0; j < 4; j++)
            wr[i][j] = reach[i][j];
        widen_by(wr[i], sigma);
    }
    if (k == 1) { /* a block with no sibling: the second lists test an empty reach, never met */
        for (int j = 0; j < 4; j++)
            reach[1][j] = wr[1][j] = j < 2 ? INFINITY : -INFINITY;
    }
    size_t P = parent_of(g, prev, b), cap = 2 * (size_t)(pw->start[P + 1] - pw->start[P]) + 1;
    size_t kn0 = 0, kn1 = 0, kw0 = 0, kw1 = 0;
    uint32_t *near1 = near + cap, *wide1 = wide != NULL ? wide + cap : NULL;
#if defined(__GNUC__)
    reach2 rn0 = reach2_of(reach[0]), rn1 = reach2_of(reach[1]), rw0 = reach2_of(wr[0]), rw1 = reach2_of(wr[1]);
#endif
    for (uint32_t e = pw->start[P]; e < pw->start[P + 1]; e++) {
        uint32_t Q = pw->near[e], c = prev->chain[Q];
        size_t d0 = g->chain_block[c] + 2 * (size_t)(Q - prev->chain_block[c]);
        size_t d1 = d0 + 2 < g->chain_block[c + 1] ? d0 + 2 : g->chain_block[c + 1];
        for (size_t d = d0; d < d1; d++) {
            const double *q = g->box + 4 * d;
#if defined(__GNUC__)
            v2d lo, hi;
            memcpy(&lo, q, sizeof lo);
            memcpy(&hi, q + 2, sizeof hi);
            hi = -hi;
            near[kn0] = (uint32_t)d;
            kn0 += meets2(lo, hi, rn0);
            near1[kn1] = (uint32_t)d;
            kn1 += meets2(lo, hi, rn1);
            if (wide != NULL) {
                wide[kw0] = (uint32_t)d;
                kw0 += meets2(lo, hi, rw0);
                wide1[kw1] = (uint32_t)d;
                kw1 += meets2(lo, hi, rw1);
            }
#else
            near[kn0] = (uint32_t)d;
            kn0 += (size_t)box_meets(q, reach[0]);
            near1[kn1] = (uint32_t)d;
            kn1 += (size_t)box_meets(q, reach[1]);
            if (wide != NULL) {
                wide[kw0] = (uint32_t)d;
                kw0 += (size_t)box_meets(q, wr[0]);
                wide1[kw1] = (uint32_t)d;
                kw1 += (size_t)box_meets(q, wr[1]);
            }
#endif
        }
    }
    memmove(near + kn0, near1, kn1 * sizeof *near);
    if (wide != NULL)
        memmove(wide + kw0, wide1, kw1 * sizeof *wide);
    nn[0] = kn0;
    nn[1] = kn1;
    nw[0] = kw0;
    nw[1] = kw1;
}

/* The lists of blocks part->b0 .. b1, written compactly into buffers sized for every child of their parents'
 * wide lists: only the pages the lists fill are touched. The counts go to near_start / wide_start[b + 1]. */
static void carried_range(const ft_segment_blocks *g, const ft_chain *const *chains, const ft_segment_blocks *prev,
                          const ft_segment_wide *pw, double sigma, uint32_t *near_start, uint32_t *wide_start,
                          list_part *part)
{
    size_t cap = 2;
    for (size_t b = part->b0; b < part->b1; b++) {
        size_t P = parent_of(g, prev, b);
        cap += 2 * (size_t)(pw->start[P + 1] - pw->start[P]) + 1;
    }
    part->near = ft_malloc_huge(cap * sizeof *part->near);
    part->wide = wide_start != NULL ? ft_malloc_huge(cap * sizeof *part->wide) : NULL;
    if (part->near == NULL || (wide_start != NULL && part->wide == NULL)) {
        part->rc = FT_E_NOMEM;
        return;
    }
    size_t kn = 0, kw = 0;
    for (size_t b = part->b0, k; b < part->b1; b += k) {
        size_t nn[2], nw[2];
        k = b + 1 < part->b1 && parent_of(g, prev, b + 1) == parent_of(g, prev, b) ? 2 : 1;
        carried_lists(g, chains, prev, pw, sigma, b, k, part->near + kn, part->wide ? part->wide + kw : NULL, nn, nw);
        for (size_t i = 0; i < k; i++) {
            near_start[b + i + 1] = (uint32_t)nn[i];
            kn += nn[i];
            if (wide_start != NULL) {
                wide_start[b + i + 1] = (uint32_t)nw[i];
                kw += nw[i];
            }
        }
    }
    part->nn = kn;
    part->nw = kw;
}

int ft_segment_blocks_join_carried(ft_segment_blocks *g, const ft_chain *const *chains,
                                   const ft_segment_blocks *prev, const ft_segment_wide *pw, int want_wide,
                                   ft_segment_wide *wide)
{
    size_t nb = g->nblock;
    *wide = (ft_segment_wide){0};
    if (pw->start == NULL || prev->nchain != g->nchain)
        return 1;
    for (size_t c = 0; c < g->nchain; c++) /* every chain's blocks twice its parent's (rounded) */
        if (g->chain_block[c + 1] - g->chain_block[c] != 2 * (prev->chain_block[c + 1] - prev->chain_block[c]) &&
            g->chain_block[c + 1] - g->chain_block[c] != 2 * (prev->chain_block[c + 1] - prev->chain_block[c]) - 1)
            return 1;
    double m, e = largest_excess(g, prev, &m);
    /* less the rounding of e and of the widening */
    double slack = pw->sigma - 2.0 * e * (1.0 + 1e-9) - 4.0 * FT_SEGMENT_WIDEN * m;
    if (!(slack >= 0.0))
        return 1; /* a block left its parent's box by more than the parents' lists allow for */
    double sigma = want_wide ? slack : -1.0;
    /* Each thread lists a contiguous range of blocks into its own buffers (only what the lists fill is
     * touched: no scratch of the size of every candidate), then the buffers are joined in block order. The
     * lists do not depend on the split. */
    int nt = 1;
#ifdef _OPENMP
    nt = omp_get_max_threads();
#endif
    list_part *part = ft_calloc((size_t)nt, sizeof *part);
    g->near_start = ft_malloc_huge((nb + 1) * sizeof *g->near_start);
    if (want_wide) {
        wide->start = ft_malloc_huge((nb + 1) * sizeof *wide->start);
        wide->sigma = sigma;
    }
    int rc = FT_OK;
    if (part == NULL || g->near_start == NULL || (want_wide && wide->start == NULL))
        rc = FT_E_NOMEM;
    if (rc == FT_OK) {
        g->near_start[0] = 0;
        if (want_wide)
            wide->start[0] = 0;
#pragma omp parallel num_threads(nt)
        {
            int t = thread_range(part, nb, &nt);
            carried_range(g, chains, prev, pw, sigma, g->near_start, want_wide ? wide->start : NULL, &part[t]);
        }
        for (int t = 0; t < nt && rc == FT_OK; t++)
            rc = part[t].rc;
        if (rc != FT_OK)
            ft_error(FT_E_NOMEM, "segment index: out of memory for the near lists of %zu blocks", nb);
    }
    if (rc == FT_OK)
        rc = pack_starts(g->near_start, nb);
    if (rc == FT_OK && want_wide)
        rc = pack_starts(wide->start, nb);
    if (rc == FT_OK && (g->near = lists_concat(part, nt, 0)) == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK && want_wide && (wide->near = lists_concat(part, nt, 1)) == NULL)
        rc = FT_E_NOMEM;
    for (int t = 0; part != NULL && t < nt; t++) {
        free(part[t].near);
        free(part[t].wide);
    }
    free(part);
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

void ft_segment_blocks_mark_local(const ft_segment_blocks *g, const ft_chain *const *chains, unsigned char *local)
{
    long long nb = (long long)g->nblock;
#pragma omp parallel for schedule(static)
    for (long long b = 0; b < nb; b++) {
        size_t k = (size_t)b / FT_GUARD_CHUNK, lo = k * FT_GUARD_CHUNK, hi = lo + FT_GUARD_CHUNK;
        uint32_t s = g->near_start[b], e = g->near_start[b + 1];
        /* The list is increasing: its ends tell whether it lies in the chunk. Then only a chunk's first block
         * and a chain's first block can have their first vertex owned outside it (the others: the block just
         * before, in the chunk). */
        unsigned char ok = e == s || (g->near[s] >= lo && g->near[e - 1] < hi);
        for (uint32_t j = s; j < e && ok; j++) {
            size_t m = g->near[j];
            if (m == lo || g->first[m] == 0)
                ok = ft_segment_block_before(g, chains, m) / FT_GUARD_CHUNK == k;
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
