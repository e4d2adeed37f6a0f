/* fracterra — render/loglog_plot.c: the log-log plot of a dimension estimate (SVG, PDF or PNG by the
 * output's extension), so that users judge the straightness of the fitted range themselves, as in
 * Arakawa & Krotkov §2.4 (Fig. 9: the points (log scale, log value) and their linear segments).
 *
 * Axes are log10 with major ticks at decades (labelled 0.01 … 1000, or 10^k beyond), minor ticks at
 * 2..9 times a decade; a table spanning less than two decades gets 1-2-5 ticks instead. The fitted
 * range is a shaded band; used rows are filled dots, the others hollow; the least-squares line runs
 * over the used rows, each segment's line is dashed in its own colour; the legend goes in the corner of
 * the plot that hides the fewest points. The file is drawn under a temporary name and renamed at the
 * end, so a failure leaves nothing behind.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/render.h"
#include "render/render_internal.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PLOT_MIN_SIDE 200
#define PLOT_MAX_SIDE 8192
#define PLOT_MAX_SEGMENTS_LISTED 6
#define PLOT_FONT 11.0
#define PLOT_LINE_H 16.0

/* The plot area and the log10 data window it shows. */
typedef struct {
    double x0, y0, w, h;       /* plot area on the canvas */
    double xmin, xmax, ymin, ymax; /* log10 window */
} frame;

typedef struct {
    double r, g, b;
} rgb;

static const rgb SEGMENT_COLOURS[] = {{0.12, 0.47, 0.71}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74},
                                      {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}};
#define NCOLOURS (sizeof SEGMENT_COLOURS / sizeof SEGMENT_COLOURS[0])

static int check_input(const ft_dim_result *r, const char *path, const ft_plot_opts *o)
{
    if (r == NULL || r->table == NULL)
        return ft_error(FT_E_INVALID, "log-log plot: no result or no table given");
    if (path == NULL || *path == '\0')
        return ft_error(FT_E_INVALID, "log-log plot: no output path given");
    if (o->width < PLOT_MIN_SIDE || o->height < PLOT_MIN_SIDE || o->width > PLOT_MAX_SIDE ||
        o->height > PLOT_MAX_SIDE)
        return ft_error(FT_E_INVALID, "log-log plot size must be within %d..%d on each side, got %d x %d",
                        PLOT_MIN_SIDE, PLOT_MAX_SIDE, o->width, o->height);
    return ft_loglog_check(r->table);
}

static double px(const frame *f, double lx)
{
    return f->x0 + (lx - f->xmin) / (f->xmax - f->xmin) * f->w;
}

static double py(const frame *f, double ly)
{
    return f->y0 + f->h - (ly - f->ymin) / (f->ymax - f->ymin) * f->h;
}

/* Widens [*lo, *hi] by 6% on each side (to +-0.5 if it is a single value). */
static void pad(double *lo, double *hi)
{
    double d = *hi - *lo;
    if (!(d > 0.0)) {
        *lo -= 0.5;
        *hi += 0.5;
        return;
    }
    *lo -= 0.06 * d;
    *hi += 0.06 * d;
}

static void frame_init(const ft_dim_result *r, const ft_plot_opts *o, frame *f)
{
    const ft_loglog *t = r->table;
    f->x0 = 78.0;
    f->y0 = o->title && *o->title ? 44.0 : 18.0;
    f->w = o->width - f->x0 - 22.0;
    f->h = o->height - f->y0 - 56.0;
    f->xmin = f->ymin = INFINITY;
    f->xmax = f->ymax = -INFINITY;
    for (size_t i = 0; i < t->n; i++) {
        double lx = log10(t->rows[i].scale), ly = log10(t->rows[i].value);
        f->xmin = fmin(f->xmin, lx);
        f->xmax = fmax(f->xmax, lx);
        f->ymin = fmin(f->ymin, ly);
        f->ymax = fmax(f->ymax, ly);
    }
    pad(&f->xmin, &f->xmax);
    pad(&f->ymin, &f->ymax);
}

