"""Errors, progress and cancellation, seeds, zero-copy grids, georeferencing helpers."""
import ctypes
import gc
import os
import subprocess

import numpy as np
import pytest

import fracterra as ft
from fracterra import _core, _lib


def test_error_carries_the_library_message_and_code(tmp_path):
    missing = tmp_path / "nope.tif"
    with pytest.raises(ft.FracterraError) as e:
        ft.read_grid(missing)
    assert str(missing) in str(e.value) and e.value.code == _lib.FT_E_IO
    with pytest.raises(ft.FracterraError) as e:
        ft.synth(32, 32, 3.5)
    assert "3.5" in str(e.value) and e.value.code == _lib.FT_E_INVALID
    with pytest.raises(ft.FracterraError) as e:
        ft.dim_surface(np.zeros((16, 16), np.float32), method="kriging")
    assert "kriging" in str(e.value)


def test_error_is_the_cli_message(cli_exe, data):
    dem = data("dem_volcano_maunga_whau_10m.tif")
    p = subprocess.run([cli_exe, "dim", "surface", dem, "--method", "spectrum"], capture_output=True, text=True)
    assert p.returncode != 0
    with pytest.raises(ft.FracterraError) as e:
        ft.dim_surface(ft.read_grid(dem), method="spectrum")
    assert e.value.code == _lib.FT_E_NUMERIC
    assert p.stderr.strip() == "fracterra: dim surface: " + str(e.value)


def test_all_nodata_is_an_error_not_a_result():
    z = np.full((32, 32), np.nan, np.float32)
    with pytest.raises(ft.FracterraError) as e:
        ft.dim_surface(z)
    assert e.value.code in (_lib.FT_E_EMPTY, _lib.FT_E_INVALID)


def test_progress_reports_and_cancels():
    seen = []

    def fn(frac, msg, arg):
        seen.append((frac, arg))
        return 1

    ft.synth(128, 128, 2.5, progress=fn, progress_arg="a")
    assert seen and all(a == "a" for _, a in seen) and seen[-1][0] == 1.0
    with pytest.raises(ft.FracterraError) as e:
        ft.synth(128, 128, 2.5, progress=lambda f, m, a: 0)
    assert e.value.code == _lib.FT_E_CANCELLED

    class Boom(Exception):
        pass

    def bad(frac, msg, arg):
        raise Boom()

    with pytest.raises(Boom):
        ft.dim_surface(ft.synth(64, 64, 2.5), progress=bad)


def test_seeds_as_in_the_cli():
    a = ft.synth(64, 64, 2.3, seed=7).z
    assert np.array_equal(a, ft.synth(64, 64, 2.3, seed=7).z)
    assert not np.array_equal(a, ft.synth(64, 64, 2.3, seed=8).z)
    assert np.array_equal(ft.synth(16, 16, 2.3).z, ft.synth(16, 16, 2.3, seed=1).z)
    ft.synth(16, 16, 2.3, seed=2**64 - 1)


def test_grids_in_and_out_without_copy():
    g = ft.synth(64, 32, 2.4, seed=3)
    assert g.z.shape == (32, 64) and g.z.dtype == np.float32 and not g.z.flags.owndata
    z = g.z
    del g
    gc.collect()
    assert np.isfinite(z).all()  # the view keeps the library's cells alive
    a = np.ascontiguousarray(z)
    c = _core._CGrid(ft.Grid(a))
    assert ctypes.addressof(c.struct.z.contents) == a.ctypes.data
    f64 = _core._CGrid(ft.Grid(z.astype(np.float64)))
    assert np.array_equal(np.ctypeslib.as_array(f64.struct.z, shape=(32 * 64,)), z.ravel())


def test_nan_and_masked_arrays_are_nodata():
    g = ft.synth(64, 64, 2.3, seed=2)
    z = g.z.copy()
    z[:8, :8] = np.nan
    r_nan = ft.dim_surface(z)
    r_ma = ft.dim_surface(np.ma.array(g.z, mask=np.isnan(z)))
    r_mask = ft.dim_surface(ft.Grid(g.z, mask=~np.isnan(z)))
    assert r_nan.D == r_ma.D == r_mask.D != ft.dim_surface(g).D


