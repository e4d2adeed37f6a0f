/* fracterra — cli/demo_lines.c: the demo's lines step: Dutton's Newfoundland sequence (Dutton 1981, Fig. 6)
 * on the bundled GSHHG shoreline. The full-resolution ring is generalized with Douglas-Peucker to about 158
 * points, enhanced with SD = 1.3, UC = 0.7, SM = 1% of the map width and no ST limit, weeded at SM and
 * smoothed once (roundness 0.5). One map shows the original, the generalized and the enhanced outlines;
 * two log-log plots give the divider dimension before (the generalized outline, automatic range) and after
 * (the enhanced outline, measured over the same rulers so that the two D compare).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "demo.h"
#include "line_edit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#define NF_FILE "gshhg_newfoundland_utm21n.geojson"
#define NF_TARGET 158

typedef struct {
    ft_layer *orig, *gen, *enh;
    ft_dim_result *before, *after;
    double tolerance, sm;
    double d_fractalized, d_weeded; /* D of the intermediate stages over the generalized chain's rulers */
    size_t n_fractalized, n_weeded;
} nf_stages;

static void stages_free(nf_stages *s)
{
    ft_layer_free(s->orig);
    ft_layer_free(s->gen);
    ft_layer_free(s->enh);
    ft_dim_result_free(s->before);
    ft_dim_result_free(s->after);
}

/* Divider dimension of every chain of the layer. */
static int layer_dim(const ft_layer *l, const ft_line_dim_opts *o, ft_dim_result **r)
{
    const ft_chain **c = malloc((l->nparts ? l->nparts : 1) * sizeof *c);
    if (c == NULL)
        return ft_error(FT_E_NOMEM, "demo: out of memory");
    for (size_t i = 0; i < l->nparts; i++)
        c[i] = l->parts[i].chain;
    int rc = ft_line_dim(c, l->nparts, FT_LINE_DIVIDER, o, r);
    free(c);
    if (rc == FT_OK)
        (*r)->method = ft_line_method_name(FT_LINE_DIVIDER);
    return rc;
}

/* A copy of l with op applied to every part (coverage topology on). */
static int edited_copy(const ft_layer *l, ft_line_op op, const void *opts, ft_layer **out)
{
    *out = ft_layer_copy(l);
    if (*out == NULL)
        return ft_last_error_code() != FT_OK ? ft_last_error_code() : FT_E_NOMEM;
    return ft_line_apply_layer(*out, op, opts, 1);
}

/* D of l over the rulers of o (whole range), into *d. */
static int stage_dim(const ft_layer *l, const ft_line_dim_opts *o, double *d)
{
    ft_dim_result *r = NULL;
    int rc = layer_dim(l, o, &r);
    if (rc == FT_OK)
        *d = r->D;
    ft_dim_result_free(r);
    return rc;
}

/* Generalize, enhance, weed, smooth, and measure every stage over the generalized chain's rulers. */
static int run_stages(nf_stages *s)
{
    double x0, y0, x1, y1;
    size_t n = 0;
    int rc = ft_layer_bbox(s->orig, &x0, &y0, &x1, &y1);
    if (rc == FT_OK)
        rc = ft_line_simplify_tolerance_for(s->orig, NF_TARGET, 1, &s->tolerance, &n);
    if (rc == FT_OK)
        rc = edited_copy(s->orig, ft_line_op_simplify, &s->tolerance, &s->gen);
    s->sm = 0.01 * (x1 - x0);
    ft_dutton_opts d = FT_DUTTON_OPTS_DEFAULT;
    ft_smooth_opts sm = FT_SMOOTH_OPTS_DEFAULT;
    d.sd = 1.3;
    d.uc = 0.7;
    d.sm = sm.sm = s->sm;
    ft_line_dim_opts o = FT_LINE_DIM_OPTS_DEFAULT;
    if (rc == FT_OK)
        rc = layer_dim(s->gen, &o, &s->before);
    if (rc == FT_OK) {
        const ft_loglog *t = s->before->table;
        o.min_scale = t->rows[0].scale;
        o.max_scale = t->rows[t->n - 1].scale;
        o.nscales = (int)t->n;
        o.fit_whole_range = 1;
        rc = edited_copy(s->gen, ft_line_op_enhance, &d, &s->enh);
    }
    if (rc == FT_OK && (rc = stage_dim(s->enh, &o, &s->d_fractalized)) == FT_OK) {
        s->n_fractalized = ft_layer_vertex_count(s->enh);
        rc = ft_line_apply_layer(s->enh, ft_line_op_weed, &s->sm, 1);
    }
    if (rc == FT_OK && (rc = stage_dim(s->enh, &o, &s->d_weeded)) == FT_OK) {
        s->n_weeded = ft_layer_vertex_count(s->enh);
        rc = ft_line_apply_layer(s->enh, ft_line_op_smooth, &sm, 1);
    }
    if (rc == FT_OK)
        rc = layer_dim(s->enh, &o, &s->after);
    return rc;
}

