"""Delaunay triangulations larger than one process, on Dask: tile and merge.

``delaunay(points, client)`` gives the same triangle set as one ``triangulate("Q", ...)`` call on
all the points, computed by Dask workers none of which holds all the points (Caraffa, Memari,
Yirci, Brédif, "Tile & Merge: Distributed Delaunay Triangulations for Cloud Computing", IEEE
BigData 2019; Isenburg, Liu, Shewchuk, Snoeyink, "Streaming computation of Delaunay
triangulations", SIGGRAPH 2006, for the same rule out of core):

1. The points are cut into tiles by a sample's quantiles (columns by x, then rows by y in each
   column: balanced counts), each point in exactly one tile by its coordinates.
2. Each tile triangulates its own points with a halo of its neighbours' points near it (one
   library call on a worker).
3. A triangle belongs to the triangulation of all the points exactly when its closed circumdisk
   holds no other point (ties: the library's rule, a symbolic perturbation that depends on the
   points' coordinates only, so every tile and the single call decide a tie alike). So a tile
   asks its neighbours for their points inside the circumdisks of the triangles around its own
   vertices (and, for an edge of its hull, for the point beyond it that makes the Delaunay
   triangle there); it adds what it receives and triangulates again, until no tile receives
   anything new. A disk inside the tile's own rectangle needs no question: no other tile has a
   point there.
4. Then the triangles around each of the tile's vertices are those of the whole triangulation,
   and each triangle is given by the tile that owns its smallest global index: the union holds
   every triangle once.

Circumdisks are computed in floating point and asked for with a margin, so a tile receives every
point that may lie in or on a disk (and a few more, which change nothing): the decisions
themselves are the library's exact predicates. A tile that cannot be triangulated alone (fewer
than three points, or all on a line) widens its halo until it can.

Dask's progress bar (``distributed.progress``) and dashboard show the rounds' tasks; cancelling
is interrupting the call (its futures are released). A worker that dies mid-run: Dask recomputes
its tasks on the others (every task is a pure function of its inputs).
"""

from __future__ import annotations

import glob
import os
import warnings
from dataclasses import dataclass
from typing import Any, Callable, Optional, Sequence

import numpy as np

from .core import TriangulateError, run
from .triangulateio import TriangulateIO

__all__ = ["DistributedTriangulation", "delaunay", "from_npy_directory", "from_parquet", "tiles_for_memory"]

# Circumdisks are asked for this much larger (relative to the coordinates' magnitude and the
# radius): far above the rounding of the floating-point centre and radius (some 10^-15 of them).
_RELATIVE_MARGIN = 1e-9
# Shewchuk's error bound of the floating-point orientation, (3 + 16ε)ε.
_ORIENT_BOUND = (3.0 + 16.0 * 2.0**-53) * 2.0**-53
# Halo width in mean point spacings of the tile: wide enough that, on uniform points, nearly
# every circumdisk at the tile's border is covered by round one, so few tiles ask again (3
# spacings took four rounds on 10^6 points in 9 tiles).
_HALO_SPACINGS = 8.0

# What one point of a tile costs a worker while its round runs, in bytes (see
# :func:`tiles_for_memory`): coordinates and global index held (24) and their k-d tree (~24);
# the merged copy with the halo (24) and the ownership mask; the engine (~85 per vertex); its
# outputs, two triangles per point with their neighbours as int32 (48) and as int64 (96);
# circumdisks and masks of the round (~60). Rounded up for numpy's temporaries.
_BYTES_PER_TILE_POINT = 450
# A Dask worker process's own resident memory before it holds any data (interpreter, dask,
# distributed, numpy, scipy and the library): measured 100–130 MB.
_WORKER_BASELINE_BYTES = 130 * 2**20
# The nanny kills a worker at 95% of its memory limit: plan below that.
_USABLE_FRACTION = 0.85


# --- Tiling ------------------------------------------------------------------------------


