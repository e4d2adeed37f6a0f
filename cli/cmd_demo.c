/* fracterra — cli/cmd_demo.c: `fracterra demo OUTDIR`: a small gallery made from the bundled data.
 *
 * The data folder is $FRACTERRA_DATA, else the source tree's tests/data (FT_SOURCE_DATADIR), else the
 * installed share/fracterra (FT_INSTALL_DATADIR). The demo is a list of steps (the static `steps` array):
 * each reads its input, writes its outputs into OUTDIR and registers them with a title, a caption and the
 * data's source; the last step writes index.html, a self-contained page showing them all with the
 * `fracterra info` figures of each input. A later capability adds its piece as one more step. If a step
 * fails, the files already written are removed (and OUTDIR, if the demo created it).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"
#include "demo.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef FT_SOURCE_DATADIR
#define FT_SOURCE_DATADIR ""
#endif
#ifndef FT_INSTALL_DATADIR
#define FT_INSTALL_DATADIR ""
#endif

#define DEMO_VOLCANO "dem_volcano_maunga_whau_10m.tif"
#define DEMO_NEWFOUNDLAND "gshhg_newfoundland_utm21n.geojson"
#define SOURCE_VOLCANO                                                                                     \
    "R <code>datasets::volcano</code>: Maunga Whau (Mt Eden), Auckland, digitized by Ross Ihaka; "          \
    "GPL-2 | GPL-3"

/* ---- helpers ---- */

char *demo_join_path(const char *dir, const char *file)
{
    size_t n = strlen(dir);
    int slash = n > 0 && dir[n - 1] == '/';
    size_t size = n + strlen(file) + 2;
    char *p = malloc(size);
    if (p)
        snprintf(p, size, "%s%s%s", dir, slash ? "" : "/", file);
    return p;
}

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

static int has_demo_data(const char *dir)
{
    char *p = demo_join_path(dir, DEMO_VOLCANO);
    int ok = p && access(p, R_OK) == 0;
    free(p);
    return ok;
}

/* The data folder, or NULL (error printed). */
static const char *find_data(const cli_command *cmd)
{
    const char *env = getenv("FRACTERRA_DATA");
    if (env && *env) {
        if (has_demo_data(env))
            return env;
        cli_error(cmd, "FRACTERRA_DATA=%s does not hold the demo data (%s)", env, DEMO_VOLCANO);
        return NULL;
    }
    if (*FT_SOURCE_DATADIR && has_demo_data(FT_SOURCE_DATADIR))
        return FT_SOURCE_DATADIR;
    if (*FT_INSTALL_DATADIR && has_demo_data(FT_INSTALL_DATADIR))
        return FT_INSTALL_DATADIR;
    cli_error(cmd, "cannot find the demo data in %s or %s; set FRACTERRA_DATA to its folder", FT_SOURCE_DATADIR,
              FT_INSTALL_DATADIR);
    return NULL;
}

/* Makes OUTDIR (not its parents). *created tells whether it did. CLI_CONTINUE or CLI_FAIL. */
static int make_outdir(const cli_command *cmd, const char *dir, int *created)
{
    *created = 0;
    if (mkdir(dir, 0777) == 0) {
        *created = 1;
        return CLI_CONTINUE;
    }
    if (errno == EEXIST && is_dir(dir))
        return CLI_CONTINUE;
    if (errno == EEXIST)
        cli_error(cmd, "%s exists and is not a folder", dir);
    else if (errno == ENOENT)
        cli_error(cmd, "cannot create %s: its parent folder does not exist", dir);
    else
        cli_error(cmd, "cannot create %s: %s", dir, strerror(errno));
    return CLI_FAIL;
}

/* Registers an output that a step is about to write; returns its path (owned by ctx) or NULL. */
const char *demo_add_output(demo_ctx *ctx, const char *file, const char *title, const char *caption, int image)
{
    if (ctx->nout == DEMO_MAX_OUTPUTS) {
        ft_error(FT_E_INVALID, "demo: too many outputs (at most %d)", DEMO_MAX_OUTPUTS);
        return NULL;
    }
    char *path = demo_join_path(ctx->outdir, file);
    if (path == NULL) {
        ft_error(FT_E_NOMEM, "demo: out of memory");
        return NULL;
    }
    demo_output *o = &ctx->out[ctx->nout++];
    o->path = path;
    o->file = file;
    o->title = title;
    o->caption = caption;
    o->image = image;
    return path;
}

/* Records the `fracterra info` figures of an input for index.html and the JSON output. */
int demo_add_input(demo_ctx *ctx, const char *file, const char *source)
{
    char *path = demo_join_path(ctx->data, file);
    json_object *info = NULL;
    int rc = path ? cli_info_describe(path, NULL, 0, &info) : ft_error(FT_E_NOMEM, "demo: out of memory");
    free(path);
    if (rc != FT_OK)
        return rc;
    json_object_object_add(info, "name", json_object_new_string(file));
    json_object_object_add(info, "source", json_object_new_string(source));
    json_object_array_add(ctx->inputs, info);
    return FT_OK;
}

