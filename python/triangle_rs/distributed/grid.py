"""A tile's points bucketed in a uniform grid, for the neighbours' circumdisk questions.

The points are kept sorted by cell (row-major), with the start of every cell: the cells of one
grid row that a disk's bounding box covers are then one contiguous range of points, so a batch
of disks is answered by numpy alone (ranges expanded, distances tested), with no per-disk
Python loop and no tree (a k-d tree of scipy cost ~20 MB of every worker's baseline and ~24
bytes per point more).
"""

from __future__ import annotations

import numpy as np

# Points per cell on average: small enough that a disk's candidates are mostly inside it.
_POINTS_PER_CELL = 2.0
# Candidate (point, disk) pairs expanded at once: bounds the answer's temporaries (~40 bytes
# per pair).
_PAIRS_PER_BATCH = 1 << 21


def grid_order(xy: np.ndarray) -> tuple:
    """``(order, grid)``: the permutation that sorts ``xy`` by cell, and the grid as one float
    array ``[x0, y0, h, columns, rows]`` with the cells' starts (``columns * rows + 1``,
    int64)."""
    if len(xy) == 0:
        return np.empty(0, np.int64), (np.array([0.0, 0.0, 1.0, 1.0, 1.0]), np.zeros(2, np.int64))
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    extent = np.maximum(hi - lo, 0.0)
    cells = max(1.0, len(xy) / _POINTS_PER_CELL)
    if extent[0] > 0 and extent[1] > 0:
        h = float(np.sqrt(extent[0] * extent[1] / cells))
    else:
        h = float(max(extent.max(), 1.0) / cells)
    # No more cells along a side than points, so that a stretched tile stays within ~n cells.
    h = max(h, float(extent.max()) / max(1.0, cells), np.finfo(float).tiny)
    columns = int(min(extent[0] / h, cells)) + 1
    rows = int(min(extent[1] / h, cells)) + 1
    cell = _cell_of(xy, lo, h, columns, rows)
    order = np.argsort(cell, kind="stable")
    starts = np.searchsorted(cell[order], np.arange(columns * rows + 1))
    return order, (np.array([lo[0], lo[1], h, columns, rows]), starts.astype(np.int64))


def _cell_of(xy: np.ndarray, lo: np.ndarray, h: float, columns: int, rows: int) -> np.ndarray:
    ix = np.clip(((xy[:, 0] - lo[0]) / h).astype(np.int64), 0, columns - 1)
    iy = np.clip(((xy[:, 1] - lo[1]) / h).astype(np.int64), 0, rows - 1)
    return iy * columns + ix


def points_in_disks(xy: np.ndarray, grid: tuple, disks: np.ndarray) -> np.ndarray:
    """The indices (into ``xy``, sorted by cell as :func:`grid_order` left it) of the points in
    some closed disk ``(cx, cy, r)``; a disk of infinite radius holds every point. Unsorted,
    with repetitions."""
    params, starts = grid
    x0, y0, h = params[0], params[1], params[2]
    columns, rows = int(params[3]), int(params[4])
    if len(xy) and len(disks) and not np.isfinite(disks[:, 2]).all():
        return np.arange(len(xy))
    if len(xy) == 0 or len(disks) == 0:
        return np.empty(0, np.int64)
    cx, cy, r = disks[:, 0], disks[:, 1], disks[:, 2]
    # Cell ranges of the disks' boxes, clipped to the grid (a box beyond it covers no cell).
    ix0 = np.floor((cx - r - x0) / h)
    ix1 = np.floor((cx + r - x0) / h)
    iy0 = np.floor((cy - r - y0) / h)
    iy1 = np.floor((cy + r - y0) / h)
    meets = (ix1 >= 0) & (ix0 <= columns - 1) & (iy1 >= 0) & (iy0 <= rows - 1)
    disks, ix0, ix1, iy0, iy1 = disks[meets], ix0[meets], ix1[meets], iy0[meets], iy1[meets]
    ix0 = np.clip(ix0, 0, columns - 1).astype(np.int64)
    ix1 = np.clip(ix1, 0, columns - 1).astype(np.int64)
    iy0 = np.clip(iy0, 0, rows - 1).astype(np.int64)
    iy1 = np.clip(iy1, 0, rows - 1).astype(np.int64)
    # One (disk, grid row) pair per row a disk's box covers: a contiguous range of points.
    spans = iy1 - iy0 + 1
    disk_of_span = np.repeat(np.arange(len(disks)), spans)
    row = iy0[disk_of_span] + (np.arange(len(disk_of_span)) - np.repeat(np.cumsum(spans) - spans, spans))
    first = starts[row * columns + ix0[disk_of_span]]
    last = starts[row * columns + ix1[disk_of_span] + 1]
    lengths = last - first
    found = []
    ends = np.cumsum(lengths)
    begin = 0
    while begin < len(lengths):
        # A batch of spans holding at most _PAIRS_PER_BATCH candidates (at least one span).
        stop = int(np.searchsorted(ends, (ends[begin - 1] if begin else 0) + _PAIRS_PER_BATCH, side="right"))
        stop = max(stop, begin + 1)
        found.append(_test_spans(xy, disks, disk_of_span[begin:stop], first[begin:stop], lengths[begin:stop]))
        begin = stop
    return np.concatenate(found) if found else np.empty(0, np.int64)


def _test_spans(xy: np.ndarray, disks: np.ndarray, disk: np.ndarray, first: np.ndarray, lengths: np.ndarray) -> np.ndarray:
    total = int(lengths.sum())
    if total == 0:
        return np.empty(0, np.int64)
    offsets = np.cumsum(lengths) - lengths
    point = np.repeat(first - offsets, lengths) + np.arange(total)
    which = np.repeat(disk, lengths)
    d = xy[point] - disks[which, :2]
    inside = (d * d).sum(axis=1) <= disks[which, 2] ** 2
    return point[inside]