@dataclass(frozen=True)
class Tiling:
    """Columns cut at ``xcuts``, each column's rows cut at ``ycuts[column]``: a point goes to
    the column of the first cut above its x (a point on a cut goes right) and so for rows."""

    xcuts: np.ndarray  # (columns - 1,)
    ycuts: np.ndarray  # (columns, rows - 1)

    @property
    def columns(self) -> int:
        return len(self.xcuts) + 1

    @property
    def rows(self) -> int:
        return self.ycuts.shape[1] + 1

    @property
    def count(self) -> int:
        return self.columns * self.rows

    def tile_of(self, xy: np.ndarray) -> np.ndarray:
        column = np.searchsorted(self.xcuts, xy[:, 0], side="right")
        tile = np.empty(len(xy), dtype=np.int64)
        for c in range(self.columns):
            mask = column == c
            tile[mask] = c * self.rows + np.searchsorted(self.ycuts[c], xy[mask, 1], side="right")
        return tile

    def rectangle(self, tile: int, bounds: np.ndarray) -> np.ndarray:
        """``[xlo, ylo, xhi, yhi]`` of the tile (the outer ones reach the points' bounds)."""
        c, r = divmod(tile, self.rows)
        xs = np.concatenate([[bounds[0]], self.xcuts, [bounds[2]]])
        ys = np.concatenate([[bounds[1]], self.ycuts[c], [bounds[3]]])
        return np.array([xs[c], ys[r], xs[c + 1], ys[r + 1]])


def _tiling_from_sample(sample: np.ndarray, columns: int, rows: int) -> Tiling:
    xcuts = np.quantile(sample[:, 0], np.arange(1, columns) / columns) if columns > 1 else np.empty(0)
    column = np.searchsorted(xcuts, sample[:, 0], side="right")
    ycuts = np.empty((columns, rows - 1))
    for c in range(columns):
        ys = sample[column == c, 1]
        if len(ys) == 0:
            ys = sample[:, 1]
        ycuts[c] = np.quantile(ys, np.arange(1, rows) / rows) if rows > 1 else np.empty(0)
    return Tiling(np.asarray(xcuts, dtype=np.float64), ycuts)


def tiles_for_memory(
    n: int,
    memory_per_worker: int,
    workers: int = 1,
    *,
    baseline: int = _WORKER_BASELINE_BYTES,
    bytes_per_point: int = _BYTES_PER_TILE_POINT,
    halo_fraction: float = 0.25,
) -> int:
    """The number of tiles for ``n`` points such that one tile's round fits in a worker of
    ``memory_per_worker`` bytes: the worker's own ``baseline``, then per point of the tile (its
    own and, ``halo_fraction`` more, its halo) ``bytes_per_point`` for the points, their k-d
    tree, the engine (~85 bytes per vertex), its outputs and the Python copies. Planned against
    85% of the limit, since the nanny kills at 95%. At least ``workers`` tiles, so that every
    worker has work.

    The tiles a worker holds between rounds (~48 bytes per point) and the results (~24 bytes
    per point) are Dask's managed data: past its ``spill`` threshold Dask writes them to disk, so
    they do not count here. Raises :class:`ValueError` when the limit does not even hold the
    baseline.
    """
    if n < 0 or workers < 1:
        raise ValueError(f"need n >= 0 and workers >= 1, got n={n}, workers={workers}")
    available = _USABLE_FRACTION * memory_per_worker - baseline
    if available <= bytes_per_point * 64:
        raise ValueError(
            f"memory_per_worker={memory_per_worker} bytes leaves no room past a worker's own "
            f"~{baseline} bytes (planned against {_USABLE_FRACTION:.0%} of the limit)"
        )
    points_per_tile = available / (bytes_per_point * (1.0 + halo_fraction))
    return max(workers, int(np.ceil(n / points_per_tile)))


# --- Tasks on the workers (pure functions of their arguments) ------------------------------


