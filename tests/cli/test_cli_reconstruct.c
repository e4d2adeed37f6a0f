/* fracterra — tests/cli/test_cli_reconstruct.c: `fracterra reconstruct` end to end on real files: Davis's 52
 * spot heights (tests/data/points_mass_topo_davis1973.csv) onto a grid given by --extent/--cell, by --cell
 * alone and by --like (geotransform, size and CRS as asked, values at the data within the stated
 * tolerance, points outside counted), the volcano and Luxembourg DEMs with voids (known cells identical,
 * no nodata left), --realizations (two bands, sd >= 0), reproducibility (same seed, same cells on 1 and 2
 * threads), and every bad input the issue names (exit code, message naming the culprit, nothing written).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/fracterra.h"
#include "ft_test_assert.h"
#include "ft_test_util.h"

#define DAVIS FT_TEST_DATA "/points_mass_topo_davis1973.csv"
#define VOLCANO FT_TEST_DATA "/dem_volcano_maunga_whau_10m.tif"
#define LUXEMBOURG FT_TEST_DATA "/dem_luxembourg_terra_30s.tif"
#define NEWFOUNDLAND FT_TEST_DATA "/gshhg_newfoundland_utm21n.geojson"
#define DAVIS_N 52

static ft_points *read_davis(void)
{
    ft_points *p = NULL;
    assert_int_equal(ft_io_read_points(DAVIS, NULL, &p), FT_OK);
    assert_int_equal(p->n, DAVIS_N);
    return p;
}

static double sd_of(const double *v, size_t n)
{
    double m = 0.0, s = 0.0;
    for (size_t i = 0; i < n; i++)
        m += v[i];
    m /= (double)n;
    for (size_t i = 0; i < n; i++)
        s += (v[i] - m) * (v[i] - m);
    return sqrt(s / (double)n);
}

/* The grid interpolated bilinearly between cell centres at (x, y) (clamped to the outer centres). */
static double bilinear(const ft_grid *g, double x, double y)
{
    double c = (x - g->gt[0]) / g->gt[1] - 0.5, r = (y - g->gt[3]) / g->gt[5] - 0.5;
    c = fmin(fmax(c, 0.0), (double)g->nx - 1.0);
    r = fmin(fmax(r, 0.0), (double)g->ny - 1.0);
    size_t c0 = (size_t)c, r0 = (size_t)r;
    size_t c1 = c0 + 1 < g->nx ? c0 + 1 : c0, r1 = r0 + 1 < g->ny ? r0 + 1 : r0;
    double fc = c - (double)c0, fr = r - (double)r0;
    const float *z = g->z;
    double top = (1 - fc) * z[r0 * g->nx + c0] + fc * z[r0 * g->nx + c1];
    double bot = (1 - fc) * z[r1 * g->nx + c0] + fc * z[r1 * g->nx + c1];
    return (1 - fr) * top + fr * bot;
}

/* RMS of (grid - z) over the points inside the grid's extent. */
static double rms_at_points(const ft_grid *g, const ft_points *p, size_t *inside)
{
    double xmin, ymin, xmax, ymax, s = 0.0;
    ft_grid_extent(g, &xmin, &ymin, &xmax, &ymax);
    size_t n = 0;
    for (size_t i = 0; i < p->n; i++) {
        if (p->x[i] < xmin || p->x[i] > xmax || p->y[i] < ymin || p->y[i] > ymax)
            continue;
        double d = bilinear(g, p->x[i], p->y[i]) - p->z[i];
        s += d * d;
        n++;
    }
    if (inside)
        *inside = n;
    return n ? sqrt(s / (double)n) : NAN;
}

static void assert_all_finite_no_mask(const ft_grid *g)
{
    assert_int_equal(ft_grid_count_valid(g), g->nx * g->ny);
    for (size_t i = 0; i < g->nx * g->ny; i++)
        assert_true(isfinite(g->z[i]));
}

/* 8% of the volcano's cells (a fixed hash of the cell index) as points at their centres, written as CSV
 * (no CRS): real elevations that fall exactly on the nodes of a --like VOLCANO grid. */
