"""Fractal dimension of elevation grids and scattered elevations (surface.h; docs/surface-*.md)."""
import ctypes

import numpy as np

from . import _structs as S
from ._lib import lib, check, parse_enum
from ._core import (as_grid, _CGrid, _CPoints, grid_from_c, take_result, Progress, crs_info, grid_ground,
                    points_ground)
from ._common import set_fit, set_scales, path_bytes

__all__ = ["dim_surface", "dim_map", "dim_points", "SURFACE_METHODS"]

SURFACE_METHODS = ("variogram", "yokoya", "pentland", "spectrum", "prism", "cubes")
# The CLI's --pairs policy (cli/surface_cli.h): exhaustive up to 1024 x 1024 cells, then 32000 points.
EXHAUSTIVE_CELLS = 1024 * 1024
DEFAULT_PAIRS = 32000


_NOISE_MODELS = {"auto": 0, "off": -1}


def _noise_mode(noise_model):
    """The CLI's --noise-model: "auto" (detect a nugget and remove it) or "off"."""
    if noise_model not in _NOISE_MODELS:
        raise ValueError("noise_model must be 'auto' or 'off', got %r" % (noise_model,))
    return _NOISE_MODELS[noise_model]


def _noise_sigmas(noise_sigma, points):
    """(sigma_xy, sigma_z) from the CLI's --noise-sigma: Z, or (XY, Z) for scattered points."""
    if noise_sigma is None:
        return 0.0, 0.0
    if isinstance(noise_sigma, (tuple, list)):
        if not points or len(noise_sigma) != 2:
            raise ValueError("noise_sigma: Z%s, got %r" % (" or (XY, Z)" if points else "", noise_sigma))
        xy, z = (float(v) for v in noise_sigma)
    else:
        xy, z = 0.0, float(noise_sigma)
    if not (xy >= 0.0 and z >= 0.0):
        raise ValueError("noise_sigma must be >= 0, got %r" % (noise_sigma,))
    return xy, z


def _surface_opts(min_scale, max_scale, nscales, fit_whole_range, pairs, seed, zscale, tile, min_valid, fit):
    o = S.ft_surface_dim_opts.default()
    set_scales(o, min_scale, max_scale, nscales, fit_whole_range)
    o.pairs = int(pairs)
    o.seed = int(seed)
    if zscale is not None:
        o.zscale = float(zscale)
    if tile is not None:
        o.tile = int(tile)
    if min_valid is not None:
        o.min_valid = float(min_valid)
    set_fit(o.fit, fit)
    return o


def dim_surface(grid, method="variogram", *, geotransform=None, wkt=None, min_scale=None, max_scale=None,
                nscales=None, fit_whole_range=None, pairs=None, seed=1, zscale=None, tile=None, fit=None,
                regime=None, noise_sigma=None, noise_model="auto", progress=None, progress_arg=None):
    """Fractal dimension D (2..3) of an elevation grid, as `fracterra dim surface`.

    grid: a Grid, a 2-D array (NaN = nodata) or a numpy.ma array; geotransform/wkt apply to arrays.
    method: one of SURFACE_METHODS. Scales are in ground units (the geotransform's). pairs: None = the
    CLI's rule (exhaustive up to 1024² cells, else 32000 random points), 0 = exhaustive, N = N points.
    A grid in longitude/latitude is measured, as by the CLI, on its warp to a transverse Mercator
    centred on it (scales in metres); without a CRS the result warns that scales are in the grid's own
    unit. regime: D from the N-th regime (the CLI's --regime). noise_sigma, noise_model: the CLI's
    --noise-sigma Z and --noise-model auto|off (variogram, yokoya, pentland). Returns a DimResult."""
    g = as_grid(grid, geotransform, wkt)
    crs = crs_info(g.wkt)
    g = grid_ground(g, crs)
    m = parse_enum(lib.ft_surface_method_parse, method, "method")
    if pairs is None:
        pairs = DEFAULT_PAIRS if g.z.size > EXHAUSTIVE_CELLS else 0
    o = _surface_opts(min_scale, max_scale, nscales, fit_whole_range, pairs, seed, zscale, tile, None, fit)
    if regime:
        o.fit.regime = int(regime)
    o.noise.mode = _noise_mode(noise_model)
    o.noise.sigma_z = _noise_sigmas(noise_sigma, False)[1]
    cg = _CGrid(g)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out = ctypes.POINTER(S.ft_dim_result)()
    pr.check(lib.ft_surface_dim(cg.ref, m, ctypes.byref(o), ctypes.byref(out)))
    r = take_result(out, crs)
    r.extra["pairs"] = int(pairs)
    return r


