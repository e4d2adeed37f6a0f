/* fracterra — fill_kriging.c: intrinsic kriging of one void from the valid cells around it
 * (docs/terrain-fill.md).
 *
 * The terrain is modelled as an intrinsic random function of order 0 with the power semivariogram
 * g(r) = r^(2H) / 2 (a fractional Brownian surface; its scale v1 does not change the weights). The best
 * linear unbiased prediction of z(x) from the conditioning values z_0 .. z_m-1 (ordinary kriging with a
 * variogram, Matheron 1973; Chilès & Delfiner, "Geostatistics", §3.4 and §4.4) is computed as simple
 * kriging of the increments z_i - z_0, whose covariance is that of the surface pinned at x_0:
 *     K_ij = g(x_i - x_0) + g(x_j - x_0) - g(x_i - x_j)        (i, j >= 1; positive definite)
 *     z*(x) = z_0 + sum_i alpha_i [g(x - x_0) + g(x_i - x_0) - g(x - x_i)],   K alpha = (z_i - z_0).
 * Its weights sum to one, it honours every z_i exactly, and it equals ordinary kriging with the
 * variogram g (the choice of the pinned point does not matter). K is factored once per void (Cholesky,
 * in double); every prediction is two triangular solves and one pass over the void's cells, with g read
 * from a table over the box's integer offsets.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/fill/fill_internal.h"

/* The prediction loop runs on several threads when it has at least this many (cell, datum) terms; each
 * cell's sum is taken in the same order on any thread count. */
#define PARALLEL_TERMS ((size_t)1 << 22)

struct ft_fill_krige {
    size_t bw, bh;
    size_t m;          /* conditioning cells; c[0] is the pinned one */
    int *cx, *cy;      /* their box coordinates */
    size_t *cidx;      /* their box indices */
    size_t nv;
    size_t *vidx;      /* void cells */
    double *g;         /* g[dy * bw + dx] = (dx² + dy²)^H / 2 */
    double *L;         /* Cholesky factor of K, (m - 1)², row-major lower */
    double *g0;        /* g(x_i - x_0), i = 1..m-1 (index i - 1) */
};

void ft_fill_krige_free(ft_fill_krige *k)
{
    if (k == NULL)
        return;
    free(k->cx);
    free(k->cy);
    free(k->cidx);
    free(k->vidx);
    free(k->g);
    free(k->L);
    free(k->g0);
    free(k);
}

static inline double gtab(const ft_fill_krige *k, int ax, int ay, int bx, int by)
{
    size_t dx = (size_t)abs(ax - bx), dy = (size_t)abs(ay - by);
    return k->g[dy * k->bw + dx];
}

static double dot(const double *a, const double *b, size_t n)
{
    double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
        s0 += a[i] * b[i];
        s1 += a[i + 1] * b[i + 1];
        s2 += a[i + 2] * b[i + 2];
        s3 += a[i + 3] * b[i + 3];
    }
    for (; i < n; i++)
        s0 += a[i] * b[i];
    return (s0 + s1) + (s2 + s3);
}

/* In-place Cholesky (Banachiewicz, row by row) of the n x n lower triangle of a; 0 or -1 if a pivot is
 * not positive. */
static int cholesky(double *a, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        double *ri = a + i * n;
        for (size_t j = 0; j < i; j++) {
            const double *rj = a + j * n;
            ri[j] = (ri[j] - dot(ri, rj, j)) / rj[j];
        }
        double d = ri[i] - dot(ri, ri, i);
        if (!(d > 0.0))
            return -1;
        ri[i] = sqrt(d);
    }
    return 0;
}

/* K with a relative nugget eps on the diagonal, into k->L (lower triangle). */
static void fill_K(ft_fill_krige *k, double eps)
{
    size_t n = k->m - 1;
    for (size_t i = 0; i < n; i++) {
        double *row = k->L + i * n;
        for (size_t j = 0; j <= i; j++)
            row[j] = k->g0[i] + k->g0[j] - gtab(k, k->cx[i + 1], k->cy[i + 1], k->cx[j + 1], k->cy[j + 1]);
        row[i] *= 1.0 + eps;
    }
}

