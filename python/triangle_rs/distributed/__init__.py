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

The package: :mod:`.tiling` (tiles and the memory planner), :mod:`.grid` (a tile's points by
cell, for the disk questions), :mod:`.tasks` (what the workers run) and, here, the driver on
the client and the readers and writers.
"""

from __future__ import annotations

import glob
import os
from dataclasses import dataclass
from typing import Any, Callable, Optional, Sequence

import numpy as np

from ..core import TriangulateError
from . import tasks
from .tiling import _BYTES_PER_TILE_POINT, _WORKER_BASELINE_BYTES  # noqa: F401 (the planner's constants, for tests)
from .tiling import room_per_worker, tiles_for_memory, tiling_from_sample

__all__ = ["DistributedTriangulation", "delaunay", "from_npy_directory", "from_parquet", "tiles_for_memory"]

# Halo width in mean point spacings of the tile: wide enough that, on uniform points, nearly
# every circumdisk at the tile's border is covered by round one, so few tiles ask again (3
# spacings took four rounds on 10^6 points in 9 tiles).
_HALO_SPACINGS = 8.0
# Input chunks are cut to this share of a worker's room when a memory limit is given:
# splitting a chunk into tiles costs ~64 bytes per point of it (coordinates, tile numbers,
# their order, the pieces).
_CHUNK_SHARE_OF_ROOM = 0.25
_SPLIT_BYTES_PER_POINT = 64


# --- The driver on the client ----------------------------------------------------------------


@dataclass
class DistributedTriangulation:
    """The result: ``points`` (the input, a dask array (n, 2 + attributes)) and ``triangles``
    (a dask array (m, 3) of global 0-based vertex indices, counter-clockwise, one block per
    tile, held on the workers). ``duplicates`` counts the input points ignored as copies of
    earlier ones (each keeps its first copy): as in the single call, they are no warning."""

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


def _as_dask_array(points: Any, chunk_rows: Optional[int]) -> Any:
    """``points`` as a dask array (n, 2 + attributes) with the columns in one chunk, its row
    chunks cut to ``chunk_rows`` when given."""
    import dask.array as da

    if isinstance(points, (str, os.PathLike)):
        path = os.fspath(points)
        if os.path.isdir(path) and glob.glob(os.path.join(path, "*.npy")):
            points = from_npy_directory(path)
        else:
            points = from_parquet(path)
    elif not isinstance(points, da.Array):
        points = da.from_array(np.asarray(points, dtype=np.float64), chunks=(chunk_rows or 1 << 20, -1))
    if points.ndim != 2 or points.shape[1] < 2:
        raise TriangulateError(f"points must be an array (n, 2 + attributes), got shape {points.shape}", 1)
    if points.chunks[1] != (points.shape[1],):
        points = points.rechunk({1: -1})
    if chunk_rows and max(points.chunks[0], default=0) > chunk_rows:
        points = points.rechunk({0: chunk_rows})
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
    :func:`tiles_for_memory`'s, so that one tile's round fits (unless ``tiles`` is given), and
    the input's chunks are cut small enough to be split within it. ``after_round(k)`` is called
    after each round (for progress, or tests). Raises :class:`TriangulateError` as the single
    call does (fewer than three points, a NaN or infinite coordinate).
    """
    import dask.array as da
    from distributed import default_client, progress

    client = client or default_client()
    workers = max(1, len(client.scheduler_info()["workers"]))
    chunk_rows = None
    if memory_per_worker is not None:
        room = room_per_worker(int(memory_per_worker))
        chunk_rows = max(1 << 14, int(room * _CHUNK_SHARE_OF_ROOM / _SPLIT_BYTES_PER_POINT))
    points = _as_dask_array(points, chunk_rows)
    n = points.shape[0]
    blocks = points.to_delayed().ravel()
    offsets = np.concatenate([[0], np.cumsum(points.chunks[0])])[:-1]
    block_futures = client.compute(list(blocks))

    # Pass 1: per chunk, finiteness, bounds, extremes and a sample.
    sample_size = max(64, min(4096, 200_000 // max(1, len(blocks))))
    summaries = client.gather(
        [client.submit(tasks.chunk_summary, b, k, sample_size, pure=True) for k, b in enumerate(block_futures)]
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
    # The tasks' floating-point geometry is on the coordinates divided by this power of two.
    unit = float(2.0 ** np.frexp(float(np.abs(bounds).max()) or 1.0)[1])
    index_dtype = np.dtype(np.int32 if n < 2**31 else np.int64)
    lowest = min((tuple(s["lowest"]) for s in filled))
    highest = max((tuple(s["highest"]) for s in filled))
    a, b = np.array(lowest), np.array(highest)
    collinear = lowest == highest or not any(
        client.gather([client.submit(tasks.off_line, f, a, b, pure=True) for f in block_futures])
    )
    if collinear:  # the single call gives no triangle either
        empty = da.zeros((0, 3), dtype=index_dtype)
        return DistributedTriangulation(points, empty, 0, 0, 0)

    # Tiles by the sample's quantiles; each tile's points gathered on one worker.
    if tiles:
        count = tiles
    elif memory_per_worker is not None:
        count = tiles_for_memory(n, int(memory_per_worker), workers)
    else:
        count = max(workers, -(-n // points_per_tile))
    tiling = tiling_from_sample(np.concatenate([s["sample"] for s in filled]), count)
    split = [
        client.submit(tasks.split_chunk, f, int(offsets[k]), tiling, index_dtype, pure=True)
        for k, f in enumerate(block_futures)
    ]
    tile_futures = []
    for t in range(tiling.count):
        pieces = [client.submit(tasks.piece, s, t, pure=True) for s in split]
        tile_futures.append(client.submit(tasks.gather_tile, index_dtype, unit, *pieces, pure=True))
    del split, block_futures
    stats = client.gather([client.submit(tasks.tile_stats, f, pure=True) for f in tile_futures])
    rectangles = [tiling.rectangle(t, bounds) for t in range(tiling.count)]
    occupied = np.array([t for t in range(tiling.count) if stats[t]["count"]])
    occupied_bounds = np.array([stats[t]["bounds"] for t in occupied])
    occupied_bounds_in_units = occupied_bounds / unit

    def meeting(box: np.ndarray, exclude: int) -> list:
        """The occupied tiles but ``exclude`` whose points' bounds meet ``box``."""
        meets = (
            (occupied_bounds[:, 0] <= box[2])
            & (occupied_bounds[:, 2] >= box[0])
            & (occupied_bounds[:, 1] <= box[3])
            & (occupied_bounds[:, 3] >= box[1])
            & (occupied != exclude)
        )
        return [int(u) for u in occupied[meets]]

    # The halo: the neighbours' points within a few mean spacings of the tile's rectangle.
    # Computed, not scattered: every future must be recomputable after a worker's death.
    nothing = client.submit(tasks.nothing_imported, index_dtype, pure=True)
    imported = {int(t): nothing for t in occupied}
    halo = {}
    for t in imported:
        r = rectangles[t] / unit  # in units: the area neither overflows nor vanishes
        area = max((r[2] - r[0]) * (r[3] - r[1]), 0.0)
        halo[t] = _HALO_SPACINGS * np.sqrt(area / stats[t]["count"]) * unit if area > 0 else 0.0

    def widen(t: int) -> None:
        r = rectangles[t]
        box = np.array([r[0] - halo[t], r[1] - halo[t], r[2] + halo[t], r[3] + halo[t]])
        answers = [client.submit(tasks.in_rectangle, tile_futures[u], box, pure=True) for u in meeting(box, t)]
        added = client.submit(tasks.add, imported[t], *answers, pure=True)
        imported[t] = client.submit(tasks.first, added, pure=True)

    for t in imported:
        widen(t)

    # Rounds: only the tiles that received new points ask again (the others' triangulations,
    # and so their questions, answers and owned triangles, are what they were: every tile's own
    # points are fixed). The first round asks every tile.
    rounds = 0
    owned: dict = {}
    duplicates_of: dict = {}
    unsettled = list(imported)
    while unsettled:
        rounds += 1
        if rounds > max_rounds:
            raise TriangulateError(f"tile and merge did not settle in {max_rounds} rounds", 1)
        questions = []
        for t in unsettled:
            result = client.submit(
                tasks.tile_round, tile_futures[t], imported[t], rectangles[t] / unit, unit, pure=True
            )
            questions.append(client.submit(tasks.first, result, pure=True))
            owned[t] = client.submit(tasks.second, result, pure=True)
        if show_progress:
            progress(questions)
        asked = dict(zip(unsettled, client.gather(questions)))
        del questions
        news = {}
        degenerate = []
        for t in unsettled:
            q = asked[t]
            duplicates_of[t] = q["duplicates"]
            if q["degenerate"]:
                halo[t] = max(2.0 * halo[t], (bounds[2] - bounds[0] + bounds[3] - bounds[1]) / 64)
                widen(t)
                degenerate.append(t)
                continue
            answers = _ask_neighbours(client, t, q, tile_futures, meeting, occupied, occupied_bounds_in_units, unit)
            if answers:
                added = client.submit(tasks.add, imported[t], *answers, pure=True)
                imported[t] = client.submit(tasks.first, added, pure=True)
                news[t] = client.submit(tasks.second, added, pure=True)
        counts = dict(zip(news, client.gather(list(news.values()))))
        unsettled = degenerate + [t for t, c in counts.items() if c > 0]
        if after_round is not None:
            after_round(rounds)

    final = [owned[t] for t in imported]
    sizes = client.gather([client.submit(len, f, pure=True) for f in final])
    # Counted in the result, not warned of: the single call ignores duplicates silently too.
    duplicates = sum(duplicates_of.values())
    triangles = da.concatenate(
        [da.from_delayed(f, shape=(size, 3), dtype=index_dtype) for f, size in zip(final, sizes)], axis=0
    )
    return DistributedTriangulation(points, triangles, rounds, len(occupied), duplicates)


def _ask_neighbours(
    client: Any,
    t: int,
    questions: dict,
    tile_futures: list,
    meeting: Callable[[np.ndarray, int], list],
    occupied: np.ndarray,
    bounds_in_units: np.ndarray,
    unit: float,
) -> list:
    """The answer futures of the tiles that tile ``t``'s disks meet or its hull edges face,
    each asked only what concerns its points' bounds (questions and bounds in units)."""
    disks, edges = questions["disks"], questions["edges"]
    candidates = set()
    if len(disks):
        box = np.array([
            (disks[:, 0] - disks[:, 2]).min(), (disks[:, 1] - disks[:, 2]).min(),
            (disks[:, 0] + disks[:, 2]).max(), (disks[:, 1] + disks[:, 2]).max(),
        ])
        candidates.update(meeting(box * unit, t))
    if len(edges):  # a hull edge's outside is a half-plane: any tile may face it
        candidates.update(int(u) for u in occupied if u != t)
    answers = []
    for u in sorted(candidates):
        ub = bounds_in_units[int(np.searchsorted(occupied, u))]
        near = (
            (disks[:, 0] + disks[:, 2] >= ub[0])
            & (disks[:, 0] - disks[:, 2] <= ub[2])
            & (disks[:, 1] + disks[:, 2] >= ub[1])
            & (disks[:, 1] - disks[:, 2] <= ub[3])
        )
        facing = tasks.edges_facing(edges, ub)
        if near.any() or facing.any():
            answers.append(client.submit(tasks.answer, tile_futures[u], disks[near], edges[facing], unit, pure=True))
    return answers
