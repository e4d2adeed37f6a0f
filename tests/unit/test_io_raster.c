/* fracterra — tests of io grid reading and writing (GeoTIFF, Arc/Info ASCII, nodata, CRS).
 * Facts checked against tests/data/README.md.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <dirent.h>
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
#include <gdal.h>
#include <ogr_srs_api.h>

#include "fracterra/io.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"
#define STATES FT_TEST_DATA "/dcw_us_states_small_albers5070.geojson"

static ft_grid *read_ok(const char *path, int band)
{
    ft_grid *g = NULL;
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    o.band = band;
    if (ft_io_read_grid(path, &o, &g) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
    return g;
}

static void write_ok(const char *path, const ft_grid *g, const ft_write_grid_opts *o)
{
    if (ft_io_write_grid(path, g, o) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
}

/* Same size, geotransform, CRS, nodata, mask and valid cells. */
static void assert_grids_equal(const ft_grid *a, const ft_grid *b, double tol)
{
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    for (int i = 0; i < 6; i++)
        assert_true(a->gt[i] == b->gt[i]);
    OGRSpatialReferenceH sa = OSRNewSpatialReference(a->crs_wkt), sb = OSRNewSpatialReference(b->crs_wkt);
    assert_true(OSRIsSame(sa, sb));
    OSRDestroySpatialReference(sa);
    OSRDestroySpatialReference(sb);
    assert_int_equal(a->has_nodata, b->has_nodata);
    if (a->has_nodata)
        assert_true(a->nodata_value == b->nodata_value);
    assert_int_equal(ft_grid_count_valid(a), ft_grid_count_valid(b));
    for (size_t r = 0; r < a->ny; r++)
        for (size_t c = 0; c < a->nx; c++) {
            assert_int_equal(ft_grid_is_valid(a, c, r), ft_grid_is_valid(b, c, r));
            if (ft_grid_is_valid(a, c, r))
                assert_true(fabs(a->z[r * a->nx + c] - b->z[r * b->nx + c]) <= tol);
        }
}

static GDALDataType file_type(const char *path, double *nodata, int *has_nodata)
{
    GDALDatasetH ds = GDALOpen(path, GA_ReadOnly);
    assert_non_null(ds);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    GDALDataType t = GDALGetRasterDataType(b);
    *nodata = GDALGetRasterNoDataValue(b, has_nodata);
    GDALClose(ds);
    return t;
}

/* ---- reading ----------------------------------------------------------------------------------- */

static void test_read_volcano(void **state)
{
    (void)state;
    ft_grid *g = read_ok(VOLCANO, 1);
    assert_int_equal(g->nx, 61);
    assert_int_equal(g->ny, 87);
    assert_null(g->mask);
    assert_int_equal(g->has_nodata, 0);
    assert_int_equal(ft_grid_count_valid(g), 61 * 87);
    assert_true(g->gt[1] == 10.0 && g->gt[5] == -10.0);
    ft_test_assert_crs_epsg(g->crs_wkt, 27200);
    double lo, hi;
    assert_int_equal(ft_grid_minmax(g, &lo, &hi), FT_OK);
    /* R's volcano heights run from 94 to 195 m */
    assert_true(lo == 94.0 && hi == 195.0);
    ft_grid_free(g);
}

static void test_read_luxembourg(void **state)
{
    (void)state;
    ft_grid *g = read_ok(LUXEMBOURG, 1);
    assert_int_equal(g->nx, 95);
    assert_int_equal(g->ny, 90);
    assert_int_equal(g->has_nodata, 1);
    assert_true(g->nodata_value == -32768.0);
    assert_non_null(g->mask);
    assert_int_equal(ft_grid_count_valid(g), 4608);
    ft_test_assert_crs_epsg(g->crs_wkt, 4326);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        assert_true((g->mask[i] != 0) == (g->z[i] != -32768.0f));
    ft_grid_free(g);
}

/* ---- round trips ------------------------------------------------------------------------------- */