static ft_points *volcano_points(const char *csv)
{
    ft_grid *g = ft_test_read_band(VOLCANO, 1);
    ft_points *p = ft_points_create(0);
    assert_non_null(p);
    for (size_t i = 0; i < g->nx * g->ny; i++) {
        if ((i * UINT64_C(2654435761)) % 100 >= 8)
            continue;
        double x, y;
        ft_grid_cell_center(g, (double)(i % g->nx), (double)(i / g->nx), &x, &y);
        assert_int_equal(ft_points_push(p, x, y, g->z[i]), FT_OK);
    }
    assert_int_equal(ft_io_write_points(csv, p), FT_OK);
    ft_grid_free(g);
    return p;
}

/* Mean |z(col + 1) - z(col)| and |z(row + 1) - z(row)|: the roughness at one cell. */
static double roughness(const ft_grid *g)
{
    double s = 0.0;
    size_t n = 0;
    for (size_t r = 0; r < g->ny; r++)
        for (size_t c = 0; c < g->nx; c++) {
            size_t i = r * g->nx + c;
            if (c + 1 < g->nx) {
                s += fabs((double)g->z[i + 1] - g->z[i]);
                n++;
            }
            if (r + 1 < g->ny) {
                s += fabs((double)g->z[i + g->nx] - g->z[i]);
                n++;
            }
        }
    return s / (double)n;
}

/* ---- points onto a grid ---- */

static void test_points_extent(void **state)
{
    (void)state;
    /* cells of 0.1 centred on multiples of 0.1: every datum (one decimal) falls on a cell centre */
    const char *out = ft_test_tmp("topo.tif");
    const char *argv[] = {"reconstruct", DAVIS, out, "--method", "smooth", "--extent", "-0.55,-0.55,6.95,6.95",
                          "--cell", "0.1", "--dim", "2.3", "--crs", "EPSG:32632", "--json", NULL};
    json_object *o = ft_test_run_json(argv);
    const char *keys[] = {"method", "D", "D_estimated", "sigma0", "k", "temperature", "levels", "data_used",
                          "data_outside", "filled", "data_rms", "realizations", "seed", "output", "nx", "ny",
                          "cell"};
    for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++)
        ft_test_json_key(o, keys[i]);
    assert_string_equal(ft_test_json_str(o, "method"), "smooth");
    assert_string_equal(ft_test_json_str(o, "output"), out);
    assert_near(ft_test_json_num(o, "D"), 2.3, 1e-12);
    /* the smooth prior's blend follows the given D (Szeliski's eq. 7): tau / (1 - tau) = 2 (D - 2) / (3 - D) */
    assert_near(ft_test_json_num(o, "tension"), (0.6 / 0.7) / (1.0 + 0.6 / 0.7), 1e-12);
    assert_false(json_object_get_boolean(ft_test_json_key(o, "D_estimated")));
    assert_int_equal(ft_test_json_int(o, "nx"), 75); /* 7.5 / 0.1 */
    assert_int_equal(ft_test_json_int(o, "ny"), 75);
    assert_near(ft_test_json_num(o, "cell"), 0.1, 1e-12);
    assert_int_equal(ft_test_json_int(o, "data_used"), DAVIS_N);
    assert_int_equal(ft_test_json_int(o, "data_outside"), 0);
    assert_int_equal(ft_test_json_int(o, "filled"), 75 * 75 - DAVIS_N); /* 52 distinct data cells */
    assert_int_equal(ft_test_json_int(o, "realizations"), 1);
    assert_int_equal(ft_test_json_int(o, "seed"), 1);
    double data_rms = ft_test_json_num(o, "data_rms");
    json_object_put(o);

    ft_grid *g = ft_test_read_band(out, 1);
    assert_int_equal(g->nx, 75);
    assert_int_equal(g->ny, 75);
    const double gt[6] = {-0.55, 0.1, 0.0, 6.95, 0.0, -0.1};
    for (int i = 0; i < 6; i++)
        assert_near(g->gt[i], gt[i], 1e-12);
    ft_test_assert_crs_epsg(g->crs_wkt, 32632);
    assert_all_finite_no_mask(g);
    /* sigma 0 interpolates: the data, on cell centres, are honoured to float precision (1e-3 of the data's
     * spread, sd 61.4 ft, is far above the rounding of 1000 ft in a float) */
    ft_points *p = read_davis();
    size_t inside = 0;
    double rms = rms_at_points(g, p, &inside);
    assert_int_equal(inside, DAVIS_N);
    assert_true(rms < 1e-3 * sd_of(p->z, p->n));
    assert_true(data_rms < 1e-3 * sd_of(p->z, p->n));
    /* an interpolator stays near the range of the data (690 .. 960 ft) */
    double lo, hi;
    ft_grid_minmax(g, &lo, &hi);
    assert_true(lo > 690.0 - 0.5 * 270.0 && hi < 960.0 + 0.5 * 270.0);
    ft_points_free(p);
    ft_grid_free(g);
    assert_int_equal(ft_test_dir_count(), 1); /* no temporary or auxiliary file */
}

