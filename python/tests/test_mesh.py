"""The keyword API: mesh(...) and the switch strings it builds."""

import numpy as np
import pytest

from triangle_rs import MeshResult, TriangulateIO, mesh, mesh_switches, triangulate

from helpers import canonical_triangles, random_points, signed_areas


def test_switches_for_the_issue_example():
    assert mesh_switches(pslg=True, min_angle=30, max_area=1e-3, conforming=True) == "QzpDq30.0a0.001"


def test_numbers_use_repr_with_exponents():
    assert mesh_switches(max_area=1e-5) == "Qza1e-05"
    assert mesh_switches(max_area=2.5e20) == "Qza2.5e+20"
    assert mesh_switches(min_angle=20.5, max_steiner=7) == "Qzq20.5S7"


def test_flags():
    switches = mesh_switches(convex_hull=True, voronoi=True, neighbors=True, edges=True, quadratic=True, jettison=True, unsuitable=True)
    assert switches == "Qzcuvneo2j"


def test_regions_add_attributes_and_regional_areas_only_when_some_area_is_positive():
    regions = np.array([[0.2, 0.2, 1.0, 0.01], [0.8, 0.2, 2.0, -1.0]])
    assert mesh_switches(pslg=True, regions=regions) == "QzpAa"
    assert mesh_switches(pslg=True, regions=regions[1:]) == "QzpA"


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf")])
def test_bad_areas_are_refused_before_the_call(bad):
    with pytest.raises(ValueError, match="max_area"):
        mesh_switches(max_area=bad)


def test_bad_angles_and_steiner_counts_are_refused():
    with pytest.raises(ValueError):
        mesh_switches(min_angle=-5)
    with pytest.raises(ValueError):
        mesh_switches(max_steiner=2.5)


def test_point_set_mesh_matches_the_switch_api():
    points = random_points(seed=11, n=60)
    result = mesh(points, neighbors=True, edges=True, voronoi=True)
    assert isinstance(result, MeshResult)
    out, vorout = result
    reference, _ = triangulate("Q", TriangulateIO(pointlist=points))
    assert canonical_triangles(out.trianglelist) == canonical_triangles(reference.trianglelist)
    assert out.neighborlist.shape == out.trianglelist.shape
    assert len(out.edgelist) > 0 and vorout.numberofpoints == out.numberoftriangles
    assert result.voronoi is vorout


def test_convex_hull_keyword():
    out, _ = mesh([[0, 0], [0, 1], [1, 1], [1, 0], [0.5, 0.5]], convex_hull=True)
    assert len(out.segmentlist) == 4


def test_domain_with_hole_quality_and_area():
    outer = [[0, 0], [1, 0], [1, 1], [0, 1]]
    inner = [[0.4, 0.4], [0.6, 0.4], [0.6, 0.6], [0.4, 0.6]]
    loop = lambda k: [[k + i, k + (i + 1) % 4] for i in range(4)]  # noqa: E731
    out, _ = mesh(outer + inner, segments=loop(0) + loop(4), holes=[[0.5, 0.5]], min_angle=25, max_area=0.01)
    areas = signed_areas(out.pointlist, out.trianglelist)
    assert np.all(areas > 0) and np.all(areas <= 0.01 + 1e-12)
    assert np.isclose(areas.sum(), 1 - 0.04)
    corners = out.pointlist[out.trianglelist]
    for i in range(3):
        u = corners[:, (i + 1) % 3] - corners[:, i]
        v = corners[:, (i + 2) % 3] - corners[:, i]
        cosine = (u * v).sum(axis=1) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1)
        assert np.all(np.degrees(np.arccos(np.clip(cosine, -1, 1))) >= 25 - 1e-6)


def test_regions_get_their_attributes():
    points = [[0, 0], [0.5, 0], [1, 0], [1, 1], [0.6, 0.6], [0, 1]]
    segments = [[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 0], [1, 4]]
    out, _ = mesh(points, segments=segments, regions=[[0.2, 0.2, 1.0, 0.01], [0.8, 0.2, 2.0, 0.05]])
    attributes = out.triangleattributelist[:, 0]
    assert set(attributes.tolist()) == {1.0, 2.0}
    areas = signed_areas(out.pointlist, out.trianglelist)
    assert np.all(areas[attributes == 1.0] <= 0.01 + 1e-12)
    assert np.all(areas[attributes == 2.0] <= 0.05 + 1e-12)
