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

/** Adds s's counts to *to (every guard and operation that reports moves). */
static inline void ft_line_guard_stats_add(ft_line_guard_stats *to, const ft_line_guard_stats *s)
{
    to->moves += s->moves;
    to->reduced += s->reduced;
    to->dropped += s->dropped;
    to->redrawn += s->redrawn;
}

/** The non-local blocks in groups: block[group_start[k] .. group_start[k + 1]) are group k's, in block
 *  order. Two non-local blocks one of which reads a vertex the other owns are in the same group; group k's
 *  blocks and the blocks they read lie in chunks chunk_lo[k] .. chunk_hi[k]. */
typedef struct {
    size_t ngroup;
    uint32_t *group_start; /**< ngroup + 1 offsets into block */
    uint32_t *block;
    uint32_t *chunk_lo, *chunk_hi;
} ft_guard_schedule;

/** The schedule of the blocks b of g with local[b] == 0 (chains: those g indexes, for their closedness). */
int ft_guard_schedule_build(ft_guard_schedule *s, const ft_segment_blocks *g, const ft_chain *const *chains,
                            const unsigned char *local);
void ft_guard_schedule_free(ft_guard_schedule *s);

/** Walks the moves of the vertices owned by the blocks b in [lo, hi) with local[b] == want, in block order,
 *  adding the counts to *s. */
typedef void (*ft_guard_walk_fn)(const void *ctx, unsigned char want, size_t lo, size_t hi, ft_line_guard_stats *s);

/** A guard's walk of every block of g (local: ft_segment_blocks_mark_local), with the result of the serial
 *  order on any thread count: each chunk's local blocks (in block order), then the other blocks in block
 *  order. On one thread just so; else the chunks in parallel, and the schedule's groups as soon as it is
 *  built and the chunks they touch are walked. Adds the counts to *s. */
void ft_guard_walk(const ft_segment_blocks *g, const ft_chain *const *chains, const unsigned char *local,
                   ft_guard_walk_fn walk, const void *ctx, ft_line_guard_stats *s);

#endif /* FRACTERRA_LINE_GUARD_SCHEDULE_H */
