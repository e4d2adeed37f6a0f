/* fracterra — cli/demo_contour.c: the demo's mountain step: every contour of a mountain grown from one seed
 * contour (the 130 m contour of Maunga Whau, made from the bundled DEM with gdal_contour) by the improved
 * contour generation method of Misawa, Chiba & Saito (§4.3), drawn as a contour map with the seed on top,
 * and its DEM (interpolated between the contours as GRASS r.surf.contour does) seen in perspective, to set
 * beside the real volcano's view of the terrain step.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "demo.h"

#include <stdio.h>
#include <stdlib.h>

#define SEED_FILE "seed_contour_volcano.geojson"
#define SOURCE_SEED                                                                                        \
    "the 130 m contour of Maunga Whau, made from <code>dem_volcano_maunga_whau_10m.tif</code> with "     \
    "<code>gdal_contour -p</code>; GPL-2 | GPL-3"
#define MOUNTAIN_SEED 8
#define MOUNTAIN_INTERVAL 5.0
#define MOUNTAIN_DOWN 3
#define MOUNTAIN_CELL 2.0

static char map_caption[768], view_caption[768];

typedef struct {
    ft_layer *seed_layer, *contours;
    ft_polygon_set *seed;
    ft_contour_stack *stack;
    ft_grid *dem;
} mountain_demo;

static void mountain_free(mountain_demo *m)
{
    ft_layer_free(m->seed_layer);
    ft_layer_free(m->contours);
    ft_polygon_set_free(m->seed);
    ft_contour_stack_free(m->stack);
    ft_grid_free(m->dem);
}

static size_t stack_vertices(const ft_contour_stack *s)
{
    size_t v = 0;
    for (size_t k = 0; k < s->n; k++)
        v += ft_polygon_set_vertices(s->levels[k].polys);
    return v;
}

static int grow(demo_ctx *ctx, mountain_demo *m)
{
    char *in = demo_join_path(ctx->data, SEED_FILE);
    ft_read_layer_opts ro = FT_READ_LAYER_OPTS_DEFAULT;
    int rc = in ? ft_io_read_layer(in, &ro, &m->seed_layer) : ft_error(FT_E_NOMEM, "demo: out of memory");
    free(in);
    if (rc == FT_OK)
        rc = demo_add_input(ctx, SEED_FILE, SOURCE_SEED);
    if (rc == FT_OK)
        rc = ft_polygon_set_from_layer(m->seed_layer, &m->seed);
    ft_mountain_opts mo = FT_MOUNTAIN_OPTS_DEFAULT;
    mo.interval = MOUNTAIN_INTERVAL;
    mo.seed_elevation = 130.0;
    mo.levels_down = MOUNTAIN_DOWN;
    mo.seed = MOUNTAIN_SEED;
    mo.match_dim = 0; /* the paper's fixed 20-40 degrees (as --theta 20,40): the bundled seed is smooth, and
                         matching its dimension would give smooth contours, not the paper's Fig. 16 */
    if (rc == FT_OK)
        rc = ft_mountain_generate(m->seed, &mo, &m->stack);
    if (rc == FT_OK)
        rc = ft_contour_stack_to_layer(m->stack, 0, m->seed_layer->crs_wkt, &m->contours);
    ft_contour_dem_opts dopt = FT_CONTOUR_DEM_OPTS_DEFAULT;
    dopt.cell = MOUNTAIN_CELL;
    if (rc == FT_OK)
        rc = ft_contour_stack_to_dem(m->stack, &dopt, m->seed_layer->crs_wkt, &m->dem);
    return rc;
}

static int draw_map(demo_ctx *ctx, const mountain_demo *m)
{
    const ft_contour_stack *s = m->stack;
    snprintf(map_caption, sizeof map_caption,
             "Every contour of a mountain grown from one seed contour (red) by the improved contour generation "
             "method of Misawa, Chiba &amp; Saito (shrinking with the d&prime; join, Fourier descriptor phase "
             "randomization, collinear removal, random midpoint displacement at the paper's fixed 20&ndash;40&deg;): "
             "%zu levels from %g m to %g m every %g m, %d grown outward below the seed, spacing d = %.1f m, %zu "
             "vertices, seed %d: <code>fracterra mountain %s mountain_contours.gpkg --interval %g --levels-down %d "
             "--theta 20,40 --seed %d</code>.",
             s->n, s->levels[0].elev, s->levels[s->n - 1].elev, s->interval, MOUNTAIN_DOWN, s->spacing,
             stack_vertices(s), MOUNTAIN_SEED, SEED_FILE, MOUNTAIN_INTERVAL, MOUNTAIN_DOWN, MOUNTAIN_SEED);
    ft_map_layer layers[2] = {
        {m->contours, "#8a5a2b", NULL, 0.7, 0.0, "generated contours"},
        {m->seed_layer, "#c0392b", NULL, 1.6, 0.0, "seed contour (130 m)"},
    };
    ft_map_opts mo = FT_MAP_OPTS_DEFAULT;
    mo.width = 700;
    mo.height = 800;
    mo.title = "A mountain grown from the 130 m contour of Maunga Whau";
    const char *out = demo_add_output(ctx, "mountain_contours.svg", "Contours grown from one seed contour",
                                      map_caption, 1);
    return out ? ft_render_map_layers(layers, 2, out, &mo) : ft_last_error_code();
}

static int draw_view(demo_ctx *ctx, const mountain_demo *m)
{
    snprintf(view_caption, sizeof view_caption,
             "The DEM of those contours (%zu &times; %zu cells of %g m; between two contours z = z<sub>lo</sub> + "
             "(z<sub>hi</sub> &minus; z<sub>lo</sub>) d<sub>lo</sub> / (d<sub>lo</sub> + d<sub>hi</sub>) as in "
             "GRASS r.surf.contour, the summits rising half an interval above the top contours) seen like the "
             "real volcano above: <code>... --dem mountain.tif --cell %g --view mountain_perspective.png</code>.",
             m->dem->nx, m->dem->ny, MOUNTAIN_CELL, MOUNTAIN_CELL);
    ft_perspective_opts po = FT_PERSPECTIVE_OPTS_DEFAULT;
    po.width = 900;
    const char *out = demo_add_output(ctx, "mountain_perspective.png", "The grown mountain, perspective view",
                                      view_caption, 1);
    return out ? ft_render_perspective(m->dem, out, &po) : ft_last_error_code();
}

int demo_step_mountain(demo_ctx *ctx)
{
    mountain_demo m = {NULL, NULL, NULL, NULL, NULL};
    int rc = grow(ctx, &m);
    if (rc == FT_OK)
        rc = draw_map(ctx, &m);
    if (rc == FT_OK)
        rc = draw_view(ctx, &m);
    mountain_free(&m);
    return rc;
}
