/* fracterra — tests/cli/test_cli_bad_input_table.c: one table of bad inputs over every command and every
 * class of failure (write safety, runaway work, the crash and the UB, exit 0 with nonsense, unclear
 * errors), run through the built binary. Every row must: not die from a signal, exit with its code, print
 * "fracterra: " and a message holding its needle (and never a bare "inf" or "nan"), leave no output and no
 * temporary file behind, and leave its input untouched. A second table runs every writing command with the
 * file size limited (RLIMIT_FSIZE, SIGXFSZ ignored: write() fails with EFBIG as on a full disk) over an
 * existing output, which must survive byte for byte.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <ctype.h>
#include <json-c/json.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "fracterra/fracterra.h"
#include "ft_test_run.h"

#define MAX_ARGS 20

typedef struct {
    const char *cls;           /* the class */
    int code;                  /* expected exit code */
    const char *needle;        /* expected in stderr */
    const char *args[MAX_ARGS]; /* "@/x": x in the test folder; "@data/x": tests/data/x */
} bad_case;

static char *dir;              /* the test folder, with the fixtures */

static char *expand(const char *a)
{
    char buf[4096];
    if (strncmp(a, "@data/", 6) == 0)
        snprintf(buf, sizeof buf, "%s/%s", FT_TEST_DATA, a + 6);
    else if (strncmp(a, "@/", 2) == 0)
        snprintf(buf, sizeof buf, "%s/%s", dir, a + 2);
    else
        snprintf(buf, sizeof buf, "%s", a);
    return strdup(buf);
}

/* The folder's entries, as one string "a|b|c|" (sorted by readdir order; compared as sets below). */
static int has_tmp_leftover(void)
{
    char cmd[4200];
    snprintf(cmd, sizeof cmd, "ls -A '%s' | grep -q 'ft-tmp'", dir);
    return system(cmd) == 0;
}

/* "inf" or "nan" as a word of the message: a number leaked without meaning. */
static int has_bare_nonfinite(const char *s)
{
    for (const char *p = s; *p; p++) {
        int start = p == s || !isalnum((unsigned char)p[-1]);
        if (start && (strncmp(p, "inf", 3) == 0 || strncmp(p, "nan", 3) == 0 || strncmp(p, "-inf", 4) == 0) &&
            !isalnum((unsigned char)p[p[0] == '-' ? 4 : 3]))
            return 1;
    }
    return 0;
}

/* Outputs the table's rows name; none of them may exist after a failed run. */
static const char *const outputs[] = {"out.geojson", "out.gmt", "out.tif", "out.png", "out.json", "out.csv",
                                      "out2.tif", "mout", "mdem", NULL};

static void run_case(const bad_case *c)
{
    const char *argv[MAX_ARGS + 1];
    char *owned[MAX_ARGS];
    int n = 0;
    for (; n < MAX_ARGS && c->args[n] != NULL; n++)
        argv[n] = owned[n] = expand(c->args[n]);
    argv[n] = NULL;
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    int ok = !r.signaled && r.status == c->code && strncmp(r.err, "fracterra: ", 11) == 0 &&
             strstr(r.err, c->needle) != NULL && !has_bare_nonfinite(r.err);
    if (!ok)
        fprintf(stderr, "[%s] %s ...: exit %d%s, stderr: %s(expected exit %d and '%s')\n", c->cls, c->args[0],
                r.status, r.signaled ? " (signal)" : "", r.err, c->code, c->needle);
    assert_true(ok);
    for (int i = 0; outputs[i] != NULL; i++) {
        char *p = ft_test_path(dir, outputs[i]);
        if (ft_test_exists(p))
            fprintf(stderr, "[%s] %s left %s\n", c->cls, c->args[0], outputs[i]);
        assert_false(ft_test_exists(p));
        free(p);
    }
    assert_false(has_tmp_leftover());
    ft_run_free(&r);
    for (int i = 0; i < n; i++)
        free(owned[i]);
}

/* ---- fixtures ---- */

