/* fracterra — io/line_z_read.c: the vertices (x, y, z) of the first line of a vector layer, for profiles
 * along a 3-D line (`dim profile LINE.geojson`; surface/profile_extract.c resamples them).
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdlib.h>

#include "internal.h"
#include "io/io_internal.h"

#include "fracterra/io.h"

/* The first LineString of g (itself, or the first part of a MultiLineString), or NULL. */
static OGRGeometryH first_line(OGRGeometryH g)
{
    OGRwkbGeometryType t = wkbFlatten(OGR_G_GetGeometryType(g));
    if (t == wkbLineString)
        return g;
    if (t == wkbMultiLineString && OGR_G_GetGeometryCount(g) > 0)
        return OGR_G_GetGeometryRef(g, 0);
    return NULL;
}

static int copy_line(OGRGeometryH line, const char *path, long long fid, double **x, double **y, double **z,
                     size_t *n)
{
    if (!OGR_G_Is3D(line))
        return ft_error(FT_E_FORMAT, "'%s': line of feature %lld has no z (a 2-D line is not a profile: give a "
                        "3-D line, or a DEM with --row or --from/--to)", path, fid);
    int m = OGR_G_GetPointCount(line);
    if (m < 3)
        return ft_error(FT_E_EMPTY, "'%s': line of feature %lld has %d vertices, fewer than 3", path, fid, m);
    *x = ft_malloc((size_t)m * sizeof **x);
    *y = ft_malloc((size_t)m * sizeof **y);
    *z = ft_malloc((size_t)m * sizeof **z);
    if (*x == NULL || *y == NULL || *z == NULL)
        return FT_E_NOMEM;
    OGR_G_GetPoints(line, *x, sizeof(double), *y, sizeof(double), *z, sizeof(double));
    for (int i = 0; i < m; i++)
        if (!isfinite((*x)[i]) || !isfinite((*y)[i]) || !isfinite((*z)[i]))
            return ft_error(FT_E_NUMERIC, "'%s': vertex %d of feature %lld is not finite (%g, %g, %g)", path, i, fid,
                            (*x)[i], (*y)[i], (*z)[i]);
    *n = (size_t)m;
    return FT_OK;
}

static int read_line_z(const char *path, const char *layer, double **x, double **y, double **z, size_t *n)
{
    if (path == NULL || x == NULL || y == NULL || z == NULL || n == NULL)
        return ft_error(FT_E_INVALID, "ft_io_read_line_z: NULL argument");
    *x = *y = *z = NULL;
    *n = 0;
    GDALDatasetH ds = NULL;
    OGRLayerH l = NULL;
    int rc = ft_io_open(path, GDAL_OF_VECTOR, &ds);
    if (rc == FT_OK)
        rc = ft_io_get_layer(ds, path, layer, &l);
    int found = 0;
    OGRFeatureH f;
    if (rc == FT_OK)
        OGR_L_ResetReading(l);
    while (rc == FT_OK && !found && (f = OGR_L_GetNextFeature(l)) != NULL) {
        OGRGeometryH g = OGR_F_GetGeometryRef(f), line = g ? first_line(g) : NULL;
        if (line != NULL) {
            found = 1;
            rc = copy_line(line, path, (long long)OGR_F_GetFID(f), x, y, z, n);
        }
        OGR_F_Destroy(f);
    }
    if (rc == FT_OK && !found)
        rc = ft_error(FT_E_EMPTY, "'%s' holds no line", path);
    if (ds)
        GDALClose(ds);
    if (rc != FT_OK) {
        free(*x);
        free(*y);
        free(*z);
        *x = *y = *z = NULL;
        *n = 0;
    }
    return rc;
}

int ft_io_read_line_z(const char *path, const char *layer, double **x, double **y, double **z, size_t *n)
{
    ft_io_enter();
    return ft_io_leave(read_line_z(path, layer, x, y, z, n));
}
