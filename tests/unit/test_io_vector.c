/* fracterra — tests of io vector reading and writing (GeoJSON, Shapefile, GeoPackage, OGR CSV/WKT).
 * Facts checked against tests/data/README.md and the files' own attributes (n_parts, n_vertices).
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
#include <strings.h>
#include <unistd.h>

#include <cmocka.h>

#include "fracterra/io.h"
#include "ft_test_util.h"

#define STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"
#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"
#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"

/* ---- helpers ----------------------------------------------------------------------------------- */

/* Same ring up to start vertex and direction. */
static int ring_same(const ft_chain *a, const ft_chain *b)
{
    if (a->n != b->n || a->closed != b->closed)
        return 0;
    size_t n = a->n;
    if (n == 0)
        return 1;
    for (size_t s = 0; s < n; s++) {
        if (b->x[s] != a->x[0] || b->y[s] != a->y[0])
            continue;
        for (int dir = -1; dir <= 1; dir += 2) {
            size_t i = 0;
            while (i < n) {
                size_t j = dir > 0 ? (s + i) % n : (s + n - i) % n;
                if (a->x[i] != b->x[j] || a->y[i] != b->y[j])
                    break;
                i++;
            }
            if (i == n)
                return 1;
        }
    }
    return 0;
}

enum { EXACT = 0, RINGS_UP_TO_ORIENTATION = 1, SHAPEFILE = 3 };

static void assert_values_equal(const ft_layer *a, const ft_layer *b, size_t f)
{
    for (size_t k = 0; k < a->nfields; k++) {
        const ft_value *u = &a->features[f].values[k], *v = &b->features[f].values[k];
        assert_int_equal(u->is_null, v->is_null);
        if (u->is_null)
            continue;
        switch (a->fields[k].type) {
        case FT_FIELD_INT: assert_int_equal(u->i, v->i); break;
        case FT_FIELD_REAL: assert_true(u->r == v->r); break;
        default: assert_string_equal(u->s, v->s); break;
        }
    }
}

/* Shapefile: ring orientation rewritten, names cut to 10 characters, single polygons not multi. */
static void assert_layers_equal(const ft_layer *a, const ft_layer *b, int mode)
{
    assert_int_equal(a->nfeatures, b->nfeatures);
    assert_int_equal(a->nparts, b->nparts);
    assert_int_equal(a->nfields, b->nfields);
    ft_test_assert_same_crs(a->crs_wkt, b->crs_wkt);
    for (size_t k = 0; k < a->nfields; k++) {
        if (mode == SHAPEFILE)
            assert_int_equal(strncasecmp(a->fields[k].name, b->fields[k].name, 10), 0);
        else
            assert_string_equal(a->fields[k].name, b->fields[k].name);
        assert_int_equal(a->fields[k].type, b->fields[k].type);
    }
    for (size_t f = 0; f < a->nfeatures; f++) {
        const ft_feature *fa = &a->features[f], *fb = &b->features[f];
        assert_int_equal(fa->type, fb->type);
        assert_int_equal(fa->count, fb->count);
        if (mode != SHAPEFILE)
            assert_int_equal(fa->multi, fb->multi);
        for (size_t p = 0; p < fa->count; p++) {
            const ft_part *pa = &a->parts[fa->first + p], *pb = &b->parts[fb->first + p];
            assert_int_equal(pa->role, pb->role);
            assert_int_equal(pa->polygon, pb->polygon);
            if (mode & RINGS_UP_TO_ORIENTATION && pa->chain->closed)
                assert_true(ring_same(pa->chain, pb->chain));
            else
                ft_test_assert_chain_equal(pa->chain, pb->chain);
        }
        assert_values_equal(a, b, f);
    }
}

