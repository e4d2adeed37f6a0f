"""make bench: what the Python package adds to a library call (target: at most 5% on a 2048² grid and
a 10^5-vertex chain).

Each package function is called with its library function replaced by a timing proxy, so that one run
gives both the time inside the C function and the time of the whole Python call (argument checks,
NumPy conversion in and out, the result object, freeing): overhead = (whole - inside) / inside, in the
same run under the same load, which a shared machine needs (separate runs differ by 10% and more).
The proxy's own cost (a Python call and two clock reads, about a microsecond) counts as overhead.
Median over REPEAT runs, after one warm-up run (FFTW plans, first-touch pages). OMP_NUM_THREADS
defaults to 1 here: the overhead is serial work, and threads on a loaded machine only add noise.

Usage: /usr/bin/python3 bench/python/overhead.py [BUILD_DIR] [REPEAT]
"""
import os
import statistics
import sys
import time

import numpy as np

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), os.pardir, os.pardir))
BUILD = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build"))
REPEAT = int(sys.argv[2]) if len(sys.argv) > 2 else 9
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("FRACTERRA_LIBRARY", os.path.join(BUILD, "libfracterra.so"))
sys.path.insert(0, os.path.join(ROOT, "python"))
import fracterra as ft  # noqa: E402
from fracterra._lib import lib  # noqa: E402

N = 2048
NV = 100000
LIMIT = 0.05


class Proxy:
    """Stands for lib.<name> during a call and accumulates the time spent in it."""

    def __init__(self, name):
        self.name, self.fn, self.inside = name, getattr(lib, name), 0.0

    def __call__(self, *args):
        t0 = time.perf_counter()
        try:
            return self.fn(*args)
        finally:
            self.inside += time.perf_counter() - t0


def measure(name, call):
    proxy = Proxy(name)
    setattr(lib, name, proxy)
    try:
        call()
        ratios, inside, whole = [], [], []
        for _ in range(REPEAT):
            proxy.inside = 0.0
            t0 = time.perf_counter()
            call()
            w = time.perf_counter() - t0
            ratios.append((w - proxy.inside) / proxy.inside)
            inside.append(proxy.inside)
            whole.append(w)
    finally:
        setattr(lib, name, proxy.fn)
    return statistics.median(inside), statistics.median(whole), statistics.median(ratios)


def main():
    g = ft.synth(N, N, 2.3)
    i = np.arange(NV, dtype=float)
    xy = np.c_[i, 50.0 * np.sin(0.013 * i) + 7.0 * np.sin(0.37 * i)]
    x, y = xy[:, 0].copy(), xy[:, 1].copy()
    cases = [
        ("synth 2048²", "ft_terrain_synth", lambda: ft.synth(N, N, 2.3)),
        ("dim_surface 2048²", "ft_surface_dim", lambda: ft.dim_surface(g)),
        ("dim_map 2048², w 256", "ft_surface_dim_map", lambda: ft.dim_map(g, 256, 256)),
        ("hillshade 2048²", "ft_render_hillshade", lambda: ft.hillshade(g)),
        ("dim_line 10^5 vertices", "ft_line_dim", lambda: ft.dim_line(xy)),
        ("dim_line 10^5 (x, y)", "ft_line_dim", lambda: ft.dim_line(x, y)),
        ("dim_line box 10^5", "ft_line_dim", lambda: ft.dim_line(xy, method="box")),
        ("enhance 10^5 (x, y)", "ft_line_enhance_layer", lambda: ft.enhance(x, y)),
        ("enhance 10^5 (n, 2)", "ft_line_enhance_layer", lambda: ft.enhance(xy)),
        ("simplify 10^5 (x, y)", "ft_line_simplify", lambda: ft.simplify(x, y, tolerance=1.0)),
        ("simplify 10^5 (n, 2)", "ft_line_simplify", lambda: ft.simplify(xy, tolerance=1.0)),
        ("smooth 10^5 (x, y)", "ft_line_smooth_layer", lambda: ft.smooth(x, y)),
        ("smooth 10^5 (n, 2)", "ft_line_smooth_layer", lambda: ft.smooth(xy)),
    ]
    print("python overhead: time of the package call outside the library function, median of %d runs "
          "(OMP_NUM_THREADS=%s; limit %.0f%%)" % (REPEAT, os.environ["OMP_NUM_THREADS"], 100 * LIMIT))
    print("  %-24s %11s %11s %9s" % ("call", "library s", "package s", "overhead"))
    worst = 0.0
    for label, name, call in cases:
        inside, whole, ratio = measure(name, call)
        worst = max(worst, ratio)
        print("  %-24s %11.5f %11.5f %8.2f%%%s" % (label, inside, whole, 100 * ratio,
                                                  "" if ratio <= LIMIT else "  OVER"))
    print("  worst %.2f%%: %s" % (100 * worst, "within the limit" if worst <= LIMIT else "OVER the limit"))


if __name__ == "__main__":
    main()
