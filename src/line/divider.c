/* fracterra — src/line/divider.c: the walking divider (structured walk) of Richardson, as Mandelbrot
 * (1977, p. 32) describes it and Dutton (1981) uses it, in Clarke's (1987) words:
 * "opening a set of dividers to a spacing d, then walking the dividers along the line, taking a total of
 * N steps ... N should contain a fraction of a step at the end of the line"; L(d) = N d and
 * D = 1 - b with b the slope of log L on log d (Clarke eq. ii-iii; Zhang et al. 2008,
 * "Structured Walk method").
 *
 * Each step ends at the first point of the chain, after the current point, at distance d from it: the
 * chain is scanned forward vertex by vertex while the vertices stay inside the circle of radius d; on
 * the first segment that leaves it the exit point solves |A + t (B - A) - P| = d (the larger root, A being
 * inside). A segment whose two ends are inside the circle lies inside it (the disc is convex), so no exit
 * is missed. The scan pointer only moves forward: one walk is O(n + N). The last, fractional step is the
 * straight distance from the last divider point to the end of the chain (to vertex 0 for a ring).
 * The same walk runs in 3-D on a geographic chain turned into Earth-centred coordinates (line_dim.c):
 * the circle becomes a sphere, the ruler a chord in metres.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/line.h"
#include "line/line_dim_internal.h"

void ft_walk_src_init(ft_walk_src *w, const ft_chain *c, int from_end)
{
    w->x = c->x;
    w->y = c->y;
    w->z = NULL;
    w->n = c->n;
    w->m = c->closed ? c->n + 1 : c->n;
    w->backward = c->closed ? 0 : (from_end != 0);
    w->off = 0;
}

/* Parameter t in [0, 1] where A + t (B - A) leaves the circle of radius^2 r2 around P, A inside it and B
 * on or outside it: the larger root of a t^2 + 2 b t + c = 0, written to avoid cancellation. */
static double circle_exit(double ax, double ay, double bx, double by, double px, double py, double r2)
{
    double ex = bx - ax, ey = by - ay;
    double fx = ax - px, fy = ay - py;
    double a = ex * ex + ey * ey;
    double b = fx * ex + fy * ey;
    double c = fx * fx + fy * fy - r2;
    double disc = b * b - a * c;
    double sq = sqrt(disc > 0.0 ? disc : 0.0);
    double t = b >= 0.0 ? -c / (b + sq) : (sq - b) / a;
    return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
}

/* One structured walk along a planar w with ruler r: the walked length (whole steps plus the last fraction). */
static void walk_plane(const ft_walk_src *w, double r, double *length, size_t *steps)
{
    const double r2 = r * r;
    double px, py, ax, ay;
    ft_walk_vertex(w, 0, &px, &py);
    ax = px;
    ay = py;
    size_t nsteps = 0;
    for (size_t k = 1; k < w->m;) {
        double bx, by;
        ft_walk_vertex(w, k, &bx, &by);
        double dx = bx - px, dy = by - py;
        if (dx * dx + dy * dy < r2) { /* B still inside: the walk's next point lies further on */
            ax = bx;
            ay = by;
            k++;
            continue;
        }
        double t = circle_exit(ax, ay, bx, by, px, py, r2);
        px = ax + t * (bx - ax);
        py = ay + t * (by - ay);
        ax = px;
        ay = py;
        nsteps++;
    }
    double ex, ey;
    ft_walk_vertex(w, w->m - 1, &ex, &ey);
    *length = (double)nsteps * r + hypot(ex - px, ey - py);
    *steps = nsteps;
}

/* Parameter t in [0, 1] where A + t (B - A) leaves the sphere (circle in the plane, d3 = 0) of radius^2 r2
 * around P, A inside it and B on or outside it: the larger root of a t^2 + 2 b t + c = 0, written to avoid
 * cancellation. */
FT_WALK_INLINE double sphere_exit(const double *a3, const double *b3, const double *p3, double r2, int d3)
{
    double ex = b3[0] - a3[0], ey = b3[1] - a3[1];
    double fx = a3[0] - p3[0], fy = a3[1] - p3[1];
    double a = ex * ex + ey * ey;
    double b = fx * ex + fy * ey;
    double c = fx * fx + fy * fy - r2;
    if (d3) {
        double ez = b3[2] - a3[2], fz = a3[2] - p3[2];
        a += ez * ez;
        b += fz * ez;
        c += fz * fz;
    }
    double disc = b * b - a * c;
    double sq = sqrt(disc > 0.0 ? disc : 0.0);
    double t = b >= 0.0 ? -c / (b + sq) : (sq - b) / a;
    return t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
}

