/* fracterra — tests/cli/test_cli_demo.c: `fracterra demo OUTDIR` makes its files; GDAL reads
 * volcano.tif back with the input's cells, geotransform and CRS; the PNG, SVGs (maps and log-log plots) and
 * HTML are well formed and the page references every image.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <gdal.h>
#include <ogr_srs_api.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ft_test_util.h"

static const char *const outputs[] = {"volcano.tif",
                                      "volcano_hillshade.png",
                                      "newfoundland.svg",
                                      "newfoundland_enhanced.svg",
                                      "newfoundland_loglog_before.svg",
                                      "newfoundland_loglog_after.svg",
                                      "terrain_synth.tif",
                                      "terrain_synth_hillshade.png",
                                      "terrain_synth_perspective.png",
                                      "volcano_gdal_hillshade.png",
                                      "volcano_perspective.png",
                                      "volcano_clarke_model.json",
                                      "urban_boundary.png",
                                      "urban_boundary_zoom.png",
                                      "mountain_contours.svg",
                                      "mountain_perspective.png",
                                      "index.html"};
#define NOUTPUTS (sizeof outputs / sizeof outputs[0])

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
    GDALAllRegister();
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
    GDALDestroyDriverManager();
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
    assert_true(json_object_array_length(ins) >= 2); /* later steps add their own inputs */
    json_object *volcano = json_object_array_get_idx(ins, 0), *nf = json_object_array_get_idx(ins, 1);
    assert_int_equal(ft_test_json_int(volcano, "cells"), 5307);
    assert_int_equal(ft_test_json_int(nf, "vertices"), 64193);
}

static float *read_cells(GDALDatasetH ds)
{
    int nx = GDALGetRasterXSize(ds), ny = GDALGetRasterYSize(ds);
    float *z = malloc(sizeof(float) * (size_t)nx * (size_t)ny);
    assert_non_null(z);
    assert_int_equal(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Read, 0, 0, nx, ny, z, nx, ny, GDT_Float32, 0, 0),
                     CE_None);
    return z;
}

static void test_volcano_tif_round_trip(void **state)
{
    char *p = out_path(state, "volcano.tif");
    GDALDatasetH in = GDALOpen(FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", GA_ReadOnly);
    GDALDatasetH out = GDALOpen(p, GA_ReadOnly);
    assert_non_null(in);
    assert_non_null(out);
    assert_string_equal(GDALGetDriverShortName(GDALGetDatasetDriver(out)), "GTiff");
    assert_int_equal(GDALGetRasterXSize(out), 61);
    assert_int_equal(GDALGetRasterYSize(out), 87);

    double gi[6], go[6];
    assert_int_equal(GDALGetGeoTransform(in, gi), CE_None);
    assert_int_equal(GDALGetGeoTransform(out, go), CE_None);
    for (int k = 0; k < 6; k++)
        assert_true(gi[k] == go[k]);

    OGRSpatialReferenceH si = OSRNewSpatialReference(GDALGetProjectionRef(in));
    OGRSpatialReferenceH so = OSRNewSpatialReference(GDALGetProjectionRef(out));
    assert_non_null(si);
    assert_non_null(so);
    assert_true(OSRIsSame(si, so));
    assert_string_equal(OSRGetAuthorityCode(so, NULL), "27200");
    OSRDestroySpatialReference(si);
    OSRDestroySpatialReference(so);

    float *zi = read_cells(in), *zo = read_cells(out);
    assert_memory_equal(zi, zo, sizeof(float) * 61 * 87);
    free(zi);
    free(zo);
    GDALClose(in);
    GDALClose(out);
    free(p);
}

static uint32_t be32(const unsigned char *b)
{
    return (uint32_t)b[0] << 24 | (uint32_t)b[1] << 16 | (uint32_t)b[2] << 8 | b[3];
}

static void test_png(void **state)
{
    char *p = out_path(state, "volcano_hillshade.png");
    size_t size = 0;
    unsigned char *b = (unsigned char *)ft_test_read_file(p, &size);
    assert_non_null(b);
    assert_true(size > 10000);
    assert_memory_equal(b, "\x89PNG\r\n\x1a\n", 8);
    assert_memory_equal(b + 12, "IHDR", 4);
    uint32_t w = be32(b + 16), h = be32(b + 20);
    assert_int_equal(w, 600);
    assert_true(h >= 850 && h <= 860); /* 600 * 87 / 61 = 855.7: the cells stay square */
    free(b);
    free(p);
}

static void test_svg(void **state)
{
    char *p = out_path(state, "newfoundland.svg");
    size_t size = 0;
    char *s = ft_test_read_svg(p, &size);
    assert_true(size > 100000); /* 64,193 vertices drawn */
    assert_non_null(strstr(s, "<path"));
    free(s);
    free(p);
}

/* The lines step: one map with the three outlines and a legend, and the two log-log plots. */
static void test_newfoundland_enhancement(void **state)
{
    char *p = out_path(state, "newfoundland_enhanced.svg");
    size_t size = 0;
    char *s = ft_test_read_svg(p, &size);
    assert_true(size > 100000); /* the full-resolution ring is drawn under the outlines */
    int paths = 0;
    for (const char *q = s; (q = strstr(q, "<path")) != NULL; q++)
        paths++;
    assert_true(paths >= 4); /* three outlines and the legend samples */
    free(s);
    free(p);
    const char *plots[] = {"newfoundland_loglog_before.svg", "newfoundland_loglog_after.svg"};
    for (int i = 0; i < 2; i++) {
        p = out_path(state, plots[i]);
        s = ft_test_read_svg(p, NULL);
        free(s);
        free(p);
    }
}

static void test_index_html(void **state)
{
    char *p = out_path(state, "index.html");
    char *s = ft_test_read_file(p, NULL);
    assert_non_null(s);
    assert_non_null(strstr(s, "<!DOCTYPE html>"));
    assert_non_null(strstr(s, "<title>fracterra demo</title>"));
    assert_non_null(strstr(s, "<img src=\"volcano_hillshade.png\""));
    assert_non_null(strstr(s, "<img src=\"newfoundland.svg\""));
    assert_non_null(strstr(s, "<img src=\"newfoundland_enhanced.svg\""));
    assert_non_null(strstr(s, "<img src=\"newfoundland_loglog_before.svg\""));
    assert_non_null(strstr(s, "<img src=\"newfoundland_loglog_after.svg\""));
    assert_non_null(strstr(s, "Douglas-Peucker to 158 points"));
    assert_non_null(strstr(s, "href=\"volcano.tif\""));
    assert_non_null(strstr(s, "LGPL-3+"));
    assert_non_null(strstr(s, "GPL-2 | GPL-3"));
    assert_non_null(strstr(s, "64193 vertices"));
    assert_non_null(strstr(s, "61 &times; 87 = 5307 cells"));
    assert_non_null(strstr(s, "</html>"));
    free(s);
    free(p);
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
        cmocka_unit_test(test_outputs_exist),      cmocka_unit_test(test_inputs_reported),
        cmocka_unit_test(test_volcano_tif_round_trip), cmocka_unit_test(test_png),
        cmocka_unit_test(test_svg),                cmocka_unit_test(test_newfoundland_enhancement),
        cmocka_unit_test(test_index_html),
        cmocka_unit_test(test_rerun_human_output), cmocka_unit_test(test_outdir_is_a_file),
    };
    return cmocka_run_group_tests(tests, group_setup, group_teardown);
}
