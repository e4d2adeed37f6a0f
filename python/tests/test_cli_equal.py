"""The Python results equal the CLI's on the same inputs: the same D to the last digit the CLI prints
(its JSON has 15 significant digits: cli/cli.c sets "%.15g"), the same table, the same cells."""
import numpy as np
import pytest

import fracterra as ft

gdal = pytest.importorskip("osgeo.gdal")

VOLCANO = "dem_volcano_maunga_whau_10m.tif"
LUX = "dem_luxembourg_terra_30s.tif"


def printed(v):
    """v as the CLI's JSON prints it, read back (null for a value that is not finite)."""
    return float("%.15g" % v) if np.isfinite(v) else None


def same_result(py, js):
    assert printed(py.D) == js["D"]
    assert printed(py.r2) == js["r2"]
    assert printed(py.stderr) == js["stderr"]
    assert [printed(v) for v in py.range] == js["range"]
    assert py.segmentation == js["segmentation"]
    assert py.warnings == js["warnings"]
    assert py.units == js.get("units", "")
    d = py.as_dict()
    assert d["choice"] == js["choice"] and d["regime"] == js["regime"]
    assert [printed(b) for b in d["breaks"]] == js["breaks"]
    assert len(d["regimes"]) == len(js["regimes"])
    for reg, jreg in zip(d["regimes"], js["regimes"]):
        assert {k: printed(v) if isinstance(v, float) else v for k, v in reg.items()} == jreg
    assert (py.noise_model is None) == ("noise" not in js)
    if py.noise_model is not None:
        assert {k: printed(v) if isinstance(v, float) else v for k, v in py.noise_model.items()} == js["noise"]
    assert len(py.table) == len(js["table"])
    for row, jrow in zip(py.table, js["table"]):
        assert (printed(row["scale"]), printed(row["value"]), printed(row["count"]), bool(row["used"])) == \
            (jrow["scale"], jrow["value"], jrow["count"], jrow["used"])


def read_band(path, band=1):
    ds = gdal.Open(str(path))
    b = ds.GetRasterBand(band)
    z = b.ReadAsArray()
    return z, b.GetMaskBand().ReadAsArray() != 0, ds.GetGeoTransform()


@pytest.mark.parametrize("method", ["variogram", "pentland", "prism", "cubes"])
def test_dim_surface(cli, data, method):
    js = cli("dim", "surface", data(VOLCANO), "--method", method)
    py = ft.dim_surface(ft.read_grid(data(VOLCANO)), method=method)
    assert py.method == js["method"]
    same_result(py, js)


def test_dim_surface_scale_range_and_gdal_grid(cli, data):
    # a lon/lat DEM: measured on its warp to a local transverse Mercator, scales in metres
    js = cli("dim", "surface", data(LUX), "--min-scale", "2000", "--max-scale", "12000")
    py = ft.dim_surface(ft.from_gdal(data(LUX)), min_scale=2000, max_scale=12000)
    same_result(py, js)
    assert py.units == "m" and js["geographic"]["crs"]


def test_dim_line_file_and_arrays(cli, data):
    path = data("gshhg_newfoundland_utm21n.geojson")
    js = cli("dim", "line", path)
    same_result(ft.dim_line(path), js)
    chains, wkt = ft.read_chains(path)
    assert "UTM zone 21N" in wkt and len(chains) == 1 and chains[0][0].shape == (64193, 2)
    coords, closed, _ = chains[0]
    same_result(ft.dim_line(coords, closed=closed, wkt=wkt), js)
    js_box = cli("dim", "line", path, "--method", "box")
    same_result(ft.dim_line(coords[:, 0], coords[:, 1], closed=closed, method="box", wkt=wkt), js_box)
    # without the CRS the scales are in an unknown unit: the result says so, as the CLI does
    bare = ft.dim_line(coords, closed=closed)
    assert bare.units == "" and any("no CRS" in w for w in bare.warnings)


@pytest.mark.parametrize("method", ["divider", "box"])
def test_dim_line_lonlat_as_the_cli(cli, data, method):
    """Lon/lat lines: walked on the ellipsoid, box-counted in a local equal-area projection; metres."""
    path = data("gshhg_newfoundland_lonlat.geojson")
    js = cli("dim", "line", path, "--method", method)
    py = ft.dim_line(path, method=method)
    same_result(py, js)
    assert py.units == "m"
    chains, wkt = ft.read_chains(path)
    same_result(ft.dim_line([c for c, _, _ in chains], closed=[cl for _, cl, _ in chains], wkt=wkt, method=method),
                js)


