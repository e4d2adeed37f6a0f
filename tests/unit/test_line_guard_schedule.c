/* fracterra — tests of line/guard_schedule.c, the parallel walk of the crossing guards' non-local blocks, on
 * a long random walk that crosses back over itself (the bench chain's kind, 300,000 vertices: several chunks
 * of the walk, thousands of non-local blocks): every non-local block is in exactly one group, each group in
 * block order, and every non-local block whose vertices a block's walk reads (found here vertex by vertex)
 * is in that block's group, every block read in the chunks the group waits for; the unfused guard and the
 * fused enhancement give the same bits and counts on 1 thread (the serial walk in block order) as on 2 and 3
 * (the groups in parallel).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <omp.h>
#include "fracterra/core.h"
#include "fracterra/line.h"
#include "line/guard_schedule.h"
#include "line/segment_index.h"
#include "test_segment_boxes.h"

#define WALK_N 300000
#define WOBBLE 2.0 /* raw moves of up to 2 m a coordinate, on 5 m steps */

/* A random walk of 5 m steps whose heading drifts (a Gaussian turn of 0.3 rad a step and a slow swing): it
 * winds back over itself again and again, as the bench chain does. */
static ft_chain *walk_chain(void)
{
    ft_chain *c = ft_chain_create(WALK_N, 0);
    assert_non_null(c);
    ft_rng *r = ft_rng_create(20240501, 11);
    double x = 0.0, y = 0.0, dir = 0.0;
    for (size_t i = 0; i < WALK_N; i++) {
        c->x[i] = x;
        c->y[i] = y;
        dir += ft_rng_gaussian(r, 0.3) + 0.01 * sin(2.0 * M_PI * (double)i / 5000.0);
        x += 5.0 * cos(dir);
        y += 5.0 * sin(dir);
    }
    c->n = WALK_N;
    ft_rng_free(r);
    return c;
}

/* The chain moved by its wobble: the raw positions of the guard's test. */
static ft_chain *wobbled(const ft_chain *c)
{
    ft_chain *r = ft_chain_copy(c);
    assert_non_null(r);
    for (size_t i = 0; i < c->n; i++) {
        r->x[i] += wobble(0, i, 0, WOBBLE);
        r->y[i] += wobble(0, i, 1, WOBBLE);
    }
    return r;
}

/* The block owning vertex u of chain c: the block of the segment ending at it (an open
 * chain's vertex 0: its first block). */
static size_t owner(const ft_segment_blocks *g, const ft_chain *ch, size_t c, size_t u)
{
    size_t n = ch->n;
    if (u == 0 && !ch->closed)
        return g->chain_block[c];
    size_t s = u == 0 ? n - 1 : u - 1;
    return g->chain_block[c] + s / FT_SEGMENT_BLOCK;
}

/* Block o, whose vertices non-local block b's walk reads (or b itself): if non-local, in b's group; local or
 * not, in the chunks the group waits for. */
static void read_in_group(const ft_guard_schedule *s, const unsigned char *local, const uint32_t *group, size_t b,
                          size_t o)
{
    uint32_t k = group[b];
    if (!local[o])
        assert_int_equal(group[o], k);
    assert_in_range(o / FT_GUARD_CHUNK, s->chunk_lo[k], s->chunk_hi[k]);
}

