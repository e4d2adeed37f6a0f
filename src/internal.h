/* fracterra — private helpers shared by the library's modules (not installed).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_INTERNAL_H
#define FRACTERRA_INTERNAL_H

#include <stddef.h>

/* Atomic output (src/core/tmpfile.c): write to ft_tmp_path(path), then ft_tmp_commit() renames it (and
 * every sibling file sharing its stem, e.g. a Shapefile's .shx/.dbf/.prj) onto the final name, or
 * ft_tmp_discard() removes them. The temporary lives in the destination folder, so rename is atomic. */
char *ft_tmp_path(const char *path);            /* malloc'd ".<stem>.ft-tmp-<pid>-<n><ext>" beside path */
int ft_tmp_commit(const char *tmp, const char *path);
void ft_tmp_discard(const char *tmp);

/* Safe allocation helpers: set FT_E_NOMEM on failure. */
void *ft_malloc(size_t size);
void *ft_calloc(size_t n, size_t size);
void *ft_realloc_array(void *p, size_t n, size_t size); /* checks n*size overflow */
char *ft_strdup(const char *s);                         /* NULL stays NULL */

#endif /* FRACTERRA_INTERNAL_H */
