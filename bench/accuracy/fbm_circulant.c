/* fracterra — bench/accuracy/fbm_circulant.c: Stein's (2002) exact fBm surfaces by intrinsic circulant
 * embedding (see fbm_circulant.h), for the accuracy programs.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fbm_circulant.h"

#include <complex.h>
#include <fftw3.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static uint64_t mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* The state is the seed hashed: a state of seed * step + c made seed k + 1's stream seed k's shifted by
 * one draw (splitmix64 walks the state by that same step), so consecutive seeds drew nearly the same
 * surfaces. Hashed, two seeds start at unrelated points of the sequence. */
void fbm_rng_seed(fbm_rng *r, uint64_t seed)
{
    r->s = mix64(seed + 0x632BE59BD9B4E019ull);
    r->have = 0;
}

static uint64_t splitmix64(uint64_t *s)
{
    return mix64(*s += 0x9E3779B97F4A7C15ull);
}

double fbm_rng_uniform(fbm_rng *r)
{
    return ((double)(splitmix64(&r->s) >> 11) + 0.5) * 0x1.0p-53;
}

double fbm_rng_normal(fbm_rng *r)
{
    if (r->have) {
        r->have = 0;
        return r->spare;
    }
    double u = fbm_rng_uniform(r), v = fbm_rng_uniform(r), m = sqrt(-2.0 * log(u));
    r->spare = m * sin(2.0 * M_PI * v);
    r->have = 1;
    return m * cos(2.0 * M_PI * v);
}

/* The smallest 2·3·5-smooth integer >= n. */
static size_t smooth(size_t n)
{
    for (;; n++) {
        size_t m = n;
        while (m % 2 == 0)
            m /= 2;
        while (m % 3 == 0)
            m /= 3;
        while (m % 5 == 0)
            m /= 5;
        if (m == 1)
            return n;
    }
}

int fbm_embedding_init(fbm_embedding *e, size_t n, double H)
{
    double alpha = 2.0 * H, R, beta = 0.0, c2;
    if (alpha <= 1.5) {
        R = 1.0;
        c2 = alpha / 2.0;
    } else {
        R = 2.0;
        beta = alpha * (2.0 - alpha) / (3.0 * R * (R * R - 1.0));
        c2 = (alpha - beta * (R - 1.0) * (R - 1.0) * (R + 2.0)) / 2.0;
    }
    double c0 = 1.0 - c2 + beta * pow(R - 1.0, 3.0);
    double h = 1.0 / ((double)(n - 1) * sqrt(2.0));
    size_t half = smooth((size_t)ceil(R / h)), P = 2 * half;
    h = R / (double)half; /* the torus holds exactly [0, R]; the n x n corner stays within diameter 1 */
    e->n = n;
    e->P = P;
    e->H = H;
    e->c2 = c2;
    e->h = h;
    e->sqrt_lam = NULL;
    fftw_complex *c = fftw_malloc(P * P * sizeof *c);
    if (c == NULL)
        return -1;
    for (size_t i = 0; i < P; i++) {
        double x = h * (double)(i <= half ? i : P - i);
        for (size_t j = 0; j < P; j++) {
            double y = h * (double)(j <= half ? j : P - j), r = hypot(x, y), v;
            v = r <= 1.0 ? c0 - pow(r, alpha) + c2 * r * r : r <= R ? beta * pow(R - r, 3.0) / r : 0.0;
            c[i * P + j] = v;
        }
    }
    fftw_plan plan;
#pragma omp critical(fftw_plan)
    plan = fftw_plan_dft_2d((int)P, (int)P, c, c, FFTW_FORWARD, FFTW_ESTIMATE);
    fftw_execute(plan);
#pragma omp critical(fftw_plan)
    fftw_destroy_plan(plan);
    e->sqrt_lam = malloc(P * P * sizeof *e->sqrt_lam);
    if (e->sqrt_lam == NULL) {
        fftw_free(c);
        return -1;
    }
    double lmax = 0.0, lmin = 0.0;
    for (size_t k = 0; k < P * P; k++) {
        double l = creal(c[k]);
        lmax = fmax(lmax, l);
        lmin = fmin(lmin, l);
        e->sqrt_lam[k] = l > 0.0 ? sqrt(l / ((double)P * (double)P)) : 0.0;
    }
    e->min_lam = lmin / lmax;
    fftw_free(c);
    if (e->min_lam < -1e-8) {
        fprintf(stderr, "fbm_circulant: embedding not positive for H %g (eigenvalue %g of the largest)\n", H,
                e->min_lam);
        fbm_embedding_free(e);
        return -1;
    }
    return 0;
}

void fbm_embedding_free(fbm_embedding *e)
{
    free(e->sqrt_lam);
    e->sqrt_lam = NULL;
}

int fbm_embedding_draw(const fbm_embedding *e, uint64_t seed, double *z)
{
    size_t P = e->P, n = e->n;
    fftw_complex *w = fftw_malloc(P * P * sizeof *w);
    if (w == NULL)
        return -1;
    fbm_rng r;
    fbm_rng_seed(&r, seed);
    for (size_t k = 0; k < P * P; k++) {
        double a = fbm_rng_normal(&r), b = fbm_rng_normal(&r);
        w[k] = e->sqrt_lam[k] * (a + I * b);
    }
    fftw_plan plan;
#pragma omp critical(fftw_plan)
    plan = fftw_plan_dft_2d((int)P, (int)P, w, w, FFTW_FORWARD, FFTW_ESTIMATE);
    fftw_execute(plan);
#pragma omp critical(fftw_plan)
    fftw_destroy_plan(plan);
    double z1 = fbm_rng_normal(&r), z2 = fbm_rng_normal(&r), k2 = sqrt(2.0 * e->c2), y0 = creal(w[0]);
    for (size_t i = 0; i < n; i++)
        for (size_t j = 0; j < n; j++)
            z[i * n + j] = creal(w[i * P + j]) - y0 + k2 * e->h * ((double)i * z1 + (double)j * z2);
    fftw_free(w);
    return 0;
}
