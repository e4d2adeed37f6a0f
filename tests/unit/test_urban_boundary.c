/* fracterra — unit tests of src/urban/boundary.c and boundary_layer.c: the midpoint-subdivision generator of
 * Zhang, Yu & Fan (2008, §2). Accuracy targets: a curve generated from a straight segment
 * with D in {1.1, ..., 1.5} and no jitter has segments of exactly r / (2 cos a)^k at level k, and its divider
 * dimension over the generated scales l_k is within 0.03 of D (box counting within 0.05); with jitter the
 * median divider dimension over 10 seeds is within 0.05; segments longer than max come out vertex for
 * vertex; the same seed gives the same bytes. Then rings, coverages and bad input.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <geos_c.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/line.h"
#include "fracterra/urban.h"

#include "test_urban.h"

static const double Ds[] = {1.1, 1.2, 1.3, 1.4, 1.5};
#define NDS (sizeof Ds / sizeof Ds[0])

static ft_chain *segment(double x0, double y0, double x1, double y1)
{
    ft_chain *c = ft_chain_create(2, 0);
    assert_non_null(c);
    assert_int_equal(ft_chain_push(c, x0, y0), FT_OK);
    assert_int_equal(ft_chain_push(c, x1, y1), FT_OK);
    return c;
}

/* The generator on c with dimension D down to `levels` levels of a segment of length r: min is set between
 * l_levels = r q^-levels and l_(levels-1), q = 2 cos a. */
