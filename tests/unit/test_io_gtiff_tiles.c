/* fracterra — tests of the GeoTIFF tiles compressed on fracterra's threads (src/io/gtiff_tiles.c): the file
 * GDAL reads back has the cells, georeferencing, nodata and codec of the file GDAL's own writer makes, on any
 * thread count; a header of another layout is left to GDAL.
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
#include <sys/stat.h>

#include <cmocka.h>
#include <cpl_string.h>
#include <gdal.h>
#include <omp.h>
#include <ogr_srs_api.h>
#include <zstd.h>

#include "fracterra/io.h"
#include "ft_test_util.h"
#include "io/io_internal.h"

/* nx x ny cells of a rough surface (not a multiple of the 256-cell tiles), with NaN and +inf cells and
 * masked ones, in UTM 33N. */
static ft_grid *odd_grid(size_t nx, size_t ny, int masked)
{
    ft_grid *g = ft_grid_create(nx, ny);
    assert_non_null(g);
    for (size_t i = 0; i < nx * ny; i++)
        g->z[i] = (float)(100.0 * sin(0.013 * (double)i) + 7.0 * cos(0.37 * (double)(i % nx) * (double)(i / nx)));
    g->z[5] = NAN;
    g->z[nx * ny - 1] = INFINITY;
    if (masked) {
        g->mask = malloc(nx * ny);
        assert_non_null(g->mask);
        memset(g->mask, 1, nx * ny);
        g->mask[nx + 3] = 0;
        g->mask[(ny / 2) * nx + nx - 1] = 0;
    }
    double gt[6] = {500000.0, 10.0, 0.0, 6000000.0, 0.0, -10.0};
    memcpy(g->gt, gt, sizeof gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(NULL);
    assert_int_equal(OSRImportFromEPSG(srs, 32633), OGRERR_NONE);
    char *wkt = NULL;
    OSRExportToWkt(srs, &wkt);
    assert_int_equal(ft_grid_set_crs(g, wkt), FT_OK);
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    return g;
}

static void write_ok(const char *path, const ft_grid *g, const ft_write_grid_opts *o)
{
    if (ft_io_write_grid(path, g, o) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
}

/* The file as GDAL reads it. */
typedef struct {
    int nx, ny, bx, by, has_nodata, has_gt;
    double gt[6], nodata;
    char wkt[4096], codec[32], pred[8];
    float *z;
} file_view;

static void view(const char *path, file_view *v)
{
    memset(v, 0, sizeof *v);
    GDALDatasetH ds = GDALOpen(path, GA_ReadOnly);
    assert_non_null(ds);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    v->nx = GDALGetRasterXSize(ds);
    v->ny = GDALGetRasterYSize(ds);
    GDALGetBlockSize(b, &v->bx, &v->by);
    assert_int_equal(GDALGetRasterDataType(b), GDT_Float32);
    v->has_gt = GDALGetGeoTransform(ds, v->gt) == CE_None;
    snprintf(v->wkt, sizeof v->wkt, "%s", GDALGetProjectionRef(ds));
    v->nodata = GDALGetRasterNoDataValue(b, &v->has_nodata);
    const char *c = GDALGetMetadataItem(ds, "COMPRESSION", "IMAGE_STRUCTURE");
    const char *p = GDALGetMetadataItem(ds, "PREDICTOR", "IMAGE_STRUCTURE");
    snprintf(v->codec, sizeof v->codec, "%s", c ? c : "");
    snprintf(v->pred, sizeof v->pred, "%s", p ? p : "");
    v->z = malloc((size_t)v->nx * (size_t)v->ny * sizeof *v->z);
    assert_non_null(v->z);
    assert_int_equal(GDALRasterIO(b, GF_Read, 0, 0, v->nx, v->ny, v->z, v->nx, v->ny, GDT_Float32, 0, 0), CE_None);
    GDALClose(ds);
}

/* Same size, blocks, georeferencing, nodata, codec and cells to the bit. */
static void assert_same_view(const file_view *a, const file_view *b)
{
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    assert_int_equal(a->bx, b->bx);
    assert_int_equal(a->by, b->by);
    assert_true(a->has_gt && b->has_gt);
    assert_memory_equal(a->gt, b->gt, sizeof a->gt);
    assert_string_equal(a->wkt, b->wkt);
    assert_int_equal(a->has_nodata, b->has_nodata);
    assert_true(a->nodata == b->nodata || (isnan(a->nodata) && isnan(b->nodata)));
    assert_string_equal(a->codec, b->codec);
    assert_string_equal(a->pred, b->pred);
    assert_memory_equal(a->z, b->z, (size_t)a->nx * (size_t)a->ny * sizeof *a->z);
}

/* Whether the first tile is a ZSTD frame that states its content size: the frames made here do, libtiff's
 * streaming encoder (GDAL's path) does not. */
static int first_tile_from_here(const char *path)
{
    GDALDatasetH ds = GDALOpen(path, GA_ReadOnly);
    assert_non_null(ds);
    GDALRasterBandH b = GDALGetRasterBand(ds, 1);
    const char *off = GDALGetMetadataItem(b, "BLOCK_OFFSET_0_0", "TIFF");
    const char *size = GDALGetMetadataItem(b, "BLOCK_SIZE_0_0", "TIFF");
    assert_non_null(off);
    assert_non_null(size);
    long o = atol(off), n = atol(size);
    GDALClose(ds);
    unsigned char head[32];
    FILE *f = fopen(path, "rb");
    assert_non_null(f);
    assert_int_equal(fseek(f, o, SEEK_SET), 0);
    size_t got = fread(head, 1, n < (long)sizeof head ? (size_t)n : sizeof head, f);
    fclose(f);
    return ZSTD_getFrameContentSize(head, got) == 256u * 256u * 4u;
}

static void free_view(file_view *v)
{
    free(v->z);
}

/* The default write (tiles compressed here) against GDAL's own writer with the same options (a caller's
 * ZSTD_LEVEL=1 sends the write through GDAL), with NaN nodata and with a finite one. */
static void test_same_as_gdal(void **state)
{
    (void)state;
    const char *const gdal_co[] = {"ZSTD_LEVEL=1", NULL};
    for (int finite = 0; finite < 2; finite++) {
        ft_grid *g = odd_grid(300, 517, 1);
        if (finite) {
            g->has_nodata = 1;
            g->nodata_value = -9999.0;
        }
        ft_write_grid_opts o = FT_WRITE_GRID_OPTS_DEFAULT;
        write_ok(ft_test_tmp("here.tif"), g, NULL);
        o.co = gdal_co;
        write_ok(ft_test_tmp("gdal.tif"), g, &o);
        assert_true(first_tile_from_here(ft_test_tmp("here.tif")));
        assert_false(first_tile_from_here(ft_test_tmp("gdal.tif")));
        file_view a, b;
        view(ft_test_tmp("here.tif"), &a);
        view(ft_test_tmp("gdal.tif"), &b);
        assert_same_view(&a, &b);
        assert_string_equal(a.codec, "ZSTD");
        assert_string_equal(a.pred, "3");
        assert_int_equal(a.has_nodata, 1);
        assert_true(finite ? a.nodata == -9999.0 : isnan(a.nodata));
        /* the invalid cells hold the nodata value, the others the grid's */
        float nd = finite ? -9999.0f : NAN;
        size_t bad[] = {5, 300 + 3, 258 * 300 + 299, 300 * 517 - 1};
        for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++)
            assert_memory_equal(&a.z[bad[k]], &nd, sizeof nd);
        assert_true(a.z[6] == g->z[6] && a.z[300 * 517 - 2] == g->z[300 * 517 - 2]);
        free_view(&a);
        free_view(&b);
        ft_grid_free(g);
    }
}

/* The same file, byte for byte, on 1 and 3 threads. */
static void test_thread_count(void **state)
{
    (void)state;
    ft_grid *g = odd_grid(700, 300, 0);
    int saved = omp_get_max_threads();
    omp_set_num_threads(1);
    write_ok(ft_test_tmp("t1.tif"), g, NULL);
    omp_set_num_threads(3);
    write_ok(ft_test_tmp("t3.tif"), g, NULL);
    omp_set_num_threads(saved);
    size_t n1, n3;
    char *a = ft_test_read_file(ft_test_tmp("t1.tif"), &n1), *b = ft_test_read_file(ft_test_tmp("t3.tif"), &n3);
    assert_non_null(a);
    assert_non_null(b);
    assert_int_equal(n1, n3);
    assert_memory_equal(a, b, n1);
    free(a);
    free(b);
    ft_grid_free(g);
}

/* A GDAL header without tiles of another codec or predictor is not filled (done 0, file unchanged); the
 * expected one is (done 1), classic or BigTIFF, and reads back as the grid. */
static void test_fill_only_expected_layout(void **state)
{
    (void)state;
    ft_grid *g = odd_grid(260, 40, 0);
    const char *sets[][3] = {{"DEFLATE", "3", "NO"}, {"ZSTD", "1", "NO"}, {"ZSTD", "3", "NO"}, {"ZSTD", "3", "YES"}};
    GDALDriverH drv = GDALGetDriverByName("GTiff");
    assert_non_null(drv);
    for (size_t k = 0; k < 4; k++) {
        const char *path = ft_test_tmp("h.tif");
        char **co = CSLSetNameValue(NULL, "TILED", "YES");
        co = CSLSetNameValue(co, "SPARSE_OK", "TRUE");
        co = CSLSetNameValue(co, "COMPRESS", sets[k][0]);
        co = CSLSetNameValue(co, "PREDICTOR", sets[k][1]);
        co = CSLSetNameValue(co, "BIGTIFF", sets[k][2]);
        GDALDatasetH ds = GDALCreate(drv, path, 260, 40, 1, GDT_Float32, co);
        CSLDestroy(co);
        assert_non_null(ds);
        GDALClose(ds);
        struct stat before, after;
        assert_int_equal(stat(path, &before), 0);
        int done = -1;
        assert_int_equal(ft_io_gtiff_tiles_fill("out.tif", path, g, 1, NAN, 1, &done), FT_OK);
        assert_int_equal(stat(path, &after), 0);
        assert_int_equal(done, k >= 2);
        if (k < 2) {
            assert_int_equal(before.st_size, after.st_size);
            continue;
        }
        assert_true(after.st_size > before.st_size);
        size_t len;
        char *bytes = ft_test_read_file(path, &len);
        assert_non_null(bytes);
        assert_true(len > 2);
        assert_int_equal(bytes[2], k == 3 ? 43 : 42); /* BigTIFF's version 43, classic 42 */
        free(bytes);
        file_view v;
        view(path, &v);
        for (size_t i = 0; i < 260 * 40; i++) {
            float want = isfinite(g->z[i]) ? g->z[i] : NAN;
            assert_memory_equal(&v.z[i], &want, sizeof want);
        }
        free_view(&v);
    }
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_same_as_gdal),
        cmocka_unit_test(test_thread_count),
        cmocka_unit_test(test_fill_only_expected_layout),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
