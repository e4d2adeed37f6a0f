/* fracterra — tests/support/ft_test_run.h: running the built `fracterra` binary from end-to-end tests.
 *
 * ft_run() forks and execs FT_BIN (no shell) with the given arguments, captures stdout and stderr and the
 * exit status; helpers make and remove temporary folders, write small fixture files and parse stdout as
 * one JSON object.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FT_TEST_RUN_H
#define FT_TEST_RUN_H

#include <json-c/json.h>
#include <stddef.h>

typedef struct {
    int status;     /**< exit code; 128 + signal number if the process was killed by a signal */
    int signaled;   /**< 1 if it died from a signal (a crash) */
    char *out;      /**< captured stdout, NUL-terminated */
    size_t out_len;
    char *err;      /**< captured stderr, NUL-terminated */
    size_t err_len;
} ft_run_result;

/** Runs FT_BIN with argv (NULL-terminated, not including the program). 0 if it ran, -1 if it could not
 *  be started. Free the result with ft_run_free. */
int ft_run_argv(ft_run_result *r, const char *const *argv);
/** Same with the arguments as a NULL-terminated list: ft_run(&r, "info", path, NULL). */
int ft_run(ft_run_result *r, ...);
void ft_run_free(ft_run_result *r);

/** stdout parsed as exactly one JSON object (NULL if it is not); release with json_object_put. */
json_object *ft_run_json(const ft_run_result *r);

/** A new empty folder /tmp/fracterra-test-XXXXXX (malloc'd path), or NULL. */
char *ft_test_mkdtemp(void);
/** Removes a folder and everything in it. */
void ft_test_rmtree(const char *dir);
/** malloc'd "dir/name". */
char *ft_test_path(const char *dir, const char *name);
/** Writes size bytes to path; 0 on success. */
int ft_test_write_file(const char *path, const void *data, size_t size);
/** Writes a NUL-terminated string to path; 0 on success. */
int ft_test_write_text(const char *path, const char *text);
/** Reads a whole file (malloc'd, NUL-terminated; *size may be NULL), or NULL. */
char *ft_test_read_file(const char *path, size_t *size);
/** 1 if path exists. */
int ft_test_exists(const char *path);
/** Number of entries in a folder (not counting . and ..), -1 if it cannot be read. */
int ft_test_count_entries(const char *dir);

#endif /* FT_TEST_RUN_H */
