/* fracterra — core/progress.c: reporting progress through a GDAL-style callback, with cancellation.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/core.h"

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
