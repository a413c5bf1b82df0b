"""``to_meshio``: meshes as ``meshio.Mesh``, written to VTK (.vtu) and Gmsh (.msh) and read back."""

import meshio  # scripts/setup-python.sh installs it (the package's [meshio] extra)
import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateIO

TWO_REGIONS = {
    "vertices": [[0, 0], [2, 0], [2, 1], [0, 1], [1, 0], [1, 1]],
    "segments": [[0, 4], [4, 1], [1, 2], [2, 5], [5, 3], [3, 0], [4, 5]],
    "vertex_attributes": [[0.0], [2.0], [2.0], [0.0], [1.0], [1.0]],
    "regions": [[0.5, 0.5, 1.0, 0.0], [1.5, 0.5, 2.0, 0.0]],
}


def test_triangles_markers_and_attributes_round_trip_through_vtu_and_msh(tmp_path):
    out = triangle_rs.triangulate(TWO_REGIONS, "pq30a0.05A")
    mesh = triangle_rs.to_meshio(out)
    assert mesh.cells[0].type == "triangle"
    np.testing.assert_array_equal(mesh.cells[0].data, out["triangles"])
    np.testing.assert_array_equal(mesh.points[:, :2], out["vertices"])
    assert np.all(mesh.points[:, 2] == 0)
    np.testing.assert_array_equal(mesh.point_data["point_markers"], out["vertex_markers"].ravel())
    np.testing.assert_array_equal(mesh.point_data["point_attribute_0"], out["vertex_attributes"][:, 0])
    # Region attribute of `A`: 1 left of x = 1, 2 right of it.
    centroid_x = out["vertices"][out["triangles"]].mean(axis=1)[:, 0]
    np.testing.assert_array_equal(mesh.cell_data["triangle_attribute_0"][0], np.where(centroid_x < 1, 1.0, 2.0))
    for name in ("mesh.vtu", "mesh.msh"):
        mesh.write(tmp_path / name)
        back = meshio.read(tmp_path / name)
        np.testing.assert_allclose(back.points[:, :2], out["vertices"])
        (triangles,) = [block.data for block in back.cells if block.type == "triangle"]
        np.testing.assert_array_equal(triangles, out["triangles"])
    back = meshio.read(tmp_path / "mesh.vtu")
    np.testing.assert_array_equal(back.cell_data["triangle_attribute_0"][0], mesh.cell_data["triangle_attribute_0"][0])


def test_quadratic_triangles_are_reordered_to_meshio_order():
    out, _ = triangle_rs.triangulate("o2", TriangulateIO(pointlist=[[0, 0], [2, 0], [1, 1.5], [2, 2], [0, 2]]))
    mesh = triangle_rs.to_meshio(out, three_d=False)
    assert mesh.cells[0].type == "triangle6" and mesh.points.shape[1] == 2
    corners = mesh.points[mesh.cells[0].data]
    # meshio (VTK): nodes 3, 4, 5 are the midpoints of edges 01, 12, 20.
    for node, (a, b) in zip((3, 4, 5), ((0, 1), (1, 2), (2, 0))):
        np.testing.assert_allclose(corners[:, node], 0.5 * (corners[:, a] + corners[:, b]))


def test_a_mesh_without_triangles_is_refused():
    with pytest.raises(ValueError, match="triangles"):
        triangle_rs.to_meshio({"vertices": [[0, 0], [1, 0], [0, 1]]})
    with pytest.raises(TypeError):
        triangle_rs.to_meshio([[0, 0], [1, 0], [0, 1]])
