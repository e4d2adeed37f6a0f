/* fracterra — tests of windowed raster reading and piece-by-piece writing (ft_io_grid_reader_*,
 * ft_io_grid_writer_*): a window holds exactly the cells, mask and georeferencing the whole read gives there,
 * and a raster written piece by piece in any order reads back as the one written at once.
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
#include <unistd.h>

#include <cmocka.h>

#include "fracterra/io.h"
#include "ft_test_util.h"

#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_utm32n.tif" /* Int16, nodata -32768, blocks of 81 x 50 */

static ft_grid *read_whole(const char *path)
{
    ft_grid *g = NULL;
    if (ft_io_read_grid(path, NULL, &g) != FT_OK)
        fail_msg("%s: %s", path, ft_last_error());
    return g;
}

/* The window (c0, r0, w x h) of r equals the same cells of the whole grid g. */
static void assert_window(ft_grid_reader *r, const ft_grid *g, size_t c0, size_t r0, size_t w, size_t h)
{
    ft_grid *t = NULL;
    if (ft_io_grid_reader_read(r, c0, r0, w, h, &t) != FT_OK)
        fail_msg("window %zu,%zu %zux%zu: %s", c0, r0, w, h, ft_last_error());
    assert_int_equal(t->nx, w);
    assert_int_equal(t->ny, h);
    /* the window's cell (0,0) is the grid's (c0, r0) on the ground */
    double x, y, tx, ty;
    ft_grid_cell_center(g, (double)c0, (double)r0, &x, &y);
    ft_grid_cell_center(t, 0.0, 0.0, &tx, &ty);
    assert_true(fabs(x - tx) < 1e-9 * fmax(1.0, fabs(x)) && fabs(y - ty) < 1e-9 * fmax(1.0, fabs(y)));
    assert_true(t->gt[1] == g->gt[1] && t->gt[5] == g->gt[5]);
    assert_int_equal(t->has_nodata, g->has_nodata);
    ft_test_assert_same_crs(t->crs_wkt, g->crs_wkt);
    for (size_t i = 0; i < h; i++)
        for (size_t j = 0; j < w; j++) {
            int va = ft_grid_is_valid(g, c0 + j, r0 + i), vb = ft_grid_is_valid(t, j, i);
            assert_int_equal(va, vb);
            if (va)
                assert_true(g->z[(r0 + i) * g->nx + c0 + j] == t->z[i * w + j]);
        }
    ft_grid_free(t);
}

static void test_windows_equal_whole_read(void **state)
{
    (void)state;
    const char *paths[] = {VOLCANO, LUXEMBOURG};
    for (int p = 0; p < 2; p++) {
        ft_grid *g = read_whole(paths[p]);
        ft_grid_reader *r = NULL;
        assert_int_equal(ft_io_grid_reader_open(paths[p], NULL, &r), FT_OK);
        const ft_grid *h = ft_io_grid_reader_header(r);
        assert_int_equal(h->nx, g->nx);
        assert_int_equal(h->ny, g->ny);
        assert_null(h->z);
        size_t bx, by;
        ft_io_grid_reader_block(r, &bx, &by);
        assert_true(bx >= 1 && by >= 1);
        assert_window(r, g, 0, 0, g->nx, g->ny);                 /* the whole band */
        assert_window(r, g, 0, by - 3, g->nx, 7);               /* across a block row */
        assert_window(r, g, 5, 11, g->nx - 9, g->ny - 20);      /* inside, both axes */
        assert_window(r, g, g->nx - 1, g->ny - 1, 1, 1);        /* the last cell */
        ft_io_grid_reader_close(r);
        ft_grid_free(g);
    }
    /* the Luxembourg DEM has nodata cells: the windows above compared masks that are not all valid */
    ft_grid *lux = read_whole(LUXEMBOURG);
    assert_true(ft_grid_count_valid(lux) < lux->nx * lux->ny);
    ft_grid_free(lux);
}

