"""Terrain: synthesis, reconstruction from sparse points or voids, Clarke's model, hillshade
(terrain.h, render.h, io.h; docs/terrain-*.md). Seeds are unsigned 64-bit integers, default 1 as in
the CLI; the same seed gives bit-identical cells on any thread count."""
import ctypes
import math

import numpy as np

from . import _structs as S
from ._lib import lib, check, parse_enum
from ._core import Grid, as_grid, _CGrid, _CPoints, grid_from_c, Progress
from ._common import path_bytes

__all__ = ["synth", "Synthesizer", "reconstruct", "ReconInfo", "clarke_fit", "clarke_simulate", "ClarkeModel", "hillshade",
           "hillshade_file", "fill", "SYNTH_METHODS", "RECON_METHODS"]

SYNTH_METHODS = ("fft", "sra", "midpoint", "exact", "sra-raw", "midpoint-raw")
RECON_METHODS = ("fractal", "conditional", "smooth")


def _wkt_of(crs):
    """WKT from a CRS given as WKT, "EPSG:n" or anything GDAL's OSRSetFromUserInput reads (the CLI's --crs)."""
    if crs is None:
        return None
    out = ctypes.c_void_p()
    check(lib.ft_io_crs_to_wkt(crs.encode(), ctypes.byref(out)))
    try:
        return ctypes.string_at(out).decode()
    finally:
        from ._lib import c_free
        c_free(out)


def _synth_opts(method, dim, sigma, cell, origin, periodic, seed):
    o = S.ft_synth_opts.default()
    o.method = parse_enum(lib.ft_synth_method_parse, method, "method")
    o.dim, o.sigma, o.cell = float(dim), float(sigma), float(cell)
    o.origin_x, o.origin_y = (float(v) for v in origin)
    o.periodic = 1 if periodic else 0
    o.seed = int(seed)
    return o


def synth(nx, ny, dim, *, method="fft", sigma=1.0, cell=1.0, origin=(0.0, 0.0), periodic=False, seed=1,
          crs=None, progress=None, progress_arg=None):
    """A fractional Brownian surface of dimension dim in (2, 3) on nx x ny cells, as `fracterra synth`:
    a Grid (north-up geotransform from origin = upper-left corner and cell; crs as the CLI's --crs)."""
    o = _synth_opts(method, dim, sigma, cell, origin, periodic, seed)
    wkt = _wkt_of(crs)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out = ctypes.POINTER(S.ft_grid)()
    pr.check(lib.ft_terrain_synth(int(nx), int(ny), ctypes.byref(o), ctypes.byref(out)))
    g = grid_from_c(out)
    g.wkt = wkt
    return g


class Synthesizer:
    """Many surfaces of one size, method and periodic flag into reused memory (ft_synth_workspace,
    ft_terrain_synth_into): the working memory (for fft the padded spectrum, 1.6x the grid) is allocated
    and touched once here, so a loop of realizations faults in no fresh memory. Calling it gives the
    Grid `synth` would give for the same arguments, bit for bit; with out= (a C-contiguous float32
    (ny, nx) array) the cells are written there and the Grid wraps out. Use as a context manager or
    call close() to free the workspace early."""

    def __init__(self, nx, ny, *, method="fft", periodic=False):
        self.nx, self.ny, self.method, self.periodic = int(nx), int(ny), method, bool(periodic)
        o = _synth_opts(method, 2.5, 1.0, 1.0, (0.0, 0.0), periodic, 1)
        ws = ctypes.c_void_p()
        check(lib.ft_synth_workspace_create(self.nx, self.ny, ctypes.byref(o), ctypes.byref(ws)))
        self._ws = ws

    def __call__(self, dim, *, sigma=1.0, cell=1.0, origin=(0.0, 0.0), seed=1, crs=None, out=None):
        if self._ws is None:
            raise ValueError("this Synthesizer is closed")
        shape = (self.ny, self.nx)
        if out is None:
            out = np.empty(shape, dtype=np.float32)
        elif not (isinstance(out, np.ndarray) and out.dtype == np.float32 and out.shape == shape
                  and out.flags.c_contiguous and out.flags.writeable):
            raise ValueError("out must be a writeable C-contiguous float32 array of shape %r" % (shape,))
        o = _synth_opts(self.method, dim, sigma, cell, origin, self.periodic, seed)
        wkt = _wkt_of(crs)
        g = S.ft_grid()
        g.ny, g.nx = shape
        g.z = out.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
        check(lib.ft_terrain_synth_into(ctypes.byref(o), self._ws, ctypes.byref(g)))
        return Grid(out, geotransform=tuple(g.gt), wkt=wkt)

    def close(self):
        if getattr(self, "_ws", None) is not None:
            lib.ft_synth_workspace_free(self._ws)
            self._ws = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        self.close()


