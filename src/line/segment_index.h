/* fracterra — line/segment_index.h: the index of segment blocks of segment_index.c, used by the crossing
 * guard (move_guard.c).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_LINE_SEGMENT_INDEX_H
#define FRACTERRA_LINE_SEGMENT_INDEX_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "fracterra/core.h"

/** Segments per block (the last block of a chain may hold fewer). */
#define FT_SEGMENT_BLOCK 8

/** Chain c's segment s (vertex s to s + 1, a ring's last one back to 0) is in block
 *  chain_block[c] + s / FT_SEGMENT_BLOCK. Block b holds segments first[b] .. first[b] + count of chain
 *  chain[b]; near[near_start[b] .. near_start[b + 1]) lists, in increasing order, every block whose swept box
 *  meets the reach of b: the union of b's swept box and that of the next block of its chain (a ring's last
 *  block: its first), itself included. */
typedef struct {
    size_t nblock, nchain;
    uint32_t *chain, *first, *chain_block; /**< per block; per block; per chain, nchain + 1 entries */
    uint32_t *near_start, *near;
    uint8_t *count; /**< segments in each block */
    double *box;    /**< the widened swept box of each block: x0, y0, x1, y1 */
} ft_segment_blocks;

/** Indexes the segments of base[0..n) by blocks, the swept box of a segment being the bounding box of its
 *  two end points' base and raw positions (with mirror: also base - (raw - base)), slightly widened. raw[c]
 *  has base[c]'s vertex count. */
int ft_segment_blocks_build(ft_segment_blocks *g, const ft_chain *const *base, const ft_chain *const *raw, size_t n,
                            int mirror);
void ft_segment_blocks_free(ft_segment_blocks *g);

/** The build in steps, for a caller that computes the swept boxes itself (dutton_guarded.c): the blocks of
 *  per_block (1..255) segments of chains[0..n) (box allocated, not filled; per_block replaces
 *  FT_SEGMENT_BLOCK above), then, once every box is in g->box (widened as
 *  block_box does), the near lists. On failure g is freed. */
int ft_segment_blocks_layout(ft_segment_blocks *g, const ft_chain *const *chains, size_t n, size_t per_block);
int ft_segment_blocks_join(ft_segment_blocks *g, const ft_chain *const *chains);

/** Wide near lists: for every block, the blocks whose boxes meet its reach widened by sigma on every side
 *  (start: nblock + 1 offsets into near). Kept from one pass of the fused enhancement to the next. */
typedef struct {
    uint32_t *start, *near;
    double sigma;
} ft_segment_wide;

/** ft_segment_blocks_join that also fills *wide (sigma >= 0); the near lists are the same. On failure g and
 *  wide are freed. */
int ft_segment_blocks_join_wide(ft_segment_blocks *g, const ft_chain *const *chains, double sigma,
                                ft_segment_wide *wide);
void ft_segment_wide_free(ft_segment_wide *w);

/** The near lists of g (boxes filled) from the pass before's index prev and its wide lists pw, with no grid:
 *  g's blocks must be prev's halved (local block j of chain c comes from prev's local block j / 2: every
 *  segment of the pass before was split and nothing added or removed since). A block's box lies in its
 *  parent's widened by E, the largest excess; if 2 E fits in pw's sigma, every block near g's block b is a
 *  child of a block in the wide list of b's parent, and filtering those children by b's reach gives exactly
 *  the lists of ft_segment_blocks_join. With want_wide, *wide gets g's wide lists for the slack left
 *  (pw's sigma - 2 E). Returns 1, g's lists untouched, when the lists cannot be carried (then join). */
int ft_segment_blocks_join_carried(ft_segment_blocks *g, const ft_chain *const *chains,
                                   const ft_segment_blocks *prev, const ft_segment_wide *pw, int want_wide,
                                   ft_segment_wide *wide);

/** Swept boxes are widened by this fraction of their largest coordinate. */
#define FT_SEGMENT_WIDEN 1e-9

/** Widens a swept box {xmin, ymin, xmax, ymax} by 1e-9 of its largest coordinate, so that no rounding of the
 *  positions it was built from falls outside it: the one rule of both guards' blocks (inline: it is called
 *  once per block of every pass). */
static inline void ft_segment_box_widen(double box[4])
{
    double a = fabs(box[0]) > fabs(box[1]) ? fabs(box[0]) : fabs(box[1]);
    double c = fabs(box[2]) > fabs(box[3]) ? fabs(box[2]) : fabs(box[3]);
    double w = FT_SEGMENT_WIDEN * (a > c ? a : c) + 1e-300;
    box[0] -= w;
    box[1] -= w;
    box[2] += w;
    box[3] += w;
}

/** The block before m along its chain, which owns m's first vertex: m - 1, or at a chain's start the chain's
 *  last block (a ring) or m itself (an open chain). */
static inline size_t ft_segment_block_before(const ft_segment_blocks *g, const ft_chain *const *chains, size_t m)
{
    uint32_t c = g->chain[m];
    if (m > g->chain_block[c])
        return m - 1;
    return chains[c]->closed ? g->chain_block[c + 1] - 1 : m;
}

/** The block after m along its chain: m + 1, or at a chain's end its first block (a ring) or m itself (an open
 *  chain). */
static inline size_t ft_segment_block_after(const ft_segment_blocks *g, const ft_chain *const *chains, size_t m)
{
    uint32_t c = g->chain[m];
    if (m + 1 < g->chain_block[c + 1])
        return m + 1;
    return chains[c]->closed ? g->chain_block[c] : m;
}

/** Blocks per chunk of a guard's parallel walk: a fixed number, so the result does not depend on threads. */
#define FT_GUARD_CHUNK 16384

/** local[b] = 1 if every vertex the test of a vertex owned by block b reads (the end points of the segments of
 *  the blocks in b's near list) is owned by a block of b's chunk (a vertex is owned by the block of the segment
 *  ending at it): the local vertices of a chunk can be walked with no regard for any other chunk. */
void ft_segment_blocks_mark_local(const ft_segment_blocks *g, const ft_chain *const *chains, unsigned char *local);

#endif /* FRACTERRA_LINE_SEGMENT_INDEX_H */
