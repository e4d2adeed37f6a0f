/* fracterra — tests/unit/test_line_guard.c: the crossing guard's promise on real lines: with UC = 1 the enhanced chain's
 * divider dimension over the scales the enhancement generates is SD (1.1, 1.2, 1.3, 1.5) within 0.03, and
 * the crossing guard leaves no self-intersection and no contact between features (checked with GEOS, not
 * with the guard's own contact test). Inputs: the 158-point Douglas-Peucker Newfoundland (GSHHG), four DCW
 * US states generalized as a coverage (Oklahoma and Colorado share a border), the 130 m contour of Maunga
 * Whau; a contour stack of the volcano DEM enhanced and smoothed stays disjoint. FT_GUARD_MEASURE=1 prints
 * every figure without asserting.
 *
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
#include <geos_c.h>
#include <omp.h>
#include "fracterra/io.h"
#include "fracterra/line.h"
#include "line/dutton_internal.h"
#include "line/segment_index.h"
#include "test_segment_boxes.h"

#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"
#define STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"
#define SEED_CONTOUR FT_TEST_DATA "/seed_contour_volcano.geojson"
#define CONTOURS FT_TEST_DATA "/contours_volcano_10m.geojson"
#define ITERATIONS 9

static ft_layer *read_layer(const char *path)
{
    ft_layer *l = NULL;
    assert_int_equal(ft_io_read_layer(path, NULL, &l), FT_OK);
    return l;
}

static void simplify_layer(ft_layer *l, double tol)
{
    assert_int_equal(ft_line_apply_layer(l, ft_line_op_simplify, &tol, 1), FT_OK);
}

static double mean_segment(const ft_layer *l)
{
    double len = 0.0;
    size_t nseg = 0;
    for (size_t p = 0; p < l->nparts; p++) {
        const ft_chain *c = l->parts[p].chain;
        for (size_t i = 0; i < ft_chain_segments(c); i++) {
            size_t j = i + 1 < c->n ? i + 1 : 0;
            len += hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
            nseg++;
        }
    }
    return len / (double)nseg;
}

/* Divider D of all parts over [lo, hi], every ruler fitted. */
static double divider_dim(const ft_layer *l, double lo, double hi)
{
    const ft_chain **c = malloc(l->nparts * sizeof *c);
    for (size_t p = 0; p < l->nparts; p++)
        c[p] = l->parts[p].chain;
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = lo;
    o.max_scale = hi;
    o.nscales = 12;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(c, l->nparts, FT_LINE_DIVIDER, &o, &r), FT_OK);
    double d = r->D;
    ft_dim_result_free(r);
    free(c);
    return d;
}

static GEOSGeometry *ring_geom(GEOSContextHandle_t h, const ft_chain *c, int polygon)
{
    size_t m = c->n + (c->closed ? 1 : 0);
    GEOSCoordSequence *s = GEOSCoordSeq_create_r(h, (unsigned)m, 2);
    for (size_t i = 0; i < m; i++) {
        size_t k = i < c->n ? i : 0;
        GEOSCoordSeq_setXY_r(h, s, (unsigned)i, c->x[k], c->y[k]);
    }
    GEOSGeometry *ring = polygon ? GEOSGeom_createLinearRing_r(h, s) : GEOSGeom_createLineString_r(h, s);
    return polygon ? GEOSGeom_createPolygon_r(h, ring, NULL, 0) : ring;
}

/* GEOS: every ring simple; polygon pairs share no interior (coverage neighbours may share boundary) or, for
 * lines (contours), every pair disjoint. Returns the number of faults. */
