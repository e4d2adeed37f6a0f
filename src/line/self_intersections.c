/* fracterra — line/self_intersections.c: the crossings that Dutton (1981, "The Uniformity Coefficient")
 * warns negative UC and narrow features ("peninsulas, fjords, isthmuses") introduce, counted, and the
 * loops they make removed.
 *
 * Counting: a proper crossing is a pair of non-adjacent segments whose interiors cross (each segment's
 * end points strictly on opposite sides of the other's line; touching and collinear overlap are not
 * crossings). Segments go into a uniform grid by their bounding boxes (about one cell per segment, cell
 * side at least the mean segment length, coarsened while the entries would exceed 16 per segment); the
 * pairs of a cell are tested, and a pair is counted only in the cell holding the lower-left corner of
 * the intersection of its two boxes, so it is counted once without any floating-point intersection.
 * Cells are independent: the count runs in parallel and does not depend on the thread count.
 *
 * Loop removal walks the chain once, appending each vertex to the output; before a segment L -> B is
 * appended, the kept output segments it crosses are looked up in a grid (lazy deletion by generation
 * stamps), and at the first crossing X along L -> B with kept segment i the loop is cut: the output
 * goes back to vertex i, X is appended, and the segment X -> B is tried again. The output shrinks at
 * every cut, so this ends, in time linear in the vertices for chains with local loops. An open chain
 * keeps its end points (the loop between two crossing segments is what goes); a ring is walked from its
 * lowest-leftmost vertex (on the convex hull, so on the outer boundary) back to it, which keeps the loop
 * holding that vertex. Floating-point cuts can leave a grazing crossing: up to three passes are made.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/line.h"
#include "edit_internal.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define NONE SIZE_MAX
#define MAX_ENTRIES_PER_SEGMENT 16
#define REPAIR_PASSES 3

/* ---- a uniform grid over a bounding box ------------------------------------------------------- */

typedef struct {
    double x0, y0, inv; /* cell of x: floor((x - x0) * inv), clamped */
    size_t gx, gy;
} grid_geom;

static size_t cell_1d(double v, double v0, double inv, size_t g)
{
    double f = floor((v - v0) * inv);
    if (!(f > 0.0))
        return 0;
    return f >= (double)(g - 1) ? g - 1 : (size_t)f;
}

typedef struct {
    size_t cx0, cy0, cx1, cy1;
} cell_box;

static cell_box cells_of(const grid_geom *g, double xa, double ya, double xb, double yb)
{
    cell_box b = {cell_1d(fmin(xa, xb), g->x0, g->inv, g->gx), cell_1d(fmin(ya, yb), g->y0, g->inv, g->gy),
                  cell_1d(fmax(xa, xb), g->x0, g->inv, g->gx), cell_1d(fmax(ya, yb), g->y0, g->inv, g->gy)};
    return b;
}

static size_t cell_index(const grid_geom *g, double x, double y)
{
    return cell_1d(y, g->y0, g->inv, g->gy) * g->gx + cell_1d(x, g->x0, g->inv, g->gx);
}

/* A grid of about nseg cells with side >= the mean segment length over the chain's box. 0 if the chain
 * has no extent (every vertex the same point: no crossing possible). */
static int grid_for(const ft_chain *c, size_t nseg, grid_geom *g)
{
    double xmin, ymin, xmax, ymax;
    ft_chain_bbox(c, &xmin, &ymin, &xmax, &ymax);
    double w = xmax - xmin, h = ymax - ymin;
    double mean = ft_chain_length(c) / (double)nseg;
    double cs = fmax(sqrt(w * h / (double)nseg), mean);
    if (!(cs > 0.0) || !isfinite(cs))
        return 0;
    for (;;) {
        double gx = floor(w / cs) + 1.0, gy = floor(h / cs) + 1.0;
        if (gx * gy <= 4.0 * (double)nseg + 16.0) {
            g->x0 = xmin;
            g->y0 = ymin;
            g->inv = 1.0 / cs;
            g->gx = (size_t)gx;
            g->gy = (size_t)gy;
            return 1;
        }
        cs *= 2.0;
    }
}

/* ---- segment tests -------------------------------------------------------------------------------- */

static int sgn(double v)
{
    return (v > 0.0) - (v < 0.0);
}

