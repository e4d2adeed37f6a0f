/* fracterra — tests/unit/test_io_gdal_handler.c: fracterra is a polite GDAL guest. A host program that
 * installs its own GDAL error handler (process-wide with CPLSetErrorHandlerEx, or on its thread's stack with
 * CPLPushErrorHandlerEx) keeps it across fracterra's io calls, failed or not. The choice documented in io.h:
 * GDAL's failures and warnings raised inside a fracterra call are caught and returned in ft_last_error(), so
 * the host's handler receives none of them; CPL_DEBUG messages pass through to it.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <cpl_conv.h>
#include <cpl_error.h>

#include "fracterra/core.h"
#include "fracterra/io.h"
#include "ft_test_util.h"

/* What the host's handler received. */
typedef struct {
    int failures; /* CE_Failure and CE_Fatal */
    int warnings;
    int debug;
    char last[256];
} host_log;

static void CPL_STDCALL host_handler(CPLErr cls, CPLErrorNum num, const char *msg)
{
    (void)num;
    host_log *log = CPLGetErrorHandlerUserData();
    if (cls == CE_Debug)
        log->debug++;
    else if (cls == CE_Warning)
        log->warnings++;
    else if (cls >= CE_Failure)
        log->failures++;
    snprintf(log->last, sizeof log->last, "%s", msg ? msg : "");
}

/* A file named .tif whose TIFF header points at a directory that is not there: GTiff raises a failure. */
static const char *broken_tiff(void)
{
    const char *path = ft_test_tmp("broken.tif");
    static const unsigned char bytes[] = {'I', 'I', 42, 0, 0x00, 0x10, 0, 0, 'x', 'y', 'z', 0};
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    assert_int_equal(fwrite(bytes, 1, sizeof bytes, f), sizeof bytes);
    assert_int_equal(fclose(f), 0);
    return path;
}

/* fracterra calls that make GDAL raise failures, then ones that succeed; none may reach the host. */
static void run_fracterra_calls(void)
{
    ft_grid *g = NULL;
    assert_int_equal(ft_io_read_grid(broken_tiff(), NULL, &g), FT_E_FORMAT);
    assert_null(g);
    char *wkt = NULL;
    assert_int_not_equal(ft_io_crs_to_wkt("EPSG:999999", &wkt), FT_OK);
    /* GDAL's own reason reached fracterra's message: the library's handler was the one called. */
    assert_non_null(strstr(ft_last_error(), "999999"));
    assert_null(wkt);

    g = ft_grid_create(4, 3);
    assert_non_null(g);
    const char *out = ft_test_tmp("ok.tif");
    assert_int_equal(ft_io_write_grid(out, g, NULL), FT_OK);
    ft_grid_free(g);
    g = NULL;
    assert_int_equal(ft_io_read_grid(out, NULL, &g), FT_OK);
    assert_int_equal(g->nx, 4);
    ft_grid_free(g);
    assert_int_equal(ft_io_crs_to_wkt("EPSG:4326", &wkt), FT_OK);
    free(wkt);
}

/* The host's handler still gets what the host itself raises after fracterra's calls. */
static void assert_host_handler_in_place(host_log *log)
{
    int before = log->warnings;
    CPLError(CE_Warning, CPLE_AppDefined, "raised by the host");
    assert_int_equal(log->warnings, before + 1);
    assert_string_equal(log->last, "raised by the host");
}

static void test_process_wide_handler_is_kept(void **state)
{
    (void)state;
    host_log log = {0};
    CPLErrorHandler prev = CPLSetErrorHandlerEx(host_handler, &log);
    run_fracterra_calls();
    assert_int_equal(log.failures, 0);
    assert_int_equal(log.warnings, 0);
    assert_host_handler_in_place(&log);
    CPLSetErrorHandlerEx(prev, NULL);
}

static void test_pushed_handler_is_kept(void **state)
{
    (void)state;
    host_log log = {0};
    CPLPushErrorHandlerEx(host_handler, &log);
    run_fracterra_calls();
    assert_int_equal(log.failures, 0);
    assert_int_equal(log.warnings, 0);
    assert_host_handler_in_place(&log);
    CPLPopErrorHandler();
}

/* The same holds when the failure is fracterra's own (a missing file: GDAL is never asked). */
static void test_missing_file_leaves_handler(void **state)
{
    (void)state;
    host_log log = {0};
    CPLPushErrorHandlerEx(host_handler, &log);
    ft_layer *l = NULL;
    assert_int_equal(ft_io_read_layer(ft_test_tmp("absent.geojson"), NULL, &l), FT_E_IO);
    assert_host_handler_in_place(&log);
    assert_int_equal(log.failures, 0);
    CPLPopErrorHandler();
}

/* Debug messages are not fracterra's to keep: with CPL_DEBUG on, the host sees GDAL's debug output of a
 * fracterra call, and still none of its failures. */
static void test_debug_messages_reach_host(void **state)
{
    (void)state;
    host_log log = {0};
    CPLSetThreadLocalConfigOption("CPL_DEBUG", "ON");
    CPLPushErrorHandlerEx(host_handler, &log);
    ft_grid *g = NULL;
    assert_int_equal(ft_io_read_grid(broken_tiff(), NULL, &g), FT_E_FORMAT);
    g = ft_grid_create(4, 3);
    assert_non_null(g);
    assert_int_equal(ft_io_write_grid(ft_test_tmp("debug.tif"), g, NULL), FT_OK);
    ft_grid_free(g);
    CPLPopErrorHandler();
    CPLSetThreadLocalConfigOption("CPL_DEBUG", NULL);
    assert_true(log.debug > 0);
    assert_int_equal(log.failures, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_process_wide_handler_is_kept),
        cmocka_unit_test(test_pushed_handler_is_kept),
        cmocka_unit_test(test_missing_file_leaves_handler),
        cmocka_unit_test(test_debug_messages_reach_host),
    };
    return FT_TEST_RUN_IO(tests, FT_TEST_DIR_SHARED);
}
