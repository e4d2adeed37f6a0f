/* fracterra — fill.c: ft_terrain_fill, the voids of a DEM filled one by one by conditional simulation
 * with the roughness of their surroundings (docs/terrain-fill.md).
 *
 * A void is a maximal 8-connected set of invalid cells. Voids whose bounding box is longer than
 * max_void cells stay nodata (a coast, the outside of a survey). For each other void:
 *  1. its model v(r) = v1 r^(2H) is fitted on the valid cells within `ring` cells (Chebyshev distance)
 *     of it (fill_variogram.c); with too few pairs, on every valid cell of the DEM;
 *  2. the valid cells within 2 cells of it are the conditioning data of the intrinsic kriging
 *     (fill_kriging.c): the mean z*;
 *  3. a realization is z* + s - s*, s an exact fBm of the model on the void's box (Stein 2002,
 *     ft_terrain_synth) and s* its kriging from the same cells (conditioning by kriging, Journel &
 *     Huijbregts 1978, ch. VII): it honours every datum, and has the model's variogram inside the void
 *     and across its border.
 * The realization r of the void whose first cell (raster order) is the raster's cell i = row * nx + col uses
 * the seed ft_rng_mix(ft_rng_mix(seed, i), r): a void gets the same cells whatever window holds it.
 *
 * ft_terrain_fill_rows fills a window of whole rows (a stripe and its halo, docs/tiling.md): every void that
 * meets the stripe's rows and lies whole in the window, with its ring, is filled as the whole-raster run
 * fills it; the voids whose first cell is in the stripe are reported, so that the stripes' reports, in row
 * order, are the whole run's.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "internal.h"
#include "terrain/fill/fill_internal.h"

/* Width (cells) of the conditioning ring, and the most conditioning cells a void's kriging takes: above
 * it the outer ring is thinned to every other cell, then every cell is strided (a 256 x 256 void has
 * about 2,060 cells within 2). */
#define COND_WIDTH 2
#define COND_MAX 2600
#define RING_MIN 10
#define RING_MAX 64
/* Boxes longer than this synthesize s spectrally (Stein's torus would not fit) and normalize its
 * one-cell increments. */
#define EXACT_MAX 1536

typedef struct {
    const ft_grid *dem;
    const uint8_t *isvoid;
    const uint32_t *label;
    size_t nx, ny;      /* the window */
    size_t row0, gny;   /* the window's first row in the raster, the raster's rows */
    size_t own0, own1;  /* the stripe: raster rows [own0, own1) */
    uint64_t *key;      /* per void: the raster index of its first cell */
} fill_ctx;

/* 1 if the window is a part of the raster (a stripe's run). */
static int windowed(const fill_ctx *c)
{
    return c->row0 > 0 || c->ny < c->gny;
}

const char *ft_fill_d_source_name(ft_fill_d_source s)
{
    switch (s) {
    case FT_FILL_D_RING: return "ring";
    case FT_FILL_D_DEM: return "dem";
    case FT_FILL_D_GIVEN: return "given";
    case FT_FILL_D_FLAT: return "flat";
    }
    return "unknown";
}

void ft_fill_result_free(ft_fill_result *r)
{
    if (r == NULL)
        return;
    free(r->voids);
    free(r);
}

static int check_opts(const ft_fill_opts *o)
{
    if (!(o->max_void >= 0.0) || !isfinite(o->max_void))
        return ft_error(FT_E_INVALID, "fill: max_void must be >= 0 cells (0 = no limit), got %g", o->max_void);
    if (o->realizations < 1)
        return ft_error(FT_E_INVALID, "fill: realizations must be >= 1, got %d", o->realizations);
    if (o->mean && o->realizations > 1)
        return ft_error(FT_E_INVALID, "fill: mean and realizations %d exclude each other (the mean is the "
                        "kriging itself)", o->realizations);
    if (!(o->dim == 0.0 || (o->dim > 2.0 && o->dim < 3.0)))
        return ft_error(FT_E_INVALID, "fill: dim must be in (2, 3) or 0 (fitted), got %g", o->dim);
    if (o->ring != 0 && o->ring < 2)
        return ft_error(FT_E_INVALID, "fill: ring must be >= 2 cells or 0 (automatic), got %d", o->ring);
    return FT_OK;
}