static void write_grid(const char *name, size_t nx, size_t ny, int all_nodata)
{
    ft_grid *g = ft_grid_create(nx, ny);
    assert_non_null(g);
    const double gt[6] = {500000.0, 10.0, 0.0, 4000000.0, 0.0, -10.0};
    memcpy(g->gt, gt, sizeof gt);
    for (size_t i = 0; i < nx * ny; i++)
        g->z[i] = (float)(i % 7);
    if (all_nodata) {
        g->mask = calloc(nx * ny, 1);
        assert_non_null(g->mask);
        g->has_nodata = 1;
        g->nodata_value = -9999.0;
    }
    char *p = ft_test_path(dir, name);
    assert_int_equal(ft_io_write_grid(p, g, NULL), FT_OK);
    free(p);
    ft_grid_free(g);
}

static void put(const char *name, const char *text)
{
    char *p = ft_test_path(dir, name);
    assert_int_equal(ft_test_write_text(p, text), 0);
    free(p);
}

/* The model `model fit` writes for the volcano, then variants with one key changed. */
static void write_models(void)
{
    char *model = ft_test_path(dir, "model.json");
    ft_run_result r;
    assert_int_equal(ft_run(&r, "model", "fit", FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", "-o", model, NULL),
                     0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    size_t len = 0;
    char *text = ft_test_read_file(model, &len);
    assert_non_null(text);
    char *trunc = strndup(text, len / 2);
    put("model_trunc.json", trunc);
    free(trunc);
    put("model_empty.json", "");
    json_object *o = json_tokener_parse(text);
    assert_non_null(o);
    json_object *grid = json_object_object_get(o, "grid"), *size = json_object_new_array();
    json_object_array_add(size, json_object_new_int(-5));
    json_object_array_add(size, json_object_new_int(3));
    json_object_object_add(grid, "size", size);
    put("model_neg.json", json_object_to_json_string(o));
    json_object_put(o);
    o = json_tokener_parse(text);
    json_object *h = json_object_array_get_idx(json_object_object_get(json_object_object_get(o, "harmonics"), "list"), 0);
    json_object_object_add(h, "k", json_object_new_int64((int64_t)1 << 62));
    put("model_k.json", json_object_to_json_string(o));
    json_object_put(o);
    free(text);
    free(model);
}

static int setup(void **state)
{
    ft_io_init();
    dir = ft_test_mkdtemp();
    if (dir == NULL)
        return -1;
    write_grid("onexn.tif", 1, 20, 0);
    write_grid("nodata.tif", 8, 8, 1);
    size_t len = 0;
    char *dem = ft_test_read_file(FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", &len);
    char *p = ft_test_path(dir, "trunc.tif");
    ft_test_write_file(p, dem, len / 2);
    free(p);
    p = ft_test_path(dir, "dem.tif"); /* a writable copy, to be refused as an output */
    ft_test_write_file(p, dem, len);
    free(p);
    free(dem);
    put("lines.geojson", "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":"
                         "{\"c\":\"a\"},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[[0,0],[100,50],"
                         "[200,0],[300,80]]}}]}");
    put("line.gmt", "> a\n0 0\n100 50\n200 0\n300 80\n400 10\n");
    put("huge.gmt", "> a\n0 0\n1e308 1\n-1e308 5\n");
    put("tiny.gmt", "> a\n1e-300 2e-300\n3e-300 5e-300\n7e-300 1e-300\n");
    put("comma.csv", "x,y,z\n1,5,2,5,3,5\n2,3,4\n");
    put("pts.csv", "x,y,z\n0,0,1\n1,0,2\n0,1,3\n1,1,4\n2,1,5\n1,2,3\n2,2,1\n");
    put("tinypts.csv", "x,y,z\n0,0,1\n1e-160,0,2\n0,1e-160,3\n1e-160,1e-160,4\n");
    write_models();
    *state = NULL;
    return 0;
}

static int teardown(void **state)
{
    ft_test_rmtree(dir);
    free(dir);
    return 0;
}

/* ---- the table ---- */

#define VOLCANO "@data/dem_volcano_maunga_whau_10m.tif"
#define NF "@data/gshhg_newfoundland_utm21n.geojson"
#define SEED "@data/seed_contour_volcano.geojson"

static const bad_case cases[] = {
    /* data loss: output = input (every command that reads and writes) */
    {"output = input", 2, "is the input file", {"enhance", "@/line.gmt", "@/line.gmt"}},
    {"output = input", 2, "is the input file", {"simplify", "@/line.gmt", "@/./line.gmt", "--tolerance", "1"}},
    {"output = input", 2, "is the input file", {"weed", "@/line.gmt", "@/line.gmt"}},
    {"output = input", 2, "is the input file", {"smooth", "@/line.gmt", "@/line.gmt"}},
    {"output = input", 2, "is the input file", {"boundary", "@/line.gmt", "@/line.gmt", "--dim", "1.3"}},
    {"output = input", 2, "is the input file", {"dim", "map", "@/dem.tif", "@/dem.tif", "--window", "8"}},
    {"output = input", 2, "is the input file", {"fill", "@/dem.tif", "@/dem.tif"}},
    {"output = input", 2, "is the input file", {"fill", "@/dem.tif", "@/./dem.tif"}},
    {"output = input", 2, "is the input file", {"model", "fit", "@/dem.tif", "-o", "@/dem.tif"}},
    {"output = input", 2, "is the input file", {"model", "simulate", "@/model.json", "@/model.json"}},
    {"output = input", 2, "is the input file", {"mountain", "@/lines.geojson", "@/lines.geojson"}},
    {"output = input", 2, "is the input file", {"mountain", SEED, "@/out.geojson", "--dem", SEED}},
    {"output = input", 2, "is the input file", {"reconstruct", "@/dem.tif", "@/dem.tif"}},
    {"output = input", 2, "is the input file", {"hillshade", "@/dem.tif", "@/dem.tif"}},
    {"output = input", 2, "is the input file", {"render", "@/dem.tif", "@/dem.tif"}},
    /* the crash and the UB */
    {"crash", 1, "too small or too large", {"dim", "points", "@/pts.csv", "--lags", "1e-300,2e-300,3e-300"}},
    {"crash", 1, "lags", {"dim", "points", "@/tinypts.csv"}},
    {"UB", 1, "grid.size", {"model", "simulate", "@/model_neg.json", "@/out.tif"}},
    /* runaway work */
    {"runaway", 1, "--iterations 16", {"enhance", NF, "@/out.geojson", "--iterations", "16"}},
    {"runaway", 1, "--passes 16", {"smooth", NF, "@/out.geojson", "--passes", "16"}},
    {"runaway", 1, "--min 0.001", {"boundary", NF, "@/out.geojson", "--dim", "1.3", "--min", "1e-3"}},
    {"runaway", 1, "--spacing 0.001", {"mountain", SEED, "@/out.geojson", "--spacing", "1e-3"}},
    {"runaway", 1, "--cell 0.001", {"mountain", SEED, "@/out.geojson", "--dem", "@/out.tif", "--cell", "1e-3"}},
    {"runaway", 2, "--cell", {"reconstruct", "@/pts.csv", "@/out.tif", "--cell", "1e-6", "--dim", "2.3"}},
    {"runaway", 1, "--cell 0.0001", {"reconstruct", "@/pts.csv", "@/out.tif", "--cell", "1e-4", "--dim", "2.3"}},
    {"runaway", 1, "--min-scale 1e-300", {"dim", "line", NF, "--min-scale", "1e-300"}},
    {"runaway", 1, "--min-scale 1e-09", {"dim", "line", NF, "--min-scale", "1e-9", "--max-scale", "1e9"}},
    {"runaway", 1, "too small to measure", {"dim", "line", "@/tiny.gmt"}},
    {"runaway", 1, "--size 65536x65536", {"synth", "@/out.tif", "--dim", "2.3", "--size", "65536x65536"}},
    {"runaway", 1, "--max-work", {"--max-work", "1000", "model", "fit", VOLCANO}},
    {"runaway", 1, "--max-work", {"dim", "surface", VOLCANO, "--max-work=1000"}},
    {"runaway", 1, "--max-work", {"dim", "map", VOLCANO, "@/out.tif", "--window", "16", "--max-work", "1000"}},
    {"runaway", 1, "--max-work", {"dim", "area", VOLCANO, "--max-work", "1000"}},
    {"runaway", 1, "--max-memory", {"--max-memory", "1K", "hillshade", VOLCANO, "@/out.png"}},
    {"runaway", 1, "--max-memory", {"--max-memory", "1K", "hillshade", VOLCANO, "@/out.tif"}}, /* 2-row chunk */
    {"runaway", 1, "--max-work", {"--max-work", "1000", "reconstruct", VOLCANO, "@/out.tif"}},
    {"runaway", 1, "--max-work", {"--max-work", "1000", "render", VOLCANO, "@/out.png"}},
    {"runaway", 2, "--max-memory needs a size", {"--max-memory", "lots", "info", VOLCANO}},
    /* exit 0 with nonsense */
    {"nonsense", 1, "trunc.tif", {"hillshade", "@/trunc.tif", "@/out.png"}},
    {"nonsense", 1, "trunc.tif", {"hillshade", "@/trunc.tif", "@/out.tif"}}, /* streamed: fails mid-file */
    {"nonsense", 1, "1 x 20 cells", {"hillshade", "@/onexn.tif", "@/out.png"}},
    {"nonsense", 1, "no valid cell", {"hillshade", "@/nodata.tif", "@/out.tif"}},
    {"nonsense", 1, "no valid cell", {"hillshade", "@/nodata.tif", "@/out.tif", "--tile-rows", "1"}}, /* stripes */
    {"nonsense", 1, "no polygon", {"urban", "table", "@/lines.geojson", "--class", "c", "-o", "@/out.csv"}},
    {"nonsense", 1, "decimal commas", {"dim", "points", "@/comma.csv"}},
    {"nonsense", 1, "z field are for OGR", {"dim", "points", "@/pts.csv", "--zfield", "elev"}},
    {"nonsense", 1, "a layer and a z field", {"reconstruct", "@/pts.csv", "@/out.tif", "--layer", "x", "--cell", "1"}},
    {"nonsense", 2, "--periodic is for --method fft",
     {"synth", "@/out.tif", "--dim", "2.3", "--size", "64x64", "--method", "sra", "--periodic"}},
    {"nonsense", 1, "cannot store Float32 cells", {"synth", "@/out.png", "--dim", "2.3", "--size", "64x64"}},
    {"nonsense", 2, "--sigma must be", {"synth", "@/out.tif", "--dim", "2.3", "--size", "64x64", "--sigma", "1e300"}},
    /* unclear errors */
    {"unclear", 1, "is empty", {"model", "simulate", "@/model_empty.json", "@/out.tif"}},
    {"unclear", 1, "truncated", {"model", "simulate", "@/model_trunc.json", "@/out.tif"}},
    {"unclear", 1, "4611686018427387904", {"model", "simulate", "@/model_k.json", "@/out.tif"}},
    {"unclear", 1, "would overflow double", {"dim", "line", "@/huge.gmt"}},
    {"unclear", 1, "would overflow double", {"enhance", "@/huge.gmt", "@/out.gmt"}},
    {"unclear", 2, "has no extension", {"mountain", SEED, "@/mout"}},
    {"unclear", 2, "has no extension", {"mountain", SEED, "@/out.geojson", "--dem", "@/mdem"}},
};

static void test_bad_input_table(void **state)
{
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        run_case(&cases[i]);
    /* the refused outputs that were inputs are intact */
    size_t a = 0, b = 0;
    char *p = ft_test_path(dir, "dem.tif");
    char *x = ft_test_read_file(p, &a), *y = ft_test_read_file(FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif", &b);
    assert_true(a == b && memcmp(x, y, a) == 0);
    free(p);
    free(x);
    free(y);
}

/* ---- a full file system ---- */

typedef struct {
    const char *out;            /* output in the test folder, pre-filled with OLD */
    long limit;                 /* RLIMIT_FSIZE in bytes: below the output's size */
    const char *args[MAX_ARGS]; /* "@out" is replaced by the output's path */
} full_case;

static const full_case full_cases[] = {
    {"f.geojson", 20000, {"enhance", NF, "@out"}},
    {"f.gmt", 20000, {"enhance", NF, "@out"}},
    {"f.shp", 20000, {"simplify", NF, "@out", "--tolerance", "10"}},
    {"f.gpkg", 20000, {"smooth", NF, "@out"}},
    {"f.geojson", 20000, {"weed", NF, "@out", "--min-segment", "10"}},
    {"f.geojson", 20000, {"boundary", NF, "@out", "--dim", "1.3"}},
    {"f.geojson", 4000, {"mountain", SEED, "@out"}},
    {"f.png", 1000, {"hillshade", VOLCANO, "@out"}},
    {"f.tif", 4000, {"hillshade", VOLCANO, "@out"}},
    {"f.tif", 4000, {"synth", "@out", "--dim", "2.3", "--size", "64x64"}},
    {"f.tif", 300, {"dim", "map", VOLCANO, "@out", "--window", "16", "--step", "8"}},
    {"f.json", 1000, {"model", "fit", VOLCANO, "-o", "@out"}},
    {"f.tif", 4000, {"model", "simulate", "@/model.json", "@out"}},
    {"f.tif", 2000, {"reconstruct", VOLCANO, "@out"}}, /* 3.6 kB with ZSTD */
    {"f.png", 4000, {"render", VOLCANO, "@out"}},
    {"f.csv", 200, {"urban", "table", "@data/dcw_us_states_small_albers5070.geojson", "--class", "name", "-o",
                    "@out"}},
};

static void test_full_file_system(void **state)
{
    struct rlimit saved;
    assert_int_equal(getrlimit(RLIMIT_FSIZE, &saved), 0);
    void (*old)(int) = signal(SIGXFSZ, SIG_IGN);
    for (size_t i = 0; i < sizeof full_cases / sizeof full_cases[0]; i++) {
        const full_case *c = &full_cases[i];
        char *out = ft_test_path(dir, c->out);
        assert_int_equal(ft_test_write_text(out, "OLD"), 0);
        const char *argv[MAX_ARGS + 1];
        char *owned[MAX_ARGS];
        int n = 0;
        for (; n < MAX_ARGS && c->args[n] != NULL; n++)
            argv[n] = owned[n] = strcmp(c->args[n], "@out") == 0 ? strdup(out) : expand(c->args[n]);
        argv[n] = NULL;
        struct rlimit lim = {(rlim_t)c->limit, saved.rlim_max};
        assert_int_equal(setrlimit(RLIMIT_FSIZE, &lim), 0);
        ft_run_result r;
        int ran = ft_run_argv(&r, argv);
        assert_int_equal(setrlimit(RLIMIT_FSIZE, &saved), 0);
        assert_int_equal(ran, 0);
        char *after = ft_test_read_file(out, NULL);
        int ok = !r.signaled && r.status == 1 && strstr(r.err, c->out) != NULL &&
                 strstr(r.err, "File too large") != NULL && after != NULL && strcmp(after, "OLD") == 0 &&
                 !has_tmp_leftover();
        if (!ok)
            fprintf(stderr, "[full fs] %s %s: exit %d, output now '%.20s', stderr: %s\n", c->args[0], c->out,
                    r.status, after ? after : "(none)", r.err);
        assert_true(ok);
        free(after);
        ft_run_free(&r);
        for (int k = 0; k < n; k++)
            free(owned[k]);
        remove(out);
        free(out);
    }
    signal(SIGXFSZ, old);
}

/* ---- Ctrl-C ---- */

/* A long synthesis interrupted after a second stops with exit 1, not by the signal, and leaves nothing. */
static void test_interrupt(void **state)
{
    char *out = ft_test_path(dir, "int.tif");
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        int null = open("/dev/null", O_WRONLY);
        dup2(null, STDOUT_FILENO);
        dup2(null, STDERR_FILENO);
        execl(FT_BIN, FT_BIN, "synth", out, "--dim", "2.3", "--size", "6000x6000", "--method", "exact", (char *)NULL);
        _exit(127);
    }
    sleep(1);
    kill(pid, SIGINT);
    int status = 0;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFEXITED(status));
    assert_int_equal(WEXITSTATUS(status), 1);
    assert_false(ft_test_exists(out));
    assert_false(has_tmp_leftover());
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_bad_input_table),
        cmocka_unit_test(test_full_file_system),
        cmocka_unit_test(test_interrupt),
    };
    return cmocka_run_group_tests_name("cli_bad_input_table", tests, setup, teardown);
}
