/* fracterra — cli/clarke_json.h: Clarke's scale-based model (Clarke 1987, z = T + cF + H) as JSON, the file
 * `fracterra model fit -o` writes and `fracterra model simulate` reads (docs/terrain-clarke.md).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#ifndef FRACTERRA_CLI_CLARKE_JSON_H
#define FRACTERRA_CLI_CLARKE_JSON_H

#include <json-c/json.h>

#include "fracterra/terrain.h"

/** The model as a JSON object (the caller releases it). */
json_object *clarke_model_to_json(const ft_clarke_model *m);
/** The model from a JSON object; FT_E_FORMAT naming `what` (the file) and the missing or malformed key. */
int clarke_model_from_json(json_object *o, const char *what, ft_clarke_model **out);
/** Writes the model to path (pretty-printed), under a temporary name renamed when complete. */
int clarke_model_write(const char *path, const ft_clarke_model *m);
/** Reads a model file: FT_E_IO if it cannot be read, FT_E_FORMAT if it is not a model (key named). */
int clarke_model_read(const char *path, ft_clarke_model **out);

#endif /* FRACTERRA_CLI_CLARKE_JSON_H */
