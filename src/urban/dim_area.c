/* fracterra — src/urban/dim_area.c: box-counting dimension of the polygons of a land-use layer (Zhang, Yu &
 * Fan 2008, §1.1-1.2: N(r) ~ r^-D, Eqs. 1-4, measured per land-use class and year), counted
 * exactly from the vector geometry instead of rasterizing at each size.
 *
 * Boundary (FT_AREA_BOUNDARY): the rings are counted by ft_line_box_count_min, the exact cell traversal of
 * the chain counter (half-open cells, mean or fewest over offsets x offsets grid origins).
 *
 * Area (FT_AREA_AREA): the boxes whose inside meets a polygon's interior. Boxes of side r are groups of
 * offsets x offsets fine cells of side g = r / offsets, on a fine grid whose origin is the lower-left corner
 * of the polygons' bounding box, so that each shifted box grid is a regrouping of the fine cells and a box
 * meets the interior iff one of its fine cells does. A fine cell (the open square) meets the interior iff
 *   (1) a ring passes through its inside: each edge is clipped to every open row strip (j, j+1) it crosses,
 *       and the columns whose open interval meets the clipped x-range are taken (an edge lying on a grid
 *       line passes through no cell's inside); or
 *   (2) no ring passes through it and its centre is inside the polygon: a scanline through the centres of
 *       each fine row crosses the polygon's edges (half-open rule: an edge counts if its lower end is at or
 *       below the line and its upper end above), crossings sorted and paired by the even-odd rule over the
 *       polygon's rings, and the cells whose centre lies in a pair's interval are taken.
 * Both set bits of row bitmaps, rasterized in stripes of fine rows (at most 32 MB at a time; each polygon
 * is drawn into the stripes its rows reach) and fed in row order to the band counter (row_bits.c), which
 * counts the boxes at every offset. The count is exact up to the rounding of the intersections; it costs
 * O(edges x rows they span + rows x polygons) to draw plus O(rows x words x offsets) to count per size.
 *
 * Automatic size range (docs/urban-boxcount.md): hi = 1/48 of the bounding-box diagonal for the boundary
 * (as for chains, line_dim.c: boxes stay small against the extent, so the few boxes a corner adds or saves
 * bend log N little) and 1/128 for the area (an area count carries an edge term ~ P / r beside A / r², of
 * relative size r P / A: at 1/128 a filled square at any orientation gives D within 0.015 of 2); lo = the
 * median segment length, but at most hi / 16 (polygons with long straight sides, such as parcels or a
 * square, have no detail below their sides: 1.2 decades are still counted) and at least hi / 1024 (bounds
 * the work). The sizes are counted in parallel, one size per thread at a time.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "fracterra/line.h"
#include "fracterra/urban.h"
#include "internal.h"
#include "line/line_shared.h"
#include "urban/urban_internal.h"

#define HI_FRACTION_BOUNDARY (1.0 / 48)
#define HI_FRACTION_AREA (1.0 / 128)
#define LO_MAX_FRACTION (1.0 / 16)  /* lo <= hi / 16 */
#define LO_MIN_FRACTION (1.0 / 1024) /* lo >= hi / 1024 */
#define MAX_SPAN ((double)(1u << 24)) /* fine cells across the extent, per axis */
#define STRIPE_WORDS ((size_t)1 << 22)  /* 32 MB of fine rows rasterized at a time */

typedef struct {
    ft_polygon_index set;
    double xmin, ymin, xmax, ymax;
    double *poly_ymin, *poly_ymax; /* per polygon */
    double median_seg;
} polygons;

