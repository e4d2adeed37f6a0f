/* fracterra — terrain/clarke/clarke_fit.c: calibrating Clarke's scale-based model z = T + cF + H on a DEM.
 *
 * Clarke, K. C. (1987). Scale-based simulation of topography. Proceedings of Auto-Carto 8, 680-688.
 *  - T (eq. xii): the least-squares plane beta0 + beta1 x + beta2 y over the valid cells, x and y the map
 *    coordinates of cell centres (solved on coordinates centred on the grid, for precision);
 *  - the detrended DEM (nodata cells filled with the trend, i.e. a residual of 0) goes through one 2-D real
 *    FFT at its own size (any size: the harmonics are those of the grid, no padding). Each real plane wave
 *    a cos(theta) + b sin(theta) has power a² + b² (eq. vi, one wave instead of Clarke's four products)
 *    and a share of the detrended variance (Parseval);
 *  - H: the waves whose share reaches the cutoff (Clarke: 2.5 %); each reports the wavelength and direction
 *    of the continuous-frequency plane wave its energy belongs to (clarke_peak.c), not the grid mode's;
 *  - F (eqs. ix, x): least squares of log10 power on log10 wavelength over every wave of non-zero power,
 *    by default on the periodogram of the residual tapered by a 2-D Hann window (divided by the window's
 *    mean square): a DEM is not periodic, and the leakage of its strong long waves through the edges of
 *    an untapered transform steepens the spectrum (on cropped fBm of D = 2.3 the untapered slope gives
 *    D = 2.22, the tapered one 2.28; opts->taper = 0 gives Clarke's raw periodogram), and over the waves
 *    of at least opts->min_wavelength cells (default 4): a surface sampled at points folds the power beyond
 *    the Nyquist frequency back into the band just below it (aliasing), which flattens the spectrum there;
 *    on ft_terrain_synth's fft surfaces (alias-compensated) of D = 2.1 / 2.3 / 2.5 / 2.8 at 512², every wave
 *    gives D = 2.35 / 2.59 / 2.84 / 3.31, waves of 4 cells or more 2.11 / 2.31 / 2.53 / 2.93;
 *    Eq. ix as printed, ((Lx/kx)² + (Ly/ky)²)^½, is infinite on the axes; the wavelength of wave (k, l)
 *    is 1 / ((k/Lx)² + (l/Ly)²)^½. Since power ~ wavelength^beta means P(f) ~ f^-beta, the dimension of
 *    a 2-D isotropic fBm surface is D = (8 - beta) / 2; Clarke's eq. viii, 3 - beta/2, is the variogram
 *    relation and is kept only as D_clarke_eq8, labelled as such (seeds README);
 *  - c: with the power-law noise, the scale of F that makes var(T) + var(H) + c² var(F) the original
 *    variance, var(F) being the regression's power summed over the waves not in H (the simulation re-solves
 *    c on its realization); with the measured spectrum (clarke_spectrum.c, corrected to the DEM's variogram
 *    by clarke_variogram.c, H refitted by least squares on a grid with nodata) c = 1.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "terrain/clarke/clarke_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fft/fft.h"
#include "internal.h"

#define CLARKE_MIN_SIDE 4

/* ---- helpers shared with clarke_simulate.c ---- */

int clarke_signed_l(size_t ky, size_t ny)
{
    return ky <= ny / 2 ? (int)ky : (int)ky - (int)ny;
}

clarke_bin clarke_bin_kind(size_t kx, size_t ky, size_t nx, size_t ny)
{
    int nyquist_col = nx % 2 == 0 && kx == nx / 2;
    if (kx != 0 && !nyquist_col)
        return CLARKE_BIN_PAIR;
    if (ky == 0)
        return kx == 0 ? CLARKE_BIN_SKIP : CLARKE_BIN_SELF;
    if (ny % 2 == 0 && ky == ny / 2)
        return CLARKE_BIN_SELF;
    return clarke_signed_l(ky, ny) > 0 ? CLARKE_BIN_PAIR : CLARKE_BIN_SKIP;
}

int clarke_frame_init(const double gt[6], size_t nx, size_t ny, clarke_frame *f)
{
    for (int i = 0; i < 6; i++)
        if (!isfinite(gt[i]))
            return ft_error(FT_E_INVALID, "Clarke model: geotransform element %d is not finite (%g)", i, gt[i]);
    double cx = hypot(gt[1], gt[4]), cy = hypot(gt[2], gt[5]);
    if (!(cx > 0.0) || !(cy > 0.0))
        return ft_error(FT_E_INVALID, "Clarke model: the cell size must be non-zero, got %g x %g", cx, cy);
    f->ex[0] = gt[1] / cx;
    f->ex[1] = gt[4] / cx;
    f->ey[0] = gt[2] / cy;
    f->ey[1] = gt[5] / cy;
    f->lx = cx * (double)nx;
    f->ly = cy * (double)ny;
    return FT_OK;
}

double clarke_wavelength(const clarke_frame *f, int k, int l)
{
    double fx = k / f->lx, fy = l / f->ly;
    double east = fx * f->ex[0] + fy * f->ey[0], north = fx * f->ex[1] + fy * f->ey[1];
    double norm = hypot(east, north);
    return norm > 0.0 ? 1.0 / norm : INFINITY;
}

