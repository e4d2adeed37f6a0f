/* fracterra — unit tests of core/layer.c: fields, features, parts, values, copy, checks.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <string.h>

#include "fracterra/core.h"
#include "ft_test_assert.h"

static ft_chain *ring_of(const double *xy, size_t n)
{
    return ft_chain_from_arrays(xy, xy + 1, n, 2, 1);
}

static const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
static const double hole[] = {0.25, 0.25, 0.25, 0.75, 0.75, 0.75, 0.75, 0.25};

/* Two features: a polygon with a hole, and a two-part multiline. */
static ft_layer *sample_layer(void)
{
    ft_layer *l = ft_layer_create("parcels", "EPSG:2154");
    assert_non_null(l);
    assert_int_equal(ft_layer_add_field(l, "name", FT_FIELD_STRING, 4, 32, 0), 0);
    assert_int_equal(ft_layer_add_field(l, "Area", FT_FIELD_REAL, 2, 12, 3), 1);
    assert_int_equal(ft_layer_add_feature(l, 100, FT_GEOM_POLYGON, 0), 0);
    assert_int_equal(ft_layer_add_part(l, ring_of(sq, 4), FT_ROLE_OUTER, 0), FT_OK);
    assert_int_equal(ft_layer_add_part(l, ring_of(hole, 4), FT_ROLE_INNER, 0), FT_OK);
    assert_int_equal(ft_layer_add_feature(l, 101, FT_GEOM_LINE, 1), 1);
    const double xs[] = {5, 6, 7}, ys[] = {-1, -2, 3};
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(xs, ys, 3, 1, 0), FT_ROLE_LINE, 0), FT_OK);
    assert_int_equal(ft_layer_add_part(l, ft_chain_from_arrays(ys, xs, 2, 1, 0), FT_ROLE_LINE, 1), FT_OK);
    return l;
}

static void test_structure(void **state)
{
    (void)state;
    ft_layer *l = sample_layer();
    assert_string_equal(l->name, "parcels");
    assert_string_equal(l->crs_wkt, "EPSG:2154");
    assert_int_equal(l->nfeatures, 2);
    assert_int_equal(l->nparts, 4);
    assert_int_equal(l->features[0].first, 0);
    assert_int_equal(l->features[0].count, 2);
    assert_int_equal(l->features[1].first, 2);
    assert_int_equal(l->features[1].count, 2);
    assert_int_equal(l->features[1].multi, 1);
    assert_true(l->features[1].fid == 101);
    assert_int_equal(l->parts[1].role, FT_ROLE_INNER);
    assert_int_equal(l->parts[3].feature, 1);
    assert_int_equal(l->parts[3].polygon, 1);
    assert_int_equal(ft_layer_vertex_count(l), 4 + 4 + 3 + 2);
    double x0, y0, x1, y1;
    assert_int_equal(ft_layer_bbox(l, &x0, &y0, &x1, &y1), FT_OK);
    assert_true(x0 == -2.0 && y0 == -2.0 && x1 == 7.0 && y1 == 6.0);
    ft_layer_free(l);
    ft_layer_free(NULL);
}

static void test_fields_and_values(void **state)
{
    (void)state;
    ft_layer *l = sample_layer();
    assert_int_equal(ft_layer_field_index(l, "AREA"), 1);
    assert_int_equal(ft_layer_field_index(l, "Name"), 0);
    assert_int_equal(ft_layer_field_index(l, "missing"), -1);
    assert_int_equal(ft_layer_add_field(l, "name", FT_FIELD_INT, 0, 0, 0), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "'name'"));
    assert_int_equal(l->features[0].values[0].is_null, 1);

    char buf[16];
    strcpy(buf, "field A");
    assert_int_equal(ft_layer_set_string(l, 0, 0, buf), FT_OK);
    buf[0] = 'X'; /* the layer holds its own copy */
    assert_string_equal(l->features[0].values[0].s, "field A");
    assert_int_equal(l->features[0].values[0].is_null, 0);
    assert_int_equal(ft_layer_set_real(l, 1, 1, 2.5), FT_OK);
    assert_true(l->features[1].values[1].r == 2.5);
    assert_int_equal(ft_layer_set_int(l, 1, 1, 3), FT_OK); /* an int widens into a real field */
    assert_true(l->features[1].values[1].r == 3.0);

    /* a field added after the features gets a null value in each */
    assert_int_equal(ft_layer_add_field(l, "pop", FT_FIELD_INT, 12, 0, 0), 2);
    assert_int_equal(l->features[0].values[2].is_null, 1);
    assert_int_equal(l->features[1].values[2].is_null, 1);
    assert_int_equal(ft_layer_set_int(l, 0, 2, INT64_C(-9000000000)), FT_OK);
    assert_true(l->features[0].values[2].i == INT64_C(-9000000000));
    assert_int_equal(ft_layer_set_real(l, 1, 2, 12.0), FT_OK);
    assert_true(l->features[1].values[2].i == 12);
    assert_int_equal(ft_layer_set_real(l, 1, 2, 12.5), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "12.5"));
    assert_int_equal(ft_layer_set_string(l, 1, 2, "x"), FT_E_INVALID);
    assert_int_equal(ft_layer_set_int(l, 0, 0, 4), FT_E_INVALID);

    assert_int_equal(ft_layer_set_int(l, 5, 0, 1), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "5"));
    assert_int_equal(ft_layer_set_int(l, 0, 9, 1), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "9"));
    assert_int_equal(ft_layer_set_string(l, 0, 0, NULL), FT_OK);
    assert_int_equal(l->features[0].values[0].is_null, 1);
    assert_null(l->features[0].values[0].s);
    ft_layer_free(l);
}

