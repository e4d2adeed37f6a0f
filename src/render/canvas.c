/* fracterra — render/canvas.c: vector and raster canvases (SVG, PDF, PNG by extension) written atomically,
 * shared by the map and the log-log plot.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "render/render_internal.h"

#include "fracterra/core.h"
#include "fracterra/io.h"
#include "internal.h"

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int ft_canvas_format_of(const char *what, const char *path, ft_canvas_format *fmt)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (dot && strcasecmp(dot, ".svg") == 0)
        *fmt = FT_CANVAS_SVG;
    else if (dot && strcasecmp(dot, ".pdf") == 0)
        *fmt = FT_CANVAS_PDF;
    else if (dot && strcasecmp(dot, ".png") == 0)
        *fmt = FT_CANVAS_PNG;
    else
        return ft_error(FT_E_INVALID, "%s output must end in .svg, .pdf or .png: %s", what, path);
    return FT_OK;
}

/* cairo's output goes through the caller's FILE, so that a failed write keeps errno for the message. */
static cairo_status_t file_write(void *closure, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, closure) == length ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

static cairo_surface_t *open_surface(ft_canvas_format fmt, FILE *f, int w, int h)
{
    if (fmt == FT_CANVAS_SVG) {
        cairo_surface_t *s = cairo_svg_surface_create_for_stream(file_write, f, w, h);
        cairo_svg_surface_restrict_to_version(s, CAIRO_SVG_VERSION_1_1);
#if CAIRO_VERSION >= CAIRO_VERSION_ENCODE(1, 15, 10)
        cairo_svg_surface_set_document_unit(s, CAIRO_SVG_UNIT_PX);
#endif
        return s;
    }
    if (fmt == FT_CANVAS_PDF)
        return cairo_pdf_surface_create_for_stream(file_write, f, w, h);
    return cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
}

typedef struct {
    const char *path;
    ft_canvas_format fmt;
    int w, h;
    ft_canvas_draw_fn draw;
    const void *arg;
} canvas_job;

/* Draws into f and finishes the surface (through ft_io_atomic_write, which checks every write). */
static int draw_to(FILE *f, const void *arg)
{
    const canvas_job *j = arg;
    cairo_surface_t *s = open_surface(j->fmt, f, j->w, j->h);
    cairo_t *cr = cairo_create(s);
    j->draw(cr, j->arg);
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);
    if (st == CAIRO_STATUS_SUCCESS && j->fmt == FT_CANVAS_PNG)
        st = cairo_surface_write_to_png_stream(s, file_write, f);
    cairo_surface_finish(s);
    if (st == CAIRO_STATUS_SUCCESS)
        st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    if (st == CAIRO_STATUS_WRITE_ERROR)
        return FT_E_IO; /* the service names the path and errno */
    if (st != CAIRO_STATUS_SUCCESS)
        return ft_error(FT_E_IO, "cannot draw %s: %s", j->path, cairo_status_to_string(st));
    return FT_OK;
}

int ft_canvas_write(const char *path, ft_canvas_format fmt, int w, int h, ft_canvas_draw_fn draw, const void *arg)
{
    canvas_job j = {path, fmt, w, h, draw, arg};
    return ft_io_atomic_write(path, draw_to, &j);
}