/* 8-connected components of isvoid: label[i] = void + 1; the voids' boxes, sizes and edge flags. */
static int label_voids(fill_ctx *c, uint32_t *label, ft_fill_void **voids, size_t *nvoids)
{
    size_t nx = c->nx, ny = c->ny, n = nx * ny, cap = 16, nv = 0;
    size_t *stack = ft_malloc(n * sizeof *stack);
    ft_fill_void *v = ft_malloc(cap * sizeof *v);
    c->key = ft_malloc(cap * sizeof *c->key);
    if (stack == NULL || v == NULL || c->key == NULL) {
        free(stack);
        free(v);
        return FT_E_NOMEM;
    }
    for (size_t s = 0; s < n; s++) {
        if (!c->isvoid[s] || label[s])
            continue;
        if (nv == cap) {
            ft_fill_void *v2 = ft_realloc_array(v, cap * 2, sizeof *v);
            uint64_t *k2 = v2 ? ft_realloc_array(c->key, cap * 2, sizeof *k2) : NULL;
            if (v2 == NULL || k2 == NULL) {
                free(stack);
                free(v2 ? v2 : v);
                return FT_E_NOMEM;
            }
            v = v2;
            c->key = k2;
            cap *= 2;
        }
        c->key[nv] = (uint64_t)(c->row0 + s / nx) * nx + s % nx;
        ft_fill_void *k = &v[nv++];
        memset(k, 0, sizeof *k);
        k->x0 = k->x1 = s % nx;
        k->y0 = k->y1 = s / nx;
        k->D = k->amplitude = k->r2 = NAN;
        size_t top = 0;
        stack[top++] = s;
        label[s] = (uint32_t)nv;
        while (top > 0) {
            size_t i = stack[--top], x = i % nx, y = i / nx;
            k->cells++;
            k->x0 = x < k->x0 ? x : k->x0;
            k->x1 = x > k->x1 ? x : k->x1;
            k->y0 = y < k->y0 ? y : k->y0;
            k->y1 = y > k->y1 ? y : k->y1;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    long a = (long)x + dx, b = (long)y + dy;
                    if (a < 0 || b < 0 || a >= (long)nx || b >= (long)ny)
                        continue;
                    size_t j = (size_t)b * nx + (size_t)a;
                    if (c->isvoid[j] && !label[j]) {
                        label[j] = (uint32_t)nv;
                        stack[top++] = j;
                    }
                }
        }
        k->edge = k->x0 == 0 || c->row0 + k->y0 == 0 || k->x1 == nx - 1 || c->row0 + k->y1 == c->gny - 1;
    }
    free(stack);
    *voids = v;
    *nvoids = nv;
    return FT_OK;
}

/* dst = src dilated by a (2w+1) square (Chebyshev distance <= w), on a bw x bh box; tmp bw*bh bytes.
 * Two passes per axis with the distance to the last set cell. */
static void dilate(const uint8_t *src, uint8_t *dst, uint8_t *tmp, size_t bw, size_t bh, size_t w)
{
    for (size_t y = 0; y < bh; y++) {
        const uint8_t *s = src + y * bw;
        uint8_t *t = tmp + y * bw;
        size_t last = (size_t)-1;
        for (size_t x = 0; x < bw; x++) {
            if (s[x])
                last = x;
            t[x] = last != (size_t)-1 && x - last <= w;
        }
        last = (size_t)-1;
        for (size_t x = bw; x-- > 0;) {
            if (s[x])
                last = x;
            if (last != (size_t)-1 && last - x <= w)
                t[x] = 1;
        }
    }
    for (size_t x = 0; x < bw; x++) {
        size_t last = (size_t)-1;
        for (size_t y = 0; y < bh; y++) {
            if (tmp[y * bw + x])
                last = y;
            dst[y * bw + x] = last != (size_t)-1 && y - last <= w;
        }
        last = (size_t)-1;
        for (size_t y = bh; y-- > 0;) {
            if (tmp[y * bw + x])
                last = y;
            if (last != (size_t)-1 && last - y <= w)
                dst[y * bw + x] = 1;
        }
    }
}

