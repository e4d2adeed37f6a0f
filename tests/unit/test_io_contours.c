/* fracterra — tests of ft_io_contour_polygons (GDAL contour polygons, as gdal_contour -p -amin elev).
 *
 * A cone z = PEAK - rho sampled at cell centres: the band with lower level e is the annulus between the
 * circles rho = PEAK - e (outer ring) and rho = PEAK - e - interval (hole), so its rings' vertices lie at
 * those radii and its area is pi (r_out^2 - r_in^2) (marching squares interpolates linearly along cell
 * edges; on a circle of radius r the error is below h^2 / (8 r) for cells of side h), less the chords.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/io.h"
#include "ft_test_assert.h"
#include "ft_test_util.h"

#define SIDE 201   /* cells; centre of the cone at the centre of cell (100, 100) */
#define PEAK 95.0  /* the cone's height: no level passes exactly through the apex */
#define INTERVAL 10.0
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"

/* Cell (c, r) has its centre at (c + 0.5, SIDE - r - 0.5); the apex at (100.5, 100.5). */
static ft_grid *cone(void)
{
    ft_grid *g = ft_grid_create(SIDE, SIDE);
    assert_non_null(g);
    double gt[6] = {0.0, 1.0, 0.0, SIDE, 0.0, -1.0};
    memcpy(g->gt, gt, sizeof gt);
    for (size_t r = 0; r < SIDE; r++)
        for (size_t c = 0; c < SIDE; c++) {
            double x = c + 0.5 - 100.5, y = (SIDE - r - 0.5) - 100.5;
            g->z[r * SIDE + c] = (float)(PEAK - hypot(x, y));
        }
    return g;
}

static double ring_area(const ft_chain *c)
{
    return fabs(ft_chain_signed_area(c));
}

/* Largest distance of a ring's vertices from the radius r around the apex. */
static double radius_error(const ft_chain *c, double r)
{
    double e = 0.0;
    for (size_t i = 0; i < c->n; i++)
        e = fmax(e, fabs(hypot(c->x[i] - 100.5, c->y[i] - 100.5) - r));
    return e;
}

static ft_layer *contours_ok(const ft_grid *g, double interval, double base)
{
    ft_layer *l = NULL;
    if (ft_io_contour_polygons(g, interval, base, &l) != FT_OK)
        fail_msg("ft_io_contour_polygons: %s", ft_last_error());
    assert_non_null(l);
    return l;
}

static double elev_of(const ft_layer *l, size_t f)
{
    int k = ft_layer_field_index(l, "elev");
    assert_true(k >= 0);
    assert_int_equal(l->fields[k].type, FT_FIELD_REAL);
    assert_false(l->features[f].values[k].is_null);
    return l->features[f].values[k].r;
}

static void test_cone_annuli(void **state)
{
    (void)state;
    ft_grid *g = cone();
    assert_int_equal(ft_grid_set_crs(g, NULL), FT_OK);
    ft_layer *l = contours_ok(g, INTERVAL, 0.0);
    assert_int_equal(l->nfields, 1);
    /* z spans PEAK - 100 sqrt 2 = -46.4 .. 94.3: bands -50, -40, ..., 90, one feature each */
    assert_int_equal(l->nfeatures, 15);
    int seen[15] = {0};
    size_t checked = 0;
    for (size_t f = 0; f < l->nfeatures; f++) {
        double e = elev_of(l, f);
        double k = (e + 50.0) / INTERVAL;
        assert_true(k >= 0.0 && k <= 14.0 && k == floor(k));
        seen[(int)k]++;
        assert_int_equal(l->features[f].type, FT_GEOM_POLYGON);
        if (e < 10.0)
            continue; /* clipped by the grid's border */
        const ft_feature *ft = &l->features[f];
        double r_out = PEAK - e, r_in = PEAK - e - INTERVAL, area = 0.0;
        size_t outers = 0, holes = 0;
        for (size_t p = ft->first; p < ft->first + ft->count; p++) {
            const ft_part *part = &l->parts[p];
            if (part->role == FT_ROLE_OUTER) {
                outers++;
                area += ring_area(part->chain);
                assert_true(radius_error(part->chain, r_out) < 0.1);
            } else {
                holes++;
                area -= ring_area(part->chain);
                assert_true(radius_error(part->chain, r_in) < 0.1);
            }
        }
        assert_int_equal(outers, 1);
        assert_int_equal(holes, e < 90.0 ? 1 : 0);
        /* Each chord of length s <= sqrt 2 (within a cell) cuts s^3 / (12 r) off its circle: at most
         * pi / 3 per ring whatever its radius; the outer ring loses it, the hole gives it back. */
        double expect = M_PI * (r_out * r_out - (r_in > 0.0 ? r_in * r_in : 0.0));
        assert_true(area <= expect + M_PI / 3.0 && area >= expect - M_PI / 3.0);
        assert_near(area / expect, 1.0, 0.01);
        checked++;
    }
    for (int k = 0; k < 15; k++)
        assert_int_equal(seen[k], 1);
    assert_int_equal(checked, 9);
    ft_layer_free(l);
    ft_grid_free(g);
}

