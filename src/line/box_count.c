/* fracterra — src/line/box_count.c: box counting of chains (Zhang, Yu & Fan 2008, §1.1:
 * N(r) ~ r^-D, D = -slope of log N on log r, their Eq. 1-2), counted exactly: N is the number of grid
 * cells holding at least one point of a segment. Cells are half-open, [x0, x0 + r) x [y0, y0 + r), so a
 * point on a grid line belongs to the cell on its right (above), a grid corner to the cell up and to the
 * right, and every point to exactly one cell.
 *
 * Traversal (Amanatides & Woo 1987, "A fast voxel traversal algorithm"): from the cell of a segment's first
 * end, step to the neighbouring cell across whichever grid line the segment meets first, until the cell of
 * its other end; the parameters t of the crossings are recomputed from the segment's end each step (no
 * accumulated error). With half-open cells a crossing in the positive direction enters the new cell at the
 * crossing point itself, one in the negative direction only after it; so when a segment passes exactly
 * through a grid corner it steps diagonally if both directions have the same sign, and otherwise steps the
 * positive axis first (the corner point's own cell) and then the negative one.
 *
 * Offsets: the count at side r is taken over k x k grid origins shifted by multiples of r / k, as their
 * mean (the default: an unbiased estimate of the expected count of a randomly placed grid, which for a
 * smooth curve is proportional to 1 / r at every r, so D = 1 holds down to a handful of boxes) or their
 * minimum (the "fewest boxes" of the literature, box-min: biased upward where the largest boxes hold few
 * counts, since the minimum of a few counts falls further below their mean the fewer they are). The
 * chains are traversed once on the fine grid of side g = r / k; the cell of a point on the grid with
 * origin shifted by (-a g, -b g) is (floor((i + a) / k), floor((j + b) / k)) for its fine cell (i, j),
 * exactly. Fine cells are bucketed by column (counting sort); each coarse column is then a run of k fine
 * columns, and distinct coarse rows in it are counted with a mark and a bit set (one bit per y offset b)
 * per coarse row: O(cells crossed) per x offset, no hashing, no sorting, and duplicates (the chain coming
 * back to a cell, shared cells of different chains) are counted once.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/line.h"
#include "internal.h"
#include "line/line_dim_internal.h"

#define BOX_OFFSETS_LIMIT 16 /* k <= 16: the y offsets of a coarse row fit the bits of a uint32_t */

/* Fine cells crossed, as (column, row) relative to the grid's first (aligned) column and row. */
typedef struct {
    uint32_t *col, *row;
    size_t n, cap;
    int64_t i0, j0; /* absolute index of relative column 0 and row 0 */
} cell_list;

typedef struct {
    double ox, oy, g; /* fine grid: origin and side */
    cell_list *cells;
} fine_grid;

static int cell_push(cell_list *l, int64_t i, int64_t j)
{
    if (l->n == l->cap) {
        if (l->cap >= FT_BOX_MAX_CELLS)
            return ft_error(FT_E_INVALID, "box counting would visit more than %llu cells: the box size is "
                            "too small for the extent", (unsigned long long)FT_BOX_MAX_CELLS);
        size_t cap = l->cap ? 2 * l->cap : 4096;
        uint32_t *c = ft_realloc_array(l->col, cap, sizeof *c);
        if (c == NULL)
            return FT_E_NOMEM;
        l->col = c;
        uint32_t *r = ft_realloc_array(l->row, cap, sizeof *r);
        if (r == NULL)
            return FT_E_NOMEM;
        l->row = r;
        l->cap = cap;
    }
    l->col[l->n] = (uint32_t)(i - l->i0);
    l->row[l->n] = (uint32_t)(j - l->j0);
    l->n++;
    return FT_OK;
}

/* floor(u) as an integer, without a libm call (|u| < 2^62, ensured by grid_extent). */
static inline int64_t ifloor(double u)
{
    int64_t i = (int64_t)u;
    return i - (u < (double)i);
}

/* Parameter of the next grid line a segment from u0 (direction du != 0, inv = 1 / du) meets, leaving
 * cell i. */
static inline double next_crossing(double u0, double du, double inv, int64_t i)
{
    return ((double)(du > 0.0 ? i + 1 : i) - u0) * inv;
}

/* Pushes every cell after the first that the segment (u0, v0) -> (u1, v1) (grid units) crosses, from
 * cell (i, j) to cell (ie, je). */
