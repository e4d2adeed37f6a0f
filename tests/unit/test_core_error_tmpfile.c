/* fracterra — unit tests of core/error.c, alloc.c, progress.c, version.c and tmpfile.c.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fracterra/core.h"
#include "fracterra/io.h"
#include "ft_test_util.h"
#include "internal.h"

static void test_version(void **state)
{
    (void)state;
    assert_string_equal(ft_version(), "0.1.0");
    assert_string_equal(ft_version(), FT_VERSION_STRING);
}

static void test_error_message_and_code(void **state)
{
    (void)state;
    ft_clear_error();
    assert_int_equal(ft_last_error_code(), FT_OK);
    assert_string_equal(ft_last_error(), "");
    assert_int_equal(ft_error(FT_E_INVALID, "sd must be in [1,2], got %.1f", 2.7), FT_E_INVALID);
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    assert_string_equal(ft_last_error(), "sd must be in [1,2], got 2.7");
    /* the previous message may be used to add context */
    ft_error(FT_E_IO, "reading '%s': %s", "dem.tif", ft_last_error());
    assert_string_equal(ft_last_error(), "reading 'dem.tif': sd must be in [1,2], got 2.7");
    assert_int_equal(ft_last_error_code(), FT_E_IO);
    ft_clear_error();
    assert_int_equal(ft_last_error_code(), FT_OK);
    assert_string_equal(ft_last_error(), "");
}

static void test_long_message_is_truncated(void **state)
{
    (void)state;
    char big[5000];
    memset(big, 'a', sizeof big - 1);
    big[sizeof big - 1] = '\0';
    ft_error(FT_E_FORMAT, "%s", big);
    size_t len = strlen(ft_last_error());
    assert_true(len > 500 && len < 2048);
    assert_int_equal(ft_last_error_code(), FT_E_FORMAT);
}

static void test_strerror(void **state)
{
    (void)state;
    const int codes[] = {FT_OK, FT_E_INVALID, FT_E_NOMEM, FT_E_IO, FT_E_FORMAT, FT_E_EMPTY,
                         FT_E_CANCELLED, FT_E_NUMERIC, FT_E_UNSUPPORTED};
    const int n = (int)(sizeof codes / sizeof codes[0]);
    for (int i = 0; i < n; i++) {
        assert_true(strlen(ft_strerror(codes[i])) > 0);
        for (int j = 0; j < i; j++)
            assert_string_not_equal(ft_strerror(codes[i]), ft_strerror(codes[j]));
    }
    assert_string_equal(ft_strerror(-1234), "unknown error");
}

static void *thread_sets_error(void *arg)
{
    (void)arg;
    ft_error(FT_E_NUMERIC, "from the thread");
    return (void *)(intptr_t)(ft_last_error_code() == FT_E_NUMERIC &&
                              strcmp(ft_last_error(), "from the thread") == 0);
}

static void test_error_is_thread_local(void **state)
{
    (void)state;
    ft_error(FT_E_EMPTY, "main thread");
    pthread_t th;
    void *ok = NULL;
    assert_int_equal(pthread_create(&th, NULL, thread_sets_error, NULL), 0);
    assert_int_equal(pthread_join(th, &ok), 0);
    assert_true(ok != NULL);
    assert_int_equal(ft_last_error_code(), FT_E_EMPTY);
    assert_string_equal(ft_last_error(), "main thread");
}

static void test_alloc_helpers(void **state)
{
    (void)state;
    void *p = ft_malloc(0);
    assert_non_null(p);
    free(p);
    int *a = ft_calloc(10, sizeof *a);
    assert_non_null(a);
    assert_int_equal(a[9], 0);
    int *b = ft_realloc_array(a, 1000, sizeof *b);
    assert_non_null(b);
    free(b);
    assert_null(ft_strdup(NULL));
    char *s = ft_strdup("fracterra");
    assert_string_equal(s, "fracterra");
    free(s);

    ft_clear_error();
    assert_null(ft_calloc(SIZE_MAX / 2, 4));
    assert_int_equal(ft_last_error_code(), FT_E_NOMEM);
    char num[32];
    snprintf(num, sizeof num, "%zu", SIZE_MAX / 2);
    assert_non_null(strstr(ft_last_error(), num));
    char keep[4] = "abc";
    char *k = malloc(4);
    memcpy(k, keep, 4);
    assert_null(ft_realloc_array(k, SIZE_MAX, 2)); /* overflow: k is left untouched */
    assert_int_equal(ft_last_error_code(), FT_E_NOMEM);
    assert_string_equal(k, "abc");
    free(k);
#if !defined(__SANITIZE_ADDRESS__)
    /* AddressSanitizer aborts on impossible sizes instead of returning NULL */
    size_t huge = SIZE_MAX - 4096;
    assert_null(ft_malloc(huge));
    assert_int_equal(ft_last_error_code(), FT_E_NOMEM);
    snprintf(num, sizeof num, "%zu bytes", huge);
    assert_non_null(strstr(ft_last_error(), num));
#endif
}

