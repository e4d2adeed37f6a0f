/* fracterra — render/map.c: one or several layers drawn as a small map (SVG, PDF or PNG by the output's
 * extension).
 *
 * The layers' bounding box is fitted into the canvas with its aspect kept and y pointing up (north up for
 * projected data). Polygon features are filled with the even-odd rule, so holes stay empty, then stroked;
 * lines are stroked. An optional title sits at the top and an optional scale bar at the bottom left, its
 * length a round 1, 2 or 5 times a power of ten in layer units (labelled in m or km, or in degrees when the
 * CRS is geographic). Several layers are drawn in order, each with its own stroke, fill, width and dash,
 * with a legend of the labelled ones in the corner of the map that covers the fewest vertices. A view window
 * (ft_map_opts.window) zooms on part of the layers, the drawing clipped to the map area. The file is drawn
 * under a temporary name and renamed when complete.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/io.h"
#include "fracterra/render.h"
#include "render/render_internal.h"
#include "internal.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAP_MARGIN 16.0
#define MAP_TITLE_H 30.0
#define MAP_BAR_H 36.0
#define MAP_MAX_SIDE 32767


typedef struct {
    double r, g, b;
} rgb;

/* The placement of layer coordinates on the canvas: X = ox + (x - xmin) k, Y = oy + (ymax - y) k. */
typedef struct {
    double xmin, ymax, k, ox, oy;
    double x0, y0, aw, ah; /* the map area */
} map_frame;

static int parse_color(const char *what, const char *s, rgb *c)
{
    unsigned v = 0;
    int used = 0;
    if (s == NULL || s[0] != '#' || strlen(s) != 7 || sscanf(s + 1, "%6x%n", &v, &used) != 1 || used != 6)
        return ft_error(FT_E_INVALID, "map %s colour must be \"#rrggbb\", got \"%s\"", what, s ? s : "(null)");
    c->r = ((v >> 16) & 0xff) / 255.0;
    c->g = ((v >> 8) & 0xff) / 255.0;
    c->b = (v & 0xff) / 255.0;
    return FT_OK;
}

static int check_opts(const ft_map_opts *o)
{
    if (o->width < 64 || o->height < 64 || o->width > MAP_MAX_SIDE || o->height > MAP_MAX_SIDE)
        return ft_error(FT_E_INVALID, "map size must be within 64..%d on each side, got %d x %d", MAP_MAX_SIDE,
                        o->width, o->height);
    if (!isfinite(o->line_width) || o->line_width < 0.0)
        return ft_error(FT_E_INVALID, "map line width must be >= 0, got %g", o->line_width);
    const double *w = o->window;
    int none = w[0] == 0.0 && w[1] == 0.0 && w[2] == 0.0 && w[3] == 0.0;
    if (!none && !(isfinite(w[0]) && isfinite(w[1]) && isfinite(w[2]) && isfinite(w[3]) && w[2] > w[0] &&
                   w[3] > w[1]))
        return ft_error(FT_E_INVALID, "map window must be finite with xmin < xmax and ymin < ymax, got %g %g %g %g",
                        w[0], w[1], w[2], w[3]);
    return FT_OK;
}

/* A layer as drawn: colours parsed, defaults applied. */
typedef struct {
    const ft_layer *layer;
    rgb stroke, fill;
    int has_fill;
    double width, dash;
    const char *label;
} map_item;

static int make_item(const ft_map_layer *ml, size_t i, const ft_map_opts *o, map_item *it)
{
    if (ml->layer == NULL)
        return ft_error(FT_E_INVALID, "map: layer %zu is missing", i + 1);
    if (!isfinite(ml->line_width) || !isfinite(ml->dash) || ml->dash < 0.0)
        return ft_error(FT_E_INVALID, "map: layer %zu line width and dash must be finite, dash >= 0", i + 1);
    int rc = parse_color("stroke", ml->stroke ? ml->stroke : o->stroke, &it->stroke);
    if (rc == FT_OK && ml->fill)
        rc = parse_color("fill", ml->fill, &it->fill);
    if (rc == FT_OK)
        rc = ft_layer_check_finite(ml->layer);
    it->layer = ml->layer;
    it->has_fill = ml->fill != NULL;
    it->width = ml->line_width > 0.0 ? ml->line_width : o->line_width;
    it->dash = ml->dash;
    it->label = ml->label;
    return rc;
}

