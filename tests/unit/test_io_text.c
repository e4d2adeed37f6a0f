/* fracterra — tests of GMT-style text chains (io/text_chains.c).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <float.h>
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
#include "ft_test_util.h"

#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"

static void test_parse(void **state)
{
    (void)state;
    const char *path = ft_test_tmp_text("in.gmt", "# a GMT file\n"
                                                  "\n"
                                                  "> first segment -Z12\n"
                                                  "0 0 99 extra\n"
                                                  "1\t1\n"
                                                  "  2,0.5\r\n"
                                                  ">\n"
                                                  ">\n"
                                                  "# a ring\n"
                                                  "10 10\n"
                                                  "11 10\n"
                                                  "11 11\n"
                                                  "10 10\n"
                                                  "> a two-vertex segment back to its start stays open\n"
                                                  "5 5\n"
                                                  "5 5\n");
    ft_layer *l = NULL;
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_OK);
    assert_int_equal(l->nfeatures, 3);
    assert_int_equal(l->nparts, 3);
    assert_string_equal(l->name, "in");
    const ft_chain *a = l->parts[0].chain, *b = l->parts[1].chain, *c = l->parts[2].chain;
    assert_int_equal(l->features[0].type, FT_GEOM_LINE);
    assert_int_equal(a->n, 3);
    assert_int_equal(a->closed, 0);
    assert_true(a->x[2] == 2.0 && a->y[2] == 0.5);
    assert_int_equal(b->n, 3);
    assert_int_equal(b->closed, 1);
    assert_true(b->x[2] == 11 && b->y[2] == 11);
    assert_int_equal(c->n, 2);
    assert_int_equal(c->closed, 0);
    ft_layer_free(l);
}

static void test_round_trip(void **state)
{
    (void)state;
    ft_layer *a = ft_layer_create("t", NULL);
    const double x[] = {0.1, 1.0 / 3.0, -123456789.123456789, 1e-300, DBL_MAX};
    const double y[] = {0.2, 2.0 / 3.0, 987654321.5, -1e-300, -DBL_MAX};
    ft_layer_add_feature(a, 0, FT_GEOM_LINE, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(x, y, 5, 1, 0), FT_ROLE_LINE, 0);
    ft_layer_add_feature(a, 1, FT_GEOM_LINE, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(x, y, 4, 1, 1), FT_ROLE_LINE, 0);
    const char *path = ft_test_tmp("rt.xy");
    assert_int_equal(ft_io_write_layer(path, a, NULL), FT_OK);
    char *text = ft_test_read_file(path, NULL);
    assert_non_null(text);
    assert_non_null(strstr(text, "0.1 0.2\n"));
    free(text);
    ft_layer *b = NULL;
    assert_int_equal(ft_io_read_layer(path, NULL, &b), FT_OK);
    assert_int_equal(b->nparts, 2);
    ft_test_assert_layer_chains_equal(a, b);
    ft_layer_free(b);
    ft_layer_free(a);
}

static void test_polygons_to_text(void **state)
{
    (void)state;
    ft_layer *a = NULL;
    assert_int_equal(ft_io_read_layer(NEWFOUNDLAND, NULL, &a), FT_OK);
    const char *path = ft_test_tmp("nf.txt");
    assert_int_equal(ft_io_write_text_chains(path, a), FT_OK);
    ft_layer *b = NULL;
    assert_int_equal(ft_io_read_text_chains(path, &b), FT_OK);
    assert_int_equal(b->nparts, 1);
    assert_int_equal(b->parts[0].chain->n, 64193);
    ft_test_assert_layer_chains_equal(a, b);
    ft_layer_free(b);
    ft_layer_free(a);

    /* holes are marked the GMT way */
    a = ft_layer_create("h", NULL);
    const double ox[] = {0, 10, 10, 0}, oy[] = {0, 0, 10, 10}, ix[] = {2, 2, 4}, iy[] = {2, 4, 4};
    ft_layer_add_feature(a, 5, FT_GEOM_POLYGON, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(ox, oy, 4, 1, 1), FT_ROLE_OUTER, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(ix, iy, 3, 1, 1), FT_ROLE_INNER, 0);
    path = ft_test_tmp("h.gmt");
    assert_int_equal(ft_io_write_layer(path, a, NULL), FT_OK);
    char *text = ft_test_read_file(path, NULL);
    assert_non_null(text);
    assert_non_null(strstr(text, "> fid=5\n0 0\n10 0\n10 10\n0 10\n0 0\n"));
    assert_non_null(strstr(text, "> fid=5 -Ph\n2 2\n2 4\n4 4\n2 2\n"));
    free(text);
    assert_int_equal(ft_io_read_text_chains(path, &b), FT_OK);
    assert_int_equal(b->nparts, 2);
    ft_test_assert_layer_chains_equal(a, b);
    ft_layer_free(b);
    ft_layer_free(a);
}

static void test_errors(void **state)
{
    (void)state;
    ft_layer *l = NULL;
    const char *path = ft_test_tmp_text("bad.gmt", "0 0\n1 1\n2 abc\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_FORMAT);
    assert_null(l);
    char want[300];
    snprintf(want, sizeof want, "%s:3:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "'abc'"));

    ft_test_put_text(path, "0 0\n1 nan\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_NUMERIC);
    snprintf(want, sizeof want, "%s:2:", path);
    assert_non_null(strstr(ft_last_error(), want));

    ft_test_put_text(path, "0 0\n7\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "missing y"));

    ft_test_put_text(path, "# nothing\n>\n\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_EMPTY);
    assert_int_equal(ft_io_read_text_chains(ft_test_tmp("missing.gmt"), &l), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "cannot open"));

    ft_read_layer_opts o = FT_READ_LAYER_OPTS_DEFAULT;
    o.where = "a > 1";
    ft_test_put_text(path, "0 0\n1 1\n");
    assert_int_equal(ft_io_read_layer(path, &o, &l), FT_E_UNSUPPORTED);

    ft_layer *a = ft_layer_create("t", NULL);
    assert_int_equal(ft_io_write_text_chains("/tmp/ft-no-such-folder-xyz/a.gmt", a), FT_E_IO);
    assert_int_equal(ft_test_dir_count(), 1);
    ft_layer_free(a);
}

static void test_stdin(void **state)
{
    (void)state;
    const char *path = ft_test_tmp_text("stdin.txt", "1 2\n3 4\n");
    int saved = dup(0);
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    assert_true(dup2(fileno(f), 0) == 0);
    fclose(f);
    ft_layer *l = NULL;
    int rc = ft_io_read_layer("-", NULL, &l);
    dup2(saved, 0);
    close(saved);
    clearerr(stdin);
    assert_int_equal(rc, FT_OK);
    assert_int_equal(l->parts[0].chain->n, 2);
    assert_true(l->parts[0].chain->y[1] == 4);
    ft_layer_free(l);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse),
        cmocka_unit_test(test_round_trip),
        cmocka_unit_test(test_polygons_to_text),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_stdin),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
