"""``TriangulateIO``: Triangle's ``struct triangulateio`` with numpy arrays, one row per item.

Row-major ``(n, 2)`` numpy arrays have exactly the memory layout of Triangle's flat C arrays (and of
Triangulate.jl's ``2 x n`` column-major matrices), so input arrays are handed to the library without
copying. Every index is 0-based (the calls in this package always pass Triangle's ``z`` switch).
"""

from __future__ import annotations

import ctypes
from typing import Any, NamedTuple

import numpy as np

from ._library import CTriangulateIO


class _Field(NamedTuple):
    dtype: type
    #: Items per row: a number for fixed-width 2-D arrays, ``None`` for a variable width
    #: (attributes, triangle corners), ``0`` for 1-D arrays (one value per item).
    width: int | None
    #: The count field of the C struct that gives the number of rows.
    rows: str
    #: The count field that gives the width, for variable widths.
    columns: str | None = None


FIELDS: dict[str, _Field] = {
    "pointlist": _Field(np.float64, 2, "numberofpoints"),
    "pointattributelist": _Field(np.float64, None, "numberofpoints", "numberofpointattributes"),
    "pointmarkerlist": _Field(np.int32, 0, "numberofpoints"),
    "trianglelist": _Field(np.int32, None, "numberoftriangles", "numberofcorners"),
    "triangleattributelist": _Field(np.float64, None, "numberoftriangles", "numberoftriangleattributes"),
    "trianglearealist": _Field(np.float64, 0, "numberoftriangles"),
    "neighborlist": _Field(np.int32, 3, "numberoftriangles"),
    "segmentlist": _Field(np.int32, 2, "numberofsegments"),
    "segmentmarkerlist": _Field(np.int32, 0, "numberofsegments"),
    "holelist": _Field(np.float64, 2, "numberofholes"),
    "regionlist": _Field(np.float64, 4, "numberofregions"),
    "edgelist": _Field(np.int32, 2, "numberofedges"),
    "edgemarkerlist": _Field(np.int32, 0, "numberofedges"),
    "normlist": _Field(np.float64, 2, "numberofedges"),
}

#: Output arrays that alias the input's (Triangle copies the pointers): never freed.
ALIASED_FIELDS = frozenset({"holelist", "regionlist"})

#: Fields the library reads from the input struct (the others are output only).
INPUT_FIELDS = (
    "pointlist",
    "pointattributelist",
    "pointmarkerlist",
    "trianglelist",
    "triangleattributelist",
    "trianglearealist",
    "segmentlist",
    "segmentmarkerlist",
    "holelist",
    "regionlist",
)

_INT32 = np.iinfo(np.int32)


def _make_empty(name: str) -> np.ndarray:
    field = FIELDS[name]
    if field.width == 0:
        shape: tuple[int, ...] = (0,)
    elif field.width is None:
        shape = (0, 3 if name == "trianglelist" else 0)
    else:
        shape = (0, field.width)
    array = np.empty(shape, dtype=field.dtype)
    array.flags.writeable = False  # shared by every TriangulateIO: nothing may change it
    return array


#: The array of an absent field: no rows, and the field's width (triangles: 3 corners;
#: attributes: none). One read-only instance per field, shared.
_EMPTY = {name: _make_empty(name) for name in FIELDS}


def _empty(name: str) -> np.ndarray:
    return _EMPTY[name]


def normalize(name: str, value: Any) -> np.ndarray:
    """Converts ``value`` to the dtype and shape of field ``name`` (C-contiguous; no copy when it
    already is). ``None`` gives the empty array of the right shape."""
    field = FIELDS[name]
    if value is None:
        return _empty(name)
    source = np.asarray(value)
    if source.size == 0:
        return _empty(name)
    if field.dtype is np.int32 and source.dtype.kind not in "iub":
        if source.dtype.kind != "f" or not np.all(np.isfinite(source)) or not np.all(source == np.round(source)):
            raise ValueError(f"{name} must hold integers, got {source.dtype} values that are not whole numbers")
    if field.dtype is np.int32 and source.dtype.kind in "iuf":
        if source.min() < _INT32.min or source.max() > _INT32.max:
            raise ValueError(f"{name} holds values outside the range of a 32-bit C int")
    array = np.ascontiguousarray(source, dtype=field.dtype)
    if field.width == 0:
        if array.ndim == 2 and array.shape[1] == 1:
            return array.reshape(-1)
        if array.ndim != 1:
            raise ValueError(f"{name} must be 1-D (one value per item) or of shape (n, 1), got shape {source.shape}")
        return array
    if field.width is None:
        if array.ndim == 1 and field.columns != "numberofcorners":
            return array.reshape(-1, 1)
        if array.ndim != 2:
            raise ValueError(f"{name} must be 2-D (one row per item), got shape {source.shape}")
        if field.columns == "numberofcorners" and array.shape[1] < 3:
            raise ValueError(f"{name} needs at least 3 corners per triangle, got shape {source.shape}")
        return array
    if array.ndim == 1 and array.size % field.width == 0:
        return array.reshape(-1, field.width)
    if array.ndim != 2 or array.shape[1] != field.width:
        raise ValueError(f"{name} must have shape (n, {field.width}), got shape {source.shape}")
    return array


