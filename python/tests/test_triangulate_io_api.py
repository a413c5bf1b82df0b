"""The Triangulate.jl-style API: triangulate(switches, TriangulateIO) -> (out, vorout)."""

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateError, TriangulateIO, triangulate

from helpers import (
    assert_delaunay_of_points,
    canonical_triangles,
    convex_hull_area,
    random_points,
    signed_areas,
    triangle_edges,
    undirected,
)

SQUARE_AND_CENTRE = np.array([[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]], dtype=float)


def test_delaunay_of_the_five_points():
    out, vorout = triangulate("Q", TriangulateIO(pointlist=SQUARE_AND_CENTRE))
    assert canonical_triangles(out.trianglelist) == canonical_triangles([[1, 0, 2], [2, 4, 3], [4, 2, 0], [2, 3, 1]])
    assert out.pointlist.tolist() == SQUARE_AND_CENTRE.tolist()
    assert out.trianglelist.dtype == np.int32 and out.trianglelist.shape == (4, 3)
    # Without `v` the Voronoi output stays empty.
    assert vorout.numberofpoints == 0 and vorout.numberofedges == 0


def test_random_point_set_gives_a_delaunay_triangulation():
    points = random_points(seed=1, n=300)
    out, _ = triangulate("Q", TriangulateIO(pointlist=points))
    assert out.numberofpoints == 300
    assert_delaunay_of_points(points, out.trianglelist)


def test_indices_are_zero_based_even_without_z():
    points = random_points(seed=2, n=20)
    out, _ = triangulate("Q", TriangulateIO(pointlist=points))
    assert out.trianglelist.min() == 0 and out.trianglelist.max() == 19


