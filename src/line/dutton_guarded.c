/* fracterra — line/dutton_guarded.c: one pass of Dutton's (1981) enhancement (dutton.c) with the crossing
 * guard fused into it, over a set of chains (one chain, or every part or arc of a layer).
 *
 * The guard's rule is move_guard.c's: the pass starts from its base geometry (the input's vertices and the
 * midpoints of its split segments, i.e. the input's own lines) and visits the moved vertices; vertex v goes
 * from V0 (its input position) towards its raw position V (dutton.c) by the first t of 1, 1/2, 1/4 for which
 * the move sweeps no other segment of the set (ft_move_sweeps: contact with the new segments or the path,
 * an end point inside the swept triangles), else stays. What the fusion saves is the memory and the
 * index: Dutton's midpoints never move, so the two neighbours of a moved vertex are fixed points, and every
 * output segment of input segment s (from V_s to M_s, from M_s to V_s+1) stays in the bounding box of V_s,
 * V_s+1 and their raw positions. So the index is built on the input's segments (half as many blocks as the
 * output's), from positions computed on the fly; the output chain is written once with the base geometry
 * and the walk moves its vertices in place: no base chain, no raw chain. The raw positions are computed
 * where they are read, a run of blocks at a time (run_raw): for the boxes, then again in the walk, into a
 * buffer of the thread's that stays in the cache. A buffer of every raw position kept through the pass (and
 * from pass to pass with the carry, sessions 10-11) cost more in page faults and memory traffic (and its
 * growth by realloc a copy in repeated calls) than the second computation, ~1 ns a vertex (dutton_raw.c).
 *
 * From the second pass on, the near lists come from the pass before's index (ft_dutton_carry,
 * ft_segment_blocks_join_carried) instead of a grid: where every segment was split and nothing was dropped,
 * local block j of a chain is made of the output of local block j / 2 before, so its box lies in that
 * parent's box widened by the largest excess E of the pass (measured, not assumed); a pass's lists are kept
 * also for the reach widened by a slack sigma, and if 2 E fits in sigma every block near a child is a child
 * of its parent's wide list: filtered by the reach, the very lists of the grid join, so the same bits. The
 * slack is guessed from the pass's largest move (carry_slack); a pass whose blocks left their parents' boxes
 * by more joins on the grid.
 *
 * Order and threads, as in move_guard.c: blocks of FT_SEGMENT_BLOCK / 2 input segments (when every segment
 * is split, the very blocks of FT_SEGMENT_BLOCK output segments that move_guard.c cuts), chunks of
 * FT_GUARD_CHUNK blocks; the vertices of the blocks whose near lists stay within their chunk are walked chunk
 * by chunk in parallel, each chunk in vertex order, then the others in chain and vertex order (in parallel
 * groups that touch no other group's vertices: guard_schedule.c, the same bits as serially). The
 * order depends on the data only: the same bits on any thread count. Where every segment is split (the
 * default window) and the boxes give the same near lists, it is move_guard.c's order, and the result its
 * bits (checked on the bench chain); where not, two competing moves may be settled the other way, with the
 * same guarantee (the output has a contact only where the input had one).
 *
 * The two segments next to the moved vertex's own (they share its fixed neighbours) are cleared first by a
 * hull test (ft_leaves_hull: the segment leaves the hull of the move at the shared point), which decides
 * nearly every case; what it cannot clear is tested with the other segments.
 *
 * The scan of the near blocks is a screen: per walked block its near list's boxes are copied side by side
 * (near_cache), a move's box is compared with eight block boxes, then with the boxes of a hit block's (at most
 * eight) output segments, at a time (AVX-512 where the processor has it, the same comparisons in plain C
 * elsewhere), and only the segments left get the exact test: the same candidates as a segment-by-segment scan,
 * so the same bits (test_screens_same_bits).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "line/dutton_internal.h"
#include "line/guard_schedule.h"
#include "line/segment_contact.h"
#include "line/segment_index.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SCREEN_AVX512 1
#else
#define SCREEN_AVX512 0
#endif

#define FUSED_BLOCK (FT_SEGMENT_BLOCK / 2) /* input segments per block: the output's FT_SEGMENT_BLOCK, as move_guard.c */
#define RAW_BLOCKS 256 /* blocks per run of raw positions (ft_dutton_raw_run: several vertices at a time) */
#define RAW_RUN (RAW_BLOCKS * FUSED_BLOCK + 1) /* the vertices of a run of blocks, its end vertex included */

