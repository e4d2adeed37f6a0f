/* fracterra — cli/demo_urban.c: the demo's urban step: the midpoint-subdivision generator of Zhang, Yu & Fan
 * (2008, §2) on the boundary of Rhode Island (the DCW outline, 9 rings: the mainland and the islands of
 * Narragansett Bay) generalized with Douglas-Peucker at 600 m (about 160 vertices, as a small-scale map
 * holds it), with D = 1.2325, the dimension the paper measured for Wuhan's urban boundary in 1997 (Table 1),
 * --max the average chord (Eqs. 11-13) and --min 100 m. Two maps draw the simulated boundary over its input
 * and the full-resolution outline: the whole state, and a window of a fifth of its width on the bay shore
 * nearest the state's centre. The box-counting dimension of each, over the same box sides, is in the
 * caption.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "demo.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define RI_FILE "dcw_us_states_small_albers5070.geojson"
#define RI_WHERE "code = 'US.RI'"
#define SOURCE_DCW "DCW-GMT 2.1.1 (Digital Chart of the World for GMT), P. Wessel; LGPL-3+"
#define RI_DIM 1.2325
#define RI_SEED 1997
#define RI_TOLERANCE 600.0
#define RI_MIN 100.0
#define ZOOM_FRACTION 0.2

typedef struct {
    ft_layer *full, *in, *out; /* DCW outline, generalized input, simulated */
    ft_boundary_info info;
    ft_boundary_opts opts;
    ft_dim_result *d_full, *d_in, *d_out;
} ri_boundary;

static void ri_free(ri_boundary *r)
{
    ft_layer_free(r->full);
    ft_layer_free(r->in);
    ft_layer_free(r->out);
    ft_dim_result_free(r->d_full);
    ft_dim_result_free(r->d_in);
    ft_dim_result_free(r->d_out);
}

/* A copy of l (NULL-safe error code in rc). */
static int copy_layer(const ft_layer *l, ft_layer **out)
{
    *out = ft_layer_copy(l);
    return *out ? FT_OK : ft_last_error_code() != FT_OK ? ft_last_error_code() : FT_E_NOMEM;
}

/* Box counting of the three boundaries over the sides of the full outline's automatic range. */
static int measure(ri_boundary *r)
{
    ft_area_dim_opts bo = FT_AREA_DIM_OPTS_DEFAULT;
    int rc = ft_urban_dim_area(r->full, NULL, 0, &bo, &r->d_full);
    if (rc != FT_OK)
        return rc;
    const ft_loglog *t = r->d_full->table;
    bo.min_cell = t->rows[0].scale;
    bo.max_cell = t->rows[t->n - 1].scale;
    bo.nscales = (int)t->n;
    rc = ft_urban_dim_area(r->in, NULL, 0, &bo, &r->d_in);
    return rc == FT_OK ? ft_urban_dim_area(r->out, NULL, 0, &bo, &r->d_out) : rc;
}

/* Reads Rhode Island, generalizes it, simulates the boundary and measures the three. */
static int simulate(demo_ctx *ctx, ri_boundary *r)
{
    ft_read_layer_opts ro = FT_READ_LAYER_OPTS_DEFAULT;
    ro.where = RI_WHERE;
    char *in = demo_join_path(ctx->data, RI_FILE);
    int rc = in ? ft_io_read_layer(in, &ro, &r->full) : ft_error(FT_E_NOMEM, "demo: out of memory");
    free(in);
    const double tolerance = RI_TOLERANCE;
    if (rc == FT_OK)
        rc = copy_layer(r->full, &r->in);
    if (rc == FT_OK)
        rc = ft_line_apply_layer(r->in, ft_line_op_simplify, &tolerance, 1);
    r->opts = (ft_boundary_opts)FT_BOUNDARY_OPTS_DEFAULT;
    r->opts.dim = RI_DIM;
    r->opts.min = RI_MIN;
    r->opts.seed = RI_SEED;
    if (rc == FT_OK)
        rc = copy_layer(r->in, &r->out);
    if (rc == FT_OK)
        rc = ft_urban_boundary_layer(r->out, &r->opts, 1, &r->info);
    return rc == FT_OK ? measure(r) : rc;
}

/* Text that lives until index.html is written (the demo runs once per process). */
static char label_full[128], label_in[128], label_out[160], caption_full[1200], caption_zoom[512];