/* --sigma S: a datum may miss by about S. The default lambda (1) misses these data (feet, sd 61) by far more
 * than 10, so the discrepancy principle lowers it until the RMS at the data (on cell centres) is in
 * [sqrt(1 - 0.06), 1] x S: within S, and the surface no longer passes through them. */
static void test_points_sigma(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("s.tif");
    const char *argv[] = {"reconstruct", DAVIS, out, "--method", "smooth", "--extent", "-0.55,-0.55,6.95,6.95",
                          "--cell", "0.1", "--sigma", "10", "--dim", "2.3", "--json", NULL};
    json_object *o = ft_test_run_json(argv);
    double data_rms = ft_test_json_num(o, "data_rms");
    json_object_put(o);
    assert_true(data_rms > 0.0 && data_rms <= 10.0);
    ft_grid *g = ft_test_read_band(out, 1);
    ft_points *p = read_davis();
    double rms = rms_at_points(g, p, NULL);
    assert_true(rms >= sqrt(1.0 - 0.06) * 10.0 - 1e-3 && rms <= 10.0 + 1e-3);
    assert_near(data_rms, rms, 0.01 * rms); /* the reported figure is this measure */
    ft_points_free(p);
    ft_grid_free(g);
}

/* --cell alone: the bounding box snapped outward to multiples of the cell, every point inside. */
static void test_points_bbox(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("bbox.tif");
    const char *argv[] = {"reconstruct", DAVIS, out, "--cell", "0.25", "--method", "smooth", "--json", NULL};
    json_object *o = ft_test_run_json(argv);
    assert_int_equal(ft_test_json_int(o, "data_used"), DAVIS_N);
    assert_int_equal(ft_test_json_int(o, "data_outside"), 0);
    assert_int_equal(ft_test_json_int(o, "nx"), 26);
    json_object_put(o);
    ft_grid *g = ft_test_read_band(out, 1);
    /* Davis: x 0.2 .. 6.3, y 0 .. 6.2. x from floor(0.2 / 0.25) = 0 to floor(6.3 / 0.25) + 1 = 26 cells; y from
     * ceil(0 / 0.25) - 1 = -1 to ceil(6.2 / 0.25) = 25 cells: 26 x 26 cells of 0.25 from (0, 6.25) */
    assert_int_equal(g->nx, 26);
    assert_int_equal(g->ny, 26);
    const double gt[6] = {0.0, 0.25, 0.0, 6.25, 0.0, -0.25};
    for (int i = 0; i < 6; i++)
        assert_near(g->gt[i], gt[i], 1e-12);
    assert_true(g->crs_wkt == NULL || g->crs_wkt[0] == '\0'); /* a CSV has no CRS, none was given */
    assert_all_finite_no_mask(g);
    ft_grid_free(g);
}

