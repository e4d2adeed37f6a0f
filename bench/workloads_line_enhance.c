/* fracterra — workloads_line_enhance.c: Dutton enhancement and Douglas-Peucker workloads of `make bench`
 * (speed targets: three enhancement iterations of a 1,000,000-vertex chain under 1 s; its
 * Douglas-Peucker at least as fast as GEOS's GEOSSimplify; with the crossing guard, the 1M chain
 * within 2x the unguarded time (line.enhance.1m.x3, whose peer column is the unguarded run and whose ratio
 * column is the guard's cost; line.enhance.1m.x3.raw is that run alone), and one iteration on a
 * layer of 100,000 features of 20 vertices under 3 s).
 *
 * Input, generated in each forked child before the timed call (untimed): one open chain of 1,000,000
 * vertices, a correlated random walk with 5 m steps (seed 20240501, the I/O workloads' line).
 * Peer: GEOSSimplify_r (GEOS's Douglas-Peucker) on the same chain, in process; the GEOS LineString is
 * built before the clock starts, as our chain is.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include <geos_c.h>

#include "fracterra/fracterra.h"

#define LINE_N 1000000
#define BENCH_SEED UINT64_C(20240501)
#define DP_TOLERANCE 20.0 /* metres, four steps of the walk */

static const double pi = 3.14159265358979323846;

typedef struct {
    ft_chain *chain;
    GEOSContextHandle_t geos;
    GEOSGeometry *line;
} line_state;

static line_state state;

/* A correlated random walk: the heading drifts by N(0, 0.3 rad) per 5 m step. */
static int make_chain(ft_bench_case *c)
{
    ft_rng *r = ft_rng_create(BENCH_SEED, 7);
    state.chain = ft_chain_create(LINE_N, 0);
    if (r == NULL || state.chain == NULL) {
        ft_rng_free(r);
        return ft_last_error_code();
    }
    double x = 500000.0, y = 5500000.0, dir = 0.0;
    for (size_t i = 0; i < LINE_N; i++) {
        state.chain->x[i] = x;
        state.chain->y[i] = y;
        dir += ft_rng_gaussian(r, 0.3) + 0.01 * sin(2.0 * pi * (double)i / 5000.0);
        x += 5.0 * cos(dir);
        y += 5.0 * sin(dir);
    }
    state.chain->n = LINE_N;
    ft_rng_free(r);
    c->state = &state;
    c->work = LINE_N;
    return FT_OK;
}

static int run_enhance(ft_bench_case *c)
{
    line_state *s = c->state;
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.iterations = 3;
    ft_chain *out = NULL;
    int rc = ft_line_enhance(s->chain, &o, &out);
    ft_chain_free(out);
    return rc;
}

static int run_enhance_raw(ft_bench_case *c)
{
    line_state *s = c->state;
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.iterations = 3;
    o.allow_crossings = 1;
    ft_chain *out = NULL;
    int rc = ft_line_enhance(s->chain, &o, &out);
    ft_chain_free(out);
    return rc;
}

/* 100,000 open lines of 20 vertices (4 m steps, heading drifting by N(0, 0.4 rad)), started on a 100 m grid
 * with random offsets of up to 50 m: neighbours come close, so the guard has contacts to refuse. */
#define LAYER_FEATURES 100000
#define LAYER_VERTICES 20
static ft_layer *bench_layer;

static int make_layer(ft_bench_case *c)
{
    ft_rng *r = ft_rng_create(BENCH_SEED, 11);
    bench_layer = ft_layer_create("bench", NULL);
    if (r == NULL || bench_layer == NULL) {
        ft_rng_free(r);
        return ft_last_error_code();
    }
    for (size_t f = 0; f < LAYER_FEATURES; f++) {
        ft_chain *ch = ft_chain_create(LAYER_VERTICES, 0);
        if (ch == NULL || ft_layer_add_feature(bench_layer, (int64_t)f, FT_GEOM_LINE, 0) < 0) {
            ft_chain_free(ch);
            ft_rng_free(r);
            return ft_last_error_code();
        }
        double x = 100.0 * (double)(f % 316) + 50.0 * ft_rng_uniform(r), y = 100.0 * (double)(f / 316) +
                                                                                 50.0 * ft_rng_uniform(r);
        double dir = 2.0 * pi * ft_rng_uniform(r);
        for (size_t i = 0; i < LAYER_VERTICES; i++) {
            ch->x[i] = x;
            ch->y[i] = y;
            dir += ft_rng_gaussian(r, 0.4);
            x += 4.0 * cos(dir);
            y += 4.0 * sin(dir);
        }
        ch->n = LAYER_VERTICES;
        if (ft_layer_add_part(bench_layer, ch, FT_ROLE_LINE, 0) != FT_OK) {
            ft_rng_free(r);
            return ft_last_error_code();
        }
    }
    ft_rng_free(r);
    c->state = bench_layer;
    c->work = LAYER_FEATURES * LAYER_VERTICES;
    return FT_OK;
}