/* ---- statistics ---------------------------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int statistics(polygons *p)
{
    size_t nseg = 0;
    for (size_t r = 0; r < p->set.nrings; r++)
        nseg += ft_chain_segments(p->set.rings[r]);
    double *len = ft_malloc((nseg ? nseg : 1) * sizeof *len);
    p->poly_ymin = ft_malloc((p->set.npolys ? p->set.npolys : 1) * sizeof *p->poly_ymin);
    p->poly_ymax = ft_malloc((p->set.npolys ? p->set.npolys : 1) * sizeof *p->poly_ymax);
    if (len == NULL || p->poly_ymin == NULL || p->poly_ymax == NULL) {
        free(len);
        return FT_E_NOMEM;
    }
    size_t m = 0;
    p->xmin = p->ymin = INFINITY;
    p->xmax = p->ymax = -INFINITY;
    for (size_t q = 0; q < p->set.npolys; q++) {
        p->poly_ymin[q] = INFINITY;
        p->poly_ymax[q] = -INFINITY;
        for (size_t r = p->set.poly_first[q]; r < p->set.poly_first[q + 1]; r++)
            for (size_t i = 0; i < p->set.rings[r]->n; i++) {
                p->poly_ymin[q] = fmin(p->poly_ymin[q], p->set.rings[r]->y[i]);
                p->poly_ymax[q] = fmax(p->poly_ymax[q], p->set.rings[r]->y[i]);
            }
    }
    for (size_t r = 0; r < p->set.nrings; r++) {
        const ft_chain *c = p->set.rings[r];
        size_t ns = ft_chain_segments(c);
        for (size_t i = 0; i < c->n; i++) {
            p->xmin = fmin(p->xmin, c->x[i]);
            p->xmax = fmax(p->xmax, c->x[i]);
            p->ymin = fmin(p->ymin, c->y[i]);
            p->ymax = fmax(p->ymax, c->y[i]);
        }
        for (size_t i = 0; i < ns; i++) {
            size_t j = i + 1 == c->n ? 0 : i + 1;
            double d = hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
            if (d > 0.0)
                len[m++] = d;
        }
    }
    if (m > 0) {
        qsort(len, m, sizeof *len, cmp_double);
        p->median_seg = len[m / 2];
    }
    free(len);
    if (m == 0)
        return ft_error(FT_E_EMPTY, "box counting: the polygons have no extent (every vertex is the same point)");
    return FT_OK;
}

/* ---- fine-grid rasterization into row bitmaps ----------------------------------------------------- */

typedef struct {
    double ox, oy, g;
    size_t ncol, nrow, words;
    size_t s0, s1;  /* the stripe of fine rows held: [s0, s1) */
    uint64_t *bits; /* (s1 - s0) rows of `words` words */
} fine;

/* Fine coordinates are >= 0 and below MAX_SPAN: floor and ceil by conversion, without a libm call. */
static inline double dmin(double a, double b)
{
    return a < b ? a : b;
}

static inline double dmax(double a, double b)
{
    return a > b ? a : b;
}

static inline int64_t ifloor(double u)
{
    int64_t i = (int64_t)u;
    return i - (u < (double)i);
}

static inline int64_t iceil(double u)
{
    int64_t i = (int64_t)u;
    return i + (u > (double)i);
}

/* Sets the columns whose open interval (i, i + 1) meets [a, b] in row j (fine units). */
static void set_cols(const fine *f, int64_t j, double a, double b)
{
    int64_t c0 = ifloor(a), c1;
    if (a == b) {
        if (a == (double)c0)
            return; /* on a column line: inside no cell */
        c1 = c0;
    } else {
        c1 = iceil(b) - 1;
    }
    const int64_t last = (int64_t)f->ncol - 1;
    c0 = c0 < 0 ? 0 : c0;
    c1 = c1 > last ? last : c1;
    if (c0 > c1 || j < (int64_t)f->s0 || j >= (int64_t)f->s1)
        return;
    ft_bits_set_range(f->bits + ((size_t)j - f->s0) * f->words, (size_t)c0, (size_t)c1);
}

/* (1): the fine cells whose inside the edge (u0, v0) -> (u1, v1) passes through. */
static void edge_cells(const fine *f, double u0, double v0, double u1, double v1)
{
    if (v0 == v1) {
        if (v0 != (double)ifloor(v0))
            set_cols(f, ifloor(v0), dmin(u0, u1), dmax(u0, u1));
        return;
    }
    double vlo = v0, ulo = u0, vhi = v1, uhi = u1;
    if (v1 < v0) {
        vlo = v1;
        ulo = u1;
        vhi = v0;
        uhi = u0;
    }
    const double dudv = (uhi - ulo) / (vhi - vlo);
    /* rows whose open strip (j, j + 1) meets (vlo, vhi), within the stripe */
    int64_t j0 = ifloor(vlo), j1 = iceil(vhi) - 1;
    j0 = j0 > (int64_t)f->s0 ? j0 : (int64_t)f->s0;
    j1 = j1 < (int64_t)f->s1 - 1 ? j1 : (int64_t)f->s1 - 1;
    for (int64_t j = j0; j <= j1; j++) {
        double ya = dmax(vlo, (double)j), yb = dmin(vhi, (double)j + 1.0);
        double xa = ya == vlo ? ulo : ulo + (ya - vlo) * dudv;
        double xb = yb == vhi ? uhi : ulo + (yb - vlo) * dudv;
        set_cols(f, j, dmin(xa, xb), dmax(xa, xb));
    }
}

