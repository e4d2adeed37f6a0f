"""ctypes mirrors of the C structs in include/fracterra/*.h.

Each Structure names its C type in _c_name_ and, for options structs, the defaults macro in _c_default_
with the same values in _defaults_ (nested structs as dicts). Options structs begin with struct_size
(FT_OPTS in core.h), which default() sets: always start from default(). python/tests/test_layout.py compiles a
small C program against the headers and checks every size, every field offset and every default
here: a header change that is not mirrored fails that test, never a user's call.
"""
import ctypes as c

_sz = c.c_size_t
_u64 = c.c_uint64
_i64 = c.c_int64
_int = c.c_int
_dbl = c.c_double
_str = c.c_char_p
_vp = c.c_void_p
_P = c.POINTER
INF = float("inf")

# int (*)(double frac, const char *msg, void *arg): GDAL's GDALProgressFunc.
PROGRESS = c.CFUNCTYPE(_int, _dbl, _str, _vp)

ALL = []


def _mirror(cls):
    ALL.append(cls)
    return cls


class _Opts(c.Structure):
    _defaults_ = {}

    @classmethod
    def default(cls):
        """The FT_*_OPTS_DEFAULT values, struct_size set in this struct and every nested one (FT_OPTS): a
        copy of the class's default bytes, made once (the defaults are numbers and NULL pointers only)."""
        proto = cls.__dict__.get("_default_bytes")
        if proto is None:
            o = cls()
            _set_sizes(o)
            _apply(o, cls._defaults_)
            proto = bytes(o)
            cls._default_bytes = proto
        return cls.from_buffer_copy(proto)


def _set_sizes(obj):
    obj.struct_size = c.sizeof(obj)
    for name, typ in obj._fields_:
        if isinstance(typ, type) and issubclass(typ, _Opts):
            _set_sizes(getattr(obj, name))


def _apply(obj, values):
    for k, v in values.items():
        if isinstance(v, dict):
            _apply(getattr(obj, k), v)
        else:
            setattr(obj, k, v)


# ---- core.h ----

@_mirror
class ft_chain(c.Structure):
    _c_name_ = "ft_chain"
    _fields_ = [("x", _P(_dbl)), ("y", _P(_dbl)), ("n", _sz), ("cap", _sz), ("closed", _int)]


@_mirror
class ft_field(c.Structure):
    _c_name_ = "ft_field"
    _fields_ = [("name", _str), ("type", _int), ("native_type", _int), ("width", _int), ("precision", _int)]


@_mirror
class ft_value(c.Structure):
    _c_name_ = "ft_value"
    _fields_ = [("is_null", _int), ("i", _i64), ("r", _dbl), ("s", _str)]


@_mirror
class ft_part(c.Structure):
    _c_name_ = "ft_part"
    _fields_ = [("chain", _P(ft_chain)), ("feature", _sz), ("polygon", _int), ("role", _int)]


@_mirror
class ft_feature(c.Structure):
    _c_name_ = "ft_feature"
    _fields_ = [("fid", _i64), ("type", _int), ("multi", _int), ("first", _sz), ("count", _sz),
                ("values", _P(ft_value))]


@_mirror
class ft_layer(c.Structure):
    _c_name_ = "ft_layer"
    _fields_ = [("name", _str), ("crs_wkt", _str), ("fields", _P(ft_field)), ("nfields", _sz),
                ("features", _P(ft_feature)), ("nfeatures", _sz), ("features_cap", _sz),
                ("parts", _P(ft_part)), ("nparts", _sz), ("parts_cap", _sz), ("topology", _vp)]


@_mirror
class ft_grid(c.Structure):
    _c_name_ = "ft_grid"
    _fields_ = [("nx", _sz), ("ny", _sz), ("z", _P(c.c_float)), ("mask", _P(c.c_uint8)), ("gt", _dbl * 6),
                ("crs_wkt", _str), ("has_nodata", _int), ("nodata_value", _dbl)]


@_mirror
class ft_points(c.Structure):
    _c_name_ = "ft_points"
    _fields_ = [("x", _P(_dbl)), ("y", _P(_dbl)), ("z", _P(_dbl)), ("w", _P(_dbl)), ("n", _sz), ("cap", _sz),
                ("crs_wkt", _str)]


@_mirror
class ft_fit(c.Structure):
    _c_name_ = "ft_fit"
    _fields_ = [("slope", _dbl), ("intercept", _dbl), ("r2", _dbl), ("stderr_slope", _dbl),
                ("stderr_intercept", _dbl), ("first", _sz), ("last", _sz), ("n", _sz)]


