/* fracterra — io/raster_mosaic.c: a GDAL virtual raster (VRT, https://gdal.org/drivers/raster/vrt.html) over
 * stripes of whole rows written as separate GeoTIFF parts, e.g. one part per MPI rank (docs/tiling.md). GDAL
 * reads the .vrt as one raster. Each part is opened and checked (width, one band, the first part's data type,
 * consecutive stripes covering the mosaic's rows); the sources are named relative to the .vrt's folder
 * (relativeToVRT="1"), so the .vrt and its parts move together. The XML goes through the atomic service.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cpl_string.h>

#include "internal.h"
#include "io/io_internal.h"

typedef struct {
    size_t rows, bx, by;
} mosaic_part;

typedef struct {
    const ft_grid *header;
    size_t n;
    const char *const *names;
    const mosaic_part *parts;
    GDALDataType type;
    int has_nodata;
    double nodata;
} mosaic;

/* "<folder of vrt><name>" (malloc'd): where a part named relative to the .vrt lies. */
static char *beside(const char *vrt, const char *name)
{
    const char *slash = strrchr(vrt, '/');
    size_t dir = slash ? (size_t)(slash - vrt) + 1 : 0, len = strlen(name);
    char *p = ft_malloc(dir + len + 1);
    if (p != NULL) {
        memcpy(p, vrt, dir);
        memcpy(p + dir, name, len + 1);
    }
    return p;
}

/* Equal nodata values, NaN equal to NaN. */
static int same_value(double a, double b)
{
    return a == b || (isnan(a) && isnan(b));
}

/* Opens part k and checks it against the mosaic: its rows, block size, and (part 0) the type and nodata. */
static int check_part(const char *vrt, mosaic *m, size_t k, mosaic_part *p)
{
    const char *name = m->names[k];
    if (name == NULL || name[0] == '\0' || name[0] == '/')
        return ft_error(FT_E_INVALID, "'%s': part %zu must be named relative to the mosaic's folder", vrt, k + 1);
    char *path = beside(vrt, name);
    if (path == NULL)
        return FT_E_NOMEM;
    GDALDatasetH ds = NULL;
    int rc = ft_io_open(path, GDAL_OF_RASTER, &ds);
    if (rc == FT_OK && (GDALGetRasterCount(ds) != 1 || (size_t)GDALGetRasterXSize(ds) != m->header->nx))
        rc = ft_error(FT_E_FORMAT, "'%s': part '%s' has %d band(s) of %d columns, the mosaic 1 of %zu", vrt, path,
                      GDALGetRasterCount(ds), GDALGetRasterXSize(ds), m->header->nx);
    if (rc == FT_OK) {
        GDALRasterBandH b = GDALGetRasterBand(ds, 1);
        int bx = 0, by = 0, has = 0;
        GDALGetBlockSize(b, &bx, &by);
        double nd = GDALGetRasterNoDataValue(b, &has);
        GDALDataType t = GDALGetRasterDataType(b);
        p->rows = (size_t)GDALGetRasterYSize(ds);
        p->bx = (size_t)bx;
        p->by = (size_t)by;
        if (k == 0) {
            m->type = t;
            m->has_nodata = has;
            m->nodata = nd;
        } else if (t != m->type || has != m->has_nodata || (has && !same_value(nd, m->nodata))) {
            rc = ft_error(FT_E_FORMAT, "'%s': part '%s' differs from the first part in data type or nodata", vrt, path);
        }
    }
    if (ds != NULL)
        GDALClose(ds);
    free(path);
    return rc;
}

/* before, s escaped for XML, after. */
static int put_escaped(FILE *f, const char *before, const char *s, const char *after)
{
    char *e = CPLEscapeString(s, -1, CPLES_XML);
    int ok = e != NULL && fputs(before, f) >= 0 && fputs(e, f) >= 0 && fputs(after, f) >= 0;
    CPLFree(e);
    return ok ? FT_OK : FT_E_IO;
}

