/* fracterra — io/clarke_model_json.c: the file format of Clarke's scale-based model (Clarke 1987, eqs. xi-xv),
 * a JSON object: what `fracterra model fit -o` writes and `model simulate` reads (docs/terrain-clarke.md).
 *
 * The object holds everything `model simulate` needs and a reader wants to judge: the estimator keys
 * every command prints ("method", "D", "r2", "stderr", "range": wavelengths fitted), then "grid" (size,
 * geotransform, CRS WKT), "original" (mean, sd, valid cells, nodata filled), "trend" (eq. xii:
 * beta0 + beta1 x + beta2 y, r2), "harmonics" (cutoff, total share, the list: k, l, a, b, power, share,
 * wavelength, direction), "regression" (eqs. x, xv: slope, intercept, r2, stderr, pairs, taper,
 * min_wavelength_cells),
 * "D_clarke_eq8" (Clarke's eq. viii, the variogram relation, labelled) and "c". Format 2 ("format_version":
 * 2) adds "noise" ("spectrum" or "power-law": the F the simulation draws), "spectrum" (the measured radial
 * spectrum: wavelength, power per plane wave, waves per ring), "regimes" (D, wavelength range in ground
 * units and cells, frequency range, slope, intercept, r2, stderr, bins) and "breaks" (wavelengths); a file
 * without "format_version" is format 1 and simulates Clarke's power law. Reading is strict: every key
 * the simulation uses must be there with the right type, and the error names it. Numbers are written with
 * the fewest digits that read back to the same double, so a model survives a write and a read bit for bit.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <json-c/json.h>

#include "fracterra/terrain.h"
#include "internal.h"
#include "io/io_internal.h"

#define MODEL_NAME "clarke1987"
/* 1: F is the regression's power law (files without "format_version"); 2: adds "noise", "spectrum",
 * "regimes" and "breaks" (F may be the measured radial spectrum). Version 1 files still load. */
#define MODEL_FORMAT_VERSION 2

/* ---- writing ---- */

/* A finite number as the shortest text that reads back to it; null otherwise. */
static json_object *jnum(double v)
{
    if (!isfinite(v))
        return NULL;
    char buf[40];
    ft_io_format_double(buf, sizeof buf, v);
    return json_object_new_double_s(v, buf);
}

static json_object *jarray(const double *v, size_t n)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < n; i++)
        json_object_array_add(a, jnum(v[i]));
    return a;
}

static json_object *grid_json(const ft_clarke_model *m)
{
    json_object *g = json_object_new_object(), *size = json_object_new_array();
    json_object_array_add(size, json_object_new_int64((int64_t)m->nx));
    json_object_array_add(size, json_object_new_int64((int64_t)m->ny));
    json_object_object_add(g, "size", size);
    json_object_object_add(g, "geotransform", jarray(m->gt, 6));
    json_object_object_add(g, "crs", m->crs_wkt ? json_object_new_string(m->crs_wkt) : NULL);
    return g;
}

static json_object *harmonic_json(const ft_clarke_harmonic *h)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "k", json_object_new_int(h->k));
    json_object_object_add(o, "l", json_object_new_int(h->l));
    json_object_object_add(o, "a", jnum(h->a));
    json_object_object_add(o, "b", jnum(h->b));
    json_object_object_add(o, "amplitude", jnum(hypot(h->a, h->b)));
    json_object_object_add(o, "power", jnum(h->power));
    json_object_object_add(o, "share", jnum(h->share));
    json_object_object_add(o, "wavelength", jnum(h->wavelength));
    json_object_object_add(o, "direction", jnum(h->direction));
    return o;
}

static json_object *harmonics_json(const ft_clarke_model *m)
{
    json_object *o = json_object_new_object(), *list = json_object_new_array();
    for (size_t i = 0; i < m->nharmonics; i++)
        json_object_array_add(list, harmonic_json(&m->harmonics[i]));
    json_object_object_add(o, "cutoff", jnum(m->cutoff));
    json_object_object_add(o, "count", json_object_new_int64((int64_t)m->nharmonics));
    json_object_object_add(o, "share", jnum(m->harmonic_share));
    json_object_object_add(o, "list", list);
    return o;
}

