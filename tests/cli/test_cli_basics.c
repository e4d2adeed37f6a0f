/* fracterra — tests/cli/test_cli_basics.c: the tool's global behaviour: --version, --help for the tool
 * and every command, exit code 2 and a "fracterra: ..." message for bad usage.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <string.h>

#include "fracterra/core.h"
#include "ft_test_run.h"

static const char *const commands[] = {"info", "demo", "dim", "enhance", "simplify", "weed", "smooth"};
#define NCOMMANDS (sizeof commands / sizeof commands[0])

static void test_version(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "--version", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_true(strncmp(r.out, "fracterra ", 10) == 0);
    assert_non_null(strstr(r.out, FT_VERSION_STRING));
    assert_int_equal(r.err_len, 0);
    ft_run_free(&r);
}

static void test_tool_help_lists_commands(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "--help", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "usage: fracterra"));
    for (size_t i = 0; i < NCOMMANDS; i++)
        assert_non_null(strstr(r.out, commands[i]));
    assert_non_null(strstr(r.out, "Example"));
    ft_run_free(&r);
}

static void test_no_arguments_is_usage_error(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "usage: fracterra"));
    assert_int_equal(r.out_len, 0);
    ft_run_free(&r);
}

/* Each command's --help and -h: usage line, options and an example on stdout, exit 0. */
static void test_command_help(void **state)
{
    for (size_t i = 0; i < NCOMMANDS; i++) {
        const char *flags[] = {"--help", "-h"};
        for (int k = 0; k < 2; k++) {
            ft_run_result r;
            assert_int_equal(ft_run(&r, commands[i], flags[k], NULL), 0);
            assert_int_equal(r.status, 0);
            char expect[64];
            snprintf(expect, sizeof expect, "usage: fracterra %s", commands[i]);
            assert_non_null(strstr(r.out, expect));
            assert_non_null(strstr(r.out, "Example"));
            assert_non_null(strstr(r.out, "--help"));
            assert_int_equal(r.err_len, 0);
            ft_run_free(&r);
        }
    }
}

static void test_help_command(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "help", "info", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "usage: fracterra info"));
    ft_run_free(&r);
}

static void test_unknown_command(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "frobnicate", "x", NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: frobnicate: unknown command"));
    assert_int_equal(r.out_len, 0);
    ft_run_free(&r);
}

static void test_unknown_global_option(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "--frobnicate", NULL), 0);
    assert_int_equal(r.status, 2);
    assert_true(strncmp(r.err, "fracterra: ", 11) == 0);
    assert_non_null(strstr(r.err, "--frobnicate"));
    ft_run_free(&r);
}

static void test_unknown_command_option(void **state)
{
    for (size_t i = 0; i < NCOMMANDS; i++) {
        ft_run_result r;
        char expect[96];
        assert_int_equal(ft_run(&r, commands[i], "--no-such-option", "x", NULL), 0);
        assert_int_equal(r.status, 2);
        snprintf(expect, sizeof expect, "fracterra: %s: unknown option '--no-such-option'", commands[i]);
        assert_non_null(strstr(r.err, expect));
        assert_non_null(strstr(r.err, "--help"));
        assert_int_equal(r.out_len, 0);
        ft_run_free(&r);
    }
}

static void test_missing_argument(void **state)
{
    const char *what[] = {"missing FILE",  "missing OUTDIR", "missing SUBCOMMAND", "missing INPUT",
                          "missing INPUT", "missing INPUT",  "missing INPUT"};
    assert_int_equal(sizeof what / sizeof what[0], NCOMMANDS); /* one message per command */
    for (size_t i = 0; i < NCOMMANDS; i++) {
        ft_run_result r;
        char expect[96];
        assert_int_equal(ft_run(&r, commands[i], NULL), 0);
        assert_int_equal(r.status, 2);
        snprintf(expect, sizeof expect, "fracterra: %s: %s", commands[i], what[i]);
        assert_non_null(strstr(r.err, expect));
        assert_int_equal(r.out_len, 0);
        ft_run_free(&r);
    }
}

static void test_option_missing_value(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", "--band", NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: info: option '--band' needs a value"));
    ft_run_free(&r);
}

static void test_bad_option_value(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", "--band", "zero", FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", NULL),
                     0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: info: --band"));
    assert_non_null(strstr(r.err, "'zero'"));
    ft_run_free(&r);
}

static void test_extra_argument(void **state)
{
    ft_run_result r;
    assert_int_equal(ft_run(&r, "info", FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", "surplus", NULL), 0);
    assert_int_equal(r.status, 2);
    assert_non_null(strstr(r.err, "fracterra: info: unexpected argument 'surplus'"));
    ft_run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_version),
        cmocka_unit_test(test_tool_help_lists_commands),
        cmocka_unit_test(test_no_arguments_is_usage_error),
        cmocka_unit_test(test_command_help),
        cmocka_unit_test(test_help_command),
        cmocka_unit_test(test_unknown_command),
        cmocka_unit_test(test_unknown_global_option),
        cmocka_unit_test(test_unknown_command_option),
        cmocka_unit_test(test_missing_argument),
        cmocka_unit_test(test_option_missing_value),
        cmocka_unit_test(test_bad_option_value),
        cmocka_unit_test(test_extra_argument),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