/* Text that lives until index.html is written (the demo runs once per process). */
static char label_orig[128], label_gen[128], label_enh[160], caption_map[1024], caption_before[512],
    caption_after[768];

static int write_map(demo_ctx *ctx, const nf_stages *s)
{
    snprintf(label_orig, sizeof label_orig, "GSHHG full resolution: %zu points", ft_layer_vertex_count(s->orig));
    snprintf(label_gen, sizeof label_gen, "Douglas-Peucker: %zu points, D = %.2f", ft_layer_vertex_count(s->gen),
             s->before->D);
    snprintf(label_enh, sizeof label_enh, "enhanced, weeded, smoothed: %zu points, D = %.2f",
             ft_layer_vertex_count(s->enh), s->after->D);
    snprintf(caption_map, sizeof caption_map,
             "Dutton's Newfoundland sequence (1981, Fig. 6) on the GSHHG shoreline: the full-resolution ring "
             "(grey) generalized with Douglas-Peucker to %zu points (tolerance %.0f m, orange), then enhanced "
             "with SD = 1.3, UC = 0.7, SM = %.0f m (1%% of the map width) and no straightness limit, weeded at "
             "SM and smoothed once (blue, %zu points). <code>fracterra simplify --vertices 158</code>, "
             "<code>fracterra enhance --sd 1.3 --uc 0.7 --sm %.0f --weed --smooth 1</code>.",
             ft_layer_vertex_count(s->gen), s->tolerance, s->sm, ft_layer_vertex_count(s->enh), s->sm);
    const char *out = demo_add_output(ctx, "newfoundland_enhanced.svg", "Newfoundland: fractal enhancement",
                                      caption_map, 1);
    ft_map_layer layers[3] = {
        {s->orig, "#a7b1bc", NULL, 2.2, 0.0, label_orig},
        {s->gen, "#d95f02", NULL, 1.0, 4.0, label_gen},
        {s->enh, "#1f3b73", NULL, 1.1, 0.0, label_enh},
    };
    ft_map_opts mo = FT_MAP_OPTS_DEFAULT;
    mo.width = mo.height = 800;
    mo.title = "Newfoundland: Dutton's fractal enhancement of a 158-point outline";
    return out ? ft_render_map_layers(layers, 3, out, &mo) : ft_last_error_code();
}

static int write_plot(demo_ctx *ctx, const char *file, const char *title, const char *caption,
                      const ft_dim_result *r)
{
    const char *out = demo_add_output(ctx, file, title, caption, 1);
    ft_plot_opts po = FT_PLOT_OPTS_DEFAULT;
    po.title = title;
    po.xlabel = "ruler (m)";
    po.ylabel = "length (m)";
    po.segments = 0;
    return out ? ft_render_loglog_plot(r, out, &po) : ft_last_error_code();
}

static int write_plots(demo_ctx *ctx, const nf_stages *s)
{
    snprintf(caption_before, sizeof caption_before,
             "Walking-divider plot of the %zu-point outline: D = %.3f &plusmn; %.3f (r&sup2; = %.3f) over "
             "rulers of %.0f to %.0f m, the automatic range of <code>fracterra dim line</code>.",
             ft_layer_vertex_count(s->gen), s->before->D, s->before->stderr_D, s->before->r2, s->before->range[0],
             s->before->range[1]);
    snprintf(caption_after, sizeof caption_after,
             "Over the same rulers, each stage: fractalized %zu points, D = %.3f; weeded %zu points, D = %.3f; "
             "smoothed (this plot) %zu points, D = %.3f &plusmn; %.3f (r&sup2; = %.3f). SD 1.3 is the dimension "
             "aimed at the generated scales (UC 0.7: D_in + UC (SD - D_in)); docs/line-newfoundland.md.",
             s->n_fractalized, s->d_fractalized, s->n_weeded, s->d_weeded, ft_layer_vertex_count(s->enh),
             s->after->D, s->after->stderr_D, s->after->r2);
    int rc = write_plot(ctx, "newfoundland_loglog_before.svg", "Newfoundland, Douglas-Peucker outline: divider",
                        caption_before, s->before);
    if (rc == FT_OK)
        rc = write_plot(ctx, "newfoundland_loglog_after.svg", "Newfoundland, enhanced outline: divider",
                        caption_after, s->after);
    return rc;
}

int demo_step_lines(demo_ctx *ctx)
{
    nf_stages s = {0};
    ft_read_layer_opts ro = FT_READ_LAYER_OPTS_DEFAULT;
    char *in = demo_join_path(ctx->data, NF_FILE);
    int rc = in ? ft_io_read_layer(in, &ro, &s.orig) : ft_error(FT_E_NOMEM, "demo: out of memory");
    free(in);
    if (rc == FT_OK)
        rc = run_stages(&s);
    if (rc == FT_OK)
        rc = write_map(ctx, &s);
    if (rc == FT_OK)
        rc = write_plots(ctx, &s);
    stages_free(&s);
    return rc;
}