def _chunk_summary(block: np.ndarray, seed: int, sample_size: int) -> dict:
    """Count, finiteness, bounds, lexicographic extremes and a sample of one chunk."""
    xy = np.asarray(block[:, :2], dtype=np.float64)
    finite = np.isfinite(xy).all(axis=1)
    if not finite.all():
        return {"count": len(xy), "first_bad": int(np.argmin(finite))}
    summary: dict = {"count": len(xy), "first_bad": None}
    if len(xy) == 0:
        return summary
    order = np.lexsort((xy[:, 1], xy[:, 0]))
    summary["bounds"] = np.array([xy[:, 0].min(), xy[:, 1].min(), xy[:, 0].max(), xy[:, 1].max()])
    summary["lowest"], summary["highest"] = xy[order[0]], xy[order[-1]]
    rng = np.random.default_rng(seed)
    take = rng.choice(len(xy), size=min(sample_size, len(xy)), replace=False)
    summary["sample"] = xy[take]
    return summary


def _off_line(block: np.ndarray, a: np.ndarray, b: np.ndarray) -> bool:
    """Whether some point of the chunk is off the line through ``a`` and ``b`` (exact)."""
    xy = np.asarray(block[:, :2], dtype=np.float64)
    left = (b[0] - a[0]) * (xy[:, 1] - a[1])
    right = (b[1] - a[1]) * (xy[:, 0] - a[0])
    det = left - right
    bound = _ORIENT_BOUND * (np.abs(left) + np.abs(right))
    if (np.abs(det) > bound).any():
        return True
    from fractions import Fraction

    fa = [Fraction(float(v)) for v in a]
    fb = [Fraction(float(v)) for v in b]
    for x, y in xy[np.abs(det) <= bound]:
        if (fb[0] - fa[0]) * (Fraction(float(y)) - fa[1]) != (fb[1] - fa[1]) * (Fraction(float(x)) - fa[0]):
            return True
    return False


def _split_chunk(block: np.ndarray, offset: int, tiling: Tiling) -> list:
    """The chunk's points per tile: ``(global indices, coordinates)``."""
    xy = np.asarray(block[:, :2], dtype=np.float64)
    tile = tiling.tile_of(xy)
    order = np.argsort(tile, kind="stable")
    starts = np.searchsorted(tile[order], np.arange(tiling.count + 1))
    pieces = []
    for t in range(tiling.count):
        take = order[starts[t] : starts[t + 1]]
        pieces.append((take.astype(np.int64) + offset, xy[take]))
    return pieces


def _piece(pieces: list, tile: int):
    return pieces[tile]


def _gather_tile(*pieces) -> tuple:
    """A tile's own points, by increasing global index (so that duplicates keep the first copy,
    as in the single call), with a k-d tree for the neighbours' questions."""
    from scipy.spatial import cKDTree

    index = np.concatenate([p[0] for p in pieces]) if pieces else np.empty(0, np.int64)
    xy = np.concatenate([p[1] for p in pieces]) if pieces else np.empty((0, 2))
    order = np.argsort(index, kind="stable")
    index, xy = index[order], xy[order]
    return index, xy, cKDTree(xy) if len(xy) else None


def _tile_stats(tile: tuple) -> dict:
    index, xy, _ = tile
    if len(xy) == 0:
        return {"count": 0, "bounds": None}
    return {"count": len(xy), "bounds": np.array([*xy.min(axis=0), *xy.max(axis=0)])}


def _in_rectangle(tile: tuple, rectangle: np.ndarray) -> tuple:
    """The tile's points in the closed rectangle ``[xlo, ylo, xhi, yhi]``."""
    index, xy, _ = tile
    inside = (
        (xy[:, 0] >= rectangle[0]) & (xy[:, 0] <= rectangle[2]) & (xy[:, 1] >= rectangle[1]) & (xy[:, 1] <= rectangle[3])
    )
    return index[inside], xy[inside]


