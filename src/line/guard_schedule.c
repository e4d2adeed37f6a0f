/* fracterra — line/guard_schedule.c: the blocks that are not local to their chunk, the crossing guards'
 * second phase (move_guard.c, dutton_guarded.c), walked in parallel with the bits of the serial walk.
 *
 * The guards walk first the local blocks, chunk by chunk in parallel, then the others (about a tenth of the
 * blocks on the bench chain) in block order; on two threads that serial phase was ~15 % of the fused pass's
 * wall time, the other core idle. Walking block b's moves reads the vertices owned by the blocks of its near
 * list and by the owners of their first vertices (the end points of the segments it tests), and by the
 * blocks up to two before and after it along its chain (its vertices' neighbours and theirs, which the hull
 * shortcut reads); it writes only the vertices b owns. The local blocks are finished: read only. Two
 * non-local blocks conflict when either is in the other's read set (the near lists are not symmetric: a reach
 * is the box of two blocks' boxes). The groups are the connected components of that relation (union-find,
 * each tree's root its least block): blocks of different groups never read what the other writes, so each
 * group walked in block order by one thread, the groups in parallel in any order, gives every block the very
 * positions the serial walk gives it: the same bits on any thread count, with no synchronisation but the
 * end. On the bench chain's three passes 716, 2559 and 5706 groups, the largest 7, 1 and 0.5 % of the work.
 * A schedule by levels (wave fronts of the conflict order: 89-173 levels, hundreds of blocks wide) was
 * tried first: on the shared two-core machine each level's barrier waited for a descheduled thread, and the
 * phase took up to 0.7 s instead of 0.04.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "line/guard_schedule.h"

#include <stdlib.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* The block before m along its chain (a ring's first: its last; an open chain's first: m itself), the owner
 * of m's first vertex. */
static inline size_t block_before(const ft_segment_blocks *g, const ft_chain *const *chains, size_t m)
{
    uint32_t c = g->chain[m];
    if (m > g->chain_block[c])
        return m - 1;
    return chains[c]->closed ? g->chain_block[c + 1] - 1 : m;
}

/* The block after m along its chain (a ring's last: its first; an open chain's last: m itself). */
static inline size_t block_after(const ft_segment_blocks *g, const ft_chain *const *chains, size_t m)
{
    uint32_t c = g->chain[m];
    if (m + 1 < g->chain_block[c + 1])
        return m + 1;
    return chains[c]->closed ? g->chain_block[c] : m;
}

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

/* The root of x's tree: every link goes to a lower number, so the root is the group's least block. The
 * threads join trees at once: a parent only ever moves to a lower ancestor (path halving) and a root is
 * linked by compare-and-swap, so every pointer read is an ancestor and no link is lost. */
static inline uint32_t root_of(uint32_t *par, uint32_t x)
{
    for (;;) {
        uint32_t p = __atomic_load_n(&par[x], __ATOMIC_RELAXED);
        if (p == x)
            return x;
        uint32_t q = __atomic_load_n(&par[p], __ATOMIC_RELAXED);
        if (q != p)
            __atomic_store_n(&par[x], q, __ATOMIC_RELAXED); /* path halving */
        x = q;
    }
}

/* Joins the tree of r with the tree of block m if m is non-local; returns the joined tree's root. */
static inline uint32_t join(const numbering *nu, uint32_t *par, uint32_t r, size_t m)
{
    if (!is_nonlocal(nu, m))
        return r;
    uint32_t a = number_of(nu, m);
    for (;;) {
        r = root_of(par, r);
        a = root_of(par, a);
        if (a == r)
            return r;
        uint32_t hi = a > r ? a : r, lo = a > r ? r : a, expect = hi;
        if (__atomic_compare_exchange_n(&par[hi], &expect, lo, 0, __ATOMIC_RELAXED, __ATOMIC_RELAXED))
            return lo;
    }
}

/* Joins non-local block b (number i) with the non-local blocks whose vertices walking b reads: the two
 * before and after it along its chain, the blocks of its near list and the owners of their first vertices
 * (the block before, in the list already unless the list skips it or m opens its chain). */
