/* fracterra — contour/fourier_descriptor.c: phase randomization of a contour's P-type Fourier descriptor
 * (Misawa, Chiba & Saito, §4.2; the descriptor is Uesaka's, "A new Fourier descriptor applicable to open
 * curves", IEICE Trans. J67-A(3), 1984).
 *
 * 1. The ring is resampled to n points Z(j) = x(j) + i y(j) equally spaced by h = L / n in arc length along
 *    it, from its first vertex (L its perimeter).
 * 2. w(j) = (Z(j+1) - Z(j)) / h, j = 0 .. n-1 (Z(n) = Z(0)): the unit edge vectors of an equilateral
 *    n-gon; a chord across one of the ring's vertices is a little shorter than h and keeps that length,
 *    so that without randomization the rebuild returns the resampled ring exactly.
 * 3. c(k) = (1/n) sum_j w(j) exp(-2 pi i j k / n): the P-type descriptor (the paper's §4.2 definition).
 * 4. Every component of signed frequency |k| >= f0 (k and n - k; k = n/2 once) gets a uniform random phase
 *    phi keeping its magnitude; the others are kept:
 *        w'(j) = sum_{|k| < f0} c(k) e^{2 pi i j k/n} + sum_{|k| >= f0} |c(k)| e^{i phi_k} e^{2 pi i j k/n}
 * 5. Z'(m) = Z(0) + h sum_{j<m} w'(j) (the paper's rebuild). c(0) is never randomized (f0 >= 1), so the
 *    ring closes as the input did; the rounding error of the closure is spread evenly over the edges.
 *    The ring is then translated so that the mean of its vertices is that of the resampled input (the
 *    arc-length centroid), and reversed if its signed area changed sign (only a randomization far below
 *    the contour's own frequencies can do that), so the orientation is the input's.
 *
 * Because the rebuild is linear, the result's own descriptor ((Z'(j+1) - Z'(j)) / h) has exactly the
 * magnitudes |c(k)| of the input and the input's components below f0. Its perimeter h sum |w'(j)| is the
 * resampled ring's when nothing is randomized; randomized phases make the |w'(j)| unequal, and since
 * sum |w'|^2 is kept (Parseval), sum |w'| can only drop a little (Cauchy-Schwarz): the paper's remark that
 * phase randomization rounds the contour slightly. The low frequencies (the shape and its size) are kept.
 *
 * Random draws: one xoshiro stream per call from (seed, stream), one phase per randomized k in order of k.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"
#include "fracterra/contour.h"
#include "fft/fft.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846
#define MAX_N (1 << 24)

static double uniform01(ft_rng_fast *r)
{
    return (double)(ft_rng_fast_next(r) >> 11) * 0x1p-53;
}

/* n points equally spaced by h in arc length along the ring, from vertex 0, into z (n complex). */
static void resample_ring(const ft_chain *c, size_t n, double h, fftw_complex *z)
{
    size_t seg = 0, nv = c->n;
    double seg_start = 0.0; /* arc length at the start of segment seg */
    double ax = c->x[0], ay = c->y[0], bx = c->x[1 % nv], by = c->y[1 % nv];
    double seg_len = hypot(bx - ax, by - ay);
    for (size_t j = 0; j < n; j++) {
        double s = (double)j * h;
        while (seg + 1 < nv && s > seg_start + seg_len) {
            seg_start += seg_len;
            seg++;
            ax = bx;
            ay = by;
            bx = c->x[(seg + 1) % nv];
            by = c->y[(seg + 1) % nv];
            seg_len = hypot(bx - ax, by - ay);
        }
        double t = seg_len > 0.0 ? (s - seg_start) / seg_len : 0.0;
        t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
        z[j][0] = ax + t * (bx - ax);
        z[j][1] = ay + t * (by - ay);
    }
}

static int check_input(const ft_chain *ring, const ft_fourier_opts *o, ft_chain **out, double *perimeter)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "fourier randomization: NULL output pointer");
    *out = NULL;
    if (ring == NULL)
        return ft_error(FT_E_INVALID, "fourier randomization: NULL ring");
    if (!ring->closed)
        return ft_error(FT_E_INVALID, "fourier randomization: the chain must be a ring (closed = 1)");
    int rc = ft_chain_check_min_vertices(ring, 3);
    if (rc == FT_OK)
        rc = ft_chain_check_finite(ring);
    if (rc != FT_OK)
        return rc;
    if (!(o->n >= 8 && o->n <= MAX_N))
        return ft_error(FT_E_INVALID, "fourier n must be in [8,%d], got %d", MAX_N, o->n);
    if (!(o->f0 >= 1 && o->f0 <= o->n / 2))
        return ft_error(FT_E_INVALID, "fourier f0 must be in [1,n/2] = [1,%d], got %d", o->n / 2, o->f0);
    *perimeter = ft_chain_length(ring);
    if (!(*perimeter > 0.0) || !isfinite(*perimeter))
        return ft_error(FT_E_NUMERIC, "fourier randomization: the ring's perimeter is %g", *perimeter);
    return FT_OK;
}

