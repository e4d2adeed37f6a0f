/* fracterra — render/series_chart.c: a line chart of several series against a numeric or category x axis
 * (SVG, PDF or PNG by the output's extension), e.g. the box-counting dimension of each land-use class
 * against year (Zhang, Yu & Fan 2008, Table 1 as a figure).
 *
 * Both axes are linear with round ticks (plot_axes.c, shared with the log-log plot), or one tick per
 * category on x. Each series is a polyline with dots in its own palette colour; a non-finite y breaks
 * the line. The legend of the named series goes right of the plot area, where it hides nothing (inside, in
 * the corner hiding the fewest points, when it would take more than half the width).
 * The file is drawn under a temporary name and renamed when complete.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/render.h"
#include "render/render_internal.h"
#include "internal.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>

#define CHART_MIN_SIDE 200
#define CHART_MAX_SIDE 8192
#define CHART_MAX_SERIES 64
#define CHART_LINE_H 16.0
#define CHART_DOT 3.4

typedef struct {
    const ft_series *s;
    size_t n;
    const ft_chart_opts *o;
    ft_plot_frame f;
} chart;

static int check_series(const ft_series *s, size_t n, const ft_chart_opts *o)
{
    for (size_t k = 0; k < n; k++) {
        if (s[k].n > 0 && (s[k].x == NULL || s[k].y == NULL))
            return ft_error(FT_E_INVALID, "chart: series %zu has no values", k + 1);
        for (size_t i = 0; i < s[k].n; i++) {
            if (!isfinite(s[k].x[i]))
                return ft_error(FT_E_INVALID, "chart: series %zu, point %zu: x is not finite", k + 1, i + 1);
            if (o->xcategories && (s[k].x[i] < 0.0 || s[k].x[i] > (double)o->ncategories - 1.0))
                return ft_error(FT_E_INVALID, "chart: series %zu, point %zu: x = %g is not a category index",
                                k + 1, i + 1, s[k].x[i]);
        }
    }
    return FT_OK;
}

static int check_input(const ft_series *s, size_t n, const char *path, const ft_chart_opts *o)
{
    if (s == NULL || n == 0 || n > CHART_MAX_SERIES)
        return ft_error(FT_E_INVALID, "chart: between 1 and %d series needed, got %zu", CHART_MAX_SERIES,
                        s ? n : 0);
    if (path == NULL || *path == '\0')
        return ft_error(FT_E_INVALID, "chart: no output path given");
    if (o->width < CHART_MIN_SIDE || o->height < CHART_MIN_SIDE || o->width > CHART_MAX_SIDE ||
        o->height > CHART_MAX_SIDE)
        return ft_error(FT_E_INVALID, "chart size must be within %d..%d on each side, got %d x %d", CHART_MIN_SIDE,
                        CHART_MAX_SIDE, o->width, o->height);
    if (o->xcategories && o->ncategories == 0)
        return ft_error(FT_E_INVALID, "chart: category axis without categories");
    return check_series(s, n, o);
}

/* The data window: every finite point (categories: all of them), padded. FT_E_EMPTY if no y is finite. */
static int frame_init(chart *c)
{
    ft_plot_frame *f = &c->f;
    f->x0 = 78.0;
    f->y0 = c->o->title && *c->o->title ? 44.0 : 18.0;
    f->w = c->o->width - f->x0 - 22.0;
    f->h = c->o->height - f->y0 - 56.0;
    f->xmin = f->ymin = INFINITY;
    f->xmax = f->ymax = -INFINITY;
    for (size_t k = 0; k < c->n; k++)
        for (size_t i = 0; i < c->s[k].n; i++) {
            if (!isfinite(c->s[k].y[i]))
                continue;
            f->xmin = fmin(f->xmin, c->s[k].x[i]);
            f->xmax = fmax(f->xmax, c->s[k].x[i]);
            f->ymin = fmin(f->ymin, c->s[k].y[i]);
            f->ymax = fmax(f->ymax, c->s[k].y[i]);
        }
    if (!isfinite(f->ymin))
        return ft_error(FT_E_EMPTY, "chart: no finite value to draw");
    if (c->o->xcategories) {
        f->xmin = -0.5; /* half a category of room on each side for the labels */
        f->xmax = (double)c->o->ncategories - 0.5;
    } else {
        ft_plot_pad(&f->xmin, &f->xmax);
    }
    ft_plot_pad(&f->ymin, &f->ymax);
    return FT_OK;
}

/* ---- axes ---- */

static void label_category(cairo_t *cr, double v, double x, double y, double ax, double ay, const void *arg)
{
    const ft_chart_opts *o = arg;
    long k = lround(v);
    if (k >= 0 && (size_t)k < o->ncategories && o->xcategories[k])
        ft_plot_text_at(cr, o->xcategories[k], x, y, ax, ay);
}

static void draw_axes(cairo_t *cr, const chart *c)
{
    ft_plot_axis x = {.label = ft_plot_label_plain}, y = {.label = ft_plot_label_plain};
    if (c->o->xcategories) {
        ft_plot_ticks_integer(c->f.xmin, c->f.xmax, &x.ticks);
        x.label = label_category;
        x.arg = c->o;
    } else {
        ft_plot_ticks_linear(c->f.xmin, c->f.xmax, &x.ticks);
    }
    ft_plot_ticks_linear(c->f.ymin, c->f.ymax, &y.ticks);
    ft_plot_draw_axes(cr, &c->f, &x, &y);
}

