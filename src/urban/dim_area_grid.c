/* fracterra — src/urban/dim_area_grid.c: box-counting dimension of one class of a classified raster (Zhang, Yu
 * & Fan 2008, §1.2: "we transformed the vector layers of different land use into raster images,
 * then fractal dimensions of land parcels distributed in the images are evaluated"; N(r) ~ r^-D, Eqs. 1-4).
 *
 * The class is the set of valid cells equal to the class value; its boundary cells are the class cells
 * with a 4-neighbour outside the class (another value, nodata, or off the grid). Either set is fed row by
 * row, as bitmaps over the class's bounding box, to the band counter (row_bits.c) with boxes of s x s
 * cells, s a whole number, the fewest over origins shifted by floor(i s / k) cells per axis (i < k,
 * k = min(offsets, s) distinct shifts). Sides given in map units are rounded to whole cells; the table's
 * scale is s times the cell side sqrt(|gt[1] gt[5] - gt[2] gt[4]|).
 *
 * Automatic range: 1 cell to 1/48 (boundary) or 1/128 (area) of the class's bounding-box diagonal, as for
 * polygons (dim_area.c), but at least 8 cells (or a quarter of the diagonal if that is less), so that the
 * series still holds several whole sizes on small rasters.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/urban.h"
#include "internal.h"
#include "urban/urban_internal.h"

#define HI_FRACTION_BOUNDARY (1.0 / 48)
#define HI_FRACTION_AREA (1.0 / 128)
#define HI_MIN_CELLS 8.0

typedef struct {
    const ft_grid *g;
    float value;
    size_t c0, c1, r0, r1; /* the class's bounding box, inclusive */
    size_t ncells;
} class_cells;

static inline int in_class(const class_cells *k, size_t col, size_t row)
{
    return ft_grid_is_valid(k->g, col, row) && k->g->z[row * k->g->nx + col] == k->value;
}

/* A class cell with a 4-neighbour outside the class. */
static int is_edge(const class_cells *k, size_t col, size_t row)
{
    const ft_grid *g = k->g;
    return col == 0 || row == 0 || col + 1 == g->nx || row + 1 == g->ny || !in_class(k, col - 1, row) ||
           !in_class(k, col + 1, row) || !in_class(k, col, row - 1) || !in_class(k, col, row + 1);
}

static int find_class(const ft_grid *g, double value, class_cells *k)
{
    *k = (class_cells){g, (float)value, SIZE_MAX, 0, SIZE_MAX, 0, 0};
    for (size_t row = 0; row < g->ny; row++)
        for (size_t col = 0; col < g->nx; col++)
            if (in_class(k, col, row)) {
                k->c0 = col < k->c0 ? col : k->c0;
                k->c1 = col > k->c1 ? col : k->c1;
                k->r0 = row < k->r0 ? row : k->r0;
                k->r1 = row > k->r1 ? row : k->r1;
                k->ncells++;
            }
    if (k->ncells == 0)
        return ft_error(FT_E_EMPTY, "box counting: no valid cell has the class value %g", value);
    return FT_OK;
}

/* Bit c of row = class cell (boundary: boundary cell) at column k->c0 + c of grid row `row`. */
static int class_row(const class_cells *k, int boundary, size_t row, uint64_t *bits, size_t words)
{
    memset(bits, 0, words * sizeof *bits);
    int any = 0;
    for (size_t col = k->c0; col <= k->c1; col++)
        if (in_class(k, col, row) && (!boundary || is_edge(k, col, row))) {
            bits[(col - k->c0) / 64] |= UINT64_C(1) << ((col - k->c0) % 64);
            any = 1;
        }
    return any;
}

/* Boxes of s x s cells holding a class (boundary) cell, the fewest over the offsets. */
static int count_boxes(const class_cells *k, int boundary, uint32_t s, int offsets, uint64_t *count)
{
    const size_t ncol = k->c1 - k->c0 + 1, words = (ncol + 63) / 64;
    uint32_t off[FT_BAND_OFFSETS_MAX];
    int noff = (uint32_t)offsets < s ? offsets : (int)s;
    for (int a = 0; a < noff; a++)
        off[a] = (uint32_t)((uint64_t)a * s / (uint64_t)noff);
    ft_band_counter *bc = ft_band_counter_create(ncol, s, off, noff);
    uint64_t *bits = ft_malloc(words * sizeof *bits);
    if (bc == NULL || bits == NULL) {
        ft_band_counter_free(bc);
        free(bits);
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : FT_E_NOMEM;
    }
    for (size_t row = k->r0; row <= k->r1; row++)
        if (class_row(k, boundary, row, bits, words))
            ft_band_counter_row(bc, row - k->r0, bits);
    *count = ft_band_counter_finish(bc);
    ft_band_counter_free(bc);
    free(bits);
    return FT_OK;
}

static int cmp_size(const void *a, const void *b)
{
    size_t x = *(const size_t *)a, y = *(const size_t *)b;
    return (x > y) - (x < y);
}