/* The box [x0, x1] x [y0, y1] of void v grown by w cells, clipped to the raster, in window cells;
 * FT_E_UNSUPPORTED when it leaves the window. */
static int grow_box(const fill_ctx *c, const ft_fill_void *v, size_t w, size_t b[4])
{
    size_t gy0 = c->row0 + v->y0, gy1 = c->row0 + v->y1;
    size_t lo = gy0 > w ? gy0 - w : 0, hi = gy1 + w < c->gny ? gy1 + w : c->gny - 1;
    if (lo < c->row0 || hi >= c->row0 + c->ny)
        return ft_error(FT_E_UNSUPPORTED, "fill: the void at cells (%zu..%zu, %zu..%zu) needs rows %zu-%zu, "
                        "beyond the window's rows %zu-%zu", v->x0, v->x1, gy0, gy1, lo, hi, c->row0,
                        c->row0 + c->ny - 1);
    b[0] = v->x0 > w ? v->x0 - w : 0;
    b[1] = lo - c->row0;
    b[2] = v->x1 + w < c->nx ? v->x1 + w : c->nx - 1;
    b[3] = hi - c->row0;
    return FT_OK;
}

/* Cells of the box b: z (valid cells; 0 on voids), mine (cells of void k), ring (valid cells within w of
 * void k). bw * bh arrays. */
static int box_arrays(const fill_ctx *c, size_t k, const size_t b[4], size_t w, float *z, uint8_t *mine,
                      uint8_t *ring)
{
    size_t bw = b[2] - b[0] + 1, bh = b[3] - b[1] + 1;
    uint8_t *tmp = ft_malloc(bw * bh);
    if (tmp == NULL)
        return FT_E_NOMEM;
    for (size_t y = 0; y < bh; y++)
        for (size_t x = 0; x < bw; x++) {
            size_t i = (b[1] + y) * c->nx + b[0] + x, j = y * bw + x;
            mine[j] = c->label[i] == (uint32_t)(k + 1);
            z[j] = c->isvoid[i] ? 0.0f : c->dem->z[i];
        }
    dilate(mine, ring, tmp, bw, bh, w);
    for (size_t y = 0; y < bh; y++)
        for (size_t x = 0; x < bw; x++) {
            size_t i = (b[1] + y) * c->nx + b[0] + x, j = y * bw + x;
            ring[j] = ring[j] && !c->isvoid[i];
        }
    free(tmp);
    return FT_OK;
}

/* The model of void k (fields D, amplitude, r2, clamped, source, ring_cells of v). *global caches the
 * DEM-wide fit (status in *gstat, 1 = not yet fitted). */
