"""Drop-in replacement for the PyPI ``triangle`` package's API: ``triangulate(dict, opts)``,
``delaunay``, ``convex_hull`` and ``voronoi``, with the same dictionary keys, dtypes, 2-D shapes and
0-based numbering, so that ``import triangle_rs as triangle`` runs existing code."""

from __future__ import annotations

from typing import Any, Mapping, Optional

import numpy as np

from .core import Progress, Unsuitable, run_arrays
from .triangulateio import _EMPTY, FIELDS, TriangulateIO, normalize, output_reader

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
#: A field's position in ``FIELDS``: the order inputs are converted and checked in.
_FIELD_ORDER = {field: k for k, field in enumerate(FIELDS)}
#: A key's position in the output dictionary.
_KEY_ORDER = {key: k for k, key in enumerate(KEYS)}
#: The output struct read straight into the output dictionary: its keys, in its order, every
#: array 2-D (markers and areas (n, 1), as the PyPI package returns them).
_DICT_READER = output_reader(_FIELD_TO_KEY, flat_as_column=True)
#: What `delaunay`, `convex_hull` and `voronoi` return.
_TRIANGLES = output_reader({"trianglelist": "trianglelist"})
_SEGMENTS = output_reader({"segmentlist": "segmentlist"})
_VORONOI = output_reader({"pointlist": "pointlist", "edgelist": "edgelist", "normlist": "normlist"})


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
    return TriangulateIO._from_arrays(_dict_arrays(tri))


def _dict_arrays(tri: Mapping[str, Any]) -> dict[str, np.ndarray]:
    """The input dictionary's arrays, converted (field name -> array, in the order of ``FIELDS``,
    the keys given only): what ``TriangulateIO(**fields)`` would hold. An unknown key raises
    ``KeyError`` before anything is converted."""
    keys = tuple(tri)
    plan = _KEY_PLANS.get(keys) or _key_plan(keys)
    arrays = {}
    for key, name in plan:  # a plain loop: a comprehension is one more function call
        arrays[name] = normalize(name, tri[key])
    return arrays


#: The keys of an input dictionary, in its order -> its (key, field name) pairs in the order of
#: ``FIELDS``: checked and sorted once per process and order of keys, not on every call.
_KEY_PLANS: dict[tuple[str, ...], tuple[tuple[str, str], ...]] = {}
_KEY_PLANS_KEPT = 256


def _key_plan(keys: tuple[str, ...]) -> tuple[tuple[str, str], ...]:
    names = [KEYS[key] for key in keys]  # an unknown key raises KeyError
    plan = tuple(sorted(zip(keys, names), key=lambda pair: _FIELD_ORDER[pair[1]]))
    if len(_KEY_PLANS) >= _KEY_PLANS_KEPT:
        _KEY_PLANS.clear()
    _KEY_PLANS[keys] = plan
    return plan


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
    arrays = _dict_arrays(tri)
    out, _ = run_arrays("Qz" + opts, arrays, unsuitable=unsuitable, progress=progress, read=(_DICT_READER, None))
    return _select_keys(out, arrays, opts)


def _select_keys(out: dict[str, np.ndarray], tin: dict[str, np.ndarray], opts: str) -> dict[str, np.ndarray]:
    """What :func:`select_outputs` keeps, on the output dictionary ``out`` (changed and
    returned); ``tin`` is the input's arrays (field name -> array)."""
    writes_polygon = "P" not in opts
    if not (writes_polygon and ("p" in opts or "c" in opts)):
        out.pop("segments", None)
        out.pop("segment_markers", None)
    if writes_polygon and "p" in opts:
        added = False
        for key, field in (("holes", "holelist"), ("regions", "regionlist")):
            if key not in out and field in tin and tin[field].size:
                out[key] = tin[field]  # the input's (Triangle hands its arrays back)
                added = True
        if added:
            out = {key: out[key] for key in sorted(out, key=_KEY_ORDER.__getitem__)}
    else:
        out.pop("holes", None)
        out.pop("regions", None)
    return out


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


def _points(pts: Any) -> dict[str, np.ndarray]:
    return {"pointlist": normalize("pointlist", np.asarray(pts, dtype=np.float64))}


def delaunay(pts: Any) -> np.ndarray:
    """The Delaunay triangulation of the points ``pts`` (n, 2): triangles (m, 3) int32.

    >>> delaunay([[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]]).shape
    (4, 3)
    """
    out, _ = run_arrays("Qz", _points(pts), read=(_TRIANGLES, None))
    return out.get("trianglelist", _EMPTY["trianglelist"])


def convex_hull(pts: Any) -> np.ndarray:
    """The convex hull of the points ``pts`` (n, 2): its edges as segments (s, 2) int32.

    >>> convex_hull([[0, 0], [0, 1], [1, 1], [1, 0]]).shape
    (4, 2)
    """
    out, _ = run_arrays("Qzc", _points(pts), read=(_SEGMENTS, None))
    return out.get("segmentlist", _EMPTY["segmentlist"])


def voronoi(pts: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The Voronoi diagram of the points ``pts`` (n, 2).

    Returns ``(vertices, edges, ray_origins, ray_directions)``: the Voronoi vertices (one per
    Delaunay triangle, (v, 2) float64), the finite edges (f, 2) int32, and for each infinite ray
    its origin vertex (1-D int32) and direction ((r, 2) float64).

    >>> vertices, edges, ray_origins, ray_directions = voronoi([[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]])
    >>> vertices.shape, edges.shape, ray_origins.shape, ray_directions.shape
    ((4, 2), (4, 2), (4,), (4, 2))
    """
    _, vorout = run_arrays("Qzv", _points(pts), read=(None, _VORONOI))
    edges = vorout.get("edgelist", _EMPTY["edgelist"])
    finite = edges[:, 1] != -1
    vertices = vorout.get("pointlist", _EMPTY["pointlist"])
    return vertices, edges[finite], edges[~finite][:, 0], vorout.get("normlist", _EMPTY["normlist"])[~finite]
