/* fracterra — workloads_contour.c: the contour mountain workloads of `make bench` (speed targets: a
 * 2,000-vertex seed to a 60-level mountain with the improved method in under 1 s; a contour stack to a 2048²
 * DEM in under 2 s).
 *
 * The seed: a star-shaped ring of 2,000 vertices, r(a) = R (1 + sum_{k=2..40} 0.25 k^-1.2 cos(k a + phi_k)),
 * R = 1,000 m, phases drawn with seed 20240508 (a lobed outline with detail at every scale, like a digitized
 * contour). The mountain: improved method (the paper's best settings, the defaults), interval 10 m, spacing
 * 7 m, 59 levels above the seed, seed 20240508; prepared untimed in the child for the DEM workloads, whose
 * cell gives the grid 2048² (or 256²) cells in all (the seed's box is not square).
 *  - contour.mountain.improved.60: ft_mountain_generate (work: vertices of the 60 levels made);
 *  - contour.dem.2048: ft_contour_stack_to_dem of that stack (work: cells);
 *  - contour.dem.256: the same at 256² cells, for the peer.
 * Peer of the DEM: GRASS GIS r.surf.contour on the same contours rasterized as lines into the same 256²
 * frame (cells crossed by a contour hold its elevation, the others are null; r.surf.contour took 107 s at
 * 512² and more than 5 minutes at 2048² on the bench machine, so the large size has no peer), imported
 * and interpolated through `grass --tmp-location XY --exec` (GRASS 8.2 has no --tmp-project; 8.4 keeps
 * --tmp-location) when grass is on PATH. The mountain has no peer: no other tool implements the contour
 * generation method.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "bench.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"

#define SEED_N 2000
#define SEED_R 1000.0
#define SEED_HARMONICS 40
#define MOUNTAIN_LEVELS 60
#define MOUNTAIN_INTERVAL 10.0
#define MOUNTAIN_SPACING 7.0
#define DEM_SIDE 2048
#define PEER_SIDE 256 /* r.surf.contour takes 107 s at 512² and over 5 minutes at 2048² */
#define BENCH_SEED UINT64_C(20240508)

static const double pi = 3.14159265358979323846;

static ft_polygon_set *held_seed;    /* in the child only */
static ft_contour_stack *held_stack; /* in the child only */

static int make_seed(ft_polygon_set **out)
{
    double phase[SEED_HARMONICS + 1];
    ft_rng *r = ft_rng_create(BENCH_SEED, 1);
    ft_chain *c = ft_chain_create(SEED_N, 1);
    *out = ft_polygon_set_create();
    if (r == NULL || c == NULL || *out == NULL) {
        ft_rng_free(r);
        ft_chain_free(c);
        ft_polygon_set_free(*out);
        *out = NULL;
        return ft_error(FT_E_NOMEM, "contour seed: out of memory");
    }
    for (int k = 2; k <= SEED_HARMONICS; k++)
        phase[k] = 2.0 * pi * ft_rng_uniform(r);
    ft_rng_free(r);
    for (int i = 0; i < SEED_N; i++) {
        double a = 2.0 * pi * i / SEED_N, f = 1.0;
        for (int k = 2; k <= SEED_HARMONICS; k++)
            f += 0.25 * pow(k, -1.2) * cos(k * a + phase[k]);
        ft_chain_push(c, 500000.0 + SEED_R * f * cos(a), 4000000.0 + SEED_R * f * sin(a));
    }
    int rc = ft_polygon_set_add(*out, c, NULL, 0);
    if (rc != FT_OK) {
        ft_chain_free(c);
        ft_polygon_set_free(*out);
        *out = NULL;
    }
    return rc;
}

static int grow(const ft_polygon_set *seed, ft_contour_stack **out)
{
    ft_mountain_opts o = FT_MOUNTAIN_OPTS_DEFAULT;
    o.interval = MOUNTAIN_INTERVAL;
    o.spacing = MOUNTAIN_SPACING;
    o.levels_up = MOUNTAIN_LEVELS - 1;
    o.seed = BENCH_SEED;
    return ft_mountain_generate(seed, &o, out);
}

