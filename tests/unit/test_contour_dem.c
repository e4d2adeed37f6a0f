/* fracterra — tests of ft_contour_stack_to_dem (the DEM of a contour stack).
 *
 * Expected values come from geometry, not from the code: concentric circles of radii R0 - k d at
 * elevations k I are the contours of the cone z = I (R0 - rho) / d, and r.surf.contour's rule
 * z = z_lo + (z_hi - z_lo) d_lo / (d_lo + d_hi) with Euclidean distances to two concentric circles gives
 * that cone exactly; above the top circle (radius r_t) the documented cap is
 * z = z_t + summit I (1 - (rho / r_t)^2). Circles are 720-gons (their sagitta, r (1 - cos(pi / 720)),
 * is below 0.001 cells here). Stacks are built by hand from the public structs.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/contour.h"
#include "ft_test_assert.h"

#define CIRCLE_N 720
#define CX 1000.0 /* centre of the circles, on a cell corner of the 1-unit grids */
#define CY 2000.0

/* ---- hand-made stacks ---- */

static ft_chain *circle(double cx, double cy, double r, int ccw)
{
    ft_chain *c = ft_chain_create(CIRCLE_N, 1);
    assert_non_null(c);
    for (int i = 0; i < CIRCLE_N; i++) {
        double a = 2.0 * M_PI * i / CIRCLE_N * (ccw ? 1.0 : -1.0);
        assert_int_equal(ft_chain_push(c, cx + r * cos(a), cy + r * sin(a)), FT_OK);
    }
    return c;
}

static ft_contour_stack *stack_new(size_t n, double interval)
{
    ft_contour_stack *s = calloc(1, sizeof *s);
    assert_non_null(s);
    s->levels = calloc(n, sizeof *s->levels);
    assert_non_null(s->levels);
    s->n = n;
    s->interval = interval;
    s->spacing = 1.0;
    for (size_t k = 0; k < n; k++) {
        s->levels[k].elev = interval * (double)k;
        s->levels[k].polys = calloc(1, sizeof(ft_polygon_set));
        assert_non_null(s->levels[k].polys);
    }
    return s;
}

/* Adds a polygon (outer ring and optional hole) to level k. */
static void add_poly(ft_contour_stack *s, size_t k, ft_chain *outer, ft_chain *hole)
{
    ft_polygon_set *ps = s->levels[k].polys;
    ps->polys = realloc(ps->polys, (ps->n + 1) * sizeof *ps->polys);
    assert_non_null(ps->polys);
    ft_polygon *p = &ps->polys[ps->n++];
    p->outer = outer;
    p->holes = NULL;
    p->nholes = 0;
    if (hole != NULL) {
        p->holes = malloc(sizeof *p->holes);
        assert_non_null(p->holes);
        p->holes[0] = hole;
        p->nholes = 1;
    }
}

static void stack_del(ft_contour_stack *s)
{
    for (size_t k = 0; k < s->n; k++) {
        ft_polygon_set *ps = s->levels[k].polys;
        for (size_t p = 0; p < ps->n; p++) {
            ft_chain_free(ps->polys[p].outer);
            for (size_t h = 0; h < ps->polys[p].nholes; h++)
                ft_chain_free(ps->polys[p].holes[h]);
            free(ps->polys[p].holes);
        }
        free(ps->polys);
        free(ps);
    }
    free(s->levels);
    free(s);
}

/* Concentric circles r_k = r0 - k d at elevations k I (every other one clockwise when mixed is set). */
static ft_contour_stack *cone_stack(size_t n, double r0, double d, double interval, int mixed)
{
    ft_contour_stack *s = stack_new(n, interval);
    for (size_t k = 0; k < n; k++)
        add_poly(s, k, circle(CX, CY, r0 - (double)k * d, !(mixed && k % 2)), NULL);
    return s;
}

static ft_grid *dem_ok(const ft_contour_stack *s, double cell, double summit)
{
    ft_contour_dem_opts o = FT_CONTOUR_DEM_OPTS_DEFAULT;
    o.cell = cell;
    o.summit = summit;
    ft_grid *g = NULL;
    if (ft_contour_stack_to_dem(s, &o, NULL, &g) != FT_OK)
        fail_msg("ft_contour_stack_to_dem: %s", ft_last_error());
    assert_non_null(g);
    assert_non_null(g->mask);
    return g;
}

static double rho_of(const ft_grid *g, size_t c, size_t r, double cx, double cy)
{
    double x, y;
    ft_grid_cell_center(g, (double)c, (double)r, &x, &y);
    return hypot(x - cx, y - cy);
}

/* ---- tests ---- */

#define R0 100.0
#define D 10.0
#define I 5.0
#define NLEV 9 /* radii 100 .. 20 */

