/* fracterra — terrain/clarke/clarke_simulate.c: inverting Clarke's scale-based model, z = T + cF + H.
 *
 * Clarke, K. C. (1987). Scale-based simulation of topography. Proceedings of Auto-Carto 8, 680-688.
 * The output grid has K times the cells of the fitted grid along each axis over the same extent (refine),
 * times E along each axis from the same upper-left corner (extent). Two inverse real FFTs of its size
 * build the two parts, as in the paper:
 *  - H: each kept wave a cos(theta) + b sin(theta) of the fitted grid, theta = 2 pi (k col/nx + l row/ny),
 *    placed at bin (k E, l E) as (a - i b)/2 with the phase shift that moves the fitted grid's cell
 *    centres onto the new ones;
 *  - F (eqs. xiii-xv): every other wave of the new grid but the DC term, amplitude sqrt(P(wavelength)),
 *    P from the log-log regression (or, model->noise = spectrum, from the DEM's measured radial spectrum:
 *    clarke_spectrum.c), divided by E² since the harmonic spacing shrinks E times per axis,
 *    and a uniform random phase (one seeded stream per spectrum row, so the cells do not depend on the
 *    thread count). Wavelengths beyond the fitted extent get the power at that extent, not an
 *    extrapolation. Amplitudes follow the regression exactly (eq. xiv gives them from P; Clarke kept the
 *    empirical signs, here phases are random).
 * F then loses its own least-squares plane (T is the model's only plane). T is evaluated at the new
 * cell centres. With the measured spectrum c = 1 (F has the DEM's variogram: clarke_variogram.c); with
 * the power law, over the cells covering the fitted extent, c solves
 * var(T + H + cF) = sd² (the positive root of the quadratic, 0 if there is none) and a constant shift
 * makes the mean the original's: Clarke scaled F "to make the new surface mean and variance similar to
 * the original".
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/clarke/clarke_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fft/fft.h"
#include "internal.h"

#define SIM_MAX_REFINE 64
#define SIM_MAX_EXTENT 16
#define SIM_MAX_CELLS ((size_t)1 << 28)

typedef struct {
    size_t nx, ny;        /* output size */
    size_t hx, rs;        /* half-spectrum width, in-place row stride */
    int k, e;             /* refine, extent */
    double gt[6];
    clarke_frame frame;   /* of the output grid */
    double max_wavelength; /* the fitted grid's longest wavelength: F's power is flat beyond it */
} sim_grid;

/* ---- checks ---- */

static int check_harmonic(const ft_clarke_model *m, size_t i)
{
    const ft_clarke_harmonic *h = &m->harmonics[i];
    if (h->k < 0 || (size_t)h->k > m->nx / 2)
        return ft_error(FT_E_INVALID, "Clarke model: harmonic %zu has k = %d, outside [0,%zu]", i, h->k, m->nx / 2);
    if ((size_t)abs(h->l) > m->ny / 2)
        return ft_error(FT_E_INVALID, "Clarke model: harmonic %zu has l = %d, outside [-%zu,%zu]", i, h->l,
                        m->ny / 2, m->ny / 2);
    if (h->k == 0 && h->l == 0)
        return ft_error(FT_E_INVALID, "Clarke model: harmonic %zu is the mean (k = l = 0)", i);
    if (!isfinite(h->a) || !isfinite(h->b))
        return ft_error(FT_E_INVALID, "Clarke model: harmonic %zu has a non-finite coefficient", i);
    return FT_OK;
}

static int check_model(const ft_clarke_model *m)
{
    if (m->nx < 2 || m->ny < 2 || m->nx > (size_t)INT32_MAX || m->ny > (size_t)INT32_MAX)
        return ft_error(FT_E_INVALID, "Clarke model: the grid size %zu x %zu is out of range", m->nx, m->ny);
    const double v[] = {m->beta0, m->beta1, m->beta2, m->mean, m->sd, m->slope, m->intercept};
    const char *names[] = {"beta0", "beta1", "beta2", "mean", "sd", "slope", "intercept"};
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++)
        if (!isfinite(v[i]))
            return ft_error(FT_E_INVALID, "Clarke model: %s is not finite", names[i]);
    if (m->sd < 0.0)
        return ft_error(FT_E_INVALID, "Clarke model: sd must be >= 0, got %g", m->sd);
    if (m->nharmonics > 0 && m->harmonics == NULL)
        return ft_error(FT_E_INVALID, "Clarke model: %zu harmonics announced, none given", m->nharmonics);
    for (size_t i = 0; i < m->nharmonics; i++) {
        int rc = check_harmonic(m, i);
        if (rc != FT_OK)
            return rc;
    }
    return clarke_check_spectrum(m);
}