static void test_reader_bad_input(void **state)
{
    (void)state;
    ft_grid_reader *r = NULL;
    assert_int_equal(ft_io_grid_reader_open(FT_TEST_DATA "/no_such.tif", NULL, &r), FT_E_IO);
    assert_null(r);
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    o.band = 2;
    assert_int_equal(ft_io_grid_reader_open(VOLCANO, &o, &r), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "band 2"));
    assert_int_equal(ft_io_grid_reader_open(FT_TEST_DATA "/contours_volcano_10m.geojson", NULL, &r), FT_E_FORMAT);
    assert_int_equal(ft_io_grid_reader_open(VOLCANO, NULL, &r), FT_OK);
    ft_grid *t = NULL;
    assert_int_equal(ft_io_grid_reader_read(r, 60, 0, 2, 5, &t), FT_E_INVALID); /* past the right edge */
    assert_non_null(strstr(ft_last_error(), "leaves the 61 x 87 band"));
    assert_int_equal(ft_io_grid_reader_read(r, 0, 80, 61, 8, &t), FT_E_INVALID);
    assert_int_equal(ft_io_grid_reader_read(r, 0, 0, 0, 8, &t), FT_E_INVALID);
    assert_null(t);
    ft_io_grid_reader_close(r);
    ft_io_grid_reader_close(NULL);
}

/* Pieces of g (stripes of h rows split in two columns), written bottom-up, read back equal to g written at
 * once, cell for cell. */
static void test_writer_pieces_any_order(void **state)
{
    (void)state;
    ft_grid *g = read_whole(LUXEMBOURG);
    const char *whole = ft_test_tmp("whole.tif"), *tiled = ft_test_tmp("tiled.tif");
    assert_int_equal(ft_io_write_grid(whole, g, NULL), FT_OK);
    ft_grid_writer *w = NULL;
    assert_int_equal(ft_io_grid_writer_create(tiled, g, 1, NULL, &w), FT_OK);
    assert_int_equal(access(tiled, F_OK), -1); /* nothing at the destination before commit */
    size_t h = 13, half = g->nx / 2;
    for (size_t r0 = (g->ny - 1) / h * h;; r0 -= h) {
        size_t rows = r0 + h <= g->ny ? h : g->ny - r0;
        for (int side = 1; side >= 0; side--) {
            size_t c0 = side ? half : 0, cols = side ? g->nx - half : half;
            ft_grid *p = ft_grid_create(cols, rows);
            assert_non_null(p);
            assert_int_equal(ft_grid_ensure_mask(p), FT_OK);
            for (size_t i = 0; i < rows; i++)
                for (size_t j = 0; j < cols; j++) {
                    p->z[i * cols + j] = g->z[(r0 + i) * g->nx + c0 + j];
                    p->mask[i * cols + j] = (uint8_t)ft_grid_is_valid(g, c0 + j, r0 + i);
                }
            assert_int_equal(ft_io_grid_writer_write(w, 1, p, c0, r0), FT_OK);
            ft_grid_free(p);
        }
        if (r0 == 0)
            break;
    }
    assert_int_equal(ft_io_grid_writer_commit(w), FT_OK);
    ft_grid *a = read_whole(whole), *b = read_whole(tiled);
    assert_int_equal(a->nx, b->nx);
    assert_int_equal(a->ny, b->ny);
    for (int k = 0; k < 6; k++)
        assert_true(a->gt[k] == b->gt[k]);
    ft_test_assert_same_crs(a->crs_wkt, b->crs_wkt);
    assert_true(b->has_nodata && b->nodata_value == g->nodata_value);
    for (size_t i = 0; i < a->nx * a->ny; i++) {
        assert_int_equal(a->mask ? a->mask[i] : 1, b->mask ? b->mask[i] : 1);
        if (a->mask == NULL || a->mask[i])
            assert_true(a->z[i] == b->z[i]);
    }
    assert_true(ft_grid_count_valid(b) < b->nx * b->ny);
    ft_grid_free(a);
    ft_grid_free(b);
    ft_grid_free(g);
}