static ft_chain *generate(const ft_chain *c, double D, double r, int levels, double jitter, uint64_t seed)
{
    const double q = 2.0 * cos(ft_urban_angle_for_dim(D));
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.dim = D;
    o.min = r * pow(q, -levels) * (1.0 + 1e-6);
    o.jitter = jitter;
    o.seed = seed;
    ft_chain *out = NULL;
    int rc = ft_urban_boundary(c, &o, &out);
    if (rc != FT_OK)
        print_error("ft_urban_boundary: %s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    return out;
}

static double dim_over_levels(const ft_chain *c, ft_line_method m, double r, double D, int lo_level, int hi_level)
{
    const double q = 2.0 * cos(ft_urban_angle_for_dim(D));
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = r * pow(q, -hi_level) * (1.0 - 1e-9);
    o.max_scale = r * pow(q, -lo_level) * (1.0 - 1e-9);
    o.nscales = hi_level - lo_level + 1;
    o.fit_whole_range = 1;
    ft_dim_result *res = NULL;
    const ft_chain *cs[] = {c};
    int rc = ft_line_dim(cs, 1, m, &o, &res);
    if (rc != FT_OK)
        print_error("ft_line_dim: %s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    double d = res->D;
    ft_dim_result_free(res);
    return d;
}

/* ------------------------------------------------------------------------------------------------ */

static void test_angle_table(void **state)
{
    (void)state;
    assert_near(ft_urban_angle_for_dim(1.0), 0.0, 1e-15);
    assert_near(ft_urban_angle_for_dim(2.0), atan(1.0), 1e-15);
    /* D = 1.5: cos a = 2^(-1/3) = 0.79370, a = 37.467 degrees */
    assert_near(ft_urban_angle_for_dim(1.5) * 180.0 / M_PI, 37.4673, 1e-4);
    for (double D = 1.1; D < 1.95; D += 0.1)
        assert_near(ft_urban_dim_for_angle(ft_urban_angle_for_dim(D)), D, 1e-12);
    assert_true(isnan(ft_urban_angle_for_dim(0.9)));
    assert_true(isnan(ft_urban_angle_for_dim(NAN)));
    assert_true(isnan(ft_urban_dim_for_angle(1.0)));
    assert_true(isnan(ft_urban_jitter_max(2.0)));
    for (double D = 1.1; D < 1.95; D += 0.1) { /* the worst leg stays shorter than its segment */
        double a = ft_urban_angle_for_dim(D), j = ft_urban_jitter_max(D);
        assert_true(j > 0.0 && j <= sqrt(0.5));
        assert_true(1.0 / (2.0 * cos(a)) + sqrt(0.5) * j * tan(a) <= 1.0 + 1e-12);
    }
}

/* Every segment at level k has length r / (2 cos a)^k, and the curve has 2^k + 1 vertices. */
static void test_exact_lengths(void **state)
{
    (void)state;
    const double r = hypot(3.0, 4.0);
    ft_chain *s = segment(1.0, 2.0, 4.0, 6.0);
    for (size_t d = 0; d < NDS; d++) {
        const double q = 2.0 * cos(ft_urban_angle_for_dim(Ds[d]));
        for (int k = 1; k <= 10; k++) {
            ft_chain *c = generate(s, Ds[d], r, k, 0.0, 7);
            assert_int_equal(c->n, ((size_t)1 << k) + 1);
            const double want = r / pow(q, k);
            for (size_t i = 0; i + 1 < c->n; i++)
                assert_near(hypot(c->x[i + 1] - c->x[i], c->y[i + 1] - c->y[i]) / want, 1.0, 1e-9);
            assert_true(c->x[0] == 1.0 && c->y[0] == 2.0 && c->x[c->n - 1] == 4.0 && c->y[c->n - 1] == 6.0);
            assert_near(ft_chain_length(c), r * pow(2.0 / q, k), 1e-9 * r * pow(2.0 / q, k));
            ft_chain_free(c);
        }
    }
    ft_chain_free(s);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Divider and box dimensions (the fewest-boxes counter, box-min, against which the generator was tuned: the
 * mean-over-offsets counter reads these curves 0.01 to 0.07 lower, from D = 1.1 to 1.5, docs/urban-boxcount.md)
 * of 10 curves of 16 levels (65537 vertices; seeds 1-10) over the generated
 * scales l_4 .. l_12: rulers above l_4 take fewer than 16 steps and feel the chord's ends, rulers below
 * l_12 (four levels above the finest segments) feel the polygon's own corners (the divider's lower cut-off,
 * like line_dim's automatic range). J is random even without jitter, and one curve's estimate varies by
 * about +-0.03 at D = 1.5, so the medians are checked, and every curve within twice the tolerance. */
static void check_generated_dims(double jitter, double tol_div, double tol_box)
{
    ft_chain *s = segment(0.0, 0.0, 1.0, 0.0);
    for (size_t d = 0; d < NDS; d++) {
        double div[10], box[10];
        for (uint64_t seed = 1; seed <= 10; seed++) {
            ft_chain *c = generate(s, Ds[d], 1.0, 16, jitter, seed);
            if (jitter == 0.0)
                assert_int_equal(c->n, 65537);
            div[seed - 1] = dim_over_levels(c, FT_LINE_DIVIDER, 1.0, Ds[d], 4, 12);
            box[seed - 1] = dim_over_levels(c, FT_LINE_BOX_MIN, 1.0, Ds[d], 4, 12);
            assert_near(div[seed - 1], Ds[d], 2.0 * tol_div);
            ft_chain_free(c);
        }
        qsort(div, 10, sizeof div[0], cmp_double);
        qsort(box, 10, sizeof box[0], cmp_double);
        double mdiv = 0.5 * (div[4] + div[5]), mbox = 0.5 * (box[4] + box[5]);
        print_message("  D = %.1f, jitter %.2f: divider median %.4f (%.4f .. %.4f), box median %.4f (%.4f .. %.4f)\n",
                      Ds[d], jitter, mdiv, div[0], div[9], mbox, box[0], box[9]);
        assert_near(mdiv, Ds[d], tol_div);
        assert_near(mbox, Ds[d], tol_box);
    }
    ft_chain_free(s);
}

/* The crossing guard: the guarded generator (the default of ft_urban_boundary_layer) on a unit segment, 15 levels,
 * D 1.1-1.5, seeds 1-5: no self-intersection (ours and GEOS's isSimple), and the median divider D over
 * l_4 .. l_11 within 0.03 of D (every curve within 0.06). */
static void test_guarded_boundary(void **state)
{
    (void)state;
    GEOSContextHandle_t h = GEOS_init_r();
    for (size_t d = 0; d < NDS; d++) {
        const double q = 2.0 * cos(ft_urban_angle_for_dim(Ds[d]));
        double div[5];
        size_t reduced = 0;
        for (uint64_t seed = 1; seed <= 5; seed++) {
            ft_layer *l = ft_layer_create("line", NULL);
            assert_true(ft_layer_add_feature(l, 1, FT_GEOM_LINE, 0) >= 0);
            assert_int_equal(ft_layer_add_part(l, segment(0.0, 0.0, 1.0, 0.0), FT_ROLE_LINE, 0), FT_OK);
            ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
            o.dim = Ds[d];
            o.min = pow(q, -15) * (1.0 + 1e-6);
            o.max = 1.0;
            o.seed = seed;
            ft_boundary_info info;
            assert_int_equal(ft_urban_boundary_layer(l, &o, 1, &info), FT_OK);
            const ft_chain *c = l->parts[0].chain;
            size_t si = 0;
            assert_int_equal(ft_line_count_self_intersections(c, &si), FT_OK);
            assert_int_equal(si, 0);
            GEOSCoordSequence *cs = GEOSCoordSeq_copyFromArrays_r(h, c->x, c->y, NULL, NULL, c->n);
            GEOSGeometry *g = GEOSGeom_createLineString_r(h, cs);
            assert_int_equal(GEOSisSimple_r(h, g), 1);
            GEOSGeom_destroy_r(h, g);
            div[seed - 1] = dim_over_levels(c, FT_LINE_DIVIDER, 1.0, Ds[d], 4, 11);
            assert_near(div[seed - 1], Ds[d], 0.06);
            reduced += info.guard.reduced + info.guard.dropped + info.guard.redrawn;
            ft_layer_free(l);
        }
        qsort(div, 5, sizeof div[0], cmp_double);
        print_message("  guarded D = %.1f: divider median %.4f (%.4f .. %.4f), apexes redrawn, reduced or dropped %zu\n",
                      Ds[d], div[2], div[0], div[4], reduced);
        assert_near(div[2], Ds[d], 0.03);
    }
    GEOS_finish_r(h);
}

/* No jitter: divider within 0.03 of D, box counting within 0.05. */
static void test_divider_dimension(void **state)
{
    (void)state;
    check_generated_dims(0.0, 0.03, 0.05);
}

/* Jitter 0.25 (apex square of half-side L / 4): divider within 0.05. */
static void test_jitter_divider_dimension(void **state)
{
    (void)state;
    check_generated_dims(0.25, 0.05, 0.1);
}

/* Finds input vertex (x, y) in c at or after index *from; returns its index. */
static size_t find_vertex(const ft_chain *c, size_t from, double x, double y)
{
    for (size_t i = from; i < c->n; i++)
        if (c->x[i] == x && c->y[i] == y)
            return i;
    fail_msg("vertex (%g, %g) not found after %zu", x, y, from);
    return 0;
}

/* Segments longer than max stay as they are; the input vertices are kept in order. */
static void test_long_segments_kept(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 10, 0, 10, 1, 11, 1.5, 11.5, 2.5, 11.5, 12.5, 12, 13};
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, 7, 2, 0);
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.dim = 1.3;
    o.min = 0.05;
    o.max = 2.0;
    ft_chain *out = NULL;
    assert_int_equal(ft_urban_boundary(c, &o, &out), FT_OK);
    size_t at[7];
    for (size_t i = 0; i < 7; i++)
        at[i] = find_vertex(out, i ? at[i - 1] : 0, xy[2 * i], xy[2 * i + 1]);
    assert_int_equal(at[0], 0);
    assert_int_equal(at[6], out->n - 1);
    assert_int_equal(at[1], 1);          /* (0,0)-(10,0), length 10 > max: no vertex between */
    assert_int_equal(at[5], at[4] + 1);  /* (11.5,2.5)-(11.5,12.5), length 10 */
    assert_true(at[2] > at[1] + 1);      /* length 1: replaced */
    assert_true(at[3] > at[2] + 1 && at[4] > at[3] + 1 && at[6] > at[5] + 1);
    ft_chain_free(out);

    /* default max: the average chord (10 + 1 + 1.118 + 1.118 + 10 + 0.707) / 6 = 3.99: the same two kept */
    assert_near(ft_urban_chord_avg(c), (20.0 + 1.0 + 2.0 * hypot(1.0, 0.5) + hypot(0.5, 0.5)) / 6.0, 1e-12);
    o.max = 0.0;
    assert_int_equal(ft_urban_boundary(c, &o, &out), FT_OK);
    assert_int_equal(out->x[1], 10.0);
    assert_int_equal(out->y[1], 0.0);
    ft_chain_free(out);
    /* segments shorter than min are not replaced either: min above every short one changes nothing there */
    o.min = 1.2;
    assert_int_equal(ft_urban_boundary(c, &o, &out), FT_OK);
    assert_int_equal(out->n, 7);
    ft_chain_free(out);
    ft_chain_free(c);
}

/* A ring stays a ring, keeps its vertices and the closing segment is generated too. */
static void test_ring(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, 4, 2, 1);
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.dim = 1.2;
    const double q = 2.0 * cos(ft_urban_angle_for_dim(1.2));
    o.min = pow(q, -5) * (1.0 + 1e-6);
    ft_chain *out = NULL;
    assert_int_equal(ft_urban_boundary(c, &o, &out), FT_OK);
    assert_int_equal(out->closed, 1);
    assert_int_equal(out->n, 4 * 32);
    for (size_t i = 0; i < 4; i++)
        assert_int_equal(find_vertex(out, 0, xy[2 * i], xy[2 * i + 1]), 32 * i);
    for (size_t i = 0; i < out->n; i++) { /* the closing segment's pieces too */
        size_t j = (i + 1) % out->n;
        assert_near(hypot(out->x[j] - out->x[i], out->y[j] - out->y[i]) * pow(q, 5), 1.0, 1e-9);
    }
    ft_chain_free(out);
    ft_chain_free(c);
}