/* One chain of the pass: the input the pass works on (densified or not), its split flags, its output. */
typedef struct {
    const ft_chain *in;
    ft_chain *dense; /* owned; NULL if in is the caller's chain */
    unsigned char *split;
    ft_chain *out;
    int all_split; /* every segment split: output segment s comes from input segment s / 2 */
} pass_chain;

typedef struct {
    pass_chain *pc;
    ft_segment_blocks g; /* blocks of the input segments */
    uint32_t *ofirst;    /* per block: the output index of its first vertex */
    ft_dutton_pass_params pp;
} fused;

static inline double dmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

static inline void box_add(double box[4], double x, double y)
{
    box[0] = dmin(box[0], x);
    box[1] = dmin(box[1], y);
    box[2] = dmax(box[2], x);
    box[3] = dmax(box[3], y);
}

/* The raw positions (x, y) of the vertices of blocks [lo, hi) of one chain, the last block's end vertex
 * included (a ring's vertex n: its vertex 0), into xy from the first block's first vertex: a vertex that
 * stays keeps its input position. Computed where they are read, a run of blocks at a time (the boxes, then
 * the walk again): ~1 ns a vertex (ft_dutton_raw_run), less than the page faults and the memory traffic of
 * a buffer of them kept through the pass. */
static void run_raw(const fused *F, size_t lo, size_t hi, double *xy)
{
    const ft_segment_blocks *g = &F->g;
    const pass_chain *p = &F->pc[g->chain[lo]];
    size_t n = p->in->n, v0 = g->first[lo], v1 = g->first[hi - 1] + g->count[hi - 1];
    ft_dutton_raw_run(p->in, p->split, &F->pp, v0, v1 < n ? v1 + 1 : n, xy);
    if (v1 == n)
        (void)ft_dutton_raw_vertex(p->in, p->split, &F->pp, 0, &xy[2 * (n - v0)], &xy[2 * (n - v0) + 1]);
}

/* The widened box of block b's input vertices and their raw positions (raw: from its first vertex's, run_raw);
 * returns the largest move of its vertices along an axis. */
static double block_box(const fused *F, size_t b, const double *raw, double box[4])
{
    double move = 0.0;
    const ft_segment_blocks *g = &F->g;
    const pass_chain *p = &F->pc[g->chain[b]];
    size_t n = p->in->n, v0 = g->first[b], v1 = v0 + g->count[b];
    box[0] = box[1] = INFINITY;
    box[2] = box[3] = -INFINITY;
    for (size_t v = v0; v <= v1; v++) {
        size_t i = v < n ? v : v - n;
        const double *r = raw + 2 * (v - v0);
        box_add(box, p->in->x[i], p->in->y[i]);
        box_add(box, r[0], r[1]);
        move = dmax(move, dmax(fabs(r[0] - p->in->x[i]), fabs(r[1] - p->in->y[i])));
    }
    ft_segment_box_widen(box);
    return move;
}

/* Block b's output with no move: its vertices at their input positions, each split segment's midpoint after
 * its first vertex; an open chain's last block writes the last vertex too. */
static void emit_base(const fused *F, size_t b)
{
    const ft_segment_blocks *g = &F->g;
    const pass_chain *p = &F->pc[g->chain[b]];
    const ft_chain *in = p->in;
    size_t n = in->n, v0 = g->first[b], v1 = v0 + g->count[b], k = F->ofirst[b];
    double *ox = p->out->x, *oy = p->out->y;
    for (size_t v = v0; v < v1; v++) {
        size_t j = v + 1 < n ? v + 1 : 0;
        ox[k] = in->x[v];
        oy[k] = in->y[v];
        k++;
        if (p->split[v]) {
            ox[k] = 0.5 * (in->x[v] + in->x[j]);
            oy[k] = 0.5 * (in->y[v] + in->y[j]);
            k++;
        }
    }
    if (!in->closed && v1 == n - 1) {
        ox[k] = in->x[v1];
        oy[k] = in->y[v1];
    }
}

/* The boxes of blocks [lo, hi) (g->box) and their base output, their raw positions a run of one chain's blocks
 * at a time; returns the largest move. */
