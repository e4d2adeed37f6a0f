/* fracterra — the file hillshade (ft_io_hillshade, the library's engine ft_render_hillshade) against GDAL's
 * own `gdaldem hillshade -compute_edges` as an oracle: every cell within 1 grey level and the same nodata
 * cells, on a projected DEM with nodata, a DEM in degrees (explicit scale, and the automatic scale equal
 * to gdaldem given the metres of a degree of latitude at the centre) and a volcano under several lights.
 * Skipped where the gdaldem program is not on PATH.
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
#include <unistd.h>

#include <cmocka.h>

#include "fracterra/io.h"
#include "fracterra/render.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_utm32n.tif"      /* Int16, nodata */
#define LUX_DEGREES FT_TEST_DATA "/dem_luxembourg_terra_30s.tif" /* WGS 84, 30" cells, nodata */

static int have_gdaldem(void)
{
    return system("command -v gdaldem >/dev/null 2>&1") == 0;
}

static ft_grid *read_whole(const char *path)
{
    ft_grid *g = NULL;
    if (ft_io_read_grid(path, NULL, &g) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
    return g;
}

/* ft_io_hillshade with o and gdaldem with the same light, z factor and scale (gdaldem_scale) agree cell by
 * cell within `tol` grey levels and have the same nodata cells; returns the largest difference. */
static int compare_with_gdaldem(const char *dem, const ft_io_hillshade_opts *o, double gdaldem_scale)
{
    const char *ours = ft_test_tmp("ours.tif"), *theirs = ft_test_tmp("gdaldem.tif");
    unlink(ours);
    unlink(theirs);
    if (ft_io_hillshade(dem, ours, o) != FT_OK)
        fail_msg("%s: %s", dem, ft_last_error());
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "gdaldem hillshade -q -compute_edges -az %.17g -alt %.17g -z %.17g -s %.17g '%s' '%s'",
             o->azimuth, o->altitude, o->z_factor, gdaldem_scale, dem, theirs);
    assert_int_equal(system(cmd), 0);
    ft_grid *a = read_whole(ours), *b = read_whole(theirs);
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    int worst = 0;
    size_t lit = 0;
    for (size_t r = 0; r < a->ny; r++)
        for (size_t c = 0; c < a->nx; c++) {
            int va = ft_grid_is_valid(a, c, r), vb = ft_grid_is_valid(b, c, r);
            if (va != vb)
                fail_msg("%s: cell (%zu, %zu) is %s here and %s in gdaldem's", dem, c, r, va ? "valid" : "nodata",
                         vb ? "valid" : "nodata");
            if (!va)
                continue;
            int d = abs((int)a->z[r * a->nx + c] - (int)b->z[r * a->nx + c]);
            worst = d > worst ? d : worst;
            lit += a->z[r * a->nx + c] > 1.0f;
        }
    assert_true(lit > a->nx * a->ny / 4); /* a real relief, not a blank image */
    ft_grid_free(a);
    ft_grid_free(b);
    unlink(ours);
    unlink(theirs);
    return worst;
}

static void test_projected_and_volcano(void **state)
{
    (void)state;
    if (!have_gdaldem())
        skip();
    ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT;
    assert_true(compare_with_gdaldem(LUXEMBOURG, &o, 1.0) <= 1);
    assert_true(compare_with_gdaldem(VOLCANO, &o, 1.0) <= 1);
    const double lights[][3] = {{135.0, 30.0, 2.0}, {0.0, 60.0, 0.5}, {270.0, 10.0, 3.0}, {360.0, 90.0, 1.0}};
    for (size_t k = 0; k < sizeof lights / sizeof lights[0]; k++) {
        o.azimuth = lights[k][0];
        o.altitude = lights[k][1];
        o.z_factor = lights[k][2];
        assert_true(compare_with_gdaldem(VOLCANO, &o, 1.0) <= 1);
    }
    o = (ft_io_hillshade_opts)FT_IO_HILLSHADE_OPTS_DEFAULT;
    o.scale = 2.5; /* scale divides both cell sizes, as gdaldem's -s */
    assert_true(compare_with_gdaldem(VOLCANO, &o, 2.5) <= 1);
}

