/* fracterra — fuzz/fuzz_gdal_raster.c: GeoTIFF through GDAL (/vsimem/) into an ft_grid, as every DEM
 * command reads it; a declared size beyond the memory bound must be refused, not allocated.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include "fuzz_util.h"

#include <cpl_vsi.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    ft_set_memory_limit(FUZZ_MEMORY_LIMIT);
    ft_io_init();
    static const char path[] = "/vsimem/fuzz.tif";
    VSILFILE *f = VSIFileFromMemBuffer(path, (GByte *)data, (vsi_l_offset)size, FALSE);
    if (f == NULL)
        abort();
    VSIFCloseL(f);
    ft_grid *g = NULL;
    int rc = ft_io_read_grid(path, NULL, &g);
    fuzz_check_error(rc);
    ft_grid_free(g);
    VSIUnlink(path);
    return 0;
}
