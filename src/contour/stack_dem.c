/* fracterra — contour/stack_dem.c: the DEM of a contour stack (ft_contour_stack_to_dem), interpolated
 * between neighbouring contours as GRASS r.surf.contour does, with summits and pits shaped above and
 * below the last contour (docs/contour-mountain.md, "From contours to a DEM").
 *
 * 1. Level index. Every ring of every level adds its signed crossings of the cell-centre rows to a
 *    difference array (+1 into an outer ring, -1 into a hole, whatever the ring's orientation); a prefix
 *    sum along each row gives, at every cell centre, the number of levels whose polygons contain it.
 *    Levels are nested, so that number minus one is the cell's level index L (-1: outside the lowest
 *    contour, nodata). One pass over all levels at once.
 * 2. Distances. A cell of band L lies between contour L (its enclosing contour, elevation z_lo) and
 *    contour L + 1 (the enclosed one(s), z_hi). It keeps two sites: the nearest point found so far on
 *    contour L and on contour L + 1. Cells within 1.5 cells of an edge get the exact nearest point of
 *    that edge (sub-cell accurate, so the DEM has no pixel staircase along the contours); then raster
 *    scans (Danielsson's vector propagation, "Euclidean distance mapping", CGIP 14, 1980, with 8
 *    neighbours) pass sites on: a neighbour in the same band gives both of its sites, one in the band
 *    below gives its upper site as a lower one, one in the band above its lower site as an upper one.
 *    Sites therefore travel through the two bands beside their contour only, as r.surf.contour's
 *    search stays between its two contours; forward and backward scans alternate until one changes
 *    nothing (after the first two, a scan visits only the rows beside a change), which reaches every
 *    cell connected to the contour, whatever the band's shape.
 * 3. Elevation. Between two contours z = z_lo + (z_hi - z_lo) d_lo / (d_lo + d_hi), d the Euclidean
 *    distances to the two sites (r.surf.contour's formula). A band region that no upper contour reaches
 *    is a summit: inside the top contour, or inside a contour with no contour above it (a secondary
 *    peak); there z = z_lo + rise (1 - (1 - t)^2), t = d_lo / max d_lo over the summit region (the
 *    connected cells of that band), rise = summit x the interval (the stack's, or this level's step
 *    for a secondary peak): a paraboloid-like cap whose slope at the contour is 2 rise / max d_lo (for
 *    summit = 0.5 and a top contour about one spacing wide: the slope of the bands below it) and flat at
 *    the top. A band region that no lower contour reaches is a pit (inside a hole of the level above,
 *    e.g. a crater) and mirrors it below z_hi. Outside the lowest contour, cells are nodata.
 *
 * Everything is deterministic: the scans run in a fixed order, the per-row parts (prefix sums,
 * elevations) in parallel over rows with no shared state.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/contour.h"
#include "internal.h"

#define DEFAULT_CELLS_ACROSS 512.0
#define MAX_SIDE 65536.0
#define MAX_CELLS 268435456.0 /* 2^28: about 8 GB of working memory */
#define SEED_REACH 1.5        /* cells within this distance of an edge get its exact nearest point */
#define NO_SITE 1e18f         /* squared distances to it (2e36) stay finite in float and lose every test */

typedef struct {
    size_t nx, ny;
    double x0, y0, cell; /* upper-left corner and cell size: cell (c, r) has its centre at u = c, v = r */
    int32_t *lev;        /* level index, -1 = outside the lowest contour */
    float *lo, *hi;      /* per cell (u, v) of the nearest point found on contour L and on contour L + 1 */
    ft_progress_fn progress;
    void *progress_arg;
} dem_work;

/* ---- checks ------------------------------------------------------------------------------------ */

