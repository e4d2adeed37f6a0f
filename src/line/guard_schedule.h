/* fracterra — line/guard_schedule.h: the second phase of the crossing guards' walk (the blocks that are not
 * local to their chunk, ft_segment_blocks_mark_local) in parallel, with the bits of the serial walk in block
 * order (guard_schedule.c). Used by move_guard.c and dutton_guarded.c.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_GUARD_SCHEDULE_H
#define FRACTERRA_LINE_GUARD_SCHEDULE_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/line.h"
#include "line/segment_index.h"

/** The non-local blocks in groups: block[group_start[k] .. group_start[k + 1]) are group k's, in block
 *  order. Two non-local blocks one of which reads a vertex the other owns are in the same group. */
typedef struct {
    size_t ngroup;
    uint32_t *group_start; /**< ngroup + 1 offsets into block */
    uint32_t *block;
} ft_guard_schedule;

/** The schedule of the blocks b of g with local[b] == 0 (chains: those g indexes, for their closedness). */
int ft_guard_schedule_build(ft_guard_schedule *s, const ft_segment_blocks *g, const ft_chain *const *chains,
                            const unsigned char *local);
void ft_guard_schedule_free(ft_guard_schedule *s);

/** Walks the moves of the vertices owned by block b, adding its counts to *s. */
typedef void (*ft_guard_walk_fn)(const void *ctx, size_t b, ft_line_guard_stats *s);

/** Walks every block b of g with local[b] == 0 (the local ones walked already), with the result of walking
 *  them one after another in block order, on any thread count: on one thread (or if the schedule cannot be
 *  allocated) in block order, else the schedule's groups in parallel, each in block order. Adds the
 *  counts to *s. */
void ft_guard_walk_nonlocal(const ft_segment_blocks *g, const ft_chain *const *chains, const unsigned char *local,
                            ft_guard_walk_fn walk, const void *ctx, ft_line_guard_stats *s);

#endif /* FRACTERRA_LINE_GUARD_SCHEDULE_H */
