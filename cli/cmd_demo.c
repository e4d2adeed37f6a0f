/* fracterra — cli/cmd_demo.c: `fracterra demo OUTDIR`: a small gallery made by running fracterra's own
 * commands on the bundled data.
 *
 * The data folder is $FRACTERRA_DATA, else the source tree's tests/data (FT_SOURCE_DATADIR), else the
 * installed share/fracterra (FT_INSTALL_DATADIR). The gallery is the static `items` array: each item is one
 * real command line (an argv array) that the demo runs by exec'ing this very binary (/proc/self/exe) in
 * OUTDIR, its stdout discarded, and the files that command writes. The caption of each item in index.html
 * and the manifest gallery.json ({"items": [{"title", "argv", "outputs"}]}) are made from that same argv, so
 * a caption is the command that produced the file (tests/cli/test_cli_demo.c re-runs every recorded argv
 * and compares the files). In an argv, a word starting with "@/" names a file of the data folder. If a
 * command fails, the files already written are removed (and OUTDIR, if the demo created it).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "cli.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef FT_SOURCE_DATADIR
#define FT_SOURCE_DATADIR ""
#endif
#ifndef FT_INSTALL_DATADIR
#define FT_INSTALL_DATADIR ""
#endif

#define DEMO_MAX_ARGS 32
#define DEMO_MAX_OUTPUTS 64
#define DEMO_VOLCANO "dem_volcano_maunga_whau_10m.tif"

/* ---- the gallery ---- */

typedef struct {
    const char *file; /* written in OUTDIR by the command */
    int image;        /* 1 if index.html shows it with <img> */
} demo_file;

typedef struct {
    const char *title;
    const char *caption;   /* what it shows (HTML); the command line follows, made from argv */
    demo_file outputs[5];  /* ends at a NULL file */
    const char *argv[DEMO_MAX_ARGS]; /* "fracterra", COMMAND, ...; ends at NULL; "@/name": data folder */
} demo_item;

