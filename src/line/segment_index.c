/* fracterra — line/segment_index.c: a uniform grid over the segments of a set of chains whose vertices move
 * during a guarded pass (move_guard.c), and the contact test between two segments.
 *
 * Every vertex of a guarded pass ends somewhere on the straight path from its base position to its raw
 * position (move_guard.c only shortens moves), so a segment's every possible position lies in the bounding
 * box of its two end points' base and raw positions, its swept box. Each segment is filed once, in every
 * cell its swept box meets (counting pass, prefix sums, filling pass: a compressed row table, no
 * reallocation); a query returns every segment whose swept box meets the query box, and the caller tests it
 * at its current position. The cell side is the mean larger side of the swept boxes, but not below
 * sqrt(area / (4 nseg)), so the grid has at most about 4 nseg cells (row-major: the cells a walk along a
 * chain queries are next to each other in memory; hashing them, tried, was 2-5 times slower).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "line/segment_index.h"

#include <math.h>
#include <stdlib.h>

#define MAX_SPAN 1048576.0          /* cells along an axis: at most 2^20 */
#define MAX_CELLS_PER_SEGMENT 4.0   /* the grid has at most about 4 nseg cells */

static inline double dmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

static double orient(double ax, double ay, double bx, double by, double cx, double cy)
{
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

/* c, known collinear with a b, lies within the closed segment a b. */
static int within(double ax, double ay, double bx, double by, double cx, double cy)
{
    return dmin(ax, bx) <= cx && cx <= dmax(ax, bx) && dmin(ay, by) <= cy && cy <= dmax(ay, by);
}

/* The closed segments a b and c d have a point in common. */
static int closed_intersect(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy)
{
    if (dmax(ax, bx) < dmin(cx, dx) || dmax(cx, dx) < dmin(ax, bx) || dmax(ay, by) < dmin(cy, dy) ||
        dmax(cy, dy) < dmin(ay, by))
        return 0;
    double d1 = orient(cx, cy, dx, dy, ax, ay), d2 = orient(cx, cy, dx, dy, bx, by);
    double d3 = orient(ax, ay, bx, by, cx, cy), d4 = orient(ax, ay, bx, by, dx, dy);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return 1;
    return (d1 == 0 && within(cx, cy, dx, dy, ax, ay)) || (d2 == 0 && within(cx, cy, dx, dy, bx, by)) ||
           (d3 == 0 && within(ax, ay, bx, by, cx, cy)) || (d4 == 0 && within(ax, ay, bx, by, dx, dy));
}

/* Two segments from the shared point s, to a and to c, overlap beyond s: collinear and the same way. */
static int fold(double sx, double sy, double ax, double ay, double cx, double cy)
{
    return orient(sx, sy, ax, ay, cx, cy) == 0 && (ax - sx) * (cx - sx) + (ay - sy) * (cy - sy) > 0;
}

int ft_segment_contact(double ax, double ay, double bx, double by, double cx, double cy, double dx, double dy)
{
    if (ax == cx && ay == cy)
        return fold(ax, ay, bx, by, dx, dy) || (bx == dx && by == dy && (ax != bx || ay != by));
    if (ax == dx && ay == dy)
        return fold(ax, ay, bx, by, cx, cy) || (bx == cx && by == cy && (ax != bx || ay != by));
    if (bx == cx && by == cy)
        return fold(bx, by, ax, ay, dx, dy);
    if (bx == dx && by == dy)
        return fold(bx, by, ax, ay, cx, cy);
    return closed_intersect(ax, ay, bx, by, cx, cy, dx, dy);
}

/* ---- the grid ----------------------------------------------------------------------------------- */

static void swept_box(const ft_chain *b, const ft_chain *r, size_t i, size_t j, double box[4])
{
    box[0] = dmin(dmin(b->x[i], r->x[i]), dmin(b->x[j], r->x[j]));
    box[1] = dmin(dmin(b->y[i], r->y[i]), dmin(b->y[j], r->y[j]));
    box[2] = dmax(dmax(b->x[i], r->x[i]), dmax(b->x[j], r->x[j]));
    box[3] = dmax(dmax(b->y[i], r->y[i]), dmax(b->y[j], r->y[j]));
}

/* Origin, cell side and size of the grid from the swept boxes. */
static int grid_frame(ft_segment_grid *g, const ft_chain *const *base, const ft_chain *const *raw, size_t n)
{
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY, side = 0.0;
    for (size_t c = 0; c < n; c++)
        for (size_t i = 0, ns = ft_chain_segments(base[c]); i < ns; i++) {
            double b[4];
            swept_box(base[c], raw[c], i, i + 1 < base[c]->n ? i + 1 : 0, b);
            x0 = dmin(x0, b[0]);
            y0 = dmin(y0, b[1]);
            x1 = dmax(x1, b[2]);
            y1 = dmax(y1, b[3]);
            side += dmax(b[2] - b[0], b[3] - b[1]);
        }
    double w = x1 - x0, h = y1 - y0, ns = (double)g->nseg;
    side = dmax(side / ns, sqrt(w * h / (MAX_CELLS_PER_SEGMENT * ns)));
    side = dmax(side, dmax(w, h) / MAX_SPAN);
    if (!(side > 0.0))
        side = dmax(dmax(w, h), 1.0);
    g->x0 = x0;
    g->y0 = y0;
    g->inv = 1.0 / side;
    g->nx = (size_t)(w / side) + 1;
    g->ny = (size_t)(h / side) + 1;
    g->nbuckets = g->nx * g->ny;
    return FT_OK;
}

/* The cell range of every segment's swept box, into k (4 per segment), and the count of every cell into
 * start[cell + 1]. Returns the number of entries (cells met, summed over the segments). */
static size_t range_and_count(ft_segment_grid *g, const ft_chain *const *base, const ft_chain *const *raw, size_t n,
                              uint32_t *k)
{
    size_t id = 0, total = 0;
    for (size_t c = 0; c < n; c++)
        for (size_t i = 0, ns = ft_chain_segments(base[c]); i < ns; i++, id++) {
            double b[4];
            size_t r[4];
            swept_box(base[c], raw[c], i, i + 1 < base[c]->n ? i + 1 : 0, b);
            ft_segment_grid_cells(g, b, r);
            for (int q = 0; q < 4; q++)
                k[4 * id + q] = (uint32_t)r[q];
            total += (r[2] - r[0] + 1) * (r[3] - r[1] + 1);
            if (total >= UINT32_MAX)
                return total; /* the caller refuses it; the counts are not used */
            for (size_t cy = r[1]; cy <= r[3]; cy++)
                for (size_t cx = r[0]; cx <= r[2]; cx++)
                    g->start[cy * g->nx + cx + 1]++;
        }
    return total;
}

static void file_segments(ft_segment_grid *g, const uint32_t *k, uint32_t *next)
{
    for (size_t id = 0; id < g->nseg; id++) {
        const uint32_t *r = k + 4 * id;
        for (size_t cy = r[1]; cy <= r[3]; cy++)
            for (size_t cx = r[0]; cx <= r[2]; cx++)
                g->ids[next[cy * g->nx + cx]++] = (uint32_t)id;
    }
}

int ft_segment_grid_build(ft_segment_grid *g, const ft_chain *const *base, const ft_chain *const *raw, size_t n)
{
    *g = (ft_segment_grid){0};
    size_t nseg = 0;
    for (size_t c = 0; c < n; c++)
        nseg += ft_chain_segments(base[c]);
    if (nseg >= UINT32_MAX)
        return ft_error(FT_E_NOMEM, "segment index: %zu segments (at most 2^32 - 2)", nseg);
    g->nseg = nseg;
    if (nseg == 0)
        return FT_OK;
    int rc = grid_frame(g, base, raw, n);
    if (rc != FT_OK)
        return rc;
    size_t ncells = g->nbuckets;
    g->start = ft_calloc(ncells + 1, sizeof *g->start);
    g->seg_chain = ft_malloc(nseg * sizeof *g->seg_chain);
    g->chain_first = ft_malloc((n + 1) * sizeof *g->chain_first);
    if (g->start == NULL || g->seg_chain == NULL || g->chain_first == NULL) {
        ft_segment_grid_free(g);
        return FT_E_NOMEM;
    }
    uint32_t id = 0;
    for (size_t c = 0; c < n; c++) {
        g->chain_first[c] = id;
        for (size_t i = 0, ns = ft_chain_segments(base[c]); i < ns; i++)
            g->seg_chain[id++] = (uint32_t)c;
    }
    g->chain_first[n] = id;
    uint32_t *ranges = ft_malloc(4 * nseg * sizeof *ranges);
    if (ranges == NULL) {
        ft_segment_grid_free(g);
        return FT_E_NOMEM;
    }
    if (range_and_count(g, base, raw, n, ranges) >= UINT32_MAX) {
        free(ranges);
        ft_segment_grid_free(g);
        return ft_error(FT_E_NOMEM, "segment index: more than 2^32 - 2 cell entries (%zu segments)", nseg);
    }
    for (size_t k = 0; k < ncells; k++)
        g->start[k + 1] += g->start[k];
    uint32_t *next = ft_malloc(ncells * sizeof *next);
    g->ids = ft_malloc((g->start[ncells] ? g->start[ncells] : 1) * sizeof *g->ids);
    if (next == NULL || g->ids == NULL) {
        free(next);
        free(ranges);
        ft_segment_grid_free(g);
        return FT_E_NOMEM;
    }
    for (size_t k = 0; k < ncells; k++)
        next[k] = g->start[k];
    file_segments(g, ranges, next);
    free(next);
    free(ranges);
    return FT_OK;
}

void ft_segment_grid_free(ft_segment_grid *g)
{
    free(g->start);
    free(g->ids);
    free(g->seg_chain);
    free(g->chain_first);
    *g = (ft_segment_grid){0};
}