class ReconInfo:
    """What a reconstruction used and achieved (ft_recon_info): dim, dim_estimated, sigma0, k,
    temperature, levels, data_used, data_outside, filled, data_rms, lambda_, tension."""

    def __init__(self, info):
        for f, _t in S.ft_recon_info._fields_:
            v = getattr(info, f)
            setattr(self, f, bool(v) if f == "dim_estimated" else v)

    def __repr__(self):
        return "ReconInfo(%s)" % ", ".join("%s=%r" % (f, getattr(self, f)) for f, _ in S.ft_recon_info._fields_)


def reconstruct(data, target=None, *, method="fractal", dim=0.0, tension=None, lambda_=1.0, sigma=0.0,
                temperature=0.0, k=0.0, sweeps=0, realizations=1, seed=1, threads=0, progress=None,
                progress_arg=None):
    """Dense terrain from sparse elevations or a DEM with voids (Arakawa & Krotkov), as
    `fracterra reconstruct`. data: a Grid/array with nodata (its voids are filled, valid cells kept),
    or (x, y, z) or (x, y, z, w) arrays with target a Grid (or array) giving the output's shape,
    geotransform and CRS. dim 0 = estimated from the data. tension None = the library's default (from D:
    Szeliski's crossover, see docs/terrain-reconstruct.md). Returns (grid, sd, info): sd is the
    per-cell standard deviation over realizations (None with one realization)."""
    o = S.ft_recon_opts.default()
    o.method = parse_enum(lib.ft_recon_method_parse, method, "method")
    o.dim, o.lambda_, o.sigma = float(dim), float(lambda_), float(sigma)
    if tension is not None:
        o.tension = float(tension)
    o.temperature, o.k, o.sweeps = float(temperature), float(k), int(sweeps)
    o.realizations, o.seed, o.threads = int(realizations), int(seed), int(threads)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out = ctypes.POINTER(S.ft_grid)()
    sd = ctypes.POINTER(S.ft_grid)()
    sd_ref = ctypes.byref(sd) if o.realizations > 1 else None
    info = S.ft_recon_info()
    if isinstance(data, tuple):
        if target is None:
            raise ValueError("reconstruct from points needs target= (a Grid giving shape and geotransform)")
        t = as_grid(target)
        p = _CPoints(*data[:4], wkt=t.wkt)
        ct = _CGrid(t)
        pr.check(lib.ft_reconstruct_points(p.ref, ct.ref, ctypes.byref(o), ctypes.byref(out), sd_ref,
                                           ctypes.byref(info)))
    else:
        cg = _CGrid(as_grid(data))
        pr.check(lib.ft_reconstruct_voids(cg.ref, ctypes.byref(o), ctypes.byref(out), sd_ref, ctypes.byref(info)))
    z = grid_from_c(out)
    s = grid_from_c(sd) if sd else None
    if s is not None:
        s.geotransform, s.wkt = z.geotransform, z.wkt
    return z, s, ReconInfo(info)


HARMONIC_DTYPE = np.dtype([(f, "i4" if f in ("k", "l") else "f8") for f, _ in S.ft_clarke_harmonic._fields_])


