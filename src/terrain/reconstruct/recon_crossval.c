/* fracterra — recon_crossval.c: the fractal method's temperature from the data's own prediction residuals
 * (cross-validation, the geostatistician's check of a variogram's sill; docs/terrain-reconstruct.md,
 * "Temperature from the data's residuals").
 *
 * Under the prior at temperature T, the error of the T = 0 prediction u* at a node the data do not fix is
 * Gaussian with variance T [lambda A_ff^-1]_ii (recon_perturb.c): the residual variance scales with T, the
 * rest is the prior's geometry. So hold out a part H of the data, predict them from the rest (u*, T = 0),
 * and draw one sample delta of the prior conditioned on the rest at T = 1 (recon_perturb.c):
 *
 *     T_cv = mean_H (d_i - u*_i)² / mean_H delta_i²,
 *
 * the temperature at which the prior's prediction errors are as large as the data's. It reads the
 * amplitude of the terrain at the distances the reconstruction has to fill, between the data, instead of
 * extrapolating a variogram line from the data's pairs down to one cell.
 *
 * Which data are held out: the remaining data must leave the same gaps as the whole set, or the residuals
 * would measure larger gaps than the reconstruction fills. R is the data's covering radius (the largest
 * distance from a cell to its nearest datum, at most FT_RECON_CV_RADIUS_MAX mean spacings); data are taken
 * in a seeded random order and held out when every cell within R of them keeps another datum within R,
 * until half the data are held out. On a random design that is a random half; on a regular lattice with
 * extra points it is the extra points (a lattice node cannot go without opening a gap wider than R).
 *
 * Cost: on grids larger than FT_RECON_CV_SIDE² the estimate runs on the central window of that size (a
 * T = 0 solve and a sample of FT_RECON_CV_SIDE² nodes: 1/16 of a 1024² reconstruction's).
 *
 * EXPERIMENT of session 8 (engineer 14v), reverted by the next commit: reached only with the environment
 * variable FT_CV set (reconstruct.c), it printed the estimators to stderr (FT_CV=0: T unchanged; FT_CV_INC:
 * the increment form; FT_MM=hmax, FT_MM_ABS: the structure-function matches; FT_CV_RANDOM: a random half
 * held out). Measured in docs/terrain-reconstruct.md ("Temperature from the data's own residuals"): none
 * of them separates SRA-lattice data from exact fBm in the needed direction.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

#include "internal.h"
#include "terrain/reconstruct/reconstruct_internal.h"

#define FT_RECON_STREAM_CV UINT64_C(0x7265637600000000)
#define FAR 1e20

/* Squared Euclidean distance transform along one line (Felzenszwalb & Huttenlocher 2012, "Distance
 * transforms of sampled functions", the lower envelope of parabolas): d[q] = min_p (q - p)² + f[p]. */
static void edt_line(const double *f, size_t n, double *d, size_t *v, double *z)
{
    size_t k = 0;
    v[0] = 0;
    z[0] = -HUGE_VAL;
    z[1] = HUGE_VAL;
    for (size_t q = 1; q < n; q++) {
        /* z[0] = -inf: the envelope never loses its first parabola's left end */
        double s;
        for (;;) {
            double p = (double)v[k];
            s = ((f[q] + (double)q * (double)q) - (f[v[k]] + p * p)) / (2.0 * (double)q - 2.0 * p);
            if (s > z[k])
                break;
            k--;
        }
        k++;
        v[k] = q;
        z[k] = s;
        z[k + 1] = HUGE_VAL;
    }
    k = 0;
    for (size_t q = 0; q < n; q++) {
        while (z[k + 1] < (double)q)
            k++;
        double dq = (double)q - (double)v[k];
        d[q] = dq * dq + f[v[k]];
    }
}