static void set_rgb(cairo_t *cr, rgb c)
{
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

static void font(cairo_t *cr, double size, int bold)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

/* Text whose reference point is placed by (ax, ay) in [0,1]: 0 = left/top, 0.5 = centre, 1 = right/bottom. */
static void text_at(cairo_t *cr, const char *s, double x, double y, double ax, double ay)
{
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_move_to(cr, x - ax * e.x_advance, y - e.y_bearing - ay * e.height);
    cairo_show_text(cr, s);
}

/* ---- ticks ---- */

typedef struct {
    double v[64]; /* log10 positions */
    int major[64];
    size_t n;
} ticks;

static void tick_add(ticks *t, double lv, int major)
{
    if (t->n < sizeof t->v / sizeof t->v[0]) {
        t->v[t->n] = lv;
        t->major[t->n++] = major;
    }
}

/* Evenly spaced ticks of value (not of its log) for a window under a decade wide: a round step of
 * 1, 2 or 5 times a power of ten giving about five ticks. */
static void ticks_linear(double lo, double hi, ticks *t)
{
    double v0 = pow(10.0, lo), v1 = pow(10.0, hi), raw = (v1 - v0) / 5.0;
    double p = pow(10.0, floor(log10(raw))), m = raw / p;
    double step = (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
    t->n = 0;
    for (double k = ceil(v0 / step); k * step <= v1 && t->n < 16; k += 1.0)
        tick_add(t, log10(k * step), 1);
}

/* Ticks of a log10 window: decades (every `stride`-th labelled, minor ticks at 2..9 if few decades);
 * 1, 2, 5 times the decades when fewer than two decades fall inside; plain round values in a window
 * that still gets fewer than three. */
static void ticks_make(double lo, double hi, ticks *t)
{
    t->n = 0;
    long k0 = (long)ceil(lo - 1e-9), k1 = (long)floor(hi + 1e-9);
    long ndec = k1 - k0 + 1;
    if (ndec >= 2) {
        long stride = (ndec + 7) / 8;
        for (long k = (long)floor(lo); k <= k1; k++) {
            if (k >= k0 && (k - k0) % stride == 0)
                tick_add(t, (double)k, 1);
            for (int m = 2; stride == 1 && ndec <= 12 && m <= 9; m++) {
                double lv = (double)k + log10((double)m);
                if (lv >= lo && lv <= hi)
                    tick_add(t, lv, 0);
            }
        }
        return;
    }
    static const int steps[3] = {1, 2, 5};
    for (long k = (long)floor(lo); k <= (long)floor(hi); k++)
        for (int m = 0; m < 3; m++) {
            double lv = (double)k + log10((double)steps[m]);
            if (lv >= lo && lv <= hi)
                tick_add(t, lv, 1);
        }
    if (t->n < 3)
        ticks_linear(lo, hi, t);
}

/* A tick label: decimal for 10^-3 .. 10^4, else "10" with a superscript exponent. */
static void tick_label(cairo_t *cr, double lv, double x, double y, double ax, double ay)
{
    double v = pow(10.0, lv);
    long k = lround(lv);
    char buf[32];
    if (fabs(lv - (double)k) > 1e-9 || (k >= -3 && k <= 4)) {
        snprintf(buf, sizeof buf, "%.4g", v);
        text_at(cr, buf, x, y, ax, ay);
        return;
    }
    char ex[24];
    snprintf(ex, sizeof ex, "%ld", k);
    cairo_text_extents_t e10, eex;
    cairo_text_extents(cr, "10", &e10);
    font(cr, PLOT_FONT * 0.75, 0);
    cairo_text_extents(cr, ex, &eex);
    font(cr, PLOT_FONT, 0);
    double wtot = e10.x_advance + eex.x_advance, left = x - ax * wtot;
    double base = y - e10.y_bearing - ay * e10.height;
    cairo_move_to(cr, left, base);
    cairo_show_text(cr, "10");
    font(cr, PLOT_FONT * 0.75, 0);
    cairo_move_to(cr, left + e10.x_advance, base - 0.45 * e10.height);
    cairo_show_text(cr, ex);
    font(cr, PLOT_FONT, 0);
}

/* Grid lines: darker at major ticks. */
static void grid_grey(cairo_t *cr, int major)
{
    double v = major ? 0.85 : 0.93;
    cairo_set_source_rgb(cr, v, v, v);
}

static void draw_axes(cairo_t *cr, const frame *f)
{
    ticks tx, ty;
    ticks_make(f->xmin, f->xmax, &tx);
    ticks_make(f->ymin, f->ymax, &ty);
    cairo_set_line_width(cr, 0.6);
    for (size_t i = 0; i < tx.n; i++) {
        double X = px(f, tx.v[i]);
        grid_grey(cr, tx.major[i]);
        cairo_move_to(cr, X, f->y0);
        cairo_line_to(cr, X, f->y0 + f->h);
        cairo_stroke(cr);
    }
    for (size_t i = 0; i < ty.n; i++) {
        double Y = py(f, ty.v[i]);
        grid_grey(cr, ty.major[i]);
        cairo_move_to(cr, f->x0, Y);
        cairo_line_to(cr, f->x0 + f->w, Y);
        cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, f->x0, f->y0, f->w, f->h);
    cairo_stroke(cr);
    font(cr, PLOT_FONT, 0);
    for (size_t i = 0; i < tx.n; i++) {
        double X = px(f, tx.v[i]), len = tx.major[i] ? 6.0 : 3.0;
        cairo_move_to(cr, X, f->y0 + f->h);
        cairo_line_to(cr, X, f->y0 + f->h + len);
        cairo_stroke(cr);
        if (tx.major[i])
            tick_label(cr, tx.v[i], X, f->y0 + f->h + 9.0, 0.5, 0.0);
    }
    for (size_t i = 0; i < ty.n; i++) {
        double Y = py(f, ty.v[i]), len = ty.major[i] ? 6.0 : 3.0;
        cairo_move_to(cr, f->x0, Y);
        cairo_line_to(cr, f->x0 - len, Y);
        cairo_stroke(cr);
        if (ty.major[i])
            tick_label(cr, ty.v[i], f->x0 - 9.0, Y, 1.0, 0.5);
    }
}

static void draw_labels(cairo_t *cr, const frame *f, const ft_plot_opts *o)
{
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    if (o->title && *o->title) {
        font(cr, 15.0, 1);
        text_at(cr, o->title, f->x0 + f->w / 2.0, 14.0, 0.5, 0.0);
    }
    font(cr, 12.0, 0);
    if (o->xlabel && *o->xlabel)
        text_at(cr, o->xlabel, f->x0 + f->w / 2.0, f->y0 + f->h + 30.0, 0.5, 0.0);
    if (o->ylabel && *o->ylabel) {
        cairo_save(cr);
        cairo_translate(cr, 16.0, f->y0 + f->h / 2.0);
        cairo_rotate(cr, -M_PI / 2.0);
        text_at(cr, o->ylabel, 0.0, 0.0, 0.5, 0.0);
        cairo_restore(cr);
    }
}

/* ---- data ---- */

static void draw_band(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    if (r->fit.n < 2)
        return;
    double X0 = px(f, log10(r->range[0])), X1 = px(f, log10(r->range[1]));
    cairo_set_source_rgb(cr, 1.0, 0.95, 0.78);
    cairo_rectangle(cr, X0, f->y0, X1 - X0, f->h);
    cairo_fill(cr);
}

static void line_over(cairo_t *cr, const frame *f, double lx0, double lx1, double slope, double icpt)
{
    cairo_move_to(cr, px(f, lx0), py(f, icpt + slope * lx0));
    cairo_line_to(cr, px(f, lx1), py(f, icpt + slope * lx1));
    cairo_stroke(cr);
}

static void draw_segments(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    static const double dash[] = {6.0, 4.0};
    cairo_set_line_width(cr, 1.6);
    cairo_set_dash(cr, dash, 2, 0.0);
    for (size_t k = 0; k < r->nsegments; k++) {
        const ft_loglog_segment *s = &r->segments[k];
        set_rgb(cr, SEGMENT_COLOURS[k % NCOLOURS]);
        line_over(cr, f, log10(s->scale_lo), log10(s->scale_hi), s->slope, s->intercept);
    }
    cairo_set_dash(cr, NULL, 0, 0.0);
}

static void draw_fit(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    if (r->fit.n < 2)
        return;
    cairo_set_source_rgb(cr, 0.80, 0.10, 0.10);
    cairo_set_line_width(cr, 2.2);
    line_over(cr, f, log10(r->range[0]), log10(r->range[1]), r->fit.slope, r->fit.intercept);
}

static void dot(cairo_t *cr, double X, double Y, int filled)
{
    cairo_new_sub_path(cr);
    cairo_arc(cr, X, Y, 3.6, 0.0, 2.0 * M_PI);
    if (filled)
        cairo_set_source_rgb(cr, 0.10, 0.20, 0.45);
    else
        cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.10, 0.20, 0.45);
    cairo_set_line_width(cr, 1.2);
    cairo_stroke(cr);
}

static void draw_points(cairo_t *cr, const frame *f, const ft_loglog *t)
{
    for (size_t i = 0; i < t->n; i++)
        dot(cr, px(f, log10(t->rows[i].scale)), py(f, log10(t->rows[i].value)), t->rows[i].used);
}

/* ---- legend ---- */

typedef struct {
    char text[PLOT_MAX_SEGMENTS_LISTED + 4][160];
    int kind[PLOT_MAX_SEGMENTS_LISTED + 4]; /* 0 used dot, 1 hollow dot, 2 fit line, 3+k segment k, -1 text */
    size_t n;
    double w, h;
} legend;

static void legend_add(legend *l, int kind, const char *text)
{
    snprintf(l->text[l->n], sizeof l->text[l->n], "%s", text);
    l->kind[l->n++] = kind;
}

static void legend_make(cairo_t *cr, const ft_dim_result *r, const ft_plot_opts *o, legend *l)
{
    char buf[160];
    l->n = 0;
    legend_add(l, 0, "used");
    legend_add(l, 1, "not used");
    if (r->fit.n >= 2) {
        snprintf(buf, sizeof buf, "D = %.3f \xc2\xb1 %.3f, r\xc2\xb2 = %.3f, range %.4g\xe2\x80\x93%.4g", r->D,
                 r->stderr_D, r->r2, r->range[0], r->range[1]);
        legend_add(l, 2, buf);
    }
    size_t shown = o->segments ? r->nsegments : 0;
    shown = shown > PLOT_MAX_SEGMENTS_LISTED ? PLOT_MAX_SEGMENTS_LISTED : shown;
    for (size_t k = 0; k < shown; k++) {
        const ft_loglog_segment *s = &r->segments[k];
        snprintf(buf, sizeof buf, "segment %zu: D = %.3f, %.4g\xe2\x80\x93%.4g, error %.3g", k + 1, s->D,
                 s->scale_lo, s->scale_hi, s->max_err);
        legend_add(l, 3 + (int)k, buf);
    }
    if (o->segments && r->nsegments > shown) {
        snprintf(buf, sizeof buf, "and %zu more segments", r->nsegments - shown);
        legend_add(l, -1, buf);
    }
    font(cr, PLOT_FONT, 0);
    l->w = 0.0;
    for (size_t i = 0; i < l->n; i++) {
        cairo_text_extents_t e;
        cairo_text_extents(cr, l->text[i], &e);
        l->w = fmax(l->w, e.x_advance);
    }
    l->w += 44.0;
    l->h = (double)l->n * PLOT_LINE_H + 10.0;
}

/* Top-left corner of the legend in the plot corner hiding the fewest points (ties: top right, top
 * left, bottom left, bottom right). */
static void legend_place(const frame *f, const ft_loglog *t, const legend *l, double *lx, double *ly)
{
    const double m = 8.0;
    double cx[4] = {f->x0 + f->w - l->w - m, f->x0 + m, f->x0 + m, f->x0 + f->w - l->w - m};
    double cy[4] = {f->y0 + m, f->y0 + m, f->y0 + f->h - l->h - m, f->y0 + f->h - l->h - m};
    size_t best = 0, best_hits = (size_t)-1;
    for (size_t c = 0; c < 4; c++) {
        size_t hits = 0;
        for (size_t i = 0; i < t->n; i++) {
            double X = px(f, log10(t->rows[i].scale)), Y = py(f, log10(t->rows[i].value));
            hits += X >= cx[c] - 4 && X <= cx[c] + l->w + 4 && Y >= cy[c] - 4 && Y <= cy[c] + l->h + 4;
        }
        if (hits < best_hits) {
            best_hits = hits;
            best = c;
        }
    }
    *lx = cx[best];
    *ly = cy[best];
}

static void legend_symbol(cairo_t *cr, int kind, double x, double y)
{
    static const double dash[] = {6.0, 4.0};
    if (kind == 0 || kind == 1) {
        dot(cr, x + 14.0, y, kind == 0);
        return;
    }
    if (kind < 0)
        return;
    if (kind == 2) {
        cairo_set_source_rgb(cr, 0.80, 0.10, 0.10);
        cairo_set_line_width(cr, 2.2);
    } else {
        set_rgb(cr, SEGMENT_COLOURS[(size_t)(kind - 3) % NCOLOURS]);
        cairo_set_line_width(cr, 1.6);
        cairo_set_dash(cr, dash, 2, 0.0);
    }
    cairo_move_to(cr, x + 2.0, y);
    cairo_line_to(cr, x + 28.0, y);
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0.0);
}

