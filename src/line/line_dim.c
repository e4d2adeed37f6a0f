/* fracterra — src/line/line_dim.c: ft_line_dim, the dimension of a set of chains by one of four methods
 * (divider.c, equipaced.c, hybrid_walk.c, box_count.c), and the method names.
 *
 * Scales form a geometric series s_i = lo (hi / lo)^(i / (N - 1)), i = 0 .. N - 1. The value at each scale
 * is summed over the chains (lengths) or counted over all of them at once (boxes), one log-log row per
 * scale, and the table is fitted by the shared module (core.h, docs/loglog.md): ft_loglog_fit_auto within
 * [lo, hi], which keeps the longest straight run by iterative least squares and reports every minimax
 * segment (Arakawa & Krotkov, §2.4), or ft_loglog_fit_range over all of [lo, hi].
 *
 * Automatic range (docs/line-dimension.md): for the walks lo = 2 x the median segment length, since shorter
 * rulers step from vertex to vertex and measure the polygon itself (slope 0: D -> 1), and hi = 1/4 of the
 * diagonal of the chains' bounding box (larger rulers take only a few steps, whose last fraction
 * dominates); for boxes lo = 1 x the median segment (a box of the vertex spacing is crossed by one or two
 * segments, and does not resolve them), hi = 1/48 of the diagonal (a smooth curve crosses N = P/r - c
 * boxes with c of a few units when the grid offset is minimised: hi keeps N above ~100 so that c bends
 * log N by less than the accuracy asked of a circle). Both fractions were tuned on the tests' straight
 * lines, circles and Koch curves.
 *
 * Equipaced polygon: the series runs over the arc-length spacing s, but the table's scale is the mean
 * side of the polygon, s L(s) / L_arc (Kaye's step length): sides are chords, shorter than s on a wiggly
 * chain, and L against s itself gives the slope 1 - 1/D instead of 1 - D.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fracterra/line.h"
#include "internal.h"
#include "line/line_dim_internal.h"

#define NSCALES_DEFAULT 16
#define NSCALES_DEFAULT_BOX 12
#define NSCALES_MAX 1000
#define STARTS_MAX 1000
#define BOX_OFFSETS_MAX 16
#define LO_SEGMENTS_WALK 2.0       /* lo = this x the median segment length: divider, equipaced, hybrid */
#define LO_SEGMENTS_BOX 1.0        /* ... box counting */
#define HI_FRACTION_WALK 0.25      /* hi = this x the bbox diagonal: divider, equipaced, hybrid */
#define HI_FRACTION_BOX (1.0 / 16) /* ... box counting */

static const char *const method_names[] = {"divider", "equipaced", "hybrid", "box", "box-min"};
#define N_METHODS (sizeof method_names / sizeof method_names[0])

const char *ft_line_method_name(ft_line_method m)
{
    return (unsigned)m < N_METHODS ? method_names[m] : "unknown";
}

int ft_line_method_parse(const char *name, ft_line_method *m)
{
    if (name == NULL || m == NULL)
        return ft_error(FT_E_INVALID, "ft_line_method_parse: NULL %s", name == NULL ? "name" : "method");
    for (size_t i = 0; i < N_METHODS; i++)
        if (strcasecmp(name, method_names[i]) == 0) {
            *m = (ft_line_method)i;
            return FT_OK;
        }
    return ft_error(FT_E_INVALID, "unknown line dimension method '%s' (divider, equipaced, hybrid, box or box-min)",
                    name);
}

/* ------------------------------------------------------------------------------------------------
 * Input checks and the chains' statistics
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    const ft_chain **chains; /* the chains with >= 2 vertices (Earth-centred copies for geographic input) */
    const double **z;        /* per chain its third coordinate, or NULL (planar) */
    ft_chain **ecef;         /* owned Earth-centred chains (geographic input), else NULL */
    double **ecef_z;
    size_t n;
    double xmin, ymin, zmin, xmax, ymax, zmax;
    size_t **start;    /* per ring its walks' start vertices (opts starts > 1), else NULL */
    double median_seg; /* median of the non-zero segment lengths */
    double length;     /* total length */
} chain_set;

