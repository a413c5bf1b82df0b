"""``TriangulateIO``: Triangle's ``struct triangulateio`` with numpy arrays, one row per item.

Row-major ``(n, 2)`` numpy arrays have exactly the memory layout of Triangle's flat C arrays (and of
Triangulate.jl's ``2 x n`` column-major matrices), so input arrays are handed to the library without
copying. Every index is 0-based (the calls in this package always pass Triangle's ``z`` switch).
"""

from __future__ import annotations

import ctypes
import operator
import struct
import sys
from itertools import compress
from typing import Any, Callable, Mapping, NamedTuple

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
_INT32_DTYPE = np.dtype(np.int32)
_INT64 = np.dtype(np.int64)
_INT32_MAX = int(_INT32.max)


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


#: Per field: the numpy dtype (the singleton instance: ``array.dtype is`` tests it), the width
#: (as in :class:`_Field`) and whether the field is the triangles' (at least 3 corners).
_SHAPES = {
    name: (np.dtype(field.dtype), field.width, field.columns == "numberofcorners") for name, field in FIELDS.items()
}


def normalize(name: str, value: Any) -> np.ndarray:
    """Converts ``value`` to the dtype and shape of field ``name`` (C-contiguous; no copy when it
    already is). ``None`` gives the empty array of the right shape."""
    dtype, width, corners = _SHAPES[name]
    if value is None:
        return _EMPTY[name]
    source = value if type(value) is np.ndarray else np.asarray(value)
    if not source.size:
        return _EMPTY[name]
    source_dtype = source.dtype
    if source_dtype is dtype:
        array = source if source.flags.c_contiguous else np.ascontiguousarray(source)
    elif source_dtype is _INT64 and dtype is _INT32_DTYPE and _SAME_VALUE_CASTS:
        # A list of Python ints (indices, markers) becomes int64: the one checked cast that
        # `_converted` ends with, without its tests, which cost as much again on every call.
        try:
            array = source.astype(dtype, order="C", casting="same_value")
        except ValueError:
            raise ValueError(f"{name} holds values outside the range of a 32-bit C int") from None
    else:
        array = _converted(name, source, dtype)
    shape = array.shape
    ndim = len(shape)
    if width:
        if ndim == 2 and shape[1] == width:
            return array
        if ndim == 1 and array.size % width == 0:
            return array.reshape(-1, width)
        raise ValueError(f"{name} must have shape (n, {width}), got shape {source.shape}")
    if width == 0:
        if ndim == 1:
            return array
        if ndim == 2 and shape[1] == 1:
            return array.reshape(-1)
        raise ValueError(f"{name} must be 1-D (one value per item) or of shape (n, 1), got shape {source.shape}")
    if ndim == 2:
        if corners and shape[1] < 3:
            raise ValueError(f"{name} needs at least 3 corners per triangle, got shape {source.shape}")
        return array
    if ndim == 1 and not corners:
        return array.reshape(-1, 1)
    raise ValueError(f"{name} must be 2-D (one row per item), got shape {source.shape}")


def _converted(name: str, source: np.ndarray, dtype: np.dtype) -> np.ndarray:
    """``source`` (not empty, of another dtype) as a C-contiguous array of ``dtype``; for the
    integer fields, refuses values that are not whole numbers or do not fit a C int."""
    if dtype.kind == "i":
        kind = source.dtype.kind
        if kind not in "iub":
            if kind != "f" or not np.all(np.isfinite(source)) or not np.all(source == np.round(source)):
                raise ValueError(f"{name} must hold integers, got {source.dtype} values that are not whole numbers")
        if kind in "iuf" and not (kind == "i" and source.dtype.itemsize <= 4):  # int8 ... int32 always fit
            if _SAME_VALUE_CASTS:
                # One pass that converts and refuses any value that changes (numpy >= 2.4).
                try:
                    return source.astype(dtype, order="C", casting="same_value")
                except ValueError:
                    raise ValueError(f"{name} holds values outside the range of a 32-bit C int") from None
            if source.min() < _INT32.min or source.max() > _INT32.max:
                raise ValueError(f"{name} holds values outside the range of a 32-bit C int")
    return np.ascontiguousarray(source, dtype=dtype)


def _same_value_casts() -> bool:
    """Whether this numpy has ``astype(..., casting="same_value")`` (numpy 2.4), which refuses a
    value that the cast would change."""
    try:
        np.ones(1).astype(np.int32, casting="same_value")
    except (TypeError, ValueError):
        return False
    try:
        np.array([2**40]).astype(np.int32, casting="same_value")
    except ValueError:
        return True
    return False  # pragma: no cover - accepted but not checked: do not rely on it


