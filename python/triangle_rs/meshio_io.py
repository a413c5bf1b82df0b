"""``to_meshio(out)``: a mesh as a ``meshio.Mesh``, to write VTK (``.vtu``), Gmsh (``.msh``),
XDMF and the other formats meshio knows in one line::

    triangle_rs.to_meshio(out).write("mesh.vtu")

meshio is an optional dependency (``pip install "./python[meshio]"``), imported on the first call.
"""

from __future__ import annotations

from typing import Any, Mapping, Union

import numpy as np

from .triangulateio import TriangulateIO

#: Triangle's ``o2`` order puts the mid-edge node opposite corner i at position 3 + i; meshio's
#: (VTK's) ``triangle6`` wants the midpoints of edges 01, 12, 20: opposite corners 2, 0, 1.
_TRIANGLE6_ORDER = [0, 1, 2, 5, 3, 4]


def _fields(mesh: Union[TriangulateIO, Mapping[str, Any]]) -> dict[str, np.ndarray]:
    """points, triangles, point markers and attributes, triangle attributes, as arrays."""
    if isinstance(mesh, TriangulateIO):
        return {
            "points": mesh.pointlist,
            "triangles": mesh.trianglelist,
            "point_markers": mesh.pointmarkerlist,
            "point_attributes": mesh.pointattributelist,
            "triangle_attributes": mesh.triangleattributelist,
        }
    if isinstance(mesh, Mapping):
        keys = {
            "points": "vertices",
            "triangles": "triangles",
            "point_markers": "vertex_markers",
            "point_attributes": "vertex_attributes",
            "triangle_attributes": "triangle_attributes",
        }
        return {name: np.asarray(mesh[key]) if key in mesh else np.empty((0,)) for name, key in keys.items()}
    raise TypeError(f"to_meshio takes a TriangulateIO or a dict of the PyPI triangle package's keys, got {type(mesh).__name__}")


def _columns(name: str, values: np.ndarray, rows: int) -> dict[str, np.ndarray]:
    """One 1-D array per column (Gmsh's writer wants scalars), named ``name_0``, ``name_1``..."""
    if values.size == 0:
        return {}
    table = values.reshape(rows, -1)
    return {f"{name}_{k}": np.ascontiguousarray(table[:, k]) for k in range(table.shape[1])}


def to_meshio(mesh: Union[TriangulateIO, Mapping[str, Any]], *, three_d: bool = True) -> Any:
    """A ``meshio.Mesh`` of the triangles of ``mesh`` (a ``TriangulateIO`` or a dict with the PyPI
    package's keys).

    Cells are ``triangle`` (3 corners) or ``triangle6`` (``o2``, reordered to meshio's order).
    Point data: ``point_markers`` and ``point_attribute_<k>``; cell data: ``triangle_attribute_<k>``
    (for example the region attribute of ``A``). Points get a zero z coordinate unless
    ``three_d=False`` (VTK and Gmsh store 3-D points).
    """
    import meshio

    fields = _fields(mesh)
    points = np.asarray(fields["points"], dtype=np.float64).reshape(-1, 2)
    triangles = np.asarray(fields["triangles"], dtype=np.int64)
    if triangles.size == 0:
        raise ValueError("to_meshio needs triangles: the mesh has none")
    triangles = triangles.reshape(len(triangles), -1)
    if triangles.shape[1] == 6:
        cell_type, triangles = "triangle6", triangles[:, _TRIANGLE6_ORDER]
    elif triangles.shape[1] == 3:
        cell_type = "triangle"
    else:
        raise ValueError(f"triangles must have 3 or 6 corners, got {triangles.shape[1]}")
    if three_d:
        points = np.column_stack([points, np.zeros(len(points))])
    point_data: dict[str, np.ndarray] = {}
    markers = np.asarray(fields["point_markers"])
    if markers.size:
        point_data["point_markers"] = markers.reshape(-1).astype(np.int32)
    point_data.update(_columns("point_attribute", np.asarray(fields["point_attributes"], dtype=np.float64), len(points)))
    cell_data = {
        name: [column]
        for name, column in _columns("triangle_attribute", np.asarray(fields["triangle_attributes"], dtype=np.float64), len(triangles)).items()
    }
    return meshio.Mesh(points, [(cell_type, triangles)], point_data=point_data, cell_data=cell_data)
