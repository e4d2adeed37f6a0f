/* fracterra — line/move_guard.c: the crossing guard of the line operations (issue 15): a pass of Dutton's
 * enhancement, of roundness smoothing, of Zhang et al.'s boundary generator or of a contour displacement
 * proposes, for every output vertex, a base position (where it is with no displacement: the input's own
 * geometry, e.g. a new midpoint on its segment) and a raw position (where the algorithm puts it). The guard
 * starts from the base geometry and visits the moved vertices chain by chain, in vertex order; vertex v goes
 * to base + t (raw - base) with the first t of 1, 1/2, 1/4 for which its two segments, from its neighbours'
 * current positions, meet no other segment of any chain (ft_segment_contact: a shared end point is allowed,
 * an overlap is not), and otherwise stays at its base position. The segments are found in the grid of
 * swept segments (segment_index.c), tested at their current positions.
 *
 * Fast path (the same result class, found in bulk): every move is first made in full; a sweep over the grid's
 * cells finds every pair of segments in contact of which an end point was moved, and takes those moved end
 * points back to base; then the segments next to the vertices taken back are checked again (taking a vertex
 * back can expose another contact), until none is found.
 * What is left is contact-free: a contact between two segments at base is the input's. Only the vertices
 * taken back then go through the vertex-by-vertex guard above, in order. Marks are set, never cleared,
 * within a sweep, so the set found does not depend on the thread count.
 *
 * Invariant: if the base geometry has no contact, every accepted move keeps it so (the only segments that
 * change are v's two, and they were just tested against all others), and a refused move changes nothing;
 * hence the output has no self-intersection and no contact between chains, by construction. A contact
 * already in the base (an input that crosses itself) stays, and the moves that touch it are refused.
 * The visiting order is fixed and serial, so the result does not depend on the thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "line/segment_index.h"

#include <math.h>
#include <stdlib.h>

#define TRIES 3 /* t = 1, 1/2, 1/4; then 0 */

typedef struct {
    ft_chain *const *cur;
    const ft_segment_grid *g;
} guard;

static inline double dmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

/* Current end points of segment id. */
static void seg_points(const guard *G, uint32_t id, double p[4])
{
    uint32_t c = G->g->seg_chain[id];
    const ft_chain *ch = G->cur[c];
    size_t i = id - G->g->chain_first[c], j = i + 1 < ch->n ? i + 1 : 0;
    p[0] = ch->x[i];
    p[1] = ch->y[i];
    p[2] = ch->x[j];
    p[3] = ch->y[j];
}

/* 1 if segments a b (id sa) or b c (id sb; either may be absent: UINT32_MAX) meet another segment. */
static int blocked(const guard *G, const double *a, const double *b, const double *c, uint32_t sa, uint32_t sb)
{
    double box[4] = {b[0], b[1], b[0], b[1]};
    if (a) {
        box[0] = dmin(box[0], a[0]), box[1] = dmin(box[1], a[1]);
        box[2] = dmax(box[2], a[0]), box[3] = dmax(box[3], a[1]);
    }
    if (c) {
        box[0] = dmin(box[0], c[0]), box[1] = dmin(box[1], c[1]);
        box[2] = dmax(box[2], c[0]), box[3] = dmax(box[3], c[1]);
    }
    size_t k[4];
    ft_segment_grid_cells(G->g, box, k);
    for (size_t cy = k[1]; cy <= k[3]; cy++)
        for (size_t cx = k[0]; cx <= k[2]; cx++) {
            size_t cell = ft_segment_grid_bucket(G->g, cx, cy);
            for (size_t e = G->g->start[cell]; e < G->g->start[cell + 1]; e++) {
                uint32_t id = G->g->ids[e];
                if (id == sa || id == sb)
                    continue;
                double p[4];
                seg_points(G, id, p);
                if (dmax(p[0], p[2]) < box[0] || dmin(p[0], p[2]) > box[2] || dmax(p[1], p[3]) < box[1] ||
                    dmin(p[1], p[3]) > box[3])
                    continue;
                if (a && ft_segment_contact(a[0], a[1], b[0], b[1], p[0], p[1], p[2], p[3]))
                    return 1;
                if (c && ft_segment_contact(b[0], b[1], c[0], c[1], p[0], p[1], p[2], p[3]))
                    return 1;
            }
        }
    return 0;
}