static int void_model(const fill_ctx *c, size_t k, ft_fill_void *v, const ft_fill_opts *o, ft_fill_model *m,
                      ft_fill_model *global, int *gstat)
{
    size_t longer = v->x1 - v->x0 > v->y1 - v->y0 ? v->x1 - v->x0 + 1 : v->y1 - v->y0 + 1;
    size_t w = o->ring > 0 ? (size_t)o->ring : (longer + 1) / 2;
    if (o->ring == 0)
        w = w < RING_MIN ? RING_MIN : w > RING_MAX ? RING_MAX : w;
    size_t b[4];
    if (grow_box(c, v, w, b) != FT_OK)
        return FT_E_UNSUPPORTED;
    size_t bw = b[2] - b[0] + 1, bh = b[3] - b[1] + 1;
    float *z = ft_malloc(bw * bh * sizeof *z);
    uint8_t *mine = ft_malloc(bw * bh), *ring = ft_malloc(bw * bh);
    int rc = z && mine && ring ? box_arrays(c, k, b, w, z, mine, ring) : FT_E_NOMEM;
    double Hf = o->dim > 0.0 ? 3.0 - o->dim : 0.0;
    if (rc == FT_OK) {
        for (size_t i = 0; i < bw * bh; i++)
            v->ring_cells += ring[i];
        rc = ft_fill_fit_model(z, ring, bw, bh, Hf, m);
        v->source = o->dim > 0.0 ? FT_FILL_D_GIVEN : FT_FILL_D_RING;
    }
    free(z);
    free(mine);
    free(ring);
    if (rc == FT_E_EMPTY && windowed(c))
        return ft_error(FT_E_UNSUPPORTED, "fill: the void at cells (%zu..%zu, %zu..%zu) has too few valid cells "
                        "around it to fit a variogram (lags 1-%d, >= %d pairs each), and a stripe cannot fit the "
                        "whole DEM's instead: fill it whole, or with a wider --ring", v->x0, v->x1,
                        c->row0 + v->y0, c->row0 + v->y1, FT_FILL_LAG_MAX, FT_FILL_MIN_PAIRS);
    if (rc == FT_E_EMPTY) {
        if (*gstat == 1) {
            const ft_grid *g = c->dem;
            uint8_t *use = ft_malloc(c->nx * c->ny);
            if (use == NULL)
                return FT_E_NOMEM;
            for (size_t i = 0; i < c->nx * c->ny; i++)
                use[i] = !c->isvoid[i];
            *gstat = ft_fill_fit_model(g->z, use, c->nx, c->ny, Hf, global);
            free(use);
        }
        rc = *gstat;
        *m = *global;
        if (o->dim == 0.0)
            v->source = FT_FILL_D_DEM;
        if (rc == FT_E_EMPTY)
            return ft_error(FT_E_EMPTY, "fill: the void at cells (%zu..%zu, %zu..%zu) has too few valid cells "
                            "around it, and the DEM too few, to fit a variogram (lags 1-%d, >= %d pairs each)",
                            v->x0, v->x1, c->row0 + v->y0, c->row0 + v->y1, FT_FILL_LAG_MAX, FT_FILL_MIN_PAIRS);
    }
    if (rc == FT_E_NUMERIC) {
        v->source = FT_FILL_D_FLAT;
        m->H = 0.5; /* the kriging weights only; no noise is added */
        m->v1 = 0.0;
        m->r2 = NAN;
        return FT_OK;
    }
    if (rc != FT_OK)
        return rc;
    v->D = 3.0 - m->H;
    v->amplitude = sqrt(m->v1);
    v->r2 = m->r2;
    v->clamped = m->clamped;
    return FT_OK;
}

/* role (box of void k grown by COND_WIDTH): 1 void cells, 2 conditioning cells. */
static int void_roles(const fill_ctx *c, size_t k, const size_t b[4], float *z, uint8_t *role, size_t *ncond)
{
    size_t bw = b[2] - b[0] + 1, bh = b[3] - b[1] + 1, n = bw * bh;
    uint8_t *mine = ft_malloc(n), *near = ft_malloc(n), *near1 = ft_malloc(n), *tmp = ft_malloc(n);
    int rc = mine && near && near1 && tmp ? box_arrays(c, k, b, COND_WIDTH, z, mine, near) : FT_E_NOMEM;
    if (rc == FT_OK) {
        dilate(mine, near1, tmp, bw, bh, 1);
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            role[i] = mine[i] ? 1 : near[i] ? 2 : 0;
            m += role[i] == 2;
        }
        if (m > COND_MAX) { /* thin the outer ring to a checkerboard */
            m = 0;
            for (size_t i = 0; i < n; i++) {
                if (role[i] == 2 && !near1[i] && ((i % bw) + (i / bw)) % 2 == 1)
                    role[i] = 0;
                m += role[i] == 2;
            }
        }
        if (m > COND_MAX) { /* then every stride-th cell */
            size_t stride = (m + COND_MAX - 1) / COND_MAX, seen = 0;
            m = 0;
            for (size_t i = 0; i < n; i++)
                if (role[i] == 2) {
                    if (seen++ % stride != 0)
                        role[i] = 0;
                    m += role[i] == 2;
                }
        }
        *ncond = m;
    }
    free(mine);
    free(near);
    free(near1);
    free(tmp);
    return rc;
}

