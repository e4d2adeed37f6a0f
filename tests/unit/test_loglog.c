/* fracterra — unit tests of core/loglog_*.c: log-log tables, iterative least squares and minimax
 * segmentation (Arakawa & Krotkov §2.4). Every expected value follows from how the table was built:
 * known slopes, known break, known noise.
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <cmocka.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fracterra/core.h"
#include "ft_test_assert.h"

static const ft_dim_map BOX = FT_DIM_MAP_BOXCOUNT;  /* D = -slope */
static const ft_dim_map SLOPE = {0.0, 1.0, 0.0, 0.0}; /* D = slope, no bounds */

/* value = c * scale^p at scales 2^0 .. 2^(n-1). */
static ft_loglog *power_law(size_t n, double c, double p)
{
    ft_loglog *t = ft_loglog_create(0);
    assert_non_null(t);
    for (size_t i = 0; i < n; i++) {
        double s = ldexp(1.0, (int)i);
        assert_int_equal(ft_loglog_push(t, s, c * pow(s, p), (double)(100 * (i + 1))), FT_OK);
    }
    return t;
}

/* Scales 2^0 .. 2^12; slope -1.2 up to 2^5 = 32 (rows 0..5), slope -1.8 from 32 on (rows 5..12).
 * Rows 0..5 (6) and 5..12 (8) are the two straight runs; row 5 lies on both. */
#define BREAK_ROW 5
#define TWO_RUN_ROWS 13
static ft_loglog *two_runs(void)
{
    ft_loglog *t = ft_loglog_create(TWO_RUN_ROWS);
    assert_non_null(t);
    double xb = BREAK_ROW * log10(2.0);
    for (int i = 0; i < TWO_RUN_ROWS; i++) {
        double x = i * log10(2.0);
        double y = x <= xb ? 3.0 - 1.2 * x : 3.0 - 1.2 * xb - 1.8 * (x - xb);
        assert_int_equal(ft_loglog_push(t, pow(10.0, x), pow(10.0, y), 0.0), FT_OK);
    }
    return t;
}

static void test_exact_power_law(void **state)
{
    (void)state;
    ft_loglog *t = power_law(10, 5.0, -1.5);
    ft_dim_result *r = NULL;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &BOX, &r), FT_OK);
    assert_near(r->fit.slope, -1.5, 1e-12);
    assert_near(r->D, 1.5, 1e-12);
    assert_near(r->r2, 1.0, 1e-12);
    assert_near(r->stderr_D, 0.0, 1e-12);
    assert_near(r->max_err, 0.0, 1e-12);
    assert_near(r->noise, 0.0, 1e-12);
    assert_near(r->range[0], 1.0, 0.0);
    assert_near(r->range[1], 512.0, 0.0);
    assert_int_equal(r->fit.n, 10);
    assert_string_equal(r->method, "regimes");
    assert_string_equal(r->segmentation, "regimes");
    assert_int_equal(r->nregimes, 1);
    assert_int_equal(r->regime, 0);
    assert_string_equal(r->choice, "the only regime");
    assert_int_equal(r->nwarnings, 0);
    assert_int_equal(r->nsegments, 1);
    assert_int_equal(r->best, 0);
    assert_near(r->segments[0].D_minimax, 1.5, 1e-12);
    for (size_t i = 0; i < r->table->n; i++)
        assert_int_equal(r->table->rows[i].used, 1);
    ft_dim_result_free(r);

    /* the map is applied as D = a + b*slope: divider-style {1, -1} gives 2.5, outside the divider's
     * [1, 2]: the only straight run does not qualify, D is the whole table's fit and says so */
    const ft_dim_map div = FT_DIM_MAP_DIVIDER;
    assert_error_names(ft_loglog_segment_ils(t, NULL, &div, &r), FT_E_NUMERIC, "D = 2.5000 lies outside [1, 2]");
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &div, &r), FT_E_NUMERIC, "rougher than any");
    assert_null(r);
    ft_loglog_free(t);
}

