/* fracterra — line/dutton_internal.h: the standard position of one junction in Dutton's (1981) enhancement,
 * shared by the enhancement pass (dutton.c) and the steady-state calibration (dutton_calibrate.c), so both
 * move a vertex with the very same arithmetic. The derivation is in dutton.c's header.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_DUTTON_INTERNAL_H
#define FRACTERRA_LINE_DUTTON_INTERNAL_H

#include <math.h>

#define FT_DUTTON_STRAIGHT_SIN 1e-12 /* a junction turning less than this (sin of the turn) has no side */

/** V's new position V + uc (V* - V) in (*ox, *oy), V* the apex of the triangle on the midpoints M1 M2 of
 *  P V and V N with apex angle theta (cos_t, sin_t), legs in the ratio |PV| / |VN|, on V's side of M1 M2.
 *  A straight junction (V on P N, going on) has no side: with straight_side 0 it stays; +1 or -1 puts V*
 *  left or right of P -> N. Returns 0 (and V itself) if V stays (no side, a reversal, a zero-length
 *  segment). */
static inline int ft_dutton_move(double px, double py, double vx, double vy, double nx, double ny, double cos_t,
                                 double sin_t, double uc, int straight_side, double *ox, double *oy)
{
    double ax = vx - px, ay = vy - py, cx = nx - vx, cy = ny - vy;
    double a2 = ax * ax + ay * ay, c2 = cx * cx + cy * cy;
    double ac = sqrt(a2 * c2);
    double turn = ax * cy - ay * cx; /* a c sin(turn): < 0 turning right, so V is left of P -> N */
    *ox = vx;
    *oy = vy;
    double side;
    if (fabs(turn) > FT_DUTTON_STRAIGHT_SIN * ac)
        side = turn < 0.0 ? 1.0 : -1.0;
    else if (straight_side != 0 && ac > 0.0 && ax * cx + ay * cy > 0.0)
        side = straight_side > 0 ? 1.0 : -1.0;
    else
        return 0;
    double e2 = a2 + c2 - 2.0 * ac * cos_t;
    double s = 0.5 * (1.0 + (a2 - c2) / e2);
    double h = side * ac * sin_t / e2;
    double ux = 0.5 * (nx - px), uy = 0.5 * (ny - py); /* M2 - M1 */
    double sx = 0.5 * (px + vx) + s * ux - h * uy;
    double sy = 0.5 * (py + vy) + s * uy + h * ux;
    *ox = vx + uc * (sx - vx);
    *oy = vy + uc * (sy - vy);
    return 1;
}

#endif /* FRACTERRA_LINE_DUTTON_INTERNAL_H */
