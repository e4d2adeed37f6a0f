/* fracterra — fft.c: FFTW3 plan cache (one plan per kind, size, direction, in-place and alignment,
 * created under a mutex with FFTW_ESTIMATE) and the 2-D real / 1-D complex transforms that execute the
 * cached plans on the caller's arrays through FFTW's thread-safe new-array execute functions; plus a
 * single-precision (fftw3f) 2-D complex-to-real transform for spectral synthesis.
 * See fft.h for layouts and normalisation (none).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fft/fft.h"

#include <limits.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include "fracterra/core.h"

/* The single-precision kinds are batches of 1-D transforms for ft_fft_c2r_2df: their ny is the batch
 * size (howmany) and nx the length. */
typedef enum {
    KIND_R2C_2D = 0,
    KIND_C2R_2D = 1,
    KIND_C2C_1D = 2,
    KIND_COLS_C2CF = 3, /* ny interleaved in-place backward c2c of length nx (element i of transform b
                           at i * ny + b) */
    KIND_ROWS_C2RF = 4  /* ny in-place c2r rows of length nx, row stride nx/2+1 complex */
} plan_kind;

typedef struct plan_entry {
    plan_kind kind;
    size_t ny, nx;
    int sign, inplace, unaligned;
    fftw_plan plan;   /* double-precision kinds */
    fftwf_plan planf; /* single-precision kinds */
    struct plan_entry *next;
} plan_entry;

static pthread_mutex_t cache_lock = PTHREAD_MUTEX_INITIALIZER;
static plan_entry *cache_head = NULL;

static int is_smooth7(size_t m)
{
    static const size_t primes[4] = {2, 3, 5, 7};
    for (int i = 0; i < 4; i++)
        while (m % primes[i] == 0)
            m /= primes[i];
    return m == 1;
}

size_t ft_fft_good_size(size_t n)
{
    if (n <= 1)
        return 1;
    /* 7-smooth numbers are dense enough (gaps < 1% beyond 10^5, a few % below) for a linear scan. */
    for (size_t m = n; m >= n; m++)
        if (is_smooth7(m))
            return m;
    return 0;
}

size_t ft_fft_real_stride(size_t nx)
{
    return 2 * (nx / 2 + 1);
}

static void *aligned_alloc_checked(size_t n, size_t elem)
{
    if (n == 0)
        n = 1;
    if (n > SIZE_MAX / elem) {
        ft_error(FT_E_NOMEM, "fft: array of %zu elements overflows size_t", n);
        return NULL;
    }
    void *p = fftw_malloc(n * elem);
    if (p == NULL)
        ft_error(FT_E_NOMEM, "fft: out of memory allocating %zu bytes", n * elem);
    return p;
}

double *ft_fft_alloc_real(size_t n)
{
    return aligned_alloc_checked(n, sizeof(double));
}

fftw_complex *ft_fft_alloc_complex(size_t n)
{
    return aligned_alloc_checked(n, sizeof(fftw_complex));
}

void ft_fft_free(void *p)
{
    if (p != NULL)
        fftw_free(p);
}

/* Large arrays are walked column-wise by the 2-D transforms: transparent huge pages (where the kernel
 * offers them on request, madvise mode) cut both the page faults of the first touch and the TLB misses
 * of the column pass. Only a hint: failure changes nothing. */
void ft_fft_advise_huge(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    const uintptr_t huge = (uintptr_t)2 << 20;
    uintptr_t lo = ((uintptr_t)p + huge - 1) & ~(huge - 1), hi = ((uintptr_t)p + bytes) & ~(huge - 1);
    if (hi > lo)
        (void)madvise((void *)lo, hi - lo, MADV_HUGEPAGE);
#else
    (void)p;
    (void)bytes;
#endif
}