void clarke_wave_geometry(const clarke_frame *f, int k, int l, double *wavelength, double *direction)
{
    clarke_wave_geometry_at(f, k, l, wavelength, direction);
}

void clarke_wave_geometry_at(const clarke_frame *f, double u, double v, double *wavelength, double *direction)
{
    double fx = u / f->lx, fy = v / f->ly;
    double east = fx * f->ex[0] + fy * f->ey[0], north = fx * f->ex[1] + fy * f->ey[1];
    double norm = hypot(east, north);
    *wavelength = norm > 0.0 ? 1.0 / norm : INFINITY;
    double az = atan2(east, north) * 180.0 / M_PI;
    az = fmod(az + 360.0, 180.0);
    *direction = az >= 180.0 ? 0.0 : az;
}

double clarke_power(const ft_clarke_model *m, double wavelength)
{
    return pow(10.0, m->intercept + m->slope * log10(wavelength));
}

/* ---- the model ---- */

ft_clarke_model *ft_clarke_model_create(size_t nharmonics)
{
    ft_clarke_model *m = ft_calloc(1, sizeof *m);
    if (m == NULL)
        return NULL;
    if (nharmonics > 0 && (m->harmonics = ft_calloc(nharmonics, sizeof *m->harmonics)) == NULL) {
        free(m);
        return NULL;
    }
    m->nharmonics = nharmonics;
    m->gt[1] = m->gt[5] = 1.0;
    return m;
}

void ft_clarke_model_free(ft_clarke_model *m)
{
    if (m == NULL)
        return;
    free(m->harmonics);
    free(m->crs_wkt);
    free(m->spectrum_wavelength);
    free(m->spectrum_power);
    free(m->spectrum_count);
    free(m->regimes);
    free(m->breaks);
    free(m);
}

/* ---- T: the least-squares plane ---- */

typedef struct {
    double n, su, sv, sz, suu, suv, svv, suz, svz, szz;
} plane_sums;

static void cell_offset(const ft_grid *g, size_t col, size_t row, double *u, double *v)
{
    double dc = (double)col + 0.5 - 0.5 * (double)g->nx, dr = (double)row + 0.5 - 0.5 * (double)g->ny;
    *u = dc * g->gt[1] + dr * g->gt[2];
    *v = dc * g->gt[4] + dr * g->gt[5];
}

static void plane_accumulate(const ft_grid *g, plane_sums *s)
{
    memset(s, 0, sizeof *s);
    for (size_t row = 0; row < g->ny; row++) {
        for (size_t col = 0; col < g->nx; col++) {
            size_t i = row * g->nx + col;
            if (!ft_grid_is_valid(g, col, row) || !isfinite(g->z[i]))
                continue;
            double u, v, z = g->z[i];
            cell_offset(g, col, row, &u, &v);
            s->n += 1.0;
            s->su += u;
            s->sv += v;
            s->sz += z;
            s->suu += u * u;
            s->suv += u * v;
            s->svv += v * v;
            s->suz += u * z;
            s->svz += v * z;
            s->szz += z * z;
        }
    }
}

/* Solves the centred normal equations; sets beta (map coordinates), mean, sd and the trend's r². */
static int plane_solve(const ft_grid *g, const plane_sums *s, ft_clarke_model *m, double *b0c)
{
    if (s->n < 3.0)
        return ft_error(FT_E_EMPTY, "Clarke model: the grid has %.0f valid cell(s) of %zu, at least 3 are needed",
                        s->n, g->nx * g->ny);
    double um = s->su / s->n, vm = s->sv / s->n, zm = s->sz / s->n;
    double cuu = s->suu - s->n * um * um, cuv = s->suv - s->n * um * vm, cvv = s->svv - s->n * vm * vm;
    double cuz = s->suz - s->n * um * zm, cvz = s->svz - s->n * vm * zm, czz = s->szz - s->n * zm * zm;
    double det = cuu * cvv - cuv * cuv;
    if (!(det > 1e-12 * cuu * cvv) || !isfinite(det))
        return ft_error(FT_E_EMPTY, "Clarke model: the valid cells lie on one line, the trend plane is undefined");
    m->beta1 = (cuz * cvv - cvz * cuv) / det;
    m->beta2 = (cvz * cuu - cuz * cuv) / det;
    *b0c = zm - m->beta1 * um - m->beta2 * vm; /* intercept on the centred coordinates */
    double xc = g->gt[0] + 0.5 * (double)g->nx * g->gt[1] + 0.5 * (double)g->ny * g->gt[2];
    double yc = g->gt[3] + 0.5 * (double)g->nx * g->gt[4] + 0.5 * (double)g->ny * g->gt[5];
    m->beta0 = *b0c - m->beta1 * xc - m->beta2 * yc;
    double explained = m->beta1 * cuz + m->beta2 * cvz;
    m->trend_r2 = czz > 0.0 ? fmin(1.0, fmax(0.0, explained / czz)) : 1.0;
    m->mean = zm;
    m->sd = sqrt(fmax(0.0, czz / s->n));
    m->valid = (size_t)s->n;
    return FT_OK;
}

