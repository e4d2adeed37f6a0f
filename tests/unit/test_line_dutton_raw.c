/* fracterra — unit tests of line/dutton_raw.c: the raw positions of a run of vertices several at a time
 * (ft_dutton_raw_run) give the bits of ft_dutton_raw_vertex, vertex by vertex, on each path the processor
 * has (one at a time, AVX2, AVX-512), over chains made awkward on purpose: straight runs, reversals,
 * zero-length segments, segments the window leaves unsplit, rings, coordinates far from the origin and
 * scaled to the edges of the double range; runs starting and ending anywhere. Then whole enhancements,
 * guarded and not, on each path.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/line.h"
#include "line/dutton_internal.h"

static const double PI = 3.14159265358979323846;
static const int PATHS[] = {FT_DUTTON_RAW_SCALAR, FT_DUTTON_RAW_AVX2, FT_DUTTON_RAW_AVX512};

/* A chain of n vertices (open or a ring) of pieces picked at random: a turn by up to 100 degrees with a step
 * of 0.1 to 10 (some outside the window), a straight run of exact unit steps along an axis, a reversal (back
 * to the vertex before), twelve steps of 12, a repeated vertex (a zero-length segment); then scaled by scale
 * and moved by (ox, oy). */
static ft_chain *awkward(size_t n, int closed, uint64_t seed, double scale, double ox, double oy)
{
    ft_chain *c = ft_chain_create(n, closed);
    ft_rng *r = ft_rng_create(seed, 3);
    assert_true(c != NULL && r != NULL);
    double x = 0.0, y = 0.0, dir = 0.0;
    while (c->n < n) {
        double u = ft_rng_uniform(r);
        if (u < 0.55) {
            dir += (ft_rng_uniform(r) - 0.5) * 2.0 * (100.0 * PI / 180.0);
            double step = 0.1 + 9.9 * ft_rng_uniform(r) * ft_rng_uniform(r);
            x += step * cos(dir);
            y += step * sin(dir);
        } else if (u < 0.7) {
            x = round(x);
            y = round(y);
            for (int k = 0; k < 6 && c->n + 1 < n; k++, x += 1.0)
                assert_int_equal(ft_chain_push(c, x * scale + ox, y * scale + oy), FT_OK);
        } else if (u < 0.8 && c->n >= 2) {
            x = (c->x[c->n - 2] - ox) / scale;
            y = (c->y[c->n - 2] - oy) / scale;
        } else if (u < 0.85) {
            for (int k = 0; k < 12 && c->n + 1 < n; k++) { /* steps of 12, past ST: every lane of a vector stays */
                assert_int_equal(ft_chain_push(c, x * scale + ox, y * scale + oy), FT_OK);
                dir += ft_rng_uniform(r) - 0.5;
                x += 12.0 * cos(dir);
                y += 12.0 * sin(dir);
            }
        } /* else the vertex before again */
        assert_int_equal(ft_chain_push(c, x * scale + ox, y * scale + oy), FT_OK);
    }
    ft_rng_free(r);
    return c;
}

/* The raw positions of every run [v0, v1) tried (the whole chain, short runs at its ends, random runs) on the
 * path forced now are ft_dutton_raw_vertex's, bit for bit. Counts the vertices that move, that stay though both
 * segments are split, and that stay unsplit, in moved[0..2]. */
static void runs_match(const ft_chain *c, const ft_dutton_pass_params *pp, uint64_t seed, size_t moved[3])
{
    size_t n = c->n, nseg = ft_chain_segments(c);
    unsigned char *split = malloc(nseg);
    double *ref = malloc(2 * n * sizeof(double)), *xy = malloc(2 * n * sizeof(double));
    assert_true(split != NULL && ref != NULL && xy != NULL);
    ft_dutton_mark_splits(c, nseg, pp->w, split);
    for (size_t v = 0; v < n; v++) {
        int m = ft_dutton_raw_vertex(c, split, pp, v, &ref[2 * v], &ref[2 * v + 1]);
        size_t ip = v > 0 ? v - 1 : n - 1;
        int both = (c->closed || (v > 0 && v + 1 < n)) && split[ip] && split[v];
        moved[m ? 0 : both ? 1 : 2]++;
    }
    ft_rng *r = ft_rng_create(seed, 5);
    for (int k = 0; k < 64; k++) {
        size_t v0 = 0, v1 = n;
        if (k >= 1 && k < 20) { /* short runs at the two ends */
            v0 = k < 10 ? (size_t)k - 1 : n - (size_t)(k - 9) * 2;
            v1 = v0 + (size_t)k % 11 + 1 < n ? v0 + (size_t)k % 11 + 1 : n;
        } else if (k >= 20) {
            v0 = (size_t)(ft_rng_uniform(r) * (double)n);
            v1 = v0 + (size_t)(ft_rng_uniform(r) * 40.0);
            v1 = v1 < n ? v1 : n;
        }
        memset(xy, 0xff, 2 * n * sizeof(double));
        ft_dutton_raw_run(c, split, pp, v0, v1, xy);
        assert_memory_equal(xy, ref + 2 * v0, 2 * (v1 - v0) * sizeof(double));
    }
    ft_rng_free(r);
    free(split);
    free(ref);
    free(xy);
}