/* Concentric circles give the cone between them (within 1% of the interval) and the documented cap
 * above the top one (within 2%), nodata outside, and the grid frame of the defaults. */
static void test_cone(void **state)
{
    (void)state;
    ft_contour_stack *s = cone_stack(NLEV, R0, D, I, 0);
    ft_grid *g = dem_ok(s, 1.0, 0.5);
    /* one cell of margin around the lowest level's 200 x 200 box, centred on it */
    assert_int_equal(g->nx, 202);
    assert_int_equal(g->ny, 202);
    assert_near(g->gt[0], CX - 101.0, 1e-9);
    assert_near(g->gt[3], CY + 101.0, 1e-9);
    assert_near(g->gt[1], 1.0, 0);
    assert_near(g->gt[5], -1.0, 0);
    double r_top = R0 - (NLEV - 1) * D, z_top = (NLEV - 1) * I;
    double worst_band = 0.0, worst_cap = 0.0, zmax = -INFINITY;
    size_t bands = 0, caps = 0;
    for (size_t r = 0; r < g->ny; r++)
        for (size_t c = 0; c < g->nx; c++) {
            double rho = rho_of(g, c, r, CX, CY);
            int valid = ft_grid_is_valid(g, c, r);
            float z = g->z[r * g->nx + c];
            if (rho > R0 + 0.01) {
                assert_false(valid);
                continue;
            }
            if (rho < R0 - 0.01)
                assert_true(valid);
            if (!valid)
                continue;
            zmax = fmax(zmax, z);
            if (rho >= r_top) {
                worst_band = fmax(worst_band, fabs(z - I * (R0 - rho) / D));
                bands++;
            } else {
                double t = rho / r_top;
                worst_cap = fmax(worst_cap, fabs(z - (z_top + 0.5 * I * (1.0 - t * t))));
                assert_true(z > z_top);
                caps++;
            }
        }
    assert_true(bands > 30000 && caps > 1200);
    if (worst_band > 0.01 * I || worst_cap > 0.02 * I)
        fail_msg("cone: worst error %g between contours, %g on the cap (interval %g)", worst_band, worst_cap, I);
    assert_true(zmax <= z_top + 0.5 * I + 1e-4);
    assert_true(zmax > z_top + 0.5 * I * 0.98);
    ft_grid_free(g);
    stack_del(s);
}

/* Clockwise rings count as the same regions (the crossing weights follow each ring's orientation). */
static void test_orientation_free(void **state)
{
    (void)state;
    ft_contour_stack *a = cone_stack(NLEV, R0, D, I, 0), *b = cone_stack(NLEV, R0, D, I, 1);
    ft_grid *ga = dem_ok(a, 2.0, 0.5), *gb = dem_ok(b, 2.0, 0.5);
    assert_int_equal(ga->nx, gb->nx);
    assert_int_equal(ga->ny, gb->ny);
    for (size_t i = 0; i < ga->nx * ga->ny; i++) {
        assert_int_equal(ga->mask[i], gb->mask[i]);
        if (ga->mask[i])
            assert_near(ga->z[i], gb->z[i], 1e-3 * I);
    }
    ft_grid_free(ga);
    ft_grid_free(gb);
    stack_del(a);
    stack_del(b);
}

/* Two peaks on one base: level 1 has two islands, level 2 only one. The secondary peak rises above z1 by
 * at most summit x (z2 - z1); every cell lies between the contours it is between; z grows along a ray
 * to each summit. */