static int check_ring(const ft_chain *c, size_t level, double elev, size_t p, const char *what, size_t h)
{
    char name[64];
    if (h == SIZE_MAX)
        snprintf(name, sizeof name, "%s ring", what);
    else
        snprintf(name, sizeof name, "%s %zu", what, h);
    if (c == NULL || c->n < 3)
        return ft_error(FT_E_INVALID, "contour stack: level %zu (elev %g), polygon %zu: %s has %zu vertices "
                                      "(a ring needs 3)",
                        level, elev, p, name, c ? c->n : 0);
    for (size_t i = 0; i < c->n; i++)
        if (!isfinite(c->x[i]) || !isfinite(c->y[i]))
            return ft_error(FT_E_NUMERIC, "contour stack: level %zu (elev %g), polygon %zu: vertex %zu of %s is not "
                                          "finite (%g, %g)",
                            level, elev, p, i, name, c->x[i], c->y[i]);
    return FT_OK;
}

static int check_stack(const ft_contour_stack *s)
{
    if (s == NULL || s->n == 0 || s->levels == NULL)
        return ft_error(FT_E_EMPTY, "contour stack: no level");
    for (size_t k = 0; k < s->n; k++) {
        const ft_contour_level *lv = &s->levels[k];
        if (!isfinite(lv->elev))
            return ft_error(FT_E_NUMERIC, "contour stack: level %zu has elevation %g", k, lv->elev);
        if (k > 0 && !(lv->elev > s->levels[k - 1].elev))
            return ft_error(FT_E_INVALID, "contour stack: elevations must increase, level %zu (elev %g) follows "
                                          "level %zu (elev %g)",
                            k, lv->elev, k - 1, s->levels[k - 1].elev);
        if (lv->polys == NULL)
            continue;
        for (size_t p = 0; p < lv->polys->n; p++) {
            const ft_polygon *pg = &lv->polys->polys[p];
            int rc = check_ring(pg->outer, k, lv->elev, p, "outer", SIZE_MAX);
            if (pg->nholes > 0 && pg->holes == NULL)
                rc = ft_error(FT_E_INVALID, "contour stack: level %zu, polygon %zu: %zu holes but no hole array",
                              k, p, pg->nholes);
            for (size_t h = 0; h < pg->nholes && rc == FT_OK; h++)
                rc = check_ring(pg->holes[h], k, lv->elev, p, "hole", h);
            if (rc != FT_OK)
                return rc;
        }
    }
    if (s->levels[0].polys == NULL || s->levels[0].polys->n == 0)
        return ft_error(FT_E_EMPTY, "contour stack: the lowest level (elev %g) has no polygon", s->levels[0].elev);
    return FT_OK;
}

static int check_opts(const ft_contour_dem_opts *o)
{
    if (!isfinite(o->cell) || o->cell < 0.0)
        return ft_error(FT_E_INVALID, "contour DEM: cell must be > 0 (0 = automatic), got %g", o->cell);
    if (!isfinite(o->margin) || o->margin < 0.0)
        return ft_error(FT_E_INVALID, "contour DEM: margin must be >= 0, got %g", o->margin);
    if (!isfinite(o->summit) || o->summit < 0.0)
        return ft_error(FT_E_INVALID, "contour DEM: summit must be >= 0 (a multiple of the interval), got %g",
                        o->summit);
    return FT_OK;
}

/* The elevation step the top summit rises by (summit x it): the stack's interval, else its mean step. */
static int top_interval(const ft_contour_stack *s, double summit, double *step)
{
    if (isfinite(s->interval) && s->interval > 0.0)
        *step = s->interval;
    else if (s->n >= 2)
        *step = (s->levels[s->n - 1].elev - s->levels[0].elev) / (double)(s->n - 1);
    else if (summit > 0.0)
        return ft_error(FT_E_INVALID, "contour DEM: the stack has one level and interval %g: the summit's rise "
                                      "(summit x interval) is undefined; give the stack an interval > 0 or summit 0",
                        s->interval);
    else
        *step = 0.0;
    return FT_OK;
}

/* ---- the grid ---------------------------------------------------------------------------------- */

static void level_bbox(const ft_polygon_set *ps, double *bb)
{
    bb[0] = bb[1] = INFINITY;
    bb[2] = bb[3] = -INFINITY;
    for (size_t p = 0; p < ps->n; p++) {
        const ft_chain *c = ps->polys[p].outer;
        for (size_t i = 0; i < c->n; i++) {
            bb[0] = fmin(bb[0], c->x[i]);
            bb[1] = fmin(bb[1], c->y[i]);
            bb[2] = fmax(bb[2], c->x[i]);
            bb[3] = fmax(bb[3], c->y[i]);
        }
    }
}