static ft_layer *read_ok(const char *path, const ft_read_layer_opts *o)
{
    ft_layer *l = NULL;
    int rc = ft_io_read_layer(path, o, &l);
    if (rc != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
    return l;
}

/* A polygon with a hole, a multilinestring with a null attribute, a line. */
static ft_layer *hand_layer(int polygons_only)
{
    ft_layer *l = ft_layer_create("hand", "EPSG:32633");
    assert_non_null(l);
    assert_int_equal(ft_layer_add_field(l, "name", FT_FIELD_STRING, -1, 0, 0), 0);
    assert_int_equal(ft_layer_add_field(l, "value", FT_FIELD_REAL, -1, 0, 0), 1);
    assert_int_equal(ft_layer_add_field(l, "count", FT_FIELD_INT, -1, 0, 0), 2);
    const double ox[] = {500000.1, 500010.3, 500010.7, 500000.9}, oy[] = {4000000.25, 4000000.5, 4000010, 4000009.75};
    const double ix[] = {500002, 500002, 500004, 500004}, iy[] = {4000002, 4000004, 4000004, 4000002};
    assert_int_equal(ft_layer_add_feature(l, 0, FT_GEOM_POLYGON, 0), 0);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(ox, oy, 4, 1, 1), FT_ROLE_OUTER, 0), FT_OK);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(ix, iy, 4, 1, 1), FT_ROLE_INNER, 0), FT_OK);
    ft_layer_set_string(l, 0, 0, "square with hole");
    ft_layer_set_real(l, 0, 1, 0.1);
    ft_layer_set_int(l, 0, 2, 4000000000LL);
    if (polygons_only)
        return l;
    const double ax[] = {0.1, 1.0 / 3.0, 2.5}, ay[] = {1e-7, 2.0, 3.75};
    const double bx[] = {10, 11}, by[] = {-5.5, -6.5};
    assert_int_equal(ft_layer_add_feature(l, 1, FT_GEOM_LINE, 1), 1);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(ax, ay, 3, 1, 0), FT_ROLE_LINE, 0), FT_OK);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(bx, by, 2, 1, 0), FT_ROLE_LINE, 0), FT_OK);
    ft_layer_set_real(l, 1, 1, -2.25);
    ft_layer_set_int(l, 1, 2, -3);
    assert_int_equal(ft_layer_add_feature(l, 2, FT_GEOM_LINE, 0), 2);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(bx, ay, 2, 1, 0), FT_ROLE_LINE, 0), FT_OK);
    ft_layer_set_string(l, 2, 0, "ligne \xc3\xa9t\xc3\xa9");
    return l;
}

/* ---- reading the fixtures ---------------------------------------------------------------------- */

static void test_read_states(void **state)
{
    (void)state;
    ft_layer *l = read_ok(STATES, NULL);
    assert_int_equal(l->nfeatures, 4);
    assert_int_equal(l->nfields, 6);
    ft_test_assert_crs_epsg(l->crs_wkt, 5070);
    int code = ft_layer_field_index(l, "code"), parts = ft_layer_field_index(l, "n_parts");
    int verts = ft_layer_field_index(l, "n_vertices");
    assert_true(code >= 0 && parts >= 0 && verts >= 0);
    assert_int_equal(l->fields[code].type, FT_FIELD_STRING);
    assert_int_equal(l->fields[parts].type, FT_FIELD_INT);
    const char *codes[] = {"US.RI", "US.OK", "US.CO", "US.WV"};
    for (size_t f = 0; f < 4; f++) {
        const ft_feature *ft = &l->features[f];
        assert_string_equal(ft->values[code].s, codes[f]);
        assert_int_equal(ft->type, FT_GEOM_POLYGON);
        assert_int_equal(ft->multi, 1);
        /* each part is one ring; n_vertices counts the closing vertex of every ring */
        assert_int_equal(ft->count, ft->values[parts].i);
        size_t nv = 0;
        for (size_t p = ft->first; p < ft->first + ft->count; p++) {
            assert_int_equal(l->parts[p].role, FT_ROLE_OUTER);
            assert_int_equal(l->parts[p].polygon, (int)(p - ft->first));
            assert_int_equal(l->parts[p].chain->closed, 1);
            nv += l->parts[p].chain->n;
        }
        assert_int_equal(nv + ft->count, ft->values[verts].i);
    }
    ft_layer_free(l);
}

