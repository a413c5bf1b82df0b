"""The drop-in API of the PyPI `triangle` package (TRIANGLE-REFERENCE.md 5), on its own test
cases, compared as sets (triangle-rs does not reproduce Triangle's element order)."""

import numpy as np
import pytest

import triangle_rs as triangle

from helpers import canonical_triangles, signed_areas, undirected

SQUARE = [[0, 0], [0, 1], [1, 1], [1, 0]]
#: A 3 x 3 square with a square hole; its region point lies in the ring (area bound 0.1).
PSLG = {
    "vertices": [[0, 0], [3, 0], [3, 3], [0, 3], [1, 1], [2, 1], [2, 2], [1, 2]],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]],
    "segment_markers": [1, 1, 1, 1, 2, 2, 2, 2],
    "holes": [[1.5, 1.5]],
    "regions": [[0.5, 0.5, 3.0, 0.1]],
}
FIVE_POINTS = [[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]]


def test_delaunay():
    triangles = triangle.delaunay(FIVE_POINTS)
    assert triangles.dtype == np.int32 and triangles.shape == (4, 3)
    assert canonical_triangles(triangles) == canonical_triangles([[1, 0, 2], [2, 4, 3], [4, 2, 0], [2, 3, 1]])


def test_convex_hull():
    segments = triangle.convex_hull(SQUARE)
    assert segments.dtype == np.int32 and segments.shape == (4, 2)
    assert undirected(segments) == undirected([[3, 0], [2, 3], [1, 2], [0, 1]])


def test_voronoi():
    vertices, edges, ray_origins, ray_directions = triangle.voronoi(FIVE_POINTS)
    assert vertices.dtype == np.float64 and vertices.shape == (4, 2)
    assert edges.dtype == np.int32 and edges.shape == (4, 2)
    assert ray_origins.dtype == np.int32 and ray_origins.shape == (4,)
    assert ray_directions.shape == (4, 2)
    position = [tuple(v) for v in vertices.round(12).tolist()]
    assert set(position) == {(0.0, 0.5), (1.0, 0.5), (0.5, 0.0), (0.5, 1.0)}
    # Same edges and rays as the PyPI package's, by position rather than by number.
    assert {frozenset((position[a], position[b])) for a, b in edges} == {
        frozenset(pair)
        for pair in [((0, 0.5), (0.5, 0)), ((0, 0.5), (0.5, 1)), ((1, 0.5), (0.5, 0)), ((1, 0.5), (0.5, 1))]
    }
    assert {(position[o], tuple(d)) for o, d in zip(ray_origins, ray_directions.round(12).tolist())} == {
        ((0.0, 0.5), (-1.0, 0.0)),
        ((1.0, 0.5), (1.0, 0.0)),
        ((0.5, 0.0), (0.0, -1.0)),
        ((0.5, 1.0), (0.0, 1.0)),
    }


def test_triangulate_returns_two_dimensional_arrays_of_the_present_fields():
    out = triangle.triangulate({"vertices": FIVE_POINTS})
    assert sorted(out) == ["triangles", "vertex_markers", "vertices"]
    assert out["vertices"].dtype == np.float64 and out["vertices"].shape == (5, 2)
    assert out["vertex_markers"].dtype == np.int32 and out["vertex_markers"].shape == (5, 1)
    assert out["vertex_markers"].ravel().tolist() == [1, 1, 0, 1, 1]
    assert out["triangles"].dtype == np.int32 and out["triangles"].shape == (4, 3)
    out = triangle.triangulate({"vertices": FIVE_POINTS}, "cne")
    assert {"segments", "segment_markers", "neighbors", "edges", "edge_markers"} <= set(out)
    assert out["segment_markers"].shape == (4, 1) and out["edge_markers"].shape == (8, 1)
    assert out["neighbors"].shape == (4, 3)


def test_triangulate_square_with_maximum_area():
    # The PyPI package's test_triangulate: 'a0.2' on the square. Triangle gives the centre and
    # the four edge midpoints; triangle-rs may place its Steiner points elsewhere, so check what
    # the switch promises.
    out = triangle.triangulate({"vertices": SQUARE}, "a0.2")
    areas = signed_areas(out["vertices"], out["triangles"])
    assert np.all(areas > 0) and np.all(areas <= 0.2 + 1e-12) and np.isclose(areas.sum(), 1.0)
    assert out["vertices"][:4].tolist() == SQUARE
    on_boundary = np.any((out["vertices"] == 0) | (out["vertices"] == 1), axis=1)
    assert out["vertex_markers"].ravel().tolist() == on_boundary.astype(int).tolist()