static void test_runs_same_bits(void **state)
{
    (void)state;
    static const struct {
        double scale, ox, oy;
    } place[] = {{1.0, 0.0, 0.0}, {1.0, 6.5e6, -4.1e7}, {1e76, 0.0, 0.0}, {1e-150, 0.0, 0.0}, {3.0, 1e12, 1e12}};
    static const struct {
        double sd, uc, st, sm;
        int bend;
    } param[] = {{1.3, 1.0, INFINITY, 0.0, 1}, {1.3, 1.0, 5.0, 0.5, 0}, {1.7, -0.6, INFINITY, 0.3, 1},
                 {1.0, 0.4, 8.0, 0.0, 0}};
    size_t tried = 0;
    for (size_t q = 0; q < sizeof PATHS / sizeof PATHS[0]; q++) {
        if (!ft_dutton_raw_force(PATHS[q]))
            continue; /* the processor has no such path */
        tried++;
        for (size_t a = 0; a < sizeof place / sizeof place[0]; a++)
            for (size_t b = 0; b < sizeof param / sizeof param[0]; b++)
                for (int closed = 0; closed < 2; closed++) {
                    double apex = ft_dutton_apex_angle(param[b].sd), s = place[a].scale;
                    ft_dutton_pass_params pp = {cos(apex), sin(apex), param[b].uc,
                                                {param[b].st * param[b].st * s * s, param[b].sm * param[b].sm * s * s},
                                                param[b].bend, 0};
                    ft_chain *c = awkward(1003 + 2 * b + (size_t)closed, closed, 40 + a, s, place[a].ox, place[a].oy);
                    size_t moved[3] = {0, 0, 0};
                    runs_match(c, &pp, 7 + b, moved);
                    assert_true(moved[0] > 50 && moved[1] > 5); /* moves, and vertices with no clear side */
                    if (param[b].st < INFINITY || param[b].sm > 0.0)
                        assert_true(moved[2] > 10); /* unsplit segments */
                    ft_chain_free(c);
                }
    }
    ft_dutton_raw_force(FT_DUTTON_RAW_AUTO);
    assert_true(tried >= 1);
}

/* Whole enhancements (3 passes, guarded and unguarded, calibrated and literal) give the same bits on every
 * path. */
static void test_enhance_same_bits(void **state)
{
    (void)state;
    ft_chain *in = awkward(5000, 0, 11, 1.0, 3e5, 5e6);
    for (int guarded = 0; guarded < 2; guarded++)
        for (int literal = 0; literal < 2; literal++) {
            ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
            o.iterations = 3;
            o.allow_crossings = !guarded;
            o.literal_sd = literal;
            o.sm = 0.3;
            ft_chain *ref = NULL;
            assert_true(ft_dutton_raw_force(FT_DUTTON_RAW_SCALAR));
            assert_int_equal(ft_line_enhance(in, &o, &ref), FT_OK);
            for (size_t q = 1; q < sizeof PATHS / sizeof PATHS[0]; q++) {
                if (!ft_dutton_raw_force(PATHS[q]))
                    continue;
                ft_chain *out = NULL;
                assert_int_equal(ft_line_enhance(in, &o, &out), FT_OK);
                assert_int_equal(out->n, ref->n);
                assert_memory_equal(out->x, ref->x, ref->n * sizeof(double));
                assert_memory_equal(out->y, ref->y, ref->n * sizeof(double));
                ft_chain_free(out);
            }
            ft_chain_free(ref);
        }
    ft_dutton_raw_force(FT_DUTTON_RAW_AUTO);
    ft_chain_free(in);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_runs_same_bits),
        cmocka_unit_test(test_enhance_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
