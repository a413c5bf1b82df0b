"""Issue 12 through Python: `rp` keeps the holes, `A` without regions gives zero attributes,
extreme coordinates give a valid mesh (checked with exact rational arithmetic) or an error, and
indices out of range are errors, never a silently emptied mesh."""

from fractions import Fraction

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateError, TriangulateIO, triangulate

try:  # the PyPI package (Triangle itself), for the differential checks
    import triangle as pypi_triangle
except ImportError:  # pragma: no cover - setup-python.sh installs it
    pypi_triangle = None

SQUARE_WITH_HOLE = {
    "vertices": [[0, 0], [4, 0], [4, 4], [0, 4], [1, 1], [3, 1], [3, 3], [1, 3]],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]],
    "holes": [[2, 2]],
}


def exact_orientation(a, b, c):
    """The sign of the orientation of three float points, exactly (rationals)."""
    ax, ay, bx, by, cx, cy = (Fraction(float(v)) for v in (*a, *b, *c))
    det = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax)
    return (det > 0) - (det < 0)


def check_valid(out, vertices):
    points, triangles = out["vertices"], out["triangles"]
    # Input vertices come back bit for bit.
    assert np.array_equal(points[: len(vertices)].view(np.uint64), np.asarray(vertices, dtype=np.float64).view(np.uint64))
    assert np.all(np.isfinite(points))
    edges = set()
    for t in triangles:
        assert exact_orientation(points[t[0]], points[t[1]], points[t[2]]) > 0, t
        for k in range(3):
            edge = (int(t[k]), int(t[(k + 1) % 3]))
            assert edge not in edges, f"directed edge {edge} twice"
            edges.add(edge)


# --- 1. rp keeps the holes ---------------------------------------------------------------------


@pytest.mark.parametrize("opts", ["rpc", "rpq30", "rpa0.5", "rpqD", "rpen"])
def test_refining_with_p_keeps_the_holes(opts):
    first = triangle_rs.triangulate(SQUARE_WITH_HOLE, "p")
    assert np.array_equal(first["holes"], [[2, 2]])
    out = triangle_rs.triangulate(first, opts)
    assert np.array_equal(out["holes"], [[2, 2]])
    check_valid(out, first["vertices"])
    if pypi_triangle is not None:
        theirs = pypi_triangle.triangulate(pypi_triangle.triangulate(SQUARE_WITH_HOLE, "p"), opts)
        assert ("holes" in out) == ("holes" in theirs)


# --- 2. A without regions ----------------------------------------------------------------------


def test_region_attributes_without_regions_are_zero():
    out = triangle_rs.triangulate(SQUARE_WITH_HOLE, "pA")
    # Triangle (and so the PyPI package) gives no attribute here, against its manual; we give 0.
    assert out["triangle_attributes"].shape == (len(out["triangles"]), 1)
    assert np.all(out["triangle_attributes"] == 0)


# --- 3. extreme coordinates --------------------------------------------------------------------


def cloud(scale, seed):
    rng = np.random.default_rng(seed)
    corners = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float64)
    inner = 0.05 + 0.9 * rng.random((16, 2))
    return np.vstack([corners, inner]) * scale


@pytest.mark.parametrize("scale", [1e300, 1e-300, 1e150, 1e-150])
@pytest.mark.parametrize("opts", ["", "p", "pq", "pD", "v"])
def test_extreme_coordinates_give_a_valid_mesh(scale, opts):
    vertices = cloud(scale, 7)
    d = {"vertices": vertices, "segments": [[0, 1], [1, 2], [2, 3], [3, 0]]}
    out = triangle_rs.triangulate(d, opts)
    check_valid(out, vertices)
    # And refining the result (r) keeps it valid.
    again = triangle_rs.triangulate(out, "rpq")
    check_valid(again, out["vertices"])


def test_coordinates_beyond_the_bound_are_refused():
    vertices = np.vstack([cloud(1e300, 3), [[1e-300, 2e-300]]])
    with pytest.raises(TriangulateError, match="binary orders of magnitude.*at most 340"):
        triangle_rs.triangulate({"vertices": vertices}, "")


# --- 4. indices and seeds ----------------------------------------------------------------------


def test_one_based_segments_in_the_zero_based_api_are_an_error():
    d = dict(SQUARE_WITH_HOLE)
    d["segments"] = np.asarray(SQUARE_WITH_HOLE["segments"]) + 1  # a Julia-style list
    with pytest.raises(RuntimeError, match=r"Segment 6 has endpoint 8.*numbered 0 to 7"):
        triangle_rs.triangulate(d, "p")
    d["segments"] = [[0, 1], [1, -2], [2, 3]]
    with pytest.raises(TriangulateError, match="endpoint -2"):
        triangle_rs.triangulate(d, "p")


def test_triangle_corners_out_of_range_and_corner_counts_are_errors():
    mesh = triangle_rs.triangulate(SQUARE_WITH_HOLE, "p")
    bad = dict(mesh)
    bad["triangles"] = mesh["triangles"].copy()
    bad["triangles"][2, 1] = 8
    with pytest.raises(TriangulateError, match="Triangle 2 has corner 8"):
        triangle_rs.triangulate(bad, "r")
    four = TriangulateIO(pointlist=mesh["vertices"], trianglelist=np.hstack([mesh["triangles"], mesh["triangles"][:, :1]]))
    with pytest.raises(TriangulateError, match="3 or 6"):
        triangle_rs.triangulate("zrQ", four)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_holes_and_regions_are_errors(bad):
    d = dict(SQUARE_WITH_HOLE, holes=[[2, bad]])
    with pytest.raises(TriangulateError, match="Hole 0"):
        triangle_rs.triangulate(d, "p")
    d = dict(SQUARE_WITH_HOLE, regions=[[bad, 0.5, 1, 0.1]])
    with pytest.raises(TriangulateError, match="Region 0"):
        triangle_rs.triangulate(d, "pA")


def test_nan_region_area_is_an_error():
    d = dict(SQUARE_WITH_HOLE, regions=[[0.5, 0.5, 1, np.nan]])
    with pytest.raises(TriangulateError, match="Region 0 has a maximum area that is NaN"):
        triangle_rs.triangulate(d, "pa")