static int check_opts(const ft_clarke_model *m, const ft_clarke_sim_opts *o, ft_grid **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "Clarke simulation: no output pointer given");
    *out = NULL;
    if (m == NULL)
        return ft_error(FT_E_INVALID, "Clarke simulation: no model given");
    if (o->refine < 1 || o->refine > SIM_MAX_REFINE)
        return ft_error(FT_E_INVALID, "Clarke simulation: refine must be in [1,%d], got %d", SIM_MAX_REFINE,
                        o->refine);
    if (o->extent < 1 || o->extent > SIM_MAX_EXTENT)
        return ft_error(FT_E_INVALID, "Clarke simulation: extent must be in [1,%d], got %d", SIM_MAX_EXTENT,
                        o->extent);
    int rc = check_model(m);
    if (rc != FT_OK)
        return rc;
    size_t f = (size_t)o->refine * (size_t)o->extent;
    if (m->nx * f > SIM_MAX_CELLS / (m->ny * f))
        return ft_error(FT_E_INVALID, "Clarke simulation: %zu x %zu cells times %zu per axis exceed %zu cells",
                        m->nx, m->ny, f, SIM_MAX_CELLS);
    return FT_OK;
}

static int sim_grid_init(const ft_clarke_model *m, const ft_clarke_sim_opts *o, sim_grid *s)
{
    s->k = o->refine;
    s->e = o->extent;
    s->nx = m->nx * (size_t)(s->k * s->e);
    s->ny = m->ny * (size_t)(s->k * s->e);
    s->hx = s->nx / 2 + 1;
    s->rs = ft_fft_real_stride(s->nx);
    memcpy(s->gt, m->gt, sizeof s->gt);
    for (int i = 1; i < 6; i++)
        if (i != 3)
            s->gt[i] /= s->k;
    clarke_frame fitted;
    int rc = clarke_frame_init(m->gt, m->nx, m->ny, &fitted);
    if (rc == FT_OK)
        rc = clarke_frame_init(s->gt, s->nx, s->ny, &s->frame);
    s->max_wavelength = fmax(fitted.lx, fitted.ly);
    return rc;
}

/* ---- spectra ---- */

static int is_edge_column(const sim_grid *s, size_t kx)
{
    return kx == 0 || (s->nx % 2 == 0 && kx == s->nx / 2);
}

static size_t row_index(const sim_grid *s, long l)
{
    long ny = (long)s->ny;
    return (size_t)(((l % ny) + ny) % ny);
}

/* Adds the wave 2 Re(c e^{i theta}) at bin (kx, l) of the output spectrum, keeping the edge columns
 * Hermitian (their bins l and -l are both stored). */
static void add_wave(const sim_grid *s, fftw_complex *spec, size_t kx, long l, double cr, double ci)
{
    size_t ky = row_index(s, l);
    clarke_bin kind = clarke_bin_kind(kx, ky, s->nx, s->ny);
    fftw_complex *x = &spec[ky * s->hx + kx];
    if (kind == CLARKE_BIN_SELF) {
        (*x)[0] += 2.0 * cr;
        return;
    }
    if (kind == CLARKE_BIN_SKIP) { /* the twin of a stored bin: add the conjugate there */
        ky = row_index(s, -l);
        x = &spec[ky * s->hx + kx];
        ci = -ci;
    }
    (*x)[0] += cr;
    (*x)[1] += ci;
    if (is_edge_column(s, kx)) {
        fftw_complex *twin = &spec[row_index(s, -clarke_signed_l(ky, s->ny)) * s->hx + kx];
        (*twin)[0] = (*x)[0];
        (*twin)[1] = -(*x)[1];
    }
}