static void join_reads(const ft_segment_blocks *g, const ft_chain *const *chains, const numbering *nu,
                       uint32_t *par, size_t b, uint32_t i)
{
    uint32_t r = i;
    size_t p = block_before(g, chains, b), q = block_after(g, chains, b);
    r = join(nu, par, r, p);
    r = join(nu, par, r, block_before(g, chains, p));
    r = join(nu, par, r, q);
    r = join(nu, par, r, block_after(g, chains, q));
    for (uint32_t e = g->near_start[b], e0 = e; e < g->near_start[b + 1]; e++) {
        size_t m = g->near[e];
        r = join(nu, par, r, m);
        if (e == e0 || g->near[e - 1] != m - 1 || g->first[m] == 0)
            r = join(nu, par, r, block_before(g, chains, m));
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
    long long nwl = (long long)nw;
#pragma omp parallel for schedule(static)
    for (long long w = 0; w < nwl; w++) {
        uint64_t bits = 0;
        for (size_t k = 0, b = 64 * (size_t)w; k < 64 && b < nb; k++, b++)
            bits |= (uint64_t)!local[b] << k;
        nu.bits[w] = bits;
    }
    for (size_t w = 0; w < nw; w++) {
        nu.rank[w] = (uint32_t)nnl;
        nnl += (size_t)__builtin_popcountll(nu.bits[w]);
    }
    /* par: the union-find forest over the numbers, then each one's group; block: number to block */
    uint32_t *par = ft_malloc((nnl ? nnl : 1) * sizeof *par);
    s->block = ft_malloc((nnl ? nnl : 1) * sizeof *s->block);
    if (par == NULL || s->block == NULL) {
        free(nu.bits);
        free(nu.rank);
        free(par);
        ft_guard_schedule_free(s);
        return FT_E_NOMEM;
    }
#pragma omp parallel for schedule(static)
    for (long long w = 0; w < nwl; w++)
        for (uint64_t bits = nu.bits[w], i = nu.rank[w]; bits != 0; bits &= bits - 1, i++) {
            par[i] = (uint32_t)i;
            s->block[i] = (uint32_t)(64 * (size_t)w + (size_t)__builtin_ctzll(bits));
        }
    long long nnll = (long long)nnl;
#pragma omp parallel for schedule(dynamic, 256)
    for (long long i = 0; i < nnll; i++)
        join_reads(g, chains, &nu, par, s->block[i], (uint32_t)i);
    free(nu.bits);
    free(nu.rank);
    /* in number order: a root opens a group; any other number's parent is lower, so its entry already
     * holds the group of its root */
    for (size_t i = 0; i < nnl; i++)
        par[i] = par[i] == i ? (uint32_t)ngroup++ : par[par[i]];
    s->group_start = ft_calloc(ngroup + 1, sizeof *s->group_start);
    uint32_t *order = ft_malloc((nnl ? nnl : 1) * sizeof *order);
    if (s->group_start == NULL || order == NULL) {
        free(par);
        free(order);
        ft_guard_schedule_free(s);
        return FT_E_NOMEM;
    }
    s->ngroup = ngroup;
    for (size_t i = 0; i < nnl; i++) /* group k's size at entry k + 1, then its start at entry k */
        s->group_start[par[i] + 1]++;
    for (size_t k = 1; k <= ngroup; k++)
        s->group_start[k] += s->group_start[k - 1];
    for (size_t i = 0; i < nnl; i++) /* each group's blocks in block order; entry k moves on to its end */
        order[s->group_start[par[i]]++] = s->block[i];
    for (size_t k = ngroup; k > 0; k--)
        s->group_start[k] = s->group_start[k - 1];
    s->group_start[0] = 0;
    free(s->block);
    s->block = order;
    free(par);
    return FT_OK;
}

void ft_guard_schedule_free(ft_guard_schedule *s)
{
    free(s->group_start);
    free(s->block);
    *s = (ft_guard_schedule){0};
}

static void add_stats(ft_line_guard_stats *to, const ft_line_guard_stats *s)
{
    to->moves += s->moves;
    to->reduced += s->reduced;
    to->dropped += s->dropped;
    to->redrawn += s->redrawn;
}

void ft_guard_walk_nonlocal(const ft_segment_blocks *g, const ft_chain *const *chains, const unsigned char *local,
                            ft_guard_walk_fn walk, const void *ctx, ft_line_guard_stats *s)
{
    ft_guard_schedule sc = {0};
    int threads = 1;
#ifdef _OPENMP
    threads = omp_get_max_threads();
#endif
    if (threads == 1 || ft_guard_schedule_build(&sc, g, chains, local) != FT_OK) {
        for (size_t b = 0; b < g->nblock; b++)
            if (!local[b])
                walk(ctx, b, s);
        return;
    }
    long long ng = (long long)sc.ngroup;
#pragma omp parallel
    {
        ft_line_guard_stats mine = {0, 0, 0, 0};
#pragma omp for schedule(dynamic, 1) nowait
        for (long long k = 0; k < ng; k++)
            for (size_t i = sc.group_start[k]; i < sc.group_start[k + 1]; i++)
                walk(ctx, sc.block[i], &mine);
#pragma omp critical(ft_guard_walk_nonlocal)
        add_stats(s, &mine);
    }
    ft_guard_schedule_free(&sc);
}
