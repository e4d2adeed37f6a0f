/* fracterra — tests/support/ft_test_util.h: one temporary folder per test program (cmocka setup, teardown
 * and between-tests emptying), paths in it, and assertions shared by the tests: files written, CRS
 * compared through OGR, chains and layers compared vertex for vertex, members of JSON objects.
 *
 * The folder is either the whole group's (ft_test_dir_setup / ft_test_dir_teardown given to
 * cmocka_run_group_tests, ft_test_dir_empty as each test's teardown) or each test's own
 * (cmocka_unit_test_setup_teardown(test, ft_test_dir_setup, ft_test_dir_teardown), FT_TEST_OWN_DIR);
 * FT_TEST_RUN_IO runs a whole group either way. Include <cmocka.h> before this header.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_UTIL_H
#define FT_TEST_UTIL_H

#include <stddef.h>
#include <stdint.h>

#include "fracterra/core.h"
#include "ft_test_run.h"

/** cmocka setup: makes a new empty folder /tmp/fracterra-test-XXXXXX. -1 if it cannot. */
int ft_test_dir_setup(void **state);
/** cmocka teardown: removes the folder and everything in it. -1 if it is still there. */
int ft_test_dir_teardown(void **state);
/** cmocka teardown between the tests of a group: removes everything in the folder. -1 if not emptied. */
int ft_test_dir_empty(void **state);

/** A cmocka test run in a folder of its own, made before and removed after it. */
#define FT_TEST_OWN_DIR(f) cmocka_unit_test_setup_teardown(f, ft_test_dir_setup, ft_test_dir_teardown)

struct CMUnitTest;

typedef enum {
    FT_TEST_DIR_SHARED, /**< one folder for the group, emptied after each test */
    FT_TEST_DIR_EACH    /**< a new folder for each test, removed after it */
} ft_test_dir_mode;

/** Runs the cmocka group tests[0..n) between ft_io_init() and ft_io_cleanup(), each test in the temporary
 *  folder as mode says. The tests must have no setup or teardown of their own (-1 if one has).
 *  Returns the number of tests that failed. */
int ft_test_run_io_group(const char *name, const struct CMUnitTest *tests, size_t n, ft_test_dir_mode mode);
/** ft_test_run_io_group on an array, named after it like cmocka_run_group_tests. */
#define FT_TEST_RUN_IO(tests, mode) ft_test_run_io_group(#tests, tests, sizeof(tests) / sizeof((tests)[0]), mode)

/** The folder made by ft_test_dir_setup. */
const char *ft_test_dir(void);
/** "folder/name" in one of 8 static buffers that are reused in turn (no need to free). */
const char *ft_test_tmp(const char *name);
/** Number of entries in the folder; fails the test if it cannot be read. */
int ft_test_dir_count(void);

/** Writes text to path; fails the test if it cannot. */
void ft_test_put_text(const char *path, const char *text);
/** Writes text to ft_test_tmp(name) and returns that path. */
const char *ft_test_tmp_text(const char *name, const char *text);

/** Reads an SVG file (malloc'd, NUL-terminated; *size may be NULL); fails the test unless it starts with
 *  "<?xml" and holds "<svg" and "</svg>". */
char *ft_test_read_svg(const char *path, size_t *size);

/** wkt is not NULL and is the same CRS as EPSG:epsg (OSRIsSame). */
void ft_test_assert_crs_epsg(const char *wkt, int epsg);
/** Both CRS are given (WKT or any OSRSetFromUserInput form) and are the same (OSRIsSame). */
void ft_test_assert_same_crs(const char *crs1, const char *crs2);

/** Same number of vertices, same closed flag, the same coordinates exactly. */
void ft_test_assert_chain_equal(const ft_chain *a, const ft_chain *b);
/** Same number of parts, each part's chain equal (ft_test_assert_chain_equal). */
void ft_test_assert_layer_chains_equal(const ft_layer *a, const ft_layer *b);

/** Member k of the JSON object o (NULL for a JSON null); fails the test if o has no member k. */
json_object *ft_test_json_key(json_object *o, const char *k);
/** Member k of o as an integer (ft_test_json_key). */
int64_t ft_test_json_int(json_object *o, const char *k);
/** Member k of o as a string (ft_test_json_key). */
const char *ft_test_json_str(json_object *o, const char *k);

/** Member k of o as a double (ft_test_json_key). */
double ft_test_json_num(json_object *o, const char *k);
/** Reads the layer at path with the default options; prints the error and fails the test if it cannot. */
ft_layer *ft_test_read_layer(const char *path);
/** Reads band (1-based) of the raster at path; prints the error and fails the test if it cannot. */
ft_grid *ft_test_read_band(const char *path, int band);

/** Element i of the JSON array a; fails the test unless i < its length. */
json_object *ft_test_json_at(json_object *a, size_t i);

/** Runs FT_BIN with argv (NULL-terminated), expects exit 0 and returns stdout as one JSON object (release
 *  with json_object_put); prints stderr and fails the test if not. */
json_object *ft_test_run_json(const char *const *argv);
/** ft_test_run_json on a list of arguments: FT_TEST_RUN_JSON("info", "--json", path). */
#define FT_TEST_RUN_JSON(...) ft_test_run_json((const char *const[]){__VA_ARGS__, NULL})
/** Runs FT_BIN with argv and fails the test unless it exits with code (not from a signal), writes nothing
 *  to stdout, and its stderr starts with "fracterra: PREFIX: " (prefix: the command, or "dim line") and
 *  holds needle. */
void ft_test_expect_failure(int code, const char *prefix, const char *needle, const char *const *argv);
/** ft_test_expect_failure on a list of arguments. */
#define FT_TEST_EXPECT_FAILURE(code, prefix, needle, ...)                                                      \
    ft_test_expect_failure(code, prefix, needle, (const char *const[]){__VA_ARGS__, NULL})

#endif /* FT_TEST_UTIL_H */