static int draw(demo_ctx *ctx, const ri_boundary *r, const char *file, const char *title, const char *caption,
                const double *window)
{
    const char *out = demo_add_output(ctx, file, title, caption, 1);
    ft_map_layer layers[3] = {
        {r->full, "#b8c2cc", "#eef1f4", 2.6, 0.0, label_full},
        {r->in, "#404a55", NULL, 1.0, 5.0, label_in},
        {r->out, "#b2182b", NULL, 1.0, 0.0, label_out},
    };
    ft_map_opts mo = FT_MAP_OPTS_DEFAULT;
    mo.width = mo.height = 800;
    mo.title = title;
    for (int i = 0; window && i < 4; i++)
        mo.window[i] = window[i];
    return out ? ft_render_map_layers(layers, 3, out, &mo) : ft_last_error_code();
}

/* A square window of ZOOM_FRACTION of the state's width around the input vertex nearest the centre of its
 * bounding box: the shore of Narragansett Bay. */
static int zoom_window(const ft_layer *l, double w[4])
{
    double x0, y0, x1, y1;
    int rc = ft_layer_bbox(l, &x0, &y0, &x1, &y1);
    double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1), bx = cx, by = cy, best = INFINITY;
    for (size_t p = 0; p < l->nparts; p++)
        for (size_t i = 0; i < l->parts[p].chain->n; i++) {
            double dx = l->parts[p].chain->x[i] - cx, dy = l->parts[p].chain->y[i] - cy;
            if (dx * dx + dy * dy < best) {
                best = dx * dx + dy * dy;
                bx = l->parts[p].chain->x[i];
                by = l->parts[p].chain->y[i];
            }
        }
    double h = 0.5 * ZOOM_FRACTION * (x1 - x0);
    w[0] = bx - h;
    w[1] = by - h;
    w[2] = bx + h;
    w[3] = by + h;
    return rc;
}

static void write_captions(const ri_boundary *r)
{
    snprintf(label_full, sizeof label_full, "DCW outline: %zu vertices, box D = %.3f", ft_layer_vertex_count(r->full),
             r->d_full->D);
    snprintf(label_in, sizeof label_in, "input, generalized: %zu vertices, box D = %.3f", r->info.vertices_in,
             r->d_in->D);
    snprintf(label_out, sizeof label_out, "simulated with D = %.4g: %zu vertices, box D = %.3f", r->opts.dim,
             r->info.vertices_out, r->d_out->D);
    snprintf(caption_full, sizeof caption_full,
             "Zhang, Yu &amp; Fan's midpoint-subdivision generator (2008, &sect;2) on the boundary of Rhode Island. "
             "The DCW outline (light grey) generalized with Douglas-Peucker at %.0f m (dashed, %zu vertices) is "
             "the input: each of its segments between %.0f m and %.0f m (the average chord, Eqs. 11-13) becomes "
             "two legs at the angle a = %.1f&deg; of D = %.4g (Eq. 9; Wuhan's urban boundary in 1997, Table 1), "
             "on a side drawn at random, and so on down to %.0f m (red, %zu vertices); the %zu longer segments, "
             "such as the straight state lines, are kept as they are. Box counting over the same sides: D = %.3f "
             "(DCW), %.3f (input), %.3f (simulated). <code>fracterra simplify states.geojson ri.geojson --where "
             "\"code = 'US.RI'\" --tolerance %.0f</code>, <code>fracterra boundary ri.geojson ri-sim.gpkg --dim "
             "%.4g --min %.0f --seed %d</code>.",
             RI_TOLERANCE, r->info.vertices_in, r->opts.min, r->info.max_used,
             ft_urban_angle_for_dim(r->opts.dim) * 180.0 / M_PI, r->opts.dim, r->opts.min, r->info.vertices_out,
             r->info.segments_kept, r->d_full->D, r->d_in->D, r->d_out->D, RI_TOLERANCE, r->opts.dim, r->opts.min,
             RI_SEED);
    snprintf(caption_zoom, sizeof caption_zoom,
             "The same, zoomed five times on the shore of Narragansett Bay: the generated detail runs through "
             "every vertex of the input, which stays in place.");
}

static int write_maps(demo_ctx *ctx, const ri_boundary *r)
{
    double w[4];
    write_captions(r);
    int rc = zoom_window(r->in, w);
    if (rc == FT_OK)
        rc = draw(ctx, r, "urban_boundary.png", "Rhode Island: a boundary simulated with D = 1.2325", caption_full,
                  NULL);
    if (rc == FT_OK)
        rc = draw(ctx, r, "urban_boundary_zoom.png", "Rhode Island, Narragansett Bay: zoom x5", caption_zoom, w);
    return rc;
}

int demo_step_urban(demo_ctx *ctx)
{
    ri_boundary r = {0};
    int rc = simulate(ctx, &r);
    if (rc == FT_OK)
        rc = demo_add_input(ctx, RI_FILE, SOURCE_DCW);
    if (rc == FT_OK)
        rc = write_maps(ctx, &r);
    ri_free(&r);
    return rc;
}
