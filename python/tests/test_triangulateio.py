"""TriangulateIO: dtypes, shapes and checks of the numpy fields, and the C struct conversion."""

import ctypes

import numpy as np
import pytest

from triangle_rs import TriangulateIO
from triangle_rs._library import CTriangulateIO
from triangle_rs.triangulateio import FIELDS, free_c, from_c, to_c


def test_struct_layout_matches_triangle_h():
    # Offsets of /usr/include/triangle.h on LP64 (TRIANGLE-REFERENCE.md 1.1).
    assert ctypes.sizeof(CTriangulateIO) == 168
    assert CTriangulateIO.numberofpoints.offset == 24
    assert CTriangulateIO.trianglelist.offset == 32
    assert CTriangulateIO.numberofcorners.offset == 68
    assert CTriangulateIO.segmentlist.offset == 80
    assert CTriangulateIO.holelist.offset == 104
    assert CTriangulateIO.regionlist.offset == 120
    assert CTriangulateIO.edgelist.offset == 136
    assert CTriangulateIO.normlist.offset == 152
    assert CTriangulateIO.numberofedges.offset == 160


def test_empty_fields_have_their_dtype_and_width():
    tio = TriangulateIO()
    assert tio.pointlist.shape == (0, 2) and tio.pointlist.dtype == np.float64
    assert tio.trianglelist.shape == (0, 3) and tio.trianglelist.dtype == np.int32
    assert tio.regionlist.shape == (0, 4)
    assert tio.pointmarkerlist.shape == (0,) and tio.pointmarkerlist.dtype == np.int32
    assert tio.pointattributelist.shape == (0, 0)
    assert tio.numberofpoints == tio.numberoftriangles == tio.numberofsegments == 0


def test_assignment_converts_lists_and_flat_arrays():
    tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]], segmentlist=[0, 1, 1, 2])
    assert tio.pointlist.dtype == np.float64 and tio.pointlist.shape == (3, 2)
    assert tio.segmentlist.tolist() == [[0, 1], [1, 2]]
    tio.pointmarkerlist = [[1], [2], [3]]
    assert tio.pointmarkerlist.tolist() == [1, 2, 3]
    tio.pointattributelist = [0.5, 1.5, 2.5]
    assert tio.pointattributelist.shape == (3, 1)
    assert tio.numberofpointattributes == 1


def test_float_arrays_are_not_copied():
    points = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    tio = TriangulateIO(pointlist=points)
    assert np.shares_memory(tio.pointlist, points)


@pytest.mark.parametrize(
    "field, value",
    [
        ("pointlist", [[0, 0, 0], [1, 1, 1]]),
        ("pointmarkerlist", [[1, 2], [3, 4]]),
        ("trianglelist", [[0, 1]]),
        ("segmentlist", [0, 1, 2]),
        ("segmentlist", [[0.5, 1]]),
        ("segmentlist", [[0, 2**40]]),
        ("regionlist", [[0, 0, 1]]),
    ],
)
def test_bad_shapes_and_values_are_refused(field, value):
    with pytest.raises(ValueError):
        TriangulateIO(**{field: value})


def test_unknown_fields_are_refused():
    with pytest.raises(TypeError):
        TriangulateIO(points=[[0, 0]])
    tio = TriangulateIO()
    with pytest.raises(AttributeError):
        tio.points = [[0, 0]]


def test_to_c_sets_counts_and_pointers():
    tio = TriangulateIO(
        pointlist=[[0, 0], [1, 0], [1, 1], [0, 1]],
        pointattributelist=[[1, 2], [3, 4], [5, 6], [7, 8]],
        segmentlist=[[0, 1], [1, 2]],
        holelist=[[0.5, 0.5]],
        regionlist=[[0.2, 0.2, 1, 0.1]],
    )
    c, keep = to_c(tio)
    assert (c.numberofpoints, c.numberofpointattributes, c.numberofsegments) == (4, 2, 2)
    assert (c.numberofholes, c.numberofregions, c.numberoftriangles, c.numberofcorners) == (1, 1, 0, 3)
    assert c.pointlist[5] == 1.0 and c.pointattributelist[7] == 8.0 and c.segmentlist[3] == 2
    assert not c.pointmarkerlist and not c.trianglelist and not c.segmentmarkerlist
    assert len(keep) == 5


def test_to_c_refuses_per_item_arrays_of_the_wrong_length():
    # The library trusts the counts (as Triangle does): a short marker list would be read past
    # its end, so the binding refuses it.
    tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]], pointmarkerlist=[1, 2])
    with pytest.raises(ValueError, match="pointmarkerlist"):
        to_c(tio)
    tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]], segmentlist=[[0, 1]], segmentmarkerlist=[1, 2])
    with pytest.raises(ValueError, match="segmentmarkerlist"):
        to_c(tio)


def test_from_c_copies_and_free_c_spares_the_aliased_arrays():
    points = (ctypes.c_double * 6)(0, 0, 1, 0, 0, 1)
    triangles = (ctypes.c_int * 3)(0, 1, 2)
    holes = (ctypes.c_double * 2)(0.25, 0.25)
    c = CTriangulateIO()
    c.pointlist = ctypes.cast(points, ctypes.POINTER(ctypes.c_double))
    c.numberofpoints = 3
    c.trianglelist = ctypes.cast(triangles, ctypes.POINTER(ctypes.c_int))
    c.numberoftriangles, c.numberofcorners = 1, 3
    c.holelist = ctypes.cast(holes, ctypes.POINTER(ctypes.c_double))
    c.numberofholes = 1
    tio = from_c(c)
    assert tio.pointlist.tolist() == [[0, 0], [1, 0], [0, 1]]
    assert tio.trianglelist.tolist() == [[0, 1, 2]]
    assert tio.holelist.tolist() == [[0.25, 0.25]]
    points[0] = 9.0  # the result is a copy, not a view of the library's memory
    assert tio.pointlist[0, 0] == 0.0

    freed = []
    free_c(c, freed.append)
    assert sorted(freed) == sorted([ctypes.addressof(points), ctypes.addressof(triangles)])
    assert not c.pointlist and not c.trianglelist and c.holelist  # holelist aliases the input
    free_c(c, freed.append)
    assert len(freed) == 2  # a second release frees nothing twice


def test_every_field_is_listed_once():
    assert len(FIELDS) == 14
    assert set(TriangulateIO.__slots__) == set(FIELDS)