static double range_boxes(fused *F, size_t lo, size_t hi)
{
    double xy[2 * RAW_RUN], move = 0.0;
    const ft_segment_blocks *g = &F->g;
    for (size_t b = lo, e; b < hi; b = e) {
        uint32_t c = g->chain[b];
        e = g->chain_block[c + 1] < hi ? g->chain_block[c + 1] : hi;
        run_raw(F, b, e, xy);
        for (size_t k = b; k < e; k++) {
            move = dmax(move, block_box(F, k, xy + 2 * (g->first[k] - g->first[b]), F->g.box + 4 * k));
            emit_base(F, k);
        }
    }
    return move;
}

/* The box test of ft_move_sweeps for the cnt (1..8) segments from s0 of x, y (segment s: vertex s to s + 1,
 * none wrapping round a ring), eight at a time: bit i is set when segment s0 + i's box meets box (the same
 * comparisons, so the same segments as the scalar test). */
static inline unsigned screen_c(const double *x, const double *y, size_t s0, size_t cnt, const double box[4])
{
    unsigned hit = 0;
    for (size_t i = 0; i < cnt; i++) {
        double p0 = x[s0 + i], p1 = y[s0 + i], p2 = x[s0 + i + 1], p3 = y[s0 + i + 1];
        int out = (ft_cmax(p0, p2) < box[0]) | (ft_cmin(p0, p2) > box[2]) | (ft_cmax(p1, p3) < box[1]) |
                  (ft_cmin(p1, p3) > box[3]);
        hit |= (unsigned)!out << i;
    }
    return hit;
}

#if SCREEN_AVX512
__attribute__((target("avx512f"))) static inline unsigned screen_avx512(const double *x, const double *y, size_t s0,
                                                                       size_t cnt, const double box[4])
{
    __mmask8 k = (__mmask8)((1u << cnt) - 1u); /* masked loads: nothing read past the block's last vertex */
    __m512d x0 = _mm512_maskz_loadu_pd(k, x + s0), x1 = _mm512_maskz_loadu_pd(k, x + s0 + 1);
    __m512d y0 = _mm512_maskz_loadu_pd(k, y + s0), y1 = _mm512_maskz_loadu_pd(k, y + s0 + 1);
    /* max_pd / min_pd return their second operand when unordered, as ft_cmax / ft_cmin do */
    __mmask8 out = _mm512_cmp_pd_mask(_mm512_max_pd(x0, x1), _mm512_set1_pd(box[0]), _CMP_LT_OQ);
    out |= _mm512_cmp_pd_mask(_mm512_min_pd(x0, x1), _mm512_set1_pd(box[2]), _CMP_GT_OQ);
    out |= _mm512_cmp_pd_mask(_mm512_max_pd(y0, y1), _mm512_set1_pd(box[1]), _CMP_LT_OQ);
    out |= _mm512_cmp_pd_mask(_mm512_min_pd(y0, y1), _mm512_set1_pd(box[3]), _CMP_GT_OQ);
    return (unsigned)(k & (__mmask8)~out);
}
#endif

typedef unsigned (*screen_fn)(const double *, const double *, size_t, size_t, const double *);

/* The near list of the block whose moves are walked, its blocks' boxes copied side by side (x0, y0, x1, y1 of
 * entry j at box[0..3][j], padded to a multiple of 8 with boxes that meet nothing), so that a move screens
 * eight blocks at a time. A list longer than NEAR_MAX is not copied (n = SIZE_MAX): read from the index. */
#define NEAR_MAX 64
typedef struct {
    size_t n;
    uint32_t m[NEAR_MAX];
    double box[4][NEAR_MAX] __attribute__((aligned(64)));
} near_cache;

static inline __attribute__((always_inline)) void near_fill(const ft_segment_blocks *g, size_t nb, near_cache *nc)
{
    uint32_t e0 = g->near_start[nb], n = g->near_start[nb + 1] - e0;
    if (n > NEAR_MAX) {
        nc->n = SIZE_MAX;
        return;
    }
    nc->n = n;
    for (uint32_t j = 0; j < n; j++) {
        uint32_t m = g->near[e0 + j];
        const double *q = g->box + 4 * (size_t)m;
        nc->m[j] = m;
        for (int k = 0; k < 4; k++)
            nc->box[k][j] = q[k];
    }
    for (uint32_t j = n; j % 8 != 0; j++) { /* padding: a box no box meets */
        nc->box[0][j] = nc->box[1][j] = INFINITY;
        nc->box[2][j] = nc->box[3][j] = -INFINITY;
    }
}

