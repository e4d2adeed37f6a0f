/* fracterra — unit tests of src/urban/dim_area.c, dim_area_grid.c, row_runs.c, class_stats.c and classes.c:
 * exact box counts on hand cases, then the accuracy targets: a filled square gives 2 +- 0.02 (area)
 * and 1 +- 0.02 (boundary), a Koch island log 4 / log 3 +- 0.03 (boundary); the same on a classified
 * raster; class statistics and grouping; bad input.
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

#include "fracterra/urban.h"

#include "test_urban.h"

/* Adds a polygon feature: an outer ring and optional holes, each given as xy pairs. */
static void add_polygon(ft_layer *l, int64_t fid, const double *outer, size_t n, const double *hole, size_t nh)
{
    assert_true(ft_layer_add_feature(l, fid, FT_GEOM_POLYGON, 0) >= 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(outer, outer + 1, n, 2, 1), FT_ROLE_OUTER, 0), FT_OK);
    if (hole != NULL)
        assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(hole, hole + 1, nh, 2, 1), FT_ROLE_INNER, 0),
                         FT_OK);
}

static void add_square(ft_layer *l, int64_t fid, double x0, double y0, double side)
{
    const double xy[] = {x0, y0, x0 + side, y0, x0 + side, y0 + side, x0, y0 + side};
    add_polygon(l, fid, xy, 4, NULL, 0);
}