/* The paper's method and the conditional one on real elevations: 8% of the volcano's cells onto its grid.
 * sigma 0: the data are nodes of the grid and are honoured (float rounding, far below 1e-3 of their sd);
 * between them the fractal and conditional surfaces are rougher than the smooth one (T = 0 minimizes the
 * curvature energy; sampling at T > 0 adds variance at every level). */
static void test_points_volcano(void **state)
{
    (void)state;
    const char *csv = ft_test_tmp("volcano8.csv");
    ft_points *p = volcano_points(csv);
    const char *methods[] = {"smooth", "fractal", "conditional"};
    double rough[3];
    for (int m = 0; m < 3; m++) {
        const char *out = ft_test_tmp("v.tif");
        const char *argv[] = {"reconstruct", csv, out, "--like", VOLCANO, "--method", methods[m], "--seed", "9",
                              "--json", NULL};
        json_object *o = ft_test_run_json(argv);
        assert_string_equal(ft_test_json_str(o, "method"), methods[m]);
        assert_int_equal(ft_test_json_int(o, "data_used"), p->n);
        assert_int_equal(ft_test_json_int(o, "data_outside"), 0);
        assert_int_equal(ft_test_json_int(o, "filled"), 61 * 87 - p->n);
        assert_true(ft_test_json_num(o, "data_rms") < 1e-3 * sd_of(p->z, p->n));
        if (m > 0) { /* D from the data (auto, the default) */
            assert_true(json_object_get_boolean(ft_test_json_key(o, "D_estimated")));
            double D = ft_test_json_num(o, "D");
            assert_true(D > 2.0 && D < 3.0);
        }
        if (m == 1) {
            assert_true(ft_test_json_num(o, "temperature") > 0.0);
            assert_true(ft_test_json_num(o, "k") > 0.0);
            assert_true(ft_test_json_num(o, "sigma0") > 0.0);
            assert_true(ft_test_json_int(o, "levels") >= 1);
        }
        json_object_put(o);
        ft_grid *g = ft_test_read_band(out, 1);
        assert_int_equal(g->nx, 61);
        assert_int_equal(g->ny, 87);
        ft_grid *v = ft_test_read_band(VOLCANO, 1);
        for (int i = 0; i < 6; i++)
            assert_near(g->gt[i], v->gt[i], 1e-9);
        ft_test_assert_same_crs(g->crs_wkt, v->crs_wkt); /* from --like: the CSV has none */
        ft_grid_free(v);
        assert_all_finite_no_mask(g);
        assert_true(rms_at_points(g, p, NULL) < 1e-3 * sd_of(p->z, p->n));
        rough[m] = roughness(g);
        ft_grid_free(g);
    }
    assert_true(rough[1] > rough[0]);
    assert_true(rough[2] > rough[0]);
    ft_points_free(p);
}

/* --like: the grid's shape, geotransform and CRS; points outside it ignored and counted. */
static void test_points_like(void **state)
{
    (void)state;
    const char *like = ft_test_tmp("like.tif"), *out = ft_test_tmp("out.tif");
    ft_grid *l = ft_grid_create(40, 65); /* x 0 .. 4, y 0 .. 6.5: 32 of the 52 points, and 1 on the border */
    assert_non_null(l);
    const double gt[6] = {0.0, 0.1, 0.0, 6.5, 0.0, -0.1};
    memcpy(l->gt, gt, sizeof gt);
    char *wkt = NULL;
    assert_int_equal(ft_io_crs_to_wkt("EPSG:2193", &wkt), FT_OK);
    assert_int_equal(ft_grid_set_crs(l, wkt), FT_OK);
    free(wkt);
    assert_int_equal(ft_io_write_grid(like, l, NULL), FT_OK);
    ft_grid_free(l);

    ft_points *p = read_davis();
    size_t expect_inside = 0;
    for (size_t i = 0; i < p->n; i++)
        expect_inside += p->x[i] >= 0.0 && p->x[i] < 4.0 && p->y[i] > 0.0 && p->y[i] <= 6.5;
    const char *argv[] = {"reconstruct", DAVIS, out, "--like", like, "--method", "smooth", "--json", NULL};
    json_object *o = ft_test_run_json(argv);
    assert_int_equal(ft_test_json_int(o, "data_used") + ft_test_json_int(o, "data_outside"), DAVIS_N);
    assert_true(ft_test_json_int(o, "data_outside") > 0);
    /* the point on the grid's border (y = 0) may count either way; all others are decided by the extent */
    assert_true(labs((long)ft_test_json_int(o, "data_used") - (long)expect_inside) <= 1);
    json_object_put(o);
    ft_grid *g = ft_test_read_band(out, 1);
    assert_int_equal(g->nx, 40);
    assert_int_equal(g->ny, 65);
    for (int i = 0; i < 6; i++)
        assert_near(g->gt[i], gt[i], 1e-12);
    ft_test_assert_crs_epsg(g->crs_wkt, 2193);
    assert_all_finite_no_mask(g);
    ft_points_free(p);
    ft_grid_free(g);
}