/* Bit j set when near entry j's block box meets box (the block test of the scalar scan: q[2] < box[0] ... ). */
static inline uint64_t near_screen_c(const near_cache *nc, const double box[4])
{
    uint64_t hit = 0;
    for (size_t j = 0; j < nc->n; j++) {
        int out = (nc->box[2][j] < box[0]) | (nc->box[0][j] > box[2]) | (nc->box[3][j] < box[1]) |
                  (nc->box[1][j] > box[3]);
        hit |= (uint64_t)!out << j;
    }
    return hit;
}

#if SCREEN_AVX512
__attribute__((target("avx512f"))) static inline uint64_t near_screen_avx512(const near_cache *nc,
                                                                            const double box[4])
{
    uint64_t hit = 0;
    __m512d b0 = _mm512_set1_pd(box[0]), b1 = _mm512_set1_pd(box[1]), b2 = _mm512_set1_pd(box[2]),
            b3 = _mm512_set1_pd(box[3]);
    for (size_t j = 0; j < nc->n; j += 8) {
        __mmask8 out = _mm512_cmp_pd_mask(_mm512_load_pd(&nc->box[2][j]), b0, _CMP_LT_OQ);
        out |= _mm512_cmp_pd_mask(_mm512_load_pd(&nc->box[0][j]), b2, _CMP_GT_OQ);
        out |= _mm512_cmp_pd_mask(_mm512_load_pd(&nc->box[3][j]), b1, _CMP_LT_OQ);
        out |= _mm512_cmp_pd_mask(_mm512_load_pd(&nc->box[1][j]), b3, _CMP_GT_OQ);
        hit |= (uint64_t)(uint8_t)~out << j;
    }
    return nc->n == NEAR_MAX ? hit : hit & (((uint64_t)1 << nc->n) - 1);
}
#endif

typedef uint64_t (*near_screen_fn)(const near_cache *, const double *);

/* 1 if the move (box its bounding box) sweeps a segment of block m other than the skip_n segments from skip
 * (only where m is in chain c). A block's output segments run from its first vertex's output index to its
 * last's (the next block's first, or the chain's end); they are screened by their boxes eight at a time
 * (screen), then tested exactly in order; a block of more than eight, or a ring's last, segment by segment. */
static inline __attribute__((always_inline)) int block_sweeps(const fused *F, size_t c, uint32_t m, size_t skip,
                                                              size_t skip_n, const double box[4], const double *a,
                                                              const double *b0, const double *b, const double *cc,
                                                              screen_fn screen)
{
    const ft_segment_blocks *g = &F->g;
    uint32_t mc = g->chain[m];
    const ft_chain *ch = F->pc[mc].out;
    size_t s0 = F->ofirst[m], s1 = m + 1 < g->chain_block[mc + 1] ? F->ofirst[m + 1] : ft_chain_segments(ch);
    size_t sk = mc == c ? skip : SIZE_MAX, sk_n = mc == c ? skip_n : 0;
    if (s1 - s0 > 8 || s1 >= ch->n) /* a ring's last segment ends at vertex 0 */
        return ft_move_sweeps(ch->x, ch->y, ch->n, s0, s1, sk, sk_n, box, a, b0, b, cc);
    unsigned hit = screen(ch->x, ch->y, s0, s1 - s0, box);
    for (size_t i = 0; i < sk_n; i++) { /* the skipped run, cyclically from sk */
        size_t s = sk + i < ch->n ? sk + i : sk + i - ch->n;
        if (s - s0 < s1 - s0)
            hit &= ~(1u << (s - s0));
    }
    for (; hit != 0; hit &= hit - 1) {
        size_t s = s0 + (size_t)__builtin_ctz(hit);
        if (ft_move_sweeps_segment(ch->x[s], ch->y[s], ch->x[s + 1], ch->y[s + 1], a, b0, b, cc))
            return 1;
    }
    return 0;
}

