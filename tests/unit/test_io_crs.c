/* fracterra — tests of the CRS service (io/crs.c, io/grid_reproject.c) and the ellipsoid (core/ellipsoid.c).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/io.h"

/* WKT2 of EPSG:4326 bound to WGS 84 (as GDAL writes a CRS with a TOWGS84 clause). */
static const char *const bound_4326 =
    "BOUNDCRS[SOURCECRS[GEOGCRS[\"WGS 84\",DATUM[\"World Geodetic System 1984\",ELLIPSOID[\"WGS 84\",6378137,"
    "298.257223563,LENGTHUNIT[\"metre\",1]]],PRIMEM[\"Greenwich\",0,ANGLEUNIT[\"degree\",0.0174532925199433]],"
    "CS[ellipsoidal,2],AXIS[\"latitude\",north,ORDER[1],ANGLEUNIT[\"degree\",0.0174532925199433]],"
    "AXIS[\"longitude\",east,ORDER[2],ANGLEUNIT[\"degree\",0.0174532925199433]],ID[\"EPSG\",4326]]],"
    "TARGETCRS[GEOGCRS[\"WGS 84\",DATUM[\"World Geodetic System 1984\",ELLIPSOID[\"WGS 84\",6378137,"
    "298.257223563,LENGTHUNIT[\"metre\",1]]],PRIMEM[\"Greenwich\",0,ANGLEUNIT[\"degree\",0.0174532925199433]],"
    "CS[ellipsoidal,2],AXIS[\"latitude\",north,ORDER[1],ANGLEUNIT[\"degree\",0.0174532925199433]],"
    "AXIS[\"longitude\",east,ORDER[2],ANGLEUNIT[\"degree\",0.0174532925199433]],ID[\"EPSG\",4326]]],"
    "ABRIDGEDTRANSFORMATION[\"Transformation from WGS 84 to WGS84\",METHOD[\"Position Vector transformation "
    "(geog2D domain)\",ID[\"EPSG\",9606]],PARAMETER[\"X-axis translation\",0,ID[\"EPSG\",8605]],"
    "PARAMETER[\"Y-axis translation\",0,ID[\"EPSG\",8606]],PARAMETER[\"Z-axis translation\",0,ID[\"EPSG\",8607]],"
    "PARAMETER[\"X-axis rotation\",0,ID[\"EPSG\",8608]],PARAMETER[\"Y-axis rotation\",0,ID[\"EPSG\",8609]],"
    "PARAMETER[\"Z-axis rotation\",0,ID[\"EPSG\",8610]],PARAMETER[\"Scale difference\",1,ID[\"EPSG\",8611]]]]";

static void test_geographic(void **state)
{
    (void)state;
    const char *geo[] = {"EPSG:4326", "EPSG:4269", "EPSG:4326+5773", bound_4326};
    for (size_t i = 0; i < sizeof geo / sizeof geo[0]; i++) {
        ft_crs_info c;
        assert_int_equal(ft_io_crs_info(geo[i], &c), FT_OK);
        assert_true(c.has_crs);
        assert_true(c.geographic);
        assert_string_equal(c.unit, "degree");
        assert_string_equal(c.scale_unit, "m");
        assert_float_equal(c.ellipsoid.a, 6378137.0, 1e-6);
        assert_float_equal(1.0 / c.ellipsoid.f, i == 1 ? 298.257222101 : 298.257223563, 1e-6);
    }
}

