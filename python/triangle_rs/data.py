"""Triangle's file formats as the PyPI ``triangle`` package reads them: ``loads`` (from strings),
``load`` (from a directory) and ``get_data`` (a named example), with the same dictionary keys.

``get_data(name)`` reads the example from the data directory of an installed PyPI ``triangle``
package when there is one (Triangle's own example files, which this project does not ship), and
otherwise from the examples of this package's own making in ``triangle_rs/data/`` (same names,
geometry drawn for this project; see ``data/README.md``).

The readers follow the PyPI package's conventions, which differ from Triangle's in places:

* numbering: if the first vertex is numbered 0 the indices are kept, else 1 is subtracted;
* markers and per-item values are ``(n, 1)`` arrays;
* a region line of ``.poly`` with four numbers (``i x y a``, as in Triangle's ``la.poly``) gives
  the row ``(x, y, 0, a)``: its last number is the maximum area; with five (``i x y attribute
  area``, Triangle's documented form) the row is ``(x, y, attribute, area)``;
* a ``.edge`` file's rays (``i origin -1 dx dy``) go to ``ray_origins`` and ``ray_directions``;
* a ``.neigh`` file gives ``triangle_neighbors``.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any, Optional

import numpy as np

#: The file extensions ``load`` reads, in the order ``loads`` parses them.
EXTENSIONS = ("node", "ele", "poly", "area", "edge", "neigh")

OWN_DATA_DIRECTORY = Path(__file__).resolve().parent / "data"


class _Tokens:
    """The numbers of a Triangle file, comments (``#`` to the end of the line) removed."""

    def __init__(self, text: str):
        self.items = [token for line in text.splitlines() for token in line.split("#", 1)[0].split()]
        self.position = 0

    def remaining(self) -> int:
        return len(self.items) - self.position

    def take(self, count: int, what: str) -> list[str]:
        if count < 0 or self.remaining() < count:
            raise ValueError(f"truncated Triangle file: {what} needs {count} more numbers, {self.remaining()} left")
        start = self.position
        self.position += count
        return self.items[start : self.position]

    def header(self, count: int, what: str) -> list[int]:
        return [int(float(value)) for value in self.take(count, what + " header")]

    def rows(self, count: int, width: int, what: str) -> np.ndarray:
        return np.array(self.take(count * width, what), dtype=object).reshape(count, width)


def _numbers(rows: np.ndarray, dtype: str) -> np.ndarray:
    # Through float64, as Triangle reads every number with strtod ("1.0" is a valid index).
    values = np.array(rows, dtype=np.float64)
    return values.astype(np.intc) if dtype == "intc" else values


class _Reader:
    """Parses the files of one example into the PyPI package's dictionary."""

    def __init__(self) -> None:
        self.data: dict[str, np.ndarray] = {}
        self.offset = 0  # 1 when the vertices are numbered from 1

    def indices(self, rows: np.ndarray) -> np.ndarray:
        return _numbers(rows, "intc") - self.offset

    def vertices(self, tokens: _Tokens) -> None:
        count, dimension, attributes, markers = tokens.header(4, "vertex")
        if count == 0:
            return
        rows = tokens.rows(count, 1 + dimension + attributes + markers, "vertices")
        self.offset = 0 if int(float(rows[0, 0])) == 0 else 1
        self.data["vertices"] = _numbers(rows[:, 1:3], "double")
        if attributes:
            self.data["vertex_attributes"] = _numbers(rows[:, 3 : 3 + attributes], "double")
        if markers:
            self.data["vertex_markers"] = _numbers(rows[:, 3 + attributes : 4 + attributes], "intc")

    def elements(self, tokens: _Tokens) -> None:
        count, corners, attributes = tokens.header(3, "triangle")
        if count == 0:
            return
        rows = tokens.rows(count, 1 + corners + attributes, "triangles")
        self.data["triangles"] = self.indices(rows[:, 1 : 1 + corners])
        if attributes:
            self.data["triangle_attributes"] = _numbers(rows[:, 1 + corners :], "double")

    def poly(self, tokens: _Tokens) -> None:
        self.vertices(tokens)
        count, markers = tokens.header(2, "segment")
        if count:
            rows = tokens.rows(count, 3 + markers, "segments")
            self.data["segments"] = self.indices(rows[:, 1:3])
            if markers:
                self.data["segment_markers"] = _numbers(rows[:, 3:4], "intc")
        if not tokens.remaining():
            return
        (count,) = tokens.header(1, "hole")
        if count:
            self.data["holes"] = _numbers(tokens.rows(count, 3, "holes")[:, 1:3], "double")
        if not tokens.remaining():
            return
        (count,) = tokens.header(1, "region")
        if count == 0:
            return
        if tokens.remaining() >= 5 * count:
            rows = _numbers(tokens.rows(count, 5, "regions")[:, 1:], "double")
        else:
            short = _numbers(tokens.rows(count, 4, "regions")[:, 1:], "double")
            rows = np.column_stack([short[:, :2], np.zeros(count), short[:, 2]])
        self.data["regions"] = rows

    def areas(self, tokens: _Tokens) -> None:
        (count,) = tokens.header(1, "area")
        if count:
            self.data["triangle_max_area"] = _numbers(tokens.rows(count, 2, "areas")[:, 1:2], "double")

    def edges(self, text: str) -> None:
        lines = [line.split("#", 1)[0].split() for line in text.splitlines()]
        lines = [line for line in lines if line]
        if not lines:
            return
        count, markers = (int(float(value)) for value in lines[0][:2])
        if count == 0:
            return
        body = lines[1 : 1 + count]
        finite = [line for line in body if len(line) == 3 + markers]
        rays = [line for line in body if len(line) == 5 + markers]
        self.data["edges"] = self.indices(np.array([line[1:3] for line in finite], dtype=object).reshape(-1, 2))
        self.data["ray_origins"] = self.indices(np.array([line[1:2] for line in rays], dtype=object).reshape(-1, 1))
        self.data["ray_directions"] = _numbers(np.array([line[3:5] for line in rays], dtype=object).reshape(-1, 2), "double")

    def neighbors(self, tokens: _Tokens) -> None:
        count, per_triangle = tokens.header(2, "neighbor")
        if count:
            rows = tokens.rows(count, 1 + per_triangle, "neighbors")
            neighbors = _numbers(rows[:, 1:], "intc")
            # -1 (no neighbour) stays -1 whatever the numbering.
            self.data["triangle_neighbors"] = np.where(neighbors >= 0, neighbors - self.offset, neighbors).astype(np.intc)


def loads(
    node: Optional[str] = None,
    ele: Optional[str] = None,
    poly: Optional[str] = None,
    area: Optional[str] = None,
    edge: Optional[str] = None,
    neigh: Optional[str] = None,
) -> dict[str, np.ndarray]:
    """The dictionary of the Triangle files given as strings (``.node``, ``.ele``, ``.poly``,
    ``.area``, ``.edge``, ``.neigh``), as the PyPI package's ``loads`` builds it.

    >>> d = loads(node="3 2 0 1\\n1 0 0 1\\n2 1 0 1\\n3 0 1 0\\n", ele="1 3 0\\n1 1 2 3\\n")
    >>> d["vertices"].shape, d["vertex_markers"].ravel().tolist(), d["triangles"].tolist()
    ((3, 2), [1, 1, 0], [[0, 1, 2]])
    """
    reader = _Reader()
    if node:
        reader.vertices(_Tokens(node))
    if ele:
        reader.elements(_Tokens(ele))
    if poly:
        reader.poly(_Tokens(poly))
    if area:
        reader.areas(_Tokens(area))
    if edge:
        reader.edges(edge)
    if neigh:
        reader.neighbors(_Tokens(neigh))
    return reader.data


def load(directory: "str | os.PathLike[str]", name: str) -> dict[str, np.ndarray]:
    """The dictionary of the files ``directory/name.node``, ``.ele``, ``.poly``, ``.area``,
    ``.edge`` and ``.neigh`` that exist (as the PyPI package's ``load``)."""
    texts: dict[str, Any] = {}
    for extension in EXTENSIONS:
        path = Path(directory) / f"{name}.{extension}"
        if path.exists():
            texts[extension] = path.read_text()
    return loads(**texts)


def pypi_data_directory() -> Optional[Path]:
    """The data directory of the installed PyPI ``triangle`` package, if there is one.

    Found through the installed distribution's metadata, not by importing ``triangle`` (which
    may be this package under that name)."""
    from importlib import metadata

    try:
        distribution = metadata.distribution("triangle")
    except metadata.PackageNotFoundError:
        return None
    directory = Path(str(distribution.locate_file("triangle/data")))
    return directory if directory.is_dir() else None


def data_directory() -> Path:
    """Where :func:`get_data` reads: the PyPI package's data directory, else this package's own."""
    return pypi_data_directory() or OWN_DATA_DIRECTORY


def get_data(name: str) -> dict[str, np.ndarray]:
    """The example ``name`` (``A``, ``box``, ``dots``, ``face``, ``face.1``, ``la``, ``spiral``,
    ``bbox.1``, ``diamond_02_00009``, ``diamond_02_00009.1.v``, ``ell``, ...) as a dictionary.

    Reads the installed PyPI ``triangle`` package's data directory when there is one, else the
    examples of this package's own making. Raises ``FileNotFoundError`` for an unknown name (the
    PyPI package returns an empty dictionary then, which only fails later)."""
    directory = data_directory()
    data = load(directory, name)
    if not data and not any((directory / f"{name}.{extension}").exists() for extension in EXTENSIONS):
        raise FileNotFoundError(f"no example named {name!r} in {directory}")
    return data


def show_data(name: str) -> None:
    """Plots the example ``name`` with :func:`triangle_rs.plot` and shows it (``pyplot``)."""
    import matplotlib.pyplot as plt

    from .pypi_plot import plot

    plot(plt.axes(), **get_data(name))
    plt.show()