/* The largest squared distance from a cell of the nx x ny window to its nearest fixed node. */
static int covering_radius2(const uint8_t *fixed, size_t nx, size_t ny, double *r2)
{
    size_t m = nx > ny ? nx : ny, n = nx * ny;
    double *g = ft_malloc(n * sizeof *g), *f = ft_malloc(m * sizeof *f), *d = ft_malloc(m * sizeof *d);
    double *z = ft_malloc((m + 1) * sizeof *z);
    size_t *v = ft_malloc(m * sizeof *v);
    int rc = g && f && d && z && v ? FT_OK : FT_E_NOMEM;
    if (rc == FT_OK) {
        for (size_t x = 0; x < nx; x++) {
            for (size_t y = 0; y < ny; y++)
                f[y] = fixed[y * nx + x] ? 0.0 : FAR;
            edt_line(f, ny, d, v, z);
            for (size_t y = 0; y < ny; y++)
                g[y * nx + x] = d[y];
        }
        double worst = 0.0;
        for (size_t y = 0; y < ny; y++) {
            edt_line(g + y * nx, nx, d, v, z);
            for (size_t x = 0; x < nx; x++)
                worst = d[x] > worst ? d[x] : worst;
        }
        *r2 = worst;
    }
    free(g);
    free(f);
    free(d);
    free(z);
    free(v);
    return rc;
}

typedef struct {
    uint64_t key;
    size_t node;
} order_item;

static int by_key(const void *a, const void *b)
{
    const order_item *x = a, *y = b;
    if (x->key != y->key)
        return x->key < y->key ? -1 : 1;
    return x->node < y->node ? -1 : x->node > y->node;
}

/* Marks in held[] the data held out (see the header comment); returns their count, or (size_t)-1 if out
 * of memory. */
static size_t hold_out(const uint8_t *fixed, size_t nx, size_t ny, uint64_t seed, uint8_t *held, double *radius2)
{
    size_t n = nx * ny, ndata = 0;
    for (size_t i = 0; i < n; i++)
        ndata += fixed[i] != 0;
    double r2 = 0.0;
    if (covering_radius2(fixed, nx, ny, &r2) != FT_OK)
        return (size_t)-1;
    double spacing = sqrt((double)n / (double)ndata), rmax = FT_RECON_CV_RADIUS_MAX * spacing;
    if (r2 > rmax * rmax || getenv("FT_CV_RANDOM"))
        r2 = floor(rmax * rmax);
    long r = (long)floor(sqrt(r2) + 1e-9);
    *radius2 = r2;
    uint32_t *cnt = ft_calloc(n, sizeof *cnt);
    order_item *ord = ft_malloc(ndata * sizeof *ord);
    if (cnt == NULL || ord == NULL) {
        free(cnt);
        free(ord);
        return (size_t)-1;
    }
    long NX = (long)nx, NY = (long)ny;
    size_t k = 0;
    for (size_t i = 0; i < n; i++) {
        if (!fixed[i])
            continue;
        ord[k].key = ft_rng_mix(ft_rng_mix(seed, FT_RECON_STREAM_CV), (uint64_t)i);
        ord[k++].node = i;
        long X = (long)(i % nx), Y = (long)(i / nx);
        for (long dy = -r; dy <= r; dy++)
            for (long dx = -r; dx <= r; dx++)
                if ((double)(dx * dx + dy * dy) <= r2 && X + dx >= 0 && X + dx < NX && Y + dy >= 0 && Y + dy < NY)
                    cnt[(size_t)(Y + dy) * nx + (size_t)(X + dx)]++;
    }
    qsort(ord, ndata, sizeof *ord, by_key);
    size_t nheld = 0;
    for (size_t j = 0; j < ndata && 2 * (nheld + 1) <= ndata; j++) {
        size_t i = ord[j].node;
        long X = (long)(i % nx), Y = (long)(i / nx);
        int ok = 1;
        for (long dy = -r; dy <= r && ok; dy++)
            for (long dx = -r; dx <= r; dx++)
                if ((double)(dx * dx + dy * dy) <= r2 && X + dx >= 0 && X + dx < NX && Y + dy >= 0 && Y + dy < NY &&
                    cnt[(size_t)(Y + dy) * nx + (size_t)(X + dx)] < 2) {
                    ok = 0;
                    break;
                }
        if (!ok)
            continue;
        for (long dy = -r; dy <= r; dy++)
            for (long dx = -r; dx <= r; dx++)
                if ((double)(dx * dx + dy * dy) <= r2 && X + dx >= 0 && X + dx < NX && Y + dy >= 0 && Y + dy < NY)
                    cnt[(size_t)(Y + dy) * nx + (size_t)(X + dx)]--;
        held[i] = 1;
        nheld++;
    }
    free(cnt);
    free(ord);
    return nheld;
}