/* A base off the multiples of the interval shifts every level. */
static void test_base_shifts_levels(void **state)
{
    (void)state;
    ft_grid *g = cone();
    ft_layer *l = contours_ok(g, 20.0, 5.0);
    for (size_t f = 0; f < l->nfeatures; f++) {
        double e = elev_of(l, f);
        assert_near(fmod(e - 5.0 + 1000.0, 20.0), 0.0, 1e-9);
        if (e < 10.0)
            continue;
        for (size_t p = l->features[f].first; p < l->features[f].first + l->features[f].count; p++)
            if (l->parts[p].role == FT_ROLE_OUTER)
                assert_true(radius_error(l->parts[p].chain, PEAK - e) < 0.1);
    }
    ft_layer_free(l);
    ft_grid_free(g);
}

/* Masked cells (the western half, x < 100) and a NaN cell are left out; the CRS is the grid's. */
static void test_nodata_and_crs(void **state)
{
    (void)state;
    ft_grid *g = cone();
    char *wkt = NULL;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:32632", &wkt), FT_OK);
    assert_int_equal(ft_grid_set_crs(g, wkt), FT_OK);
    free(wkt);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    for (size_t r = 0; r < SIDE; r++)
        for (size_t c = 0; c < 100; c++)
            g->mask[r * SIDE + c] = 0;
    g->z[150 * SIDE + 150] = NAN;
    ft_layer *l = contours_ok(g, INTERVAL, 0.0);
    ft_test_assert_crs_epsg(l->crs_wkt, 32632);
    double xmin, ymin, xmax, ymax;
    assert_int_equal(ft_layer_bbox(l, &xmin, &ymin, &xmax, &ymax), FT_OK);
    assert_true(xmin >= 100.0 - 1e-9); /* no vertex west of the first valid cell's centre */
    /* the NaN cell is a hole: some ring passes within one cell of its centre (150.5, 50.5) */
    int near_nan = 0;
    for (size_t p = 0; p < l->nparts; p++)
        for (size_t i = 0; i < l->parts[p].chain->n; i++)
            near_nan |= hypot(l->parts[p].chain->x[i] - 150.5, l->parts[p].chain->y[i] - 50.5) <= 1.0;
    assert_true(near_nan);
    ft_layer_free(l);
    ft_grid_free(g);
}

/* A real DEM with nodata outside the country: levels are multiples of 100 spanning its range. */
static void test_luxembourg(void **state)
{
    (void)state;
    ft_grid *g = NULL;
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_read_grid(LUXEMBOURG, &ro, &g), FT_OK);
    double zmin, zmax;
    assert_int_equal(ft_grid_minmax(g, &zmin, &zmax), FT_OK);
    ft_layer *l = contours_ok(g, 100.0, 0.0);
    ft_test_assert_crs_epsg(l->crs_wkt, 4326);
    double lo = INFINITY, hi = -INFINITY;
    for (size_t f = 0; f < l->nfeatures; f++) {
        lo = fmin(lo, elev_of(l, f));
        hi = fmax(hi, elev_of(l, f));
    }
    assert_near(lo, 100.0 * floor(zmin / 100.0), 1e-9);
    assert_near(hi, 100.0 * floor(zmax / 100.0), 1e-9);
    assert_int_equal(l->nfeatures, (size_t)llround((hi - lo) / 100.0) + 1);
    ft_layer_free(l);
    ft_grid_free(g);
}

static void test_bad_input(void **state)
{
    (void)state;
    ft_grid *g = cone();
    ft_layer *l = (ft_layer *)&l;
    assert_error_names(ft_io_contour_polygons(g, 0.0, 0.0, &l), FT_E_INVALID, "interval");
    assert_null(l);
    assert_error_names(ft_io_contour_polygons(g, -5.0, 0.0, &l), FT_E_INVALID, "-5");
    assert_error_names(ft_io_contour_polygons(g, NAN, 0.0, &l), FT_E_INVALID, "interval");
    assert_error_names(ft_io_contour_polygons(g, 10.0, INFINITY, &l), FT_E_INVALID, "base");
    assert_error_names(ft_io_contour_polygons(NULL, 10.0, 0.0, &l), FT_E_INVALID, "grid");
    assert_error_names(ft_io_contour_polygons(g, 1e-6, 0.0, &l), FT_E_INVALID, "bands");
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    memset(g->mask, 0, SIDE * SIDE);
    assert_error_names(ft_io_contour_polygons(g, 10.0, 0.0, &l), FT_E_EMPTY, "no valid cell");
    ft_grid_free(g);
    ft_grid *tiny = ft_grid_create(1, 1);
    assert_error_names(ft_io_contour_polygons(tiny, 10.0, 0.0, &l), FT_E_INVALID, "1 x 1");
    ft_grid_free(tiny);
    assert_null(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cone_annuli),       cmocka_unit_test(test_base_shifts_levels),
        cmocka_unit_test(test_nodata_and_crs),    cmocka_unit_test(test_luxembourg),
        cmocka_unit_test(test_bad_input),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
