/* fracterra — io/crs_name.c: what a CRS calls itself: its name and its own top-level EPSG code, read by OSR
 * from the WKT (the code is the one the WKT states, ID["EPSG",...] or AUTHORITY["EPSG","..."]; no lookup
 * that could guess one).
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "io/io_internal.h"

static int crs_name(const char *wkt, char *name, size_t size, int *epsg)
{
    if (name == NULL || size == 0 || epsg == NULL)
        return ft_error(FT_E_INVALID, "ft_io_crs_name: NULL or empty output");
    name[0] = '\0';
    *epsg = 0;
    OGRSpatialReferenceH srs = NULL;
    int rc = ft_io_srs_from_wkt(wkt, &srs);
    if (rc != FT_OK || srs == NULL)
        return rc;
    const char *n = OSRGetName(srs);
    snprintf(name, size, "%s", n ? n : "");
    const char *auth = OSRGetAuthorityName(srs, NULL), *code = OSRGetAuthorityCode(srs, NULL);
    if (auth != NULL && code != NULL && strcasecmp(auth, "EPSG") == 0) {
        long c = strtol(code, NULL, 10);
        *epsg = c > 0 && c < 2147483647L ? (int)c : 0;
    }
    OSRDestroySpatialReference(srs);
    return FT_OK;
}

int ft_io_crs_name(const char *wkt, char *name, size_t size, int *epsg)
{
    ft_io_enter();
    return ft_io_leave(crs_name(wkt, name, size, epsg));
}