static json_object *regression_json(const ft_clarke_model *m)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "slope", jnum(m->slope));
    json_object_object_add(o, "intercept", jnum(m->intercept));
    json_object_object_add(o, "r2", jnum(m->r2));
    json_object_object_add(o, "stderr_slope", jnum(m->stderr_slope));
    json_object_object_add(o, "pairs", json_object_new_int64((int64_t)m->npairs));
    json_object_object_add(o, "taper", json_object_new_string(m->taper ? "hann" : "none"));
    json_object_object_add(o, "min_wavelength_cells", jnum(m->min_wavelength));
    return o;
}

static double cell_size(const ft_clarke_model *m)
{
    return fmin(hypot(m->gt[1], m->gt[4]), hypot(m->gt[2], m->gt[5]));
}

static json_object *spectrum_json(const ft_clarke_model *m)
{
    json_object *o = json_object_new_object();
    json_object_object_add(o, "rings_per_octave", json_object_new_int(4));
    json_object_object_add(o, "wavelength", jarray(m->spectrum_wavelength, m->nspectrum));
    json_object_object_add(o, "power", jarray(m->spectrum_power, m->nspectrum));
    json_object_object_add(o, "waves", jarray(m->spectrum_count, m->nspectrum));
    return o;
}

static json_object *regime_json(const ft_clarke_model *m, const ft_clarke_regime *g)
{
    json_object *o = json_object_new_object();
    double wl[2] = {g->wavelength_lo, g->wavelength_hi}, cells[2], freq[2] = {1.0 / g->wavelength_hi,
                                                                               1.0 / g->wavelength_lo};
    cells[0] = wl[0] / cell_size(m);
    cells[1] = wl[1] / cell_size(m);
    json_object_object_add(o, "D", jnum(g->D));
    json_object_object_add(o, "stderr", jnum(g->stderr_D));
    json_object_object_add(o, "r2", jnum(g->r2));
    json_object_object_add(o, "wavelength", jarray(wl, 2));
    json_object_object_add(o, "wavelength_cells", jarray(cells, 2));
    json_object_object_add(o, "frequency", jarray(freq, 2));
    json_object_object_add(o, "slope", jnum(g->slope));
    json_object_object_add(o, "intercept", jnum(g->intercept));
    json_object_object_add(o, "bins", json_object_new_int64((int64_t)g->bins));
    return o;
}

static json_object *regimes_json(const ft_clarke_model *m)
{
    json_object *a = json_object_new_array();
    for (size_t i = 0; i < m->nregimes; i++)
        json_object_array_add(a, regime_json(m, &m->regimes[i]));
    return a;
}

/* Sentences for the user about the model: a D outside [2, 3] is reported, never silently used. */
static json_object *warnings_json(const ft_clarke_model *m)
{
    json_object *a = json_object_new_array();
    char buf[256];
    if (m->D < 2.0 || m->D > 3.0) {
        snprintf(buf, sizeof buf, "the one power law's D = %.3f lies outside [2, 3]: the spectrum is not one "
                 "fractal law (see \"regimes\")", m->D);
        json_object_array_add(a, json_object_new_string(buf));
    }
    for (size_t i = 0; i < m->nregimes; i++) {
        const ft_clarke_regime *g = &m->regimes[i];
        if (g->D < 2.0 || g->D > 3.0) {
            snprintf(buf, sizeof buf, "regime %zu (wavelengths %.4g-%.4g) has D = %.3f outside [2, 3]", i + 1,
                     g->wavelength_lo, g->wavelength_hi, g->D);
            json_object_array_add(a, json_object_new_string(buf));
        }
    }
    if (m->nspectrum > 0 && m->nregimes == 0)
        json_object_array_add(a, json_object_new_string("the regime search found no straight run in the spectrum"));
    return a;
}

