"""Drop-in replacement for the PyPI ``triangle`` package's API: ``triangulate(dict, opts)``,
``delaunay``, ``convex_hull`` and ``voronoi``, with the same dictionary keys, dtypes, 2-D shapes and
0-based numbering, so that ``import triangle_rs as triangle`` runs existing code."""

from __future__ import annotations

from typing import Any, Mapping, Optional

import numpy as np

from .core import Progress, Unsuitable, run
from .triangulateio import FIELDS, TriangulateIO

#: The PyPI package's dictionary keys for the C struct's fields.
KEYS: dict[str, str] = {
    "vertices": "pointlist",
    "vertex_attributes": "pointattributelist",
    "vertex_markers": "pointmarkerlist",
    "triangles": "trianglelist",
    "triangle_attributes": "triangleattributelist",
    "triangle_max_area": "trianglearealist",
    "segments": "segmentlist",
    "segment_markers": "segmentmarkerlist",
    "holes": "holelist",
    "regions": "regionlist",
    "neighbors": "neighborlist",
    "edges": "edgelist",
    "edge_markers": "edgemarkerlist",
}
_FIELD_TO_KEY = {field: key for key, field in KEYS.items()}


def to_dict(tio: TriangulateIO) -> dict[str, np.ndarray]:
    """The PyPI package's output dictionary: only the fields that are present, every array 2-D
    with one row per item (markers as ``(n, 1)``)."""
    result: dict[str, np.ndarray] = {}
    for field, key in _FIELD_TO_KEY.items():
        array = getattr(tio, field)
        if array.size == 0:
            continue
        result[key] = array.reshape(-1, 1) if FIELDS[field].width == 0 else array
    return result


def from_dict(tri: Mapping[str, Any]) -> TriangulateIO:
    """A ``TriangulateIO`` from the PyPI package's input dictionary. An unknown key raises
    ``KeyError``, as the PyPI package does."""
    fields = {}
    for key, value in tri.items():
        if key not in KEYS:
            raise KeyError(key)
        fields[KEYS[key]] = value
    return TriangulateIO(**fields)


def triangulate(
    tri: Mapping[str, Any],
    opts: str = "",
    *,
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
) -> dict[str, np.ndarray]:
    """Triangulates the dictionary ``tri`` with Triangle's switches ``opts``, as the PyPI
    ``triangle`` package does (``Q`` and ``z`` are always added).

    Keys: ``vertices`` (n, 2), ``vertex_attributes``, ``vertex_markers``, ``segments`` (s, 2),
    ``segment_markers``, ``holes`` (h, 2), ``regions`` (r, 4: x, y, attribute, max area),
    ``triangles`` and ``triangle_attributes``/``triangle_max_area`` (for ``r``). The result has the
    same keys plus ``neighbors`` (``n``) and ``edges``/``edge_markers`` (``e``).
    ``unsuitable`` (an extension) is the per-call test of switch ``u`` (without it, ``u`` applies
    Triangle's built-in test, as the PyPI package does); ``progress=True`` (an extension) shows a
    progress bar, and a callable ``progress(phase, done, estimate)`` is told.

    >>> out = triangulate({'vertices': [[0, 0], [0, 1], [1, 1], [1, 0]]})
    >>> sorted(out), out['triangles'].shape, out['vertex_markers'].shape
    (['triangles', 'vertex_markers', 'vertices'], (2, 3), (4, 1))
    """
    if not isinstance(opts, str):
        raise TypeError(f"opts must be a str, got {type(opts).__name__}")
    if unsuitable is not None and "u" not in opts:
        raise ValueError("an unsuitable callback is used only with the switch 'u': add it to opts")
    tio = from_dict(tri)
    out, _ = run("Qz" + opts, tio, unsuitable=unsuitable, progress=progress)
    return to_dict(select_outputs(out, tio, opts))


def select_outputs(out: TriangulateIO, tin: TriangulateIO, opts: str) -> TriangulateIO:
    """The output fields Triangle (and so the PyPI package) returns for the switches ``opts``:
    segments only with ``p`` or ``c``; the input's holes and regions whenever ``p`` is given
    (Triangle hands the input's arrays back), ``r`` included; neither with ``P`` (no polygon
    output). ``opts`` holds no other letters that matter here: numbers are digits, ``.`` and
    (triangle-rs only) ``e``."""
    letters = set(opts)
    writes_polygon = "P" not in letters
    if not (writes_polygon and letters & {"p", "c"}):
        out.segmentlist = None
        out.segmentmarkerlist = None
    if writes_polygon and "p" in letters:
        if not out.numberofholes:
            out.holelist = tin.holelist
        if not out.numberofregions:
            out.regionlist = tin.regionlist
    else:
        out.holelist = None
        out.regionlist = None
    return out


def _points(pts: Any) -> TriangulateIO:
    return TriangulateIO(pointlist=np.asarray(pts, dtype=np.float64))


def delaunay(pts: Any) -> np.ndarray:
    """The Delaunay triangulation of the points ``pts`` (n, 2): triangles (m, 3) int32.

    >>> delaunay([[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]]).shape
    (4, 3)
    """
    out, _ = run("Qz", _points(pts))
    return out.trianglelist


def convex_hull(pts: Any) -> np.ndarray:
    """The convex hull of the points ``pts`` (n, 2): its edges as segments (s, 2) int32.

    >>> convex_hull([[0, 0], [0, 1], [1, 1], [1, 0]]).shape
    (4, 2)
    """
    out, _ = run("Qzc", _points(pts))
    return out.segmentlist


def voronoi(pts: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The Voronoi diagram of the points ``pts`` (n, 2).

    Returns ``(vertices, edges, ray_origins, ray_directions)``: the Voronoi vertices (one per
    Delaunay triangle, (v, 2) float64), the finite edges (f, 2) int32, and for each infinite ray
    its origin vertex (1-D int32) and direction ((r, 2) float64).

    >>> vertices, edges, ray_origins, ray_directions = voronoi([[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]])
    >>> vertices.shape, edges.shape, ray_origins.shape, ray_directions.shape
    ((4, 2), (4, 2), (4,), (4, 2))
    """
    _, vorout = run("Qzv", _points(pts))
    edges = vorout.edgelist
    finite = edges[:, 1] != -1
    return vorout.pointlist, edges[finite], edges[~finite][:, 0], vorout.normlist[~finite]
