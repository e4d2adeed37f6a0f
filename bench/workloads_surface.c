/* fracterra — workloads_surface.c: the grid dimension estimators of `make bench` (speed):
 *
 *  - surface.<method>.<n>: ft_surface_dim with the method's defaults on an n x n fft surface of D = 2.5
 *    (prepared untimed in the child), n = 2048 and 4096, every method; the lag methods exhaustive (every
 *    pair of every cell along rows and columns, lags 1 .. n/8);
 *  - surface.spectrum.holes.4096: the spectrum of the 4096² surface with 10 % of its cells in nodata
 *    blobs of radius 5-25 cells (the differences touching them left out: the same work as without);
 *  - surface.map.4096.t1 / .t2: ft_surface_dim_map of the 4096² surface, variogram, 64-cell windows, step
 *    16 (64,009 windows; block sums of the pair counters, src/surface/dim_map_lags.c), whole-range fits,
 *    on 1 and 2 threads.
 * (Variogram with 32,000 random points: surface.variogram.32k in workloads_terrain.c.)
 *
 * Peers: Gwyddion's four estimators in process, when the bench was built with libgwyddion
 * (FT_HAVE_GWYDDION, optional at configure time): variogram <-> gwy_data_field_fractal_partitioning,
 * cubes <-> _cubecounting, prism <-> _triangulation, spectrum <-> _psdf, each with its _dim fit, on the
 * same grid copied into a GwyDataField untimed. Gwyddion resamples the field to 2^k + 1 cells per side
 * (linear interpolation, inside the timed call) where fracterra uses every cell as it is.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"

#ifdef FT_HAVE_GWYDDION
#include <libgwyddion/gwyddion.h>
#include <libprocess/gwyprocess.h>
#endif

#define SURF_DIM 2.5
#define SURF_SEED UINT64_C(20240601)
#define MAP_N 4096
#define MAP_WINDOW 64
#define MAP_STEP 16

static ft_grid *held; /* in the child only */

static int surface_of(size_t n)
{
    ft_synth_opts o = FT_SYNTH_OPTS_DEFAULT;
    o.dim = SURF_DIM;
    o.seed = SURF_SEED;
    return ft_terrain_synth(n, n, &o, &held);
}

static int prepare_2048(ft_bench_case *c)
{
    (void)c;
    return surface_of(2048);
}

static int prepare_4096(ft_bench_case *c)
{
    (void)c;
    return surface_of(4096);
}

/* The 4096² surface with 10 % of its cells in nodata discs of random centres and radii 5-25 cells. */
static int prepare_holes_4096(ft_bench_case *c)
{
    (void)c;
    int rc = surface_of(4096);
    if (rc != FT_OK || (rc = ft_grid_ensure_mask(held)) != FT_OK)
        return rc;
    ft_rng *rng = ft_rng_create(SURF_SEED, 1);
    if (rng == NULL)
        return FT_E_NOMEM;
    size_t n = held->nx, holes = 0;
    while ((double)holes < 0.10 * (double)(n * n)) {
        double cx = ft_rng_uniform(rng) * (double)n, cy = ft_rng_uniform(rng) * (double)n;
        double rad = 5.0 + 20.0 * ft_rng_uniform(rng);
        for (long i = (long)(cy - rad); i <= (long)(cy + rad) + 1; i++)
            for (long j = (long)(cx - rad); j <= (long)(cx + rad) + 1; j++) {
                if (i < 0 || j < 0 || i >= (long)n || j >= (long)n)
                    continue;
                size_t k = (size_t)i * n + (size_t)j;
                if (held->mask[k] && hypot((double)j - cx, (double)i - cy) < rad) {
                    held->mask[k] = 0;
                    holes++;
                }
            }
    }
    ft_rng_free(rng);
    return FT_OK;
}

static int setup_holes(ft_bench_case *c)
{
    c->work = 4096.0 * 4096.0;
    c->peer_none = "none: Gwyddion's fractal PSDF takes no mask";
    return FT_OK;
}

static int measure(ft_surface_method m)
{
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim(held, m, NULL, &r);
    ft_dim_result_free(r);
    return rc;
}

#define RUN_METHOD(name, m)                                                                                  \
    static int run_##name(ft_bench_case *c)                                                                  \
    {                                                                                                        \
        (void)c;                                                                                             \
        return measure(m);                                                                                   \
    }