/* ---- voids ---- */

/* Punches nodata into a copy of dem: a disk of radius 6 cells, a 9 x 4 block and every 17th cell; returns
 * how many cells were valid before and are nodata now. */
static size_t punch(ft_grid *g)
{
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    size_t n = 0;
    for (size_t r = 0; r < g->ny; r++)
        for (size_t c = 0; c < g->nx; c++) {
            size_t i = r * g->nx + c;
            double dc = (double)c - 0.4 * (double)g->nx, dr = (double)r - 0.4 * (double)g->ny;
            int hole = dc * dc + dr * dr <= 36.0 ||
                       (c >= g->nx / 2 + 10 && c < g->nx / 2 + 19 && r >= g->ny / 2 + 15 && r < g->ny / 2 + 19) ||
                       i % 17 == 5;
            if (hole && g->mask[i]) {
                g->mask[i] = 0;
                n++;
            }
        }
    if (!g->has_nodata) {
        g->has_nodata = 1;
        g->nodata_value = -9999.0;
    }
    return n;
}

static void check_voids(const char *dem_path, const char *method)
{
    const char *holed = ft_test_tmp("holed.tif"), *out = ft_test_tmp("filled.tif");
    ft_grid *orig = ft_test_read_band(dem_path, 1);
    ft_grid *h = ft_grid_copy(orig);
    assert_non_null(h);
    size_t valid_before = ft_grid_count_valid(h);
    size_t punched = punch(h);
    assert_true(punched > 0);
    assert_int_equal(ft_io_write_grid(holed, h, NULL), FT_OK);
    ft_grid *back = ft_test_read_band(holed, 1); /* the file as the command reads it */
    size_t voids = back->nx * back->ny - ft_grid_count_valid(back);
    assert_int_equal(ft_grid_count_valid(back), valid_before - punched);

    const char *argv[] = {"reconstruct", holed, out, "--method", method, "--seed", "11", "--json", NULL};
    json_object *o = ft_test_run_json(argv);
    assert_string_equal(ft_test_json_str(o, "method"), method);
    assert_true(json_object_get_boolean(ft_test_json_key(o, "D_estimated")));
    double D = ft_test_json_num(o, "D");
    assert_true(D > 2.0 && D < 3.0);
    assert_int_equal(ft_test_json_int(o, "filled"), voids);
    assert_int_equal(ft_test_json_int(o, "data_used"), back->nx * back->ny - voids);
    assert_near(ft_test_json_num(o, "data_rms"), 0.0, 1e-6); /* known cells are kept exactly */
    json_object_put(o);

    ft_grid *f = ft_test_read_band(out, 1);
    assert_int_equal(f->nx, back->nx);
    assert_int_equal(f->ny, back->ny);
    for (int i = 0; i < 6; i++)
        assert_near(f->gt[i], back->gt[i], 1e-9);
    ft_test_assert_same_crs(f->crs_wkt, back->crs_wkt);
    assert_all_finite_no_mask(f); /* no nodata left */
    /* the punched cells (valid in the original): a filling that knows the terrain around a hole beats the
     * original's mean there, so its RMSE against the original is below the original's sd; the cells outside
     * the data (Luxembourg's border region) are extrapolation: finite, no more is asked */
    double s = 0.0, ss = 0.0, err = 0.0;
    size_t nv = 0, np = 0, same = 0;
    for (size_t i = 0; i < f->nx * f->ny; i++)
        if (ft_grid_is_valid(orig, i % orig->nx, i / orig->nx)) {
            s += orig->z[i];
            ss += (double)orig->z[i] * orig->z[i];
            nv++;
        }
    double sd = sqrt(ss / (double)nv - (s / (double)nv) * (s / (double)nv));
    for (size_t i = 0; i < f->nx * f->ny; i++) {
        if (back->mask[i]) {
            same += f->z[i] == back->z[i]; /* identical, bit for bit */
        } else if (ft_grid_is_valid(orig, i % orig->nx, i / orig->nx)) {
            err += ((double)f->z[i] - orig->z[i]) * ((double)f->z[i] - orig->z[i]);
            np++;
        }
    }
    assert_int_equal(np, punched);
    assert_true(sqrt(err / (double)np) < sd);
    assert_int_equal(same, back->nx * back->ny - voids);
    ft_grid_free(f);
    ft_grid_free(back);
    ft_grid_free(h);
    ft_grid_free(orig);
}

