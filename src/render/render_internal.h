/* fracterra — private helpers of the render module (src/render/), not installed.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_RENDER_INTERNAL_H
#define FRACTERRA_RENDER_INTERNAL_H

#include <cairo.h>
#include <stddef.h>

typedef enum { FT_CANVAS_SVG, FT_CANVAS_PDF, FT_CANVAS_PNG } ft_canvas_format;

/* The canvas format from the path's extension (.svg, .pdf, .png, any case); FT_E_INVALID naming `what` and
 * the path otherwise. */
int ft_canvas_format_of(const char *what, const char *path, ft_canvas_format *fmt);

/* Draws with draw(cr, arg) on a w x h canvas and writes it to path atomically (temporary name beside path,
 * renamed when complete; nothing left behind on failure). FT_E_IO naming path if cairo fails. */
typedef void (*ft_canvas_draw_fn)(cairo_t *cr, const void *arg);
int ft_canvas_write(const char *path, ft_canvas_format fmt, int w, int h, ft_canvas_draw_fn draw, const void *arg);

/* The colour of t in [0, 1] through the grey (colormap 0) or hypsometric (1) ramp (grid_image.c), shared by
 * grid images and the perspective view. */
void ft_render_ramp(double t, int colormap, double rgb[3]);

/* ---- plot axes (plot_axes.c), shared by the log-log plot and the series chart ---- */

#define FT_PLOT_FONT 11.0
#define FT_PLOT_MAX_TICKS 64

/* The plot area on the canvas and the data window it shows (in axis units: log10 for log axes). */
typedef struct {
    double x0, y0, w, h;
    double xmin, xmax, ymin, ymax;
} ft_plot_frame;

/* Canvas x and y of a data position. */
double ft_plot_px(const ft_plot_frame *f, double x);
double ft_plot_py(const ft_plot_frame *f, double y);
/* Widens [*lo, *hi] by 6% on each side (to +-0.5 if it is a single value). */
void ft_plot_pad(double *lo, double *hi);

void ft_plot_font(cairo_t *cr, double size, int bold);
/* Text whose reference point is placed by (ax, ay) in [0,1]: 0 = left/top, 0.5 = centre, 1 = right/bottom. */
void ft_plot_text_at(cairo_t *cr, const char *s, double x, double y, double ax, double ay);

/* Tick positions along an axis, in axis units; major ticks are labelled. */
typedef struct {
    double v[FT_PLOT_MAX_TICKS];
    int major[FT_PLOT_MAX_TICKS];
    size_t n;
} ft_plot_ticks;

/* Ticks of a log10 window: decades, 1-2-5 ticks under two decades, round values under one. */
void ft_plot_ticks_log(double lo, double hi, ft_plot_ticks *t);
/* About five round ticks (1, 2 or 5 times a power of ten apart) of a linear window. */
void ft_plot_ticks_linear(double lo, double hi, ft_plot_ticks *t);
/* Ticks at every integer of [lo, hi] (category axes), at most FT_PLOT_MAX_TICKS. */
void ft_plot_ticks_integer(double lo, double hi, ft_plot_ticks *t);

/* Draws the label of the tick at axis value v with its reference point at (x, y) placed by (ax, ay). */
typedef void (*ft_plot_label_fn)(cairo_t *cr, double v, double x, double y, double ax, double ay, const void *arg);
/* Log axes: decimal for 10^-3 .. 10^4, else 10 with a superscript exponent. */
void ft_plot_label_log(cairo_t *cr, double v, double x, double y, double ax, double ay, const void *arg);
/* Linear axes: the value with %.6g. */
void ft_plot_label_plain(cairo_t *cr, double v, double x, double y, double ax, double ay, const void *arg);

/* One axis: its ticks and how they are labelled. */
typedef struct {
    ft_plot_ticks ticks;
    ft_plot_label_fn label;
    const void *arg;
} ft_plot_axis;

/* Grid lines, the frame, tick marks and tick labels of both axes. */
void ft_plot_draw_axes(cairo_t *cr, const ft_plot_frame *f, const ft_plot_axis *x, const ft_plot_axis *y);
/* The title centred at the top and the axis labels (each may be NULL or ""). */
void ft_plot_draw_titles(cairo_t *cr, const ft_plot_frame *f, const char *title, const char *xlabel,
                         const char *ylabel);
/* Number of data points drawn inside the canvas rectangle [x, x + w] x [y, y + h]. */
typedef size_t (*ft_plot_hits_fn)(const ft_plot_frame *f, double x, double y, double w, double h, const void *arg);
/* Top-left corner (*lx, *ly) of a w x h legend in the corner of the plot area hiding the fewest points
 * (ties: top right, top left, bottom left, bottom right). */
void ft_plot_legend_corner(const ft_plot_frame *f, double w, double h, ft_plot_hits_fn hits, const void *arg,
                           double *lx, double *ly);
/* Sets the source to colour k of a small qualitative palette (cycled). */
void ft_plot_palette(cairo_t *cr, size_t k);
/* A legend's box: white, slightly transparent, grey outline. */
void ft_plot_legend_box(cairo_t *cr, double x, double y, double w, double h);

#endif /* FRACTERRA_RENDER_INTERNAL_H */
