/* fracterra — tests/cli/test_cli_demo.c: `fracterra demo OUTDIR` makes its files by running fracterra's
 * commands; gallery.json records each argv and the files it wrote, and index.html shows that argv as the
 * caption. The gallery is checked by re-running every recorded argv in a fresh folder and comparing the
 * files byte for byte, so a caption that is not the command that made the file fails. Also: the images,
 * SVGs and HTML are well formed and the inputs are described.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ft_test_util.h"

static const char *const outputs[] = {"terrain_synth.tif",
                                      "terrain_synth_hillshade.png",
                                      "terrain_synth_perspective.png",
                                      "volcano_hillshade.png",
                                      "volcano_perspective.png",
                                      "volcano_clarke_model.json",
                                      "newfoundland_158.geojson",
                                      "newfoundland_enhanced.geojson",
                                      "newfoundland_loglog_before.svg",
                                      "newfoundland_loglog_after.svg",
                                      "newfoundland_b.geojson",
                                      "newfoundland_c.geojson",
                                      "newfoundland_d.geojson",
                                      "newfoundland_a_divider.svg",
                                      "newfoundland_b_divider.svg",
                                      "newfoundland_c_divider.svg",
                                      "newfoundland_d_divider.svg",
                                      "urban_ri.geojson",
                                      "urban_ri_simulated.geojson",
                                      "urban_ri_simulated_loglog.svg",
                                      "mountain_contours.svg",
                                      "mountain_perspective.png",
                                      "mountain_contours.geojson",
                                      "mountain.tif",
                                      "gallery.json",
                                      "index.html"};
#define NOUTPUTS (sizeof outputs / sizeof outputs[0])
#define NCOMMANDS 21 /* every output but gallery.json and index.html comes from one of 21 commands */
typedef struct {
    char *dir; /* temporary parent */
    char *out; /* dir/out: the demo's OUTDIR, made by the demo */
    json_object *json;
} fixture;

/* Runs the demo once for the whole group (it is the expensive part). */
static int group_setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (f == NULL || (f->dir = ft_test_mkdtemp()) == NULL || (f->out = ft_test_path(f->dir, "out")) == NULL)
        return -1;
    ft_run_result r;
    if (ft_run(&r, "demo", "--json", f->out, NULL) != 0)
        return -1;
    if (r.status != 0)
        fprintf(stderr, "demo failed (%d): %s\n", r.status, r.err);
    f->json = r.status == 0 ? ft_run_json(&r) : NULL;
    ft_run_free(&r);
    *state = f;
    return f->json ? 0 : -1;
}

static int group_teardown(void **state)
{
    fixture *f = *state;
    json_object_put(f->json);
    ft_test_rmtree(f->dir);
    free(f->out);
    free(f->dir);
    free(f);
    return 0;
}

static char *out_path(void **state, const char *name)
{
    fixture *f = *state;
    char *p = ft_test_path(f->out, name);
    assert_non_null(p);
    return p;
}

static void test_outputs_exist(void **state)
{
    fixture *f = *state;
    json_object *outs = ft_test_json_key(f->json, "outputs");
    assert_int_equal(json_object_array_length(outs), NOUTPUTS);
    for (size_t i = 0; i < NOUTPUTS; i++) {
        char *p = out_path(state, outputs[i]);
        assert_true(ft_test_exists(p));
        int listed = 0;
        for (size_t k = 0; k < NOUTPUTS; k++)
            listed |= strcmp(json_object_get_string(json_object_array_get_idx(outs, k)), p) == 0;
        assert_true(listed);
        free(p);
    }
    /* nothing else (no temporary file left over) */
    assert_int_equal(ft_test_count_entries(f->out), (int)NOUTPUTS);
}

static void test_inputs_reported(void **state)
{
    fixture *f = *state;
    json_object *ins = ft_test_json_key(f->json, "inputs");
    assert_int_equal(json_object_array_length(ins), 4);
    json_object *volcano = json_object_array_get_idx(ins, 0), *nf = json_object_array_get_idx(ins, 1);
    assert_int_equal(ft_test_json_int(volcano, "cells"), 5307);
    assert_int_equal(ft_test_json_int(nf, "vertices"), 64193);
}

static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

