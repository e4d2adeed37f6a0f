/* fracterra — core/alloc.c: allocation helpers that set FT_E_NOMEM (with the byte count) on failure.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

/* Zero-byte requests allocate one byte, so that a non-NULL return always means success. */
void *ft_malloc(size_t size)
{
    void *p = malloc(size ? size : 1);
    if (p == NULL)
        ft_error(FT_E_NOMEM, "out of memory allocating %zu bytes", size);
    return p;
}

void *ft_calloc(size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size) {
        ft_error(FT_E_NOMEM, "cannot allocate %zu x %zu bytes: size overflows", n, size);
        return NULL;
    }
    void *p = calloc(n ? n : 1, size ? size : 1);
    if (p == NULL)
        ft_error(FT_E_NOMEM, "out of memory allocating %zu x %zu bytes", n, size);
    return p;
}

/* Like realloc(p, n*size): on failure p is left untouched and NULL is returned. */
void *ft_realloc_array(void *p, size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size) {
        ft_error(FT_E_NOMEM, "cannot allocate %zu x %zu bytes: size overflows", n, size);
        return NULL;
    }
    size_t bytes = n * size;
    void *q = realloc(p, bytes ? bytes : 1);
    if (q == NULL)
        ft_error(FT_E_NOMEM, "out of memory allocating %zu bytes", bytes);
    return q;
}

/* Large arrays filled once and read a few times (an index rebuilt every pass) cost more in the kernel than in
 * the code: every fresh 4 kB page is a fault and a clear. From FT_HUGE_MIN bytes on, the block is aligned
 * on 2 MB and asks for transparent huge pages (madvise mode): one fault per 2 MB. Only a hint: where the
 * kernel has none to give, the pages are small and nothing else changes. Freed with free(). Not for every
 * array: on a virtual machine whose host provisions a fresh huge page on its first write, an array written
 * once and dropped can get slower (measured on the chains: docs/line-enhance.md, Speed, session 10). */
#define FT_HUGE_MIN ((size_t)2 << 20)

void *ft_malloc_huge(size_t size)
{
#ifdef MADV_HUGEPAGE
    if (size >= FT_HUGE_MIN) {
        size_t bytes = (size + FT_HUGE_MIN - 1) & ~(FT_HUGE_MIN - 1);
        void *p = NULL;
        if (bytes < size || posix_memalign(&p, FT_HUGE_MIN, bytes) != 0) {
            ft_error(FT_E_NOMEM, "out of memory allocating %zu bytes", size);
            return NULL;
        }
        (void)madvise(p, bytes, MADV_HUGEPAGE);
        return p;
    }
#endif
    return ft_malloc(size);
}

void *ft_calloc_huge(size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size) {
        ft_error(FT_E_NOMEM, "cannot allocate %zu x %zu bytes: size overflows", n, size);
        return NULL;
    }
    if (n * size < FT_HUGE_MIN)
        return ft_calloc(n, size);
    void *p = ft_malloc_huge(n * size);
    if (p != NULL)
        memset(p, 0, n * size);
    return p;
}

char *ft_strdup(const char *s)
{
    if (s == NULL)
        return NULL;
    size_t len = strlen(s) + 1;
    char *d = ft_malloc(len);
    if (d != NULL)
        memcpy(d, s, len);
    return d;
}
