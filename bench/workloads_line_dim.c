/* fracterra — workloads_line_dim.c: chain-dimension workloads of `make bench` (speed targets:
 * divider over 16 rulers and box counting over 12 sizes of a 1,000,000-vertex chain, each under 0.5 s).
 *
 * Input, built in each child before timing (deterministic, no RNG): a midpoint-generator curve of
 * dimension 1.3 (each segment becomes two legs at base angle a, cos a = 2^(1/1.3 - 1); apex on the left
 * at even levels, on the right at odd ones), 20 levels (1,048,577 vertices) cut to its first 1,000,000
 * vertices, scaled to 100 km. The automatic scale range is used (2 x the median segment to a quarter of
 * the diagonal for the divider; the median segment to 1/48 of it for boxes), with the default 4 x 4 grid
 * offsets. No peer: no installed tool measures the dimension of a line.
 *
 * line.divider.1m.lonlat (speed target: at most 3 x line.divider.1m): the same curve laid at
 * 50 N in longitude/latitude degrees (x / metres per degree of longitude, y / metres per degree of
 * latitude there, WGS 84), walked on the ellipsoid (opts.ellipsoid): the chain is turned into Earth-centred
 * points once, then the 16 walks step by 3-D chords.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/fracterra.h"

#define CURVE_LEVELS 20
#define CURVE_VERTICES 1000000
#define CURVE_D 1.3

static ft_chain *curve; /* built in the child by prepare */

static int build_curve(void)
{
    const size_t n = ((size_t)1 << CURVE_LEVELS) + 1;
    ft_chain *c = ft_chain_create(n, 0);
    if (c == NULL)
        return ft_last_error_code();
    double *x = c->x, *y = c->y;
    for (size_t i = 0; i < n; i++)
        x[i] = y[i] = 0.0;
    x[n - 1] = 100000.0;
    const double ca = pow(2.0, 1.0 / CURVE_D - 1.0), half_tan = 0.5 * sqrt(1.0 - ca * ca) / ca;
    for (int l = 0; l < CURVE_LEVELS; l++) {
        size_t step = (n - 1) >> l, half = step / 2;
        double side = l % 2 == 0 ? 1.0 : -1.0;
        for (size_t i = 0; i + step < n; i += step) {
            double dx = x[i + step] - x[i], dy = y[i + step] - y[i];
            x[i + half] = x[i] + 0.5 * dx - side * half_tan * dy;
            y[i + half] = y[i] + 0.5 * dy + side * half_tan * dx;
        }
    }
    c->n = CURVE_VERTICES;
    curve = c;
    return FT_OK;
}

static int line_setup(ft_bench_case *c)
{
    c->work = CURVE_VERTICES;
    c->peer_none = "none: no installed tool measures the fractal dimension of a line";
    return FT_OK;
}

static int line_prepare(ft_bench_case *c)
{
    (void)c;
    return build_curve();
}

static const ft_ellipsoid wgs84 = FT_ELLIPSOID_WGS84;
static int lonlat; /* 1: the curve is in degrees, walked on wgs84 */

static int lonlat_prepare(ft_bench_case *c)
{
    (void)c;
    int rc = build_curve();
    double per_lon, per_lat;
    ft_ellipsoid_metres_per_degree(&wgs84, 50.0, &per_lon, &per_lat);
    for (size_t i = 0; rc == FT_OK && i < curve->n; i++) {
        curve->x[i] = 6.0 + curve->x[i] / per_lon;
        curve->y[i] = 50.0 + curve->y[i] / per_lat;
    }
    lonlat = 1;
    return rc;
}

static int run_method(ft_line_method m, int nscales)
{
    const ft_chain *cs[] = {curve};
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    o.nscales = nscales;
    o.ellipsoid = lonlat ? &wgs84 : NULL;
    ft_dim_result *r = NULL;
    int rc = ft_line_dim(cs, 1, m, &o, &r);
    ft_dim_result_free(r);
    return rc;
}

static int divider_run(ft_bench_case *c)
{
    (void)c;
    return run_method(FT_LINE_DIVIDER, 16);
}

static int box_run(ft_bench_case *c)
{
    (void)c;
    return run_method(FT_LINE_BOX, 12);
}

static const ft_bench_workload line_dim_workloads[] = {
    {"line.divider.1m", "ft_line_dim divider, 16 rulers, both ends, on a 1,000,000-vertex D = 1.3 curve",
     FT_BENCH_VERTICES, line_setup, line_prepare, divider_run, NULL},
    {"line.divider.1m.lonlat", "ft_line_dim divider, 16 rulers, both ends, on that curve in lon/lat at 50 N, "
     "walked on the WGS 84 ellipsoid (target: <= 3 x line.divider.1m)", FT_BENCH_VERTICES, line_setup,
     lonlat_prepare, divider_run, NULL},
    {"line.box.1m", "ft_line_dim box counting, 12 sizes x 16 grid offsets, on the same curve", FT_BENCH_VERTICES,
     line_setup, line_prepare, box_run, NULL},
};

const ft_bench_suite ft_bench_suite_line_dim = {"line_dim", line_dim_workloads,
                                                sizeof line_dim_workloads / sizeof line_dim_workloads[0]};