static size_t geos_faults(const ft_layer *l, int polygons)
{
    GEOSContextHandle_t h = GEOS_init_r();
    size_t n = l->nparts, faults = 0;
    GEOSGeometry **g = malloc(n * sizeof *g);
    for (size_t p = 0; p < n; p++) {
        g[p] = ring_geom(h, l->parts[p].chain, polygons);
        GEOSGeometry *line = ring_geom(h, l->parts[p].chain, 0);
        faults += GEOSisSimple_r(h, line) != 1;
        if (getenv("FT_GUARD_MEASURE") && GEOSisSimple_r(h, line) != 1)
            print_message("part %zu not simple\n", p);
        GEOSGeom_destroy_r(h, line);
    }
    for (size_t a = 0; a < n; a++)
        for (size_t b = a + 1; b < n; b++)
        {
            int f = polygons ? GEOSRelatePattern_r(h, g[a], g[b], "2********") != 0
                             : GEOSDisjoint_r(h, g[a], g[b]) != 1;
            if (f && getenv("FT_GUARD_MEASURE")) {
                GEOSGeometry *x = GEOSIntersection_r(h, g[a], g[b]);
                double area = 0;
                GEOSArea_r(h, x, &area);
                print_message("parts %zu %zu: interiors meet, area %g\n", a, b, area);
                GEOSGeom_destroy_r(h, x);
            }
            faults += f;
        }
    for (size_t p = 0; p < n; p++)
        GEOSGeom_destroy_r(h, g[p]);
    free(g);
    GEOS_finish_r(h);
    return faults;
}

static size_t self_intersections(const ft_layer *l)
{
    size_t total = 0;
    for (size_t p = 0; p < l->nparts; p++) {
        size_t k = 0;
        assert_int_equal(ft_line_count_self_intersections(l->parts[p].chain, &k), FT_OK);
        total += k;
    }
    return total;
}

/* check_dim: assert D within 0.03 of SD. No self-intersection, and no GEOS fault the input did not have. */
static void check_enhanced(const char *name, const ft_layer *in, int polygons, int check_dim, int iterations)
{
    static const double sds[] = {1.1, 1.2, 1.3, 1.5};
    double seg_in = mean_segment(in);
    size_t base_faults = geos_faults(in, polygons);
    print_message("%s: %zu parts, %zu vertices, GEOS faults of the input %zu\n", name, in->nparts,
                  ft_layer_vertex_count(in), base_faults);
    for (size_t k = 0; k < sizeof sds / sizeof sds[0]; k++) {
        ft_layer *l = ft_layer_copy(in);
        ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
        o.sd = sds[k];
        o.iterations = iterations;
        ft_line_guard_stats st = {0, 0, 0, 0};
        assert_int_equal(ft_line_enhance_layer(l, &o, 1, NULL, &st), FT_OK);
        double seg_out = mean_segment(l);
        double d = divider_dim(l, 8.0 * seg_out, 0.5 * seg_in);
        size_t si = self_intersections(l), gf = geos_faults(l, polygons);
        print_message("%-18s SD %.1f: %zu vertices, D %.3f over %.0f-%.0f, moves %zu reduced %zu dropped %zu, "
                      "self-intersections %zu, GEOS faults %zu\n",
                      name, sds[k], ft_layer_vertex_count(l), d, 8.0 * seg_out, 0.5 * seg_in, st.moves, st.reduced,
                      st.dropped, si, gf);
        if (getenv("FT_GUARD_MEASURE") == NULL) {
            if (check_dim)
                assert_true(fabs(d - sds[k]) <= 0.03);
            assert_int_equal(si, 0);
            assert_true(gf <= base_faults);
        }
        ft_layer_free(l);
    }
}

static void test_newfoundland_uc1(void **state)
{
    (void)state;
    ft_layer *l = read_layer(NEWFOUNDLAND);
    simplify_layer(l, 9234.0); /* 158 vertices: docs/line-newfoundland.md */
    assert_true(ft_layer_vertex_count(l) >= 150 && ft_layer_vertex_count(l) <= 166);
    check_enhanced("Newfoundland 158", l, 1, 1, ITERATIONS);
    ft_layer_free(l);
}

static void test_states_coverage_uc1(void **state)
{
    (void)state;
    ft_layer *l = read_layer(STATES);
    simplify_layer(l, 1000.0);
    /* Colorado's and Oklahoma's borders are straight segments of hundreds of kilometres; the calibrated mode cuts
     * segments over 1.5 times the input's mean into pieces of about the mean and bends straight junctions, so
     * they are enhanced over the same scales as the rest (without: 1.088, 1.155, 1.207, 1.265). The generalized
     * input has one pair of overlapping parts (per-arc Douglas-Peucker); it stays, no other. */
    check_enhanced("4 US states", l, 1, 1, ITERATIONS);
    ft_layer_free(l);
}

