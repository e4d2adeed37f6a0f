/* fracterra — tests/support/ft_test_util.c: the per-program temporary folder and shared assertions.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "ft_test_util.h"

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ogr_srs_api.h>

#include "fracterra/io.h"

#define FT_TEST_TMP_BUFFERS 8
#define FT_TEST_TMP_SIZE 512

static char *g_dir;

int ft_test_dir_setup(void **state)
{
    (void)state;
    free(g_dir);
    g_dir = ft_test_mkdtemp();
    return g_dir ? 0 : -1;
}

int ft_test_dir_teardown(void **state)
{
    (void)state;
    if (g_dir == NULL)
        return -1;
    ft_test_rmtree(g_dir);
    int left = ft_test_exists(g_dir);
    free(g_dir);
    g_dir = NULL;
    return left ? -1 : 0;
}

int ft_test_dir_empty(void **state)
{
    (void)state;
    if (g_dir == NULL)
        return -1;
    DIR *d = opendir(g_dir);
    if (d == NULL)
        return -1;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char *p = ft_test_path(g_dir, e->d_name);
        if (p)
            ft_test_rmtree(p); /* a file or a folder */
        free(p);
    }
    closedir(d);
    return ft_test_count_entries(g_dir) == 0 ? 0 : -1;
}

int ft_test_run_io_group(const char *name, const struct CMUnitTest *tests, size_t n, ft_test_dir_mode mode)
{
    struct CMUnitTest *t = calloc(n ? n : 1, sizeof *t);
    if (t == NULL)
        return -1;
    for (size_t i = 0; i < n; i++) {
        if (tests[i].setup_func != NULL || tests[i].teardown_func != NULL) {
            fprintf(stderr, "%s: %s has its own setup or teardown\n", name, tests[i].name);
            free(t);
            return -1;
        }
        t[i] = tests[i];
        t[i].setup_func = mode == FT_TEST_DIR_EACH ? ft_test_dir_setup : NULL;
        t[i].teardown_func = mode == FT_TEST_DIR_EACH ? ft_test_dir_teardown : ft_test_dir_empty;
    }
    ft_io_init();
    int shared = mode == FT_TEST_DIR_SHARED;
    int failed = _cmocka_run_group_tests(name, t, n, shared ? ft_test_dir_setup : NULL,
                                         shared ? ft_test_dir_teardown : NULL);
    ft_io_cleanup();
    free(t);
    return failed;
}

const char *ft_test_dir(void)
{
    assert_non_null(g_dir);
    return g_dir;
}

const char *ft_test_tmp(const char *name)
{
    static char buf[FT_TEST_TMP_BUFFERS][FT_TEST_TMP_SIZE];
    static int k;
    k = (k + 1) % FT_TEST_TMP_BUFFERS;
    int n = snprintf(buf[k], sizeof buf[k], "%s/%s", ft_test_dir(), name);
    assert_true(n > 0 && (size_t)n < sizeof buf[k]);
    return buf[k];
}

int ft_test_dir_count(void)
{
    int n = ft_test_count_entries(ft_test_dir());
    assert_true(n >= 0);
    return n;
}

void ft_test_put_text(const char *path, const char *text)
{
    assert_non_null(path);
    assert_int_equal(ft_test_write_text(path, text), 0);
}

const char *ft_test_tmp_text(const char *name, const char *text)
{
    const char *path = ft_test_tmp(name);
    ft_test_put_text(path, text);
    return path;
}

char *ft_test_read_svg(const char *path, size_t *size)
{
    char *s = ft_test_read_file(path, size);
    assert_non_null(s);
    assert_true(strncmp(s, "<?xml", 5) == 0);
    assert_non_null(strstr(s, "<svg"));
    assert_non_null(strstr(s, "</svg>"));
    return s;
}

void ft_test_assert_crs_epsg(const char *wkt, int epsg)
{
    assert_non_null(wkt);
    OGRSpatialReferenceH a = OSRNewSpatialReference(wkt), b = OSRNewSpatialReference(NULL);
    assert_non_null(a);
    assert_int_equal(OSRImportFromEPSG(b, epsg), OGRERR_NONE);
    assert_true(OSRIsSame(a, b));
    OSRDestroySpatialReference(a);
    OSRDestroySpatialReference(b);
}