static int check_opts(ft_line_method method, const ft_line_dim_opts *o)
{
    if ((unsigned)method >= N_METHODS)
        return ft_error(FT_E_INVALID, "line dimension method must be 0..4, got %d", (int)method);
    if (!(o->min_scale >= 0.0) || !isfinite(o->min_scale))
        return ft_error(FT_E_INVALID, "min_scale must be finite and >= 0 (0 = automatic), got %g", o->min_scale);
    if (!(o->max_scale >= 0.0) || !isfinite(o->max_scale))
        return ft_error(FT_E_INVALID, "max_scale must be finite and >= 0 (0 = automatic), got %g", o->max_scale);
    if (o->min_scale > 0.0 && o->max_scale > 0.0 && !(o->min_scale < o->max_scale))
        return ft_error(FT_E_INVALID, "min_scale (%g) must be less than max_scale (%g)", o->min_scale,
                        o->max_scale);
    if (o->nscales != 0 && (o->nscales < 3 || o->nscales > NSCALES_MAX))
        return ft_error(FT_E_INVALID, "nscales must be in [3, %d] (0 = default), got %d", NSCALES_MAX, o->nscales);
    if (!(o->min_r2 >= 0.0 && o->min_r2 <= 1.0))
        return ft_error(FT_E_INVALID, "min_r2 must be in [0, 1], got %g", o->min_r2);
    if (o->box_offsets < 1 || o->box_offsets > BOX_OFFSETS_MAX)
        return ft_error(FT_E_INVALID, "box_offsets must be in [1, %d], got %d", BOX_OFFSETS_MAX, o->box_offsets);
    if (o->starts < 1 || o->starts > STARTS_MAX)
        return ft_error(FT_E_INVALID, "starts must be in [1, %d], got %d", STARTS_MAX, o->starts);
    if (o->starts > 1 && method != FT_LINE_DIVIDER)
        return ft_error(FT_E_INVALID, "starts (%d) applies to the divider only, not to the %s", o->starts,
                        method_names[method]);
    if (o->only_start < -1 || o->only_start >= o->starts)
        return ft_error(FT_E_INVALID, "only_start must be -1 (all) or in [0, %d), got %d", o->starts,
                        o->only_start);
    return FT_OK;
}

/* Keeps the chains with >= 2 vertices after checking every chain's coordinates. */
static int collect_chains(const ft_chain *const *chains, size_t n, chain_set *s)
{
    if (chains == NULL || n == 0)
        return ft_error(FT_E_EMPTY, "line dimension: no chains (n = %zu)", chains == NULL ? (size_t)0 : n);
    s->chains = ft_malloc(n * sizeof *s->chains);
    s->z = ft_calloc(n, sizeof *s->z);
    if (s->chains == NULL || s->z == NULL)
        return FT_E_NOMEM;
    for (size_t c = 0; c < n; c++) {
        if (chains[c] == NULL)
            return ft_error(FT_E_INVALID, "line dimension: chain %zu is NULL", c);
        if (ft_chain_check_finite(chains[c]) != FT_OK) {
            char msg[256];
            snprintf(msg, sizeof msg, "%s", ft_last_error());
            return ft_error(FT_E_NUMERIC, "line dimension: chain %zu: %s", c, msg);
        }
        if (chains[c]->n >= 2)
            s->chains[s->n++] = chains[c];
    }
    if (s->n == 0)
        return ft_error(FT_E_EMPTY, "line dimension: none of the %zu chain%s has 2 vertices or more", n,
                        n == 1 ? "" : "s");
    return FT_OK;
}

/* Geographic input: replaces every chain by its Earth-centred copy on the ellipsoid (x, y and z in metres),
 * so that the walks measure straight 3-D chords. A chord is shorter than the geodesic between its ends by
 * s^3 / (24 R^2) (1 m in 100 km, 1e-5 relative; docs/geographic.md). */