/* The window's problem: p's nodes in [x0, x0 + nx) x [y0, y0 + ny), the held-out data free. */
static ft_recon_problem *window_problem(const ft_recon_problem *p, size_t x0, size_t y0, size_t nx, size_t ny)
{
    ft_recon_problem *q = ft_recon_problem_create(nx, ny, p->nthreads);
    if (q == NULL)
        return NULL;
    for (size_t y = 0; y < ny; y++)
        for (size_t x = 0; x < nx; x++) {
            size_t i = (y0 + y) * p->nx + x0 + x, j = y * nx + x;
            q->d[j] = p->d[i];
            q->lev[0].fixed[j] = p->lev[0].fixed[i];
        }
    return q;
}

int ft_recon_temperature_cv(const ft_recon_problem *p, double lambda, double tension, double H, uint64_t seed,
                            double *T, size_t *nheld)
{
    *T = 0.0;
    *nheld = 0;
    size_t nx = p->nx < FT_RECON_CV_SIDE ? p->nx : FT_RECON_CV_SIDE;
    size_t ny = p->ny < FT_RECON_CV_SIDE ? p->ny : FT_RECON_CV_SIDE;
    for (size_t i = 0; i < p->nx * p->ny; i++)
        if (p->lev[0].c[i] > 0.0f)
            return FT_OK; /* soft data: their misfit is not a prediction error */
    ft_recon_problem *q = window_problem(p, (p->nx - nx) / 2, (p->ny - ny) / 2, nx, ny);
    size_t n = nx * ny, ndata = 0;
    uint8_t *held = q ? ft_calloc(n, 1) : NULL;
    float *ustar = ft_calloc(n, sizeof *ustar), *u = ft_malloc(n * sizeof *u);
    int rc = q && held && ustar && u ? FT_OK : FT_E_NOMEM;
    for (size_t i = 0; rc == FT_OK && i < n; i++)
        ndata += q->lev[0].fixed[i] != 0;
    size_t m = 0;
    double r2 = 0.0;
    if (rc == FT_OK && ndata >= 2 * FT_RECON_CV_MIN) {
        m = hold_out(q->lev[0].fixed, nx, ny, seed, held, &r2);
        if (m == (size_t)-1)
            rc = FT_E_NOMEM;
    }
    if (rc == FT_OK && m >= FT_RECON_CV_MIN) {
        for (size_t i = 0; i < n; i++)
            if (held[i])
                q->lev[0].fixed[i] = 0;
        q->prior_H = H;
        rc = ft_recon_hierarchy(q, lambda, tension);
        if (rc == FT_OK)
            rc = ft_recon_solve(q, ustar, NULL, NULL);
        if (rc == FT_OK)
            rc = ft_recon_fractal(q, ustar, 1.0, ft_rng_mix(seed, FT_RECON_STREAM_CV), u, NULL);
        double vd = 0.0, vp = 0.0, A = 0.0, B = 0.0, V = 0.0;
        long r = (long)floor(sqrt(r2) + 1e-9), NX = (long)nx, NY = (long)ny;
        for (size_t i = 0; rc == FT_OK && i < n; i++)
            if (held[i]) {
                double e = (double)q->d[i] - (double)ustar[i], s = (double)u[i] - (double)ustar[i];
                vd += e * e;
                vp += s * s;
                long X = (long)(i % nx), Y = (long)(i / nx);
                for (long dy = -r; dy <= r; dy++)
                    for (long dx = -r; dx <= r; dx++) {
                        if ((double)(dx * dx + dy * dy) > r2 || X + dx < 0 || X + dx >= NX || Y + dy < 0 || Y + dy >= NY)
                            continue;
                        size_t j = (size_t)(Y + dy) * nx + (size_t)(X + dx);
                        if (!q->lev[0].fixed[j])
                            continue;
                        double a = (double)q->d[i] - (double)q->d[j], b = (double)ustar[i] - (double)q->d[j];
                        A += a * a;
                        B += b * b;
                        V += s * s;
                    }
            }
        if (rc == FT_OK && vp > 0.0 && vd > 0.0) {
            *T = vd / vp;
            *nheld = m;
            fprintf(stderr, "CVINC %.6g\n", (A - B) / V);
            if (getenv("FT_CV_INC"))
                *T = (A - B) / V;
        }
    }
    ft_recon_problem_free(q);
    free(held);
    free(ustar);
    free(u);
    return rc;
}

