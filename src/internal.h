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

/* The library's copy of a caller's options struct (FT_OPTS in core.h): *lib holds the defaults of the
 * lib_size-byte struct on entry; the first user->struct_size bytes of *user are copied over them and
 * lib->struct_size becomes lib_size. FT_E_INVALID naming type when struct_size is below
 * sizeof(size_t) or above lib_size. user NULL leaves the defaults. */
int ft_opts_take(void *lib, size_t lib_size, const void *user, const char *type);
/* FT_OPTS_TAKE(local, user, type): ft_opts_take on a local struct of the given type name. */
#define FT_OPTS_TAKE(local, user, type) ft_opts_take(&(local), sizeof(local), (user), #type)

#endif /* FRACTERRA_INTERNAL_H */