/* Shortest and longest wavelength of the grid (the regression's range). */
static void wavelength_range(const ft_clarke_model *m, double range[2])
{
    double cx = hypot(m->gt[1], m->gt[4]), cy = hypot(m->gt[2], m->gt[5]);
    range[0] = 1.0 / hypot(0.5 / cx, 0.5 / cy);
    range[1] = fmax((double)m->nx * cx, (double)m->ny * cy);
}

static json_object *model_to_json(const ft_clarke_model *m)
{
    json_object *o = json_object_new_object(), *t = json_object_new_object(), *orig = json_object_new_object();
    double range[2];
    wavelength_range(m, range);
    json_object_object_add(o, "method", json_object_new_string("clarke"));
    json_object_object_add(o, "model", json_object_new_string(MODEL_NAME));
    json_object_object_add(o, "format_version", json_object_new_int(MODEL_FORMAT_VERSION));
    json_object_object_add(o, "noise", json_object_new_string(m->noise == FT_CLARKE_NOISE_SPECTRUM ? "spectrum"
                                                                                                   : "power-law"));
    json_object_object_add(o, "D", jnum(m->D));
    json_object_object_add(o, "D_clarke_eq8", jnum(m->D_clarke_eq8));
    json_object_object_add(o, "r2", jnum(m->r2));
    json_object_object_add(o, "stderr", jnum(0.5 * m->stderr_slope));
    json_object_object_add(o, "range", jarray(range, 2));
    json_object_object_add(o, "c", jnum(m->c));
    json_object_object_add(o, "grid", grid_json(m));
    json_object_object_add(orig, "mean", jnum(m->mean));
    json_object_object_add(orig, "sd", jnum(m->sd));
    json_object_object_add(orig, "valid", json_object_new_int64((int64_t)m->valid));
    json_object_object_add(orig, "nodata_filled", json_object_new_int64((int64_t)m->nodata_filled));
    json_object_object_add(o, "original", orig);
    json_object_object_add(t, "beta0", jnum(m->beta0));
    json_object_object_add(t, "beta1", jnum(m->beta1));
    json_object_object_add(t, "beta2", jnum(m->beta2));
    json_object_object_add(t, "r2", jnum(m->trend_r2));
    json_object_object_add(o, "trend", t);
    json_object_object_add(o, "harmonics", harmonics_json(m));
    json_object_object_add(o, "regression", regression_json(m));
    json_object_object_add(o, "regimes", regimes_json(m));
    json_object_object_add(o, "breaks", jarray(m->breaks, m->nregimes > 1 ? m->nregimes - 1 : 0));
    json_object_object_add(o, "spectrum", spectrum_json(m));
    json_object_object_add(o, "warnings", warnings_json(m));
    return o;
}

static const int json_flags = JSON_C_TO_STRING_PRETTY | JSON_C_TO_STRING_SPACED | JSON_C_TO_STRING_NOSLASHESCAPE;

char *ft_io_clarke_model_to_json(const ft_clarke_model *m)
{
    if (m == NULL) {
        ft_error(FT_E_INVALID, "ft_io_clarke_model_to_json: NULL model");
        return NULL;
    }
    json_object *o = model_to_json(m);
    char *text = o ? ft_strdup(json_object_to_json_string_ext(o, json_flags)) : NULL;
    json_object_put(o);
    if (text == NULL)
        ft_error(FT_E_NOMEM, "out of memory for the model's JSON");
    return text;
}

static int write_model(FILE *f, const void *arg)
{
    const char *text = json_object_to_json_string_ext((json_object *)arg, json_flags);
    return fputs(text, f) < 0 || fputc('\n', f) == EOF ? FT_E_IO : FT_OK;
}

int ft_io_write_clarke_model(const char *path, const ft_clarke_model *m)
{
    if (m == NULL)
        return ft_error(FT_E_INVALID, "ft_io_write_clarke_model: NULL model");
    json_object *o = model_to_json(m);
    if (o == NULL)
        return ft_error(FT_E_NOMEM, "out of memory for the model's JSON");
    int rc = ft_io_atomic_write(path, write_model, o);
    json_object_put(o);
    return rc;
}

/* ---- reading ---- */