static void test_local_slopes(void **state)
{
    (void)state;
    ft_loglog *t = power_law(10, 3.0, -1.5);
    for (size_t i = 0; i < t->n; i++)
        assert_near(t->rows[i].slope, -1.5, 1e-12);

    /* pushed from large to small scale, then sorted: same slopes, increasing scales */
    ft_loglog *d = ft_loglog_create(0);
    for (int i = 9; i >= 0; i--)
        assert_int_equal(ft_loglog_push(d, ldexp(1.0, i), 3.0 * pow(ldexp(1.0, i), -1.5), 0.0), FT_OK);
    assert_int_not_equal(ft_loglog_check(d), FT_OK);
    assert_int_equal(ft_loglog_sort(d), FT_OK);
    assert_int_equal(ft_loglog_check(d), FT_OK);
    for (size_t i = 0; i < d->n; i++) {
        assert_near(d->rows[i].scale, ldexp(1.0, (int)i), 0.0);
        assert_near(d->rows[i].slope, -1.5, 1e-12);
    }

    /* two runs: one-sided -1.2 / -1.8 away from the break, centred (-1.5) at the break row */
    ft_loglog *b = two_runs();
    for (int i = 0; i < TWO_RUN_ROWS; i++)
        assert_near(b->rows[i].slope, i < BREAK_ROW ? -1.2 : i > BREAK_ROW ? -1.8 : -1.5, 1e-12);
    /* a single row has no slope yet */
    ft_loglog *one = ft_loglog_create(1);
    assert_int_equal(ft_loglog_push(one, 1.0, 1.0, 0.0), FT_OK);
    assert_true(isnan(one->rows[0].slope));
    ft_loglog_free(one);
    ft_loglog_free(b);
    ft_loglog_free(d);
    ft_loglog_free(t);
}

static void test_two_runs_minimax(void **state)
{
    (void)state;
    ft_loglog *t = two_runs();
    ft_loglog_segment *s = NULL;
    size_t n = 0;
    assert_int_equal(ft_loglog_segment_minimax(t, NULL, &BOX, &s, &n), FT_OK);
    assert_int_equal(n, 2);
    assert_int_equal(s[0].first, 0);
    assert_int_equal(s[0].last, BREAK_ROW);
    assert_int_equal(s[1].first, BREAK_ROW);
    assert_int_equal(s[1].last, TWO_RUN_ROWS - 1);
    assert_near(s[0].slope, -1.2, 1e-12);
    assert_near(s[1].slope, -1.8, 1e-12);
    assert_near(s[0].D, 1.2, 1e-12);
    assert_near(s[1].D, 1.8, 1e-12);
    assert_near(s[1].D_minimax, 1.8, 1e-12);
    assert_near(s[0].max_err, 0.0, 1e-12);
    assert_near(s[0].scale_hi, 32.0, 1e-9);
    assert_int_equal(s[1].n, 8);
    ft_loglog_segments_free(s);
    ft_loglog_free(t);
}

static void test_two_runs_ils(void **state)
{
    (void)state;
    ft_loglog *t = two_runs();
    ft_dim_result *r = NULL;
    assert_int_equal(ft_loglog_segment_ils(t, NULL, &BOX, &r), FT_OK);
    assert_int_equal(r->fit.first, BREAK_ROW);
    assert_int_equal(r->fit.last, TWO_RUN_ROWS - 1);
    assert_near(r->D, 1.8, 1e-12);
    assert_near(r->range[0], 32.0, 1e-9);
    assert_near(r->range[1], 4096.0, 1e-6);
    for (int i = 0; i < TWO_RUN_ROWS; i++)
        assert_int_equal(r->table->rows[i].used, i >= BREAK_ROW);
    assert_int_equal(r->nsegments, 0);
    ft_dim_result_free(r);

    /* fit_auto: ILS picks the longer run, minimax keeps both segments, the run is segment 1 */
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &BOX, &r), FT_OK);
    assert_near(r->D, 1.8, 1e-12);
    assert_int_equal(r->nsegments, 2);
    assert_int_equal(r->best, 1);
    ft_dim_result_free(r);

    /* the estimator's upper limit 32 (inclusive, whatever the last bits of the computed scale) leaves
     * only the -1.2 run */
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 32.0, NULL, &BOX, &r), FT_OK);
    assert_near(r->D, 1.2, 1e-12);
    assert_int_equal(r->fit.first, 0);
    assert_int_equal(r->fit.last, BREAK_ROW);
    assert_int_equal(r->nsegments, 1);
    for (int i = 0; i < TWO_RUN_ROWS; i++)
        assert_int_equal(r->table->rows[i].used, i <= BREAK_ROW);
    ft_dim_result_free(r);

    /* minimax method: D over the longest segment */
    ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
    o.method = FT_LOGLOG_MINIMAX;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_OK);
    assert_string_equal(r->method, "minimax");
    assert_int_equal(r->best, 1);
    assert_near(r->D, 1.8, 1e-12);
    assert_int_equal(r->fit.n, 8);
    ft_dim_result_free(r);
    ft_loglog_free(t);
}

/* A jump of 0.3 in log10 value between rows 5 and 6 (same slope on both sides): two disjoint
 * segments, no connector between them. */