def test_pslg_with_hole_and_regions_keys():
    out = triangle.triangulate(PSLG, "pA")
    assert out["holes"].tolist() == [[1.5, 1.5]]
    assert out["regions"].shape == (1, 4)
    assert out["triangle_attributes"].shape == (len(out["triangles"]), 1)
    assert np.isclose(signed_areas(out["vertices"], out["triangles"]).sum(), 8.0)


def test_one_dimensional_marker_input_is_accepted():
    out = triangle.triangulate({"vertices": FIVE_POINTS, "vertex_markers": [7, 7, 7, 7, 7]})
    assert out["vertex_markers"].ravel().tolist() == [7] * 5
    out = triangle.triangulate({"vertices": FIVE_POINTS, "vertex_markers": [[7], [7], [7], [7], [7]]})
    assert out["vertex_markers"].ravel().tolist() == [7] * 5


def test_unknown_key_raises_key_error():
    with pytest.raises(KeyError):
        triangle.triangulate({"vertices": FIVE_POINTS, "vertexes": FIVE_POINTS})


def test_existing_code_runs_with_the_import_changed():
    # The PyPI package's documented usage, unchanged but for the import line.
    import triangle_rs as tr

    A = dict(vertices=np.array(((0, 0), (1, 0), (1, 1), (0, 1))))
    B = tr.triangulate(A)
    assert len(B["triangles"]) == 2
    assert isinstance(tr.delaunay(np.array(FIVE_POINTS)), np.ndarray)


def test_refinement_with_per_triangle_maximum_areas():
    # The PyPI package's `ra` with `triangle_max_area` (one bound per input triangle; negative:
    # none): triangles inside the bounded input triangle obey its bound.
    first = triangle.triangulate({"vertices": SQUARE})
    assert first["triangles"].shape == (2, 3)
    tri = {"vertices": first["vertices"], "triangles": first["triangles"], "triangle_max_area": [0.02, -1.0]}
    out = triangle.triangulate(tri, "ra")
    areas = signed_areas(out["vertices"], out["triangles"])
    assert np.all(areas > 0) and np.isclose(areas.sum(), 1.0)
    bounded = first["vertices"][first["triangles"][0]]
    centroids = out["vertices"][out["triangles"]].mean(axis=1)

    def inside(p):
        a, b, c = bounded
        cross = lambda u, v, w: (v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0])  # noqa: E731
        return cross(a, b, p) > 0 and cross(b, c, p) > 0 and cross(c, a, p) > 0

    in_bounded = np.array([inside(p) for p in centroids])
    assert in_bounded.sum() >= 0.5 / 0.02
    assert np.all(areas[in_bounded] <= 0.02 + 1e-12)
    assert len(out["triangles"]) > len(first["triangles"])


# --- the same output keys as the PyPI package for the same switches ------------------------------

WITH_ATTRIBUTES = {"vertices": SQUARE, "vertex_attributes": [[1], [2], [3], [4]], "vertex_markers": [5, 6, 7, 8]}
KEY_CASES = [
    ("square", s) for s in ["", "a0.2", "q", "c", "cne", "v", "o2", "j", "B", "P", "N", "E", "I", "cP"]
] + [("attributes", s) for s in ["", "q", "ca0.1"]] + [
    ("pslg", s) for s in ["", "p", "pA", "pq", "pc", "pne", "pP", "cP", "pcP", "pa0.1", "pAa", "pv", "c", "pq30a0.05AQ"]
] + [("face.1", s) for s in ["r", "rc", "rp", "rpc", "rq", "rpq", "rpP", "rpa100"]] + [
    ("bbox.1", s) for s in ["ra", "rpa", "rpa0.2"]
] + [("la", s) for s in ["pqa", "pqaA"]]  # fmt: skip


def _input(name, pypi):
    if name == "square":
        return {"vertices": SQUARE}
    if name == "attributes":
        return WITH_ATTRIBUTES
    if name == "pslg":
        return PSLG
    return pypi.get_data(name)


@pytest.fixture(scope="module")
def pypi():
    import triangle as real

    assert not real.__name__.startswith("triangle_rs")
    return real