def test_markers_neighbours_and_edges():
    points = random_points(seed=3, n=40)
    out, _ = triangulate("Qne", TriangulateIO(pointlist=points))
    triangles = out.trianglelist
    # Neighbour i lies opposite corner i, and shares that edge.
    for t, row in enumerate(out.neighborlist):
        for i, neighbour in enumerate(row):
            edge = {triangles[t][(i + 1) % 3], triangles[t][(i + 2) % 3]}
            if neighbour == -1:
                continue
            assert edge <= set(triangles[neighbour]) and neighbour != t
    # Every edge once; markers 1 exactly on the hull (the edges with one triangle).
    assert undirected(out.edgelist) == triangle_edges(triangles)
    assert len(out.edgelist) == len(triangle_edges(triangles))
    counts = {}
    for t in triangles:
        for e in undirected([(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]):
            counts[e] = counts.get(e, 0) + 1
    for edge, marker in zip(out.edgelist, out.edgemarkerlist):
        assert marker == (1 if counts[frozenset(edge.tolist())] == 1 else 0)
    hull_vertices = {v for e, n in counts.items() if n == 1 for v in e}
    assert set(np.flatnonzero(out.pointmarkerlist == 1)) == hull_vertices


def test_convex_hull_segments():
    points = random_points(seed=4, n=50)
    out, _ = triangulate("cQ", TriangulateIO(pointlist=points))
    assert len(undirected(out.segmentlist)) == len(out.segmentlist) >= 3
    assert np.all(out.segmentmarkerlist == 1)
    # The segments form one closed loop through hull vertices enclosing the hull's area.
    degree = np.bincount(out.segmentlist.ravel(), minlength=50)
    assert set(degree[degree > 0]) == {2}
    ordered = [out.segmentlist[0][0]]
    nexts = {}
    for a, b in out.segmentlist:
        nexts.setdefault(a, []).append(b)
        nexts.setdefault(b, []).append(a)
    previous = None
    while True:
        current = ordered[-1]
        candidates = [v for v in nexts[current] if v != previous]
        following = candidates[0]
        if following == ordered[0]:
            break
        previous = current
        ordered.append(following)
    polygon = points[ordered]
    area = 0.5 * abs(np.dot(polygon[:, 0], np.roll(polygon[:, 1], -1)) - np.dot(polygon[:, 1], np.roll(polygon[:, 0], -1)))
    assert np.isclose(area, convex_hull_area(points))


def test_voronoi_output():
    out, vorout = triangulate("vQ", TriangulateIO(pointlist=SQUARE_AND_CENTRE))
    assert vorout.numberofpoints == out.numberoftriangles == 4
    vertices = {tuple(p) for p in vorout.pointlist.round(12).tolist()}
    assert vertices == {(0.0, 0.5), (1.0, 0.5), (0.5, 0.0), (0.5, 1.0)}
    finite = vorout.edgelist[:, 1] != -1
    assert finite.sum() == 4 and (~finite).sum() == 4
    assert np.all(vorout.normlist[finite] == 0)
    # Each Voronoi vertex is its triangle's circumcentre.
    for t, centre in zip(out.trianglelist, vorout.pointlist):
        distances = np.linalg.norm(out.pointlist[t] - centre, axis=1)
        assert np.allclose(distances, distances[0])


def test_point_attributes_and_markers_pass_through():
    points = random_points(seed=5, n=10)
    attributes = np.column_stack([np.arange(10.0), np.arange(10.0) ** 2])
    markers = np.arange(10, 20)
    out, _ = triangulate("Q", TriangulateIO(pointlist=points, pointattributelist=attributes, pointmarkerlist=markers))
    assert out.pointattributelist.tolist() == attributes.tolist()
    assert out.pointmarkerlist.tolist() == markers.tolist()


def test_suppression_switches():
    points = random_points(seed=6, n=10)
    out, _ = triangulate("QB", TriangulateIO(pointlist=points))
    assert out.numberoftriangles > 0 and out.pointmarkerlist.size == 0
    out, _ = triangulate("QN", TriangulateIO(pointlist=points))
    assert out.pointlist.size == 0 and out.numberoftriangles > 0
    out, _ = triangulate("QE", TriangulateIO(pointlist=points))
    assert out.trianglelist.size == 0 and out.numberofpoints == 10


def test_every_algorithm_gives_the_same_triangles():
    points = random_points(seed=7, n=200)
    reference = canonical_triangles(triangulate("Q", TriangulateIO(pointlist=points))[0].trianglelist)
    for switches in ("Qi", "QF", "Ql"):
        out, _ = triangulate(switches, TriangulateIO(pointlist=points))
        assert canonical_triangles(out.trianglelist) == reference, switches


def test_exponent_in_switches_is_a_number():
    # Triangle would read "a1e-2" as area 1 plus the `e` switch; triangle-rs reads 0.01.
    tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [1, 1], [0, 1]])
    out, _ = triangulate("Qa1e-2", tio)
    assert out.edgelist.size == 0
    assert np.all(signed_areas(out.pointlist, out.trianglelist) <= 0.01 + 1e-12)


def test_segments_need_p_and_describe_a_domain():
    tio = TriangulateIO(
        pointlist=[[0, 0], [1, 0], [1, 1], [0.6, 0.6], [0, 1]],
        segmentlist=[[0, 1], [1, 2], [2, 3], [3, 4], [4, 0]],
        segmentmarkerlist=[1, 2, 3, 4, 5],
    )
    out, _ = triangulate("pQ", tio)
    assert out.numberoftriangles == 3
    assert np.isclose(signed_areas(out.pointlist, out.trianglelist).sum(), 1 - 0.5 * 0.4)
    assert {tuple(sorted(s)): m for s, m in zip(out.segmentlist.tolist(), out.segmentmarkerlist)} == {
        (0, 1): 1, (1, 2): 2, (2, 3): 3, (3, 4): 4, (0, 4): 5,
    }


