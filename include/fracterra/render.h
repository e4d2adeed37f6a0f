/* fracterra — render.h: hillshade, grid images and vector maps (cairo: PNG, SVG, PDF by extension).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_RENDER_H
#define FRACTERRA_RENDER_H

#include "core.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    size_t struct_size; /**< sizeof(ft_hillshade_opts); see FT_OPTS in core.h */
    double azimuth;   /**< light direction, degrees clockwise from north; default 315 */
    double altitude;  /**< light elevation above the horizon, degrees; default 45 */
    double z_factor;  /**< vertical exaggeration; default 1 */
    double scale;     /**< ground units of the horizontal coordinates per elevation unit: divides both cell sizes,
                           as gdaldem's -s (1 when both are metres; the metres of a degree for a DEM in
                           degrees, which ft_io_hillshade works out when given 0); > 0, default 1 */
} ft_hillshade_opts;
#define FT_HILLSHADE_OPTS_DEFAULT                                                                                    \
    {.struct_size = sizeof(ft_hillshade_opts), .azimuth = 315.0, .altitude = 45.0, .z_factor = 1.0, .scale = 1.0}

/** Hillshade (Horn's 3x3 slope and aspect, as gdaldem hillshade -compute_edges) in [0, 255]: the library's
 *  one hillshade engine (ft_io_hillshade and ft_io_hillshade_rows use it). Nodata cells stay nodata; a
 *  nodata neighbour takes the centre's value and the edge cells are shaded from a linear extrapolation
 *  (gdaldem's rule). At least 2 x 2 cells. The output keeps the input's geotransform and CRS. */
FT_API int ft_render_hillshade(const ft_grid *dem, const ft_hillshade_opts *opts, ft_grid **out);

typedef struct {
    size_t struct_size; /**< sizeof(ft_grid_image_opts); see FT_OPTS in core.h */
    int width;              /**< image width in pixels; 0 = one pixel per cell (height follows) */
    const ft_grid *shade;   /**< optional hillshade (same size) multiplied into the colours; NULL = none */
    int colormap;           /**< 0 = grey, 1 = hypsometric (green-brown-white) */
} ft_grid_image_opts;
#define FT_GRID_IMAGE_OPTS_DEFAULT {.struct_size = sizeof(ft_grid_image_opts), .width = 0, .shade = NULL, .colormap = 0}

/** Writes a grid as a PNG image, stretched between its minimum and maximum; nodata is transparent. */
FT_API int ft_render_grid_png(const ft_grid *g, const char *path, const ft_grid_image_opts *opts);

typedef struct {
    size_t struct_size; /**< sizeof(ft_map_opts); see FT_OPTS in core.h */
    int width, height;       /**< canvas size in points/pixels; default 800 x 600 (aspect kept) */
    double line_width;       /**< stroke width; default 0.8 */
    const char *stroke;      /**< stroke colour "#rrggbb"; default "#1f3b73" */
    const char *fill;        /**< fill colour for polygons, NULL = none; default "#e8eef5" */
    const char *title;       /**< optional title drawn at the top; NULL = none */
    int scale_bar;           /**< 1 to draw a scale bar in layer units; default 1 */
    double window[4];        /**< xmin, ymin, xmax, ymax of the area shown (a zoom; what lies outside is
                                  clipped); all 0 (default) = the layers' extent */
} ft_map_opts;
#define FT_MAP_OPTS_DEFAULT                                                                                          \
    {.struct_size = sizeof(ft_map_opts), .width = 800, .height = 600, .line_width = 0.8, .stroke = "#1f3b73",        \
     .fill = "#e8eef5", .title = NULL, .scale_bar = 1, .window = {0.0, 0.0, 0.0, 0.0}}

/** Draws a layer's chains (polygons filled even-odd, lines stroked) to SVG, PNG or PDF by extension. */
FT_API int ft_render_map(const ft_layer *layer, const char *path, const ft_map_opts *opts);

/** One layer of a multi-layer map. */
typedef struct {
    const ft_layer *layer;
    const char *stroke;  /**< "#rrggbb"; NULL = the map's stroke */
    const char *fill;    /**< polygon fill "#rrggbb", or NULL for none */
    double line_width;   /**< <= 0: the map's line width */
    double dash;         /**< dash length in points/pixels; 0 = solid */
    const char *label;   /**< legend entry; NULL = not in the legend */
} ft_map_layer;

/** Draws several layers on one map (SVG, PNG or PDF by extension), in order (the first at the bottom), framed
 *  on the union of their extents; the labelled layers get a legend in the corner of the map that hides
 *  the fewest vertices. The map options give the size, title, scale bar (in the first layer's CRS units) and
 *  the default stroke and line width (opts->fill is not used: each layer gives its own). */
FT_API int ft_render_map_layers(const ft_map_layer *layers, size_t n, const char *path, const ft_map_opts *opts);

