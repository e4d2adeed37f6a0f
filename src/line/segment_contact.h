/* fracterra — line/segment_contact.h: whether two segments touch, for the crossing guard (move_guard.c):
 * orientation tests on the closed segments, a shared end point allowed unless the two overlap.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_SEGMENT_CONTACT_H
#define FRACTERRA_LINE_SEGMENT_CONTACT_H

#include <math.h>
#include <stddef.h>

static inline double ft_cmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double ft_cmax(double a, double b)
{
    return a > b ? a : b;
}

static inline double ft_orient2(double ax, double ay, double bx, double by, double cx, double cy)
{
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

/* c, known collinear with a b, lies within the closed segment a b. */
static inline int ft_within_segment(double ax, double ay, double bx, double by, double cx, double cy)
{
    return ft_cmin(ax, bx) <= cx && cx <= ft_cmax(ax, bx) && ft_cmin(ay, by) <= cy && cy <= ft_cmax(ay, by);
}

/* The closed segments a b and c d have a point in common. */
static inline int ft_closed_intersect(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                                      double dy)
{
    if (ft_cmax(ax, bx) < ft_cmin(cx, dx) || ft_cmax(cx, dx) < ft_cmin(ax, bx) || ft_cmax(ay, by) < ft_cmin(cy, dy) ||
        ft_cmax(cy, dy) < ft_cmin(ay, by))
        return 0;
    double d1 = ft_orient2(cx, cy, dx, dy, ax, ay), d2 = ft_orient2(cx, cy, dx, dy, bx, by);
    double d3 = ft_orient2(ax, ay, bx, by, cx, cy), d4 = ft_orient2(ax, ay, bx, by, dx, dy);
    if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
        return 1;
    return (d1 == 0 && ft_within_segment(cx, cy, dx, dy, ax, ay)) ||
           (d2 == 0 && ft_within_segment(cx, cy, dx, dy, bx, by)) ||
           (d3 == 0 && ft_within_segment(ax, ay, bx, by, cx, cy)) ||
           (d4 == 0 && ft_within_segment(ax, ay, bx, by, dx, dy));
}

/* Two segments from the shared point s, to a and to c, overlap beyond s: collinear and the same way. */
static inline int ft_segment_fold(double sx, double sy, double ax, double ay, double cx, double cy)
{
    return ft_orient2(sx, sy, ax, ay, cx, cy) == 0 && (ax - sx) * (cx - sx) + (ay - sy) * (cy - sy) > 0;
}

/** 1 if the closed segments a b and c d meet anywhere but at a shared end point (two segments from a
 *  shared end point meet only if they overlap: collinear, the same way). */
static inline int ft_segment_contact(double ax, double ay, double bx, double by, double cx, double cy, double dx,
                                     double dy)
{
    if (ax == cx && ay == cy)
        return ft_segment_fold(ax, ay, bx, by, dx, dy) || (bx == dx && by == dy && (ax != bx || ay != by));
    if (ax == dx && ay == dy)
        return ft_segment_fold(ax, ay, bx, by, cx, cy) || (bx == cx && by == cy && (ax != bx || ay != by));
    if (bx == cx && by == cy)
        return ft_segment_fold(bx, by, ax, ay, dx, dy);
    if (bx == dx && by == dy)
        return ft_segment_fold(bx, by, ax, ay, cx, cy);
    return ft_closed_intersect(ax, ay, bx, by, cx, cy, dx, dy);
}

/* p lies strictly inside the triangle a b c (either orientation). */
static inline int ft_strictly_inside(const double *a, const double *b, const double *c, double px, double py)
{
    double o1 = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0]);
    double o2 = (c[0] - b[0]) * (py - b[1]) - (c[1] - b[1]) * (px - b[0]);
    double o3 = (a[0] - c[0]) * (py - c[1]) - (a[1] - c[1]) * (px - c[0]);
    return (o1 > 0 && o2 > 0 && o3 > 0) || (o1 < 0 && o2 < 0 && o3 < 0);
}

/** The exact part of ft_move_sweeps for one segment p0 p1 to p2 p3 (its box already known to meet the move's):
 *  contact with a b, b cc or the path b0 b, or its first end point strictly inside a b0 b or b0 b cc. */
