/* fracterra — render/grid_image.c: a grid as a PNG image (grey or hypsometric tints, optional hillshade).
 *
 * Valid cells are stretched linearly between the grid's minimum and maximum, coloured through a grey ramp
 * or a hypsometric one (green lowlands, tan, brown, white summits), and optionally multiplied by a
 * hillshade of the same size (ambient term 0.25 so that shadows stay readable). Nodata is transparent. The
 * image of one pixel per cell is then resampled to the requested width by cairo (bilinear when enlarging,
 * box filtering when reducing), written to a temporary name and renamed onto the output.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fracterra/render.h"
#include "fracterra/io.h"
#include "internal.h"
#include "render/render_internal.h"

#include <cairo.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#define FT_PNG_MAX_SIDE 32767 /* cairo's limit for an image surface side */
#define FT_SHADE_AMBIENT 0.25

typedef struct {
    double t;
    double r, g, b;
} color_stop;

static const color_stop hypsometric[] = {
    {0.00, 0.24, 0.49, 0.27}, {0.20, 0.55, 0.71, 0.42}, {0.45, 0.91, 0.85, 0.58},
    {0.70, 0.71, 0.54, 0.35}, {0.88, 0.55, 0.45, 0.40}, {1.00, 0.98, 0.98, 0.98},
};

void ft_render_ramp(double t, int colormap, double rgb[3])
{
    if (colormap == 0) {
        rgb[0] = rgb[1] = rgb[2] = t;
        return;
    }
    size_t n = sizeof hypsometric / sizeof hypsometric[0];
    size_t k = 1;
    while (k < n - 1 && t > hypsometric[k].t)
        k++;
    const color_stop *a = &hypsometric[k - 1], *b = &hypsometric[k];
    double u = (t - a->t) / (b->t - a->t);
    u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    rgb[0] = a->r + u * (b->r - a->r);
    rgb[1] = a->g + u * (b->g - a->g);
    rgb[2] = a->b + u * (b->b - a->b);
}

static int check_args(const ft_grid *g, const char *path, const ft_grid_image_opts *o)
{
    if (g == NULL || g->z == NULL || g->nx == 0 || g->ny == 0)
        return ft_error(FT_E_INVALID, "grid image: no grid given");
    if (path == NULL || *path == '\0')
        return ft_error(FT_E_INVALID, "grid image: no output path given");
    if (o->colormap != 0 && o->colormap != 1)
        return ft_error(FT_E_INVALID, "grid image colormap must be 0 (grey) or 1 (hypsometric), got %d",
                        o->colormap);
    if (o->width < 0 || o->width > FT_PNG_MAX_SIDE)
        return ft_error(FT_E_INVALID, "grid image width must be in [0,%d] pixels, got %d", FT_PNG_MAX_SIDE,
                        o->width);
    if (o->shade && (o->shade->nx != g->nx || o->shade->ny != g->ny || o->shade->z == NULL))
        return ft_error(FT_E_INVALID, "grid image: the shade grid is %zu x %zu, the grid %zu x %zu",
                        o->shade ? o->shade->nx : 0, o->shade ? o->shade->ny : 0, g->nx, g->ny);
    return FT_OK;
}

/* Mean of the valid shade values: used where the grid is valid but the shade is not (its edge). */
static double shade_mean(const ft_grid *s)
{
    double sum = 0.0;
    size_t n = 0;
    for (size_t k = 0; k < s->nx * s->ny; k++) {
        if ((s->mask == NULL || s->mask[k]) && isfinite(s->z[k])) {
            sum += s->z[k];
            n++;
        }
    }
    return n ? sum / (double)n : 255.0;
}

static uint32_t cell_pixel(const ft_grid *g, size_t k, double zmin, double zrange, const ft_grid_image_opts *o,
                           double shade_fill)
{
    if ((g->mask && !g->mask[k]) || !isfinite(g->z[k]))
        return 0; /* transparent */
    double t = zrange > 0.0 ? (g->z[k] - zmin) / zrange : 0.5;
    double rgb[3];
    ft_render_ramp(t, o->colormap, rgb);
    if (o->shade) {
        const ft_grid *s = o->shade;
        double v = ((s->mask == NULL || s->mask[k]) && isfinite(s->z[k])) ? s->z[k] : shade_fill;
        v = v < 0.0 ? 0.0 : (v > 255.0 ? 255.0 : v);
        double f = FT_SHADE_AMBIENT + (1.0 - FT_SHADE_AMBIENT) * v / 255.0;
        for (int c = 0; c < 3; c++)
            rgb[c] *= f;
    }
    uint32_t r = (uint32_t)lround(rgb[0] * 255.0), gr = (uint32_t)lround(rgb[1] * 255.0),
             b = (uint32_t)lround(rgb[2] * 255.0);
    return 0xff000000u | (r << 16) | (gr << 8) | b;
}