/* A DEM in degrees: with an explicit scale both take it; the automatic scale is the metres of a degree of
 * latitude on WGS 84 at the DEM's centre (49.8 N: 111,197 m by the meridian-arc formula), which gdaldem
 * matches when given that figure. */
static void test_degrees(void **state)
{
    (void)state;
    if (!have_gdaldem())
        skip();
    ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT;
    o.scale = 111120.0;
    assert_true(compare_with_gdaldem(LUX_DEGREES, &o, 111120.0) <= 1);
    ft_grid *g = read_whole(LUX_DEGREES);
    double lat = g->gt[3] + 0.5 * (double)g->ny * g->gt[5];
    ft_grid_free(g);
    /* WGS 84 meridian arc per degree: (pi/180) a (1 - e^2) / (1 - e^2 sin^2 lat)^1.5 */
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f), s = sin(lat * M_PI / 180.0);
    double per_lat = M_PI / 180.0 * a * (1.0 - e2) / pow(1.0 - e2 * s * s, 1.5);
    assert_true(per_lat > 111100.0 && per_lat < 111300.0);
    o.scale = 0.0;
    double used = 0.0; /* the scale the CLI reports */
    assert_int_equal(ft_io_hillshade_scale(LUX_DEGREES, &o, &used), FT_OK);
    assert_true(fabs(used / per_lat - 1.0) < 1e-9);
    assert_int_equal(ft_io_hillshade_scale(LUXEMBOURG, NULL, &used), FT_OK);
    assert_true(used == 1.0);
    ft_io_hillshade_opts given = o;
    given.scale = 2.5;
    assert_int_equal(ft_io_hillshade_scale(LUX_DEGREES, &given, &used), FT_OK);
    assert_true(used == 2.5);
    assert_int_equal(ft_io_hillshade_scale(FT_TEST_DATA "/no_such.tif", NULL, &used), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "no_such.tif"));
    assert_true(compare_with_gdaldem(LUX_DEGREES, &o, per_lat) <= 1);
    /* the oracle can fail: 1 instead of the metres of a degree is another image */
    assert_true(compare_with_gdaldem(LUX_DEGREES, &o, 1.0) > 1);
}

/* A DEM of 2048 x 1100 cells is streamed in three chunks of whole blocks (512, 512 and 76 rows; the
 * chunk is about 1 M cells): nodata at and beside the chunk boundaries (rows 511/512, 1023), a first chunk
 * without a mask and a last one without nodata after a masked one, a NaN cell, nodata on the edges. The
 * GeoTIFF (streamed into the dataset) and the PNG (one image, CreateCopy) hold, cell for cell, the
 * engine's shade of the whole grid in gdaldem's bytes (1 + 254 s / 255 rounded, 0 = nodata). */
/* A DEM whose 2-row chunk (22 bytes x 20000 x 4 rows of window) exceeds the memory bound is refused, naming
 * --max-memory, and no output is left; 1 MB still holds its decoded block (256 x 256 Float32). */
static void test_stream_beyond_memory_refused(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(20000, 3);
    assert_non_null(g);
    g->gt[1] = 10.0;
    g->gt[5] = -10.0;
    for (size_t i = 0; i < g->nx * g->ny; i++)
        g->z[i] = (float)(i % 97);
    const char *dem = ft_test_tmp("wide_dem.tif"), *out = ft_test_tmp("wide_shade.tif");
    assert_int_equal(ft_io_write_grid(dem, g, NULL), FT_OK);
    ft_grid_free(g);
    ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT;
    ft_set_memory_limit((size_t)1 << 20);
    int rc = ft_io_hillshade(dem, out, &o);
    ft_set_memory_limit(0);
    assert_int_equal(rc, FT_E_NOMEM);
    assert_non_null(strstr(ft_last_error(), "chunks of 2 rows"));
    assert_non_null(strstr(ft_last_error(), "--max-memory"));
    assert_int_equal(access(out, F_OK), -1);
    ft_set_memory_limit((size_t)2 << 20); /* 1.76 MB: shaded */
    rc = ft_io_hillshade(dem, out, &o);
    ft_set_memory_limit(0);
    if (rc != FT_OK)
        fail_msg("%s", ft_last_error());
}