typedef struct {
    const char *what; /* the file, for messages */
    int rc;           /* first error */
} reader;

static json_object *get(reader *r, json_object *o, const char *parent, const char *key, json_type type)
{
    json_object *v = NULL;
    if (r->rc != FT_OK)
        return NULL;
    int found = o && json_object_object_get_ex(o, key, &v);
    int ok = found && v && (json_object_is_type(v, type) ||
                            (type == json_type_double && json_object_is_type(v, json_type_int)));
    if (!ok) {
        const char *kind = type == json_type_double || type == json_type_int ? "a number"
                           : type == json_type_object                       ? "an object"
                           : type == json_type_array                        ? "an array"
                                                                             : "a string";
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"%s%s%s\" is %s, it must be %s", r->what, parent, *parent ? "." : "",
                         key, found ? "malformed" : "missing", kind);
        return NULL;
    }
    return v;
}

static double num(reader *r, json_object *o, const char *parent, const char *key)
{
    json_object *v = get(r, o, parent, key, json_type_double);
    double d = v ? json_object_get_double(v) : 0.0;
    if (v && !isfinite(d))
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"%s.%s\" is not a finite number", r->what, parent, key);
    return d;
}

/* An integer in [min, max]; 0 (and the error set) when it is missing or out of range. json-c saturates
 * integers beyond 64 bits, so those too are reported as out of range rather than read as some other value. */
static long long integer(reader *r, json_object *o, const char *parent, const char *key, long long min, long long max)
{
    json_object *v = get(r, o, parent, key, json_type_int);
    long long i = v ? (long long)json_object_get_int64(v) : 0;
    if (v && (i < min || i > max)) {
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"%s.%s\" must be an integer in [%lld, %lld], got %s", r->what, parent,
                         key, min, max, json_object_to_json_string(v));
        return 0;
    }
    return i;
}

/* Element i of an array as a number (ints accepted). */
static double element(reader *r, json_object *a, const char *key, size_t i)
{
    json_object *v = a ? json_object_array_get_idx(a, i) : NULL;
    if (r->rc == FT_OK && (v == NULL || !(json_object_is_type(v, json_type_double) || json_object_is_type(v, json_type_int)))) {
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"%s\" element %zu is missing or not a number", r->what, key, i);
        return 0.0;
    }
    return v ? json_object_get_double(v) : 0.0;
}

static void read_grid(reader *r, json_object *o, ft_clarke_model *m)
{
    json_object *g = get(r, o, "", "grid", json_type_object);
    json_object *size = get(r, g, "grid", "size", json_type_array);
    json_object *gt = get(r, g, "grid", "geotransform", json_type_array);
    if (r->rc == FT_OK && (json_object_array_length(size) != 2 || json_object_array_length(gt) != 6))
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"grid.size\" needs 2 numbers and \"grid.geotransform\" 6", r->what);
    double nx = element(r, size, "grid.size", 0), ny = element(r, size, "grid.size", 1);
    if (r->rc == FT_OK && (!(nx >= 2.0 && nx <= 1e9) || !(ny >= 2.0 && ny <= 1e9) || nx != floor(nx) || ny != floor(ny)))
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"grid.size\" must be two integers >= 2, got [%g, %g]", r->what, nx, ny);
    if (r->rc == FT_OK) {
        m->nx = (size_t)nx;
        m->ny = (size_t)ny;
    }
    for (size_t i = 0; i < 6; i++)
        m->gt[i] = element(r, gt, "grid.geotransform", i);
    json_object *crs = NULL;
    if (r->rc == FT_OK && g && json_object_object_get_ex(g, "crs", &crs) && crs) {
        if (!json_object_is_type(crs, json_type_string))
            r->rc = ft_error(FT_E_FORMAT, "%s: key \"grid.crs\" must be a WKT string or null", r->what);
        else if ((m->crs_wkt = ft_strdup(json_object_get_string(crs))) == NULL)
            r->rc = ft_error(FT_E_NOMEM, "%s: out of memory for the CRS", r->what);
    }
}