static int same_bytes(const ft_chain *a, const ft_chain *b)
{
    return a->n == b->n && a->closed == b->closed && memcmp(a->x, b->x, a->n * sizeof *a->x) == 0 &&
           memcmp(a->y, b->y, a->n * sizeof *a->y) == 0;
}

/* Same seed, same bytes; another seed, another curve; the chain walked backwards gives the same curve
 * backwards (each segment's stream is keyed by its end points). */
static void test_reproducible(void **state)
{
    (void)state;
    const double xy[] = {0, 0, 1, 0.2, 2, -0.1, 3, 0.4, 4, 0};
    ft_chain *c = ft_chain_from_arrays(xy, xy + 1, 5, 2, 0);
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.dim = 1.35;
    o.min = 0.01;
    o.jitter = 0.2;
    o.seed = 42;
    ft_chain *a = NULL, *b = NULL, *other = NULL, *back = NULL;
    assert_int_equal(ft_urban_boundary(c, &o, &a), FT_OK);
    assert_int_equal(ft_urban_boundary(c, &o, &b), FT_OK);
    assert_true(a->n > 500);
    assert_true(same_bytes(a, b));
    o.seed = 43;
    assert_int_equal(ft_urban_boundary(c, &o, &other), FT_OK);
    assert_false(same_bytes(a, other));
    o.seed = 42;
    ft_chain_reverse(c);
    assert_int_equal(ft_urban_boundary(c, &o, &back), FT_OK);
    ft_chain_reverse(back);
    assert_true(same_bytes(a, back));
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(other);
    ft_chain_free(back);
    ft_chain_free(c);
}