/* The Hann taper sin²(pi (i + 1/2) / n) of cell i of n. */
static double hann(size_t i, size_t n)
{
    double v = sin(M_PI * ((double)i + 0.5) / (double)n);
    return v * v;
}

/* Mean of the squared 2-D taper over the grid: a tapered periodogram divided by it estimates the same
 * power per wave as an untapered one. */
static double taper_power(size_t nx, size_t ny)
{
    double sx = 0.0, sy = 0.0;
    for (size_t i = 0; i < nx; i++)
        sx += hann(i, nx) * hann(i, nx);
    for (size_t i = 0; i < ny; i++)
        sy += hann(i, ny) * hann(i, ny);
    return (sx / (double)nx) * (sy / (double)ny);
}

/* The taper of every index 0 .. n-1 (all 1 without taper); NULL (error set) if out of memory. */
static double *taper_table(size_t n, int taper)
{
    double *w = ft_malloc(n * sizeof *w);
    for (size_t i = 0; w && i < n; i++)
        w[i] = taper ? hann(i, n) : 1.0;
    return w;
}

/* The residual z - T (times the taper if asked) in the in-place FFT layout (row stride rs); nodata cells
 * get 0, i.e. they are filled with T. */
static int residual_fill(const ft_grid *g, const ft_clarke_model *m, double b0c, int taper, double *r, size_t rs)
{
    double *wx = taper_table(g->nx, taper), *wy = wx ? taper_table(g->ny, taper) : NULL;
    if (wy == NULL) {
        free(wx);
        return ft_last_error_code();
    }
    const long nrows = (long)g->ny;
#pragma omp parallel for schedule(static)
    for (long row = 0; row < nrows; row++) {
        for (size_t col = 0; col < g->nx; col++) {
            size_t i = (size_t)row * g->nx + col;
            double u, v;
            cell_offset(g, col, (size_t)row, &u, &v);
            int ok = ft_grid_is_valid(g, col, (size_t)row) && isfinite(g->z[i]);
            r[(size_t)row * rs + col] =
                ok ? wy[row] * wx[col] * (g->z[i] - (b0c + m->beta1 * u + m->beta2 * v)) : 0.0;
        }
    }
    free(wx);
    free(wy);
    return FT_OK;
}

/* ---- H and F: the spectrum ---- */

/* Plane-wave coefficients of bin F: a cos + b sin = (2/N) Re(F e^{i theta}) for a pair, F/N for a self-
 * conjugate bin. Returns the variance the wave carries. */
static double wave_coefficients(const fftw_complex F, clarke_bin kind, double n, double *a, double *b)
{
    if (kind == CLARKE_BIN_SELF) {
        *a = F[0] / n;
        *b = 0.0;
        return *a * *a;
    }
    *a = 2.0 * F[0] / n;
    *b = -2.0 * F[1] / n;
    return 0.5 * (*a * *a + *b * *b);
}

typedef struct {
    double *log_wavelength, *log_power; /* log10, one row per wave of non-zero power */
    size_t n;
} regression_input;

/* log10 wavelength and log10 power (divided by norm, the taper's mean square) of every wave of non-zero
 * power and wavelength >= min_wavelength: rows in parallel into fixed slots, then compacted in order. */
static void collect_regression(const fftw_complex *spec, size_t nx, size_t ny, const clarke_frame *fr, double norm,
                               double min_wavelength, regression_input *ri)
{
    size_t hx = nx / 2 + 1;
    double n = (double)nx * (double)ny;
    const long nrows = (long)ny;
#pragma omp parallel for schedule(static)
    for (long ky = 0; ky < nrows; ky++) {
        for (size_t kx = 0; kx < hx; kx++) {
            size_t i = (size_t)ky * hx + kx;
            clarke_bin kind = clarke_bin_kind(kx, (size_t)ky, nx, ny);
            double a = 0.0, b = 0.0, wl = 0.0;
            ri->log_wavelength[i] = NAN;
            if (kind == CLARKE_BIN_SKIP)
                continue;
            wave_coefficients(spec[i], kind, n, &a, &b);
            double p = (a * a + b * b) / norm;
            if (!(p > 0.0) || !isfinite(p) ||
                (wl = clarke_wavelength(fr, (int)kx, clarke_signed_l((size_t)ky, ny))) < min_wavelength)
                continue;
            ri->log_wavelength[i] = log10(wl);
            ri->log_power[i] = log10(p);
        }
    }
    ri->n = 0;
    for (size_t i = 0; i < ny * hx; i++) {
        if (isnan(ri->log_wavelength[i]))
            continue;
        ri->log_wavelength[ri->n] = ri->log_wavelength[i];
        ri->log_power[ri->n++] = ri->log_power[i];
    }
}

typedef struct {
    ft_clarke_harmonic *sig; /* waves at or above the cutoff */
    size_t nsig, cap;
    double total_var;        /* detrended variance (Parseval, DC excluded) */
} harmonic_scan;

static int push_significant(harmonic_scan *s, const ft_clarke_harmonic *h)
{
    if (s->nsig == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 16;
        ft_clarke_harmonic *p = ft_realloc_array(s->sig, cap, sizeof *p);
        if (p == NULL)
            return ft_last_error_code();
        s->sig = p;
        s->cap = cap;
    }
    s->sig[s->nsig++] = *h;
    return FT_OK;
}

