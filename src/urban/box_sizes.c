/* fracterra — src/urban/box_sizes.c: the box sides of the polygon and raster box counters and the fit of
 * their log-log table (Zhang, Yu & Fan 2008, §1.1: ln N(r) = -D ln r + ln c, Eq. 2, fitted by
 * least squares, Eq. 4), shared with every estimator through ft_loglog_fit_auto (docs/loglog.md).
 *
 * Sides are either the caller's explicit list (sorted, all kept) or the geometric series
 * s_i = lo (hi / lo)^(i / (N - 1)), i = 0 .. N - 1, where a zero limit is replaced by the counter's automatic
 * one (docs/urban-boxcount.md).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <strings.h>

#include "internal.h"
#include "urban/urban_internal.h"

#define NSCALES_DEFAULT 12
#define NSCALES_MAX 1000
#define OFFSETS_MAX 16

static const char *const what_names[] = {"boundary", "area"};

const char *ft_area_what_name(ft_area_what w)
{
    return (unsigned)w < 2 ? what_names[w] : "unknown";
}

int ft_area_what_parse(const char *name, ft_area_what *w)
{
    if (name == NULL || w == NULL)
        return ft_error(FT_E_INVALID, "ft_area_what_parse: NULL %s", name == NULL ? "name" : "what");
    for (unsigned i = 0; i < 2; i++)
        if (strcasecmp(name, what_names[i]) == 0) {
            *w = (ft_area_what)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "unknown box count '%s' (boundary or area)", name);
}

int ft_area_sizes_check(const ft_area_dim_opts *o)
{
    if ((unsigned)o->what > FT_AREA_AREA)
        return ft_error(FT_E_INVALID, "box counting: what must be boundary (0) or area (1), got %d", (int)o->what);
    if (o->offsets < 1 || o->offsets > OFFSETS_MAX)
        return ft_error(FT_E_INVALID, "box counting: offsets must be in [1, %d], got %d", OFFSETS_MAX, o->offsets);
    if (o->ncells > 0) {
        if (o->cells == NULL)
            return ft_error(FT_E_INVALID, "box counting: %zu cell sizes but a NULL list", o->ncells);
        if (o->ncells < 2)
            return ft_error(FT_E_INVALID, "box counting: at least 2 cell sizes are needed for a slope, got %zu",
                            o->ncells);
        for (size_t i = 0; i < o->ncells; i++)
            if (!(o->cells[i] > 0.0) || !isfinite(o->cells[i]))
                return ft_error(FT_E_INVALID, "box counting: cell size %zu must be finite and > 0, got %g", i + 1,
                                o->cells[i]);
        return FT_OK;
    }
    if (!(o->min_cell >= 0.0) || !isfinite(o->min_cell))
        return ft_error(FT_E_INVALID, "box counting: min_cell must be finite and >= 0 (0 = automatic), got %g",
                        o->min_cell);
    if (!(o->max_cell >= 0.0) || !isfinite(o->max_cell))
        return ft_error(FT_E_INVALID, "box counting: max_cell must be finite and >= 0 (0 = automatic), got %g",
                        o->max_cell);
    if (o->min_cell > 0.0 && o->max_cell > 0.0 && !(o->min_cell < o->max_cell))
        return ft_error(FT_E_INVALID, "box counting: min_cell (%g) must be less than max_cell (%g)", o->min_cell,
                        o->max_cell);
    if (o->nscales != 0 && (o->nscales < 3 || o->nscales > NSCALES_MAX))
        return ft_error(FT_E_INVALID, "box counting: nscales must be in [3, %d] (0 = default), got %d", NSCALES_MAX,
                        o->nscales);
    return FT_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int ft_area_sizes(const ft_area_dim_opts *o, double lo_auto, double hi_auto, double **sizes, size_t *n)
{
    *sizes = NULL;
    *n = 0;
    if (o->ncells > 0) {
        double *s = ft_malloc(o->ncells * sizeof *s);
        if (s == NULL)
            return FT_E_NOMEM;
        for (size_t i = 0; i < o->ncells; i++)
            s[i] = o->cells[i];
        qsort(s, o->ncells, sizeof *s, cmp_double);
        for (size_t i = 1; i < o->ncells; i++)
            if (s[i] == s[i - 1]) {
                double dup = s[i];
                free(s);
                return ft_error(FT_E_INVALID, "box counting: cell size %g is given twice", dup);
            }
        *sizes = s;
        *n = o->ncells;
        return FT_OK;
    }
    double lo = o->min_cell > 0.0 ? o->min_cell : lo_auto, hi = o->max_cell > 0.0 ? o->max_cell : hi_auto;
    if (!(lo > 0.0 && lo < hi) || !isfinite(hi))
        return ft_error(FT_E_INVALID, "box counting: empty size range: min_cell %g%s, max_cell %g%s; set the cell "
                        "sizes", lo, o->min_cell > 0.0 ? "" : " (automatic)", hi,
                        o->max_cell > 0.0 ? "" : " (automatic)");
    int ns = o->nscales > 0 ? o->nscales : NSCALES_DEFAULT;
    double *s = ft_malloc((size_t)ns * sizeof *s);
    if (s == NULL)
        return FT_E_NOMEM;
    const double step = log(hi / lo) / (ns - 1);
    for (int i = 0; i < ns; i++)
        s[i] = i == ns - 1 ? hi : lo * exp(step * i);
    *sizes = s;
    *n = (size_t)ns;
    return FT_OK;
}

int ft_area_fit(const ft_loglog *t, const ft_area_dim_opts *o, const char *method, ft_dim_result **out)
{
    const ft_dim_map map = FT_DIM_MAP_BOXCOUNT;
    double lo = t->rows[0].scale, hi = t->rows[t->n - 1].scale;
    int rc = o->fit_whole_range ? ft_loglog_fit_range(t, lo, hi, &map, out)
                                : ft_loglog_fit_auto(t, lo, hi, &o->fit, &map, out);
    if (rc == FT_OK)
        (*out)->method = method;
    return rc;
}