static void test_projected_units(void **state)
{
    (void)state;
    static const struct {
        const char *crs, *scale_unit;
        double metres;
    } cases[] = {{"EPSG:32621", "m", 1.0}, {"EPSG:2263", "US ft", 1200.0 / 3937.0},
                 {"EPSG:2927", "US ft", 1200.0 / 3937.0}, {"EPSG:3857", "m", 1.0},
                 {"EPSG:32632+5773", "m", 1.0}, {"EPSG:27700", "m", 1.0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        ft_crs_info c;
        assert_int_equal(ft_io_crs_info(cases[i].crs, &c), FT_OK);
        assert_true(c.has_crs);
        assert_false(c.geographic);
        assert_string_equal(c.scale_unit, cases[i].scale_unit);
        assert_float_equal(c.metres_per_unit, cases[i].metres, 1e-12);
        assert_true(c.ellipsoid.a > 6.3e6);
    }
    ft_crs_info c;
    assert_int_equal(ft_io_crs_info("+proj=tmerc +lon_0=0 +ellps=GRS80 +units=ft", &c), FT_OK);
    assert_string_equal(c.scale_unit, "ft");
}

static void test_no_crs_and_bad(void **state)
{
    (void)state;
    ft_crs_info c;
    assert_int_equal(ft_io_crs_info(NULL, &c), FT_OK);
    assert_false(c.has_crs);
    assert_false(c.geographic);
    assert_string_equal(c.scale_unit, "");
    assert_int_equal(ft_io_crs_info("", &c), FT_OK);
    assert_false(c.has_crs);
    assert_int_equal(ft_io_crs_info("EPSG:999999", &c), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "EPSG:999999"));
}

/* Metres per degree against the textbook values for WGS 84 (e.g. 111 319.49 m of longitude at the
 * equator, 110 574.3 m of latitude there and 111 694.0 at the pole; 55 800 m of longitude and 111 412 m of
 * latitude at 60 degrees). */
static void test_ellipsoid(void **state)
{
    (void)state;
    const ft_ellipsoid w = FT_ELLIPSOID_WGS84;
    double plon, plat;
    ft_ellipsoid_metres_per_degree(&w, 0.0, &plon, &plat);
    assert_float_equal(plon, 111319.49, 0.01);
    assert_float_equal(plat, 110574.27, 0.01);
    ft_ellipsoid_metres_per_degree(&w, 90.0, NULL, &plat);
    assert_float_equal(plat, 111693.97, 0.05);
    ft_ellipsoid_metres_per_degree(&w, 60.0, &plon, &plat);
    assert_float_equal(plon, 55800.0, 0.5);
    assert_float_equal(plat, 111412.0, 0.5);
    double x, y, z;
    ft_ellipsoid_to_ecef(&w, 0.0, 90.0, &x, &y, &z);
    assert_float_equal(z, 6356752.314245, 1e-5); /* the semi-minor axis */
    ft_ellipsoid_to_ecef(&w, 90.0, 0.0, &x, &y, &z);
    assert_float_equal(y, 6378137.0, 1e-6);
}

/* A layer in lon/lat through a local LAEA and back returns where it started; the LAEA centre maps to 0, 0. */
static void test_layer_round_trip(void **state)
{
    (void)state;
    char *geo = NULL, *laea = NULL;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:4326", &geo), FT_OK);
    assert_int_equal(ft_io_local_crs(geo, FT_LOCAL_LAEA, -55.5, 48.5, &laea), FT_OK);
    assert_non_null(strstr(laea, "Lambert azimuthal equal-area centred on 48.5000N 55.5000W"));
    ft_layer *l = ft_layer_create("t", geo);
    ft_layer_add_feature(l, 1, FT_GEOM_LINE, 0);
    ft_chain *c = ft_chain_create(3, 0);
    ft_chain_push(c, -55.5, 48.5);
    ft_chain_push(c, -55.0, 48.5);
    ft_chain_push(c, -55.0, 49.0);
    ft_layer_add_part(l, c, FT_ROLE_LINE, 0);
    assert_int_equal(ft_io_layer_reproject(l, laea), FT_OK);
    assert_float_equal(c->x[0], 0.0, 1e-6);
    assert_float_equal(c->y[0], 0.0, 1e-6);
    assert_float_equal(c->x[1], 36960.0, 100.0); /* ~ 0.5 deg x 73 916 m at 48.5 N */
    assert_int_equal(ft_io_layer_reproject(l, geo), FT_OK);
    assert_float_equal(c->x[2], -55.0, 1e-9);
    assert_float_equal(c->y[2], 49.0, 1e-9);
    ft_layer_free(l);
    free(laea);
    free(geo);
}