/* One structured walk along w with ruler r: the walked length (whole steps plus the last fraction). d3: a
 * constant, 1 for Earth-centred chains (w->z set); the planar walk never touches z. */
FT_WALK_INLINE void walk_impl(const ft_walk_src *w, double r, double *length, size_t *steps, int d3)
{
    const double r2 = r * r;
    double p[3], a[3];
    ft_walk_vertex3(w, 0, &p[0], &p[1], &p[2], d3);
    a[0] = p[0];
    a[1] = p[1];
    a[2] = p[2];
    size_t nsteps = 0;
    for (size_t k = 1; k < w->m;) {
        double b[3];
        ft_walk_vertex3(w, k, &b[0], &b[1], &b[2], d3);
        double dx = b[0] - p[0], dy = b[1] - p[1], d2 = dx * dx + dy * dy;
        if (d3)
            d2 += (b[2] - p[2]) * (b[2] - p[2]);
        if (d2 < r2) { /* B still inside: the walk's next point lies further on */
            a[0] = b[0];
            a[1] = b[1];
            if (d3)
                a[2] = b[2];
            k++;
            continue;
        }
        double t = sphere_exit(a, b, p, r2, d3);
        a[0] = p[0] = a[0] + t * (b[0] - a[0]);
        a[1] = p[1] = a[1] + t * (b[1] - a[1]);
        if (d3)
            a[2] = p[2] = a[2] + t * (b[2] - a[2]);
        nsteps++;
    }
    double e[3];
    ft_walk_vertex3(w, w->m - 1, &e[0], &e[1], &e[2], d3);
    *length = (double)nsteps * r + (d3 ? ft_walk_dist(e[0] - p[0], e[1] - p[1], e[2] - p[2])
                                       : hypot(e[0] - p[0], e[1] - p[1]));
    *steps = nsteps;
}

static void walk(const ft_walk_src *w, double r, double *length, size_t *steps)
{
    if (w->z)
        walk_impl(w, r, length, steps, 1);
    else
        walk_plane(w, r, length, steps);
}

void ft_line_divider_length(const ft_chain *c, const double *z, double r, int both_ends, double *length,
                            double *steps)
{
    ft_walk_src w;
    double len;
    size_t st;
    ft_walk_src_init(&w, c, 0);
    w.z = z;
    walk(&w, r, &len, &st);
    if (c->closed || !both_ends) {
        *length = len;
        *steps = (double)st;
        return;
    }
    double len2;
    size_t st2;
    ft_walk_src_init(&w, c, 1);
    w.z = z;
    walk(&w, r, &len2, &st2);
    *length = 0.5 * (len + len2);
    *steps = 0.5 * ((double)st + (double)st2);
}

void ft_line_divider_ring_from(const ft_chain *c, const double *z, size_t off, double r, double *length,
                               double *steps)
{
    ft_walk_src w;
    size_t st;
    ft_walk_src_init(&w, c, 0);
    w.z = z;
    w.off = off < c->n ? off : 0;
    walk(&w, r, length, &st);
    *steps = (double)st;
}

void ft_line_ring_starts(const ft_chain *c, const double *z, size_t nstarts, size_t *start)
{
    double total = 0.0;
    for (size_t i = 0; i < c->n; i++) {
        size_t j = i + 1 == c->n ? 0 : i + 1;
        total += ft_walk_dist(c->x[j] - c->x[i], c->y[j] - c->y[i], z ? z[j] - z[i] : 0.0);
    }
    double s = 0.0; /* arc length from vertex 0 to vertex i */
    size_t i = 0;
    for (size_t k = 0; k < nstarts; k++) {
        double want = total * (double)k / (double)nstarts;
        while (i + 1 < c->n && s < want) {
            s += ft_walk_dist(c->x[i + 1] - c->x[i], c->y[i + 1] - c->y[i], z ? z[i + 1] - z[i] : 0.0);
            i++;
        }
        start[k] = i;
    }
}

int ft_line_divider_walk(const ft_chain *c, double ruler, int from_end, double *length, size_t *steps)
{
    if (c == NULL || length == NULL)
        return ft_error(FT_E_INVALID, "ft_line_divider_walk: NULL %s", c == NULL ? "chain" : "length");
    if (!(ruler > 0.0) || !isfinite(ruler))
        return ft_error(FT_E_INVALID, "ruler must be finite and > 0, got %g", ruler);
    int rc = ft_chain_check_min_vertices(c, 2);
    if (rc == FT_OK)
        rc = ft_chain_check_finite(c);
    if (rc != FT_OK)
        return rc;
    ft_walk_src w;
    size_t st;
    ft_walk_src_init(&w, c, from_end);
    walk(&w, ruler, length, &st);
    if (steps != NULL)
        *steps = st;
    return FT_OK;
}