def dim_map(grid, window, step=None, method="variogram", *, geotransform=None, wkt=None, min_scale=None,
            max_scale=None, nscales=None, pairs=0, seed=1, min_valid=0.5, zscale=None, tile=None, fit=None,
            progress=None, progress_arg=None):
    """A local D map, as `fracterra dim map`: D in every window x window cells whose upper-left cell
    is a multiple of step (default window / 4), each window fitted over the same scale range. Returns
    (D, r2): two Grids on the lattice of the window centres, nodata where a window has fewer valid cells
    than min_valid or the method fails. A grid in longitude/latitude is first warped, as by the CLI,
    to a transverse Mercator centred on it."""
    g = as_grid(grid, geotransform, wkt)
    g = grid_ground(g, crs_info(g.wkt))
    m = parse_enum(lib.ft_surface_method_parse, method, "method")
    window = int(window)
    if step is None:
        step = max(1, window // 4)
    o = _surface_opts(min_scale, max_scale, nscales, True, pairs, seed, zscale, tile, min_valid, fit)
    cg = _CGrid(g)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    D = ctypes.POINTER(S.ft_grid)()
    r2 = ctypes.POINTER(S.ft_grid)()
    pr.check(lib.ft_surface_dim_map(cg.ref, window, int(step), m, ctypes.byref(o), ctypes.byref(D),
                                    ctypes.byref(r2)))
    return grid_from_c(D), grid_from_c(r2)


LAG_DTYPE = np.dtype([("lag", "f8"), ("dist", "f8"), ("A", "f8"), ("B", "f8"), ("C", "f8"), ("drawn", "u8"),
                      ("value", "f8"), ("value_se", "f8"), ("status", "U9")])
_LAG_STATUS = ("kept", "few_pairs", "noise", "zero")


def read_points(path, *, x=None, y=None, z=None, weight=None, layer=None, zfield=None):
    """Scattered points through the library's reader (CSV, XYZ text, OGR point layers):
    (x, y, z, w, wkt) with w None when no weight column was named."""
    from ._core import points_to_numpy
    o = S.ft_read_points_opts.default()
    keep = []
    for k, v in (("x", x), ("y", y), ("z", z), ("weight", weight), ("layer", layer), ("zfield", zfield)):
        if v is not None:
            keep.append(v.encode())
            setattr(o, k, keep[-1])
    out = ctypes.POINTER(S.ft_points)()
    check(lib.ft_io_read_points(path_bytes(path), ctypes.byref(o), ctypes.byref(out)))
    try:
        return points_to_numpy(out)
    finally:
        lib.ft_points_free(out)


def dim_points(x, y=None, z=None, w=None, *, method="yokoya", wkt=None, lags=None, eps=None, min_pairs=None,
               exact=False, sample=None, seed=1, noise_sigma=None, noise_model="auto", min_scale=None,
               max_scale=None, nscales=None, fit_auto=False, fit=None, regime=None, progress=None, progress_arg=None,
               **read_opts):
    """Fractal dimension of scattered elevations (Arakawa & Krotkov's counters), as `fracterra dim
    points`. x, y, z: arrays; or x alone a path read by the library (read_opts: x=, y=, z= column
    names are then given as xcol=, ycol=, zcol=, layer=, zfield=). Returns a DimResult whose
    extra["lags"] is the per-lag counter table (dropped lags included, with their status). Points in
    longitude/latitude are projected, as by the CLI, to a transverse Mercator centred on them (lags in
    metres). noise_sigma: Z or (XY, Z), the CLI's --noise-sigma [XY,]Z; noise_model: "auto" or "off"."""
    if y is None and z is None:
        cols = {k[0]: read_opts.pop(k + "col") for k in ("xcol", "ycol", "zcol") if k + "col" in read_opts}
        x, y, z, w_read, wkt_read = read_points(x, **cols, **read_opts)
        w = w if w is not None else w_read
        wkt = wkt or wkt_read
    elif read_opts:
        raise TypeError("unexpected options %s" % ", ".join(read_opts))
    crs = crs_info(wkt)
    x, y = points_ground(x, y, wkt, crs)
    p = _CPoints(x, y, z, w, wkt)
    o = S.ft_points_dim_opts.default()
    o.method = parse_enum(lib.ft_points_method_parse, method, "method")
    keep = None
    if lags is not None:
        keep = np.ascontiguousarray(lags, dtype=np.float64).ravel()
        o.lags = keep.ctypes.data_as(ctypes.POINTER(ctypes.c_double))
        o.nuser_lags = keep.size
    set_scales(o, min_scale, max_scale, nscales, False, ("min_lag", "max_lag", "nlags"))
    if eps is not None:
        o.eps = float(eps)
    if min_pairs is not None:
        o.min_pairs = int(min_pairs)
    o.exact = 1 if exact else 0
    if sample:
        o.sample = int(sample)
    o.seed = int(seed)
    o.noise_sigma_xy, o.noise_sigma = _noise_sigmas(noise_sigma, True)
    o.noise_mode = _noise_mode(noise_model)
    if regime:
        o.fit.regime = int(regime)
    o.fit_auto = 1 if fit_auto else 0
    set_fit(o.fit, fit)
    counters = ctypes.POINTER(S.ft_points_counters)()
    o.counters = ctypes.pointer(counters)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out = ctypes.POINTER(S.ft_dim_result)()
    try:
        pr.check(lib.ft_surface_dim_points(p.ref, ctypes.byref(o), ctypes.byref(out)))
        r = take_result(out, crs)
        c = counters.contents
        table = np.zeros(c.n, LAG_DTYPE)
        for i in range(c.n):
            lg = c.lags[i]
            table[i] = (lg.lag, lg.dist, lg.A, lg.B, lg.C, lg.drawn, lg.value, lg.value_se, _LAG_STATUS[lg.status])
        r.extra.update(lags=table, eps=c.eps, spacing=c.spacing, pairs=c.pairs.decode(),
                       sample_stderr=c.D_sample_se if c.sample else None)
        return r
    finally:
        lib.ft_points_counters_free(counters)
