/* fracterra — tests/unit/test_io_clarke_model.c: the model file of Clarke's scale-based model
 * (ft_io_write_clarke_model / ft_io_read_clarke_model): a written model reads back bit for bit, a model
 * fitted to a real DEM simulates the same surface after a round trip, and a broken file is an error that
 * names the file and the key.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/core.h"
#include "fracterra/io.h"
#include "fracterra/terrain.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"

/* A model whose numbers need all 17 digits (1/3, 0.1 + 0.2) or sit at the ends of the double range. */
static ft_clarke_model *awkward_model(void)
{
    ft_clarke_model *m = ft_clarke_model_create(2);
    assert_non_null(m);
    m->beta0 = 1.0 / 3.0;
    m->beta1 = 0.1 + 0.2;
    m->beta2 = -2.5e-300;
    m->trend_r2 = 0.987654321012345678;
    m->nx = 61;
    m->ny = 87;
    const double gt[6] = {1756638.4999999998, 10.000000000000002, 0.0, 5921918.1, 0.0, -10.0};
    memcpy(m->gt, gt, sizeof gt);
    m->crs_wkt = strdup("LOCAL_CS[\"a \\\"quoted\\\" name\"]");
    m->mean = 130.18726591760299;
    m->sd = 25.832;
    m->valid = 5307;
    m->nodata_filled = 0;
    m->cutoff = 2.5;
    m->taper = 1;
    m->min_wavelength = 4.0;
    m->harmonics[0] = (ft_clarke_harmonic){.k = 1, .l = -2, .a = 7.0 / 9.0, .b = -1e-17, .share = 0.41,
                                           .wavelength = 387.29833462074168, .direction = 26.565051177077986};
    m->harmonics[0].power = m->harmonics[0].a * m->harmonics[0].a + m->harmonics[0].b * m->harmonics[0].b;
    m->harmonics[1] = (ft_clarke_harmonic){.k = 0, .l = 3, .a = 1e300, .b = 2.0, .share = 0.05,
                                           .wavelength = 290.0, .direction = 90.0};
    m->harmonics[1].power = m->harmonics[1].a * m->harmonics[1].a + m->harmonics[1].b * m->harmonics[1].b;
    m->harmonic_share = 0.46;
    m->slope = -2.6180339887498949;
    m->intercept = 4.4;
    m->r2 = 0.8;
    m->stderr_slope = 0.0123;
    m->npairs = 2553;
    m->D = (8.0 - m->slope) / 2.0;
    m->D_clarke_eq8 = 3.0 - m->slope / 2.0;
    m->c = 1.0 / 7.0;
    /* format 2: the measured spectrum, two regimes and their break */
    m->noise = FT_CLARKE_NOISE_SPECTRUM;
    m->nspectrum = 3;
    m->spectrum_wavelength = malloc(3 * sizeof(double));
    m->spectrum_power = malloc(3 * sizeof(double));
    m->spectrum_count = malloc(3 * sizeof(double));
    m->regimes = calloc(2, sizeof *m->regimes);
    m->breaks = malloc(sizeof(double));
    assert_true(m->spectrum_wavelength && m->spectrum_power && m->spectrum_count && m->regimes && m->breaks);
    const double wl[3] = {21.0, 1.0 / 3.0 * 100.0, 610.0}, pw[3] = {0.1 + 0.2, 7e-5, 123456.789}, ct[3] = {
                                                                                                 812, 96, 2};
    memcpy(m->spectrum_wavelength, wl, sizeof wl);
    memcpy(m->spectrum_power, pw, sizeof pw);
    memcpy(m->spectrum_count, ct, sizeof ct);
    m->regimes[0] = (ft_clarke_regime){.wavelength_lo = 21.0, .wavelength_hi = 100.0 / 3.0, .slope = 2.9,
                                       .intercept = -8.6069, .D = 2.55, .r2 = 0.99, .stderr_D = 0.04, .bins = 11};
    m->regimes[1] = (ft_clarke_regime){.wavelength_lo = 100.0 / 3.0, .wavelength_hi = 610.0, .slope = -1.15,
                                       .intercept = 6.77, .D = 4.575, .r2 = 0.9, .stderr_D = 0.08, .bins = 7};
    m->nregimes = 2;
    m->breaks[0] = 1.0 / 3.0 * 101.0;
    return m;
}

