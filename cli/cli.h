/* fracterra — cli/cli.h: what every command shares: its description, option parsing, error and warning
 * printing in the form "fracterra: COMMAND: message", exit codes, JSON output, progress, CRS labels.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_H
#define FRACTERRA_CLI_H

#include <getopt.h>
#include <json-c/json.h>
#include <stddef.h>
#include <stdio.h>

#include "fracterra/fracterra.h"

/* Exit codes, and CLI_CONTINUE for "parsing went fine, go on". */
enum { CLI_OK = 0, CLI_FAIL = 1, CLI_USAGE = 2, CLI_CONTINUE = -1 };

typedef struct cli_command {
    const char *name;    /**< "info" */
    const char *summary; /**< one line for `fracterra --help` */
    const char *usage;   /**< "fracterra info FILE [--layer NAME] [--band N] [--json]" */
    const char *help;    /**< description, options and at least one example */
    int (*run)(const struct cli_command *cmd, int argc, char **argv); /**< argv[0] is the command name */
} cli_command;

/* The commands (one cmd_<name>.c each), listed in fracterra.c's dispatch table. */
extern const cli_command cli_cmd_info;
extern const cli_command cli_cmd_demo;
extern const cli_command cli_cmd_synth;     /* terrain */
extern const cli_command cli_cmd_model;
extern const cli_command cli_cmd_reconstruct; /* reconstruction */
extern const cli_command cli_cmd_fill;        /* void filling */
extern const cli_command cli_cmd_mountain;    /* contour mountain */
extern const cli_command cli_cmd_hillshade;
extern const cli_command cli_cmd_render;
extern const cli_command cli_cmd_dim;
extern const cli_command cli_cmd_enhance;
extern const cli_command cli_cmd_simplify;
extern const cli_command cli_cmd_weed;
extern const cli_command cli_cmd_smooth;
extern const cli_command cli_cmd_urban;     /* urban morphology, with its subcommands */
extern const cli_command cli_cmd_urban_table;
extern const cli_command cli_cmd_urban_regress;
extern const cli_command cli_cmd_boundary;
/* The subcommands of `fracterra dim` (cmd_dim_<name>.c), listed in cmd_dim.c's table. */
extern const cli_command cli_cmd_dim_line;
extern const cli_command cli_cmd_dim_surface;
extern const cli_command cli_cmd_dim_profile;
extern const cli_command cli_cmd_dim_map;
extern const cli_command cli_cmd_dim_area;
extern const cli_command cli_cmd_dim_points;

/** Sets up output conventions (JSON number format) and the Ctrl-C handler; called once by main. */
void cli_init(void);

/* ---- messages (stderr) ---- */

