/* fracterra — core/alloc.c: allocation helpers that set FT_E_NOMEM (with the byte count) on failure.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "fracterra/core.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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