/* Every field the file holds, compared exactly (== on doubles: the same value, not a close one). */
static void assert_same_model(const ft_clarke_model *a, const ft_clarke_model *b)
{
    assert_true(a->beta0 == b->beta0 && a->beta1 == b->beta1 && a->beta2 == b->beta2);
    assert_true(a->trend_r2 == b->trend_r2);
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    for (int i = 0; i < 6; i++)
        assert_true(a->gt[i] == b->gt[i]);
    if (a->crs_wkt == NULL)
        assert_null(b->crs_wkt);
    else
        assert_string_equal(a->crs_wkt, b->crs_wkt);
    assert_true(a->mean == b->mean && a->sd == b->sd);
    assert_int_equal(a->valid, b->valid);
    assert_int_equal(a->nodata_filled, b->nodata_filled);
    assert_true(a->cutoff == b->cutoff && a->min_wavelength == b->min_wavelength);
    assert_int_equal(a->taper, b->taper);
    assert_int_equal(a->nharmonics, b->nharmonics);
    for (size_t i = 0; i < a->nharmonics; i++) {
        const ft_clarke_harmonic *x = &a->harmonics[i], *y = &b->harmonics[i];
        assert_int_equal(x->k, y->k);
        assert_int_equal(x->l, y->l);
        assert_true(x->a == y->a && x->b == y->b && x->power == y->power && x->share == y->share);
        assert_true(x->wavelength == y->wavelength && x->direction == y->direction);
    }
    assert_true(a->harmonic_share == b->harmonic_share);
    assert_true(a->slope == b->slope && a->intercept == b->intercept && a->r2 == b->r2);
    assert_true(a->stderr_slope == b->stderr_slope);
    assert_int_equal(a->npairs, b->npairs);
    assert_true(a->D == b->D && a->D_clarke_eq8 == b->D_clarke_eq8 && a->c == b->c);
    assert_int_equal(a->noise, b->noise);
    assert_int_equal(a->nspectrum, b->nspectrum);
    for (size_t i = 0; i < a->nspectrum; i++)
        assert_true(a->spectrum_wavelength[i] == b->spectrum_wavelength[i] &&
                    a->spectrum_power[i] == b->spectrum_power[i] && a->spectrum_count[i] == b->spectrum_count[i]);
    assert_int_equal(a->nregimes, b->nregimes);
    for (size_t i = 0; i < a->nregimes; i++) {
        const ft_clarke_regime *x = &a->regimes[i], *y = &b->regimes[i];
        assert_true(x->wavelength_lo == y->wavelength_lo && x->wavelength_hi == y->wavelength_hi);
        assert_true(x->slope == y->slope && x->intercept == y->intercept && x->D == y->D && x->r2 == y->r2);
        assert_true(x->stderr_D == y->stderr_D);
        assert_int_equal(x->bins, y->bins);
        if (i + 1 < a->nregimes)
            assert_true(a->breaks[i] == b->breaks[i]);
    }
}

static void test_round_trip_is_exact(void **state)
{
    (void)state;
    ft_clarke_model *m = awkward_model(), *back = NULL;
    const char *path = ft_test_tmp("model.json");
    assert_int_equal(ft_io_write_clarke_model(path, m), FT_OK);
    assert_int_equal(ft_io_read_clarke_model(path, &back), FT_OK);
    assert_same_model(m, back);
    assert_int_equal(ft_test_dir_count(), 1); /* no temporary left beside it */
    ft_clarke_model_free(back);
    ft_clarke_model_free(m);
}

