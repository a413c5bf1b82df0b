"""The tasks that run on the workers: pure functions of their arguments, so that Dask can
recompute any of them on another worker when one dies.

A tile is a tuple ``(index, xy, grid, hull)``: its points' global indices (int32 below 2^31
points) and coordinates, sorted by grid cell, the grid (:mod:`.grid`) that answers the
neighbours' disk questions, and the positions of its points' convex hull vertices (for the
hull-edge questions). Imported points are ``(index, xy)``.

The geometry that decides which points to send (circumdisks, hull-edge sides, the grid) is
floating point on the coordinates divided by ``unit``, the power of two at or above the
points' largest magnitude: exact (barring underflow far below the margins), and no product of
coordinates overflows at 10^300 or vanishes at 10^-300. Questions travel in those units. The
triangulations themselves are the library's, on the coordinates as given.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from ..core import run
from ..triangulateio import TriangulateIO
from .grid import grid_order, points_in_disks
from .tiling import Tiling

# Circumdisks are asked for this much larger, relative to the radius, past the bound on their
# rounding error (see _circumdisks); and hull-edge lines are thickened by this much.
RELATIVE_MARGIN = 1e-9
# The absolute margin in units (coordinates at most 1 there): 2^-40, far above the rounding of
# a centre's coordinates (2^-53).
_ABSOLUTE_MARGIN = 2.0**-40
_EPS = 2.0**-53
# Shewchuk's error bound of the floating-point orientation, (3 + 16ε)ε.
_ORIENT_BOUND = (3.0 + 16.0 * 2.0**-53) * 2.0**-53
# Circumdisks computed at once in a round: bounds its temporaries (~150 bytes per triangle).
_TRIANGLES_PER_BATCH = 1 << 17


def chunk_summary(block: np.ndarray, seed: int, sample_size: int) -> dict:
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


def off_line(block: np.ndarray, a: np.ndarray, b: np.ndarray) -> bool:
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


def split_chunk(block: np.ndarray, offset: int, tiling: Tiling, index_dtype: Any) -> list:
    """The chunk's points per tile: ``(global indices, coordinates)``."""
    xy = np.asarray(block[:, :2], dtype=np.float64)
    tile = tiling.tile_of(xy)
    order = np.argsort(tile, kind="stable")
    starts = np.searchsorted(tile[order], np.arange(tiling.count + 1))
    pieces = []
    for t in range(tiling.count):
        take = order[starts[t] : starts[t + 1]]
        pieces.append(((take + offset).astype(index_dtype), xy[take]))
    return pieces


def piece(pieces: list, tile: int) -> tuple:
    return pieces[tile]


def gather_tile(index_dtype: Any, unit: float, *pieces) -> tuple:
    """A tile's own points from the chunks' pieces, sorted by grid cell (in units)."""
    index = np.concatenate([p[0] for p in pieces]) if pieces else np.empty(0, index_dtype)
    xy = np.concatenate([p[1] for p in pieces]) if pieces else np.empty((0, 2))
    order, grid = grid_order(xy / unit)
    index, xy = index[order], xy[order]
    return index, xy, grid, _hull_positions(xy / unit)


def _hull_positions(xy: np.ndarray) -> np.ndarray:
    """The positions of the convex hull's vertices, in floating point (Andrew's monotone chain
    on the points outside the extremes' octagon, Akl and Toussaint 1978): a hint of which
    points to send beyond a hull edge, never a decision, so rounding may miss or add one."""
    if len(xy) < 3:
        return np.arange(len(xy))
    x, y = xy[:, 0], xy[:, 1]
    extremes = np.unique([f(v) for f in (np.argmin, np.argmax) for v in (x, y, x + y, x - y)])
    ring = xy[extremes]
    centre = ring.mean(axis=0)
    angle = np.arctan2(ring[:, 1] - centre[1], ring[:, 0] - centre[0])
    ring = ring[np.argsort(angle)]
    # A point strictly inside the octagon (left of all its edges, counter-clockwise) is no
    # hull vertex.
    outside = np.zeros(len(xy), dtype=bool)
    for k in range(len(ring)):
        a, b = ring[k], ring[(k + 1) % len(ring)]
        outside |= (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]) <= 0
    candidates = np.flatnonzero(outside)
    candidates = candidates[np.lexsort((y[candidates], x[candidates]))]
    hull: list = []
    for sweep in (candidates, candidates[::-1]):
        start = len(hull)
        for p in sweep.tolist():
            while len(hull) - start >= 2:
                o, a = hull[-2], hull[-1]
                if (x[a] - x[o]) * (y[p] - y[o]) - (y[a] - y[o]) * (x[p] - x[o]) > 0:
                    break
                hull.pop()
            hull.append(p)
        hull.pop()
    return np.unique(np.array(hull, dtype=np.int64))