/* A real contour stack (gdal_contour of the volcano DEM every 10 m), enhanced (SD 1.7, 3 iterations) then
 * smoothed twice, guarded: every contour simple and every pair of contours disjoint (GEOS). The raw
 * algorithm's contacts are printed for comparison. */
static size_t stack_faults(int allow_crossings, ft_line_guard_stats *st)
{
    ft_layer *l = read_layer(CONTOURS);
    size_t before = geos_faults(l, 0);
    assert_int_equal(before, 0);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 1.7;
    o.iterations = 3;
    o.allow_crossings = allow_crossings;
    ft_smooth_opts so = FT_SMOOTH_OPTS_DEFAULT;
    so.passes = 2;
    so.allow_crossings = allow_crossings;
    assert_int_equal(ft_line_enhance_layer(l, &o, 1, NULL, st), FT_OK);
    size_t after_enhance = geos_faults(l, 0);
    assert_int_equal(ft_line_smooth_layer(l, &so, 1, st), FT_OK);
    size_t after_smooth = geos_faults(l, 0);
    print_message("contour stack (%zu contours, %zu vertices), %s: GEOS faults %zu after enhance, %zu after "
                  "smoothing\n",
                  l->nparts, ft_layer_vertex_count(l), allow_crossings ? "raw" : "guarded", after_enhance,
                  after_smooth);
    ft_layer_free(l);
    return after_enhance + after_smooth;
}

static void test_contour_stack_disjoint(void **state)
{
    (void)state;
    ft_line_guard_stats raw = {0, 0, 0, 0}, st = {0, 0, 0, 0};
    assert_true(stack_faults(1, &raw) > 0); /* the raw algorithm does make contours meet here */
    assert_int_equal(stack_faults(0, &st), 0);
    print_message("guard: %zu moves, %zu reduced, %zu dropped\n", st.moves, st.reduced, st.dropped);
}

static void test_volcano_contour_uc1(void **state)
{
    (void)state;
    ft_layer *l = read_layer(SEED_CONTOUR);
    check_enhanced("volcano 130 m", l, 1, 1, ITERATIONS);
    ft_layer_free(l);
}

/* Bad input: errors name the value. */
static void expect_plan_error(const ft_chain *c, ft_dutton_opts o, const char *msg)
{
    ft_chain *out = (ft_chain *)1;
    assert_int_equal(ft_line_enhance(c, &o, &out), FT_E_INVALID);
    assert_null(out);
    if (strstr(ft_last_error(), msg) == NULL)
        print_error("message '%s' lacks '%s'\n", ft_last_error(), msg);
    assert_non_null(strstr(ft_last_error(), msg));
}

static void test_bad_input(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 10, 0, 10, 10, 0, 10};
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, 4, 2, 1);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.uc = 0.5;
    o.input_dim = 1.2;
    o.sd = 1.9; /* target 1.2 + 0.5 (1.9 - 1.2) = 1.55 > 1.453, the most UC 0.5 reaches */
    expect_plan_error(c, o, "a target dimension of 1.550 is out of reach with uc = 0.5: the enhanced chain's "
                            "dimension stops rising at 1.45");
    o.input_dim = 2.5;
    expect_plan_error(c, o, "input_dim must be 0 (measured) or in [1,2], got 2.5");
    o.input_dim = 0.0; /* a square: no divider dimension to measure */
    o.sd = 1.3;
    expect_plan_error(c, o, "uc < 1 needs the input's dimension D_in and it cannot be measured");
    /* the guard itself: base and raw must match */
    ft_chain *b = ft_chain_copy(c), *r = ft_chain_from_arrays(xy, xy + 1, 3, 2, 1);
    assert_int_equal(ft_line_guard_moves(&b, (const ft_chain *const *)&r, 1, FT_GUARD_REDUCE, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "chain 0 has 4 base and 3 raw vertices"));
    ft_chain_free(b);
    ft_chain_free(r);
    ft_chain_free(c);
}