static const demo_item items[] = {
    {"Synthetic terrain (GeoTIFF)",
     "A fractional Brownian surface of D = 2.3 (spectral synthesis on a padded grid), 512 &times; 512 cells of "
     "10 m, standard deviation 60 m, seeded.",
     {{"terrain_synth.tif", 0}},
     {"fracterra", "synth", "terrain_synth.tif", "--dim", "2.3", "--size", "512x512", "--cell", "10", "--sigma",
      "60", "--seed", "2024"}},
    {"Synthetic terrain, shaded relief",
     "GDAL's hillshade (light from the north-west at 45&deg;, z-factor 2) times its colour relief with "
     "fracterra's hypsometric ramp.",
     {{"terrain_synth_hillshade.png", 1}},
     {"fracterra", "hillshade", "terrain_synth.tif", "terrain_synth_hillshade.png", "--z-factor", "2", "--color"}},
    {"Synthetic terrain, perspective view",
     "The same surface seen from the south-south-west, 35&deg; down, z-buffered and lit.",
     {{"terrain_synth_perspective.png", 1}},
     {"fracterra", "render", "terrain_synth.tif", "terrain_synth_perspective.png", "--width", "900"}},
    {"Maunga Whau, shaded relief",
     "The 10 m DEM of Maunga Whau (61 &times; 87 cells): GDAL's hillshade, z-factor 2, times its colour relief.",
     {{"volcano_hillshade.png", 1}},
     {"fracterra", "hillshade", "@/" DEMO_VOLCANO, "volcano_hillshade.png", "--z-factor", "2", "--color"}},
    {"Maunga Whau, perspective view",
     "The 10 m DEM seen from the south-south-west, 35&deg; down, vertical exaggeration chosen automatically.",
     {{"volcano_perspective.png", 1}},
     {"fracterra", "render", "@/" DEMO_VOLCANO, "volcano_perspective.png", "--width", "900"}},
    {"Maunga Whau, Clarke model",
     "Clarke's model z = T + cF + H (1987) fitted to the volcano: trend, significant harmonics and "
     "spectral slope. A cone's spectrum is steeper than any fractional Brownian surface's, so the command "
     "warns that its D falls outside (2,3).",
     {{"volcano_clarke_model.json", 0}},
     {"fracterra", "model", "fit", "@/" DEMO_VOLCANO, "-o", "volcano_clarke_model.json"}},
    {"Newfoundland, Douglas-Peucker outline",
     "Dutton's Newfoundland sequence (1981, Fig. 6), first step: the GSHHG full-resolution shoreline "
     "(64,193 vertices) generalized with Douglas-Peucker to at most 158 vertices.",
     {{"newfoundland_158.geojson", 0}},
     {"fracterra", "simplify", "@/gshhg_newfoundland_utm21n.geojson", "newfoundland_158.geojson", "--vertices",
      "158"}},
    {"Newfoundland, enhanced outline",
     "The generalized outline enhanced with SD = 1.3, UC = 0.7, SM = 5100 m (1% of the island's width) and no "
     "straightness limit, weeded at SM and smoothed once, with Dutton's own pass, which moves the 158 "
     "vertices (158 to 328, 296 and 592 points; the paper's sequence with the vertices kept follows).",
     {{"newfoundland_enhanced.geojson", 0}},
     {"fracterra", "enhance", "newfoundland_158.geojson", "newfoundland_enhanced.geojson", "--sd", "1.3", "--uc",
      "0.7", "--sm", "5100", "--weed", "--smooth", "1"}},
    {"Newfoundland, Douglas-Peucker outline: divider",
     "Walking-divider log-log plot of the generalized outline, over its automatic ruler range (the command "
     "warns that at 158 points no straight run of a decade exists).",
     {{"newfoundland_loglog_before.svg", 1}},
     {"fracterra", "dim", "line", "newfoundland_158.geojson", "--plot", "newfoundland_loglog_before.svg"}},
    {"Newfoundland, enhanced outline: divider",
     "The same for the enhanced outline (its own automatic range).",
     {{"newfoundland_loglog_after.svg", 1}},
     {"fracterra", "dim", "line", "newfoundland_enhanced.geojson", "--plot", "newfoundland_loglog_after.svg"}},
    {"Newfoundland, the paper's sequence: enhanced",
     "Stage B of Fig. 6 with the paper's parameters (SD = 1.3, UC = 0.7, no straightness limit, SM = 7372 m: "
     "1% of the width of a 4:3 map window holding the island, 737 km) and <code>--keep-vertices</code>: the "
     "158 vertices stay where they are and each new midpoint goes where Dutton's pass puts it relative to its "
     "two neighbours, so the detail is added below the outline's segments and its shape at their scale and "
     "above stays (Dutton's pass itself moves the 158 vertices and lowers D over the rulers below by 0.06). "
     "158 to 328 points (Dutton: 302; every segment here is longer than SM and split, and the two over 3 times "
     "the mean are first cut into 4).",
     {{"newfoundland_b.geojson", 0}},
     {"fracterra", "enhance", "newfoundland_158.geojson", "newfoundland_b.geojson", "--sd", "1.3", "--uc", "0.7",
      "--sm", "7372", "--keep-vertices"}},
    {"Newfoundland, the paper's sequence: weeded",
     "Stage C: segments shorter than SM weeded out (Dutton's weeding): 293 points, 10.7% fewer (Dutton: "
     "about 10%; 267 by his 534).",
     {{"newfoundland_c.geojson", 0}},
     {"fracterra", "weed", "newfoundland_b.geojson", "newfoundland_c.geojson", "--min-segment", "7372"}},
    {"Newfoundland, the paper's sequence: smoothed",
     "Stage D: smoothed once (roundness 0.5, segments of at least SM): every vertex cut in two, 586 points "
     "(Dutton: 534).",
     {{"newfoundland_d.geojson", 0}},
     {"fracterra", "smooth", "newfoundland_c.geojson", "newfoundland_d.geojson", "--sm", "7372"}},
#define NF_RULERS "--min-scale", "48540.3", "--max-scale", "187304", "--scales", "16", "--starts", "48"
    {"Newfoundland A (158 points): divider over the common rulers",
     "Every stage is measured over the same 16 rulers, 48.5 to 187.3 km (the 158-point outline's automatic "
     "range), the walk averaged over 48 start vertices spread evenly round the ring: one walk's D moves by "
     "about 0.05 with its start. The plot gives D; <code>--json</code> adds each start's spread. "
     "docs/line-newfoundland.md tabulates the stages. Measured: D 1.509 (158 points).",
     {{"newfoundland_a_divider.svg", 1}},
     {"fracterra", "dim", "line", "newfoundland_158.geojson", NF_RULERS, "--plot", "newfoundland_a_divider.svg"}},
    {"Newfoundland B (enhanced): divider over the common rulers",
     "The same rulers and starts. Measured: D 1.515 (328 points), +0.006 from A.",
     {{"newfoundland_b_divider.svg", 1}},
     {"fracterra", "dim", "line", "newfoundland_b.geojson", NF_RULERS, "--plot", "newfoundland_b_divider.svg"}},
    {"Newfoundland C (weeded): divider over the common rulers",
     "The same rulers and starts. Measured: D 1.515 (293 points), +0.006 from A.",
     {{"newfoundland_c_divider.svg", 1}},
     {"fracterra", "dim", "line", "newfoundland_c.geojson", NF_RULERS, "--plot", "newfoundland_c_divider.svg"}},
    {"Newfoundland D (smoothed): divider over the common rulers",
     "The same rulers and starts. Measured: D 1.486 (586 points), -0.023 from A.",
     {{"newfoundland_d_divider.svg", 1}},
     {"fracterra", "dim", "line", "newfoundland_d.geojson", NF_RULERS, "--plot", "newfoundland_d_divider.svg"}},
#undef NF_RULERS
    {"Rhode Island, simplified boundary",
     "Rhode Island's boundary from the DCW states, simplified with Douglas-Peucker at 600 m: the input of "
     "the boundary simulation.",
     {{"urban_ri.geojson", 0}},
     {"fracterra", "simplify", "@/dcw_us_states_small_albers5070.geojson", "urban_ri.geojson", "--where",
      "code = 'US.RI'", "--tolerance", "600"}},
    {"Rhode Island: a boundary simulated with D = 1.2325",
     "Detail of dimension 1.2325 added to the simplified boundary by the midpoint-subdivision generator "
     "(Zhang, Yu &amp; Fan 2008) down to 100 m segments, seeded.",
     {{"urban_ri_simulated.geojson", 0}},
     {"fracterra", "boundary", "urban_ri.geojson", "urban_ri_simulated.geojson", "--dim", "1.2325", "--min",
      "100", "--seed", "1997"}},
    {"Rhode Island, simulated boundary: box counting",
     "Box-counting log-log plot of the simulated boundary.",
     {{"urban_ri_simulated_loglog.svg", 1}},
     {"fracterra", "dim", "line", "urban_ri_simulated.geojson", "--method", "box", "--plot",
      "urban_ri_simulated_loglog.svg"}},
    {"Contours grown from one seed contour",
     "Every contour of a mountain grown from the 130 m contour of Maunga Whau by the improved contour "
     "generation method of Misawa, Chiba &amp; Saito, every 5 m, 3 levels grown outward below the seed, the "
     "paper's fixed 20-40&deg; displacement angles; the contour map (seed in red), the DEM interpolated "
     "between the contours and its perspective view.",
     {{"mountain_contours.svg", 1}, {"mountain_perspective.png", 1}, {"mountain_contours.geojson", 0},
      {"mountain.tif", 0}},
     {"fracterra", "mountain", "@/seed_contour_volcano.geojson", "mountain_contours.geojson", "--interval", "5",
      "--levels-down", "3", "--theta", "20,40", "--seed", "8", "--dem", "mountain.tif", "--cell", "2", "--view",
      "mountain_perspective.png", "--map", "mountain_contours.svg"}},
};
#define NITEMS (sizeof items / sizeof items[0])

