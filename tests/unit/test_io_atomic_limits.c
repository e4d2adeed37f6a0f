/* fracterra — tests/unit/test_io_atomic_limits.c: the atomic-write service's checked stdio writer and
 * same-file test (src/io/atomic_write.c), and the memory/work bounds (src/core/limits.c).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fracterra/fracterra.h"
#include "ft_test_run.h"

static char *dir;

static int setup(void **state)
{
    dir = ft_test_mkdtemp();
    return dir ? 0 : -1;
}

static int teardown(void **state)
{
    ft_test_rmtree(dir);
    free(dir);
    return 0;
}

static int write_new(FILE *f, const void *arg)
{
    fputs((const char *)arg, f);
    return FT_OK;
}

static int fail_half_way(FILE *f, const void *arg)
{
    fputs("half", f);
    return ft_error(FT_E_NUMERIC, "the writer gave up");
}

static void test_atomic_write_keeps_old_on_failure(void **state)
{
    char *p = ft_test_path(dir, "a.txt");
    assert_int_equal(ft_io_atomic_write(p, write_new, "first\n"), FT_OK);
    assert_int_equal(ft_io_atomic_write(p, fail_half_way, NULL), FT_E_NUMERIC);
    assert_string_equal(ft_last_error(), "the writer gave up");
    char *text = ft_test_read_file(p, NULL);
    assert_string_equal(text, "first\n");
    free(text);
    assert_int_equal(ft_test_count_entries(dir), 1); /* no temporary left */
    assert_int_equal(ft_io_atomic_write(p, write_new, "second\n"), FT_OK);
    text = ft_test_read_file(p, NULL);
    assert_string_equal(text, "second\n");
    free(text);
    remove(p);
    free(p);
}

static void test_atomic_write_missing_folder(void **state)
{
    assert_int_equal(ft_io_atomic_write("/nonexistent-fracterra/x.txt", write_new, "x"), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "/nonexistent-fracterra"));
}

static void test_same_file(void **state)
{
    char *a = ft_test_path(dir, "s.txt"), *hard = ft_test_path(dir, "hard.txt"), *sym = ft_test_path(dir, "sym.txt");
    char *dotted = ft_test_path(dir, "./s.txt"), *fresh = ft_test_path(dir, "fresh.txt");
    assert_int_equal(ft_test_write_text(a, "x"), 0);
    assert_int_equal(link(a, hard), 0);
    assert_int_equal(symlink(a, sym), 0);
    assert_int_equal(ft_io_same_file(a, a), 1);
    assert_int_equal(ft_io_same_file(a, hard), 1);   /* same inode */
    assert_int_equal(ft_io_same_file(sym, a), 1);    /* resolved */
    assert_int_equal(ft_io_same_file(a, dotted), 1);
    assert_int_equal(ft_io_same_file(a, fresh), 0);  /* not created yet, another name */
    assert_int_equal(ft_io_same_file(fresh, fresh), 1);
    assert_int_equal(ft_io_same_file("-", "-"), 0);  /* stdin and stdout */
    remove(a);
    remove(hard);
    remove(sym);
    free(a);
    free(hard);
    free(sym);
    free(dotted);
    free(fresh);
}

static void test_memory_and_work_bounds(void **state)
{
    assert_true(ft_memory_limit() > 0);
    ft_set_memory_limit((size_t)1 << 20);
    assert_int_equal(ft_memory_limit(), (size_t)1 << 20);
    assert_int_equal(ft_check_memory(1048576.0, "exactly the limit"), FT_OK);
    assert_int_equal(ft_check_memory(3.0 * 1048576.0, "--size 9x9"), FT_E_NOMEM);
    assert_non_null(strstr(ft_last_error(), "--size 9x9 would need 3 MB"));
    assert_non_null(strstr(ft_last_error(), "--max-memory"));
    assert_int_equal(ft_check_memory(INFINITY, "--iterations 4000"), FT_E_NOMEM);
    assert_null(strstr(ft_last_error(), "inf ")); /* no bare inf in the message */
    ft_set_memory_limit(0);
    assert_true(ft_memory_limit() > ((size_t)1 << 20));
    ft_set_work_limit(100.0);
    assert_int_equal(ft_check_work(100.0, "a"), FT_OK);
    assert_int_equal(ft_check_work(101.0, "--min-scale 1e-9"), FT_E_UNSUPPORTED);
    assert_non_null(strstr(ft_last_error(), "--min-scale 1e-9 would take 101 steps"));
    ft_set_work_limit(0.0);
    assert_true(ft_work_limit() == FT_WORK_LIMIT_DEFAULT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_atomic_write_keeps_old_on_failure),
        cmocka_unit_test(test_atomic_write_missing_folder),
        cmocka_unit_test(test_same_file),
        cmocka_unit_test(test_memory_and_work_bounds),
    };
    return cmocka_run_group_tests_name("io_atomic_limits", tests, setup, teardown);
}