static void test_round_trip_geotiff(void **state)
{
    (void)state;
    const char *inputs[] = {VOLCANO, LUXEMBOURG};
    for (int k = 0; k < 2; k++) {
        ft_grid *a = read_ok(inputs[k], 1);
        const char *path = ft_test_tmp("rt.tif");
        write_ok(path, a, NULL);
        ft_grid *b = read_ok(path, 1);
        assert_grids_equal(a, b, 0.0);
        double nd;
        int has;
        assert_int_equal(file_type(path, &nd, &has), GDT_Float32);
        assert_int_equal(has, k == 1);
        ft_grid_free(b);
        ft_grid_free(a);
    }
    /* the Luxembourg DEM back in its own Int16 type */
    ft_grid *a = read_ok(LUXEMBOURG, 1);
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.type = GDT_Int16;
    const char *path = ft_test_tmp("lux16.tiff");
    write_ok(path, a, &o);
    double nd;
    int has;
    assert_int_equal(file_type(path, &nd, &has), GDT_Int16);
    assert_true(has && nd == -32768.0);
    ft_grid *b = read_ok(path, 1);
    assert_grids_equal(a, b, 0.0);
    ft_grid_free(b);
    ft_grid_free(a);
    assert_int_equal(ft_test_dir_count(), 2);
}

static void test_round_trip_ascii(void **state)
{
    (void)state;
    ft_grid *a = read_ok(LUXEMBOURG, 1);
    const char *path = ft_test_tmp("lux.asc");
    write_ok(path, a, NULL);
    assert_int_equal(access(ft_test_tmp("lux.prj"), F_OK), 0);
    ft_grid *b = read_ok(path, 1);
    assert_int_equal(ft_grid_count_valid(b), 4608);
    assert_true(b->has_nodata && b->nodata_value == -32768.0);
    for (size_t i = 0; i < a->nx * a->ny; i++)
        if (a->mask[i])
            assert_true(a->z[i] == b->z[i]);
    for (int i = 0; i < 6; i++)
        assert_true(fabs(a->gt[i] - b->gt[i]) < 1e-9);
    ft_grid_free(b);
    ft_grid_free(a);
    /* no temporary left behind, only the grid and its companions */
    DIR *d = opendir(ft_test_dir());
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        assert_null(strstr(e->d_name, "ft-tmp"));
    closedir(d);
}

/* ---- nodata ------------------------------------------------------------------------------------ */

static void test_nodata_rules(void **state)
{
    (void)state;
    ft_grid *g = ft_grid_create(4, 3);
    for (size_t i = 0; i < 12; i++)
        g->z[i] = (float)i;
    g->z[5] = NAN;           /* unmasked NaN: nodata on the way out */
    ft_grid_ensure_mask(g);
    g->mask[0] = 0;

    const char *path = ft_test_tmp("f.tif");
    write_ok(path, g, NULL);
    double nd;
    int has;
    assert_int_equal(file_type(path, &nd, &has), GDT_Float32);
    assert_true(has && isnan(nd));
    ft_grid *b = read_ok(path, 1);
    assert_int_equal(ft_grid_count_valid(b), 10);
    assert_false(ft_grid_is_valid(b, 0, 0));
    assert_false(ft_grid_is_valid(b, 1, 1));
    assert_true(b->z[11] == 11.0f);
    ft_grid_free(b);

    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.type = GDT_Int16;
    path = ft_test_tmp("i.tif");
    write_ok(path, g, &o);
    file_type(path, &nd, &has);
    assert_true(has && nd == -9999.0);
    b = read_ok(path, 1);
    assert_int_equal(ft_grid_count_valid(b), 10);
    ft_grid_free(b);

    o.type = GDT_Byte;
    path = ft_test_tmp("b.tif");
    write_ok(path, g, &o);
    file_type(path, &nd, &has);
    assert_true(has && nd == 255.0);
    ft_grid_free(g);

    /* an all-nodata grid reads fine; callers see 0 valid cells */
    g = ft_grid_create(3, 3);
    ft_grid_ensure_mask(g);
    memset(g->mask, 0, 9);
    g->has_nodata = 1;
    g->nodata_value = -1;
    path = ft_test_tmp("none.tif");
    write_ok(path, g, NULL);
    b = read_ok(path, 1);
    assert_int_equal(ft_grid_count_valid(b), 0);
    assert_true(b->nodata_value == -1.0);
    ft_grid_free(b);
    ft_grid_free(g);

    /* Float32 rows go to GDAL as floats in chunks of about 2^20 cells: straight from the grid where a chunk
     * has no invalid cell (the first here), through a copy with the nodata value where it has (the second) */
    g = ft_grid_create(1100, 1000);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        g->z[i] = (float)i * 0.37f - 1234.5f;
    ft_grid_ensure_mask(g);
    g->mask[1050000] = 0;
    g->z[1060000] = INFINITY;
    g->has_nodata = 1;
    g->nodata_value = -9999.0;
    path = ft_test_tmp("chunks.tif");
    write_ok(path, g, NULL);
    b = read_ok(path, 1);
    assert_int_equal(ft_grid_count_valid(b), g->nx * g->ny - 2);
    assert_true(b->nodata_value == -9999.0);
    assert_false(ft_grid_is_valid(b, 1050000 % 1100, 1050000 / 1100));
    assert_false(ft_grid_is_valid(b, 1060000 % 1100, 1060000 / 1100));
    for (size_t i = 0; i < g->nx * g->ny; i++)
        if (i != 1050000 && i != 1060000 && b->z[i] != g->z[i])
            fail_msg("cell %zu: wrote %g, read %g", i, (double)g->z[i], (double)b->z[i]);
    ft_grid_free(b);
    ft_grid_free(g);

    /* no geotransform in the file: the default one */
    g = ft_grid_create(2, 2);
    path = ft_test_tmp("plain.tif");
    write_ok(path, g, NULL);
    b = read_ok(path, 1);
    assert_true(b->gt[0] == 0 && b->gt[1] == 1 && b->gt[5] == 1 && b->gt[3] == 0);
    assert_null(b->crs_wkt);
    assert_int_equal(b->has_nodata, 0);
    ft_grid_free(b);
    ft_grid_free(g);
}