/* The inputs of the gallery, for the table of index.html. */
static const struct {
    const char *file;
    const char *source; /* HTML */
} inputs[] = {
    {DEMO_VOLCANO, "R <code>datasets::volcano</code>: Maunga Whau (Mt Eden), Auckland, digitized by Ross Ihaka; "
                   "GPL-2 | GPL-3"},
    {"gshhg_newfoundland_utm21n.geojson",
     "GSHHG 2.3.7 full resolution shoreline, Wessel &amp; Smith (1996); LGPL-3+"},
    {"dcw_us_states_small_albers5070.geojson",
     "DCW-GMT 2.1.1 (Digital Chart of the World for GMT), P. Wessel; LGPL-3+"},
    {"seed_contour_volcano.geojson",
     "the 130 m contour of Maunga Whau, made from <code>" DEMO_VOLCANO "</code> with <code>gdal_contour "
     "-p</code>; GPL-2 | GPL-3"},
};
#define NINPUTS (sizeof inputs / sizeof inputs[0])

typedef struct {
    const cli_command *cmd;
    const char *data;   /* the data folder */
    const char *outdir;
    char *path[DEMO_MAX_OUTPUTS]; /* OUTDIR/file of each output written or being written */
    const char *file[DEMO_MAX_OUTPUTS];
    size_t nout;
    char *argv[NITEMS][DEMO_MAX_ARGS]; /* the argv run, data paths resolved */
    json_object *inputs; /* array: `fracterra info` of each input, plus "name" and "source" */
} demo_ctx;

