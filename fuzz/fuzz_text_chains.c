/* fracterra — fuzz/fuzz_text_chains.c: GMT-style text chains (`x y` lines, `>` segment headers,
 * `#` comments), then the finiteness check every line command runs on what it read.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fuzz_util.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ft_set_memory_limit(FUZZ_MEMORY_LIMIT);
    const char *path = fuzz_file(".gmt", data, size);
    ft_layer *l = NULL;
    int rc = ft_io_read_text_chains(path, &l);
    fuzz_check_error(rc);
    if (rc == FT_OK) {
        rc = ft_layer_check_finite(l);
        fuzz_check_error(rc);
    }
    ft_layer_free(l);
    return 0;
}