static void test_two_peaks(void **state)
{
    (void)state;
    ft_contour_stack *s = stack_new(3, 10.0);
    add_poly(s, 0, circle(CX, CY, 100.0, 1), NULL);
    add_poly(s, 1, circle(CX - 45.0, CY, 40.0, 1), NULL); /* main peak */
    add_poly(s, 1, circle(CX + 55.0, CY, 30.0, 1), NULL); /* secondary */
    add_poly(s, 2, circle(CX - 45.0, CY, 20.0, 1), NULL);
    ft_grid *g = dem_ok(s, 1.0, 0.5);
    double sec_max = -INFINITY, main_max = -INFINITY;
    for (size_t r = 0; r < g->ny; r++)
        for (size_t c = 0; c < g->nx; c++) {
            if (!ft_grid_is_valid(g, c, r))
                continue;
            double z = g->z[r * g->nx + c];
            double r0 = rho_of(g, c, r, CX, CY), rm = rho_of(g, c, r, CX - 45.0, CY),
                   rs = rho_of(g, c, r, CX + 55.0, CY);
            int in1 = rm < 40.0 - 0.01 || rs < 30.0 - 0.01, out1 = rm > 40.0 + 0.01 && rs > 30.0 + 0.01;
            assert_true(r0 < 100.0 + 0.01);
            assert_true(z >= 0.0 - 1e-4);
            if (in1)
                assert_true(z >= 10.0 - 1e-4);
            if (out1)
                assert_true(z <= 10.0 + 1e-4);
            if (rm < 20.0 - 0.01)
                assert_true(z > 20.0);
            if (rm > 20.0 + 0.01)
                assert_true(z <= 20.0 + 1e-4);
            if (rs < 30.0)
                sec_max = fmax(sec_max, z);
            if (rm < 20.0)
                main_max = fmax(main_max, z);
        }
    assert_true(sec_max > 10.0 + 0.9 * 5.0 && sec_max <= 15.0 + 1e-4);
    assert_true(main_max > 20.0 + 0.9 * 5.0 && main_max <= 25.0 + 1e-4);
    /* monotone along the rays from the base's edge to each summit's centre */
    double sx[2] = {CX - 45.0, CX + 55.0};
    for (int p = 0; p < 2; p++) {
        double prev = -INFINITY;
        double x_edge = p == 0 ? CX - 99.5 : CX + 99.5;
        for (int k = 0; k <= 200; k++) {
            double x = x_edge + (sx[p] - x_edge) * k / 200.0;
            double col = (x - g->gt[0]) / g->gt[1] - 0.5, row = (CY - g->gt[3]) / g->gt[5] - 0.5;
            size_t c = (size_t)lround(col), r = (size_t)lround(row);
            double z = g->z[r * g->nx + c];
            assert_true(z >= prev - 1e-4);
            prev = z;
        }
    }
    ft_grid_free(g);
    stack_del(s);
}

/* A crater: level 1 is an annulus (outer 80, hole 30). Inside the hole the cells lie in band 0 with no
 * contour 0 to reach: a pit mirroring the cap, from z1 at the hole's ring down to z1 - summit x I. */
static void test_crater(void **state)
{
    (void)state;
    ft_contour_stack *s = stack_new(2, 10.0);
    add_poly(s, 0, circle(CX, CY, 100.0, 1), NULL);
    add_poly(s, 1, circle(CX, CY, 80.0, 1), circle(CX, CY, 30.0, 0));
    ft_grid *g = dem_ok(s, 1.0, 0.5);
    double zmin_pit = INFINITY;
    for (size_t r = 0; r < g->ny; r++)
        for (size_t c = 0; c < g->nx; c++) {
            if (!ft_grid_is_valid(g, c, r))
                continue;
            double rho = rho_of(g, c, r, CX, CY), z = g->z[r * g->nx + c];
            if (rho < 30.0 - 0.01) {
                double t = 1.0 - rho / 30.0, expect = 10.0 - 5.0 * (1.0 - (1.0 - t) * (1.0 - t));
                assert_near(z, expect, 0.02 * 10.0);
                zmin_pit = fmin(zmin_pit, z);
            } else if (rho > 80.0 + 0.01) {
                assert_near(z, 10.0 * (100.0 - rho) / 20.0, 0.01 * 10.0);
            } else if (rho > 30.0 + 0.01 && rho < 80.0 - 0.01) {
                assert_true(z > 10.0); /* the rim: a summit region shaped by the distance to both rings */
            }
        }
    assert_near(zmin_pit, 5.0, 0.1);
    ft_grid_free(g);
    stack_del(s);
}

/* Default cell = the larger extent / 512; margin; CRS copied; summit 0 leaves the top flat. */
static void test_frame_crs_and_flat_top(void **state)
{
    (void)state;
    ft_contour_stack *s = stack_new(2, 10.0);
    /* a 400 x 100 rectangle and a smaller one inside */
    double x[4] = {0, 400, 400, 0}, y[4] = {0, 0, 100, 100};
    double xi[4] = {100, 300, 300, 100}, yi[4] = {30, 30, 70, 70};
    add_poly(s, 0, ft_chain_from_arrays(x, y, 4, 1, 1), NULL);
    add_poly(s, 1, ft_chain_from_arrays(xi, yi, 4, 1, 1), NULL);
    ft_contour_dem_opts o = FT_CONTOUR_DEM_OPTS_DEFAULT;
    o.summit = 0.0;
    o.margin = 10.0;
    ft_grid *g = NULL;
    const char *wkt = "LOCAL_CS[\"test\",UNIT[\"metre\",1]]";
    assert_int_equal(ft_contour_stack_to_dem(s, &o, wkt, &g), FT_OK);
    assert_near(g->gt[1], 400.0 / 512.0, 1e-12);
    assert_int_equal(g->nx, (size_t)ceil(420.0 / (400.0 / 512.0)));
    assert_int_equal(g->ny, (size_t)ceil(120.0 / (400.0 / 512.0)));
    assert_string_equal(g->crs_wkt, wkt);
    double zmin, zmax;
    assert_int_equal(ft_grid_minmax(g, &zmin, &zmax), FT_OK);
    assert_near(zmax, 10.0, 1e-5);
    assert_true(zmin >= 0.0 && zmin < 0.5);
    /* between the rectangles, along the row nearest y = 50, west of the inner one: the distances to the
     * outer and inner rectangles' sides */
    size_t r = (size_t)floor((g->gt[3] - 50.0) / g->gt[1]);
    size_t checked = 0;
    for (size_t c = 0; c < g->nx; c++) {
        double cx, cy;
        ft_grid_cell_center(g, (double)c, (double)r, &cx, &cy);
        if (!(cx > 0.5 && cx < 99.5))
            continue;
        double dlo = fmin(fmin(cx, 400.0 - cx), fmin(cy, 100.0 - cy));
        double dhi = hypot(100.0 - cx, fmax(0.0, fmax(30.0 - cy, cy - 70.0)));
        assert_near(g->z[r * g->nx + c], 10.0 * dlo / (dlo + dhi), 0.01 * 10.0);
        checked++;
    }
    assert_true(checked > 120);
    ft_grid_free(g);
    stack_del(s);
}