/* Two unit squares sharing the edge x = 1: on the coverage both rings carry the same detail along it and
 * the corners (nodes) stay; running twice gives the same bytes. */
static ft_layer *two_squares(void)
{
    ft_layer *l = ft_layer_create("parcels", NULL);
    const double a[] = {0, 0, 1, 0, 1, 1, 0, 1}, b[] = {1, 0, 2, 0, 2, 1, 1, 1};
    assert_true(ft_layer_add_feature(l, 1, FT_GEOM_POLYGON, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(a, a + 1, 4, 2, 1), FT_ROLE_OUTER, 0), FT_OK);
    assert_true(ft_layer_add_feature(l, 2, FT_GEOM_POLYGON, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(b, b + 1, 4, 2, 1), FT_ROLE_OUTER, 0), FT_OK);
    return l;
}

static size_t index_of(const ft_chain *c, double x, double y)
{
    return find_vertex(c, 0, x, y);
}

/* The shared edge x = 1 runs (1,0) -> (1,1) in the left square (counter-clockwise) and (1,1) -> (1,0) in
 * the right one: both rings must carry the same vertices along it, in opposite orders. */
static void check_shared(const ft_layer *l)
{
    const ft_chain *a = l->parts[0].chain, *b = l->parts[1].chain;
    size_t a0 = index_of(a, 1, 0), a1 = index_of(a, 1, 1), b0 = index_of(b, 1, 1), b1 = index_of(b, 1, 0);
    assert_true(a1 > a0 + 10);
    size_t nb = (b1 + b->n - b0) % b->n;
    assert_int_equal(a1 - a0, nb);
    for (size_t k = 0; k <= nb; k++) {
        size_t i = a0 + k, j = (b1 + b->n - k) % b->n;
        assert_true(a->x[i] == b->x[j] && a->y[i] == b->y[j]);
    }
}

