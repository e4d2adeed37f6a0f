/* fracterra — fuzz/fuzz_urban_table.c: the table `urban table` writes and `urban regress` reads (CSV or
 * JSON). The first byte picks the format and whether a class is named.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fuzz_util.h"

#include "urban_cli.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    ft_set_memory_limit(FUZZ_MEMORY_LIMIT);
    const char *path = fuzz_file((data[0] & 1) ? ".json" : ".csv", data + 1, size - 1);
    static const char *const measures[2] = {"area", "D"};
    urban_columns c = {0};
    int rc = urban_columns_read(path, (data[0] & 2) ? "Colorado" : NULL, measures, &c);
    fuzz_check_error(rc);
    urban_columns_free(&c);
    return 0;
}