_SAME_VALUE_CASTS = _same_value_casts()


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

    @classmethod
    def _from_arrays(cls, arrays: Mapping[str, np.ndarray]) -> "TriangulateIO":
        """A ``TriangulateIO`` of ``arrays`` (field name -> an array of the field's dtype and
        shape, as :func:`normalize` returns it), taken as they are; the other fields empty."""
        tio = object.__new__(cls)
        for name, empty in _EMPTY.items():
            _set_field(tio, name, arrays.get(name, empty))
        return tio

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


_set_field = object.__setattr__


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
#
# Every call converts, so this is the per-call cost of the package (issue 36): the struct is
# written with one `struct.pack_into` and read with one `struct.unpack_from` (no per-field ctypes
# objects), input arrays are passed by their data address (no copy), and each output array is one
# `np.frombuffer` view of the library's memory, copied at once, then freed.


def _layout() -> struct.Struct:
    """The ``struct`` format of :class:`CTriangulateIO` (pointers ``P``, ints ``i``, native
    alignment), checked field by field against the ctypes offsets."""
    codes = ["i" if ctype is ctypes.c_int else "P" for _, ctype in CTriangulateIO._fields_]
    for k, (name, ctype) in enumerate(CTriangulateIO._fields_):
        start = struct.calcsize("@" + "".join(codes[: k + 1])) - ctypes.sizeof(ctype)
        if start != getattr(CTriangulateIO, name).offset:  # pragma: no cover - an exotic ABI
            raise ImportError(f"struct triangulateio: the offset of {name} is not the one ctypes computes")
    return struct.Struct("@" + "".join(codes))


_LAYOUT = _layout()
#: A field's position in the values of `_LAYOUT`.
_INDEX = {name: k for k, (name, _) in enumerate(CTriangulateIO._fields_)}
#: An input struct before its fields are set: no arrays, no items, 3 corners per triangle.
_INPUT_DEFAULTS = tuple(3 if name == "numberofcorners" else 0 for name, _ in CTriangulateIO._fields_)
#: The count fields that give the numbers of items, in the order `to_c` checks them.
_ROW_COUNT_INDICES = tuple(
    _INDEX[name] for name in ("numberofpoints", "numberoftriangles", "numberofsegments", "numberofholes", "numberofregions")
)

#: Per input field: its pointer's index, its rows' count's index, whether it sets that count
#: (the item lists) or must match it (the per-item lists), and the index of its width's count.
_INPUTS = {
    name: (
        _INDEX[name],
        _INDEX[FIELDS[name].rows],
        name in ("pointlist", "trianglelist", "segmentlist", "holelist", "regionlist"),
        _INDEX[FIELDS[name].columns] if FIELDS[name].columns else None,
    )
    for name in INPUT_FIELDS
}


class OutputReader(NamedTuple):
    """Which arrays :func:`read_output` copies out of an output struct, under which names, in
    which order (see :func:`output_reader`)."""

    #: Per array: its name in the result, its pointer's index in the values of `_LAYOUT`, its
    #: rows' count's index, its width's count's index (``None`` for a fixed width) and the dtype
    #: of one row (a subarray dtype such as ``(float64, (2,))`` for a fixed width:
    #: `np.frombuffer` then makes the 2-D array at once).
    entries: tuple[tuple[str, int, int, int | None, np.dtype], ...]
    #: The values of `_LAYOUT` -> the entries' pointers (``compress`` picks the set ones).
    pointers: Callable[[tuple[int, ...]], tuple[int, ...]]


def output_reader(names: Mapping[str, str], flat_as_column: bool = False) -> OutputReader:
    """An :class:`OutputReader` for the fields ``names`` (field -> its name in the result, in the
    order of the result); with ``flat_as_column`` the 1-D fields (markers, areas) come as
    ``(n, 1)`` arrays."""
    entries = []
    for field_name, name in names.items():
        field = FIELDS[field_name]
        width = 1 if field.width == 0 and flat_as_column else field.width
        row = np.dtype((field.dtype, (width,))) if width else np.dtype(field.dtype)  # None: a width's count
        entries.append((name, _INDEX[field_name], _INDEX[field.rows], _INDEX[field.columns] if field.columns else None, row))
    indices = [entry[1] for entry in entries]
    pointers = operator.itemgetter(*indices) if len(indices) > 1 else lambda values, k=indices[0]: (values[k],)
    return OutputReader(tuple(entries), pointers)