/* Cell size, origin and size covering the lowest level plus the margin. */
static int grid_frame(const ft_contour_stack *s, const ft_contour_dem_opts *o, dem_work *w)
{
    double bb[4];
    level_bbox(s->levels[0].polys, bb);
    double width = bb[2] - bb[0], height = bb[3] - bb[1], extent = fmax(width, height);
    if (!(extent > 0.0))
        return ft_error(FT_E_INVALID, "contour stack: the lowest level (elev %g) has no extent",
                        s->levels[0].elev);
    double cell = o->cell > 0.0 ? o->cell : extent / DEFAULT_CELLS_ACROSS;
    double margin = o->margin > 0.0 ? o->margin : cell;
    double nx = ceil((width + 2.0 * margin) / cell), ny = ceil((height + 2.0 * margin) / cell);
    if (!(nx <= MAX_SIDE && ny <= MAX_SIDE && nx * ny <= MAX_CELLS))
        return ft_error(FT_E_INVALID, "contour DEM: cell %g and margin %g over a %g x %g extent give %.0f x %.0f "
                                      "cells (at most %.0f a side and %.0f in all)",
                        cell, margin, width, height, nx, ny, MAX_SIDE, MAX_CELLS);
    w->nx = nx < 1.0 ? 1 : (size_t)nx;
    w->ny = ny < 1.0 ? 1 : (size_t)ny;
    w->cell = cell;
    /* centred on the lowest level's box */
    w->x0 = 0.5 * (bb[0] + bb[2]) - 0.5 * (double)w->nx * cell;
    w->y0 = 0.5 * (bb[1] + bb[3]) + 0.5 * (double)w->ny * cell;
    return FT_OK;
}

static inline double to_u(const dem_work *w, double x)
{
    return (x - w->x0) / w->cell - 0.5;
}

static inline double to_v(const dem_work *w, double y)
{
    return (w->y0 - y) / w->cell - 0.5;
}

/* ---- 1. level index ---------------------------------------------------------------------------- */

/* Adds weight (+1 inside an outer ring, -1 inside a hole) at the first cell centre right of every
 * crossing of the ring with a row of cell centres (half-open rule: no double count at vertices). */
static void add_ring_crossings(dem_work *w, const ft_chain *ring, int inside)
{
    int weight = ft_chain_signed_area(ring) > 0.0 ? inside : -inside;
    double vmax = (double)w->ny;
    for (size_t i = 0; i < ring->n; i++) {
        size_t j = i + 1 < ring->n ? i + 1 : 0;
        double ua = to_u(w, ring->x[i]), va = to_v(w, ring->y[i]);
        double ub = to_u(w, ring->x[j]), vb = to_v(w, ring->y[j]);
        if (va == vb)
            continue;
        /* rows r with lo <= r < hi; going down the rows (v up, y down) on a counter-clockwise ring is its
         * western side: the cells east of it are inside */
        int dir = vb > va ? weight : -weight;
        double lo = fmax(fmin(va, vb), -1.0), hi = fmin(fmax(va, vb), vmax + 1.0);
        long r0 = (long)ceil(lo), r1 = (long)ceil(hi) - 1;
        if (r0 < 0)
            r0 = 0;
        if (r1 > (long)w->ny - 1)
            r1 = (long)w->ny - 1;
        double slope = (ub - ua) / (vb - va);
        for (long r = r0; r <= r1; r++) {
            double u = ua + ((double)r - va) * slope;
            double c = floor(u) + 1.0;
            if (c < 0.0)
                c = 0.0;
            if (c < (double)w->nx)
                w->lev[(size_t)r * w->nx + (size_t)c] += dir;
        }
    }
}