void ft_test_assert_same_crs(const char *crs1, const char *crs2)
{
    assert_non_null(crs1);
    assert_non_null(crs2);
    OGRSpatialReferenceH a = OSRNewSpatialReference(NULL), b = OSRNewSpatialReference(NULL);
    assert_int_equal(OSRSetFromUserInput(a, crs1), OGRERR_NONE);
    assert_int_equal(OSRSetFromUserInput(b, crs2), OGRERR_NONE);
    assert_true(OSRIsSame(a, b));
    OSRDestroySpatialReference(a);
    OSRDestroySpatialReference(b);
}

void ft_test_assert_chain_equal(const ft_chain *a, const ft_chain *b)
{
    assert_int_equal(a->n, b->n);
    assert_int_equal(a->closed, b->closed);
    for (size_t i = 0; i < a->n; i++) {
        assert_true(a->x[i] == b->x[i]);
        assert_true(a->y[i] == b->y[i]);
    }
}

void ft_test_assert_layer_chains_equal(const ft_layer *a, const ft_layer *b)
{
    assert_int_equal(a->nparts, b->nparts);
    for (size_t p = 0; p < a->nparts; p++)
        ft_test_assert_chain_equal(a->parts[p].chain, b->parts[p].chain);
}

json_object *ft_test_json_key(json_object *o, const char *k)
{
    json_object *v = NULL;
    assert_true(json_object_object_get_ex(o, k, &v));
    return v;
}

int64_t ft_test_json_int(json_object *o, const char *k)
{
    return json_object_get_int64(ft_test_json_key(o, k));
}

const char *ft_test_json_str(json_object *o, const char *k)
{
    return json_object_get_string(ft_test_json_key(o, k));
}

ft_layer *ft_test_read_layer(const char *path)
{
    ft_layer *l = NULL;
    ft_read_layer_opts o = FT_READ_LAYER_OPTS_DEFAULT;
    if (ft_io_read_layer(path, &o, &l) != FT_OK)
        fprintf(stderr, "%s\n", ft_last_error());
    assert_non_null(l);
    return l;
}

ft_grid *ft_test_read_band(const char *path, int band)
{
    ft_grid *g = NULL;
    ft_read_grid_opts o = FT_READ_GRID_OPTS_DEFAULT;
    o.band = band;
    int rc = ft_io_read_grid(path, &o, &g);
    if (rc != FT_OK)
        fprintf(stderr, "%s band %d: %s\n", path, band, ft_last_error());
    assert_int_equal(rc, FT_OK);
    return g;
}

double ft_test_json_num(json_object *o, const char *k)
{
    return json_object_get_double(ft_test_json_key(o, k));
}

json_object *ft_test_json_at(json_object *a, size_t i)
{
    assert_true(i < json_object_array_length(a));
    return json_object_array_get_idx(a, i);
}

json_object *ft_test_run_json(const char *const *argv)
{
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    if (r.status != 0)
        fprintf(stderr, "fracterra %s %s: exit %d: %s", argv[0], argv[1] ? argv[1] : "", r.status, r.err);
    assert_int_equal(r.status, 0);
    json_object *o = ft_run_json(&r);
    assert_non_null(o);
    ft_run_free(&r);
    return o;
}

void ft_test_expect_failure(int code, const char *prefix, const char *needle, const char *const *argv)
{
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    char head[64];
    snprintf(head, sizeof head, "fracterra: %s: ", prefix);
    if (r.status != code || r.signaled || r.out_len != 0 || strstr(r.err, head) != r.err ||
        strstr(r.err, needle) == NULL)
        fprintf(stderr, "expected exit %d, '%s...%s'; got exit %d, stdout %zu bytes, stderr: %s", code, head,
                needle, r.status, r.out_len, r.err);
    assert_false(r.signaled);
    assert_int_equal(r.status, code);
    assert_int_equal(r.out_len, 0);
    assert_true(strstr(r.err, head) == r.err);
    assert_non_null(strstr(r.err, needle));
    ft_run_free(&r);
}