/* The text of ft_io_clarke_model_to_json is the file's: the same keys a reader of --json expects. */
static void test_json_text(void **state)
{
    (void)state;
    ft_clarke_model *m = awkward_model();
    char *text = ft_io_clarke_model_to_json(m);
    assert_non_null(text);
    assert_non_null(strstr(text, "\"model\": \"clarke1987\""));
    assert_non_null(strstr(text, "\"method\": \"clarke\""));
    assert_non_null(strstr(text, "0.30000000000000004")); /* 0.1 + 0.2, all 17 digits */
    assert_non_null(strstr(text, "\"cutoff\": 2.5"));       /* not 2.5000000000000000 */
    free(text);
    ft_clarke_model_free(m);
}

/* A model fitted to the volcano simulates the same surface (same seed) before and after a round trip. */
static void test_fitted_model_simulates_the_same(void **state)
{
    (void)state;
    ft_grid *dem = NULL, *a = NULL, *b = NULL;
    assert_int_equal(ft_io_read_grid(VOLCANO, NULL, &dem), FT_OK);
    ft_clarke_model *m = NULL, *back = NULL;
    assert_int_equal(ft_clarke_fit(dem, NULL, &m), FT_OK);
    const char *path = ft_test_tmp("volcano.json");
    assert_int_equal(ft_io_write_clarke_model(path, m), FT_OK);
    assert_int_equal(ft_io_read_clarke_model(path, &back), FT_OK);
    assert_same_model(m, back);
    ft_clarke_sim_opts so = FT_CLARKE_SIM_OPTS_DEFAULT;
    so.seed = 7;
    assert_int_equal(ft_clarke_simulate(m, &so, &a), FT_OK);
    assert_int_equal(ft_clarke_simulate(back, &so, &b), FT_OK);
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    assert_memory_equal(a->z, b->z, a->nx * a->ny * sizeof a->z[0]);
    ft_grid_free(a);
    ft_grid_free(b);
    ft_clarke_model_free(back);
    ft_clarke_model_free(m);
    ft_grid_free(dem);
}

/* Writes the model, replaces `from` by `to` in its text, and expects reading it to fail with code and needle. */
static void expect_broken(const char *from, const char *to, int code, const char *needle)
{
    ft_clarke_model *m = awkward_model(), *back = NULL;
    char *text = ft_io_clarke_model_to_json(m);
    assert_non_null(text);
    char *at = strstr(text, from);
    assert_non_null(at);
    size_t n = strlen(text) - strlen(from) + strlen(to) + 1;
    char *edited = malloc(n);
    assert_non_null(edited);
    snprintf(edited, n, "%.*s%s%s", (int)(at - text), text, to, at + strlen(from));
    const char *path = ft_test_tmp_text("broken.json", edited);
    assert_int_equal(ft_io_read_clarke_model(path, &back), code);
    assert_null(back);
    assert_non_null(strstr(ft_last_error(), "broken.json"));
    if (strstr(ft_last_error(), needle) == NULL)
        fail_msg("'%s' does not name '%s'", ft_last_error(), needle);
    free(edited);
    free(text);
    ft_clarke_model_free(m);
}

/* A file without "format_version" (format 1, written before the measured spectrum) still loads, as Clarke's
 * power law; a spectrum whose wavelengths do not increase reads, but the simulation refuses it by name. */
