"""What the estimators share: the log-log fit options and the scale options of the CLI's `dim`
commands (--min-scale, --max-scale, --scales; both limits given = least squares over that range)."""
import os

from . import _structs as S


def set_fit(opts_fit, fit):
    """Applies a dict of ft_loglog_opts fields (method 'regimes' (default), 'ils' or 'minimax', tol,
    width, tol_sigma, min_points, max_iter, min_span, bounds_tol, curve_dD, curve_alpha, regime) over
    the defaults."""
    if not fit:
        return
    for k, v in fit.items():
        if k not in S.FIT_DEFAULTS:
            raise ValueError("fit: unknown option %r (known: %s)" % (k, ", ".join(sorted(S.FIT_DEFAULTS))))
        if k == "method":
            v = {"ils": 0, "minimax": 1, "regimes": 2}.get(v, v)
            if v not in (0, 1, 2):
                raise ValueError("fit method must be 'regimes', 'ils' or 'minimax', got %r" % (fit["method"],))
        setattr(opts_fit, k, v)


def set_scales(o, min_scale, max_scale, nscales, fit_whole_range, names=("min_scale", "max_scale", "nscales")):
    """The CLI's scale policy: 0 = automatic; with both limits given, least squares over the range
    unless fit_whole_range says otherwise."""
    lo, hi, n = names
    setattr(o, lo, float(min_scale or 0.0))
    setattr(o, hi, float(max_scale or 0.0))
    setattr(o, n, int(nscales or 0))
    if fit_whole_range is None:
        fit_whole_range = bool(min_scale) and bool(max_scale)
    if hasattr(o, "fit_whole_range"):
        o.fit_whole_range = 1 if fit_whole_range else 0


def path_bytes(path):
    """A str, bytes or os.PathLike path as the bytes the C library takes."""
    return os.fsencode(path)
