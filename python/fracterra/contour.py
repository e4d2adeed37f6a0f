"""Every contour of a mountain from one seed contour (Misawa, Chiba & Saito; contour.h,
docs/contour-mountain.md)."""
import ctypes
import math

from . import _structs as S
from ._lib import lib, check, parse_enum
from ._core import chain_to_numpy, grid_from_c, Progress
from .line import _read_layer

__all__ = ["mountain", "MOUNTAIN_METHODS"]

MOUNTAIN_METHODS = ("simple", "midpoint", "fourier", "improved")
SEED_ELEV_FIELD = b"elev"  # the CLI's: the seed's elevation when every feature holds the same number


def _layer_seed_elevation(lay):
    k = lib.ft_layer_field_index(lay, SEED_ELEV_FIELD)
    L = lay.contents
    if k < 0 or L.fields[k].type == 2 or L.nfeatures == 0:
        return None
    v = None
    for f in range(L.nfeatures):
        x = L.features[f].values[k]
        e = math.nan if x.is_null else (float(x.i) if L.fields[k].type == 0 else x.r)
        if not math.isfinite(e) or (v is not None and e != v):
            return None
        v = e
    return v


def _levels(stack):
    out = []
    for i in range(stack.n):
        lv = stack.levels[i]
        polys = []
        ps = lv.polys.contents
        for j in range(ps.n):
            p = ps.polys[j]
            polys.append((chain_to_numpy(p.outer), [chain_to_numpy(p.holes[h]) for h in range(p.nholes)]))
        out.append((lv.elev, polys))
    return out


def mountain(path, *, method="improved", interval=10.0, spacing=0.0, seed_elevation=None, levels_up=-1,
             levels_down=0, join="dprime", dprime=0.0, dsecond=0.5, theta=(20.0, 40.0), n=1024, f0=256,
             match_dim=True, allow_crossings=False, seed=1, dem=False, cell=0.0, summit=0.5, layer=None, where=None, progress=None,
             progress_arg=None):
    """Grows every contour of a mountain from the seed polygon(s) of a vector layer, as
    `fracterra mountain`. seed_elevation None = the layer's `elev` field when every feature holds the
    same number, else 0 (the CLI's rule). Returns (levels, dem, info): levels a list of (elevation,
    [(outer, [holes])]) with rings as (n, 2) arrays, dem a Grid (when dem=True, as --dem) or None,
    info a dict with the spacing d and d' used and the crossing guard's counts (guard_moves,
    guard_reduced, guard_dropped; allow_crossings=True makes every move in full, as --allow-crossings)."""
    o = S.ft_mountain_opts.default()
    o.method = parse_enum(lib.ft_mountain_method_parse, method, "method")
    o.interval, o.spacing = float(interval), float(spacing)
    o.levels_up, o.levels_down = int(levels_up), int(levels_down)
    o.shrink.join = parse_enum(lib.ft_contour_join_parse, join, "join")
    o.shrink.dprime, o.dsecond = float(dprime), float(dsecond)
    o.theta_min, o.theta_max = (float(t) for t in theta)
    o.fourier.n, o.fourier.f0 = int(n), int(f0)
    o.match_dim = 1 if match_dim else 0
    o.allow_crossings = 1 if allow_crossings else 0
    o.seed = int(seed)
    dopts = S.ft_contour_dem_opts.default()
    dopts.cell, dopts.summit = float(cell), float(summit)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    pr.install(dopts)
    lay = _read_layer(path, layer, where, fields=True)
    ps = ctypes.POINTER(S.ft_polygon_set)()
    stack = ctypes.POINTER(S.ft_contour_stack)()
    try:
        check(lib.ft_polygon_set_from_layer(lay, ctypes.byref(ps)))
        if seed_elevation is None:
            seed_elevation = _layer_seed_elevation(lay)
        o.seed_elevation = float(seed_elevation or 0.0)
        pr.check(lib.ft_mountain_generate(ps, ctypes.byref(o), ctypes.byref(stack)))
        grid = None
        if dem:
            g = ctypes.POINTER(S.ft_grid)()
            pr.check(lib.ft_contour_stack_to_dem(stack, ctypes.byref(dopts), lay.contents.crs_wkt, ctypes.byref(g)))
            grid = grid_from_c(g)
        st = stack.contents
        return _levels(st), grid, {"spacing": st.spacing, "interval": st.interval, "dprime": st.dprime,
                                   "seed_elevation": o.seed_elevation, "guard_moves": st.guard_moves,
                                   "guard_reduced": st.guard_reduced, "guard_dropped": st.guard_dropped}
    finally:
        lib.ft_contour_stack_free(stack)
        lib.ft_polygon_set_free(ps)
        lib.ft_layer_free(lay)
