"""Where the points go: quantile tiles, and how many tiles a worker's memory allows."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# What one point of a tile costs a worker while its round runs, in bytes (see
# :func:`tiles_for_memory`), measured on 10^5–10^6-point tiles (peak RSS of the round over the
# worker's RSS before it, per point of the tile with its halo): the merged copy with the halo
# and its order (~40); the engine (~85 per vertex); its outputs, two triangles per point with
# their neighbours as int32, in C and then in numpy (~96); the owned triangles (~24); the
# round's masks and the circumdisks of one batch (~20). Rounded up for the allocator.
_BYTES_PER_TILE_POINT = 300
# A Dask worker process's own resident memory before it holds any data (interpreter, dask,
# distributed, numpy and the library): measured 85–95 MB.
_WORKER_BASELINE_BYTES = 96 * 2**20
# The nanny kills a worker at 95% of its memory limit: plan below that.
_USABLE_FRACTION = 0.85


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
        tile = np.empty(len(xy), dtype=np.int32)
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


def tiling_from_sample(sample: np.ndarray, count: int) -> Tiling:
    """About ``count`` tiles (a near-square grid of columns and rows) with balanced counts of
    the sample's points."""
    columns = max(1, int(round(np.sqrt(count))))
    rows = max(1, -(-count // columns))
    xcuts = np.quantile(sample[:, 0], np.arange(1, columns) / columns) if columns > 1 else np.empty(0)
    column = np.searchsorted(xcuts, sample[:, 0], side="right")
    ycuts = np.empty((columns, rows - 1))
    for c in range(columns):
        ys = sample[column == c, 1]
        if len(ys) == 0:
            ys = sample[:, 1]
        ycuts[c] = np.quantile(ys, np.arange(1, rows) / rows) if rows > 1 else np.empty(0)
    return Tiling(np.asarray(xcuts, dtype=np.float64), ycuts)


def room_per_worker(memory_per_worker: int, baseline: int = _WORKER_BASELINE_BYTES) -> float:
    """The bytes a worker of ``memory_per_worker`` has for one task past its own baseline,
    planned against 85% of the limit (the nanny kills at 95%)."""
    return _USABLE_FRACTION * memory_per_worker - baseline


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
    own and, ``halo_fraction`` more, its halo) ``bytes_per_point`` for the merged points, the
    engine (~85 bytes per vertex), its outputs and the Python copies. Planned against 85% of the
    limit, since the nanny kills at 95%. At least ``workers`` tiles, so that every worker has
    work.

    The tiles a worker holds between rounds (20 bytes per point) and the results (~24 bytes
    per point) are Dask's managed data: past its ``spill`` threshold Dask writes them to disk, so
    they do not count here. Raises :class:`ValueError` when the limit does not even hold the
    baseline.
    """
    if n < 0 or workers < 1:
        raise ValueError(f"need n >= 0 and workers >= 1, got n={n}, workers={workers}")
    available = room_per_worker(memory_per_worker, baseline)
    if available <= bytes_per_point * 64:
        raise ValueError(
            f"memory_per_worker={memory_per_worker} bytes leaves no room past a worker's own "
            f"~{baseline} bytes (planned against {_USABLE_FRACTION:.0%} of the limit)"
        )
    points_per_tile = available / (bytes_per_point * (1.0 + halo_fraction))
    return max(workers, int(np.ceil(n / points_per_tile)))
