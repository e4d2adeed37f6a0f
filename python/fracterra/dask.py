"""A local D map of a dask array, block by block with dask.array.map_overlap, equal cell for cell to
fracterra.dim_map on the whole array (docs/python.md, "Scaling out with dask").

Every window of dim_map is measured on its own cells only (fixed scale range, exhaustive pairs), so a
block that holds the windows whose upper-left cell lies in its core, plus the window - step cells of
overlap that the last of them reaches into, gives exactly the whole array's values for them."""
import numpy as np

from .surface import dim_map

__all__ = ["dim_map_dask"]


def dim_map_dask(z, window, step=None, geotransform=(0.0, 1.0, 0.0, 0.0, 0.0, 1.0), method="variogram", **opts):
    """The D map of a 2-D dask array z (NaN = nodata) as a dask array of float32 (NaN where dim_map
    leaves nodata), on the lattice of dim_map(z, window, step). Chunks must be multiples of step (the
    last excepted) and at least window - step cells (a thinner last chunk is merged into the one before). opts: dim_map's options (pairs, seed, min_scale, ...; pairs must
    stay 0, exhaustive, for block results to equal the whole array's)."""
    import dask.array as da

    window = int(window)
    step = max(1, window // 4) if step is None else int(step)
    depth = window - step
    merged = tuple(cs[:-2] + (cs[-2] + cs[-1],) if len(cs) > 1 and cs[-1] < depth else cs for cs in z.chunks)
    if merged != z.chunks:  # a last chunk thinner than the overlap joins the one before it
        z = z.rechunk(merged)
    for axis, cs in enumerate(z.chunks):
        if any(c % step for c in cs[:-1]) or (len(cs) > 1 and min(cs) < depth):
            raise ValueError("axis %d: chunks %r must be multiples of step %d and at least window - step = %d"
                             % (axis, cs, step, depth))
    if opts.get("pairs", 0):
        raise ValueError("dim_map_dask needs exhaustive pairs (pairs=0): random pairs depend on the window's place")
    n_out = [(n - window) // step + 1 for n in z.shape]
    if min(n_out) < 1:
        raise ValueError("the array (%d x %d) is smaller than one window of %d cells" % (z.shape[1], z.shape[0],
                                                                                           window))
    starts = [np.cumsum((0,) + cs[:-1]) for cs in z.chunks]

    def out_counts(axis):
        # windows whose upper-left cell u (a multiple of step) lies in each chunk's core
        counts = []
        for s, c in zip(starts[axis], z.chunks[axis]):
            us = [u for u in range(s, s + c, step) if u + window <= z.shape[axis]]
            counts.append(len(us))
        return tuple(counts)

    out_chunks = (out_counts(0), out_counts(1))
    gt = tuple(float(v) for v in geotransform)

    def block(b, block_id=None):
        i, j = block_id
        r0, c0 = starts[0][i], starts[1][j]
        off_r, off_c = (depth if i > 0 else 0), (depth if j > 0 else 0)
        nr, nc = out_chunks[0][i], out_chunks[1][j]
        if nr == 0 or nc == 0:
            return np.empty((nr, nc), np.float32)
        sub = b[off_r:off_r + (nr - 1) * step + window, off_c:off_c + (nc - 1) * step + window]
        sub_gt = (gt[0] + c0 * gt[1] + r0 * gt[2], gt[1], gt[2], gt[3] + c0 * gt[4] + r0 * gt[5], gt[4], gt[5])
        D, _r2 = dim_map(np.ascontiguousarray(sub, dtype=np.float32), window, step, method=method,
                         geotransform=sub_gt, **opts)
        return np.where(D.mask, D.z, np.float32(np.nan)) if D.mask is not None else D.z

    return da.map_overlap(block, z, depth=depth, boundary="none", trim=False, chunks=out_chunks,
                          dtype=np.float32)
