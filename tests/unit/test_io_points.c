/* fracterra — tests of scattered point reading and writing (CSV, XYZ, OGR point layers).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "fracterra/io.h"
#include "ft_test_util.h"

#define DAVIS FT_TEST_DATA "/points_mass_topo_davis1973.csv"
#define STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"

static ft_points *read_ok(const char *path, const ft_read_points_opts *o)
{
    ft_points *p = NULL;
    if (ft_io_read_points(path, o, &p) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
    return p;
}

static void assert_points_equal(const ft_points *a, const ft_points *b)
{
    assert_int_equal(a->n, b->n);
    assert_int_equal(a->w != NULL, b->w != NULL);
    for (size_t i = 0; i < a->n; i++) {
        assert_true(a->x[i] == b->x[i]);
        assert_true(a->y[i] == b->y[i]);
        assert_true(a->z[i] == b->z[i]);
        if (a->w)
            assert_true(a->w[i] == b->w[i]);
    }
}

/* ---- CSV --------------------------------------------------------------------------------------- */

static void test_read_davis(void **state)
{
    (void)state;
    ft_points *p = read_ok(DAVIS, NULL);
    assert_int_equal(p->n, 52);
    assert_null(p->w);
    assert_true(p->x[0] == 0.3 && p->y[0] == 6.1 && p->z[0] == 870);
    assert_true(p->x[51] == 3.6 && p->y[51] == 6 && p->z[51] == 705);
    ft_points_free(p);
}

static void test_csv_variants(void **state)
{
    (void)state;
    const char *path = ft_test_tmp_text("semi.csv", "\xEF\xBB\xBF\"Easting\";\"North ing\";ELEV;conf\n"
                                                    "1,5;2;3,25;0,5\n"
                                                    "\n"
                                                    "\"10\";20;30;2\r\n");
    ft_read_points_opts o = FT_READ_POINTS_OPTS_DEFAULT;
    o.x = "easting";
    o.y = "north ing";
    o.z = "elev";
    o.weight = "CONF";
    ft_points *p = read_ok(path, &o);
    assert_int_equal(p->n, 2);
    assert_true(p->x[0] == 1.5 && p->y[0] == 2 && p->z[0] == 3.25 && p->w[0] == 0.5);
    assert_true(p->x[1] == 10 && p->z[1] == 30 && p->w[1] == 2);
    ft_points_free(p);

    path = ft_test_tmp_text("order.csv", "id,Z,name,Y,X\n1,100,\"a, b\",2,3\n");
    p = read_ok(path, NULL);
    assert_int_equal(p->n, 1);
    assert_true(p->x[0] == 3 && p->y[0] == 2 && p->z[0] == 100);
    ft_points_free(p);
}

