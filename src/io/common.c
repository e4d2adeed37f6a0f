/* fracterra — io/common.c: helpers shared by the readers and writers: paths and extensions, opening a
 * dataset of the wanted kind with clear errors, layer lookup, driver choice, CRS and number text.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#define _LARGEFILE64_SOURCE 1 /* VSIStatBufL is struct stat64 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>

#include "internal.h"
#include "io/io_internal.h"

static const char *base_name(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

const char *ft_io_ext(const char *path)
{
    const char *base = base_name(path);
    const char *dot = strrchr(base, '.');
    return (dot && dot != base) ? dot + 1 : "";
}

int ft_io_ext_in(const char *path, const char *list)
{
    const char *ext = ft_io_ext(path);
    size_t n = strlen(ext);
    if (n == 0)
        return 0;
    for (const char *p = list; *p;) {
        size_t len = strcspn(p, " ");
        if (len == n && strncasecmp(p, ext, n) == 0)
            return 1;
        p += len;
        while (*p == ' ')
            p++;
    }
    return 0;
}

char *ft_io_stem(const char *path)
{
    const char *base = base_name(path);
    const char *ext = ft_io_ext(path);
    size_t n = ext[0] ? (size_t)(ext - 1 - base) : strlen(base);
    char *s = ft_malloc(n + 1);
    if (s) {
        memcpy(s, base, n);
        s[n] = '\0';
    }
    return s;
}

int ft_io_is_stdio(const char *path)
{
    return path != NULL && strcmp(path, "-") == 0;
}

int ft_io_check_readable(const char *path)
{
    if (path == NULL || path[0] == '\0')
        return ft_error(FT_E_INVALID, "no input file given");
    if (ft_io_is_stdio(path))
        return FT_OK;
    VSIStatBufL st;
    errno = 0;
    if (VSIStatL(path, &st) != 0)
        return ft_error(FT_E_IO, "cannot open '%s': %s", path, strerror(errno ? errno : ENOENT));
    if (VSI_ISDIR(st.st_mode))
        return FT_OK;
    VSILFILE *f = VSIFOpenL(path, "rb");
    if (f == NULL)
        return ft_error(FT_E_IO, "cannot open '%s': %s", path, strerror(errno ? errno : EACCES));
    VSIFCloseL(f);
    return FT_OK;
}

char *ft_io_threads_begin(void)
{
    const char *old = CPLGetThreadLocalConfigOption("GDAL_NUM_THREADS", NULL);
    char *prev = old != NULL ? CPLStrdup(old) : NULL;
    if (CPLGetConfigOption("GDAL_NUM_THREADS", NULL) == NULL)
        CPLSetThreadLocalConfigOption("GDAL_NUM_THREADS", "ALL_CPUS");
    return prev;
}

void ft_io_threads_end(char *prev)
{
    CPLSetThreadLocalConfigOption("GDAL_NUM_THREADS", prev);
    CPLFree(prev);
}

int ft_io_open(const char *path, unsigned int kind, GDALDatasetH *ds)
{
    *ds = NULL;
    ft_io_init();
    int rc = ft_io_check_readable(path);
    if (rc != FT_OK)
        return rc;
    ft_io_gdal_reset();
    char *prev = (kind & GDAL_OF_RASTER) ? ft_io_threads_begin() : NULL;
    *ds = GDALOpenEx(path, kind | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR, NULL, NULL, NULL);
    if (kind & GDAL_OF_RASTER)
        ft_io_threads_end(prev);
    if (*ds != NULL)
        return FT_OK;
    char reason[1024];
    snprintf(reason, sizeof reason, "%s", ft_io_gdal_msg());
    unsigned int other = (kind & GDAL_OF_VECTOR) ? GDAL_OF_RASTER : GDAL_OF_VECTOR;
    GDALDatasetH od = GDALOpenEx(path, other | GDAL_OF_READONLY, NULL, NULL, NULL);
    if (od != NULL) {
        GDALClose(od);
        if (kind & GDAL_OF_VECTOR)
            return ft_error(FT_E_FORMAT, "'%s' is a raster, not a vector layer", path);
        return ft_error(FT_E_FORMAT, "'%s' is a vector dataset, not a raster", path);
    }
    const char *what = (kind & GDAL_OF_VECTOR) ? "vector" : "raster";
    if (reason[0] != '\0' && strstr(reason, "not recognized") == NULL)
        return ft_error(FT_E_FORMAT, "'%s' is not a readable %s file: %s", path, what, reason);
    return ft_error(FT_E_FORMAT, "'%s' is not in a recognized %s format", path, what);
}

int ft_io_get_layer(GDALDatasetH ds, const char *path, const char *name, OGRLayerH *layer)
{
    int n = GDALDatasetGetLayerCount(ds);
    *layer = NULL;
    if (n <= 0)
        return ft_error(FT_E_FORMAT, "'%s' holds no vector layer", path);
    if (name == NULL) {
        *layer = GDALDatasetGetLayer(ds, 0);
        return FT_OK;
    }
    *layer = GDALDatasetGetLayerByName(ds, name);
    if (*layer != NULL)
        return FT_OK;
    char list[1024] = "";
    size_t used = 0;
    for (int i = 0; i < n && used < sizeof list - 1; i++) {
        const char *ln = OGR_L_GetName(GDALDatasetGetLayer(ds, i));
        int k = snprintf(list + used, sizeof list - used, "%s%s", i ? ", " : "", ln);
        if (k < 0)
            break;
        used += (size_t)k;
    }
    return ft_error(FT_E_FORMAT, "no layer '%s' in '%s' (layers: %s)", name, path, list);
}

/* Driver names fixed by fracterra for the common extensions; the rest is looked up. */
static const char *known_driver(const char *ext, const char *cap)
{
    static const struct { const char *exts, *cap, *driver; } map[] = {
        {"geojson json", GDAL_DCAP_VECTOR, "GeoJSON"},
        {"shp", GDAL_DCAP_VECTOR, "ESRI Shapefile"},
        {"gpkg", GDAL_DCAP_VECTOR, "GPKG"},
        {"tif tiff", GDAL_DCAP_RASTER, "GTiff"},
        {"asc", GDAL_DCAP_RASTER, "AAIGrid"},
        {"gpkg", GDAL_DCAP_RASTER, "GPKG"},
    };
    char probe[64];
    snprintf(probe, sizeof probe, "x.%s", ext);
    for (size_t i = 0; i < sizeof map / sizeof map[0]; i++)
        if (strcmp(map[i].cap, cap) == 0 && ft_io_ext_in(probe, map[i].exts))
            return map[i].driver;
    return NULL;
}

