/* fracterra — line/guard_schedule.c: the walk of the crossing guards (move_guard.c, dutton_guarded.c) over
 * their blocks, in parallel, with the bits of the serial order: each chunk's local blocks, then the others.
 *
 * The chunks' local blocks read and write only their own chunk's vertices, so the chunks run in parallel.
 * The other blocks (about a tenth on the bench chain) were then walked serially in block order: on two
 * threads ~15 % of the fused pass's wall time, the other core idle. Walking block b's moves reads the
 * vertices owned by the blocks of its near list and by the owners of their first vertices (the end points of
 * the segments it tests), and by the blocks up to two before and after it along its chain (its vertices'
 * neighbours and theirs, which the hull shortcut reads); it writes only the vertices b owns. Two non-local
 * blocks conflict when either is in the other's read set (both ways: the near lists are not symmetric, a
 * reach being the box of two blocks' boxes). The groups are the connected components of that relation
 * (union-find, each tree's root its least block): blocks of different groups never read what the other
 * writes, so each group walked in block order by one thread, the groups in parallel in any order, gives
 * every block the very positions the serial walk gives it, once the local blocks it reads are walked: a
 * group waits for the chunks of its blocks and of every block they read (the local blocks of a chunk read
 * its non-local blocks' vertices before those move). So the same bits on any thread count.
 *
 * One loop takes items from a shared counter: first the schedule's build (serial, overlapping the other
 * threads' chunks), then the chunks, then the groups, each after the chunks it needs are done (a flag per
 * chunk). There is no barrier but the loop's end: on the shared machine, a schedule by levels (wave fronts
 * of the conflict order, 89-173 levels on the bench chain, a barrier each) and the groups in a loop of
 * their own after the build's own parallel loops both lost more waiting for descheduled threads than they
 * gained. On the bench chain's three passes: 26, 49 and 77 thousand non-local blocks in 716, 2559 and 5706
 * groups, the largest 7, 1 and 0.5 % of the phase's work; the build, ~16 ms of CPU a call against ~85 ms
 * of walking it schedules, runs while the other threads walk chunks. One thread walks in the serial order,
 * with no schedule. Each thread counts the moves in its own counters (the per-chunk counters the guards had
 * shared cache lines between the threads, written at every move).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "line/guard_schedule.h"

#include <sched.h>
#include <stdlib.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* The non-local blocks numbered in block order: bit b % 64 of word b / 64 of bits is set for a non-local
 * block, whose number is rank[b / 64] + the bits below it; small enough to stay in cache, where an array
 * over every block would not. */
typedef struct {
    uint64_t *bits;
    uint32_t *rank;
} numbering;

static inline int is_nonlocal(const numbering *nu, size_t b)
{
    return (int)(nu->bits[b / 64] >> (b % 64)) & 1;
}

static inline uint32_t number_of(const numbering *nu, size_t b)
{
    uint64_t below = nu->bits[b / 64] & ((UINT64_C(1) << (b % 64)) - 1);
    return nu->rank[b / 64] + (uint32_t)__builtin_popcountll(below);
}

/* The root of x's tree: every link goes to a lower number, so the root is the group's least block. */
static inline uint32_t root_of(uint32_t *par, uint32_t x)
{
    while (par[x] != x) {
        par[x] = par[par[x]]; /* path halving */
        x = par[x];
    }
    return x;
}

/* Block m read by the walk of a block whose tree's root is r: m's chunk widens the chunks read [*c0, *c1],
 * and if m is non-local its tree is joined with r's. Returns the joined tree's root. */
static inline uint32_t join(const numbering *nu, uint32_t *par, uint32_t r, size_t m, uint32_t *c0, uint32_t *c1)
{
    uint32_t c = (uint32_t)(m / FT_GUARD_CHUNK);
    *c0 = c < *c0 ? c : *c0;
    *c1 = c > *c1 ? c : *c1;
    if (!is_nonlocal(nu, m))
        return r;
    uint32_t a = root_of(par, number_of(nu, m));
    if (a == r)
        return r;
    if (a < r)
        return par[r] = a;
    par[a] = r;
    return r;
}

/* Joins non-local block b (number i) with the non-local blocks whose vertices walking b reads: the two
 * before and after it along its chain, the blocks of its near list and the owners of their first vertices
 * (the block before, in the list already unless the list skips it or m opens its chain). The chunks of b
 * and of all the blocks read, local or not, widen [*c0, *c1]. */
