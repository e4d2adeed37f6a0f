/* fracterra — accuracy tests of ft_line_dim (src/line/line_dim.c) on curves of known dimension, to the
 * accuracy targets: straight lines and circles (D = 1), the Koch curve (log 4 / log 3), midpoint-generator curves
 * (D = ln 2 / ln(2 cos a)); then the method names, the table, progress and bad input.
 *
 * Midpoint-generator curves: each segment becomes two legs at base angle a, cos a = 2^(1/D - 1), the apex on
 * the left of the segment at even levels and on its right at odd levels (deterministic, alternating by
 * level). With a < 45 degrees every apex of the next level then lies on the parent's base, and each piece
 * stays inside the triangle on its base: the pieces of a level touch only at their ends, the curve never
 * overlaps itself, and its dimension is the similarity dimension ln 2 / ln(2 cos a) exactly. Its pieces of
 * level k (length l_k = (2 cos a)^-k) lie inside the circle of radius l_k around their first vertex, so a
 * divider just shorter than l_k steps from vertex to vertex of level k: the test uses those eight rulers,
 * the generator's own scales (Richardson's construction), and checks the walk finds them.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/line.h"
#include "ft_test_assert.h"

static const double pi = 3.14159265358979323846;

/* ------------------------------------------------------------------------------------------------
 * Curves
 * --------------------------------------------------------------------------------------------- */

/* A straight line of length 100 at angle `angle`, n vertices at random arc positions (seeded). */
static ft_chain *straight_line(uint64_t seed, size_t n, double angle)
{
    ft_rng *r = ft_rng_create(seed, 1);
    double *t = malloc(n * sizeof *t);
    assert_non_null(t);
    t[0] = 0.0;
    for (size_t i = 1; i < n; i++)
        t[i] = t[i - 1] + 0.5 + ft_rng_uniform(r);
    ft_chain *c = ft_chain_create(n, 0);
    for (size_t i = 0; i < n; i++)
        ft_chain_push(c, 3.0 + 100.0 * t[i] / t[n - 1] * cos(angle), -7.0 + 100.0 * t[i] / t[n - 1] * sin(angle));
    free(t);
    ft_rng_free(r);
    return c;
}

/* A circle ring of radius R centred at (cx, cy), n vertices from a seeded starting angle. */
static ft_chain *circle(uint64_t seed, size_t n, double R)
{
    ft_rng *r = ft_rng_create(seed, 2);
    double phase = 2.0 * pi * ft_rng_uniform(r), cx = 100.0 * ft_rng_uniform(r), cy = -50.0 * ft_rng_uniform(r);
    ft_chain *c = ft_chain_create(n, 1);
    for (size_t i = 0; i < n; i++)
        ft_chain_push(c, cx + R * cos(phase + 2.0 * pi * (double)i / (double)n),
                      cy + R * sin(phase + 2.0 * pi * (double)i / (double)n));
    ft_rng_free(r);
    return c;
}

/* The Koch curve on (0,0)-(1,0): each segment becomes four of a third, the bump on its left. */
static ft_chain *koch(int levels)
{
    size_t n = 1;
    for (int l = 0; l < levels; l++)
        n *= 4;
    ft_chain *c = ft_chain_create(n + 1, 0), *d = ft_chain_create(n + 1, 0);
    ft_chain_push(c, 0, 0);
    ft_chain_push(c, 1, 0);
    const double h = sqrt(3.0) / 2.0;
    for (int l = 0; l < levels; l++) {
        d->n = 0;
        for (size_t i = 0; i + 1 < c->n; i++) {
            double ax = c->x[i], ay = c->y[i], dx = (c->x[i + 1] - ax) / 3, dy = (c->y[i + 1] - ay) / 3;
            ft_chain_push(d, ax, ay);
            ft_chain_push(d, ax + dx, ay + dy);
            ft_chain_push(d, ax + 1.5 * dx - h * dy, ay + 1.5 * dy + h * dx);
            ft_chain_push(d, ax + 2 * dx, ay + 2 * dy);
        }
        ft_chain_push(d, c->x[c->n - 1], c->y[c->n - 1]);
        ft_chain *t = c;
        c = d;
        d = t;
    }
    ft_chain_free(d);
    return c;
}