int ft_fill_krige_create(const uint8_t *role, size_t bw, size_t bh, double H, ft_fill_krige **out)
{
    *out = NULL;
    if (!(H > 0.0 && H < 1.0))
        return ft_error(FT_E_INVALID, "fill: the kriging needs 0 < H < 1, got H = %g", H);
    ft_fill_krige *k = ft_calloc(1, sizeof *k);
    if (k == NULL)
        return FT_E_NOMEM;
    k->bw = bw;
    k->bh = bh;
    size_t n = bw * bh;
    for (size_t i = 0; i < n; i++) {
        k->m += role[i] == 2;
        k->nv += role[i] == 1;
    }
    if (k->m == 0) {
        ft_fill_krige_free(k);
        return ft_error(FT_E_EMPTY, "fill: a void has no valid cell around it");
    }
    k->cx = ft_malloc(k->m * sizeof *k->cx);
    k->cy = ft_malloc(k->m * sizeof *k->cy);
    k->cidx = ft_malloc(k->m * sizeof *k->cidx);
    k->vidx = ft_malloc((k->nv ? k->nv : 1) * sizeof *k->vidx);
    k->g = ft_malloc(n * sizeof *k->g);
    k->g0 = ft_malloc(k->m * sizeof *k->g0);
    k->L = ft_malloc(((k->m - 1) * (k->m - 1) + 1) * sizeof *k->L);
    if (!k->cx || !k->cy || !k->cidx || !k->vidx || !k->g || !k->g0 || !k->L) {
        ft_fill_krige_free(k);
        return FT_E_NOMEM;
    }
    size_t a = 0, b = 0;
    for (size_t i = 0; i < n; i++) {
        if (role[i] == 2) {
            k->cidx[a] = i;
            k->cx[a] = (int)(i % bw);
            k->cy[a] = (int)(i / bw);
            a++;
        } else if (role[i] == 1) {
            k->vidx[b++] = i;
        }
        size_t dx = i % bw, dy = i / bw;
        k->g[i] = 0.5 * pow((double)(dx * dx + dy * dy), H);
    }
    for (size_t i = 1; i < k->m; i++)
        k->g0[i - 1] = gtab(k, k->cx[i], k->cy[i], k->cx[0], k->cy[0]);
    /* K is positive definite in exact arithmetic; a nugget of 1e-12 .. 1e-6 of the diagonal guards the
     * round-off of near-collinear configurations and H near 1 */
    int ok = -1;
    for (double eps = 1e-12; ok != 0 && eps <= 1e-6; eps *= 100.0) {
        fill_K(k, eps);
        ok = cholesky(k->L, k->m - 1);
    }
    if (ok != 0) {
        size_t m = k->m;
        ft_fill_krige_free(k);
        return ft_error(FT_E_NUMERIC, "fill: the kriging system of a void (%zu conditioning cells, H = %g) "
                        "is not positive definite", m, H);
    }
    *out = k;
    return FT_OK;
}

int ft_fill_krige_predict(const ft_fill_krige *k, const float *vals, float *out)
{
    size_t n = k->m - 1;
    double z0 = vals[k->cidx[0]];
    double *alpha = ft_malloc((n + 1) * sizeof *alpha);
    if (alpha == NULL)
        return FT_E_NOMEM;
    /* L y = r, then L^T alpha = y */
    for (size_t i = 0; i < n; i++) {
        double r = (double)vals[k->cidx[i + 1]] - z0;
        alpha[i] = (r - dot(k->L + i * n, alpha, i)) / k->L[i * n + i];
    }
    for (size_t i = n; i-- > 0;) {
        double s = alpha[i];
        for (size_t j = i + 1; j < n; j++)
            s -= k->L[j * n + i] * alpha[j];
        alpha[i] = s / k->L[i * n + i];
    }
    double A = 0.0, B = 0.0;
    for (size_t i = 0; i < n; i++) {
        A += alpha[i];
        B += alpha[i] * k->g0[i];
    }
    const int *cx = k->cx + 1, *cy = k->cy + 1;
    const int x0 = k->cx[0], y0 = k->cy[0];
    const long nv = (long)k->nv;
#pragma omp parallel for schedule(static) if (k->nv * n >= PARALLEL_TERMS)
    for (long v = 0; v < nv; v++) {
        size_t idx = k->vidx[v];
        int vx = (int)(idx % k->bw), vy = (int)(idx / k->bw);
        double s = 0.0;
        for (size_t i = 0; i < n; i++)
            s += alpha[i] * k->g[(size_t)abs(vy - cy[i]) * k->bw + (size_t)abs(vx - cx[i])];
        out[idx] = (float)(z0 + gtab(k, vx, vy, x0, y0) * A + B - s);
    }
    free(alpha);
    return FT_OK;
}