static int to_ecef(chain_set *s, const ft_ellipsoid *e)
{
    if (!(e->a > 0.0) || !(e->f >= 0.0 && e->f < 1.0))
        return ft_error(FT_E_INVALID, "ellipsoid must have a > 0 and 0 <= f < 1, got a = %g, f = %g", e->a, e->f);
    s->ecef = ft_calloc(s->n, sizeof *s->ecef);
    s->ecef_z = ft_calloc(s->n, sizeof *s->ecef_z);
    if (s->ecef == NULL || s->ecef_z == NULL)
        return FT_E_NOMEM;
    for (size_t c = 0; c < s->n; c++) {
        const ft_chain *g = s->chains[c];
        for (size_t i = 0; i < g->n; i++)
            if (!(fabs(g->y[i]) <= 90.0) || !(fabs(g->x[i]) <= 540.0))
                return ft_error(FT_E_INVALID, "line dimension: chain %zu vertex %zu at (%g, %g) is outside longitude "
                                "[-540, 540] and latitude [-90, 90]: the coordinates are not longitude/latitude degrees "
                                "(a GeoJSON file without a \"crs\" member is longitude/latitude by RFC 7946)",
                                c, i, g->x[i], g->y[i]);
        s->ecef[c] = ft_chain_create(g->n, g->closed);
        s->ecef_z[c] = ft_malloc(g->n * sizeof *s->ecef_z[c]);
        if (s->ecef[c] == NULL || s->ecef_z[c] == NULL)
            return FT_E_NOMEM;
        for (size_t i = 0; i < g->n; i++)
            ft_ellipsoid_to_ecef(e, g->x[i], g->y[i], &s->ecef[c]->x[i], &s->ecef[c]->y[i], &s->ecef_z[c][i]);
        s->ecef[c]->n = g->n;
        s->chains[c] = s->ecef[c];
        s->z[c] = s->ecef_z[c];
    }
    return FT_OK;
}

/* The start vertices of every ring's walks (opts starts > 1, Andrle 1992), on the chains as walked. */
static int ring_starts(chain_set *s, int starts)
{
    if (starts < 2)
        return FT_OK;
    s->start = ft_calloc(s->n, sizeof *s->start);
    if (s->start == NULL)
        return FT_E_NOMEM;
    for (size_t c = 0; c < s->n; c++) {
        if (!s->chains[c]->closed)
            continue;
        s->start[c] = ft_malloc((size_t)starts * sizeof *s->start[c]);
        if (s->start[c] == NULL)
            return FT_E_NOMEM;
        ft_line_ring_starts(s->chains[c], s->z[c], (size_t)starts, s->start[c]);
    }
    return FT_OK;
}

static int has_ring(const chain_set *s)
{
    for (size_t c = 0; c < s->n; c++)
        if (s->chains[c]->closed)
            return 1;
    return 0;
}

static void chain_set_clear(chain_set *s)
{
    for (size_t c = 0; s->start && c < s->n; c++)
        free(s->start[c]);
    free(s->start);
    for (size_t c = 0; s->ecef && c < s->n; c++) {
        ft_chain_free(s->ecef[c]);
        free(s->ecef_z ? s->ecef_z[c] : NULL);
    }
    free(s->ecef);
    free(s->ecef_z);
    free(s->chains);
    free(s->z);
}

/* The k-th smallest of v[0..n) (v is reordered): Wirth's selection, O(n) on average; runs of equal values
 * (equal segments are common in generated lines) split evenly. */
static double select_kth(double *v, size_t n, size_t k)
{
    ptrdiff_t l = 0, m = (ptrdiff_t)n - 1, kk = (ptrdiff_t)k;
    while (l < m) {
        double x = v[kk];
        ptrdiff_t i = l, j = m;
        do {
            while (v[i] < x)
                i++;
            while (x < v[j])
                j--;
            if (i <= j) {
                double t = v[i];
                v[i] = v[j];
                v[j] = t;
                i++;
                j--;
            }
        } while (i <= j);
        if (j < kk)
            l = i;
        if (kk < i)
            m = j;
    }
    return v[kk];
}

static int set_statistics(chain_set *s)
{
    size_t nseg = 0;
    for (size_t c = 0; c < s->n; c++)
        nseg += ft_chain_segments(s->chains[c]);
    double *len = ft_malloc(nseg * sizeof *len);
    if (len == NULL)
        return FT_E_NOMEM;
    size_t m = 0;
    s->xmin = s->ymin = s->zmin = INFINITY;
    s->xmax = s->ymax = s->zmax = -INFINITY;
    s->length = 0.0;
    for (size_t c = 0; c < s->n; c++) {
        const ft_chain *ch = s->chains[c];
        const double *z = s->z[c];
        size_t ns = ft_chain_segments(ch);
        for (size_t i = 0; i < ch->n; i++) {
            double x = ch->x[i], y = ch->y[i], h = z ? z[i] : 0.0;
            s->xmin = x < s->xmin ? x : s->xmin;
            s->xmax = x > s->xmax ? x : s->xmax;
            s->ymin = y < s->ymin ? y : s->ymin;
            s->ymax = y > s->ymax ? y : s->ymax;
            s->zmin = h < s->zmin ? h : s->zmin;
            s->zmax = h > s->zmax ? h : s->zmax;
        }
        for (size_t i = 0; i < ns; i++) {
            size_t j = i + 1 == ch->n ? 0 : i + 1;
            double d = ft_walk_dist(ch->x[j] - ch->x[i], ch->y[j] - ch->y[i], z ? z[j] - z[i] : 0.0);
            s->length += d;
            if (d > 0.0)
                len[m++] = d;
        }
    }
    s->median_seg = m > 0 ? select_kth(len, m, m / 2) : 0.0;
    free(len);
    if (m == 0)
        return ft_error(FT_E_EMPTY, "line dimension: the chains have zero length (every vertex repeats the "
                        "first)");
    return FT_OK;
}