/* ---- summaries: strip by strip, equal to the read grid's count and range -------------------------- */

static void assert_summary_of(const char *path, int band)
{
    ft_grid *g = read_ok(path, band);
    ft_grid_summary s;
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    o.band = band;
    if (ft_io_summarize_grid(path, &o, &s) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
    assert_int_equal(s.header.nx, g->nx);
    assert_int_equal(s.header.ny, g->ny);
    assert_null(s.header.z);
    assert_null(s.header.mask);
    for (int i = 0; i < 6; i++)
        assert_true(s.header.gt[i] == g->gt[i]);
    assert_true((s.header.crs_wkt == NULL) == (g->crs_wkt == NULL));
    if (g->crs_wkt != NULL)
        assert_string_equal(s.header.crs_wkt, g->crs_wkt);
    assert_int_equal(s.header.has_nodata, g->has_nodata);
    assert_true(s.header.nodata_value == g->nodata_value);
    assert_int_equal(s.valid, ft_grid_count_valid(g));
    double lo, hi;
    if (ft_grid_minmax(g, &lo, &hi) == FT_OK) {
        assert_true(s.zmin == lo);
        assert_true(s.zmax == hi);
    } else {
        assert_int_equal(s.valid, 0);
        assert_true(isnan(s.zmin) && isnan(s.zmax));
    }
    ft_grid_summary_clear(&s);
    assert_null(s.header.crs_wkt);
    ft_grid_free(g);
}

static void test_summary(void **state)
{
    (void)state;
    assert_summary_of(VOLCANO, 1);
    assert_summary_of(LUXEMBOURG, 1);
    /* 1500 x 1400 cells: several strips of about 1 M cells; nodata and NaN cells in the first and the last
     * strip, the extremes in the last one, so that a strip lost or counted twice shows */
    ft_grid *g = ft_grid_create(1500, 1400);
    ft_grid_ensure_mask(g);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        g->z[i] = (float)((i * 7919) % 10007) * 0.25f;
    g->mask[3] = 0;
    g->mask[g->nx * g->ny - 2] = 0;
    g->z[10] = NAN;
    g->z[g->nx * 1399 + 5] = -123.5f;
    g->z[g->nx * 1399 + 6] = 9999.75f;
    g->has_nodata = 1;
    g->nodata_value = -32768.0;
    const char *path = ft_test_tmp("strips.tif");
    write_ok(path, g, NULL);
    assert_summary_of(path, 1);
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.type = GDT_Int16; /* nodata compared in the band's own type */
    path = ft_test_tmp("strips16.tif");
    write_ok(path, g, &o);
    assert_summary_of(path, 1);
    /* all nodata: 0 valid, NaN range */
    memset(g->mask, 0, g->nx * g->ny);
    path = ft_test_tmp("strips_none.tif");
    write_ok(path, g, NULL);
    assert_summary_of(path, 1);
    ft_grid_free(g);

    ft_grid_summary s;
    ft_read_grid_opts bo = FT_READ_GRID_OPTS_DEFAULT;
    bo.band = 2;
    assert_int_equal(ft_io_summarize_grid(VOLCANO, &bo, &s), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "band 2"));
    assert_null(s.header.crs_wkt);
    assert_int_equal(ft_io_summarize_grid("/tmp/ft-missing-file.tif", NULL, &s), FT_E_IO);
    assert_int_equal(ft_io_summarize_grid(STATES, NULL, &s), FT_E_FORMAT);
}