@_mirror
class ft_loglog_row(c.Structure):
    _c_name_ = "ft_loglog_row"
    _fields_ = [("scale", _dbl), ("value", _dbl), ("count", _dbl), ("slope", _dbl), ("used", _int)]


@_mirror
class ft_loglog(c.Structure):
    _c_name_ = "ft_loglog"
    _fields_ = [("rows", _P(ft_loglog_row)), ("n", _sz), ("cap", _sz)]


@_mirror
class ft_dim_map(c.Structure):
    _c_name_ = "ft_dim_map"
    _fields_ = [("a", _dbl), ("b", _dbl), ("d_min", _dbl), ("d_max", _dbl)]


@_mirror
class ft_loglog_opts(_Opts):
    _c_name_ = "ft_loglog_opts"
    _c_default_ = "FT_LOGLOG_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("method", _int), ("tol", _dbl), ("width", _dbl), ("tol_sigma", _dbl), ("min_points", _sz),
                ("max_iter", _int), ("min_span", _dbl), ("bounds_tol", _dbl), ("curve_dD", _dbl),
                ("curve_alpha", _dbl), ("regime", _int)]
    _defaults_ = dict(method=2, tol=0.02, width=0.04, tol_sigma=3.0, min_points=3, max_iter=50, min_span=4.0,
                      bounds_tol=0.025, curve_dD=0.05, curve_alpha=0.01, regime=0)


FIT_DEFAULTS = ft_loglog_opts._defaults_


@_mirror
class ft_loglog_segment(c.Structure):
    _c_name_ = "ft_loglog_segment"
    _fields_ = [("first", _sz), ("last", _sz), ("n", _sz), ("scale_lo", _dbl), ("scale_hi", _dbl),
                ("slope", _dbl), ("intercept", _dbl), ("D", _dbl), ("r2", _dbl), ("stderr_D", _dbl),
                ("max_err", _dbl), ("D_minimax", _dbl)]


@_mirror
class ft_ellipsoid(c.Structure):
    _c_name_ = "ft_ellipsoid"
    _fields_ = [("a", _dbl), ("f", _dbl)]


WGS84 = ft_ellipsoid(6378137.0, 1.0 / 298.257223563)


@_mirror
class ft_noise_model(c.Structure):
    _c_name_ = "ft_noise_model"
    _fields_ = [("fitted", _int), ("applied", _int), ("power", _dbl), ("c0", _dbl), ("a", _dbl), ("H", _dbl),
                ("F", _dbl), ("sigma_z", _dbl), ("floor", _dbl), ("s", _dbl), ("sigma_xy", _dbl),
                ("detected", _int), ("positions", _int)]


@_mirror
class ft_dim_result(c.Structure):
    _c_name_ = "ft_dim_result"
    _fields_ = [("method", _str), ("segmentation", _str), ("D", _dbl), ("r2", _dbl), ("stderr_D", _dbl),
                ("range", _dbl * 2), ("max_err", _dbl), ("noise", _dbl), ("tol", _dbl), ("width", _dbl),
                ("fit", ft_fit), ("map", ft_dim_map), ("table", _P(ft_loglog)),
                ("segments", _P(ft_loglog_segment)), ("nsegments", _sz), ("best", _sz),
                ("warnings", _P(_str)), ("nwarnings", _sz), ("units", c.c_char * 32),
                ("regimes", _P(ft_loglog_segment)), ("nregimes", _sz), ("regime", _sz), ("breaks", _P(_dbl)),
                ("choice", _str), ("nugget", ft_noise_model)]


# ---- io.h ----

@_mirror
class ft_read_layer_opts(_Opts):
    _c_name_ = "ft_read_layer_opts"
    _c_default_ = "FT_READ_LAYER_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("layer", _str), ("where", _str), ("fields", _str)]


@_mirror
class ft_read_grid_opts(_Opts):
    _c_name_ = "ft_read_grid_opts"
    _c_default_ = "FT_READ_GRID_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("band", _int)]
    _defaults_ = dict(band=1)


@_mirror
class ft_write_grid_opts(_Opts):
    _c_name_ = "ft_write_grid_opts"
    _c_default_ = "FT_WRITE_GRID_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("driver", _str), ("co", _P(_str)), ("type", _int)]


