/* fracterra — unit tests of the ring operators of the contour generation method (Misawa, Chiba & Saito
 * §4.1–4.3): contour/midpoint_displace.c, contour/fourier_descriptor.c, contour/remove_collinear.c.
 * Midpoint displacement: no segment longer than max_seg, original vertices kept in order, every new vertex
 * on the perpendicular through its parent's midpoint at min(d'', l tan theta), theta in range. Fourier:
 * a square (whose Nyquist component is 0) comes back as its resampling exactly; an irregular ring within
 * the Nyquist term's bound; magnitudes |c(k)| kept, components below f0 kept, centroid kept, perimeter
 * under the Parseval/Cauchy-Schwarz bound. Collinear removal: a square with extra points gives its 4
 * corners. Reproducibility and bad input for all three. Expected values come from the geometry, a naive
 * DFT and an arc-length resampling written here.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/contour.h"
#include "ft_test_assert.h"

static const double PI = 3.14159265358979323846;

/* A ring of n vertices around (cx, cy), radius r jittered by +-jitter (fraction), counter-clockwise. */
static ft_chain *blob(size_t n, double cx, double cy, double r, double jitter, uint64_t seed)
{
    ft_chain *c = ft_chain_create(n, 1);
    assert_non_null(c);
    ft_rng *g = ft_rng_create(seed, 7);
    for (size_t i = 0; i < n; i++) {
        double a = 2.0 * PI * (double)i / (double)n, rad = r * (1.0 + jitter * (2.0 * ft_rng_uniform(g) - 1.0));
        assert_int_equal(ft_chain_push(c, cx + rad * cos(a), cy + rad * sin(a)), FT_OK);
    }
    ft_rng_free(g);
    return c;
}

static ft_chain *square(double cx, double cy, double side, size_t per_side, int ccw)
{
    ft_chain *c = ft_chain_create(4 * per_side, 1);
    const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; k++) {
        const double *a = corner[k], *b = corner[(k + 1) % 4];
        for (size_t j = 0; j < per_side; j++) {
            double t = (double)j / (double)per_side;
            double x = a[0] + t * (b[0] - a[0]), y = a[1] + t * (b[1] - a[1]);
            assert_int_equal(ft_chain_push(c, cx + 0.5 * side * x, cy + 0.5 * side * y), FT_OK);
        }
    }
    if (!ccw)
        ft_chain_reverse(c);
    return c;
}

static int same_chain(const ft_chain *a, const ft_chain *b)
{
    if (a->n != b->n || a->closed != b->closed)
        return 0;
    return memcmp(a->x, b->x, a->n * sizeof(double)) == 0 && memcmp(a->y, b->y, a->n * sizeof(double)) == 0;
}

static double seg_len(const ft_chain *c, size_t i)
{
    size_t j = (i + 1) % c->n;
    return hypot(c->x[j] - c->x[i], c->y[j] - c->y[i]);
}

/* ------------------------------------------------------------------------------------------------
 * Midpoint displacement
 * --------------------------------------------------------------------------------------------- */

static ft_chain *displace(const ft_chain *in, double max_seg, double max_off, double tmin, double tmax,
                          uint64_t seed, uint64_t stream)
{
    ft_midpoint_opts o = FT_MIDPOINT_OPTS_DEFAULT;
    o.max_seg = max_seg;
    o.max_offset = max_off;
    o.theta_min = tmin;
    o.theta_max = tmax;
    ft_chain *out = NULL;
    int rc = ft_contour_midpoint_displace(in, &o, seed, stream, &out);
    if (rc != FT_OK)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    return out;
}

typedef struct {
    double max_off, tan_min, tan_max;
    size_t checked;
} split_rule;

/* The vertices strictly between out[ia] and out[ib] (indices mod n) came from splitting the segment
 * ia -> ib: its split vertex projects onto the segment's midpoint and lies min(d'', l tan theta) off it,
 * theta in [theta_min, theta_max]; then both halves are checked the same way. */