static void level_index(dem_work *w, const ft_contour_stack *s)
{
    for (size_t k = 0; k < s->n; k++) {
        const ft_polygon_set *ps = s->levels[k].polys;
        for (size_t p = 0; ps != NULL && p < ps->n; p++) {
            add_ring_crossings(w, ps->polys[p].outer, 1);
            for (size_t h = 0; h < ps->polys[p].nholes; h++)
                add_ring_crossings(w, ps->polys[p].holes[h], -1);
        }
    }
    int32_t top = (int32_t)s->n - 1;
    long ny = (long)w->ny;
#pragma omp parallel for schedule(static)
    for (long r = 0; r < ny; r++) {
        int32_t *row = w->lev + (size_t)r * w->nx, sum = 0;
        for (size_t c = 0; c < w->nx; c++) {
            sum += row[c];
            row[c] = sum < 1 ? -1 : (sum - 1 > top ? top : sum - 1);
        }
    }
}

/* ---- 2. distances ------------------------------------------------------------------------------ */

static inline float dist2(const float *site, float u, float v)
{
    float du = site[0] - u, dv = site[1] - v;
    return du * du + dv * dv;
}

/* Offers the nearest point of segment a-b to the cells near it that lie in the band below (as their
 * upper site) or above (as their lower site) this edge's contour, level k. */
static void seed_edge(dem_work *w, double ua, double va, double ub, double vb, int32_t k)
{
    double du = ub - ua, dv = vb - va, len2 = du * du + dv * dv;
    long r0 = (long)floor(fmax(fmin(va, vb) - SEED_REACH, 0.0));
    long r1 = (long)ceil(fmin(fmax(va, vb) + SEED_REACH, (double)w->ny - 1.0));
    for (long r = r0; r <= r1; r++) {
        double t0 = 0.0, t1 = 1.0;
        if (dv != 0.0) {
            double ta = ((double)r - SEED_REACH - va) / dv, tb = ((double)r + SEED_REACH - va) / dv;
            t0 = fmax(0.0, fmin(ta, tb));
            t1 = fmin(1.0, fmax(ta, tb));
            if (t0 > t1)
                continue;
        } else if (fabs(va - (double)r) > SEED_REACH) {
            continue;
        }
        double umin = fmin(ua + t0 * du, ua + t1 * du) - SEED_REACH, umax = fmax(ua + t0 * du, ua + t1 * du) + SEED_REACH;
        long c0 = (long)ceil(fmax(umin, 0.0)), c1 = (long)floor(fmin(umax, (double)w->nx - 1.0));
        for (long c = c0; c <= c1; c++) {
            size_t i = (size_t)r * w->nx + (size_t)c;
            float *site = w->lev[i] == k ? w->lo + 2 * i : (w->lev[i] == k - 1 ? w->hi + 2 * i : NULL);
            if (site == NULL)
                continue;
            double t = len2 > 0.0 ? (((double)c - ua) * du + ((double)r - va) * dv) / len2 : 0.0;
            t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
            float q[2] = {(float)(ua + t * du), (float)(va + t * dv)};
            if (dist2(q, (float)c, (float)r) < dist2(site, (float)c, (float)r)) {
                site[0] = q[0];
                site[1] = q[1];
            }
        }
    }
}

static void seed_ring(dem_work *w, const ft_chain *ring, int32_t k)
{
    for (size_t i = 0; i < ring->n; i++) {
        size_t j = i + 1 < ring->n ? i + 1 : 0;
        seed_edge(w, to_u(w, ring->x[i]), to_v(w, ring->y[i]), to_u(w, ring->x[j]), to_v(w, ring->y[j]), k);
    }
}

static void seed_sites(dem_work *w, const ft_contour_stack *s)
{
    size_t n = w->nx * w->ny;
    for (size_t i = 0; i < 2 * n; i++)
        w->lo[i] = w->hi[i] = NO_SITE;
    for (size_t k = 0; k < s->n; k++) {
        const ft_polygon_set *ps = s->levels[k].polys;
        for (size_t p = 0; ps != NULL && p < ps->n; p++) {
            seed_ring(w, ps->polys[p].outer, (int32_t)k);
            for (size_t h = 0; h < ps->polys[p].nholes; h++)
                seed_ring(w, ps->polys[p].holes[h], (int32_t)k);
        }
    }
}