static void read_harmonic(reader *r, json_object *h, ft_clarke_harmonic *out)
{
    out->k = (int)integer(r, h, "harmonics.list[]", "k", 0, INT32_MAX);
    out->l = (int)integer(r, h, "harmonics.list[]", "l", -(long long)INT32_MAX, INT32_MAX);
    out->a = num(r, h, "harmonics.list[]", "a");
    out->b = num(r, h, "harmonics.list[]", "b");
    out->power = out->a * out->a + out->b * out->b;
    out->share = num(r, h, "harmonics.list[]", "share");
    out->wavelength = num(r, h, "harmonics.list[]", "wavelength");
    out->direction = num(r, h, "harmonics.list[]", "direction");
}

static int read_harmonics(reader *r, json_object *o, ft_clarke_model **mp)
{
    json_object *hs = get(r, o, "", "harmonics", json_type_object);
    json_object *list = get(r, hs, "harmonics", "list", json_type_array);
    if (r->rc != FT_OK)
        return r->rc;
    size_t n = json_object_array_length(list);
    if ((*mp = ft_clarke_model_create(n)) == NULL)
        return r->rc = ft_last_error_code();
    (*mp)->cutoff = num(r, hs, "harmonics", "cutoff");
    (*mp)->harmonic_share = num(r, hs, "harmonics", "share");
    for (size_t i = 0; i < n && r->rc == FT_OK; i++) {
        json_object *h = json_object_array_get_idx(list, i);
        if (!json_object_is_type(h, json_type_object))
            r->rc = ft_error(FT_E_FORMAT, "%s: key \"harmonics.list\" element %zu is not an object", r->what, i);
        else
            read_harmonic(r, h, &(*mp)->harmonics[i]);
    }
    return r->rc;
}

static void read_scalars(reader *r, json_object *o, ft_clarke_model *m)
{
    json_object *t = get(r, o, "", "trend", json_type_object);
    json_object *orig = get(r, o, "", "original", json_type_object);
    json_object *reg = get(r, o, "", "regression", json_type_object);
    m->beta0 = num(r, t, "trend", "beta0");
    m->beta1 = num(r, t, "trend", "beta1");
    m->beta2 = num(r, t, "trend", "beta2");
    m->trend_r2 = num(r, t, "trend", "r2");
    m->mean = num(r, orig, "original", "mean");
    m->sd = num(r, orig, "original", "sd");
    m->valid = (size_t)integer(r, orig, "original", "valid", 0, LLONG_MAX);
    m->nodata_filled = (size_t)integer(r, orig, "original", "nodata_filled", 0, LLONG_MAX);
    m->slope = num(r, reg, "regression", "slope");
    m->intercept = num(r, reg, "regression", "intercept");
    m->r2 = num(r, reg, "regression", "r2");
    m->stderr_slope = num(r, reg, "regression", "stderr_slope");
    m->npairs = (size_t)integer(r, reg, "regression", "pairs", 0, LLONG_MAX);
    json_object *taper = get(r, reg, "regression", "taper", json_type_string);
    m->taper = taper && strcmp(json_object_get_string(taper), "hann") == 0;
    m->min_wavelength = num(r, reg, "regression", "min_wavelength_cells");
    m->D = num(r, o, "", "D");
    m->D_clarke_eq8 = num(r, o, "", "D_clarke_eq8");
    m->c = num(r, o, "", "c");
    if (r->rc == FT_OK && m->sd < 0.0)
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"original.sd\" must be >= 0, got %g", r->what, m->sd);
}

/* A numeric array of exactly n elements (n = SIZE_MAX: any length, set into *n_out) into a new buffer. */
static double *num_array(reader *r, json_object *o, const char *parent, const char *key, size_t *n)
{
    json_object *a = get(r, o, parent, key, json_type_array);
    if (a == NULL)
        return NULL;
    size_t len = json_object_array_length(a);
    if (*n != SIZE_MAX && len != *n) {
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"%s.%s\" has %zu elements, %zu expected", r->what, parent, key, len,
                         *n);
        return NULL;
    }
    *n = len;
    double *v = ft_malloc((len ? len : 1) * sizeof *v);
    if (v == NULL) {
        r->rc = ft_last_error_code();
        return NULL;
    }
    char name[64];
    snprintf(name, sizeof name, "%s.%s", parent, key);
    for (size_t i = 0; i < len && r->rc == FT_OK; i++)
        v[i] = element(r, a, name, i);
    return v;
}