static double spectrum_total_variance(const fftw_complex *spec, size_t nx, size_t ny)
{
    size_t hx = nx / 2 + 1;
    double n = (double)nx * (double)ny, total = 0.0;
    for (size_t ky = 0; ky < ny; ky++) {
        for (size_t kx = 0; kx < hx; kx++) {
            clarke_bin kind = clarke_bin_kind(kx, ky, nx, ny);
            double a, b;
            if (kind != CLARKE_BIN_SKIP)
                total += wave_coefficients(spec[ky * hx + kx], kind, n, &a, &b);
        }
    }
    return total;
}

/* The waves whose share of the detrended variance reaches cutoff percent. */
static int scan_harmonics(const fftw_complex *spec, size_t nx, size_t ny, const clarke_frame *fr, double cutoff,
                          harmonic_scan *s)
{
    size_t hx = nx / 2 + 1;
    double n = (double)nx * (double)ny;
    s->total_var = spectrum_total_variance(spec, nx, ny);
    if (!(s->total_var > 0.0))
        return FT_OK;
    for (size_t ky = 0; ky < ny; ky++) {
        for (size_t kx = 0; kx < hx; kx++) {
            clarke_bin kind = clarke_bin_kind(kx, ky, nx, ny);
            if (kind == CLARKE_BIN_SKIP)
                continue;
            ft_clarke_harmonic h = {.k = (int)kx, .l = clarke_signed_l(ky, ny)};
            double var = wave_coefficients(spec[ky * hx + kx], kind, n, &h.a, &h.b);
            h.share = var / s->total_var;
            if (100.0 * h.share < cutoff)
                continue;
            h.power = h.a * h.a + h.b * h.b;
            clarke_wave_geometry(fr, h.k, h.l, &h.wavelength, &h.direction);
            int rc = push_significant(s, &h);
            if (rc != FT_OK)
                return rc;
        }
    }
    return FT_OK;
}

static int by_share_desc(const void *pa, const void *pb)
{
    const ft_clarke_harmonic *a = pa, *b = pb;
    if (a->share != b->share)
        return a->share < b->share ? 1 : -1;
    return a->k != b->k ? a->k - b->k : a->l - b->l; /* a total order: the same on every platform */
}

/* Log-log regression of power on wavelength (eqs. ix, x) and the two dimensions. */
static int regression(const regression_input *s, ft_clarke_model *m)
{
    if (s->n < 2)
        return ft_error(FT_E_EMPTY, "Clarke model: the detrended DEM has %zu harmonic(s) of non-zero power, the "
                        "regression needs at least 2 (is the surface a plane?)", s->n);
    ft_fit fit;
    int rc = ft_fit_line(s->log_wavelength, s->log_power, 0, s->n - 1, &fit);
    if (rc != FT_OK)
        return rc;
    m->slope = fit.slope;
    m->intercept = fit.intercept;
    m->r2 = fit.r2;
    m->stderr_slope = fit.stderr_slope;
    m->npairs = fit.n;
    m->D = (8.0 - fit.slope) / 2.0;
    m->D_clarke_eq8 = 3.0 - fit.slope / 2.0;
    return FT_OK;
}

/* var(F) for c = 1: the regression's power over every wave of the grid that is not in H. */
static double fractal_variance(const ft_clarke_model *m, const clarke_frame *fr)
{
    size_t nx = m->nx, ny = m->ny, hx = nx / 2 + 1;
    double *rows = ft_calloc(ny, sizeof *rows);
    if (rows == NULL)
        return 0.0;
    const long nrows = (long)ny;
#pragma omp parallel for schedule(static)
    for (long ky = 0; ky < nrows; ky++) {
        double sum = 0.0;
        for (size_t kx = 0; kx < hx; kx++) {
            clarke_bin kind = clarke_bin_kind(kx, (size_t)ky, nx, ny);
            if (kind == CLARKE_BIN_SKIP)
                continue;
            double p = clarke_noise_power(m, clarke_wavelength(fr, (int)kx, clarke_signed_l((size_t)ky, ny)));
            sum += kind == CLARKE_BIN_SELF ? p : 0.5 * p;
        }
        rows[ky] = sum;
    }
    double var = 0.0;
    for (size_t ky = 0; ky < ny; ky++) /* in row order: the same bits on any thread count */
        var += rows[ky];
    free(rows);
    for (size_t i = 0; i < m->nharmonics; i++) {
        const ft_clarke_harmonic *h = &m->harmonics[i];
        int self = (h->k == 0 || 2 * (size_t)h->k == nx) && (h->l == 0 || 2 * (size_t)abs(h->l) == ny);
        double p = clarke_noise_power(m, clarke_wavelength(fr, h->k, h->l)); /* the mode's, as in the sum */
        var -= self ? p : 0.5 * p;
    }
    return var;
}