static void test_groups_hold_every_read(void **state)
{
    (void)state;
    ft_chain *c = walk_chain(), *r = wobbled(c);
    const ft_chain *base[1] = {c}, *raw[1] = {r};
    ft_segment_blocks g;
    assert_int_equal(ft_segment_blocks_build(&g, base, raw, 1, 0), FT_OK);
    unsigned char *local = malloc(g.nblock);
    uint32_t *group = malloc(g.nblock * sizeof *group);
    assert_non_null(local);
    assert_non_null(group);
    ft_segment_blocks_mark_local(&g, base, local);
    ft_guard_schedule s;
    assert_int_equal(ft_guard_schedule_build(&s, &g, base, local), FT_OK);
    size_t nnl = 0, largest = 0;
    for (size_t b = 0; b < g.nblock; b++) {
        nnl += !local[b];
        group[b] = UINT32_MAX;
    }
    assert_true(nnl > 1000);                        /* the walk has many non-local blocks */
    assert_true(s.ngroup > 10);                     /* and they fall into many groups */
    assert_int_equal(s.group_start[s.ngroup], nnl); /* every one listed */
    for (size_t k = 0; k < s.ngroup; k++) {
        assert_true(s.group_start[k + 1] > s.group_start[k]);
        size_t size = s.group_start[k + 1] - s.group_start[k];
        largest = size > largest ? size : largest;
        for (size_t i = s.group_start[k]; i < s.group_start[k + 1]; i++) {
            uint32_t b = s.block[i];
            assert_true(b < g.nblock);
            assert_false(local[b]);
            assert_int_equal(group[b], UINT32_MAX); /* once */
            group[b] = (uint32_t)k;
            if (i > s.group_start[k])
                assert_true(s.block[i - 1] < b); /* block order */
        }
    }
    assert_true(largest < nnl / 4);
    /* the vertices walking b reads: the end points of the segments of its near list's blocks, and its own
     * vertices' neighbours and theirs (two along the chain either way) */
    for (size_t b = 0; b < g.nblock; b++) {
        if (local[b])
            continue;
        read_in_group(&s, local, group, b, b);
        for (uint32_t e = g.near_start[b]; e < g.near_start[b + 1]; e++) {
            size_t m = g.near[e];
            for (size_t u = g.first[m]; u <= g.first[m] + g.count[m]; u++)
                read_in_group(&s, local, group, b, owner(&g, c, 0, u));
        }
        long long lo = (long long)g.first[b] - 1, hi = (long long)(g.first[b] + g.count[b]) + 2;
        for (long long u = lo < 0 ? 0 : lo; u <= hi && u < (long long)c->n; u++) /* open: no wrapping */
            read_in_group(&s, local, group, b, owner(&g, c, 0, (size_t)u));
    }
    ft_guard_schedule_free(&s);
    free(group);
    free(local);
    ft_segment_blocks_free(&g);
    ft_chain_free(r);
    ft_chain_free(c);
}

/* The unfused guard (ft_line_guard_moves) over the walk and its wobble, and two guarded enhancement passes
 * (the fused guard): on 1, 2 and 3 threads the same bits and counts. */
static void test_bits_on_any_thread_count(void **state)
{
    (void)state;
    ft_chain *c = walk_chain(), *r = wobbled(c);
    const ft_chain *raw[1] = {r};
    ft_chain *moved[3] = {NULL, NULL, NULL}, *enhanced[3] = {NULL, NULL, NULL};
    ft_line_guard_stats st[3];
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.iterations = 2;
    int threads = omp_get_max_threads();
    for (int t = 0; t < 3; t++) {
        omp_set_num_threads(t + 1);
        moved[t] = ft_chain_copy(c);
        st[t] = (ft_line_guard_stats){0, 0, 0, 0};
        assert_int_equal(ft_line_guard_moves(&moved[t], raw, 1, FT_GUARD_REDUCE, &st[t]), FT_OK);
        assert_int_equal(ft_line_enhance(c, &o, &enhanced[t]), FT_OK);
    }
    omp_set_num_threads(threads);
    assert_true(st[0].reduced + st[0].dropped > 1000); /* the order matters: many moves are cut */
    for (int t = 1; t < 3; t++) {
        assert_int_equal(st[t].moves, st[0].moves);
        assert_int_equal(st[t].reduced, st[0].reduced);
        assert_int_equal(st[t].dropped, st[0].dropped);
        assert_memory_equal(moved[t]->x, moved[0]->x, c->n * sizeof(double));
        assert_memory_equal(moved[t]->y, moved[0]->y, c->n * sizeof(double));
        assert_int_equal(enhanced[t]->n, enhanced[0]->n);
        assert_memory_equal(enhanced[t]->x, enhanced[0]->x, enhanced[0]->n * sizeof(double));
        assert_memory_equal(enhanced[t]->y, enhanced[0]->y, enhanced[0]->n * sizeof(double));
    }
    for (int t = 0; t < 3; t++) {
        ft_chain_free(moved[t]);
        ft_chain_free(enhanced[t]);
    }
    ft_chain_free(r);
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_groups_hold_every_read),
        cmocka_unit_test(test_bits_on_any_thread_count),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
