"""``loads``/``load``/``get_data``: the PyPI package's readers of Triangle's files, compared with the
PyPI package itself on every example of its data directory (read in place, never copied), and the
examples of our own making that ``get_data`` falls back to."""

from pathlib import Path

import numpy as np
import pytest

import triangle_rs
import triangle_rs.data
from triangle_rs.data import EXTENSIONS, OWN_DATA_DIRECTORY

from helpers import signed_areas


def _names(directory: Path) -> list[str]:
    return sorted({path.name.rsplit(".", 1)[0] for path in directory.iterdir() if path.suffix[1:] in EXTENSIONS})


@pytest.fixture(scope="module")
def pypi():
    import triangle as real

    assert not real.__name__.startswith("triangle_rs")
    return real


def test_the_data_directory_is_the_pypi_packages_when_installed(pypi):
    assert triangle_rs.data.data_directory().resolve() == Path(pypi.data.get_data_dir()).resolve()


def _assert_same(ours: dict, theirs: dict) -> None:
    assert sorted(ours) == sorted(theirs)
    for key in theirs:
        assert ours[key].shape == theirs[key].shape, key
        assert ours[key].dtype.kind == theirs[key].dtype.kind, key
        np.testing.assert_array_equal(ours[key], theirs[key], err_msg=key)


PYPI_NAMES = _names(triangle_rs.data.pypi_data_directory())


def test_the_pypi_package_has_its_examples():
    assert len(PYPI_NAMES) > 30


@pytest.mark.parametrize("name", PYPI_NAMES)
def test_every_example_of_the_pypi_package_reads_as_it_does(name, pypi):
    ours, theirs = triangle_rs.get_data(name), pypi.get_data(name)
    if name == "la.1":
        # Triangle wrote this file's regions with five numbers a line; the PyPI package reads
        # four a line, so its rows slide out of step. Ours are the file's regions: the same
        # points as in la.poly.
        np.testing.assert_array_equal(ours.pop("regions")[:, :2], triangle_rs.get_data("la")["regions"][:, :2])
        del theirs["regions"]
    _assert_same(ours, theirs)


def test_loads_numbering_from_one_and_zero():
    one = triangle_rs.loads(node="3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n", ele="1 3 1\n1 1 2 3 7.5\n")
    zero = triangle_rs.loads(node="3 2 0 0\n0 0 0\n1 1 0\n2 0 1\n", ele="1 3 1\n0 0 1 2 7.5\n")
    for d in (one, zero):
        assert d["triangles"].tolist() == [[0, 1, 2]] and d["triangle_attributes"].tolist() == [[7.5]]
        assert "vertex_markers" not in d


def test_region_lines_with_four_and_five_numbers():
    square = "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n4 0\n1 1 2\n2 2 3\n3 3 4\n4 4 1\n0\n"
    # Four numbers (as Triangle's la.poly): the last is the maximum area, the attribute 0.
    four = triangle_rs.loads(poly=square + "1\n1 0.5 0.5 0.25\n")
    assert four["regions"].tolist() == [[0.5, 0.5, 0.0, 0.25]]
    # Five, as Triangle documents: attribute, then maximum area.
    five = triangle_rs.loads(poly=square + "1\n1 0.5 0.5 7 0.25  # comment\n")
    assert five["regions"].tolist() == [[0.5, 0.5, 7.0, 0.25]]


def test_truncated_file_is_a_clear_error():
    with pytest.raises(ValueError, match="truncated"):
        triangle_rs.loads(node="3 2 0 0\n1 0 0\n2 1 0\n")


def test_unknown_example_is_an_error():
    with pytest.raises(FileNotFoundError):
        triangle_rs.get_data("no such example")


@pytest.mark.parametrize("name", _names(OWN_DATA_DIRECTORY))
def test_examples_of_our_own_making_are_valid(name):
    d = triangle_rs.load(OWN_DATA_DIRECTORY, name)
    vertices = d["vertices"]
    assert vertices.ndim == 2 and vertices.shape[1] == 2 and len(vertices) >= 3
    for key in ("segments", "triangles", "edges"):
        if key in d:
            assert d[key].min() >= 0 and d[key].max() < len(vertices), key
    if "triangles" in d:
        assert np.all(signed_areas(vertices, d["triangles"]) > 0)
        if "triangle_max_area" in d:
            assert len(d["triangle_max_area"]) == len(d["triangles"])
    if "segments" in d and "triangles" not in d:
        # A PSLG: Triangle meshes it.
        out = triangle_rs.triangulate(d, "p")
        assert np.all(signed_areas(out["vertices"], out["triangles"]) > 0)