class ClarkeModel:
    """Clarke's scale-based model z = T + cF + H fitted to a DEM (ft_clarke_model): the trend
    (beta0, beta1, beta2, trend_r2), the significant harmonics (a structured array), the spectral
    regression (slope, intercept, r2, stderr_slope, npairs, D, D_clarke_eq8) and c. Keeps the C model
    for clarke_simulate."""

    def __init__(self, ptr):
        self._ptr = ptr
        m = ptr.contents
        for f, _t in S.ft_clarke_model._fields_:
            if f in ("harmonics", "crs_wkt", "gt", "spectrum_wavelength", "spectrum_power", "spectrum_count",
                     "regimes", "breaks"):
                continue
            setattr(self, f, getattr(m, f))
        self.geotransform = tuple(m.gt)
        self.wkt = m.crs_wkt.decode() if m.crs_wkt else None
        self.noise = "spectrum" if m.noise == 1 else "power-law"
        self.spectrum = {k: np.array([getattr(m, "spectrum_" + k)[i] for i in range(m.nspectrum)])
                         for k in ("wavelength", "power", "count")}
        self.regimes = [{f: getattr(m.regimes[i], f) for f, _ in S.ft_clarke_regime._fields_}
                        for i in range(m.nregimes)]
        self.breaks = [m.breaks[i] for i in range(max(0, m.nregimes - 1))]
        self.harmonics = np.zeros(m.nharmonics, HARMONIC_DTYPE)
        for i in range(m.nharmonics):
            h = m.harmonics[i]
            self.harmonics[i] = tuple(getattr(h, f) for f, _ in S.ft_clarke_harmonic._fields_)

    def __del__(self):
        if getattr(self, "_ptr", None):
            lib.ft_clarke_model_free(self._ptr)
            self._ptr = None

    def __repr__(self):
        return "ClarkeModel(D=%.4f, %d harmonics, c=%.4g)" % (self.D, self.nharmonics, self.c)


def clarke_fit(dem, *, cutoff=2.5, taper=True, min_wavelength=4.0, noise="spectrum", progress=None,
               progress_arg=None):
    """Fits Clarke's model to a DEM (a Grid or array), as `fracterra model`'s fit. noise: the F the model
    simulates, "spectrum" (the DEM's measured radial spectrum) or "power-law" (Clarke's one law)."""
    if noise not in ("spectrum", "power-law"):
        raise ValueError("noise must be 'spectrum' or 'power-law', got %r" % (noise,))
    o = S.ft_clarke_opts.default()
    o.cutoff, o.taper, o.min_wavelength = float(cutoff), 1 if taper else 0, float(min_wavelength)
    o.noise = 1 if noise == "spectrum" else 0
    pr = Progress(progress, progress_arg)
    pr.install(o)
    cg = _CGrid(as_grid(dem))
    out = ctypes.POINTER(S.ft_clarke_model)()
    pr.check(lib.ft_clarke_fit(cg.ref, ctypes.byref(o), ctypes.byref(out)))
    return ClarkeModel(out)


def clarke_simulate(model, *, refine=1, extent=1, seed=1, progress=None, progress_arg=None):
    """Simulates T + cF + H from a ClarkeModel on (extent * refine) times the fitted cells per axis.
    Returns (grid, c_used)."""
    o = S.ft_clarke_sim_opts.default()
    o.refine, o.extent, o.seed = int(refine), int(extent), int(seed)
    c_used = ctypes.c_double()
    o.c_used = ctypes.pointer(c_used)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out = ctypes.POINTER(S.ft_grid)()
    pr.check(lib.ft_clarke_simulate(model._ptr, ctypes.byref(o), ctypes.byref(out)))
    return grid_from_c(out), c_used.value


def hillshade(dem, *, azimuth=315.0, altitude=45.0, z_factor=1.0, scale=1.0, geotransform=None):
    """The library's in-memory hillshade of a grid (ft_render_hillshade: Horn's 3x3 slope and aspect, as
    gdaldem -compute_edges): a Grid of shades in [0, 255], nodata only where the DEM is, with the input's
    geotransform and CRS. scale: ground units of the horizontal coordinates per elevation unit (gdaldem's
    -s). `fracterra hillshade` on files (same engine) is hillshade_file."""
    o = S.ft_hillshade_opts.default()
    o.azimuth, o.altitude, o.z_factor, o.scale = float(azimuth), float(altitude), float(z_factor), float(scale)
    # the engine takes a non-finite cell as nodata itself, and its mask bytes are 0 or 1 (render/hillshade.c)
    cg = _CGrid(as_grid(dem, geotransform), nonfinite_is_nodata=True)
    out = ctypes.POINTER(S.ft_grid)()
    check(lib.ft_render_hillshade(cg.ref, ctypes.byref(o), ctypes.byref(out)))
    return grid_from_c(out, mask_view=True)


