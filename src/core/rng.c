/* fracterra — core/rng.c: seeded random streams on GSL's MT19937, derived from (seed, stream) by
 * SplitMix64 so that results never depend on call order or thread count; and ft_rng_fast, a xoshiro256++
 * stream with a ziggurat normal generator for bulk draws (spectral synthesis).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#define MT_N 624

struct ft_rng {
    gsl_rng *gsl;
};

/* GSL's MT19937 state (gsl/rng/mt.c); checked against gsl_rng_size() before use. */
typedef struct {
    unsigned long mt[MT_N];
    int mti;
} mt_state;

static uint64_t splitmix64_next(uint64_t *state)
{
    uint64_t z = (*state += UINT64_C(0x9E3779B97F4A7C15));
    z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
    return z ^ (z >> 31);
}

/* For a fixed seed this is a bijection of the stream id, so two streams of one seed never coincide. */
uint64_t ft_rng_mix(uint64_t seed, uint64_t stream)
{
    uint64_t s = seed;
    uint64_t h = splitmix64_next(&s);
    h += stream * UINT64_C(0xD1B54A32D192ED03);
    return splitmix64_next(&h);
}

/* gsl_rng_set() keeps only 32 bits of the seed for MT19937, so distinct streams would collide after
 * about 2^16 of them; the whole 19937-bit state is filled from SplitMix64 instead (with the top bit
 * of the first word set, as MT's init_by_array does, so the state is never all zero). */
static void seed_state(gsl_rng *g, uint64_t mixed)
{
    if (gsl_rng_size(g) != sizeof(mt_state)) {
        gsl_rng_set(g, (unsigned long)((mixed >> 32) ^ mixed));
        return;
    }
    mt_state *st = gsl_rng_state(g);
    uint64_t sm = mixed;
    for (int i = 0; i < MT_N; i += 2) {
        uint64_t v = splitmix64_next(&sm);
        st->mt[i] = (unsigned long)(v & 0xffffffffu);
        st->mt[i + 1] = (unsigned long)(v >> 32);
    }
    st->mt[0] = 0x80000000UL;
    st->mti = MT_N;
}

/* The gsl_rng is assembled by hand (as gsl_rng_alloc does) so that out of memory reports FT_E_NOMEM
 * instead of reaching GSL's default error handler, which aborts. */
ft_rng *ft_rng_create(uint64_t seed, uint64_t stream)
{
    const gsl_rng_type *type = gsl_rng_mt19937;
    ft_rng *r = ft_calloc(1, sizeof *r);
    if (r == NULL)
        return NULL;
    r->gsl = ft_calloc(1, sizeof *r->gsl);
    if (r->gsl == NULL)
        goto fail;
    r->gsl->type = type;
    r->gsl->state = ft_calloc(1, type->size);
    if (r->gsl->state == NULL)
        goto fail;
    seed_state(r->gsl, ft_rng_mix(seed, stream));
    return r;
fail:
    ft_rng_free(r);
    return NULL;
}

void ft_rng_free(ft_rng *r)
{
    if (r == NULL)
        return;
    if (r->gsl != NULL)
        free(r->gsl->state);
    free(r->gsl);
    free(r);
}

static uint64_t draw32(ft_rng *r)
{
    return (uint64_t)gsl_rng_get(r->gsl) & UINT64_C(0xffffffff);
}

/* 53 random bits (two draws, as MT's genrand_res53), so every double in [0,1) on the 2^-53 grid
 * can occur. */
double ft_rng_uniform(ft_rng *r)
{
    uint64_t a = draw32(r) >> 5;
    uint64_t b = draw32(r) >> 6;
    return ((double)a * 67108864.0 + (double)b) * (1.0 / 9007199254740992.0);
}

/* Rejection sampling: draws below (2^k mod n) are discarded so every residue is equally likely. */
uint64_t ft_rng_uint(ft_rng *r, uint64_t n)
{
    if (n <= 1)
        return 0;
    if (n <= UINT64_C(0x100000000)) {
        uint64_t threshold = (UINT64_C(0x100000000) - n) % n;
        for (;;) {
            uint64_t v = draw32(r);
            if (v >= threshold)
                return v % n;
        }
    }
    uint64_t threshold = (0 - n) % n;
    for (;;) {
        uint64_t hi = draw32(r);
        uint64_t v = (hi << 32) | draw32(r);
        if (v >= threshold)
            return v % n;
    }
}

double ft_rng_gaussian(ft_rng *r, double sigma)
{
    return gsl_ran_gaussian_ziggurat(r->gsl, sigma);
}

void *ft_rng_gsl(ft_rng *r)
{
    return r ? r->gsl : NULL;
}

/* ---- ft_rng_fast: xoshiro256++ (Blackman & Vigna 2021) ---- */

void ft_rng_fast_init(ft_rng_fast *r, uint64_t seed, uint64_t stream)
{
    uint64_t sm = ft_rng_mix(seed, stream);
    for (int i = 0; i < 4; i++)
        r->s[i] = splitmix64_next(&sm); /* SplitMix64 never yields four zeros in a row */
}

static inline uint64_t rotl64(uint64_t x, int k)
{
    return (x << k) | (x >> (64 - k));
}

static inline uint64_t xoshiro_next(uint64_t s[4])
{
    uint64_t result = rotl64(s[0] + s[3], 23) + s[0];
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl64(s[3], 45);
    return result;
}