static void test_step_gives_disjoint_segments(void **state)
{
    (void)state;
    ft_loglog *t = ft_loglog_create(0);
    for (int i = 0; i < 13; i++) {
        double x = 0.25 * i, y = 2.0 - 0.5 * x + (i >= 6 ? 0.3 : 0.0);
        assert_int_equal(ft_loglog_push(t, pow(10.0, x), pow(10.0, y), 0.0), FT_OK);
    }
    ft_loglog_segment *s = NULL;
    size_t n = 0;
    assert_int_equal(ft_loglog_segment_minimax(t, NULL, &SLOPE, &s, &n), FT_OK);
    assert_int_equal(n, 2);
    assert_int_equal(s[0].first, 0);
    assert_int_equal(s[0].last, 5);
    assert_int_equal(s[1].first, 6);
    assert_int_equal(s[1].last, 12);
    assert_near(s[0].slope, -0.5, 1e-12);
    assert_near(s[1].slope, -0.5, 1e-12);
    ft_loglog_segments_free(s);
    ft_loglog_free(t);
}

/* One segment through (0,0), (1,3), (3,6) in log10 space: the minimax line has slope 2 (parallel to
 * the chord of the outer points, y - 2x = 0, 1, 0), error 0.5; least squares: slope 27/14. */
static void test_minimax_line_by_hand(void **state)
{
    (void)state;
    ft_loglog *t = ft_loglog_create(3);
    assert_int_equal(ft_loglog_push(t, 1.0, 1.0, 0.0), FT_OK);
    assert_int_equal(ft_loglog_push(t, 10.0, 1000.0, 0.0), FT_OK);
    assert_int_equal(ft_loglog_push(t, 1000.0, 1e6, 0.0), FT_OK);
    ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
    o.width = 10.0;
    ft_loglog_segment *s = NULL;
    size_t n = 0;
    assert_int_equal(ft_loglog_segment_minimax(t, &o, &SLOPE, &s, &n), FT_OK);
    assert_int_equal(n, 1);
    assert_near(s[0].max_err, 0.5, 1e-12);
    assert_near(s[0].D_minimax, 2.0, 1e-12);
    /* x = 0 1 3, y = 0 3 6: xm = 4/3, ym = 3, Sxx = 14/3, Sxy = 9 -> slope 27/14 */
    assert_near(s[0].D, 27.0 / 14.0, 1e-12);
    ft_loglog_segments_free(s);
    ft_loglog_free(t);
}

/* An exact power law whose last row is 0.3 (log10) too high: ILS drops it, D stays exact. */
static void test_ils_drops_outlier(void **state)
{
    (void)state;
    ft_loglog *t = power_law(12, 1.0, -1.5);
    t->rows[11].value *= 2.0;
    ft_loglog_update_slopes(t);
    ft_dim_result *r = NULL;
    assert_int_equal(ft_loglog_segment_ils(t, NULL, &BOX, &r), FT_OK);
    assert_int_equal(r->fit.first, 0);
    assert_int_equal(r->fit.last, 10);
    assert_near(r->D, 1.5, 1e-12);
    assert_int_equal(r->table->rows[11].used, 0);
    ft_dim_result_free(r);
    ft_loglog_free(t);
}

/* y = 2 - 1.5 x + e, e ~ N(0, sigma) i.i.d., x evenly over [0, 3] (scales 1..1000). For the rows
 * actually used, the least-squares slope has sd sigma / sqrt(Sxx); D must lie within 4 sd of 1.5
 * (two-sided probability 6e-5 per seed). */
#define NOISY_ROWS 25
#define NOISE_SD 0.01
static ft_loglog *noisy_power_law(uint64_t seed, size_t n, double sd)
{
    ft_rng *g = ft_rng_create(seed, 7);
    assert_non_null(g);
    ft_loglog *t = ft_loglog_create(n);
    for (size_t i = 0; i < n; i++) {
        double x = 3.0 * (double)i / (double)(n - 1);
        double y = 2.0 - 1.5 * x + ft_rng_gaussian(g, sd);
        assert_int_equal(ft_loglog_push(t, pow(10.0, x), pow(10.0, y), 1.0), FT_OK);
    }
    ft_rng_free(g);
    return t;
}

static double slope_sd(const ft_loglog *t, size_t first, size_t last, double sd)
{
    double m = 0.0, sxx = 0.0;
    for (size_t i = first; i <= last; i++)
        m += log10(t->rows[i].scale);
    m /= (double)(last - first + 1);
    for (size_t i = first; i <= last; i++)
        sxx += (log10(t->rows[i].scale) - m) * (log10(t->rows[i].scale) - m);
    return sd / sqrt(sxx);
}

