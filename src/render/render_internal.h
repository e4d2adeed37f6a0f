/* fracterra — private helpers of the render module (src/render/), not installed.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_RENDER_INTERNAL_H
#define FRACTERRA_RENDER_INTERNAL_H

#include <cairo.h>

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

#endif /* FRACTERRA_RENDER_INTERNAL_H */