static void frame_init(const ft_map_opts *o, double bx0, double by0, double bx1, double by1, map_frame *f)
{
    f->x0 = MAP_MARGIN;
    f->y0 = MAP_MARGIN + (o->title ? MAP_TITLE_H : 0.0);
    f->aw = o->width - 2.0 * MAP_MARGIN;
    f->ah = o->height - f->y0 - MAP_MARGIN - (o->scale_bar ? MAP_BAR_H : 0.0);
    double dx = bx1 - bx0, dy = by1 - by0;
    if (dx <= 0.0 && dy <= 0.0)
        dx = dy = 1.0; /* a single point: any scale will do */
    double kx = dx > 0.0 ? f->aw / dx : INFINITY, ky = dy > 0.0 ? f->ah / dy : INFINITY;
    f->k = kx < ky ? kx : ky;
    f->xmin = bx0;
    f->ymax = by1;
    f->ox = f->x0 + (f->aw - (bx1 - bx0) * f->k) / 2.0;
    f->oy = f->y0 + (f->ah - (by1 - by0) * f->k) / 2.0;
}

static void chain_path(cairo_t *cr, const ft_chain *c, const map_frame *f)
{
    for (size_t i = 0; i < c->n; i++) {
        double X = f->ox + (c->x[i] - f->xmin) * f->k, Y = f->oy + (f->ymax - c->y[i]) * f->k;
        if (i == 0)
            cairo_move_to(cr, X, Y);
        else
            cairo_line_to(cr, X, Y);
    }
    if (c->closed)
        cairo_close_path(cr);
}

static void draw_feature(cairo_t *cr, const map_item *it, const ft_feature *ft, const map_frame *f)
{
    const ft_layer *l = it->layer;
    cairo_new_path(cr);
    for (size_t p = ft->first; p < ft->first + ft->count && p < l->nparts; p++)
        if (l->parts[p].chain && l->parts[p].chain->n >= 2)
            chain_path(cr, l->parts[p].chain, f);
    if (ft->type == FT_GEOM_POLYGON && it->has_fill) {
        cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
        cairo_set_source_rgb(cr, it->fill.r, it->fill.g, it->fill.b);
        cairo_fill_preserve(cr);
    }
    cairo_set_source_rgb(cr, it->stroke.r, it->stroke.g, it->stroke.b);
    cairo_stroke(cr);
}

static void set_line_style(cairo_t *cr, const map_item *it)
{
    cairo_set_line_width(cr, it->width);
    cairo_set_dash(cr, &it->dash, it->dash > 0.0 ? 1 : 0, 0.0);
}

static void draw_item(cairo_t *cr, const map_item *it, const map_frame *f)
{
    set_line_style(cr, it);
    for (size_t i = 0; i < it->layer->nfeatures; i++)
        if (it->layer->features[i].type != FT_GEOM_NONE)
            draw_feature(cr, it, &it->layer->features[i], f);
}

/* 1 if the CRS service says the WKT is geographic (coordinates in degrees). */
static int crs_is_geographic(const char *wkt)
{
    ft_crs_info crs;
    if (ft_io_crs_info(wkt, &crs) != FT_OK) {
        ft_clear_error();
        return 0;
    }
    return crs.geographic;
}

/* The largest 1, 2 or 5 times a power of ten not above x (x > 0). */
static double round_length(double x)
{
    double p = pow(10.0, floor(log10(x)));
    double m = x / p;
    return (m >= 5.0 ? 5.0 : m >= 2.0 ? 2.0 : 1.0) * p;
}

static void scale_label(double len, int geographic, char *buf, size_t size)
{
    if (geographic)
        snprintf(buf, size, "%g\xc2\xb0", len);
    else if (len >= 1000.0)
        snprintf(buf, size, "%g km", len / 1000.0);
    else
        snprintf(buf, size, "%g m", len);
}

static void draw_scale_bar(cairo_t *cr, const map_frame *f, const ft_map_opts *o, int geographic)
{
    double len = round_length(f->aw / 4.0 / f->k);
    double px = len * f->k, x = f->x0, y = o->height - MAP_MARGIN - 14.0, h = 5.0;
    for (int s = 0; s < 4; s++) {
        cairo_rectangle(cr, x + s * px / 4.0, y, px / 4.0, h);
        double v = (s % 2 == 0) ? 0.1 : 1.0;
        cairo_set_source_rgb(cr, v, v, v);
        cairo_fill_preserve(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_set_line_width(cr, 0.6);
        cairo_stroke(cr);
    }
    char label[64];
    scale_label(len, geographic, label, sizeof label);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 10.0);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, x - 2.0, y + h + 11.0);
    cairo_show_text(cr, "0");
    cairo_text_extents_t e;
    cairo_text_extents(cr, label, &e);
    cairo_move_to(cr, x + px - e.x_advance / 2.0, y + h + 11.0);
    cairo_show_text(cr, label);
}

