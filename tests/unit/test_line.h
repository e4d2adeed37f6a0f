/* fracterra — tests/unit/test_line.h: a helper the Dutton tests share (include <cmocka.h> first): the
 * divider dimension of one chain over a range of rulers.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_LINE_H
#define FT_TEST_LINE_H

#include "fracterra/line.h"

/** Divider D of a chain over [lo, hi], 12 rulers, every scale fitted; fails the test (printing the error)
 *  unless it succeeds. Free the result with ft_dim_result_free. */
static inline ft_dim_result *line_divider_fit(const ft_chain *c, double lo, double hi)
{
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.min_scale = lo;
    o.max_scale = hi;
    o.nscales = 12;
    o.fit_whole_range = 1;
    ft_dim_result *res = NULL;
    const ft_chain *chains[] = {c};
    int rc = ft_line_dim(chains, 1, FT_LINE_DIVIDER, &o, &res);
    if (rc != FT_OK)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    return res;
}

#endif /* FT_TEST_LINE_H */
