"""fracterra inside dask.array.map_overlap: a local D map computed block by block equals the whole
array's, cell for cell."""
import numpy as np
import pytest

import fracterra as ft

da = pytest.importorskip("dask.array")
from fracterra.dask import dim_map_dask  # noqa: E402


def whole(z, gt, window, step):
    D, _ = ft.dim_map(z, window, step, geotransform=gt)
    return np.where(D.mask, D.z, np.nan) if D.mask is not None else D.z


@pytest.mark.parametrize("chunks", [(48, 64), (40, 56), (32, 40)])
def test_blocks_equal_the_whole_array(chunks):
    g = ft.synth(150, 130, 2.4, seed=11, cell=25.0, origin=(300000, 5000000))
    z = g.z.copy()
    z[40:55, 60:90] = np.nan  # a void: windows over it are nodata in both
    want = whole(z, g.geotransform, 16, 8)
    got = dim_map_dask(da.from_array(z, chunks=chunks), 16, 8, geotransform=g.geotransform)
    got = got.compute(scheduler="threads")
    assert got.shape == want.shape == ((130 - 16) // 8 + 1, (150 - 16) // 8 + 1)
    assert np.isnan(want).any() and np.isfinite(want).any()
    assert np.array_equal(got, want, equal_nan=True)


def test_bad_chunks_are_refused():
    z = da.zeros((64, 64), chunks=(30, 32), dtype=np.float32)
    with pytest.raises(ValueError, match="multiples of step"):
        dim_map_dask(z, 16, 8)