/* Midpoint-generator curve of dimension D on (0,0)-(1,0), `levels` levels, sides alternating by level. */
static ft_chain *midpoint_curve(double D, int levels)
{
    size_t n = ((size_t)1 << levels) + 1;
    double *x = calloc(n, sizeof *x), *y = calloc(n, sizeof *y);
    assert_true(x != NULL && y != NULL);
    x[n - 1] = 1.0;
    const double ca = pow(2.0, 1.0 / D - 1.0), half_tan = 0.5 * sqrt(1.0 - ca * ca) / ca;
    for (int l = 0; l < levels; l++) {
        size_t step = (n - 1) >> l, half = step / 2;
        double side = (l % 2 == 0) ? 1.0 : -1.0;
        for (size_t i = 0; i + step < n; i += step) {
            double dx = x[i + step] - x[i], dy = y[i + step] - y[i];
            x[i + half] = x[i] + 0.5 * dx - side * half_tan * dy;
            y[i + half] = y[i] + 0.5 * dy + side * half_tan * dx;
        }
    }
    ft_chain *c = ft_chain_from_arrays(x, y, n, 1, 0);
    free(x);
    free(y);
    return c;
}

static double dim_of(const ft_chain *c, ft_line_method m, const ft_line_dim_opts *o)
{
    ft_line_dim_opts def = FT_LINE_DIM_OPTS_DEFAULT;
    ft_dim_result *r = NULL;
    const ft_chain *cs[] = {c};
    int rc = ft_line_dim(cs, 1, m, o ? o : &def, &r);
    if (rc != FT_OK)
        print_error("ft_line_dim(%s): %s\n", ft_line_method_name(m), ft_last_error());
    assert_int_equal(rc, FT_OK);
    assert_string_equal(r->method, ft_line_method_name(m));
    double D = r->D;
    print_message("    %-9s D = %.4f  r2 = %.4f  range %.4g .. %.4g  (%zu of %zu rows)\n", r->method, D, r->r2,
                  r->range[0], r->range[1], r->fit.n, r->table->n);
    ft_dim_result_free(r);
    return D;
}

/* ------------------------------------------------------------------------------------------------
 * Accuracy
 * --------------------------------------------------------------------------------------------- */

static const ft_line_method all_methods[] = {FT_LINE_DIVIDER, FT_LINE_EQUIPACED, FT_LINE_BOX};

static void test_straight_line_is_1(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        ft_chain *c = straight_line(seed, 2000, 0.3 * (double)seed);
        print_message("  straight line, seed %llu\n", (unsigned long long)seed);
        for (size_t m = 0; m < 3; m++)
            assert_near(dim_of(c, all_methods[m], NULL), 1.0, 0.005);
        ft_chain_free(c);
    }
}

static void test_circle_is_1(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        ft_chain *c = circle(seed, 10000, 5.0 * (double)seed);
        print_message("  circle, seed %llu\n", (unsigned long long)seed);
        for (size_t m = 0; m < 3; m++)
            assert_near(dim_of(c, all_methods[m], NULL), 1.0, 0.005);
        ft_chain_free(c);
    }
}

static void test_koch_7_levels(void **state)
{
    (void)state;
    const double D = log(4.0) / log(3.0);
    ft_chain *c = koch(7);
    assert_int_equal(c->n, 16385);
    print_message("  Koch curve, 7 levels (D = %.4f)\n", D);
    assert_near(dim_of(c, FT_LINE_DIVIDER, NULL), D, 0.01);
    assert_near(dim_of(c, FT_LINE_EQUIPACED, NULL), D, 0.01);
    assert_near(dim_of(c, FT_LINE_BOX, NULL), D, 0.02);
    ft_chain_reverse(c); /* the same curve walked the other way */
    assert_near(dim_of(c, FT_LINE_DIVIDER, NULL), D, 0.01);
    ft_chain_free(c);
}

static void test_midpoint_curves_8_levels(void **state)
{
    (void)state;
    const double Ds[] = {1.1, 1.3, 1.5, 1.7};
    for (size_t i = 0; i < 4; i++) {
        ft_chain *c = midpoint_curve(Ds[i], 8);
        const double q = 2.0 * pow(2.0, 1.0 / Ds[i] - 1.0); /* l_k = q^-k */
        ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
        o.min_scale = pow(q, -8) * (1.0 - 1e-9);
        o.max_scale = pow(q, -1) * (1.0 - 1e-9);
        o.nscales = 8;
        print_message("  midpoint curve, 8 levels, D = %.1f, rulers l_8 .. l_1\n", Ds[i]);
        assert_near(dim_of(c, FT_LINE_DIVIDER, &o), Ds[i], 0.02);
        ft_chain_free(c);
    }
}