static void scale_c(ft_clarke_model *m, const clarke_frame *fr, double total_var)
{
    double var_h = m->harmonic_share * total_var;
    double var_f = fractal_variance(m, fr);
    /* var(T) = r² var(z) over the valid cells: least squares makes the residual orthogonal to T. */
    double left = m->sd * m->sd * (1.0 - m->trend_r2) - var_h;
    m->c = var_f > 0.0 && left > 0.0 ? sqrt(left / var_f) : 0.0;
}

/* ---- the fit ---- */

static int check_input(const ft_grid *dem, const ft_clarke_opts *o, ft_clarke_model **out)
{
    if (out == NULL)
        return ft_error(FT_E_INVALID, "Clarke model: no output pointer given");
    *out = NULL;
    if (dem == NULL || dem->z == NULL)
        return ft_error(FT_E_INVALID, "Clarke model: no grid given");
    if (!isfinite(o->min_wavelength) || o->min_wavelength < 0.0)
        return ft_error(FT_E_INVALID, "Clarke model: min_wavelength must be >= 0 cells, got %g", o->min_wavelength);
    if (o->noise != FT_CLARKE_NOISE_POWER_LAW && o->noise != FT_CLARKE_NOISE_SPECTRUM)
        return ft_error(FT_E_INVALID, "Clarke model: noise must be power-law (%d) or spectrum (%d), got %d",
                        FT_CLARKE_NOISE_POWER_LAW, FT_CLARKE_NOISE_SPECTRUM, (int)o->noise);
    if (o->taper != 0 && o->taper != 1)
        return ft_error(FT_E_INVALID, "Clarke model: taper must be 0 (none) or 1 (Hann), got %d", o->taper);
    if (!isfinite(o->cutoff) || o->cutoff <= 0.0 || o->cutoff > 100.0)
        return ft_error(FT_E_INVALID, "Clarke model: cutoff must be in (0,100] percent, got %g", o->cutoff);
    if (dem->nx < CLARKE_MIN_SIDE || dem->ny < CLARKE_MIN_SIDE)
        return ft_error(FT_E_INVALID, "Clarke model: the grid must have at least %d x %d cells, got %zu x %zu",
                        CLARKE_MIN_SIDE, CLARKE_MIN_SIDE, dem->nx, dem->ny);
    if (dem->nx > (size_t)INT32_MAX || dem->ny > (size_t)INT32_MAX)
        return ft_error(FT_E_INVALID, "Clarke model: the grid is too large (%zu x %zu)", dem->nx, dem->ny);
    return FT_OK;
}

static int model_init(const ft_grid *dem, const ft_clarke_opts *o, ft_clarke_model **mp, clarke_frame *fr)
{
    int rc = clarke_frame_init(dem->gt, dem->nx, dem->ny, fr);
    if (rc != FT_OK)
        return rc;
    ft_clarke_model *m = ft_clarke_model_create(0);
    if (m == NULL)
        return ft_last_error_code();
    m->nx = dem->nx;
    m->ny = dem->ny;
    memcpy(m->gt, dem->gt, sizeof m->gt);
    m->cutoff = o->cutoff;
    m->taper = o->taper;
    m->min_wavelength = o->min_wavelength;
    m->noise = o->noise;
    if (dem->crs_wkt && (m->crs_wkt = ft_strdup(dem->crs_wkt)) == NULL) {
        ft_clarke_model_free(m);
        return ft_last_error_code();
    }
    *mp = m;
    return FT_OK;
}

/* T over the valid cells; *b0c is its value at the grid's centre. */
static int fit_trend(const ft_grid *dem, ft_clarke_model *m, double *b0c)
{
    plane_sums sums;
    plane_accumulate(dem, &sums);
    int rc = plane_solve(dem, &sums, m, b0c);
    m->nodata_filled = dem->nx * dem->ny - m->valid;
    return rc;
}

/* The spectrum of the (tapered) residual, in place in buf. */
static int transform_residual(const ft_grid *dem, const ft_clarke_model *m, double b0c, int taper, double *buf)
{
    int rc = residual_fill(dem, m, b0c, taper, buf, ft_fft_real_stride(dem->nx));
    return rc == FT_OK ? ft_fft_r2c_2d(dem->ny, dem->nx, buf, (fftw_complex *)(void *)buf) : rc;
}

/* The regression (on the tapered spectrum if asked), then H on the raw spectrum. */
static int analyse(const ft_grid *dem, ft_clarke_model *m, double b0c, const clarke_frame *fr,
                   const ft_clarke_opts *o, double *buf, regression_input *ri, harmonic_scan *hs)
{
    const fftw_complex *spec = (const fftw_complex *)(const void *)buf;
    int rc = transform_residual(dem, m, b0c, o->taper, buf);
    if (rc != FT_OK)
        return rc;
    double cell = fmin(fr->lx / (double)m->nx, fr->ly / (double)m->ny);
    collect_regression(spec, m->nx, m->ny, fr, o->taper ? taper_power(m->nx, m->ny) : 1.0,
                       o->min_wavelength * cell * (1.0 - 1e-9), ri);
    if ((rc = ft_progress(o->progress, o->progress_arg, 0.5, "Clarke model: harmonics")) != FT_OK)
        return rc;
    if (o->taper && (rc = transform_residual(dem, m, b0c, 0, buf)) != FT_OK)
        return rc;
    if ((rc = scan_harmonics(spec, m->nx, m->ny, fr, o->cutoff, hs)) != FT_OK)
        return rc;
    if ((rc = ft_progress(o->progress, o->progress_arg, 0.8, "Clarke model: regression")) != FT_OK)
        return rc;
    return regression(ri, m);
}