static void test_read_newfoundland(void **state)
{
    (void)state;
    ft_layer *l = read_ok(NEWFOUNDLAND, NULL);
    assert_int_equal(l->nfeatures, 1);
    assert_int_equal(l->nparts, 1);
    assert_int_equal(l->features[0].type, FT_GEOM_POLYGON);
    assert_int_equal(l->features[0].multi, 0);
    assert_int_equal(l->parts[0].chain->n, 64193);
    assert_int_equal(l->parts[0].chain->closed, 1);
    ft_test_assert_crs_epsg(l->crs_wkt, 32621);
    ft_layer_free(l);
}

static void test_where_and_fields(void **state)
{
    (void)state;
    ft_read_layer_opts o = FT_READ_LAYER_OPTS_DEFAULT;
    o.where = "code = 'US.RI'";
    o.fields = " name , n_parts";
    ft_layer *l = read_ok(STATES, &o);
    assert_int_equal(l->nfeatures, 1);
    assert_int_equal(l->nfields, 2);
    assert_string_equal(l->fields[0].name, "name");
    assert_string_equal(l->fields[1].name, "n_parts");
    assert_string_equal(l->features[0].values[0].s, "Rhode Island");
    assert_int_equal(l->features[0].count, 9);
    ft_layer_free(l);

    o.where = NULL;
    o.fields = "";
    l = read_ok(STATES, &o);
    assert_int_equal(l->nfields, 0);
    assert_int_equal(l->nfeatures, 4);
    ft_layer_free(l);

    o.fields = "name,population";
    l = NULL;
    assert_int_equal(ft_io_read_layer(STATES, &o, &l), FT_E_FORMAT);
    assert_null(l);
    assert_non_null(strstr(ft_last_error(), "'population'"));
    assert_non_null(strstr(ft_last_error(), STATES));

    o.fields = NULL;
    o.where = "code = 'XX'";
    assert_int_equal(ft_io_read_layer(STATES, &o, &l), FT_E_EMPTY);
    o.where = "no_such_column > 3";
    assert_int_equal(ft_io_read_layer(STATES, &o, &l), FT_E_INVALID);
}

static void test_curves_and_z(void **state)
{
    (void)state;
    const char *path = ft_test_tmp_text("curves.csv", "id,WKT\n"
                                                      "1,\"CIRCULARSTRING (0 0,1 1,2 0)\"\n"
                                                      "2,\"LINESTRING Z (0 0 5,1 1 6,2 2 7)\"\n"
                                                      "3,\"CURVEPOLYGON (CIRCULARSTRING (0 0,2 0,0 0))\"\n"
                                                      "4,\"POLYGON ZM ((0 0 1 2,4 0 1 2,4 4 1 2,0 0 1 2))\"\n"
                                                      "5,\"MULTILINESTRING M ((0 0 1,1 0 1),(5 5 1,6 6 1))\"\n");
    ft_layer *l = read_ok(path, NULL);
    assert_int_equal(l->nfeatures, 5);
    assert_int_equal(l->features[0].type, FT_GEOM_LINE);
    assert_true(l->parts[0].chain->n > 3); /* linearized arc */
    const ft_chain *arc = l->parts[0].chain;
    assert_true(fabs(arc->x[arc->n - 1] - 2) < 1e-12 && fabs(arc->y[arc->n - 1]) < 1e-12);
    assert_int_equal(l->features[1].type, FT_GEOM_LINE);
    assert_int_equal(l->parts[l->features[1].first].chain->n, 3);
    assert_int_equal(l->features[2].type, FT_GEOM_POLYGON);
    assert_int_equal(l->parts[l->features[2].first].chain->closed, 1);
    assert_int_equal(l->features[3].type, FT_GEOM_POLYGON);
    assert_int_equal(l->parts[l->features[3].first].chain->n, 3);
    assert_int_equal(l->features[4].multi, 1);
    assert_int_equal(l->features[4].count, 2);
    ft_layer_free(l);
}