/* A 3-arc-second-like grid at 50 N warped to a local transverse Mercator: square cells of the requested
 * size, a plane stays a plane (z = longitude's ground distance). */
static void test_grid_reproject(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(40, 30);
    double d = 1.0 / 1200.0;
    g->gt[0] = 6.0;
    g->gt[1] = d;
    g->gt[3] = 50.0;
    g->gt[5] = -d;
    char *geo = NULL, *tm = NULL;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:4326", &geo), FT_OK);
    ft_grid_set_crs(g, geo);
    for (size_t r = 0; r < g->ny; r++)
        for (size_t k = 0; k < g->nx; k++)
            g->z[r * g->nx + k] = (float)(k * 10.0);
    assert_int_equal(ft_io_local_crs(geo, FT_LOCAL_TMERC, 6.0 + 20 * d, 50.0 - 15 * d, &tm), FT_OK);
    ft_grid *p = NULL;
    assert_int_equal(ft_io_grid_reproject(g, tm, 50.0, &p), FT_OK);
    assert_float_equal(p->gt[1], 50.0, 0.0);
    assert_float_equal(p->gt[5], -50.0, 0.0);
    /* ground width: 40 cells of 3" at 50 N ~ 40 x 59.7 m = 2388 m -> about 48 cells of 50 m */
    assert_true(p->nx >= 47 && p->nx <= 50);
    assert_true(p->ny >= 55 && p->ny <= 58); /* 30 x 92.7 m */
    ft_grid_free(p);
    assert_int_equal(ft_io_grid_reproject(g, tm, -1.0, &p), FT_E_INVALID);
    free(g->crs_wkt);
    g->crs_wkt = NULL;
    assert_int_equal(ft_io_grid_reproject(g, tm, 50.0, &p), FT_E_INVALID);
    ft_grid_free(g);
    free(geo);
    free(tm);
}

/* Grid azimuth of true north: minus the meridian convergence atan(tan(lon - lon0) sin(lat)) (spherical
 * approximation, within 0.01 deg at these latitudes); points from gdaltransform. 0 for lon/lat and no CRS. */
static void test_grid_north(void **state)
{
    (void)state;
    static const struct {
        const char *crs;
        double x, y, lon, lat, lon0;
    } cases[] = {{"EPSG:32632", 294088.34657009, 5522182.08825041, 6.1375, 49.8167, 9.0},
                 {"EPSG:32605", 657091.710172919, 6877812.60098824, -150.0, 62.0, -153.0}};
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char *wkt = NULL;
        double az = NAN, d2r = M_PI / 180.0;
        assert_int_equal(ft_io_crs_to_wkt(cases[i].crs, &wkt), FT_OK);
        assert_int_equal(ft_io_crs_grid_north(wkt, cases[i].x, cases[i].y, &az), FT_OK);
        double expect = -atan(tan((cases[i].lon - cases[i].lon0) * d2r) * sin(cases[i].lat * d2r)) / d2r;
        print_message("  %s: grid north %.4f deg, expected %.4f\n", cases[i].crs, az, expect);
        assert_true(fabs(az - expect) < 0.01);
        free(wkt);
    }
    char *geo = NULL;
    double az = 1.0;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:4326", &geo), FT_OK);
    assert_int_equal(ft_io_crs_grid_north(geo, 6.0, 49.0, &az), FT_OK);
    assert_true(az == 0.0);
    az = 1.0;
    assert_int_equal(ft_io_crs_grid_north(NULL, 6.0, 49.0, &az), FT_OK);
    assert_true(az == 0.0);
    free(geo);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_geographic),        cmocka_unit_test(test_projected_units),
        cmocka_unit_test(test_no_crs_and_bad),    cmocka_unit_test(test_ellipsoid),
        cmocka_unit_test(test_layer_round_trip),  cmocka_unit_test(test_grid_reproject),
        cmocka_unit_test(test_grid_north),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
