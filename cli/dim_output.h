/* fracterra — cli/dim_output.h: what every dimension estimator command shares (`dim line` now; areas,
 * surfaces and points later): the scale options (--min-scale --max-scale --scales --segments --plot
 * --json), and one printer of ft_dim_result sets, as JSON (DESIGN.md "JSON results") or a short table,
 * with the log-log plots of --plot.
 *
 * A command collects its results in a cli_dim_report: one group for the whole input, or one group per
 * feature (or value of --by FIELD), each holding one result per method. The JSON is then
 *   one group, one method:       { extra..., group info..., "method", "D", "r2", "stderr", "range", "segmentation",
 *                                  "max_err", "choice", "regime", "regimes", "breaks", "units", "warnings",
 *                                  "table" }
 *   one group, several methods:  { extra..., group info..., "results": [ {...}, ... ] }
 *   feature groups:              { extra..., "features": [ {"id": ..., group info..., result or "results"} ] }
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_DIM_OUTPUT_H
#define FRACTERRA_CLI_DIM_OUTPUT_H

#include "cli.h"

/* The scale and output options of an estimator command. */
typedef struct {
    double min_scale, max_scale; /**< 0 = automatic */
    int nscales;                 /**< 0 = the estimator's default */
    int segments;                /**< --segments: report (and plot) every linear segment of the log-log table */
    const char *plot;            /**< --plot FILE (.svg, .png, .pdf) or NULL */
    int json;                    /**< --json */
    int regime;                  /**< --regime N: D from the N-th regime (by increasing scale); 0 = the widest */
} cli_dim_opts;
#define CLI_DIM_OPTS_DEFAULT {0.0, 0.0, 0, 0, NULL, 0, 0}

/* getopt values of the shared options (--json is 'j'). */
enum {
    CLI_DIM_OPT_MIN_SCALE = 0x100,
    CLI_DIM_OPT_MAX_SCALE,
    CLI_DIM_OPT_SCALES,
    CLI_DIM_OPT_SEGMENTS,
    CLI_DIM_OPT_PLOT,
    CLI_DIM_OPT_REGIME,
};
#define CLI_DIM_LONGOPTS                                                                                     \
    {"min-scale", required_argument, NULL, CLI_DIM_OPT_MIN_SCALE},                                           \
        {"max-scale", required_argument, NULL, CLI_DIM_OPT_MAX_SCALE},                                       \
        {"scales", required_argument, NULL, CLI_DIM_OPT_SCALES},                                             \
        {"segments", no_argument, NULL, CLI_DIM_OPT_SEGMENTS}, {"plot", required_argument, NULL, CLI_DIM_OPT_PLOT}, \
        {"regime", required_argument, NULL, CLI_DIM_OPT_REGIME}, {"json", no_argument, NULL, 'j'}
#define CLI_DIM_SHORTOPTS "j"
#define CLI_DIM_MAX_SCALES 1000
/* Their help text, for the commands' own. */
#define CLI_DIM_OPTIONS_HELP                                                                                 \
    "      --min-scale S    smallest scale (ruler, box side) in the CRS's unit, metres for lon/lat data\n"     \
    "                       (measured on the ellipsoid or in a local projection); default: from the data\n"     \
    "      --max-scale S    largest scale, same unit; default: from the extent\n"                               \
    "      --scales N       scales in the geometric series between them (3..1000); default: the method's\n"     \
    "      --regime N       D from the N-th regime (straight run, by increasing scale); default: the widest\n"  \
    "      --segments       also report every straight segment of the log-log plot (minimax polyline)\n"       \
    "      --plot FILE      draw the log-log plot to FILE.svg, .png or .pdf (several results: FILE-ID-METHOD.ext)\n" \
    "  -j, --json           print one JSON object: method, D, r2, stderr, range, units, regimes, breaks,\n"     \
    "                       warnings, table (and segments)\n"

/** --noise-sigma Z (or XY,Z when allow_xy): standard deviations of the noise on z and on x, y (xy = 0 when
 *  only Z is given). CLI_CONTINUE or CLI_USAGE naming the text. */
int cli_parse_noise_sigma(const cli_command *cmd, const char *arg, int allow_xy, double *xy, double *z);
/** --noise-model auto|off into 0 / -1. */
int cli_parse_noise_model(const cli_command *cmd, const char *arg, int *mode);

/* Returned by cli_dim_option for an option that is not one of the shared ones. */
#define CLI_DIM_NOT_SHARED (-100)

/** Handles a shared option: CLI_CONTINUE, CLI_USAGE (bad value, message printed) or CLI_DIM_NOT_SHARED. */
int cli_dim_option(const cli_command *cmd, int opt, const char *arg, cli_dim_opts *o);
/** The options of the commands that read a method and a layer (dim line, dim profile): -m into *method,
 *  -l into *layer, any other as cli_dim_option. CLI_CONTINUE, CLI_USAGE or CLI_DIM_NOT_SHARED. */
int cli_dim_input_option(const cli_command *cmd, int opt, const char *arg, cli_dim_opts *o, const char **method,
                         const char **layer);
/** Checks the options together once parsed (--min-scale below --max-scale): CLI_CONTINUE or CLI_USAGE. */
int cli_dim_check(const cli_command *cmd, const cli_dim_opts *o);

typedef struct cli_dim_report cli_dim_report;

/** A new empty report; `input` (kept, not copied) names the input in plot titles. NULL if out of memory. */
cli_dim_report *cli_dim_report_create(const char *input);
void cli_dim_report_free(cli_dim_report *rep);
/** Starts a group: a feature (id = its id or --by value, owned; JSON null allowed with is_feature = 1) or the
 *  whole input (is_feature = 0). label names it in messages and plot files; info (owned, may be NULL) holds
 *  figures printed with it ("chains", "vertices"). FT_OK or FT_E_NOMEM. */
int cli_dim_report_group(cli_dim_report *rep, int is_feature, json_object *id, const char *label,
                         json_object *info);
/** Adds a result to the current group, taking ownership of r; xlabel and ylabel (static) label its plot. */
int cli_dim_report_add(cli_dim_report *rep, ft_dim_result *r, const char *xlabel, const char *ylabel);
/** Marks the current group as failed with the library's last error (printed as a warning, and as "error" in
 *  the JSON). */
void cli_dim_report_group_failed(const cli_command *cmd, cli_dim_report *rep);
/** Number of results in the report. */
size_t cli_dim_report_count(const cli_dim_report *rep);

/** Writes the plots (--plot), then prints the report (JSON with --json, else the table). extra (owned, may be
 *  NULL) holds top-level members printed first ("file", "layer"). CLI_OK, or CLI_FAIL (message printed,
 *  plots already written removed). */
int cli_dim_report_print(const cli_command *cmd, cli_dim_report *rep, const cli_dim_opts *o, json_object *extra);

#endif /* FRACTERRA_CLI_DIM_OUTPUT_H */