static void draw_legend(cairo_t *cr, const frame *f, const ft_dim_result *r, const ft_plot_opts *o)
{
    legend l;
    legend_make(cr, r, o, &l);
    double x, y;
    legend_place(f, r->table, &l, &x, &y);
    cairo_rectangle(cr, x, y, l.w, l.h);
    cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.9);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
    for (size_t i = 0; i < l.n; i++) {
        double yc = y + 5.0 + PLOT_LINE_H * ((double)i + 0.5);
        legend_symbol(cr, l.kind[i], x + 4.0, yc);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        font(cr, PLOT_FONT, 0);
        text_at(cr, l.text[i], x + 38.0, yc, 0.0, 0.5);
    }
}

static void draw_plot(cairo_t *cr, const frame *f, const ft_dim_result *r, const ft_plot_opts *o)
{
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    draw_band(cr, f, r);
    draw_axes(cr, f);
    cairo_save(cr);
    cairo_rectangle(cr, f->x0, f->y0, f->w, f->h);
    cairo_clip(cr);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    if (o->segments)
        draw_segments(cr, f, r);
    draw_fit(cr, f, r);
    draw_points(cr, f, r->table);
    cairo_restore(cr);
    draw_labels(cr, f, o);
    draw_legend(cr, f, r, o);
}

/* What draw_plot needs, passed through the canvas writer. */
typedef struct {
    const frame *frame;
    const ft_dim_result *result;
    const ft_plot_opts *opts;
} plot_job;

static void draw_job(cairo_t *cr, const void *arg)
{
    const plot_job *j = arg;
    draw_plot(cr, j->frame, j->result, j->opts);
}

int ft_render_loglog_plot(const ft_dim_result *r, const char *path, const ft_plot_opts *opts)
{
    ft_plot_opts defaults = FT_PLOT_OPTS_DEFAULT;
    const ft_plot_opts *o = opts ? opts : &defaults;
    ft_canvas_format fmt = FT_CANVAS_SVG;
    int rc = check_input(r, path, o);
    if (rc == FT_OK)
        rc = ft_canvas_format_of("log-log plot", path, &fmt);
    if (rc != FT_OK)
        return rc;
    frame f;
    frame_init(r, o, &f);
    plot_job job = {&f, r, o};
    return ft_canvas_write(path, fmt, o->width, o->height, draw_job, &job);
}
