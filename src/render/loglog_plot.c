/* fracterra — render/loglog_plot.c: the log-log plot of a dimension estimate (SVG, PDF or PNG by the
 * output's extension), so that users judge the straightness of the fitted range themselves, as in
 * Arakawa & Krotkov §2.4 (Fig. 9: the points (log scale, log value) and their linear segments).
 *
 * Axes are log10 with major ticks at decades (labelled 0.01 … 1000, or 10^k beyond), minor ticks at
 * 2..9 times a decade; a table spanning less than two decades gets 1-2-5 ticks instead. The fitted
 * range is a shaded band; used rows are filled dots, the others hollow; the least-squares line runs
 * over the used rows, each regime (straight run, docs/loglog.md) is a solid line in its own colour over its
 * scales and each break between regimes a dotted vertical line, each segment's line (--segments) is
 * dashed in its own colour; the legend goes in the corner of
 * the plot that hides the fewest points. The file is drawn under a temporary name and renamed at the
 * end, so a failure leaves nothing behind.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/render.h"
#include "fracterra/surface.h"
#include "render/render_internal.h"
#include "internal.h"

#include <cairo.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PLOT_MIN_SIDE 200
#define PLOT_MAX_SIDE 8192
#define PLOT_MAX_SEGMENTS_LISTED 6
#define PLOT_LINE_H 16.0
#define PLOT_MAX_REGIMES_LISTED 4
#define KIND_REGIME 100 /* legend kind of regime k: KIND_REGIME + k */

typedef ft_plot_frame frame; /* log10 window */

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
    ft_plot_pad(&f->xmin, &f->xmax);
    ft_plot_pad(&f->ymin, &f->ymax);
}

static void draw_axes(cairo_t *cr, const frame *f)
{
    ft_plot_axis x = {.label = ft_plot_label_log}, y = {.label = ft_plot_label_log};
    ft_plot_ticks_log(f->xmin, f->xmax, &x.ticks);
    ft_plot_ticks_log(f->ymin, f->ymax, &y.ticks);
    ft_plot_draw_axes(cr, f, &x, &y);
}

/* ---- data ---- */

static void draw_band(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    if (r->fit.n < 2)
        return;
    double X0 = ft_plot_px(f, log10(r->range[0])), X1 = ft_plot_px(f, log10(r->range[1]));
    cairo_set_source_rgb(cr, 1.0, 0.95, 0.78);
    cairo_rectangle(cr, X0, f->y0, X1 - X0, f->h);
    cairo_fill(cr);
}

static void line_over(cairo_t *cr, const frame *f, double lx0, double lx1, double slope, double icpt)
{
    cairo_move_to(cr, ft_plot_px(f, lx0), ft_plot_py(f, icpt + slope * lx0));
    cairo_line_to(cr, ft_plot_px(f, lx1), ft_plot_py(f, icpt + slope * lx1));
    cairo_stroke(cr);
}

static void draw_segments(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    static const double dash[] = {6.0, 4.0};
    cairo_set_line_width(cr, 1.6);
    cairo_set_dash(cr, dash, 2, 0.0);
    for (size_t k = 0; k < r->nsegments; k++) {
        const ft_loglog_segment *s = &r->segments[k];
        ft_plot_palette(cr, k);
        line_over(cr, f, log10(s->scale_lo), log10(s->scale_hi), s->slope, s->intercept);
    }
    cairo_set_dash(cr, NULL, 0, 0.0);
}

/* Regime k's colour: the palette from its far end, so regimes and segments do not share colours. */
static void regime_colour(cairo_t *cr, size_t k)
{
    static const double rgb[][3] = {{0.10, 0.45, 0.75}, {0.95, 0.55, 0.05}, {0.20, 0.60, 0.25},
                                    {0.55, 0.30, 0.70}};
    const double *c = rgb[k % 4];
    cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}