static void check_subdivision(const ft_chain *out, size_t ia, size_t ib, split_rule *r)
{
    size_t n = out->n, count = (ib + n - ia) % n;
    if (count <= 1)
        return;
    double ax = out->x[ia], ay = out->y[ia], bx = out->x[ib], by = out->y[ib];
    double dx = bx - ax, dy = by - ay, len = hypot(dx, dy), l = 0.5 * len;
    size_t best = n;
    double best_t = INFINITY, best_off = 0.0;
    for (size_t k = 1; k < count; k++) {
        size_t m = (ia + k) % n;
        double px = out->x[m] - ax, py = out->y[m] - ay;
        double t = (px * dx + py * dy) / (len * len), off = fabs(px * dy - py * dx) / len;
        if (fabs(t - 0.5) < fabs(best_t - 0.5)) {
            best = m;
            best_t = t;
            best_off = off;
        }
    }
    assert_near(best_t, 0.5, 1e-9);
    double tol = 1e-9 * (1.0 + len);
    assert_true(best_off <= r->max_off + tol);
    assert_true(best_off <= l * r->tan_max + tol);
    if (best_off < r->max_off - tol) /* not capped by d'': l tan theta with theta >= theta_min */
        assert_true(best_off >= l * r->tan_min - tol);
    r->checked++;
    check_subdivision(out, ia, best, r);
    check_subdivision(out, best, ib, r);
}

/* Indices in out of the input's vertices, found in order; fails if one is missing. */
static size_t *find_originals(const ft_chain *in, const ft_chain *out)
{
    size_t *idx = malloc(in->n * sizeof *idx), j = 0;
    for (size_t i = 0; i < in->n; i++) {
        while (j < out->n && !(out->x[j] == in->x[i] && out->y[j] == in->y[i]))
            j++;
        assert_true(j < out->n);
        idx[i] = j;
    }
    return idx;
}

static void check_displacement(const ft_chain *in, double max_seg, double max_off, double tmin, double tmax,
                               uint64_t seed)
{
    ft_chain *out = displace(in, max_seg, max_off, tmin, tmax, seed, 3);
    assert_int_equal(out->closed, in->closed);
    size_t nseg = ft_chain_segments(out);
    for (size_t i = 0; i < nseg; i++)
        assert_true(seg_len(out, i) <= max_seg * (1.0 + 1e-12));
    size_t *idx = find_originals(in, out);
    assert_int_equal(idx[0], 0);
    if (!in->closed)
        assert_int_equal(idx[in->n - 1], out->n - 1);
    split_rule r = {max_off, tan(tmin * PI / 180.0), tan(tmax * PI / 180.0), 0};
    size_t nin = ft_chain_segments(in);
    for (size_t i = 0; i < nin; i++)
        check_subdivision(out, idx[i], idx[(i + 1) % in->n], &r);
    assert_int_equal(r.checked, out->n - in->n); /* every new vertex is a checked split vertex */
    assert_true(r.checked > 0);
    free(idx);
    ft_chain_free(out);
}

static void test_midpoint_rules(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 5; seed++) {
        ft_chain *ring = blob(12, 3.0, -2.0, 50.0, 0.3, seed); /* segments ~26 long */
        check_displacement(ring, 4.0, 2.0, 20.0, 40.0, seed);    /* d'' caps the long ones */
        check_displacement(ring, 1.5, 100.0, 0.0, 20.0, seed);   /* l tan theta throughout */
        check_displacement(ring, 6.0, 0.0, 20.0, 40.0, seed);    /* plain subdivision */
        ring->closed = 0;                                        /* the same vertices as an open chain */
        check_displacement(ring, 4.0, 2.0, 20.0, 40.0, seed);
        ft_chain_free(ring);
    }
}

/* theta_min = theta_max: each split vertex is exactly min(d'', l tan theta) off its parent's midpoint. */
static void test_midpoint_fixed_angle(void **state)
{
    (void)state;
    double xs[2] = {0.0, 64.0}, ys[2] = {0.0, 0.0};
    ft_chain *seg = ft_chain_from_arrays(xs, ys, 2, 1, 0);
    ft_chain *out = displace(seg, 10.0, 1e9, 30.0, 30.0, 5, 0);
    /* 64 -> 2 x 36.95 (l = 32, offset 32 tan 30 = 18.475) -> ... halves shrink by 1/(2 cos 30) = 0.577 */
    double len = 64.0;
    size_t levels = 0;
    while (len > 10.0) {
        len = len / (2.0 * cos(30.0 * PI / 180.0));
        levels++;
    }
    assert_int_equal(out->n, ((size_t)1 << levels) + 1);
    double first_off = 32.0 * tan(30.0 * PI / 180.0);
    size_t mid = 0;
    for (size_t i = 0; i < out->n; i++)
        if (fabs(out->x[i] - 32.0) < 1e-12 && fabs(fabs(out->y[i]) - first_off) < 1e-9)
            mid = i;
    assert_true(mid > 0);
    for (size_t i = 0; i + 1 < out->n; i++)
        assert_near(seg_len(out, i), len, 1e-9);
    ft_chain_free(out);
    ft_chain_free(seg);
}