static void check_noisy(ft_loglog_method method)
{
    for (uint64_t seed = 1; seed <= 6; seed++) {
        ft_loglog *t = noisy_power_law(seed, NOISY_ROWS, NOISE_SD);
        ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
        o.method = method;
        ft_dim_result *r = NULL;
        assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_OK);
        double sd = slope_sd(t, r->fit.first, r->fit.last, NOISE_SD);
        assert_near(r->D, 1.5, 4.0 * sd);
        /* a straight table: the chosen run holds most of it */
        assert_true(r->fit.n >= NOISY_ROWS / 2);
        /* the reported standard error estimates the same sd (within a factor 2 at n >= 12) */
        assert_true(r->stderr_D > 0.5 * sd && r->stderr_D < 2.0 * sd);
        ft_dim_result_free(r);
        ft_loglog_free(t);
    }
}

static void test_noisy_power_law_ils(void **state)
{
    (void)state;
    check_noisy(FT_LOGLOG_ILS);
}

static void test_noisy_power_law_minimax(void **state)
{
    (void)state;
    check_noisy(FT_LOGLOG_MINIMAX);
}

/* The noise estimate follows sigma (400 rows: the MAD estimate has a relative sd near 6%) and ignores a
 * break in slope. */
static void test_noise_estimate(void **state)
{
    (void)state;
    for (uint64_t seed = 1; seed <= 3; seed++) {
        ft_loglog *t = noisy_power_law(seed, 400, 0.02);
        assert_near(ft_loglog_noise(t, 0, t->n - 1), 0.02, 0.2 * 0.02);
        ft_loglog_free(t);
    }
    ft_loglog *b = two_runs();
    assert_near(ft_loglog_noise(b, 0, b->n - 1), 0.0, 1e-12);
    assert_near(ft_loglog_noise(b, 0, 1), 0.0, 0.0);
    ft_loglog_free(b);
}

static void test_fit_range_marks_rows(void **state)
{
    (void)state;
    ft_loglog *t = power_law(10, 2.0, -1.5); /* scales 1 2 4 ... 512 */
    ft_dim_result *r = NULL;
    assert_int_equal(ft_loglog_fit_range(t, 3.0, 70.0, &BOX, &r), FT_OK);
    for (size_t i = 0; i < t->n; i++)
        assert_int_equal(r->table->rows[i].used, i >= 2 && i <= 6); /* 4 8 16 32 64 */
    assert_int_equal(r->fit.n, 5);
    assert_near(r->range[0], 4.0, 0.0);
    assert_near(r->range[1], 64.0, 0.0);
    assert_near(r->D, 1.5, 1e-12);
    assert_string_equal(r->method, "range");
    /* the caller's table is untouched */
    for (size_t i = 0; i < t->n; i++)
        assert_int_equal(t->rows[i].used, 0);
    ft_dim_result_free(r);

    /* limits on the rows themselves are inclusive; 0 = no limit */
    assert_int_equal(ft_loglog_fit_range(t, 4.0, 64.0, &BOX, &r), FT_OK);
    assert_int_equal(r->fit.n, 5);
    ft_dim_result_free(r);
    assert_int_equal(ft_loglog_fit_range(t, 0.0, 0.0, &BOX, &r), FT_OK);
    assert_int_equal(r->fit.n, 10);
    ft_dim_result_free(r);
    assert_int_equal(ft_loglog_fit_range(t, 100.0, 0.0, &BOX, &r), FT_OK);
    assert_int_equal(r->fit.first, 7);
    assert_int_equal(r->fit.n, 3);
    ft_dim_result_free(r);
    ft_loglog_free(t);
}

static void test_bad_tables(void **state)
{
    (void)state;
    ft_dim_result *r = (ft_dim_result *)&r;
    ft_loglog *t = ft_loglog_create(0);
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &BOX, &r), FT_E_EMPTY, "empty");
    assert_null(r);
    assert_error_names(ft_loglog_push(t, 0.0, 1.0, 0.0), FT_E_INVALID, "scale = 0");
    assert_error_names(ft_loglog_push(t, -2.0, 1.0, 0.0), FT_E_INVALID, "scale = -2");
    assert_error_names(ft_loglog_push(t, NAN, 1.0, 0.0), FT_E_NUMERIC, "scale = nan");
    assert_error_names(ft_loglog_push(t, 1.0, NAN, 0.0), FT_E_NUMERIC, "value = nan");
    assert_error_names(ft_loglog_push(t, 1.0, 0.0, 0.0), FT_E_INVALID, "value = 0");
    assert_error_names(ft_loglog_push(t, 1.0, INFINITY, 0.0), FT_E_NUMERIC, "value = inf");
    assert_error_names(ft_loglog_push(t, 1.0, 1.0, -1.0), FT_E_INVALID, "count = -1");
    assert_int_equal(t->n, 0);
    assert_int_equal(ft_loglog_push(t, 1.0, 1.0, 0.0), FT_OK);
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &BOX, &r), FT_E_INVALID, "at least 2 rows");
    ft_loglog_free(t);

    /* rows edited in place are checked by every fit */
    t = power_law(6, 1.0, -1.0);
    t->rows[3].scale = -1.0;
    assert_error_names(ft_loglog_fit_range(t, 0.0, 0.0, &BOX, &r), FT_E_INVALID, "row 3 scale = -1");
    t->rows[3].scale = 8.0;
    t->rows[4].value = NAN;
    assert_error_names(ft_loglog_segment_ils(t, NULL, &BOX, &r), FT_E_NUMERIC, "row 4 value = nan");
    t->rows[4].value = 1.0 / 16.0;
    t->rows[2].scale = 64.0;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &BOX, &r), FT_E_INVALID, "ft_loglog_sort");
    assert_null(r);
    ft_loglog_free(t);
}