/* Zeroes the bins of H (and their conjugate twins in the edge columns) of a half-spectrum. */
static void remove_harmonics(const ft_clarke_model *m, fftw_complex *spec)
{
    size_t hx = m->nx / 2 + 1;
    for (size_t i = 0; i < m->nharmonics; i++) {
        const ft_clarke_harmonic *h = &m->harmonics[i];
        size_t up = (size_t)(((long)h->l % (long)m->ny + (long)m->ny) % (long)m->ny);
        size_t down = (size_t)(((-(long)h->l) % (long)m->ny + (long)m->ny) % (long)m->ny);
        memset(&spec[up * hx + (size_t)h->k], 0, sizeof(fftw_complex));
        if (h->k == 0 || 2 * (size_t)h->k == m->nx)
            memset(&spec[down * hx + (size_t)h->k], 0, sizeof(fftw_complex));
    }
}

/* The power of every wave of F's own part of the residual, z - T - H (the grid modes of H removed), on
 * the periodogram under the fit's taper, divided by the taper's mean square; NaN where the half-spectrum
 * holds no wave of its own or the power is 0. buf: the FFT buffer (overwritten). */
/* z - T - H with H's grid modes removed (untapered; nodata cells hold -H), row stride rs, into buf. */
static int residual_without_harmonics(const ft_grid *dem, const ft_clarke_model *m, double b0c, double *buf)
{
    size_t nx = m->nx, ny = m->ny, rs = ft_fft_real_stride(nx);
    fftw_complex *spec = (fftw_complex *)(void *)buf;
    int rc = transform_residual(dem, m, b0c, 0, buf);
    if (rc != FT_OK)
        return rc;
    remove_harmonics(m, spec);
    if ((rc = ft_fft_c2r_2d(ny, nx, spec, buf)) != FT_OK)
        return rc;
    double n = (double)nx * (double)ny; /* FFTW's inverse is unnormalised */
    for (size_t row = 0; row < ny; row++)
        for (size_t col = 0; col < nx; col++)
            buf[row * rs + col] /= n;
    return FT_OK;
}

static int noise_wave_powers(const ft_grid *dem, const ft_clarke_model *m, double b0c, int taper, double *buf,
                             double *wave_power)
{
    size_t nx = m->nx, ny = m->ny, hx = nx / 2 + 1, rs = ft_fft_real_stride(nx);
    fftw_complex *spec = (fftw_complex *)(void *)buf;
    int rc = residual_without_harmonics(dem, m, b0c, buf);
    if (rc != FT_OK)
        return rc;
    double *wx = taper_table(nx, taper), *wy = wx ? taper_table(ny, taper) : NULL;
    if (wy == NULL) {
        free(wx);
        return ft_last_error_code();
    }
    double n = (double)nx * (double)ny, norm = taper ? taper_power(nx, ny) : 1.0;
    for (size_t row = 0; row < ny; row++)
        for (size_t col = 0; col < nx; col++)
            buf[row * rs + col] *= wy[row] * wx[col];
    free(wx);
    free(wy);
    if ((rc = ft_fft_r2c_2d(ny, nx, buf, spec)) != FT_OK)
        return rc;
    for (size_t ky = 0; ky < ny; ky++) {
        for (size_t kx = 0; kx < hx; kx++) {
            clarke_bin kind = clarke_bin_kind(kx, ky, nx, ny);
            double a = 0.0, b = 0.0;
            wave_power[ky * hx + kx] = NAN;
            if (kind == CLARKE_BIN_SKIP)
                continue;
            wave_coefficients(spec[ky * hx + kx], kind, n, &a, &b);
            double p = (a * a + b * b) / norm;
            if (p > 0.0 && isfinite(p))
                wave_power[ky * hx + kx] = p;
        }
    }
    return FT_OK;
}

static void take_harmonics(ft_clarke_model *m, harmonic_scan *hs)
{
    qsort(hs->sig, hs->nsig, sizeof *hs->sig, by_share_desc);
    m->harmonics = hs->sig;
    m->nharmonics = hs->nsig;
    hs->sig = NULL;
    for (size_t i = 0; i < m->nharmonics; i++)
        m->harmonic_share += m->harmonics[i].share;
}

/* ---- H on a grid with nodata: least squares over the valid cells ---- */

/* cos and sin of each harmonic's phase along the columns and the rows, so that the design matrix's terms
 * a_i cos(theta_i), b_i sin(theta_i), theta_i = 2 pi (k col / nx + l row / ny), cost no trigonometry per cell. */
typedef struct {
    double *cc, *sc, *cr, *sr; /* [harmonic * nx + col], [harmonic * ny + row] */
} lsq_tables;

