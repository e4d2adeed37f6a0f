"""Box-counting dimension of polygon layers (urban.h; docs/urban-boxcount.md)."""
import ctypes

import numpy as np

from . import _structs as S
from ._lib import lib, check, parse_enum, FracterraError, FT_E_NOMEM, FT_E_CANCELLED
from ._core import take_result, Progress, crs_info, layer_ground
from ._common import set_fit, set_scales
from .line import _read_layer

__all__ = ["dim_area"]


def dim_area(path, *, what="boundary", by=None, layer=None, where=None, cells=None, min_scale=None,
             max_scale=None, nscales=None, offsets=None, fewest=False, fit=None, regime=None, progress=None,
             progress_arg=None):
    """Box-counting dimension of every polygon of a vector layer, as `fracterra dim area`: what is
    "boundary" (boxes crossed by the rings) or "area" (boxes touching the interior); cells, explicit box
    sides (map units, then every one is fitted), else a geometric series between min_scale and
    max_scale. Returns a DimResult; with by=FIELD (the CLI's --class) a list of (label, result) pairs,
    the whole layer first (label None) then one per value of the field in the library's class order,
    a class that cannot be measured giving its FracterraError instead of a result. As the CLI, a layer
    in longitude/latitude is measured in a Lambert equal-area projection centred on it (sides in
    metres). fewest: the fewest count over the grid origins instead of their mean (biased upward)."""
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
    o.fewest = 1 if fewest else 0
    set_fit(o.fit, fit)
    if regime:
        o.fit.regime = int(regime)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    lp = _read_layer(path, layer, where, fields=by is not None)
    classes = ctypes.POINTER(S.ft_urban_classes)()
    try:
        crs = crs_info(lp.contents.crs_wkt)
        layer_ground(lp, crs)
        whole = _measure(lp, None, 0, o, pr, crs)
        if by is None:
            return whole
        check(lib.ft_urban_classes_by_field(lp, by.encode(), ctypes.byref(classes)))
        out = [(None, whole)]
        cs = classes.contents
        for i in range(cs.n):
            cl = cs.classes[i]
            try:
                out.append((cl.label.decode(), _measure(lp, cl.features, cl.n, o, pr, crs)))
            except FracterraError as e:
                if e.code in (FT_E_NOMEM, FT_E_CANCELLED):
                    raise
                out.append((cl.label.decode(), e))
        return out
    finally:
        lib.ft_urban_classes_free(classes)
        lib.ft_layer_free(lp)


def _measure(lp, features, n, o, pr, crs):
    out = ctypes.POINTER(S.ft_dim_result)()
    pr.check(lib.ft_urban_dim_area(lp, features, n, ctypes.byref(o), ctypes.byref(out)))
    return take_result(out, crs)
