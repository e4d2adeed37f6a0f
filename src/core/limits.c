/* fracterra — core/limits.c: the memory and work bounds every estimate is checked against before a long
 * or large computation starts (so that a typo in a size or scale is refused in a millisecond instead of
 * running for hours or being killed by the kernel half-way through a write).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/core.h"

#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <unistd.h>

static _Atomic size_t memory_limit;     /* 0: the default */
static _Atomic double work_limit;       /* 0: the default */

size_t ft_memory_limit(void)
{
    size_t m = atomic_load(&memory_limit);
    if (m != 0)
        return m;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if (pages <= 0 || page <= 0)
        return (size_t)4 << 30; /* unknown machine: 4 GB */
    double half = 0.5 * (double)pages * (double)page;
    return half >= (double)SIZE_MAX ? SIZE_MAX : (size_t)half;
}

void ft_set_memory_limit(size_t bytes)
{
    atomic_store(&memory_limit, bytes);
}

double ft_work_limit(void)
{
    double w = atomic_load(&work_limit);
    return w > 0.0 ? w : FT_WORK_LIMIT_DEFAULT;
}

void ft_set_work_limit(double steps)
{
    atomic_store(&work_limit, steps > 0.0 && isfinite(steps) ? steps : 0.0);
}

/* "512 MB", "12.5 GB", "3.2e+04 TB". */
static void human_bytes(double b, char *buf, size_t size)
{
    static const char *const unit[] = {"bytes", "KB", "MB", "GB", "TB"};
    int u = 0;
    while (b >= 1024.0 && u < 4) {
        b /= 1024.0;
        u++;
    }
    snprintf(buf, size, u == 0 ? "%.0f %s" : "%.3g %s", b, unit[u]);
}

int ft_check_memory(double bytes, const char *what)
{
    double limit = (double)ft_memory_limit();
    if (bytes <= limit)
        return FT_OK;
    char need[32], have[32];
    if (isfinite(bytes))
        human_bytes(bytes, need, sizeof need);
    else
        snprintf(need, sizeof need, "more than any machine's");
    human_bytes(limit, have, sizeof have);
    return ft_error(FT_E_NOMEM, "%s would need %s of memory, more than the %s limit (raise it with --max-memory)",
                    what ? what : "this computation", need, have);
}

int ft_check_work(double steps, const char *what)
{
    double limit = ft_work_limit();
    if (steps <= limit)
        return FT_OK;
    if (isfinite(steps))
        return ft_error(FT_E_UNSUPPORTED, "%s would take %.3g steps, more than the %.3g limit (raise it with --max-work)",
                        what ? what : "this computation", steps, limit);
    return ft_error(FT_E_UNSUPPORTED, "%s would never finish (unbounded work)", what ? what : "this computation");
}
