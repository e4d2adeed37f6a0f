/* fracterra — tests/support/ft_test_assert.h: assertions shared by the unit tests (include <cmocka.h>
 * first): a double within a tolerance (cmocka 1.1 compares floats only), and an error code with a message
 * naming a text.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_ASSERT_H
#define FT_TEST_ASSERT_H

#include <math.h>
#include <string.h>

#include "fracterra/core.h"

/** Fails the test at file:line unless |a - b| <= tol (NaN never is); what names the value checked. */
static inline void ft_test_check_near(double a, double b, double tol, const char *what, const char *file,
                                      int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%s: %.17g != %.17g (tolerance %g)\n", what, a, b, tol);
        _fail(file, line);
    }
}
/** |a - b| <= tol, printing both values (and the expression a) if not. */
#define assert_near(a, b, tol) ft_test_check_near((a), (b), (tol), #a, __FILE__, __LINE__)

/** rc equals code and ft_last_error() contains text. */
#define assert_error_names(rc, code, text)                                                                   \
    do {                                                                                                     \
        assert_int_equal((rc), (code));                                                                      \
        if (strstr(ft_last_error(), (text)) == NULL) {                                                       \
            print_error("error \"%s\" does not name \"%s\"\n", ft_last_error(), (text));                    \
            _fail(__FILE__, __LINE__);                                                                       \
        }                                                                                                    \
    } while (0)

#endif /* FT_TEST_ASSERT_H */