def test_holes_and_regions_are_copied_back_with_p():
    tio = TriangulateIO(
        pointlist=[[0, 0], [3, 0], [3, 3], [0, 3], [1, 1], [2, 1], [2, 2], [1, 2]],
        segmentlist=[[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]],
        holelist=[[1.5, 1.5]],
        regionlist=[[0.5, 0.5, 7.0, -1.0]],
    )
    out, _ = triangulate("pAQ", tio)
    assert out.holelist.tolist() == [[1.5, 1.5]]
    assert out.regionlist.tolist() == [[0.5, 0.5, 7.0, -1.0]]
    assert np.isclose(signed_areas(out.pointlist, out.trianglelist).sum(), 9 - 1)
    assert np.all(out.triangleattributelist[:, 0] == 7.0)


def test_quadratic_triangles_have_six_nodes():
    points = random_points(seed=8, n=12)
    out, _ = triangulate("Qo2", TriangulateIO(pointlist=points))
    assert out.trianglelist.shape[1] == 6
    corners = out.pointlist[out.trianglelist[:, :3]]
    for i in range(3):
        # Node 3 + i lies opposite corner i, at the midpoint of the other two.
        midpoint = (corners[:, (i + 1) % 3] + corners[:, (i + 2) % 3]) / 2
        assert np.allclose(out.pointlist[out.trianglelist[:, 3 + i]], midpoint)


def test_refining_a_mesh():
    square = TriangulateIO(pointlist=[[0, 0], [1, 0], [1, 1], [0, 1]])
    first, _ = triangulate("Q", square)
    out, _ = triangulate("rQa0.05", first)
    assert np.all(signed_areas(out.pointlist, out.trianglelist) <= 0.05 + 1e-12)
    assert np.isclose(signed_areas(out.pointlist, out.trianglelist).sum(), 1.0)


def test_output_can_be_fed_back_as_input():
    points = random_points(seed=9, n=30)
    first, _ = triangulate("Q", TriangulateIO(pointlist=points))
    again, _ = triangulate("Q", first)
    assert canonical_triangles(again.trianglelist) == canonical_triangles(first.trianglelist)


def test_numberof_functions():
    out, _ = triangulate("cQ", TriangulateIO(pointlist=SQUARE_AND_CENTRE))
    assert triangle_rs.numberofpoints(out) == 5
    assert triangle_rs.numberoftriangles(out) == 4
    assert triangle_rs.numberofsegments(out) == 4
    assert "trianglelist=(4, 3)" in repr(out)


def test_arguments_are_checked():
    tio = TriangulateIO(pointlist=SQUARE_AND_CENTRE)
    with pytest.raises(TypeError):
        triangulate(b"Q", tio)
    with pytest.raises(TypeError):
        triangulate("Q", {"pointlist": SQUARE_AND_CENTRE})
    with pytest.raises(TypeError):
        triangle_rs.core.triangulate("Q", SQUARE_AND_CENTRE)
    with pytest.raises(ValueError, match="switch 'u'"):
        triangulate("Q", tio, unsuitable=lambda *args: False)


def test_refining_second_order_triangles_drops_their_mid_nodes():
    # As Triangle: `r` on six-node triangles uses their corners and leaves the mid-edge nodes out.
    points = random_points(seed=8, n=12)
    o2, _ = triangulate("Qo2", TriangulateIO(pointlist=points))
    assert o2.trianglelist.shape[1] == 6 and o2.numberofpoints > 12
    out, _ = triangulate("rQ", o2)
    assert out.numberofpoints == 12 and out.pointlist.tolist() == points.tolist()
    assert canonical_triangles(out.trianglelist) == canonical_triangles(o2.trianglelist[:, :3])
    refined, _ = triangulate("rQa0.01", o2)
    assert np.all(signed_areas(refined.pointlist, refined.trianglelist) <= 0.01 + 1e-12)
    # No leftover mid-edge node: every output point is a corner of some triangle.
    assert set(refined.trianglelist.ravel().tolist()) == set(range(refined.numberofpoints))
