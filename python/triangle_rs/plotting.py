"""Plots of triangulations with matplotlib, as in the lecture notes (and Triangulate.jl up to v2.5):
``plot_triangulateio(ax, tio, voronoi=None, circumcircles=False)`` and
``plot_in_out(triin, triout, voronoi=None, circumcircles=False)``.

They draw the points; the triangles (filled by their first attribute, e.g. the region attribute of
``A``, on a pastel scale); the segments as thick lines coloured by marker; hole points (red x) and
region points (coloured by attribute) of an input; optionally the Voronoi diagram (green vertices,
edges and rays) and each triangle's circumcircle with its centre.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.collections import LineCollection, PatchCollection, PolyCollection
from matplotlib.colors import Normalize
from matplotlib.figure import Figure
from matplotlib.patches import Circle

from .triangulateio import TriangulateIO

_VORONOI_COLOR = "tab:green"
_CIRCLE_COLOR = "tab:purple"


def _pastel(values: np.ndarray, colormap: str = "viridis") -> np.ndarray:
    """Colours for ``values`` on ``colormap``, blended half-way to white."""
    values = np.asarray(values, dtype=float)
    low, high = (float(values.min()), float(values.max())) if values.size else (0.0, 1.0)
    norm = Normalize(low, high if high > low else low + 1.0)
    colors = colormaps[colormap](norm(values))
    colors[:, :3] = 0.5 * colors[:, :3] + 0.5
    return colors


def _marker_colors(markers: np.ndarray) -> np.ndarray:
    """One distinct colour per boundary marker value (tab10, cycling)."""
    palette = colormaps["tab10"]
    return np.array([palette(int(m) % 10) for m in markers])


def circumcircles_of(points: np.ndarray, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centres (m, 2) and radii (m,) of the circumcircles of ``triangles`` (first 3 corners).

    Uses coordinates relative to the first corner, which keeps the formula accurate for small
    triangles far from the origin."""
    a = points[triangles[:, 0]]
    b = points[triangles[:, 1]] - a
    c = points[triangles[:, 2]] - a
    b2 = (b**2).sum(axis=1)
    c2 = (c**2).sum(axis=1)
    d = 2.0 * (b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0])
    with np.errstate(divide="ignore", invalid="ignore"):
        ux = (c[:, 1] * b2 - b[:, 1] * c2) / d
        uy = (b[:, 0] * c2 - c[:, 0] * b2) / d
    centres = a + np.column_stack([ux, uy])
    radii = np.hypot(ux, uy)
    return centres, radii


def _view_box(tio: TriangulateIO) -> Optional[tuple[float, float, float, float]]:
    """The box the plot shows: the input geometry with a margin (circumcentres and Voronoi
    vertices can lie far away)."""
    parts = [tio.pointlist, tio.holelist, tio.regionlist[:, :2]]
    coordinates = np.vstack([p for p in parts if len(p)]) if any(len(p) for p in parts) else np.empty((0, 2))
    if not len(coordinates):
        return None
    low, high = coordinates.min(axis=0), coordinates.max(axis=0)
    margin = 0.1 * max(float((high - low).max()), 1e-12)
    return low[0] - margin, high[0] + margin, low[1] - margin, high[1] + margin