static void test_bad_options(void **state)
{
    (void)state;
    ft_loglog *t = power_law(8, 1.0, -1.0);
    ft_dim_result *r = NULL;
    ft_loglog_segment *s = NULL;
    size_t n = 0;
    assert_error_names(ft_loglog_fit_range(t, 100.0, 10.0, &BOX, &r), FT_E_INVALID,
                       "100 is above upper scale limit 10");
    assert_error_names(ft_loglog_fit_auto(t, 100.0, 10.0, NULL, &BOX, &r), FT_E_INVALID, "100");
    assert_error_names(ft_loglog_fit_range(t, -1.0, 0.0, &BOX, &r), FT_E_INVALID, "got -1");
    assert_error_names(ft_loglog_fit_range(t, 0.0, NAN, &BOX, &r), FT_E_INVALID, "got nan");
    assert_error_names(ft_loglog_fit_range(t, 1000.0, 2000.0, &BOX, &r), FT_E_EMPTY, "0 row(s)");
    assert_error_names(ft_loglog_fit_range(t, 0.0, 0.0, NULL, &r), FT_E_INVALID, "map");
    const ft_dim_map flat = {1.0, 0.0, 0.0, 0.0};
    assert_error_names(ft_loglog_fit_range(t, 0.0, 0.0, &flat, &r), FT_E_INVALID, "b != 0");

    ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
    o.width = 0.0;
    assert_error_names(ft_loglog_segment_minimax(t, &o, &BOX, &s, &n), FT_E_INVALID, "width must be > 0");
    assert_null(s);
    o.width = -0.5;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_E_INVALID, "got -0.5");
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    o.tol = 0.0;
    assert_error_names(ft_loglog_segment_ils(t, &o, &BOX, &r), FT_E_INVALID, "tol must be > 0");
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    o.tol_sigma = -1.0;
    assert_error_names(ft_loglog_segment_ils(t, &o, &BOX, &r), FT_E_INVALID, "tol_sigma");
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    o.min_points = 1;
    assert_error_names(ft_loglog_segment_ils(t, &o, &BOX, &r), FT_E_INVALID, "min_points must be >= 2, got 1");
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    o.max_iter = 0;
    assert_error_names(ft_loglog_segment_ils(t, &o, &BOX, &r), FT_E_INVALID, "max_iter");
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    o.method = (ft_loglog_method)7;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_E_INVALID, "method 7");
    /* too few rows inside the limits for min_points */
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    assert_error_names(ft_loglog_fit_auto(t, 1.0, 2.0, &o, &BOX, &r), FT_E_EMPTY, "at least 3");
    assert_null(r);
    ft_loglog_free(t);
}

/* Zig-zag rows (alternating +-0.2 about a line) with absolute tolerances only: no three rows are
 * straight within 0.02, so both methods fail with a message naming the tolerance. */
static void test_no_straight_run(void **state)
{
    (void)state;
    ft_loglog *t = ft_loglog_create(0);
    for (int i = 0; i < 10; i++)
        assert_int_equal(ft_loglog_push(t, pow(10.0, 0.2 * i), pow(10.0, (i % 2 ? 0.2 : -0.2)), 0.0), FT_OK);
    ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
    o.tol_sigma = 0.0;
    o.method = FT_LOGLOG_ILS;
    ft_dim_result *r = NULL;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_E_NUMERIC, "0.02");
    o.method = FT_LOGLOG_MINIMAX;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_E_NUMERIC, "width 0.04");
    assert_null(r);
    ft_loglog_free(t);
}