/* GDAL's hillshade keeps the DEM's 61 x 87 cells; the perspective view is the --width asked for. */
static void test_png(void **state)
{
    static const struct {
        const char *file;
        uint32_t width, height; /* height 0: not checked */
    } pngs[] = {{"volcano_hillshade.png", 61, 87}, {"terrain_synth_hillshade.png", 512, 512},
                {"volcano_perspective.png", 900, 0}};
    for (size_t i = 0; i < sizeof pngs / sizeof pngs[0]; i++) {
        char *p = out_path(state, pngs[i].file);
        size_t size = 0;
        unsigned char *b = (unsigned char *)ft_test_read_file(p, &size);
        assert_non_null(b);
        assert_true(size > 1000);
        assert_memory_equal(b, "\x89PNG\r\n\x1a\n", 8);
        assert_memory_equal(b + 12, "IHDR", 4);
        assert_int_equal(be32(b + 16), pngs[i].width);
        if (pngs[i].height)
            assert_int_equal(be32(b + 20), pngs[i].height);
        free(b);
        free(p);
    }
}

static void test_svgs(void **state)
{
    const char *svgs[] = {"newfoundland_loglog_before.svg", "newfoundland_loglog_after.svg",
                          "newfoundland_a_divider.svg", "newfoundland_d_divider.svg",
                          "urban_ri_simulated_loglog.svg", "mountain_contours.svg"};
    for (size_t i = 0; i < sizeof svgs / sizeof svgs[0]; i++) {
        char *p = out_path(state, svgs[i]);
        char *s = ft_test_read_svg(p, NULL);
        assert_non_null(strstr(s, "<path"));
        free(s);
        free(p);
    }
}

static json_object *read_gallery(void **state)
{
    char *p = out_path(state, "gallery.json");
    json_object *g = json_object_from_file(p);
    free(p);
    assert_non_null(g);
    return g;
}

/* The words of argv as index.html shows them: a word with a space or quote in double quotes (HTML-escaped). */
static char *caption_of(json_object *argv)
{
    size_t cap = 4096, n = 0;
    char *s = calloc(cap, 1);
    assert_non_null(s);
    for (size_t i = 0; i < json_object_array_length(argv); i++) {
        const char *w = json_object_get_string(json_object_array_get_idx(argv, i));
        int quote = strpbrk(w, " '\"") != NULL;
        n += (size_t)snprintf(s + n, cap - n, "%s%s%s%s", i ? " " : "", quote ? "&quot;" : "", w,
                              quote ? "&quot;" : "");
        assert_true(n < cap);
    }
    return s;
}

/* Every command of gallery.json is the caption index.html shows, and together they cover the outputs. */
static void test_index_captions_are_the_commands(void **state)
{
    json_object *g = read_gallery(state), *items = ft_test_json_key(g, "items");
    char *p = out_path(state, "index.html");
    char *html = ft_test_read_file(p, NULL);
    assert_non_null(html);
    assert_int_equal(json_object_array_length(items), NCOMMANDS);
    size_t covered = 0;
    for (size_t k = 0; k < NCOMMANDS; k++) {
        json_object *it = json_object_array_get_idx(items, k);
        json_object *argv = ft_test_json_key(it, "argv");
        assert_string_equal(json_object_get_string(json_object_array_get_idx(argv, 0)), "fracterra");
        char *cap = caption_of(argv);
        if (strstr(html, cap) == NULL)
            fail_msg("index.html does not show the command %s", cap);
        free(cap);
        covered += json_object_array_length(ft_test_json_key(it, "outputs"));
    }
    assert_int_equal(covered, NOUTPUTS - 2);
    /* one caption written out by hand: the quoting of a word with spaces */
    char expect[1024];
    assert_true(snprintf(expect, sizeof expect,
                         "<code class=\"cmd\">fracterra simplify %s/dcw_us_states_small_albers5070.geojson "
                         "urban_ri.geojson --where &quot;code = 'US.RI'&quot; --tolerance 600</code>",
                         json_object_get_string(ft_test_json_key(g, "data_dir"))) < (int)sizeof expect);
    assert_non_null(strstr(html, expect));
    assert_non_null(strstr(html, "<img src=\"mountain_contours.svg\""));
    assert_non_null(strstr(html, "href=\"terrain_synth.tif\""));
    assert_non_null(strstr(html, "LGPL-3+"));
    assert_non_null(strstr(html, "GPL-2 | GPL-3"));
    assert_non_null(strstr(html, "64193 vertices"));
    assert_non_null(strstr(html, "61 &times; 87 = 5307 cells"));
    assert_non_null(strstr(html, "</html>"));
    free(html);
    free(p);
    json_object_put(g);
}

