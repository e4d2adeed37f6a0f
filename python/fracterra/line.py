"""Fractal dimension of chains and Dutton's enhancement with its companions (line.h, urban.h's
boundary generator; docs/line-*.md, docs/urban-boundary.md). A chain is an (n, 2) float64 array of
x, y, or two arrays x and y; a ring does not repeat its first vertex (closed=True). The chain
operations answer in the form they were asked in: f(xy) gives an (n, 2) array, f(x, y) gives (x, y),
both views of the library's result chain (nothing is copied out; the (n, 2) view's columns are the
chain's x and y arrays, so it is not C-ordered: np.ascontiguousarray gives an interleaved copy). weed,
simplify, remove_loops and dim_line read x and y in place; an (n, 2) array, and any input of enhance,
smooth and boundary (the CLI's guarded layer steps, which own their chain), is copied in once."""
import ctypes
import os

import numpy as np

from . import _structs as S
from ._lib import lib, check, check_ptr, parse_enum, FracterraError, FT_E_FORMAT, FT_E_EMPTY, FT_E_NOMEM, FT_E_CANCELLED
from ._core import (xy_arrays, chain_from_coords, chain_to_numpy, chain_views, chain_xy_view, ChainSet, _CChain,
                    take_result, Progress, crs_info, points_ground, FT_LOCAL_LAEA)
from ._common import set_fit, set_scales, path_bytes

__all__ = ["read_chains", "dim_line", "enhance", "smooth", "weed", "simplify", "remove_loops", "boundary",
           "edit_file", "LINE_METHODS"]

LINE_METHODS = ("divider", "equipaced", "hybrid", "box", "box-min")
FT_LINE_BOX, FT_LINE_BOX_MIN = 3, 4


def _read_layer(path, layer=None, where=None, fields=False):
    o = S.ft_read_layer_opts.default()
    keep = [v.encode() if v is not None else None for v in (layer, where)]
    o.layer, o.where = keep
    if not fields:
        o.fields = b""
    out = ctypes.POINTER(S.ft_layer)()
    check(lib.ft_io_read_layer(path_bytes(path), ctypes.byref(o), ctypes.byref(out)))
    return out


def read_chains(path, *, layer=None, where=None):
    """The chains of a vector layer (OGR) or GMT text file, read by the library's reader: a list of
    (coords, closed, feature) with coords an (n, 2) array, rings without their closing vertex, and the
    layer's CRS as WKT: (chains, wkt)."""
    lp = _read_layer(path, layer, where)
    try:
        lay = lp.contents
        chains = []
        for i in range(lay.nparts):
            part = lay.parts[i]
            chains.append((chain_to_numpy(part.chain), bool(part.chain.contents.closed), int(part.feature)))
        return chains, (lay.crs_wkt.decode() if lay.crs_wkt else None)
    finally:
        lib.ft_layer_free(lp)


