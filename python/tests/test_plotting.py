"""The plots (matplotlib, Agg backend): what they draw, and that they render."""

import matplotlib

matplotlib.use("Agg")

import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection, PatchCollection, PolyCollection  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.image import imread  # noqa: E402

import triangle_rs  # noqa: E402
from triangle_rs import TriangulateIO, triangulate  # noqa: E402
from triangle_rs.plotting import circumcircles_of, plot_in_out, plot_triangulateio  # noqa: E402

FIVE_POINTS = [[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]]


def collections(ax, kind):
    return [c for c in ax.collections if type(c) is kind]


def test_circumcircles_of_a_right_triangle():
    centres, radii = circumcircles_of(np.array([[0.0, 0.0], [2.0, 0.0], [0.0, 2.0]]), np.array([[0, 1, 2]]))
    assert np.allclose(centres, [[1.0, 1.0]]) and np.allclose(radii, [np.sqrt(2.0)])


def test_triangles_voronoi_and_circumcircles_are_drawn():
    out, vorout = triangulate("vQ", TriangulateIO(pointlist=FIVE_POINTS))
    ax = Figure().subplots()
    plot_triangulateio(ax, out, voronoi=vorout, circumcircles=True)
    lines = collections(ax, LineCollection)
    black = [c for c in lines if np.allclose(c.get_colors()[0][:3], 0)]
    assert len(black) == 1 and len(black[0].get_segments()) == 3 * 4  # three edges per triangle
    green = [c for c in lines if c not in black]
    assert len(green) == 1 and len(green[0].get_segments()) == 8  # 4 finite edges + 4 rays
    (circles,) = collections(ax, PatchCollection)
    assert len(circles.get_paths()) == 4
    assert ax.get_aspect() == 1.0


def test_segments_are_coloured_by_marker_and_regions_filled_by_attribute():
    tio = TriangulateIO(
        pointlist=[[0, 0], [1, 0], [1, 1], [0, 1]],
        segmentlist=[[0, 1], [1, 2], [2, 3], [3, 0]],
        segmentmarkerlist=[1, 1, 2, 3],
        trianglelist=[[0, 1, 2], [0, 2, 3]],
        triangleattributelist=[[1.0], [2.0]],
    )
    ax = Figure().subplots()
    plot_triangulateio(ax, tio)
    (faces,) = collections(ax, PolyCollection)
    face_colors = faces.get_facecolors()
    assert len(face_colors) == 2 and not np.allclose(face_colors[0], face_colors[1])
    thick = [c for c in collections(ax, LineCollection) if c.get_linewidths()[0] == 3]
    colors = thick[0].get_colors()
    assert np.allclose(colors[0], colors[1]) and not np.allclose(colors[1], colors[2])
    assert not np.allclose(colors[2], colors[3])


def test_input_side_shows_holes_and_regions():
    tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [1, 1]], holelist=[[0.5, 0.2]], regionlist=[[0.7, 0.3, 1, 0]])
    ax = Figure().subplots()
    plot_triangulateio(ax, tio)
    # points, hole marks, region marks
    assert len(ax.collections) == 3


def test_plot_in_out_writes_a_png(tmp_path):
    triin = TriangulateIO(pointlist=np.random.default_rng(0).random((30, 2)))
    triout, vorout = triangulate("vQ", triin)
    figure = plot_in_out(triin, triout, voronoi=vorout, circumcircles=True, title="thirty points")
    assert [ax.get_title() for ax in figure.axes] == ["In", "Out"]
    assert figure.texts[0].get_text() == "thirty points"
    path = tmp_path / "in_out.png"
    figure.savefig(path)
    image = imread(path)
    assert image.shape[0] > 100 and image.shape[1] > 100
    # Not a blank canvas: many pixels are far from white.
    assert (image[..., :3].sum(axis=2) < 2.0).mean() > 0.01


def test_plot_functions_are_reachable_from_the_package():
    triin = TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1], [1, 1]])
    triout, _ = triangle_rs.triangulate("", triin)
    figure = triangle_rs.plot_in_out(triin, triout, title="four points")
    assert len(figure.axes) == 2 and figure.axes[1].collections
    ax = figure.axes[0]
    assert triangle_rs.plot_triangulateio(ax, triout) is ax