static double orient(double ax, double ay, double bx, double by, double cx, double cy)
{
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

/* 1 if [p1, p2] and [q1, q2] cross properly. */
static int proper(double p1x, double p1y, double p2x, double p2y, double q1x, double q1y, double q2x, double q2y)
{
    int a = sgn(orient(p1x, p1y, p2x, p2y, q1x, q1y)), b = sgn(orient(p1x, p1y, p2x, p2y, q2x, q2y));
    if (a * b >= 0)
        return 0;
    int c = sgn(orient(q1x, q1y, q2x, q2y, p1x, p1y)), d = sgn(orient(q1x, q1y, q2x, q2y, p2x, p2y));
    return c * d < 0;
}

/* ---- counting ------------------------------------------------------------------------------------ */

typedef struct {
    const ft_chain *c;
    size_t nseg;
    grid_geom g;
    size_t *start; /* gx * gy + 1: CSR offsets */
    size_t *seg;   /* segment indices by cell */
} seg_grid;

static void seg_ends(const ft_chain *c, size_t s, double *ax, double *ay, double *bx, double *by)
{
    size_t t = s + 1 < c->n ? s + 1 : 0;
    *ax = c->x[s];
    *ay = c->y[s];
    *bx = c->x[t];
    *by = c->y[t];
}

static cell_box seg_cells(const seg_grid *sg, size_t s)
{
    double ax, ay, bx, by;
    seg_ends(sg->c, s, &ax, &ay, &bx, &by);
    return cells_of(&sg->g, ax, ay, bx, by);
}

static double box_cells(cell_box b)
{
    return (double)(b.cx1 - b.cx0 + 1) * (double)(b.cy1 - b.cy0 + 1);
}

/* Coarsens the grid until the entries fit, then fills the CSR arrays. */
static int seg_grid_build(seg_grid *sg)
{
    for (;;) {
        double total = 0.0;
        for (size_t s = 0; s < sg->nseg; s++)
            total += box_cells(seg_cells(sg, s));
        if (total <= (double)MAX_ENTRIES_PER_SEGMENT * (double)sg->nseg || (sg->g.gx == 1 && sg->g.gy == 1))
            break;
        sg->g.inv *= 0.5;
        sg->g.gx = (sg->g.gx + 1) / 2;
        sg->g.gy = (sg->g.gy + 1) / 2;
    }
    size_t ncell = sg->g.gx * sg->g.gy;
    if ((sg->start = ft_calloc(ncell + 1, sizeof *sg->start)) == NULL)
        return FT_E_NOMEM;
    for (size_t s = 0; s < sg->nseg; s++) {
        cell_box b = seg_cells(sg, s);
        for (size_t cy = b.cy0; cy <= b.cy1; cy++)
            for (size_t cx = b.cx0; cx <= b.cx1; cx++)
                sg->start[cy * sg->g.gx + cx + 1]++;
    }
    for (size_t k = 0; k < ncell; k++)
        sg->start[k + 1] += sg->start[k];
    size_t *fill = ft_malloc((ncell ? ncell : 1) * sizeof *fill);
    if (fill == NULL || (sg->seg = ft_realloc_array(NULL, sg->start[ncell] + 1, sizeof *sg->seg)) == NULL) {
        free(fill);
        return FT_E_NOMEM;
    }
    memcpy(fill, sg->start, ncell * sizeof *fill);
    for (size_t s = 0; s < sg->nseg; s++) {
        cell_box b = seg_cells(sg, s);
        for (size_t cy = b.cy0; cy <= b.cy1; cy++)
            for (size_t cx = b.cx0; cx <= b.cx1; cx++)
                sg->seg[fill[cy * sg->g.gx + cx]++] = s;
    }
    free(fill);
    return FT_OK;
}

static int adjacent(const seg_grid *sg, size_t a, size_t b)
{
    size_t lo = a < b ? a : b, hi = a < b ? b : a;
    return hi - lo == 1 || (sg->c->closed && lo == 0 && hi == sg->nseg - 1);
}

/* 1 if segments a and b cross and cell k is the one that counts them. */
static int counts_here(const seg_grid *sg, size_t k, size_t a, size_t b)
{
    double a1x, a1y, a2x, a2y, b1x, b1y, b2x, b2y;
    seg_ends(sg->c, a, &a1x, &a1y, &a2x, &a2y);
    seg_ends(sg->c, b, &b1x, &b1y, &b2x, &b2y);
    double rx = fmax(fmin(a1x, a2x), fmin(b1x, b2x)), ry = fmax(fmin(a1y, a2y), fmin(b1y, b2y));
    if (rx > fmin(fmax(a1x, a2x), fmax(b1x, b2x)) || ry > fmin(fmax(a1y, a2y), fmax(b1y, b2y)))
        return 0;
    if (cell_index(&sg->g, rx, ry) != k)
        return 0;
    return proper(a1x, a1y, a2x, a2y, b1x, b1y, b2x, b2y);
}

static size_t count_cell(const seg_grid *sg, size_t k)
{
    size_t n = 0;
    for (size_t i = sg->start[k]; i < sg->start[k + 1]; i++)
        for (size_t j = i + 1; j < sg->start[k + 1]; j++) {
            size_t a = sg->seg[i], b = sg->seg[j];
            if (!adjacent(sg, a, b) && counts_here(sg, k, a, b))
                n++;
        }
    return n;
}

static int count_crossings(const ft_chain *c, size_t *count)
{
    *count = 0;
    seg_grid sg;
    memset(&sg, 0, sizeof sg);
    sg.c = c;
    sg.nseg = ft_chain_segments(c);
    if (sg.nseg < 3 || !grid_for(c, sg.nseg, &sg.g))
        return FT_OK;
    int rc = seg_grid_build(&sg);
    if (rc == FT_OK) {
        size_t ncell = sg.g.gx * sg.g.gy, total = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : total) if (ncell > 4096)
        for (size_t k = 0; k < ncell; k++)
            total += count_cell(&sg, k);
        *count = total;
    }
    free(sg.start);
    free(sg.seg);
    return rc;
}

