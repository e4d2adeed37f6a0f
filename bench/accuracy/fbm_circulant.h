/* fracterra — bench/accuracy/fbm_circulant.h: an exact fractional Brownian surface generator written for
 * the accuracy programs only, independent of fracterra's own synthesis (src/terrain/), so that a bias
 * shared by the generator and the estimators cannot hide: Stein's (2002) intrinsic circulant embedding
 * ("Fast and exact simulation of fractional Brownian surfaces", J. Comput. Graph. Stat. 11(3)).
 *
 * The stationary covariance ρ(r) = c0 - r^α + c2 r² (r <= 1), β (R - r)³ / r (1 < r <= R), 0 beyond,
 * α = 2H, with R = 1, c2 = α/2 for α <= 1.5 and R = 2, β = α(2 - α) / (3R(R² - 1)),
 * c2 = (α - β(R - 1)²(R + 2)) / 2 for α > 1.5 (c0 = 1 - c2 + β(R - 1)³), is embedded in a torus of side
 * 2R; its field Y has E(Y(s) - Y(t))² = 2(|s - t|^α - c2 |s - t|²) for |s - t| <= 1, so
 * X(t) = Y(t) - Y(0) + sqrt(2 c2) (t · Z), Z ~ N(0, I₂), is exactly fBm with E(X(s) - X(t))² = 2|s - t|^α
 * on a square of diameter 1: an n x n lattice of spacing 1 / ((n - 1) sqrt 2).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_BENCH_FBM_CIRCULANT_H
#define FRACTERRA_BENCH_FBM_CIRCULANT_H

#include <stddef.h>
#include <stdint.h>

/** The embedding of one (n, H): the square roots of the torus's eigenvalues, scaled for the FFT. */
typedef struct {
    size_t n, P;       /* output side, torus side */
    double H, c2, h;   /* Hurst exponent, c2, lattice spacing */
    double *sqrt_lam;  /* P x P */
    double min_lam;    /* the most negative eigenvalue before clipping, relative to the largest */
} fbm_embedding;

/** Builds the embedding; 0 on success, -1 (message on stderr) otherwise. */
int fbm_embedding_init(fbm_embedding *e, size_t n, double H);
void fbm_embedding_free(fbm_embedding *e);
/** One surface, n x n row-major into z (exact fBm, X(0) = 0); seed gives the Gaussian draws.
 *  Thread-safe for distinct z. 0 on success, -1 when out of memory. */
int fbm_embedding_draw(const fbm_embedding *e, uint64_t seed, double *z);

/** Counter-based standard normal draws (splitmix64 + Box-Muller), independent of fracterra's RNG. */
typedef struct {
    uint64_t s;
    int have;
    double spare;
} fbm_rng;
void fbm_rng_seed(fbm_rng *r, uint64_t seed);
double fbm_rng_uniform(fbm_rng *r); /* (0, 1) */
double fbm_rng_normal(fbm_rng *r);

#endif /* FRACTERRA_BENCH_FBM_CIRCULANT_H */