def hillshade_file(dem_path, out_path, *, azimuth=315.0, altitude=45.0, z_factor=1.0, scale=0.0, color=False,
                   band=1):
    """The hillshade of a DEM file written to out_path (PNG, GeoTIFF, ... by extension) as gdaldem writes it,
    exactly `fracterra hillshade` (ft_io_hillshade). scale 0 = the metres of a degree of latitude at the
    DEM's centre for a DEM in degrees, else 1."""
    o = S.ft_io_hillshade_opts.default()
    o.azimuth, o.altitude, o.z_factor, o.scale = float(azimuth), float(altitude), float(z_factor), float(scale)
    o.color, o.band = 1 if color else 0, int(band)
    check(lib.ft_io_hillshade(path_bytes(dem_path), path_bytes(out_path), ctypes.byref(o)))


def _void_dict(v, i):
    """One void as the CLI's JSON "voids" item (cli/cmd_fill.c)."""
    d = {"id": i, "cells_box": [v.x0, v.y0, v.x1, v.y1], "cells": v.cells, "edge": bool(v.edge),
         "filled": bool(v.filled)}
    if v.filled:
        flat = v.source == 3  # FT_FILL_D_FLAT
        d.update(D=None if flat else v.D, amplitude=0.0 if flat else v.amplitude,
                 r2=v.r2 if math.isfinite(v.r2) else None, D_source=lib.ft_fill_d_source_name(v.source).decode(),
                 ring_cells=v.ring_cells, conditioning_cells=v.conditioning)
    w = []
    if not v.filled:
        w.append("larger than --max-void: left nodata")
    if v.clamped:
        w.append("the ring's variogram slope gave D outside [2.01, 2.99]: clamped")
    if v.filled and v.source == 1:  # FT_FILL_D_DEM
        w.append("too few valid pairs in the ring: D and amplitude from the whole DEM")
    if v.filled and v.source == 3:
        w.append("flat surroundings: filled with the kriging mean")
    d["warnings"] = w
    return d


def fill(dem, *, valid=None, max_void=100, mean=False, realizations=1, dim=None, ring=None, seed=1,
         geotransform=None, wkt=None, progress=None, progress_arg=None):
    """Fills the nodata voids of a DEM by conditional simulation (ft_terrain_fill), as `fracterra fill`:
    a power variogram fitted on a ring around each void, the kriging of the cells within 2 cells of it
    plus an fBm of that variogram minus its own kriging; valid cells are kept bit for bit.

    dem: a Grid, 2-D array (NaN = nodata) or numpy.ma array. valid: None, or a bool array of the DEM's
    shape whose False cells are filled too (the CLI's --mask). max_void: voids whose bounding box is
    longer than this many cells stay nodata (0 = fill all; the CLI's "Nm" ground form is not wrapped).
    mean: the kriging mean instead of a realization; realizations N > 1: the per-cell mean and sd of N.
    dim: D in (2, 3) for every void (None = fitted per void); ring: ring width in cells (None = auto).
    Returns (grid, sd, info): sd a Grid with realizations > 1 (else None); info the CLI's JSON members
    voids_found, voids_filled, cells_filled, cells_left and voids (a list of dicts)."""
    g = as_grid(dem, geotransform, wkt)
    o = S.ft_fill_opts.default()
    o.max_void = float(max_void)
    o.mean = 1 if mean else 0
    o.realizations = int(realizations)
    if dim is not None:
        o.dim = float(dim)
    if ring is not None:
        o.ring = int(ring)
    o.seed = int(seed)
    cg = _CGrid(g)
    keep = None
    if valid is not None:
        keep = np.ascontiguousarray(valid, dtype=np.uint8)
        if keep.shape != g.z.shape:
            raise ValueError("valid has shape %r, the DEM %r" % (keep.shape, g.z.shape))
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out, sd = ctypes.POINTER(S.ft_grid)(), ctypes.POINTER(S.ft_grid)()
    res = ctypes.POINTER(S.ft_fill_result)()
    vp = keep.ctypes.data_as(ctypes.POINTER(ctypes.c_uint8)) if keep is not None else None
    pr.check(lib.ft_terrain_fill(cg.ref, vp, ctypes.byref(o), ctypes.byref(out),
                                 ctypes.byref(sd) if o.realizations > 1 else None, ctypes.byref(res)))
    try:
        r = res.contents
        info = {"voids_found": r.nvoids, "voids_filled": r.voids_filled, "cells_filled": r.cells_filled,
                "cells_left": r.cells_left, "voids": [_void_dict(r.voids[i], i + 1) for i in range(r.nvoids)]}
    finally:
        lib.ft_fill_result_free(res)
    z = grid_from_c(out)
    return z, (grid_from_c(sd) if sd else None), info
