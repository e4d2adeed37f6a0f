/* fracterra — workloads_urban.c: urban morphology workloads of `make bench` (speed targets: box
 * counting a layer of 100,000 polygons over 10 box sizes in under 2 s; the boundary generator producing
 * 1,000,000 vertices in under 0.5 s).
 *
 * Inputs, generated in each forked child before the timed call (untimed):
 *  - a synthetic parcel map: 400 x 250 quadrilateral parcels of about 20 m x 30 m tiling a 8 km x 7.5 km
 *    block, every shared corner moved by up to 4 m (seed 20240504), so parcels share their edges exactly
 *    as a cadastral coverage does; 100,000 polygons, 400,000 vertices;
 *  - a city outline: a ring of 1,000 vertices on a circle of 5 km radius (equal chords of 31.4 m), given
 *    D = 1.25, jitter 0.1 and min = 1.15 l_10 (about ten subdivision levels): 1,086,040 vertices.
 * No peer: GDAL rasterizes (gdal_rasterize) but does not box-count, and no tool implements the generator.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>

#include "fracterra/fracterra.h"

#define PARCELS_X 400
#define PARCELS_Y 250
#define PARCEL_W 20.0
#define PARCEL_H 30.0
#define CORNER_JITTER 4.0
#define BENCH_SEED UINT64_C(20240504)
#define OUTLINE_N 1000
#define OUTLINE_R 5000.0
#define OUTLINE_D 1.25
#define OUTLINE_LEVELS 10

static const double pi = 3.14159265358979323846;

typedef struct {
    ft_layer *parcels;
    ft_chain *outline;
} urban_state;

static urban_state state;

/* Corner (i, j) of the parcel grid, moved by its own draw. */
static void corner(const double *dx, const double *dy, size_t i, size_t j, double *x, double *y)
{
    size_t k = j * (PARCELS_X + 1) + i;
    *x = 400000.0 + PARCEL_W * (double)i + dx[k];
    *y = 3400000.0 + PARCEL_H * (double)j + dy[k];
}

static int make_parcels(ft_bench_case *c)
{
    const size_t nc = (PARCELS_X + 1) * (PARCELS_Y + 1);
    ft_rng *r = ft_rng_create(BENCH_SEED, 1);
    double *dx = malloc(nc * sizeof *dx), *dy = malloc(nc * sizeof *dy);
    state.parcels = ft_layer_create("parcels", NULL);
    if (r == NULL || dx == NULL || dy == NULL || state.parcels == NULL) {
        ft_rng_free(r);
        free(dx);
        free(dy);
        return ft_error(FT_E_NOMEM, "parcels: out of memory");
    }
    for (size_t k = 0; k < nc; k++) {
        dx[k] = CORNER_JITTER * (2.0 * ft_rng_uniform(r) - 1.0);
        dy[k] = CORNER_JITTER * (2.0 * ft_rng_uniform(r) - 1.0);
    }
    int rc = FT_OK;
    for (size_t j = 0; rc == FT_OK && j < PARCELS_Y; j++)
        for (size_t i = 0; rc == FT_OK && i < PARCELS_X; i++) {
            ft_chain *ring = ft_chain_create(4, 1);
            if (ring == NULL || ft_layer_add_feature(state.parcels, (int64_t)(j * PARCELS_X + i), FT_GEOM_POLYGON,
                                                     0) < 0) {
                ft_chain_free(ring);
                rc = FT_E_NOMEM;
                break;
            }
            double x, y;
            const size_t ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
            for (int v = 0; v < 4; v++) {
                corner(dx, dy, ci[v], cj[v], &x, &y);
                ft_chain_push(ring, x, y);
            }
            rc = ft_layer_add_part(state.parcels, ring, FT_ROLE_OUTER, 0);
        }
    ft_rng_free(r);
    free(dx);
    free(dy);
    c->state = &state;
    c->work = (double)ft_layer_vertex_count(state.parcels);
    return rc;
}

static int run_boxcount(ft_bench_case *c, ft_area_what what)
{
    urban_state *s = c->state;
    ft_area_dim_opts o = FT_AREA_DIM_OPTS_DEFAULT;
    o.what = what;
    o.nscales = 10;
    ft_dim_result *r = NULL;
    int rc = ft_urban_dim_area(s->parcels, NULL, 0, &o, &r);
    ft_dim_result_free(r);
    return rc;
}

static int run_boxcount_area(ft_bench_case *c)
{
    return run_boxcount(c, FT_AREA_AREA);
}

static int run_boxcount_boundary(ft_bench_case *c)
{
    return run_boxcount(c, FT_AREA_BOUNDARY);
}

static int make_outline(ft_bench_case *c)
{
    state.outline = ft_chain_create(OUTLINE_N, 1);
    if (state.outline == NULL)
        return FT_E_NOMEM;
    for (size_t i = 0; i < OUTLINE_N; i++) {
        double t = 2.0 * pi * (double)i / OUTLINE_N;
        ft_chain_push(state.outline, OUTLINE_R * cos(t), OUTLINE_R * sin(t));
    }
    c->state = &state;
    return FT_OK;
}

static int run_boundary(ft_bench_case *c)
{
    urban_state *s = c->state;
    ft_boundary_opts o = FT_BOUNDARY_OPTS_DEFAULT;
    o.dim = OUTLINE_D;
    o.jitter = 0.1;
    o.seed = BENCH_SEED;
    double chord = ft_urban_chord_avg(s->outline);
    /* l_10 plus 15 %: jittered legs vary by a few per cent, so this stops after about ten levels */
    o.min = chord * pow(2.0 * cos(ft_urban_angle_for_dim(OUTLINE_D)), -OUTLINE_LEVELS) * 1.15;
    ft_chain *out = NULL;
    int rc = ft_urban_boundary(s->outline, &o, &out);
    if (rc == FT_OK)
        c->work = (double)out->n;
    ft_chain_free(out);
    return rc;
}

static int setup_boxcount(ft_bench_case *c)
{
    c->work = 4.0 * PARCELS_X * PARCELS_Y;
    c->peer_none = "GDAL rasterizes (gdal_rasterize) but does not count boxes";
    return FT_OK;
}

static int setup_boundary(ft_bench_case *c)
{
    c->work = (double)OUTLINE_N * (1 << OUTLINE_LEVELS);
    c->peer_none = "no other tool implements the midpoint-subdivision generator";
    return FT_OK;
}

static const ft_bench_workload workloads[] = {
    {"urban.boxcount.area.100k", "ft_urban_dim_area, area: 100,000 parcels (400,000 vertices), 10 box sizes, 4x4 "
     "offsets", FT_BENCH_VERTICES, setup_boxcount, make_parcels, run_boxcount_area, NULL},
    {"urban.boxcount.boundary.100k", "ft_urban_dim_area, boundary: the same parcels, 10 box sizes, 4x4 offsets",
     FT_BENCH_VERTICES, setup_boxcount, make_parcels, run_boxcount_boundary, NULL},
    {"urban.boundary.1m", "ft_urban_boundary: a 1,000-vertex ring to 1,086,040 vertices (D 1.25, jitter 0.1, about "
     "10 levels)", FT_BENCH_VERTICES, setup_boundary, make_outline, run_boundary, NULL},
};

const ft_bench_suite ft_bench_suite_urban = {"urban", workloads, sizeof workloads / sizeof workloads[0]};