static void draw_regimes(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    static const double dots[] = {2.0, 3.0};
    cairo_set_line_width(cr, 1.8);
    for (size_t k = 0; r->nregimes > 1 && k < r->nregimes; k++) {
        const ft_loglog_segment *s = &r->regimes[k];
        regime_colour(cr, k);
        line_over(cr, f, log10(s->scale_lo), log10(s->scale_hi), s->slope, s->intercept);
    }
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    cairo_set_line_width(cr, 1.0);
    cairo_set_dash(cr, dots, 2, 0.0);
    for (size_t k = 0; r->breaks != NULL && k + 1 < r->nregimes; k++) {
        double X = ft_plot_px(f, log10(r->breaks[k]));
        cairo_move_to(cr, X, f->y0);
        cairo_line_to(cr, X, f->y0 + f->h);
        cairo_stroke(cr);
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

/* log10 of the statistic the data show with the noise, from the fit line (the noise-free statistic) and the
 * noise model (docs/surface-noise.md): (v^p + c0)^(1/p) on grids, v sqrt(model / power law) on points. */
static double noisy_value(const ft_dim_result *r, double lx)
{
    const ft_noise_model *m = &r->nugget;
    double ly = r->fit.intercept + r->fit.slope * lx, d = pow(10.0, lx);
    if (m->positions) {
        double signal = m->a * pow(d, 2.0 * m->H);
        return ly + 0.5 * log10((m->c0 + m->a * ft_nugget_eiv_moment(m->H, d, m->s)) / signal);
    }
    return log10(pow(pow(10.0, m->power * ly) + m->c0, 1.0 / m->power));
}

/* The fitted structure function with the noise, dashed, over the table's scales. */
static void draw_noise_curve(cairo_t *cr, const frame *f, const ft_dim_result *r)
{
    static const double dash[] = {3.0, 3.0};
    if (!r->nugget.applied || r->fit.n < 2 || !(r->nugget.a > 0.0))
        return;
    cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
    cairo_set_line_width(cr, 1.4);
    cairo_set_dash(cr, dash, 2, 0.0);
    double lx0 = f->xmin, lx1 = f->xmax;
    for (int k = 0; k <= 100; k++) {
        double lx = lx0 + (lx1 - lx0) * k / 100.0, ly = noisy_value(r, lx);
        if (!isfinite(ly))
            continue;
        if (k == 0)
            cairo_move_to(cr, ft_plot_px(f, lx), ft_plot_py(f, ly));
        else
            cairo_line_to(cr, ft_plot_px(f, lx), ft_plot_py(f, ly));
    }
    cairo_stroke(cr);
    cairo_set_dash(cr, NULL, 0, 0.0);
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
        dot(cr, ft_plot_px(f, log10(t->rows[i].scale)), ft_plot_py(f, log10(t->rows[i].value)), t->rows[i].used);
}

/* ---- legend ---- */

typedef struct {
    char text[PLOT_MAX_SEGMENTS_LISTED + PLOT_MAX_REGIMES_LISTED + 7][160];
    int kind[PLOT_MAX_SEGMENTS_LISTED + PLOT_MAX_REGIMES_LISTED + 7]; /* 0 used dot, 1 hollow dot, 2 fit line,
                                                       3+k segment k, KIND_REGIME+k regime k, -1 text,
                                                       -2 the fit with the noise */
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
        snprintf(buf, sizeof buf, "D = %.3f \xc2\xb1 %.3f, r\xc2\xb2 = %.3f, range %.4g\xe2\x80\x93%.4g%s%s", r->D,
                 r->stderr_D, r->r2, r->range[0], r->range[1], r->units[0] ? " " : "", r->units);
        legend_add(l, 2, buf);
    }
    size_t nreg = r->nregimes > 1 ? r->nregimes : 0;
    nreg = nreg > PLOT_MAX_REGIMES_LISTED ? PLOT_MAX_REGIMES_LISTED : nreg;
    for (size_t k = 0; k < nreg; k++) {
        const ft_loglog_segment *s = &r->regimes[k];
        snprintf(buf, sizeof buf, "regime %zu%s: D = %.3f, %.4g\xe2\x80\x93%.4g%s", k + 1, k == r->regime ? " (D)" : "",
                 s->D, s->scale_lo, s->scale_hi, k + 1 < r->nregimes ? "" : "");
        legend_add(l, KIND_REGIME + (int)k, buf);
    }
    if (nreg > 0) {
        char br[120] = "breaks (dotted):";
        for (size_t k = 0; k + 1 < r->nregimes && k < 3; k++) {
            size_t used = strlen(br);
            snprintf(br + used, sizeof br - used, " %.4g", r->breaks[k]);
        }
        legend_add(l, -1, br);
    }
    if (r->nugget.applied && r->fit.n >= 2 && r->nugget.a > 0.0) {
        snprintf(buf, sizeof buf, "fit with the noise (sd %.3g on z%s), removed from the points", r->nugget.sigma_z,
                 r->nugget.positions ? ", and on x, y" : "");
        legend_add(l, -2, buf);
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
    ft_plot_font(cr, FT_PLOT_FONT, 0);
    l->w = 0.0;
    for (size_t i = 0; i < l->n; i++) {
        cairo_text_extents_t e;
        cairo_text_extents(cr, l->text[i], &e);
        l->w = fmax(l->w, e.x_advance);
    }
    l->w += 44.0;
    l->h = (double)l->n * PLOT_LINE_H + 10.0;
}

/* Table rows drawn inside a canvas rectangle (with a 4-pixel margin). */
static size_t rows_inside(const frame *f, double x, double y, double w, double h, const void *arg)
{
    const ft_loglog *t = arg;
    size_t hits = 0;
    for (size_t i = 0; i < t->n; i++) {
        double X = ft_plot_px(f, log10(t->rows[i].scale)), Y = ft_plot_py(f, log10(t->rows[i].value));
        hits += X >= x - 4 && X <= x + w + 4 && Y >= y - 4 && Y <= y + h + 4;
    }
    return hits;
}

static void legend_symbol(cairo_t *cr, int kind, double x, double y)
{
    static const double dash[] = {6.0, 4.0};
    if (kind == 0 || kind == 1) {
        dot(cr, x + 14.0, y, kind == 0);
        return;
    }
    if (kind == -2) {
        static const double dots[] = {3.0, 3.0};
        cairo_set_source_rgb(cr, 0.35, 0.35, 0.35);
        cairo_set_line_width(cr, 1.4);
        cairo_set_dash(cr, dots, 2, 0.0);
        cairo_move_to(cr, x + 2.0, y);
        cairo_line_to(cr, x + 28.0, y);
        cairo_stroke(cr);
        cairo_set_dash(cr, NULL, 0, 0.0);
        return;
    }
    if (kind < 0)
        return;
    if (kind == 2) {
        cairo_set_source_rgb(cr, 0.80, 0.10, 0.10);
        cairo_set_line_width(cr, 2.2);
    } else if (kind >= KIND_REGIME) {
        regime_colour(cr, (size_t)(kind - KIND_REGIME));
        cairo_set_line_width(cr, 1.8);
    } else {
        ft_plot_palette(cr, (size_t)(kind - 3));
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
    ft_plot_legend_corner(f, l.w, l.h, rows_inside, r->table, &x, &y);
    ft_plot_legend_box(cr, x, y, l.w, l.h);
    for (size_t i = 0; i < l.n; i++) {
        double yc = y + 5.0 + PLOT_LINE_H * ((double)i + 0.5);
        legend_symbol(cr, l.kind[i], x + 4.0, yc);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        ft_plot_font(cr, FT_PLOT_FONT, 0);
        ft_plot_text_at(cr, l.text[i], x + 38.0, yc, 0.0, 0.5);
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
    draw_regimes(cr, f, r);
    draw_noise_curve(cr, f, r);
    draw_fit(cr, f, r);
    draw_points(cr, f, r->table);
    cairo_restore(cr);
    ft_plot_draw_titles(cr, f, o->title, o->xlabel, o->ylabel);
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
    ft_plot_opts taken = FT_PLOT_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_plot_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
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