class TriangulateIO:
    """Input or output of a triangulation: Triangle's ``struct triangulateio`` as numpy arrays.

    Every field is a numpy array with one row per item (empty when absent); assigning converts to
    the field's dtype and shape. Counts are derived from the arrays (``numberofpoints`` ...).
    Indices are 0-based. ``-1`` means "no neighbour" in ``neighborlist`` and "infinite ray" as the
    second index of a Voronoi ``edgelist``, whose direction is then the ``normlist`` row.

    >>> tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]])
    >>> tio.numberofpoints, tio.pointlist.dtype, tio.trianglelist.shape
    (3, dtype('float64'), (0, 3))
    """

    __slots__ = tuple(FIELDS)

    pointlist: np.ndarray
    """(n, 2) float64: x, y of each point."""
    pointattributelist: np.ndarray
    """(n, k) float64: k attributes per point (interpolated at new points)."""
    pointmarkerlist: np.ndarray
    """(n,) int32: boundary marker per point."""
    trianglelist: np.ndarray
    """(m, 3) or (m, 6) int32: corners counter-clockwise (then the ``o2`` mid-edge nodes)."""
    triangleattributelist: np.ndarray
    """(m, k) float64: attributes per triangle (``A`` appends the region attribute)."""
    trianglearealist: np.ndarray
    """(m,) float64: per-triangle maximum area (input for ``ra``)."""
    neighborlist: np.ndarray
    """(m, 3) int32: neighbour opposite each corner, -1 for none (``n``)."""
    segmentlist: np.ndarray
    """(s, 2) int32: segment endpoints."""
    segmentmarkerlist: np.ndarray
    """(s,) int32: boundary marker per segment."""
    holelist: np.ndarray
    """(h, 2) float64: a point inside each hole."""
    regionlist: np.ndarray
    """(r, 4) float64: x, y, attribute, maximum area (<= 0: unconstrained) per region."""
    edgelist: np.ndarray
    """(e, 2) int32: edge endpoints (``e``), or Voronoi edges (second index -1 for a ray)."""
    edgemarkerlist: np.ndarray
    """(e,) int32: boundary marker per edge."""
    normlist: np.ndarray
    """(e, 2) float64: Voronoi ray directions ((0, 0) for finite edges)."""

    def __init__(self, **fields: Any):
        unknown = set(fields) - set(FIELDS)
        if unknown:
            raise TypeError(f"unknown TriangulateIO field(s): {', '.join(sorted(unknown))}")
        for name in FIELDS:
            setattr(self, name, fields.get(name))

    def __setattr__(self, name: str, value: Any) -> None:
        if name not in FIELDS:
            raise AttributeError(f"TriangulateIO has no field {name!r}")
        object.__setattr__(self, name, normalize(name, value))

    @property
    def numberofpoints(self) -> int:
        return len(self.pointlist)

    @property
    def numberofpointattributes(self) -> int:
        return self.pointattributelist.shape[1] if len(self.pointattributelist) else 0

    @property
    def numberoftriangles(self) -> int:
        return len(self.trianglelist)

    @property
    def numberofcorners(self) -> int:
        return self.trianglelist.shape[1]

    @property
    def numberoftriangleattributes(self) -> int:
        return self.triangleattributelist.shape[1] if len(self.triangleattributelist) else 0

    @property
    def numberofsegments(self) -> int:
        return len(self.segmentlist)

    @property
    def numberofholes(self) -> int:
        return len(self.holelist)

    @property
    def numberofregions(self) -> int:
        return len(self.regionlist)

    @property
    def numberofedges(self) -> int:
        return len(self.edgelist)

    def copy(self) -> "TriangulateIO":
        """A deep copy."""
        return TriangulateIO(**{name: getattr(self, name).copy() for name in FIELDS})

    def __repr__(self) -> str:
        present = [f"{name}={getattr(self, name).shape}" for name in FIELDS if getattr(self, name).size]
        return f"TriangulateIO({', '.join(present)})"


