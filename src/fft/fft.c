/* fracterra — fft.c: FFTW3 plan cache (one plan per kind, size, direction, in-place and alignment,
 * created under a mutex with FFTW_ESTIMATE) and the 2-D real / 1-D complex transforms that execute the
 * cached plans on the caller's arrays through FFTW's thread-safe new-array execute functions.
 * See fft.h for layouts and normalisation (none).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fft/fft.h"

#include <limits.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>

#include "fracterra/core.h"

typedef enum { KIND_R2C_2D = 0, KIND_C2R_2D = 1, KIND_C2C_1D = 2 } plan_kind;

typedef struct plan_entry {
    plan_kind kind;
    size_t ny, nx;
    int sign, inplace, unaligned;
    fftw_plan plan;
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

static fftw_plan make_plan(plan_kind kind, size_t ny, size_t nx, int sign, unsigned flags, void *in,
                           void *out)
{
    switch (kind) {
    case KIND_R2C_2D:
        return fftw_plan_dft_r2c_2d((int)ny, (int)nx, in, out, flags);
    case KIND_C2R_2D:
        return fftw_plan_dft_c2r_2d((int)ny, (int)nx, in, out, flags);
    case KIND_C2C_1D:
        return fftw_plan_dft_1d((int)nx, in, out, sign, flags);
    }
    return NULL;
}

/* The cached plan for this problem, created on first use. With FFTW_ESTIMATE the planner neither reads
 * nor writes the arrays, so the caller's own arrays serve for planning. */
static fftw_plan get_plan(plan_kind kind, size_t ny, size_t nx, int sign, void *in, void *out)
{
    int inplace = in == out;
    int unaligned = fftw_alignment_of(in) != 0 || fftw_alignment_of(out) != 0;
    fftw_plan plan = NULL;
    pthread_mutex_lock(&cache_lock);
    for (plan_entry *e = cache_head; e != NULL; e = e->next)
        if (e->kind == kind && e->ny == ny && e->nx == nx && e->sign == sign && e->inplace == inplace &&
            e->unaligned == unaligned) {
            plan = e->plan;
            break;
        }
    if (plan == NULL) {
        unsigned flags = FFTW_ESTIMATE | (unaligned ? FFTW_UNALIGNED : 0u);
        if (kind == KIND_C2R_2D)
            flags |= FFTW_DESTROY_INPUT;
        plan_entry *e = malloc(sizeof *e);
        if (e != NULL) {
            e->plan = make_plan(kind, ny, nx, sign, flags, in, out);
            if (e->plan == NULL) {
                free(e);
            } else {
                e->kind = kind;
                e->ny = ny;
                e->nx = nx;
                e->sign = sign;
                e->inplace = inplace;
                e->unaligned = unaligned;
                e->next = cache_head;
                cache_head = e;
                plan = e->plan;
            }
        }
    }
    pthread_mutex_unlock(&cache_lock);
    if (plan == NULL)
        ft_error(FT_E_NOMEM, "fft: FFTW could not plan a %zu x %zu transform", ny, nx);
    return plan;
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
        fftw_destroy_plan(e->plan);
        free(e);
        e = next;
    }
    cache_head = NULL;
    fftw_cleanup();
    pthread_mutex_unlock(&cache_lock);
}