/* The counts of the table, in increasing size, for the explicit sizes given. */
static void counts_at(const ft_layer *l, ft_area_what what, const double *cells, size_t n, int offsets, double *out)
{
    ft_area_dim_opts o = FT_AREA_DIM_OPTS_DEFAULT;
    o.what = what;
    o.cells = cells;
    o.ncells = n;
    o.offsets = offsets;
    o.fit_whole_range = 1;
    o.fewest = 1; /* the hand counts are the fewest over origins at multiples of r / offsets */
    ft_dim_result *r = NULL;
    int rc = ft_urban_dim_area(l, NULL, 0, &o, &r);
    if (rc != FT_OK)
        print_error("ft_urban_dim_area: %s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    assert_string_equal(r->method, what == FT_AREA_AREA ? "box-area" : "box-boundary");
    assert_int_equal(r->table->n, n);
    for (size_t i = 0; i < n; i++) {
        assert_true(r->table->rows[i].value == r->table->rows[i].count);
        assert_int_equal(r->table->rows[i].used, 1);
        out[i] = r->table->rows[i].value;
    }
    ft_dim_result_free(r);
}

static double dim_of(const ft_layer *l, ft_area_what what)
{
    ft_area_dim_opts o = FT_AREA_DIM_OPTS_DEFAULT;
    o.what = what;
    ft_dim_result *r = NULL;
    int rc = ft_urban_dim_area(l, NULL, 0, &o, &r);
    if (rc != FT_OK)
        print_error("ft_urban_dim_area: %s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    double D = r->D;
    print_message("    %-12s D = %.4f  r2 = %.5f  range %.4g .. %.4g  (%zu of %zu sizes)\n", r->method, D, r->r2,
                  r->range[0], r->range[1], r->fit.n, r->table->n);
    ft_dim_result_free(r);
    return D;
}

/* ------------------------------------------------------------------------------------------------
 * Exact counts
 * --------------------------------------------------------------------------------------------- */

/* Square [0,4]²: area 16, 4, 1 boxes of side 1, 2, 4; boundary 16, 8, 4 (half-open cells: x = 4 lies in
 * the fifth column, and the middle box of side 2 holds no boundary point); offsets cannot do better. */
static void test_square_counts(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("sq", NULL);
    add_square(l, 1, 0, 0, 4);
    const double cells[] = {4, 1, 2};
    double v[3];
    for (int k = 1; k <= 4; k *= 2) {
        counts_at(l, FT_AREA_AREA, cells, 3, k, v);
        assert_true(v[0] == 16 && v[1] == 4 && v[2] == 1);
        counts_at(l, FT_AREA_BOUNDARY, cells, 3, k, v);
        assert_true(v[0] == 16 && v[1] == 8 && v[2] == 4);
    }
    /* a box that only touches the square along an edge does not count: side 0.5 gives 8 x 8 */
    const double half[] = {0.5, 3};
    counts_at(l, FT_AREA_AREA, half, 2, 1, v);
    assert_true(v[0] == 64 && v[1] == 4); /* side 3 aligned: 2 x 2 */
    ft_layer_free(l);

    /* [0,4]² with the hole [1,3]²: 12 unit boxes meet the interior; the boundary adds the hole's ring */
    l = ft_layer_create("holed", NULL);
    const double outer[] = {0, 0, 4, 0, 4, 4, 0, 4}, hole[] = {1, 1, 1, 3, 3, 3, 3, 1};
    add_polygon(l, 1, outer, 4, hole, 4);
    const double one[] = {1, 2};
    counts_at(l, FT_AREA_AREA, one, 2, 1, v);
    assert_true(v[0] == 12 && v[1] == 4);
    counts_at(l, FT_AREA_BOUNDARY, one, 2, 1, v);
    assert_true(v[0] == 24 && v[1] == 9); /* 16 cells for the outer ring, 8 for the hole's; not [2,3)² */
    ft_layer_free(l);

    /* two squares sharing an edge, and an overlapping third: cells counted once */
    l = ft_layer_create("two", NULL);
    add_square(l, 1, 0, 0, 2);
    add_square(l, 2, 2, 0, 2);
    add_square(l, 3, 1, 0, 2);
    const double unit[] = {1, 4};
    counts_at(l, FT_AREA_AREA, unit, 2, 1, v);
    assert_true(v[0] == 8 && v[1] == 1);
    ft_layer_free(l);

    /* a triangle (0,0) (3,0) (0,3): unit cells meeting the interior are the 6 below the diagonal; the
     * diagonal only touches the corners of (1,1), (2,0) and (0,2) (open cells) */
    l = ft_layer_create("tri", NULL);
    const double tri[] = {0, 0, 3, 0, 0, 3};
    add_polygon(l, 1, tri, 3, NULL, 0);
    const double tcells[] = {1, 3};
    counts_at(l, FT_AREA_AREA, tcells, 2, 1, v);
    assert_true(v[0] == 6 && v[1] == 1);
    ft_layer_free(l);
}

/* ------------------------------------------------------------------------------------------------
 * Accuracy
 * --------------------------------------------------------------------------------------------- */

static void test_filled_square(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("square", NULL);
    add_square(l, 1, 123.4, -56.7, 10.0);
    print_message("  square of side 10 at (123.4, -56.7)\n");
    assert_near(dim_of(l, FT_AREA_AREA), 2.0, 0.02);
    assert_near(dim_of(l, FT_AREA_BOUNDARY), 1.0, 0.02);
    ft_layer_free(l);
    /* the same square turned by 30 degrees */
    l = ft_layer_create("turned", NULL);
    const double c = cos(M_PI / 6), s = sin(M_PI / 6);
    const double xy[] = {0, 0, 10 * c, 10 * s, 10 * c - 10 * s, 10 * s + 10 * c, -10 * s, 10 * c};
    add_polygon(l, 1, xy, 4, NULL, 0);
    print_message("  square of side 10 turned by 30 degrees\n");
    assert_near(dim_of(l, FT_AREA_AREA), 2.0, 0.02);
    assert_near(dim_of(l, FT_AREA_BOUNDARY), 1.0, 0.02);
    ft_layer_free(l);
}

/* The Koch island (snowflake) of `levels` levels on the unit triangle: clockwise, so the bumps on the left of
 * each edge point outwards. */
static ft_chain *koch_island(int levels)
{
    const double h = sqrt(3.0) / 2.0;
    ft_chain *c = ft_chain_create(3, 1), *d = ft_chain_create(3, 1);
    ft_chain_push(c, 0, 0);
    ft_chain_push(c, 0.5, h);
    ft_chain_push(c, 1, 0);
    for (int l = 0; l < levels; l++) {
        d->n = 0;
        for (size_t i = 0; i < c->n; i++) {
            size_t j = (i + 1) % c->n;
            double ax = c->x[i], ay = c->y[i], dx = (c->x[j] - ax) / 3, dy = (c->y[j] - ay) / 3;
            ft_chain_push(d, ax, ay);
            ft_chain_push(d, ax + dx, ay + dy);
            ft_chain_push(d, ax + 1.5 * dx - h * dy, ay + 1.5 * dy + h * dx);
            ft_chain_push(d, ax + 2 * dx, ay + 2 * dy);
        }
        ft_chain *t = c;
        c = d;
        d = t;
    }
    ft_chain_free(d);
    return c;
}

static void test_koch_island(void **state)
{
    (void)state;
    const double D = log(4.0) / log(3.0);
    ft_layer *l = ft_layer_create("koch", NULL);
    assert_true(ft_layer_add_feature(l, 1, FT_GEOM_POLYGON, 0) >= 0);
    ft_chain *c = koch_island(6);
    assert_int_equal(c->n, 3 * 4096);
    assert_true(ft_chain_signed_area(c) < 0.0);
    assert_int_equal(ft_layer_add_part(l, c, FT_ROLE_OUTER, 0), FT_OK);
    print_message("  Koch island, 6 levels (boundary D = %.4f)\n", D);
    assert_near(dim_of(l, FT_AREA_BOUNDARY), D, 0.03);
    assert_near(dim_of(l, FT_AREA_AREA), 2.0, 0.05); /* the interior dominates */
    ft_urban_stats st;
    assert_int_equal(ft_urban_layer_stats(l, NULL, 0, &st), FT_OK);
    /* area after n levels: (sqrt 3 / 4)(8/5 - (3/5)(4/9)^n) */
    assert_near(st.area, sqrt(3.0) / 4.0 * (1.6 - 0.6 * pow(4.0 / 9.0, 6)), 1e-12);
    assert_near(st.perimeter, 3.0 * pow(4.0 / 3.0, 6), 1e-9);
    ft_layer_free(l);
}

/* ------------------------------------------------------------------------------------------------
 * Classified rasters
 * --------------------------------------------------------------------------------------------- */

/* 400 x 400 cells of 2 m: class 3 is the square of 300 x 300 cells at (50, 40), class 5 two 10 x 10
 * squares, row 399 is nodata. */
static ft_grid *class_grid(void)
{
    ft_grid *g = ft_grid_create(400, 400);
    assert_non_null(g);
    g->gt[1] = 2.0;
    g->gt[5] = -2.0;
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t row = 0; row < 400; row++)
        for (size_t col = 0; col < 400; col++) {
            float v = 0.0f;
            if (col >= 50 && col < 350 && row >= 40 && row < 340)
                v = 3.0f;
            if (row >= 370 && row < 380 && ((col >= 10 && col < 20) || (col >= 30 && col < 40)))
                v = 5.0f;
            g->z[row * 400 + col] = v;
            g->mask[row * 400 + col] = row != 399;
        }
    return g;
}

static void test_grid_classes(void **state)
{
    (void)state;
    ft_grid *g = class_grid();
    ft_area_dim_opts o = FT_AREA_DIM_OPTS_DEFAULT;
    ft_dim_result *r = NULL;
    /* hand counts: class 5 in boxes of 1, 5 and 10 cells (2, 10, 20 m) */
    const double cells[] = {2, 10, 20};
    o.cells = cells;
    o.ncells = 3;
    o.fit_whole_range = 1;
    o.what = FT_AREA_AREA;
    assert_int_equal(ft_urban_dim_area_grid(g, 5.0, &o, &r), FT_OK);
    assert_true(r->table->rows[0].value == 200 && r->table->rows[1].value == 8 && r->table->rows[2].value == 2);
    assert_near(r->table->rows[2].scale, 20.0, 1e-12);
    ft_dim_result_free(r);
    o.what = FT_AREA_BOUNDARY; /* the ring of 36 cells of each square */
    assert_int_equal(ft_urban_dim_area_grid(g, 5.0, &o, &r), FT_OK);
    assert_true(r->table->rows[0].value == 72 && r->table->rows[1].value == 8 && r->table->rows[2].value == 2);
    ft_dim_result_free(r);

    /* accuracy on the filled square, automatic range */
    o = (ft_area_dim_opts)FT_AREA_DIM_OPTS_DEFAULT;
    o.what = FT_AREA_AREA;
    assert_int_equal(ft_urban_dim_area_grid(g, 3.0, &o, &r), FT_OK);
    print_message("  raster square: area D = %.4f over %zu sizes (%g .. %g m)\n", r->D, r->table->n, r->range[0],
                  r->range[1]);
    assert_near(r->D, 2.0, 0.02);
    ft_dim_result_free(r);
    o.what = FT_AREA_BOUNDARY;
    assert_int_equal(ft_urban_dim_area_grid(g, 3.0, &o, &r), FT_OK);
    print_message("  raster square: boundary D = %.4f over %zu sizes (%g .. %g m)\n", r->D, r->table->n,
                  r->range[0], r->range[1]);
    assert_near(r->D, 1.0, 0.02);
    ft_dim_result_free(r);

    ft_urban_stats st;
    assert_int_equal(ft_urban_grid_stats(g, 5.0, &st), FT_OK);
    assert_int_equal(st.ncells, 200);
    assert_int_equal(st.npolygons, 2);
    assert_near(st.area, 800.0, 1e-9);
    assert_near(st.perimeter, 2 * 4 * 10 * 2.0, 1e-9);
    assert_int_equal(ft_urban_grid_stats(g, 0.0, &st), FT_OK);
    assert_int_equal(st.npolygons, 1); /* the background around everything, row 199 is nodata */
    assert_int_equal(st.ncells, 399 * 400 - 300 * 300 - 200);
    ft_grid_free(g);
}

/* ------------------------------------------------------------------------------------------------
 * Classes, subsets, statistics
 * --------------------------------------------------------------------------------------------- */

static void test_classes_and_subsets(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("landuse", NULL);
    assert_int_equal(ft_layer_add_field(l, "use", FT_FIELD_STRING, -1, 0, 0), 0);
    const char *uses[] = {"residential", "industrial", "residential", NULL, "water"};
    for (size_t i = 0; i < 5; i++) {
        add_square(l, (int64_t)(10 + i), 4.0 * (double)i, 0, 2.0);
        if (uses[i] != NULL)
            assert_int_equal(ft_layer_set_string(l, i, 0, uses[i]), FT_OK);
    }
    assert_true(ft_layer_add_feature(l, 99, FT_GEOM_LINE, 0) >= 0); /* a line: in no class */
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays((double[]){0, 0, 1, 1}, (double[]){0, 0, 1, 1}, 2, 2, 0),
                                       FT_ROLE_LINE, 0), FT_OK);
    ft_urban_classes *c = NULL;
    assert_int_equal(ft_urban_classes_by_field(l, "USE", &c), FT_OK);
    assert_int_equal(c->n, 3);
    assert_int_equal(c->nnull, 1);
    assert_string_equal(c->classes[0].label, "industrial");
    assert_string_equal(c->classes[1].label, "residential");
    assert_string_equal(c->classes[2].label, "water");
    assert_int_equal(c->classes[1].n, 2);
    assert_int_equal(c->classes[1].features[0], 0);
    assert_int_equal(c->classes[1].features[1], 2);

    const double cells[] = {0.5, 1, 2};
    ft_area_dim_opts o = FT_AREA_DIM_OPTS_DEFAULT;
    o.what = FT_AREA_AREA;
    o.cells = cells;
    o.ncells = 3;
    o.offsets = 1;
    o.fewest = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_urban_dim_area(l, c->classes[1].features, c->classes[1].n, &o, &r), FT_OK);
    assert_true(r->table->rows[0].value == 32 && r->table->rows[1].value == 8 && r->table->rows[2].value == 2);
    assert_near(r->D, 2.0, 1e-12);
    ft_dim_result_free(r);
    ft_urban_stats st;
    assert_int_equal(ft_urban_layer_stats(l, c->classes[1].features, c->classes[1].n, &st), FT_OK);
    assert_int_equal(st.nfeatures, 2);
    assert_int_equal(st.npolygons, 2);
    assert_near(st.area, 8.0, 1e-12);
    assert_near(st.perimeter, 16.0, 1e-12);
    assert_int_equal(ft_urban_layer_stats(l, NULL, 0, &st), FT_OK); /* the line is not counted */
    assert_int_equal(st.nfeatures, 5);
    assert_near(st.area, 20.0, 1e-12);
    /* the whole layer in box counting: the line feature is an error naming it */
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "feature 99 is a line");
    ft_urban_classes_free(c);
    ft_urban_classes_free(NULL);
    assert_error_names(ft_urban_classes_by_field(l, "zoning", &c), FT_E_INVALID, "no field 'zoning'");
    assert_error_names(ft_urban_classes_by_field(l, "zoning", &c), FT_E_INVALID, "fields: use");
    ft_layer_free(l);
}

