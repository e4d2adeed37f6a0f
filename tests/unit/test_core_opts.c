/* fracterra — unit tests of the options-struct contract (FT_OPTS in core.h, src/core/opts.c): a caller
 * built against an older header (a smaller struct_size) gets the library's defaults for the fields it
 * did not have; a zeroed struct and a struct larger than the library's are refused, naming the type.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <string.h>

#include "fracterra/core.h"
#include "fracterra/surface.h"
#include "fracterra/terrain.h"

static ft_grid *surface(void)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.dim = 2.4;
    so.seed = 7;
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(64, 64, &so, &g), FT_OK);
    return g;
}

static void test_every_default_carries_its_size(void **state)
{
    (void)state;
    ft_synth_opts s = FT_SYNTH_OPTS_DEFAULT;
    ft_variogram_opts v = FT_VARIOGRAM_OPTS_DEFAULT;
    ft_surface_dim_opts d = FT_SURFACE_DIM_OPTS_DEFAULT;
    assert_int_equal(s.struct_size, sizeof s);
    assert_int_equal(v.struct_size, sizeof v);
    assert_int_equal(d.struct_size, sizeof d);
    assert_int_equal(v.fit.struct_size, sizeof v.fit); /* nested structs carry theirs too */
    assert_int_equal(v.noise.struct_size, sizeof v.noise);
}

static void test_an_older_caller_gets_defaults_for_the_fields_it_lacks(void **state)
{
    (void)state;
    ft_grid *g = surface();
    ft_variogram_opts dflt = FT_VARIOGRAM_OPTS_DEFAULT;
    ft_dim_result *want = NULL, *got = NULL;
    assert_int_equal(ft_surface_dim_variogram(g, &dflt, &want), FT_OK);

    /* A header without the trailing noise member: its bytes hold garbage the library must not read. */
    ft_variogram_opts old = FT_VARIOGRAM_OPTS_DEFAULT;
    old.struct_size = offsetof(ft_variogram_opts, noise);
    memset(&old.noise, 0x7f, sizeof old.noise);
    assert_int_equal(ft_surface_dim_variogram(g, &old, &got), FT_OK);
    assert_memory_equal(&got->D, &want->D, sizeof want->D);
    assert_int_equal(got->table->n, want->table->n);
    ft_dim_result_free(want);
    ft_dim_result_free(got);
    ft_grid_free(g);
}

static void test_a_zeroed_struct_is_refused_naming_the_type(void **state)
{
    (void)state;
    ft_grid *g = surface();
    ft_variogram_opts zero;
    memset(&zero, 0, sizeof zero);
    ft_dim_result *r = NULL;
    assert_int_equal(ft_surface_dim_variogram(g, &zero, &r), FT_E_INVALID);
    assert_null(r);
    assert_non_null(strstr(ft_last_error(), "ft_variogram_opts"));
    assert_non_null(strstr(ft_last_error(), "FT_*_OPTS_DEFAULT"));

    ft_synth_opts s;
    memset(&s, 0, sizeof s);
    ft_grid *out = NULL;
    assert_int_equal(ft_terrain_synth(8, 8, &s, &out), FT_E_INVALID);
    assert_null(out);
    assert_non_null(strstr(ft_last_error(), "ft_synth_opts"));
    ft_grid_free(g);
}

static void test_a_struct_from_a_newer_header_is_refused(void **state)
{
    (void)state;
    ft_synth_opts s = FT_SYNTH_OPTS_DEFAULT;
    s.struct_size = sizeof s + 16;
    ft_grid *out = NULL;
    assert_int_equal(ft_terrain_synth(8, 8, &s, &out), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "newer"));
    assert_null(out);
}

static void test_null_options_mean_the_defaults(void **state)
{
    (void)state;
    ft_synth_opts s = FT_SYNTH_OPTS_DEFAULT;
    ft_grid *a = NULL, *b = NULL;
    assert_int_equal(ft_terrain_synth(32, 32, NULL, &a), FT_OK);
    assert_int_equal(ft_terrain_synth(32, 32, &s, &b), FT_OK);
    assert_memory_equal(a->z, b->z, 32 * 32 * sizeof *a->z);
    ft_grid_free(a);
    ft_grid_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_default_carries_its_size),
        cmocka_unit_test(test_an_older_caller_gets_defaults_for_the_fields_it_lacks),
        cmocka_unit_test(test_a_zeroed_struct_is_refused_naming_the_type),
        cmocka_unit_test(test_a_struct_from_a_newer_header_is_refused),
        cmocka_unit_test(test_null_options_mean_the_defaults),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
