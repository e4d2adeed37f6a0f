/* fracterra — unit tests of render/loglog_plot.c: the log-log plot is written as SVG, PNG and PDF with
 * the right signatures, atomically (no temporary left behind), and a failed write leaves nothing.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fracterra/core.h"
#include "fracterra/render.h"

typedef struct {
    char dir[64];
    ft_dim_result *r;
} fixture;

/* Two straight runs (slopes -1.2 then -1.8, break at 32) fitted by the default segmentation. */
static int setup(void **state)
{
    fixture *f = calloc(1, sizeof *f);
    if (f == NULL)
        return -1;
    snprintf(f->dir, sizeof f->dir, "/tmp/ft-loglog-plot-XXXXXX");
    if (mkdtemp(f->dir) == NULL)
        return -1;
    ft_loglog *t = ft_loglog_create(0);
    for (int i = 0; i <= 12; i++) {
        double x = i * log10(2.0), xb = 5 * log10(2.0);
        double y = x <= xb ? 3.0 - 1.2 * x : 3.0 - 1.2 * xb - 1.8 * (x - xb);
        if (ft_loglog_push(t, pow(10.0, x), pow(10.0, y), 10.0 * i) != FT_OK)
            return -1;
    }
    const ft_dim_map box = FT_DIM_MAP_BOXCOUNT;
    int rc = ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &box, &f->r);
    ft_loglog_free(t);
    if (rc != FT_OK)
        return -1;
    *state = f;
    return 0;
}

static int teardown(void **state)
{
    fixture *f = *state;
    DIR *d = opendir(f->dir);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        char p[512];
        snprintf(p, sizeof p, "%s/%s", f->dir, e->d_name);
        unlink(p);
    }
    if (d)
        closedir(d);
    rmdir(f->dir);
    ft_dim_result_free(f->r);
    free(f);
    return 0;
}

/* 1 if the file starts with sig (len bytes). */
static int starts_with(const char *path, const char *sig, size_t len)
{
    char buf[64] = {0};
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return 0;
    size_t got = fread(buf, 1, len, fp);
    fclose(fp);
    return got == len && memcmp(buf, sig, len) == 0;
}

/* Number of entries in the folder other than . and .. */
static int entries(const char *dir)
{
    int n = 0;
    DIR *d = opendir(dir);
    struct dirent *e;
    while (d && (e = readdir(d)) != NULL)
        n += strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0;
    if (d)
        closedir(d);
    return n;
}

static void test_svg_png_pdf(void **state)
{
    fixture *f = *state;
    char svg[128], png[128], pdf[128];
    snprintf(svg, sizeof svg, "%s/plot.svg", f->dir);
    snprintf(png, sizeof png, "%s/plot.PNG", f->dir);
    snprintf(pdf, sizeof pdf, "%s/plot.pdf", f->dir);
    ft_plot_opts o = FT_PLOT_OPTS_DEFAULT;
    o.title = "Two straight runs";
    o.xlabel = "box side";
    o.ylabel = "boxes N";
    assert_int_equal(ft_render_loglog_plot(f->r, svg, &o), FT_OK);
    assert_int_equal(ft_render_loglog_plot(f->r, png, NULL), FT_OK);
    assert_int_equal(ft_render_loglog_plot(f->r, pdf, &o), FT_OK);
    assert_true(starts_with(svg, "<?xml", 5));
    assert_true(starts_with(png, "\x89PNG\r\n\x1a\n", 8));
    assert_true(starts_with(pdf, "%PDF-", 5));
    assert_int_equal(entries(f->dir), 3); /* no temporary left */
    struct stat st;
    assert_int_equal(stat(png, &st), 0);
    assert_true(st.st_size > 1000);
}

static void test_failed_write_leaves_nothing(void **state)
{
    fixture *f = *state;
    char path[160];
    snprintf(path, sizeof path, "%s/missing/plot.svg", f->dir);
    assert_int_equal(ft_render_loglog_plot(f->r, path, NULL), FT_E_IO);
    assert_non_null(strstr(ft_last_error(), "missing"));
    snprintf(path, sizeof path, "%s/missing/plot.png", f->dir);
    assert_int_not_equal(ft_render_loglog_plot(f->r, path, NULL), FT_OK);
    assert_int_equal(access(path, F_OK), -1);
    assert_int_equal(entries(f->dir), 0);
}

static void test_bad_arguments(void **state)
{
    fixture *f = *state;
    char path[160];
    snprintf(path, sizeof path, "%s/plot.gif", f->dir);
    assert_int_equal(ft_render_loglog_plot(f->r, path, NULL), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "plot.gif"));
    snprintf(path, sizeof path, "%s/plot.svg", f->dir);
    ft_plot_opts o = FT_PLOT_OPTS_DEFAULT;
    o.width = 10;
    assert_int_equal(ft_render_loglog_plot(f->r, path, &o), FT_E_INVALID);
    assert_non_null(strstr(ft_last_error(), "10 x 540"));
    assert_int_equal(ft_render_loglog_plot(NULL, path, NULL), FT_E_INVALID);
    assert_int_equal(ft_render_loglog_plot(f->r, NULL, NULL), FT_E_INVALID);
    assert_int_equal(entries(f->dir), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_svg_png_pdf, setup, teardown),
        cmocka_unit_test_setup_teardown(test_failed_write_leaves_nothing, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_arguments, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