fftwf_complex *ft_fft_alloc_complexf(size_t n)
{
    if (n == 0)
        n = 1;
    if (n > SIZE_MAX / sizeof(fftwf_complex)) {
        ft_error(FT_E_NOMEM, "fft: array of %zu elements overflows size_t", n);
        return NULL;
    }
    fftwf_complex *p = fftwf_malloc(n * sizeof(fftwf_complex));
    if (p == NULL)
        ft_error(FT_E_NOMEM, "fft: out of memory allocating %zu bytes", n * sizeof(fftwf_complex));
    else
        ft_fft_advise_huge(p, n * sizeof(fftwf_complex));
    return p;
}

void ft_fft_freef(void *p)
{
    if (p != NULL)
        fftwf_free(p);
}

static int check_size(const char *what, size_t ny, size_t nx, const void *in, const void *out)
{
    if (ny == 0 || nx == 0)
        return ft_error(FT_E_INVALID, "fft: %s size must be positive, got %zu x %zu", what, ny, nx);
    if (ny > INT_MAX || nx > INT_MAX)
        return ft_error(FT_E_INVALID, "fft: %s size %zu x %zu exceeds FFTW's int range", what, ny, nx);
    if (in == NULL || out == NULL)
        return ft_error(FT_E_INVALID, "fft: %s needs input and output arrays, got NULL", what);
    return FT_OK;
}

/* Plans e's problem into e->plan or e->planf; 0 if FFTW could not. */
static int make_plan(plan_entry *e, unsigned flags, void *in, void *out)
{
    int ny = (int)e->ny, nx = (int)e->nx, ncx = nx / 2 + 1;
    e->plan = NULL;
    e->planf = NULL;
    switch (e->kind) {
    case KIND_R2C_2D:
        e->plan = fftw_plan_dft_r2c_2d(ny, nx, in, out, flags);
        break;
    case KIND_C2R_2D:
        e->plan = fftw_plan_dft_c2r_2d(ny, nx, in, out, flags);
        break;
    case KIND_C2C_1D:
        e->plan = fftw_plan_dft_1d(nx, in, out, e->sign, flags);
        break;
    case KIND_COLS_C2CF:
        e->planf = fftwf_plan_many_dft(1, &nx, ny, in, NULL, ny, 1, out, NULL, ny, 1, FFTW_BACKWARD, flags);
        break;
    case KIND_ROWS_C2RF:
        e->planf = fftwf_plan_many_dft_c2r(1, &nx, ny, in, NULL, 1, ncx, out, NULL, 1, 2 * ncx, flags);
        break;
    }
    return e->plan != NULL || e->planf != NULL;
}

/* The cached plan entry for this problem, created on first use. With FFTW_ESTIMATE the planner neither
 * reads nor writes the arrays, so the caller's own arrays serve for planning. */
static const plan_entry *get_entry(plan_kind kind, size_t ny, size_t nx, int sign, void *in, void *out)
{
    int inplace = in == out;
    int single = kind == KIND_COLS_C2CF || kind == KIND_ROWS_C2RF;
    int unaligned = single ? fftwf_alignment_of(in) != 0 || fftwf_alignment_of(out) != 0
                           : fftw_alignment_of(in) != 0 || fftw_alignment_of(out) != 0;
    plan_entry *found = NULL;
    pthread_mutex_lock(&cache_lock);
    for (plan_entry *e = cache_head; e != NULL; e = e->next)
        if (e->kind == kind && e->ny == ny && e->nx == nx && e->sign == sign && e->inplace == inplace &&
            e->unaligned == unaligned) {
            found = e;
            break;
        }
    if (found == NULL) {
        unsigned flags = FFTW_ESTIMATE | (unaligned ? FFTW_UNALIGNED : 0u);
        if (kind == KIND_C2R_2D || kind == KIND_ROWS_C2RF)
            flags |= FFTW_DESTROY_INPUT;
        plan_entry *e = malloc(sizeof *e);
        if (e != NULL) {
            e->kind = kind;
            e->ny = ny;
            e->nx = nx;
            e->sign = sign;
            e->inplace = inplace;
            e->unaligned = unaligned;
            if (!make_plan(e, flags, in, out)) {
                free(e);
            } else {
                e->next = cache_head;
                cache_head = e;
                found = e;
            }
        }
    }
    pthread_mutex_unlock(&cache_lock);
    if (found == NULL)
        ft_error(FT_E_NOMEM, "fft: FFTW could not plan a %zu x %zu transform", ny, nx);
    return found;
}

