/* fracterra — surface/points_pairs_exact.c: the counters of Arakawa & Krotkov §2.4 step 1 by the paper's
 * own enumeration: every pair i < j of the N points, O(N²) ("after considering all pairs of data
 * points"). The reference the grid enumeration (points_pairs_grid.c) must match bit for bit; both use the
 * per-pair test and fixed-point sums of points_internal.h. OpenMP over i, one set of counters per thread,
 * merged as integers.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <omp.h>
#include <stdlib.h>

#include "internal.h"
#include "points_internal.h"

#define CHUNKS 64

int pts_pairs_exact(const ft_points *p, const pts_lags *L, pts_acc *acc, ft_progress_fn fn, void *arg)
{
    int nt = omp_get_max_threads();
    pts_acc *part = ft_calloc((size_t)nt * L->n, sizeof *part);
    if (part == NULL)
        return FT_E_NOMEM;
    size_t n = p->n;
    int rc = FT_OK;
    /* Chunks of equal pair counts: row i holds n - 1 - i pairs. */
    size_t i0 = 0;
    for (size_t chunk = 0; rc == FT_OK && chunk < CHUNKS && i0 < n; chunk++) {
        double left = 1.0 - (double)(chunk + 1) / CHUNKS;
        size_t i1 = chunk + 1 == CHUNKS ? n : (size_t)((double)n * (1.0 - sqrt(left)));
        if (i1 < i0)
            i1 = i0;
#pragma omp parallel for schedule(dynamic, 8)
        for (size_t i = i0; i < i1; i++) {
            pts_acc *a = part + (size_t)omp_get_thread_num() * L->n;
            double xi = p->x[i], yi = p->y[i], zi = p->z[i];
            for (size_t j = i + 1; j < n; j++) {
                double dx = p->x[j] - xi, dy = p->y[j] - yi;
                pts_add_pair(L, a, dx * dx + dy * dy, p->z[j] - zi);
            }
        }
        i0 = i1;
        rc = ft_progress(fn, arg, (double)(chunk + 1) / CHUNKS, "pairs");
    }
    for (int t = 0; rc == FT_OK && t < nt; t++)
        pts_acc_merge(acc, part + (size_t)t * L->n, L->n);
    free(part);
    return rc;
}