static int driver_has(GDALDriverH d, const char *item)
{
    const char *v = GDALGetMetadataItem(d, item, NULL);
    return v != NULL && EQUAL(v, "YES");
}

static int driver_writes_ext(GDALDriverH d, const char *ext)
{
    const char *list = GDALGetMetadataItem(d, GDAL_DMD_EXTENSIONS, NULL);
    if (list == NULL)
        list = GDALGetMetadataItem(d, GDAL_DMD_EXTENSION, NULL);
    if (list == NULL || strlen(ext) > 60)
        return 0;
    char probe[64];
    snprintf(probe, sizeof probe, "x.%s", ext);
    return ft_io_ext_in(probe, list);
}

int ft_io_find_driver(const char *path, const char *name, const char *cap, GDALDriverH *drv)
{
    ft_io_init();
    *drv = NULL;
    int raster = strcmp(cap, GDAL_DCAP_RASTER) == 0;
    if (name != NULL) {
        *drv = GDALGetDriverByName(name);
        if (*drv == NULL || !driver_has(*drv, cap))
            return ft_error(FT_E_FORMAT, "no %s driver named '%s'", raster ? "raster" : "vector", name);
        if (!driver_has(*drv, GDAL_DCAP_CREATE) && !driver_has(*drv, GDAL_DCAP_CREATECOPY))
            return ft_error(FT_E_UNSUPPORTED, "driver '%s' cannot write files", name);
        return FT_OK;
    }
    const char *ext = ft_io_ext(path);
    if (ext[0] == '\0') {
        if (raster) {
            *drv = GDALGetDriverByName("GTiff");
            return FT_OK;
        }
        return ft_error(FT_E_FORMAT, "cannot tell the format of '%s' without an extension; name a driver",
                        path);
    }
    const char *known = known_driver(ext, cap);
    if (known != NULL && (*drv = GDALGetDriverByName(known)) != NULL)
        return FT_OK;
    GDALDriverH copy_only = NULL;
    for (int i = 0; i < GDALGetDriverCount(); i++) {
        GDALDriverH d = GDALGetDriver(i);
        if (!driver_has(d, cap) || !driver_writes_ext(d, ext))
            continue;
        if (driver_has(d, GDAL_DCAP_CREATE)) {
            *drv = d;
            return FT_OK;
        }
        if (copy_only == NULL && raster && driver_has(d, GDAL_DCAP_CREATECOPY))
            copy_only = d;
    }
    if (copy_only != NULL) {
        *drv = copy_only;
        return FT_OK;
    }
    return ft_error(FT_E_FORMAT, "no %s driver writes '.%s' files ('%s'); name a driver",
                    raster ? "raster" : "vector", ext, path);
}