static int run_enhance_layer(ft_bench_case *c)
{
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    return ft_line_enhance_layer(c->state, &o, 0, NULL, NULL);
}

static int setup_layer(ft_bench_case *c)
{
    c->work = LAYER_FEATURES * LAYER_VERTICES;
    c->peer_none = "no other library implements Dutton's enhancement";
    return FT_OK;
}

static int run_simplify(ft_bench_case *c)
{
    line_state *s = c->state;
    ft_chain *out = NULL;
    int rc = ft_line_simplify(s->chain, DP_TOLERANCE, &out);
    ft_chain_free(out);
    return rc;
}

static int prepare_geos(ft_bench_case *c)
{
    int rc = make_chain(c);
    if (rc != FT_OK)
        return rc;
    state.geos = GEOS_init_r();
    if (state.geos == NULL)
        return ft_error(FT_E_NOMEM, "GEOS_init_r failed");
    GEOSCoordSequence *seq =
        GEOSCoordSeq_copyFromArrays_r(state.geos, state.chain->x, state.chain->y, NULL, NULL, state.chain->n);
    if (seq == NULL || (state.line = GEOSGeom_createLineString_r(state.geos, seq)) == NULL)
        return ft_error(FT_E_NOMEM, "GEOS: cannot build the %zu-vertex LineString", state.chain->n);
    return FT_OK;
}

static int run_geos_simplify(ft_bench_case *c)
{
    line_state *s = c->state;
    GEOSGeometry *g = GEOSSimplify_r(s->geos, s->line, DP_TOLERANCE);
    if (g == NULL)
        return ft_error(FT_E_NUMERIC, "GEOSSimplify_r failed");
    GEOSGeom_destroy_r(s->geos, g);
    return FT_OK;
}

static int setup_enhance(ft_bench_case *c)
{
    c->work = LINE_N;
    c->peer_none = "no other library implements Dutton's enhancement";
    return FT_OK;
}

/* The guarded row's peer is the unguarded run of the same chain, in process: the ratio column is the
 * crossing guard's cost, the 2x target of issue 15. */
static int setup_enhance_guarded(ft_bench_case *c)
{
    c->work = LINE_N;
    c->peer_prepare = make_chain;
    c->peer_run = run_enhance_raw;
    c->peer_label = "ft_line_enhance with allow_crossings (no crossing guard), in process: ratio = guard's cost, target <= 2";
    c->min_repeat = 3;
    return FT_OK;
}

static int setup_simplify(ft_bench_case *c)
{
    c->work = LINE_N;
    c->peer_prepare = prepare_geos;
    c->peer_run = run_geos_simplify;
    c->peer_label = "GEOSSimplify_r (GEOS " GEOS_CAPI_VERSION "), in process, tolerance 20 m";
    return FT_OK;
}

static const ft_bench_workload workloads[] = {
    {"line.enhance.1m.x3", "ft_line_enhance: 3 guarded iterations (SD 1.3, UC 1, ST inf, SM 0) of a 1M-vertex chain",
     FT_BENCH_VERTICES, setup_enhance_guarded, make_chain, run_enhance, NULL},
    {"line.enhance.1m.x3.raw", "the same with --allow-crossings (no crossing guard): the 2x reference",
     FT_BENCH_VERTICES, setup_enhance, make_chain, run_enhance_raw, NULL},
    {"line.enhance.layer.100k", "ft_line_enhance_layer: 1 iteration (SD 1.3, UC 1, guarded) of 100,000 lines x 20 vertices",
     FT_BENCH_VERTICES, setup_layer, make_layer, run_enhance_layer, NULL},
    {"line.simplify.1m", "ft_line_simplify: Douglas-Peucker, tolerance 20 m, of a 1M-vertex chain (5 m steps)",
     FT_BENCH_VERTICES, setup_simplify, make_chain, run_simplify, NULL},
};

const ft_bench_suite ft_bench_suite_line_enhance = {"line", workloads, sizeof workloads / sizeof workloads[0]};