@_mirror
class ft_read_points_opts(_Opts):
    _c_name_ = "ft_read_points_opts"
    _c_default_ = "FT_READ_POINTS_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("x", _str), ("y", _str), ("z", _str), ("weight", _str), ("layer", _str), ("zfield", _str)]


@_mirror
class ft_io_hillshade_opts(_Opts):
    _c_name_ = "ft_io_hillshade_opts"
    _c_default_ = "FT_IO_HILLSHADE_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("azimuth", _dbl), ("altitude", _dbl), ("z_factor", _dbl), ("scale", _dbl), ("color", _int),
                ("band", _int)]
    _defaults_ = dict(azimuth=315.0, altitude=45.0, z_factor=1.0, scale=0.0, color=0, band=1)


@_mirror
class ft_crs_info(c.Structure):
    _c_name_ = "ft_crs_info"
    _fields_ = [("has_crs", _int), ("geographic", _int), ("name", c.c_char * 128), ("unit", c.c_char * 48),
                ("scale_unit", c.c_char * 16), ("metres_per_unit", _dbl), ("ellipsoid", ft_ellipsoid),
                ("ellipsoid_name", c.c_char * 64)]


# ---- render.h ----

@_mirror
class ft_hillshade_opts(_Opts):
    _c_name_ = "ft_hillshade_opts"
    _c_default_ = "FT_HILLSHADE_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("azimuth", _dbl), ("altitude", _dbl), ("z_factor", _dbl), ("scale", _dbl)]
    _defaults_ = dict(azimuth=315.0, altitude=45.0, z_factor=1.0, scale=1.0)


# ---- surface.h ----

@_mirror
class ft_noise_opts(_Opts):
    _c_name_ = "ft_noise_opts"
    _c_default_ = "FT_NOISE_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("mode", _int), ("sigma_z", _dbl), ("sigma_xy", _dbl)]
    _defaults_ = dict(mode=0, sigma_z=0.0, sigma_xy=0.0)


NOISE_DEFAULTS = ft_noise_opts._defaults_


@_mirror
class ft_surface_dim_opts(_Opts):
    _c_name_ = "ft_surface_dim_opts"
    _c_default_ = "FT_SURFACE_DIM_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("min_scale", _dbl), ("max_scale", _dbl), ("nscales", _int), ("pairs", _sz), ("seed", _u64),
                ("zscale", _dbl), ("tile", _sz), ("min_valid", _dbl), ("fit", ft_loglog_opts),
                ("fit_whole_range", _int), ("progress", PROGRESS), ("progress_arg", _vp), ("noise", ft_noise_opts)]
    _defaults_ = dict(min_scale=0.0, max_scale=0.0, nscales=0, pairs=0, seed=1, zscale=0.0, tile=0,
                      min_valid=0.5, fit=FIT_DEFAULTS, fit_whole_range=0, noise=NOISE_DEFAULTS)


@_mirror
class ft_points_lag(c.Structure):
    _c_name_ = "ft_points_lag"
    _fields_ = [("lag", _dbl), ("dist", _dbl), ("A", _dbl), ("B", _dbl), ("C", _dbl), ("drawn", _u64),
                ("value", _dbl), ("value_se", _dbl), ("status", _int)]


@_mirror
class ft_points_counters(c.Structure):
    _c_name_ = "ft_points_counters"
    _fields_ = [("method", _int), ("lags", _P(ft_points_lag)), ("n", _sz), ("kept", _sz), ("eps", _dbl),
                ("spacing", _dbl), ("min_pairs", _sz), ("pairs", _str), ("sample", _u64),
                ("D_sample_se", _dbl)]


@_mirror
class ft_points_dim_opts(_Opts):
    _c_name_ = "ft_points_dim_opts"
    _c_default_ = "FT_POINTS_DIM_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("method", _int), ("lags", _P(_dbl)), ("nuser_lags", _sz), ("min_lag", _dbl), ("max_lag", _dbl),
                ("nlags", _int), ("eps", _dbl), ("min_pairs", _sz), ("exact", _int), ("sample", _sz),
                ("seed", _u64), ("noise_sigma", _dbl), ("fit", ft_loglog_opts), ("fit_auto", _int),
                ("counters", _P(_P(ft_points_counters))), ("progress", PROGRESS), ("progress_arg", _vp),
                ("noise_sigma_xy", _dbl), ("noise_mode", _int)]
    _defaults_ = dict(method=0, nuser_lags=0, min_lag=0.0, max_lag=0.0, nlags=0, eps=0.0, min_pairs=100, exact=0,
                      sample=0, seed=1, noise_sigma=0.0, fit=FIT_DEFAULTS, fit_auto=0, noise_sigma_xy=0.0,
                      noise_mode=0)


