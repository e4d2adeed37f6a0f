/* fracterra — core/rng.c: seeded random streams on GSL's MT19937, derived from (seed, stream) by
 * SplitMix64 so that results never depend on call order or thread count.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>
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