static int check_chain(const char *op, const ft_chain *c)
{
    if (c == NULL)
        return ft_error(FT_E_INVALID, "%s: NULL chain", op);
    int rc = ft_chain_check_min_vertices(c, c->closed ? 3 : 2);
    return rc == FT_OK ? ft_chain_check_finite(c) : rc;
}

int ft_line_count_self_intersections(const ft_chain *c, size_t *count)
{
    if (count == NULL)
        return ft_error(FT_E_INVALID, "self-intersections: NULL count");
    *count = 0;
    int rc = check_chain("self-intersections", c);
    return rc == FT_OK ? count_crossings(c, count) : rc;
}

/* ---- loop removal ---------------------------------------------------------------------------------- */

typedef struct {
    size_t seg, next;
    uint32_t gen;
} entry;

typedef struct {
    grid_geom g;
    size_t *head;          /* per cell: first entry or NONE */
    entry *pool;
    size_t npool, cappool;
    uint32_t *gen;         /* per output segment: generation of its current entries */
    ft_chain *out;         /* the walk so far */
} walker;

static int walker_init(walker *w, const ft_chain *in, size_t nwalk)
{
    memset(w, 0, sizeof *w);
    if (!grid_for(in, nwalk - 1, &w->g)) {
        w->g.x0 = in->x[0];
        w->g.y0 = in->y[0];
        w->g.inv = 1.0;
        w->g.gx = w->g.gy = 1;
    }
    size_t ncell = w->g.gx * w->g.gy;
    w->cappool = 2 * nwalk + 16;
    if ((w->head = ft_malloc(ncell * sizeof *w->head)) == NULL ||
        (w->pool = ft_realloc_array(NULL, w->cappool, sizeof *w->pool)) == NULL ||
        (w->gen = ft_calloc(nwalk + 1, sizeof *w->gen)) == NULL ||
        (w->out = ft_chain_create(nwalk + 1, in->closed)) == NULL)
        return FT_E_NOMEM;
    for (size_t k = 0; k < ncell; k++)
        w->head[k] = NONE;
    return FT_OK;
}

static void walker_free(walker *w)
{
    free(w->head);
    free(w->pool);
    free(w->gen);
    ft_chain_free(w->out);
}

/* Registers output segment s (vertex s to s + 1) under a new generation. */
static int insert_segment(walker *w, size_t s)
{
    const ft_chain *o = w->out;
    cell_box b = cells_of(&w->g, o->x[s], o->y[s], o->x[s + 1], o->y[s + 1]);
    uint32_t gen = ++w->gen[s];
    for (size_t cy = b.cy0; cy <= b.cy1; cy++)
        for (size_t cx = b.cx0; cx <= b.cx1; cx++) {
            if (w->npool == w->cappool) {
                entry *p = ft_realloc_array(w->pool, 2 * w->cappool, sizeof *p);
                if (p == NULL)
                    return FT_E_NOMEM;
                w->pool = p;
                w->cappool *= 2;
            }
            size_t k = cy * w->g.gx + cx;
            w->pool[w->npool] = (entry){s, w->head[k], gen};
            w->head[k] = w->npool++;
        }
    return FT_OK;
}

