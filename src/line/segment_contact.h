/* fracterra — line/segment_contact.h: whether two segments touch, for the crossing guard (move_guard.c):
 * orientation tests on the closed segments, a shared end point allowed unless the two overlap.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_SEGMENT_CONTACT_H
#define FRACTERRA_LINE_SEGMENT_CONTACT_H

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

#endif /* FRACTERRA_LINE_SEGMENT_CONTACT_H */
