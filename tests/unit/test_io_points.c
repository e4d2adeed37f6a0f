/* fracterra — tests of scattered point reading and writing (CSV, XYZ, OGR point layers).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <dirent.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>
#include <ogr_srs_api.h>

#include "fracterra/io.h"

#define DAVIS FT_TEST_DATA "/points_mass_topo_davis1973.csv"
#define STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"

static char g_dir[64];

static const char *tmp_file(const char *name)
{
    static char buf[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", g_dir, name);
    return buf[k];
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static int count_files(const char *dir)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            n++;
    closedir(d);
    return n;
}

static void empty_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return;
    struct dirent *e;
    char path[512];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        remove(path);
    }
    closedir(d);
}

static int setup(void **state)
{
    (void)state;
    strcpy(g_dir, "/tmp/ft-io-points-XXXXXX");
    return mkdtemp(g_dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    empty_dir(g_dir);
    return rmdir(g_dir);
}

static int after_each(void **state)
{
    (void)state;
    empty_dir(g_dir);
    return 0;
}

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
    const char *path = tmp_file("semi.csv");
    write_text(path, "\xEF\xBB\xBF\"Easting\";\"North ing\";ELEV;conf\n"
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

    path = tmp_file("order.csv");
    write_text(path, "id,Z,name,Y,X\n1,100,\"a, b\",2,3\n");
    p = read_ok(path, NULL);
    assert_int_equal(p->n, 1);
    assert_true(p->x[0] == 3 && p->y[0] == 2 && p->z[0] == 100);
    ft_points_free(p);
}

static void test_csv_errors(void **state)
{
    (void)state;
    ft_points *p = NULL;
    const char *path = tmp_file("bad.csv");
    write_text(path, "x,y,z\n1,2,3\n4,5,6\n7,8,high\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_null(p);
    char want[300];
    snprintf(want, sizeof want, "%s:4:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "column 'z' (3)"));
    assert_non_null(strstr(ft_last_error(), "'high'"));

    write_text(path, "x,y,z\n1,inf,3\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_NUMERIC);
    snprintf(want, sizeof want, "%s:2:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "column 'y'"));

    write_text(path, "x,y,z\n1,2\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "column 'z'"));

    write_text(path, "x,y,elevation\n1,2,3\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "no column 'z'"));
    assert_non_null(strstr(ft_last_error(), "x, y, elevation"));
    assert_non_null(strstr(ft_last_error(), path));

    write_text(path, "x,y,z\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_EMPTY);
    write_text(path, "");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_EMPTY);
    assert_int_equal(ft_io_read_points(tmp_file("missing.csv"), NULL, &p), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "cannot open"));
}

/* ---- XYZ --------------------------------------------------------------------------------------- */

static void test_xyz(void **state)
{
    (void)state;
    const char *path = tmp_file("p.xyz");
    write_text(path, "x y z w\n# comment\n\n1 2 3 0.5\n  4\t5 6 2 extra\n");
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

    write_text(path, "1 2 3\n4 5 x6\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    char want[300];
    snprintf(want, sizeof want, "%s:2:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "'x6'"));
    write_text(path, "1 2\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_FORMAT);
    write_text(path, "# only comments\n");
    assert_int_equal(ft_io_read_points(path, NULL, &p), FT_E_EMPTY);
}

/* ---- OGR point layers -------------------------------------------------------------------------- */

static void test_ogr_points(void **state)
{
    (void)state;
    const char *path = tmp_file("p.geojson");
    write_text(path, "{\"type\":\"FeatureCollection\",\"crs\":{\"type\":\"name\",\"properties\":"
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

    path = tmp_file("p2.geojson");
    write_text(path, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
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
        const char *path = tmp_file(names[k]);
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
        const char *path = tmp_file(wnames[k]);
        assert_int_equal(ft_io_write_points(path, a), FT_OK);
        ft_points *b = read_ok(path, &o);
        assert_points_equal(a, b);
        if (k == 2) {
            OGRSpatialReferenceH s = OSRNewSpatialReference(b->crs_wkt), t = OSRNewSpatialReference(NULL);
            OSRImportFromEPSG(t, 26986);
            assert_true(OSRIsSame(s, t));
            OSRDestroySpatialReference(s);
            OSRDestroySpatialReference(t);
        }
        ft_points_free(b);
    }
    int before = count_files(g_dir);
    assert_int_equal(ft_io_write_points("/tmp/ft-no-such-folder-xyz/p.csv", a), FT_E_IO);
    assert_int_equal(ft_io_write_points(tmp_file("p.unknownext"), a), FT_E_FORMAT);
    assert_int_equal(count_files(g_dir), before);
    ft_points_free(a);
}

int main(void)
{
    ft_io_init();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_read_davis, after_each),
        cmocka_unit_test_teardown(test_csv_variants, after_each),
        cmocka_unit_test_teardown(test_csv_errors, after_each),
        cmocka_unit_test_teardown(test_xyz, after_each),
        cmocka_unit_test_teardown(test_ogr_points, after_each),
        cmocka_unit_test_teardown(test_write_round_trips, after_each),
    };
    int failed = cmocka_run_group_tests(tests, setup, teardown);
    ft_io_cleanup();
    return failed;
}
