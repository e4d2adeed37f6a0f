/* fracterra — fuzz/fuzz_gdal_vector.c: GeoJSON through GDAL/OGR (/vsimem/) into fracterra's types: the
 * layer reader the line and urban commands use, and the point reader of `dim points`/`reconstruct`.
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
    static const char path[] = "/vsimem/fuzz.geojson";
    VSILFILE *f = VSIFileFromMemBuffer(path, (GByte *)data, (vsi_l_offset)size, FALSE);
    if (f == NULL)
        abort();
    VSIFCloseL(f);
    ft_layer *l = NULL;
    int rc = ft_io_read_layer(path, NULL, &l);
    fuzz_check_error(rc);
    if (rc == FT_OK)
        fuzz_check_error(ft_layer_check_finite(l));
    ft_layer_free(l);
    ft_points *p = NULL;
    rc = ft_io_read_points(path, NULL, &p);
    fuzz_check_error(rc);
    ft_points_free(p);
    VSIUnlink(path);
    return 0;
}
