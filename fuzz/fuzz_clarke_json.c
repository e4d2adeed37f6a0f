/* fracterra — fuzz/fuzz_clarke_json.c: the Clarke scale-based model file that `model fit -o` writes and
 * `model simulate` reads (ft_io_read_clarke_model).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fuzz_util.h"

#include "fracterra/io.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ft_set_memory_limit(FUZZ_MEMORY_LIMIT);
    const char *path = fuzz_file(".json", data, size);
    ft_clarke_model *m = NULL;
    int rc = ft_io_read_clarke_model(path, &m);
    fuzz_check_error(rc);
    ft_clarke_model_free(m);
    return 0;
}