/* A staircase about the trend D = 1.7 of a divider table (L ~ step^(1 - D), slope p = -0.7): K periods
 * of M rows, dx = 0.025 (log10) between rows, so a period spans P = M dx = 0.2 decades (a factor 1.58,
 * the lacunarity of a midpoint curve). Within a period the rows climb as a tread of slope +1 (length
 * proportional to the ruler, D = 0, as while a divider takes the same number of steps); between periods
 * the value drops so that the period's mean slope is p:
 *   y_i = p x_i + (1 - p) r dx,   x_i = i dx,   r = i mod M.
 * Least squares over all N = K M rows: x = dx (M j + r) with j, r independent and uniform, so
 * cov(x, r dx) = dx² var(r) and var(x) = dx² (M² var(j) + var(r)), var(r) = (M² - 1)/12,
 * var(j) = (K² - 1)/12, and the slope is p + (1 - p)(M² - 1)/(N² - 1): D = 1.7 - 1.7 (M² - 1)/(N² - 1). */
#define STAIR_M 8
#define STAIR_K 8
#define STAIR_DX 0.025
#define STAIR_D 1.7
static ft_loglog *staircase(void)
{
    const double p = 1.0 - STAIR_D;
    ft_loglog *t = ft_loglog_create(STAIR_M * STAIR_K);
    assert_non_null(t);
    for (int i = 0; i < STAIR_M * STAIR_K; i++) {
        double x = i * STAIR_DX, y = 1.0 + p * x + (1.0 - p) * (i % STAIR_M) * STAIR_DX;
        assert_int_equal(ft_loglog_push(t, pow(10.0, x), pow(10.0, y), 0.0), FT_OK);
    }
    return t;
}

static double staircase_ls_D(void)
{
    const double n = STAIR_M * STAIR_K, m = STAIR_M;
    return STAIR_D - STAIR_D * (m * m - 1.0) / (n * n - 1.0);
}

static void check_whole_range(const ft_dim_result *r, size_t rows)
{
    assert_string_equal(r->segmentation, FT_LOGLOG_WHOLE_RANGE);
    assert_non_null(ft_dim_result_find_warning(r, NULL));
    assert_non_null(ft_dim_result_find_warning(r, "whole range"));
    assert_int_equal(r->fit.first, 0);
    assert_int_equal(r->fit.n, rows);
    for (size_t i = 0; i < r->table->n; i++)
        assert_int_equal(r->table->rows[i].used, 1);
}

static void test_staircase_gives_trend(void **state)
{
    (void)state;
    ft_loglog *t = staircase();
    const ft_dim_map div = FT_DIM_MAP_DIVIDER, div_unbounded = {1.0, -1.0, 0.0, 0.0};
    const size_t n = STAIR_M * STAIR_K;
    ft_dim_result *r = NULL;

    /* the rule before min_span and bounds: the longest straight run is a tread, D = 0 exactly */
    ft_loglog_opts old = FT_LOGLOG_OPTS_DEFAULT, ils = FT_LOGLOG_OPTS_DEFAULT;
    old.min_span = 1.0;
    old.method = ils.method = FT_LOGLOG_ILS;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &old, &div_unbounded, &r), FT_OK);
    assert_near(r->D, 0.0, 1e-9);
    assert_int_equal(r->fit.n, STAIR_M);
    assert_string_equal(r->segmentation, "ils");
    ft_dim_result_free(r);

    /* default: the staircase has no curvature, so the whole table is one regime, its trend */
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &div, &r), FT_OK);
    assert_near(r->D, staircase_ls_D(), 1e-9);
    assert_int_equal(r->nregimes, 1);
    assert_int_equal(r->fit.n, n);
    assert_null(ft_dim_result_find_warning(r, "whole range"));
    ft_dim_result_free(r);

    /* ILS: no tread qualifies (a factor 10^(7 x 0.025) = 1.50 < 4, D = 0 outside [1, 2]); D is the
     * whole table's least-squares trend, flagged */
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &ils, &div, &r), FT_OK);
    assert_near(r->D, staircase_ls_D(), 1e-9);
    assert_near(r->D, STAIR_D, 0.03);
    check_whole_range(r, n);
    assert_int_equal(r->best, FT_LOGLOG_NONE);
    assert_true(r->nsegments >= STAIR_K); /* every tread is still reported as a minimax segment */
    for (size_t k = 0; k < r->nsegments; k++)
        if (r->segments[k].n >= 3)
            assert_near(r->segments[k].D, 0.0, 1e-9);
    ft_dim_result_free(r);

    /* each rule alone is enough here: bounds only, span only; and the minimax method alike */
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &old, &div, &r), FT_OK);
    assert_near(r->D, staircase_ls_D(), 1e-9);
    check_whole_range(r, n);
    ft_dim_result_free(r);
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &ils, &div_unbounded, &r), FT_OK);
    assert_near(r->D, staircase_ls_D(), 1e-9);
    check_whole_range(r, n);
    ft_dim_result_free(r);
    ft_loglog_opts mm = FT_LOGLOG_OPTS_DEFAULT;
    mm.method = FT_LOGLOG_MINIMAX;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &mm, &div, &r), FT_OK);
    assert_near(r->D, staircase_ls_D(), 1e-9);
    check_whole_range(r, n);
    ft_dim_result_free(r);
    ft_loglog_free(t);
}

