/* fracterra — fuzz/fuzz_points_text.c: the scattered-point text readers (CSV with a header row, XYZ).
 * The first byte picks the format and the column options; the rest is the file.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fuzz_util.h"

#include <math.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1)
        return 0;
    ft_set_memory_limit(FUZZ_MEMORY_LIMIT);
    uint8_t mode = data[0];
    const char *path = fuzz_file((mode & 1) ? ".xyz" : ".csv", data + 1, size - 1);
    ft_read_points_opts o = FT_READ_POINTS_OPTS_DEFAULT;
    if (mode & 2) {
        o.x = "lon";
        o.y = "lat";
        o.z = "elev";
    }
    if (mode & 4)
        o.weight = "w";
    ft_points *p = NULL;
    int rc = ft_io_read_points(path, &o, &p);
    fuzz_check_error(rc);
    if (rc == FT_OK) {
        /* What the reader returns is what every estimator trusts: finite coordinates, n > 0. */
        if (p == NULL || p->n == 0)
            abort();
        for (size_t i = 0; i < p->n; i++)
            if (!isfinite(p->x[i]) || !isfinite(p->y[i]) || !isfinite(p->z[i]))
                abort();
    }
    ft_points_free(p);
    return 0;
}