def test_non_finite_cells_are_found_without_a_false_mask():
    import warnings
    big = np.full((16, 16), 3e38, np.float32)  # every cell finite, their sum overflows
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert _core._CGrid(ft.Grid(big))._mask is None
        big[3, 4], big[5, 6] = np.inf, -np.inf  # Inf - Inf: a NaN sum
        m = _core._CGrid(ft.Grid(big))._mask
    assert m.dtype == np.uint8 and m.sum() == 16 * 16 - 2 and m[3, 4] == 0 and m[5, 6] == 0
    assert _core._CGrid(ft.Grid(np.ones((4, 4))))._mask is None


def test_gdal_round_trip_keeps_georeferencing(data):
    pytest.importorskip("osgeo.gdal")
    g = ft.read_grid(data("dem_luxembourg_terra_30s.tif"))
    h = ft.from_gdal(ft.to_gdal(g))
    assert h.geotransform == g.geotransform
    assert np.array_equal(h.mask, g.mask) and np.array_equal(h.z[h.mask], g.z[g.mask])
    assert "WGS 84" in h.wkt


def test_write_grid_reads_back(tmp_path):
    g = ft.synth(40, 30, 2.2, seed=5, cell=10, origin=(1000, 2000), crs="EPSG:3857")
    ft.write_grid(tmp_path / "g.tif", g)
    h = ft.read_grid(tmp_path / "g.tif")
    assert np.array_equal(h.z, g.z) and h.geotransform == (1000, 10, 0, 2000, 0, -10)
    assert "3857" in h.wkt or "Pseudo-Mercator" in h.wkt


def test_result_table_and_dict():
    r = ft.dim_surface(ft.synth(128, 128, 2.5, seed=1, method="exact"))
    assert 2.4 < r.D < 2.6  # an exact fBm of D = 2.5 (variogram: median error 0.01)
    used = r.table[r.table["used"]]
    assert used["scale"][0] == r.range[0] and used["scale"][-1] == r.range[1]
    d = r.as_dict()
    assert d["D"] == r.D and len(d["table"]) == len(r.table)


def test_result_arrays_are_built_on_first_access():
    g = ft.synth(128, 128, 2.5, seed=1, method="exact")
    r, lazy = ft.dim_surface(g), ft.dim_surface(g)
    assert r._c is not None  # the C result is kept until the arrays are asked for
    want = (r.table.copy(), r.segments.copy(), r.regimes.copy())
    assert r._c is None and r.table is r.table  # built once, the C result released
    del g
    gc.collect()
    _ = [np.ones(4096) for _ in range(64)]
    import pickle
    back = pickle.loads(pickle.dumps(lazy))  # pickling builds them
    for a, b in zip(want, (back.table, back.segments, back.regimes)):
        assert a.dtype == b.dtype and a.tobytes() == b.tobytes()
    assert back.as_dict() == r.as_dict() and len(want[0]) > 0 and len(want[2]) >= 1


def test_reconstruct_from_points_honours_the_data():
    g = ft.synth(33, 33, 2.3, seed=4, cell=1.0)
    rng = np.random.default_rng(0)
    rows, cols = rng.integers(0, 33, 80), rng.integers(0, 33, 80)
    x, y = cols + 0.5, -(rows + 0.5)
    z = g.z[rows, cols].astype(float)
    out, sd, info = ft.reconstruct((x, y, z), target=g, method="smooth")
    assert info.data_used == 80 and sd is None
    assert info.data_rms < 1e-3 * float(np.ptp(z))


def test_clarke_simulate_and_hillshade():
    dem = ft.synth(64, 64, 2.3, seed=6, sigma=50)
    m = ft.clarke_fit(dem)
    sim, c = ft.clarke_simulate(m, refine=2, seed=3)
    assert sim.z.shape == (128, 128) and c > 0
    shade = ft.hillshade(dem)
    assert shade.z.shape == dem.z.shape and np.nanmax(shade.z) <= 255