/* An edge of the scanline: active on centre lines vlo <= vc < vhi, crossing at u = ulo + (vc - vlo) dudv. */
typedef struct {
    double vlo, vhi, ulo, dudv;
} sedge;

typedef struct {
    sedge *edges;
    size_t nedges, cap;
    size_t *active;
    double *xs;
} scan_buf;

static int cmp_sedge(const void *a, const void *b)
{
    double x = ((const sedge *)a)->vlo, y = ((const sedge *)b)->vlo;
    return (x > y) - (x < y);
}

static void sort_small(double *v, size_t n)
{
    if (n > 32) {
        qsort(v, n, sizeof *v, cmp_double);
        return;
    }
    for (size_t i = 1; i < n; i++) {
        double x = v[i];
        size_t k = i;
        for (; k > 0 && v[k - 1] > x; k--)
            v[k] = v[k - 1];
        v[k] = x;
    }
}

/* The polygon's edges in fine units: (1) marks the cells they pass through; the non-horizontal ones are kept
 * for the scanline, sorted by their lower end. */
static int load_edges(const fine *f, const ft_polygon_index *s, size_t poly, scan_buf *b)
{
    size_t need = 0;
    for (size_t r = s->poly_first[poly]; r < s->poly_first[poly + 1]; r++)
        need += s->rings[r]->n;
    if (need > b->cap) {
        sedge *e = ft_realloc_array(b->edges, need, sizeof *e);
        size_t *a = e ? ft_realloc_array(b->active, need, sizeof *a) : NULL;
        double *x = a ? ft_realloc_array(b->xs, need, sizeof *x) : NULL;
        if (e != NULL)
            b->edges = e;
        if (a != NULL)
            b->active = a;
        if (x == NULL)
            return FT_E_NOMEM;
        b->xs = x;
        b->cap = need;
    }
    b->nedges = 0;
    for (size_t r = s->poly_first[poly]; r < s->poly_first[poly + 1]; r++) {
        const ft_chain *c = s->rings[r];
        for (size_t i = 0; i < c->n; i++) {
            size_t j = i + 1 == c->n ? 0 : i + 1;
            double u0 = (c->x[i] - f->ox) / f->g, v0 = (c->y[i] - f->oy) / f->g;
            double u1 = (c->x[j] - f->ox) / f->g, v1 = (c->y[j] - f->oy) / f->g;
            edge_cells(f, u0, v0, u1, v1);
            if (v0 == v1)
                continue;
            b->edges[b->nedges++] = v0 < v1 ? (sedge){v0, v1, u0, (u1 - u0) / (v1 - v0)}
                                             : (sedge){v1, v0, u1, (u0 - u1) / (v0 - v1)};
        }
    }
    qsort(b->edges, b->nedges, sizeof *b->edges, cmp_sedge);
    return FT_OK;
}

/* (2): the fine cells of the stripe whose centre is inside the polygon (even-odd over its rings). */
static void interior_cells(const fine *f, scan_buf *b)
{
    double vmax = -INFINITY;
    for (size_t e = 0; e < b->nedges; e++)
        vmax = dmax(vmax, b->edges[e].vhi);
    size_t next = 0, nactive = 0;
    int64_t j = iceil(b->edges[0].vlo - 0.5);
    j = j > (int64_t)f->s0 ? j : (int64_t)f->s0;
    for (double vc = (double)j + 0.5; vc < vmax && j < (int64_t)f->s1; j++, vc += 1.0) {
        while (next < b->nedges && b->edges[next].vlo <= vc)
            b->active[nactive++] = next++;
        size_t w = 0, nx = 0;
        for (size_t a = 0; a < nactive; a++) {
            const sedge *e = &b->edges[b->active[a]];
            if (e->vhi <= vc)
                continue; /* finished: drop it */
            b->active[w++] = b->active[a];
            b->xs[nx++] = e->ulo + (vc - e->vlo) * e->dudv;
        }
        nactive = w;
        sort_small(b->xs, nx);
        for (size_t k = 0; k + 1 < nx; k += 2) {
            int64_t c0 = iceil(b->xs[k] - 0.5), c1 = ifloor(b->xs[k + 1] - 0.5);
            if (c0 <= c1)
                set_cols(f, j, (double)c0 + 0.5, (double)c1 + 0.5);
        }
    }
}