/* The kept segment that L -> B (L the last output vertex) crosses first along L -> B, NONE if none;
 * *t is the parameter of the crossing on L -> B. */
static size_t first_crossing(const walker *w, double bx, double by, double *t)
{
    const ft_chain *o = w->out;
    size_t m = o->n, best = NONE;
    double lx = o->x[m - 1], ly = o->y[m - 1], dx = bx - lx, dy = by - ly;
    cell_box b = cells_of(&w->g, lx, ly, bx, by);
    for (size_t cy = b.cy0; cy <= b.cy1; cy++)
        for (size_t cx = b.cx0; cx <= b.cx1; cx++)
            for (size_t e = w->head[cy * w->g.gx + cx]; e != NONE; e = w->pool[e].next) {
                size_t s = w->pool[e].seg;
                if (s + 2 >= m || w->pool[e].gen != w->gen[s])
                    continue; /* gone, stale, or adjacent to L -> B (s = m - 2) */
                double qx = o->x[s], qy = o->y[s], ex = o->x[s + 1] - qx, ey = o->y[s + 1] - qy;
                if (!proper(lx, ly, bx, by, qx, qy, qx + ex, qy + ey))
                    continue;
                double u = ((qx - lx) * ey - (qy - ly) * ex) / (dx * ey - dy * ex);
                if (best == NONE || u < *t || (u == *t && s < best)) {
                    best = s;
                    *t = u;
                }
            }
    return best;
}

static int push_vertex(walker *w, double x, double y)
{
    ft_chain *o = w->out;
    if (o->n > 0 && o->x[o->n - 1] == x && o->y[o->n - 1] == y)
        return FT_OK;
    o->x[o->n] = x;
    o->y[o->n] = y;
    o->n++;
    return o->n >= 2 ? insert_segment(w, o->n - 2) : FT_OK;
}

/* Appends B after cutting every loop that L -> B closes. */
static int walk_to(walker *w, double bx, double by)
{
    double t = 0.0;
    size_t s;
    while (w->out->n >= 3 && (s = first_crossing(w, bx, by, &t)) != NONE) {
        ft_chain *o = w->out;
        double lx = o->x[o->n - 1], ly = o->y[o->n - 1];
        o->n = s + 1;
        int rc = push_vertex(w, lx + t * (bx - lx), ly + t * (by - ly));
        if (rc != FT_OK)
            return rc;
    }
    return push_vertex(w, bx, by);
}

/* The lowest, then leftmost, vertex of a ring: on its convex hull. */
static size_t hull_vertex(const ft_chain *c)
{
    size_t s = 0;
    for (size_t i = 1; i < c->n; i++)
        if (c->y[i] < c->y[s] || (c->y[i] == c->y[s] && c->x[i] < c->x[s]))
            s = i;
    return s;
}

static int remove_pass(const ft_chain *in, ft_chain **out)
{
    size_t n = in->n, s = in->closed ? hull_vertex(in) : 0, nwalk = in->closed ? n + 1 : n;
    walker w;
    int rc = walker_init(&w, in, nwalk);
    for (size_t k = 0; k < nwalk && rc == FT_OK; k++) {
        size_t i = (s + k) % n;
        rc = walk_to(&w, in->x[i], in->y[i]);
    }
    if (rc == FT_OK && in->closed) {
        ft_chain *o = w.out;
        if (o->n > 1 && o->x[o->n - 1] == o->x[0] && o->y[o->n - 1] == o->y[0])
            o->n--;
        if (o->n < 3)
            rc = ft_error(FT_E_NUMERIC, "remove loops: the ring collapses to %zu vertices", o->n);
    }
    if (rc == FT_OK) {
        *out = w.out;
        w.out = NULL;
    }
    walker_free(&w);
    return rc;
}

int ft_line_remove_loops(const ft_chain *in, ft_chain **out)
{
    int rc = ft_edit_check_chain("remove loops", in, out);
    if (rc != FT_OK)
        return rc;
    ft_chain *cur = NULL;
    size_t crossings = 1;
    for (int pass = 0; pass < REPAIR_PASSES && crossings > 0 && rc == FT_OK; pass++) {
        ft_chain *next = NULL;
        rc = remove_pass(cur ? cur : in, &next);
        ft_chain_free(cur);
        cur = next;
        if (rc == FT_OK)
            rc = count_crossings(cur, &crossings);
    }
    if (rc != FT_OK) {
        ft_chain_free(cur);
        return rc;
    }
    *out = cur;
    return FT_OK;
}