/* A move that would jump over a small island is refused, though its end position touches nothing. */
static void test_no_jump_over_island(void **state)
{
    (void)state;
    const double line[] = {0, 0, 5, 0, 10, 0}, raw_line[] = {0, 0, 5, 4, 10, 0};
    const double island[] = {4.8, 1, 5.2, 1, 5, 1.4};
    ft_chain *base[2] = {ft_chain_from_arrays(line, line + 1, 3, 2, 0),
                         ft_chain_from_arrays(island, island + 1, 3, 2, 1)};
    const ft_chain *raw[2] = {ft_chain_from_arrays(raw_line, raw_line + 1, 3, 2, 0), NULL};
    raw[1] = ft_chain_copy(base[1]);
    ft_line_guard_stats st = {0, 0, 0, 0};
    assert_int_equal(ft_line_guard_moves(base, raw, 2, FT_GUARD_REDUCE, &st), FT_OK);
    assert_int_equal(st.moves, 1);
    /* t = 1 (y 4) and 1/2 (y 2) jump over the island (y 1 .. 1.4); 1/4 (y 1) would touch it: dropped */
    assert_int_equal(st.dropped, 1);
    assert_true(base[0]->y[1] == 0.0);
    for (int k = 0; k < 2; k++) {
        ft_chain_free(base[k]);
        ft_chain_free((ft_chain *)raw[k]);
    }
}

/* A chain long enough for several chunks of the parallel walk (16,384 blocks of 8 segments each): a spiral
 * of 1 m steps whose turns are 1.5 m apart, jittered by up to 0.3 m (simple, and every turn lies next to the
 * one before, so the moves near a chunk's start wait for the serial walk and some moves are refused): one
 * guarded pass gives the same bits on 1 and 3 threads, and no self-intersection. */
static void test_thread_count(void **state)
{
    (void)state;
    const size_t n = 160000; /* 320,000 segments after the pass: 3 chunks */
    ft_chain *c = ft_chain_create(n, 0);
    ft_rng *r = ft_rng_create(20240501, 7);
    double theta = 0.0;
    for (size_t i = 0; i < n; i++) {
        double rad = 100.0 + 1.5 * theta / (2.0 * M_PI), jit = 0.6 * (ft_rng_uniform(r) - 0.5);
        c->x[i] = (rad + jit) * cos(theta);
        c->y[i] = (rad + jit) * sin(theta);
        theta += 1.0 / rad;
    }
    c->n = n;
    ft_rng_free(r);
    size_t k = 1;
    assert_int_equal(ft_line_count_self_intersections(c, &k), FT_OK);
    assert_int_equal(k, 0);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.iterations = 1;
    int threads = omp_get_max_threads();
    ft_chain *out[2] = {NULL, NULL};
    for (int t = 0; t < 2; t++) {
        omp_set_num_threads(t == 0 ? 1 : 3);
        assert_int_equal(ft_line_enhance(c, &o, &out[t]), FT_OK);
    }
    omp_set_num_threads(threads);
    assert_int_equal(out[0]->n, 2 * n - 1);
    assert_int_equal(out[1]->n, out[0]->n);
    assert_memory_equal(out[0]->x, out[1]->x, out[0]->n * sizeof(double));
    assert_memory_equal(out[0]->y, out[1]->y, out[0]->n * sizeof(double));
    k = 1;
    assert_int_equal(ft_line_count_self_intersections(out[0], &k), FT_OK);
    assert_int_equal(k, 0);
    ft_chain_free(out[0]);
    ft_chain_free(out[1]);
    ft_chain_free(c);
}

/* ft_line_pass_enhance under another name: ft_line_run_passes then takes the unfused path (the pass writes
 * base and raw chains, ft_line_guard_moves walks them), the reference for the fused guarded pass. */
static int pass_enhance_unfused(const ft_chain *in, const void *ctx, ft_chain **base, ft_chain **raw)
{
    return ft_line_pass_enhance(in, ctx, base, raw);
}