/* The bin of harmonic h on the output grid, and its coefficient there. */
static void harmonic_bin(const ft_clarke_model *m, const sim_grid *s, const ft_clarke_harmonic *h, size_t *kx,
                         long *l, double *cr, double *ci)
{
    double shift = 0.5 / s->k - 0.5; /* fitted-grid column of output cell 0's centre */
    double phi = 2.0 * M_PI * (h->k * shift / (double)m->nx + h->l * shift / (double)m->ny);
    double re = 0.5 * h->a, im = -0.5 * h->b;
    *cr = re * cos(phi) - im * sin(phi);
    *ci = re * sin(phi) + im * cos(phi);
    *kx = (size_t)h->k * (size_t)s->e;
    *l = (long)h->l * s->e;
}

static void fill_harmonics(const ft_clarke_model *m, const sim_grid *s, fftw_complex *spec)
{
    for (size_t i = 0; i < m->nharmonics; i++) {
        size_t kx;
        long l;
        double cr, ci;
        harmonic_bin(m, s, &m->harmonics[i], &kx, &l, &cr, &ci);
        add_wave(s, spec, kx, l, cr, ci);
    }
}

static double fractal_amplitude(const ft_clarke_model *m, const sim_grid *s, size_t kx, size_t ky)
{
    double wl = clarke_wavelength(&s->frame, (int)kx, clarke_signed_l(ky, s->ny));
    double p = clarke_noise_power(m, fmin(wl, s->max_wavelength)) / ((double)s->e * (double)s->e);
    return isfinite(p) && p > 0.0 ? sqrt(p) : 0.0;
}

/* One spectrum row of F from its own random stream. */
static int fill_fractal_row(const ft_clarke_model *m, const sim_grid *s, uint64_t seed, size_t ky,
                            fftw_complex *row)
{
    ft_rng *r = ft_rng_create(seed, ky);
    if (r == NULL)
        return ft_last_error_code();
    for (size_t kx = 0; kx < s->hx; kx++) {
        double u = ft_rng_uniform(r);
        clarke_bin kind = clarke_bin_kind(kx, ky, s->nx, s->ny);
        double amp = kind == CLARKE_BIN_SKIP ? 0.0 : fractal_amplitude(m, s, kx, ky);
        if (kind == CLARKE_BIN_SELF) {
            row[kx][0] = u < 0.5 ? amp : -amp;
            row[kx][1] = 0.0;
        } else {
            row[kx][0] = 0.5 * amp * cos(2.0 * M_PI * u);
            row[kx][1] = 0.5 * amp * sin(2.0 * M_PI * u);
        }
    }
    ft_rng_free(r);
    return FT_OK;
}

/* Copies the conjugates of the edge columns' l > 0 bins onto their l < 0 twins. */
static void fractal_edges(const sim_grid *s, fftw_complex *spec)
{
    for (size_t kx = 0; kx < s->hx; kx++) {
        if (!is_edge_column(s, kx))
            continue;
        for (size_t ky = 0; ky < s->ny; ky++) {
            if (clarke_bin_kind(kx, ky, s->nx, s->ny) != CLARKE_BIN_SKIP || (kx == 0 && ky == 0))
                continue;
            const fftw_complex *src = &spec[row_index(s, -clarke_signed_l(ky, s->ny)) * s->hx + kx];
            spec[ky * s->hx + kx][0] = (*src)[0];
            spec[ky * s->hx + kx][1] = -(*src)[1];
        }
    }
}

/* Zeroes F at the bins H occupies. */
static void fractal_clear_harmonics(const ft_clarke_model *m, const sim_grid *s, fftw_complex *spec)
{
    for (size_t i = 0; i < m->nharmonics; i++) {
        size_t kx;
        long l;
        double cr, ci;
        harmonic_bin(m, s, &m->harmonics[i], &kx, &l, &cr, &ci);
        memset(&spec[row_index(s, l) * s->hx + kx], 0, sizeof(fftw_complex));
        memset(&spec[row_index(s, -l) * s->hx + kx], 0, sizeof(fftw_complex));
    }
}

