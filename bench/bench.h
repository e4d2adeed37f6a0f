/* fracterra — bench.h: the `make bench` harness's workload registry.
 *
 * A workload is one named piece of work (read a 4096² GeoTIFF, run `fracterra info` on a 1M-vertex line).
 * The harness runs each workload N times, every repetition in its own forked child, and reports the
 * median wall time, the throughput in the workload's unit and the child's peak resident memory
 * (wait4 ru_maxrss); when a peer tool (GDAL, GRASS GIS, GEOS command-line tools) doing the same work is
 * on PATH it is run the same way and the ratio ours/peer is printed.
 *
 * Adding a domain: write bench/workloads_<domain>.c with a static table of ft_bench_workload and one
 * `const ft_bench_suite ft_bench_suite_<domain>`, declare it below and add it to the list in harness.c.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_BENCH_H
#define FRACTERRA_BENCH_H

#include <stddef.h>

/** What a workload's throughput counts. */
typedef enum {
    FT_BENCH_CELLS = 0,    /**< grid cells, printed as Mcells/s */
    FT_BENCH_VERTICES = 1, /**< chain vertices, printed as Mvertices/s */
    FT_BENCH_BYTES = 2     /**< bytes, printed as MB/s */
} ft_bench_unit;

#define FT_BENCH_MAX_ARGV 24

/** One workload's run-time data, filled by its setup (in the harness process). Strings in argv and
 *  peer_argv are malloc'd (ft_bench_strdup/ft_bench_strf) and freed by the harness. */
typedef struct ft_bench_case {
    void *state;                         /**< private to the workload; released by its teardown */
    double work;                         /**< amount of work of one repetition, in the workload's unit;
                                              run() may correct it (the child's value is reported) */
    char *argv[FT_BENCH_MAX_ARGV];       /**< command workloads: our command line, argv[0] a path */
    char *peer_argv[FT_BENCH_MAX_ARGV];  /**< the peer's command line; peer_argv[0] == NULL: no peer */
    const char *peer_none;               /**< why there is no peer (printed when peer_argv[0] is NULL) */
    char *scratch;                       /**< an output path removed after every repetition, or NULL */
    /** An in-process peer (a library doing the same work, e.g. GEOS), used when peer_argv[0] is NULL:
     *  peer_prepare (untimed, may be NULL) and peer_run (timed) run in a forked child, like prepare and
     *  run; peer_label (static) describes it in the report. */
    int (*peer_prepare)(struct ft_bench_case *c);
    int (*peer_run)(struct ft_bench_case *c);
    const char *peer_label;
    int min_repeat; /**< at least this many repetitions of ours and of the peer (0: the --repeat count),
                         for a row whose spread matters (each row prints min, median and max) */
} ft_bench_case;

typedef struct {
    const char *name;      /**< "<domain>.<object>.<verb>", e.g. "io.geotiff.read" */
    const char *summary;   /**< one line: what one repetition does */
    ft_bench_unit unit;
    /** In the harness process, once, before the repetitions. Keep it light: generate heavy inputs with
     *  ft_bench_in_child so the harness (and so every child's starting memory) stays small. */
    int (*setup)(ft_bench_case *c);
    /** In the forked child, untimed, before run (e.g. load what is to be written). May be NULL. */
    int (*prepare)(ft_bench_case *c);
    /** In the forked child, timed. NULL for a command workload: then argv is executed and timed. Returns
     *  0 or a negative FT_E_* code with ft_last_error() set. */
    int (*run)(ft_bench_case *c);
    /** In the harness process, once, after the repetitions. May be NULL. */
    void (*teardown)(ft_bench_case *c);
} ft_bench_workload;

typedef struct {
    const char *domain;                   /**< "io" */
    const ft_bench_workload *workloads;
    size_t count;
} ft_bench_suite;

/* The suites, one per bench/workloads_<domain>.c; harness.c lists them. */
extern const ft_bench_suite ft_bench_suite_io;
extern const ft_bench_suite ft_bench_suite_terrain;
extern const ft_bench_suite ft_bench_suite_clarke;
extern const ft_bench_suite ft_bench_suite_line_dim;
extern const ft_bench_suite ft_bench_suite_line_enhance;
extern const ft_bench_suite ft_bench_suite_surface;
extern const ft_bench_suite ft_bench_suite_urban;
extern const ft_bench_suite ft_bench_suite_points;
extern const ft_bench_suite ft_bench_suite_reconstruct;
extern const ft_bench_suite ft_bench_suite_fill;
extern const ft_bench_suite ft_bench_suite_contour;
extern const ft_bench_suite ft_bench_suite_tiles;

/* ------------------------------------------------------------------------------------------------
 * Helpers the harness offers to workloads
 * --------------------------------------------------------------------------------------------- */

/** The bench's temporary folder (created on first use under $FT_BENCH_DIR or /tmp), NULL on failure. */
const char *ft_bench_dir(void);
/** A malloc'd path "<bench dir>/<name>", registered for removal (with any "<path>.aux.xml") when the
 *  harness exits, also on SIGINT/SIGTERM. NULL on failure. */
char *ft_bench_path(const char *name);
/** The built `fracterra` program beside this harness (found through /proc/self/exe), NULL if absent. */
const char *ft_bench_fracterra_program(void);
/** Runs fn(arg) in a forked child and waits: heavy input generation does not grow the harness.
 *  Returns fn's result (0 or a negative code); the child's error message is printed to stderr. */
int ft_bench_in_child(int (*fn)(void *arg), void *arg);
/** malloc'd copies (abort-free: NULL if out of memory). */
char *ft_bench_strdup(const char *s);
char *ft_bench_strf(const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 1, 2)))
#endif
    ;

#endif /* FRACTERRA_BENCH_H */
