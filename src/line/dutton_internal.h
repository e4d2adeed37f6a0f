/* fracterra — line/dutton_internal.h: the standard position of one junction in Dutton's (1981) enhancement,
 * shared by the enhancement pass (dutton.c) and the steady-state calibration (dutton_calibrate.c), so both
 * move a vertex with the very same arithmetic. The derivation is in dutton.c's header.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_DUTTON_INTERNAL_H
#define FRACTERRA_LINE_DUTTON_INTERNAL_H

#include <math.h>

#include "fracterra/line.h"
#include "line/edit_internal.h"

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

/** One pass's parameters (dutton.c): the apex angle, UC, the segment window, and whether straight junctions
 *  bend (calibrated mode, alternating sides). */
typedef struct {
    double cos_t, sin_t, uc;
    ft_edit_window w;
    int bend_straight;
    int keep_vertices; /* only the new midpoints move (emit_vertex in dutton.c) */
} ft_dutton_pass_params;

/** split[i] = 1 if segment i (vertex i to i+1, cyclically on a ring) is in the window. */
void ft_dutton_mark_splits(const ft_chain *in, size_t nseg, ft_edit_window w, unsigned char *split);

/** Checks a pass's input chain and plan, fills *pp and, in calibrated mode, the densified chain the pass
 *  works on (*dense; NULL when no segment needs cutting or on failure: then the pass works on in). */
int ft_dutton_pass_prepare(const ft_chain *in, const ft_dutton_plan *p, ft_dutton_pass_params *pp, ft_chain **dense);

/** Where a pass puts vertex i of in (split from ft_dutton_mark_splits): moved iff both its segments are
 *  split. Returns 1 if it moves (even by nothing), 0 if it stays; (*x, *y) is the position either way. */
static inline int ft_dutton_raw_vertex(const ft_chain *in, const unsigned char *split, const ft_dutton_pass_params *pp,
                                       size_t i, double *x, double *y)
{
    size_t n = in->n;
    int has_prev = in->closed || i > 0, has_next = in->closed || i + 1 < n;
    size_t ip = i > 0 ? i - 1 : n - 1, in_ = i + 1 < n ? i + 1 : 0;
    *x = in->x[i];
    *y = in->y[i];
    if (!(has_prev && has_next && split[ip] && split[i]))
        return 0;
    return ft_dutton_move(in->x[ip], in->y[ip], in->x[i], in->y[i], in->x[in_], in->y[in_], pp->cos_t, pp->sin_t,
                          pp->uc, pp->bend_straight ? (i % 2 ? 1 : -1) : 0, x, y);
}

/** The raw positions (ft_dutton_raw_vertex) of vertices [v0, v1) of in: vertex v's at xy[2 (v - v0)] and
 *  xy[2 (v - v0) + 1]. Several vertices at a time, with the very bits of ft_dutton_raw_vertex (dutton_raw.c). */
void ft_dutton_raw_run(const ft_chain *in, const unsigned char *split, const ft_dutton_pass_params *pp, size_t v0,
                       size_t v1, double *xy);

/** The paths of ft_dutton_raw_run: the widest the processor has (the default), one vertex at a time, AVX2, AVX-512. */
enum { FT_DUTTON_RAW_AUTO, FT_DUTTON_RAW_SCALAR, FT_DUTTON_RAW_AVX2, FT_DUTTON_RAW_AVX512 };

/** Tests only: makes ft_dutton_raw_run take path (FT_DUTTON_RAW_*). Returns 1, or 0 (and changes nothing) if
 *  the processor cannot run it. */
int ft_dutton_raw_force(int path);

/** 1 if the fused guarded pass below does with plan p what ft_line_pass_enhance and the crossing guard do: the
 *  pass moves only the input's vertices, never the new midpoints (their fixed places are what the fusion rests
 *  on). A plan whose pass moves the midpoints must give 0 here (ft_line_run_passes then takes the unfused
 *  guard). */
int ft_dutton_plan_fusable(const ft_dutton_plan *p);

/** What one fused pass hands the next: its block index, so that the next pass's near lists come from it
 *  with no grid join (dutton_guarded.c). */
typedef struct ft_dutton_carry ft_dutton_carry;
ft_dutton_carry *ft_dutton_carry_create(void);
void ft_dutton_carry_free(ft_dutton_carry *k);

/** One guarded pass of the enhancement over the chain set in[0..n) (guard fused into the pass,
 *  dutton_guarded.c): out[c] receives chain c's result (repeated vertices not yet removed); stats (may be
 *  NULL) is added to. carry (may be NULL) holds the pass before's index, which this pass uses if in is that
 *  pass's output unchanged, and receives this pass's when passes_left (the passes still to come) > 0. The
 *  result does not depend on carry. On failure every out[c] is NULL. */
int ft_dutton_pass_guarded(const ft_chain *const *in, size_t n, const ft_dutton_plan *p, ft_chain **out,
                           ft_line_guard_stats *stats, ft_dutton_carry *carry, int passes_left);

/** Tests only: 1 makes the fused pass's walk screen segment boxes in plain C even where AVX-512 runs (it
 *  must give the same bits); 0 (the default) lets it pick. */
void ft_dutton_guard_generic(int on);

#endif /* FRACTERRA_LINE_DUTTON_INTERNAL_H */