static void read_spectrum(reader *r, json_object *o, ft_clarke_model *m)
{
    json_object *sp = get(r, o, "", "spectrum", json_type_object);
    size_t n = SIZE_MAX;
    m->spectrum_wavelength = num_array(r, sp, "spectrum", "wavelength", &n);
    if (r->rc == FT_OK)
        m->nspectrum = n;
    m->spectrum_power = num_array(r, sp, "spectrum", "power", &n);
    m->spectrum_count = num_array(r, sp, "spectrum", "waves", &n);
}

static void read_regime(reader *r, json_object *g, ft_clarke_regime *out)
{
    size_t two = 2;
    double *wl = num_array(r, g, "regimes[]", "wavelength", &two);
    if (wl) {
        out->wavelength_lo = wl[0];
        out->wavelength_hi = wl[1];
    }
    free(wl);
    out->D = num(r, g, "regimes[]", "D");
    out->stderr_D = num(r, g, "regimes[]", "stderr");
    out->r2 = num(r, g, "regimes[]", "r2");
    out->slope = num(r, g, "regimes[]", "slope");
    out->intercept = num(r, g, "regimes[]", "intercept");
    out->bins = (size_t)integer(r, g, "regimes[]", "bins", 0, LLONG_MAX);
}

static void read_regimes(reader *r, json_object *o, ft_clarke_model *m)
{
    json_object *list = get(r, o, "", "regimes", json_type_array);
    size_t n = list ? json_object_array_length(list) : 0;
    if (r->rc != FT_OK || n == 0)
        return;
    if ((m->regimes = ft_calloc(n, sizeof *m->regimes)) == NULL) {
        r->rc = ft_last_error_code();
        return;
    }
    m->nregimes = n;
    for (size_t i = 0; i < n && r->rc == FT_OK; i++) {
        json_object *g = json_object_array_get_idx(list, i);
        if (!json_object_is_type(g, json_type_object))
            r->rc = ft_error(FT_E_FORMAT, "%s: key \"regimes\" element %zu is not an object", r->what, i);
        else
            read_regime(r, g, &m->regimes[i]);
    }
    size_t nb = n - 1;
    m->breaks = num_array(r, o, "", "breaks", &nb);
}

/* Format 2's F: the noise kind, the measured spectrum and its regimes. */
static void read_noise(reader *r, json_object *o, ft_clarke_model *m)
{
    json_object *noise = get(r, o, "", "noise", json_type_string);
    if (noise && strcmp(json_object_get_string(noise), "spectrum") == 0)
        m->noise = FT_CLARKE_NOISE_SPECTRUM;
    else if (noise && strcmp(json_object_get_string(noise), "power-law") == 0)
        m->noise = FT_CLARKE_NOISE_POWER_LAW;
    else if (noise)
        r->rc = ft_error(FT_E_FORMAT, "%s: key \"noise\" is \"%s\", it must be \"spectrum\" or \"power-law\"",
                         r->what, json_object_get_string(noise));
    read_spectrum(r, o, m);
    read_regimes(r, o, m);
}

/* The file's format version: 1 when absent (files written before format 2). */
static long long format_version(reader *r, json_object *o)
{
    json_object *v = NULL;
    if (!json_object_object_get_ex(o, "format_version", &v))
        return 1;
    return integer(r, o, "", "format_version", 1, MODEL_FORMAT_VERSION);
}