#: Every field, under its own name, in the order of :data:`FIELDS` (what `TriangulateIO` holds).
FIELD_READER = output_reader({name: name for name in FIELDS})


#: (dtype, width) -> the dtype of a row of ``width`` items, for the variable widths.
_ROWS: dict[tuple[np.dtype, int], np.dtype] = {}


def _row_dtype(dtype: np.dtype, width: int) -> np.dtype:
    row = _ROWS.get((dtype, width))
    if row is None:
        row = _ROWS[(dtype, width)] = np.dtype((dtype, (width,)))
    return row


#: The pointers of an output struct that the library allocated (all but the aliased ones).
_ALLOCATED = operator.itemgetter(*(_INDEX[name] for name in FIELDS if name not in ALIASED_FIELDS))


def _data_pointer_offset() -> int | None:
    """Where a numpy array object holds the address of its data, from the object's address
    (``id``), or ``None`` to use ``array.ctypes.data``. That builds a ctypes helper object (~3 µs
    a call); on CPython numpy keeps the address in the array object (``PyArrayObject_fields.data``,
    right after the object header), which is read in a fraction of that. Checked once per process
    against ``array.ctypes.data``."""
    if sys.implementation.name != "cpython":
        return None  # pragma: no cover - id() is not an address there
    offset = object.__basicsize__
    probe = np.arange(8.0)
    probes = (probe, probe[3:], probe.reshape(2, 4)[1], np.arange(6, dtype=np.int32)[2:])
    try:
        if all(_read_pointer(id(array) + offset).value == array.ctypes.data for array in probes):
            return offset
    except Exception:  # noqa: BLE001 - pragma: no cover - use the portable way
        pass
    return None  # pragma: no cover


_read_pointer = ctypes.c_void_p.from_address
_DATA_POINTER_OFFSET = _data_pointer_offset()


def _address(array: np.ndarray) -> int:
    """The address of ``array``'s data (not empty)."""
    if _DATA_POINTER_OFFSET is None:
        return array.ctypes.data  # pragma: no cover - not CPython
    return _read_pointer(id(array) + _DATA_POINTER_OFFSET).value


_memmove = ctypes.memmove

#: The process's address space as one buffer: a ctypes array at address 0 of the largest size
#: Python allows (making it allocates and reads nothing). ``np.frombuffer(_MEMORY, dtype, count,
#: offset=address)`` is then a view of the ``count`` items at ``address``: the cheapest way from
#: numpy to an array the library allocated (one call; no ctypes type or object per array, as
#: ``np.ctypeslib.as_array`` makes, ~8 µs; faster than ``np.empty`` and ``ctypes.memmove``). Only
#: the arrays the library hands back are read through it, each copied at once; it is never read
#: as a whole.
_MEMORY = (ctypes.c_char * sys.maxsize).from_address(0)
_frombuffer = np.frombuffer


def _copy_out(pointer: int, dtype: np.dtype, rows: int) -> np.ndarray:
    """A copy of the ``rows`` items of ``dtype`` (a row dtype or a scalar one) at ``pointer``,
    where `_MEMORY` does not reach (addresses past ``sys.maxsize``)."""
    array = np.empty(rows, dtype)
    _memmove(_address(array), pointer, array.nbytes)
    return array


def input_struct(arrays: Mapping[str, np.ndarray]) -> CTriangulateIO:
    """The C struct for the input ``arrays`` (field name -> an array as :func:`normalize` returns
    it; absent fields may be left out; fields that are not inputs are ignored), pointing into
    them: the caller keeps them alive for the duration of the call. Checks that the per-item
    arrays match their item counts (the library trusts the counts, as Triangle does); ``arrays``
    are checked in their order, which callers keep that of :data:`FIELDS`."""
    values = list(_INPUT_DEFAULTS)
    offset = _DATA_POINTER_OFFSET
    too_many = False  # a count past a C int: refused once every array is checked, as before
    for name, array in arrays.items():
        known = _INPUTS.get(name)
        if known is None or not array.size:
            continue
        pointer_index, rows_index, sets_rows, columns_index = known
        rows = len(array)
        if sets_rows:
            values[rows_index] = rows
            if rows > _INT32_MAX:
                too_many = True
        elif rows != values[rows_index]:
            rows_name = FIELDS[name].rows
            raise ValueError(
                f"{name} has {rows} rows but {rows_name} is {values[rows_index]} "
                f"(it must have one row per item, or be empty)"
            )
        if columns_index is not None:
            values[columns_index] = array.shape[1]
        # `_address(array)`, inline: this runs for every input array of every call.
        values[pointer_index] = _read_pointer(id(array) + offset).value if offset is not None else array.ctypes.data
    if too_many:  # a flag, not `max` over the counts: that costs a tenth of this function
        for index in _ROW_COUNT_INDICES:
            if values[index] > _INT32_MAX:
                raise ValueError(f"{CTriangulateIO._fields_[index][0]} = {values[index]} does not fit a C int")
    c = CTriangulateIO()
    _LAYOUT.pack_into(c, 0, *values)
    return c


