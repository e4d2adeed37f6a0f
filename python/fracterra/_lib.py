"""Loading libfracterra, its errors, and the ctypes prototypes of the functions the package calls.

The library is found, in order, through the FRACTERRA_LIBRARY environment variable (a path to
libfracterra.so), the absolute path written into _install_config.py by `cmake --install`, the build
tree beside the source tree (build/libfracterra.so, for working from a checkout), and the loader's
search path. ctypes releases the GIL around every foreign call, so long calls do not block other
Python threads.
"""
import ctypes
import ctypes.util
import os

from . import _structs as S

__all__ = ["FracterraError", "lib", "check", "check_ptr", "library_path"]

# FT_E_* codes of core.h; the layout test checks them against the header.
FT_OK = 0
FT_E_INVALID = -1
FT_E_NOMEM = -2
FT_E_IO = -3
FT_E_FORMAT = -4
FT_E_EMPTY = -5
FT_E_CANCELLED = -6
FT_E_NUMERIC = -7
FT_E_UNSUPPORTED = -8


class FracterraError(Exception):
    """A library call failed: str(e) is ft_last_error()'s message, e.code the FT_E_* code."""

    def __init__(self, message, code):
        super().__init__(message)
        self.code = code


def _candidates():
    env = os.environ.get("FRACTERRA_LIBRARY")
    if env:
        return [env], True
    paths = []
    try:
        from . import _install_config  # written by cmake --install
        paths.append(_install_config.LIBRARY)
    except ImportError:
        pass
    here = os.path.dirname(os.path.abspath(__file__))
    paths.append(os.path.join(here, os.pardir, os.pardir, "build", "libfracterra.so"))
    found = ctypes.util.find_library("fracterra")
    if found:
        paths.append(found)
    return paths, False


def _load():
    paths, explicit = _candidates()
    errors = []
    for p in paths:
        if os.sep in p and not os.path.exists(p):
            errors.append("%s: no such file" % p)
            continue
        try:
            return ctypes.CDLL(p), os.path.abspath(p) if os.sep in p else p
        except OSError as e:
            errors.append(str(e))
        if explicit:
            break
    raise ImportError("fracterra: cannot load libfracterra.so (set FRACTERRA_LIBRARY to its path): "
                      + "; ".join(errors))


lib, library_path = _load()

_c = ctypes
_P = _c.POINTER
_sz = _c.c_size_t
_int = _c.c_int
_dbl = _c.c_double
_str = _c.c_char_p
_vp = _c.c_void_p
_i64 = _c.c_int64