static void test_streamed_equals_whole_engine(void **state)
{
    (void)state;
    const size_t nx = 2048, ny = 1100;
    ft_grid *g = ft_grid_create(nx, ny);
    assert_non_null(g);
    g->gt[1] = 10.0;
    g->gt[5] = -10.0;
    uint64_t s = 12345;
    for (size_t r = 0; r < ny; r++)
        for (size_t c = 0; c < nx; c++) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            double noise = (double)(s >> 11) / 9007199254740992.0 - 0.5;
            g->z[r * nx + c] = (float)(300.0 * sin(c / 97.0) * cos(r / 61.0) + 40.0 * sin(c / 7.0 + r / 11.0) + 5.0 * noise);
        }
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    const size_t holes[][2] = {{100, 511}, {101, 512}, {0, 512}, {2047, 513}, {700, 1023}, {701, 1022}, {5, 0}};
    for (size_t k = 0; k < sizeof holes / sizeof holes[0]; k++)
        g->mask[holes[k][1] * nx + holes[k][0]] = 0;
    for (size_t c = 1000; c < 1040; c++) /* a band of nodata across the boundary of the first two chunks */
        for (size_t r = 509; r < 515; r++)
            g->mask[r * nx + c] = 0;
    g->z[800 * nx + 900] = NAN;
    g->has_nodata = 1;
    g->nodata_value = -32768.0;
    const char *dem = ft_test_tmp("stream_dem.tif");
    assert_int_equal(ft_io_write_grid(dem, g, NULL), FT_OK);
    ft_grid_free(g);

    ft_grid *whole = read_whole(dem), *sh = NULL;
    ft_hillshade_opts ro = FT_HILLSHADE_OPTS_DEFAULT;
    assert_int_equal(ft_render_hillshade(whole, &ro, &sh), FT_OK);
    /* whole blocks of rows; one image; chunks of 37 rows under a memory bound of 22 bytes x 2048 x (37 + 2) */
    const char *outs[] = {ft_test_tmp("stream_shade.tif"), ft_test_tmp("stream_shade.png"),
                          ft_test_tmp("stream_bound.tif")};
    for (size_t k = 0; k < 3; k++) {
        unlink(outs[k]);
        ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT;
        ft_set_memory_limit(k == 2 ? 22 * nx * (37 + 2) + 1000 : 0);
        int rc = ft_io_hillshade(dem, outs[k], &o);
        ft_set_memory_limit(0);
        if (rc != FT_OK)
            fail_msg("%s: %s", outs[k], ft_last_error());
        ft_grid *b = read_whole(outs[k]);
        assert_int_equal(b->nx, nx);
        assert_int_equal(b->ny, ny);
        size_t nodata = 0;
        for (size_t i = 0; i < nx * ny; i++) {
            int valid = sh->mask == NULL || sh->mask[i];
            double want = valid ? floor(1.0 + 254.0 * (double)sh->z[i] / 255.0 + 0.5) : 0.0;
            double got = ft_grid_is_valid(b, i % nx, i / nx) ? (double)b->z[i] : 0.0;
            if (got != want)
                fail_msg("%s: cell (%zu, %zu) is %g, the whole grid's engine gives %g", outs[k], i % nx, i / nx, got,
                         want);
            nodata += !valid;
        }
        assert_int_equal(nodata, 7 + 40 * 6 + 1);
        ft_grid_free(b);
    }
    ft_grid_free(sh);
    ft_grid_free(whole);
    if (have_gdaldem()) {
        ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT;
        assert_true(compare_with_gdaldem(dem, &o, 1.0) <= 1);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_projected_and_volcano),
        cmocka_unit_test(test_degrees),
        cmocka_unit_test(test_streamed_equals_whole_engine),
        cmocka_unit_test(test_stream_beyond_memory_refused),
    };
    return cmocka_run_group_tests(tests, ft_test_dir_setup, ft_test_dir_teardown);
}
