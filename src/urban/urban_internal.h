/* fracterra — src/urban/urban_internal.h: what the files of src/urban share. Not installed.
 *
 * Box counting on a fine grid (row_bits.c): boxes of m x m fine cells (m = offsets for the vector counter,
 * whose fine cell is r / offsets; m = s cells for the raster counter), the grid origin shifted by (a, b)
 * fine cells, map fine cell (i, j) to box (floor((i + a) / m), floor((j + b) / m)); the box count is the
 * number of distinct boxes holding an occupied fine cell.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_URBAN_INTERNAL_H
#define FRACTERRA_URBAN_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/urban.h"

/* ---- boundary.c ------------------------------------------------------------------------------------ */

/** Checks dim, min, max (0 allowed: automatic) and jitter of the generator's options; the error names the
 *  value. */
int ft_urban_boundary_check(const ft_boundary_opts *o);

/* ---- boundary_guarded.c ---------------------------------------------------------------------------- */

/** The generator level by level through the crossing guard, on every part (or arc, on a coverage) of l,
 *  with the resolved max. */
int ft_urban_boundary_guarded(ft_layer *l, const ft_boundary_opts *o, double max, int coverage,
                              ft_line_guard_stats *stats);

/* ---- polygon_index.c ------------------------------------------------------------------------------- */

/** The rings of the selected polygon features of a layer, grouped by polygon: a borrowed view of the
 *  layer's parts (valid while the layer lives), not a copy. */
typedef struct {
    const ft_chain **rings;   /**< every ring (outer and inner) of the selection, polygon by polygon */
    unsigned char *inner;     /**< per ring: 1 for an inner ring (hole) */
    size_t nrings;
    size_t *poly_first;       /**< polygon p holds rings[poly_first[p] .. poly_first[p + 1]) */
    size_t npolys;
    size_t nfeatures;         /**< polygon features selected */
} ft_polygon_index;

/** Collects the rings of features[0 .. nfeatures) (NULL = every feature). Features without geometry are
 *  skipped; with strict, a line feature is an error naming it (else it is skipped); every coordinate must
 *  be finite. An empty result is not an error here. */
int ft_polygon_index_collect(const ft_layer *l, const size_t *features, size_t nfeatures, int strict, ft_polygon_index *s);
void ft_polygon_index_clear(ft_polygon_index *s);

/* ---- row_bits.c ------------------------------------------------------------------------------------ */

#define FT_BAND_OFFSETS_MAX 16

/** Counts boxes of m x m fine cells over the origins shifted by (offsets[p], offsets[q]) fine cells
 *  (0 <= offsets < m, noff <= FT_BAND_OFFSETS_MAX), from the rows of occupied fine cells given in
 *  increasing row order. */
typedef struct ft_band_counter ft_band_counter;

/** A counter for rows of ncol cells. NULL (error set) on bad arguments or out of memory. */
ft_band_counter *ft_band_counter_create(size_t ncol, uint32_t m, const uint32_t *offsets, int noff);
/** Adds fine row `row` (bit c of bits[c / 64] = cell c occupied; ceil(ncol / 64) words, bits beyond ncol
 *  clear). Rows must come in increasing order; rows with no cell may be left out. */
void ft_band_counter_row(ft_band_counter *bc, size_t row, const uint64_t *bits);
/** The fewest boxes over the offset pairs, once every row was given. */
uint64_t ft_band_counter_finish(ft_band_counter *bc);
/** After ft_band_counter_finish: the mean count over the origins. */
double ft_band_counter_mean(const ft_band_counter *bc);
void ft_band_counter_free(ft_band_counter *bc);
/** Sets bits c0 .. c1 (inclusive) of a row bitmap. */
void ft_bits_set_range(uint64_t *bits, size_t c0, size_t c1);

/* ---- box_sizes.c ----------------------------------------------------------------------------------- */

/** Checks the size options (explicit list or series, offsets, nscales); the error names the value. */
int ft_area_sizes_check(const ft_area_dim_opts *o);
/** The box sides to count, increasing: the options' explicit list (sorted), or a geometric series of
 *  nscales sides between the options' limits, each 0 limit replaced by lo_auto / hi_auto. *sizes is
 *  allocated. The error names the limits when the range is empty. */
int ft_area_sizes(const ft_area_dim_opts *o, double lo_auto, double hi_auto, double **sizes, size_t *n);
/** Fits the table of counts: ft_loglog_fit_auto within [lo, hi] or ft_loglog_fit_range (fit_whole_range)
 *  with FT_DIM_MAP_BOXCOUNT, and names the result's method. */
int ft_area_fit(const ft_loglog *t, const ft_area_dim_opts *o, const char *method, ft_dim_result **out);

#endif /* FRACTERRA_URBAN_INTERNAL_H */