static int stop_at_half(double frac, const char *msg, void *arg)
{
    (void)msg;
    *(double *)arg = frac;
    return frac < 0.5;
}

static void test_progress(void **state)
{
    (void)state;
    double last = -1.0;
    assert_int_equal(ft_progress(NULL, NULL, 0.3, "x"), FT_OK);
    assert_int_equal(ft_progress(stop_at_half, &last, 0.25, "rows"), FT_OK);
    assert_true(last == 0.25);
    assert_int_equal(ft_progress(stop_at_half, &last, 0.75, "rows"), FT_E_CANCELLED);
    assert_int_equal(ft_last_error_code(), FT_E_CANCELLED);
    assert_non_null(strstr(ft_last_error(), "cancelled"));
    assert_int_equal(ft_progress(stop_at_half, &last, 7.0, NULL), FT_E_CANCELLED);
    assert_true(last == 1.0); /* clamped to [0, 1] */
    assert_int_equal(ft_progress(stop_at_half, &last, -3.0, NULL), FT_OK);
    assert_true(last == 0.0);
}

/* ---- temporary output files ---------------------------------------------------------------- */

/* Writes a file holding its own path. */
static void touch(const char *path)
{
    ft_test_put_text(path, path);
}

static int count_entries(const char *needle)
{
    DIR *d = opendir(ft_test_dir());
    struct dirent *e;
    int n = 0;
    while ((e = readdir(d)) != NULL)
        n += strstr(e->d_name, needle) != NULL;
    closedir(d);
    return n;
}

/* tmp with its extension replaced by ext (tmp ends with ".shp"). */
static void sibling(char *out, size_t size, const char *tmp, const char *ext)
{
    snprintf(out, size, "%.*s%s", (int)(strlen(tmp) - 4), tmp, ext);
}

static void test_tmp_path_form(void **state)
{
    (void)state;
    char path[512], prefix[512];
    snprintf(path, sizeof path, "%s/a.b.tif", ft_test_dir());
    char *t1 = ft_io_atomic_tmp(path), *t2 = ft_io_atomic_tmp(path);
    assert_non_null(t1);
    assert_non_null(t2);
    snprintf(prefix, sizeof prefix, "%s/.a.b.ft-tmp-%ld-", ft_test_dir(), (long)getpid());
    assert_memory_equal(t1, prefix, strlen(prefix));
    assert_string_equal(t1 + strlen(t1) - 4, ".tif"); /* the LAST extension only */
    assert_string_not_equal(t1, t2);
    free(t1);
    free(t2);

    t1 = ft_io_atomic_tmp("relative.gpkg");
    assert_non_null(t1);
    snprintf(prefix, sizeof prefix, ".relative.ft-tmp-%ld-", (long)getpid());
    assert_memory_equal(t1, prefix, strlen(prefix));
    assert_string_equal(t1 + strlen(t1) - 5, ".gpkg");
    free(t1);

    snprintf(path, sizeof path, "%s/noext", ft_test_dir());
    t1 = ft_io_atomic_tmp(path);
    snprintf(prefix, sizeof prefix, "%s/.noext.ft-tmp-", ft_test_dir());
    assert_memory_equal(t1, prefix, strlen(prefix));
    assert_null(strchr(t1 + strlen(prefix), '.'));
    free(t1);
}

static void test_tmp_path_missing_folder(void **state)
{
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/no-such-folder/out.tif", ft_test_dir());
    assert_null(ft_io_atomic_tmp(path));
    assert_int_equal(ft_last_error_code(), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "no-such-folder"));
    assert_null(ft_io_atomic_tmp(""));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
    snprintf(path, sizeof path, "%s/", ft_test_dir());
    assert_null(ft_io_atomic_tmp(path));
    assert_int_equal(ft_last_error_code(), FT_E_INVALID);
}

