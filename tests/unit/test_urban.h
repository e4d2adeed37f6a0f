/* fracterra — tests/unit/test_urban.h: the assertions the urban tests share (include <cmocka.h> first): an
 * error code with a message naming a text, and a value within a tolerance, both from ft_test_assert.h.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_URBAN_H
#define FT_TEST_URBAN_H

#include "fracterra/core.h"
#include "ft_test_assert.h"

#endif /* FT_TEST_URBAN_H */