static void test_add_part_takes_ownership_even_on_failure(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create(NULL, NULL);
    assert_null(l->name);
    /* no feature yet: fails, and the chain is freed (AddressSanitizer would report a leak) */
    assert_int_equal(ft_layer_add_part(l, ring_of(sq, 4), FT_ROLE_OUTER, 0), FT_E_INVALID);
    assert_int_equal(ft_layer_add_feature(l, 1, FT_GEOM_POLYGON, 0), 0);
    assert_int_equal(ft_layer_add_part(l, ring_of(sq, 4), (ft_part_role)7, 0), FT_E_INVALID);
    assert_int_equal(ft_layer_add_part(l, NULL, FT_ROLE_OUTER, 0), FT_E_INVALID);
    assert_int_equal(l->nparts, 0);
    assert_int_equal(ft_layer_bbox(l, NULL, NULL, NULL, NULL), FT_E_EMPTY);
    ft_layer_free(l);
}

static void test_many_features_grow(void **state)
{
    (void)state;
    ft_layer *l = ft_layer_create("grow", NULL);
    ft_layer_add_field(l, "id", FT_FIELD_INT, 0, 0, 0);
    for (int f = 0; f < 5000; f++) {
        assert_true(ft_layer_add_feature(l, f, FT_GEOM_POLYGON, 0) == f);
        assert_int_equal(ft_layer_add_part(l, ring_of(sq, 4), FT_ROLE_OUTER, 0), FT_OK);
        assert_int_equal(ft_layer_set_int(l, (size_t)f, 0, f * 2), FT_OK);
    }
    assert_int_equal(l->nfeatures, 5000);
    assert_int_equal(l->nparts, 5000);
    assert_true(l->features[4999].values[0].i == 9998);
    assert_int_equal(l->features[4999].first, 4999);
    assert_int_equal(ft_layer_vertex_count(l), 20000);
    ft_layer_free(l);
}

static void test_check_finite_names_feature_part_vertex(void **state)
{
    (void)state;
    ft_layer *l = sample_layer();
    assert_int_equal(ft_layer_check_finite(l), FT_OK);
    l->parts[3].chain->y[1] = NAN; /* feature 1, its part 1, vertex 1 */
    assert_int_equal(ft_layer_check_finite(l), FT_E_NUMERIC);
    const char *msg = ft_last_error();
    assert_non_null(strstr(msg, "feature 1"));
    assert_non_null(strstr(msg, "part 1"));
    assert_non_null(strstr(msg, "vertex 1"));
    assert_non_null(strstr(msg, "nan"));
    ft_layer_free(l);
}

static void test_copy_is_deep(void **state)
{
    (void)state;
    ft_layer *l = sample_layer();
    ft_layer_set_string(l, 0, 0, "north");
    ft_layer_set_real(l, 0, 1, 0.75);
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    ft_layer *d = ft_layer_copy(l);
    assert_non_null(d);
    l->parts[0].chain->x[1] = 99.0;
    ft_layer_set_string(l, 0, 0, "south");
    l->topology->arcs[0]->x[0] = -5.0;
    assert_true(d->parts[0].chain->x[1] == 1.0);
    assert_string_equal(d->features[0].values[0].s, "north");
    assert_true(d->features[0].values[1].r == 0.75);
    assert_int_equal(d->features[1].values[0].is_null, 1);
    assert_string_equal(d->fields[1].name, "Area");
    assert_int_equal(d->fields[1].width, 12);
    assert_int_equal(d->fields[1].precision, 3);
    assert_int_equal(d->fields[1].native_type, 2);
    assert_int_equal(d->nparts, 4);
    assert_int_equal(d->parts[1].role, FT_ROLE_INNER);
    assert_string_equal(d->crs_wkt, "EPSG:2154");
    assert_non_null(d->topology);
    assert_int_equal(d->topology->narcs, l->topology->narcs);
    assert_true(d->topology->arcs[0]->x[0] != -5.0);
    assert_int_equal(d->topology->nrings[0], 1);
    ft_layer_free(l);
    ft_layer_free(d);
}

static void test_add_part_drops_stale_topology(void **state)
{
    (void)state;
    ft_layer *l = sample_layer();
    assert_int_equal(ft_layer_build_topology(l, 0.0), FT_OK);
    assert_non_null(l->topology);
    assert_int_equal(ft_layer_add_part(l, ring_of(sq, 4), FT_ROLE_LINE, 2), FT_OK);
    assert_null(l->topology);
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_structure),
        cmocka_unit_test(test_fields_and_values),
        cmocka_unit_test(test_add_part_takes_ownership_even_on_failure),
        cmocka_unit_test(test_many_features_grow),
        cmocka_unit_test(test_check_finite_names_feature_part_vertex),
        cmocka_unit_test(test_copy_is_deep),
        cmocka_unit_test(test_add_part_drops_stale_topology),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
