/* fracterra — recon_stencil.c: the discrete energy of the reconstruction and its Gauss-Seidel sweeps
 * (Arakawa & Krotkov §3.2 eqs. 6, 9-10; Szeliski 1990; Terzopoulos' splines under tension).
 *
 * On a level with node spacing h = 1 (in the level's own nodes) the energy is
 *     E(u) = sum_i c_i/2 (u_i - d_i)² + tp/2 [sum (u_xx)² + 2 sum (u_xy)² + sum (u_yy)²] + mem/2 sum |grad u|²
 * with u_xx = u(x-1) - 2 u(x) + u(x+1) at every node whose two neighbours exist, u_xy = the mixed
 * difference of every 2 x 2 block of nodes, grad u = the forward differences of every pair of neighbours:
 * only the differences that fit in the grid count (natural boundary conditions). E = 1/2 u'Au - u'b + k
 * (eq. 9) with, inside the grid, the 13-node thin-plate stencil (20, -8, 2, 1) and the 5-node membrane
 * stencil (4, -1); near the edges (A u)_i is summed term by term. The Gauss-Seidel update of node i is
 * u+_i = u_i + (b_i - (A u)_i) / a_ii.
 *
 * Colours: node (x, y) has colour (x + 2y) mod 5; the stencil's offsets (±1, 0), (0, ±1), (±1, ±1),
 * (±2, 0), (0, ±2) all change it, so nodes of one colour never see each other: a colour's rows are updated
 * in parallel and the sweep's result does not depend on the thread count.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define NCOLOURS 5
/* The wavefront's lag in rows between consecutive colours: more than the stencil's reach (2 rows). */
#define WAVE_LAG 3

double ft_recon_prior_diag(const ft_recon_level *L)
{
    return 20.0 * L->tp + 4.0 * L->mem;
}