static inline int ft_move_sweeps_segment(double p0, double p1, double p2, double p3, const double *a,
                                         const double *b0, const double *b, const double *cc)
{
    if (a && ft_segment_contact(a[0], a[1], b[0], b[1], p0, p1, p2, p3))
        return 1;
    if (cc && ft_segment_contact(b[0], b[1], cc[0], cc[1], p0, p1, p2, p3))
        return 1;
    if (ft_segment_contact(b0[0], b0[1], b[0], b[1], p0, p1, p2, p3))
        return 1;
    return (a && ft_strictly_inside(a, b0, b, p0, p1)) || (cc && ft_strictly_inside(b0, b, cc, p0, p1));
}

/** 1 if moving a vertex from b0 to b, its neighbours a and cc (NULL when absent) staying, sweeps one of the
 *  segments s0 .. s1 - 1 (segment s: vertex s to s + 1, a ring's last back to 0) of the chain x, y of n
 *  vertices other than the skip_n segments from skip (cyclically; the moved vertex's own, and those already
 *  cleared): contact with a b, b cc or the path b0 b, or a segment's first end point strictly inside the
 *  triangles a b0 b, b0 b cc. box is the bounding box of a, b0, b and cc. Used by the crossing guards
 *  (move_guard.c, dutton_guarded.c). */
static inline int ft_move_sweeps(const double *x, const double *y, size_t n, size_t s0, size_t s1, size_t skip,
                                 size_t skip_n, const double box[4], const double *a, const double *b0, const double *b,
                                 const double *cc)
{
    for (size_t s = s0; s < s1; s++) {
        if (s - skip < skip_n || s + n - skip < skip_n)
            continue;
        size_t j = s + 1 < n ? s + 1 : 0;
        double p0 = x[s], p1 = y[s], p2 = x[j], p3 = y[j];
        if (ft_cmax(p0, p2) < box[0] || ft_cmin(p0, p2) > box[2] || ft_cmax(p1, p3) < box[1] ||
            ft_cmin(p1, p3) > box[3])
            continue;
        if (ft_move_sweeps_segment(p0, p1, p2, p3, a, b0, b, cc))
            return 1;
    }
    return 0;
}

/** 1 if the segment from x to p certainly meets the convex hull of x, q0, q1 and q2 only at x: some line
 *  through x along one of the directions q - x has q0, q1, q2 strictly on one side (by a relative margin of
 *  1e-9) and p strictly on the other. 0 when not sure (the hull's angle at x near pi or above, p near its
 *  edge, a zero-length direction). Exact reasoning: the half-plane holds the hull, and the segment leaves it
 *  at x. */
static inline __attribute__((always_inline)) int ft_leaves_hull(const double *x, const double *p, const double *q0,
                                                                const double *q1, const double *q2)
{
    const double eps2 = 1e-18; /* the margin, squared: the tests compare squares, no square root */
    double ux = p[0] - x[0], uy = p[1] - x[1];
    double d[3][2] = {{q0[0] - x[0], q0[1] - x[1]}, {q1[0] - x[0], q1[1] - x[1]}, {q2[0] - x[0], q2[1] - x[1]}};
    double len2[3], lu2 = ux * ux + uy * uy;
    for (int j = 0; j < 3; j++)
        len2[j] = d[j][0] * d[j][0] + d[j][1] * d[j][1];
    for (int i = 0; i < 3; i++) {
        double nx = -d[i][1], ny = d[i][0]; /* d_i turned +90 degrees; |n| = |d_i| */
        double nu = nx * ux + ny * uy;
        if (!(nu * nu > eps2 * len2[i] * lu2))
            continue;
        double sgn = nu < 0.0 ? 1.0 : -1.0; /* the side of the q's: opposite to p */
        int ok = 1;
        for (int j = 0; j < 3 && ok; j++) {
            double v = sgn * (nx * d[j][0] + ny * d[j][1]);
            ok = j == i || (v > 0.0 && v * v > eps2 * len2[i] * len2[j]);
        }
        if (ok)
            return 1;
    }
    return 0;
}

#endif /* FRACTERRA_LINE_SEGMENT_CONTACT_H */