static int cancel_at_half(double frac, const char *msg, void *arg)
{
    (void)msg;
    (void)arg;
    return frac < 0.5;
}

static void test_bad_options(void **state)
{
    (void)state;
    ft_contour_stack *s = cone_stack(3, 50.0, 10.0, 5.0, 0);
    ft_contour_dem_opts o = FT_CONTOUR_DEM_OPTS_DEFAULT;
    ft_grid *g = (ft_grid *)&g;
    o.cell = -1.0;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_INVALID, "cell");
    assert_null(g);
    o.cell = 0.0;
    o.margin = NAN;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_INVALID, "margin");
    o.margin = 0.0;
    o.summit = -0.5;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_INVALID, "summit");
    o.summit = 0.5;
    o.cell = 1e-4;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_INVALID, "cells");
    o.cell = 0.0;
    assert_error_names(ft_contour_stack_to_dem(NULL, &o, NULL, &g), FT_E_EMPTY, "no level");
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, NULL), FT_E_INVALID, "output");
    o.progress = cancel_at_half;
    assert_int_equal(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_CANCELLED);
    assert_null(g);
    o.progress = NULL;
    /* elevations must increase */
    s->levels[2].elev = s->levels[1].elev;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_INVALID, "level 2");
    s->levels[2].elev = 10.0;
    /* a NaN vertex, a two-vertex ring */
    double keep = s->levels[1].polys->polys[0].outer->x[7];
    s->levels[1].polys->polys[0].outer->x[7] = NAN;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_NUMERIC, "vertex 7");
    s->levels[1].polys->polys[0].outer->x[7] = keep;
    size_t n = s->levels[2].polys->polys[0].outer->n;
    s->levels[2].polys->polys[0].outer->n = 2;
    assert_error_names(ft_contour_stack_to_dem(s, &o, NULL, &g), FT_E_INVALID, "level 2");
    s->levels[2].polys->polys[0].outer->n = n;
    /* a single level without an interval has no summit height */
    ft_contour_stack *one = cone_stack(1, 50.0, 10.0, 0.0, 0);
    assert_error_names(ft_contour_stack_to_dem(one, &o, NULL, &g), FT_E_INVALID, "interval");
    o.summit = 0.0;
    assert_int_equal(ft_contour_stack_to_dem(one, &o, NULL, &g), FT_OK);
    ft_grid_free(g);
    stack_del(one);
    stack_del(s);
}

/* The same stack gives the same cells on 1 and 2 threads. */
static void test_deterministic(void **state)
{
    (void)state;
    ft_contour_stack *s = stack_new(3, 10.0);
    add_poly(s, 0, circle(CX, CY, 100.0, 1), NULL);
    add_poly(s, 1, circle(CX - 45.0, CY, 40.0, 1), NULL);
    add_poly(s, 1, circle(CX + 55.0, CY, 30.0, 1), NULL);
    add_poly(s, 2, circle(CX - 45.0, CY, 20.0, 1), NULL);
    int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    ft_grid *a = dem_ok(s, 0.7, 0.5);
    omp_set_num_threads(2);
    ft_grid *b = dem_ok(s, 0.7, 0.5);
    omp_set_num_threads(threads);
    assert_int_equal(a->nx * a->ny, b->nx * b->ny);
    assert_memory_equal(a->z, b->z, a->nx * a->ny * sizeof(float));
    assert_memory_equal(a->mask, b->mask, a->nx * a->ny);
    ft_grid_free(a);
    ft_grid_free(b);
    stack_del(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cone),          cmocka_unit_test(test_orientation_free),
        cmocka_unit_test(test_two_peaks),     cmocka_unit_test(test_crater),
        cmocka_unit_test(test_frame_crs_and_flat_top), cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_deterministic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