/* The VRT's XML (GDAL's schema, data/gdalvrt.xsd): the mosaic's georeferencing, one band, one source a part. */
static int write_xml(FILE *f, const void *arg)
{
    const mosaic *m = arg;
    const ft_grid *h = m->header;
    const char *type = GDALGetDataTypeName(m->type);
    fprintf(f, "<VRTDataset rasterXSize=\"%zu\" rasterYSize=\"%zu\">\n", h->nx, h->ny);
    if (h->crs_wkt != NULL && h->crs_wkt[0] != '\0' && put_escaped(f, "  <SRS>", h->crs_wkt, "</SRS>\n") != FT_OK)
        return FT_E_IO;
    fprintf(f, "  <GeoTransform>%.17g, %.17g, %.17g, %.17g, %.17g, %.17g</GeoTransform>\n", h->gt[0], h->gt[1],
            h->gt[2], h->gt[3], h->gt[4], h->gt[5]);
    fprintf(f, "  <VRTRasterBand dataType=\"%s\" band=\"1\">\n", type);
    if (m->has_nodata)
        fprintf(f, "    <NoDataValue>%.17g</NoDataValue>\n", m->nodata);
    size_t row0 = 0;
    for (size_t k = 0; k < m->n; k++) {
        const mosaic_part *p = &m->parts[k];
        fprintf(f, "    <SimpleSource>\n");
        if (put_escaped(f, "      <SourceFilename relativeToVRT=\"1\">", m->names[k], "</SourceFilename>\n") != FT_OK)
            return FT_E_IO;
        fprintf(f, "      <SourceBand>1</SourceBand>\n");
        fprintf(f,
                "      <SourceProperties RasterXSize=\"%zu\" RasterYSize=\"%zu\" DataType=\"%s\" BlockXSize=\"%zu\" "
                "BlockYSize=\"%zu\"/>\n",
                h->nx, p->rows, type, p->bx, p->by);
        fprintf(f, "      <SrcRect xOff=\"0\" yOff=\"0\" xSize=\"%zu\" ySize=\"%zu\"/>\n", h->nx, p->rows);
        fprintf(f, "      <DstRect xOff=\"0\" yOff=\"%zu\" xSize=\"%zu\" ySize=\"%zu\"/>\n", row0, h->nx, p->rows);
        fprintf(f, "    </SimpleSource>\n");
        row0 += p->rows;
    }
    fprintf(f, "  </VRTRasterBand>\n</VRTDataset>\n");
    return FT_OK;
}

static int write_mosaic(const char *path, const ft_grid *header, size_t n, const char *const *parts)
{
    if (path == NULL || header == NULL || header->nx == 0 || header->ny == 0 || n == 0 || parts == NULL)
        return ft_error(FT_E_INVALID, "mosaic: no path, an empty header or no parts");
    if (!ft_io_ext_in(path, "vrt"))
        return ft_error(FT_E_INVALID, "mosaic '%s': the name must end in .vrt", path);
    mosaic_part *p = ft_calloc(n, sizeof *p);
    if (p == NULL)
        return FT_E_NOMEM;
    mosaic m = {.header = header, .n = n, .names = parts, .parts = p};
    int rc = FT_OK;
    size_t rows = 0;
    for (size_t k = 0; k < n && rc == FT_OK; k++) {
        rc = check_part(path, &m, k, &p[k]);
        rows += rc == FT_OK ? p[k].rows : 0;
    }
    if (rc == FT_OK && rows != header->ny)
        rc = ft_error(FT_E_INVALID, "mosaic '%s': its %zu parts hold %zu rows, the mosaic has %zu", path, n, rows,
                      header->ny);
    if (rc == FT_OK)
        rc = ft_io_atomic_write(path, write_xml, &m);
    free(p);
    return rc;
}

int ft_io_write_mosaic_vrt(const char *path, const ft_grid *header, size_t n, const char *const *parts)
{
    ft_io_enter();
    return ft_io_leave(write_mosaic(path, header, n, parts));
}
