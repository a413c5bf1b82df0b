"""Shared checks: geometric validity of triangulations (results are compared as sets: triangle-rs
does not reproduce Triangle's element order)."""

from __future__ import annotations

from typing import Iterable

import numpy as np


def signed_areas(points: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    a, b, c = (points[triangles[:, i]] for i in range(3))
    return 0.5 * ((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))


def canonical_triangles(triangles: Iterable[Iterable[int]]) -> set[tuple[int, int, int]]:
    """Triangles as a set, each rotated to start at its smallest index (orientation kept)."""
    result = set()
    for t in triangles:
        t = [int(v) for v in t][:3]
        k = t.index(min(t))
        result.add(tuple(t[k:] + t[:k]))
    return result


def undirected(edges: Iterable[Iterable[int]]) -> set[frozenset[int]]:
    return {frozenset(int(v) for v in e) for e in edges}


def triangle_edges(triangles: np.ndarray) -> set[frozenset[int]]:
    return undirected(np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]]))


def convex_hull_area(points: np.ndarray) -> float:
    """Area of the convex hull (Andrew's monotone chain), independent of the library."""
    pts = sorted(map(tuple, np.asarray(points, dtype=float)))

    def half(sequence):
        chain = []
        for p in sequence:
            while len(chain) >= 2 and (
                (chain[-1][0] - chain[-2][0]) * (p[1] - chain[-2][1])
                - (chain[-1][1] - chain[-2][1]) * (p[0] - chain[-2][0])
            ) <= 0:
                chain.pop()
            chain.append(p)
        return chain

    hull = half(pts)[:-1] + half(reversed(pts))[:-1]
    x = np.array([p[0] for p in hull])
    y = np.array([p[1] for p in hull])
    return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1)))


def assert_delaunay_of_points(points: np.ndarray, triangles: np.ndarray) -> None:
    """``triangles`` triangulate the convex hull of ``points``: counter-clockwise, non-degenerate,
    covering the hull's area exactly, and with empty circumcircles (Delaunay)."""
    points = np.asarray(points, dtype=float)
    areas = signed_areas(points, triangles)
    assert np.all(areas > 0), "every triangle must be counter-clockwise and non-degenerate"
    assert np.isclose(areas.sum(), convex_hull_area(points), rtol=1e-9)
    assert_empty_circumcircles(points, triangles)


def assert_empty_circumcircles(points: np.ndarray, triangles: np.ndarray, tolerance: float = 1e-9) -> None:
    a, b, c = (points[triangles[:, i]] for i in range(3))
    for k in range(len(triangles)):
        # In-circle determinant of every point against triangle k (positive = strictly inside).
        rows = np.stack([a[k], b[k], c[k]]) - points[:, None, :]
        lifted = (rows**2).sum(axis=2)
        det = (
            rows[:, 0, 0] * (rows[:, 1, 1] * lifted[:, 2] - lifted[:, 1] * rows[:, 2, 1])
            - rows[:, 0, 1] * (rows[:, 1, 0] * lifted[:, 2] - lifted[:, 1] * rows[:, 2, 0])
            + lifted[:, 0] * (rows[:, 1, 0] * rows[:, 2, 1] - rows[:, 1, 1] * rows[:, 2, 0])
        )
        scale = np.abs(rows).max() ** 4 + 1e-300
        assert np.all(det <= tolerance * scale), f"a point lies inside the circumcircle of triangle {k}"


def random_points(seed: int, n: int) -> np.ndarray:
    return np.random.default_rng(seed).random((n, 2))