static void join_reads(const ft_segment_blocks *g, const ft_chain *const *chains, const numbering *nu,
                       uint32_t *par, size_t b, uint32_t i, uint32_t *c0, uint32_t *c1)
{
    uint32_t r = join(nu, par, root_of(par, i), b, c0, c1); /* b's own chunk */
    size_t p = ft_segment_block_before(g, chains, b), q = ft_segment_block_after(g, chains, b);
    r = join(nu, par, r, p, c0, c1);
    r = join(nu, par, r, ft_segment_block_before(g, chains, p), c0, c1);
    r = join(nu, par, r, q, c0, c1);
    r = join(nu, par, r, ft_segment_block_after(g, chains, q), c0, c1);
    for (uint32_t e = g->near_start[b], e0 = e; e < g->near_start[b + 1]; e++) {
        size_t m = g->near[e];
        r = join(nu, par, r, m, c0, c1);
        if (e == e0 || g->near[e - 1] != m - 1 || g->first[m] == 0)
            r = join(nu, par, r, ft_segment_block_before(g, chains, m), c0, c1);
    }
}

int ft_guard_schedule_build(ft_guard_schedule *s, const ft_segment_blocks *g, const ft_chain *const *chains,
                            const unsigned char *local)
{
    *s = (ft_guard_schedule){0};
    size_t nb = g->nblock, nw = (nb + 63) / 64, nnl = 0, ngroup = 0;
    numbering nu = {ft_malloc((nw ? nw : 1) * sizeof *nu.bits), ft_malloc((nw ? nw : 1) * sizeof *nu.rank)};
    if (nu.bits == NULL || nu.rank == NULL) {
        free(nu.bits);
        free(nu.rank);
        return FT_E_NOMEM;
    }
    for (size_t w = 0; w < nw; w++) {
        uint64_t bits = 0;
        for (size_t k = 0, b = 64 * w; k < 64 && b < nb; k++, b++)
            bits |= (uint64_t)!local[b] << k;
        nu.bits[w] = bits;
        nu.rank[w] = (uint32_t)nnl;
        nnl += (size_t)__builtin_popcountll(bits);
    }
    /* par: the union-find forest over the numbers, then each one's group; block: number to block; c0, c1:
     * the chunks each one reads */
    size_t nn = nnl ? nnl : 1;
    uint32_t *par = ft_malloc(nn * sizeof *par), *c0 = ft_malloc(nn * sizeof *c0), *c1 = ft_malloc(nn * sizeof *c1);
    s->block = ft_malloc(nn * sizeof *s->block);
    if (par == NULL || c0 == NULL || c1 == NULL || s->block == NULL)
        goto fail;
    for (size_t b = 0, i = 0; b < nb; b++)
        if (!local[b])
            par[i] = (uint32_t)i, s->block[i++] = (uint32_t)b;
    for (size_t i = 0; i < nnl; i++) {
        c0[i] = UINT32_MAX;
        c1[i] = 0;
        join_reads(g, chains, &nu, par, s->block[i], (uint32_t)i, &c0[i], &c1[i]);
    }
    /* in number order: a root opens a group; any other number's parent is lower, so its entry already
     * holds the group of its root */
    for (size_t i = 0; i < nnl; i++)
        par[i] = par[i] == i ? (uint32_t)ngroup++ : par[par[i]];
    s->group_start = ft_calloc(ngroup + 1, sizeof *s->group_start);
    s->chunk_lo = ft_malloc((ngroup ? ngroup : 1) * sizeof *s->chunk_lo);
    s->chunk_hi = ft_calloc(ngroup ? ngroup : 1, sizeof *s->chunk_hi);
    uint32_t *order = ft_malloc(nn * sizeof *order);
    if (s->group_start == NULL || s->chunk_lo == NULL || s->chunk_hi == NULL || order == NULL) {
        free(order);
        goto fail;
    }
    s->ngroup = ngroup;
    for (size_t k = 0; k < ngroup; k++)
        s->chunk_lo[k] = UINT32_MAX;
    for (size_t i = 0; i < nnl; i++) { /* group k's size at entry k + 1, then its start at entry k */
        uint32_t k = par[i];
        s->group_start[k + 1]++;
        s->chunk_lo[k] = c0[i] < s->chunk_lo[k] ? c0[i] : s->chunk_lo[k];
        s->chunk_hi[k] = c1[i] > s->chunk_hi[k] ? c1[i] : s->chunk_hi[k];
    }
    for (size_t k = 1; k <= ngroup; k++)
        s->group_start[k] += s->group_start[k - 1];
    for (size_t i = 0; i < nnl; i++) /* each group's blocks in block order; entry k moves on to its end */
        order[s->group_start[par[i]]++] = s->block[i];
    for (size_t k = ngroup; k > 0; k--)
        s->group_start[k] = s->group_start[k - 1];
    s->group_start[0] = 0;
    free(s->block);
    s->block = order;
    free(nu.bits);
    free(nu.rank);
    free(par);
    free(c0);
    free(c1);
    return FT_OK;
fail:
    free(nu.bits);
    free(nu.rank);
    free(par);
    free(c0);
    free(c1);
    ft_guard_schedule_free(s);
    return FT_E_NOMEM;
}

