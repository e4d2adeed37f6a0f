/* fracterra — chains in longitude/latitude walked on the ellipsoid (line_dim.c with opts.ellipsoid).
 * The reference lengths come from PROJ's geodesic routines (GeographicLib's C port, geod_inverse), which
 * fracterra does not use: the walks measure straight 3-D chords between Earth-centred points.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <geodesic.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/line.h"

static const ft_ellipsoid wgs84 = FT_ELLIPSOID_WGS84;

/* The parallel at lat, one vertex every step degrees, as a ring. */
static ft_chain *parallel(double lat, double step)
{
    size_t n = (size_t)lround(360.0 / step);
    ft_chain *c = ft_chain_create(n, 1);
    for (size_t i = 0; i < n; i++)
        ft_chain_push(c, -180.0 + (double)i * step, lat);
    return c;
}

/* Sum of the geodesic lengths of the chain's segments (ring closed). */
static double geodesic_length(const ft_chain *c)
{
    struct geod_geodesic g;
    geod_init(&g, wgs84.a, wgs84.f);
    double sum = 0.0;
    for (size_t i = 0; i < c->n; i++) {
        size_t j = (i + 1) % c->n;
        double s12 = 0.0;
        geod_inverse(&g, c->y[i], c->x[i], c->y[j], c->x[j], &s12, NULL, NULL);
        sum += s12;
    }
    return sum;
}

/* A densified parallel at 60 N: every walk's length at rulers of 500 m to 20 km equals the ellipsoidal
 * length (geod_inverse) within 0.1%, and D = 1. Also the closed form 2 pi N cos(phi). */
static void test_parallel_60N(void **state)
{
    (void)state;
    ft_chain *c = parallel(60.0, 0.05);
    const ft_chain *set[1] = {c};
    double ref = geodesic_length(c);
    double e2 = wgs84.f * (2.0 - wgs84.f), s = sin(60.0 * M_PI / 180.0);
    double closed_form = 2.0 * M_PI * wgs84.a / sqrt(1.0 - e2 * s * s) * 0.5;
    assert_true(fabs(ref / closed_form - 1.0) < 1e-5);
    for (int m = 0; m < 3; m++) {
        ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
        o.ellipsoid = &wgs84;
        o.min_scale = 500.0;
        o.max_scale = 20000.0;
        o.nscales = 5;
        o.fit_whole_range = 1;
        ft_dim_result *r = NULL;
        assert_int_equal(ft_line_dim(set, 1, (ft_line_method)m, &o, &r), FT_OK);
        assert_string_equal(r->units, "m");
        assert_int_equal(r->table->n, 5);
        for (size_t i = 0; i < r->table->n; i++) {
            double rel = r->table->rows[i].value / ref - 1.0;
            print_message("  %s ruler %8.0f m: length %.1f m, geodesic %.1f m, %+.2e\n", ft_line_method_name(m),
                          r->table->rows[i].scale, r->table->rows[i].value, ref, rel);
            assert_true(fabs(rel) < 1e-3);
        }
        assert_true(fabs(r->D - 1.0) < 1e-3);
        ft_dim_result_free(r);
    }
    ft_chain_free(c);
}

/* A meridian arc from 45 N to 60 N (open, 0.01 degree steps): the divider length at 1 km is the meridian
 * arc's geodesic length within 0.1%. */
static void test_meridian(void **state)
{
    (void)state;
    ft_chain *c = ft_chain_create(1501, 0);
    for (int i = 0; i <= 1500; i++)
        ft_chain_push(c, 10.0, 45.0 + 0.01 * i);
    struct geod_geodesic g;
    geod_init(&g, wgs84.a, wgs84.f);
    double ref = 0.0;
    geod_inverse(&g, 45.0, 10.0, 60.0, 10.0, &ref, NULL, NULL);
    double len = 0.0;
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.ellipsoid = &wgs84;
    o.min_scale = 1000.0;
    o.max_scale = 4000.0;
    o.nscales = 3;
    o.fit_whole_range = 1;
    const ft_chain *set[1] = {c};
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_OK);
    len = r->table->rows[0].value;
    assert_true(fabs(len / ref - 1.0) < 1e-3);
    ft_dim_result_free(r);
    ft_chain_free(c);
}

/* Rulers longer than a lon/lat line, box counting without projection, latitudes beyond 90: errors. */
static void test_errors(void **state)
{
    (void)state;
    ft_chain *c = ft_chain_create(3, 0); /* about 5 km at 50 N */
    ft_chain_push(c, 6.00, 50.0);
    ft_chain_push(c, 6.03, 50.01);
    ft_chain_push(c, 6.07, 50.0);
    const ft_chain *set[1] = {c};
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.ellipsoid = &wgs84;
    o.min_scale = 1000.0;
    o.max_scale = 100000.0;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);
    assert_null(r);
    print_message("  %s\n", ft_last_error());
    assert_non_null(strstr(ft_last_error(), "of the range [1000, 100000] m is longer than the chains"));
    assert_non_null(strstr(ft_last_error(), " m long"));
    o.fit_whole_range = 0; /* automatic fitting within the limits: fewer than 3 usable rulers */
    o.min_scale = 4000.0;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);
    print_message("  %s\n", ft_last_error());
    assert_non_null(strstr(ft_last_error(), "rulers in [4000, 100000] m fit once along the chains"));
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_BOX, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "equal-area"));
    c->y[1] = 95.0;
    o.min_scale = 500.0;
    o.max_scale = 2000.0;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), ", 95) is outside longitude"));
    c->y[1] = 45.0;
    c->x[1] = 5120.0; /* metres taken for degrees */
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "(5120, 45) is outside longitude"));
    ft_chain_free(c);
}

/* The r² floor: a table that is not a line fails when min_r2 is set, names the range. */
static void test_r2_floor(void **state)
{
    (void)state;
    /* white noise of amplitude 50 along x every 5 units, then its end 4000 units away: the divider table
     * falls steeply at small rulers and flattens at large ones, nothing like a line */
    ft_chain *c = ft_chain_create(0, 0);
    uint32_t u = 12345u;
    for (int i = 0; i < 200; i++) {
        u = u * 1664525u + 1013904223u;
        ft_chain_push(c, 5.0 * i, 50.0 * (double)(u >> 8) / 16777216.0);
    }
    ft_chain_push(c, 5000.0, 0.0);
    const ft_chain *set[1] = {c};
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = 1.0;
    o.max_scale = 400.0;
    o.nscales = 4;
    o.fit_whole_range = 1;
    ft_dim_result *r = NULL;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_OK);
    double r2 = r->r2;
    print_message("  noise then a jump: D = %.3f +- %.3f, r2 = %.3f\n", r->D, r->stderr_D, r2);
    assert_true(r->stderr_D > FT_LINE_R2_MAX_STDERR);
    ft_dim_result_free(r);
    r = NULL;
    o.min_r2 = r2 + 0.05 > 1.0 ? 1.0 : r2 + 0.05;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);
    assert_null(r);
    assert_non_null(strstr(ft_last_error(), "r2 ="));
    assert_non_null(strstr(ft_last_error(), "[1, 400]"));
    o.min_r2 = 1.5;
    assert_int_equal(ft_line_dim(set, 1, FT_LINE_DIVIDER, &o, &r), FT_E_INVALID);
    ft_chain_free(c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parallel_60N),
        cmocka_unit_test(test_meridian),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_r2_floor),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