/* 1 if moving the vertex at output index k of chain c from b0 to b (neighbours a and cc, fixed) sweeps a
 * segment of a block in nb's near list (nc, or the index when it did not fit), other than the skip_n segments
 * from skip (its own two, and the neighbouring ones already cleared). */
static inline __attribute__((always_inline)) int blocked(const fused *F, size_t c, size_t nb, const near_cache *nc,
                                                         size_t skip, size_t skip_n, const double *a,
                                                         const double *b0, const double *b, const double *cc,
                                                         screen_fn screen, near_screen_fn near_screen)
{
    double box[4] = {dmin(b[0], b0[0]), dmin(b[1], b0[1]), dmax(b[0], b0[0]), dmax(b[1], b0[1])};
    box_add(box, a[0], a[1]);
    box_add(box, cc[0], cc[1]);
    const ft_segment_blocks *g = &F->g;
    if (nc->n != SIZE_MAX) {
        for (uint64_t hit = near_screen(nc, box); hit != 0; hit &= hit - 1)
            if (block_sweeps(F, c, nc->m[__builtin_ctzll(hit)], skip, skip_n, box, a, b0, b, cc, screen))
                return 1;
        return 0;
    }
    for (uint32_t e = g->near_start[nb]; e < g->near_start[nb + 1]; e++) {
        uint32_t m = g->near[e];
        const double *q = g->box + 4 * (size_t)m;
        if (q[2] < box[0] || q[0] > box[2] || q[3] < box[1] || q[1] > box[3])
            continue;
        if (block_sweeps(F, c, m, skip, skip_n, box, a, b0, b, cc, screen))
            return 1;
    }
    return 0;
}

/* Whether moving the vertex at output index k (neighbours at ka and kc) from b0 to b leaves the chain's
 * neighbouring segments (ka - 1 to ka, kc to kc + 1) clear, by the hull shortcut (ft_leaves_hull); the
 * segments it cannot clear are tested with the others. Then the scan of the near blocks. */
static inline __attribute__((always_inline)) int move_blocked(const fused *F, size_t c, size_t nb,
                                                              const near_cache *nc, size_t k, const double *a,
                                                              const double *b0, const double *b, const double *cc,
                                                              screen_fn screen, near_screen_fn near_screen)
{
    const ft_chain *o = F->pc[c].out;
    size_t n = o->n, ka = k > 0 ? k - 1 : n - 1, kc = k + 1 < n ? k + 1 : 0;
    size_t skip = ka, skip_n = 2; /* segments kp, ka, k, kc are consecutive: the run skipped is a part of them */
    if (n >= 6) {
        size_t kp = ka > 0 ? ka - 1 : n - 1, kn = kc + 1 < n ? kc + 1 : 0;
        double p[2] = {o->x[kp], o->y[kp]}, q[2] = {o->x[kn], o->y[kn]};
        if (ft_leaves_hull(a, p, b0, b, cc))
            skip = kp, skip_n++;
        if (ft_leaves_hull(cc, q, a, b0, b))
            skip_n++;
    }
    return blocked(F, c, nb, nc, skip, skip_n, a, b0, b, cc, screen, near_screen);
}

static void count_move(ft_line_guard_stats *s, double t)
{
    s->moves++;
    s->reduced += t > 0.0 && t < 1.0;
    s->dropped += t == 0.0;
}

/* Walks the moved vertices owned by blocks [lo, hi) whose local flag is `want`, in chain and vertex order
 * (block b owns the end points of its segments but the first; an open chain's first block its first too). */
