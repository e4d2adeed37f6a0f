"""Conversions between NumPy and the library's types: grids, chains, points, dimension results, and
the progress callback."""
import ctypes
import math

import numpy as np

from . import _structs as S
from ._lib import lib, check, check_ptr, c_free, c_strdup

__all__ = ["Grid", "DimResult"]

IDENTITY_GT = (0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
_DP = ctypes.POINTER(ctypes.c_double)


class Grid:
    """A raster as fracterra sees it: z, a (rows, cols) float32 array with row 0 at the top (north);
    mask, None (every cell valid) or a bool array of the same shape (True = valid); geotransform,
    GDAL's six coefficients; wkt, the CRS as WKT or None; nodata, the value written back for masked
    cells or None."""

    __slots__ = ("z", "mask", "geotransform", "wkt", "nodata")

    def __init__(self, z, mask=None, geotransform=None, wkt=None, nodata=None):
        z = np.asarray(z)
        if z.ndim != 2:
            raise ValueError("a grid is a 2-D array (rows, cols); got shape %r" % (z.shape,))
        self.z = z
        self.mask = None if mask is None else np.asarray(mask, dtype=bool)
        if self.mask is not None and self.mask.shape != z.shape:
            raise ValueError("mask shape %r differs from the grid's %r" % (self.mask.shape, z.shape))
        gt = IDENTITY_GT if geotransform is None else tuple(float(v) for v in geotransform)
        if len(gt) != 6:
            raise ValueError("a geotransform has 6 coefficients, got %d" % len(gt))
        self.geotransform = gt
        self.wkt = wkt
        self.nodata = nodata

    @property
    def shape(self):
        return self.z.shape

    def masked(self):
        """z as a numpy.ma array (nodata masked)."""
        return np.ma.array(self.z, mask=None if self.mask is None else ~self.mask)

    def __repr__(self):
        return "Grid(%d x %d cells, gt=%r%s)" % (self.z.shape[1], self.z.shape[0], self.geotransform,
                                                 ", with CRS" if self.wkt else "")


def as_grid(g, geotransform=None, wkt=None):
    """A Grid from a Grid, a numpy.ma array or a 2-D array (NaN cells are nodata)."""
    if isinstance(g, Grid):
        return g
    if isinstance(g, np.ma.MaskedArray):
        m = np.ma.getmaskarray(g)
        return Grid(np.ma.getdata(g), mask=~m if m.any() else None, geotransform=geotransform, wkt=wkt)
    return Grid(g, geotransform=geotransform, wkt=wkt)


class _CGrid:
    """An ft_grid over a Grid's memory for a call taking `const ft_grid *`: no copy when z is a
    C-contiguous float32 array (the library only reads it). Keeps what it points at alive."""

    def __init__(self, grid, nonfinite_is_nodata=False):
        """nonfinite_is_nodata: the C function itself takes a non-finite cell as nodata (ft_render_hillshade),
        so no mask need be made for NaN/Inf cells."""
        z = grid.z
        if z.dtype != np.float32 or not z.flags.c_contiguous:
            z = np.ascontiguousarray(z, dtype=np.float32)
        mask = grid.mask
        if mask is None and not nonfinite_is_nodata:
            with np.errstate(over="ignore", invalid="ignore"):
                total = z.sum()  # z is float32 here: a sum needs no temporary, unlike np.isfinite(z).all()
            if not np.isfinite(total):  # a NaN or Inf cell, or a sum that overflowed (every cell may be finite)
                finite = np.isfinite(z)
                mask = None if finite.all() else finite
        self._z = z
        self._mask = None if mask is None else np.ascontiguousarray(mask, dtype=np.uint8)
        self._wkt = grid.wkt.encode() if grid.wkt else None
        s = S.ft_grid()
        s.ny, s.nx = z.shape
        s.z = z.ctypes.data_as(ctypes.POINTER(ctypes.c_float))
        if self._mask is not None:
            s.mask = self._mask.ctypes.data_as(ctypes.POINTER(ctypes.c_uint8))
        s.gt[:] = grid.geotransform
        s.crs_wkt = self._wkt
        if grid.nodata is not None:
            s.has_nodata, s.nodata_value = 1, float(grid.nodata)
        self.struct = s

    @property
    def ref(self):
        return ctypes.byref(self.struct)


class _Owner:
    """Frees a library-allocated object when the last NumPy view of its memory goes."""

    def __init__(self, ptr, free):
        self.ptr, self.free = ptr, free

    def __del__(self):
        if self.ptr:
            self.free(self.ptr)
            self.ptr = None


def grid_from_c(ptr, mask_view=False):
    """A Grid over a library-allocated ft_grid *: z is a view of its cells (no copy), freed with the
    array; the geotransform and CRS are copied, and so is the mask unless mask_view (for a C function
    whose mask bytes are exactly 0 or 1, read as a bool view)."""
    g = ptr.contents
    ny, nx = g.ny, g.nx
    owner = _Owner(ptr, lib.ft_grid_free)
    buf = (ctypes.c_float * (nx * ny)).from_address(ctypes.addressof(g.z.contents)) if nx * ny else None
    if buf is None:
        z = np.zeros((ny, nx), np.float32)
    else:
        buf._fracterra_owner = owner
        z = np.frombuffer(buf, dtype=np.float32).reshape(ny, nx)
    mask = None
    if g.mask and mask_view:
        mbuf = (ctypes.c_uint8 * (nx * ny)).from_address(ctypes.addressof(g.mask.contents))
        mbuf._fracterra_owner = owner
        mask = np.frombuffer(mbuf, dtype=np.bool_).reshape(ny, nx)
    elif g.mask:
        mask = np.ctypeslib.as_array(g.mask, shape=(ny * nx,)).reshape(ny, nx).astype(bool)
    wkt = g.crs_wkt.decode() if g.crs_wkt else None
    return Grid(z, mask=mask, geotransform=tuple(g.gt), wkt=wkt,
                nodata=g.nodata_value if g.has_nodata else None)


# ---- chains ----

def xy_arrays(x, y=None):
    """(x, y) float64 contiguous arrays from x and y, or from one (n, 2) array."""
    if y is None:
        a = np.asarray(x, dtype=np.float64)
        if a.ndim != 2 or a.shape[1] != 2:
            raise ValueError("coordinates: expected an (n, 2) array or x and y, got shape %r" % (a.shape,))
        return np.ascontiguousarray(a[:, 0]), np.ascontiguousarray(a[:, 1])
    x = np.ascontiguousarray(x, dtype=np.float64).ravel()
    y = np.ascontiguousarray(y, dtype=np.float64).ravel()
    if x.shape != y.shape:
        raise ValueError("x has %d values and y %d" % (x.size, y.size))
    return x, y


def chain_new(x, y, closed):
    """A library ft_chain * copied from coordinate arrays (free with ft_chain_free)."""
    dp = ctypes.POINTER(ctypes.c_double)
    return check_ptr(lib.ft_chain_from_arrays(x.ctypes.data_as(dp), y.ctypes.data_as(dp), x.size, 1,
                                              1 if closed else 0))


def chain_from_coords(coords, y=None, closed=False):
    """An ft_chain * from x and y, or from an (n, 2) array: a C-contiguous float64 (n, 2) array is read
    in place as interleaved x y (stride 2), the library's one copy being the only one."""
    if y is None:
        a = np.asarray(coords)
        if a.ndim == 2 and a.shape[1] == 2 and a.dtype == np.float64 and a.flags.c_contiguous:
            dp = ctypes.POINTER(ctypes.c_double)
            base = a.ctypes.data
            return check_ptr(lib.ft_chain_from_arrays(ctypes.cast(base, dp), ctypes.cast(base + 8, dp), a.shape[0],
                                                      2, 1 if closed else 0))
    x, yy = xy_arrays(coords, y)
    return chain_new(x, yy, closed)


def chain_to_numpy(ptr):
    """An (n, 2) float64 array copied from an ft_chain *."""
    c = ptr.contents
    out = np.empty((c.n, 2))
    if c.n:
        nbytes = 8 * c.n
        out[:, 0] = np.frombuffer((ctypes.c_char * nbytes).from_address(ctypes.addressof(c.x.contents)), np.float64)
        out[:, 1] = np.frombuffer((ctypes.c_char * nbytes).from_address(ctypes.addressof(c.y.contents)), np.float64)
    return out


def _double_ptr(a):
    """A double * to a contiguous float64 array's first element (the fast route for writable arrays)."""
    try:
        return ctypes.pointer(ctypes.c_double.from_buffer(a))
    except (TypeError, ValueError):  # read-only or empty
        return ctypes.cast(a.ctypes.data, _DP)


class _CChain:
    """An ft_chain over two float64 arrays for a call taking `const ft_chain *` (no copy when they are
    contiguous float64; the library only reads them)."""

    def __init__(self, x, y, closed):
        self._x, self._y = xy_arrays(x, y)
        s = S.ft_chain(_double_ptr(self._x), _double_ptr(self._y), self._x.size, self._x.size, 1 if closed else 0)
        self.struct = s
        self.ref = ctypes.byref(s)


def _chain_addresses(c):
    return (ctypes.c_void_p.from_buffer(c, S.ft_chain.x.offset).value,
            ctypes.c_void_p.from_buffer(c, S.ft_chain.y.offset).value)


def chain_views(ptr):
    """(x, y): NumPy views of a library-allocated ft_chain's coordinates (no copy), the chain freed
    with the last of them."""
    c = ptr.contents
    if c.n == 0:
        lib.ft_chain_free(ptr)
        return np.empty(0), np.empty(0)
    owner = _Owner(ptr, lib.ft_chain_free)
    return tuple(np.asarray(_Memory(a, (c.n,), "<f8", owner)) for a in _chain_addresses(c))


def chain_xy_view(ptr):
    """An (n, 2) float64 NumPy view of a library-allocated ft_chain (no copy), the chain freed with the
    view: column 0 is the chain's x array and column 1 its y array, so the row stride is 8 bytes and the
    column stride is the distance from x to y. Each column is contiguous; the array is not C-ordered
    (np.ascontiguousarray gives an interleaved copy)."""
    c = ptr.contents
    if c.n == 0:
        lib.ft_chain_free(ptr)
        return np.empty((0, 2))
    owner = _Owner(ptr, lib.ft_chain_free)
    ax, ay = _chain_addresses(c)
    return np.asarray(_Memory(ax, (c.n, 2), "<f8", owner, (8, ay - ax)))


class _Memory:
    """Library memory seen by NumPy through the array interface (base of the array), keeping the
    owner that frees it alive."""

    __slots__ = ("__array_interface__", "owner")

    def __init__(self, addr, shape, typestr, owner, strides=None):
        self.__array_interface__ = {"data": (addr, False), "shape": shape, "typestr": typestr, "version": 3,
                                    "strides": strides}
        self.owner = owner


class ChainSet:
    """A list of ft_chain * made from Python coordinates for a call taking `const ft_chain *const *`,
    freed together: an (n, 2) array is copied by the library (stride 2 when C-ordered float64), an (x, y)
    pair of arrays is read in place (no copy when they are contiguous float64)."""

    def __init__(self, chains):
        self.ptrs, self._owned, self._borrowed = [], [], []
        try:
            for coords, closed in chains:
                if isinstance(coords, tuple):
                    cc = _CChain(coords[0], coords[1], closed)
                    self._borrowed.append(cc)
                    self.ptrs.append(ctypes.pointer(cc.struct))
                else:
                    p = chain_from_coords(coords, None, closed)
                    self._owned.append(p)
                    self.ptrs.append(p)
        except Exception:
            self.close()
            raise
        self.array = (ctypes.POINTER(S.ft_chain) * max(1, len(self.ptrs)))(*self.ptrs)

    def close(self):
        for p in self._owned:
            lib.ft_chain_free(p)
        self.ptrs, self._owned, self._borrowed = [], [], []

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


# ---- points ----

class _CPoints:
    """An ft_points over float64 arrays (no copy when they are contiguous float64)."""

    def __init__(self, x, y, z, w=None, wkt=None):
        arrs = [np.ascontiguousarray(v, dtype=np.float64).ravel() for v in (x, y, z)]
        if not arrs[0].size == arrs[1].size == arrs[2].size:
            raise ValueError("x, y and z differ in length: %d, %d, %d" % tuple(a.size for a in arrs))
        self._keep = arrs
        dp = ctypes.POINTER(ctypes.c_double)
        s = S.ft_points()
        s.x, s.y, s.z = (a.ctypes.data_as(dp) for a in arrs)
        if w is not None:
            w = np.ascontiguousarray(w, dtype=np.float64).ravel()
            if w.size != arrs[0].size:
                raise ValueError("w has %d values, x %d" % (w.size, arrs[0].size))
            self._keep.append(w)
            s.w = w.ctypes.data_as(dp)
        s.n = s.cap = arrs[0].size
        self._wkt = wkt.encode() if wkt else None
        s.crs_wkt = self._wkt
        self.struct = s

    @property
    def ref(self):
        return ctypes.byref(self.struct)


def points_to_numpy(ptr):
    p = ptr.contents
    n = p.n
    cols = [np.ctypeslib.as_array(getattr(p, k), shape=(n,)).copy() if n else np.empty(0) for k in "xyz"]
    w = np.ctypeslib.as_array(p.w, shape=(n,)).copy() if p.w and n else None
    return cols[0], cols[1], cols[2], w, (p.crs_wkt.decode() if p.crs_wkt else None)


# ---- results ----

TABLE_DTYPE = np.dtype([("scale", "f8"), ("value", "f8"), ("count", "f8"), ("slope", "f8"), ("used", "?")])
SEGMENT_DTYPE = np.dtype([("first", "i8"), ("last", "i8"), ("n", "i8"), ("scale_lo", "f8"), ("scale_hi", "f8"),
                          ("slope", "f8"), ("intercept", "f8"), ("D", "f8"), ("r2", "f8"), ("stderr_D", "f8"),
                          ("max_err", "f8"), ("D_minimax", "f8")])


_NONE = ctypes.c_size_t(-1).value


def _noise_model(m):
    """The white-noise (nugget) model of a lag estimator as the CLI's JSON "noise" member, or None when
    none was fitted (docs/surface-noise.md)."""
    if not m.fitted:
        return None
    d = {"detected": bool(m.detected or m.applied), "removed": bool(m.applied), "sigma_z": m.sigma_z}
    if m.s > 0.0 or m.sigma_xy > 0.0:
        d["sigma_xy"] = m.sigma_xy
    d.update(nugget=m.c0, H=m.H, F=m.F, floor=m.floor)
    return d


def _regime_dicts(regimes, chosen):
    return [{"min_scale": float(s["scale_lo"]), "max_scale": float(s["scale_hi"]), "D": float(s["D"]),
             "se": float(s["stderr_D"]), "r2": float(s["r2"]), "rows": int(s["n"]), "chosen": i == chosen}
            for i, s in enumerate(regimes)]


class DimResult:
    """A fractal dimension with everything needed to judge it (docs/loglog.md): D, stderr (of D), r2,
    range (the scales of the first and last used rows), units, method, segmentation, noise, max_err,
    table (a NumPy structured array: scale, value, count, slope, used), segments (structured array of
    the minimax segments), best (index of the segment that gave D, or None), regimes (structured
    array of the straight runs by increasing scale, same fields as segments), regime (index in regimes
    of the one that gave D, or None), breaks (scales where neighbouring regimes meet, len(regimes) - 1),
    choice (why these rows give D), noise (the noise level of the segmentation), noise_model (dict of the
    lag estimators' nugget model: detected, removed, sigma_z, [sigma_xy,] nugget, H, F, floor; None when
    not fitted), warnings (list of str), slope and intercept of the least-squares line, and extra (what the call adds, e.g. counters).
    table, segments and regimes are copied from the C result when first read (then it is freed)."""

    def __init__(self, ptr, owner=None):
        r = ptr.contents
        self.method = r.method.decode() if r.method else None
        self.segmentation = r.segmentation.decode() if r.segmentation else None
        self.D = r.D
        self.r2 = r.r2
        self.stderr = r.stderr_D
        self.range = (r.range[0], r.range[1])
        self.max_err = r.max_err
        self.noise = r.noise
        self.slope = r.fit.slope
        self.intercept = r.fit.intercept
        self.units = r.units.decode()
        self._arrays, self._c = None, (ptr, owner)
        if owner is None:
            self._build()
        self.best = None if r.best == _NONE else int(r.best)
        self.regime = None if r.regime == _NONE or r.nregimes == 0 else int(r.regime)
        self.breaks = [float(r.breaks[i]) for i in range(r.nregimes - 1)] if r.breaks and r.nregimes > 1 else []
        self.choice = r.choice.decode() if r.choice else ""
        self.noise_model = _noise_model(r.nugget)
        self.warnings = [r.warnings[i].decode("utf-8", "replace") for i in range(r.nwarnings)]
        self.extra = {}

    def _build(self):
        """table, segments and regimes copied from the C result, which is released afterwards (with an
        owner, the first access builds them: a caller that reads only D does not pay for them)."""
        if self._arrays is not None:
            return self._arrays
        r = self._c[0].contents
        t = r.table.contents if r.table else None
        n = t.n if t else 0
        table = np.zeros(n, TABLE_DTYPE)
        for i in range(n):
            row = t.rows[i]
            table[i] = (row.scale, row.value, row.count, row.slope, bool(row.used))
        segments = np.zeros(r.nsegments, SEGMENT_DTYPE)
        for i in range(r.nsegments):
            s = r.segments[i]
            segments[i] = tuple(getattr(s, f) for f, _ in S.ft_loglog_segment._fields_)
        regimes = np.zeros(r.nregimes, SEGMENT_DTYPE)
        for i in range(r.nregimes):
            s = r.regimes[i]
            regimes[i] = tuple(getattr(s, f) for f, _ in S.ft_loglog_segment._fields_)
        self._arrays, self._c = (table, segments, regimes), None
        return self._arrays

    table = property(lambda self: self._build()[0], doc="the log-log table (structured array)")
    segments = property(lambda self: self._build()[1], doc="the minimax segments (structured array)")
    regimes = property(lambda self: self._build()[2], doc="the straight runs by increasing scale")

    def __getstate__(self):
        self._build()
        return self.__dict__

    def as_dict(self):
        """The result as plain Python values (the CLI's JSON members of the same names)."""
        return {"method": self.method, "segmentation": self.segmentation, "D": self.D, "r2": self.r2,
                "stderr": self.stderr, "range": list(self.range), "units": self.units,
                "max_err": self.max_err, "choice": self.choice,
                "regime": None if self.regime is None else self.regime + 1,
                "regimes": _regime_dicts(self.regimes, self.regime), "breaks": list(self.breaks),
                "warnings": list(self.warnings),
                "table": [dict(zip(TABLE_DTYPE.names, (float(a), float(b), float(c), float(d), bool(e))))
                          for a, b, c, d, e in self.table.tolist()],
                **({"noise": dict(self.noise_model)} if self.noise_model is not None else {})}

    def __repr__(self):
        return "DimResult(method=%r, D=%.4f, stderr=%.4f, r2=%.4f, range=%.6g..%.6g%s%s)" % (
            self.method, self.D, self.stderr, self.r2, self.range[0], self.range[1],
            " " + self.units if self.units else "", ", %d warning(s)" % len(self.warnings) if self.warnings else "")


def take_result(out, crs=None):
    """A DimResult from the ft_dim_result * the library filled (out, the pointer whose address the call
    was given), which the DimResult owns from here: the C result is freed once its arrays are built or
    with the DimResult. With crs (an ft_crs_info from crs_info), the units and the no-CRS warning as the
    CLI sets them (cli_geo_units)."""
    ptr = ctypes.cast(out, ctypes.POINTER(S.ft_dim_result))  # a copy of the pointer value
    owner = _Owner(ptr, lib.ft_dim_result_free)
    if crs is not None:
        geo_units(ptr, crs)
    return DimResult(ptr, owner)


# ---- geographic input (the CLI's cli_geo.c) ----

FT_LOCAL_LAEA, FT_LOCAL_TMERC = 0, 1
NO_CRS_WARNING = "the input has no CRS: scales are in its own coordinate unit, taken as planar"
_NO_CRS_WARNING_BYTES = NO_CRS_WARNING.encode()


_no_crs = []  # the bytes of crs_info(None), asked of the library once (a value struct: no pointers)


def crs_info(wkt):
    """The library's CRS service (ft_io_crs_info) on a WKT (None: no CRS): a new ft_crs_info."""
    if wkt is None and _no_crs:
        return S.ft_crs_info.from_buffer_copy(_no_crs[0])
    info = S.ft_crs_info()
    check(lib.ft_io_crs_info(wkt.encode() if isinstance(wkt, str) else wkt, ctypes.byref(info)))
    if wkt is None:
        _no_crs.append(bytes(info))
    return info


def geo_units(out, crs):
    """Sets the result's units from the CRS ("m" for lon/lat and metre CRSs, "ft", ...), or without a
    CRS warns that the scales are in the data's own unit; nothing if the estimator set units."""
    if out.contents.units:
        return
    if crs.scale_unit:
        lib.ft_dim_result_set_units(out, crs.scale_unit)
    elif not crs.has_crs:
        lib.ft_dim_result_warn(out, b"%s", _NO_CRS_WARNING_BYTES)


def _local_crs(wkt, kind, x0, y0, x1, y1):
    p = ctypes.c_void_p()
    check(lib.ft_io_local_crs(wkt.encode(), kind, 0.5 * (x0 + x1), 0.5 * (y0 + y1), ctypes.byref(p)))
    try:
        return ctypes.string_at(p.value)
    finally:
        c_free(p.value)


def grid_ground(grid, crs):
    """A lon/lat grid warped to a transverse Mercator centred on it, cells of the same ground area
    (cli_geo_grid_local); other grids unchanged."""
    if not crs.geographic:
        return grid
    cg = _CGrid(grid)
    e = [ctypes.c_double() for _ in range(4)]
    lib.ft_grid_extent(cg.ref, *(ctypes.byref(v) for v in e))
    x0, y0, x1, y1 = (v.value for v in e)
    local = _local_crs(grid.wkt, FT_LOCAL_TMERC, x0, y0, x1, y1)
    per_lon, per_lat = ctypes.c_double(), ctypes.c_double()
    lib.ft_ellipsoid_metres_per_degree(ctypes.byref(crs.ellipsoid), 0.5 * (y0 + y1), ctypes.byref(per_lon),
                                       ctypes.byref(per_lat))
    gt = grid.geotransform
    cell = math.sqrt(abs(gt[1]) * per_lon.value * abs(gt[5]) * per_lat.value)
    out = ctypes.POINTER(S.ft_grid)()
    check(lib.ft_io_grid_reproject(cg.ref, local, cell, ctypes.byref(out)))
    return grid_from_c(out)


def layer_ground(lp, crs, kind=FT_LOCAL_LAEA):
    """Reprojects a library layer (ft_layer *) in lon/lat in place to a local projection centred on its
    bounding box (cli_geo_layer_ground); other layers unchanged."""
    if not crs.geographic:
        return
    e = [ctypes.c_double() for _ in range(4)]
    check(lib.ft_layer_bbox(lp, *(ctypes.byref(v) for v in e)))
    local = _local_crs(lp.contents.crs_wkt.decode(), kind, *(v.value for v in e))
    check(lib.ft_io_layer_reproject(lp, local))


def points_ground(x, y, wkt, crs, kind=FT_LOCAL_TMERC, bbox=None):
    """(x, y) of lon/lat points projected to a local projection (transverse Mercator for points, as
    cli_geo_points_ground; Lambert equal-area for box counts, as cli_geo_layer_local) centred on bbox
    (default: theirs), in metres; other points unchanged."""
    if not crs.geographic or len(x) == 0:
        return x, y
    x = np.array(x, dtype=np.float64).ravel()
    y = np.array(y, dtype=np.float64).ravel()
    local = _local_crs(wkt, kind, *(bbox or (x.min(), y.min(), x.max(), y.max())))
    p = _CPoints(x, y, np.zeros_like(x))
    addr = c_strdup(wkt.encode())
    p.struct.crs_wkt = ctypes.cast(addr, ctypes.c_char_p)
    try:
        check(lib.ft_io_points_reproject(p.ref, local))
    finally:
        c_free(ctypes.c_void_p.from_buffer(p.struct, S.ft_points.crs_wkt.offset).value)
    return p._keep[0], p._keep[1]


# ---- progress ----

class Progress:
    """Wraps a Python callable fn(frac, message, arg) (GDAL's signature: GDALTermProgress-style, or
    osgeo.gdal.TermProgress_nocb) as the library's ft_progress_fn. A false (but not None) return value
    cancels the call (FracterraError with code FT_E_CANCELLED); an exception in fn cancels it too and
    is raised again after the call."""

    def __init__(self, fn, arg=None):
        self.fn, self.arg, self.error = fn, arg, None
        self.c = S.PROGRESS(self._call) if fn is not None else None

    def _call(self, frac, msg, _):
        try:
            r = self.fn(frac, msg.decode("utf-8", "replace") if msg else "", self.arg)
        except BaseException as e:  # noqa: B902 - must not cross the C frames
            self.error = e
            return 0
        return 1 if r is None or r else 0

    def install(self, opts):
        """Sets opts.progress (left NULL, its default, without a callable)."""
        if self.c is not None:
            opts.progress = self.c

    def check(self, rc):
        if self.error is not None:
            err, self.error = self.error, None
            raise err
        return check(rc)
