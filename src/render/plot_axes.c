/* fracterra — render/plot_axes.c: what the plots share (render_internal.h): the frame mapping data to the
 * canvas, text placement, tick positions for log, linear and category axes, tick labels, grid lines, the
 * framed axes with their ticks, titles and legend boxes. Used by the log-log plot and the series chart.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "render/render_internal.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>

double ft_plot_px(const ft_plot_frame *f, double x)
{
    return f->x0 + (x - f->xmin) / (f->xmax - f->xmin) * f->w;
}

double ft_plot_py(const ft_plot_frame *f, double y)
{
    return f->y0 + f->h - (y - f->ymin) / (f->ymax - f->ymin) * f->h;
}

void ft_plot_pad(double *lo, double *hi)
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

void ft_plot_font(cairo_t *cr, double size, int bold)
{
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

void ft_plot_text_at(cairo_t *cr, const char *s, double x, double y, double ax, double ay)
{
    cairo_text_extents_t e;
    cairo_text_extents(cr, s, &e);
    cairo_move_to(cr, x - ax * e.x_advance, y - e.y_bearing - ay * e.height);
    cairo_show_text(cr, s);
}

/* ---- ticks ---- */

static void tick_add(ft_plot_ticks *t, double v, int major)
{
    if (t->n < FT_PLOT_MAX_TICKS) {
        t->v[t->n] = v;
        t->major[t->n++] = major;
    }
}

/* A round step, 1, 2 or 5 times a power of ten, near raw (> 0). */
static double round_step(double raw)
{
    double p = pow(10.0, floor(log10(raw))), m = raw / p;
    return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

/* Multiples of a round step in [v0, v1], about five of them, at most 16. */
static void ticks_round(double v0, double v1, int log_positions, ft_plot_ticks *t)
{
    double step = v1 > v0 ? round_step((v1 - v0) / 5.0) : 1.0;
    t->n = 0;
    for (double k = ceil(v0 / step); k * step <= v1 && t->n < 16; k += 1.0) {
        double v = k * step;
        tick_add(t, log_positions ? log10(v) : (fabs(v) < 1e-9 * step ? 0.0 : v), 1);
    }
}

void ft_plot_ticks_linear(double lo, double hi, ft_plot_ticks *t)
{
    ticks_round(lo, hi, 0, t);
}

void ft_plot_ticks_integer(double lo, double hi, ft_plot_ticks *t)
{
    t->n = 0;
    for (double k = ceil(lo); k <= hi; k += 1.0)
        tick_add(t, k, 1);
}

void ft_plot_ticks_log(double lo, double hi, ft_plot_ticks *t)
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
        ticks_round(pow(10.0, lo), pow(10.0, hi), 1, t);
}

/* ---- tick labels ---- */

void ft_plot_label_plain(cairo_t *cr, double v, double x, double y, double ax, double ay, const void *arg)
{
    (void)arg;
    char buf[32];
    snprintf(buf, sizeof buf, "%.6g", v);
    ft_plot_text_at(cr, buf, x, y, ax, ay);
}

void ft_plot_label_log(cairo_t *cr, double lv, double x, double y, double ax, double ay, const void *arg)
{
    (void)arg;
    double v = pow(10.0, lv);
    long k = lround(lv);
    char buf[32];
    if (fabs(lv - (double)k) > 1e-9 || (k >= -3 && k <= 4)) {
        snprintf(buf, sizeof buf, "%.4g", v);
        ft_plot_text_at(cr, buf, x, y, ax, ay);
        return;
    }
    char ex[24];
    snprintf(ex, sizeof ex, "%ld", k);
    cairo_text_extents_t e10, eex;
    cairo_text_extents(cr, "10", &e10);
    ft_plot_font(cr, FT_PLOT_FONT * 0.75, 0);
    cairo_text_extents(cr, ex, &eex);
    ft_plot_font(cr, FT_PLOT_FONT, 0);
    double wtot = e10.x_advance + eex.x_advance, left = x - ax * wtot;
    double base = y - e10.y_bearing - ay * e10.height;
    cairo_move_to(cr, left, base);
    cairo_show_text(cr, "10");
    ft_plot_font(cr, FT_PLOT_FONT * 0.75, 0);
    cairo_move_to(cr, left + e10.x_advance, base - 0.45 * e10.height);
    cairo_show_text(cr, ex);
    ft_plot_font(cr, FT_PLOT_FONT, 0);
}

/* ---- axes ---- */

/* Grid lines: darker at major ticks. */
static void grid_grey(cairo_t *cr, int major)
{
    double v = major ? 0.85 : 0.93;
    cairo_set_source_rgb(cr, v, v, v);
}

