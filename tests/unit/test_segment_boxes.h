/* fracterra — tests/unit/test_segment_boxes.h: made-up moves for the tests of the crossing guard's block index
 * (test_line_guard.c, test_line_segment_index.c): a displacement per vertex, the swept boxes it gives, and the
 * chains a pass would leave. Include after cmocka.h, math.h, stdint.h and line/segment_index.h.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_SEGMENT_BOXES_H
#define FT_TEST_SEGMENT_BOXES_H

/* A made-up displacement of vertex i of chain c, each coordinate in [-m, m]. */
static inline double wobble(size_t c, size_t i, int axis, double m)
{
    uint64_t h = (uint64_t)(c * 1000003u + i * 2 + (size_t)axis + 1) * UINT64_C(0x9E3779B97F4A7C15);
    h ^= h >> 29;
    return m * (2.0 * (double)(h % 1000003u) / 1000002.0 - 1.0);
}

/* Swept boxes of g's blocks: each vertex and its wobble of size m, widened as the guards do. */
static inline void fill_boxes(ft_segment_blocks *g, ft_chain *const *ch, double m)
{
    for (size_t b = 0; b < g->nblock; b++) {
        const ft_chain *c = ch[g->chain[b]];
        double *q = g->box + 4 * b;
        q[0] = q[1] = INFINITY;
        q[2] = q[3] = -INFINITY;
        for (size_t v = g->first[b]; v <= g->first[b] + g->count[b]; v++) {
            size_t i = v < c->n ? v : v - c->n;
            double x[2] = {c->x[i], c->x[i] + wobble(g->chain[b], i, 0, m)};
            double y[2] = {c->y[i], c->y[i] + wobble(g->chain[b], i, 1, m)};
            for (int k = 0; k < 2; k++) {
                q[0] = fmin(q[0], x[k]);
                q[1] = fmin(q[1], y[k]);
                q[2] = fmax(q[2], x[k]);
                q[3] = fmax(q[3], y[k]);
            }
        }
        ft_segment_box_widen(q);
    }
}

/* Chains with every segment split, each vertex moved halfway towards its wobble of size m (as a pass
 * leaves them: inside the swept boxes), each midpoint on the segment's input. */
static inline ft_chain *halved(const ft_chain *c, size_t k, double m)
{
    size_t ns = ft_chain_segments(c);
    ft_chain *h = ft_chain_create(c->n + ns, c->closed);
    assert_non_null(h);
    for (size_t i = 0, o = 0; i < c->n; i++) {
        size_t j = i + 1 < c->n ? i + 1 : 0;
        h->x[o] = c->x[i] + 0.5 * wobble(k, i, 0, m);
        h->y[o++] = c->y[i] + 0.5 * wobble(k, i, 1, m);
        if (i < ns) {
            h->x[o] = 0.5 * (c->x[i] + c->x[j]);
            h->y[o++] = 0.5 * (c->y[i] + c->y[j]);
        }
    }
    h->n = c->n + ns;
    return h;
}

/* A tight spiral of 3000 vertices (arms 0.8 apart: lists reach across arms), a ring of `ring` vertices inside
 * it and a line of 300 across both, in c[0..2]. */
static inline void spiral_ring_line(ft_chain *c[3], size_t ring)
{
    c[0] = ft_chain_create(3000, 0);
    c[1] = ft_chain_create(ring, 1);
    c[2] = ft_chain_create(300, 0);
    assert_non_null(c[0]);
    assert_non_null(c[1]);
    assert_non_null(c[2]);
    for (size_t i = 0; i < 3000; i++) {
        double t = 0.05 * (double)i, r = 5.0 + 0.8 * t / (2.0 * M_PI);
        c[0]->x[i] = r * cos(t);
        c[0]->y[i] = r * sin(t);
    }
    for (size_t i = 0; i < ring; i++) {
        c[1]->x[i] = 3.0 * cos(2.0 * M_PI * (double)i / (double)ring);
        c[1]->y[i] = 3.0 * sin(2.0 * M_PI * (double)i / (double)ring);
    }
    for (size_t i = 0; i < 300; i++) {
        c[2]->x[i] = -20.0 + 40.0 * (double)i / 299.0;
        c[2]->y[i] = 0.3;
    }
    c[0]->n = 3000, c[1]->n = ring, c[2]->n = 300;
}

#endif /* FT_TEST_SEGMENT_BOXES_H */
