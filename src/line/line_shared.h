/* fracterra — src/line/line_shared.h: what Line offers the library's other parts (Urban counts the boxes
 * its polygon rings cross with Line's exact cell traversal, box_count.c). Not installed. Other parts include
 * this header, never Line's *_internal.h (docs/architecture.md).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_SHARED_H
#define FRACTERRA_LINE_SHARED_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/core.h"

/** Box counting at one box side: the fewest cells crossed over k x k grid origins offset by multiples of
 *  size / k from (ox, oy). Chains with fewer than 2 vertices count their single vertex's cell (n = 1) or
 *  nothing. Fails with FT_E_INVALID if the traversal would visit more than FT_BOX_MAX_CELLS cells,
 *  FT_E_NOMEM if memory runs out. */
int ft_line_box_count_min(const ft_chain *const *chains, size_t n, double size, int k, double ox, double oy,
                          uint64_t *count);
/** The same count over the k x k origins: the fewest (fewest, may be NULL) and the mean (mean, may be NULL;
 *  an unbiased estimate of the count of a randomly placed grid). */
int ft_line_box_count_offsets(const ft_chain *const *chains, size_t n, double size, int k, double ox, double oy,
                              uint64_t *fewest, double *mean);

/** Upper bound on the cells one box count may visit (keeps memory and time bounded for tiny boxes). */
#define FT_BOX_MAX_CELLS ((uint64_t)1 << 30)

#endif /* FRACTERRA_LINE_SHARED_H */