/* Offers the sites of neighbour j to cell i (see the header comment); 1 if a site of i changed. */
static inline int relax(dem_work *w, size_t i, size_t j, float u, float v, float *dlo, float *dhi)
{
    int32_t li = w->lev[i], lj = w->lev[j];
    int changed = 0;
    const float *to_lo = NULL, *to_hi = NULL;
    if (lj == li) {
        to_lo = w->lo + 2 * j;
        to_hi = w->hi + 2 * j;
    } else if (lj == li - 1) {
        to_lo = w->hi + 2 * j;
    } else if (lj == li + 1) {
        to_hi = w->lo + 2 * j;
    }
    if (to_lo != NULL) {
        float d = dist2(to_lo, u, v);
        if (d < *dlo) {
            *dlo = d;
            w->lo[2 * i] = to_lo[0];
            w->lo[2 * i + 1] = to_lo[1];
            changed = 1;
        }
    }
    if (to_hi != NULL) {
        float d = dist2(to_hi, u, v);
        if (d < *dhi) {
            *dhi = d;
            w->hi[2 * i] = to_hi[0];
            w->hi[2 * i + 1] = to_hi[1];
            changed = 1;
        }
    }
    return changed;
}

/* One forward (top-down) or backward (bottom-up) scan; returns whether any site changed. A row is visited
 * only when a site can change in it: in the first scans (all set), or when it or a neighbouring row
 * changed in the previous scan (prev), or the row visited just before it in this scan changed (cur). */
static int scan(dem_work *w, int forward, int all, const uint8_t *prev, uint8_t *cur)
{
    long nx = (long)w->nx, ny = (long)w->ny;
    long dr = forward ? -1 : 1;          /* the row already visited in this scan */
    long first = forward ? 0 : ny - 1, step = forward ? 1 : -1;
    int changed = 0;
    for (long r = first; r >= 0 && r < ny; r += step) {
        long before = r + dr;
        int has_prev = before >= 0 && before < ny;
        cur[r] = 0;
        if (!all && !prev[r] && !(r > 0 && prev[r - 1]) && !(r + 1 < ny && prev[r + 1]) && !(has_prev && cur[before]))
            continue;
        int row_changed = 0;
        /* along the row, away from the previous row's neighbours first, then back */
        for (int pass = 0; pass < 2; pass++) {
            long c0 = (pass == 0) == forward ? 0 : nx - 1, dc = (pass == 0) == forward ? 1 : -1;
            for (long c = c0; c >= 0 && c < nx; c += dc) {
                size_t i = (size_t)r * w->nx + (size_t)c;
                if (w->lev[i] < 0)
                    continue;
                float u = (float)c, v = (float)r;
                float dlo = dist2(w->lo + 2 * i, u, v), dhi = dist2(w->hi + 2 * i, u, v);
                long back = c - dc;
                if (back >= 0 && back < nx && w->lev[i - (size_t)c + (size_t)back] >= 0)
                    row_changed |= relax(w, i, (size_t)r * w->nx + (size_t)back, u, v, &dlo, &dhi);
                if (pass == 0 && has_prev) {
                    for (long k = c - 1; k <= c + 1; k++)
                        if (k >= 0 && k < nx && w->lev[(size_t)before * w->nx + (size_t)k] >= 0)
                            row_changed |= relax(w, i, (size_t)before * w->nx + (size_t)k, u, v, &dlo, &dhi);
                }
            }
        }
        cur[r] = (uint8_t)row_changed;
        changed |= row_changed;
    }
    return changed;
}

/* Forward and backward scans until a whole scan changes nothing. */
static int propagate(dem_work *w)
{
    uint8_t *a = ft_calloc(w->ny, 1), *b = ft_calloc(w->ny, 1);
    if (a == NULL || b == NULL) {
        free(a);
        free(b);
        return FT_E_NOMEM;
    }
    double frac = 0.3;
    int rc = FT_OK, first = 1;
    for (int forward = 1;; forward = !forward) {
        int changed = scan(w, forward, first, a, b);
        uint8_t *t = a; /* this scan's changes become the next scan's previous ones */
        a = b;
        b = t;
        if (!forward)
            first = 0;
        if ((rc = ft_progress(w->progress, w->progress_arg, frac, "contour DEM: distances")) != FT_OK)
            break;
        frac += 0.25 * (0.8 - frac);
        if (!changed && !first)
            break;
    }
    free(a);
    free(b);
    return rc;
}