static void test_voids_volcano(void **state)
{
    (void)state;
    check_voids(VOLCANO, "fractal");
}

/* Luxembourg: Int16 with nodata outside the country (large voids reaching the edges) plus the punched ones. */
static void test_voids_luxembourg(void **state)
{
    (void)state;
    check_voids(LUXEMBOURG, "conditional");
}

/* ---- realizations and reproducibility ---- */

static void test_realizations(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("mc.tif"), *csv = ft_test_tmp("volcano8.csv");
    ft_points_free(volcano_points(csv));
    const char *argv[] = {"reconstruct", csv, out, "--like", VOLCANO, "--method", "conditional", "--realizations",
                          "3", "--seed", "5", "--json", NULL};
    json_object *o = ft_test_run_json(argv);
    assert_int_equal(ft_test_json_int(o, "realizations"), 3);
    assert_string_equal(ft_test_json_str(o, "bands"), "1: mean, 2: sd");
    json_object_put(o);
    ft_grid *mean = ft_test_read_band(out, 1), *sd = ft_test_read_band(out, 2);
    ft_grid *none = NULL;
    ft_read_grid_opts b3 = FT_READ_GRID_OPTS_DEFAULT;
    b3.band = 3;
    assert_int_equal(ft_io_read_grid(out, &b3, &none), FT_E_FORMAT); /* exactly two bands */
    assert_int_equal(sd->nx, mean->nx);
    assert_int_equal(sd->ny, mean->ny);
    for (int i = 0; i < 6; i++)
        assert_near(sd->gt[i], mean->gt[i], 1e-12);
    size_t positive = 0;
    for (size_t i = 0; i < sd->nx * sd->ny; i++) {
        assert_true(isfinite(sd->z[i]) && sd->z[i] >= 0.0f);
        positive += sd->z[i] > 0.0f;
    }
    assert_true(positive > sd->nx * sd->ny / 2); /* the runs differ away from the data */
    assert_all_finite_no_mask(mean);
    ft_grid_free(mean);
    ft_grid_free(sd);
}