#: ``struct_values(c)``: every field of the struct ``c``, in order, as Python ints (one call).
struct_values = _LAYOUT.unpack_from


def read_output(c: CTriangulateIO, reader: OutputReader = FIELD_READER) -> dict[str, np.ndarray]:
    """Copies the arrays that the library wrote into ``c``: name -> a new array, for the fields
    of ``reader`` that are present, in its order. The pointers stay in ``c``."""
    return read_values(_LAYOUT.unpack_from(c), reader)


def read_values(values: tuple[int, ...], reader: OutputReader = FIELD_READER) -> dict[str, np.ndarray]:
    """:func:`read_output` of the struct whose :func:`struct_values` are ``values``."""
    arrays: dict[str, np.ndarray] = {}
    # Only the fields whose pointer is set (`compress` picks them in C).
    for name, pointer_index, rows_index, columns_index, dtype in compress(reader.entries, reader.pointers(values)):
        rows = values[rows_index]
        if rows <= 0:
            continue
        if columns_index is not None:
            width = values[columns_index]
            if width <= 0:
                continue
            dtype = _ROWS.get((dtype, width)) or _row_dtype(dtype, width)
        try:
            arrays[name] = _frombuffer(_MEMORY, dtype, rows, values[pointer_index]).copy()
        except (ValueError, OverflowError):  # pragma: no cover - an address past sys.maxsize
            arrays[name] = _copy_out(values[pointer_index], dtype, rows)
    return arrays


def release_outputs(free: Any, *structs: CTriangulateIO) -> None:
    """Releases the arrays the library allocated in the output ``structs`` with ``free`` (the
    library's ``trifree``), except ``holelist``/``regionlist``, which alias the input's arrays.
    Leaves the pointers in the structs, which are not to be used again (:func:`free_c` clears
    them)."""
    release_values(free, *map(_LAYOUT.unpack_from, structs))


def release_values(free: Any, *structs_values: tuple[int, ...]) -> None:
    """:func:`release_outputs` of the structs whose :func:`struct_values` are given."""
    for values in structs_values:
        for pointer in filter(None, _ALLOCATED(values)):
            free(pointer)


def to_c(tio: TriangulateIO) -> tuple[CTriangulateIO, list[np.ndarray]]:
    """The C struct for ``tio`` as input, pointing into its arrays, and the arrays to keep alive
    for the duration of the call. Checks that the per-item arrays match their item counts (the
    library trusts the counts, as Triangle does)."""
    arrays = input_arrays(tio)
    return input_struct(arrays), [array for array in arrays.values() if array.size]


def input_arrays(tio: TriangulateIO) -> dict[str, np.ndarray]:
    """The input fields of ``tio`` as the library reads them (field name -> array)."""
    return {name: normalize(name, getattr(tio, name)) for name in INPUT_FIELDS}


def from_c(c: CTriangulateIO) -> TriangulateIO:
    """Copies every array that the library wrote into ``c`` into a new ``TriangulateIO``.

    The pointers stay in ``c``: release them with :func:`free_c`."""
    return TriangulateIO._from_arrays(read_output(c))


def free_c(c: CTriangulateIO, free: Any) -> None:
    """Releases the arrays the library allocated in output struct ``c`` with ``free`` (the
    library's ``trifree``), except ``holelist``/``regionlist``, which alias the input's arrays.
    Clears the released pointers so that a second call is harmless."""
    values = list(_LAYOUT.unpack_from(c))
    for name in FIELDS:
        index = _INDEX[name]
        pointer = values[index]
        if pointer and name not in ALIASED_FIELDS:
            free(pointer)
            values[index] = 0
    _LAYOUT.pack_into(c, 0, *values)