def _local_delaunay(xy: np.ndarray) -> Optional[tuple]:
    """Triangles and neighbours of the library's Delaunay triangulation, or ``None`` when the
    points make none (fewer than three, or all on a line)."""
    if len(xy) < 3:
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # duplicates: counted by the caller
        out, _ = run("Qzn", TriangulateIO(pointlist=np.ascontiguousarray(xy)))
    triangles = np.asarray(out.trianglelist, dtype=np.int64).reshape(-1, 3)
    if len(triangles) == 0:
        return None
    return triangles, np.asarray(out.neighborlist, dtype=np.int64).reshape(-1, 3)


def _merged(tile: tuple, imported: tuple) -> tuple:
    """Own and imported points together, by increasing global index."""
    index = np.concatenate([tile[0], imported[0]])
    xy = np.concatenate([tile[1], imported[1]])
    order = np.argsort(index, kind="stable")
    return index[order], xy[order]


def _circumdisks(xy: np.ndarray, triangles: np.ndarray, scale: float) -> np.ndarray:
    """``(cx, cy, r)`` per triangle, the radius enlarged by the margin."""
    a, b, c = xy[triangles[:, 0]], xy[triangles[:, 1]], xy[triangles[:, 2]]
    ba, ca = b - a, c - a
    d = 2.0 * (ba[:, 0] * ca[:, 1] - ba[:, 1] * ca[:, 0])
    lb, lc = (ba**2).sum(axis=1), (ca**2).sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (ca[:, 1] * lb - ba[:, 1] * lc) / d
        uy = (ba[:, 0] * lc - ca[:, 0] * lb) / d
    r = np.hypot(ux, uy)
    centre = a + np.stack([ux, uy], axis=1)
    r = r * (1.0 + _RELATIVE_MARGIN) + _RELATIVE_MARGIN * scale
    r[~np.isfinite(r)] = np.inf
    return np.column_stack([centre, r])


def _round(tile: tuple, imported: tuple, rectangle: np.ndarray, scale: float) -> dict:
    """One round of a tile: triangulates its points with what it imported, and returns the
    questions for its neighbours: the circumdisks of the triangles around its own vertices that
    reach out of its rectangle, and its hull edges at its own vertices (outward: the interior
    on their left)."""
    index, xy = _merged(tile, imported)
    own = np.isin(index, tile[0])
    mesh = _local_delaunay(xy)
    if mesh is None:
        return {"degenerate": True, "disks": np.empty((0, 3)), "edges": np.empty((0, 4))}
    triangles, neighbours = mesh
    around_own = own[triangles].any(axis=1)
    disks = _circumdisks(xy, triangles[around_own], scale)
    reaching_out = (
        (disks[:, 0] - disks[:, 2] <= rectangle[0])
        | (disks[:, 0] + disks[:, 2] >= rectangle[2])
        | (disks[:, 1] - disks[:, 2] <= rectangle[1])
        | (disks[:, 1] + disks[:, 2] >= rectangle[3])
    )
    # Hull edges: neighbour k (opposite corner k) missing; the edge runs from corner k+1 to k+2.
    edges = []
    for k in range(3):
        hull = neighbours[:, k] < 0
        u, v = triangles[hull, (k + 1) % 3], triangles[hull, (k + 2) % 3]
        at_own = own[u] | own[v]
        edges.append(np.column_stack([xy[u[at_own]], xy[v[at_own]]]))
    return {"degenerate": False, "disks": disks[reaching_out], "edges": np.concatenate(edges)}


