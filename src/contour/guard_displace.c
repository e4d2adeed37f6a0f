/* fracterra — contour/guard_displace.c: the crossing guard (line/move_guard.c) applied to the random midpoint
 * displacement of the mountain generator (Misawa, Chiba & Saito §4.1, contour/midpoint_displace.c): the
 * displaced rings of a level must stay simple, apart from each other, and clear of the level below (the
 * contour stack stays nested by construction, not only by the clipping of mountain.c's nesting step).
 *
 * A displaced ring holds the undisplaced ring's vertices, in order, with the added vertices between them.
 * Its base puts every added vertex back on the segment it was drawn from, at its fraction of the displaced
 * piece's length, so the base is the undisplaced ring with collinear vertices added: clear of everything if
 * the undisplaced rings are. The guard then moves each added vertex towards its displaced position all, half,
 * a quarter of the way or not at all, as far as it sweeps no other segment (FT_GUARD_REDUCE); the rings of
 * the level below are in the chain set, fixed.
 *
 * The Fourier phase randomization (fourier_descriptor.c, §4.2) is guarded the same way
 * (ft_contour_guard_rings): its base is the ring resampled to the n points the randomization starts from,
 * vertex j of the randomized ring being drawn from vertex j of the resampled one. The resampled ring cuts
 * the input ring's corners by at most half a step (perimeter / n), far less than the spacing d between
 * levels, so it is clear of the level below; rings of one level that come closer than that may touch in
 * the base, and the guard cannot part them (mountain.c's clean and nesting steps still do).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "internal.h"
#include "contour/contour_internal.h"
#include "fracterra/line.h"

#include <math.h>
#include <stdlib.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* A level's rings hold a few thousand vertices: far less than one of the guard's parallel chunks, so its
 * parallel regions only wait at their barriers (seconds of spinning per mountain on a loaded machine:
 * test_contour_mountain took 11.6 s of CPU on 2 threads against 0.95 s on one). Below this many vertices
 * the guard runs on the calling thread; the guard gives the same bits on any thread count. */
#define GUARD_SERIAL_BELOW 65536

/* The displaced ring's base for the crossing guard: ring with every vertex the displacement added put back
 * on the segment of ring it was drawn from, at its fraction of the displaced piece's length (so the base is
 * ring itself with collinear vertices added, and every added vertex moves from there to its displaced
 * position). *out stays NULL (no error) if ring's vertices are not found in raw, in order. */
static int undisplaced(const ft_chain *ring, const ft_chain *raw, ft_chain **out)
{
    *out = NULL;
    size_t n = ring->n, nseg = ft_chain_segments(ring), p = 0;
    if (!ring->closed || !raw->closed || raw->n < n || raw->x[0] != ring->x[0] || raw->y[0] != ring->y[0])
        return FT_OK;
    ft_chain *b = ft_chain_copy(raw);
    if (b == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < nseg; i++) {
        size_t j = i + 1 < n ? i + 1 : 0, q = raw->n; /* the last segment ends at raw's vertex 0 */
        if (j != 0)
            for (q = p + 1; q < raw->n && (raw->x[q] != ring->x[j] || raw->y[q] != ring->y[j]); q++)
                ;
        if (q >= raw->n && j != 0) {
            ft_chain_free(b);
            return FT_OK;
        }
        double total = 0.0, run = 0.0;
        for (size_t k = p; k < q; k++) {
            size_t k1 = k + 1 < raw->n ? k + 1 : 0;
            total += hypot(raw->x[k1] - raw->x[k], raw->y[k1] - raw->y[k]);
        }
        for (size_t k = p + 1; k < q; k++) {
            run += hypot(raw->x[k] - raw->x[k - 1], raw->y[k] - raw->y[k - 1]);
            double t = total > 0.0 ? run / total : 0.0;
            b->x[k] = ring->x[i] + t * (ring->x[j] - ring->x[i]);
            b->y[k] = ring->y[i] + t * (ring->y[j] - ring->y[i]);
        }
        p = q;
    }
    *out = b;
    return FT_OK;
}

int ft_contour_guard_rings(ft_chain **rings, ft_chain **bases, size_t nr, const ft_polygon_set *below,
                           ft_line_guard_stats *stats)
{
    if ((rings == NULL || bases == NULL) && nr > 0)
        return ft_error(FT_E_INVALID, "guarded rings: NULL rings");
    size_t nb = ft_polygon_set_ring_count(below), n = nr + nb;
    ft_chain **base = ft_calloc(n + 1, sizeof *base);
    const ft_chain **raw = ft_calloc(n + 1, sizeof *raw);
    int rc = base != NULL && raw != NULL ? FT_OK : FT_E_NOMEM;
    for (size_t k = 0; k < nr; k++) {
        if (base != NULL)
            base[k] = bases[k];
        else
            ft_chain_free(bases[k]);
        bases[k] = NULL;
        if (raw != NULL)
            raw[k] = rings[k];
        if (rc == FT_OK && (rings[k]->n != base[k]->n || rings[k]->closed != base[k]->closed))
            rc = ft_error(FT_E_INVALID, "guarded rings: ring %zu has %zu vertices, its base %zu", k, rings[k]->n,
                          base[k]->n);
    }
    for (size_t k = 0; rc == FT_OK && k < nb; k++) {
        raw[nr + k] = ft_polygon_set_ring(below, k);
        if ((base[nr + k] = ft_chain_copy(raw[nr + k])) == NULL)
            rc = FT_E_NOMEM;
    }
    size_t nv = 0;
    for (size_t k = 0; rc == FT_OK && k < n; k++)
        nv += raw[k]->n;
#ifdef _OPENMP
    int threads = omp_get_max_threads(); /* the calling thread's setting, restored below */
    if (nv < GUARD_SERIAL_BELOW)
        omp_set_num_threads(1);
#endif
    if (rc == FT_OK)
        rc = ft_line_guard_moves(base, raw, n, FT_GUARD_REDUCE, stats);
#ifdef _OPENMP
    omp_set_num_threads(threads);
#endif
    for (size_t k = 0; k < n && base != NULL; k++) {
        if (rc == FT_OK && k < nr) {
            ft_chain_free(rings[k]);
            rings[k] = base[k];
        } else {
            ft_chain_free(base[k]);
        }
    }
    free(base);
    free(raw);
    return rc;
}

int ft_contour_guard_displaced(ft_chain **rings, const ft_chain *const *used, size_t nr, const ft_polygon_set *below,
                               ft_line_guard_stats *stats)
{
    if ((rings == NULL || used == NULL) && nr > 0)
        return ft_error(FT_E_INVALID, "guarded displacement: NULL rings");
    ft_chain **base = ft_calloc(nr + 1, sizeof *base);
    int rc = base != NULL ? FT_OK : FT_E_NOMEM;
    for (size_t k = 0; rc == FT_OK && k < nr; k++) {
        rc = undisplaced(used[k], rings[k], &base[k]);
        if (rc == FT_OK && base[k] == NULL && (base[k] = ft_chain_copy(rings[k])) == NULL)
            rc = FT_E_NOMEM;
    }
    if (rc == FT_OK)
        rc = ft_contour_guard_rings(rings, base, nr, below, stats); /* takes the bases */
    for (size_t k = 0; k < nr && base != NULL; k++)
        ft_chain_free(base[k]);
    free(base);
    return rc;
}