def test_dim_area_lonlat_as_the_cli(cli, data):
    path = data("dcw_us_states_small_lonlat.geojson")
    js = cli("dim", "area", path)
    py = ft.dim_area(path)
    same_result(py, js)
    assert py.units == "m"


def test_dim_points(cli, data):
    path = data("points_mass_topo_davis1973.csv")
    js = cli("dim", "points", path, "--min-pairs", "5", "--method", "pentland")
    py = ft.dim_points(path, min_pairs=5, method="pentland")
    same_result(py, js)
    x, y, z, w, _ = ft.read_points(path)
    py2 = ft.dim_points(x, y, z, min_pairs=5, method="pentland")
    assert py2.D == py.D
    dropped = [printed(l["lag"]) for l in py.extra["lags"] if l["status"] != "kept"]
    assert dropped == [d["lag"] for d in js["dropped_lags"]]


def test_dim_area(cli, data):
    path = data("dcw_us_states_small_albers5070.geojson")
    js = cli("dim", "area", path)
    py = ft.dim_area(path)
    assert py.method == js["method"]
    same_result(py, js)


def test_dim_map_cells(cli, data, tmp_path):
    out = tmp_path / "map.tif"
    cli("dim", "map", data(VOLCANO), out, "--window", "16", "--step", "8")
    D, r2 = ft.dim_map(ft.read_grid(data(VOLCANO)), 16, 8)
    for band, g in ((1, D), (2, r2)):
        z, valid, gt = read_band(out, band)
        assert gt == g.geotransform
        gm = np.ones(g.z.shape, bool) if g.mask is None else g.mask
        assert np.array_equal(valid, gm)
        assert np.array_equal(z[valid], g.z[gm])


def test_synth_cells(cli, tmp_path):
    out = tmp_path / "s.tif"
    cli("synth", out, "--dim", "2.4", "--size", "64x48", "--seed", "9", "--method", "sra", "--cell", "30",
        "--origin", "500000,4000000", "--crs", "EPSG:32633")
    g = ft.synth(64, 48, 2.4, method="sra", seed=9, cell=30, origin=(500000, 4000000), crs="EPSG:32633")
    z, valid, gt = read_band(out)
    assert valid.all() and g.mask is None
    assert np.array_equal(z, g.z)
    assert gt == g.geotransform
    assert "32633" in g.wkt


def test_hillshade_file_cells(cli, data, tmp_path):
    a, b = tmp_path / "cli.tif", tmp_path / "py.tif"
    cli("hillshade", data(VOLCANO), a, "--azimuth", "300")
    ft.hillshade_file(data(VOLCANO), b, azimuth=300)
    assert np.array_equal(read_band(a)[0], read_band(b)[0])


def test_reconstruct_voids_cells(cli, data, tmp_path):
    out = tmp_path / "r.tif"
    cli("reconstruct", data(LUX), out, "--method", "conditional", "--seed", "5")
    z, s, info = ft.reconstruct(ft.read_grid(data(LUX)), method="conditional", seed=5)
    zc, valid, gt = read_band(out)
    assert s is None and info.filled > 0
    assert np.array_equal(zc, z.z) and gt == z.geotransform


def test_clarke_fit(cli, data, tmp_path):
    js = cli("model", "fit", data(VOLCANO))
    m = ft.clarke_fit(ft.read_grid(data(VOLCANO)))
    # the model JSON writes the shortest text that reads back to the same double: equal, not "%.15g"
    assert js["D"] == m.D and js["c"] == m.c
    assert m.nharmonics == len(m.harmonics) > 0
    assert js["noise"] == m.noise == "spectrum"
    assert [g["D"] for g in js["regimes"]] == [g["D"] for g in m.regimes]
    assert js["spectrum"]["power"] == list(m.spectrum["power"])


LINE = np.array([[0, 0], [10, 1], [20, -2], [30, 4], [40, 0], [55, 3], [70, 1]], dtype=float)


def read_gmt(path):
    return np.array([[float(v) for v in ln.split()[:2]] for ln in open(path) if ln[0] not in ">#"])


@pytest.mark.parametrize("args,fn,kw", [
    (["enhance", "--sd", "1.4", "--iterations", "2"], ft.enhance, dict(sd=1.4, iterations=2)),
    (["enhance", "--target-dim", "1.5", "--uc", "0.7"], ft.enhance, dict(target_dim=1.5, uc=0.7)),
    (["simplify", "--tolerance", "2.5"], ft.simplify, dict(tolerance=2.5)),
    (["weed", "--min-segment", "12"], ft.weed, dict(min_segment=12)),
    (["smooth", "--passes", "2"], ft.smooth, dict(passes=2)),
    (["boundary", "--dim", "1.3", "--min", "1", "--seed", "4"], ft.boundary, dict(dim=1.3, min=1, seed=4,
                                                                                closed=False)),
])
def test_line_edits_same_vertices(cli, tmp_path, args, fn, kw):
    src, dst = tmp_path / "in.gmt", tmp_path / "out.gmt"
    src.write_text("".join("%r %r\n" % (x, y) for x, y in LINE))
    cli(args[0], src, dst, *args[1:], json_out=False)
    assert np.array_equal(fn(LINE, **kw), read_gmt(dst))