typedef struct {
    size_t struct_size; /**< sizeof(ft_plot_opts); see FT_OPTS in core.h */
    int width, height;  /**< canvas size in points/pixels; default 720 x 540 */
    const char *title;  /**< drawn at the top; NULL = none */
    const char *xlabel; /**< x axis label; default "scale" */
    const char *ylabel; /**< y axis label; default "value" */
    int segments;       /**< 1 to draw every segment's line when the result has segments; default 1 */
} ft_plot_opts;
#define FT_PLOT_OPTS_DEFAULT                                                                                         \
    {.struct_size = sizeof(ft_plot_opts), .width = 720, .height = 540, .title = NULL, .xlabel = "scale",             \
     .ylabel = "value", .segments = 1}

/** The log-log plot of an estimator's result (SVG, PNG or PDF by extension): log10 axes with decade
 *  ticks, used rows filled and the others hollow, the fitted range shaded, the fitted line over it,
 *  every segment's line, and a legend "D = 1.262 ± 0.004, r² = 0.999, range 10–1000". The file is
 *  written under a temporary name and renamed when complete. */
FT_API int ft_render_loglog_plot(const ft_dim_result *r, const char *path, const ft_plot_opts *opts);

/** One series of a chart: points (x[i], y[i]) joined in order; a non-finite y leaves a gap. */
typedef struct {
    const char *name;     /**< legend entry; NULL = not in the legend */
    const double *x, *y;  /**< n values each */
    size_t n;
} ft_series;

typedef struct {
    size_t struct_size; /**< sizeof(ft_chart_opts); see FT_OPTS in core.h */
    int width, height;               /**< canvas size in points/pixels; default 720 x 540 */
    const char *title;               /**< drawn at the top; NULL = none */
    const char *xlabel, *ylabel;     /**< axis labels; default "x" and "y" */
    const char *const *xcategories;  /**< NULL: numeric x axis; else x = 0 .. ncategories - 1, each tick
                                          labelled with its category (years such as "1959", "1980s") */
    size_t ncategories;
} ft_chart_opts;
#define FT_CHART_OPTS_DEFAULT                                                                                        \
    {.struct_size = sizeof(ft_chart_opts), .width = 720, .height = 540, .title = NULL, .xlabel = "x", .ylabel = "y", \
     .xcategories = NULL, .ncategories = 0}

/** A line chart of several series (SVG, PNG or PDF by extension): linear axes with round ticks (or one
 *  tick per category), each series a line with dots in its own colour, a legend of the named series in
 *  the corner hiding the fewest points. Written under a temporary name, renamed when complete. */
FT_API int ft_render_series_chart(const ft_series *series, size_t n, const char *path, const ft_chart_opts *opts);

/* ------------------------------------------------------------------------------------------------
 * Perspective (bird's-eye) view of a DEM (docs/render-perspective.md)
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    size_t struct_size; /**< sizeof(ft_perspective_opts); see FT_OPTS in core.h */
    double azimuth;        /**< direction the viewer looks towards, degrees clockwise from north; default 20 */
    double elevation;      /**< angle of the line of sight below the horizon, degrees in [5, 90]; default 35 */
    double exaggeration;   /**< vertical exaggeration, > 0; 0 (default) = automatic: 1, or more so that the
                                relief reaches 1/6 of the extent's half-diagonal */
    int width;             /**< image width in pixels, [64, 8192]; default 1200 (height follows the scene) */
    double light_azimuth;  /**< sun direction, degrees clockwise from north; default 315 */
    double light_altitude; /**< sun elevation, degrees in (0, 90]; default 40 */
    double scale;          /**< ground units per elevation unit; 0 (default) = the ellipsoid's metres per
                                degree of latitude and of longitude at the grid's centre when its CRS is
                                geographic (ft_io_crs_info), else 1 */
    int sky;               /**< 1 (default): a sky gradient behind the terrain; 0: transparent */
} ft_perspective_opts;
#define FT_PERSPECTIVE_OPTS_DEFAULT                                                                                  \
    {.struct_size = sizeof(ft_perspective_opts), .azimuth = 20.0, .elevation = 35.0, .exaggeration = 0.0,            \
     .width = 1200, .light_azimuth = 315.0, .light_altitude = 40.0, .scale = 0.0, .sky = 1}

/** Renders the lit surface in perspective to a PNG: every quad of four valid neighbouring cells becomes
 *  two triangles, z-buffered, coloured by hypsometric tints times Lambert shading with a little aerial
 *  haze, on a sky gradient; nodata cells leave holes. Written under a temporary name, renamed when
 *  complete. */
FT_API int ft_render_perspective(const ft_grid *dem, const char *path, const ft_perspective_opts *opts);

#ifdef __cplusplus
}
#endif
#endif /* FRACTERRA_RENDER_H */
