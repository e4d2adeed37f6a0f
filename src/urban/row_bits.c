/* fracterra — src/urban/row_bits.c: box counting over the rows of a fine grid, the counter behind the exact
 * box-counting dimension of polygon layers and classified rasters (Zhang, Yu & Fan 2008, §1.1,
 * Eqs. 1-4: N(r) ~ r^-D).
 *
 * Boxes are m x m fine cells; with the origin shifted by (a, b) fine cells, fine cell (i, j) lies in box
 * (floor((i + a) / m), floor((j + b) / m)), exactly. The occupied fine cells arrive one row at a time, in
 * increasing row order, as a bitmap (one bit per column). For every y offset b an accumulator ORs the rows
 * of the current box row J = floor((j + b) / m); when a row of another box row arrives (or at the end) the
 * accumulator is flushed: for every x offset a, its runs of set bits [c0, c1] become box columns
 * [(c0 + a) / m, (c1 + a) / m], whose union is counted in one sweep (the runs come sorted). Memory is
 * one bitmap per y offset; time per row is O(offsets x words) plus the runs at each flush, whatever the
 * area covered. The count at the box side is the fewest over the offset pairs.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "urban/urban_internal.h"

struct ft_band_counter {
    size_t ncol, words;
    uint32_t m;
    int noff;
    uint32_t offsets[FT_BAND_OFFSETS_MAX];
    uint64_t *acc;       /* noff x words: the OR of the current box row's fine rows, per y offset */
    uint64_t band[FT_BAND_OFFSETS_MAX]; /* box row held by each accumulator + 1 (0 = empty) */
    uint64_t counts[FT_BAND_OFFSETS_MAX * FT_BAND_OFFSETS_MAX]; /* [b][a] */
};

ft_band_counter *ft_band_counter_create(size_t ncol, uint32_t m, const uint32_t *offsets, int noff)
{
    if (m < 1 || noff < 1 || noff > FT_BAND_OFFSETS_MAX || ncol == 0) {
        ft_error(FT_E_INVALID, "box counting: box of %u cells with %d offsets over %zu columns", (unsigned)m, noff,
                 ncol);
        return NULL;
    }
    for (int q = 0; q < noff; q++)
        if (offsets[q] >= m) {
            ft_error(FT_E_INVALID, "box counting: offset %u must be less than the box (%u cells)",
                     (unsigned)offsets[q], (unsigned)m);
            return NULL;
        }
    ft_band_counter *bc = ft_calloc(1, sizeof *bc);
    if (bc == NULL)
        return NULL;
    bc->ncol = ncol;
    bc->words = (ncol + 63) / 64;
    bc->m = m;
    bc->noff = noff;
    memcpy(bc->offsets, offsets, (size_t)noff * sizeof *offsets);
    bc->acc = ft_calloc((size_t)noff * bc->words, sizeof *bc->acc);
    if (bc->acc == NULL) {
        free(bc);
        return NULL;
    }
    return bc;
}

void ft_band_counter_free(ft_band_counter *bc)
{
    if (bc == NULL)
        return;
    free(bc->acc);
    free(bc);
}

/* Index of the first set bit at or after c, or n. */
static size_t next_set(const uint64_t *w, size_t n, size_t c)
{
    size_t i = c / 64;
    uint64_t x = c % 64 ? w[i] & (~UINT64_C(0) << (c % 64)) : w[i];
    const size_t nw = (n + 63) / 64;
    while (x == 0) {
        if (++i >= nw)
            return n;
        x = w[i];
    }
    size_t r = i * 64 + (size_t)__builtin_ctzll(x);
    return r < n ? r : n;
}

/* Index of the first clear bit at or after c, or n. */
static size_t next_clear(const uint64_t *w, size_t n, size_t c)
{
    size_t i = c / 64;
    uint64_t x = ~w[i] & (c % 64 ? ~UINT64_C(0) << (c % 64) : ~UINT64_C(0));
    const size_t nw = (n + 63) / 64;
    while (x == 0) {
        if (++i >= nw)
            return n;
        x = ~w[i];
    }
    size_t r = i * 64 + (size_t)__builtin_ctzll(x);
    return r < n ? r : n;
}

/* Box columns holding a set bit of the accumulator, for x offset a. */
static uint64_t box_columns(const uint64_t *acc, size_t ncol, uint32_t m, uint32_t a)
{
    uint64_t total = 0, next_free = 0; /* box columns below next_free are counted */
    for (size_t c = next_set(acc, ncol, 0); c < ncol;) {
        size_t e = next_clear(acc, ncol, c);
        uint64_t lo = ((uint64_t)c + a) / m, hi = ((uint64_t)e - 1 + a) / m;
        if (lo < next_free)
            lo = next_free;
        if (hi >= lo) {
            total += hi - lo + 1;
            next_free = hi + 1;
        }
        c = e < ncol ? next_set(acc, ncol, e) : ncol;
    }
    return total;
}

static void flush(ft_band_counter *bc, int q)
{
    uint64_t *acc = bc->acc + (size_t)q * bc->words;
    for (int p = 0; p < bc->noff; p++)
        bc->counts[q * FT_BAND_OFFSETS_MAX + p] += box_columns(acc, bc->ncol, bc->m, bc->offsets[p]);
    memset(acc, 0, bc->words * sizeof *acc);
    bc->band[q] = 0;
}

void ft_band_counter_row(ft_band_counter *bc, size_t row, const uint64_t *bits)
{
    for (int q = 0; q < bc->noff; q++) {
        uint64_t band = ((uint64_t)row + bc->offsets[q]) / bc->m + 1;
        if (bc->band[q] != band && bc->band[q] != 0)
            flush(bc, q);
        bc->band[q] = band;
        uint64_t *acc = bc->acc + (size_t)q * bc->words;
        for (size_t w = 0; w < bc->words; w++)
            acc[w] |= bits[w];
    }
}

uint64_t ft_band_counter_finish(ft_band_counter *bc)
{
    for (int q = 0; q < bc->noff; q++)
        if (bc->band[q] != 0)
            flush(bc, q);
    uint64_t best = UINT64_MAX;
    for (int q = 0; q < bc->noff; q++)
        for (int p = 0; p < bc->noff; p++)
            best = bc->counts[q * FT_BAND_OFFSETS_MAX + p] < best ? bc->counts[q * FT_BAND_OFFSETS_MAX + p] : best;
    return best;
}

double ft_band_counter_mean(const ft_band_counter *bc)
{
    double sum = 0.0;
    for (int q = 0; q < bc->noff; q++)
        for (int p = 0; p < bc->noff; p++)
            sum += (double)bc->counts[q * FT_BAND_OFFSETS_MAX + p];
    return sum / ((double)bc->noff * (double)bc->noff);
}

void ft_bits_set_range(uint64_t *bits, size_t c0, size_t c1)
{
    size_t w0 = c0 / 64, w1 = c1 / 64;
    uint64_t m0 = ~UINT64_C(0) << (c0 % 64), m1 = ~UINT64_C(0) >> (63 - c1 % 64);
    if (w0 == w1) {
        bits[w0] |= m0 & m1;
        return;
    }
    bits[w0] |= m0;
    for (size_t w = w0 + 1; w < w1; w++)
        bits[w] = ~UINT64_C(0);
    bits[w1] |= m1;
}