static inline __attribute__((always_inline)) void walk(const fused *F, const unsigned char *local,
                                                       unsigned char want, size_t lo, size_t hi,
                                                       ft_line_guard_stats *s, screen_fn screen,
                                                       near_screen_fn near_screen)
{
    static const double ts[] = {1.0, 0.5, 0.25};
    const ft_segment_blocks *g = &F->g;
    near_cache nc;
    double xy[2 * RAW_RUN];
    size_t r0 = 0, r1 = 0; /* the blocks whose raw positions are in xy: a run of walked blocks of one chain */
    for (size_t b = lo; b < hi; b++) {
        if (local[b] != want)
            continue;
        size_t c = g->chain[b];
        if (b >= r1) {
            size_t end = g->chain_block[c + 1] < hi ? g->chain_block[c + 1] : hi;
            end = end - b < RAW_BLOCKS ? end : b + RAW_BLOCKS;
            for (r0 = b, r1 = b + 1; r1 < end && local[r1] == want;)
                r1++;
            run_raw(F, r0, r1, xy);
        }
        near_fill(g, b, &nc);
        const pass_chain *p = &F->pc[c];
        size_t nout = p->out->n, v = g->first[b], v1 = v + g->count[b], k = F->ofirst[b];
        const double *raw = xy + 2 * (v - g->first[r0]);
        double *ox = p->out->x, *oy = p->out->y;
        for (; v <= v1; v++, raw += 2) {
            size_t ki = k < nout ? k : 0;
            if (v < v1)
                k += 1 + p->split[v];
            if (v == g->first[b] && (b > g->chain_block[c] || p->in->closed))
                continue; /* owned by the block before */
            double bx = ox[ki], by = oy[ki], dx = raw[0] - bx, dy = raw[1] - by;
            if (dx == 0.0 && dy == 0.0)
                continue; /* stays (run_raw), or moves by nothing */
            size_t ka = ki > 0 ? ki - 1 : nout - 1, kc = ki + 1 < nout ? ki + 1 : 0;
            double a[2] = {ox[ka], oy[ka]}, cc[2] = {ox[kc], oy[kc]}, b0[2] = {bx, by}, t = 0.0;
            for (int q = 0; q < 3; q++) {
                double nbx[2] = {bx + ts[q] * dx, by + ts[q] * dy};
                if (!move_blocked(F, c, b, &nc, ki, a, b0, nbx, cc, screen, near_screen)) {
                    ox[ki] = nbx[0];
                    oy[ki] = nbx[1];
                    t = ts[q];
                    break;
                }
            }
            count_move(s, t);
        }
    }
}

static void walk_blocks_c(const fused *F, const unsigned char *local, unsigned char want, size_t lo, size_t hi,
                          ft_line_guard_stats *s)
{
    walk(F, local, want, lo, hi, s, screen_c, near_screen_c);
}

#if SCREEN_AVX512
__attribute__((target("avx512f"))) static void walk_blocks_avx512(const fused *F, const unsigned char *local,
                                                                 unsigned char want, size_t lo, size_t hi,
                                                                 ft_line_guard_stats *s)
{
    walk(F, local, want, lo, hi, s, screen_avx512, near_screen_avx512);
}
#endif

/* The screens this run may use: tests only (ft_dutton_guard_generic), to compare the two. */
static int generic_only;

void ft_dutton_guard_generic(int on)
{
    generic_only = on;
}

typedef void (*walk_fn)(const fused *, const unsigned char *, unsigned char, size_t, size_t, ft_line_guard_stats *);

/* The walk for this processor: AVX-512 where it runs (and is not switched off), else plain C; the same
 * segments reach the exact tests either way, so the same bits. */
static walk_fn pick_walk(void)
{
#if SCREEN_AVX512
    if (!generic_only && __builtin_cpu_supports("avx512f"))
        return walk_blocks_avx512;
#endif
    return walk_blocks_c;
}

/* The walk for the scheduler (guard_schedule.c). */
typedef struct {
    const fused *F;
    const unsigned char *local;
    walk_fn walk;
} walk_ctx;

static void walk_range(const void *ctx, unsigned char want, size_t lo, size_t hi, ft_line_guard_stats *s)
{
    const walk_ctx *w = ctx;
    w->walk(w->F, w->local, want, lo, hi, s);
}

static void free_chains(pass_chain *pc, size_t n, int keep_out)
{
    for (size_t c = 0; pc != NULL && c < n; c++) {
        ft_chain_free(pc[c].dense);
        free(pc[c].split);
        if (!keep_out)
            ft_chain_free(pc[c].out);
    }
    free(pc);
}

