"""``plot``, ``compare``, ``comparev`` and ``show_data`` against the PyPI package's, on what the
documentation scripts do not exercise: labels, markers, ``comparev``, ``show_data``."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import triangle_rs  # noqa: E402


@pytest.fixture(scope="module")
def pypi():
    import triangle as real

    assert not real.__name__.startswith("triangle_rs")
    return real


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _texts(module, **d):
    ax = plt.figure().add_subplot()
    module.plot(ax, **d)
    return sorted(text.get_text() for text in ax.texts), ax


def test_labels_and_markers_are_the_pypi_packages(pypi):
    d = triangle_rs.triangulate({"vertices": [[0, 0], [1, 0], [1, 1], [0, 1]], "vertex_markers": [3, 4, 5, 6]})
    for options in ({"labels": True}, {"markers": True}):
        ours, ax = _texts(triangle_rs, **d, **options)
        theirs, _ = _texts(pypi, **d, **options)
        assert ours == theirs and len(ours) == 4
        assert not ax.get_xaxis().get_visible() and not ax.get_yaxis().get_visible()
        assert ax.get_aspect() == 1.0


def test_comparev_stacks_two_axes_sharing_x(pypi):
    face = triangle_rs.get_data("face")
    for module in (triangle_rs, pypi):
        module.comparev(plt, face, triangle_rs.triangulate(face, "p"))
    ours, theirs = (plt.figure(n) for n in plt.get_fignums())
    for figure in (ours, theirs):
        top, bottom = figure.axes
        assert top.get_position().y0 > bottom.get_position().y1 - 1e-9  # one above the other
        assert tuple(figure.get_size_inches()) == (3.0, 6.0)
    for a, b in zip(ours.axes, theirs.axes):
        np.testing.assert_allclose(a.axis(), b.axis(), atol=1e-9 * max(1.0, np.ptp(b.axis())))


def test_show_data_plots_the_example_and_shows_it(monkeypatch):
    shown = []
    monkeypatch.setattr(plt, "show", lambda *a, **k: shown.append(plt.gcf()))
    triangle_rs.show_data("A")
    (figure,) = shown
    (ax,) = figure.axes
    vertices = triangle_rs.get_data("A")["vertices"]
    assert sum(len(c.get_offsets()) for c in ax.collections) >= len(vertices)