/* Node (x, y) of level L near an edge: (A x)_i summed term by term, and a_ii. */
static double apply_edge(const ft_recon_level *L, const float *u, size_t x, size_t y, double *diag)
{
    size_t nx = L->nx, ny = L->ny;
    long X = (long)x, Y = (long)y, NX = (long)nx, NY = (long)ny;
#define U(a, b) ((double)u[(size_t)(b) * nx + (size_t)(a)])
    double gtp = 0.0, dtp = 0.0, gm = 0.0, dm = 0.0;
    /* u_xx and u_yy centred at x-1, x, x+1 (and y-1, y, y+1) */
    for (long c = X - 1; c <= X + 1; c++)
        if (c - 1 >= 0 && c + 1 < NX) {
            double e = U(c - 1, Y) - 2.0 * U(c, Y) + U(c + 1, Y), k = c == X ? -2.0 : 1.0;
            gtp += k * e;
            dtp += k * k;
        }
    for (long c = Y - 1; c <= Y + 1; c++)
        if (c - 1 >= 0 && c + 1 < NY) {
            double e = U(X, c - 1) - 2.0 * U(X, c) + U(X, c + 1), k = c == Y ? -2.0 : 1.0;
            gtp += k * e;
            dtp += k * k;
        }
    /* u_xy of the four 2 x 2 blocks that hold the node (weight 2) */
    for (long cx = X - 1; cx <= X; cx++)
        for (long cy = Y - 1; cy <= Y; cy++)
            if (cx >= 0 && cy >= 0 && cx + 1 < NX && cy + 1 < NY) {
                double e = U(cx, cy) - U(cx + 1, cy) - U(cx, cy + 1) + U(cx + 1, cy + 1);
                double k = ((cx == X) == (cy == Y)) ? 1.0 : -1.0;
                gtp += 2.0 * k * e;
                dtp += 2.0;
            }
    /* membrane: the node's neighbours */
    double ui = U(X, Y);
    static const long off[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    for (int k = 0; k < 4; k++) {
        long a = X + off[k][0], b = Y + off[k][1];
        if (a >= 0 && b >= 0 && a < NX && b < NY) {
            gm += ui - U(a, b);
            dm += 1.0;
        }
    }
#undef U
    double ci = L->c[y * nx + x];
    *diag = L->tp * dtp + L->mem * dm + ci;
    return L->tp * gtp + L->mem * gm + ci * ui;
}

/* Interior node (2 <= x < nx - 2, 2 <= y < ny - 2): the 13-node stencil. */
static inline double apply_inner(const ft_recon_level *L, const float *u, size_t i, size_t nx, double *diag)
{
    const float *p = u + i;
    double c0 = p[0];
    double n1 = (double)p[-1] + (double)p[1] + (double)p[-(long)nx] + (double)p[nx];
    double d1 = (double)p[-(long)nx - 1] + (double)p[-(long)nx + 1] + (double)p[nx - 1] + (double)p[nx + 1];
    double n2 = (double)p[-2] + (double)p[2] + (double)p[-2 * (long)nx] + (double)p[2 * nx];
    double ci = L->c[i];
    *diag = 20.0 * L->tp + 4.0 * L->mem + ci;
    return L->tp * (20.0 * c0 - 8.0 * n1 + 2.0 * d1 + n2) + L->mem * (4.0 * c0 - n1) + ci * c0;
}

double ft_recon_apply(const ft_recon_level *L, const float *x, size_t col, size_t row, double *diag)
{
    if (col >= 2 && row >= 2 && col + 2 < L->nx && row + 2 < L->ny)
        return apply_inner(L, x, row * L->nx + col, L->nx, diag);
    return apply_edge(L, x, col, row, diag);
}

/* The nodes of colour k in row y: x = x0, x0 + 5, ... */
static size_t first_of_colour(int k, size_t y)
{
    return (size_t)(((long)k - 2 * (long)(y % NCOLOURS) + 2 * NCOLOURS) % NCOLOURS);
}

static void sweep_row(const ft_recon_level *L, float *x, const float *b, int k, size_t y)
{
    size_t nx = L->nx, ny = L->ny, row = y * nx;
    int inner_row = y >= 2 && y + 2 < ny;
    for (size_t c = first_of_colour(k, y); c < nx; c += NCOLOURS) {
        size_t i = row + c;
        if (L->fixed[i])
            continue;
        double a, ax = inner_row && c >= 2 && c + 2 < nx ? apply_inner(L, x, i, nx, &a) : apply_edge(L, x, c, y, &a);
        if (!(a > 0.0))
            continue;
        x[i] = (float)((double)x[i] + ((b ? (double)b[i] : 0.0) - ax) / a);
    }
}

/* One pass over the rows: at step t, the s-th colour of the sweep on row t - WAVE_LAG s. */
static void sweep_wavefront(const ft_recon_level *L, float *x, const float *b, int reverse)
{
    long ny = (long)L->ny;
    for (long t = 0; t < ny + WAVE_LAG * (NCOLOURS - 1); t++)
        for (int s = 0; s < NCOLOURS; s++) {
            long y = t - WAVE_LAG * s;
            if (y >= 0 && y < ny)
                sweep_row(L, x, b, reverse ? NCOLOURS - 1 - s : s, (size_t)y);
        }
}

int ft_recon_sweep(const ft_recon_level *L, float *x, const float *b, int reverse, int nthreads)
{
    size_t nx = L->nx, ny = L->ny;
    if (ft_recon_threads(nthreads, nx * ny) == 1) {
        sweep_wavefront(L, x, b, reverse);
        return FT_OK;
    }
    for (int s = 0; s < NCOLOURS; s++) {
        int k = reverse ? NCOLOURS - 1 - s : s;
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nx * ny)) schedule(static)
        for (size_t y = 0; y < ny; y++)
            sweep_row(L, x, b, k, y);
    }
    return FT_OK;
}

double ft_recon_residual(const ft_recon_level *L, const float *x, const float *b, float *r, int nthreads)
{
    size_t nx = L->nx, ny = L->ny;
    double *rows = malloc(ny * sizeof *rows);
#pragma omp parallel for num_threads(ft_recon_threads(nthreads, nx * ny)) schedule(static)
    for (size_t y = 0; y < ny; y++) {
        double s = 0.0;
        for (size_t c = 0; c < nx; c++) {
            size_t i = y * nx + c;
            if (L->fixed[i]) {
                r[i] = 0.0f;
                continue;
            }
            double a, v = (b ? (double)b[i] : 0.0) - ft_recon_apply(L, x, c, y, &a);
            r[i] = (float)v;
            s += v * v;
        }
        if (rows)
            rows[y] = s;
    }
    double s = 0.0;
    if (rows) {
        for (size_t y = 0; y < ny; y++)
            s += rows[y];
        free(rows);
    } else {
        s = NAN;
    }
    return s;
}
