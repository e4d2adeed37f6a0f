/* fracterra — tests of ft_io_read_any: one open, the kind decided from the content, the right reader.
 * Figures are the facts of tests/data/README.md.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/io.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"
#define COAST FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"
#define STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"
#define TOPO FT_TEST_DATA "/points_mass_topo_davis1973.csv"

static void test_grid(void **state)
{
    (void)state;
    ft_data d;
    assert_int_equal(ft_io_read_any(VOLCANO, NULL, NULL, NULL, &d), FT_OK);
    assert_int_equal(d.kind, FT_KIND_GRID);
    assert_non_null(d.grid);
    assert_null(d.layer);
    assert_null(d.points);
    assert_int_equal(d.grid->nx, 61);
    assert_int_equal(d.grid->ny, 87);
    ft_data_clear(&d);
    assert_null(d.grid);

    assert_int_equal(ft_io_read_any(LUXEMBOURG, NULL, NULL, NULL, &d), FT_OK);
    assert_int_equal(ft_grid_count_valid(d.grid), 4608);
    ft_data_clear(&d);
}

static void test_chains(void **state)
{
    (void)state;
    ft_data d;
    assert_int_equal(ft_io_read_any(COAST, NULL, NULL, NULL, &d), FT_OK);
    assert_int_equal(d.kind, FT_KIND_CHAINS);
    assert_non_null(d.layer);
    assert_int_equal(d.layer->nparts, 1);
    assert_int_equal(d.layer->parts[0].chain->n, 64193);
    assert_int_equal(d.layer->parts[0].chain->closed, 1);
    ft_data_clear(&d);

    /* Options reach the reader: an attribute filter keeps one state of four. */
    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    lo.where = "code = 'US.CO'";
    assert_int_equal(ft_io_read_any(STATES, &lo, NULL, NULL, &d), FT_OK);
    assert_int_equal(d.layer->nfeatures, 1);
    ft_data_clear(&d);
}

static void test_points(void **state)
{
    (void)state;
    ft_data d;
    assert_int_equal(ft_io_read_any(TOPO, NULL, NULL, NULL, &d), FT_OK);
    assert_int_equal(d.kind, FT_KIND_POINTS);
    assert_int_equal(d.points->n, 52);
    ft_data_clear(&d);
}

static void test_errors(void **state)
{
    (void)state;
    ft_data d;
    assert_int_equal(ft_io_read_any(FT_TEST_DATA "/no_such_file.tif", NULL, NULL, NULL, &d), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "no_such_file.tif"));
    assert_null(d.grid);

    ft_read_grid_opts go = FT_READ_GRID_OPTS_DEFAULT;
    go.band = 2;
    assert_int_equal(ft_io_read_any(VOLCANO, NULL, &go, NULL, &d), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "band 2"));

    ft_read_layer_opts lo = FT_READ_LAYER_OPTS_DEFAULT;
    lo.layer = "nope";
    assert_int_equal(ft_io_read_any(STATES, &lo, NULL, NULL, &d), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "nope"));
    assert_null(d.layer);

    /* A file GDAL does not read at all. */
    assert_int_equal(ft_io_read_any(FT_TEST_DATA "/README.md", NULL, NULL, NULL, &d), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "README.md"));
    ft_data_clear(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_grid),
        cmocka_unit_test(test_chains),
        cmocka_unit_test(test_points),
        cmocka_unit_test(test_errors),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    ft_io_cleanup();
    return failed;
}