/* ------------------------------------------------------------------------------------------------
 * Scales and measurement
 * --------------------------------------------------------------------------------------------- */

/* Diagonal of the chains' bounding box (3-D for Earth-centred chains): their extent. */
static double extent_diagonal(const chain_set *s)
{
    return ft_walk_dist(s->xmax - s->xmin, s->ymax - s->ymin, s->zmax - s->zmin);
}

static int scale_range(const chain_set *s, ft_line_method method, const ft_line_dim_opts *o, double *lo,
                       double *hi)
{
    double diag = extent_diagonal(s);
    int box = method == FT_LINE_BOX || method == FT_LINE_BOX_MIN;
    double lo_auto = (box ? LO_SEGMENTS_BOX : LO_SEGMENTS_WALK) * s->median_seg;
    double hi_auto = (box ? HI_FRACTION_BOX : HI_FRACTION_WALK) * diag;
    *lo = o->min_scale > 0.0 ? o->min_scale : lo_auto;
    *hi = o->max_scale > 0.0 ? o->max_scale : hi_auto;
    const char *u = o->ellipsoid ? " m" : "";
    if (!(*lo < *hi))
        return ft_error(FT_E_INVALID, "empty scale range: min_scale %g%s%s >= max_scale %g%s%s (median segment %g%s, "
                        "bounding-box diagonal %g%s); set --min-scale/--max-scale", *lo, u,
                        o->min_scale > 0.0 ? "" : (box ? " (automatic: median segment)"
                                                       : " (automatic: 2 x median segment)"), *hi, u,
                        o->max_scale > 0.0 ? "" : (box ? " (automatic: diagonal / 16)" : " (automatic: diagonal / 4)"),
                        s->median_seg, u, diag, u);
    return FT_OK;
}

/* Divider length and steps of a ring at ruler r: the walk from start[only_start], or the mean over the
 * starts. */
static void divider_starts(const ft_chain *c, const double *z, const size_t *start, const ft_line_dim_opts *o,
                           double r, double *length, double *steps)
{
    if (o->only_start >= 0) {
        ft_line_divider_ring_from(c, z, start[o->only_start], r, length, steps);
        return;
    }
    double len = 0.0, st = 0.0;
    for (int k = 0; k < o->starts; k++) {
        double l, n;
        ft_line_divider_ring_from(c, z, start[k], r, &l, &n);
        len += l;
        st += n;
    }
    *length = len / o->starts;
    *steps = st / o->starts;
}

/* value and count of the method at scale r, summed over the chains. */
static int measure(const chain_set *s, ft_line_method method, const ft_line_dim_opts *o, double r, double *value,
                   double *count)
{
    if (method == FT_LINE_BOX || method == FT_LINE_BOX_MIN) {
        uint64_t fewest = 0;
        double mean = 0.0;
        /* the mean samples the origins at the centres of k x k strata of the cell (stratified sampling of
         * a random origin); the fewest keeps the literature's origins at multiples of r / k from the corner */
        double half = method == FT_LINE_BOX ? 0.5 * r / o->box_offsets : 0.0;
        int rc = ft_line_box_count_offsets(s->chains, s->n, r, o->box_offsets, s->xmin - half, s->ymin - half,
                                           &fewest, &mean);
        *value = *count = method == FT_LINE_BOX ? mean : (double)fewest;
        return rc;
    }
    double len = 0.0, steps = 0.0;
    for (size_t c = 0; c < s->n; c++) {
        double l = 0.0, k = 0.0;
        if (method == FT_LINE_DIVIDER && s->start && s->start[c])
            divider_starts(s->chains[c], s->z[c], s->start[c], o, r, &l, &k);
        else if (method == FT_LINE_DIVIDER)
            ft_line_divider_length(s->chains[c], s->z[c], r, o->both_ends, &l, &k);
        else if (method == FT_LINE_EQUIPACED)
            ft_line_equipaced_length(s->chains[c], s->z[c], r, &l, &k);
        else
            ft_line_hybrid_length(s->chains[c], s->z[c], r, o->both_ends, &l, &k);
        len += l;
        steps += k;
    }
    *value = len;
    *count = steps;
    return FT_OK;
}