/* Rows at 2^0 .. 2^14: a divider-style table with slope -0.3 (D = 1.3) up to 2^5 (rows 0..5, 6 rows, a
 * factor 32) and slope s_long from there on (rows 5..14, 10 rows, a factor 512). */
static ft_loglog *short_in_long_out(double s_long)
{
    ft_loglog *t = ft_loglog_create(15);
    double xb = 5.0 * log10(2.0);
    for (int i = 0; i < 15; i++) {
        double x = i * log10(2.0), y = x <= xb ? -0.3 * x : -0.3 * xb + s_long * (x - xb);
        assert_int_equal(ft_loglog_push(t, pow(10.0, x), pow(10.0, y), 0.0), FT_OK);
    }
    return t;
}

static void test_out_of_bounds_never_chosen(void **state)
{
    (void)state;
    const ft_dim_map div = FT_DIM_MAP_DIVIDER, div_unbounded = {1.0, -1.0, 0.0, 0.0};
    ft_loglog_opts mm = FT_LOGLOG_OPTS_DEFAULT, ils = FT_LOGLOG_OPTS_DEFAULT;
    mm.method = FT_LOGLOG_MINIMAX;
    ils.method = FT_LOGLOG_ILS;
    ft_dim_result *r = NULL;
    /* the long run has slope +0.5, D = 0.5: without bounds it wins, with them the short run (D = 1.3) */
    ft_loglog *t = short_in_long_out(0.5);
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &ils, &div_unbounded, &r), FT_OK);
    assert_near(r->D, 0.5, 1e-12);
    ft_dim_result_free(r);
    for (int method = 0; method < 2; method++) {
        assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, method ? &mm : &ils, &div, &r), FT_OK);
        assert_near(r->D, 1.3, 1e-12);
        assert_int_equal(r->fit.first, 0);
        assert_int_equal(r->fit.last, 5);
        assert_string_equal(r->segmentation, method ? "minimax" : "ils");
        assert_int_equal(r->nwarnings, 0);
        assert_int_equal(r->best, 0);
        ft_dim_result_free(r);
    }
    ft_loglog_free(t);

    /* D = 2.02 is within the tolerance 0.025 of [1, 2]: the long run wins, reported as D = 2 with a
     * warning; D = 2.1 is not */
    t = short_in_long_out(-1.02);
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &div, &r), FT_OK);
    assert_near(r->D, 2.0, 0.0);
    assert_non_null(ft_dim_result_find_warning(r, "D = 2.0200 estimated, 2 reported"));
    ft_dim_result_free(r);
    ft_loglog_free(t);
    t = short_in_long_out(-1.1);
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &div, &r), FT_OK);
    assert_near(r->D, 1.3, 1e-12);
    ft_dim_result_free(r);
    ft_loglog_opts wide = FT_LOGLOG_OPTS_DEFAULT;
    wide.bounds_tol = 0.2;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &wide, &div, &r), FT_OK);
    assert_near(r->D, 2.0, 0.0);
    assert_near(r->fit.slope, -1.1, 1e-12);
    ft_dim_result_free(r);
    ft_loglog_free(t);

    /* a power law whose D lies outside the bounds everywhere: an error, by every method and a user range */
    t = power_law(10, 1.0, 0.5); /* divider: D = 1 - 0.5 = 0.5 */
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &div, &r), FT_E_NUMERIC, "outside [1, 2]");
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &ils, &div, &r), FT_E_NUMERIC, "smoother than any");
    assert_error_names(ft_loglog_fit_range(t, 0.0, 0.0, &div, &r), FT_E_NUMERIC, "D = 0.5000");
    assert_null(r);
    ft_loglog_free(t);
}

/* An exact power law over a factor 2^1.75 = 3.4 (8 rows, 2^(i/4)): straight, but too short to assert a
 * power law under the default min_span 4; min_span 3 accepts it. */