/* Chain c's input (densified), split flags and output chain of the right size. */
static int prepare_chain(const ft_chain *in, const ft_dutton_plan *p, ft_dutton_pass_params *pp, pass_chain *q)
{
    int rc = ft_dutton_pass_prepare(in, p, pp, &q->dense);
    if (rc != FT_OK)
        return rc;
    q->in = q->dense ? q->dense : in;
    size_t n = q->in->n, nseg = ft_chain_segments(q->in), extra = 0;
    q->split = ft_malloc(nseg ? nseg : 1);
    if (q->split == NULL)
        return FT_E_NOMEM;
    ft_dutton_mark_splits(q->in, nseg, pp->w, q->split);
    for (size_t i = 0; i < nseg; i++)
        extra += q->split[i];
    q->all_split = extra == nseg;
    if (n > SIZE_MAX / 2 || n + extra >= UINT32_MAX)
        return ft_error(FT_E_NOMEM, "enhance: %zu vertices overflow", n + extra);
    q->out = ft_chain_create(n + extra, q->in->closed);
    if (q->out == NULL)
        return FT_E_NOMEM;
    q->out->n = n + extra;
    if (nseg == 0) { /* a single vertex: nothing to split or move */
        for (size_t i = 0; i < n; i++) {
            q->out->x[i] = q->in->x[i];
            q->out->y[i] = q->in->y[i];
        }
    }
    return FT_OK;
}

/* Output index of every block's first vertex: the splits before it in its chain, counted per block. */
static void first_outputs(fused *F)
{
    const ft_segment_blocks *g = &F->g;
    long long nb = (long long)g->nblock;
#pragma omp parallel for schedule(static)
    for (long long b = 0; b < nb; b++) {
        const unsigned char *split = F->pc[g->chain[b]].split;
        uint32_t cnt = 0;
        for (size_t s = g->first[b], e = s + g->count[b]; s < e; s++)
            cnt += split[s];
        F->ofirst[b] = cnt + g->count[b]; /* for now: the output vertices the block adds */
    }
    for (size_t c = 0; c < g->nchain; c++) {
        uint32_t k = 0;
        for (size_t b = g->chain_block[c]; b < g->chain_block[c + 1]; b++) {
            uint32_t add = F->ofirst[b];
            F->ofirst[b] = k;
            k += add;
        }
    }
}

/* The index of the pass before, kept for the next pass's near lists (ft_segment_blocks_join_carried). */
struct ft_dutton_carry {
    ft_segment_blocks g;  /* its blocks and boxes (near lists freed) */
    ft_segment_wide wide; /* its wide lists; start NULL when there is nothing to carry */
    size_t *nout;         /* per chain: the vertices of its output */
    int halved;           /* every segment was split: the next pass's blocks are these halved */
};

ft_dutton_carry *ft_dutton_carry_create(void)
{
    return ft_calloc(1, sizeof(ft_dutton_carry));
}

static void carry_clear(ft_dutton_carry *k)
{
    ft_segment_blocks_free(&k->g);
    ft_segment_wide_free(&k->wide);
    free(k->nout);
    k->nout = NULL;
    k->halved = 0;
}

void ft_dutton_carry_free(ft_dutton_carry *k)
{
    if (k != NULL)
        carry_clear(k);
    free(k);
}

/* Whether this pass's blocks are the carried pass's halved: the same chains, each the carried output itself
 * (no vertex dropped since, none added by densification), every segment of the pass before split. */
static int carry_fits(const ft_dutton_carry *k, const fused *F, size_t n)
{
    if (k == NULL || !k->halved || k->wide.start == NULL || k->g.nchain != n)
        return 0;
    for (size_t c = 0; c < n; c++)
        if (F->pc[c].dense != NULL || F->pc[c].in->n != k->nout[c])
            return 0;
    return 1;
}

/* The slack of the wide lists: the passes after this one move by about CARRY_RATIO of the pass before's
 * largest move (segments shrink by f / 2 each pass: 0.59 at D 1.3); two blocks come closer by up to twice
 * the excess of each pass left. Only speed depends on it: a pass whose blocks left their parents' boxes by
 * more joins on the grid again. */
#define CARRY_RATIO 0.6
static double carry_slack(double move, int passes_left)
{
    double s = 0.0, r = 1.0;
    for (int k = 0; k < passes_left; k++)
        s += (r *= CARRY_RATIO);
    return 2.0 * move * s;
}