RUN_METHOD(variogram, FT_SURFACE_VARIOGRAM)
RUN_METHOD(yokoya, FT_SURFACE_YOKOYA)
RUN_METHOD(pentland, FT_SURFACE_PENTLAND)
RUN_METHOD(spectrum, FT_SURFACE_SPECTRUM)
RUN_METHOD(prism, FT_SURFACE_PRISM)
RUN_METHOD(cubes, FT_SURFACE_CUBES)

/* The variogram without the noise model (its cost against surface.variogram.4096). */
static int run_variogram_nonoise(ft_bench_case *c)
{
    (void)c;
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.noise.mode = -1;
    ft_dim_result *r = NULL;
    int rc = ft_surface_dim(held, FT_SURFACE_VARIOGRAM, &o, &r);
    ft_dim_result_free(r);
    return rc;
}

/* ---- Gwyddion peers ---- */

#ifdef FT_HAVE_GWYDDION
static GwyDataField *gwy_field;

static int gwy_prepare(ft_bench_case *c, size_t n)
{
    (void)c;
    int rc = surface_of(n);
    if (rc != FT_OK)
        return rc;
    gwy_process_type_init();
    gwy_field = gwy_data_field_new((gint)n, (gint)n, (gdouble)n, (gdouble)n, FALSE);
    gdouble *d = gwy_data_field_get_data(gwy_field);
    for (size_t i = 0; i < n * n; i++)
        d[i] = held->z[i];
    gwy_data_field_invalidate(gwy_field);
    return FT_OK;
}

static int gwy_prepare_2048(ft_bench_case *c)
{
    return gwy_prepare(c, 2048);
}

static int gwy_prepare_4096(ft_bench_case *c)
{
    return gwy_prepare(c, 4096);
}

typedef void (*gwy_fractal_fn)(GwyDataField *, GwyDataLine *, GwyDataLine *, GwyInterpolationType);
typedef gdouble (*gwy_dim_fn)(GwyDataLine *, GwyDataLine *, gdouble *, gdouble *);

static int gwy_run(gwy_fractal_fn f, gwy_dim_fn dim)
{
    GwyDataLine *x = gwy_data_line_new(1, 1.0, FALSE), *y = gwy_data_line_new(1, 1.0, FALSE);
    gdouble a, b;
    f(gwy_field, x, y, GWY_INTERPOLATION_LINEAR);
    volatile gdouble D = dim(x, y, &a, &b);
    (void)D;
    g_object_unref(x);
    g_object_unref(y);
    return FT_OK;
}

#define GWY_RUN(name, f, dim)                                                                                \
    static int gwy_run_##name(ft_bench_case *c)                                                              \
    {                                                                                                        \
        (void)c;                                                                                             \
        return gwy_run(f, dim);                                                                              \
    }
GWY_RUN(partitioning, gwy_data_field_fractal_partitioning, gwy_data_field_fractal_partitioning_dim)
GWY_RUN(cubecounting, gwy_data_field_fractal_cubecounting, gwy_data_field_fractal_cubecounting_dim)
GWY_RUN(triangulation, gwy_data_field_fractal_triangulation, gwy_data_field_fractal_triangulation_dim)
GWY_RUN(psdf, gwy_data_field_fractal_psdf, gwy_data_field_fractal_psdf_dim)
#endif

/* Setup of a method workload on an n x n grid: the work in cells, and the Gwyddion peer if any. */
static int setup_method(ft_bench_case *c, size_t n, ft_surface_method m)
{
    c->work = (double)n * (double)n;
#ifdef FT_HAVE_GWYDDION
    static int (*const runs[FT_SURFACE_NMETHODS])(ft_bench_case *) = {
        gwy_run_partitioning, NULL, NULL, gwy_run_psdf, gwy_run_triangulation, gwy_run_cubecounting};
    static const char *const labels[FT_SURFACE_NMETHODS] = {
        "Gwyddion gwy_data_field_fractal_partitioning + _dim (resampled to 2^k+1)", NULL, NULL,
        "Gwyddion gwy_data_field_fractal_psdf + _dim (row PSDF, Hann)",
        "Gwyddion gwy_data_field_fractal_triangulation + _dim (resampled to 2^k+1)",
        "Gwyddion gwy_data_field_fractal_cubecounting + _dim (resampled to 2^k+1)"};
    if (runs[m] != NULL) {
        c->peer_prepare = n == 2048 ? gwy_prepare_2048 : gwy_prepare_4096;
        c->peer_run = runs[m];
        c->peer_label = labels[m];
        return FT_OK;
    }
    c->peer_none = "none: Gwyddion has no Yokoya or Pentland estimator";
#else
    (void)m;
    c->peer_none = "none: the bench was built without libgwyddion (libgwyddion20-dev)";
#endif
    return FT_OK;
}