def _answer(tile: tuple, disks: np.ndarray, edges: np.ndarray, scale: float) -> tuple:
    """A neighbour's answer: its points in or near the disks, and for each hull edge the point
    beyond it whose circle through the edge's ends bulges least beyond it (the Delaunay apex
    there, among this tile's points) with the points within the margin of the edge's line."""
    index, xy, tree = tile
    found: list = []
    if tree is not None and len(disks):
        finite = np.isfinite(disks[:, 2])
        if finite.any():
            hits = tree.query_ball_point(disks[finite, :2], disks[finite, 2], return_sorted=False)
            # One concatenation of the per-disk lists: a Python generator over them was the
            # answer's main cost on large tiles.
            lists = [h for h in hits if h]
            if lists:
                found.append(np.concatenate([np.asarray(h, dtype=np.int64) for h in lists]))
    if len(xy) and len(edges):
        for ax, ay, bx, by in edges:
            ex, ey = bx - ax, by - ay
            # Beyond (right of) the edge, or within the margin of its line.
            side = ex * (xy[:, 1] - ay) - ey * (xy[:, 0] - ax)
            length = np.hypot(ex, ey)
            near = np.abs(side) <= _RELATIVE_MARGIN * length * (scale + length)
            beyond = side < 0
            candidates = np.flatnonzero(beyond & ~near)
            if len(candidates):
                mx, my = 0.5 * (ax + bx), 0.5 * (ay + by)
                nx, ny = ey / length, -ex / length  # outward unit normal
                p = xy[candidates]
                dx, dy = p[:, 0] - mx, p[:, 1] - my
                half2 = 0.25 * length * length
                t = ((dx * dx + dy * dy) - half2) / (2.0 * (dx * nx + dy * ny))
                found.append(np.array([candidates[np.argmin(t)]]))
            found.append(np.flatnonzero(near))
    if not found:
        return np.empty(0, np.int64), np.empty((0, 2))
    take = np.unique(np.concatenate([np.asarray(f, dtype=np.int64) for f in found]))
    return index[take], xy[take]


def _add(imported: tuple, *answers) -> tuple:
    """The imported points with the answers' new ones; and how many were new."""
    index = np.concatenate([imported[0], *[a[0] for a in answers]])
    xy = np.concatenate([imported[1], *[a[1] for a in answers]])
    index, first = np.unique(index, return_index=True)
    return (index, xy[first]), len(index) - len(imported[0])


def _edges_facing(edges: np.ndarray, box: np.ndarray, scale: float) -> np.ndarray:
    """Which hull edges (``ax, ay, bx, by``, interior on the left) have some corner of ``box``
    beyond them or within the margin of their line."""
    if len(edges) == 0:
        return np.zeros(0, dtype=bool)
    ex, ey = edges[:, 2] - edges[:, 0], edges[:, 3] - edges[:, 1]
    length = np.hypot(ex, ey)
    facing = np.zeros(len(edges), dtype=bool)
    for x, y in ((box[0], box[1]), (box[2], box[1]), (box[0], box[3]), (box[2], box[3])):
        side = ex * (y - edges[:, 1]) - ey * (x - edges[:, 0])
        facing |= side <= _RELATIVE_MARGIN * length * (scale + length)
    return facing


def _nothing_imported() -> tuple:
    return np.empty(0, np.int64), np.empty((0, 2))


def _first(pair: tuple):
    return pair[0]


def _second(pair: tuple):
    return pair[1]


def _owned_triangles(tile: tuple, imported: tuple, index_dtype: Any) -> np.ndarray:
    """The triangles (global indices) whose smallest index is the tile's own."""
    index, xy = _merged(tile, imported)
    mesh = _local_delaunay(xy)
    if mesh is None:
        return np.empty((0, 3), dtype=index_dtype)
    global_triangles = index[mesh[0]]
    keep = np.isin(global_triangles.min(axis=1), tile[0])
    return global_triangles[keep].astype(index_dtype)


def _duplicates(tile: tuple) -> int:
    xy = tile[1]
    if len(xy) == 0:
        return 0
    return len(xy) - len(np.unique(xy, axis=0))


# --- The driver on the client ----------------------------------------------------------------