static void test_midpoint_reproducible(void **state)
{
    (void)state;
    ft_chain *ring = blob(20, 0, 0, 30.0, 0.2, 4);
    ft_chain *a = displace(ring, 2.0, 1.0, 20, 40, 11, 5), *b = displace(ring, 2.0, 1.0, 20, 40, 11, 5);
    ft_chain *c = displace(ring, 2.0, 1.0, 20, 40, 12, 5), *d = displace(ring, 2.0, 1.0, 20, 40, 11, 6);
    assert_true(same_chain(a, b));
    assert_false(same_chain(a, c));
    assert_false(same_chain(a, d));
    /* segments already short: the chain is copied */
    ft_chain *e = displace(ring, 1000.0, 1.0, 20, 40, 11, 5);
    assert_true(same_chain(e, ring));
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(c);
    ft_chain_free(d);
    ft_chain_free(e);
    ft_chain_free(ring);
}

static void test_midpoint_bad_input(void **state)
{
    (void)state;
    ft_chain *ring = blob(8, 0, 0, 10.0, 0.0, 1), *out = NULL;
    ft_midpoint_opts o = FT_MIDPOINT_OPTS_DEFAULT;
    assert_error_names(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_INVALID, "max_seg");
    o.max_seg = 1.0;
    o.max_offset = -1.0;
    assert_error_names(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_INVALID, "max_offset");
    o.max_offset = 1.0;
    o.theta_max = 90.0;
    assert_error_names(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_INVALID, "theta_max");
    o.theta_max = 10.0;
    o.theta_min = 20.0;
    assert_error_names(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_INVALID, "theta_max");
    o.theta_min = 0.0;
    assert_error_names(ft_contour_midpoint_displace(ring, NULL, 1, 0, &out), FT_E_INVALID, "max_seg");
    assert_int_equal(ft_contour_midpoint_displace(NULL, &o, 1, 0, &out), FT_E_INVALID);
    ring->x[3] = NAN;
    assert_int_equal(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_NUMERIC);
    ring->x[3] = 0.0;
    ring->n = 2;
    assert_int_equal(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_INVALID);
    ring->n = 8;
    o.max_seg = 1e-9;
    assert_error_names(ft_contour_midpoint_displace(ring, &o, 1, 0, &out), FT_E_INVALID, "max_seg");
    assert_null(out);
    ft_chain_free(ring);
}

/* ------------------------------------------------------------------------------------------------
 * Fourier descriptor
 * --------------------------------------------------------------------------------------------- */

/* n points spaced L/n in arc length along the ring from vertex 0 (cumulative lengths, binary search). */
static void arc_resample(const ft_chain *c, size_t n, double *x, double *y)
{
    size_t m = c->n;
    double *cum = malloc((m + 1) * sizeof *cum);
    cum[0] = 0.0;
    for (size_t i = 0; i < m; i++)
        cum[i + 1] = cum[i] + seg_len(c, i);
    for (size_t j = 0; j < n; j++) {
        double s = cum[m] * (double)j / (double)n;
        size_t lo = 0, hi = m; /* cum[lo] <= s < cum[hi] */
        while (hi - lo > 1) {
            size_t mid = (lo + hi) / 2;
            if (cum[mid] <= s)
                lo = mid;
            else
                hi = mid;
        }
        double t = (s - cum[lo]) / (cum[lo + 1] - cum[lo]);
        size_t b = (lo + 1) % m;
        x[j] = c->x[lo] + t * (c->x[b] - c->x[lo]);
        y[j] = c->y[lo] + t * (c->y[b] - c->y[lo]);
    }
    free(cum);
}

/* Naive DFT c(k) = (1/n) sum_j w(j) exp(-2 pi i jk/n) of w(j) = (Z(j+1) - Z(j)) / h. */
static void descriptor(const double *x, const double *y, size_t n, double h, double *re, double *im)
{
    for (size_t k = 0; k < n; k++) {
        double sr = 0.0, si = 0.0;
        for (size_t j = 0; j < n; j++) {
            size_t j1 = (j + 1) % n;
            double wr = (x[j1] - x[j]) / h, wi = (y[j1] - y[j]) / h;
            double a = -2.0 * PI * (double)((j * k) % n) / (double)n;
            sr += wr * cos(a) - wi * sin(a);
            si += wr * sin(a) + wi * cos(a);
        }
        re[k] = sr / (double)n;
        im[k] = si / (double)n;
    }
}