def plot_triangulateio(
    ax: Axes,
    tio: TriangulateIO,
    voronoi: Optional[TriangulateIO] = None,
    circumcircles: bool = False,
    *,
    title: Optional[str] = None,
) -> Axes:
    """Draws ``tio`` (input or output of a triangulation) into the matplotlib axes ``ax``.

    Args:
        ax: the axes to draw into.
        tio: points, triangles, segments, holes and regions to draw.
        voronoi: the ``vorout`` of the same call (switch ``v``): its vertices, finite edges and
            rays (clipped to the view) are drawn in green.
        circumcircles: also draw each triangle's circumcircle and centre.
        title: an optional axes title.

    Returns:
        ``ax``.
    """
    points = tio.pointlist
    triangles = tio.trianglelist[:, :3] if len(tio.trianglelist) else np.empty((0, 3), dtype=np.int32)
    box = _view_box(tio)

    if len(triangles):
        corners = points[triangles]
        if tio.numberoftriangleattributes:
            faces = PolyCollection(corners, facecolors=_pastel(tio.triangleattributelist[:, 0]), edgecolors="none")
            ax.add_collection(faces)
        edges = np.concatenate([corners[:, [0, 1]], corners[:, [1, 2]], corners[:, [2, 0]]])
        ax.add_collection(LineCollection(edges, colors="black", linewidths=0.6, zorder=2))
        if circumcircles:
            centres, radii = circumcircles_of(points, triangles)
            finite = np.isfinite(radii)
            circles = [Circle(tuple(c), r) for c, r in zip(centres[finite], radii[finite])]
            ax.add_collection(
                PatchCollection(circles, facecolors="none", edgecolors=_CIRCLE_COLOR, linewidths=0.5, alpha=0.6, zorder=1)
            )
            ax.scatter(centres[finite, 0], centres[finite, 1], s=6, color=_CIRCLE_COLOR, zorder=3)

    if len(tio.segmentlist):
        markers = tio.segmentmarkerlist if len(tio.segmentmarkerlist) == len(tio.segmentlist) else np.zeros(len(tio.segmentlist), dtype=int)
        ax.add_collection(
            LineCollection(points[tio.segmentlist], colors=_marker_colors(markers), linewidths=3, zorder=4)
        )

    if voronoi is not None and len(voronoi.pointlist):
        _plot_voronoi(ax, voronoi, box)

    if len(points):
        ax.scatter(points[:, 0], points[:, 1], s=12, color="black", zorder=5)

    if not len(triangles):
        # Input side: show where holes and regions are seeded.
        if len(tio.holelist):
            ax.scatter(tio.holelist[:, 0], tio.holelist[:, 1], marker="x", s=60, color="red", zorder=6)
        if len(tio.regionlist):
            ax.scatter(
                tio.regionlist[:, 0],
                tio.regionlist[:, 1],
                marker="o",
                s=60,
                c=_pastel(tio.regionlist[:, 2])[:, :3] * 0.8,
                edgecolors="black",
                zorder=6,
            )

    if box is not None:
        ax.set_xlim(box[0], box[1])
        ax.set_ylim(box[2], box[3])
    ax.set_aspect("equal")
    if title is not None:
        ax.set_title(title)
    return ax


def _plot_voronoi(ax: Axes, voronoi: TriangulateIO, box: Optional[tuple[float, float, float, float]]) -> None:
    vertices = voronoi.pointlist
    edges = voronoi.edgelist
    ax.scatter(vertices[:, 0], vertices[:, 1], s=14, color=_VORONOI_COLOR, zorder=4)
    if not len(edges):
        return
    finite = edges[:, 1] >= 0
    segments = [vertices[edges[finite]]]
    rays = ~finite
    if rays.any():
        directions = voronoi.normlist[rays] if len(voronoi.normlist) == len(edges) else np.zeros((rays.sum(), 2))
        origins = vertices[edges[rays, 0]]
        # Long enough to leave the view box from any origin inside or near it.
        if box is not None:
            span = max(box[1] - box[0], box[3] - box[2])
            far = np.abs(origins - [(box[0] + box[1]) / 2, (box[2] + box[3]) / 2]).max(initial=0.0)
            reach = 2.0 * (span + far)
        else:
            reach = 1.0
        lengths = np.hypot(directions[:, 0], directions[:, 1])
        lengths[lengths == 0] = 1.0
        ends = origins + directions / lengths[:, None] * reach
        segments.append(np.stack([origins, ends], axis=1))
    ax.add_collection(LineCollection(np.concatenate(segments), colors=_VORONOI_COLOR, linewidths=1.2, zorder=3))


def plot_in_out(
    triin: TriangulateIO,
    triout: TriangulateIO,
    voronoi: Optional[TriangulateIO] = None,
    circumcircles: bool = False,
    *,
    title: str = "",
    figure: Optional[Figure] = None,
    **figure_options: Any,
) -> Figure:
    """Two panels side by side: the input ("In") and the output ("Out", with the Voronoi diagram
    and circumcircles when asked for).

    Args:
        triin, triout: the input and the output of a triangulation.
        voronoi: the ``vorout`` of the call, drawn on the output panel.
        circumcircles: draw the output triangles' circumcircles.
        title: the figure title.
        figure: draw into this figure (it is cleared); otherwise a new one is made with
            ``figure_options`` (default size 10 x 5 inches).

    Returns:
        The figure; save it with ``fig.savefig("out.png")``.
    """
    if figure is None:
        from matplotlib.figure import Figure as _Figure

        figure_options.setdefault("figsize", (10, 5))
        figure = _Figure(**figure_options)
    else:
        figure.clear()
    axes_in, axes_out = figure.subplots(1, 2, sharex=True, sharey=True)
    plot_triangulateio(axes_in, triin, title="In")
    plot_triangulateio(axes_out, triout, voronoi=voronoi, circumcircles=circumcircles, title="Out")
    # The output may have grown beyond the input (convex hull, Steiner points): show both whole.
    box_in, box_out = _view_box(triin), _view_box(triout)
    boxes = [b for b in (box_in, box_out) if b is not None]
    if boxes:
        axes_out.set_xlim(min(b[0] for b in boxes), max(b[1] for b in boxes))
        axes_out.set_ylim(min(b[2] for b in boxes), max(b[3] for b in boxes))
    if title:
        figure.suptitle(title)
    figure.tight_layout()
    return figure