static int traverse(cell_list *l, double u0, double v0, double u1, double v1, int64_t i, int64_t j, int64_t ie,
                    int64_t je)
{
    const double du = u1 - u0, dv = v1 - v0, inv_u = 1.0 / du, inv_v = 1.0 / dv;
    const int64_t si = du > 0.0 ? 1 : -1, sj = dv > 0.0 ? 1 : -1;
    while (i != ie || j != je) {
        int step_i, step_j;
        if (i == ie) {
            step_i = 0;
            step_j = 1;
        } else if (j == je) {
            step_i = 1;
            step_j = 0;
        } else {
            double ti = next_crossing(u0, du, inv_u, i), tj = next_crossing(v0, dv, inv_v, j);
            step_i = ti < tj || (ti == tj && (si == sj || si > 0));
            step_j = tj < ti || (ti == tj && (si == sj || sj > 0));
        }
        i += step_i ? si : 0;
        j += step_j ? sj : 0;
        int rc = cell_push(l, i, j);
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

static int chain_cells(const ft_chain *c, const fine_grid *f)
{
    if (c->n == 0)
        return FT_OK;
    ft_walk_src w;
    ft_walk_src_init(&w, c, 0);
    double x, y;
    ft_walk_vertex(&w, 0, &x, &y);
    double u0 = (x - f->ox) / f->g, v0 = (y - f->oy) / f->g;
    int64_t i0 = ifloor(u0), j0 = ifloor(v0);
    int rc = cell_push(f->cells, i0, j0);
    for (size_t k = 1; rc == FT_OK && k < w.m; k++) {
        ft_walk_vertex(&w, k, &x, &y);
        double u1 = (x - f->ox) / f->g, v1 = (y - f->oy) / f->g;
        int64_t i1 = ifloor(u1), j1 = ifloor(v1);
        if (i1 != i0 || j1 != j0)
            rc = traverse(f->cells, u0, v0, u1, v1, i0, j0, i1, j1);
        u0 = u1;
        v0 = v1;
        i0 = i1;
        j0 = j1;
    }
    return rc;
}

static int64_t floor_div(int64_t a, int64_t k)
{
    int64_t q = a / k;
    return (a % k != 0 && a < 0) ? q - 1 : q;
}

/* The fine grid's index range over the chains' extent, first column and row aligned to multiples of k so
 * that coarse indices of relative fine indices are plain divisions. Sets *ncol, *nrow. */
static int grid_extent(const ft_chain *const *chains, size_t n, const fine_grid *f, int k, cell_list *l,
                       size_t *ncol, size_t *nrow)
{
    double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY;
    for (size_t c = 0; c < n; c++) {
        const ft_chain *ch = chains[c];
        for (size_t i = 0; i < ch->n; i++) {
            double x = ch->x[i], y = ch->y[i];
            xmin = x < xmin ? x : xmin;
            xmax = x > xmax ? x : xmax;
            ymin = y < ymin ? y : ymin;
            ymax = y > ymax ? y : ymax;
        }
    }
    double span = fmax((xmax - xmin) / f->g, (ymax - ymin) / f->g);
    if (!(span < (double)FT_BOX_MAX_CELLS))
        return ft_error(FT_E_INVALID, "box counting: the extent spans %.3g cells of side %g, more than %llu",
                        span, f->g, (unsigned long long)FT_BOX_MAX_CELLS);
    double far = fmax(fmax(fabs(xmin - f->ox), fabs(xmax - f->ox)), fmax(fabs(ymin - f->oy), fabs(ymax - f->oy)));
    if (!(far / f->g < 0x1p62))
        return ft_error(FT_E_INVALID, "box counting: the grid origin (%g, %g) is too far from the chains for "
                        "cells of side %g", f->ox, f->oy, f->g);
    l->i0 = floor_div(ifloor((xmin - f->ox) / f->g), k) * k;
    l->j0 = floor_div(ifloor((ymin - f->oy) / f->g), k) * k;
    *ncol = (size_t)(ifloor((xmax - f->ox) / f->g) - l->i0 + 1);
    *nrow = (size_t)(ifloor((ymax - f->oy) / f->g) - l->j0 + 1);
    return FT_OK;
}

/* Rows of the fine cells, bucketed by column: rows[start[i] .. start[i+1]) are column i's. */
static int bucket_by_column(const cell_list *l, size_t ncol, uint32_t **rows_out, size_t **start_out)
{
    size_t *start = ft_calloc(ncol + 1, sizeof *start);
    uint32_t *rows = ft_malloc((l->n ? l->n : 1) * sizeof *rows);
    if (start == NULL || rows == NULL) {
        free(start);
        free(rows);
        return FT_E_NOMEM;
    }
    for (size_t e = 0; e < l->n; e++)
        start[l->col[e] + 1]++;
    for (size_t i = 0; i < ncol; i++)
        start[i + 1] += start[i];
    for (size_t e = 0; e < l->n; e++)
        rows[start[l->col[e]]++] = l->row[e];
    for (size_t i = ncol; i > 0; i--)
        start[i] = start[i - 1];
    start[0] = 0;
    *rows_out = rows;
    *start_out = start;
    return FT_OK;
}

/* Per coarse row: the coarse column that last touched it (+ 1) and which y offsets b hit it there. */
typedef struct {
    uint32_t mark;
    uint32_t bits;
} row_state;

/* Adds a finished (column, row) cell to the count of every y offset that hit it. */
static inline void flush_row(row_state *r, int k, uint64_t *counts)
{
    for (int b = 0; b < k; b++)
        counts[b] += (r->bits >> b) & 1u;
    r->bits = 0;
}

static inline void hit_row(row_state *r, uint32_t mark, uint32_t bits, int k, uint64_t *counts)
{
    if (r->mark != mark) {
        if (r->bits)
            flush_row(r, k, counts);
        r->mark = mark;
    }
    r->bits |= bits;
}

/* Distinct coarse cells for x offset a and every y offset b (counts[b]), from column-bucketed fine rows
 * given as q = row / k and rem = row % k: with offset b the coarse row is q + (rem + b >= k), so offsets
 * b < k - rem hit row q and the others row q + 1 — two bit masks per fine cell instead of k lookups.
 * rows holds nj coarse rows; coarse column I is marked I + 1. */
static void count_offsets(const uint32_t *q, const uint8_t *rem, const size_t *start, size_t ncol, int k, int a,
                          row_state *rows, size_t nj, uint64_t *counts)
{
    memset(rows, 0, nj * sizeof *rows);
    for (int b = 0; b < k; b++)
        counts[b] = 0;
    const size_t ku = (size_t)k;
    const uint32_t all = (1u << k) - 1u;
    size_t ni = (ncol - 1 + (size_t)a) / ku + 1;
    for (size_t ci = 0; ci < ni; ci++) {
        size_t lo = ci * ku >= (size_t)a ? ci * ku - (size_t)a : 0;
        size_t hi = ci * ku + ku - (size_t)a; /* exclusive */
        if (hi > ncol)
            hi = ncol;
        const uint32_t mark = (uint32_t)(ci + 1);
        for (size_t e = start[lo]; e < start[hi]; e++) {
            uint32_t low = (1u << (k - rem[e])) - 1u; /* offsets b < k - rem */
            hit_row(&rows[q[e]], mark, low, k, counts);
            if (rem[e] != 0)
                hit_row(&rows[q[e] + 1], mark, all & ~low, k, counts);
        }
    }
    for (size_t j = 0; j < nj; j++)
        if (rows[j].bits)
            flush_row(&rows[j], k, counts);
}

/* Splits bucketed fine rows into q = row / k and rem = row % k (a multiply-shift division, exact for rows
 * below 2^36 and k <= 16). */
static void split_rows(const uint32_t *rows, size_t n, int k, uint32_t *q, uint8_t *rem)
{
    const uint64_t magic = (UINT64_C(1) << 40) / (uint64_t)k + 1;
    for (size_t e = 0; e < n; e++) {
        uint32_t j = rows[e], qq = (uint32_t)(((uint64_t)j * magic) >> 40);
        rem[e] = (uint8_t)(j - qq * (uint32_t)k);
        q[e] = qq; /* may overwrite rows[e] */
    }
}

/* The fewest cells and their total over the k x offsets a (in parallel: each a is independent and integer
 * counts do not depend on the order, so the result is the same on any number of threads) and the k y
 * offsets b. */
static int count_offsets_all(const cell_list *l, size_t ncol, size_t nrow, int k, uint64_t *count, uint64_t *total)
{
    uint32_t *rows = NULL;
    size_t *start = NULL;
    int rc = bucket_by_column(l, ncol, &rows, &start);
    if (rc != FT_OK)
        return rc;
    const size_t nj = (nrow - 1) / (size_t)k + 2; /* coarse rows, one more for q + 1 */
    uint8_t *rem = ft_malloc(l->n);
    uint64_t best_a[BOX_OFFSETS_LIMIT], sum_a[BOX_OFFSETS_LIMIT];
    int failed = 0;
    if (rem == NULL) {
        free(rows);
        free(start);
        return FT_E_NOMEM;
    }
    split_rows(rows, l->n, k, rows, rem); /* q overwrites the rows in place */
#pragma omp parallel for schedule(dynamic, 1) reduction(| : failed) if (l->n >= 65536)
    for (int a = 0; a < k; a++) {
        row_state *state = malloc(nj * sizeof *state);
        uint64_t counts[BOX_OFFSETS_LIMIT];
        best_a[a] = UINT64_MAX;
        sum_a[a] = 0;
        if (state == NULL) {
            failed = 1;
            continue;
        }
        count_offsets(rows, rem, start, ncol, k, a, state, nj, counts);
        for (int b = 0; b < k; b++) {
            best_a[a] = counts[b] < best_a[a] ? counts[b] : best_a[a];
            sum_a[a] += counts[b];
        }
        free(state);
    }
    uint64_t best = UINT64_MAX, sum = 0;
    for (int a = 0; a < k; a++) {
        best = best_a[a] < best ? best_a[a] : best;
        sum += sum_a[a];
    }
    *count = best;
    *total = sum;
    free(rem);
    free(rows);
    free(start);
    return failed ? ft_error(FT_E_NOMEM, "out of memory counting boxes") : FT_OK;
}

int ft_line_box_count_offsets(const ft_chain *const *chains, size_t n, double size, int k, double ox, double oy,
                              uint64_t *fewest, double *mean)
{
    if (k < 1 || k > BOX_OFFSETS_LIMIT)
        return ft_error(FT_E_INVALID, "box offsets per axis must be in [1, %d], got %d", BOX_OFFSETS_LIMIT, k);
    cell_list cells = {0};
    fine_grid f = {ox, oy, size / k, &cells};
    size_t ncol = 0, nrow = 0;
    uint64_t count = 0, total = 0;
    int rc = grid_extent(chains, n, &f, k, &cells, &ncol, &nrow);
    for (size_t c = 0; rc == FT_OK && c < n; c++)
        rc = chain_cells(chains[c], &f);
    if (rc == FT_OK && cells.n > 0)
        rc = count_offsets_all(&cells, ncol, nrow, k, &count, &total);
    free(cells.col);
    free(cells.row);
    if (fewest != NULL)
        *fewest = count;
    if (mean != NULL)
        *mean = (double)total / ((double)k * (double)k);
    return rc;
}

int ft_line_box_count_min(const ft_chain *const *chains, size_t n, double size, int k, double ox, double oy,
                          uint64_t *count)
{
    return ft_line_box_count_offsets(chains, n, size, k, ox, oy, count, NULL);
}

int ft_line_box_count(const ft_chain *const *chains, size_t n, double size, double ox, double oy,
                      uint64_t *count)
{
    if (count == NULL)
        return ft_error(FT_E_INVALID, "ft_line_box_count: NULL count");
    *count = 0;
    if (chains == NULL || n == 0)
        return ft_error(FT_E_EMPTY, "box counting: no chains (n = %zu)", chains == NULL ? (size_t)0 : n);
    if (!(size > 0.0) || !isfinite(size))
        return ft_error(FT_E_INVALID, "box size must be finite and > 0, got %g", size);
    if (!isfinite(ox) || !isfinite(oy))
        return ft_error(FT_E_INVALID, "grid origin must be finite, got (%g, %g)", ox, oy);
    size_t nv = 0;
    for (size_t c = 0; c < n; c++) {
        if (chains[c] == NULL)
            return ft_error(FT_E_INVALID, "box counting: chain %zu is NULL", c);
        if (ft_chain_check_finite(chains[c]) != FT_OK) {
            char msg[256];
            snprintf(msg, sizeof msg, "%s", ft_last_error());
            return ft_error(FT_E_NUMERIC, "chain %zu: %s", c, msg);
        }
        nv += chains[c]->n;
    }
    if (nv == 0)
        return FT_OK;
    return ft_line_box_count_min(chains, n, size, 1, ox, oy, count);
}