static void test_csv_errors(void **state)
{
    (void)state;
    ft_points *p = NULL;
    const char *path = ft_test_tmp_text("bad.csv", "x,y,z\n1,2,3\n4,5,6\n7,8,high\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_null(p);
    char want[300];
    snprintf(want, sizeof want, "%s:4:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "column 'z' (3)"));
    assert_non_null(strstr(ft_last_error(), "'high'"));

    ft_test_put_text(path, "x,y,z\n1,inf,3\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_NUMERIC);
    snprintf(want, sizeof want, "%s:2:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "column 'y'"));

    ft_test_put_text(path, "x,y,z\n1,2\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "column 'z'"));

    ft_test_put_text(path, "x,y,elevation\n1,2,3\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "no column 'z'"));
    assert_non_null(strstr(ft_last_error(), "x, y, elevation"));
    assert_non_null(strstr(ft_last_error(), path));

    ft_test_put_text(path, "x,y,z\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_EMPTY);
    ft_test_put_text(path, "");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_EMPTY);
    assert_int_equal(ft_io_read_points(ft_test_tmp("missing.csv"), NULL, &p), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "cannot open"));
}

/* ---- XYZ --------------------------------------------------------------------------------------- */

static void test_xyz(void **state)
{
    (void)state;
    const char *path = ft_test_tmp_text("p.xyz", "x y z w\n# comment\n\n1 2 3 0.5\n  4\t5 6 2 extra\n");
    ft_points *p = read_ok(path, NULL);
    assert_int_equal(p->n, 2);
    assert_null(p->w);
    assert_true(p->x[1] == 4 && p->y[1] == 5 && p->z[1] == 6);
    ft_points_free(p);
    ft_read_points_opts o = FT_READ_POINTS_OPTS_DEFAULT;
    o.weight = "w";
    p = read_ok(path, &o);
    assert_non_null(p->w);
    assert_true(p->w[0] == 0.5 && p->w[1] == 2);
    ft_points_free(p);

    ft_test_put_text(path, "1 2 3\n4 5 x6\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    char want[300];
    snprintf(want, sizeof want, "%s:2:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "'x6'"));
    ft_test_put_text(path, "1 2\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    ft_test_put_text(path, "# only comments\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_EMPTY);
}

/* ---- OGR point layers -------------------------------------------------------------------------- */

static void test_ogr_points(void **state)
{
    (void)state;
    const char *path = ft_test_tmp("p.geojson");
    ft_test_put_text(path, "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":"
                           "{\"name\":\"urn:ogc:def:crs:EPSG::32633\"}},\"features\":["
                           "{\"type\":\"Feature\",\"properties\":{\"elev\":7.5,\"s\":2},"
                           "\"geometry\":{\"type\":\"Point\",\"coordinates\":[1,2,3]}},"
                           "{\"type\":\"Feature\",\"properties\":{\"elev\":8.5,\"s\":4},"
                           "\"geometry\":{\"type\":\"MultiPoint\",\"coordinates\":[[4,5,6],[7,8,9]]}}]}\n");
    ft_points *p = read_ok(path, NULL);
    assert_int_equal(p->n, 3);
    assert_true(p->x[2] == 7 && p->y[2] == 8 && p->z[2] == 9);
    assert_non_null(p->crs_wkt);
    ft_points_free(p);
    ft_read_points_opts o = FT_READ_POINTS_OPTS_DEFAULT;
    o.zfield = "elev";
    o.weight = "s";
    p = read_ok(path, &o);
    assert_true(p->z[0] == 7.5 && p->z[2] == 8.5 && p->w[1] == 4);
    ft_points_free(p);
    o.zfield = "height";
    assert_int_equal(ft_io_read_points(path, &o, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "'height'"));

    path = ft_test_tmp("p2.geojson");
    ft_test_put_text(path, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                           "\"geometry\":{\"type\":\"Point\",\"coordinates\":[1,2]}}]}\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "no Z"));

    assert_int_equal(ft_io_read_points(STATES, NULL, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "not points"));
    assert_int_equal(ft_io_read_points(FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", NULL, &p), FT_E_FORMAT);
}

/* ---- writing ----------------------------------------------------------------------------------- */

static void test_write_round_trips(void **state)
{
    (void)state;
    ft_points *a = read_ok(DAVIS, NULL);
    ft_points_push(a, 1.0 / 3.0, 1e-310, -0.1);
    const char *names[] = {"o.csv", "o.xyz", "o.geojson", "o.gpkg"};
    for (int k = 0; k < 4; k++) {
        const char *path = ft_test_tmp(names[k]);
        if (ft_io_write_points(path, a) != FT_OK)
            fail_msg("%s: %s", path, ft_last_error());
        ft_points *b = read_ok(path, NULL);
        assert_points_equal(a, b);
        ft_points_free(b);
    }
    /* with weights and a CRS */
    ft_points_ensure_weights(a);
    a->w[3] = 0.25;
    ft_points_set_crs(a, "EPSG:26986");
    ft_read_points_opts o = FT_READ_POINTS_OPTS_DEFAULT;
    o.weight = "w";
    const char *wnames[] = {"w.csv", "w.xyz", "w.gpkg"};
    for (int k = 0; k < 3; k++) {
        const char *path = ft_test_tmp(wnames[k]);
        assert_int_equal(ft_io_write_points(path, a), FT_OK);
        ft_points *b = read_ok(path, &o);
        assert_points_equal(a, b);
        if (k == 2)
            ft_test_assert_crs_epsg(b->crs_wkt, 26986);
        ft_points_free(b);
    }
    int before = ft_test_dir_count();
    assert_int_equal(ft_io_write_points("/tmp/ft-no-such-folder-xyz/p.csv", a), FT_E_IO);
    assert_int_equal(ft_io_write_points(ft_test_tmp("p.unknownext"), a), FT_E_FORMAT);
    assert_int_equal(ft_test_dir_count(), before);
    ft_points_free(a);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_davis),
        cmocka_unit_test(test_csv_variants),
        cmocka_unit_test(test_csv_errors),
        cmocka_unit_test(test_xyz),
        cmocka_unit_test(test_ogr_points),
        cmocka_unit_test(test_write_round_trips),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