/* s = an unconditional fBm of the model on the box (bw x bh), E(s(x) - s(y))² = v1 r^(2H). */
static int void_fbm(size_t bw, size_t bh, const ft_fill_model *m, uint64_t seed, float *s)
{
    ft_synth_opts so = FT_SYNTH_OPTS_DEFAULT;
    int exact = bw <= EXACT_MAX && bh <= EXACT_MAX;
    so.method = exact ? FT_SYNTH_EXACT : FT_SYNTH_FFT;
    so.dim = 3.0 - m->H;
    so.sigma = 0.0;
    so.seed = seed;
    ft_grid *g = NULL;
    int rc = ft_terrain_synth(bw > 1 ? bw : 2, bh > 1 ? bh : 2, &so, &g);
    if (rc != FT_OK)
        return rc;
    double scale = sqrt(m->v1);
    if (!exact) { /* the spectral surface's raw scale: make its one-cell mean square 1 */
        double ss = 0.0, nn = 0.0;
        for (size_t y = 0; y < bh; y++)
            for (size_t x = 0; x + 1 < bw; x++) {
                double d = (double)g->z[y * g->nx + x + 1] - g->z[y * g->nx + x];
                ss += d * d;
                nn += 1.0;
            }
        scale = nn > 0.0 && ss > 0.0 ? scale / sqrt(ss / nn) : 0.0;
    }
    for (size_t y = 0; y < bh; y++)
        for (size_t x = 0; x < bw; x++)
            s[y * bw + x] = (float)(scale * g->z[y * g->nx + x]);
    ft_grid_free(g);
    return FT_OK;
}

/* Fills void k into out (and sd). */
static int fill_void(const fill_ctx *c, size_t k, ft_fill_void *v, const ft_fill_model *m, const ft_fill_opts *o,
                     ft_grid *out, ft_grid *sd)
{
    size_t b[4];
    if (grow_box(c, v, COND_WIDTH, b) != FT_OK)
        return FT_E_UNSUPPORTED;
    size_t bw = b[2] - b[0] + 1, bh = b[3] - b[1] + 1, n = bw * bh;
    float *z = ft_malloc(n * sizeof *z), *mean = ft_malloc(n * sizeof *mean);
    uint8_t *role = ft_malloc(n);
    float *s = NULL, *ks = NULL;
    double *acc = NULL, *acc2 = NULL;
    ft_fill_krige *kr = NULL;
    int rc = z && mean && role ? void_roles(c, k, b, z, role, &v->conditioning) : FT_E_NOMEM;
    if (rc == FT_OK)
        rc = ft_fill_krige_create(role, bw, bh, m->H, &kr);
    if (rc == FT_OK)
        rc = ft_fill_krige_predict(kr, z, mean);
    int R = o->mean || m->v1 == 0.0 ? 0 : o->realizations;
    if (rc == FT_OK && R > 0) {
        s = ft_malloc(n * sizeof *s);
        ks = ft_malloc(n * sizeof *ks);
        acc = ft_calloc(n, sizeof *acc);
        acc2 = ft_calloc(n, sizeof *acc2);
        if (!s || !ks || !acc || !acc2)
            rc = FT_E_NOMEM;
    }
    uint64_t vseed = ft_rng_mix(o->seed, c->key[k]);
    for (int r = 0; r < R && rc == FT_OK; r++) {
        rc = void_fbm(bw, bh, m, ft_rng_mix(vseed, (uint64_t)r), s);
        if (rc == FT_OK)
            rc = ft_fill_krige_predict(kr, s, ks);
        if (rc != FT_OK)
            break;
        for (size_t i = 0; i < n; i++)
            if (role[i] == 1) { /* Welford */
                double u = (double)mean[i] + (double)s[i] - (double)ks[i], d = u - acc[i];
                acc[i] += d / (r + 1);
                acc2[i] += d * (u - acc[i]);
            }
    }
    if (rc == FT_OK)
        for (size_t y = 0; y < bh; y++)
            for (size_t x = 0; x < bw; x++) {
                size_t j = y * bw + x, i = (b[1] + y) * c->nx + b[0] + x;
                if (role[j] != 1)
                    continue;
                out->z[i] = (float)(R > 0 ? acc[j] : mean[j]);
                out->mask[i] = 1;
                if (sd)
                    sd->z[i] = R > 1 ? (float)sqrt(acc2[j] / (R - 1)) : 0.0f;
            }
    ft_fill_krige_free(kr);
    free(z);
    free(mean);
    free(role);
    free(s);
    free(ks);
    free(acc);
    free(acc2);
    return rc;
}