/* The cell that gives the DEM side² cells in all (the seed's box is not square: about side x side). */
static double dem_cell(const ft_polygon_set *seed, int side)
{
    double x0, y0, x1, y1;
    ft_chain_bbox(seed->polys[0].outer, &x0, &y0, &x1, &y1);
    return sqrt((x1 - x0) * (y1 - y0)) / (side - 2.0);
}

/* ---- contour.mountain.improved.60 ---- */

static int mountain_setup(ft_bench_case *c)
{
    c->work = (double)SEED_N * MOUNTAIN_LEVELS;
    c->peer_none = "none: no other tool implements the contour generation method";
    return FT_OK;
}

static int mountain_prepare(ft_bench_case *c)
{
    (void)c;
    return make_seed(&held_seed);
}

static int mountain_run(ft_bench_case *c)
{
    ft_contour_stack *s = NULL;
    int rc = grow(held_seed, &s);
    if (rc == FT_OK) {
        double v = 0.0;
        for (size_t k = 0; k < s->n; k++)
            v += (double)ft_polygon_set_vertices(s->levels[k].polys);
        c->work = v;
        if (s->n != MOUNTAIN_LEVELS)
            rc = ft_error(FT_E_INVALID, "the bench mountain has %zu levels, not %d", s->n, MOUNTAIN_LEVELS);
    }
    ft_contour_stack_free(s);
    return rc;
}

/* ---- contour.dem.2048, contour.dem.256 ---- */

/* Sets every cell crossed by segment a-b (sampled every quarter cell) to z. */
static void burn_segment(ft_grid *g, double ax, double ay, double bx, double by, float z)
{
    double cell = g->gt[1], len = hypot(bx - ax, by - ay);
    int steps = (int)ceil(4.0 * len / cell) + 1;
    for (int i = 0; i <= steps; i++) {
        double t = (double)i / steps, x = ax + t * (bx - ax), y = ay + t * (by - ay);
        double col = floor((x - g->gt[0]) / cell), row = floor((g->gt[3] - y) / cell);
        if (col < 0.0 || row < 0.0 || col >= (double)g->nx || row >= (double)g->ny)
            continue;
        size_t k = (size_t)row * g->nx + (size_t)col;
        g->z[k] = z;
        g->mask[k] = 1;
    }
}

static void burn_ring(ft_grid *g, const ft_chain *r, float z)
{
    for (size_t i = 0; i < r->n; i++) {
        size_t j = i + 1 < r->n ? i + 1 : 0;
        burn_segment(g, r->x[i], r->y[i], r->x[j], r->y[j], z);
    }
}

typedef struct {
    const char *path;
    int side;
} peer_raster;

/* In a child: the stack, its DEM's frame, and the contours rasterized as lines into that frame. */
static int write_peer_raster(void *arg)
{
    const peer_raster *pr = arg;
    ft_polygon_set *seed = NULL;
    ft_contour_stack *s = NULL;
    ft_grid *frame = NULL, *g = NULL;
    ft_contour_dem_opts o = FT_CONTOUR_DEM_OPTS_DEFAULT;
    int rc = make_seed(&seed);
    if (rc == FT_OK)
        rc = grow(seed, &s);
    if (rc == FT_OK) {
        o.cell = dem_cell(seed, pr->side);
        rc = ft_contour_stack_to_dem(s, &o, NULL, &frame);
    }
    if (rc == FT_OK && (g = ft_grid_create(frame->nx, frame->ny)) == NULL)
        rc = FT_E_NOMEM;
    if (rc == FT_OK)
        rc = ft_grid_ensure_mask(g);
    if (rc == FT_OK) {
        memcpy(g->gt, frame->gt, sizeof g->gt);
        memset(g->mask, 0, g->nx * g->ny);
        for (size_t k = 0; k < s->n; k++) {
            const ft_polygon_set *ps = s->levels[k].polys;
            for (size_t p = 0; p < ps->n; p++) {
                burn_ring(g, ps->polys[p].outer, (float)s->levels[k].elev);
                for (size_t h = 0; h < ps->polys[p].nholes; h++)
                    burn_ring(g, ps->polys[p].holes[h], (float)s->levels[k].elev);
            }
        }
        rc = ft_io_write_grid(pr->path, g, NULL);
    }
    ft_grid_free(g);
    ft_grid_free(frame);
    ft_contour_stack_free(s);
    ft_polygon_set_free(seed);
    return rc;
}