static void draw_title(cairo_t *cr, const ft_map_opts *o)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, 16.0);
    cairo_text_extents_t e;
    cairo_text_extents(cr, o->title, &e);
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    cairo_move_to(cr, (o->width - e.x_advance) / 2.0, MAP_MARGIN + 16.0);
    cairo_show_text(cr, o->title);
}

/* ---- legend ---- */

#define LEGEND_FONT 12.0
#define LEGEND_ROW 18.0
#define LEGEND_SAMPLE 28.0
#define LEGEND_PAD 8.0

static void legend_size(cairo_t *cr, const map_item *items, size_t n, double *w, double *h)
{
    double tw = 0.0;
    size_t rows = 0;
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, LEGEND_FONT);
    for (size_t i = 0; i < n; i++) {
        if (items[i].label == NULL)
            continue;
        cairo_text_extents_t e;
        cairo_text_extents(cr, items[i].label, &e);
        tw = e.x_advance > tw ? e.x_advance : tw;
        rows++;
    }
    *w = rows ? 3.0 * LEGEND_PAD + LEGEND_SAMPLE + tw : 0.0;
    *h = rows ? 2.0 * LEGEND_PAD + rows * LEGEND_ROW - (LEGEND_ROW - LEGEND_FONT) : 0.0;
}

/* Vertices of every layer inside the canvas rectangle [x, x + w] x [y, y + h] (at most ~20,000 looked at). */
static size_t vertices_in(const map_item *items, size_t n, const map_frame *f, double x, double y, double w, double h)
{
    size_t total = 0, count = 0;
    for (size_t i = 0; i < n; i++)
        total += ft_layer_vertex_count(items[i].layer);
    size_t step = total / 20000 + 1;
    for (size_t i = 0; i < n; i++) {
        const ft_layer *l = items[i].layer;
        for (size_t p = 0; p < l->nparts; p++) {
            const ft_chain *c = l->parts[p].chain;
            for (size_t k = 0; c && k < c->n; k += step) {
                double X = f->ox + (c->x[k] - f->xmin) * f->k, Y = f->oy + (f->ymax - c->y[k]) * f->k;
                count += X >= x && X <= x + w && Y >= y && Y <= y + h;
            }
        }
    }
    return count;
}

static void draw_legend(cairo_t *cr, const map_item *items, size_t n, const map_frame *f)
{
    double w, h;
    legend_size(cr, items, n, &w, &h);
    if (w <= 0.0)
        return;
    /* corners: top-right, top-left, bottom-right, bottom-left; the first hiding the fewest vertices */
    double xs[4] = {f->x0 + f->aw - w, f->x0, f->x0 + f->aw - w, f->x0};
    double ys[4] = {f->y0, f->y0, f->y0 + f->ah - h, f->y0 + f->ah - h};
    size_t best = 0, least = (size_t)-1;
    for (size_t c = 0; c < 4; c++) {
        size_t v = vertices_in(items, n, f, xs[c], ys[c], w, h);
        if (v < least) {
            least = v;
            best = c;
        }
    }
    double x = xs[best], y = ys[best];
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_rectangle(cr, x, y, w, h);
    cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.85);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 0.6);
    cairo_stroke(cr);
    double row = y + LEGEND_PAD + LEGEND_FONT / 2.0;
    for (size_t i = 0; i < n; i++) {
        if (items[i].label == NULL)
            continue;
        set_line_style(cr, &items[i]);
        cairo_set_source_rgb(cr, items[i].stroke.r, items[i].stroke.g, items[i].stroke.b);
        cairo_move_to(cr, x + LEGEND_PAD, row);
        cairo_line_to(cr, x + LEGEND_PAD + LEGEND_SAMPLE, row);
        cairo_stroke(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        cairo_move_to(cr, x + 2.0 * LEGEND_PAD + LEGEND_SAMPLE, row + LEGEND_FONT / 2.0 - 2.0);
        cairo_show_text(cr, items[i].label);
        row += LEGEND_ROW;
    }
}

/* ---- the map ---- */

/* What draw_map needs, passed through the canvas writer. */
typedef struct {
    const map_item *items;
    size_t n;
    const map_frame *frame;
    const ft_map_opts *opts;
} map_job;