static fftw_plan get_plan(plan_kind kind, size_t ny, size_t nx, int sign, void *in, void *out)
{
    const plan_entry *e = get_entry(kind, ny, nx, sign, in, out);
    return e != NULL ? e->plan : NULL;
}

int ft_fft_r2c_2d(size_t ny, size_t nx, const double *in, fftw_complex *out)
{
    int rc = check_size("r2c", ny, nx, in, out);
    if (rc != FT_OK)
        return rc;
    /* FFTW's r2c does not write its input out of place (FFTW_PRESERVE_INPUT is its default for r2c);
     * the cast only meets its non-const prototype. */
    double *src = (double *)(uintptr_t)in;
    fftw_plan p = get_plan(KIND_R2C_2D, ny, nx, 0, src, out);
    if (p == NULL)
        return FT_E_NOMEM;
    fftw_execute_dft_r2c(p, src, out);
    return FT_OK;
}

int ft_fft_c2r_2d(size_t ny, size_t nx, fftw_complex *in, double *out)
{
    int rc = check_size("c2r", ny, nx, in, out);
    if (rc != FT_OK)
        return rc;
    fftw_plan p = get_plan(KIND_C2R_2D, ny, nx, 0, in, out);
    if (p == NULL)
        return FT_E_NOMEM;
    fftw_execute_dft_c2r(p, in, out);
    return FT_OK;
}

/* ft_fft_c2r_2df: the 2-D inverse as its two passes of 1-D transforms (row-column algorithm), blocked
 * for the cache and spread over OpenMP threads. FFTW_ESTIMATE's own rank-2 plans walk the columns one
 * at a time at a stride of a whole row for many sizes (5120² takes 2.3x as long as 4608²); here a
 * block of COL_BLOCK columns is gathered into a contiguous buffer (one cache line per row), transformed
 * and scattered back, then the rows are transformed ROW_BLOCK at a time in place. Every block runs the
 * same cached plan on the same layout whichever thread takes it, so the result does not depend on the
 * thread count. */
#define COL_BLOCK 8   /* complex columns per block: 64 bytes of a row */
#define ROW_BLOCK 16  /* rows per batch; even, so every batch starts as aligned as row 0 */

static void column_block(fftwf_complex *spec, size_t ny, size_t ncx, size_t c0, fftwf_complex *buf,
                         fftwf_plan plan)
{
    size_t w = ncx - c0 < COL_BLOCK ? ncx - c0 : COL_BLOCK;
    if (w < COL_BLOCK)
        memset(buf, 0, COL_BLOCK * ny * sizeof *buf);
    for (size_t y = 0; y < ny; y++)
        memcpy(buf + y * COL_BLOCK, spec + y * ncx + c0, w * sizeof *buf);
    fftwf_execute_dft(plan, buf, buf);
    for (size_t y = 0; y < ny; y++)
        memcpy(spec + y * ncx + c0, buf + y * COL_BLOCK, w * sizeof *buf);
}

static fftwf_plan get_planf(plan_kind kind, size_t howmany, size_t n, void *in, void *out)
{
    const plan_entry *e = get_entry(kind, howmany, n, 0, in, out);
    return e != NULL ? e->planf : NULL;
}

