/* fracterra — tests of line/segment_index.c against their definitions: every near and wide list is the
 * increasing list of the blocks whose boxes meet the block's reach (its box and the next block's, widened by
 * sigma for the wide lists), found here by testing every pair; the lists are the same on any thread count;
 * ft_segment_blocks_mark_local marks exactly the blocks whose listed blocks and their first vertices' owners
 * all lie in the block's chunk.
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
#include "line/segment_index.h"
#include "test_segment_boxes.h"

/* The reach of block b by the header's definition: its box and its chain's next block's (a ring's last
 * block: the ring's first; an open chain's last: itself), widened by s. */
static void reach(const ft_segment_blocks *g, ft_chain *const *ch, size_t b, double s, double r[4])
{
    size_t c = g->chain[b], nx = b + 1;
    if (nx == g->chain_block[c + 1])
        nx = ch[c]->closed ? g->chain_block[c] : b;
    const double *p = g->box + 4 * b, *q = g->box + 4 * nx;
    r[0] = fmin(p[0], q[0]) - s;
    r[1] = fmin(p[1], q[1]) - s;
    r[2] = fmax(p[2], q[2]) + s;
    r[3] = fmax(p[3], q[3]) + s;
}

/* Block b's list (start, list) is every block whose box meets its reach widened by s, in increasing order. */
static void list_is_brute(const ft_segment_blocks *g, ft_chain *const *ch, const uint32_t *start,
                          const uint32_t *list, size_t b, double s)
{
    double r[4];
    reach(g, ch, b, s, r);
    uint32_t e = start[b];
    for (size_t m = 0; m < g->nblock; m++) {
        const double *q = g->box + 4 * m;
        if (q[2] < r[0] || q[0] > r[2] || q[3] < r[1] || q[1] > r[3])
            continue;
        assert_true(e < start[b + 1]);
        assert_int_equal(list[e], m);
        e++;
    }
    assert_int_equal(e, start[b + 1]);
}

/* A tight spiral (arms 0.8 apart: lists reach across arms), a ring inside it, a line across both and a
 * one-segment chain on the line. */
static void spiral_set(ft_chain *c[4])
{
    spiral_ring_line(c, 401);
    c[3] = ft_chain_create(2, 0);
    assert_non_null(c[3]);
    c[3]->x[0] = 1.0, c[3]->y[0] = 0.2, c[3]->x[1] = 1.5, c[3]->y[1] = 0.4;
    c[3]->n = 2;
}

/* The grid join's near lists and wide lists are the pairwise definition's, on 1, 2 and 3 threads (each
 * thread lists a range of blocks into its own buffer: the joined lists must not depend on the split). */
static void test_grid_lists(void **state)
{
    (void)state;
    ft_chain *c[4];
    spiral_set(c);
    int threads = omp_get_max_threads();
    for (int nt = 1; nt <= 3; nt++) {
        omp_set_num_threads(nt);
        for (size_t per = 3; per <= 4; per++) {
            ft_segment_blocks g;
            ft_segment_wide w;
            assert_int_equal(ft_segment_blocks_layout(&g, (const ft_chain *const *)c, 4, per), FT_OK);
            fill_boxes(&g, c, 0.2);
            assert_int_equal(ft_segment_blocks_join_wide(&g, (const ft_chain *const *)c, 0.5, &w), FT_OK);
            for (size_t b = 0; b < g.nblock; b++) {
                list_is_brute(&g, c, g.near_start, g.near, b, 0.0);
                list_is_brute(&g, c, w.start, w.near, b, 0.5);
            }
            assert_true(w.start[g.nblock] > g.near_start[g.nblock] + g.nblock); /* sigma widens the lists */
            free(g.near_start);
            free(g.near);
            g.near_start = g.near = NULL;
            assert_int_equal(ft_segment_blocks_join(&g, (const ft_chain *const *)c), FT_OK);
            for (size_t b = 0; b < g.nblock; b++)
                list_is_brute(&g, c, g.near_start, g.near, b, 0.0);
            ft_segment_wide_free(&w);
            ft_segment_blocks_free(&g);
        }
    }
    omp_set_num_threads(threads);
    for (int k = 0; k < 4; k++)
        ft_chain_free(c[k]);
}

/* The carried lists (children of the parent's wide list, two siblings per scan, each thread a range) are
 * the pairwise definition's on 1, 2 and 3 threads, both the near lists and the wide lists handed on. */
static void test_carried_lists(void **state)
{
    (void)state;
    ft_chain *c[4], *h[4];
    spiral_set(c);
    for (size_t k = 0; k < 4; k++)
        h[k] = halved(c[k], k, 0.2);
    ft_segment_blocks prev;
    ft_segment_wide pw;
    assert_int_equal(ft_segment_blocks_layout(&prev, (const ft_chain *const *)c, 4, 4), FT_OK);
    fill_boxes(&prev, c, 0.2);
    assert_int_equal(ft_segment_blocks_join_wide(&prev, (const ft_chain *const *)c, 0.5, &pw), FT_OK);
    int threads = omp_get_max_threads();
    for (int nt = 1; nt <= 3; nt++) {
        omp_set_num_threads(nt);
        for (int want_wide = 0; want_wide < 2; want_wide++) {
            ft_segment_blocks g;
            ft_segment_wide w;
            assert_int_equal(ft_segment_blocks_layout(&g, (const ft_chain *const *)h, 4, 4), FT_OK);
            fill_boxes(&g, h, 0.1);
            assert_int_equal(ft_segment_blocks_join_carried(&g, (const ft_chain *const *)h, &prev, &pw, want_wide, &w),
                             FT_OK);
            for (size_t b = 0; b < g.nblock; b++) {
                list_is_brute(&g, h, g.near_start, g.near, b, 0.0);
                if (want_wide)
                    list_is_brute(&g, h, w.start, w.near, b, w.sigma);
            }
            assert_true(want_wide ? w.sigma > 0.0 && w.start != NULL : w.start == NULL);
            ft_segment_wide_free(&w);
            ft_segment_blocks_free(&g);
        }
    }
    omp_set_num_threads(threads);
    ft_segment_wide_free(&pw);
    ft_segment_blocks_free(&prev);
    for (size_t k = 0; k < 4; k++) {
        ft_chain_free(c[k]);
        ft_chain_free(h[k]);
    }
}