static void draw_grid(cairo_t *cr, const ft_plot_frame *f, const ft_plot_ticks *tx, const ft_plot_ticks *ty)
{
    cairo_set_line_width(cr, 0.6);
    for (size_t i = 0; i < tx->n; i++) {
        double X = ft_plot_px(f, tx->v[i]);
        grid_grey(cr, tx->major[i]);
        cairo_move_to(cr, X, f->y0);
        cairo_line_to(cr, X, f->y0 + f->h);
        cairo_stroke(cr);
    }
    for (size_t i = 0; i < ty->n; i++) {
        double Y = ft_plot_py(f, ty->v[i]);
        grid_grey(cr, ty->major[i]);
        cairo_move_to(cr, f->x0, Y);
        cairo_line_to(cr, f->x0 + f->w, Y);
        cairo_stroke(cr);
    }
}

void ft_plot_draw_axes(cairo_t *cr, const ft_plot_frame *f, const ft_plot_axis *x, const ft_plot_axis *y)
{
    draw_grid(cr, f, &x->ticks, &y->ticks);
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 1.0);
    cairo_rectangle(cr, f->x0, f->y0, f->w, f->h);
    cairo_stroke(cr);
    ft_plot_font(cr, FT_PLOT_FONT, 0);
    for (size_t i = 0; i < x->ticks.n; i++) {
        double X = ft_plot_px(f, x->ticks.v[i]), len = x->ticks.major[i] ? 6.0 : 3.0;
        cairo_move_to(cr, X, f->y0 + f->h);
        cairo_line_to(cr, X, f->y0 + f->h + len);
        cairo_stroke(cr);
        if (x->ticks.major[i])
            x->label(cr, x->ticks.v[i], X, f->y0 + f->h + 9.0, 0.5, 0.0, x->arg);
    }
    for (size_t i = 0; i < y->ticks.n; i++) {
        double Y = ft_plot_py(f, y->ticks.v[i]), len = y->ticks.major[i] ? 6.0 : 3.0;
        cairo_move_to(cr, f->x0, Y);
        cairo_line_to(cr, f->x0 - len, Y);
        cairo_stroke(cr);
        if (y->ticks.major[i])
            y->label(cr, y->ticks.v[i], f->x0 - 9.0, Y, 1.0, 0.5, y->arg);
    }
}

void ft_plot_draw_titles(cairo_t *cr, const ft_plot_frame *f, const char *title, const char *xlabel,
                         const char *ylabel)
{
    cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
    if (title && *title) {
        ft_plot_font(cr, 15.0, 1);
        ft_plot_text_at(cr, title, f->x0 + f->w / 2.0, 14.0, 0.5, 0.0);
    }
    ft_plot_font(cr, 12.0, 0);
    if (xlabel && *xlabel)
        ft_plot_text_at(cr, xlabel, f->x0 + f->w / 2.0, f->y0 + f->h + 30.0, 0.5, 0.0);
    if (ylabel && *ylabel) {
        cairo_save(cr);
        cairo_translate(cr, 16.0, f->y0 + f->h / 2.0);
        cairo_rotate(cr, -M_PI / 2.0);
        ft_plot_text_at(cr, ylabel, 0.0, 0.0, 0.5, 0.0);
        cairo_restore(cr);
    }
}

void ft_plot_legend_box(cairo_t *cr, double x, double y, double w, double h)
{
    cairo_rectangle(cr, x, y, w, h);
    cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.9);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.6, 0.6, 0.6);
    cairo_set_line_width(cr, 0.8);
    cairo_stroke(cr);
}

void ft_plot_palette(cairo_t *cr, size_t k)
{
    static const double colours[][3] = {{0.12, 0.47, 0.71}, {0.17, 0.63, 0.17}, {0.58, 0.40, 0.74},
                                        {1.00, 0.50, 0.05}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}};
    const double *c = colours[k % (sizeof colours / sizeof colours[0])];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}

void ft_plot_legend_corner(const ft_plot_frame *f, double w, double h, ft_plot_hits_fn hits, const void *arg,
                           double *lx, double *ly)
{
    const double m = 8.0;
    double cx[4] = {f->x0 + f->w - w - m, f->x0 + m, f->x0 + m, f->x0 + f->w - w - m};
    double cy[4] = {f->y0 + m, f->y0 + m, f->y0 + f->h - h - m, f->y0 + f->h - h - m};
    size_t best = 0, least = (size_t)-1;
    for (size_t c = 0; c < 4; c++) {
        size_t n = hits(f, cx[c], cy[c], w, h, arg);
        if (n < least) {
            least = n;
            best = c;
        }
    }
    *lx = cx[best];
    *ly = cy[best];
}
