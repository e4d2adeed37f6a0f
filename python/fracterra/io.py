"""Reading and writing grids: through the library's own GDAL readers (read_grid, write_grid, exactly
what the CLI reads and writes) and, when osgeo.gdal is installed, to and from GDAL datasets in memory
(from_gdal, to_gdal). Georeferencing is GDAL's geotransform and the CRS as WKT."""
import ctypes

import numpy as np

from . import _structs as S
from ._lib import lib, check
from ._core import Grid, as_grid, _CGrid, grid_from_c
from ._common import path_bytes

__all__ = ["read_grid", "write_grid", "from_gdal", "to_gdal"]


def read_grid(path, band=1):
    """One band of a raster as a Grid (float32 cells, nodata as the mask), as every fracterra command
    reads it (ft_io_read_grid)."""
    o = S.ft_read_grid_opts.default()
    o.band = int(band)
    out = ctypes.POINTER(S.ft_grid)()
    check(lib.ft_io_read_grid(path_bytes(path), ctypes.byref(o), ctypes.byref(out)))
    return grid_from_c(out)


def write_grid(path, grid, *, driver=None, geotransform=None, wkt=None):
    """Writes a Grid (or array) with its geotransform, CRS and nodata through the library's writer
    (driver from the extension, GeoTIFF tiled, ZSTD or DEFLATE level 1 on every core by default); replaces
    path only on success."""
    o = S.ft_write_grid_opts.default()
    keep = driver.encode() if driver else None
    o.driver = keep
    cg = _CGrid(as_grid(grid, geotransform, wkt))
    check(lib.ft_io_write_grid(path_bytes(path), cg.ref, ctypes.byref(o)))


def from_gdal(ds, band=1):
    """A Grid from an osgeo.gdal Dataset (or a path opened with gdal.Open): the band as float32, its
    nodata value and mask band as the mask, the geotransform and the projection WKT."""
    from osgeo import gdal
    if not isinstance(ds, gdal.Dataset):
        ds = gdal.Open(str(ds))
        if ds is None:
            raise OSError(gdal.GetLastErrorMsg())
    b = ds.GetRasterBand(int(band))
    z = b.ReadAsArray().astype(np.float32)
    valid = b.GetMaskBand().ReadAsArray() != 0
    valid &= np.isfinite(z)
    nd = b.GetNoDataValue()
    return Grid(z, mask=None if valid.all() else valid, geotransform=ds.GetGeoTransform(),
                wkt=ds.GetProjection() or None, nodata=nd)


def to_gdal(grid, path="", driver="MEM", nodata=None):
    """An osgeo.gdal Dataset holding a Grid (Float32, masked cells set to nodata: the grid's, the
    argument, or NaN); driver "MEM" (default) keeps it in memory, else it is created at path."""
    from osgeo import gdal
    g = as_grid(grid)
    ny, nx = g.z.shape
    ds = gdal.GetDriverByName(driver).Create(str(path), nx, ny, 1, gdal.GDT_Float32)
    ds.SetGeoTransform(g.geotransform)
    if g.wkt:
        ds.SetProjection(g.wkt)
    b = ds.GetRasterBand(1)
    z = np.array(g.z, dtype=np.float32)
    if g.mask is not None:
        nd = nodata if nodata is not None else g.nodata if g.nodata is not None else float("nan")
        z[~g.mask] = nd
        b.SetNoDataValue(nd)
    b.WriteArray(z)
    return ds