/* ---- failures ---------------------------------------------------------------------------------- */

static void test_bad_inputs(void **state)
{
    (void)state;
    ft_grid *g = NULL;
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    assert_int_equal(ft_io_read_grid("/tmp/ft-missing-file.tif", &o, &g), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "cannot open '/tmp/ft-missing-file.tif'"));
    assert_int_equal(ft_io_read_grid(STATES, &o, &g), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "is a vector dataset, not a raster"));
    o.band = 2;
    assert_int_equal(ft_io_read_grid(VOLCANO, &o, &g), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "band 2"));
    assert_non_null(strstr(ft_last_error(), "1 band"));
    o.band = 0;
    assert_int_equal(ft_io_read_grid(VOLCANO, &o, &g), FT_E_FORMAT);
    assert_null(g);
    ft_test_put_text(ft_test_tmp("junk.tif"), "not a tiff");
    assert_int_equal(ft_io_read_grid(ft_test_tmp("junk.tif"), NULL, &g), FT_E_FORMAT);
}

static void test_write_failures_leave_nothing(void **state)
{
    (void)state;
    ft_grid *g = read_ok(VOLCANO, 1);
    assert_int_equal(ft_io_write_grid("/tmp/ft-no-such-folder-xyz/a.tif", g, NULL), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "/tmp/ft-no-such-folder-xyz"));
    assert_int_equal(access("/tmp/ft-no-such-folder-xyz", F_OK), -1);

    /* GTiff creates the file, then refuses the options: the temporary is removed */
    const char *const bad[] = {"PHOTOMETRIC=YCBCR", NULL};
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.co = bad;
    assert_int_equal(ft_io_write_grid(ft_test_tmp("bad.tif"), g, &o), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "bad.tif"));
    assert_int_equal(ft_test_dir_count(), 0);

    /* an existing file survives a failed overwrite */
    write_ok(ft_test_tmp("keep.tif"), g, NULL);
    assert_int_equal(ft_io_write_grid(ft_test_tmp("keep.tif"), g, &o), FT_E_IO);
    assert_int_equal(ft_test_dir_count(), 1);
    ft_grid *b = read_ok(ft_test_tmp("keep.tif"), 1);
    assert_grids_equal(g, b, 0.0);
    ft_grid_free(b);

    o.co = NULL;
    o.type = 9999;
    assert_int_equal(ft_io_write_grid(ft_test_tmp("t.tif"), g, &o), FT_E_INVALID);
    o.type = GDT_CFloat32;
    assert_int_equal(ft_io_write_grid(ft_test_tmp("t.tif"), g, &o), FT_E_UNSUPPORTED);
    o.type = 0;
    assert_int_equal(ft_io_write_grid(ft_test_tmp("t.unknownext"), g, &o), FT_E_FORMAT);
    o.driver = "NoSuchDriver";
    assert_int_equal(ft_io_write_grid(ft_test_tmp("t.tif"), g, &o), FT_E_FORMAT);
    assert_int_equal(ft_test_dir_count(), 1);
    ft_grid_free(g);
}

static void test_driver_choice(void **state)
{
    (void)state;
    ft_grid *g = read_ok(VOLCANO, 1);
    const char *path = ft_test_tmp("noext");
    write_ok(path, g, NULL);
    GDALDatasetH ds = GDALOpen(path, GA_ReadOnly);
    assert_non_null(ds);
    assert_string_equal(GDALGetDriverShortName(GDALGetDatasetDriver(ds)), "GTiff");
    GDALClose(ds);
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.driver = "AAIGrid";
    path = ft_test_tmp("forced.txt");
    write_ok(path, g, &o);
    ft_grid *b = read_ok(path, 1);
    assert_int_equal(ft_grid_count_valid(b), 61 * 87);
    assert_true(b->z[100] == g->z[100]);
    ft_grid_free(b);
    path = ft_test_tmp("v.img");
    write_ok(path, g, NULL); /* Erdas Imagine, found by its extension */
    b = read_ok(path, 1);
    assert_true(b->z[7] == g->z[7]);
    assert_grids_equal(g, b, 0.0);
    ft_grid_free(b);
    /* a format that cannot hold the CRS fails rather than dropping it */
    assert_int_equal(ft_io_write_grid(ft_test_tmp("v.rst"), g, NULL), FT_E_UNSUPPORTED);
    assert_non_null(strstr(ft_last_error(), "cannot store its CRS"));
    assert_int_equal(access(ft_test_tmp("v.rst"), F_OK), -1);
    ft_grid_free(g);
}