/* One row per scale of the geometric series; rows where the chains are shorter than one ruler (a walk
 * takes no whole step: its value is the chord between the ends, or 0 for rings) are left out: they say
 * nothing about the line's detail, and kept they read as D = 1. */
static int build_table(const chain_set *s, ft_line_method method, const ft_line_dim_opts *o, double lo,
                       double hi, int nscales, ft_loglog **out)
{
    ft_loglog *t = ft_loglog_create((size_t)nscales);
    if (t == NULL)
        return FT_E_NOMEM;
    const double ratio = log(hi / lo) / (nscales - 1);
    const int box = method == FT_LINE_BOX || method == FT_LINE_BOX_MIN;
    char msg[64];
    int rc = FT_OK;
    for (int i = 0; rc == FT_OK && i < nscales; i++) {
        double r = i == nscales - 1 ? hi : lo * exp(ratio * i), value = 0.0, count = 0.0;
        rc = measure(s, method, o, r, &value, &count);
        double scale = method == FT_LINE_EQUIPACED ? r * value / s->length : r;
        int usable = box ? value > 0.0 : value >= r;
        if (rc == FT_OK && usable)
            rc = ft_loglog_push(t, scale, value, count);
        else if (rc == FT_OK && o->fit_whole_range) /* the range was asked for: say it does not fit */
            rc = ft_error(FT_E_INVALID, "%s %g%s of the range [%g, %g]%s is longer than the chains: they are %g%s "
                          "long and %g%s across; choose a largest scale below %g%s", box ?
                          "box size" : "ruler", r, o->ellipsoid ? " m" : "", lo, hi, o->ellipsoid ? " m" : "",
                          s->length, o->ellipsoid ? " m" : "", extent_diagonal(s), o->ellipsoid ? " m" : "",
                          HI_FRACTION_WALK * extent_diagonal(s), o->ellipsoid ? " m" : "");
        snprintf(msg, sizeof msg, "%s: scale %d of %d", method_names[method], i + 1, nscales);
        if (rc == FT_OK)
            rc = ft_progress(o->progress, o->progress_arg, (i + 1.0) / nscales, msg);
    }
    if (rc == FT_OK && method == FT_LINE_EQUIPACED)
        rc = ft_loglog_sort(t);
    const char *u = o->ellipsoid ? " m" : "";
    if (rc == FT_OK && t->n < 3)
        rc = ft_error(FT_E_INVALID, "only %zu of %d %s in [%g, %g]%s %s; the chains are %g%s long and %g%s "
                      "across: lower the largest scale (about %g%s) or measure a longer line", t->n, nscales,
                      box ? "box sizes" : "rulers", lo, hi, u,
                      box ? "cover a box" : "fit once along the chains", s->length, u,
                      extent_diagonal(s), u, HI_FRACTION_WALK * extent_diagonal(s), u);
    if (rc != FT_OK) {
        ft_loglog_free(t);
        return rc;
    }
    *out = t;
    return FT_OK;
}

/* FT_E_INVALID if the fit's r² is below min_r2 while its values do change and its D is not pinned (line.h,
 * FT_LINE_R2_FLOOR). */
static int check_r2(const ft_dim_result *r, double min_r2, const char *unit)
{
    const ft_loglog *t = r->table;
    double vmin = INFINITY, vmax = -INFINITY;
    for (size_t i = r->fit.first; t && i <= r->fit.last && i < t->n; i++) {
        double v = log10(t->rows[i].value);
        vmin = v < vmin ? v : vmin;
        vmax = v > vmax ? v : vmax;
    }
    if (r->r2 >= min_r2 || !(vmax - vmin > FT_LINE_R2_MIN_SPREAD) || r->stderr_D < FT_LINE_R2_MAX_STDERR)
        return FT_OK;
    return ft_error(FT_E_INVALID, "the log-log fit over [%g, %g]%s has r2 = %.3f, below %.2f: the table is not a "
                    "straight line there (D would be %.4f +- %.3f); choose another range (see the table with --plot)",
                    r->range[0], r->range[1], unit, r->r2, min_r2, r->D, r->stderr_D);
}