static int lsq_tables_init(const ft_clarke_model *m, lsq_tables *t)
{
    size_t nh = m->nharmonics;
    t->cc = ft_malloc((2 * nh * (m->nx + m->ny) + 1) * sizeof(double)); /* + 1: no harmonic is no error */
    if (t->cc == NULL)
        return ft_last_error_code();
    t->sc = t->cc + nh * m->nx;
    t->cr = t->sc + nh * m->nx;
    t->sr = t->cr + nh * m->ny;
    for (size_t i = 0; i < nh; i++) {
        for (size_t col = 0; col < m->nx; col++) {
            double a = 2.0 * M_PI * (double)m->harmonics[i].k * (double)col / (double)m->nx;
            t->cc[i * m->nx + col] = cos(a);
            t->sc[i * m->nx + col] = sin(a);
        }
        for (size_t row = 0; row < m->ny; row++) {
            double a = 2.0 * M_PI * (double)m->harmonics[i].l * (double)row / (double)m->ny;
            t->cr[i * m->ny + row] = cos(a);
            t->sr[i * m->ny + row] = sin(a);
        }
    }
    return FT_OK;
}

/* Unknown j at cell (col, row): cos(theta_{j/2}) for even j, sin for odd j. */
static double lsq_term(const ft_clarke_model *m, const lsq_tables *t, size_t j, size_t col, size_t row)
{
    size_t i = j / 2, c = i * m->nx + col, r = i * m->ny + row;
    return j % 2 == 0 ? t->cc[c] * t->cr[r] - t->sc[c] * t->sr[r] : t->sc[c] * t->cr[r] + t->cc[c] * t->sr[r];
}

/* Solves a x = y (n x n, row-major, overwritten) by Gaussian elimination with partial pivoting; 0 if singular. */
static int solve_small(double *a, double *y, size_t n)
{
    for (size_t c = 0; c < n; c++) {
        size_t p = c;
        for (size_t r = c + 1; r < n; r++)
            if (fabs(a[r * n + c]) > fabs(a[p * n + c]))
                p = r;
        if (!(fabs(a[p * n + c]) > 1e-9 * (double)n))
            return 0;
        for (size_t k = 0; k < n && p != c; k++) {
            double t = a[c * n + k];
            a[c * n + k] = a[p * n + k];
            a[p * n + k] = t;
        }
        double t = y[c];
        y[c] = y[p];
        y[p] = t;
        for (size_t r = c + 1; r < n; r++) {
            double f = a[r * n + c] / a[c * n + c];
            for (size_t k = c; k < n; k++)
                a[r * n + k] -= f * a[c * n + k];
            y[r] -= f * y[c];
        }
    }
    for (size_t c = n; c-- > 0;) {
        for (size_t k = c + 1; k < n; k++)
            y[c] -= a[c * n + k] * y[k];
        y[c] /= a[c * n + c];
    }
    return 1;
}

#define LSQ_MAX_HARMONICS 64 /* more (a cutoff far below 2.5 %): the FFT's coefficients are kept */

/* On a grid with nodata, the FFT of the trend-filled residual gives each wave of H the amplitude it has
 * over the whole grid, about the valid share of its amplitude over the DEM: the rest stays in z - T - H,
 * correlated with H, and a simulation (H plus random phases) loses it. The coefficients a, b of H's modes
 * are refitted jointly by least squares on the valid cells (the sine of a self-conjugate mode is 0 on the
 * grid and is left at 0). Unchanged if the system is singular or H has more than LSQ_MAX_HARMONICS waves. */
static int harmonics_least_squares(const ft_grid *dem, ft_clarke_model *m, const lsq_tables *tb,
                                   const double *res, size_t rs)
{
    size_t n = 2 * m->nharmonics;
    if (n == 0 || m->nodata_filled == 0 || m->nharmonics > LSQ_MAX_HARMONICS)
        return FT_OK;
    double *a = ft_calloc(n * n + 2 * n, sizeof *a);
    if (a == NULL)
        return ft_last_error_code();
    double *y = a + n * n, *t = y + n;
    for (size_t row = 0; row < dem->ny; row++)
        for (size_t col = 0; col < dem->nx; col++) {
            if (!ft_grid_is_valid(dem, col, row) || !isfinite(dem->z[row * dem->nx + col]))
                continue;
            for (size_t j = 0; j < n; j++)
                t[j] = lsq_term(m, tb, j, col, row);
            for (size_t i = 0; i < n; i++) {
                y[i] += t[i] * res[row * rs + col];
                for (size_t j = i; j < n; j++)
                    a[i * n + j] += t[i] * t[j];
            }
        }
    for (size_t i = 0; i < n; i++) /* the lower triangle */
        for (size_t j = 0; j < i; j++)
            a[i * n + j] = a[j * n + i];
    for (size_t j = 1; j < n; j += 2) /* a sine that is 0 everywhere: keep b = 0 */
        if (!(a[j * n + j] > 1e-9)) {
            for (size_t k = 0; k < n; k++)
                a[j * n + k] = a[k * n + j] = 0.0;
            a[j * n + j] = 1.0;
            y[j] = 0.0;
        }
    if (solve_small(a, y, n))
        for (size_t i = 0; i < m->nharmonics; i++) {
            m->harmonics[i].a = y[2 * i];
            m->harmonics[i].b = y[2 * i + 1];
            m->harmonics[i].power = y[2 * i] * y[2 * i] + y[2 * i + 1] * y[2 * i + 1];
        }
    free(a);
    return FT_OK;
}