/* Box sides in whole cells, increasing and distinct. */
static int cell_sizes(const ft_area_dim_opts *o, const class_cells *k, double side, size_t **out, size_t *n)
{
    double diag = hypot((double)(k->c1 - k->c0 + 1), (double)(k->r1 - k->r0 + 1));
    double *sizes = NULL;
    size_t ns = 0;
    double hi = (o->what == FT_AREA_AREA ? HI_FRACTION_AREA : HI_FRACTION_BOUNDARY) * diag;
    hi = fmax(hi, fmin(HI_MIN_CELLS, 0.25 * diag)) * side;
    int rc = ft_area_sizes(o, side, hi, &sizes, &ns);
    if (rc != FT_OK)
        return rc;
    size_t *s = ft_malloc(ns * sizeof *s);
    if (s == NULL) {
        free(sizes);
        return FT_E_NOMEM;
    }
    for (size_t i = 0; i < ns; i++) {
        double c = floor(sizes[i] / side + 0.5);
        if (o->ncells > 0 && c < 1.0) {
            rc = ft_error(FT_E_INVALID, "box counting: cell size %g is less than half a raster cell (%g)", sizes[i],
                          side);
            break;
        }
        s[i] = c < 1.0 ? 1 : (size_t)c;
    }
    free(sizes);
    if (rc != FT_OK) {
        free(s);
        return rc;
    }
    qsort(s, ns, sizeof *s, cmp_size);
    size_t w = 0;
    for (size_t i = 0; i < ns; i++)
        if (w == 0 || s[i] != s[w - 1])
            s[w++] = s[i];
    if (w < 2) {
        free(s);
        return ft_error(FT_E_INVALID, "box counting: the sizes round to fewer than 2 distinct whole cells (cell "
                        "side %g); widen the range", side);
    }
    *out = s;
    *n = w;
    return FT_OK;
}

static int build_table(const class_cells *k, const ft_area_dim_opts *o, const size_t *cells, size_t n, double side,
                       ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create(n);
    if (t == NULL)
        return FT_E_NOMEM;
    int rc = ft_progress(o->progress, o->progress_arg, 0.0, "box counting");
    for (size_t i = 0; rc == FT_OK && i < n; i++) {
        if (cells[i] > UINT32_MAX) {
            rc = ft_error(FT_E_INVALID, "box counting: a box of %zu cells is too large", cells[i]);
            break;
        }
        uint64_t count = 0;
        rc = count_boxes(k, o->what == FT_AREA_BOUNDARY, (uint32_t)cells[i], o->offsets, &count);
        if (rc == FT_OK && count > 0)
            rc = ft_loglog_push(t, (double)cells[i] * side, (double)count, (double)count);
        char msg[64];
        snprintf(msg, sizeof msg, "box counting: size %zu of %zu", i + 1, n);
        if (rc == FT_OK)
            rc = ft_progress(o->progress, o->progress_arg, (i + 1.0) / (double)n, msg);
    }
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

int ft_urban_dim_area_grid(const ft_grid *classes, double class_value, const ft_area_dim_opts *o,
                           ft_dim_result **out)
{
    ft_area_dim_opts taken = FT_AREA_DIM_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (o != NULL) {
        if (FT_OPTS_TAKE(taken, o, ft_area_dim_opts) != FT_OK)
            return FT_E_INVALID;
        o = &taken;
    }
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_dim_area_grid: NULL out");
    *out = NULL;
    if (classes == NULL || classes->z == NULL || classes->nx == 0 || classes->ny == 0)
        return ft_error(FT_E_EMPTY, "box counting: empty grid");
    if (!isfinite(class_value))
        return ft_error(FT_E_INVALID, "box counting: class value must be finite, got %g", class_value);
    const ft_area_dim_opts defaults = FT_AREA_DIM_OPTS_DEFAULT;
    o = o != NULL ? o : &defaults;
    int rc = ft_area_sizes_check(o);
    if (rc != FT_OK)
        return rc;
    const double *gt = classes->gt;
    double side = sqrt(fabs(gt[1] * gt[5] - gt[2] * gt[4]));
    if (!(side > 0.0) || !isfinite(side))
        return ft_error(FT_E_INVALID, "box counting: the grid's cells have no area (geotransform %g %g %g %g %g %g)",
                        gt[0], gt[1], gt[2], gt[3], gt[4], gt[5]);
    class_cells k;
    rc = find_class(classes, class_value, &k);
    if (rc != FT_OK)
        return rc;
    size_t *cells = NULL, n = 0;
    ft_loglog *t = NULL;
    rc = cell_sizes(o, &k, side, &cells, &n);
    if (rc == FT_OK)
        rc = build_table(&k, o, cells, n, side, &t);
    if (rc == FT_OK)
        rc = ft_area_fit(t, o, o->what == FT_AREA_AREA ? "box-area" : "box-boundary", out);
    ft_loglog_free(t);
    free(cells);
    return rc;
}