/* ---- steps ---- */

static int step_volcano_tif(demo_ctx *ctx)
{
    ft_read_grid_opts ro = FT_READ_GRID_OPTS_DEFAULT;
    ft_write_grid_opts wo = FT_WRITE_GRID_OPTS_DEFAULT;
    char *in = demo_join_path(ctx->data, DEMO_VOLCANO);
    if (in == NULL)
        return ft_error(FT_E_NOMEM, "demo: out of memory");
    int rc = ft_io_read_grid(in, &ro, &ctx->volcano);
    free(in);
    if (rc == FT_OK)
        rc = demo_add_input(ctx, DEMO_VOLCANO, SOURCE_VOLCANO);
    if (rc != FT_OK)
        return rc;
    const char *out = demo_add_output(ctx, "volcano.tif", "Maunga Whau DEM (GeoTIFF)",
                                 "The 10 m DEM of Maunga Whau read and written back through fracterra's GeoTIFF "
                                 "writer: same cells, geotransform and CRS.",
                                 0);
    return out ? ft_io_write_grid(out, ctx->volcano, &wo) : ft_last_error_code();
}

static int step_volcano_hillshade(demo_ctx *ctx)
{
    ft_hillshade_opts ho = FT_HILLSHADE_OPTS_DEFAULT;
    ft_grid_image_opts io = FT_GRID_IMAGE_OPTS_DEFAULT;
    ft_grid *shade = NULL;
    ho.z_factor = 2.0; /* the volcano's gentle slopes read better with some exaggeration */
    int rc = ft_render_hillshade(ctx->volcano, &ho, &shade);
    if (rc != FT_OK)
        return rc;
    io.width = 600;
    io.colormap = 1;
    io.shade = shade;
    const char *out = demo_add_output(ctx, "volcano_hillshade.png", "Maunga Whau, shaded relief",
                                 "Hypsometric tints multiplied by a hillshade (Horn's method, light from the "
                                 "north-west at 45&deg;, "
                                 "vertical exaggeration 2), enlarged from 61 &times; 87 cells to 600 pixels wide.",
                                 1);
    rc = out ? ft_render_grid_png(ctx->volcano, out, &io) : ft_last_error_code();
    ft_grid_free(shade);
    return rc;
}

static int step_newfoundland_map(demo_ctx *ctx)
{
    ft_read_layer_opts ro = FT_READ_LAYER_OPTS_DEFAULT;
    ft_map_opts mo = FT_MAP_OPTS_DEFAULT;
    ft_layer *l = NULL;
    char *in = demo_join_path(ctx->data, DEMO_NEWFOUNDLAND);
    if (in == NULL)
        return ft_error(FT_E_NOMEM, "demo: out of memory");
    int rc = ft_io_read_layer(in, &ro, &l);
    free(in);
    if (rc == FT_OK)
        rc = demo_add_input(ctx, DEMO_NEWFOUNDLAND, SOURCE_GSHHG);
    if (rc == FT_OK) {
        const char *out = demo_add_output(ctx, "newfoundland.svg", "Newfoundland shoreline",
                                     "The island's full-resolution GSHHG shoreline, one ring, drawn as an SVG "
                                     "map with a scale bar.",
                                     1);
        mo.title = "Newfoundland: GSHHG full-resolution shoreline (UTM 21N)";
        mo.width = 800;
        mo.height = 800;
        rc = out ? ft_render_map(l, out, &mo) : ft_last_error_code();
    }
    ft_layer_free(l);
    return rc;
}

/* HTML-escapes s into f. */
static void html_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '<')
            fputs("&lt;", f);
        else if (*s == '>')
            fputs("&gt;", f);
        else if (*s == '&')
            fputs("&amp;", f);
        else if (*s == '"')
            fputs("&quot;", f);
        else
            fputc(*s, f);
    }
}

static long long jint(json_object *o, const char *key)
{
    json_object *v = NULL;
    return json_object_object_get_ex(o, key, &v) ? (long long)json_object_get_int64(v) : 0;
}

static const char *jstr(json_object *o, const char *key)
{
    json_object *v = NULL;
    return json_object_object_get_ex(o, key, &v) && v ? json_object_get_string(v) : "";
}

