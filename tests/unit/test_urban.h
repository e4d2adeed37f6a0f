/* fracterra — tests/unit/test_urban.h: the assertions the urban tests share (include <cmocka.h>, <math.h>
 * and <string.h> first): an error code with a message naming a text, and a value within a tolerance.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_URBAN_H
#define FT_TEST_URBAN_H

#include "fracterra/core.h"

#define assert_error_names(rc, code, text)                                                                   \
    do {                                                                                                     \
        assert_int_equal((rc), (code));                                                                      \
        if (strstr(ft_last_error(), (text)) == NULL) {                                                       \
            print_error("error \"%s\" does not name \"%s\"\n", ft_last_error(), (text));                    \
            _fail(__FILE__, __LINE__);                                                                       \
        }                                                                                                    \
    } while (0)

static inline void check_near(double a, double b, double tol, const char *what, const char *file, int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%s: %.6f is not within %g of %.6f\n", what, a, tol, b);
        _fail(file, line);
    }
}
#define assert_near(a, b, tol) check_near((a), (b), (tol), #a, __FILE__, __LINE__)

#endif /* FT_TEST_URBAN_H */