/* Moves vertex i of chain c towards raw as far as the guard allows; returns the t used (1, 0.5, 0.25, 0). */
static double guard_vertex(const guard *G, size_t c, size_t i, const ft_chain *raw)
{
    ft_chain *ch = G->cur[c];
    size_t n = ch->n;
    int has_prev = ch->closed || i > 0, has_next = ch->closed || i + 1 < n;
    size_t ip = i > 0 ? i - 1 : n - 1, in = i + 1 < n ? i + 1 : 0;
    uint32_t first = G->g->chain_first[c];
    uint32_t sa = has_prev ? first + (uint32_t)ip : UINT32_MAX, sb = has_next ? first + (uint32_t)i : UINT32_MAX;
    double a[2], cc[2];
    if (has_prev)
        a[0] = ch->x[ip], a[1] = ch->y[ip];
    if (has_next)
        cc[0] = ch->x[in], cc[1] = ch->y[in];
    double bx = ch->x[i], by = ch->y[i], dx = raw->x[i] - bx, dy = raw->y[i] - by, t = 1.0;
    for (int k = 0; k < TRIES; k++, t *= 0.5) {
        double b[2] = {bx + t * dx, by + t * dy};
        if (!blocked(G, has_prev ? a : NULL, b, has_next ? cc : NULL, sa, sb)) {
            ch->x[i] = b[0];
            ch->y[i] = b[1];
            return t;
        }
    }
    return 0.0;
}

static int check_pair(const ft_chain *b, const ft_chain *r, size_t c)
{
    if (b == NULL || r == NULL)
        return ft_error(FT_E_INVALID, "crossing guard: chain %zu is NULL", c);
    if (b->n != r->n || b->closed != r->closed)
        return ft_error(FT_E_INVALID, "crossing guard: chain %zu has %zu base and %zu raw vertices", c, b->n,
                        r->n);
    return FT_OK;
}

/* ---- phase 1: every move at once, then the ones in a contact taken back ------------------------------- */

enum { AT_BASE = 0, AT_RAW = 1, SUSPECT = 2 };

typedef struct {
    ft_chain *const *cur;
    const ft_chain *const *raw;
    double **bx, **by;           /* base positions */
    unsigned char **state, **mark;
    const ft_segment_grid *g;
} phase1;

static void seg_ends(const phase1 *P, uint32_t id, size_t *c, size_t *i, size_t *j)
{
    *c = P->g->seg_chain[id];
    *i = id - P->g->chain_first[*c];
    *j = *i + 1 < P->cur[*c]->n ? *i + 1 : 0;
}

/* Marks the AT_RAW end points of two segments in contact; returns 1 if any was marked. */
static int mark_pair(const phase1 *P, uint32_t s, uint32_t t)
{
    size_t c[2], i[2], j[2];
    seg_ends(P, s, &c[0], &i[0], &j[0]);
    seg_ends(P, t, &c[1], &i[1], &j[1]);
    int any = 0;
    for (int k = 0; k < 2; k++) {
        size_t v[2] = {i[k], j[k]};
        for (int e = 0; e < 2; e++)
            if (P->state[c[k]][v[e]] == AT_RAW) {
#pragma omp atomic write
                P->mark[c[k]][v[e]] = 1;
                any = 1;
            }
    }
    return any;
}