def tile_stats(tile: tuple) -> dict:
    index, xy = tile[0], tile[1]
    if len(xy) == 0:
        return {"count": 0, "bounds": None}
    return {"count": len(xy), "bounds": np.array([*xy.min(axis=0), *xy.max(axis=0)])}


def in_rectangle(tile: tuple, rectangle: np.ndarray) -> tuple:
    """The tile's points in the closed rectangle ``[xlo, ylo, xhi, yhi]``."""
    index, xy = tile[0], tile[1]
    inside = (
        (xy[:, 0] >= rectangle[0]) & (xy[:, 0] <= rectangle[2]) & (xy[:, 1] >= rectangle[1]) & (xy[:, 1] <= rectangle[3])
    )
    return index[inside], xy[inside]


def nothing_imported(index_dtype: Any) -> tuple:
    return np.empty(0, index_dtype), np.empty((0, 2))


def first(pair: tuple) -> Any:
    return pair[0]


def second(pair: tuple) -> Any:
    return pair[1]


def _local_delaunay(xy: np.ndarray) -> Optional[tuple]:
    """Triangles and neighbours (int32, as the library gives them) of the library's Delaunay
    triangulation, or ``None`` when the points make none (fewer than three, or on a line)."""
    if len(xy) < 3:
        return None
    # Duplicates are counted by the round; the call warns of nothing (a Delaunay triangulation
    # has no bound to fall short of).
    out, _ = run("Qzn", TriangulateIO(pointlist=np.ascontiguousarray(xy)))
    triangles = np.asarray(out.trianglelist).reshape(-1, 3)
    if len(triangles) == 0:
        return None
    return triangles, np.asarray(out.neighborlist).reshape(-1, 3)