/* The owner of block m's first vertex (the block of the segment ending at it), by its definition. */
static size_t owner(const ft_segment_blocks *g, ft_chain *const *ch, size_t m)
{
    size_t c = g->chain[m];
    if (g->first[m] > 0)
        return m - 1;
    return ch[c]->closed ? g->chain_block[c + 1] - 1 : m;
}

/* mark_local against its definition over more than two chunks of blocks: rings of 3 blocks in overlapping
 * clusters (lists across rings, rings across chunk boundaries, a ring's first vertex owned by its last block)
 * and open chains of 3 blocks in between; and a straight line whose fifth block is the second chunk's first
 * (16384 = 5460 x 3 + 4), crossed near that block's end by a one-segment chain listed in the second chunk:
 * that chain's list holds the line's block 16384 but not block 16383, which owns 16384's first vertex. */
static ft_chain *cluster_chain(size_t k)
{
    enum { NV = 12 };
    int ring = k % 3 != 2;
    ft_chain *c = ft_chain_create(NV, ring);
    assert_non_null(c);
    double cx = 3.0 * (double)(k / 5), cy = 0.7 * (double)(k % 5);
    for (size_t i = 0; i < NV; i++) {
        double t = 2.0 * M_PI * (double)i / NV;
        c->x[i] = cx + (ring ? cos(t) : -1.0 + 2.0 * (double)i / (NV - 1));
        c->y[i] = cy + (ring ? sin(t) : 0.3);
    }
    c->n = NV;
    return c;
}

static void test_mark_local(void **state)
{
    (void)state;
    enum { NFILL = 5460, NCH = NFILL + 2 + 6000 };
    ft_chain **c = malloc(NCH * sizeof *c);
    assert_non_null(c);
    for (size_t k = 0; k < NFILL; k++)
        c[k] = cluster_chain(k);
    c[NFILL] = ft_chain_create(41, 0); /* 40 segments: blocks 16380 .. 16389 */
    c[NFILL + 1] = ft_chain_create(2, 0);
    assert_non_null(c[NFILL]);
    assert_non_null(c[NFILL + 1]);
    for (size_t i = 0; i < 41; i++) {
        c[NFILL]->x[i] = 1000.0 + (double)i;
        c[NFILL]->y[i] = -50.0;
    }
    c[NFILL]->n = 41;
    c[NFILL + 1]->x[0] = c[NFILL + 1]->x[1] = 1019.5; /* across block 16384: segments 16 .. 19, x 1016 .. 1020 */
    c[NFILL + 1]->y[0] = -50.5;
    c[NFILL + 1]->y[1] = -49.5;
    c[NFILL + 1]->n = 2;
    for (size_t k = NFILL + 2; k < NCH; k++)
        c[k] = cluster_chain(k);
    ft_segment_blocks g;
    assert_int_equal(ft_segment_blocks_layout(&g, (const ft_chain *const *)c, NCH, 4), FT_OK);
    assert_true(g.nblock > 2 * FT_GUARD_CHUNK);
    assert_int_equal(g.chain_block[NFILL + 1], FT_GUARD_CHUNK + 6);
    fill_boxes(&g, c, 0.3);
    assert_int_equal(ft_segment_blocks_join(&g, (const ft_chain *const *)c), FT_OK);
    unsigned char *local = malloc(g.nblock);
    assert_non_null(local);
    ft_segment_blocks_mark_local(&g, (const ft_chain *const *)c, local);
    size_t marked = 0, cut = 0;
    for (size_t b = 0; b < g.nblock; b++) {
        size_t k = b / FT_GUARD_CHUNK;
        unsigned char ok = 1;
        for (uint32_t e = g.near_start[b]; e < g.near_start[b + 1]; e++)
            ok &= g.near[e] / FT_GUARD_CHUNK == k && owner(&g, c, g.near[e]) / FT_GUARD_CHUNK == k;
        assert_int_equal(local[b], ok);
        marked += ok;
        cut += !ok;
    }
    assert_true(marked > g.nblock / 2 && cut > 0); /* both kinds occur */
    size_t x = FT_GUARD_CHUNK + 6, xs = g.near_start[x]; /* the crossing chain: not local, by block 16383 */
    assert_int_equal(local[x], 0);
    assert_true(g.near[xs] == FT_GUARD_CHUNK && g.near[g.near_start[x + 1] - 1] == x);
    for (size_t b = 0; b < g.nblock; b += 97)       /* and the lists it read are the definition's */
        list_is_brute(&g, c, g.near_start, g.near, b, 0.0);
    free(local);
    ft_segment_blocks_free(&g);
    for (size_t k = 0; k < NCH; k++)
        ft_chain_free(c[k]);
    free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid_lists),
        cmocka_unit_test(test_carried_lists),
        cmocka_unit_test(test_mark_local),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