def test_mountain_levels_and_dem(cli, data, tmp_path):
    seed = data("seed_contour_volcano.geojson")
    js = cli("mountain", seed, tmp_path / "m.geojson", "--dem", tmp_path / "m.tif", "--seed", "3")
    levels, dem, info = ft.mountain(seed, seed=3, dem=True)
    assert info["seed_elevation"] == js["seed_elevation"] and printed(info["spacing"]) == js["spacing"]
    assert [e for e, _ in levels] == js["elevations"]
    assert [sum(len(o) + sum(len(h) for h in hs) for o, hs in polys) for _, polys in levels] == js["vertices"]
    g = js["crossing_guard"]
    assert (info["guard_moves"], info["guard_reduced"], info["guard_dropped"]) == (g["moves"], g["reduced"],
                                                                                   g["dropped"])
    z, valid, gt = read_band(tmp_path / "m.tif")
    assert gt == dem.geotransform
    gm = np.ones(dem.z.shape, bool) if dem.mask is None else dem.mask
    assert np.array_equal(valid, gm) and np.array_equal(z[valid], dem.z[gm])


def test_dim_line_by_field(cli, data):
    path = data("dcw_us_states_small_albers5070.geojson")
    js = cli("dim", "line", path, "--by", "code", "--method", "hybrid")
    py = ft.dim_line(path, by="code", method="hybrid")
    assert [k for k, _ in py] == [f["id"] for f in js["features"]]
    for (_, r), f in zip(py, js["features"]):
        same_result(r, f)
    with pytest.raises(ft.FracterraError, match="no field 'nope'"):
        ft.dim_line(path, by="nope")


def test_dim_area_by_class(cli, data):
    path = data("dcw_us_states_small_albers5070.geojson")
    js = cli("dim", "area", path, "--class", "code", "--what", "area")
    py = ft.dim_area(path, by="code", what="area")
    assert [k for k, _ in py] == [f["id"] for f in js["features"]]
    for (_, r), f in zip(py, js["features"]):
        same_result(r, f)


@pytest.mark.parametrize("args,steps,coverage", [
    (["simplify", "--tolerance", "2000"], [("simplify", dict(tolerance=2000))], True),
    (["enhance", "--sd", "1.4", "--uc", "0.7", "--sm", "800", "--weed", "--smooth", "1"],
     # the CLI gives smooth the enhance step's st and sm
     [("enhance", dict(sd=1.4, uc=0.7, sm=800)), ("weed", dict(min_segment=800)), ("smooth", dict(passes=1, sm=800))],
     True),
    (["smooth", "--passes", "2", "--no-coverage"], [("smooth", dict(passes=2))], False),
])
def test_edit_file_same_geometry(cli, data, tmp_path, args, steps, coverage):
    src = data("dcw_us_states_small_albers5070.geojson")
    a, b = tmp_path / "cli.geojson", tmp_path / "py.geojson"
    js = cli(args[0], src, a, *args[1:])
    rep = ft.edit_file(src, b, steps, coverage=coverage)
    assert rep["coverage"] == js["coverage"] and rep["vertices_out"] == js["vertices_out"]
    ca, wa = ft.read_chains(a)
    cb, wb = ft.read_chains(b)
    assert wa == wb and len(ca) == len(cb)
    for (xa, ra, fa), (xb, rb, fb) in zip(ca, cb):
        assert (ra, fa) == (rb, fb) and np.array_equal(xa, xb)