/* ---- helpers ---- */

static char *join_path(const char *dir, const char *file)
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
    char *p = join_path(dir, DEMO_VOLCANO);
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

/* Registers an output about to be written, so that a failed demo removes it. FT_OK or FT_E_*. */
static int add_output(demo_ctx *ctx, const char *file)
{
    if (ctx->nout == DEMO_MAX_OUTPUTS)
        return ft_error(FT_E_INVALID, "demo: too many outputs (at most %d)", DEMO_MAX_OUTPUTS);
    char *path = join_path(ctx->outdir, file);
    if (path == NULL)
        return ft_error(FT_E_NOMEM, "demo: out of memory");
    ctx->path[ctx->nout] = path;
    ctx->file[ctx->nout++] = file;
    return FT_OK;
}

/* Records the `fracterra info` figures of every input for index.html and the JSON output. */
static int describe_inputs(demo_ctx *ctx)
{
    for (size_t i = 0; i < NINPUTS; i++) {
        char *path = join_path(ctx->data, inputs[i].file);
        json_object *info = NULL;
        int rc = path ? cli_info_describe(path, NULL, 0, &info) : ft_error(FT_E_NOMEM, "demo: out of memory");
        free(path);
        if (rc != FT_OK)
            return rc;
        json_object_object_add(info, "name", json_object_new_string(inputs[i].file));
        json_object_object_add(info, "source", json_object_new_string(inputs[i].source));
        json_object_array_add(ctx->inputs, info);
    }
    return FT_OK;
}

/* ctx->argv[k]: the item's argv with "@/name" resolved in the data folder. */
static int resolve_argv(demo_ctx *ctx, size_t k)
{
    for (size_t i = 0; items[k].argv[i]; i++) {
        const char *a = items[k].argv[i];
        ctx->argv[k][i] = strncmp(a, "@/", 2) == 0 ? join_path(ctx->data, a + 2) : strdup(a);
        if (ctx->argv[k][i] == NULL)
            return ft_error(FT_E_NOMEM, "demo: out of memory");
    }
    return FT_OK;
}

/* Runs argv (argv[0] "fracterra") as this binary in dir, stdout discarded, stderr kept. FT_OK if it exits 0. */
static int run_in(const char *dir, char *const *argv)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return ft_error(FT_E_IO, "demo: cannot start a command: %s", strerror(errno));
    if (pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        if (chdir(dir) != 0 || fd < 0 || dup2(fd, STDOUT_FILENO) < 0)
            _exit(127);
        execv("/proc/self/exe", argv);
        _exit(127);
    }
    int st = 0;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR)
            return ft_error(FT_E_IO, "demo: lost a command: %s", strerror(errno));
    if (WIFEXITED(st) && WEXITSTATUS(st) == 0)
        return FT_OK;
    if (WIFSIGNALED(st))
        return ft_error(FT_E_IO, "`%s %s` died from signal %d", argv[0], argv[1], WTERMSIG(st));
    return ft_error(FT_E_IO, "`%s %s` exited with status %d", argv[0], argv[1], WEXITSTATUS(st));
}

static int run_item(demo_ctx *ctx, size_t k)
{
    int rc = resolve_argv(ctx, k);
    for (size_t i = 0; rc == FT_OK && items[k].outputs[i].file; i++)
        rc = add_output(ctx, items[k].outputs[i].file);
    return rc == FT_OK ? run_in(ctx->outdir, ctx->argv[k]) : rc;
}

/* ---- index.html and gallery.json ---- */

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