static int pair_contact(const phase1 *P, uint32_t s, uint32_t t)
{
    size_t cs, is, js, ct, it, jt;
    seg_ends(P, s, &cs, &is, &js);
    seg_ends(P, t, &ct, &it, &jt);
    const ft_chain *a = P->cur[cs], *b = P->cur[ct];
    if (P->state[cs][is] != AT_RAW && P->state[cs][js] != AT_RAW && P->state[ct][it] != AT_RAW &&
        P->state[ct][jt] != AT_RAW)
        return 0; /* both at base: a contact of the input, not of this pass */
    if (dmax(a->x[is], a->x[js]) < dmin(b->x[it], b->x[jt]) || dmax(b->x[it], b->x[jt]) < dmin(a->x[is], a->x[js]) ||
        dmax(a->y[is], a->y[js]) < dmin(b->y[it], b->y[jt]) || dmax(b->y[it], b->y[jt]) < dmin(a->y[is], a->y[js]))
        return 0;
    return ft_segment_contact(a->x[is], a->y[is], a->x[js], a->y[js], b->x[it], b->y[it], b->x[jt], b->y[jt]);
}

/* One sweep over the cells: marks the AT_RAW vertices of every pair in contact. Returns the marks made. */
static size_t sweep(const phase1 *P)
{
    const ft_segment_grid *g = P->g;
    size_t ncells = g->nbuckets, found = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : found) if (ncells > 4096)
    for (size_t cell = 0; cell < ncells; cell++)
        for (size_t e = g->start[cell]; e < g->start[cell + 1]; e++)
            for (size_t f = e + 1; f < g->start[cell + 1]; f++)
                if (pair_contact(P, g->ids[e], g->ids[f]))
                    found += (size_t)mark_pair(P, g->ids[e], g->ids[f]);
    return found;
}

/* Marks the contacts of segment id (chain c, first vertex i) at its current position. */
static size_t recheck_segment(const phase1 *P, size_t c, size_t i)
{
    const ft_chain *ch = P->cur[c];
    size_t j = i + 1 < ch->n ? i + 1 : 0, k[4], found = 0;
    uint32_t id = P->g->chain_first[c] + (uint32_t)i;
    double box[4] = {dmin(ch->x[i], ch->x[j]), dmin(ch->y[i], ch->y[j]), dmax(ch->x[i], ch->x[j]),
                     dmax(ch->y[i], ch->y[j])};
    ft_segment_grid_cells(P->g, box, k);
    for (size_t cy = k[1]; cy <= k[3]; cy++)
        for (size_t cx = k[0]; cx <= k[2]; cx++) {
            size_t b = ft_segment_grid_bucket(P->g, cx, cy);
            for (size_t e = P->g->start[b]; e < P->g->start[b + 1]; e++)
                if (P->g->ids[e] != id && pair_contact(P, id, P->g->ids[e]))
                    found += (size_t)mark_pair(P, id, P->g->ids[e]);
        }
    return found;
}

/* After a take-back: the contacts of the segments next to the vertices taken back (list[0..m)). */
static size_t recheck(const phase1 *P, const size_t *list, size_t m)
{
    size_t found = 0;
    for (size_t q = 0; q < m; q++) {
        size_t c = list[2 * q], i = list[2 * q + 1];
        const ft_chain *ch = P->cur[c];
        if (ch->closed || i > 0)
            found += recheck_segment(P, c, i > 0 ? i - 1 : ch->n - 1);
        if (ch->closed || i + 1 < ch->n)
            found += recheck_segment(P, c, i);
    }
    return found;
}

/* Takes the marked vertices back to base, as SUSPECT. Returns how many. */
static size_t take_back(const phase1 *P, size_t n, size_t **list, size_t *cap)
{
    size_t k = 0;
    for (size_t c = 0; c < n; c++)
        for (size_t i = 0; i < P->cur[c]->n; i++)
            if (P->mark[c][i]) {
                P->mark[c][i] = 0;
                P->state[c][i] = SUSPECT;
                P->cur[c]->x[i] = P->bx[c][i];
                P->cur[c]->y[i] = P->by[c][i];
                if (k >= *cap) {
                    size_t nc = *cap ? 2 * *cap : 1024;
                    size_t *t = realloc(*list, 2 * nc * sizeof **list);
                    if (t == NULL)
                        return SIZE_MAX;
                    *list = t;
                    *cap = nc;
                }
                (*list)[2 * k] = c;
                (*list)[2 * k + 1] = i;
                k++;
            }
    return k;
}