static void test_short_window_flagged(void **state)
{
    (void)state;
    ft_loglog *t = ft_loglog_create(8);
    for (int i = 0; i < 8; i++) {
        double s = pow(2.0, i / 4.0);
        assert_int_equal(ft_loglog_push(t, s, pow(s, -1.25), 0.0), FT_OK);
    }
    ft_dim_result *r = NULL;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &BOX, &r), FT_OK);
    assert_near(r->D, 1.25, 1e-12);
    check_whole_range(r, 8);
    assert_non_null(ft_dim_result_find_warning(r, "factor of 4"));
    assert_int_equal(r->best, 0); /* the one minimax segment spans the whole window */
    ft_dim_result_free(r);
    ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
    o.min_span = 3.0;
    assert_int_equal(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_OK);
    assert_near(r->D, 1.25, 1e-12);
    assert_string_equal(r->segmentation, "regimes");
    assert_int_equal(r->nwarnings, 1);
    assert_non_null(ft_dim_result_find_warning(r, "narrow band"));
    ft_dim_result_free(r);
    ft_loglog_free(t);
}

static void test_bounds_options(void **state)
{
    (void)state;
    ft_loglog *t = power_law(8, 1.0, -1.5);
    ft_dim_result *r = NULL;
    ft_loglog_opts o = FT_LOGLOG_OPTS_DEFAULT;
    o.min_span = 0.5;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_E_INVALID, "min_span must be >= 1");
    o.min_span = NAN;
    assert_error_names(ft_loglog_segment_ils(t, &o, &BOX, &r), FT_E_INVALID, "min_span");
    o = (ft_loglog_opts)FT_LOGLOG_OPTS_DEFAULT;
    o.bounds_tol = -0.1;
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, &o, &BOX, &r), FT_E_INVALID, "bounds_tol must be >= 0");
    const ft_dim_map reversed = {0.0, -1.0, 2.0, 1.0}, half = {0.0, -1.0, 1.0, 1.0};
    assert_error_names(ft_loglog_fit_auto(t, 0.0, 0.0, NULL, &reversed, &r), FT_E_INVALID, "[2, 1]");
    assert_error_names(ft_loglog_fit_range(t, 0.0, 0.0, &half, &r), FT_E_INVALID, "d_min < d_max");
    assert_null(r);
    /* every estimator map carries its interval */
    const ft_dim_map maps[] = {FT_DIM_MAP_DIVIDER, FT_DIM_MAP_BOXCOUNT_LINE, FT_DIM_MAP_VARIOGRAM_PROFILE,
                               FT_DIM_MAP_INCREMENT_PROFILE, FT_DIM_MAP_SPECTRUM_PROFILE, FT_DIM_MAP_PRISM,
                               FT_DIM_MAP_BOXCOUNT_SURFACE, FT_DIM_MAP_VARIOGRAM_SURFACE,
                               FT_DIM_MAP_INCREMENT_SURFACE, FT_DIM_MAP_SPECTRUM_SURFACE, FT_DIM_MAP_BOXCOUNT};
    for (size_t i = 0; i < sizeof maps / sizeof maps[0]; i++) {
        double lo = i < 5 ? 1.0 : i < 10 ? 2.0 : 1.0, hi = i < 5 ? 2.0 : 3.0;
        assert_near(maps[i].d_min, lo, 0.0);
        assert_near(maps[i].d_max, hi, 0.0);
    }
    /* profile maps: H = 0.5 (D = 1.5) as gamma ~ lag^1, E|dz| ~ d^0.5, P(f) ~ f^-2 */
    assert_near(maps[2].a + maps[2].b * 1.0, 1.5, 1e-15);
    assert_near(maps[3].a + maps[3].b * 0.5, 1.5, 1e-15);
    assert_near(maps[4].a + maps[4].b * -2.0, 1.5, 1e-15);
    ft_loglog_free(t);
}

static void test_free_null(void **state)
{
    (void)state;
    ft_loglog_free(NULL);
    ft_dim_result_free(NULL);
    ft_loglog_segments_free(NULL);
    ft_loglog_update_slopes(NULL);
    assert_null(ft_loglog_copy(NULL));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_exact_power_law),
        cmocka_unit_test(test_local_slopes),
        cmocka_unit_test(test_two_runs_minimax),
        cmocka_unit_test(test_two_runs_ils),
        cmocka_unit_test(test_step_gives_disjoint_segments),
        cmocka_unit_test(test_minimax_line_by_hand),
        cmocka_unit_test(test_ils_drops_outlier),
        cmocka_unit_test(test_noisy_power_law_ils),
        cmocka_unit_test(test_noisy_power_law_minimax),
        cmocka_unit_test(test_noise_estimate),
        cmocka_unit_test(test_fit_range_marks_rows),
        cmocka_unit_test(test_bad_tables),
        cmocka_unit_test(test_bad_options),
        cmocka_unit_test(test_no_straight_run),
        cmocka_unit_test(test_staircase_gives_trend),
        cmocka_unit_test(test_out_of_bounds_never_chosen),
        cmocka_unit_test(test_short_window_flagged),
        cmocka_unit_test(test_bounds_options),
        cmocka_unit_test(test_free_null),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