static ft_chain *randomize(const ft_chain *in, int n, int f0, uint64_t seed, uint64_t stream)
{
    ft_fourier_opts o = FT_FOURIER_OPTS_DEFAULT;
    o.n = n;
    o.f0 = f0;
    ft_chain *out = NULL;
    int rc = ft_contour_fourier_randomize(in, &o, seed, stream, &out);
    if (rc != FT_OK)
        print_error("%s\n", ft_last_error());
    assert_int_equal(rc, FT_OK);
    assert_non_null(out);
    assert_int_equal(out->n, (size_t)n);
    assert_true(out->closed);
    return out;
}

/* A square's unit edge vectors are constant along each side over an even number of edges, so its Nyquist
 * component is 0 and f0 = n/2 gives back the resampled square exactly; 4 vertices or 40, the same. */
static void test_fourier_nyquist_only_square(void **state)
{
    (void)state;
    for (int ccw = 0; ccw <= 1; ccw++)
        for (size_t per_side = 1; per_side <= 10; per_side += 9) {
            ft_chain *sq = square(10.0, 20.0, 4.0, per_side, ccw);
            const size_t n = 64;
            ft_chain *out = randomize(sq, (int)n, (int)n / 2, 3, 0);
            double x[64], y[64];
            arc_resample(sq, n, x, y);
            for (size_t j = 0; j < n; j++) {
                assert_near(out->x[j], x[j], 1e-12);
                assert_near(out->y[j], y[j], 1e-12);
            }
            ft_chain *res = ft_chain_from_arrays(x, y, n, 1, 1);
            assert_near(ft_chain_length(out), ft_chain_length(res), 1e-12);
            assert_near(ft_chain_signed_area(out), ft_chain_signed_area(res), 1e-12);
            if (per_side == 1 || ccw) /* vertex 0 is a corner: every corner is a sample */
                assert_near(ft_chain_length(out), 16.0, 1e-12);
            assert_true(ccw ? ft_chain_signed_area(out) > 15.0 : ft_chain_signed_area(out) < -15.0);
            ft_chain_free(res);
            ft_chain_free(out);
            ft_chain_free(sq);
        }
}

/* An irregular ring with f0 = n/2: only the Nyquist term changes, by at most 2 |c(n/2)| per edge, which
 * alternates in sign, so each vertex moves by at most 2 h |c(n/2)| plus the same for the centroid shift. */
static void test_fourier_nyquist_only_blob(void **state)
{
    (void)state;
    ft_chain *in = blob(37, -5.0, 7.0, 20.0, 0.25, 2);
    const size_t n = 256;
    double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *re = malloc(n * sizeof *re),
           *im = malloc(n * sizeof *im);
    arc_resample(in, n, x, y);
    double h = ft_chain_length(in) / (double)n;
    descriptor(x, y, n, h, re, im);
    double nyq = hypot(re[n / 2], im[n / 2]);
    assert_true(nyq > 0.0);
    for (uint64_t seed = 1; seed <= 3; seed++) {
        ft_chain *out = randomize(in, (int)n, (int)n / 2, seed, 0);
        double bound = 4.0 * h * nyq + 1e-9;
        for (size_t j = 0; j < n; j++)
            assert_true(hypot(out->x[j] - x[j], out->y[j] - y[j]) <= bound);
        double p_res = 0.0;
        for (size_t j = 0; j < n; j++)
            p_res += hypot(x[(j + 1) % n] - x[j], y[(j + 1) % n] - y[j]);
        assert_near(ft_chain_length(out), p_res, 2.0 * n * h * nyq + 1e-9);
        ft_chain_free(out);
    }
    free(x);
    free(y);
    free(re);
    free(im);
    ft_chain_free(in);
}

/* f0 = 8 of n = 128: |c(k)| kept for every k, c(k) kept for |k| < 8, the other phases changed, the
 * vertex mean kept, the perimeter within the Cauchy-Schwarz bound h sqrt(n sum |w|^2) of the kept energy. */