static void test_large_linestring(void **state)
{
    (void)state;
    const char *path = ft_test_tmp("big.geojson");
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    const size_t n = 200000;
    fputs("{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
          "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[", f);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%s[%zu.5,%zu.25]", i ? "," : "", i, 2 * i);
    fputs("]}}]}\n", f);
    fclose(f);
    ft_layer *l = read_ok(path, NULL);
    assert_int_equal(l->parts[0].chain->n, n);
    assert_true(l->parts[0].chain->x[n - 1] == (double)(n - 1) + 0.5);
    assert_true(l->parts[0].chain->y[n - 1] == 2.0 * (double)(n - 1) + 0.25);
    ft_layer_free(l);
}

/* ---- round trips ------------------------------------------------------------------------------- */

static void round_trip(const ft_layer *a, const char *name, int mode)
{
    const char *path = ft_test_tmp(name);
    if (ft_io_write_layer(path, a, NULL) != FT_OK)
        fail_msg("writing %s: %s", path, ft_last_error());
    ft_layer *b = read_ok(path, NULL);
    assert_layers_equal(a, b, mode);
    ft_layer_free(b);
}

static void test_round_trip_states(void **state)
{
    (void)state;
    ft_layer *a = read_ok(STATES, NULL);
    round_trip(a, "states.geojson", EXACT);
    round_trip(a, "states.gpkg", EXACT);
    round_trip(a, "states.shp", SHAPEFILE);
    assert_int_equal(access(ft_test_tmp("states.dbf"), F_OK), 0);
    assert_int_equal(access(ft_test_tmp("states.prj"), F_OK), 0);
    ft_layer_free(a);
}

static void test_round_trip_hand_layer(void **state)
{
    (void)state;
    ft_layer *a = hand_layer(0);
    assert_true(a->features[1].values[0].is_null);
    round_trip(a, "hand.geojson", EXACT);
    round_trip(a, "hand.gpkg", EXACT);
    ft_layer_free(a);

    /* Shapefile: one geometry kind per file; its driver rewinds rings, null strings survive */
    a = hand_layer(1);
    ft_layer_add_feature(a, 1, FT_GEOM_POLYGON, 1);
    const double x[] = {0, 1, 1}, y[] = {0, 0, 1}, x2[] = {5, 6, 6}, y2[] = {5, 5, 6};
    ft_layer_add_part(a, ft_chain_from_arrays(x, y, 3, 1, 1), FT_ROLE_OUTER, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(x2, y2, 3, 1, 1), FT_ROLE_OUTER, 1);
    round_trip(a, "hand.shp", SHAPEFILE);
    ft_layer_free(a);
}

static void test_shapefile_orientation(void **state)
{
    (void)state;
    ft_layer *a = hand_layer(1);
    double area_outer = ft_chain_signed_area(a->parts[0].chain);
    assert_true(area_outer > 0); /* built counter-clockwise */
    const char *path = ft_test_tmp("orient.shp");
    assert_int_equal(ft_io_write_layer(path, a, NULL), FT_OK);
    ft_layer *b = read_ok(path, NULL);
    assert_true(ft_chain_signed_area(b->parts[0].chain) < 0); /* outer clockwise */
    assert_true(ft_chain_signed_area(b->parts[1].chain) > 0); /* hole counter-clockwise */
    assert_true(ring_same(a->parts[0].chain, b->parts[0].chain));
    ft_layer_free(b);
    /* GeoJSON keeps the order as given */
    path = ft_test_tmp("orient.geojson");
    assert_int_equal(ft_io_write_layer(path, a, NULL), FT_OK);
    b = read_ok(path, NULL);
    assert_true(ft_chain_signed_area(b->parts[0].chain) > 0);
    ft_layer_free(b);
    ft_layer_free(a);
}