def _circumdisks(xy: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """``(cx, cy, r)`` per triangle (coordinates in units, at most 1), the radius enlarged past a
    bound on the rounding of the floating-point centre and radius (first-order, Higham's
    model, with a factor of 4 to spare), then by the margins. A triangle too flat for floating
    point to place its centre (the bound reaches the divisor) gets an infinite radius: every
    point is asked for, which is always enough."""
    a, b, c = xy[triangles[:, 0]], xy[triangles[:, 1]], xy[triangles[:, 2]]
    ba, ca = b - a, c - a
    p, q = ba[:, 0] * ca[:, 1], ba[:, 1] * ca[:, 0]
    d = 2.0 * (p - q)
    lb, lc = (ba**2).sum(axis=1), (ca**2).sum(axis=1)
    nx = ca[:, 1] * lb - ba[:, 1] * lc
    ny = ba[:, 0] * lc - ca[:, 0] * lb
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        ux, uy = nx / d, ny / d
        d_error = 16.0 * _EPS * (np.abs(p) + np.abs(q))
        reliable = d_error < 0.5 * np.abs(d)
        spread = np.abs(ux) + np.abs(uy)
        u_error = (
            8.0 * _EPS * (np.abs(ca[:, 1] * lb) + np.abs(ba[:, 1] * lc) + np.abs(ba[:, 0] * lc) + np.abs(ca[:, 0] * lb))
            + spread * d_error
        ) / (np.abs(d) - d_error)
        r = np.hypot(ux, uy)
        error = 2.0 * u_error + 4.0 * _EPS * (r + np.abs(a).sum(axis=1) + spread)
        r = r + 4.0 * error + RELATIVE_MARGIN * r + _ABSOLUTE_MARGIN
    centre = a + np.stack([ux, uy], axis=1)
    flat = ~(reliable & np.isfinite(r) & np.isfinite(centre).all(axis=1))
    r[flat] = np.inf
    centre[flat] = a[flat]
    return np.column_stack([centre, r])


def _reaching_out(disks: np.ndarray, rectangle: np.ndarray) -> np.ndarray:
    return (
        (disks[:, 0] - disks[:, 2] <= rectangle[0])
        | (disks[:, 0] + disks[:, 2] >= rectangle[2])
        | (disks[:, 1] - disks[:, 2] <= rectangle[1])
        | (disks[:, 1] + disks[:, 2] >= rectangle[3])
    )


def tile_round(tile: tuple, imported: tuple, rectangle: np.ndarray, unit: float) -> tuple:
    """One round of a tile: triangulates its points with what it imported, and returns
    ``(questions, owned)``.

    ``rectangle`` and the questions are in units (see the module documentation).
    ``questions`` for the neighbours: the circumdisks of the triangles around the tile's own
    vertices that reach out of its rectangle, and its hull edges at its own vertices (outward:
    the interior on their left); with how many own points duplicate another (each is left out
    of the triangulation, as by the single call). ``owned``: the triangles (global indices)
    whose smallest index is the tile's own — the tile's share of the result once no question
    brings a new point."""
    own_count = len(tile[0])
    index = np.concatenate([tile[0], imported[0]])
    # By increasing global index: duplicates keep their first copy, as in the single call, and
    # a triangle's smallest local index is its smallest global one.
    order = np.argsort(index, kind="stable")
    index = index[order]
    xy = np.concatenate([tile[1], imported[1]])[order]
    own = order < own_count
    del order
    mesh = _local_delaunay(xy)
    if mesh is None:
        questions = {"degenerate": True, "disks": np.empty((0, 3)), "edges": np.empty((0, 4)), "duplicates": 0}
        return questions, np.empty((0, 3), dtype=index.dtype)
    triangles, neighbours = mesh
    used = np.zeros(len(xy), dtype=bool)
    used[triangles.ravel()] = True
    duplicates = own_count - int(np.count_nonzero(used & own))
    del used
    owned = index[triangles[own[triangles.min(axis=1)]]]

    around_own = np.flatnonzero(own[triangles].any(axis=1))
    xy = xy / unit
    disks = []
    for begin in range(0, len(around_own), _TRIANGLES_PER_BATCH):
        batch = _circumdisks(xy, triangles[around_own[begin : begin + _TRIANGLES_PER_BATCH]])
        disks.append(batch[_reaching_out(batch, rectangle)])
    del around_own
    # Hull edges: neighbour k (opposite corner k) missing; the edge runs from corner k+1 to k+2.
    edges = []
    for k in range(3):
        hull = neighbours[:, k] < 0
        u, v = triangles[hull, (k + 1) % 3], triangles[hull, (k + 2) % 3]
        at_own = own[u] | own[v]
        edges.append(np.column_stack([xy[u[at_own]], xy[v[at_own]]]))
    questions = {
        "degenerate": False,
        "disks": np.concatenate(disks) if disks else np.empty((0, 3)),
        "edges": np.concatenate(edges),
        "duplicates": duplicates,
    }
    return questions, owned


def answer(tile: tuple, disks: np.ndarray, edges: np.ndarray, unit: float) -> tuple:
    """A neighbour's answer: its points in or near the disks, and for each hull edge the point
    beyond it whose circle through the edge's ends bulges least beyond it (the Delaunay apex
    there, among this tile's points), the points within the margin of the edge's line, and
    this tile's hull vertices beyond it (so that the asking tile's hull reaches the whole
    set's in one round, not one apex a round along it). Questions in units."""
    index, xy_as_given, grid, hull = tile
    xy = xy_as_given / unit
    found = [points_in_disks(xy, grid, disks)] if len(disks) else []
    if len(xy) and len(edges):
        for ax, ay, bx, by in edges:
            ex, ey = bx - ax, by - ay
            # Beyond (right of) the edge, or within the margin of its line.
            side = ex * (xy[:, 1] - ay) - ey * (xy[:, 0] - ax)
            length = np.hypot(ex, ey)
            near = np.abs(side) <= RELATIVE_MARGIN * length * (1.0 + length)
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
                found.append(hull[beyond[hull] & ~near[hull]])
            found.append(np.flatnonzero(near))
    if not found:
        return index[:0], xy_as_given[:0]
    take = np.unique(np.concatenate([np.asarray(f, dtype=np.int64) for f in found]))
    return index[take], xy_as_given[take]


def add(imported: tuple, *answers) -> tuple:
    """The imported points with the answers' new ones; and how many were new."""
    index = np.concatenate([imported[0], *[a[0] for a in answers]])
    xy = np.concatenate([imported[1], *[a[1] for a in answers]])
    index, first_copy = np.unique(index, return_index=True)
    return (index, xy[first_copy]), len(index) - len(imported[0])


def edges_facing(edges: np.ndarray, box: np.ndarray) -> np.ndarray:
    """Which hull edges (``ax, ay, bx, by``, interior on the left) have some corner of ``box``
    beyond them or within the margin of their line (both in units)."""
    if len(edges) == 0:
        return np.zeros(0, dtype=bool)
    ex, ey = edges[:, 2] - edges[:, 0], edges[:, 3] - edges[:, 1]
    length = np.hypot(ex, ey)
    facing = np.zeros(len(edges), dtype=bool)
    for x, y in ((box[0], box[1]), (box[2], box[1]), (box[0], box[3]), (box[2], box[3])):
        side = ex * (y - edges[:, 1]) - ey * (x - edges[:, 0])
        facing |= side <= RELATIVE_MARGIN * length * (1.0 + length)
    return facing
