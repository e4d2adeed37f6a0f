"""Box-counting dimension of polygon layers (urban.h; docs/urban-boxcount.md)."""
import ctypes

import numpy as np

from . import _structs as S
from ._lib import lib, parse_enum
from ._core import take_result, Progress
from ._common import set_fit, set_scales
from .line import _read_layer

__all__ = ["dim_area"]


def dim_area(path, *, what="boundary", layer=None, where=None, cells=None, min_scale=None, max_scale=None,
             nscales=None, offsets=None, fit=None, progress=None, progress_arg=None):
    """Box-counting dimension of every polygon of a vector layer, as `fracterra dim area` without
    --class: what is "boundary" (boxes crossed by the rings) or "area" (boxes touching the interior);
    cells, explicit box sides (map units, then every one is fitted), else a geometric series between
    min_scale and max_scale. Returns a DimResult."""
    o = S.ft_area_dim_opts.default()
    o.what = parse_enum(lib.ft_area_what_parse, what, "what")
    keep = None
    if cells is not None:
        keep = np.ascontiguousarray(cells, dtype=np.float64).ravel()
        o.cells = keep.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
        o.ncells = keep.size
    set_scales(o, min_scale, max_scale, nscales, None, ("min_cell", "max_cell", "nscales"))
    o.fit_whole_range = 1 if (keep is not None and keep.size) or (min_scale and max_scale) else 0
    if offsets is not None:
        o.offsets = int(offsets)
    set_fit(o.fit, fit)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    lp = _read_layer(path, layer, where)
    out = ctypes.POINTER(S.ft_dim_result)()
    try:
        pr.check(lib.ft_urban_dim_area(lp, None, 0, ctypes.byref(o), ctypes.byref(out)))
    finally:
        lib.ft_layer_free(lp)
    return take_result(out)