/* The `fracterra info` figures of one input, in a sentence. */
static void html_input_figures(FILE *f, json_object *in)
{
    json_object *crs = NULL, *size = NULL;
    const char *kind = jstr(in, "kind");
    if (strcmp(kind, "grid") == 0 && json_object_object_get_ex(in, "size", &size)) {
        fprintf(f, "grid of %lld &times; %lld = %lld cells (%lld valid)",
                (long long)json_object_get_int64(json_object_array_get_idx(size, 0)),
                (long long)json_object_get_int64(json_object_array_get_idx(size, 1)), jint(in, "cells"),
                jint(in, "valid"));
    } else if (strcmp(kind, "chains") == 0) {
        fprintf(f, "%lld feature(s), %lld ring(s), %lld line(s), %lld vertices (%lld with closing vertices)",
                jint(in, "features"), jint(in, "rings"), jint(in, "lines"), jint(in, "vertices"),
                jint(in, "file_vertices"));
    } else {
        fprintf(f, "%lld points", jint(in, "points"));
    }
    if (json_object_object_get_ex(in, "crs", &crs) && crs) {
        fputs(", CRS ", f);
        html_text(f, jstr(crs, "name"));
        if (jint(crs, "epsg"))
            fprintf(f, " (EPSG:%lld)", jint(crs, "epsg"));
    }
}

static void html_outputs(FILE *f, const demo_ctx *ctx)
{
    fputs("<h2>What the demo made</h2>\n", f);
    for (size_t i = 0; i < ctx->nout; i++) {
        const demo_output *o = &ctx->out[i];
        if (strcmp(o->file, "index.html") == 0)
            continue;
        fputs("<figure>\n", f);
        if (o->image) {
            fputs("<img src=\"", f);
            html_text(f, o->file);
            fputs("\" alt=\"", f);
            html_text(f, o->title);
            fputs("\">\n", f);
        }
        fputs("<figcaption><a href=\"", f);
        html_text(f, o->file);
        fputs("\">", f);
        html_text(f, o->file);
        fputs("</a>: <b>", f);
        html_text(f, o->title);
        fprintf(f, "</b>. %s</figcaption>\n</figure>\n", o->caption);
    }
}

static void html_inputs(FILE *f, const demo_ctx *ctx)
{
    fputs("<h2>Inputs and data sources</h2>\n<table>\n<tr><th>file</th><th>what <code>fracterra info</code> "
          "sees</th><th>source and licence</th></tr>\n",
          f);
    for (size_t i = 0; i < json_object_array_length(ctx->inputs); i++) {
        json_object *in = json_object_array_get_idx(ctx->inputs, i);
        fputs("<tr><td><code>", f);
        html_text(f, jstr(in, "name"));
        fputs("</code></td><td>", f);
        html_input_figures(f, in);
        fprintf(f, "</td><td>%s</td></tr>\n", jstr(in, "source"));
    }
    fputs("</table>\n<p>Full provenance: <code>tests/data/README.md</code> in the source tree, "
          "<code>share/fracterra/README.md</code> once installed.</p>\n",
          f);
}

static void html_page(FILE *f, const demo_ctx *ctx)
{
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>fracterra demo</title>\n"
          "<style>\nbody{font-family:sans-serif;max-width:58em;margin:2em auto;padding:0 1em;color:#222}\n"
          "figure{margin:1.5em 0}img{max-width:100%;border:1px solid #ccc}figcaption{margin-top:.4em}\n"
          "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:.3em .6em;text-align:left}\n"
          "</style>\n</head>\n<body>\n<h1>fracterra demo</h1>\n",
          f);
    fprintf(f, "<p>Made by <code>fracterra demo</code> (fracterra %s) from the data bundled with fracterra, "
               "a library and command-line tool for the fractal geometry of maps.</p>\n",
            ft_version());
    html_outputs(f, ctx);
    html_inputs(f, ctx);
    fputs("</body>\n</html>\n", f);
}

static int write_page(FILE *f, const void *ctx)
{
    html_page(f, ctx);
    return FT_OK;
}

static int step_index_html(demo_ctx *ctx)
{
    const char *out = demo_add_output(ctx, "index.html", "the gallery page", "This page.", 0);
    if (out == NULL)
        return ft_last_error_code();
    return cli_write_file(out, write_page, ctx);
}

/* The demo, in order; index.html comes last so that it shows everything before it. */
static const struct {
    const char *name;
    demo_step_fn run;
} steps[] = {
    {"volcano GeoTIFF", step_volcano_tif},
    {"volcano hillshade", step_volcano_hillshade},
    {"Newfoundland map", step_newfoundland_map},
    {"Newfoundland enhancement", demo_step_lines},
    {"terrain", demo_step_terrain},
    {"urban boundary", demo_step_urban},
    {"mountain", demo_step_mountain},
    {"index.html", step_index_html},
};

/* ---- the command ---- */

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    if (opt == 'j') {
        *(int *)ctx = 1;
        return CLI_CONTINUE;
    }
    return cli_usage_error(cmd, "unexpected option");
}