/* The guard fused into the enhancement pass (dutton_guarded.c) gives the unfused guard's very bits and counts
 * when every segment is split: two guarded passes over a set of two chains that come close, a jittered
 * spiral of 1 m steps (open, 40,000 vertices: several chunks of the walk after the first pass) and a ring
 * (SD 1.5, on 3 threads). Some moves must be reduced or refused for the comparison to mean anything. */
/* Guarded passes over copies of c[0..n), fused and unfused: the same counts and the same bits. */
static void fused_matches_unfused(ft_chain *const *c, size_t n, const ft_dutton_opts *o, int passes)
{
    ft_dutton_plan plan;
    assert_int_equal(ft_dutton_plan_make((const ft_chain *const *)c, n, o, &plan), FT_OK);
    ft_chain **fused = calloc(n, sizeof *fused), **ref = calloc(n, sizeof *ref);
    assert_non_null(fused);
    assert_non_null(ref);
    for (size_t k = 0; k < n; k++) {
        fused[k] = ft_chain_copy(c[k]);
        ref[k] = ft_chain_copy(c[k]);
    }
    ft_line_guard_stats sf = {0, 0, 0, 0}, sr = {0, 0, 0, 0};
    int threads = omp_get_max_threads();
    omp_set_num_threads(3);
    assert_int_equal(ft_line_run_passes(fused, n, ft_line_pass_enhance, &plan, passes, FT_GUARD_REDUCE, &sf), FT_OK);
    assert_int_equal(ft_line_run_passes(ref, n, pass_enhance_unfused, &plan, passes, FT_GUARD_REDUCE, &sr), FT_OK);
    omp_set_num_threads(threads);
    assert_true(sr.reduced + sr.dropped > 100);
    assert_int_equal(sf.moves, sr.moves);
    assert_int_equal(sf.reduced, sr.reduced);
    assert_int_equal(sf.dropped, sr.dropped);
    for (size_t k = 0; k < n; k++) {
        assert_int_equal(fused[k]->n, ref[k]->n);
        assert_int_equal(fused[k]->closed, ref[k]->closed);
        assert_memory_equal(fused[k]->x, ref[k]->x, ref[k]->n * sizeof(double));
        assert_memory_equal(fused[k]->y, ref[k]->y, ref[k]->n * sizeof(double));
        ft_chain_free(fused[k]);
        ft_chain_free(ref[k]);
    }
    free(fused);
    free(ref);
}

/* A jittered spiral of 1 m steps (open, 40,000 vertices: several chunks of the walk after a pass), or a
 * random walk of 1 m steps with sharp turns, and a ring 1.2 m inside the spiral's first turn. */
static void spiral_and_ring(ft_chain *c[2], int walk)
{
    const size_t n = 40000, nr = 600;
    c[0] = ft_chain_create(n, 0);
    c[1] = ft_chain_create(nr, 1);
    ft_rng *r = ft_rng_create(20240501, 9);
    double theta = 0.0, x = 0.0, y = 0.0;
    for (size_t i = 0; i < n; i++) {
        double rad = 100.0 + 1.5 * theta / (2.0 * M_PI), jit = 0.6 * (ft_rng_uniform(r) - 0.5);
        c[0]->x[i] = walk ? x : (rad + jit) * cos(theta);
        c[0]->y[i] = walk ? y : (rad + jit) * sin(theta);
        theta += walk ? ft_rng_gaussian(r, 2.5) : 1.0 / rad;
        x += cos(theta);
        y += sin(theta);
    }
    for (size_t i = 0; i < nr; i++) {
        double t = 2.0 * M_PI * (double)i / (double)nr, rad = 98.8 + 0.5 * (ft_rng_uniform(r) - 0.5);
        c[1]->x[i] = rad * cos(t);
        c[1]->y[i] = rad * sin(t);
    }
    c[0]->n = n;
    c[1]->n = nr;
    ft_rng_free(r);
}

/* The guard fused into the enhancement pass (dutton_guarded.c) gives the unfused guard's very bits and counts
 * when every segment is split (on 3 threads): the spiral and its ring (SD 1.5, 2 passes), the sharp walk and
 * the ring (SD 1.5; literal SD 1.3 with UC -1, Dutton's exaggeration), and the real contour stack of the
 * volcano (SD 1.7, 3 passes), where a few moves are stopped by the segments next to their own. Some moves
 * must be reduced or refused for the comparison to mean anything. */