/* ---- 3. elevations ----------------------------------------------------------------------------- */

enum { CELL_BAND = 0, CELL_SUMMIT = 1, CELL_PIT = 2, CELL_NONE = 3 };

static int cell_kind(const dem_work *w, size_t i, int32_t top)
{
    int has_lo = w->lo[2 * i] < 0.5f * NO_SITE, has_hi = w->hi[2 * i] < 0.5f * NO_SITE;
    if (w->lev[i] == top)
        return has_lo ? CELL_SUMMIT : CELL_NONE;
    if (has_lo && has_hi)
        return CELL_BAND;
    return has_lo ? CELL_SUMMIT : (has_hi ? CELL_PIT : CELL_NONE);
}

/* The summit and pit regions: connected (8 neighbours) cells of one band and one kind. Each gets
 * z = z_ref +- rise (1 - (1 - t)^2), t = d / max d over the region (d: distance to its one contour). */
static int shape_regions(const dem_work *w, const ft_contour_stack *s, double top_step, double summit, float *z)
{
    size_t n = w->nx * w->ny, nshaped = 0;
    int32_t top = (int32_t)s->n - 1;
    for (size_t i = 0; i < n; i++) {
        int kind = w->lev[i] >= 0 ? cell_kind(w, i, top) : CELL_NONE;
        nshaped += kind == CELL_SUMMIT || kind == CELL_PIT;
    }
    if (nshaped == 0)
        return FT_OK;
    uint8_t *seen = ft_calloc(n, 1);
    size_t *queue = ft_malloc(nshaped * sizeof *queue);
    if (seen == NULL || queue == NULL) {
        free(seen);
        free(queue);
        return FT_E_NOMEM;
    }
    for (size_t seed = 0; seed < n; seed++) {
        if (w->lev[seed] < 0 || seen[seed] != 0)
            continue;
        int kind = cell_kind(w, seed, top);
        if (kind != CELL_SUMMIT && kind != CELL_PIT)
            continue;
        /* flood the region, its cells in queue[0 .. len) */
        size_t len = 0, head = 0;
        int32_t k = w->lev[seed];
        queue[len++] = seed;
        seen[seed] = 1;
        double dmax = 0.0;
        while (head < len) {
            size_t i = queue[head++];
            const float *site = kind == CELL_SUMMIT ? w->lo + 2 * i : w->hi + 2 * i;
            dmax = fmax(dmax, sqrt((double)dist2(site, (float)(i % w->nx), (float)(i / w->nx))));
            long r = (long)(i / w->nx), c = (long)(i % w->nx);
            for (long rr = r - 1; rr <= r + 1; rr++)
                for (long cc = c - 1; cc <= c + 1; cc++) {
                    if (rr < 0 || cc < 0 || rr >= (long)w->ny || cc >= (long)w->nx)
                        continue;
                    size_t j = (size_t)rr * w->nx + (size_t)cc;
                    if (seen[j] == 0 && w->lev[j] == k && cell_kind(w, j, top) == kind) {
                        seen[j] = 1;
                        queue[len++] = j;
                    }
                }
        }
        double zk = s->levels[k].elev, step = k == top ? top_step : s->levels[k + 1].elev - zk;
        double rise = summit * step;
        for (size_t q = 0; q < len; q++) {
            size_t i = queue[q];
            const float *site = kind == CELL_SUMMIT ? w->lo + 2 * i : w->hi + 2 * i;
            double d = sqrt((double)dist2(site, (float)(i % w->nx), (float)(i / w->nx)));
            double t = dmax > 0.0 ? d / dmax : 0.0, shape = 1.0 - (1.0 - t) * (1.0 - t);
            z[i] = (float)(kind == CELL_SUMMIT ? zk + rise * shape : zk + step - rise * shape);
        }
    }
    free(seen);
    free(queue);
    return FT_OK;
}