/** "fracterra: CMD: message". */
void cli_error(const cli_command *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/** "fracterra: CMD: warning: message". */
void cli_warn(const cli_command *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/** Prints the library's last error for cmd and returns CLI_FAIL. */
int cli_fail(const cli_command *cmd);
/** Prints a usage error, the usage line and a hint to --help; returns CLI_USAGE. */
int cli_usage_error(const cli_command *cmd, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/** Prints the command's full help on stdout. */
void cli_print_help(const cli_command *cmd);

/* ---- options ---- */

/** Every command's long options include this entry (handled by cli_parse_options). */
#define CLI_OPT_HELP {"help", no_argument, NULL, 'h'}
#define CLI_OPT_END {NULL, 0, NULL, 0}

/** Called for each option other than --help; returns CLI_CONTINUE or an exit code. */
typedef int (*cli_opt_fn)(const cli_command *cmd, int opt, const char *arg, void *ctx);

/** getopt_long over argv (argv[0] = command name), with "-h"/"--help" built in and getopt's own messages
 *  replaced by "fracterra: CMD: ..." ones. Returns CLI_CONTINUE with *first_arg set to the index of the
 *  first positional argument, CLI_OK after printing the help, or CLI_USAGE (message printed). */
int cli_parse_options(const cli_command *cmd, int argc, char **argv, const struct option *longopts,
                      const char *shortopts, cli_opt_fn fn, void *ctx, int *first_arg);
/** Parses an integer option value in [min, max]: CLI_CONTINUE, or CLI_USAGE naming the option. */
int cli_parse_int(const cli_command *cmd, const char *option, const char *arg, long min, long max, int *out);
/* Flags of cli_parse_double: open ends of the interval, and "inf" accepted as a value. */
enum { CLI_CLOSED = 0, CLI_OPEN_LO = 1, CLI_OPEN_HI = 2, CLI_ALLOW_INF = 4 };
/** Parses a number option value in the interval lo..hi (ends closed unless flagged open; hi may be INFINITY):
 *  CLI_CONTINUE, or CLI_USAGE naming the option, the interval and the value. NaN is always refused. */
int cli_parse_double(const cli_command *cmd, const char *option, const char *arg, double lo, double hi, int flags,
                     double *out);
/** Runs `fracterra CMD SUBCOMMAND ...`: the entry of subs whose name ends in argv[1] ("dim line" for "line"), with
 *  argv shifted so that its argv[0] is the subcommand; "--help" prints cmd's help; a missing or unknown
 *  subcommand, or an option before it, is a usage error. */
int cli_run_subcommand(const cli_command *cmd, const cli_command *const *subs, size_t n, int argc, char **argv);
/** Checks that there are exactly n positional arguments, named in names (for the messages). Returns
 *  CLI_CONTINUE or CLI_USAGE. */
int cli_expect_args(const cli_command *cmd, int argc, char **argv, int first, const char *const *names, int n);

/** Refuses (CLI_FAIL, message printed) a grid whose measurement would exceed the work bound: cells × levels,
 *  levels = log2 of its longer side (the scales an estimator or a pyramid visits). CLI_CONTINUE otherwise. */
int cli_check_grid_work(const cli_command *cmd, const char *path, const ft_grid *g);

/* ---- output ---- */

/** Refuses (CLI_USAGE, before any work) an output that is the same file as an input (ft_io_same_file):
 *  what names the output ("OUT", "--dem", ...) and the NULL-terminated list of input paths (NULL entries
 *  before the end may be skipped by passing "" instead). CLI_CONTINUE otherwise; out may be NULL. */
int cli_refuse_overwrite(const cli_command *cmd, const char *what, const char *out, ...);

/** Prints o pretty-printed on stdout, then releases it. CLI_OK, or CLI_FAIL if stdout cannot be written. */
int cli_print_json(const cli_command *cmd, json_object *o);
/** Writes o as pretty JSON (the format --json prints) followed by a newline; FT_OK or FT_E_IO. */
int cli_json_fput(json_object *o, FILE *f);
/** Writes path through fn(f, arg) under a temporary name beside it, renamed when complete; nothing is left
 *  behind on failure. FT_OK, or an FT_E_* code with ft_error naming path. */
typedef int (*cli_write_fn)(FILE *f, const void *arg);
int cli_write_file(const char *path, cli_write_fn fn, const void *arg);
/** A JSON number, or null when v is not finite (JSON has no NaN). */
json_object *cli_json_double(double v);
/** A progress callback: GDALTermProgress's bar when stderr is a terminal, silent otherwise (pipes and logs);
 *  both return 0 (stop) once Ctrl-C or TERM was received, so that the work unwinds without output. */
ft_progress_fn cli_progress(void);
/** 1 once Ctrl-C (SIGINT) or SIGTERM was received (cli_init installs the handler). */
int cli_interrupted(void);

/* ---- shared with other commands ---- */

/** What `fracterra info` reports about a file, as a JSON object (see cmd_info.c); warnings (all-nodata
 *  grid, short chains) go into its "warnings" array. layer may be NULL; band 0 means the default band. */
int cli_info_describe(const char *path, const char *layer, int band, json_object **out);
/** Reads the lines and polygons of a vector layer or GMT text file as the line commands do (layer and where
 *  may be NULL) and checks the coordinates are finite: CLI_CONTINUE, CLI_USAGE for a bad --where filter,
 *  CLI_FAIL otherwise (message printed). */
int cli_read_layer(const cli_command *cmd, const char *path, const char *layer, const char *where, ft_layer **out);

#endif /* FRACTERRA_CLI_H */