static void test_seed(void **state)
{
    (void)state;
    const char *a = ft_test_tmp("a.tif"), *b = ft_test_tmp("b.tif"), *c = ft_test_tmp("c.tif");
    const char *csv = ft_test_tmp("volcano8.csv");
    ft_points_free(volcano_points(csv));
    const char *argv[] = {"reconstruct", csv, a, "--like", VOLCANO, "--dim", "2.5", "--seed", "42", "--threads",
                          "1", NULL};
    ft_run_result r;
    assert_int_equal(ft_run_argv(&r, argv), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    argv[2] = b; /* same seed on two threads: the same cells */
    argv[10] = "2";
    assert_int_equal(ft_run_argv(&r, argv), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    argv[2] = c; /* another seed: other cells */
    argv[8] = "43";
    assert_int_equal(ft_run_argv(&r, argv), 0);
    assert_int_equal(r.status, 0);
    ft_run_free(&r);
    ft_grid *ga = ft_test_read_band(a, 1), *gb = ft_test_read_band(b, 1), *gc = ft_test_read_band(c, 1);
    assert_int_equal(ga->nx, gb->nx);
    assert_int_equal(ga->ny, gb->ny);
    assert_memory_equal(ga->z, gb->z, ga->nx * ga->ny * sizeof(float));
    assert_true(memcmp(ga->z, gc->z, ga->nx * ga->ny * sizeof(float)) != 0);
    ft_grid_free(ga);
    ft_grid_free(gb);
    ft_grid_free(gc);
}

/* ---- bad input ---- */

static void test_bad_usage(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("x.tif");
    const char *method[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--method", "kriging", NULL};
    ft_test_expect_failure(2, "reconstruct", "'kriging'", method);
    const char *dim[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--dim", "3.2", NULL};
    ft_test_expect_failure(2, "reconstruct", "--dim", dim);
    const char *dimtext[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--dim", "rough", NULL};
    ft_test_expect_failure(2, "reconstruct", "'rough'", dimtext);
    const char *cell[] = {"reconstruct", DAVIS, out, "--cell", "0", NULL};
    ft_test_expect_failure(2, "reconstruct", "--cell", cell);
    const char *extent[] = {"reconstruct", DAVIS, out, "--extent", "7,0,1,6", "--cell", "0.1", NULL};
    ft_test_expect_failure(2, "reconstruct", "xmin 7", extent);
    const char *extent_text[] = {"reconstruct", DAVIS, out, "--extent", "0,0,7", "--cell", "0.1", NULL};
    ft_test_expect_failure(2, "reconstruct", "'0,0,7'", extent_text);
    const char *both[] = {"reconstruct", DAVIS, out, "--like", VOLCANO, "--extent", "0,0,7,7", "--cell", "0.1",
                          NULL};
    ft_test_expect_failure(2, "reconstruct", "--like", both);
    const char *raster[] = {"reconstruct", VOLCANO, out, "--extent", "0,0,7,7", "--cell", "0.1", NULL};
    ft_test_expect_failure(2, "reconstruct", "--extent", raster);
    const char *raster_weight[] = {"reconstruct", VOLCANO, out, "--weight", "w", NULL};
    ft_test_expect_failure(2, "reconstruct", "--weight", raster_weight);
    const char *nogrid[] = {"reconstruct", DAVIS, out, NULL};
    ft_test_expect_failure(2, "reconstruct", "--cell", nogrid);
    const char *temp[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--method", "smooth", "--temperature", "1",
                          NULL};
    ft_test_expect_failure(2, "reconstruct", "--temperature", temp);
    const char *real[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--realizations", "0", NULL};
    ft_test_expect_failure(2, "reconstruct", "--realizations", real);
    const char *crs[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--crs", "EPSG:999999", NULL};
    ft_test_expect_failure(2, "reconstruct", "EPSG:999999", crs);
    const char *huge[] = {"reconstruct", DAVIS, out, "--cell", "1e-6", NULL};
    ft_test_expect_failure(2, "reconstruct", "--cell", huge);
    const char *noout[] = {"reconstruct", DAVIS, NULL};
    ft_test_expect_failure(2, "reconstruct", "OUT", noout);
    assert_int_equal(ft_test_dir_count(), 0);
}

static void test_bad_data(void **state)
{
    (void)state;
    const char *out = ft_test_tmp("x.tif");
    const char *two = ft_test_tmp_text("two.csv", "x,y,z\n0,0,1\n1,1,2\n");
    const char *few[] = {"reconstruct", two, out, "--cell", "0.1", NULL};
    ft_test_expect_failure(1, "reconstruct", "2 points", few);
    const char *line = ft_test_tmp_text("line.csv", "x,y,z\n0,0,1\n1,1,2\n2,2,3\n3,3,1\n");
    /* cell 0.5: the points fall on diagonal nodes (at 0.1 the rounding of x / 0.1 puts one beside the line) */
    const char *collinear[] = {"reconstruct", line, out, "--cell", "0.5", "--dim", "2.3", NULL};
    /* the library's message follows the command's prefix once (no "reconstruct: reconstruct:") */
    ft_test_expect_failure(1, "reconstruct", "fracterra: reconstruct: the 4 data nodes are all on one line",
                           collinear);
    /* 52 points give too few pairs per lag for D and Pentland's sigma0 (100 each by default) */
    const char *davis[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--method", "fractal", NULL};
    ft_test_expect_failure(1, "reconstruct", "fracterra: reconstruct: cannot estimate", davis);
    const char *text = ft_test_tmp_text("bad.csv", "x,y,z\n0,0,1\n1,one,2\n2,0,3\n");
    const char *garbage[] = {"reconstruct", text, out, "--cell", "0.1", NULL};
    ft_test_expect_failure(1, "reconstruct", "bad.csv", garbage);
    const char *missing[] = {"reconstruct", ft_test_tmp("none.csv"), out, "--cell", "0.1", NULL};
    ft_test_expect_failure(1, "reconstruct", "none.csv", missing);
    const char *weight[] = {"reconstruct", DAVIS, out, "--cell", "0.1", "--weight", "conf", NULL};
    ft_test_expect_failure(1, "reconstruct", "conf", weight);
    const char *lines[] = {"reconstruct", NEWFOUNDLAND, out, "--cell", "1000", NULL};
    ft_test_expect_failure(1, "reconstruct", "gshhg_newfoundland_utm21n.geojson", lines);
    const char *like[] = {"reconstruct", DAVIS, out, "--like", ft_test_tmp("nolike.tif"), NULL};
    ft_test_expect_failure(1, "reconstruct", "nolike.tif", like);
    const char *folder[] = {"reconstruct", DAVIS, ft_test_tmp("missing/x.tif"), "--cell", "0.1", NULL};
    ft_test_expect_failure(1, "reconstruct", "missing", folder);
    /* a DEM without a valid cell */
    ft_grid *g = ft_grid_create(8, 8);
    assert_non_null(g);
    assert_int_equal(ft_grid_ensure_mask(g), FT_OK);
    memset(g->mask, 0, 64);
    g->has_nodata = 1;
    g->nodata_value = -9999.0;
    const char *empty = ft_test_tmp("empty.tif");
    assert_int_equal(ft_io_write_grid(empty, g, NULL), FT_OK);
    ft_grid_free(g);
    const char *nodata[] = {"reconstruct", empty, out, NULL};
    ft_test_expect_failure(1, "reconstruct", "", nodata);
    assert_int_equal(ft_test_dir_count(), 4); /* the four fixtures, no output */
}

static void test_help(void **state)
{
    (void)state;
    ft_run_result r;
    assert_int_equal(ft_run(&r, "reconstruct", "--help", NULL), 0);
    assert_int_equal(r.status, 0);
    assert_non_null(strstr(r.out, "Example"));
    assert_non_null(strstr(r.out, "--realizations"));
    ft_run_free(&r);
    assert_int_equal(ft_run(&r, "--help", NULL), 0);
    assert_non_null(strstr(r.out, "reconstruct"));
    ft_run_free(&r);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_points_extent),  cmocka_unit_test(test_points_sigma),
        cmocka_unit_test(test_points_bbox),    cmocka_unit_test(test_points_like),
        cmocka_unit_test(test_points_volcano),
        cmocka_unit_test(test_voids_volcano),  cmocka_unit_test(test_voids_luxembourg),
        cmocka_unit_test(test_realizations),   cmocka_unit_test(test_seed),
        cmocka_unit_test(test_bad_usage),      cmocka_unit_test(test_bad_data),
        cmocka_unit_test(test_help),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_EACH);
}