/* The column pass over blocks [0, nblocks) of COL_BLOCK columns; 0, or 1 if out of memory. */
static int column_pass(fftwf_complex *spec, size_t ny, size_t ncx)
{
    size_t nblocks = (ncx + COL_BLOCK - 1) / COL_BLOCK;
    int failed = 0;
#pragma omp parallel reduction(| : failed)
    {
        fftwf_complex *buf = fftwf_malloc(COL_BLOCK * ny * sizeof *buf);
        fftwf_plan plan = buf ? get_planf(KIND_COLS_C2CF, COL_BLOCK, ny, buf, buf) : NULL;
        failed |= plan == NULL;
#pragma omp for schedule(static)
        for (size_t k = 0; k < nblocks; k++)
            if (plan != NULL)
                column_block(spec, ny, ncx, k * COL_BLOCK, buf, plan);
        if (buf != NULL)
            fftwf_free(buf);
    }
    return failed;
}

/* The row pass: batches of ROW_BLOCK rows, the last one shorter with its own plan; 0, or 1 if FFTW could
 * not plan. */
static int row_pass(fftwf_complex *spec, size_t ny, size_t nx)
{
    size_t ncx = nx / 2 + 1, nfull = ny / ROW_BLOCK, rest = ny % ROW_BLOCK;
    fftwf_plan full = nfull ? get_planf(KIND_ROWS_C2RF, ROW_BLOCK, nx, spec, spec) : NULL;
    fftwf_complex *tail = spec + nfull * ROW_BLOCK * ncx;
    fftwf_plan last = rest ? get_planf(KIND_ROWS_C2RF, rest, nx, tail, tail) : NULL;
    if ((nfull && full == NULL) || (rest && last == NULL))
        return 1;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < nfull; k++) {
        fftwf_complex *rows = spec + k * ROW_BLOCK * ncx;
        fftwf_execute_dft_c2r(full, rows, (float *)rows);
    }
    if (rest)
        fftwf_execute_dft_c2r(last, tail, (float *)tail);
    return 0;
}

int ft_fft_c2r_2df_rows(size_t ny, size_t nx, fftwf_complex *spec, size_t nrows)
{
    int rc = check_size("c2r", ny, nx, spec, spec);
    if (rc != FT_OK)
        return rc;
    if (nrows == 0 || nrows > ny)
        return ft_error(FT_E_INVALID, "fft: %zu output rows asked of a %zu-row transform", nrows, ny);
    /* whole batches only, so every row kept goes through the plan (and batch) of the full row pass */
    size_t rows = (nrows + ROW_BLOCK - 1) / ROW_BLOCK * ROW_BLOCK;
    if (rows > ny)
        rows = ny;
    size_t ncx = nx / 2 + 1;
    if (column_pass(spec, ny, ncx) || row_pass(spec, rows, nx))
        return ft_error(FT_E_NOMEM, "fft: out of memory or no FFTW plan for a %zu x %zu transform", ny, nx);
    return FT_OK;
}

int ft_fft_c2r_2df(size_t ny, size_t nx, fftwf_complex *spec)
{
    return ft_fft_c2r_2df_rows(ny, nx, spec, ny);
}

int ft_fft_c2c_1d(size_t n, fftw_complex *in, fftw_complex *out, int sign)
{
    int rc = check_size("c2c", 1, n, in, out);
    if (rc != FT_OK)
        return rc;
    if (sign != FT_FFT_FORWARD && sign != FT_FFT_BACKWARD)
        return ft_error(FT_E_INVALID, "fft: sign must be -1 (forward) or +1 (backward), got %d", sign);
    fftw_plan p = get_plan(KIND_C2C_1D, 1, n, sign, in, out);
    if (p == NULL)
        return FT_E_NOMEM;
    fftw_execute_dft(p, in, out);
    return FT_OK;
}

void ft_fft_cleanup(void)
{
    pthread_mutex_lock(&cache_lock);
    plan_entry *e = cache_head;
    while (e != NULL) {
        plan_entry *next = e->next;
        if (e->plan != NULL)
            fftw_destroy_plan(e->plan);
        if (e->planf != NULL)
            fftwf_destroy_plan(e->planf);
        free(e);
        e = next;
    }
    cache_head = NULL;
    fftw_cleanup();
    fftwf_cleanup();
    pthread_mutex_unlock(&cache_lock);
}