static size_t longer_side(const ft_fill_void *v)
{
    return v->x1 - v->x0 > v->y1 - v->y0 ? v->x1 - v->x0 + 1 : v->y1 - v->y0 + 1;
}

/* 1 if void k is the stripe's to report (its first cell is in the stripe's rows). */
static int owned(const fill_ctx *c, size_t k)
{
    size_t row = (size_t)(c->key[k] / c->nx);
    return row >= c->own0 && row < c->own1;
}

/* 1 if void v has a cell in the stripe's rows. */
static int meets(const fill_ctx *c, const ft_fill_void *v)
{
    return c->row0 + v->y0 < c->own1 && c->row0 + v->y1 >= c->own0;
}

/* 1 if void v touches a window edge row that is not the raster's: it may go on beyond the window. */
static int cut(const fill_ctx *c, const ft_fill_void *v)
{
    return (v->y0 == 0 && c->row0 > 0) || (v->y1 == c->ny - 1 && c->row0 + c->ny < c->gny);
}

static int fill_all(fill_ctx *c, const ft_fill_opts *o, ft_fill_void *voids, size_t nv, ft_grid *out,
                    ft_grid *sd, ft_fill_result *res)
{
    ft_fill_model global;
    int gstat = 1;
    size_t total = 0, done = 0;
    for (size_t k = 0; k < nv; k++) {
        ft_fill_void *v = &voids[k];
        v->filled = o->max_void == 0.0 || (double)longer_side(v) <= o->max_void;
        /* a void cut by the window: only one already longer than max_void, and not the stripe's to report,
         * is known well enough (left nodata) */
        if (meets(c, v) && cut(c, v) && (v->filled || owned(c, k)))
            return ft_error(FT_E_UNSUPPORTED, "fill: the void at cells (%zu..%zu, %zu..) goes on beyond the "
                            "window's rows %zu-%zu", v->x0, v->x1, c->row0 + v->y0, c->row0,
                            c->row0 + c->ny - 1);
        total += v->filled && meets(c, v) ? v->cells : 0;
    }
    for (size_t k = 0; k < nv; k++) {
        ft_fill_void *v = &voids[k];
        if (!meets(c, v))
            continue;
        if (!v->filled) {
            res->cells_left += owned(c, k) ? v->cells : 0;
            continue;
        }
        ft_fill_model m;
        int rc = void_model(c, k, v, o, &m, &global, &gstat);
        if (rc == FT_OK)
            rc = fill_void(c, k, v, &m, o, out, sd);
        if (rc != FT_OK)
            return rc;
        if (owned(c, k)) {
            res->voids_filled++;
            res->cells_filled += v->cells;
        }
        done += v->cells;
        rc = ft_progress(o->progress, o->progress_arg, (double)done / (double)(total ? total : 1), "fill");
        if (rc != FT_OK)
            return rc;
    }
    return FT_OK;
}

/* The result keeps the stripe's voids, their rows in the raster's. */
static void keep_owned(const fill_ctx *c, ft_fill_result *r)
{
    size_t n = 0;
    for (size_t k = 0; k < r->nvoids; k++)
        if (owned(c, k)) {
            r->voids[n] = r->voids[k];
            r->voids[n].y0 += c->row0;
            r->voids[n].y1 += c->row0;
            n++;
        }
    r->nvoids = n;
}

