/* fracterra — cli/urban_cli.h: what the urban commands (dim area, urban table, urban regress) share:
 * measuring a polygon layer class by class (or a classified raster value by value) with the box-counting
 * estimator of urban.h, the options of that estimator, and the column names of the per-year table that
 * `urban table` writes and `urban regress` reads.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_URBAN_H
#define FRACTERRA_CLI_URBAN_H

#include "cli.h"

#include <stdio.h>

/* ---- box-counting options shared by dim area and urban table ---- */

#define URBAN_MAX_CELLS 1000

/* --what, --cell (repeatable, or a comma-separated list), --offsets. */
typedef struct {
    ft_area_dim_opts dim;
    double cells[URBAN_MAX_CELLS];
} urban_box_args;

enum { URBAN_OPT_WHAT = 0x300, URBAN_OPT_CELL, URBAN_OPT_OFFSETS, URBAN_OPT_FEWEST };
#define URBAN_BOX_LONGOPTS                                                                                   \
    {"what", required_argument, NULL, URBAN_OPT_WHAT}, {"cell", required_argument, NULL, URBAN_OPT_CELL},    \
        {"offsets", required_argument, NULL, URBAN_OPT_OFFSETS}, {"fewest-boxes", no_argument, NULL, URBAN_OPT_FEWEST}
#define URBAN_BOX_HELP                                                                                       \
    "      --what W         boundary (default: boxes crossed by the rings) or area (boxes touching the\n"       \
    "                       polygons' interior)\n"                                                              \
    "      --cell SIZE      count exactly these box sides (map units); repeat it or give a list 10,20,40.\n"    \
    "                       D is then fitted over all of them. Default: a geometric series (see below)\n"       \
    "      --offsets K      grid origins per axis, their mean count kept (1..16); default 4\n"                \
    "      --fewest-boxes   keep the fewest count over the origins instead (the literature's; biased upward\n" \
    "                       where the largest boxes hold few counts)\n"

/* Returned by urban_box_option for an option that is not one of the shared ones. */
#define URBAN_NOT_SHARED (-102)

/** Resets a to the estimator's defaults. */
void urban_box_init(urban_box_args *a);
/** Handles --what, --cell, --offsets: CLI_CONTINUE, CLI_USAGE (message printed) or URBAN_NOT_SHARED. */
int urban_box_option(const cli_command *cmd, int opt, const char *arg, urban_box_args *a);

/* ---- measuring class by class ---- */

/* One set measured: the whole layer, one class of --class FIELD, or one value of a classified raster. */
typedef struct {
    const char *label;           /**< "residential", "3"; NULL for the whole layer */
    json_object *id;             /**< the class as JSON, typed like the field (borrowed); NULL: whole layer */
    const ft_urban_stats *stats; /**< its polygons or cells */
    int is_grid;                 /**< 1 for a raster class */
} urban_set;

/* Called once per set, in order, with its result (ownership passed; NULL when it could not be measured,
 * ft_last_error() then says why). Returns FT_OK to go on, or an error code to stop. */
typedef int (*urban_set_fn)(const urban_set *s, ft_dim_result *r, void *ctx);

/** Measures the polygons of l: the whole layer first (if whole), then each class of `field` (if not NULL)
 *  in the order of ft_urban_classes_by_field. A set that cannot be measured is passed with r = NULL; out of
 *  memory and cancellation stop. FT_OK, or the error (set) that stopped it. */
int urban_measure_layer(const ft_layer *l, const char *field, int whole, const ft_area_dim_opts *o,
                        urban_set_fn fn, void *ctx);
/** Measures each class of a classified raster (ft_urban_grid_classes: its distinct valid values, increasing,
 *  at most FT_URBAN_MAX_CLASSES of them). */
int urban_measure_grid(const ft_grid *g, const ft_area_dim_opts *o, urban_set_fn fn, void *ctx);

/** A set's figures as a new JSON object: "features", "polygons", "holes", "area", "perimeter" (layers) or
 *  "cells", "polygons", "area", "perimeter" (rasters). */
json_object *urban_set_info(const urban_set *s);

/* ---- the per-year table ---- */

/* Column names: the whole layer's are the bare measures ("D", "area"); a class's are "CLASS.MEASURE"
 * ("residential.D"). The measures of each group, in order. */
#define URBAN_MEASURES {"D", "stderr", "area", "polygons"}
#define URBAN_NMEASURES 4
/** "CLASS.MEASURE", or MEASURE when cls is NULL, into buf. */
void urban_column_name(const char *cls, const char *measure, char *buf, size_t size);

/** Writes s as one CSV field (quoted when it holds a comma, a quote, a line break or outer spaces). */
void urban_csv_field(FILE *f, const char *s);

/* Columns of a table, as `urban regress` reads them: CSV with a header row (RFC 4180 quoting), or the
 * JSON `urban table` writes ({"rows": [{MEASURE: v, "classes": {CLASS: {MEASURE: v}}}]}, or an array of
 * row objects). Column CLASS.MEASURE is found as that CSV header (case-insensitive), or in a JSON row as
 * classes[CLASS][MEASURE] or "CLASS.MEASURE". */
typedef struct {
    double *v[2];   /**< the two columns' values, rows with both present */
    size_t n;       /**< rows kept */
    size_t skipped; /**< rows where a value was empty or null */
    size_t rows;    /**< data rows in the table */
} urban_columns;

/** Reads columns names[0] and names[1] (full column names, "residential.D" or "D"; cls is the class they
 *  belong to, or NULL) of the table at path. FT_E_IO if it cannot be read, FT_E_FORMAT naming the file, the
 *  line or row and the column for a missing column or a value that is not a number. */
int urban_columns_read(const char *path, const char *cls, const char *const measures[2], urban_columns *out);
void urban_columns_free(urban_columns *c);

#endif /* FRACTERRA_CLI_URBAN_H */