def numberofpoints(tio: TriangulateIO) -> int:
    """Triangulate.jl's ``numberofpoints(tio)``."""
    return tio.numberofpoints


def numberoftriangles(tio: TriangulateIO) -> int:
    """Triangulate.jl's ``numberoftriangles(tio)``."""
    return tio.numberoftriangles


def numberofsegments(tio: TriangulateIO) -> int:
    """Triangulate.jl's ``numberofsegments(tio)``."""
    return tio.numberofsegments


def numberofedges(tio: TriangulateIO) -> int:
    """Triangulate.jl's ``numberofedges(tio)``."""
    return tio.numberofedges


# --- conversion to and from the C struct -------------------------------------------------------


def to_c(tio: TriangulateIO) -> tuple[CTriangulateIO, list[np.ndarray]]:
    """The C struct for ``tio`` as input, pointing into its arrays, and the arrays to keep alive
    for the duration of the call. Checks that the per-item arrays match their item counts (the
    library trusts the counts, as Triangle does)."""
    arrays = {name: normalize(name, getattr(tio, name)) for name in INPUT_FIELDS}
    c = CTriangulateIO()
    counts = {
        "numberofpoints": len(arrays["pointlist"]),
        "numberoftriangles": len(arrays["trianglelist"]),
        "numberofsegments": len(arrays["segmentlist"]),
        "numberofholes": len(arrays["holelist"]),
        "numberofregions": len(arrays["regionlist"]),
    }
    keep: list[np.ndarray] = []
    for name, array in arrays.items():
        field = FIELDS[name]
        if array.size == 0:
            continue
        if len(array) != counts[field.rows]:
            raise ValueError(
                f"{name} has {len(array)} rows but {field.rows} is {counts[field.rows]} "
                f"(it must have one row per item, or be empty)"
            )
        pointer_type = type(getattr(c, name))
        setattr(c, name, array.ctypes.data_as(pointer_type))
        keep.append(array)
    for count_name, value in counts.items():
        if value > _INT32.max:
            raise ValueError(f"{count_name} = {value} does not fit a C int")
        setattr(c, count_name, value)
    if arrays["pointattributelist"].size:
        c.numberofpointattributes = arrays["pointattributelist"].shape[1]
    c.numberofcorners = arrays["trianglelist"].shape[1]
    if arrays["triangleattributelist"].size:
        c.numberoftriangleattributes = arrays["triangleattributelist"].shape[1]
    return c, keep


def _rows_and_width(c: CTriangulateIO, field: _Field) -> tuple[int, int]:
    rows = max(getattr(c, field.rows), 0)
    if field.width is None:
        width = max(getattr(c, field.columns), 0) if field.columns else 0
    else:
        width = field.width or 1
    return rows, width


def from_c(c: CTriangulateIO) -> TriangulateIO:
    """Copies every array that the library wrote into ``c`` into a new ``TriangulateIO``.

    The pointers stay in ``c``: release them with :func:`free_c`."""
    tio = TriangulateIO()
    for name, field in FIELDS.items():
        pointer = getattr(c, name)
        if not pointer:
            continue
        rows, width = _rows_and_width(c, field)
        if rows == 0 or width == 0:
            continue
        flat = np.ctypeslib.as_array(pointer, shape=(rows * width,))
        data = flat.copy() if field.width == 0 else flat.reshape(rows, width).copy()
        object.__setattr__(tio, name, data)
    return tio


def free_c(c: CTriangulateIO, free: Any) -> None:
    """Releases the arrays the library allocated in output struct ``c`` with ``free`` (the
    library's ``trifree``), except ``holelist``/``regionlist``, which alias the input's arrays.
    Clears the released pointers so that a second call is harmless."""
    for name in FIELDS:
        if name in ALIASED_FIELDS:
            continue
        pointer = getattr(c, name)
        if pointer:
            free(ctypes.cast(pointer, ctypes.c_void_p).value)
            setattr(c, name, type(pointer)())