@pytest.mark.parametrize("name, opts", KEY_CASES, ids=[f"{n}-{o or 'none'}" for n, o in KEY_CASES])
def test_output_keys_match_the_pypi_package(name, opts, pypi):
    tri = _input(name, pypi)
    theirs = pypi.triangulate(tri, opts)
    ours = triangle.triangulate(tri, opts)
    assert sorted(ours) == sorted(theirs)
    # Holes and regions come back as given (Triangle hands the input's arrays back), `r` included.
    for key in ("holes", "regions"):
        if key in theirs:
            assert ours[key].tolist() == theirs[key].tolist() == np.asarray(tri[key], dtype=float).tolist()
    for key, array in ours.items():
        assert array.ndim == 2 and array.dtype.kind == theirs[key].dtype.kind, key


# --- switch u without a callback: Triangle's built-in test ---------------------------------------


def _builtin_unsuitable(origin, dest, apex):
    """Triangle's built-in ``u`` test as observed on the PyPI package: the longest edge, squared,
    above 0.02 + 0.05 (x^2 + y^2) of the origin (the first vertex the test is given)."""
    longest = max(
        (p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2 for p, q in ((origin, dest), (dest, apex), (apex, origin))
    )
    return longest > 0.05 * (origin[0] ** 2 + origin[1] ** 2) + 0.02


def _passes_from_some_corner(out):
    """Every triangle passes the built-in test with one of its corners as origin (which corner
    Triangle gives as origin is its own affair)."""
    points = out["vertices"]
    for a, b, c in points[out["triangles"]]:
        assert not (_builtin_unsuitable(a, b, c) and _builtin_unsuitable(b, c, a) and _builtin_unsuitable(c, a, b))


@pytest.mark.parametrize("shift", [(0.0, 0.0), (-1.0, -1.0)])
def test_u_without_a_callback_applies_the_built_in_test(shift, pypi):
    vertices = np.array(SQUARE, dtype=float) * (1 if shift == (0.0, 0.0) else 2) + shift
    tri = {"vertices": vertices, "segments": [[0, 1], [1, 2], [2, 3], [3, 0]]}
    domain = 1.0 if shift == (0.0, 0.0) else 4.0
    theirs = pypi.triangulate(tri, "pu")
    ours = triangle.triangulate(tri, "pu")
    # The unit square: Triangle 117 triangles, ours 137; [-1, 1]^2: 492 and 566 (the order of the
    # splits, and which corner a triangle's origin is, differ).
    assert len(theirs["triangles"]) in (117, 492)
    assert abs(len(ours["triangles"]) - len(theirs["triangles"])) <= 0.2 * len(theirs["triangles"])
    for out in (theirs, ours):
        _passes_from_some_corner(out)
        areas = signed_areas(out["vertices"], out["triangles"])
        assert np.all(areas > 0) and np.isclose(areas.sum(), domain)
    # The Triangulate.jl-style API, without a callback, gives the same mesh.
    tio = triangle.TriangulateIO(pointlist=vertices, segmentlist=np.array(tri["segments"], dtype=np.int32))
    out, _ = triangle.triangulate("pQu", tio)
    assert out.numberoftriangles == len(ours["triangles"])
    # A callback replaces the built-in test.
    assert len(triangle.triangulate(tri, "pu", unsuitable=lambda *_: False)["triangles"]) == 2


def test_the_built_in_threshold_matches_the_pypi_package_bit_for_bit(pypi):
    # One triangle given with `r`: its first corner is the origin the test sees, in both.
    for ox, oy in [(0.0, 0.0), (1.0, 0.3), (-2.7, 1.1), (13.1, 7.7)]:
        threshold = np.sqrt(0.05 * (ox * ox + oy * oy) + 0.02)
        for ulps in range(-4, 5):
            h = threshold
            for _ in range(abs(ulps)):
                h = np.nextafter(h, np.inf if ulps > 0 else 0.0)
            points = [[ox, oy], [ox, oy + h], [ox - 0.05 * h, oy + 0.5 * h]]
            expected = _builtin_unsuitable(*points)
            tri = {"vertices": points, "triangles": [[0, 1, 2]]}
            assert (len(pypi.triangulate(tri, "ru")["triangles"]) > 1) == expected, (points, ulps)
            assert (len(triangle.triangulate(tri, "ru")["triangles"]) > 1) == expected, (points, ulps)