/* Keeps this pass's index (boxes, chains, wide lists) in k for the next one; F->g is left empty. */
static int carry_keep(ft_dutton_carry *k, fused *F, size_t n, ft_segment_wide *wide)
{
    carry_clear(k);
    free(F->g.near);
    free(F->g.near_start);
    F->g.near = F->g.near_start = NULL;
    k->g = F->g;
    F->g = (ft_segment_blocks){0};
    k->wide = *wide;
    *wide = (ft_segment_wide){0};
    k->nout = ft_malloc((n ? n : 1) * sizeof *k->nout);
    if (k->nout == NULL) {
        carry_clear(k);
        return FT_E_NOMEM;
    }
    k->halved = 1;
    for (size_t c = 0; c < n; c++) {
        k->nout[c] = F->pc[c].out->n;
        k->halved &= F->pc[c].all_split;
    }
    return FT_OK;
}

int ft_dutton_plan_fusable(const ft_dutton_plan *p)
{
    return p != NULL && !p->keep_vertices; /* keep_vertices moves the midpoints */
}

int ft_dutton_pass_guarded(const ft_chain *const *in, size_t n, const ft_dutton_plan *p, ft_chain **out,
                           ft_line_guard_stats *stats, ft_dutton_carry *carry, int passes_left)
{
    ft_segment_wide wide = {0};
    int keep = carry != NULL && passes_left > 0;
    for (size_t c = 0; c < n; c++)
        out[c] = NULL;
    fused F = {0};
    F.pc = ft_calloc(n ? n : 1, sizeof *F.pc);
    if (F.pc == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    for (size_t c = 0; c < n && rc == FT_OK; c++)
        rc = prepare_chain(in[c], p, &F.pp, &F.pc[c]);
    const ft_chain **work = rc == FT_OK ? ft_malloc((n ? n : 1) * sizeof *work) : NULL;
    if (rc == FT_OK && work == NULL)
        rc = FT_E_NOMEM;
    for (size_t c = 0; c < n && rc == FT_OK; c++)
        work[c] = F.pc[c].in;
    if (rc == FT_OK)
        rc = ft_segment_blocks_layout(&F.g, work, n, FUSED_BLOCK);
    size_t nb = F.g.nblock;
    unsigned char *local = NULL;
    if (rc == FT_OK) {
        F.ofirst = ft_malloc((nb ? nb : 1) * sizeof *F.ofirst);
        local = ft_malloc(nb ? nb : 1);
        if (F.ofirst == NULL || local == NULL)
            rc = FT_E_NOMEM;
    }
    if (rc == FT_OK) {
        first_outputs(&F);
        long long nbl = (long long)nb;
        double move = 0.0;
        long long nrun = (nbl + RAW_BLOCKS - 1) / RAW_BLOCKS;
#pragma omp parallel for schedule(static) reduction(max : move)
        for (long long r = 0; r < nrun; r++) {
            size_t lo = (size_t)r * RAW_BLOCKS, hi = r + 1 < nrun ? lo + RAW_BLOCKS : nb;
            move = dmax(move, range_boxes(&F, lo, hi));
        }
        rc = 1;
        if (carry_fits(carry, &F, n))
            rc = ft_segment_blocks_join_carried(&F.g, work, &carry->g, &carry->wide, keep, &wide);
        if (rc == 1 && keep)
            rc = ft_segment_blocks_join_wide(&F.g, work, carry_slack(move, passes_left), &wide);
        else if (rc == 1)
            rc = ft_segment_blocks_join(&F.g, work);
        if (carry != NULL)
            carry_clear(carry); /* used: its memory is not held through the walk */
    }
    if (rc == FT_OK) {
        ft_segment_blocks_mark_local(&F.g, work, local);
        walk_ctx wc = {&F, local, pick_walk()};
        ft_line_guard_stats s = {0, 0, 0, 0};
        ft_guard_walk(&F.g, work, local, walk_range, &wc, &s);
        if (stats)
            ft_line_guard_stats_add(stats, &s);
        for (size_t c = 0; c < n; c++)
            out[c] = F.pc[c].out;
    }
    if (carry != NULL && rc == FT_OK && keep)
        rc = carry_keep(carry, &F, n, &wide);
    else if (carry != NULL)
        carry_clear(carry);
    ft_segment_wide_free(&wide);
    if (rc != FT_OK)
        for (size_t c = 0; c < n; c++)
            out[c] = NULL;
    free(work);
    free(local);
    free(F.ofirst);
    ft_segment_blocks_free(&F.g);
    free_chains(F.pc, n, rc == FT_OK);
    return rc;
}
