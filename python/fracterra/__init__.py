"""fracterra for Python: the fractal geometry of maps, over libfracterra through ctypes.

Grids are NumPy float32 arrays (row 0 north) with GDAL's geotransform and the CRS as WKT (Grid);
chains are (n, 2) float64 arrays; dimension results are DimResult objects carrying D, its standard
error, r², the scale range and units, the whole log-log table as a structured array, the segments
and the warnings. Errors raise FracterraError with the library's message. Long calls release the GIL
and take progress=fn(frac, message, arg) (GDAL's callback signature; return 0/False to cancel).
See docs/python.md.
"""
from ._lib import FracterraError, library_path, lib as _clib
from ._core import Grid, DimResult
from .surface import dim_surface, dim_map, dim_points, read_points, SURFACE_METHODS
from .line import (read_chains, dim_line, enhance, smooth, weed, simplify, remove_loops, boundary, edit_file,
                   LINE_METHODS)
from .terrain import (synth, Synthesizer, reconstruct, ReconInfo, clarke_fit, clarke_simulate, ClarkeModel,
                      hillshade, hillshade_file, fill, SYNTH_METHODS, RECON_METHODS)
from .urban import dim_area
from .profile import dim_profile, PROFILE_METHODS
from .contour import mountain, MOUNTAIN_METHODS
from .io import read_grid, write_grid, from_gdal, to_gdal

__version__ = _clib.ft_version().decode()

__all__ = ["FracterraError", "Grid", "DimResult", "library_path", "__version__",
           "dim_surface", "dim_map", "dim_points", "read_points", "dim_line", "read_chains", "dim_area", "dim_profile",
           "enhance", "smooth", "weed", "simplify", "remove_loops", "boundary", "edit_file",
           "synth", "Synthesizer", "reconstruct", "ReconInfo", "clarke_fit", "clarke_simulate", "ClarkeModel",
           "hillshade", "hillshade_file", "fill", "mountain", "read_grid", "write_grid", "from_gdal", "to_gdal",
           "SURFACE_METHODS", "LINE_METHODS", "SYNTH_METHODS", "RECON_METHODS", "MOUNTAIN_METHODS", "PROFILE_METHODS"]