# (name, restype, argtypes): every function the package calls, declared once.
_PROTOTYPES = [
    ("ft_version", _str, []),
    ("ft_last_error", _str, []),
    ("ft_last_error_code", _int, []),
    ("ft_clear_error", None, []),
    ("ft_strerror", _str, [_int]),
    # core types
    ("ft_grid_create", _P(S.ft_grid), [_sz, _sz]),
    ("ft_grid_free", None, [_P(S.ft_grid)]),
    ("ft_chain_from_arrays", _P(S.ft_chain), [_P(_dbl), _P(_dbl), _sz, _sz, _int]),
    ("ft_chain_free", None, [_P(S.ft_chain)]),
    ("ft_points_free", None, [_P(S.ft_points)]),
    ("ft_layer_free", None, [_P(S.ft_layer)]),
    ("ft_dim_result_free", None, [_P(S.ft_dim_result)]),
    ("ft_grid_extent", None, [_P(S.ft_grid), _P(_dbl), _P(_dbl), _P(_dbl), _P(_dbl)]),
    # io
    ("ft_io_read_grid", _int, [_str, _P(S.ft_read_grid_opts), _P(_P(S.ft_grid))]),
    ("ft_io_write_grid", _int, [_str, _P(S.ft_grid), _P(S.ft_write_grid_opts)]),
    ("ft_io_read_layer", _int, [_str, _P(S.ft_read_layer_opts), _P(_P(S.ft_layer))]),
    ("ft_io_read_points", _int, [_str, _P(S.ft_read_points_opts), _P(_P(S.ft_points))]),
    ("ft_io_hillshade", _int, [_str, _str, _P(S.ft_io_hillshade_opts)]),
    ("ft_io_hillshade_scale", _int, [_str, _P(S.ft_io_hillshade_opts), _P(_dbl)]),
    ("ft_io_crs_to_wkt", _int, [_str, _P(_vp)]),
    ("ft_io_crs_info", _int, [_str, _P(S.ft_crs_info)]),
    ("ft_io_local_crs", _int, [_str, _int, _dbl, _dbl, _P(_vp)]),
    ("ft_io_grid_reproject", _int, [_P(S.ft_grid), _str, _dbl, _P(_P(S.ft_grid))]),
    ("ft_io_points_reproject", _int, [_P(S.ft_points), _str]),
    ("ft_io_layer_reproject", _int, [_P(S.ft_layer), _str]),
    ("ft_layer_bbox", _int, [_P(S.ft_layer), _P(_dbl), _P(_dbl), _P(_dbl), _P(_dbl)]),
    ("ft_ellipsoid_metres_per_degree", None, [_P(S.ft_ellipsoid), _dbl, _P(_dbl), _P(_dbl)]),
    ("ft_dim_result_set_units", None, [_P(S.ft_dim_result), _str]),
    ("ft_dim_result_warn", _int, [_P(S.ft_dim_result), _str, _str]),
    # surface
    ("ft_surface_method_parse", _int, [_str, _P(_int)]),
    ("ft_surface_method_name", _str, [_int]),
    ("ft_surface_dim", _int, [_P(S.ft_grid), _int, _P(S.ft_surface_dim_opts), _P(_P(S.ft_dim_result))]),
    ("ft_surface_dim_map", _int, [_P(S.ft_grid), _sz, _sz, _int, _P(S.ft_surface_dim_opts),
                                  _P(_P(S.ft_grid)), _P(_P(S.ft_grid))]),
    ("ft_points_method_parse", _int, [_str, _P(_int)]),
    ("ft_surface_dim_points", _int, [_P(S.ft_points), _P(S.ft_points_dim_opts), _P(_P(S.ft_dim_result))]),
    ("ft_points_counters_free", None, [_P(S.ft_points_counters)]),
    ("ft_profile_dim", _int, [_P(_dbl), _sz, _dbl, _int, _P(_P(S.ft_dim_result))]),
    ("ft_profile_from_grid_row", _int, [_P(S.ft_grid), _sz, _P(_P(_dbl)), _P(_sz), _P(_dbl)]),
    ("ft_profile_transect", _int, [_P(S.ft_grid), _dbl, _dbl, _dbl, _dbl, _P(_P(_dbl)), _P(_sz), _P(_dbl)]),
    ("ft_profile_resample", _int, [_P(_dbl), _P(_dbl), _P(_dbl), _sz, _dbl, _P(_P(_dbl)), _P(_sz), _P(_dbl)]),
    ("ft_io_read_line_z", _int, [_str, _str, _P(_P(_dbl)), _P(_P(_dbl)), _P(_P(_dbl)), _P(_sz)]),
    # line
    ("ft_line_method_parse", _int, [_str, _P(_int)]),
    ("ft_line_method_name", _str, [_int]),
    ("ft_line_dim", _int, [_P(_P(S.ft_chain)), _sz, _int, _P(S.ft_line_dim_opts), _P(_P(S.ft_dim_result))]),
    ("ft_line_enhance", _int, [_P(S.ft_chain), _P(S.ft_dutton_opts), _P(_P(S.ft_chain))]),
    ("ft_line_smooth", _int, [_P(S.ft_chain), _P(S.ft_smooth_opts), _P(_P(S.ft_chain))]),
    ("ft_line_weed", _int, [_P(S.ft_chain), _dbl, _P(_P(S.ft_chain))]),
    ("ft_line_simplify", _int, [_P(S.ft_chain), _dbl, _P(_P(S.ft_chain))]),
    ("ft_line_remove_loops", _int, [_P(S.ft_chain), _P(_P(S.ft_chain))]),
    ("ft_line_apply_layer", _int, [_P(S.ft_layer), _vp, _vp, _int]),
    ("ft_line_enhance_layer", _int, [_P(S.ft_layer), _P(S.ft_dutton_opts), _int, _vp, _vp]),
    ("ft_line_smooth_layer", _int, [_P(S.ft_layer), _P(S.ft_smooth_opts), _int, _vp]),
    ("ft_urban_boundary_layer", _int, [_P(S.ft_layer), _P(S.ft_boundary_opts), _int, _vp]),
    ("ft_layer_create", _P(S.ft_layer), [_str, _str]),
    ("ft_layer_add_feature", _i64, [_P(S.ft_layer), _i64, _int, _int]),
    ("ft_layer_add_part", _int, [_P(S.ft_layer), _P(S.ft_chain), _int, _int]),
    ("ft_layer_check_finite", _int, [_P(S.ft_layer)]),
    ("ft_layer_vertex_count", _sz, [_P(S.ft_layer)]),
    ("ft_io_write_layer", _int, [_str, _P(S.ft_layer), _P(S.ft_write_layer_opts)]),
    # terrain
    ("ft_synth_method_parse", _int, [_str, _P(_int)]),
    ("ft_terrain_synth", _int, [_sz, _sz, _P(S.ft_synth_opts), _P(_P(S.ft_grid))]),
    ("ft_synth_workspace_create", _int, [_sz, _sz, _P(S.ft_synth_opts), _P(_vp)]),
    ("ft_synth_workspace_free", None, [_vp]),
    ("ft_terrain_synth_into", _int, [_P(S.ft_synth_opts), _vp, _P(S.ft_grid)]),
    ("ft_recon_method_parse", _int, [_str, _P(_int)]),
    ("ft_reconstruct_points", _int, [_P(S.ft_points), _P(S.ft_grid), _P(S.ft_recon_opts), _P(_P(S.ft_grid)),
                                     _P(_P(S.ft_grid)), _P(S.ft_recon_info)]),
    ("ft_reconstruct_voids", _int, [_P(S.ft_grid), _P(S.ft_recon_opts), _P(_P(S.ft_grid)), _P(_P(S.ft_grid)),
                                    _P(S.ft_recon_info)]),
    ("ft_terrain_fill", _int, [_P(S.ft_grid), _P(_c.c_uint8), _P(S.ft_fill_opts), _P(_P(S.ft_grid)),
                               _P(_P(S.ft_grid)), _P(_P(S.ft_fill_result))]),
    ("ft_fill_result_free", None, [_P(S.ft_fill_result)]),
    ("ft_fill_d_source_name", _str, [_int]),
    ("ft_clarke_fit", _int, [_P(S.ft_grid), _P(S.ft_clarke_opts), _P(_P(S.ft_clarke_model))]),
    ("ft_clarke_simulate", _int, [_P(S.ft_clarke_model), _P(S.ft_clarke_sim_opts), _P(_P(S.ft_grid))]),
    ("ft_clarke_model_free", None, [_P(S.ft_clarke_model)]),
    ("ft_render_hillshade", _int, [_P(S.ft_grid), _P(S.ft_hillshade_opts), _P(_P(S.ft_grid))]),
    # urban
    ("ft_area_what_parse", _int, [_str, _P(_int)]),
    ("ft_urban_dim_area", _int, [_P(S.ft_layer), _P(_sz), _sz, _P(S.ft_area_dim_opts), _P(_P(S.ft_dim_result))]),
    ("ft_urban_classes_by_field", _int, [_P(S.ft_layer), _str, _P(_P(S.ft_urban_classes))]),
    ("ft_urban_classes_free", None, [_P(S.ft_urban_classes)]),
    ("ft_urban_boundary", _int, [_P(S.ft_chain), _P(S.ft_boundary_opts), _P(_P(S.ft_chain))]),
    # contour
    ("ft_layer_field_index", _int, [_P(S.ft_layer), _str]),
    ("ft_polygon_set_from_layer", _int, [_P(S.ft_layer), _P(_P(S.ft_polygon_set))]),
    ("ft_polygon_set_free", None, [_P(S.ft_polygon_set)]),
    ("ft_mountain_method_parse", _int, [_str, _P(_int)]),
    ("ft_contour_join_parse", _int, [_str, _P(_int)]),
    ("ft_mountain_generate", _int, [_P(S.ft_polygon_set), _P(S.ft_mountain_opts), _P(_P(S.ft_contour_stack))]),
    ("ft_contour_stack_to_dem", _int, [_P(S.ft_contour_stack), _P(S.ft_contour_dem_opts), _str,
                                       _P(_P(S.ft_grid))]),
    ("ft_contour_stack_free", None, [_P(S.ft_contour_stack)]),
]