static void cleanup(demo_ctx *ctx, int failed, int created)
{
    for (size_t i = 0; i < ctx->nout; i++) {
        if (failed)
            unlink(ctx->out[i].path);
        free(ctx->out[i].path);
    }
    if (failed && created)
        rmdir(ctx->outdir);
    json_object_put(ctx->inputs);
    ft_grid_free(ctx->volcano);
}

static int report(demo_ctx *ctx, int json)
{
    if (!json) {
        printf("fracterra demo: data from %s\n", ctx->data);
        for (size_t i = 0; i < ctx->nout; i++)
            printf("  wrote %-40s %s\n", ctx->out[i].path, ctx->out[i].title);
        printf("open %s in a browser\n", ctx->out[ctx->nout - 1].path);
        return CLI_OK;
    }
    json_object *o = json_object_new_object(), *outs = json_object_new_array();
    for (size_t i = 0; i < ctx->nout; i++)
        json_object_array_add(outs, json_object_new_string(ctx->out[i].path));
    json_object_object_add(o, "outdir", json_object_new_string(ctx->outdir));
    json_object_object_add(o, "data_dir", json_object_new_string(ctx->data));
    json_object_object_add(o, "outputs", outs);
    json_object_object_add(o, "inputs", json_object_get(ctx->inputs));
    return cli_print_json(ctx->cmd, o);
}

static int run_demo(const cli_command *cmd, int argc, char **argv)
{
    static const struct option longopts[] = {{"json", no_argument, NULL, 'j'}, CLI_OPT_HELP, CLI_OPT_END};
    static const char *const names[] = {"OUTDIR"};
    int json = 0, first = 0, created = 0;
    int rc = cli_parse_options(cmd, argc, argv, longopts, "j", on_option, &json, &first);
    if (rc == CLI_CONTINUE)
        rc = cli_expect_args(cmd, argc, argv, first, names, 1);
    if (rc != CLI_CONTINUE)
        return rc;

    demo_ctx ctx = {.cmd = cmd, .outdir = argv[first]};
    if ((ctx.data = find_data(cmd)) == NULL || make_outdir(cmd, ctx.outdir, &created) != CLI_CONTINUE)
        return CLI_FAIL;
    ctx.inputs = json_object_new_array();
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; i++) {
        if (steps[i].run(&ctx) != FT_OK) {
            cli_error(cmd, "%s: %s", steps[i].name, ft_last_error());
            cleanup(&ctx, 1, created);
            return CLI_FAIL;
        }
    }
    rc = report(&ctx, json);
    cleanup(&ctx, 0, created);
    return rc;
}

const cli_command cli_cmd_demo = {
    "demo",
    "make a small gallery (GeoTIFF, shaded relief, maps, log-log plots, index.html) from the bundled data",
    "fracterra demo OUTDIR [--json]",
    "Writes into OUTDIR (created if missing; its parent must exist):\n"
    "  volcano.tif                     the Maunga Whau DEM written back through fracterra's GeoTIFF writer\n"
    "  volcano_hillshade.png           hypsometric tints times a hillshade, 600 pixels wide\n"
    "  newfoundland.svg                a map of the GSHHG shoreline of Newfoundland with a scale bar\n"
    "  newfoundland_enhanced.svg       Dutton's sequence: the shoreline generalized to 158 points, enhanced,\n"
    "                                  weeded and smoothed, drawn over the original\n"
    "  newfoundland_loglog_before.svg  divider log-log plot of the 158-point outline\n"
    "  newfoundland_loglog_after.svg   the same for the enhanced outline\n"
    "  terrain_synth.tif               a synthetic fBm terrain, D = 2.3, 512 x 512 cells, seeded\n"
    "  terrain_synth_hillshade.png     its GDAL hillshade times a colour relief\n"
    "  terrain_synth_perspective.png   its perspective view\n"
    "  volcano_gdal_hillshade.png      the volcano's GDAL hillshade times a colour relief\n"
    "  volcano_perspective.png         the volcano's perspective view\n"
    "  volcano_clarke_model.json       Clarke's model fitted to the volcano (figures in index.html)\n"
    "  urban_boundary.png              Rhode Island's boundary with detail of D = 1.2325 added by the\n"
    "                                  midpoint-subdivision generator, drawn over the input\n"
    "  urban_boundary_zoom.png         the same on a window a fifth of the state's width\n"
    "  index.html                      a page showing them, with the inputs' figures and data sources\n"
    "The data folder is $FRACTERRA_DATA, else the source tree's tests/data, else the installed\n"
    "share/fracterra. If a step fails, nothing is left behind.\n\n"
    "Options:\n"
    "  -j, --json   print {\"outdir\", \"data_dir\", \"outputs\": [paths], \"inputs\": [info...]} on stdout\n"
    "  -h, --help   print this help\n\n"
    "Example:\n"
    "  fracterra demo out/ && xdg-open out/index.html\n",
    run_demo,
};