/* Mean squared increment at lags 1..hmax along rows and columns of an nx x ny field. */
static void msq_increments(const float *u, size_t nx, size_t ny, int hmax, double *s)
{
    for (int h = 1; h <= hmax; h++) {
        double sum = 0.0;
        size_t c = 0, H = (size_t)h;
        for (size_t y = 0; y < ny; y++)
            for (size_t x = 0; x < nx; x++) {
                double z = u[y * nx + x];
                if (x + H < nx) {
                    double d = u[y * nx + x + H] - z;
                    sum += d * d;
                    c++;
                }
                if (y + H < ny) {
                    double d = u[(y + H) * nx + x] - z;
                    sum += d * d;
                    c++;
                }
            }
        s[h] = c ? sum / (double)c : 0.0;
    }
}

int ft_recon_temperature_mm(const ft_recon_problem *p, double lambda, double tension, double H, uint64_t seed,
                            const double *target, int hmax, double *T)
{
    *T = 0.0;
    size_t nx = p->nx < FT_RECON_CV_SIDE ? p->nx : FT_RECON_CV_SIDE;
    size_t ny = p->ny < FT_RECON_CV_SIDE ? p->ny : FT_RECON_CV_SIDE;
    ft_recon_problem *q = window_problem(p, (p->nx - nx) / 2, (p->ny - ny) / 2, nx, ny);
    size_t n = nx * ny;
    float *ustar = ft_calloc(n, sizeof *ustar), *u = ft_malloc(n * sizeof *u);
    int rc = q && ustar && u ? FT_OK : FT_E_NOMEM;
    if (rc == FT_OK) {
        q->prior_H = H;
        rc = ft_recon_hierarchy(q, lambda, tension);
    }
    if (rc == FT_OK)
        rc = ft_recon_solve(q, ustar, NULL, NULL);
    if (rc == FT_OK)
        rc = ft_recon_fractal(q, NULL, 1.0, ft_rng_mix(seed, FT_RECON_STREAM_CV), u, NULL);
    if (rc == FT_OK) {
        for (size_t i = 0; i < n; i++)
            u[i] -= ustar[i];
        double su[64], sd[64], num = 0.0, den = 0.0;
        msq_increments(ustar, nx, ny, hmax, su);
        msq_increments(u, nx, ny, hmax, sd);
        for (int h = 1; h <= hmax; h++) {
            double w = 1.0 / (target[h] * target[h]);
            num += w * sd[h] * (target[h] - su[h]);
            den += w * sd[h] * sd[h];
            if (getenv("FT_MM_V"))
                fprintf(stderr, "  h %d target %.5g ustar %.5g delta1 %.5g\n", h, target[h], su[h], sd[h]);
        }
        *T = den > 0.0 ? num / den : 0.0;
        if (getenv("FT_MM_ABS")) {
            /* mean |dz| matching: sum_h M_h(T) / t_h = hmax, M_h(T) = mean |a + sqrt(T) b| */
            const double *ta = target + 32;
            double lo = 1e-8, hi = 1e3;
            for (int it = 0; it < 60; it++) {
                double mid = sqrt(lo * hi), st = sqrt(mid), f = 0.0;
                for (int h = 1; h <= hmax; h++) {
                    size_t H2 = (size_t)h, c = 0;
                    double sum = 0.0;
                    for (size_t y = 0; y < ny; y++)
                        for (size_t x = 0; x < nx; x++) {
                            size_t i = y * nx + x;
                            if (x + H2 < nx) {
                                sum += fabs((double)ustar[i + H2] - ustar[i] + st * ((double)u[i + H2] - u[i]));
                                c++;
                            }
                            if (y + H2 < ny) {
                                sum += fabs((double)ustar[i + H2 * nx] - ustar[i] + st * ((double)u[i + H2 * nx] - u[i]));
                                c++;
                            }
                        }
                    f += sum / (double)c / ta[h];
                }
                if (f > (double)hmax)
                    hi = mid;
                else
                    lo = mid;
            }
            *T = sqrt(lo * hi);
        }
    }
    ft_recon_problem_free(q);
    free(ustar);
    free(u);
    return rc;
}
