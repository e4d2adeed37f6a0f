/* fracterra — io/probe.c: what a path holds (grid, chains, points) and whether an output can be created.
 *
 * SPDX-License-Identifier: GPL-3.0-or-later
 */
#include <errno.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "internal.h"
#include "io/io_internal.h"

int ft_io_is_text_chains(const char *path)
{
    return path != NULL && (ft_io_is_stdio(path) || ft_io_ext_in(path, "gmt xy txt"));
}

int ft_io_is_text_points(const char *path)
{
    return path != NULL && ft_io_ext_in(path, "csv xyz");
}

/* Kind of a geometry type; FT_KIND_UNKNOWN for none, unknown or mixed collections. */
static ft_file_kind kind_of_type(OGRwkbGeometryType t)
{
    t = wkbFlatten(t);
    if (t == wkbPoint || t == wkbMultiPoint)
        return FT_KIND_POINTS;
    if (t == wkbUnknown || t == wkbNone || t == wkbGeometryCollection)
        return FT_KIND_UNKNOWN;
    if (OGR_GT_IsSubClassOf(t, wkbCurve) || OGR_GT_IsSubClassOf(t, wkbSurface) ||
        OGR_GT_IsSubClassOf(t, wkbMultiCurve) || OGR_GT_IsSubClassOf(t, wkbMultiSurface))
        return FT_KIND_CHAINS;
    return FT_KIND_UNKNOWN;
}

/* A layer of unknown declared type: the kind of its first features' geometries. */
static ft_file_kind kind_of_features(OGRLayerH layer)
{
    ft_file_kind kind = FT_KIND_UNKNOWN;
    OGR_L_ResetReading(layer);
    OGRFeatureH f;
    for (int i = 0; i < 1000 && kind == FT_KIND_UNKNOWN && (f = OGR_L_GetNextFeature(layer)) != NULL; i++) {
        OGRGeometryH g = OGR_F_GetGeometryRef(f);
        if (g != NULL)
            kind = kind_of_type(OGR_G_GetGeometryType(g));
        OGR_F_Destroy(f);
    }
    OGR_L_ResetReading(layer);
    return kind;
}

int ft_io_dataset_kind(GDALDatasetH ds, const char *path, const char *layer, ft_file_kind *kind)
{
    *kind = FT_KIND_UNKNOWN;
    if (layer == NULL && GDALGetRasterCount(ds) > 0) {
        *kind = FT_KIND_GRID;
        return FT_OK;
    }
    OGRLayerH l;
    int rc = ft_io_get_layer(ds, path, layer, &l);
    if (rc != FT_OK)
        return rc;
    *kind = kind_of_type(OGR_L_GetGeomType(l));
    if (*kind == FT_KIND_UNKNOWN)
        *kind = kind_of_features(l);
    if (*kind == FT_KIND_UNKNOWN)
        return ft_error(FT_E_FORMAT, "layer '%s' of '%s' holds no line, polygon or point geometry", OGR_L_GetName(l),
                        path);
    return FT_OK;
}

/* Kind of a plain-text file by its extension; FT_KIND_UNKNOWN if it is not one. */
static ft_file_kind text_kind(const char *path)
{
    if (ft_io_is_text_points(path))
        return FT_KIND_POINTS;
    if (ft_io_is_text_chains(path))
        return FT_KIND_CHAINS;
    return FT_KIND_UNKNOWN;
}

/* Opens path as raster or vector, with a clear error when GDAL reads neither. */
static int open_any(const char *path, GDALDatasetH *ds)
{
    ft_io_init();
    ft_io_gdal_reset();
    char *prev = ft_io_threads_begin(); /* a GeoTIFF decodes its blocks on every core */
    *ds = GDALOpenEx(path, GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY, NULL, NULL, NULL);
    ft_io_threads_end(prev);
    if (*ds == NULL)
        return ft_error(FT_E_FORMAT, "'%s' is neither a raster nor a vector format GDAL reads", path);
    return FT_OK;
}

static int probe(const char *path, const char *layer, ft_file_kind *kind)
{
    *kind = FT_KIND_UNKNOWN;
    int rc = ft_io_check_readable(path);
    if (rc != FT_OK)
        return rc;
    if ((*kind = text_kind(path)) != FT_KIND_UNKNOWN)
        return FT_OK;
    GDALDatasetH ds;
    if ((rc = open_any(path, &ds)) != FT_OK)
        return rc;
    rc = ft_io_dataset_kind(ds, path, layer, kind);
    GDALClose(ds);
    return rc;
}

int ft_io_probe(const char *path, const char *layer, ft_file_kind *kind)
{
    ft_io_enter();
    return ft_io_leave(probe(path, layer, kind));
}