def test_chain_inputs_agree():
    t = np.linspace(0, 20, 400)
    xy = np.c_[t, np.sin(3 * t) + 0.3 * np.sin(17 * t)]
    a = ft.dim_line(xy)
    b = ft.dim_line(xy[:, 0], xy[:, 1])
    c = ft.dim_line([xy[:200], xy[199:]])
    assert a.D == b.D and a.method == "divider" and np.isfinite(c.D)
    with pytest.raises(ValueError):
        ft.dim_line(np.zeros((5, 3)))


def test_chain_ops_answer_in_the_form_asked():
    t = np.linspace(0, 10, 50)
    x, y = t.copy(), np.sin(t)
    xy = np.c_[x, y]
    ex, ey = ft.enhance(x, y, sd=1.5)
    e2 = ft.enhance(xy, sd=1.5)
    assert np.array_equal(np.c_[ex, ey], e2) and len(ex) == 2 * len(x) - 1
    assert np.isfinite(ex).all()
    sx, sy = ft.simplify(x, y, tolerance=0.5)
    assert not sx.flags.owndata and not sy.flags.owndata  # views of the library's chain
    assert np.array_equal(np.c_[sx, sy], ft.simplify(xy, tolerance=0.5))


def test_n2_results_are_views_of_the_library_chain():
    t = np.linspace(0, 10, 200)
    xy = np.c_[t, np.sin(t) + 0.2 * np.sin(7 * t)]
    ring = np.c_[np.cos(2 * np.pi * t / 10), np.sin(2 * np.pi * t / 10)][:-1]
    cases = [(ft.enhance, xy, dict(sd=1.5)), (ft.smooth, xy, dict(passes=2)), (ft.weed, xy, dict(min_segment=0.2)),
             (ft.simplify, xy, dict(tolerance=0.05)), (ft.remove_loops, xy, {}),
             (ft.boundary, ring, dict(dim=1.3, min=0.01, seed=2))]
    for fn, data, kw in cases:
        closed = fn is ft.boundary
        v = fn(data, closed=closed, **kw)
        ex, ey = fn(data[:, 0], data[:, 1], closed=closed, **kw)
        assert type(v) is np.ndarray and v.dtype == np.float64 and v.shape == (len(ex), 2), fn.__name__
        assert not v.flags.owndata and v.flags.writeable
        assert v[:, 0].flags.c_contiguous and v[:, 1].flags.c_contiguous  # x and y arrays of the chain
        assert np.array_equal(v[:, 0], ex) and np.array_equal(v[:, 1], ey)
        c = np.ascontiguousarray(v)
        assert c.flags.c_contiguous and np.array_equal(c, v)
        assert np.array_equal(ft.simplify(v, tolerance=0.1), ft.simplify(c, tolerance=0.1))  # a view reads as input
    v = ft.enhance(xy, sd=1.5)
    total = float(v.sum())
    del xy
    gc.collect()
    _ = [np.ones(4096) for _ in range(64)]
    assert float(v.sum()) == total  # the view keeps the library's chain alive
    v[0, 1] = 5.0
    assert v[0, 1] == 5.0


def test_dim_line_reads_x_and_y_in_place():
    t = np.linspace(0, 20, 400)
    x, y = t.copy(), np.sin(3 * t) + 0.3 * np.sin(17 * t)
    seen = []
    real = _lib.lib.ft_line_dim

    def spy(chains, n, *rest):
        seen.append(ctypes.addressof(chains[0].contents.x.contents))
        return real(chains, n, *rest)
    _lib.lib.ft_line_dim = spy
    try:
        a = ft.dim_line(x, y)
    finally:
        _lib.lib.ft_line_dim = real
    assert seen == [x.ctypes.data]  # the library walked x itself, not a copy
    assert a.as_dict() == ft.dim_line(np.c_[x, y]).as_dict()
    with pytest.raises(ValueError):
        ft.dim_line(x, y[:-1])