static void phase1_free(phase1 *P, size_t n)
{
    for (size_t c = 0; c < n; c++) {
        if (P->bx)
            free(P->bx[c]);
        if (P->state)
            free(P->state[c]);
        if (P->mark)
            free(P->mark[c]);
    }
    free(P->bx);
    free(P->by);
    free(P->state);
    free(P->mark);
}

/* Allocates the per-vertex arrays, keeps the base positions and puts every moved vertex at raw. */
static int phase1_init(phase1 *P, ft_chain *const *chains, const ft_chain *const *raw, size_t n, size_t *moves)
{
    size_t m = n ? n : 1;
    P->cur = chains;
    P->raw = raw;
    P->bx = ft_calloc(m, sizeof *P->bx);
    P->by = ft_calloc(m, sizeof *P->by);
    P->state = ft_calloc(m, sizeof *P->state);
    P->mark = ft_calloc(m, sizeof *P->mark);
    if (!P->bx || !P->by || !P->state || !P->mark)
        return FT_E_NOMEM;
    for (size_t c = 0; c < n; c++) {
        size_t nv = chains[c]->n;
        P->bx[c] = ft_malloc(2 * (nv ? nv : 1) * sizeof(double));
        P->state[c] = ft_calloc(nv ? nv : 1, 1);
        P->mark[c] = ft_calloc(nv ? nv : 1, 1);
        if (!P->bx[c] || !P->state[c] || !P->mark[c])
            return FT_E_NOMEM;
        P->by[c] = P->bx[c] + nv;
        for (size_t i = 0; i < nv; i++) {
            P->bx[c][i] = chains[c]->x[i];
            P->by[c][i] = chains[c]->y[i];
            if (raw[c]->x[i] != chains[c]->x[i] || raw[c]->y[i] != chains[c]->y[i]) {
                P->state[c][i] = AT_RAW;
                chains[c]->x[i] = raw[c]->x[i];
                chains[c]->y[i] = raw[c]->y[i];
                (*moves)++;
            }
        }
    }
    return FT_OK;
}

int ft_line_guard_moves(ft_chain *const *chains, const ft_chain *const *raw, size_t n, ft_line_guard_stats *stats)
{
    if ((chains == NULL || raw == NULL) && n > 0)
        return ft_error(FT_E_INVALID, "crossing guard: NULL chains");
    for (size_t c = 0; c < n; c++) {
        int rc = check_pair(chains[c], raw[c], c);
        if (rc != FT_OK)
            return rc;
    }
    ft_segment_grid g;
    int rc = ft_segment_grid_build(&g, (const ft_chain *const *)chains, raw, n);
    if (rc != FT_OK)
        return rc;
    ft_line_guard_stats s = {0, 0, 0};
    phase1 P = {0};
    P.g = &g;
    rc = phase1_init(&P, chains, raw, n, &s.moves);
    size_t *list = NULL, cap = 0;
    size_t found = rc == FT_OK ? sweep(&P) : 0;
    while (found > 0) {
        size_t m = take_back(&P, n, &list, &cap);
        if (m == SIZE_MAX) {
            rc = FT_E_NOMEM;
            break;
        }
        found = recheck(&P, list, m);
    }
    free(list);
    guard G = {chains, &g};
    for (size_t c = 0; c < n && rc == FT_OK; c++)
        for (size_t i = 0; i < chains[c]->n; i++) {
            if (P.state[c][i] != SUSPECT)
                continue;
            double t = guard_vertex(&G, c, i, raw[c]);
            s.reduced += t > 0.0 && t < 1.0;
            s.dropped += t == 0.0;
        }
    phase1_free(&P, n);
    ft_segment_grid_free(&g);
    if (rc == FT_OK && stats) {
        stats->moves += s.moves;
        stats->reduced += s.reduced;
        stats->dropped += s.dropped;
    }
    return rc;
}