/* z - T - H at the valid cells (0 elsewhere), row stride rs. */
static void residual_minus_harmonics(const ft_grid *dem, const ft_clarke_model *m, const lsq_tables *tb, double *res,
                                     size_t rs)
{
    for (size_t row = 0; row < dem->ny; row++)
        for (size_t col = 0; col < dem->nx; col++) {
            if (!ft_grid_is_valid(dem, col, row) || !isfinite(dem->z[row * dem->nx + col])) {
                res[row * rs + col] = 0.0;
                continue;
            }
            for (size_t i = 0; i < m->nharmonics; i++)
                res[row * rs + col] -= m->harmonics[i].a * lsq_term(m, tb, 2 * i, col, row) +
                                       m->harmonics[i].b * lsq_term(m, tb, 2 * i + 1, col, row);
        }
}

static int fit_spectrum(const ft_grid *dem, ft_clarke_model *m, double b0c, const clarke_frame *fr,
                        const ft_clarke_opts *o)
{
    size_t nwaves = m->ny * (m->nx / 2 + 1);
    regression_input ri = {ft_malloc(nwaves * sizeof(double)), ft_malloc(nwaves * sizeof(double)), 0};
    double *wave_power = ft_malloc(nwaves * sizeof(double));
    harmonic_scan hs = {0};
    double *buf = ft_fft_alloc_real(ft_fft_real_stride(dem->nx) * dem->ny);
    int rc = ri.log_wavelength && ri.log_power && wave_power && buf ? FT_OK : ft_last_error_code();
    if (rc == FT_OK)
        rc = analyse(dem, m, b0c, fr, o, buf, &ri, &hs);
    if (rc == FT_OK) {
        take_harmonics(m, &hs);
        rc = residual_fill(dem, m, b0c, 0, buf, ft_fft_real_stride(dem->nx));
    }
    if (rc == FT_OK)
        rc = clarke_refine_harmonics(dem, buf, ft_fft_real_stride(dem->nx), fr, m->harmonics, m->nharmonics);
    if (rc == FT_OK)
        rc = noise_wave_powers(dem, m, b0c, o->taper, buf, wave_power);
    if (rc == FT_OK)
        rc = clarke_measure_spectrum(m, fr, wave_power);
    if (rc == FT_OK && m->noise == FT_CLARKE_NOISE_SPECTRUM)
        rc = residual_fill(dem, m, b0c, 0, buf, ft_fft_real_stride(dem->nx));
    lsq_tables tb = {0};
    if (rc == FT_OK && m->noise == FT_CLARKE_NOISE_SPECTRUM)
        rc = lsq_tables_init(m, &tb);
    if (rc == FT_OK && m->noise == FT_CLARKE_NOISE_SPECTRUM)
        rc = harmonics_least_squares(dem, m, &tb, buf, ft_fft_real_stride(dem->nx));
    if (rc == FT_OK && m->noise == FT_CLARKE_NOISE_SPECTRUM)
        residual_minus_harmonics(dem, m, &tb, buf, ft_fft_real_stride(dem->nx));
    free(tb.cc);
    if (rc == FT_OK && m->noise == FT_CLARKE_NOISE_SPECTRUM)
        rc = clarke_match_variogram(m, fr, dem, buf, ft_fft_real_stride(dem->nx));
    if (rc == FT_OK) {
        double cell = fmin(fr->lx / (double)m->nx, fr->ly / (double)m->ny);
        rc = clarke_spectrum_regimes(m, o->min_wavelength * cell * (1.0 - 1e-9));
    }
    if (rc == FT_OK && m->noise == FT_CLARKE_NOISE_SPECTRUM)
        m->c = 1.0; /* the matched spectrum is F itself */
    else if (rc == FT_OK)
        scale_c(m, fr, hs.total_var);
    free(ri.log_wavelength);
    free(ri.log_power);
    free(wave_power);
    free(hs.sig);
    ft_fft_free(buf);
    return rc;
}

int ft_clarke_fit(const ft_grid *dem, const ft_clarke_opts *opts, ft_clarke_model **out)
{
    ft_clarke_opts taken = FT_CLARKE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_clarke_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_clarke_opts defaults = FT_CLARKE_OPTS_DEFAULT;
    const ft_clarke_opts *o = opts ? opts : &defaults;
    int rc = check_input(dem, o, out);
    if (rc != FT_OK)
        return rc;
    ft_clarke_model *m = NULL;
    clarke_frame fr;
    double b0c = 0.0;
    if ((rc = model_init(dem, o, &m, &fr)) != FT_OK)
        return rc;
    if ((rc = ft_progress(o->progress, o->progress_arg, 0.0, "Clarke model: trend")) == FT_OK)
        rc = fit_trend(dem, m, &b0c);
    if (rc == FT_OK)
        rc = fit_spectrum(dem, m, b0c, &fr, o);
    if (rc == FT_OK)
        rc = ft_progress(o->progress, o->progress_arg, 1.0, "Clarke model: done");
    if (rc != FT_OK) {
        ft_clarke_model_free(m);
        return rc;
    }
    *out = m;
    return FT_OK;
}