static void test_coverage(void **state)
{
    (void)state;
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.dim = 1.25;
    o.min = 0.02;
    o.seed = 5;
    for (int coverage = 1; coverage >= 0; coverage--) {
        /* plain mode: the shared edge is two coincident segments, a contact the guard would never move
         * across; the unguarded generator shows that segment-keyed streams give both the same detail */
        o.allow_crossings = !coverage;
        ft_layer *l = two_squares(), *m = two_squares();
        ft_boundary_info info;
        assert_int_equal(ft_urban_boundary_layer(l, &o, coverage, &info), FT_OK);
        assert_int_equal(ft_urban_boundary_layer(m, &o, coverage, NULL), FT_OK);
        assert_int_equal(info.vertices_in, 8);
        assert_int_equal(info.vertices_out, ft_layer_vertex_count(l));
        assert_true(info.vertices_out > 100);
        assert_near(info.max_used, 1.0, 1e-12);
        assert_int_equal(info.segments_kept, 0);
        print_message("  coverage %d: %zu -> %zu vertices\n", coverage, info.vertices_in, info.vertices_out);
        check_shared(l); /* on a coverage by topology; in plain mode by the segment-keyed streams */
        for (size_t p = 0; p < 2; p++) {
            assert_true(same_bytes(l->parts[p].chain, m->parts[p].chain));
            const ft_chain *c = l->parts[p].chain;
            for (size_t k = 0; k < 4; k++) { /* corners stay */
                double cx = (double)p + (k == 1 || k == 2), cy = (double)(k >= 2);
                size_t i = 0;
                while (i < c->n && !(c->x[i] == cx && c->y[i] == cy))
                    i++;
                assert_true(i < c->n);
            }
        }
        ft_layer_free(l);
        ft_layer_free(m);
    }
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_chain *s = segment(0, 0, 1, 0), *out = NULL;
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.min = 0.1;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "dim must be in (1, 2)");
    const double bad_dims[] = {1.0, 2.0, 0.5, 2.5, NAN};
    const char *bad_dim_text[] = {"got 1", "got 2", "got 0.5", "got 2.5", "got nan"};
    for (size_t i = 0; i < 5; i++) {
        o.dim = bad_dims[i];
        assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, bad_dim_text[i]);
    }
    o.dim = 1.3;
    o.min = 0.0;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "min must be finite and > 0");
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "map units), got 0");
    o.min = -2.0;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "got -2");
    o.min = NAN;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "map units), got nan");
    o.min = 0.5;
    o.max = 0.25;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "max (0.25) must not be less than min (0.5)");
    o.max = NAN;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "max must be finite");
    o.max = 0.0;
    o.min = 2.0;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "average chord length 1");
    o.min = 0.1;
    o.jitter = 0.9;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "jitter must be in [0, ");
    o.jitter = -0.1;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "got -0.1");
    o.jitter = NAN;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "got nan");
    o.jitter = 0.0;
    o.min = 1e-9;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "raise min (1e-09)");
    o.min = 0.1;
    s->y[1] = NAN;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_NUMERIC, "vertex 1");
    s->n = 1;
    assert_error_names(ft_urban_boundary(s, &o, &out), FT_E_INVALID, "at least 2 vertices, got 1");
    assert_null(out);
    ft_chain_free(s);

    ft_layer *l = ft_layer_create("empty", NULL);
    assert_error_names(ft_urban_boundary_layer(l, &o, 1, NULL), FT_E_EMPTY, "no segment");
    ft_layer_free(l);
    l = two_squares();
    l->parts[1].chain->x[2] = INFINITY;
    assert_error_names(ft_urban_boundary_layer(l, &o, 1, NULL), FT_E_NUMERIC, "vertex 2");
    ft_layer_free(l);
    l = two_squares();
    o.max = 0.01;
    assert_error_names(ft_urban_boundary_layer(l, &o, 1, NULL), FT_E_INVALID, "max (0.01)");
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_angle_table),
        cmocka_unit_test(test_exact_lengths),
        cmocka_unit_test(test_divider_dimension),
        cmocka_unit_test(test_jitter_divider_dimension),
        cmocka_unit_test(test_long_segments_kept),
        cmocka_unit_test(test_ring),
        cmocka_unit_test(test_reproducible),
        cmocka_unit_test(test_coverage),
        cmocka_unit_test(test_guarded_boundary),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