# ---- line.h ----

FT_LINE_R2_FLOOR = 0.5  # line.h: the least r² the CLI accepts


@_mirror
class ft_line_dim_opts(_Opts):
    _c_name_ = "ft_line_dim_opts"
    _c_default_ = "FT_LINE_DIM_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("min_scale", _dbl), ("max_scale", _dbl), ("nscales", _int), ("both_ends", _int),
                ("box_offsets", _int), ("fit", ft_loglog_opts), ("fit_whole_range", _int),
                ("progress", PROGRESS), ("progress_arg", _vp), ("ellipsoid", _P(ft_ellipsoid)), ("min_r2", _dbl),
                ("starts", _int), ("only_start", _int)]
    _defaults_ = dict(min_scale=0.0, max_scale=0.0, nscales=0, both_ends=1, box_offsets=4, fit=FIT_DEFAULTS,
                      fit_whole_range=0, min_r2=0.0, starts=1, only_start=-1)


@_mirror
class ft_dutton_opts(_Opts):
    _c_name_ = "ft_dutton_opts"
    _c_default_ = "FT_DUTTON_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("sd", _dbl), ("uc", _dbl), ("st", _dbl), ("sm", _dbl), ("iterations", _int),
                ("target_dim", _dbl), ("input_dim", _dbl), ("literal_sd", _int), ("allow_crossings", _int),
                ("keep_vertices", _int)]
    _defaults_ = dict(sd=1.3, uc=1.0, st=INF, sm=0.0, iterations=1, target_dim=0.0, input_dim=0.0, literal_sd=0,
                      allow_crossings=0, keep_vertices=0)


@_mirror
class ft_smooth_opts(_Opts):
    _c_name_ = "ft_smooth_opts"
    _c_default_ = "FT_SMOOTH_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("passes", _int), ("roundness", _dbl), ("st", _dbl), ("sm", _dbl), ("allow_crossings", _int)]
    _defaults_ = dict(passes=1, roundness=0.5, st=INF, sm=0.0, allow_crossings=0)


# ---- terrain.h ----

@_mirror
class ft_synth_opts(_Opts):
    _c_name_ = "ft_synth_opts"
    _c_default_ = "FT_SYNTH_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("method", _int), ("dim", _dbl), ("sigma", _dbl), ("cell", _dbl), ("origin_x", _dbl),
                ("origin_y", _dbl), ("periodic", _int), ("seed", _u64), ("progress", PROGRESS),
                ("progress_arg", _vp)]
    _defaults_ = dict(method=0, dim=2.3, sigma=1.0, cell=1.0, origin_x=0.0, origin_y=0.0, periodic=0, seed=1)


@_mirror
class ft_fill_opts(_Opts):
    _c_name_ = "ft_fill_opts"
    _c_default_ = "FT_FILL_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("max_void", _dbl), ("mean", _int), ("realizations", _int), ("dim", _dbl), ("ring", _int),
                ("seed", _u64), ("progress", PROGRESS), ("progress_arg", _vp)]
    _defaults_ = dict(max_void=100.0, mean=0, realizations=1, dim=0.0, ring=0, seed=1)


@_mirror
class ft_fill_void(c.Structure):
    _c_name_ = "ft_fill_void"
    _fields_ = [("x0", _sz), ("y0", _sz), ("x1", _sz), ("y1", _sz), ("cells", _sz), ("edge", _int), ("filled", _int),
                ("D", _dbl), ("amplitude", _dbl), ("r2", _dbl), ("clamped", _int), ("source", _int),
                ("ring_cells", _sz), ("conditioning", _sz)]


@_mirror
class ft_fill_result(c.Structure):
    _c_name_ = "ft_fill_result"
    _fields_ = [("voids", _P(ft_fill_void)), ("nvoids", _sz), ("voids_filled", _sz), ("cells_filled", _sz),
                ("cells_left", _sz)]


@_mirror
class ft_clarke_harmonic(c.Structure):
    _c_name_ = "ft_clarke_harmonic"
    _fields_ = [("k", _int), ("l", _int), ("a", _dbl), ("b", _dbl), ("power", _dbl), ("share", _dbl),
                ("wavelength", _dbl), ("direction", _dbl)]