def test_dim_profile_row_transect_line(cli, data, tmp_path):
    dem = data(VOLCANO)
    js = cli("dim", "profile", dem, "--row", "30")
    py = ft.dim_profile(dem, row=30, method="both")
    assert [r.method for r in py] == [j["method"] for j in js["results"]] == ["madogram", "variogram"]
    for r, j in zip(py, js["results"]):
        same_result(r, j)
    assert py[0].extra["samples"] == js["samples"] and printed(py[0].extra["spacing"]) == js["spacing"]
    # the same row given as a Grid, and as a bare array with its spacing
    g = ft.read_grid(dem)
    same_result(ft.dim_profile(g, row=30, method="madogram"), js["results"][0])
    same_result(ft.dim_profile(g.z[30].astype(float), spacing=abs(g.geotransform[1]), method="madogram"),
                js["results"][0])
    x0, dx, _, y0, _, dy = g.geotransform
    a = (x0 + 5.5 * dx, y0 + 10.5 * dy)
    b = (x0 + 50.5 * dx, y0 + 70.5 * dy)
    jt = cli("dim", "profile", dem, "--from", "%r,%r" % a, "--to", "%r,%r" % b, "--method", "variogram")
    pt = ft.dim_profile(dem, start=a, end=b)
    same_result(pt, jt)
    assert pt.extra["profile"] == jt["profile"] == "transect"
    # a 3-D line: z resampled along its horizontal length
    t = np.linspace(0.0, 900.0, 181)
    line = tmp_path / "line3d.geojson"
    zz = 10 * np.sin(t / 37.0) + np.cos(t / 5.3) + 0.3 * np.sin(t * 1.7)
    line.write_text('{"type": "FeatureCollection", "features": [{"type": "Feature", "properties": {}, '
                    '"geometry": {"type": "LineString", "coordinates": [%s]}}]}'
                    % ", ".join("[%r, %r, %r]" % (v, 0.5 * v, w) for v, w in zip(t, zz)))
    jl = cli("dim", "profile", line, "--method", "madogram")
    pl = ft.dim_profile(line, method="madogram")
    same_result(pl, jl)
    assert pl.extra["samples"] == jl["samples"]
    with pytest.raises(ValueError, match="spacing"):
        ft.dim_profile(np.arange(10.0))


@pytest.mark.parametrize("args,kw", [([], {}), (["--mean"], dict(mean=True)),
                                     (["--realizations", "3", "--seed", "5"], dict(realizations=3, seed=5)),
                                     (["--max-void", "6", "--dim", "2.3"], dict(max_void=6, dim=2.3))])
def test_fill_same_cells(cli, data, tmp_path, args, kw):
    g = ft.read_grid(data(VOLCANO))
    z = g.z.copy()
    z[20:24, 30:33] = np.nan   # an inner void of 12 cells
    z[50:60, 10:20] = np.nan   # one of 10 x 10 (left nodata with --max-void 6)
    z[0:2, 0:3] = np.nan       # one on the edge
    holes = ft.Grid(z, mask=np.isfinite(z), geotransform=g.geotransform, wkt=g.wkt, nodata=-9999.0)
    src, dst = tmp_path / "holes.tif", tmp_path / "filled.tif"
    ft.write_grid(src, holes)
    js = cli("fill", src, dst, *args)
    out, sd, info = ft.fill(ft.read_grid(src), **kw)
    for k in ("voids_found", "voids_filled", "cells_filled", "cells_left"):
        assert info[k] == js[k]
    assert len(info["voids"]) == len(js["voids"]) == 3
    for v, jv in zip(info["voids"], js["voids"]):
        assert {k: printed(x) if isinstance(x, float) else x for k, x in v.items()} == jv
    cz, valid, gt = read_band(dst)
    pm = np.ones(out.z.shape, bool) if out.mask is None else out.mask
    assert gt == out.geotransform and np.array_equal(valid, pm) and np.array_equal(cz[valid], out.z[pm])
    assert np.array_equal(out.z[np.isfinite(z)], z[np.isfinite(z)])  # valid cells kept bit for bit
    if kw.get("realizations", 1) > 1:
        csd, _, _ = read_band(dst, 2)
        assert np.array_equal(csd[valid], sd.z[pm])
    else:
        assert sd is None


def test_dim_points_lonlat_as_the_cli(cli, data, tmp_path):
    """Lon/lat points (a GeoJSON point layer in WGS 84): lags in metres in a local transverse Mercator."""
    x, y, z, _, _ = ft.read_points(data("points_mass_topo_davis1973.csv"))
    lon, lat = -71.0 + x * 0.004, 42.0 + y * 0.003
    path = tmp_path / "pts.geojson"
    path.write_text('{"type": "FeatureCollection", "features": [%s]}' % ", ".join(
        '{"type": "Feature", "properties": {"z": %r}, "geometry": {"type": "Point", "coordinates": [%r, %r]}}'
        % (c, a, b) for a, b, c in zip(lon, lat, z)))
    js = cli("dim", "points", path, "--zfield", "z", "--min-pairs", "5")
    py = ft.dim_points(path, zfield="z", min_pairs=5)
    same_result(py, js)
    assert py.units == "m" and js["geographic"]