/* The one-pixel-per-cell image (every step-th cell when the grid exceeds cairo's size limit). */
static cairo_surface_t *cells_surface(const ft_grid *g, const ft_grid_image_opts *o, size_t step)
{
    double zmin, zmax;
    if (ft_grid_minmax(g, &zmin, &zmax) != FT_OK) {
        ft_error(FT_E_EMPTY, "grid image: the grid has no valid cell (all %zu cells are nodata)", g->nx * g->ny);
        return NULL;
    }
    int w = (int)((g->nx + step - 1) / step), h = (int)((g->ny + step - 1) / step);
    cairo_surface_t *s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
    if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
        ft_error(FT_E_NOMEM, "grid image: cannot make a %d x %d image: %s", w, h,
                 cairo_status_to_string(cairo_surface_status(s)));
        cairo_surface_destroy(s);
        return NULL;
    }
    double shade_fill = o->shade ? shade_mean(o->shade) : 255.0;
    cairo_surface_flush(s);
    unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    for (int row = 0; row < h; row++) {
        uint32_t *line = (uint32_t *)(void *)(data + (size_t)row * (size_t)stride);
        for (int col = 0; col < w; col++) {
            size_t k = (size_t)row * step * g->nx + (size_t)col * step;
            line[col] = cell_pixel(g, k, zmin, zmax - zmin, o, shade_fill);
        }
    }
    cairo_surface_mark_dirty(s);
    return s;
}

/* Resamples src to width x height (transparent background) and writes it as PNG to path. */
static cairo_status_t png_write(void *closure, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, closure) == length ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

/* The image as PNG into f (ft_io_atomic_write checks the writes and names the path and errno). */
static int png_to(FILE *f, const void *surface)
{
    cairo_status_t st = cairo_surface_write_to_png_stream((cairo_surface_t *)surface, png_write, f);
    if (st == CAIRO_STATUS_WRITE_ERROR)
        return FT_E_IO;
    return st == CAIRO_STATUS_SUCCESS ? FT_OK : ft_error(FT_E_IO, "cannot encode PNG: %s", cairo_status_to_string(st));
}

static int write_scaled_png(cairo_surface_t *src, int width, int height, const char *path)
{
    int sw = cairo_image_surface_get_width(src), sh = cairo_image_surface_get_height(src);
    cairo_surface_t *dst = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height);
    cairo_t *cr = cairo_create(dst);
    cairo_scale(cr, (double)width / sw, (double)height / sh);
    cairo_set_source_surface(cr, src, 0, 0);
    cairo_pattern_t *pat = cairo_get_source(cr);
    cairo_pattern_set_extend(pat, CAIRO_EXTEND_PAD);
    cairo_filter_t filter = CAIRO_FILTER_NEAREST;
    if (width != sw)
        filter = width > sw ? CAIRO_FILTER_BILINEAR : CAIRO_FILTER_GOOD;
    cairo_pattern_set_filter(pat, filter);
    cairo_set_operator(cr, CAIRO_OPERATOR_SOURCE);
    cairo_paint(cr);
    cairo_status_t st = cairo_status(cr);
    cairo_destroy(cr);

    int rc = st == CAIRO_STATUS_SUCCESS ? ft_io_atomic_write(path, png_to, dst)
                                        : ft_error(FT_E_NOMEM, "cannot draw %s: %s", path, cairo_status_to_string(st));
    cairo_surface_destroy(dst);
    return rc;
}

int ft_render_grid_png(const ft_grid *g, const char *path, const ft_grid_image_opts *opts)
{
    ft_grid_image_opts taken = FT_GRID_IMAGE_OPTS_DEFAULT; /* FT_OPTS in core.h */
    if (opts != NULL) {
        if (FT_OPTS_TAKE(taken, opts, ft_grid_image_opts) != FT_OK)
            return FT_E_INVALID;
        opts = &taken;
    }
    ft_grid_image_opts defaults = FT_GRID_IMAGE_OPTS_DEFAULT;
    const ft_grid_image_opts *o = opts ? opts : &defaults;
    int rc = check_args(g, path, o);
    if (rc != FT_OK)
        return rc;

    size_t side = g->nx > g->ny ? g->nx : g->ny;
    size_t step = (side + FT_PNG_MAX_SIDE - 1) / FT_PNG_MAX_SIDE;
    int width = o->width > 0 ? o->width : (int)((g->nx + step - 1) / step);
    double height = round((double)g->ny * width / (double)g->nx);
    if (height < 1.0 || height > FT_PNG_MAX_SIDE)
        return ft_error(FT_E_INVALID, "grid image: a width of %d pixels gives a height of %.0f, outside [1,%d]",
                        width, height, FT_PNG_MAX_SIDE);

    cairo_surface_t *cells = cells_surface(g, o, step);
    if (cells == NULL)
        return ft_last_error_code();
    rc = write_scaled_png(cells, width, (int)height, path);
    cairo_surface_destroy(cells);
    return rc;
}