@_mirror
class ft_clarke_regime(c.Structure):
    _c_name_ = "ft_clarke_regime"
    _fields_ = [("wavelength_lo", _dbl), ("wavelength_hi", _dbl), ("slope", _dbl), ("intercept", _dbl), ("D", _dbl),
                ("r2", _dbl), ("stderr_D", _dbl), ("bins", _sz)]


@_mirror
class ft_clarke_model(c.Structure):
    _c_name_ = "ft_clarke_model"
    _fields_ = [("beta0", _dbl), ("beta1", _dbl), ("beta2", _dbl), ("trend_r2", _dbl), ("nx", _sz), ("ny", _sz),
                ("gt", _dbl * 6), ("crs_wkt", _str), ("mean", _dbl), ("sd", _dbl), ("valid", _sz),
                ("nodata_filled", _sz), ("cutoff", _dbl), ("taper", _int), ("min_wavelength", _dbl),
                ("harmonics", _P(ft_clarke_harmonic)), ("nharmonics", _sz), ("harmonic_share", _dbl),
                ("slope", _dbl), ("intercept", _dbl), ("r2", _dbl), ("stderr_slope", _dbl), ("npairs", _sz),
                ("D", _dbl), ("D_clarke_eq8", _dbl), ("c", _dbl), ("noise", _int), ("nspectrum", _sz),
                ("spectrum_wavelength", _P(_dbl)), ("spectrum_power", _P(_dbl)), ("spectrum_count", _P(_dbl)),
                ("regimes", _P(ft_clarke_regime)), ("nregimes", _sz), ("breaks", _P(_dbl))]


@_mirror
class ft_clarke_opts(_Opts):
    _c_name_ = "ft_clarke_opts"
    _c_default_ = "FT_CLARKE_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("cutoff", _dbl), ("taper", _int), ("min_wavelength", _dbl), ("progress", PROGRESS),
                ("progress_arg", _vp), ("noise", _int)]
    _defaults_ = dict(cutoff=2.5, taper=1, min_wavelength=4.0, noise=1)


@_mirror
class ft_clarke_sim_opts(_Opts):
    _c_name_ = "ft_clarke_sim_opts"
    _c_default_ = "FT_CLARKE_SIM_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("refine", _int), ("extent", _int), ("seed", _u64), ("c_used", _P(_dbl)), ("progress", PROGRESS),
                ("progress_arg", _vp)]
    _defaults_ = dict(refine=1, extent=1, seed=1)


@_mirror
class ft_recon_opts(_Opts):
    _c_name_ = "ft_recon_opts"
    _c_default_ = "FT_RECON_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("method", _int), ("dim", _dbl), ("tension", _dbl), ("lambda_", _dbl), ("sigma", _dbl),
                ("temperature", _dbl), ("k", _dbl), ("sweeps", _int), ("realizations", _int), ("seed", _u64),
                ("threads", _int), ("progress", PROGRESS), ("progress_arg", _vp)]
    _c_field_names_ = {"lambda_": "lambda"}
    _defaults_ = dict(method=0, dim=0.0, tension=-1.0, lambda_=1.0, sigma=0.0, temperature=0.0, k=0.0, sweeps=0,
                      realizations=1, seed=1, threads=0)


@_mirror
class ft_recon_info(c.Structure):
    _c_name_ = "ft_recon_info"
    _fields_ = [("dim", _dbl), ("dim_estimated", _int), ("sigma0", _dbl), ("k", _dbl), ("temperature", _dbl),
                ("levels", _int), ("data_used", _sz), ("data_outside", _sz), ("filled", _sz), ("data_rms", _dbl),
                ("lambda_", _dbl), ("tension", _dbl)]
    _c_field_names_ = {"lambda_": "lambda"}


# ---- urban.h ----

@_mirror
class ft_area_dim_opts(_Opts):
    _c_name_ = "ft_area_dim_opts"
    _c_default_ = "FT_AREA_DIM_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("what", _int), ("cells", _P(_dbl)), ("ncells", _sz), ("min_cell", _dbl), ("max_cell", _dbl),
                ("nscales", _int), ("offsets", _int), ("fit", ft_loglog_opts), ("fit_whole_range", _int),
                ("fewest", _int), ("progress", PROGRESS), ("progress_arg", _vp)]
    _defaults_ = dict(what=0, ncells=0, min_cell=0.0, max_cell=0.0, nscales=0, offsets=4, fit=FIT_DEFAULTS,
                      fit_whole_range=0, fewest=0)