void ft_guard_schedule_free(ft_guard_schedule *s)
{
    free(s->group_start);
    free(s->block);
    free(s->chunk_lo);
    free(s->chunk_hi);
    *s = (ft_guard_schedule){0};
}

/* The serial walk: the chunks' local blocks, then the others in block order. */
static void walk_serial(const ft_segment_blocks *g, ft_guard_walk_fn walk, const void *ctx, ft_line_guard_stats *s)
{
    size_t nb = g->nblock;
    for (size_t b0 = 0; b0 < nb; b0 += FT_GUARD_CHUNK)
        walk(ctx, 1, b0, b0 + FT_GUARD_CHUNK < nb ? b0 + FT_GUARD_CHUNK : nb, s);
    walk(ctx, 0, 0, nb, s);
}

/* Waits until *flag is set (by another thread, with release). */
static void wait_for(const int *flag)
{
    for (unsigned spin = 0; !__atomic_load_n(flag, __ATOMIC_ACQUIRE); spin++)
        if (spin >= 256)
            sched_yield();
}

void ft_guard_walk(const ft_segment_blocks *g, const ft_chain *const *chains, const unsigned char *local,
                   ft_guard_walk_fn walk, const void *ctx, ft_line_guard_stats *s)
{
    size_t nb = g->nblock, nchunk = (nb + FT_GUARD_CHUNK - 1) / FT_GUARD_CHUNK;
    int threads = 1;
#ifdef _OPENMP
    threads = omp_get_max_threads();
#endif
    int *done = threads > 1 ? ft_calloc(nchunk + 1, sizeof *done) : NULL; /* per chunk; [nchunk]: built */
    if (done == NULL) {
        walk_serial(g, walk, ctx, s);
        return;
    }
    ft_guard_schedule sc = {0};
    int built = FT_OK;
    size_t next = 0; /* the next item: 0 the schedule, 1 .. nchunk the chunks, then the groups */
#pragma omp parallel
    {
        ft_line_guard_stats mine = {0, 0, 0, 0};
        for (;;) {
            size_t k = __atomic_fetch_add(&next, 1, __ATOMIC_RELAXED);
            if (k == 0) {
                built = ft_guard_schedule_build(&sc, g, chains, local);
                __atomic_store_n(&done[nchunk], 1, __ATOMIC_RELEASE);
            } else if (k <= nchunk) {
                size_t b0 = (k - 1) * FT_GUARD_CHUNK, b1 = b0 + FT_GUARD_CHUNK < nb ? b0 + FT_GUARD_CHUNK : nb;
                walk(ctx, 1, b0, b1, &mine);
                __atomic_store_n(&done[k - 1], 1, __ATOMIC_RELEASE);
            } else {
                wait_for(&done[nchunk]);
                size_t j = k - nchunk - 1;
                if (built != FT_OK || j >= sc.ngroup)
                    break;
                for (size_t c = sc.chunk_lo[j]; c <= sc.chunk_hi[j]; c++)
                    wait_for(&done[c]);
                for (size_t i = sc.group_start[j]; i < sc.group_start[j + 1]; i++)
                    walk(ctx, 0, sc.block[i], sc.block[i] + 1, &mine);
            }
        }
#pragma omp critical(ft_guard_walk)
        ft_line_guard_stats_add(s, &mine);
    }
    if (built != FT_OK) /* no schedule: the chunks are walked, the others in block order */
        walk(ctx, 0, 0, nb, s);
    ft_guard_schedule_free(&sc);
    free(done);
}