static void test_fourier_magnitudes_centroid_perimeter(void **state)
{
    (void)state;
    const size_t n = 128;
    const int f0 = 8;
    ft_chain *in = blob(23, 100.0, -40.0, 15.0, 0.2, 5);
    double x[128], y[128], re[128], im[128], ore[128], oim[128];
    arc_resample(in, n, x, y);
    double h = ft_chain_length(in) / (double)n;
    descriptor(x, y, n, h, re, im);
    double mx = 0, my = 0, energy = 0;
    for (size_t j = 0; j < n; j++) {
        mx += x[j] / (double)n;
        my += y[j] / (double)n;
        size_t j1 = (j + 1) % n;
        energy += ((x[j1] - x[j]) * (x[j1] - x[j]) + (y[j1] - y[j]) * (y[j1] - y[j])) / (h * h);
    }
    for (uint64_t seed = 1; seed <= 4; seed++) {
        ft_chain *out = randomize(in, (int)n, f0, seed, 9);
        assert_true(ft_chain_signed_area(out) > 0.0);
        descriptor(out->x, out->y, n, h, ore, oim);
        size_t changed = 0;
        for (size_t k = 1; k < n; k++) {
            size_t ka = k <= n / 2 ? k : n - k;
            assert_near(hypot(ore[k], oim[k]), hypot(re[k], im[k]), 1e-10);
            if (ka < (size_t)f0) {
                assert_near(ore[k], re[k], 1e-10);
                assert_near(oim[k], im[k], 1e-10);
            } else if (hypot(ore[k] - re[k], oim[k] - im[k]) > 1e-6 * hypot(re[k], im[k]) + 1e-12) {
                changed++;
            }
        }
        assert_true(changed > 100);
        double cx = 0, cy = 0;
        for (size_t j = 0; j < n; j++) {
            cx += out->x[j] / (double)n;
            cy += out->y[j] / (double)n;
        }
        assert_near(cx, mx, 1e-9);
        assert_near(cy, my, 1e-9);
        assert_true(ft_chain_length(out) <= h * sqrt((double)n * energy) * (1.0 + 1e-12));
        ft_chain_free(out);
    }
    ft_chain_free(in);
}

static void test_fourier_reproducible_and_orientation(void **state)
{
    (void)state;
    ft_chain *in = blob(50, 0, 0, 10.0, 0.3, 8);
    ft_chain *a = randomize(in, 128, 16, 1, 2), *b = randomize(in, 128, 16, 1, 2);
    ft_chain *c = randomize(in, 128, 16, 2, 2), *d = randomize(in, 128, 16, 1, 3);
    assert_true(same_chain(a, b));
    assert_false(same_chain(a, c));
    assert_false(same_chain(a, d));
    ft_chain_reverse(in);
    ft_chain *e = randomize(in, 128, 16, 1, 2);
    assert_true(ft_chain_signed_area(e) < 0.0);
    /* fewer vertices than n: resampled up to n all the same */
    ft_chain *tri = blob(3, 0, 0, 1.0, 0.0, 1);
    ft_chain *f = randomize(tri, 1024, 256, 1, 0);
    assert_near(ft_chain_signed_area(f), ft_chain_signed_area(tri), 1e-2 * ft_chain_signed_area(tri));
    ft_chain_free(a);
    ft_chain_free(b);
    ft_chain_free(c);
    ft_chain_free(d);
    ft_chain_free(e);
    ft_chain_free(f);
    ft_chain_free(tri);
    ft_chain_free(in);
}

static void test_fourier_bad_input(void **state)
{
    (void)state;
    ft_chain *ring = blob(8, 0, 0, 10.0, 0.0, 1), *out = NULL;
    ft_fourier_opts o = FT_FOURIER_OPTS_DEFAULT;
    o.n = 4;
    assert_error_names(ft_contour_fourier_randomize(ring, &o, 1, 0, &out), FT_E_INVALID, "n must");
    o.n = 64;
    o.f0 = 0;
    assert_error_names(ft_contour_fourier_randomize(ring, &o, 1, 0, &out), FT_E_INVALID, "f0");
    o.f0 = 33;
    assert_error_names(ft_contour_fourier_randomize(ring, &o, 1, 0, &out), FT_E_INVALID, "f0");
    o.f0 = 8;
    ring->closed = 0;
    assert_error_names(ft_contour_fourier_randomize(ring, &o, 1, 0, &out), FT_E_INVALID, "ring");
    ring->closed = 1;
    ring->y[2] = INFINITY;
    assert_int_equal(ft_contour_fourier_randomize(ring, &o, 1, 0, &out), FT_E_NUMERIC);
    for (size_t i = 0; i < ring->n; i++)
        ring->x[i] = ring->y[i] = 1.0; /* zero perimeter */
    assert_int_equal(ft_contour_fourier_randomize(ring, &o, 1, 0, &out), FT_E_NUMERIC);
    assert_null(out);
    ft_chain_free(ring);
}