def _coords(c):
    a = np.asarray(c, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != 2:
        raise ValueError("coordinates: expected an (n, 2) array or x and y, got shape %r" % (a.shape,))
    return a


def _chain_list(coords, y, closed):
    """[(coords, closed)] from one chain (x and y, kept as an (x, y) pair that ChainSet reads in place, or an
    (n, 2) array) or a list of (n, 2) arrays."""
    if y is not None:
        return [(xy_arrays(coords, y), bool(closed))]
    if isinstance(coords, np.ndarray) and coords.ndim == 2:
        return [(_coords(coords), bool(closed))]
    items = list(coords)
    flags = closed if isinstance(closed, (list, tuple)) else [closed] * len(items)
    if len(flags) != len(items):
        raise ValueError("closed: %d flags for %d chains" % (len(flags), len(items)))
    return [(_coords(c), bool(f)) for c, f in zip(items, flags)]


def dim_line(coords, y=None, *, closed=False, method="divider", by=None, layer=None, where=None, wkt=None,
             min_scale=None, max_scale=None, nscales=None, fit_whole_range=None, both_ends=True, box_offsets=None,
             min_r2=S.FT_LINE_R2_FLOOR, fit=None, regime=None, progress=None, progress_arg=None, _bbox=None):
    """Fractal dimension D (1..2) of a set of chains, as `fracterra dim line`: the values at each scale
    are summed over the chains and one log-log table is fitted.

    coords: a path (every part of every feature of the layer; layer= and where= select), x with y, an
    (n, 2) array, or a list of (n, 2) arrays (closed: one flag or one per chain). method: one of
    LINE_METHODS. Returns a DimResult. With a path and by=FIELD (the CLI's --by; "fid" per feature when
    the layer has no such field): a list of (value, result) pairs, one per distinct value in order of
    first appearance, a group that cannot be measured giving its FracterraError instead of a result.
    wkt: the CRS of coordinates given as arrays (a file's own CRS is used otherwise). As the CLI: chains
    in longitude/latitude are walked on the CRS's ellipsoid (scales in metres) and box-counted in a
    Lambert equal-area projection centred on the layer; a fit with r² below min_r2 (the CLI's floor,
    FT_LINE_R2_FLOOR = 0.5; 0 = off) fails; units come from the CRS (no CRS: a warning says the scales
    are in the data's own unit). regime: D from the N-th regime (the CLI's --regime)."""
    if isinstance(coords, (str, bytes, os.PathLike)):
        if by is not None:
            return _dim_line_by(coords, by, layer, where, dict(method=method, min_scale=min_scale,
                                max_scale=max_scale, nscales=nscales, fit_whole_range=fit_whole_range,
                                both_ends=both_ends, box_offsets=box_offsets, min_r2=min_r2, fit=fit,
                                regime=regime, progress=progress, progress_arg=progress_arg))
        chains, wkt = read_chains(coords, layer=layer, where=where)
        items = [(c, cl) for c, cl, _f in chains if len(c) >= 2]
    else:
        if by is not None:
            raise ValueError("by= groups the features of a file; got coordinates")
        items = _chain_list(coords, y, closed)
    m = parse_enum(lib.ft_line_method_parse, method, "method")
    crs = crs_info(wkt)
    if crs.geographic and m in (FT_LINE_BOX, FT_LINE_BOX_MIN):
        items = _project_chains(items, wkt, crs, _bbox)
    o = S.ft_line_dim_opts.default()
    set_scales(o, min_scale, max_scale, nscales, fit_whole_range)
    o.both_ends = 1 if both_ends else 0
    if box_offsets is not None:
        o.box_offsets = int(box_offsets)
    o.min_r2 = float(min_r2 or 0.0)
    set_fit(o.fit, fit)
    if regime:
        o.fit.regime = int(regime)
    if crs.geographic and m not in (FT_LINE_BOX, FT_LINE_BOX_MIN):
        o.ellipsoid = ctypes.pointer(crs.ellipsoid)
    pr = Progress(progress, progress_arg)
    pr.install(o)
    out = ctypes.POINTER(S.ft_dim_result)()
    with ChainSet(items) as cs:
        pr.check(lib.ft_line_dim(cs.array, len(cs.ptrs), m, ctypes.byref(o), ctypes.byref(out)))
    r = take_result(out, crs)
    r.method = LINE_METHODS[m]
    return r


def _project_chains(items, wkt, crs, bbox):
    """Lon/lat chains in the Lambert equal-area projection centred on bbox (default: theirs), as the CLI
    box-counts them (cli_geo_layer_local)."""
    if not items:
        return items
    items = [(np.column_stack(c) if isinstance(c, tuple) else c, cl) for c, cl in items]
    xy = np.concatenate([c for c, _ in items])
    x, y = points_ground(xy[:, 0], xy[:, 1], wkt, crs, FT_LOCAL_LAEA, bbox)
    out, k = [], 0
    for c, cl in items:
        out.append((np.column_stack((x[k:k + len(c)], y[k:k + len(c)])), cl))
        k += len(c)
    return out


def _feature_keys(lay, by, path):
    """Each feature's --by key as the CLI makes it (cli/cmd_dim_line.c): the field's value (None when
    null), or the feature id when by is "fid" and no field has that name."""
    L = lay.contents
    k = lib.ft_layer_field_index(lay, by.encode())
    if k < 0 and by.lower() != "fid":
        raise FracterraError("--by: no field '%s' in '%s'" % (by, os.fsdecode(path)), FT_E_FORMAT)
    keys = []
    for f in range(L.nfeatures):
        feat = L.features[f]
        if k < 0:
            keys.append(int(feat.fid))
            continue
        v = feat.values[k]
        t = L.fields[k].type
        keys.append(None if v.is_null else int(v.i) if t == 0 else float(v.r) if t == 1 else
                    (v.s or b"").decode())
    return keys


def _dim_line_by(path, by, layer, where, kw):
    lay = _read_layer(path, layer, where, fields=True)
    try:
        L = lay.contents
        kw["wkt"] = L.crs_wkt.decode() if L.crs_wkt else None
        parts = [chain_to_numpy(L.parts[p].chain) for p in range(L.nparts) if L.parts[p].chain]
        if parts:
            allxy = np.concatenate(parts)
            kw["_bbox"] = (allxy[:, 0].min(), allxy[:, 1].min(), allxy[:, 0].max(), allxy[:, 1].max())
        groups = {}
        for f, key in enumerate(_feature_keys(lay, by, path)):
            groups.setdefault(key, []).append(f)  # insertion order = order of first appearance
        out = []
        for key, feats in groups.items():
            items = []
            for f in feats:
                feat = L.features[f]
                for p in range(feat.first, feat.first + feat.count):
                    ch = L.parts[p].chain
                    if ch and ch.contents.n >= 2:
                        items.append((chain_to_numpy(ch), bool(ch.contents.closed)))
            try:
                if not items:
                    raise FracterraError("%s=%s: no chain of 2 or more vertices to measure" % (by, key), FT_E_EMPTY)
                out.append((key, dim_line([c for c, _ in items], closed=[cl for _, cl in items], **kw)))
            except FracterraError as e:
                if e.code in (FT_E_NOMEM, FT_E_CANCELLED):
                    raise
                out.append((key, e))
        return out
    finally:
        lib.ft_layer_free(lay)


def _chain_op(fn, coords, y, closed, *args):
    """Runs a chain operation. Called with x and y it reads them in place and returns (x, y); called
    with an (n, 2) array it copies it into a library chain once (read with stride 2 when C-ordered
    float64) and returns an (n, 2) array. Either way the answer is NumPy views of the library's result
    chain (chain_views, chain_xy_view): nothing is copied out."""
    out = ctypes.POINTER(S.ft_chain)()
    if y is not None:
        cin = _CChain(coords, y, closed)
        check(fn(cin.ref, *args, ctypes.byref(out)))
        return chain_views(out)
    cin = chain_from_coords(_coords(coords), None, closed)
    try:
        check(fn(cin, *args, ctypes.byref(out)))
    finally:
        lib.ft_chain_free(cin)
    return chain_xy_view(out)


def _layer_step(step, coords, y, closed, opts):
    """Runs a layer-level operation (the CLI's: one plan, the crossing guard) on one chain held in a
    one-part layer; answers as _chain_op does (x and y: (x, y) arrays; (n, 2): an (n, 2) array).
    The library's copy into the layer is the only copy in; the result chain is taken from the layer
    before it is freed and answered as views (chain_views, chain_xy_view): no copy out."""
    cin = chain_from_coords(coords, y, closed) if y is not None else chain_from_coords(_coords(coords), None, closed)
    lay = lib.ft_layer_create(b"chain", None)
    if not lay:
        lib.ft_chain_free(cin)
        check_ptr(lay)
    try:
        rc = lib.ft_layer_add_feature(lay, 0, 2 if closed else 1, 0)
        if rc < 0:
            lib.ft_chain_free(cin)
            check(int(rc))
        check(lib.ft_layer_add_part(lay, cin, 1 if closed else 0, 0))  # the layer owns cin from here
        check(step(lay, ctypes.byref(opts), 0, None))
        part = lay.contents.parts[0]
        result = ctypes.cast(part.chain, ctypes.POINTER(S.ft_chain))  # a copy of the pointer value
        part.chain = None  # detached: freed with the last view, not with the layer
    finally:
        lib.ft_layer_free(lay)
    return chain_views(result) if y is not None else chain_xy_view(result)


def enhance(coords, y=None, *, closed=False, sd=1.3, uc=1.0, st=None, sm=0.0, iterations=1, target_dim=None,
            input_dim=None, literal_sd=False, allow_crossings=False, keep_vertices=False):
    """Dutton's fractal enhancement of one chain, as `fracterra enhance` (ft_line_enhance_layer): the
    target dimension D_in + uc (sd - D_in) with D_in measured (or input_dim), or target_dim; literal_sd:
    Dutton's literal apex angle; unless allow_crossings, moves that would make the chain touch itself
    are reduced; keep_vertices (one iteration): the input's vertices stay, each new midpoint M of P N goes
    to M - (dP + dN) / 2 (--keep-vertices). Returns an (n, 2) array (or (x, y) arrays). End points of
    open chains stay."""
    o = _dutton(sd, uc, st, sm, iterations, target_dim, input_dim, literal_sd, allow_crossings, keep_vertices)
    return _layer_step(_enhance_layer, coords, y, closed, o)


def smooth(coords, y=None, *, closed=False, passes=1, roundness=0.5, st=None, sm=0.0, allow_crossings=False):
    """Roundness smoothing (corner cutting; roundness 0.5 is Chaikin's) of one chain, as `fracterra
    smooth` (guarded against self-contact unless allow_crossings)."""
    o = _smooth(passes, roundness, st, sm, allow_crossings)
    return _layer_step(lib.ft_line_smooth_layer, coords, y, closed, o)


def weed(coords, y=None, *, closed=False, min_segment):
    """Drops vertices so that no segment is shorter than min_segment (map units)."""
    return _chain_op(lib.ft_line_weed, coords, y, closed, float(min_segment))


def simplify(coords, y=None, *, closed=False, tolerance):
    """Douglas-Peucker simplification with a distance tolerance (map units)."""
    return _chain_op(lib.ft_line_simplify, coords, y, closed, float(tolerance))


def remove_loops(coords, y=None, *, closed=False):
    """Removes the loops that self-intersections make."""
    return _chain_op(lib.ft_line_remove_loops, coords, y, closed)


def boundary(coords, y=None, *, closed=True, dim, min, max=0.0, jitter=0.0, seed=1, stream=0,
             allow_crossings=False):
    """Zhang et al.'s midpoint-subdivision boundary generator on one chain, as `fracterra boundary`
    (ft_urban_boundary_layer): dim in (1, 2), min > 0 and max (0 = the chain's average chord) in map
    units; seeded as the CLI; level by level through the crossing guard unless allow_crossings."""
    o = S.ft_boundary_opts.default()
    o.dim, o.min, o.max, o.jitter = float(dim), float(min), float(max), float(jitter)
    o.seed, o.stream = int(seed), int(stream)
    o.allow_crossings = 1 if allow_crossings else 0
    return _layer_step(lib.ft_urban_boundary_layer, coords, y, closed, o)


def _dutton(sd=1.3, uc=1.0, st=None, sm=0.0, iterations=1, target_dim=None, input_dim=None, literal_sd=False,
            allow_crossings=False, keep_vertices=False):
    o = S.ft_dutton_opts.default()
    o.sd, o.uc, o.sm, o.iterations = float(sd), float(uc), float(sm), int(iterations)
    if st is not None:
        o.st = float(st)
    if target_dim is not None:
        o.target_dim = float(target_dim)
    if input_dim is not None:
        o.input_dim = float(input_dim)
    o.literal_sd = 1 if literal_sd else 0
    o.allow_crossings = 1 if allow_crossings else 0
    o.keep_vertices = 1 if keep_vertices else 0
    return o


def _smooth(passes=1, roundness=0.5, st=None, sm=0.0, allow_crossings=False):
    o = S.ft_smooth_opts.default()
    o.passes, o.roundness, o.sm = int(passes), float(roundness), float(sm)
    if st is not None:
        o.st = float(st)
    o.allow_crossings = 1 if allow_crossings else 0
    return o


def _enhance_layer(lay, opts, coverage, stats):
    return lib.ft_line_enhance_layer(lay, opts, coverage, None, stats)


# step name: (the library's ft_line_op, or a layer function (the CLI's guarded steps), how its options are
# made from keyword arguments)
_LAYER_OPS = {
    "enhance": (_enhance_layer, _dutton),
    "smooth": ("ft_line_smooth_layer", _smooth),
    "weed": ("ft_line_op_weed", lambda min_segment: ctypes.c_double(float(min_segment))),
    "simplify": ("ft_line_op_simplify", lambda tolerance: ctypes.c_double(float(tolerance))),
    "repair": ("ft_line_op_remove_loops", lambda: None),
}


def edit_file(src, dst, steps, *, coverage=True, layer=None, where=None, driver=None):
    """Edits every line and ring of a vector layer and writes it, as `fracterra enhance|smooth|weed|
    simplify` do: steps is a list of (name, options) with name "enhance" (sd, uc, st, sm, iterations,
    target_dim, input_dim, literal_sd, allow_crossings), "smooth" (passes, roundness, st, sm,
    allow_crossings), "weed" (min_segment), "simplify" (tolerance) or "repair" (no options), applied in
    order: enhance and smooth as the CLI's guarded layer steps (ft_line_enhance_layer: one plan for the
    layer; ft_line_smooth_layer), the others through ft_line_apply_layer. On a polygon layer with
    coverage=True (the CLI without --no-coverage) shared boundaries are edited once along the arc-node
    topology, so neighbours stay coincident. Attributes and CRS are kept; dst is replaced only when the
    whole write succeeded. Returns {"coverage", "vertices_in", "vertices_out", "stages": [(name, vertices)]}."""
    prepared = []
    for name, kw in steps:
        if name not in _LAYER_OPS:
            raise ValueError("unknown step %r (known: %s)" % (name, ", ".join(_LAYER_OPS)))
        fn, make = _LAYER_OPS[name]
        if callable(fn) or fn.endswith("_layer"):
            prepared.append((name, fn if callable(fn) else getattr(lib, fn), make(**(kw or {})), True))
        else:
            prepared.append((name, ctypes.cast(getattr(lib, fn), ctypes.c_void_p), make(**(kw or {})), False))
    lay = _read_layer(src, layer, where, fields=True)
    try:
        check(lib.ft_layer_check_finite(lay))
        L = lay.contents
        rings = any(L.parts[i].role != 0 for i in range(L.nparts))
        cov = 1 if coverage and rings else 0
        report = {"coverage": bool(cov), "vertices_in": lib.ft_layer_vertex_count(lay), "stages": []}
        for name, op, opts, layer_fn in prepared:
            if layer_fn:
                check(op(lay, ctypes.byref(opts), cov, None))
            else:
                check(lib.ft_line_apply_layer(lay, op, ctypes.byref(opts) if opts is not None else None, cov))
            report["stages"].append((name, lib.ft_layer_vertex_count(lay)))
        report["vertices_out"] = lib.ft_layer_vertex_count(lay)
        wo = S.ft_write_layer_opts.default()
        keep = driver.encode() if driver else None
        wo.driver = keep
        check(lib.ft_io_write_layer(path_bytes(dst), lay, ctypes.byref(wo)))
        return report
    finally:
        lib.ft_layer_free(lay)
