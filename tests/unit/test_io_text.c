/* fracterra — tests of GMT-style text chains (io/text_chains.c).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <dirent.h>
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

#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"

static char g_dir[64];

static const char *tmp_file(const char *name)
{
    static char buf[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", g_dir, name);
    return buf[k];
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "r");
    assert_non_null(f);
    static char buf[8192];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

static int count_files(const char *dir)
{
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0)
            n++;
    closedir(d);
    return n;
}

static void empty_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (d == NULL)
        return;
    struct dirent *e;
    char path[512];
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        remove(path);
    }
    closedir(d);
}

static int setup(void **state)
{
    (void)state;
    strcpy(g_dir, "/tmp/ft-io-text-XXXXXX");
    return mkdtemp(g_dir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    empty_dir(g_dir);
    return rmdir(g_dir);
}

static int after_each(void **state)
{
    (void)state;
    empty_dir(g_dir);
    return 0;
}

static void assert_chain_equal(const ft_chain *a, const ft_chain *b)
{
    assert_int_equal(a->n, b->n);
    assert_int_equal(a->closed, b->closed);
    for (size_t i = 0; i < a->n; i++) {
        assert_true(a->x[i] == b->x[i]);
        assert_true(a->y[i] == b->y[i]);
    }
}

static void test_parse(void **state)
{
    (void)state;
    const char *path = tmp_file("in.gmt");
    write_text(path, "# a GMT file\n"
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
    const char *path = tmp_file("rt.xy");
    assert_int_equal(ft_io_write_layer(path, a, NULL), FT_OK);
    assert_non_null(strstr(slurp(path), "0.1 0.2\n"));
    ft_layer *b = NULL;
    assert_int_equal(ft_io_read_layer(path, NULL, &b), FT_OK);
    assert_int_equal(b->nparts, 2);
    assert_chain_equal(a->parts[0].chain, b->parts[0].chain);
    assert_chain_equal(a->parts[1].chain, b->parts[1].chain);
    ft_layer_free(b);
    ft_layer_free(a);
}

static void test_polygons_to_text(void **state)
{
    (void)state;
    ft_layer *a = NULL;
    assert_int_equal(ft_io_read_layer(NEWFOUNDLAND, NULL, &a), FT_OK);
    const char *path = tmp_file("nf.txt");
    assert_int_equal(ft_io_write_text_chains(path, a), FT_OK);
    ft_layer *b = NULL;
    assert_int_equal(ft_io_read_text_chains(path, &b), FT_OK);
    assert_int_equal(b->nparts, 1);
    assert_int_equal(b->parts[0].chain->n, 64193);
    assert_chain_equal(a->parts[0].chain, b->parts[0].chain);
    ft_layer_free(b);
    ft_layer_free(a);

    /* holes are marked the GMT way */
    a = ft_layer_create("h", NULL);
    const double ox[] = {0, 10, 10, 0}, oy[] = {0, 0, 10, 10}, ix[] = {2, 2, 4}, iy[] = {2, 4, 4};
    ft_layer_add_feature(a, 5, FT_GEOM_POLYGON, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(ox, oy, 4, 1, 1), FT_ROLE_OUTER, 0);
    ft_layer_add_part(a, ft_chain_from_arrays(ix, iy, 3, 1, 1), FT_ROLE_INNER, 0);
    path = tmp_file("h.gmt");
    assert_int_equal(ft_io_write_layer(path, a, NULL), FT_OK);
    const char *text = slurp(path);
    assert_non_null(strstr(text, "> fid=5\n0 0\n10 0\n10 10\n0 10\n0 0\n"));
    assert_non_null(strstr(text, "> fid=5 -Ph\n2 2\n2 4\n4 4\n2 2\n"));
    assert_int_equal(ft_io_read_text_chains(path, &b), FT_OK);
    assert_int_equal(b->nparts, 2);
    assert_chain_equal(a->parts[0].chain, b->parts[0].chain);
    assert_chain_equal(a->parts[1].chain, b->parts[1].chain);
    ft_layer_free(b);
    ft_layer_free(a);
}

static void test_errors(void **state)
{
    (void)state;
    ft_layer *l = NULL;
    const char *path = tmp_file("bad.gmt");
    write_text(path, "0 0\n1 1\n2 abc\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_FORMAT);
    assert_null(l);
    char want[300];
    snprintf(want, sizeof want, "%s:3:", path);
    assert_non_null(strstr(ft_last_error(), want));
    assert_non_null(strstr(ft_last_error(), "'abc'"));

    write_text(path, "0 0\n1 nan\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_NUMERIC);
    snprintf(want, sizeof want, "%s:2:", path);
    assert_non_null(strstr(ft_last_error(), want));

    write_text(path, "0 0\n7\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "missing y"));

    write_text(path, "# nothing\n>\n\n");
    assert_int_equal(ft_io_read_text_chains(path, &l), FT_E_EMPTY);
    assert_int_equal(ft_io_read_text_chains(tmp_file("missing.gmt"), &l), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "cannot open"));

    ft_read_layer_opts o = FT_READ_LAYER_OPTS_DEFAULT;
    o.where = "a > 1";
    write_text(path, "0 0\n1 1\n");
    assert_int_equal(ft_io_read_layer(path, &o, &l), FT_E_UNSUPPORTED);

    ft_layer *a = ft_layer_create("t", NULL);
    assert_int_equal(ft_io_write_text_chains("/tmp/ft-no-such-folder-xyz/a.gmt", a), FT_E_IO);
    assert_int_equal(count_files(g_dir), 1);
    ft_layer_free(a);
}

static void test_stdin(void **state)
{
    (void)state;
    const char *path = tmp_file("stdin.txt");
    write_text(path, "1 2\n3 4\n");
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
    ft_io_init();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_teardown(test_parse, after_each),
        cmocka_unit_test_teardown(test_round_trip, after_each),
        cmocka_unit_test_teardown(test_polygons_to_text, after_each),
        cmocka_unit_test_teardown(test_errors, after_each),
        cmocka_unit_test_teardown(test_stdin, after_each),
    };
    int failed = cmocka_run_group_tests(tests, setup, teardown);
    ft_io_cleanup();
    return failed;
}