/* Rasterizes every polygon that reaches the stripe. */
static int rasterize_stripe(const polygons *p, const fine *f, scan_buf *b)
{
    for (size_t q = 0; q < p->set.npolys; q++) {
        if (ifloor((p->poly_ymax[q] - f->oy) / f->g) < (int64_t)f->s0 ||
            ifloor((p->poly_ymin[q] - f->oy) / f->g) >= (int64_t)f->s1)
            continue;
        int rc = load_edges(f, &p->set, q, b);
        if (rc != FT_OK)
            return rc;
        if (b->nedges > 0)
            interior_cells(f, b);
    }
    return FT_OK;
}

/* ---- counting ------------------------------------------------------------------------------------ */

static int row_empty(const uint64_t *row, size_t words)
{
    for (size_t w = 0; w < words; w++)
        if (row[w] != 0)
            return 0;
    return 1;
}

static int count_area(const polygons *p, double r, int k, int fewest, double *count)
{
    /* mean: origins at the centres of k x k strata of a box (stratified sampling of a random origin) */
    double half = fewest ? 0.0 : 0.5 * r / k;
    fine f = {p->xmin - half, p->ymin - half, r / k, 0, 0, 0, 0, 0, NULL};
    double spanx = (p->xmax - f.ox) / f.g, spany = (p->ymax - f.oy) / f.g;
    if (!(fmax(spanx, spany) < MAX_SPAN))
        return ft_error(FT_E_INVALID, "box counting: box side %g is too small for the extent (%.3g fine cells "
                        "across, at most %.0f)", r, fmax(spanx, spany), MAX_SPAN);
    f.ncol = (size_t)floor(spanx) + 1;
    f.nrow = (size_t)floor(spany) + 1;
    f.words = (f.ncol + 63) / 64;
    const size_t stripe = STRIPE_WORDS / f.words > 0 ? STRIPE_WORDS / f.words : 1;
    uint32_t offsets[FT_BAND_OFFSETS_MAX];
    for (int a = 0; a < k; a++)
        offsets[a] = (uint32_t)a;
    ft_band_counter *bc = ft_band_counter_create(f.ncol, (uint32_t)k, offsets, k);
    f.bits = ft_malloc((stripe < f.nrow ? stripe : f.nrow) * f.words * sizeof *f.bits);
    scan_buf b = {0};
    int rc = bc != NULL && f.bits != NULL ? FT_OK : FT_E_NOMEM;
    for (f.s0 = 0; rc == FT_OK && f.s0 < f.nrow; f.s0 = f.s1) {
        f.s1 = f.s0 + stripe < f.nrow ? f.s0 + stripe : f.nrow;
        memset(f.bits, 0, (f.s1 - f.s0) * f.words * sizeof *f.bits);
        rc = rasterize_stripe(p, &f, &b);
        for (size_t j = f.s0; rc == FT_OK && j < f.s1; j++) {
            const uint64_t *row = f.bits + (j - f.s0) * f.words;
            if (!row_empty(row, f.words))
                ft_band_counter_row(bc, j, row);
        }
    }
    if (rc == FT_OK) {
        uint64_t least = ft_band_counter_finish(bc);
        *count = fewest ? (double)least : ft_band_counter_mean(bc);
    }
    ft_band_counter_free(bc);
    free(f.bits);
    free(b.edges);
    free(b.active);
    free(b.xs);
    return rc;
}

static int count_one(const polygons *p, const ft_area_dim_opts *o, double r, double *count)
{
    if (o->what == FT_AREA_AREA)
        return count_area(p, r, o->offsets, o->fewest, count);
    uint64_t least = 0;
    double mean = 0.0;
    double half = o->fewest ? 0.0 : 0.5 * r / o->offsets; /* as in count_area */
    int rc = ft_line_box_count_offsets(p->set.rings, p->set.nrings, r, o->offsets, p->xmin - half, p->ymin - half,
                                       &least, &mean);
    *count = o->fewest ? (double)least : mean;
    return rc;
}

/* The sizes are counted in parallel (each count is an integer of its own, so the table does not depend on
 * the number of threads); progress is reported by the master thread, and a cancel stops the others before
 * their next size. The first failing size's error is raised again on the calling thread. */