static void test_format_1_and_bad_spectrum(void **state)
{
    (void)state;
    ft_clarke_model *m = awkward_model(), *back = NULL;
    char *text = ft_io_clarke_model_to_json(m);
    assert_non_null(text);
    char *v = strstr(text, "\"format_version\""), *d = strstr(text, "\"D\""), *r = strstr(text, "\"regimes\"");
    assert_true(v && d && r && v < d && d < r);
    size_t n = strlen(text) + 16;
    char *old = malloc(n);
    assert_non_null(old);
    snprintf(old, n, "%.*s%.*s\"x\": 0}", (int)(v - text), text, (int)(r - d), d);
    assert_int_equal(ft_io_read_clarke_model(ft_test_tmp_text("v1.json", old), &back), FT_OK);
    assert_int_equal(back->noise, FT_CLARKE_NOISE_POWER_LAW);
    assert_int_equal(back->nspectrum, 0);
    assert_int_equal(back->nregimes, 0);
    assert_true(back->D == m->D && back->slope == m->slope);
    ft_clarke_model_free(back);
    back = NULL;

    m->spectrum_wavelength[1] = 10.0; /* below the first ring's 21 */
    assert_int_equal(ft_io_write_clarke_model(ft_test_tmp("bad.json"), m), FT_OK);
    assert_int_equal(ft_io_read_clarke_model(ft_test_tmp("bad.json"), &back), FT_OK);
    ft_grid *g = NULL;
    back->harmonics[1].a = 1.0; /* the awkward 1e300 would be its own error */
    assert_int_equal(ft_clarke_simulate(back, NULL, &g), FT_E_INVALID);
    assert_null(g);
    if (strstr(ft_last_error(), "spectrum wavelength 1") == NULL)
        fail_msg("'%s' does not name the spectrum wavelength", ft_last_error());
    free(old);
    free(text);
    ft_clarke_model_free(back);
    ft_clarke_model_free(m);
}

static void test_broken_files(void **state)
{
    (void)state;
    expect_broken("\"beta1\"", "\"beta_one\"", FT_E_FORMAT, "trend.beta1");
    expect_broken("\"clarke1987\"", "\"clarke1988\"", FT_E_FORMAT, "clarke1988");
    expect_broken("\"size\": [", "\"size\": [ -5, ", FT_E_FORMAT, "grid.size");
    expect_broken("\"regression\"", "\"regression\": 1, \"x\"", FT_E_FORMAT, "regression");
    expect_broken("\"harmonics\"", "", FT_E_FORMAT, "not valid JSON");
    expect_broken("\"format_version\": 2", "\"format_version\": 3", FT_E_FORMAT, "format_version");
    expect_broken("\"noise\": \"spectrum\"", "\"noise\": \"pink\"", FT_E_FORMAT, "pink");
    expect_broken("\"waves\": [", "\"waves\": [ 1,", FT_E_FORMAT, "spectrum.waves");
    expect_broken("\"spectrum\": {", "\"spectrum_\": {", FT_E_FORMAT, "\"spectrum\"");
    expect_broken("\"breaks\": [", "\"breaks\": [ 5,", FT_E_FORMAT, "breaks");
    ft_clarke_model *back = NULL;
    assert_int_equal(ft_io_read_clarke_model(ft_test_tmp_text("empty.json", " \n"), &back), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "empty"));
    assert_int_equal(ft_io_read_clarke_model(ft_test_tmp_text("cut.json", "{\"model\": \"clarke"), &back),
                     FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "truncated"));
    assert_int_equal(ft_io_read_clarke_model(ft_test_tmp("absent.json"), &back), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "absent.json"));
    assert_null(back);
}

/* A model written into a folder that does not exist: FT_E_IO naming it, nothing written. */
static void test_write_failure_leaves_nothing(void **state)
{
    (void)state;
    ft_clarke_model *m = awkward_model();
    assert_int_equal(ft_io_write_clarke_model(ft_test_tmp("no/such/folder/model.json"), m), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "folder"));
    assert_int_equal(ft_test_dir_count(), 0);
    assert_int_equal(ft_io_write_clarke_model(ft_test_tmp("m.json"), NULL), FT_E_INVALID);
    ft_clarke_model_free(m);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip_is_exact),
        cmocka_unit_test(test_json_text),
        cmocka_unit_test(test_fitted_model_simulates_the_same),
        cmocka_unit_test(test_broken_files),
        cmocka_unit_test(test_format_1_and_bad_spectrum),
        cmocka_unit_test(test_write_failure_leaves_nothing),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
