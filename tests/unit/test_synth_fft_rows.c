/* fracterra — tests/unit/test_synth_fft_rows.c: the fft synthesis in slabs of rows (synth_fft_rows.c, the
 * library side of `mpiexec -n N fracterra synth`): slabs of any height, put together with the library's own
 * c2r, give ft_terrain_synth's cells bit for bit (the spectrum, plane, crop and rescale are the same numbers
 * in the same order), on odd, even, padded and periodic grids; bad arguments are refused. The MPI transform
 * itself is tested end to end in tests/cli/test_cli_tiles.c.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdlib.h>
#include <string.h>

#include "fft/fft.h"
#include "fracterra/terrain.h"

/* The surface from slabs of `slab` grid rows, each slab's rows handled on their own. */
static void slabs_equal_whole(size_t nx, size_t ny, const ft_synth_opts *so, size_t slab)
{
    size_t px = 0, py = 0;
    assert_int_equal(ft_synth_fft_grid_size(nx, ny, so, &px, &py), FT_OK);
    assert_true(px >= nx && py >= ny);
    size_t ncx = px / 2 + 1, rs = 2 * ncx;
    float *spec = malloc(py * rs * sizeof *spec);
    double *sums = malloc(2 * ny * sizeof *sums);
    assert_non_null(spec);
    assert_non_null(sums);
    for (size_t r = 0; r < py; r += slab)
        assert_int_equal(ft_synth_fft_spectrum_rows(nx, ny, so, r, r + slab < py ? slab : py - r, spec + r * rs), FT_OK);
    assert_int_equal(ft_fft_c2r_2df(py, px, (fftwf_complex *)spec), FT_OK);
    for (size_t r = 0; r < py; r += slab)
        assert_int_equal(ft_synth_fft_surface_rows(nx, ny, so, r, r + slab < py ? slab : py - r, spec + r * rs,
                                                   r < ny ? sums + 2 * r : NULL), FT_OK);
    ft_grid *g = NULL;
    assert_int_equal(ft_terrain_synth(nx, ny, so, &g), FT_OK);
    for (size_t r = 0; r < ny; r += slab) {
        size_t n = r + slab < ny ? slab : ny - r;
        assert_int_equal(ft_synth_rescale_rows(nx, ny, so, sums, n, spec + r * rs), FT_OK);
        assert_memory_equal(spec + r * rs, g->z + r * nx, n * nx * sizeof(float));
    }
    ft_grid_free(g);
    free(sums);
    free(spec);
}

static void test_slabs_equal_whole(void **state)
{
    (void)state;
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    so.seed = 17;
    so.dim = 2.3;
    slabs_equal_whole(203, 157, &so, 7);   /* padded grid, odd sizes */
    slabs_equal_whole(203, 157, &so, 1000); /* one slab */
    so.dim = 2.8;
    so.sigma = 0.0;
    slabs_equal_whole(64, 50, &so, 3);    /* raw scale */
    so.periodic = 1;
    so.sigma = 5.0;
    slabs_equal_whole(97, 66, &so, 11);   /* periodic: the grid is the output, odd px */
    slabs_equal_whole(1, 1, &so, 1);
}

static void test_rows_errors(void **state)
{
    (void)state;
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    size_t px = 0, py = 0;
    float row[2 * 40];
    double sums[2 * 10];
    assert_int_equal(ft_synth_fft_grid_size(40, 10, &so, &px, &py), FT_OK);
    assert_int_equal(ft_synth_fft_spectrum_rows(40, 10, &so, py, 1, row), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "outside"));
    assert_int_equal(ft_synth_fft_surface_rows(40, 10, &so, 0, py + 1, row, sums), FT_E_INVALID);
    assert_int_equal(ft_synth_fft_spectrum_rows(40, 10, &so, 0, 1, NULL), FT_E_INVALID);
    assert_int_equal(ft_synth_rescale_rows(40, 10, &so, NULL, 1, row), FT_E_INVALID);
    assert_int_equal(ft_synth_fft_grid_size(0, 10, &so, &px, &py), FT_E_INVALID);
    so.method = FT_SYNTH_SRA;
    assert_int_equal(ft_synth_fft_grid_size(40, 10, &so, &px, &py), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "method fft, got sra"));
    so.method = FT_SYNTH_FFT;
    so.dim = 3.2;
    assert_int_equal(ft_synth_fft_spectrum_rows(40, 10, &so, 0, 1, row), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "3.2"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_slabs_equal_whole),
        cmocka_unit_test(test_rows_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