static void test_fused_matches_unfused(void **state)
{
    (void)state;
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 1.5;
    for (int walk = 0; walk < 2; walk++) {
        ft_chain *c[2];
        spiral_and_ring(c, walk);
        fused_matches_unfused(c, 2, &o, 2);
        if (walk) {
            ft_dutton_opts e = o;
            e.sd = 1.3;
            e.uc = -1.0;
            e.literal_sd = 1;
            fused_matches_unfused(c, 2, &e, 2);
        }
        ft_chain_free(c[0]);
        ft_chain_free(c[1]);
    }
    ft_layer *l = read_layer(CONTOURS);
    ft_chain **parts = calloc(l->nparts, sizeof *parts);
    assert_non_null(parts);
    for (size_t p = 0; p < l->nparts; p++)
        parts[p] = l->parts[p].chain;
    o.sd = 1.7;
    fused_matches_unfused(parts, l->nparts, &o, 3);
    free(parts);
    ft_layer_free(l);
}

/* Guarded passes over copies of c[0..n) with the walk's plain-C screen or the one the processor picks; the
 * copies are returned in out, the counts added to st. */
static void run_screen(ft_chain *const *c, size_t n, const ft_dutton_opts *o, int passes, int generic,
                       ft_chain **out, ft_line_guard_stats *st)
{
    ft_dutton_plan plan;
    assert_int_equal(ft_dutton_plan_make((const ft_chain *const *)c, n, o, &plan), FT_OK);
    for (size_t k = 0; k < n; k++)
        assert_non_null(out[k] = ft_chain_copy(c[k]));
    ft_dutton_guard_generic(generic);
    int rc = ft_line_run_passes(out, n, ft_line_pass_enhance, &plan, passes, FT_GUARD_REDUCE, st);
    ft_dutton_guard_generic(0);
    assert_int_equal(rc, FT_OK);
}

/* The fused walk screens segment boxes eight at a time, with AVX-512 where the processor has it, else in
 * plain C; both must hand the exact tests the same segments, so give the same bits. The plain screen against
 * the unfused guard (the sharp walk and the ring, whose last block wraps round: the segment-by-segment path),
 * then the two screens against each other where SM leaves segments unsplit in the second pass (blocks of
 * fewer than eight output segments), a case the unfused guard cannot be compared with. On a processor without
 * AVX-512 the second comparison is plain C twice. */
static void test_screens_same_bits(void **state)
{
    (void)state;
    ft_chain *c[2];
    spiral_and_ring(c, 1);
    ft_dutton_opts o = FT_DUTTON_OPTS_DEFAULT;
    o.sd = 1.5;
    ft_dutton_guard_generic(1);
    fused_matches_unfused(c, 2, &o, 2);
    ft_dutton_guard_generic(0);
    o.sm = 0.55; /* the first pass splits every 1 m step; the second only the halves not shorter than 0.55 m */
    ft_chain *g[2], *v[2];
    ft_line_guard_stats sg = {0, 0, 0, 0}, sv = {0, 0, 0, 0};
    run_screen(c, 2, &o, 2, 1, g, &sg);
    run_screen(c, 2, &o, 2, 0, v, &sv);
    assert_true(sg.reduced + sg.dropped > 100);
    assert_int_equal(sg.moves, sv.moves);
    assert_int_equal(sg.reduced, sv.reduced);
    assert_int_equal(sg.dropped, sv.dropped);
    for (size_t k = 0; k < 2; k++) {
        size_t all = c[k]->closed ? 4 * c[k]->n : 4 * (c[k]->n - 1) + 1; /* every segment split twice */
        assert_true(g[k]->n > 2 * c[k]->n && g[k]->n < all); /* spiral: 89,367 of 159,997 */
        assert_int_equal(g[k]->n, v[k]->n);
        assert_memory_equal(g[k]->x, v[k]->x, g[k]->n * sizeof(double));
        assert_memory_equal(g[k]->y, v[k]->y, g[k]->n * sizeof(double));
        ft_chain_free(g[k]);
        ft_chain_free(v[k]);
        ft_chain_free(c[k]);
    }
}