static int build_table(const polygons *p, const ft_area_dim_opts *o, const double *sizes, size_t n, ft_loglog **out)
{
    double *counts = ft_calloc(n, sizeof *counts);
    int *rcs = ft_calloc(n, sizeof *rcs);
    char (*msgs)[256] = ft_calloc(n, sizeof *msgs);
    if (counts == NULL || rcs == NULL || msgs == NULL) {
        free(counts);
        free(rcs);
        free(msgs);
        return FT_E_NOMEM;
    }
    int rc = ft_progress(o->progress, o->progress_arg, 0.0, "box counting");
    int cancelled = rc != FT_OK;
    size_t done = 0;
#pragma omp parallel for schedule(dynamic, 1) shared(cancelled, done)
    for (size_t i = 0; i < n; i++) {
        int stop;
#pragma omp atomic read
        stop = cancelled;
        if (stop) {
            rcs[i] = FT_E_CANCELLED;
            continue;
        }
        rcs[i] = count_one(p, o, sizes[i], &counts[i]);
        if (rcs[i] != FT_OK)
            snprintf(msgs[i], sizeof msgs[i], "%s", ft_last_error());
        size_t now;
#pragma omp atomic capture
        now = ++done;
#ifdef _OPENMP
        if (omp_get_thread_num() != 0)
            continue;
#endif
        char msg[64];
        snprintf(msg, sizeof msg, "box counting: %zu of %zu sizes", now, n);
        if (ft_progress(o->progress, o->progress_arg, (double)now / (double)n, msg) != FT_OK) {
#pragma omp atomic write
            cancelled = 1;
        }
    }
    if (cancelled)
        rc = ft_error(FT_E_CANCELLED, "box counting: cancelled");
    for (size_t i = 0; rc == FT_OK && i < n; i++)
        if (rcs[i] != FT_OK)
            rc = ft_error(rcs[i], "%s", msgs[i]);
    ft_loglog *t = rc == FT_OK ? ft_loglog_create(n) : NULL;
    if (rc == FT_OK && t == NULL)
        rc = FT_E_NOMEM;
    for (size_t i = 0; rc == FT_OK && i < n; i++)
        if (counts[i] > 0)
            rc = ft_loglog_push(t, sizes[i], counts[i], counts[i]);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 1.0, "box counting");
    if (rc == FT_OK && t->n < 2)
        rc = ft_error(FT_E_INVALID, "box counting: only %zu of %zu sizes found a box", t->n, n);
    free(counts);
    free(rcs);
    free(msgs);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

int ft_urban_dim_area(const ft_layer *l, const size_t *features, size_t nfeatures, const ft_area_dim_opts *o,
                      ft_dim_result **out)
{
    ft_area_dim_opts taken = FT_AREA_DIM_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (o != NULL) {
        if (FT_OPTS_TAKE(taken, o, ft_area_dim_opts) != FT_OK)
            return FT_E_INVALID;
        o = &taken;
    }
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_urban_dim_area: NULL out");
    *out = NULL;
    const ft_area_dim_opts defaults = FT_AREA_DIM_OPTS_DEFAULT;
    o = o != NULL ? o : &defaults;
    int rc = ft_area_sizes_check(o);
    if (rc != FT_OK)
        return rc;
    polygons p = {0};
    rc = ft_polygon_index_collect(l, features, nfeatures, 1, &p.set);
    if (rc != FT_OK)
        return rc;
    if (p.set.nrings == 0)
        rc = ft_error(FT_E_EMPTY, "box counting: no polygon among the %zu selected feature%s",
                      features != NULL ? nfeatures : l->nfeatures,
                      (features != NULL ? nfeatures : l->nfeatures) == 1 ? "" : "s");
    if (rc == FT_OK)
        rc = statistics(&p);
    double *sizes = NULL;
    size_t n = 0;
    if (rc == FT_OK) {
        double hi = (o->what == FT_AREA_AREA ? HI_FRACTION_AREA : HI_FRACTION_BOUNDARY) *
                    hypot(p.xmax - p.xmin, p.ymax - p.ymin);
        double lo = fmax(fmin(p.median_seg, LO_MAX_FRACTION * hi), LO_MIN_FRACTION * hi);
        rc = ft_area_sizes(o, lo, hi, &sizes, &n);
    }
    ft_loglog *t = NULL;
    if (rc == FT_OK)
        rc = build_table(&p, o, sizes, n, &t);
    if (rc == FT_OK)
        rc = ft_area_fit(t, o, o->what == FT_AREA_AREA ? "box-area" : "box-boundary", out);
    ft_loglog_free(t);
    free(sizes);
    free(p.poly_ymin);
    free(p.poly_ymax);
    ft_polygon_index_clear(&p.set);
    return rc;
}
