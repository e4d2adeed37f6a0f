/* fracterra — tests/unit/test_urban_grid_classes.c: the classes of a classified raster
 * (ft_urban_grid_classes): distinct valid values in increasing order, nodata left out, and a continuous or
 * empty raster refused with a message that says why.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/core.h"
#include "fracterra/urban.h"

static ft_grid *grid_of(const float *z, const unsigned char *valid, size_t nx, size_t ny)
{
    ft_grid *g = ft_grid_create(nx, ny);
    assert_non_null(g);
    memcpy(g->z, z, nx * ny * sizeof *z);
    if (valid) {
        assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
        memcpy(g->mask, valid, nx * ny);
    }
    return g;
}

static void test_distinct_values(void **state)
{
    (void)state;
    const float z[] = {3, 1, 2, 1, 7, 3, -4, 1};
    const unsigned char valid[] = {1, 1, 1, 1, 0, 1, 1, 1}; /* the 7 is nodata */
    ft_grid *g = grid_of(z, valid, 4, 2);
    float *v = NULL;
    size_t n = 0;
    assert_int_equal(ft_urban_grid_classes(g, FT_URBAN_MAX_CLASSES, &v, &n), FT_OK);
    assert_int_equal(n, 4);
    const float want[] = {-4, 1, 2, 3};
    for (size_t i = 0; i < n; i++)
        assert_true(v[i] == want[i]);
    free(v);
    /* exactly max_classes is allowed, one more is not */
    assert_int_equal(ft_urban_grid_classes(g, 4, &v, &n), FT_OK);
    free(v);
    assert_int_equal(ft_urban_grid_classes(g, 3, &v, &n), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "4 distinct values, more than 3"));
    assert_null(v);
    assert_int_equal(n, 0);
    ft_grid_free(g);
}

static void test_not_classified(void **state)
{
    (void)state;
    float *v = NULL;
    size_t n = 0;
    const float real[] = {1, 2, 2.5f, 1};
    ft_grid *g = grid_of(real, NULL, 2, 2);
    assert_int_equal(ft_urban_grid_classes(g, FT_URBAN_MAX_CLASSES, &v, &n), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "2.5, not a whole number"));
    ft_grid_free(g);
    const float with_nan[] = {1, NAN, 2, 1};
    g = grid_of(with_nan, NULL, 2, 2);
    assert_int_equal(ft_urban_grid_classes(g, FT_URBAN_MAX_CLASSES, &v, &n), FT_E_INVALID);
    ft_grid_free(g);
    const unsigned char none[] = {0, 0, 0, 0};
    g = grid_of(real, none, 2, 2);
    assert_int_equal(ft_urban_grid_classes(g, FT_URBAN_MAX_CLASSES, &v, &n), FT_E_EMPTY);
    assert_non_null(strstr(ft_last_error(), "no valid cell"));
    assert_int_equal(ft_urban_grid_classes(NULL, 10, &v, &n), FT_E_INVALID);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_distinct_values),
        cmocka_unit_test(test_not_classified),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