@dataclass
class DistributedTriangulation:
    """The result: ``points`` (the input, a dask array (n, 2 + attributes)) and ``triangles``
    (a dask array (m, 3) of global 0-based vertex indices, counter-clockwise, one block per
    tile, held on the workers)."""

    points: Any
    triangles: Any
    rounds: int
    tiles: int
    duplicates: int

    def to_npy(self, directory: str) -> list:
        """Writes the triangles as ``triangles-<block>.npy`` files, one block at a time."""
        os.makedirs(directory, exist_ok=True)
        paths = []
        for k, block in enumerate(self.triangles.to_delayed().ravel()):
            path = os.path.join(directory, f"triangles-{k:05d}.npy")
            np.save(path, np.asarray(block.compute()))
            paths.append(path)
        return paths

    def to_triangle_files(self, base: str) -> tuple:
        """Writes Triangle's ``base.node`` and ``base.ele`` (numbered from 1), streaming the
        blocks: the client holds one block at a time."""
        n, columns = self.points.shape
        node, ele = base + ".node", base + ".ele"
        with open(node, "w") as f:
            f.write(f"{n} 2 {columns - 2} 0\n")
            first = 1
            for block in self.points.to_delayed().ravel():
                rows = np.asarray(block.compute(), dtype=np.float64)
                numbers = np.arange(first, first + len(rows))
                np.savetxt(f, np.column_stack([numbers, rows]), fmt=["%d"] + ["%.17g"] * columns)
                first += len(rows)
        with open(ele, "w") as f:
            f.write(f"{self.triangles.shape[0]} 3 0\n")
            first = 1
            for block in self.triangles.to_delayed().ravel():
                rows = np.asarray(block.compute(), dtype=np.int64) + 1
                numbers = np.arange(first, first + len(rows))
                np.savetxt(f, np.column_stack([numbers, rows]), fmt="%d")
                first += len(rows)
        return node, ele


def from_npy_directory(directory: str) -> Any:
    """A dask array of the ``.npy`` chunks in ``directory`` (sorted by name; each (m, 2 + k)),
    read lazily on the workers."""
    import dask
    import dask.array as da

    paths = sorted(glob.glob(os.path.join(directory, "*.npy")))
    if not paths:
        raise ValueError(f"no .npy files in {directory}")
    blocks = []
    for path in paths:
        header = np.load(path, mmap_mode="r")
        blocks.append(da.from_delayed(dask.delayed(np.load)(path), shape=header.shape, dtype=header.dtype))
    return da.concatenate(blocks, axis=0)


def from_parquet(path: str, columns: Optional[Sequence[str]] = None) -> Any:
    """A dask array of Parquet files' columns (``x``, ``y`` and any attributes; all columns by
    default), through ``dask.dataframe`` (needs pyarrow)."""
    import dask.dataframe as dd

    frame = dd.read_parquet(path, columns=list(columns) if columns else None)
    return frame.to_dask_array(lengths=True).astype(np.float64)


def _as_dask_array(points: Any) -> Any:
    import dask.array as da

    if isinstance(points, (str, os.PathLike)):
        path = os.fspath(points)
        if os.path.isdir(path) and glob.glob(os.path.join(path, "*.npy")):
            points = from_npy_directory(path)
        else:
            points = from_parquet(path)
    elif not isinstance(points, da.Array):
        points = da.from_array(np.asarray(points, dtype=np.float64), chunks=(1 << 20, -1))
    if points.ndim != 2 or points.shape[1] < 2:
        raise TriangulateError(f"points must be an array (n, 2 + attributes), got shape {points.shape}", 1)
    if points.chunks[1] != (points.shape[1],):
        points = points.rechunk({1: -1})
    return points