/* ------------------------------------------------------------------------------------------------
 * The result, names, progress, several chains
 * --------------------------------------------------------------------------------------------- */

static void test_table_and_range(void **state)
{
    (void)state;
    ft_chain *c = koch(5);
    const ft_chain *cs[] = {c};
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = 0.01;
    o.max_scale = 0.3;
    o.nscales = 9;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_OK);
    assert_int_equal(r->table->n, 9);
    assert_near(r->table->rows[0].scale, 0.01, 1e-15);
    assert_near(r->table->rows[8].scale, 0.3, 1e-15);
    assert_near(r->table->rows[4].scale, sqrt(0.01 * 0.3), 1e-12); /* geometric series */
    for (size_t i = 0; i < 9; i++) {
        assert_int_equal(r->table->rows[i].used, 1);
        double len = 0;
        size_t st = 0;
        assert_int_equal(ft_line_divider_walk(c, r->table->rows[i].scale, 0, &len, &st), FT_OK);
        double len2 = 0;
        size_t st2 = 0;
        assert_int_equal(ft_line_divider_walk(c, r->table->rows[i].scale, 1, &len2, &st2), FT_OK);
        assert_near(r->table->rows[i].value, 0.5 * (len + len2), 1e-12);
        assert_near(r->table->rows[i].count, 0.5 * ((double)st + (double)st2), 0);
    }
    assert_near(r->range[0], 0.01, 1e-15);
    assert_near(r->range[1], 0.3, 1e-15);
    ft_dim_result_free(r);
    /* box rows count boxes */
    o.nscales = 5;
    assert_int_equal(ft_line_dim(cs, 1, FT_LINE_BOX, &o, &r), FT_OK);
    for (size_t i = 0; i < r->table->n; i++)
        assert_near(r->table->rows[i].count, r->table->rows[i].value, 0);
    assert_string_equal(r->method, "box");
    ft_dim_result_free(r);
    ft_chain_free(c);
}

static void test_method_names(void **state)
{
    (void)state;
    const char *names[] = {"divider", "equipaced", "hybrid", "box"};
    for (int i = 0; i < 4; i++) {
        ft_line_method m = FT_LINE_BOX;
        assert_string_equal(ft_line_method_name((ft_line_method)i), names[i]);
        assert_int_equal(ft_line_method_parse(names[i], &m), FT_OK);
        assert_int_equal((int)m, i);
    }
    ft_line_method m;
    assert_error_names(ft_line_method_parse("ruler", &m), FT_E_INVALID, "'ruler'");
    assert_error_names(ft_line_method_parse(NULL, &m), FT_E_INVALID, "NULL");
}

static int count_calls(double frac, const char *msg, void *arg)
{
    (void)frac;
    (void)msg;
    int *n = arg;
    return ++*n < 3;
}

static void test_progress_cancels(void **state)
{
    (void)state;
    ft_chain *c = koch(4);
    const ft_chain *cs[] = {c};
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    int calls = 0;
    o.progress = count_calls;
    o.progress_arg = &calls;
    ft_dim_result *r = (ft_dim_result *)&calls;
    assert_int_equal(ft_line_dim(cs, 1, FT_LINE_HYBRID, &o, &r), FT_E_CANCELLED);
    assert_null(r);
    assert_int_equal(calls, 3);
    ft_chain_free(c);
}

/* The lengths of a set are the sums of its chains': a Koch curve cut in two measures like the whole over
 * the same rulers (the cut only adds a fractional step), and single-vertex chains are skipped. Boxes
 * are counted over the whole set at once, so the cut changes nothing. */