uint64_t ft_rng_fast_next(ft_rng_fast *r)
{
    return xoshiro_next(r->s);
}

/* ---- Ziggurat (Marsaglia & Tsang, "The ziggurat method for generating random variables", J. Stat.
 * Softw. 5(8), 2000), 256 layers, r and v from the paper. Each draw gives the layer from its low 8 bits
 * and a signed 53-bit value from its top 53 bits, so the two are independent (Doornik 2005 showed the
 * correlation of the original, which took both from one 32-bit word). ---- */

#define ZIG_N 256
#define ZIG_R 3.6541528853610088
#define ZIG_V 4.92867323399e-3
#define ZIG_M 4503599627370496.0 /* 2^52: |value| < 2^52 */

static struct {
    uint64_t k[ZIG_N]; /* |value| < k[i]: inside layer i's rectangle under the curve */
    double w[ZIG_N]; /* x = value * w[i] */
    double f[ZIG_N]; /* exp(-x_i^2 / 2) */
} zig;
static pthread_once_t zig_once = PTHREAD_ONCE_INIT;

/* Marsaglia & Tsang's zigset: layer 0 is the base strip with the tail beyond r, layer i >= 1 the
 * rectangle of half-width x_i between heights f[i] and f[i-1], x_255 = r. */
static void zig_tables(void)
{
    double dn = ZIG_R, tn = dn, q = ZIG_V / exp(-0.5 * dn * dn);
    zig.k[0] = (uint64_t)(dn / q * ZIG_M);
    zig.k[1] = 0;
    zig.w[0] = q / ZIG_M;
    zig.w[ZIG_N - 1] = dn / ZIG_M;
    zig.f[0] = 1.0;
    zig.f[ZIG_N - 1] = exp(-0.5 * dn * dn);
    for (int i = ZIG_N - 2; i >= 1; i--) {
        dn = sqrt(-2.0 * log(ZIG_V / dn + exp(-0.5 * dn * dn)));
        zig.k[i + 1] = (uint64_t)(dn / tn * ZIG_M);
        tn = dn;
        zig.f[i] = exp(-0.5 * dn * dn);
        zig.w[i] = dn / ZIG_M;
    }
}

/* Uniform in (0, 1]: 53 bits, never 0 (its log is taken). */
static inline double uniform_open0(uint64_t s[4])
{
    return (double)((xoshiro_next(s) >> 11) + 1) * (1.0 / 9007199254740992.0);
}

/* A draw's layer (low 8 bits) and signed 53-bit value (top 53 bits), |value| <= 2^52. */
static inline unsigned zig_layer(uint64_t u)
{
    return (unsigned)(u & 0xff);
}

static inline int64_t zig_value(uint64_t u)
{
    return (int64_t)(u >> 11) - (INT64_C(1) << 52);
}

static inline uint64_t zig_abs(int64_t j)
{
    return j < 0 ? (uint64_t)0 - (uint64_t)j : (uint64_t)j;
}

/* The slow path, about 0.7% of draws: the tail (layer 0, Marsaglia 1964) or the wedge test; a
 * rejection draws afresh from s. */
static double zig_slow(uint64_t s[4], uint64_t u)
{
    for (;;) {
        unsigned i = zig_layer(u);
        int64_t j = zig_value(u);
        double x = (double)j * zig.w[i];
        if (i == 0) {
            double t, y;
            do {
                t = -log(uniform_open0(s)) / ZIG_R;
                y = -log(uniform_open0(s));
            } while (y + y < t * t);
            return j > 0 ? ZIG_R + t : -ZIG_R - t;
        }
        if (zig.f[i] + uniform_open0(s) * (zig.f[i - 1] - zig.f[i]) < exp(-0.5 * x * x))
            return x;
        u = xoshiro_next(s);
        if (zig_abs(zig_value(u)) < zig.k[zig_layer(u)])
            return (double)zig_value(u) * zig.w[zig_layer(u)];
    }
}

/* Draws are made ZIG_CHUNK at a time in a tight loop (the state stays in registers), then each becomes
 * a deviate; the slow path draws what it needs after the chunk. */
#define ZIG_CHUNK 64

static void draw_chunk(uint64_t state[4], uint64_t *u, size_t n)
{
    uint64_t s[4] = {state[0], state[1], state[2], state[3]};
    for (size_t m = 0; m < n; m++)
        u[m] = xoshiro_next(s);
    for (int k = 0; k < 4; k++)
        state[k] = s[k];
}

void ft_rng_fast_normals(ft_rng_fast *r, float *out, size_t n)
{
    pthread_once(&zig_once, zig_tables);
    uint64_t u[ZIG_CHUNK];
    for (size_t m0 = 0; m0 < n; m0 += ZIG_CHUNK) {
        size_t len = n - m0 < ZIG_CHUNK ? n - m0 : ZIG_CHUNK;
        draw_chunk(r->s, u, len);
        for (size_t m = 0; m < len; m++) {
            unsigned i = zig_layer(u[m]);
            int64_t j = zig_value(u[m]);
            double x = zig_abs(j) < zig.k[i] ? (double)j * zig.w[i] : zig_slow(r->s, u[m]);
            out[m0 + m] = (float)x;
        }
    }
}