@_mirror
class ft_boundary_opts(_Opts):
    _c_name_ = "ft_boundary_opts"
    _c_default_ = "FT_BOUNDARY_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("dim", _dbl), ("min", _dbl), ("max", _dbl), ("jitter", _dbl), ("seed", _u64), ("stream", _u64),
                ("allow_crossings", _int)]
    _defaults_ = dict(dim=0.0, min=0.0, max=0.0, jitter=0.0, seed=1, stream=0, allow_crossings=0)


# ---- contour.h ----

@_mirror
class ft_polygon(c.Structure):
    _c_name_ = "ft_polygon"
    _fields_ = [("outer", _P(ft_chain)), ("holes", _P(_P(ft_chain))), ("nholes", _sz)]


@_mirror
class ft_polygon_set(c.Structure):
    _c_name_ = "ft_polygon_set"
    _fields_ = [("polys", _P(ft_polygon)), ("n", _sz), ("cap", _sz)]


@_mirror
class ft_shrink_opts(_Opts):
    _c_name_ = "ft_shrink_opts"
    _c_default_ = "FT_SHRINK_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("join", _int), ("dprime", _dbl), ("quad_segs", _int), ("min_area", _dbl)]
    _defaults_ = dict(join=0, dprime=1.2, quad_segs=8, min_area=0.5)


@_mirror
class ft_fourier_opts(_Opts):
    _c_name_ = "ft_fourier_opts"
    _c_default_ = "FT_FOURIER_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("n", _int), ("f0", _int)]
    _defaults_ = dict(n=1024, f0=256)


@_mirror
class ft_mountain_opts(_Opts):
    _c_name_ = "ft_mountain_opts"
    _c_default_ = "FT_MOUNTAIN_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("method", _int), ("interval", _dbl), ("spacing", _dbl), ("seed_elevation", _dbl),
                ("levels_up", _int), ("levels_down", _int), ("shrink", ft_shrink_opts), ("dsecond", _dbl),
                ("theta_min", _dbl), ("theta_max", _dbl), ("fourier", ft_fourier_opts), ("collinear_deg", _dbl),
                ("match_dim", _int), ("allow_crossings", _int), ("seed", _u64), ("progress", PROGRESS), ("progress_arg", _vp)]
    _defaults_ = dict(method=3, interval=10.0, spacing=0.0, seed_elevation=0.0, levels_up=-1, levels_down=0,
                      shrink=dict(join=0, dprime=0.0, quad_segs=8, min_area=0.5), dsecond=0.5, theta_min=20.0,
                      theta_max=40.0, fourier=dict(n=1024, f0=256), collinear_deg=0.0, match_dim=1,
                      allow_crossings=0, seed=1)


@_mirror
class ft_contour_level(c.Structure):
    _c_name_ = "ft_contour_level"
    _fields_ = [("elev", _dbl), ("polys", _P(ft_polygon_set))]


@_mirror
class ft_contour_stack(c.Structure):
    _c_name_ = "ft_contour_stack"
    _fields_ = [("levels", _P(ft_contour_level)), ("n", _sz), ("spacing", _dbl), ("interval", _dbl),
                ("dprime", _dbl), ("guard_moves", _sz), ("guard_reduced", _sz), ("guard_dropped", _sz)]


@_mirror
class ft_contour_dem_opts(_Opts):
    _c_name_ = "ft_contour_dem_opts"
    _c_default_ = "FT_CONTOUR_DEM_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("cell", _dbl), ("margin", _dbl), ("summit", _dbl), ("progress", PROGRESS), ("progress_arg", _vp)]
    _defaults_ = dict(cell=0.0, margin=0.0, summit=0.5)


@_mirror
class ft_urban_class(c.Structure):
    _c_name_ = "ft_urban_class"
    _fields_ = [("label", _str), ("features", _P(_sz)), ("n", _sz)]


@_mirror
class ft_urban_classes(c.Structure):
    _c_name_ = "ft_urban_classes"
    _fields_ = [("classes", _P(ft_urban_class)), ("n", _sz), ("nnull", _sz)]


@_mirror
class ft_write_layer_opts(_Opts):
    _c_name_ = "ft_write_layer_opts"
    _c_default_ = "FT_WRITE_LAYER_OPTS_DEFAULT"
    _fields_ = [("struct_size", _sz), ("driver", _str), ("layer", _str), ("lco", _P(_str))]
