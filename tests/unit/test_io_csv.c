/* fracterra — tests/unit/test_io_csv.c: the library's CSV tokenizer (ft_io_csv_*), the one reader behind
 * CSV points and the CLI's per-year tables: separators, RFC 4180 quoting, skipped lines, line numbers,
 * decimal commas, and an error naming file and line for each kind of broken text.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "fracterra/core.h"
#include "fracterra/io.h"
#include "ft_test_util.h"

static ft_io_csv *open_text(const char *name, const char *text)
{
    ft_io_csv *c = NULL;
    assert_int_equal(ft_io_csv_open(ft_test_tmp_text(name, text), &c), FT_OK);
    return c;
}

/* Reads the next record and checks its line and fields (a NULL-terminated list). */
static void expect_record(ft_io_csv *c, long line, const char *const *want)
{
    size_t n = 0, k = 0;
    char *const *f = NULL;
    assert_int_equal(ft_io_csv_next(c, &n, &f), 1);
    assert_int_equal(ft_io_csv_line(c), line);
    for (; want[k] != NULL; k++) {
        assert_true(k < n);
        assert_string_equal(f[k], want[k]);
    }
    assert_int_equal(n, k);
}
#define EXPECT_RECORD(c, line, ...) expect_record(c, line, (const char *const[]){__VA_ARGS__, NULL})

static void test_separators(void **state)
{
    (void)state;
    ft_io_csv *c = open_text("comma.csv", "x,y,z\n1,2,3\n");
    assert_int_equal(ft_io_csv_separator(c), ',');
    EXPECT_RECORD(c, 2, "1", "2", "3");
    ft_io_csv_close(c);
    c = open_text("semi.csv", "x;y;z\n1,5;2;3\n");
    assert_int_equal(ft_io_csv_separator(c), ';');
    EXPECT_RECORD(c, 2, "1,5", "2", "3");
    ft_io_csv_close(c);
    /* tab: empty fields are kept (blanks are spaces only) */
    c = open_text("tab.csv", "x\ty\tz\n1\t\t3\n");
    assert_int_equal(ft_io_csv_separator(c), '\t');
    EXPECT_RECORD(c, 2, "1", "", "3");
    ft_io_csv_close(c);
}

/* Quoted fields hold separators, doubled quotes and line breaks; the next record's line number follows. */
static void test_quoting_and_lines(void **state)
{
    (void)state;
    ft_io_csv *c = open_text("q.csv", "\xEF\xBB\xBF" "name,\"area, m2\"\r\n"
                                      "# a comment\r\n"
                                      "\r\n"
                                      "  \"say \"\"hi\"\"\" , 12 \r\n"
                                      "\"two\nlines\",3\n"
                                      "last,4");
    char *const *head = NULL;
    assert_int_equal(ft_io_csv_header(c, &head), 2);
    assert_string_equal(head[0], "name");
    assert_string_equal(head[1], "area, m2");
    size_t col = 9;
    assert_int_equal(ft_io_csv_find(c, "AREA, M2", &col), FT_OK);
    assert_int_equal(col, 1);
    EXPECT_RECORD(c, 4, "say \"hi\"", "12");
    EXPECT_RECORD(c, 5, "two\nlines", "3");
    EXPECT_RECORD(c, 7, "last", "4");
    size_t n;
    char *const *f;
    assert_int_equal(ft_io_csv_next(c, &n, &f), 0);
    ft_io_csv_close(c);
}

static void test_numbers(void **state)
{
    (void)state;
    double v = 0.0;
    ft_io_csv *semi = open_text("s.csv", "a;b\n");
    ft_io_csv *comma = open_text("c.csv", "a,b\n");
    assert_true(ft_io_csv_number(semi, "2,5", &v) && v == 2.5);
    assert_true(ft_io_csv_number(semi, " -1.25e3 ", &v) && v == -1250.0);
    assert_false(ft_io_csv_number(semi, "1,000,5", &v));
    assert_false(ft_io_csv_number(comma, "2,5", &v));
    assert_false(ft_io_csv_number(NULL, "2,5", &v));
    assert_false(ft_io_csv_number(semi, "", &v));
    assert_false(ft_io_csv_number(semi, "12 m", &v));
    ft_io_csv_close(semi);
    ft_io_csv_close(comma);
}

static void expect_error(const char *name, const char *text, int code, const char *needle)
{
    const char *path = ft_test_tmp_text(name, text);
    ft_io_csv *c = NULL;
    int rc = ft_io_csv_open(path, &c);
    size_t n;
    char *const *f;
    if (rc == FT_OK)
        while ((rc = ft_io_csv_next(c, &n, &f)) == 1)
            ;
    ft_io_csv_close(c);
    assert_int_equal(rc, code);
    assert_non_null(strstr(ft_last_error(), name));
    if (strstr(ft_last_error(), needle) == NULL)
        fail_msg("'%s' does not say '%s'", ft_last_error(), needle);
}

static void test_broken_text(void **state)
{
    (void)state;
    expect_error("empty.csv", "\n  \n# only a comment\n", FT_E_EMPTY, "no header row");
    expect_error("after.csv", "a,b\n1,2\n\"x\"y,3\n", FT_E_FORMAT, ":3: text after the closing quote of field 1");
    expect_error("open.csv", "a,b\n1,2\n\"never closed,3\n4,5\n", FT_E_FORMAT, ":3: a quoted field is not closed");
    ft_io_csv *c = NULL;
    static const char nul[] = "a,b\n1,2\n3\0,4\n";
    FILE *f = fopen(ft_test_tmp("nul.csv"), "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(nul, 1, sizeof nul - 1, f), sizeof nul - 1);
    assert_int_equal(fclose(f), 0);
    assert_int_equal(ft_io_csv_open(ft_test_tmp("nul.csv"), &c), FT_OK);
    size_t n;
    char *const *fields;
    assert_int_equal(ft_io_csv_next(c, &n, &fields), 1);
    assert_int_equal(ft_io_csv_next(c, &n, &fields), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "nul.csv:3: a NUL byte"));
    ft_io_csv_close(c);
    c = NULL;
    assert_int_equal(ft_io_csv_open(ft_test_tmp("absent.csv"), &c), FT_E_IO);
    assert_null(c);
    c = open_text("cols.csv", "x,y\n");
    size_t col;
    assert_int_equal(ft_io_csv_find(c, "z", &col), FT_E_FORMAT);
    assert_non_null(strstr(ft_last_error(), "has no column 'z' (columns: x, y)"));
    ft_io_csv_close(c);
    ft_io_csv_close(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_separators),
        cmocka_unit_test(test_quoting_and_lines),
        cmocka_unit_test(test_numbers),
        cmocka_unit_test(test_broken_text),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