for _name, _res, _args in _PROTOTYPES:
    _f = getattr(lib, _name)
    _f.restype = _res
    _f.argtypes = _args

_libc = ctypes.CDLL(None)
_libc.free.argtypes = [_vp]
_libc.free.restype = None
_libc.strdup.argtypes = [_str]
_libc.strdup.restype = _vp


def c_strdup(b):
    """A malloc'd copy of bytes b (for a field the library may free())."""
    return _libc.strdup(b)


def c_free(ptr):
    """free() of a pointer the library allocated with malloc (e.g. ft_io_crs_to_wkt's WKT)."""
    _libc.free(ptr)


def raise_last(code=None):
    msg = lib.ft_last_error()
    msg = msg.decode("utf-8", "replace") if msg else ""
    if code is None:
        code = lib.ft_last_error_code()
    if not msg:
        s = lib.ft_strerror(code)
        msg = s.decode() if s else "fracterra error %d" % code
    raise FracterraError(msg, code)


def check(rc):
    """Raises FracterraError with the library's message when a call returned a negative FT_E_* code."""
    if rc < 0:
        raise_last(rc)
    return rc


def check_ptr(p):
    if not p:
        raise_last()
    return p


_parsed = {}  # (parser's name, name) -> value, for the names the library's parser accepted


def parse_enum(parser, name, what):
    """An enum value from its name through the library's own parser (ft_*_method_parse), asked once
    per name."""
    if not isinstance(name, str):
        raise TypeError("%s must be a string, got %r" % (what, name))
    key = (parser.__name__, name)
    v = _parsed.get(key)
    if v is None:
        c = _int()
        check(parser(name.encode(), ctypes.byref(c)))
        v = _parsed[key] = c.value
    return v
