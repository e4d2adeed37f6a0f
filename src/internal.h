/* fracterra — private helpers shared by the library's modules (not installed).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_INTERNAL_H
#define FRACTERRA_INTERNAL_H

#include <stddef.h>

/* Safe allocation helpers: set FT_E_NOMEM on failure. */
void *ft_malloc(size_t size);
void *ft_calloc(size_t n, size_t size);
void *ft_realloc_array(void *p, size_t n, size_t size); /* checks n*size overflow */
char *ft_strdup(const char *s);                         /* NULL stays NULL */

#endif /* FRACTERRA_INTERNAL_H */