/* Runs argv (after "fracterra") in dir; 1 if every one of files there equals the demo's, byte for byte. */
static int rerun_matches(void **state, const char *dir, json_object *argv, json_object *files)
{
    size_t n = json_object_array_length(argv);
    const char **a = calloc(n, sizeof *a);
    assert_non_null(a);
    for (size_t i = 1; i < n; i++)
        a[i - 1] = json_object_get_string(json_object_array_get_idx(argv, i));
    char cwd[4096];
    assert_non_null(getcwd(cwd, sizeof cwd));
    assert_int_equal(chdir(dir), 0);
    ft_run_result r;
    int ran = ft_run_argv(&r, a);
    assert_int_equal(chdir(cwd), 0);
    assert_int_equal(ran, 0);
    if (r.status != 0)
        fail_msg("%s %s exited %d: %s", a[0], a[1], r.status, r.err);
    free(a);
    ft_run_free(&r);
    int same = 1;
    for (size_t i = 0; i < json_object_array_length(files); i++) {
        const char *file = json_object_get_string(json_object_array_get_idx(files, i));
        char *mine = ft_test_path(dir, file), *demo = out_path(state, file);
        size_t n1 = 0, n2 = 0;
        char *b1 = ft_test_read_file(mine, &n1), *b2 = ft_test_read_file(demo, &n2);
        assert_non_null(b1);
        assert_non_null(b2);
        if (n1 != n2 || memcmp(b1, b2, n1) != 0) {
            fprintf(stderr, "%s: not the demo's file\n", file);
            same = 0;
        }
        free(b1);
        free(b2);
        free(mine);
        free(demo);
    }
    return same;
}

/* Each recorded argv, run in order in a fresh folder, writes the demo's files again, byte for byte. */
static void test_commands_reproduce_the_gallery(void **state)
{
    json_object *g = read_gallery(state), *items = ft_test_json_key(g, "items");
    char *dir = ft_test_mkdtemp();
    assert_non_null(dir);
    for (size_t k = 0; k < json_object_array_length(items); k++) {
        json_object *it = json_object_array_get_idx(items, k);
        assert_true(rerun_matches(state, dir, ft_test_json_key(it, "argv"), ft_test_json_key(it, "outputs")));
    }
    /* the check can fail: the hillshade with another z-factor is not the demo's file */
    json_object *argv = json_object_new_array();
    const char *words[] = {"fracterra", "hillshade", "terrain_synth.tif", "terrain_synth_hillshade.png",
                           "--z-factor", "3", "--color"};
    for (size_t i = 0; i < sizeof words / sizeof words[0]; i++)
        json_object_array_add(argv, json_object_new_string(words[i]));
    json_object *outs = json_object_new_array();
    json_object_array_add(outs, json_object_new_string("terrain_synth_hillshade.png"));
    assert_false(rerun_matches(state, dir, argv, outs));
    json_object_put(argv);
    json_object_put(outs);
    ft_test_rmtree(dir);
    free(dir);
    json_object_put(g);
}

/* A second run into the existing folder replaces the files; the human report names index.html. */
static void test_rerun_human_output(void **state)
{
    fixture *f = *state;
    ft_run_result r;
    assert_int_equal(ft_run(&r, "demo", f->out, NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "index.html"));
    assert_null(ft_run_json(&r));
    assert_int_equal(ft_test_count_entries(f->out), (int)NOUTPUTS);
    ft_run_free(&r);
}

/* OUTDIR naming an existing file is refused. */
static void test_outdir_is_a_file(void **state)
{
    fixture *f = *state;
    char *p = out_path(state, "index.html");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "demo", p, NULL), 0);
    assert_int_equal(r.status, 1);
    assert_non_null(strstr(r.err, "fracterra: demo: "));
    assert_non_null(strstr(r.err, "not a folder"));
    assert_int_equal(ft_test_count_entries(f->out), (int)NOUTPUTS);
    ft_run_free(&r);
    free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outputs_exist),
        cmocka_unit_test(test_inputs_reported),
        cmocka_unit_test(test_png),
        cmocka_unit_test(test_svgs),
        cmocka_unit_test(test_index_captions_are_the_commands),
        cmocka_unit_test(test_commands_reproduce_the_gallery),
        cmocka_unit_test(test_rerun_human_output),
        cmocka_unit_test(test_outdir_is_a_file),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