static void lists_equal(const uint32_t *s1, const uint32_t *l1, const uint32_t *s2, const uint32_t *l2, size_t nb)
{
    assert_memory_equal(s1, s2, (nb + 1) * sizeof *s1);
    assert_memory_equal(l1, l2, s1[nb] * sizeof *l1);
}

/* The near lists carried from the pass before (ft_segment_blocks_join_carried, used by the fused enhancement
 * from its second pass on) are the grid join's, list for list, and so are the wide lists it hands on; when a
 * block leaves its parent's box by more than the slack allows, it refuses (the caller joins on the grid).
 * A tight spiral (arms 0.8 apart, blocks about 2 long: lists reach across arms), a ring inside it and a line
 * across both. */
static void test_carried_index(void **state)
{
    (void)state;
    ft_chain *c[3];
    spiral_ring_line(c, 400);
    ft_segment_blocks prev, g, ref;
    ft_segment_wide pw, w, wref;
    assert_int_equal(ft_segment_blocks_layout(&prev, (const ft_chain *const *)c, 3, 4), FT_OK);
    fill_boxes(&prev, c, 0.2);
    assert_int_equal(ft_segment_blocks_join_wide(&prev, (const ft_chain *const *)c, 0.5, &pw), FT_OK);
    ft_chain *h[3];
    for (size_t k = 0; k < 3; k++)
        h[k] = halved(c[k], k, 0.2);
    size_t far = 0; /* near-list entries that are not the block itself or its chain neighbours */
    for (int refuse = 0; refuse < 2; refuse++) {
        assert_int_equal(ft_segment_blocks_layout(&g, (const ft_chain *const *)h, 3, 4), FT_OK);
        assert_int_equal(ft_segment_blocks_layout(&ref, (const ft_chain *const *)h, 3, 4), FT_OK);
        fill_boxes(&g, h, refuse ? 0.4 : 0.1); /* excess 0.1: 2 E fits in 0.5; 0.4 does not */
        memcpy(ref.box, g.box, 4 * g.nblock * sizeof *g.box);
        int rc = ft_segment_blocks_join_carried(&g, (const ft_chain *const *)h, &prev, &pw, 1, &w);
        if (refuse) {
            assert_int_equal(rc, 1);
            assert_null(g.near_start);
        } else {
            assert_int_equal(rc, FT_OK);
            assert_true(w.sigma > 0.0 && w.sigma < 0.5);
            assert_int_equal(ft_segment_blocks_join_wide(&ref, (const ft_chain *const *)h, w.sigma, &wref), FT_OK);
            lists_equal(g.near_start, g.near, ref.near_start, ref.near, g.nblock);
            lists_equal(w.start, w.near, wref.start, wref.near, g.nblock);
            for (size_t b = 0; b < g.nblock; b++)
                for (uint32_t e = g.near_start[b]; e < g.near_start[b + 1]; e++)
                    far += g.near[e] + 1 < b || g.near[e] > b + 2;
            ft_segment_wide_free(&wref);
        }
        ft_segment_wide_free(&w);
        ft_segment_blocks_free(&g);
        ft_segment_blocks_free(&ref);
    }
    assert_true(far > 1000); /* the lists do reach across the spiral's arms */
    ft_segment_wide_free(&pw);
    ft_segment_blocks_free(&prev);
    for (size_t k = 0; k < 3; k++) {
        ft_chain_free(c[k]);
        ft_chain_free(h[k]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_newfoundland_uc1),
        cmocka_unit_test(test_states_coverage_uc1),
        cmocka_unit_test(test_volcano_contour_uc1),
        cmocka_unit_test(test_contour_stack_disjoint),
        cmocka_unit_test(test_bad_input),
        cmocka_unit_test(test_no_jump_over_island),
        cmocka_unit_test(test_thread_count),
        cmocka_unit_test(test_fused_matches_unfused),
        cmocka_unit_test(test_carried_index),
        cmocka_unit_test(test_screens_same_bits),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
