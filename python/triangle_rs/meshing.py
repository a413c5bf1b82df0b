"""A keyword API for people who do not want to write switch strings:
``mesh(points, segments=..., holes=..., regions=..., min_angle=30, max_area=1e-3, conforming=True)``.
It builds Triangle's switch string (:func:`mesh_switches`) and calls the library."""

from __future__ import annotations

import math
from typing import Any, NamedTuple, Optional

import numpy as np

from .core import Unsuitable, run
from .triangulateio import TriangulateIO


class MeshResult(NamedTuple):
    """What :func:`mesh` returns; unpacks as ``out, vorout`` like :func:`triangulate`."""

    mesh: TriangulateIO
    voronoi: TriangulateIO


def _number(name: str, value: float, *, positive: bool) -> str:
    """A float as the library's switch parser reads it: ``repr`` (shortest round-trip, with an
    exponent for small and large values, e.g. ``1e-05``), which triangle-rs accepts."""
    number = float(value)
    if not math.isfinite(number) or number < 0 or (positive and number == 0):
        bound = "> 0" if positive else ">= 0"
        raise ValueError(f"{name} must be a finite number {bound}, got {value!r}")
    return repr(number)


def _region_rows(regions: Any) -> np.ndarray:
    array = np.asarray(regions, dtype=np.float64)
    if array.ndim == 1:
        array = array.reshape(1, -1)
    if array.ndim != 2 or array.shape[1] not in (3, 4):
        raise ValueError(
            f"regions must have rows (x, y, attribute) or (x, y, attribute, max_area), got shape {array.shape}"
        )
    if array.shape[1] == 3:
        # No area column: the region is not area-constrained (Triangle: a value <= 0).
        array = np.hstack([array, np.full((len(array), 1), -1.0)])
    return array


def mesh_switches(
    *,
    pslg: bool = False,
    regions: Optional[np.ndarray] = None,
    min_angle: Optional[float] = None,
    max_area: Optional[float] = None,
    conforming: bool = False,
    convex_hull: bool = False,
    max_steiner: Optional[int] = None,
    unsuitable: bool = False,
    voronoi: bool = False,
    neighbors: bool = False,
    edges: bool = False,
    quadratic: bool = False,
    jettison: bool = False,
) -> str:
    """The switch string :func:`mesh` passes (always quiet and 0-based: ``Qz``).

    >>> mesh_switches(pslg=True, min_angle=30, max_area=1e-3, conforming=True)
    'QzpDq30.0a0.001'
    >>> mesh_switches(max_area=1e-5, edges=True)
    'Qzea1e-05'
    """
    flags = "Qz"
    if pslg:
        flags += "p"
    if convex_hull:
        flags += "c"
    if conforming:
        flags += "D"
    if unsuitable:
        flags += "u"
    if voronoi:
        flags += "v"
    if neighbors:
        flags += "n"
    if edges:
        flags += "e"
    if quadratic:
        flags += "o2"
    if jettison:
        flags += "j"
    if regions is not None and len(regions):
        # Regional attributes go to triangleattributelist[:, 0]; regional areas need `a`
        # without a number, which only the regions with a positive area use.
        flags += "A"
        if np.any(regions[:, 3] > 0):
            flags += "a"
    # Numbers last, each directly after its letter, so no number runs into a flag letter.
    numbers = ""
    if min_angle is not None:
        numbers += "q" + _number("min_angle", min_angle, positive=False)
    if max_area is not None:
        numbers += "a" + _number("max_area", max_area, positive=True)
    if max_steiner is not None:
        if int(max_steiner) != max_steiner or max_steiner < 0:
            raise ValueError(f"max_steiner must be a whole number >= 0, got {max_steiner!r}")
        numbers += f"S{int(max_steiner)}"
    return flags + numbers


def mesh(
    points: Any,
    segments: Any = None,
    *,
    segment_markers: Any = None,
    point_markers: Any = None,
    point_attributes: Any = None,
    holes: Any = None,
    regions: Any = None,
    min_angle: Optional[float] = None,
    max_area: Optional[float] = None,
    conforming: bool = False,
    convex_hull: bool = False,
    max_steiner: Optional[int] = None,
    unsuitable: Optional[Unsuitable] = None,
    voronoi: bool = False,
    neighbors: bool = False,
    edges: bool = False,
    quadratic: bool = False,
    jettison: bool = False,
) -> MeshResult:
    """Meshes a point set or a planar straight line graph without a switch string.

    Args:
        points: (n, 2) coordinates.
        segments: (s, 2) 0-based point indices of the edges the mesh must contain (boundaries,
            hole boundaries, interfaces). Giving segments, holes or regions meshes the domain they
            enclose (Triangle's ``p``: triangles outside the segments are removed unless
            ``convex_hull``).
        segment_markers, point_markers: boundary markers, one per segment / point.
        point_attributes: (n, k) values interpolated at new points.
        holes: (h, 2) a point inside each hole.
        regions: rows (x, y, attribute[, max_area]): a point inside each region, its attribute
            (written to ``triangleattributelist[:, 0]``) and its maximum triangle area (<= 0 or
            absent: none).
        min_angle: minimum angle in degrees (``q``; up to about 33 terminates in practice).
        max_area: maximum triangle area everywhere (``a``).
        conforming: every triangle truly Delaunay (``D``).
        convex_hull: keep the convex hull triangulated and output its segments (``c``).
        max_steiner: at most this many added points (``S``).
        unsuitable: ``f(x1, y1, x2, y2, x3, y3, area) -> bool``, True to split the triangle (``u``).
        voronoi, neighbors, edges: also output the Voronoi diagram (``v``), the neighbour list
            (``n``), the edge list (``e``).
        quadratic: 6-node triangles (``o2``). jettison: drop unused points (``j``).

    Returns:
        ``MeshResult(mesh, voronoi)``, which unpacks as ``out, vorout``.
    """
    region_rows = _region_rows(regions) if regions is not None else None
    pslg = segments is not None or holes is not None or region_rows is not None
    switches = mesh_switches(
        pslg=pslg,
        regions=region_rows,
        min_angle=min_angle,
        max_area=max_area,
        conforming=conforming,
        convex_hull=convex_hull,
        max_steiner=max_steiner,
        unsuitable=unsuitable is not None,
        voronoi=voronoi,
        neighbors=neighbors,
        edges=edges,
        quadratic=quadratic,
        jettison=jettison,
    )
    tio = TriangulateIO(
        pointlist=points,
        pointmarkerlist=point_markers,
        pointattributelist=point_attributes,
        segmentlist=segments,
        segmentmarkerlist=segment_markers,
        holelist=holes,
        regionlist=region_rows,
    )
    out, vorout = run(switches, tio, unsuitable=unsuitable)
    return MeshResult(out, vorout)