static int fill_fractal(const ft_clarke_model *m, const sim_grid *s, uint64_t seed, fftw_complex *spec)
{
    int rc = FT_OK;
    const long ny = (long)s->ny;
#pragma omp parallel for schedule(static)
    for (long ky = 0; ky < ny; ky++) {
        int r = fill_fractal_row(m, s, seed, (size_t)ky, spec + (size_t)ky * s->hx);
        if (r != FT_OK) {
#pragma omp critical(ft_clarke_sim)
            rc = r;
        }
    }
    if (rc != FT_OK)
        return rc;
    fractal_edges(s, spec);
    fractal_clear_harmonics(m, s, spec);
    return FT_OK;
}

/* Removes F's least-squares plane over the whole output grid: F is the scale-independent part of the
 * DETRENDED surface, and its longest waves would otherwise correlate with T (a wave of one cycle across
 * the grid is 78 % correlated with a plane) and make var(T + H + cF) a poor guide to c. On a full grid
 * the centred column and row indices are orthogonal, so the two slopes are independent sums. */
static void detrend_fractal(const sim_grid *s, double *f)
{
    double cm = 0.5 * ((double)s->nx - 1.0), rm = 0.5 * ((double)s->ny - 1.0);
    double sc = 0.0, sr = 0.0, scc = 0.0, srr = 0.0;
    for (size_t row = 0; row < s->ny; row++) {
        double dr = (double)row - rm, rowsum = 0.0;
        for (size_t col = 0; col < s->nx; col++) {
            double v = f[row * s->rs + col];
            rowsum += v;
            sc += v * ((double)col - cm);
        }
        sr += rowsum * dr;
        srr += dr * dr * (double)s->nx;
    }
    for (size_t col = 0; col < s->nx; col++)
        scc += ((double)col - cm) * ((double)col - cm) * (double)s->ny;
    double bc = scc > 0.0 ? sc / scc : 0.0, br = srr > 0.0 ? sr / srr : 0.0;
    for (size_t row = 0; row < s->ny; row++)
        for (size_t col = 0; col < s->nx; col++)
            f[row * s->rs + col] -= bc * ((double)col - cm) + br * ((double)row - rm);
}

/* ---- T, statistics and assembly ---- */

typedef struct {
    double x0, y0, b0; /* T = b0 + beta1 (x - x0) + beta2 (y - y0), (x0, y0) the fitted grid's centre */
} trend_eval;

static void trend_init(const ft_clarke_model *m, trend_eval *t)
{
    t->x0 = m->gt[0] + 0.5 * (double)m->nx * m->gt[1] + 0.5 * (double)m->ny * m->gt[2];
    t->y0 = m->gt[3] + 0.5 * (double)m->nx * m->gt[4] + 0.5 * (double)m->ny * m->gt[5];
    t->b0 = m->beta0 + m->beta1 * t->x0 + m->beta2 * t->y0;
}

static double trend_at(const ft_clarke_model *m, const sim_grid *s, const trend_eval *t, size_t col, size_t row)
{
    double dc = (double)col + 0.5, dr = (double)row + 0.5;
    double dx = s->gt[0] + dc * s->gt[1] + dr * s->gt[2] - t->x0;
    double dy = s->gt[3] + dc * s->gt[4] + dr * s->gt[5] - t->y0;
    return t->b0 + m->beta1 * dx + m->beta2 * dy;
}

typedef struct {
    double n, sg, sf, sgg, sff, sgf;
} block_sums;

/* Sums of G = T + H and F over the cells covering the fitted extent. */
static void block_accumulate(const ft_clarke_model *m, const sim_grid *s, const double *h, const double *f,
                             block_sums *b)
{
    trend_eval t;
    trend_init(m, &t);
    memset(b, 0, sizeof *b);
    size_t bx = m->nx * (size_t)s->k, by = m->ny * (size_t)s->k;
    for (size_t row = 0; row < by; row++) {
        for (size_t col = 0; col < bx; col++) {
            double g = trend_at(m, s, &t, col, row) + h[row * s->rs + col], fv = f[row * s->rs + col];
            b->n += 1.0;
            b->sg += g;
            b->sf += fv;
            b->sgg += g * g;
            b->sff += fv * fv;
            b->sgf += g * fv;
        }
    }
}

/* c >= 0 with var(G + cF) = sd² (power-law noise; 1 for the measured spectrum, whose variogram is the
 * DEM's), and the shift that gives the original mean. */