static int model_from_json(json_object *o, const char *what, ft_clarke_model **out)
{
    reader r = {what, FT_OK};
    *out = NULL;
    json_object *name = get(&r, o, "", "model", json_type_string);
    if (name && strcmp(json_object_get_string(name), MODEL_NAME) != 0)
        r.rc = ft_error(FT_E_FORMAT, "%s: key \"model\" is \"%s\", not \"%s\"", what, json_object_get_string(name),
                        MODEL_NAME);
    ft_clarke_model *m = NULL;
    long long version = format_version(&r, o);
    if (read_harmonics(&r, o, &m) == FT_OK) {
        read_grid(&r, o, m);
        read_scalars(&r, o, m);
        if (version >= 2)
            read_noise(&r, o, m);
    }
    if (r.rc != FT_OK) {
        ft_clarke_model_free(m);
        return r.rc;
    }
    *out = m;
    return FT_OK;
}

/* The whole file into a malloc'd, NUL-terminated buffer. */
static int slurp(const char *path, char **buf, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return ft_error(FT_E_IO, "cannot open '%s': %s", path, strerror(errno));
    size_t n = 0, cap = 4096;
    char *b = malloc(cap);
    size_t got;
    while (b != NULL && (got = fread(b + n, 1, cap - n - 1, f)) > 0) {
        n += got;
        if (n + 1 == cap) {
            char *more = cap < ((size_t)1 << 30) ? realloc(b, 2 * cap) : NULL;
            if (more == NULL)
                free(b);
            b = more;
            cap *= 2;
        }
    }
    int bad = ferror(f);
    fclose(f);
    if (b == NULL || bad) {
        free(b);
        return b == NULL ? ft_error(FT_E_NOMEM, "%s: too large for a model file", path)
                         : ft_error(FT_E_IO, "cannot read '%s': %s", path, strerror(errno));
    }
    b[n] = '\0';
    *buf = b;
    *len = n;
    return FT_OK;
}

/* Parses a model file with messages in the user's terms: empty, cut short, or broken at a byte offset. */
static int parse_file(const char *path, json_object **out)
{
    char *buf = NULL;
    size_t len = 0;
    int rc = slurp(path, &buf, &len);
    if (rc != FT_OK)
        return rc;
    size_t lead = strspn(buf, " \t\r\n");
    if (lead == len) {
        free(buf);
        return ft_error(FT_E_FORMAT, "%s is empty: a model file is the JSON object 'fracterra model fit -o' writes",
                        path);
    }
    if (strlen(buf) != len) {
        free(buf);
        return ft_error(FT_E_FORMAT, "%s is not a text file (it holds a NUL byte): not a model file", path);
    }
    json_tokener *tok = json_tokener_new();
    if (tok == NULL) {
        free(buf);
        return ft_error(FT_E_NOMEM, "out of memory reading %s", path);
    }
    json_object *o = json_tokener_parse_ex(tok, buf, (int)(len > INT_MAX ? INT_MAX : len));
    enum json_tokener_error err = json_tokener_get_error(tok);
    size_t at = json_tokener_get_parse_end(tok);
    if (o != NULL && at + strspn(buf + at, " \t\r\n") != len) {
        json_object_put(o);
        o = NULL;
        rc = ft_error(FT_E_FORMAT, "%s: unexpected text after the model's JSON object at byte %zu", path, at);
    } else if (o == NULL && err == json_tokener_continue) {
        rc = ft_error(FT_E_FORMAT, "%s ends before its JSON is complete (%zu bytes): the file is truncated", path, len);
    } else if (o == NULL) {
        rc = ft_error(FT_E_FORMAT, "%s is not valid JSON: the text breaks off at byte %zu", path, at);
    }
    json_tokener_free(tok);
    free(buf);
    *out = o;
    return rc;
}

int ft_io_read_clarke_model(const char *path, ft_clarke_model **out)
{
    if (out == NULL || path == NULL)
        return ft_error(FT_E_INVALID, "ft_io_read_clarke_model: NULL path or out");
    *out = NULL;
    json_object *o = NULL;
    int rc = parse_file(path, &o);
    if (rc != FT_OK)
        return rc;
    rc = json_object_is_type(o, json_type_object)
                 ? model_from_json(o, path, out)
                 : ft_error(FT_E_FORMAT, "%s: a model must be a JSON object", path);
    json_object_put(o);
    return rc;
}