static int fill_window(const ft_grid *dem, const uint8_t *invalid, const size_t rows[4], const ft_fill_opts *opts,
                       ft_grid **out, ft_grid **sd_out, ft_fill_result **res)
{
    ft_fill_opts o = FT_FILL_OPTS_DEFAULT;
    if (FT_OPTS_TAKE(o, opts, ft_fill_opts) != FT_OK)
        return FT_E_INVALID;
    if (out == NULL)
        return ft_error(FT_E_INVALID, "fill: out is NULL");
    *out = NULL;
    if (sd_out)
        *sd_out = NULL;
    if (res)
        *res = NULL;
    int rc = check_opts(&o);
    if (rc != FT_OK)
        return rc;
    if (dem == NULL || dem->z == NULL || dem->nx == 0 || dem->ny == 0)
        return ft_error(FT_E_INVALID, "fill: the DEM is NULL or empty");
    size_t nx = dem->nx, ny = dem->ny, n = nx * ny, nvoid = 0;
    uint8_t *isvoid = ft_malloc(n);
    uint32_t *label = ft_calloc(n, sizeof *label);
    ft_fill_result *r = ft_calloc(1, sizeof *r);
    ft_grid *g = ft_grid_copy(dem), *sd = NULL;
    fill_ctx c = {dem, isvoid, label, nx, ny, rows[0], rows[1], rows[2], rows[3], NULL};
    if (isvoid == NULL || label == NULL || r == NULL || g == NULL) {
        rc = FT_E_NOMEM;
        goto done;
    }
    for (size_t i = 0; i < n; i++) {
        isvoid[i] = (dem->mask && !dem->mask[i]) || !isfinite(dem->z[i]) || (invalid && !invalid[i]);
        nvoid += isvoid[i];
    }
    if (nvoid == n && rows[0] == 0 && ny == rows[1]) { /* a stripe may lie in a void */
        rc = ft_error(FT_E_EMPTY, "fill: the DEM (%zu x %zu) has no valid cell", nx, ny);
        goto done;
    }
    if ((rc = ft_grid_ensure_mask(g)) != FT_OK)
        goto done;
    for (size_t i = 0; i < n; i++)
        if (isvoid[i]) {
            g->mask[i] = 0;
            g->z[i] = 0.0f;
        }
    if (sd_out) {
        if ((sd = ft_grid_create(nx, ny)) == NULL) {
            rc = FT_E_NOMEM;
            goto done;
        }
        memcpy(sd->gt, dem->gt, sizeof sd->gt);
        if ((rc = ft_grid_set_crs(sd, dem->crs_wkt)) != FT_OK || (rc = ft_grid_ensure_mask(sd)) != FT_OK)
            goto done;
        memcpy(sd->mask, g->mask, n);
    }
    rc = label_voids(&c, label, &r->voids, &r->nvoids);
    if (rc == FT_OK)
        rc = fill_all(&c, &o, r->voids, r->nvoids, g, sd, r);
    if (rc == FT_OK)
        keep_owned(&c, r);
    if (rc == FT_OK && sd) {
        /* the sd grid's mask follows the output's */
        memcpy(sd->mask, g->mask, n);
    }
done:
    free(isvoid);
    free(label);
    free(c.key);
    if (rc != FT_OK) {
        ft_grid_free(g);
        ft_grid_free(sd);
        ft_fill_result_free(r);
        return rc;
    }
    *out = g;
    if (sd_out)
        *sd_out = sd;
    if (res)
        *res = r;
    else
        ft_fill_result_free(r);
    return FT_OK;
}

int ft_terrain_fill(const ft_grid *dem, const uint8_t *invalid, const ft_fill_opts *opts, ft_grid **out,
                    ft_grid **sd_out, ft_fill_result **res)
{
    size_t ny = dem != NULL ? dem->ny : 0, rows[4] = {0, ny, 0, ny};
    return fill_window(dem, invalid, rows, opts, out, sd_out, res);
}

int ft_terrain_fill_rows(const ft_grid *win, const uint8_t *invalid, size_t row0, size_t ny, size_t own0,
                         size_t own1, const ft_fill_opts *opts, ft_grid **out, ft_grid **sd_out,
                         ft_fill_result **res)
{
    if (out != NULL)
        *out = NULL;
    if (win != NULL && !(row0 + win->ny <= ny && row0 <= own0 && own0 < own1 && own1 <= row0 + win->ny))
        return ft_error(FT_E_INVALID, "fill: rows %zu-%zu of a window of rows %zu-%zu in %zu rows: not a stripe "
                        "inside the window inside the raster", own0, own1 - 1, row0, row0 + win->ny - 1, ny);
    size_t rows[4] = {row0, ny, own0, own1};
    return fill_window(win, invalid, rows, opts, out, sd_out, res);
}
