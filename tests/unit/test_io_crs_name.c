/* fracterra — tests/unit/test_io_crs_name.c: ft_io_crs_name, the name and the stated EPSG code of a CRS
 * (WKT1 and WKT2, a compound CRS's root code, a WKT with no code, empty and broken input).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/core.h"
#include "fracterra/io.h"
#include "ft_test_util.h"

static void expect_name(const char *user_crs, const char *name, int epsg)
{
    char *wkt = NULL, got[256];
    int code = -1;
    assert_int_equal(ft_io_crs_to_wkt(user_crs, &wkt), FT_OK);
    assert_int_equal(ft_io_crs_name(wkt, got, sizeof got, &code), FT_OK);
    assert_string_equal(got, name);
    assert_int_equal(code, epsg);
    free(wkt);
}

static void test_epsg_crs(void **state)
{
    (void)state;
    expect_name("EPSG:32632", "WGS 84 / UTM zone 32N", 32632);
    expect_name("EPSG:4326", "WGS 84", 4326);
    /* a compound CRS: the root's own code, not its horizontal part's */
    expect_name("EPSG:5972", "ETRS89 / UTM zone 32N + NN2000 height", 5972);
}

static void test_wkt_without_code(void **state)
{
    (void)state;
    const char *wkt1 = "PROJCS[\"my \"\"local\"\" grid\",GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\","
                       "6378137,298.257223563,AUTHORITY[\"EPSG\",\"7030\"]],AUTHORITY[\"EPSG\",\"6326\"]],"
                       "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433],AUTHORITY[\"EPSG\",\"4326\"]],"
                       "PROJECTION[\"Transverse_Mercator\"],PARAMETER[\"latitude_of_origin\",0],"
                       "PARAMETER[\"central_meridian\",9],PARAMETER[\"scale_factor\",0.9996],"
                       "PARAMETER[\"false_easting\",500000],PARAMETER[\"false_northing\",0],UNIT[\"metre\",1]]";
    char name[256];
    int epsg = -1;
    assert_int_equal(ft_io_crs_name(wkt1, name, sizeof name, &epsg), FT_OK);
    assert_string_equal(name, "my \"local\" grid");
    assert_int_equal(epsg, 0); /* the inner GEOGCS says 4326; the CRS itself states no code */
    /* a short buffer: truncated, terminated */
    assert_int_equal(ft_io_crs_name(wkt1, name, 6, &epsg), FT_OK);
    assert_string_equal(name, "my \"l");
}

static void test_empty_and_broken(void **state)
{
    (void)state;
    char name[64] = "x";
    int epsg = -1;
    assert_int_equal(ft_io_crs_name(NULL, name, sizeof name, &epsg), FT_OK);
    assert_string_equal(name, "");
    assert_int_equal(epsg, 0);
    assert_int_equal(ft_io_crs_name("", name, sizeof name, &epsg), FT_OK);
    assert_int_equal(ft_io_crs_name("PROJCS[\"broken\",", name, sizeof name, &epsg), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "invalid CRS"));
    assert_int_equal(ft_io_crs_name("EPSG:4326", NULL, 0, &epsg), FT_E_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_epsg_crs),
        cmocka_unit_test(test_wkt_without_code),
        cmocka_unit_test(test_empty_and_broken),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