static void test_writer_bad_input_leaves_nothing(void **state)
{
    (void)state;
    ft_grid *g = read_whole(VOLCANO);
    ft_grid_writer *w = NULL;
    /* only GeoTIFF can be written piece by piece */
    assert_int_equal(ft_io_grid_writer_create(ft_test_tmp("v.asc"), g, 1, NULL, &w), FT_E_UNSUPPORTED);
    assert_non_null(strstr(ft_last_error(), "GeoTIFF"));
    assert_null(w);
    assert_int_equal(ft_io_grid_writer_create(ft_test_tmp("v.tif"), g, 0, NULL, &w), FT_E_INVALID);
    assert_int_equal(ft_io_grid_writer_create(ft_test_tmp("no/such/dir/v.tif"), g, 1, NULL, &w), FT_E_IO);
    assert_int_equal(ft_io_grid_writer_create(ft_test_tmp("v.tif"), g, 2, NULL, &w), FT_OK);
    assert_int_equal(ft_io_grid_writer_write(w, 3, g, 0, 0), FT_E_INVALID);  /* no band 3 */
    assert_int_equal(ft_io_grid_writer_write(w, 1, g, 1, 0), FT_E_INVALID);  /* past the right edge */
    assert_non_null(strstr(ft_last_error(), "leaves the 61 x 87 raster"));
    assert_int_equal(ft_io_grid_writer_write(w, 1, g, 0, 0), FT_OK);
    ft_io_grid_writer_abort(w); /* an abandoned write leaves no file, not even its temporary */
    assert_int_equal(ft_test_dir_count(), 0);
    ft_io_grid_writer_abort(NULL);
    ft_grid_free(g);
}

/* Rows of the hillshade shaded from a stripe plus one row of halo are the whole DEM's, at the top and bottom
 * edges, across the nodata of the Luxembourg DEM, and with the automatic scale of a DEM in degrees. */
static void test_hillshade_rows_equal_whole(void **state)
{
    (void)state;
    const char *dems[] = {LUXEMBOURG, FT_TEST_DATA "/dem_luxembourg_terra_30s.tif", VOLCANO};
    for (int d = 0; d < 3; d++) {
        const char *path = ft_test_tmp("shade.tif");
        assert_int_equal(ft_io_hillshade(dems[d], path, NULL), FT_OK);
        ft_grid *whole = read_whole(path);
        size_t cuts[][2] = {{0, 1}, {0, 9}, {9, 13}, {22, 1}, {whole->ny - 5, 5}};
        size_t nonzero = 0;
        for (int k = 0; k < 5; k++) {
            ft_grid *rows = NULL;
            assert_int_equal(ft_io_hillshade_rows(dems[d], NULL, cuts[k][0], cuts[k][1], &rows), FT_OK);
            assert_int_equal(rows->nx, whole->nx);
            assert_int_equal(rows->ny, cuts[k][1]);
            assert_true(rows->gt[3] == whole->gt[3] + (double)cuts[k][0] * whole->gt[5]);
            for (size_t i = 0; i < rows->nx * rows->ny; i++) {
                size_t at = cuts[k][0] * whole->nx + i;
                float w = ft_grid_is_valid(whole, at % whole->nx, at / whole->nx) ? whole->z[at] : 0.0f;
                assert_true(rows->z[i] == w);
                nonzero += rows->z[i] != 0.0f;
            }
            ft_grid_free(rows);
        }
        assert_true(nonzero > 0);
        ft_grid_free(whole);
        unlink(path);
    }
    ft_grid *g = NULL;
    ft_io_hillshade_opts o = FT_IO_HILLSHADE_OPTS_DEFAULT;
    o.color = 1;
    assert_int_equal(ft_io_hillshade_rows(VOLCANO, &o, 0, 5, &g), FT_E_UNSUPPORTED);
    assert_int_equal(ft_io_hillshade_rows(VOLCANO, NULL, 85, 5, &g), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "leave the 87 rows"));
    assert_null(g);
}