def delaunay(
    points: Any,
    client: Any = None,
    *,
    tiles: Optional[int] = None,
    points_per_tile: int = 1 << 20,
    memory_per_worker: Optional[int] = None,
    max_rounds: int = 64,
    after_round: Optional[Callable[[int], None]] = None,
    show_progress: bool = False,
) -> DistributedTriangulation:
    """The Delaunay triangulation of ``points`` on a Dask cluster: the same triangle set as one
    ``triangulate("Q", ...)`` call on all of them (see the module documentation).

    ``points``: a dask array (n, 2 + attributes) (attributes are carried, not used), a numpy
    array, a directory of ``.npy`` chunks or a Parquet path. ``client``: a
    ``distributed.Client`` (the current one by default). ``tiles``: how many (about
    ``n / points_per_tile`` by default, at least one per worker). ``memory_per_worker``
    (bytes, e.g. the workers' ``memory_limit``): the tile count is then
    :func:`tiles_for_memory`'s, so that one tile's round fits (unless ``tiles`` is given).
    ``after_round(k)`` is called
    after each round (for progress, or tests). Raises :class:`TriangulateError` as the single
    call does (fewer than three points, a NaN or infinite coordinate).
    """
    import dask.array as da
    from distributed import default_client, progress, wait

    client = client or default_client()
    points = _as_dask_array(points)
    n = points.shape[0]
    blocks = points.to_delayed().ravel()
    offsets = np.concatenate([[0], np.cumsum(points.chunks[0])])[:-1]
    block_futures = client.compute(list(blocks))

    # Pass 1: per chunk, finiteness, bounds, extremes and a sample.
    sample_size = max(64, min(4096, 200_000 // max(1, len(blocks))))
    summaries = client.gather(
        [client.submit(_chunk_summary, b, k, sample_size, pure=True) for k, b in enumerate(block_futures)]
    )
    for k, s in enumerate(summaries):
        if s["first_bad"] is not None:
            raise TriangulateError(
                f"Vertex {offsets[k] + s['first_bad']} has a coordinate that is NaN or infinite.", 1
            )
    if n < 3:
        raise TriangulateError("Input must have at least three input vertices.", 1)
    filled = [s for s in summaries if s["count"]]
    bounds = np.array(
        [
            min(s["bounds"][0] for s in filled),
            min(s["bounds"][1] for s in filled),
            max(s["bounds"][2] for s in filled),
            max(s["bounds"][3] for s in filled),
        ]
    )
    scale = float(np.abs(bounds).max()) or 1.0
    index_dtype = np.int32 if n < 2**31 else np.int64
    lowest = min((tuple(s["lowest"]) for s in filled))
    highest = max((tuple(s["highest"]) for s in filled))
    a, b = np.array(lowest), np.array(highest)
    collinear = lowest == highest or not any(
        client.gather([client.submit(_off_line, f, a, b, pure=True) for f in block_futures])
    )
    if collinear:  # the single call gives no triangle either
        empty = da.zeros((0, 3), dtype=index_dtype)
        return DistributedTriangulation(points, empty, 0, 0, 0)

    # Tiles by the sample's quantiles; each tile's points gathered on one worker.
    workers = max(1, len(client.scheduler_info()["workers"]))
    if tiles:
        count = tiles
    elif memory_per_worker is not None:
        count = tiles_for_memory(n, int(memory_per_worker), workers)
    else:
        count = max(workers, -(-n // points_per_tile))
    columns = max(1, int(round(np.sqrt(count))))
    rows = max(1, -(-count // columns))
    tiling = _tiling_from_sample(np.concatenate([s["sample"] for s in filled]), columns, rows)
    split = [client.submit(_split_chunk, f, int(offsets[k]), tiling, pure=True) for k, f in enumerate(block_futures)]
    tile_futures = []
    for t in range(tiling.count):
        pieces = [client.submit(_piece, s, t, pure=True) for s in split]
        tile_futures.append(client.submit(_gather_tile, *pieces, pure=True))
    del split, block_futures
    stats = client.gather([client.submit(_tile_stats, f, pure=True) for f in tile_futures])
    rectangles = [tiling.rectangle(t, bounds) for t in range(tiling.count)]
    occupied = [t for t in range(tiling.count) if stats[t]["count"]]

    def intersecting(box: np.ndarray, exclude: int) -> list:
        return [
            u
            for u in occupied
            if u != exclude
            and stats[u]["bounds"][0] <= box[2]
            and stats[u]["bounds"][2] >= box[0]
            and stats[u]["bounds"][1] <= box[3]
            and stats[u]["bounds"][3] >= box[1]
        ]

    # The halo: the neighbours' points within a few mean spacings of the tile's rectangle.
    # Computed, not scattered: every future must be recomputable after a worker's death.
    nothing = client.submit(_nothing_imported, pure=True)
    imported = {t: nothing for t in occupied}
    halo = {}
    for t in occupied:
        r = rectangles[t]
        area = max((r[2] - r[0]) * (r[3] - r[1]), 0.0)
        halo[t] = _HALO_SPACINGS * np.sqrt(area / stats[t]["count"]) if area > 0 else 0.0

    def widen(t: int) -> None:
        r = rectangles[t]
        box = np.array([r[0] - halo[t], r[1] - halo[t], r[2] + halo[t], r[3] + halo[t]])
        answers = [client.submit(_in_rectangle, tile_futures[u], box, pure=True) for u in intersecting(box, t)]
        added = client.submit(_add, imported[t], *answers, pure=True)
        imported[t] = client.submit(_first, added, pure=True)

    for t in occupied:
        widen(t)

    # Rounds: only the tiles that received new points ask again (the others' triangulations,
    # and so their questions and the answers, are what they were: every tile's own points are
    # fixed). The first round asks every tile.
    rounds = 0
    unsettled = list(occupied)
    while unsettled:
        rounds += 1
        if rounds > max_rounds:
            raise TriangulateError(f"tile and merge did not settle in {max_rounds} rounds", 1)
        questions = [
            client.submit(_round, tile_futures[t], imported[t], rectangles[t], scale, pure=True) for t in unsettled
        ]
        if show_progress:
            progress(questions)
        asked = dict(zip(unsettled, client.gather(questions)))
        news = {}
        degenerate = []
        for t in unsettled:
            q = asked[t]
            if q["degenerate"]:
                halo[t] = max(2.0 * halo[t], (bounds[2] - bounds[0] + bounds[3] - bounds[1]) / 64)
                widen(t)
                degenerate.append(t)
                continue
            disks, edges = q["disks"], q["edges"]
            answers = []
            for u in occupied:
                if u == t:
                    continue
                ub = stats[u]["bounds"]
                near = (
                    (disks[:, 0] + disks[:, 2] >= ub[0])
                    & (disks[:, 0] - disks[:, 2] <= ub[2])
                    & (disks[:, 1] + disks[:, 2] >= ub[1])
                    & (disks[:, 1] - disks[:, 2] <= ub[3])
                )
                facing = _edges_facing(edges, ub, scale)
                if near.any() or facing.any():
                    answers.append(
                        client.submit(_answer, tile_futures[u], disks[near], edges[facing], scale, pure=True)
                    )
            if answers:
                added = client.submit(_add, imported[t], *answers, pure=True)
                imported[t] = client.submit(_first, added, pure=True)
                news[t] = client.submit(_second, added, pure=True)
        counts = dict(zip(news, client.gather(list(news.values()))))
        unsettled = degenerate + [t for t, c in counts.items() if c > 0]
        if after_round is not None:
            after_round(rounds)

    owned = [client.submit(_owned_triangles, tile_futures[t], imported[t], index_dtype, pure=True) for t in occupied]
    wait(owned)
    sizes = client.gather([client.submit(len, f, pure=True) for f in owned])
    duplicates = sum(client.gather([client.submit(_duplicates, tile_futures[t], pure=True) for t in occupied]))
    if duplicates:
        warnings.warn(f"{duplicates} duplicate vertices were ignored (each keeps its first copy).", RuntimeWarning, stacklevel=2)
    triangles = da.concatenate(
        [da.from_delayed(f, shape=(size, 3), dtype=index_dtype) for f, size in zip(owned, sizes)], axis=0
    )
    return DistributedTriangulation(points, triangles, rounds, len(occupied), duplicates)
