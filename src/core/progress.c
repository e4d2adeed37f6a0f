/* fracterra — core/progress.c: reporting progress through a GDAL-style callback, with cancellation, and
 * the scaled ranges a job of several stages reports through (src/internal.h).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>

#include "fracterra/core.h"
#include "internal.h"

int ft_progress(ft_progress_fn fn, void *arg, double frac, const char *msg)
{
    if (fn == NULL)
        return FT_OK;
    if (!(frac >= 0.0))
        frac = 0.0;
    else if (frac > 1.0)
        frac = 1.0;
    if (fn(frac, msg, arg) == 0)
        return ft_error(FT_E_CANCELLED, "cancelled by the progress callback at %.0f%%%s%s", 100.0 * frac,
                        msg && *msg ? ": " : "", msg ? msg : "");
    return FT_OK;
}

ft_progress_range ft_progress_range_whole(ft_progress_fn fn, void *arg)
{
    ft_progress_range r = {fn, arg, 0.0, 1.0};
    return r;
}

int ft_progress_range_report(const ft_progress_range *p, double f, const char *msg)
{
    if (p == NULL || p->fn == NULL)
        return FT_OK;
    return ft_progress(p->fn, p->arg, p->base + p->span * fmin(1.0, fmax(0.0, f)), msg);
}

ft_progress_range ft_progress_range_sub(const ft_progress_range *p, double from, double to)
{
    ft_progress_range s = {NULL, NULL, 0.0, 0.0};
    if (p != NULL)
        s = (ft_progress_range){p->fn, p->arg, p->base + from * p->span, (to - from) * p->span};
    return s;
}