void ft_data_clear(ft_data *d)
{
    if (d == NULL)
        return;
    ft_grid_free(d->grid);
    ft_layer_free(d->layer);
    ft_points_free(d->points);
    memset(d, 0, sizeof *d);
}

/* Reads a plain-text file of the given kind. */
static int read_text(const char *path, ft_file_kind kind, const ft_read_points_opts *po, ft_data *out)
{
    out->kind = kind;
    if (kind == FT_KIND_POINTS)
        return ft_io_read_points(path, po, &out->points);
    return ft_io_read_text_chains(path, &out->layer);
}

/* ft_io_read_any, a grid summarized into *summary when summary is not NULL. */
static int read_any(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                    const ft_read_points_opts *po, ft_data *out, ft_grid_summary *summary)
{
    ft_read_layer_opts l = FT_READ_LAYER_OPTS_DEFAULT;
    ft_read_grid_opts g = FT_READ_GRID_OPTS_DEFAULT;
    ft_read_points_opts p = FT_READ_POINTS_OPTS_DEFAULT;
    if (lo != NULL)
        l = *lo;
    if (go != NULL)
        g = *go;
    if (po != NULL)
        p = *po;
    memset(out, 0, sizeof *out);
    int rc = ft_io_check_readable(path);
    if (rc != FT_OK)
        return rc;
    ft_file_kind kind = text_kind(path);
    if (kind != FT_KIND_UNKNOWN)
        rc = read_text(path, kind, &p, out);
    else {
        const char *layer = l.layer != NULL ? l.layer : p.layer;
        GDALDatasetH ds;
        if ((rc = open_any(path, &ds)) != FT_OK)
            return rc;
        rc = ft_io_dataset_kind(ds, path, layer, &out->kind);
        l.layer = p.layer = layer;
        if (rc == FT_OK && out->kind == FT_KIND_GRID && summary != NULL)
            rc = ft_io_summarize_grid_ds(ds, path, &g, summary);
        else if (rc == FT_OK && out->kind == FT_KIND_GRID)
            rc = ft_io_read_grid_ds(ds, path, &g, &out->grid);
        else if (rc == FT_OK && out->kind == FT_KIND_CHAINS)
            rc = ft_io_read_layer_ds(ds, path, &l, &out->layer);
        else if (rc == FT_OK)
            rc = ft_io_read_points_ds(ds, path, &p, &out->points);
        GDALClose(ds);
    }
    if (rc != FT_OK)
        ft_data_clear(out);
    return rc;
}

int ft_io_read_any(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                   const ft_read_points_opts *po, ft_data *out)
{
    ft_io_enter();
    return ft_io_leave(read_any(path, lo, go, po, out, NULL));
}

static int read_any_summary(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                            const ft_read_points_opts *po, ft_data *out, ft_grid_summary *summary)
{
    memset(summary, 0, sizeof *summary);
    int rc = read_any(path, lo, go, po, out, summary);
    if (rc != FT_OK)
        ft_grid_summary_clear(summary);
    return rc;
}

int ft_io_read_any_summary(const char *path, const ft_read_layer_opts *lo, const ft_read_grid_opts *go,
                           const ft_read_points_opts *po, ft_data *out, ft_grid_summary *summary)
{
    ft_io_enter();
    return ft_io_leave(read_any_summary(path, lo, go, po, out, summary));
}

/* The folder part of path ("." when it has none); malloc'd. */
static char *folder_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (slash == NULL)
        return ft_strdup(".");
    if (slash == path)
        return ft_strdup("/");
    char *dir = ft_malloc((size_t)(slash - path) + 1);
    if (dir) {
        memcpy(dir, path, (size_t)(slash - path));
        dir[slash - path] = '\0';
    }
    return dir;
}

int ft_io_check_writable(const char *path)
{
    if (path == NULL || path[0] == '\0')
        return ft_error(FT_E_INVALID, "no output file given");
    if (ft_io_is_stdio(path))
        return FT_OK;
    struct stat st;
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return ft_error(FT_E_IO, "cannot write '%s': it is a folder", path);
    char *dir = folder_of(path);
    if (dir == NULL)
        return FT_E_NOMEM;
    int rc = FT_OK;
    if (stat(dir, &st) != 0)
        rc = ft_error(FT_E_IO, "cannot write '%s': folder '%s' does not exist", path, dir);
    else if (!S_ISDIR(st.st_mode))
        rc = ft_error(FT_E_IO, "cannot write '%s': '%s' is not a folder", path, dir);
    else if (access(dir, W_OK | X_OK) != 0)
        rc = ft_error(FT_E_IO, "cannot write '%s': folder '%s' is not writable (%s)", path, dir,
                      strerror(errno));
    free(dir);
    return rc;
}