static void test_commit_renames_siblings(void **state)
{
    (void)state;
    char path[512], tmp_sib[600], other[600], final[600];
    snprintf(path, sizeof path, "%s/roads.shp", ft_test_dir());
    char *tmp = ft_io_atomic_tmp(path);
    assert_non_null(tmp);
    touch(tmp);
    const char *exts[] = {".shx", ".dbf", ".prj", ".cpg"};
    for (int i = 0; i < 4; i++) {
        sibling(tmp_sib, sizeof tmp_sib, tmp, exts[i]);
        touch(tmp_sib);
    }
    /* the temp of another writer whose counter merely starts with ours must not be touched */
    sibling(other, sizeof other, tmp, "0.shx");
    touch(other);
    assert_int_equal(ft_io_atomic_commit(tmp, path), FT_OK);
    assert_true(ft_test_exists(path));
    assert_false(ft_test_exists(tmp));
    for (int i = 0; i < 4; i++) {
        snprintf(final, sizeof final, "%s/roads%s", ft_test_dir(), exts[i]);
        assert_true(ft_test_exists(final));
    }
    assert_true(ft_test_exists(other));
    assert_int_equal(count_entries("ft-tmp"), 1);
    remove(other);
    free(tmp);
}

static void test_commit_replaces_existing(void **state)
{
    (void)state;
    char path[512];
    snprintf(path, sizeof path, "%s/dem.tif", ft_test_dir());
    touch(path);
    char *tmp = ft_io_atomic_tmp(path);
    FILE *f = fopen(tmp, "w");
    fputs("new", f);
    fclose(f);
    assert_int_equal(ft_io_atomic_commit(tmp, path), FT_OK);
    char buf[8] = {0};
    f = fopen(path, "r");
    assert_non_null(fgets(buf, sizeof buf, f));
    fclose(f);
    assert_string_equal(buf, "new");
    free(tmp);
}

static void test_discard_removes_all(void **state)
{
    (void)state;
    char path[512], tmp_sib[600];
    snprintf(path, sizeof path, "%s/parcels.shp", ft_test_dir());
    char *tmp = ft_io_atomic_tmp(path);
    touch(tmp);
    sibling(tmp_sib, sizeof tmp_sib, tmp, ".shx");
    touch(tmp_sib);
    sibling(tmp_sib, sizeof tmp_sib, tmp, ".dbf");
    touch(tmp_sib);
    ft_error(FT_E_FORMAT, "writer failed");
    ft_io_atomic_discard(tmp);
    assert_int_equal(count_entries("parcels"), 0);
    assert_false(ft_test_exists(path));
    /* discarding keeps the error that caused it */
    assert_int_equal(ft_last_error_code(), FT_E_FORMAT);
    assert_string_equal(ft_last_error(), "writer failed");
    ft_io_atomic_discard(tmp); /* twice is harmless */
    ft_io_atomic_discard(NULL);
    free(tmp);
}

static void test_commit_failure_names_path_and_cleans_up(void **state)
{
    (void)state;
    char path[512], keep[600];
    snprintf(path, sizeof path, "%s/busy.tif", ft_test_dir());
    assert_int_equal(mkdir(path, 0700), 0); /* a non-empty folder where the file should go */
    snprintf(keep, sizeof keep, "%s/keep", path);
    touch(keep);
    char *tmp = ft_io_atomic_tmp(path);
    touch(tmp);
    assert_int_equal(ft_io_atomic_commit(tmp, path), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), path));
    assert_false(ft_test_exists(tmp));
    assert_int_equal(count_entries("ft-tmp"), 0);
    free(tmp);

    /* a temp that was never written */
    snprintf(path, sizeof path, "%s/never.tif", ft_test_dir());
    tmp = ft_io_atomic_tmp(path);
    assert_int_equal(ft_io_atomic_commit(tmp, path), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "never.tif"));
    assert_false(ft_test_exists(path));
    free(tmp);
    assert_int_equal(ft_io_atomic_commit("/tmp/not-a-temp.tif", path), FT_E_INVALID);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_error_message_and_code),
        cmocka_unit_test(test_long_message_is_truncated),
        cmocka_unit_test(test_strerror),
        cmocka_unit_test(test_error_is_thread_local),
        cmocka_unit_test(test_alloc_helpers),
        cmocka_unit_test(test_progress),
    };
    const struct CMUnitTest tmp_tests[] = {
        cmocka_unit_test(test_tmp_path_form),
        cmocka_unit_test(test_tmp_path_missing_folder),
        cmocka_unit_test(test_commit_renames_siblings),
        cmocka_unit_test(test_commit_replaces_existing),
        cmocka_unit_test(test_discard_removes_all),
        cmocka_unit_test(test_commit_failure_names_path_and_cleans_up),
    };
    int failed = cmocka_run_group_tests_name("errors", tests, NULL, NULL);
    failed += cmocka_run_group_tests_name("tmpfile", tmp_tests, ft_test_dir_setup, ft_test_dir_teardown);
    return failed;
}