def test_options_defaults_are_fresh_copies():
    a = ft._structs.ft_line_dim_opts.default()
    a.min_r2, a.fit.regime = 0.9, 3
    b = ft._structs.ft_line_dim_opts.default()
    assert b.min_r2 != 0.9 and b.fit.regime == 0 and b.struct_size == ctypes.sizeof(b)


def test_enhance_keep_vertices_keeps_the_input_vertices():
    t = np.linspace(0, 10, 50)
    xy = np.c_[t, np.sin(t)]
    e = ft.enhance(xy, sd=1.5, keep_vertices=True)
    moved = ft.enhance(xy, sd=1.5)
    assert len(e) == len(moved) == 2 * len(xy) - 1
    assert np.array_equal(e[::2], xy)  # Dutton's pass moves them: the default does not keep them
    assert not np.array_equal(moved[::2], xy)
    assert not np.allclose(e[1::2], 0.5 * (xy[:-1] + xy[1:]))  # the midpoints carry the detail
    with pytest.raises(ft.FracterraError):
        ft.enhance(xy, sd=1.5, keep_vertices=True, iterations=2)


def test_version_is_cmakes_project_version():
    import re
    root = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir)
    text = open(os.path.join(root, "CMakeLists.txt")).read()
    assert ft.__version__ == re.search(r"project\(fracterra VERSION ([0-9.]+)", text).group(1)


def test_synthesizer_reuses_memory_and_gives_synth_cells():
    """Synthesizer (ft_terrain_synth_into): the cells and geotransform of synth, into out= when given."""
    for method, periodic in (("fft", False), ("fft", True), ("sra", False)):
        with ft.Synthesizer(131, 97, method=method, periodic=periodic) as s:
            out = np.full((97, 131), np.nan, dtype=np.float32)
            for seed in (3, 4):
                ref = ft.synth(131, 97, 2.45, method=method, periodic=periodic, seed=seed, cell=10.0,
                               origin=(500.0, 900.0), sigma=3.0)
                g = s(2.45, seed=seed, cell=10.0, origin=(500.0, 900.0), sigma=3.0, out=out)
                assert g.z is out
                assert np.array_equal(out, ref.z)
                assert g.geotransform == ref.geotransform
                assert np.array_equal(s(2.45, seed=seed, cell=10.0, origin=(500.0, 900.0), sigma=3.0).z, ref.z)
            with pytest.raises(ValueError, match="C-contiguous float32"):
                s(2.45, out=np.zeros((97, 130), dtype=np.float32))
            with pytest.raises(ft.FracterraError, match="dimension"):
                s(3.5)
    s.close()
    with pytest.raises(ValueError, match="closed"):
        s(2.3)
    with pytest.raises(ft.FracterraError, match="size"):
        ft.Synthesizer(0, 10)


def test_hillshade_takes_nonfinite_cells_as_nodata():
    """hillshade passes NaN/Inf cells to the engine, which takes them as nodata: the same shades and mask
    as the same DEM given with an explicit mask; the output mask is a live bool view."""
    dem = ft.synth(96, 80, 2.3, seed=5, cell=10.0, sigma=40.0)
    z = dem.z.copy()
    z[10, 10:14] = np.nan
    z[40, 50] = np.inf
    z[0, 0] = -np.inf
    valid = np.isfinite(z)
    a = ft.hillshade(ft.Grid(z, geotransform=dem.geotransform))
    b = ft.hillshade(ft.Grid(np.where(valid, z, 0.0).astype(np.float32), mask=valid, geotransform=dem.geotransform))
    assert a.mask is not None and a.mask.dtype == np.bool_
    assert np.array_equal(a.mask, b.mask)
    assert not a.mask[10, 11] and not a.mask[40, 50] and not a.mask[0, 0] and a.mask[60, 60]
    assert np.array_equal(a.z[a.mask], b.z[b.mask])
    m = a.mask
    del a
    gc.collect()
    assert m.sum() == b.mask.sum()  # the view keeps the library's grid alive
