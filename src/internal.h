/* fracterra — private helpers shared by the library's modules (not installed).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_INTERNAL_H
#define FRACTERRA_INTERNAL_H

#include <stddef.h>

#include "fracterra/core.h"

/* Safe allocation helpers: set FT_E_NOMEM on failure. */
void *ft_malloc(size_t size);
void *ft_calloc(size_t n, size_t size);
void *ft_realloc_array(void *p, size_t n, size_t size); /* checks n*size overflow */
char *ft_strdup(const char *s);                         /* NULL stays NULL */
/* The same for large arrays written once per use (indexes rebuilt every pass): from 2 MB on, aligned on
 * 2 MB with a transparent-huge-page hint (one page fault per 2 MB instead of per 4 kB). Freed with free(). */
void *ft_malloc_huge(size_t size);
void *ft_calloc_huge(size_t n, size_t size);

/* The library's copy of a caller's options struct (FT_OPTS in core.h): *lib holds the defaults of the
 * lib_size-byte struct on entry; the first user->struct_size bytes of *user are copied over them and
 * lib->struct_size becomes lib_size. FT_E_INVALID naming type when struct_size is below
 * sizeof(size_t) or above lib_size. user NULL leaves the defaults. */
int ft_opts_take(void *lib, size_t lib_size, const void *user, const char *type);
/* FT_OPTS_TAKE(local, user, type): ft_opts_take on a local struct of the given type name. */
#define FT_OPTS_TAKE(local, user, type) ft_opts_take(&(local), sizeof(local), (user), #type)

/* The input of a chain operation (Line's editing, Contour's operators): out not NULL (set to NULL), the chain
 * not NULL, finite, with >= 2 vertices (>= 3 for a ring). Errors name the operation op. */
static inline int ft_chain_check_operand(const char *op, const ft_chain *in, ft_chain **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "%s: NULL output pointer", op);
    *out = NULL;
    if (in == NULL)
        return ft_error(FT_E_INVALID, "%s: NULL chain", op);
    int rc = ft_chain_check_min_vertices(in, in->closed ? 3 : 2);
    if (rc == FT_OK)
        rc = ft_chain_check_finite(in);
    return rc;
}

/* Scaled progress (core/progress.c), as GDAL's GDALCreateScaledProgress: a stage of a long job reports its
 * own fraction f in [0, 1], which reaches the caller's callback as base + span * f. */
typedef struct {
    ft_progress_fn fn; /* the caller's callback, may be NULL */
    void *arg;
    double base, span;
} ft_progress_range;
/** The whole of the caller's progress: fraction f reported as f. */
ft_progress_range ft_progress_range_whole(ft_progress_fn fn, void *arg);
/** Reports fraction f (clamped to [0, 1]) of the range; p may be NULL (nothing reported). FT_E_CANCELLED
 *  (error set) if the callback asked to stop. */
int ft_progress_range_report(const ft_progress_range *p, double f, const char *msg);
/** The part [from, to] (fractions of p) of the range p; a silent range when p is NULL. */
ft_progress_range ft_progress_range_sub(const ft_progress_range *p, double from, double to);

#endif /* FRACTERRA_INTERNAL_H */