int ft_contour_fourier_randomize(const ft_chain *ring, const ft_fourier_opts *opts, uint64_t seed,
                                 uint64_t stream, ft_chain **out)
{
    return ft_contour_fourier_randomize_paired(ring, opts, seed, stream, NULL, out);
}

int ft_contour_fourier_randomize_paired(const ft_chain *ring, const ft_fourier_opts *opts, uint64_t seed,
                                        uint64_t stream, ft_chain **base, ft_chain **out)
{
    if (base != NULL)
        *base = NULL;
    ft_fourier_opts o = FT_FOURIER_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_fourier_opts) != FT_OK)
        return FT_E_INVALID;
    double perimeter = 0.0;
    int rc = check_input(ring, &o, out, &perimeter);
    if (rc != FT_OK)
        return rc;

    size_t n = (size_t)o.n;
    double h = perimeter / (double)n;
    fftw_complex *z = ft_fft_alloc_complex(n), *c = ft_fft_alloc_complex(n);
    ft_chain *res = ft_chain_create(n, 1), *b = base != NULL ? ft_chain_create(n, 1) : NULL;
    if (z == NULL || c == NULL || res == NULL || (base != NULL && b == NULL)) {
        rc = FT_E_NOMEM;
        goto done;
    }
    resample_ring(ring, n, h, z);
    for (size_t j = 0; b != NULL && j < n; j++) {
        b->x[j] = z[j][0];
        b->y[j] = z[j][1];
    }
    if (b != NULL)
        b->n = n;
    double mx = 0.0, my = 0.0;
    for (size_t j = 0; j < n; j++) {
        mx += z[j][0];
        my += z[j][1];
    }
    mx /= (double)n;
    my /= (double)n;

    /* w(j) = (Z(j+1) - Z(j)) / h */
    for (size_t j = 0; j < n; j++) {
        size_t k = (j + 1) % n;
        c[j][0] = (z[k][0] - z[j][0]) / h;
        c[j][1] = (z[k][1] - z[j][1]) / h;
    }
    rc = ft_fft_c2c_1d(n, c, c, FT_FFT_FORWARD); /* n c(k) */
    if (rc != FT_OK)
        goto done;

    ft_rng_fast rng;
    ft_rng_fast_init(&rng, seed, stream);
    for (size_t k = 1; k < n; k++) {
        size_t kabs = k <= n / 2 ? k : n - k;
        if (kabs < (size_t)o.f0)
            continue;
        double mag = hypot(c[k][0], c[k][1]);
        double phi = 2.0 * PI * uniform01(&rng);
        c[k][0] = mag * cos(phi);
        c[k][1] = mag * sin(phi);
    }
    rc = ft_fft_c2c_1d(n, c, c, FT_FFT_BACKWARD); /* n w'(j): the 1/n of c(k) is applied below */
    if (rc != FT_OK)
        goto done;

    /* Z'(m) = Z(0) + h sum_{j<m} w'(j), closure error spread evenly */
    double scale = h / (double)n, sx = 0.0, sy = 0.0;
    for (size_t j = 0; j < n; j++) {
        sx += c[j][0] * scale;
        sy += c[j][1] * scale;
    }
    double ex = sx / (double)n, ey = sy / (double)n;
    double x = z[0][0], y = z[0][1], cx = 0.0, cy = 0.0;
    for (size_t j = 0; j < n; j++) {
        res->x[j] = x;
        res->y[j] = y;
        cx += x;
        cy += y;
        x += c[j][0] * scale - ex;
        y += c[j][1] * scale - ey;
    }
    res->n = n;
    cx /= (double)n;
    cy /= (double)n;
    for (size_t j = 0; j < n; j++) {
        res->x[j] += mx - cx;
        res->y[j] += my - cy;
    }
    double a_in = ft_chain_signed_area(ring), a_out = ft_chain_signed_area(res);
    if ((a_in > 0.0 && a_out < 0.0) || (a_in < 0.0 && a_out > 0.0)) {
        ft_chain_reverse(res);
        if (b != NULL)
            ft_chain_reverse(b); /* vertex j of res still comes from vertex j of b */
    }
    rc = ft_chain_check_finite(res);

done:
    ft_fft_free(z);
    ft_fft_free(c);
    if (rc != FT_OK) {
        ft_chain_free(res);
        ft_chain_free(b);
        return rc;
    }
    if (base != NULL)
        *base = b;
    *out = res;
    return FT_OK;
}