/* ---- series ---- */

static void dot(cairo_t *cr, double X, double Y)
{
    cairo_new_sub_path(cr);
    cairo_arc(cr, X, Y, CHART_DOT, 0.0, 2.0 * M_PI);
    cairo_fill(cr);
}

static void draw_series(cairo_t *cr, const ft_plot_frame *f, const ft_series *s, size_t k)
{
    ft_plot_palette(cr, k);
    cairo_set_line_width(cr, 1.8);
    int open = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (!isfinite(s->y[i])) {
            open = 0;
            continue;
        }
        double X = ft_plot_px(f, s->x[i]), Y = ft_plot_py(f, s->y[i]);
        if (open)
            cairo_line_to(cr, X, Y);
        else
            cairo_move_to(cr, X, Y);
        open = 1;
    }
    cairo_stroke(cr);
    for (size_t i = 0; i < s->n; i++)
        if (isfinite(s->y[i]))
            dot(cr, ft_plot_px(f, s->x[i]), ft_plot_py(f, s->y[i]));
}

/* ---- legend ---- */

/* Width of the legend of the named series (0 if none is named). */
static double legend_width(cairo_t *cr, const chart *c)
{
    double w = 0.0;
    ft_plot_font(cr, FT_PLOT_FONT, 0);
    for (size_t k = 0; k < c->n; k++) {
        if (c->s[k].name == NULL)
            continue;
        cairo_text_extents_t e;
        cairo_text_extents(cr, c->s[k].name, &e);
        w = fmax(w, e.x_advance + 48.0);
    }
    return w;
}

static size_t points_inside(const ft_plot_frame *f, double x, double y, double w, double h, const void *arg)
{
    const chart *c = arg;
    size_t hits = 0;
    for (size_t k = 0; k < c->n; k++)
        for (size_t i = 0; i < c->s[k].n; i++) {
            if (!isfinite(c->s[k].y[i]))
                continue;
            double X = ft_plot_px(f, c->s[k].x[i]), Y = ft_plot_py(f, c->s[k].y[i]);
            hits += X >= x - 4 && X <= x + w + 4 && Y >= y - 4 && Y <= y + h + 4;
        }
    return hits;
}

static size_t legend_rows(const chart *c)
{
    size_t rows = 0;
    for (size_t k = 0; k < c->n; k++)
        rows += c->s[k].name != NULL;
    return rows;
}

/* The legend at (x, y): one row per named series, its line and dot then its name. */
static void draw_legend(cairo_t *cr, const chart *c, double x, double y, double w)
{
    ft_plot_legend_box(cr, x, y, w, (double)legend_rows(c) * CHART_LINE_H + 10.0);
    double yc = y + 5.0 + CHART_LINE_H * 0.5;
    for (size_t k = 0; k < c->n; k++) {
        if (c->s[k].name == NULL)
            continue;
        ft_plot_palette(cr, k);
        cairo_set_line_width(cr, 1.8);
        cairo_move_to(cr, x + 6.0, yc);
        cairo_line_to(cr, x + 32.0, yc);
        cairo_stroke(cr);
        dot(cr, x + 19.0, yc);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        ft_plot_font(cr, FT_PLOT_FONT, 0);
        ft_plot_text_at(cr, c->s[k].name, x + 40.0, yc, 0.0, 0.5);
        yc += CHART_LINE_H;
    }
}

static void draw_chart(cairo_t *cr, const void *arg)
{
    chart c0 = *(const chart *)arg, *c = &c0;
    double lw = legend_width(cr, c), lx = 0.0, ly = c->f.y0;
    int outside = lw > 0.0 && lw < c->f.w / 2.0;
    if (outside) {
        c->f.w -= lw + 12.0; /* right of the plot, where it hides nothing */
        lx = c->f.x0 + c->f.w + 12.0;
    } else if (lw > 0.0) {
        ft_plot_legend_corner(&c->f, lw, (double)legend_rows(c) * CHART_LINE_H + 10.0, points_inside, c, &lx, &ly);
    }
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    draw_axes(cr, c);
    cairo_save(cr);
    cairo_rectangle(cr, c->f.x0, c->f.y0, c->f.w, c->f.h);
    cairo_clip(cr);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    for (size_t k = 0; k < c->n; k++)
        draw_series(cr, &c->f, &c->s[k], k);
    cairo_restore(cr);
    ft_plot_draw_titles(cr, &c->f, c->o->title, c->o->xlabel, c->o->ylabel);
    if (lw > 0.0)
        draw_legend(cr, c, lx, ly, lw);
}

int ft_render_series_chart(const ft_series *series, size_t n, const char *path, const ft_chart_opts *opts)
{
    ft_chart_opts taken = FT_CHART_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_chart_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_chart_opts defaults = FT_CHART_OPTS_DEFAULT;
    chart c = {.s = series, .n = n, .o = opts ? opts : &defaults};
    ft_canvas_format fmt = FT_CANVAS_SVG;
    int rc = check_input(series, n, path, c.o);
    if (rc == FT_OK)
        rc = ft_canvas_format_of("chart", path, &fmt);
    if (rc == FT_OK)
        rc = frame_init(&c);
    return rc == FT_OK ? ft_canvas_write(path, fmt, c.o->width, c.o->height, draw_chart, &c) : rc;
}