#define SETUP(name, n, m)                                                                                    \
    static int setup_##name##_##n(ft_bench_case *c)                                                          \
    {                                                                                                        \
        return setup_method(c, n, m);                                                                        \
    }
SETUP(variogram, 2048, FT_SURFACE_VARIOGRAM)
SETUP(yokoya, 2048, FT_SURFACE_YOKOYA)
SETUP(pentland, 2048, FT_SURFACE_PENTLAND)
SETUP(spectrum, 2048, FT_SURFACE_SPECTRUM)
SETUP(prism, 2048, FT_SURFACE_PRISM)
SETUP(cubes, 2048, FT_SURFACE_CUBES)
SETUP(variogram, 4096, FT_SURFACE_VARIOGRAM)
SETUP(yokoya, 4096, FT_SURFACE_YOKOYA)
SETUP(pentland, 4096, FT_SURFACE_PENTLAND)
SETUP(spectrum, 4096, FT_SURFACE_SPECTRUM)
SETUP(prism, 4096, FT_SURFACE_PRISM)
SETUP(cubes, 4096, FT_SURFACE_CUBES)

/* ---- dim map ---- */

static int map_setup(ft_bench_case *c)
{
    c->work = (double)MAP_N * (double)MAP_N;
    c->peer_none = "none: no installed tool maps local fractal dimension";
    return FT_OK;
}

static int map_prepare(int threads)
{
    omp_set_num_threads(threads);
    return surface_of(MAP_N);
}

static int map_prepare_t1(ft_bench_case *c)
{
    (void)c;
    return map_prepare(1);
}

static int map_prepare_t2(ft_bench_case *c)
{
    (void)c;
    return map_prepare(2);
}

static int map_run(ft_bench_case *c)
{
    (void)c;
    ft_surface_dim_opts o = FT_SURFACE_DIM_OPTS_DEFAULT;
    o.fit_whole_range = 1;
    ft_grid *D = NULL, *r2 = NULL;
    int rc = ft_surface_dim_map(held, MAP_WINDOW, MAP_STEP, FT_SURFACE_VARIOGRAM, &o, &D, &r2);
    ft_grid_free(D);
    ft_grid_free(r2);
    return rc;
}

#define METHOD_WL(name, n, what)                                                                             \
    {"surface." #name "." #n, what " of a " #n "x" #n " fft surface (D = 2.5), default options", FT_BENCH_CELLS, \
     setup_##name##_##n, prepare_##n, run_##name, NULL}

static const ft_bench_workload surface_workloads[] = {
    METHOD_WL(variogram, 2048, "exhaustive variogram D"),
    METHOD_WL(yokoya, 2048, "exhaustive Yokoya D"),
    METHOD_WL(pentland, 2048, "exhaustive Pentland D"),
    METHOD_WL(spectrum, 2048, "power-spectrum D"),
    METHOD_WL(prism, 2048, "triangular prism D"),
    METHOD_WL(cubes, 2048, "cube-counting D"),
    METHOD_WL(variogram, 4096, "exhaustive variogram D"),
    METHOD_WL(yokoya, 4096, "exhaustive Yokoya D"),
    METHOD_WL(pentland, 4096, "exhaustive Pentland D"),
    METHOD_WL(spectrum, 4096, "power-spectrum D"),
    METHOD_WL(prism, 4096, "triangular prism D"),
    METHOD_WL(cubes, 4096, "cube-counting D"),
    {"surface.variogram.nonoise.4096", "exhaustive variogram D of a 4096x4096 fft surface (D = 2.5), "
     "--noise-model off", FT_BENCH_CELLS, setup_variogram_4096, prepare_4096, run_variogram_nonoise, NULL},
    {"surface.spectrum.holes.4096", "power-spectrum D of a 4096x4096 fft surface (D = 2.5) with 10% of its cells in "
     "nodata blobs", FT_BENCH_CELLS, setup_holes, prepare_holes_4096, run_spectrum, NULL},
    {"surface.map.4096.t1", "dim map of a 4096x4096 surface, variogram, 64-cell windows, step 16, 1 thread",
     FT_BENCH_CELLS, map_setup, map_prepare_t1, map_run, NULL},
    {"surface.map.4096.t2", "dim map of a 4096x4096 surface, variogram, 64-cell windows, step 16, 2 threads",
     FT_BENCH_CELLS, map_setup, map_prepare_t2, map_run, NULL},
};

const ft_bench_suite ft_bench_suite_surface = {"surface", surface_workloads,
                                               sizeof surface_workloads / sizeof surface_workloads[0]};