static void draw_map(cairo_t *cr, const void *arg)
{
    const map_job *j = arg;
    const ft_map_opts *o = j->opts;
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_save(cr);
    if (o->window[2] > o->window[0]) {
        cairo_rectangle(cr, j->frame->x0, j->frame->y0, j->frame->aw, j->frame->ah);
        cairo_clip(cr);
    }
    for (size_t i = 0; i < j->n; i++)
        draw_item(cr, &j->items[i], j->frame);
    cairo_restore(cr);
    draw_legend(cr, j->items, j->n, j->frame);
    cairo_set_dash(cr, NULL, 0, 0.0);
    if (o->title && *o->title)
        draw_title(cr, o);
    if (o->scale_bar)
        draw_scale_bar(cr, j->frame, o, crs_is_geographic(j->items[0].layer->crs_wkt));
}

/* The union of the layers' bounding boxes; FT_E_EMPTY if none has a vertex. */
static int items_bbox(const map_item *items, size_t n, double *bx0, double *by0, double *bx1, double *by1)
{
    int found = 0;
    for (size_t i = 0; i < n; i++) {
        double x0, y0, x1, y1;
        if (ft_layer_bbox(items[i].layer, &x0, &y0, &x1, &y1) != FT_OK)
            continue;
        *bx0 = found && *bx0 < x0 ? *bx0 : x0;
        *by0 = found && *by0 < y0 ? *by0 : y0;
        *bx1 = found && *bx1 > x1 ? *bx1 : x1;
        *by1 = found && *by1 > y1 ? *by1 : y1;
        found = 1;
    }
    if (!found) {
        const char *name = items[0].layer->name;
        return ft_error(FT_E_EMPTY, "map: layer '%s' has no vertex to draw", name ? name : "");
    }
    return FT_OK;
}

static int render_items(const map_item *items, size_t n, const char *path, ft_canvas_format fmt,
                        const ft_map_opts *o)
{
    double bx0 = 0.0, by0 = 0.0, bx1 = 0.0, by1 = 0.0;
    int rc = items_bbox(items, n, &bx0, &by0, &bx1, &by1);
    if (rc != FT_OK)
        return rc;
    if (o->window[2] > o->window[0]) {
        bx0 = o->window[0];
        by0 = o->window[1];
        bx1 = o->window[2];
        by1 = o->window[3];
    }
    map_frame f;
    frame_init(o, bx0, by0, bx1, by1, &f);
    if (f.aw < 16.0 || f.ah < 16.0)
        return ft_error(FT_E_INVALID, "map: a %d x %d canvas leaves no room for the map", o->width, o->height);
    map_job job = {items, n, &f, o};
    return ft_canvas_write(path, fmt, o->width, o->height, draw_map, &job);
}

int ft_render_map_layers(const ft_map_layer *layers, size_t n, const char *path, const ft_map_opts *opts)
{
    ft_map_opts taken = FT_MAP_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_map_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_map_opts defaults = FT_MAP_OPTS_DEFAULT;
    const ft_map_opts *o = opts ? opts : &defaults;
    ft_canvas_format fmt = FT_CANVAS_SVG;
    if (layers == NULL || n == 0)
        return ft_error(FT_E_INVALID, "map: no layer given");
    if (path == NULL || *path == '\0')
        return ft_error(FT_E_INVALID, "map: no output path given");
    int rc = ft_canvas_format_of("map", path, &fmt);
    if (rc == FT_OK)
        rc = check_opts(o);
    map_item *items = rc == FT_OK ? calloc(n, sizeof *items) : NULL;
    if (rc == FT_OK && items == NULL)
        rc = ft_error(FT_E_NOMEM, "map: out of memory");
    for (size_t i = 0; rc == FT_OK && i < n; i++)
        rc = make_item(&layers[i], i, o, &items[i]);
    if (rc == FT_OK)
        rc = render_items(items, n, path, fmt, o);
    free(items);
    return rc;
}

int ft_render_map(const ft_layer *layer, const char *path, const ft_map_opts *opts)
{
    ft_map_opts taken = FT_MAP_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_map_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_map_opts defaults = FT_MAP_OPTS_DEFAULT;
    const ft_map_opts *o = opts ? opts : &defaults;
    if (layer == NULL)
        return ft_error(FT_E_INVALID, "map: no layer given");
    ft_map_layer one = {layer, o->stroke, o->fill, o->line_width, 0.0, NULL};
    return ft_render_map_layers(&one, 1, path, o);
}