static void test_names(void **state)
{
    (void)state;
    ft_area_what w;
    assert_int_equal(ft_area_what_parse("Area", &w), FT_OK);
    assert_int_equal(w, FT_AREA_AREA);
    assert_int_equal(ft_area_what_parse("boundary", &w), FT_OK);
    assert_int_equal(w, FT_AREA_BOUNDARY);
    assert_string_equal(ft_area_what_name(FT_AREA_AREA), "area");
    assert_error_names(ft_area_what_parse("perimeter", &w), FT_E_INVALID, "'perimeter'");
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_dim_result *r = NULL;
    ft_area_dim_opts o = FT_AREA_DIM_OPTS_DEFAULT;
    ft_layer *l = ft_layer_create("empty", NULL);
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_EMPTY, "no polygon");
    add_square(l, 7, 0, 0, 1);
    const size_t bad_index[] = {3};
    assert_error_names(ft_urban_dim_area(l, bad_index, 1, &o, &r), FT_E_INVALID, "feature index 3");
    o.offsets = 0;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "offsets must be in [1, 16], got 0");
    o.offsets = 4;
    o.nscales = 2;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "nscales must be in [3, 1000]");
    o.nscales = 0;
    o.min_cell = 2;
    o.max_cell = 1;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "min_cell (2) must be less than");
    o.min_cell = NAN;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "got nan");
    o.min_cell = 0;
    o.max_cell = 0;
    const double cells[] = {0.1, -1}, dup[] = {0.1, 0.2, 0.1}, tiny[] = {1e-9, 0.5};
    o.cells = cells;
    o.ncells = 2;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID,
                       "cell size 2 must be finite and > 0, got -1");
    o.cells = dup;
    o.ncells = 3;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "cell size 0.1 is given twice");
    o.what = FT_AREA_AREA;
    o.cells = tiny;
    o.ncells = 2;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_INVALID, "box side 1e-09 is too small");
    o = (ft_area_dim_opts)FT_AREA_DIM_OPTS_DEFAULT;
    l->parts[0].chain->y[2] = NAN;
    assert_error_names(ft_urban_dim_area(l, NULL, 0, &o, &r), FT_E_NUMERIC, "feature 7, part 0");
    assert_error_names(ft_urban_layer_stats(l, NULL, 0, &(ft_urban_stats){0}), FT_E_NUMERIC, "vertex 2");
    ft_layer_free(l);
    assert_null(r);

    ft_grid *g = class_grid();
    assert_error_names(ft_urban_dim_area_grid(g, 4.0, &o, &r), FT_E_EMPTY, "no valid cell has the class value 4");
    assert_error_names(ft_urban_dim_area_grid(g, NAN, &o, &r), FT_E_INVALID, "class value must be finite, got nan");
    const double sub[] = {0.5, 4};
    o.cells = sub;
    o.ncells = 2;
    assert_error_names(ft_urban_dim_area_grid(g, 3.0, &o, &r), FT_E_INVALID, "cell size 0.5 is less than half");
    o = (ft_area_dim_opts)FT_AREA_DIM_OPTS_DEFAULT;
    g->gt[1] = 0.0;
    assert_error_names(ft_urban_dim_area_grid(g, 3.0, &o, &r), FT_E_INVALID, "no area");
    ft_grid_free(g);
    assert_error_names(ft_urban_dim_area_grid(NULL, 3.0, &o, &r), FT_E_EMPTY, "empty grid");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_square_counts),
        cmocka_unit_test(test_filled_square),
        cmocka_unit_test(test_koch_island),
        cmocka_unit_test(test_grid_classes),
        cmocka_unit_test(test_classes_and_subsets),
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