static void test_write_driver_and_layer_name(void **state)
{
    (void)state;
    ft_layer *a = hand_layer(0);
    ft_write_layer_opts o = FT_WRITE_LAYER_OPTS_DEFAULT;
    o.driver = "GPKG";
    o.layer = "mine";
    const char *path = ft_test_tmp("forced.dat");
    assert_int_equal(ft_io_write_layer(path, a, &o), FT_OK);
    ft_read_layer_opts r = FT_READ_LAYER_OPTS_DEFAULT;
    r.layer = "mine";
    ft_layer *b = read_ok(path, &r);
    assert_layers_equal(a, b, EXACT);
    ft_layer_free(b);
    r.layer = "other";
    assert_int_equal(ft_io_read_layer(path, &r, &b), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "'other'"));
    assert_non_null(strstr(ft_last_error(), "mine"));
    assert_int_equal(ft_io_write_layer(ft_test_tmp("x.unknownext"), a, NULL), FT_E_FORMAT);
    o.driver = "NoSuchDriver";
    assert_int_equal(ft_io_write_layer(ft_test_tmp("x.gpkg"), a, &o), FT_E_FORMAT);
    ft_layer_free(a);
}

/* ---- failures ---------------------------------------------------------------------------------- */

static void test_bad_inputs(void **state)
{
    (void)state;
    ft_layer *l = NULL;
    assert_int_equal(ft_io_read_layer(FT_TEST_DATA "/no_such_file.geojson", NULL, &l), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "cannot open '" FT_TEST_DATA "/no_such_file.geojson'"));

    const char *garbage = ft_test_tmp_text("garbage.geojson", "this is not { json at all ]]\n");
    assert_int_equal(ft_io_read_layer(garbage, NULL, &l), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), garbage));

    assert_int_equal(ft_io_read_layer(VOLCANO, NULL, &l), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "is a raster, not a vector layer"));

    const char *pts = ft_test_tmp("points.geojson");
    ft_test_put_text(pts, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                          "\"geometry\":{\"type\":\"Point\",\"coordinates\":[1,2]}}]}\n");
    assert_int_equal(ft_io_read_layer(pts, NULL, &l), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "points"));

    const char *empty = ft_test_tmp("empty.geojson");
    ft_test_put_text(empty, "{\"type\":\"FeatureCollection\",\"name\":\"nothing\",\"features\":[]}\n");
    assert_int_equal(ft_io_read_layer(empty, NULL, &l), FT_E_EMPTY);
    assert_non_null(strstr(ft_last_error(), empty));
    assert_non_null(strstr(ft_last_error(), "nothing"));

    const char *nan = ft_test_tmp("nan.geojson");
    ft_test_put_text(nan, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"id\":7,"
                          "\"properties\":{},"
                          "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0],[1,NaN],[2,2]]}}]}\n");
    assert_int_equal(ft_io_read_layer(nan, NULL, &l), FT_E_NUMERIC);
    assert_non_null(strstr(ft_last_error(), "feature 7"));
    assert_non_null(strstr(ft_last_error(), "vertex 1"));
    assert_null(l);
}

static void test_short_chains_kept(void **state)
{
    (void)state;
    const char *path = ft_test_tmp("short.geojson");
    ft_test_put_text(path, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\","
                           "\"properties\":{\"a\":null},"
                           "\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0]]}},"
                           "{\"type\":\"Feature\",\"properties\":{\"a\":1},\"geometry\":null}]}\n");
    ft_layer *l = read_ok(path, NULL);
    assert_int_equal(l->nfeatures, 2);
    assert_int_equal(l->parts[0].chain->n, 1);
    assert_int_equal(l->features[1].type, FT_GEOM_NONE);
    assert_int_equal(l->features[1].count, 0);
    assert_true(l->features[0].values[0].is_null);
    ft_layer_free(l);
}

