"""The PyPI ``triangle`` package's plots: ``plot(ax, **d)``, ``compare(plt, A, B)`` and
``comparev(plt, A, B)`` for its dictionaries (input, output, ``get_data`` examples, Voronoi).

Nothing here imports matplotlib: the caller hands in the axes or ``pyplot``, so
``from triangle_rs import *`` stays free of it.

``plot`` draws, for the keys present: vertices (black dots, optionally numbered with
``labels=True`` or labelled by marker with ``markers=True``), segments (thick red), triangles
(black edges with the corners marked), holes (red x), edges and Voronoi rays (thin black; rays are
drawn long and the view kept to what was there before them), regions (blue stars with their
attribute) and triangle attributes (magenta centroids with their value). The axes get an equal
aspect and no tick labels.
"""

from __future__ import annotations

from typing import Any, Mapping

import numpy as np

#: How far a Voronoi ray is drawn, in units of its direction vector: far enough to leave any view.
_RAY_LENGTH = 100.0


def _line_collection(ax: Any, lines: np.ndarray, **style: Any) -> None:
    # The class comes from matplotlib, which the caller has imported already (it made `ax`).
    from matplotlib.collections import LineCollection

    ax.add_collection(LineCollection(lines, **style))
    ax.autoscale_view()


def _vertices(ax: Any, d: Mapping[str, Any]) -> np.ndarray:
    vertices = np.asarray(d["vertices"], dtype=np.float64).reshape(-1, 2)
    ax.scatter(vertices[:, 0], vertices[:, 1], color="k")
    if "labels" in d:
        for index, (x, y) in enumerate(vertices):
            ax.text(x, y, str(index))
    if "markers" in d:
        for (x, y), marker in zip(vertices, np.asarray(d["vertex_markers"]).reshape(len(vertices), -1)):
            ax.text(x, y, str(marker))
    return vertices


def _segments(ax: Any, vertices: np.ndarray, segments: Any) -> None:
    ends = vertices[np.asarray(segments, dtype=np.intp).reshape(-1, 2)]
    _line_collection(ax, ends, colors="r", linewidths=3, zorder=0)


def _triangles(ax: Any, vertices: np.ndarray, triangles: Any) -> None:
    corners = np.asarray(triangles, dtype=np.intp)
    ax.triplot(vertices[:, 0], vertices[:, 1], corners[:, :3], "ko-")


def _holes(ax: Any, holes: Any) -> None:
    points = np.asarray(holes, dtype=np.float64).reshape(-1, 2)
    ax.scatter(points[:, 0], points[:, 1], marker="x", color="r")


def _edges(ax: Any, vertices: np.ndarray, d: Mapping[str, Any]) -> None:
    edges = np.asarray(d["edges"], dtype=np.intp).reshape(-1, 2)
    if len(edges):
        _line_collection(ax, vertices[edges], colors="k", linewidths=0.5)
    if "ray_origins" not in d or "ray_directions" not in d:
        return
    view = ax.axis()
    origins = vertices[np.asarray(d["ray_origins"], dtype=np.intp).ravel()]
    directions = np.asarray(d["ray_directions"], dtype=np.float64).reshape(-1, 2)
    if len(origins):
        rays = np.stack([origins, origins + _RAY_LENGTH * directions], axis=1)
        _line_collection(ax, rays, colors="k", linewidths=0.5)
    ax.axis(view)  # the rays run far out: keep the view of the finite part


def _regions(ax: Any, regions: Any) -> None:
    rows = np.asarray(regions, dtype=np.float64).reshape(-1, 4)
    ax.scatter(rows[:, 0], rows[:, 1], marker="*", color="b")
    for x, y, attribute, _area in rows:
        ax.text(x, y, f" {attribute:g}", color="b", va="center")


def _triangle_attributes(ax: Any, vertices: np.ndarray, d: Mapping[str, Any]) -> None:
    triangles = np.asarray(d["triangles"], dtype=np.intp)[:, :3]
    values = np.asarray(d["triangle_attributes"], dtype=np.float64).reshape(len(triangles), -1)[:, 0]
    centroids = vertices[triangles].mean(axis=1)
    ax.scatter(centroids[:, 0], centroids[:, 1], marker=".", color="m", zorder=1)
    for (x, y), value in zip(centroids, values):
        ax.text(x, y, f" {value:g}", color="m", zorder=1, va="center")


def plot(ax: Any, **kw: Any) -> None:
    """Draws the triangulation dictionary ``kw`` (the PyPI package's keys) into the axes ``ax``."""
    ax.set_aspect("equal")
    vertices = _vertices(ax, kw)
    if "segments" in kw:
        _segments(ax, vertices, kw["segments"])
    if "triangles" in kw:
        _triangles(ax, vertices, kw["triangles"])
    if "holes" in kw:
        _holes(ax, kw["holes"])
    if "edges" in kw:
        _edges(ax, vertices, kw)
    if "regions" in kw:
        _regions(ax, kw["regions"])
    if "triangle_attributes" in kw:
        _triangle_attributes(ax, vertices, kw)
    ax.get_xaxis().set_visible(False)
    ax.get_yaxis().set_visible(False)


def _side_by_side(plt: Any, first: Mapping[str, Any], second: Mapping[str, Any], figsize: Any, layout: tuple[int, int], shared: str) -> None:
    plt.figure(figsize=figsize)
    rows, columns = layout
    first_axes = plt.subplot(rows, columns, 1)
    plot(first_axes, **first)
    view = first_axes.axis()
    second_axes = plt.subplot(rows, columns, 2, **{shared: first_axes})
    plot(second_axes, **second)
    second_axes.axis(view)
    plt.tight_layout()


def compare(plt: Any, A: Mapping[str, Any], B: Mapping[str, Any], figsize: Any = (6, 3)) -> None:
    """A new ``pyplot`` figure with ``A`` left and ``B`` right, both in ``A``'s view."""
    _side_by_side(plt, A, B, figsize, (1, 2), "sharey")


def comparev(plt: Any, A: Mapping[str, Any], B: Mapping[str, Any], figsize: Any = (3, 6)) -> None:
    """A new ``pyplot`` figure with ``A`` above and ``B`` below, both in ``A``'s view."""
    _side_by_side(plt, A, B, figsize, (2, 1), "sharex")