/* 1 if coordinate v (stride-free array of n) only grows or only falls, strictly. */
static int monotone(const double *v, size_t n)
{
    int up = 1, down = 1;
    for (size_t i = 1; i < n && (up || down); i++) {
        up &= v[i] > v[i - 1];
        down &= v[i] < v[i - 1];
    }
    return up || down;
}

/* 1 if every open chain is the graph of a function of x or of y (x or y strictly monotone along it) and
 * the set has at least 16 vertices: the chains look like profiles (elevation against distance), whose
 * divider or box dimension does not measure their roughness (self-affine, not self-similar). */
static int looks_like_profile(const chain_set *s)
{
    size_t nv = 0;
    for (size_t c = 0; c < s->n; c++) {
        const ft_chain *ch = s->chains[c];
        if (ch->closed || !(monotone(ch->x, ch->n) || monotone(ch->y, ch->n)))
            return 0;
        nv += ch->n;
    }
    return nv >= 16;
}

int ft_line_dim(const ft_chain *const *chains, size_t n, ft_line_method method, const ft_line_dim_opts *opts,
                ft_dim_result **out)
{
    ft_line_dim_opts taken = FT_LINE_DIM_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_line_dim_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    if (out == NULL)
        return ft_error(FT_E_INVALID, "ft_line_dim: NULL out");
    *out = NULL;
    const ft_line_dim_opts defaults = FT_LINE_DIM_OPTS_DEFAULT;
    const ft_line_dim_opts *o = opts != NULL ? opts : &defaults;
    int rc = check_opts(method, o);
    if (rc != FT_OK)
        return rc;
    chain_set s = {0};
    ft_loglog *t = NULL;
    double lo = 0.0, hi = 0.0;
    int box = method == FT_LINE_BOX || method == FT_LINE_BOX_MIN;
    int nscales = o->nscales > 0 ? o->nscales : (box ? NSCALES_DEFAULT_BOX : NSCALES_DEFAULT);
    if (o->ellipsoid != NULL && box)
        return ft_error(FT_E_INVALID, "box counting of longitude/latitude chains needs them projected to an "
                        "equal-area CRS first (boxes of equal ground area)");
    rc = collect_chains(chains, n, &s);
    if (rc == FT_OK && o->ellipsoid != NULL)
        rc = to_ecef(&s, o->ellipsoid);
    if (rc == FT_OK)
        rc = set_statistics(&s);
    if (rc == FT_OK)
        rc = ring_starts(&s, o->starts);
    if (rc == FT_OK)
        rc = scale_range(&s, method, o, &lo, &hi);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 0.0, method_names[method]);
    if (rc == FT_OK)
        rc = build_table(&s, method, o, lo, hi, nscales, &t);
    if (rc == FT_OK && method == FT_LINE_EQUIPACED) { /* limits in mean-side units: the whole table */
        lo = t->rows[0].scale;
        hi = t->rows[t->n - 1].scale;
    }
    if (rc == FT_OK) {
        const ft_dim_map map_len = FT_DIM_MAP_DIVIDER, map_box = FT_DIM_MAP_BOXCOUNT_LINE;
        const ft_dim_map *map = box ? &map_box : &map_len;
        rc = o->fit_whole_range ? ft_loglog_fit_range(t, lo, hi, map, out)
                                : ft_loglog_fit_auto(t, lo, hi, &o->fit, map, out);
    }
    if (rc == FT_OK)
        rc = check_r2(*out, o->min_r2, o->ellipsoid ? " m" : "");
    if (rc == FT_OK) {
        (*out)->method = method_names[method];
        if (o->ellipsoid)
            ft_dim_result_set_units(*out, "m");
    }
    if (rc == FT_OK && o->starts > 1 && o->only_start < 0 && !has_ring(&s))
        rc = ft_dim_result_warn(*out, "starts: none of the chains is a ring (a closed line); open chains are walked "
                                "from both ends, so the %d starts change nothing", o->starts);
    if (rc == FT_OK && o->ellipsoid == NULL && looks_like_profile(&s))
        rc = ft_dim_result_warn(*out, "profile: every chain is a graph over one axis (x or y only grows or only "
                                "falls along it): if it is a profile (elevation against distance), the %s does not "
                                "measure its roughness (a self-affine graph of D = 2 - H reads near 1 or far off); "
                                "use `fracterra dim profile`", method_names[method]);
    if (rc != FT_OK && *out != NULL) {
        ft_dim_result_free(*out);
        *out = NULL;
    }
    ft_loglog_free(t);
    chain_set_clear(&s);
    return rc;
}