static void test_several_chains(void **state)
{
    (void)state;
    ft_chain *k = koch(6);
    size_t h = k->n / 2;
    ft_chain *a = ft_chain_from_arrays(k->x, k->y, h + 1, 1, 0);
    ft_chain *b = ft_chain_from_arrays(k->x + h, k->y + h, k->n - h, 1, 0);
    const double p[] = {5, 5};
    ft_chain *dot = ft_chain_from_arrays(p, p + 1, 1, 1, 0);
    const ft_chain *parts[] = {a, dot, b};
    const ft_chain *whole[] = {k};
    ft_dim_result *r = NULL, *w = NULL;
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.max_scale = 0.1;
    o.fit_whole_range = 1;
    assert_int_equal(ft_line_dim(parts, 3, FT_LINE_DIVIDER, &o, &r), FT_OK);
    assert_int_equal(ft_line_dim(whole, 1, FT_LINE_DIVIDER, &o, &w), FT_OK);
    assert_near(r->D, w->D, 0.01);
    assert_near(r->table->rows[0].scale, w->table->rows[0].scale, 0); /* same median segment */
    ft_dim_result_free(r);
    ft_dim_result_free(w);
    assert_int_equal(ft_line_dim(parts, 3, FT_LINE_BOX, NULL, &r), FT_OK);
    assert_int_equal(ft_line_dim(whole, 1, FT_LINE_BOX, NULL, &w), FT_OK);
    for (size_t i = 0; i < r->table->n; i++)
        assert_near(r->table->rows[i].value, w->table->rows[i].value, 0);
    ft_dim_result_free(r);
    ft_dim_result_free(w);
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(dot);
    ft_chain_free(k);
}

/* ------------------------------------------------------------------------------------------------
 * Bad input
 * --------------------------------------------------------------------------------------------- */

static void test_bad_input(void **state)
{
    (void)state;
    ft_chain *c = koch(3);
    const ft_chain *cs[] = {c};
    ft_dim_result *r = NULL;
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    assert_error_names(ft_line_dim(cs, 0, FT_LINE_DIVIDER, &o, &r), FT_E_EMPTY, "no chains");
    assert_error_names(ft_line_dim(NULL, 3, FT_LINE_DIVIDER, &o, &r), FT_E_EMPTY, "no chains");
    assert_null(r);

    const double p[] = {1, 2};
    ft_chain *one = ft_chain_from_arrays(p, p + 1, 1, 1, 0), *none = ft_chain_create(0, 1);
    const ft_chain *shorts[] = {one, none};
    assert_error_names(ft_line_dim(shorts, 2, FT_LINE_BOX, &o, &r), FT_E_EMPTY, "2 vertices");

    o.min_scale = 0.5;
    o.max_scale = 0.1;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID, "min_scale (0.5)");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = -1.0;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID, "min_scale must be");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    o.max_scale = -0.25;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_EQUIPACED, &o, &r), FT_E_INVALID, "-0.25");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = NAN;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID, "nan");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    o.nscales = 2;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID, "got 2");
    o.nscales = -5;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_BOX, &o, &r), FT_E_INVALID, "got -5");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    o.box_offsets = 0;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_BOX, &o, &r), FT_E_INVALID, "box_offsets");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    assert_error_names(ft_line_dim(cs, 1, (ft_line_method)9, &o, &r), FT_E_INVALID, "got 9");
    /* an automatic lower limit above the user's max_scale */
    o.max_scale = 1e-6;
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID, "max_scale 1e-06");
    o = (ft_line_dim_opts)FT_LINE_DIM_OPTS_DEFAULT;
    o.fit.tol = -1.0; /* the shared fit's options are checked too */
    assert_int_equal(ft_line_dim(cs, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);

    c->y[5] = NAN;
    const ft_chain *two[] = {one, c};
    assert_error_names(ft_line_dim(two, 2, FT_LINE_DIVIDER, NULL, &r), FT_E_NUMERIC, "chain 1: vertex 5");
    const double same[] = {2, 2, 2, 2, 2, 2};
    ft_chain *flat = ft_chain_from_arrays(same, same + 1, 3, 2, 0);
    const ft_chain *fl[] = {flat};
    assert_error_names(ft_line_dim(fl, 1, FT_LINE_DIVIDER, NULL, &r), FT_E_EMPTY, "zero length");
    assert_error_names(ft_line_dim(cs, 1, FT_LINE_DIVIDER, NULL, NULL), FT_E_INVALID, "NULL");
    assert_null(r);
    ft_chain_free(flat);
    ft_chain_free(one);
    ft_chain_free(none);
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_straight_line_is_1),
        cmocka_unit_test(test_circle_is_1),
        cmocka_unit_test(test_koch_7_levels),
        cmocka_unit_test(test_midpoint_curves_8_levels),
        cmocka_unit_test(test_table_and_range),
        cmocka_unit_test(test_method_names),
        cmocka_unit_test(test_progress_cancels),
        cmocka_unit_test(test_several_chains),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
