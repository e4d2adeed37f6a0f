/* fracterra — line/dutton_calibrate.c: calibrated mode of Dutton's (1981) enhancement: the apex angle that
 * gives the enhanced chain a wanted divider dimension, and the dimension an apex angle gives.
 *
 * Why SD's literal angle (pi - 2a, cos a = 2^(1/SD - 1), the midpoint generator of Zhang et al. 2008 Eq. 9)
 * does not give dimension SD, and what does (alpha = (pi - theta) / 2 is the base angle of the apex theta):
 *  1. A junction that already has the apex angle theta is its own standard position (dutton.c), so after
 *     the first pass the former vertices never move again (uc = 1, no tolerances): every pass moves exactly
 *     the previous pass's midpoints.
 *  2. Hence the piece of chain between two consecutive standardized vertices L and R, with the previous
 *     midpoint N between them, evolves on its own: a cell (L, N, R). A pass moves N to its standard
 *     position N' and leaves the cells (L, M1, N') and (N', M2, R), M1 and M2 the midpoints of LN and NR.
 *     With a = |LN|, c = |NR| and the legs p = b a / E, q = b c / E of dutton.c (2b = |LR|,
 *     E^2 = a^2 + c^2 - 2 a c cos theta) the cell's length a + c becomes a/2 + p + q + c/2, a growth of
 *         g = 1/2 + |LR| / (2E)     (for a = c and N bent by 2 beta: g = (1 + cos beta / cos alpha) / 2).
 *     Only the halves next to N grow; the halves next to L and R are carried over. The midpoint generator
 *     moves every vertex of a straight line (beta = 0) and grows by 1 / cos alpha: Dutton's pass grows by
 *     at most half as much above 1 (exactly half if N were straight; it is already bent).
 *  3. M1 bends by the angle through which N' leaves the line LN as seen from M1: for a = c, beta' =
 *     (alpha - beta) / 2, whose fixed point beta = alpha / 3 gives the symmetric estimate
 *         f ~ (1 + cos(alpha / 3) / cos alpha) / 2     (1.0772 at SD = 1.3; measured on chains 1.0766).
 *     But the new cells have unequal legs (a / 2 against p), the leg ratios and bends spread over the
 *     cells, and the estimate drifts high as alpha grows (apex 70 degrees: 1.329 against 1.289). So the
 *     steady-state growth f(theta) is computed: the cells of a canonical junction (legs 1 and 1, bent
 *     halfway between straight and theta) are followed depth-first for CELL_DEPTH passes, summing the
 *     chain length L_k of each pass, and f = sqrt(L_K / L_(K-2)) (the growth alternates about its limit
 *     with a ratio near -1/2; two passes cancel that). The limit does not depend on the starting cell:
 *     junction angles of 60 to 170 degrees and leg ratios 0.4 to 2.5 agree to 2e-4 in f at depth 12 and
 *     2e-5 at depth 16 (apex 70 degrees; closer at wider apexes), about 1e-3 in D at depth 12. It is the
 *     growth measured on whole enhanced chains: random walks and the 158-point Newfoundland coast give D
 *     within 0.002 of it from 1.1 to 1.7, a 16-gon within 0.008 (tests/unit/test_line_dutton_calibrated.c).
 *  4. After k passes the chain has 2^k times the segments and f^k times the length: its mean segment is
 *     (f / 2)^k times the input's, and the divider, whose rulers follow the segments, measures
 *         D = ln 2 / ln(2 / f)
 *     (two pieces of mean ratio f / 2; not 1 + log2 f, which would hold if the rulers halved per pass).
 *     Measured with rulers well inside the generated scales (12 passes, rulers from 8 output segments to
 *     a quarter of an input segment) the divider gives this D within 0.02 up to D = 1.5 on those inputs.
 *     At rulers of a few segments it reads low (6 passes, fine scales: 1.25-1.27 for D = 1.3).
 *  5. D(theta) rises from 1 at theta = pi as the apex closes. Below about 73 degrees the
 *     steady state starts to cross itself, and below 60 degrees (FT_DUTTON_APEX_MIN, an equilateral
 *     apex, where SD -> infinity would put the literal relation) the measured divider stops rising
 *     (~1.70 - 1.76): calibrated mode stops there, at D(60 degrees) = 1.777.
 * ft_dutton_apex_for_dimension inverts D(theta) by bisection on [60 degrees, pi]: about 40 evaluations of a
 * 2^12-cell recursion, a few milliseconds, cached per thread for the last target (a layer enhances many
 * arcs with one target). Everything is deterministic: fixed start, fixed depth, fixed summation order.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/line.h"
#include "line/dutton_internal.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define CELL_DEPTH 12        /* passes followed from the canonical cell */
#define BISECT_TOL 1e-12     /* radians: the apex angle is found to this width */

typedef struct {
    double cos_t, sin_t;
    double len[CELL_DEPTH + 1]; /* chain length after each pass */
} cell_walk;

/* Adds cell (L, N, R)'s length at `depth`, then moves N (item 2) and follows its two child cells. */
static void cell_grow(cell_walk *w, double lx, double ly, double nx, double ny, double rx, double ry, int depth)
{
    w->len[depth] += hypot(nx - lx, ny - ly) + hypot(rx - nx, ry - ny);
    if (depth == CELL_DEPTH)
        return;
    double sx, sy;
    ft_dutton_move(lx, ly, nx, ny, rx, ry, w->cos_t, w->sin_t, 1.0, 0, &sx, &sy);
    cell_grow(w, lx, ly, 0.5 * (lx + nx), 0.5 * (ly + ny), sx, sy, depth + 1);
    cell_grow(w, sx, sy, 0.5 * (nx + rx), 0.5 * (ny + ry), rx, ry, depth + 1);
}

