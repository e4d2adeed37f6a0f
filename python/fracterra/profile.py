"""Fractal dimension of a profile, the graph of z against distance (surface.h's profile API; docs/profile.md):
D = 2 - H by the power-variation estimators of Gneiting, Sevcikova & Percival (2012), lags 1 and 2."""
import ctypes
import os

import numpy as np

from . import _structs as S
from ._lib import lib, check, c_free
from ._core import as_grid, _CGrid, take_result
from ._common import path_bytes

__all__ = ["dim_profile", "PROFILE_METHODS"]

PROFILE_METHODS = ("variogram", "madogram")
_DP = ctypes.POINTER(ctypes.c_double)


def _take(zp, n, spacing):
    """A float64 array copied from a library-allocated double * of n values (freed), and the spacing."""
    try:
        return np.ctypeslib.as_array(zp, shape=(n.value,)).copy() if n.value else np.empty(0), spacing.value
    finally:
        c_free(ctypes.cast(zp, ctypes.c_void_p).value)


def _from_grid(g, row, start, end):
    cg = _CGrid(g)
    zp, n, sp = _DP(), ctypes.c_size_t(), ctypes.c_double()
    if row is not None:
        if int(row) < 0:
            raise ValueError("row must be >= 0, got %r" % (row,))
        check(lib.ft_profile_from_grid_row(cg.ref, int(row), ctypes.byref(zp), ctypes.byref(n), ctypes.byref(sp)))
    else:
        (x0, y0), (x1, y1) = start, end
        check(lib.ft_profile_transect(cg.ref, float(x0), float(y0), float(x1), float(y1), ctypes.byref(zp),
                                      ctypes.byref(n), ctypes.byref(sp)))
    return _take(zp, n, sp)


def _from_line(path, layer, spacing):
    x, y, z = _DP(), _DP(), _DP()
    m = ctypes.c_size_t()
    check(lib.ft_io_read_line_z(path_bytes(path), layer.encode() if layer else None, ctypes.byref(x),
                                ctypes.byref(y), ctypes.byref(z), ctypes.byref(m)))
    try:
        zp, n, sp = _DP(), ctypes.c_size_t(), ctypes.c_double()
        check(lib.ft_profile_resample(x, y, z, m.value, float(spacing or 0.0), ctypes.byref(zp), ctypes.byref(n),
                                      ctypes.byref(sp)))
        return _take(zp, n, sp)
    finally:
        for p in (x, y, z):
            c_free(ctypes.cast(p, ctypes.c_void_p).value)


def dim_profile(source, *, row=None, start=None, end=None, spacing=None, method="variogram", band=1, layer=None):
    """Fractal dimension D (1..2) of a profile, as `fracterra dim profile`.

    source: a 1-D array of elevations at a regular spacing (spacing= required, ground units); a Grid or
    2-D array with row= (row N of the grid, at its x cell size) or start=(x, y), end=(x, y) (a transect in
    map coordinates, bilinear at the smaller cell side); or a path: a DEM (band=) with row= or start/end,
    else a 3-D line (layer=) resampled along its horizontal length at spacing= (default: the median
    horizontal segment). method: "variogram" (p = 2), "madogram" (p = 1) or "both" (a list of two results,
    madogram first, as the CLI). Each DimResult's extra holds "profile" ("array", "row", "transect" or
    "line"), "samples" and "spacing"."""
    if method not in PROFILE_METHODS + ("both",):
        raise ValueError("method must be madogram, variogram or both, got %r" % (method,))
    on_grid = row is not None or start is not None or end is not None
    if on_grid and (start is None) != (end is None):
        raise ValueError("start and end go together")
    if row is not None and start is not None:
        raise ValueError("give either row or start/end, not both")
    if isinstance(source, (str, bytes, os.PathLike)):
        if on_grid:
            from .io import read_grid
            z, sp = _from_grid(read_grid(source, band), row, start, end)
            kind = "row" if row is not None else "transect"
        else:
            z, sp = _from_line(source, layer, spacing)
            kind = "line"
    elif on_grid:
        z, sp = _from_grid(as_grid(source), row, start, end)
        kind = "row" if row is not None else "transect"
    else:
        z = np.ascontiguousarray(source, dtype=np.float64)
        if z.ndim != 1:
            raise ValueError("a profile is a 1-D array of elevations; got shape %r (a grid needs row= or "
                             "start=/end=)" % (z.shape,))
        if spacing is None:
            raise ValueError("spacing: the distance between the profile's samples is needed for an array")
        sp, kind = float(spacing), "array"
    methods = (1, 0) if method == "both" else (PROFILE_METHODS.index(method),)
    zp = z.ctypes.data_as(_DP)
    out = []
    for m in methods:
        res = ctypes.POINTER(S.ft_dim_result)()
        check(lib.ft_profile_dim(zp, z.size, sp, m, ctypes.byref(res)))
        r = take_result(res)
        r.extra.update(profile=kind, samples=int(z.size), spacing=sp)
        out.append(r)
    return out if method == "both" else out[0]