static void solve_scale(const ft_clarke_model *m, const block_sums *b, double *c, double *shift)
{
    double mg = b->sg / b->n, mf = b->sf / b->n;
    double vg = b->sgg / b->n - mg * mg, vf = b->sff / b->n - mf * mf, cov = b->sgf / b->n - mg * mf;
    double target = m->sd * m->sd;
    *c = 0.0;
    if (m->noise == FT_CLARKE_NOISE_SPECTRUM) { /* F is in the DEM's units already (clarke_variogram.c) */
        *c = 1.0;
    } else if (vf > 0.0) {
        double disc = cov * cov - vf * (vg - target);
        double root = disc >= 0.0 ? (-cov + sqrt(disc)) / vf : 0.0;
        *c = root > 0.0 ? root : 0.0;
    }
    *shift = m->mean - (mg + *c * mf);
}

static int assemble(const ft_clarke_model *m, const sim_grid *s, const double *h, const double *f, double c,
                    double shift, ft_grid **out)
{
    ft_grid *g = ft_grid_create(s->nx, s->ny);
    if (g == NULL)
        return ft_last_error_code();
    memcpy(g->gt, s->gt, sizeof g->gt);
    int rc = ft_grid_set_crs(g, m->crs_wkt);
    if (rc != FT_OK) {
        ft_grid_free(g);
        return rc;
    }
    trend_eval t;
    trend_init(m, &t);
    const long ny = (long)s->ny;
#pragma omp parallel for schedule(static)
    for (long row = 0; row < ny; row++)
        for (size_t col = 0; col < s->nx; col++) {
            size_t i = (size_t)row * s->rs + col;
            g->z[(size_t)row * s->nx + col] =
                (float)(trend_at(m, s, &t, col, (size_t)row) + h[i] + c * f[i] + shift);
        }
    *out = g;
    return FT_OK;
}

/* ---- entry ---- */

static int transform_parts(const ft_clarke_model *m, const sim_grid *s, const ft_clarke_sim_opts *o, double *h,
                           double *f)
{
    size_t n = s->rs * s->ny;
    memset(h, 0, n * sizeof *h);
    fill_harmonics(m, s, (fftw_complex *)(void *)h);
    int rc = ft_fft_c2r_2d(s->ny, s->nx, (fftw_complex *)(void *)h, h);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 0.3, "Clarke simulation: fractal noise");
    if (rc == FT_OK)
        rc = fill_fractal(m, s, o->seed, (fftw_complex *)(void *)f);
    if (rc == FT_OK)
        rc = ft_fft_c2r_2d(s->ny, s->nx, (fftw_complex *)(void *)f, f);
    if (rc == FT_OK)
        detrend_fractal(s, f);
    return rc;
}

int ft_clarke_simulate(const ft_clarke_model *m, const ft_clarke_sim_opts *opts, ft_grid **out)
{
    ft_clarke_sim_opts taken = FT_CLARKE_SIM_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_clarke_sim_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_clarke_sim_opts defaults = FT_CLARKE_SIM_OPTS_DEFAULT;
    const ft_clarke_sim_opts *o = opts ? opts : &defaults;
    int rc = check_opts(m, o, out);
    sim_grid s;
    if (rc == FT_OK)
        rc = sim_grid_init(m, o, &s);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 0.0, "Clarke simulation: harmonics");
    if (rc != FT_OK)
        return rc;
    double *h = ft_fft_alloc_real(s.rs * s.ny), *f = h ? ft_fft_alloc_real(s.rs * s.ny) : NULL;
    rc = f ? transform_parts(m, &s, o, h, f) : ft_last_error_code();
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 0.8, "Clarke simulation: scaling");
    if (rc == FT_OK) {
        block_sums b;
        double c, shift;
        block_accumulate(m, &s, h, f, &b);
        solve_scale(m, &b, &c, &shift);
        if (o->c_used)
            *o->c_used = c;
        rc = assemble(m, &s, h, f, c, shift, out);
    }
    ft_fft_free(h);
    ft_fft_free(f);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 1.0, "Clarke simulation: done");
    if (rc != FT_OK) {
        ft_grid_free(*out);
        *out = NULL;
    }
    return rc;
}