static void test_write_failures_leave_nothing(void **state)
{
    (void)state;
    ft_layer *a = hand_layer(0);
    assert_int_equal(ft_io_write_layer("/tmp/ft-no-such-folder-xyz/out.geojson", a, NULL), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "/tmp/ft-no-such-folder-xyz"));
    assert_int_equal(access("/tmp/ft-no-such-folder-xyz", F_OK), -1);
    assert_int_equal(ft_test_dir_count(), 0);

    /* a Shapefile holds one geometry kind: polygons then lines fail mid-way */
    const char *shp = ft_test_tmp("mixed.shp");
    int rc = ft_io_write_layer(shp, a, NULL);
    assert_int_equal(rc, FT_E_IO);
    assert_non_null(strstr(ft_last_error(), shp));
    assert_int_equal(ft_test_dir_count(), 0);

    /* an existing file survives a failed overwrite */
    const char *keep = ft_test_tmp("keep.shp");
    ft_layer *poly = hand_layer(1);
    assert_int_equal(ft_io_write_layer(keep, poly, NULL), FT_OK);
    int before = ft_test_dir_count();
    assert_int_equal(ft_io_write_layer(keep, a, NULL), FT_E_IO);
    assert_int_equal(ft_test_dir_count(), before);
    ft_layer *b = read_ok(keep, NULL);
    assert_layers_equal(poly, b, SHAPEFILE);
    ft_layer_free(b);
    ft_layer_free(poly);
    ft_layer_free(a);
}

static void test_probe_and_checks(void **state)
{
    (void)state;
    ft_file_kind k;
    assert_int_equal(ft_io_probe(STATES, NULL, &k), FT_OK);
    assert_int_equal(k, FT_KIND_CHAINS);
    assert_int_equal(ft_io_probe(VOLCANO, NULL, &k), FT_OK);
    assert_int_equal(k, FT_KIND_GRID);
    assert_int_equal(ft_io_probe(FT_TEST_DATA "/points_mass_topo_davis1973.csv", NULL, &k), FT_OK);
    assert_int_equal(k, FT_KIND_POINTS);
    const char *pts = ft_test_tmp("p.geojson");
    ft_test_put_text(pts, "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
                          "\"geometry\":{\"type\":\"Point\",\"coordinates\":[1,2,3]}}]}\n");
    assert_int_equal(ft_io_probe(pts, NULL, &k), FT_OK);
    assert_int_equal(k, FT_KIND_POINTS);
    assert_int_equal(ft_io_probe("/tmp/ft-missing-file.tif", NULL, &k), FT_E_IO);
    const char *garbage = ft_test_tmp_text("garbage.bin", "\x01\x02garbage");
    assert_int_equal(ft_io_probe(garbage, NULL, &k), FT_E_FORMAT);
    assert_int_equal(ft_io_probe(STATES, "nope", &k), FT_E_FORMAT);

    assert_true(ft_io_is_text_chains("a/b.GMT"));
    assert_true(ft_io_is_text_chains("x.xy"));
    assert_false(ft_io_is_text_chains("x.geojson"));
    assert_true(ft_io_is_text_points("p.csv"));
    assert_true(ft_io_is_text_points("p.XYZ"));
    assert_false(ft_io_is_text_points("p.gpkg"));

    assert_int_equal(ft_io_check_writable(ft_test_tmp("new.tif")), FT_OK);
    assert_int_equal(ft_io_check_writable("relative-name.tif"), FT_OK);
    assert_int_equal(ft_io_check_writable("/tmp/ft-no-such-folder-xyz/a.tif"), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "'/tmp/ft-no-such-folder-xyz'"));
    assert_int_equal(ft_io_check_writable(ft_test_dir()), FT_E_IO);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_states),
        cmocka_unit_test(test_read_newfoundland),
        cmocka_unit_test(test_where_and_fields),
        cmocka_unit_test(test_curves_and_z),
        cmocka_unit_test(test_large_linestring),
        cmocka_unit_test(test_round_trip_states),
        cmocka_unit_test(test_round_trip_hand_layer),
        cmocka_unit_test(test_shapefile_orientation),
        cmocka_unit_test(test_write_driver_and_layer_name),
        cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_short_chains_kept),
        cmocka_unit_test(test_write_failures_leave_nothing),
        cmocka_unit_test(test_probe_and_checks),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