/* Cells between two contours, and nodata outside the lowest one. */
static void band_elevations(const dem_work *w, const ft_contour_stack *s, ft_grid *g)
{
    int32_t top = (int32_t)s->n - 1;
    long ny = (long)w->ny;
#pragma omp parallel for schedule(static)
    for (long r = 0; r < ny; r++) {
        for (size_t c = 0; c < w->nx; c++) {
            size_t i = (size_t)r * w->nx + c;
            int32_t k = w->lev[i];
            g->mask[i] = k >= 0;
            g->z[i] = 0.0f;
            if (k < 0)
                continue;
            int kind = cell_kind(w, i, top);
            double zlo = s->levels[k].elev;
            if (kind == CELL_NONE) {
                g->z[i] = (float)zlo;
            } else if (kind == CELL_BAND) {
                double dlo = sqrt((double)dist2(w->lo + 2 * i, (float)c, (float)r));
                double dhi = sqrt((double)dist2(w->hi + 2 * i, (float)c, (float)r));
                double zhi = s->levels[k + 1].elev;
                g->z[i] = (float)(dlo + dhi > 0.0 ? zlo + (zhi - zlo) * dlo / (dlo + dhi) : zlo);
            }
        }
    }
}

/* ---- the function ------------------------------------------------------------------------------ */

static int build(dem_work *w, const ft_contour_stack *s, const ft_contour_dem_opts *o, double top_step, ft_grid *g)
{
    int rc = ft_progress(w->progress, w->progress_arg, 0.0, "contour DEM: levels");
    if (rc != FT_OK)
        return rc;
    level_index(w, s);
    if ((rc = ft_progress(w->progress, w->progress_arg, 0.15, "contour DEM: seeds")) != FT_OK)
        return rc;
    seed_sites(w, s);
    if ((rc = propagate(w)) != FT_OK)
        return rc;
    if ((rc = ft_progress(w->progress, w->progress_arg, 0.85, "contour DEM: elevations")) != FT_OK)
        return rc;
    band_elevations(w, s, g);
    if ((rc = shape_regions(w, s, top_step, o->summit, g->z)) != FT_OK)
        return rc;
    return ft_progress(w->progress, w->progress_arg, 1.0, "contour DEM: done");
}

int ft_contour_stack_to_dem(const ft_contour_stack *s, const ft_contour_dem_opts *opts, const char *crs_wkt,
                            ft_grid **out)
{
    ft_contour_dem_opts taken = FT_CONTOUR_DEM_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_contour_dem_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    if (out == NULL)
        return ft_error(FT_E_INVALID, "contour DEM: no output pointer given");
    *out = NULL;
    ft_contour_dem_opts defaults = FT_CONTOUR_DEM_OPTS_DEFAULT;
    const ft_contour_dem_opts *o = opts ? opts : &defaults;
    double top_step = 0.0;
    int rc = check_opts(o);
    if (rc == FT_OK)
        rc = check_stack(s);
    if (rc == FT_OK)
        rc = top_interval(s, o->summit, &top_step);
    if (rc == FT_OK && s->n > (size_t)INT32_MAX - 1)
        rc = ft_error(FT_E_INVALID, "contour stack: %zu levels (at most %d)", s->n, INT32_MAX - 1);
    dem_work w = {.progress = o->progress, .progress_arg = o->progress_arg};
    if (rc == FT_OK)
        rc = grid_frame(s, o, &w);
    if (rc != FT_OK)
        return rc;
    size_t n = w.nx * w.ny;
    ft_grid *g = ft_grid_create(w.nx, w.ny);
    w.lev = ft_calloc(n, sizeof *w.lev);
    w.lo = ft_malloc(2 * n * sizeof *w.lo);
    w.hi = ft_malloc(2 * n * sizeof *w.hi);
    rc = g && w.lev && w.lo && w.hi ? ft_grid_ensure_mask(g) : FT_E_NOMEM;
    if (rc == FT_OK && crs_wkt != NULL)
        rc = ft_grid_set_crs(g, crs_wkt);
    if (rc == FT_OK) {
        const double gt[6] = {w.x0, w.cell, 0.0, w.y0, 0.0, -w.cell};
        memcpy(g->gt, gt, sizeof gt);
        rc = build(&w, s, o, top_step, g);
    }
    free(w.lev);
    free(w.lo);
    free(w.hi);
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    *out = g;
    return FT_OK;
}