/* ------------------------------------------------------------------------------------------------
 * Collinear removal
 * --------------------------------------------------------------------------------------------- */

static void test_collinear_square(void **state)
{
    (void)state;
    /* side 4 with 5 points per side, starting from the middle of the bottom side */
    ft_chain *sq = square(1.0, 2.0, 4.0, 5, 1);
    ft_chain *rot = ft_chain_create(sq->n, 1);
    for (size_t i = 0; i < sq->n; i++)
        ft_chain_push(rot, sq->x[(i + 2) % sq->n], sq->y[(i + 2) % sq->n]);
    ft_chain *out = NULL;
    assert_int_equal(ft_contour_remove_collinear(rot, 1.0, &out), FT_OK);
    assert_int_equal(out->n, 4);
    const double want[4][2] = {{3, 0}, {3, 4}, {-1, 4}, {-1, 0}}; /* the input's cyclic order from index 0 */
    for (size_t i = 0; i < 4; i++) {
        assert_near(out->x[i], want[i][0], 0.0);
        assert_near(out->y[i], want[i][1], 0.0);
    }
    ft_chain_free(out);
    /* threshold 0 keeps everything */
    assert_int_equal(ft_contour_remove_collinear(rot, 0.0, &out), FT_OK);
    assert_true(same_chain(out, rot));
    ft_chain_free(out);
    /* a threshold above every angle still keeps a triangle */
    assert_int_equal(ft_contour_remove_collinear(rot, 179.0, &out), FT_OK);
    assert_int_equal(out->n, 3);
    ft_chain_free(out);
    ft_chain_free(rot);
    ft_chain_free(sq);
}

/* A regular 36-gon turns 10 degrees per vertex: a 5 degree threshold keeps it; a zig-zag open chain keeps
 * its turns and end points and loses its collinear points and duplicates. */
static void test_collinear_angles_and_open_chains(void **state)
{
    (void)state;
    ft_chain *poly = blob(36, 0, 0, 5.0, 0.0, 1), *out = NULL;
    assert_int_equal(ft_contour_remove_collinear(poly, 5.0, &out), FT_OK);
    assert_true(same_chain(out, poly));
    ft_chain_free(out);
    double xs[] = {0, 1, 2, 2, 3, 4, 4, 4, 4.5};
    double ys[] = {0, 0, 0, 0, 0, 0, 1, 2, 2.5};
    ft_chain *zig = ft_chain_from_arrays(xs, ys, 9, 1, 0);
    assert_int_equal(ft_contour_remove_collinear(zig, 1.0, &out), FT_OK);
    const double wx[] = {0, 4, 4, 4.5}, wy[] = {0, 0, 2, 2.5};
    assert_int_equal(out->n, 4);
    assert_false(out->closed);
    for (size_t i = 0; i < 4; i++) {
        assert_near(out->x[i], wx[i], 0.0);
        assert_near(out->y[i], wy[i], 0.0);
    }
    ft_chain_free(out);
    assert_error_names(ft_contour_remove_collinear(zig, -1.0, &out), FT_E_INVALID, "angle");
    assert_error_names(ft_contour_remove_collinear(zig, NAN, &out), FT_E_INVALID, "angle");
    assert_int_equal(ft_contour_remove_collinear(NULL, 1.0, &out), FT_E_INVALID);
    assert_null(out);
    ft_chain_free(zig);
    ft_chain_free(poly);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_midpoint_rules),
        cmocka_unit_test(test_midpoint_fixed_angle),
        cmocka_unit_test(test_midpoint_reproducible),
        cmocka_unit_test(test_midpoint_bad_input),
        cmocka_unit_test(test_fourier_nyquist_only_square),
        cmocka_unit_test(test_fourier_nyquist_only_blob),
        cmocka_unit_test(test_fourier_magnitudes_centroid_perimeter),
        cmocka_unit_test(test_fourier_reproducible_and_orientation),
        cmocka_unit_test(test_fourier_bad_input),
        cmocka_unit_test(test_collinear_square),
        cmocka_unit_test(test_collinear_angles_and_open_chains),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