/* A word as a POSIX shell reads it back: bare if it is plain, else in double quotes. */
static void html_shell_word(FILE *f, const char *w)
{
    int plain = *w != '\0';
    for (const char *c = w; *c; c++)
        plain &= strchr("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./,:=@+-", *c) != NULL;
    if (plain) {
        html_text(f, w);
        return;
    }
    fputs("&quot;", f);
    for (const char *c = w; *c; c++) {
        char one[2] = {*c, '\0'};
        if (strchr("\"\\$`", *c))
            fputc('\\', f);
        html_text(f, one);
    }
    fputs("&quot;", f);
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

static void html_item(FILE *f, const demo_ctx *ctx, size_t k)
{
    const demo_item *it = &items[k];
    fputs("<figure>\n", f);
    for (size_t i = 0; it->outputs[i].file; i++) {
        if (!it->outputs[i].image)
            continue;
        fputs("<img src=\"", f);
        html_text(f, it->outputs[i].file);
        fputs("\" alt=\"", f);
        html_text(f, it->title);
        fputs("\">\n", f);
    }
    fputs("<figcaption><b>", f);
    html_text(f, it->title);
    fprintf(f, "</b>. %s Made by:<br>\n<code class=\"cmd\">", it->caption);
    for (size_t i = 0; ctx->argv[k][i]; i++) {
        if (i)
            fputc(' ', f);
        html_shell_word(f, ctx->argv[k][i]);
    }
    fputs("</code><br>\nwhich wrote", f);
    for (size_t i = 0; it->outputs[i].file; i++) {
        fputs(i ? ", <a href=\"" : " <a href=\"", f);
        html_text(f, it->outputs[i].file);
        fputs("\">", f);
        html_text(f, it->outputs[i].file);
        fputs("</a>", f);
    }
    fputs(".</figcaption>\n</figure>\n", f);
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

static int write_page(FILE *f, const void *arg)
{
    const demo_ctx *ctx = arg;
    fputs("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>fracterra demo</title>\n"
          "<style>\nbody{font-family:sans-serif;max-width:58em;margin:2em auto;padding:0 1em;color:#222}\n"
          "figure{margin:1.5em 0}img{max-width:100%;border:1px solid #ccc}figcaption{margin-top:.4em}\n"
          "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:.3em .6em;text-align:left}\n"
          "</style>\n</head>\n<body>\n<h1>fracterra demo</h1>\n",
          f);
    fprintf(f, "<p>Made by <code>fracterra demo</code> (fracterra %s) from the data bundled with fracterra, "
               "a library and command-line tool for the fractal geometry of maps. Each file below was written "
               "by the command shown under it, run in this folder; <code>gallery.json</code> lists them.</p>\n"
               "<h2>What the demo made</h2>\n",
            ft_version());
    for (size_t k = 0; k < NITEMS; k++)
        html_item(f, ctx, k);
    html_inputs(f, ctx);
    fputs("</body>\n</html>\n", f);
    return FT_OK;
}

static json_object *gallery_json(const demo_ctx *ctx)
{
    json_object *o = json_object_new_object(), *arr = json_object_new_array();
    for (size_t k = 0; k < NITEMS; k++) {
        json_object *it = json_object_new_object(), *argv = json_object_new_array(),
                    *outs = json_object_new_array();
        for (size_t i = 0; ctx->argv[k][i]; i++)
            json_object_array_add(argv, json_object_new_string(ctx->argv[k][i]));
        for (size_t i = 0; items[k].outputs[i].file; i++)
            json_object_array_add(outs, json_object_new_string(items[k].outputs[i].file));
        json_object_object_add(it, "title", json_object_new_string(items[k].title));
        json_object_object_add(it, "argv", argv);
        json_object_object_add(it, "outputs", outs);
        json_object_array_add(arr, it);
    }
    json_object_object_add(o, "data_dir", json_object_new_string(ctx->data));
    json_object_object_add(o, "items", arr);
    return o;
}

static int write_manifest(FILE *f, const void *arg)
{
    json_object *o = gallery_json(arg);
    fputs(json_object_to_json_string_ext(o, JSON_C_TO_STRING_PRETTY | JSON_C_TO_STRING_NOSLASHESCAPE), f);
    fputc('\n', f);
    json_object_put(o);
    return FT_OK;
}

/* ---- the command ---- */

static int on_option(const cli_command *cmd, int opt, const char *arg, void *ctx)
{
    (void)arg;
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
            unlink(ctx->path[i]);
        free(ctx->path[i]);
    }
    if (failed && created)
        rmdir(ctx->outdir);
    for (size_t k = 0; k < NITEMS; k++)
        for (size_t i = 0; ctx->argv[k][i]; i++)
            free(ctx->argv[k][i]);
    json_object_put(ctx->inputs);
}

static int report(demo_ctx *ctx, int json)
{
    if (!json) {
        printf("fracterra demo: data from %s\n", ctx->data);
        for (size_t i = 0; i < ctx->nout; i++)
            printf("  wrote %s\n", ctx->path[i]);
        printf("open %s in a browser\n", ctx->path[ctx->nout - 1]);
        return CLI_OK;
    }
    json_object *o = json_object_new_object(), *outs = json_object_new_array();
    for (size_t i = 0; i < ctx->nout; i++)
        json_object_array_add(outs, json_object_new_string(ctx->path[i]));
    json_object_object_add(o, "outdir", json_object_new_string(ctx->outdir));
    json_object_object_add(o, "data_dir", json_object_new_string(ctx->data));
    json_object_object_add(o, "outputs", outs);
    json_object_object_add(o, "inputs", json_object_get(ctx->inputs));
    json_object *g = gallery_json(ctx), *gi = NULL;
    json_object_object_get_ex(g, "items", &gi);
    json_object_object_add(o, "items", json_object_get(gi));
    json_object_put(g);
    return cli_print_json(ctx->cmd, o);
}

/* Runs every item, then writes gallery.json and index.html (last, so that it shows everything). */
static int make_gallery(demo_ctx *ctx)
{
    int rc = describe_inputs(ctx);
    for (size_t k = 0; rc == FT_OK && k < NITEMS; k++)
        rc = run_item(ctx, k);
    if (rc == FT_OK && (rc = add_output(ctx, "gallery.json")) == FT_OK)
        rc = cli_write_file(ctx->path[ctx->nout - 1], write_manifest, ctx);
    if (rc == FT_OK && (rc = add_output(ctx, "index.html")) == FT_OK)
        rc = cli_write_file(ctx->path[ctx->nout - 1], write_page, ctx);
    return rc;
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

    static demo_ctx ctx; /* the demo runs once per process; its argv table is large */
    memset(&ctx, 0, sizeof ctx);
    ctx.cmd = cmd;
    ctx.outdir = argv[first];
    if ((ctx.data = find_data(cmd)) == NULL || make_outdir(cmd, ctx.outdir, &created) != CLI_CONTINUE)
        return CLI_FAIL;
    ctx.inputs = json_object_new_array();
    if (make_gallery(&ctx) != FT_OK) {
        cli_error(cmd, "%s", ft_last_error());
        cleanup(&ctx, 1, created);
        return CLI_FAIL;
    }
    rc = report(&ctx, json);
    cleanup(&ctx, 0, created);
    return rc;
}

const cli_command cli_cmd_demo = {
    "demo",
    "make a small gallery by running fracterra's commands on the bundled data (index.html)",
    "fracterra demo OUTDIR [--json]",
    "Runs fracterra's own commands on the bundled data, in OUTDIR (created if missing; its parent must\n"
    "exist), each as a separate process of this binary:\n"
    "  synth, hillshade, render        a synthetic fBm terrain (D = 2.3, 512 x 512, seeded), its shaded\n"
    "                                  relief and perspective view\n"
    "  hillshade, render, model fit    the same for the Maunga Whau DEM, and Clarke's model fitted to it\n"
    "  simplify, enhance, dim line     Dutton's Newfoundland sequence: the GSHHG shoreline generalized to\n"
    "                                  158 points and enhanced; divider log-log plots of both; the paper's\n"
    "                                  sequence stage by stage (enhance --keep-vertices, weed, smooth),\n"
    "                                  each stage's divider over common rulers, 48 start vertices\n"
    "  simplify, boundary, dim line    Rhode Island's boundary with detail of D = 1.2325 added by the\n"
    "                                  midpoint-subdivision generator; its box-counting plot\n"
    "  mountain                        contours grown from one seed contour: map, DEM, perspective view\n"
    "then writes gallery.json ({\"data_dir\", \"items\": [{\"title\", \"argv\", \"outputs\"}]}: every command line\n"
    "run and the files it wrote) and index.html, which shows each file with the command that made it. Run\n"
    "in OUTDIR, any recorded argv writes the same file again.\n"
    "The data folder is $FRACTERRA_DATA, else the source tree's tests/data, else the installed\n"
    "share/fracterra. If a command fails, nothing is left behind.\n\n"
    "Options:\n"
    "  -j, --json   print {\"outdir\", \"data_dir\", \"outputs\": [paths], \"inputs\": [info...], \"items\"}\n"
    "  -h, --help   print this help\n\n"
    "Example:\n"
    "  fracterra demo out/ && xdg-open out/index.html\n",
    run_demo,
};