/* The raster at path equals g: size, georeferencing, CRS, mask and cells. */
static void assert_mosaic_is(const char *path, const ft_grid *g)
{
    ft_grid *m = read_whole(path);
    assert_int_equal(m->nx, g->nx);
    assert_int_equal(m->ny, g->ny);
    for (int k = 0; k < 6; k++)
        assert_true(m->gt[k] == g->gt[k]);
    ft_test_assert_same_crs(m->crs_wkt, g->crs_wkt);
    for (size_t i = 0; i < g->nx * g->ny; i++) {
        int va = g->mask == NULL || g->mask[i], vb = m->mask == NULL || m->mask[i];
        assert_int_equal(va, vb);
        if (va)
            assert_true(g->z[i] == m->z[i]);
    }
    ft_grid_free(m);
}

/* Three stripes of a DEM written as parts and mosaicked by a VRT read back as the DEM, cell for cell, also
 * after the .vrt and its parts moved together to another folder; bad mosaics are refused, nothing written. */
static void test_mosaic_vrt_of_parts(void **state)
{
    (void)state;
    ft_grid *g = read_whole(VOLCANO);
    ft_grid_reader *r = NULL;
    assert_int_equal(ft_io_grid_reader_open(VOLCANO, NULL, &r), FT_OK);
    const char *names[] = {"mos.part-0000.tif", "mos.part-0001.tif", "mos.part-0002.tif"};
    size_t cut[] = {0, g->ny / 3, g->ny / 3 + 17, g->ny};
    for (int k = 0; k < 3; k++) {
        ft_grid *t = NULL;
        assert_int_equal(ft_io_grid_reader_read(r, 0, cut[k], g->nx, cut[k + 1] - cut[k], &t), FT_OK);
        assert_int_equal(ft_io_write_grid(ft_test_tmp(names[k]), t, NULL), FT_OK);
        ft_grid_free(t);
    }
    ft_io_grid_reader_close(r);
    char *vrt = strdup(ft_test_tmp("mos.vrt"));
    assert_int_equal(ft_io_write_mosaic_vrt(vrt, g, 3, names), FT_OK);
    assert_mosaic_is(vrt, g);
    char *dir = strdup(ft_test_tmp("moved"));
    assert_int_equal(mkdir(dir, 0755), 0);
    char to[4096];
    for (int k = 0; k < 3; k++) {
        snprintf(to, sizeof to, "%s/%s", dir, names[k]);
        assert_int_equal(rename(ft_test_tmp(names[k]), to), 0);
    }
    snprintf(to, sizeof to, "%s/mos.vrt", dir);
    assert_int_equal(rename(vrt, to), 0);
    assert_mosaic_is(to, g);
    /* refusals, in the moved folder (the parts are there) */
    char bad[4096];
    snprintf(bad, sizeof bad, "%s/bad.vrt", dir);
    assert_int_equal(ft_io_write_mosaic_vrt(bad, g, 2, names), FT_E_INVALID); /* rows do not add up */
    assert_non_null(strstr(ft_last_error(), "hold"));
    g->nx++;
    assert_int_equal(ft_io_write_mosaic_vrt(bad, g, 3, names), FT_E_FORMAT); /* width */
    g->nx--;
    const char *missing[] = {"mos.part-0000.tif", "nothere.tif", "mos.part-0002.tif"};
    assert_int_equal(ft_io_write_mosaic_vrt(bad, g, 3, missing), FT_E_IO);
    const char *absolute[] = {to};
    assert_int_equal(ft_io_write_mosaic_vrt(bad, g, 1, absolute), FT_E_INVALID);
    snprintf(bad, sizeof bad, "%s/bad.tif", dir);
    assert_int_equal(ft_io_write_mosaic_vrt(bad, g, 3, names), FT_E_INVALID); /* not .vrt */
    assert_int_equal(access(bad, F_OK), -1);
    snprintf(bad, sizeof bad, "%s/bad.vrt", dir);
    assert_int_equal(access(bad, F_OK), -1);
    free(dir);
    free(vrt);
    ft_grid_free(g);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_windows_equal_whole_read),
        cmocka_unit_test(test_reader_bad_input),
        cmocka_unit_test(test_writer_pieces_any_order),
        cmocka_unit_test(test_writer_bad_input_leaves_nothing),
        cmocka_unit_test(test_hillshade_rows_equal_whole),
        cmocka_unit_test(test_mosaic_vrt_of_parts),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