char *ft_io_srs_to_wkt(OGRSpatialReferenceH srs)
{
    if (srs == NULL)
        return NULL;
    const char *const wkt2[] = {"FORMAT=WKT2_2018", NULL};
    char *w = NULL;
    if (OSRExportToWktEx(srs, &w, wkt2) != OGRERR_NONE || w == NULL || w[0] == '\0') {
        CPLFree(w);
        w = NULL;
        if (OSRExportToWkt(srs, &w) != OGRERR_NONE) {
            CPLFree(w);
            return NULL;
        }
    }
    char *out = ft_strdup(w);
    CPLFree(w);
    return out;
}

int ft_io_srs_from_wkt(const char *wkt, OGRSpatialReferenceH *srs)
{
    *srs = NULL;
    if (wkt == NULL || wkt[0] == '\0')
        return FT_OK;
    OGRSpatialReferenceH s = OSRNewSpatialReference(NULL);
    if (s == NULL)
        return ft_error(FT_E_NOMEM, "out of memory creating a CRS");
    ft_io_gdal_reset();
    if (OSRSetFromUserInput(s, wkt) != OGRERR_NONE) {
        OSRDestroySpatialReference(s);
        return ft_io_fail(FT_E_INVALID, "invalid CRS '%.60s%s'", wkt, strlen(wkt) > 60 ? "..." : "");
    }
    OSRSetAxisMappingStrategy(s, OAMS_TRADITIONAL_GIS_ORDER);
    *srs = s;
    return FT_OK;
}

void ft_io_format_double(char *buf, size_t size, double v)
{
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, v);
        if (prec == 17 || strtod(buf, NULL) == v || isnan(v))
            break;
    }
}

void ft_io_put_double(FILE *f, double v)
{
    char buf[40];
    ft_io_format_double(buf, sizeof buf, v);
    fputs(buf, f);
}

int ft_io_parse_double(const char *s, double *v)
{
    char *end;
    while (*s == ' ' || *s == '\t')
        s++;
    if (*s == '\0')
        return 0;
    errno = 0;
    *v = strtod(s, &end);
    if (end == s)
        return 0;
    while (*end == ' ' || *end == '\t' || *end == '\r' || *end == '\n')
        end++;
    return *end == '\0';
}

FILE *ft_io_fopen_read(const char *path)
{
    return ft_io_is_stdio(path) ? stdin : fopen(path, "r");
}