/* The file's COMPRESSION and PREDICTOR as GDAL reports them ("" when absent). */
static void file_codec(const char *path, char codec[32], char pred[8])
{
    GDALDatasetH ds = GDALOpen(path, GA_ReadOnly);
    assert_non_null(ds);
    const char *c = GDALGetMetadataItem(ds, "COMPRESSION", "IMAGE_STRUCTURE");
    const char *p = GDALGetMetadataItem(ds, "PREDICTOR", "IMAGE_STRUCTURE");
    snprintf(codec, 32, "%s", c ? c : "");
    snprintf(pred, 8, "%s", p ? p : "");
    GDALClose(ds);
}

/* GeoTIFF codec: ZSTD + predictor by default (this GDAL has ZSTD), DEFLATE with a caller's ZLEVEL or with
 * FRACTERRA_GTIFF_COMPRESS, the caller's COMPRESS over both, a bad variable an error with nothing
 * written; cells identical. */
static void test_default_codec(void **state)
{
    (void)state;
    ft_grid *g = read_ok(VOLCANO, 1);
    char codec[32], pred[8];
    const char *path = ft_test_tmp("z.tif");
    unsetenv("FRACTERRA_GTIFF_COMPRESS");
    write_ok(path, g, NULL);
    file_codec(path, codec, pred);
    assert_string_equal(codec, "ZSTD");
    assert_string_equal(pred, "3");
    ft_grid *b = read_ok(path, 1);
    assert_grids_equal(g, b, 0.0);
    ft_grid_free(b);
    ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
    o.type = GDT_Int16;
    write_ok(path, g, &o);
    file_codec(path, codec, pred);
    assert_string_equal(codec, "ZSTD");
    assert_string_equal(pred, "2");

    const char *const zlevel[] = {"ZLEVEL=9", NULL}; /* a DEFLATE level alone asks for DEFLATE */
    o = (ft_write_grid_opts)FT_WRITE_GRID_OPTS_DEFAULT;
    o.co = zlevel;
    write_ok(path, g, &o);
    file_codec(path, codec, pred);
    assert_string_equal(codec, "DEFLATE");

    setenv("FRACTERRA_GTIFF_COMPRESS", "deflate", 1);
    write_ok(path, g, NULL);
    file_codec(path, codec, pred);
    assert_string_equal(codec, "DEFLATE");
    assert_string_equal(pred, "3");
    b = read_ok(path, 1);
    assert_grids_equal(g, b, 0.0);
    ft_grid_free(b);
    const char *const lzw[] = {"COMPRESS=LZW", NULL};
    o = (ft_write_grid_opts)FT_WRITE_GRID_OPTS_DEFAULT;
    o.co = lzw;
    write_ok(path, g, &o);
    file_codec(path, codec, pred);
    assert_string_equal(codec, "LZW");

    setenv("FRACTERRA_GTIFF_COMPRESS", "JPEG", 1);
    assert_int_equal(ft_io_write_grid(ft_test_tmp("bad.tif"), g, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "FRACTERRA_GTIFF_COMPRESS='JPEG'"));
    assert_int_equal(access(ft_test_tmp("bad.tif"), F_OK), -1);
    write_ok(ft_test_tmp("v.asc"), g, NULL); /* other drivers do not look at it */
    unsetenv("FRACTERRA_GTIFF_COMPRESS");
    assert_int_equal(access(ft_test_tmp("v.prj"), F_OK), 0);
    assert_int_equal(ft_test_dir_count(), 3); /* z.tif, v.asc, v.prj */
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_volcano),
        cmocka_unit_test(test_read_luxembourg),
        cmocka_unit_test(test_round_trip_geotiff),
        cmocka_unit_test(test_round_trip_ascii),
        cmocka_unit_test(test_nodata_rules),
        cmocka_unit_test(test_summary),
        cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_write_failures_leave_nothing),
        cmocka_unit_test(test_driver_choice),
        cmocka_unit_test(test_default_codec),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