static int dem_setup(ft_bench_case *c)
{
    c->work = (double)DEM_SIDE * DEM_SIDE;
    c->peer_none = "GRASS r.surf.contour runs for minutes at this size: it is compared in contour.dem.256";
    return FT_OK;
}

static int dem_peer_setup(ft_bench_case *c)
{
    c->work = (double)PEER_SIDE * PEER_SIDE;
    char *raster = ft_bench_path("contour_lines_256.tif");
    if (raster == NULL)
        return ft_last_error_code();
    peer_raster pr = {raster, PEER_SIDE};
    int rc = ft_bench_in_child(write_peer_raster, &pr);
    char *script = rc == FT_OK ? ft_bench_strf("r.in.gdal -o input=%s output=contour_lines --quiet && "
                                               "g.region raster=contour_lines && r.surf.contour "
                                               "input=contour_lines output=fracterra_bench --overwrite --quiet",
                                               raster)
                               : NULL;
    free(raster);
    if (rc != FT_OK)
        return rc;
    if (script == NULL)
        return ft_error(FT_E_NOMEM, "out of memory");
    const char *args[] = {"grass", "--tmp-location", "XY", "--exec", "sh", "-c"};
    for (size_t i = 0; i < sizeof args / sizeof args[0]; i++)
        if ((c->peer_argv[i] = ft_bench_strdup(args[i])) == NULL) {
            free(script);
            return ft_error(FT_E_NOMEM, "out of memory");
        }
    c->peer_argv[6] = script;
    return FT_OK;
}

static int dem_prepare(ft_bench_case *c)
{
    (void)c;
    int rc = make_seed(&held_seed);
    return rc == FT_OK ? grow(held_seed, &held_stack) : rc;
}

static int dem_of_side(ft_bench_case *c, int side)
{
    ft_contour_dem_opts o = FT_CONTOUR_DEM_OPTS_DEFAULT;
    o.cell = dem_cell(held_seed, side);
    ft_grid *g = NULL;
    int rc = ft_contour_stack_to_dem(held_stack, &o, NULL, &g);
    if (rc == FT_OK)
        c->work = (double)g->nx * (double)g->ny;
    ft_grid_free(g);
    return rc;
}

static int dem_run(ft_bench_case *c)
{
    return dem_of_side(c, DEM_SIDE);
}

static int dem_peer_run(ft_bench_case *c)
{
    return dem_of_side(c, PEER_SIDE);
}

static const ft_bench_workload contour_workloads[] = {
    {"contour.mountain.improved.60", "2,000-vertex seed to a 60-level mountain, improved method (d' = 3d, "
     "d'' = 0.5d, 20-40 deg, f0 = 256, n = 1024)", FT_BENCH_VERTICES, mountain_setup, mountain_prepare,
     mountain_run, NULL},
    {"contour.dem.2048", "that 60-level stack to a 2048x2048 DEM (r.surf.contour's interpolation, summit cap)",
     FT_BENCH_CELLS, dem_setup, dem_prepare, dem_run, NULL},
    {"contour.dem.256", "the same stack to a 256x256 DEM, beside GRASS r.surf.contour on its rasterized lines",
     FT_BENCH_CELLS, dem_peer_setup, dem_prepare, dem_peer_run, NULL},
};

const ft_bench_suite ft_bench_suite_contour = {"contour", contour_workloads,
                                               sizeof contour_workloads / sizeof contour_workloads[0]};