/* Steady-state length growth per pass for apex angle theta (item 3). */
static double steady_growth(double theta)
{
    cell_walk w = {cos(theta), sin(theta), {0.0}};
    double phi = 0.5 * (PI + theta); /* the canonical cell: legs 1, 1, bent halfway to theta */
    cell_grow(&w, 0.0, 0.0, 1.0, 0.0, 1.0 - cos(phi), sin(phi), 0);
    return sqrt(w.len[CELL_DEPTH] / w.len[CELL_DEPTH - 2]);
}

double ft_dutton_steady_dimension(double apex)
{
    if (!(apex >= FT_DUTTON_APEX_MIN && apex <= PI))
        return NAN;
    double f = steady_growth(apex);
    return log(2.0) / log(2.0 / f); /* item 4 */
}

/* Bisection: D(theta) decreases from D(60 degrees) to D(pi) = 1. */
static double bisect_apex(double target_dim)
{
    double lo = FT_DUTTON_APEX_MIN, hi = PI;
    while (hi - lo > BISECT_TOL) {
        double mid = 0.5 * (lo + hi);
        if (ft_dutton_steady_dimension(mid) > target_dim)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* ---- UC < 1 (item 6) --------------------------------------------------------------------------- */

#define UC_RING 12   /* vertices of the star ring the steady state is measured on */
#define UC_PASSES 10 /* passes: 12 * 2^10 vertices */

static double ring_length(const double *x, const double *y, size_t n)
{
    double s = 0.0;
    for (size_t i = 0; i < n; i++)
        s += hypot(x[(i + 1) % n] - x[i], y[(i + 1) % n] - y[i]);
    return s;
}

/* One pass on a ring of n vertices (a, b) into 2n (c, d): every vertex moved, every segment split. */
static void ring_pass(const double *ax, const double *ay, size_t n, double cos_t, double sin_t, double uc, double *cx,
                      double *cy)
{
    for (size_t i = 0; i < n; i++) {
        size_t ip = (i + n - 1) % n, in = (i + 1) % n;
        ft_dutton_move(ax[ip], ay[ip], ax[i], ay[i], ax[in], ay[in], cos_t, sin_t, uc, 0, &cx[2 * i],
                       &cy[2 * i]);
        cx[2 * i + 1] = 0.5 * (ax[i] + ax[in]);
        cy[2 * i + 1] = 0.5 * (ay[i] + ay[in]);
    }
}

static double steady_dimension_ring(double apex, double uc)
{
    const size_t nmax = (size_t)UC_RING << UC_PASSES;
    double *buf = malloc(4 * nmax * sizeof *buf);
    if (buf == NULL)
        return NAN;
    double *x = buf, *y = buf + nmax, *nx = buf + 2 * nmax, *ny = buf + 3 * nmax;
    const double two_pi = 2.0 * PI;
    for (size_t i = 0; i < UC_RING; i++) { /* a star: radii 1 and 0.6 alternate */
        double r = i % 2 ? 0.6 : 1.0, a = two_pi * (double)i / UC_RING;
        x[i] = r * cos(a);
        y[i] = r * sin(a);
    }
    size_t n = UC_RING;
    double len[UC_PASSES + 1];
    len[0] = ring_length(x, y, n);
    for (int k = 1; k <= UC_PASSES; k++) {
        ring_pass(x, y, n, cos(apex), sin(apex), uc, nx, ny);
        n *= 2;
        double *t = x;
        x = nx;
        nx = t;
        t = y;
        y = ny;
        ny = t;
        len[k] = ring_length(x, y, n);
    }
    free(buf);
    double f = sqrt(len[UC_PASSES] / len[UC_PASSES - 2]);
    return log(2.0) / log(2.0 / f);
}

double ft_dutton_steady_dimension_uc(double apex, double uc)
{
    if (!(apex >= FT_DUTTON_APEX_MIN && apex <= PI) || !(uc > 0.0 && uc <= 1.0))
        return NAN;
    return uc == 1.0 ? ft_dutton_steady_dimension(apex) : steady_dimension_ring(apex, uc);
}

double ft_dutton_max_dimension(double uc)
{
    return ft_dutton_steady_dimension_uc(FT_DUTTON_APEX_MIN, uc);
}

double ft_dutton_apex_for_target(double target_dim, double uc)
{
    if (uc == 1.0)
        return ft_dutton_apex_for_dimension(target_dim);
    double dmax = ft_dutton_max_dimension(uc);
    if (isnan(dmax) || !(target_dim >= 1.0 && target_dim <= dmax))
        return NAN;
    if (target_dim == 1.0)
        return PI;
    double lo = FT_DUTTON_APEX_MIN, hi = PI;
    while (hi - lo > 1e-9) { /* the ring's D is smooth in the angle; 1e-9 rad is far below its noise */
        double mid = 0.5 * (lo + hi);
        if (steady_dimension_ring(mid, uc) > target_dim)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

double ft_dutton_target_dimension(double sd, double uc, double input_dim)
{
    return input_dim + uc * (sd - input_dim);
}

double ft_dutton_apex_for_dimension(double target_dim)
{
    static _Thread_local double cached_target = NAN, cached_apex = NAN;
    if (target_dim == cached_target)
        return cached_apex;
    if (!(target_dim >= 1.0 && target_dim <= ft_dutton_steady_dimension(FT_DUTTON_APEX_MIN)))
        return NAN;
    double apex = target_dim == 1.0 ? PI : bisect_apex(target_dim);
    cached_target = target_dim;
    cached_apex = apex;
    return apex;
}
