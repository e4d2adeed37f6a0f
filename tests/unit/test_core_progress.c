/* fracterra — tests/unit/test_core_progress.c: Core's scaled progress (src/internal.h): stages nested in a
 * job report fractions of the caller's whole range, clamped, and a cancel from the callback stops them.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmocka.h>

#include "fracterra/core.h"
#include "internal.h"

typedef struct {
    double last;
    int calls, stop_above; /* the callback returns 0 once a fraction exceeds stop_above percent */
} seen;

static int record(double frac, const char *msg, void *arg)
{
    (void)msg;
    seen *s = arg;
    s->last = frac;
    s->calls++;
    return !(100.0 * frac > s->stop_above);
}

static void test_nested_ranges(void **state)
{
    (void)state;
    seen s = {-1.0, 0, 101};
    ft_progress_range whole = ft_progress_range_whole(record, &s);
    ft_progress_range second = ft_progress_range_sub(&whole, 0.2, 0.6); /* 20 % .. 60 % */
    ft_progress_range inner = ft_progress_range_sub(&second, 0.5, 1.0); /* 40 % .. 60 % */
    assert_int_equal(ft_progress_range_report(&whole, 0.1, "a"), FT_OK);
    assert_true(s.last == 0.1);
    assert_int_equal(ft_progress_range_report(&second, 0.5, "b"), FT_OK);
    assert_true(s.last > 0.4 - 1e-15 && s.last < 0.4 + 1e-15);
    assert_int_equal(ft_progress_range_report(&inner, 0.5, "c"), FT_OK);
    assert_true(s.last > 0.5 - 1e-15 && s.last < 0.5 + 1e-15);
    assert_int_equal(ft_progress_range_report(&inner, 7.0, "clamped"), FT_OK);
    assert_true(s.last > 0.6 - 1e-15 && s.last < 0.6 + 1e-15);
    assert_int_equal(ft_progress_range_report(&inner, -3.0, "clamped"), FT_OK);
    assert_true(s.last > 0.4 - 1e-15 && s.last < 0.4 + 1e-15);
    assert_int_equal(s.calls, 5);
}

static void test_silent_and_cancel(void **state)
{
    (void)state;
    assert_int_equal(ft_progress_range_report(NULL, 0.5, "x"), FT_OK);
    ft_progress_range none = ft_progress_range_sub(NULL, 0.0, 1.0);
    assert_null(none.fn);
    assert_int_equal(ft_progress_range_report(&none, 0.5, "x"), FT_OK);
    seen s = {-1.0, 0, 50};
    ft_progress_range whole = ft_progress_range_whole(record, &s);
    ft_progress_range late = ft_progress_range_sub(&whole, 0.4, 0.8);
    assert_int_equal(ft_progress_range_report(&late, 0.2, "ok"), FT_OK);           /* 48 % */
    assert_int_equal(ft_progress_range_report(&late, 0.5, "stop"), FT_E_CANCELLED); /* 60 % */
    assert_int_equal(ft_last_error_code(), FT_E_CANCELLED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nested_ranges),
        cmocka_unit_test(test_silent_and_cancel),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
