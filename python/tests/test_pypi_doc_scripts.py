"""The PyPI ``triangle`` package's 33 documentation scripts (``doc/plot/*.py``) run unchanged with
``triangle`` being triangle_rs, and draw the same kind of picture as with the PyPI package.

The scripts are not in this repository (they are the PyPI package's, LGPL): the test setup
downloads the package's source distribution with pip (``triangle==20200424``, the newest one
published as a source distribution) once into ``target/pypi-triangle-sdist/`` and runs its 32
scripts from there. The 33rd, ``ex7.py``, is not in that source distribution; its stand-in of our
own making is ``doc_scripts/ex7.py`` (regions with attributes, ``pA``).

Each script runs in this process with the Agg backend, once with ``sys.modules['triangle']`` set
to triangle_rs and once with the real PyPI package, and the figures are compared: the same number
of figures and of axes, the same view (axis limits, which depend on everything drawn), the same
number of line artists (triangle edges and corners), the same colours (black vertices, edges and
triangles, red segments and holes, blue regions, magenta triangle attributes: so the same kinds of
things drawn), labels present in the same axes, and something drawn in every axes.
"""

from __future__ import annotations

import runpy
import subprocess
import sys
import tarfile
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402

import triangle_rs  # noqa: E402
import triangle_rs.data  # noqa: E402

HERE = Path(__file__).resolve().parent
REPOSITORY = HERE.parent.parent
SDIST_VERSION = "20200424"
SDIST_CACHE = REPOSITORY / "target" / "pypi-triangle-sdist"
OWN_SCRIPTS = HERE / "doc_scripts"

#: The 33 scripts of drufat/triangle's doc/plot (ex7 from doc_scripts/).
SCRIPTS = [
    "PSLG", "api_convex_hull", "api_delaunay", "api_triangulate", "api_voronoi", "bndries",
    "conforming_delaunay", "conforming_delaunay1", "constrained_conforming_delaunay",
    "constrained_conforming_delaunay1", "constrained_delaunay", "constrained_delaunay1",
    "convex_hull", "delaunay", "delaunay1", "ex1", "ex2", "ex3", "ex4", "ex5", "ex6", "ex7", "face",
    "holes_cavities", "quality", "quality1", "quality2", "refine", "refine1", "refine2", "voronoi",
    "voronoi1", "voronoi3",
]  # fmt: skip

#: The scripts that read examples with get_data.
USES_GET_DATA = [
    "PSLG", "bndries", "conforming_delaunay", "conforming_delaunay1", "constrained_conforming_delaunay",
    "constrained_conforming_delaunay1", "constrained_delaunay", "constrained_delaunay1", "convex_hull",
    "delaunay", "delaunay1", "face", "holes_cavities", "quality", "quality1", "quality2", "refine",
    "refine1", "refine2", "voronoi", "voronoi1",
]  # fmt: skip


def _download_sdist() -> Path:
    """doc/plot of the PyPI package's source distribution, downloaded once (pip) and cached."""
    plot_directory = SDIST_CACHE / "doc" / "plot"
    if plot_directory.is_dir():
        return plot_directory
    SDIST_CACHE.mkdir(parents=True, exist_ok=True)
    archive = SDIST_CACHE / f"triangle-{SDIST_VERSION}.tar.gz"
    if not archive.exists():
        result = subprocess.run(
            [sys.executable, "-m", "pip", "download", "--quiet", "--disable-pip-version-check", "--no-deps",
             "--no-binary", ":all:", "--dest", str(SDIST_CACHE), f"triangle=={SDIST_VERSION}"],
            capture_output=True, text=True, timeout=300,
        )  # fmt: skip
        assert archive.exists(), (
            "could not download the PyPI triangle package's source distribution (it holds the "
            f"documentation scripts): {result.stdout}{result.stderr}"
        )
    prefix = f"triangle-{SDIST_VERSION}/doc/plot/"
    with tarfile.open(archive) as tar:
        for member in tar.getmembers():
            if member.isfile() and member.name.startswith(prefix) and member.name.endswith(".py"):
                target = plot_directory / member.name[len(prefix) :]
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_bytes(tar.extractfile(member).read())
    return plot_directory


@pytest.fixture(scope="module")
def script_paths() -> dict[str, Path]:
    downloaded = _download_sdist()
    paths = {path.stem: path for path in downloaded.glob("*.py")}
    paths.update({path.stem: path for path in OWN_SCRIPTS.glob("*.py")})
    missing = sorted(set(SCRIPTS) - set(paths))
    assert not missing, f"scripts missing: {missing}"
    return paths


@pytest.fixture(scope="module")
def pypi_triangle():
    """The real PyPI package (imported under its own name before any swap)."""
    saved = sys.modules.pop("triangle", None)
    try:
        import triangle as real
    finally:
        if saved is not None:
            sys.modules["triangle"] = saved
    assert not real.__name__.startswith("triangle_rs")
    return real


def _run_script(path: Path, module) -> list[dict]:
    """Runs the script with ``import triangle`` giving ``module``; a summary of each figure."""
    saved = sys.modules.get("triangle")
    sys.modules["triangle"] = module
    plt.close("all")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # plt.show() under Agg warns that it shows nothing
            runpy.run_path(str(path), run_name="__main__")
        return [_summary(plt.figure(number)) for number in plt.get_fignums()]
    finally:
        plt.close("all")
        if saved is None:
            sys.modules.pop("triangle", None)
        else:
            sys.modules["triangle"] = saved


def _summary(figure) -> dict:
    return {
        "axes": [
            {
                "view": np.array(ax.axis(), dtype=float),
                "lines": len(ax.lines),
                "labelled": bool(ax.texts),
                "drawn": len(ax.collections) + len(ax.lines) + len(ax.patches),
                "colours": _colours(ax),
            }
            for ax in figure.axes
        ]
    }


def _colours(ax) -> set[tuple[float, ...]]:
    """The colours of everything drawn in ``ax`` (black vertices and edges, red segments and
    holes, blue regions, magenta attributes), transparent ones left out."""
    from matplotlib.colors import to_rgba_array

    found = []
    for collection in ax.collections:
        found += [collection.get_facecolors(), collection.get_edgecolors()]
    for line in ax.lines:
        found += [to_rgba_array(line.get_color()), to_rgba_array(line.get_markerfacecolor())]
    for patch in ax.patches:
        found += [to_rgba_array(patch.get_facecolor()), to_rgba_array(patch.get_edgecolor())]
    found += [to_rgba_array(text.get_color()) for text in ax.texts]
    rows = np.concatenate([np.asarray(c, dtype=float).reshape(-1, 4) for c in found]) if found else np.empty((0, 4))
    return {tuple(row) for row in rows.round(3) if row[3] > 0}


def _assert_same_kind_of_picture(ours: list[dict], theirs: list[dict]) -> None:
    assert ours, "the script drew no figure"
    assert len(ours) == len(theirs), "not the same number of figures"
    for our_figure, their_figure in zip(ours, theirs):
        assert len(our_figure["axes"]) == len(their_figure["axes"]) > 0
        for our_axes, their_axes in zip(our_figure["axes"], their_figure["axes"]):
            assert our_axes["drawn"] > 0, "an empty axes"
            assert our_axes["lines"] == their_axes["lines"]
            assert our_axes["labelled"] == their_axes["labelled"]
            assert our_axes["colours"] == their_axes["colours"]
            span = max(np.ptp(their_axes["view"][:2]), np.ptp(their_axes["view"][2:]))
            np.testing.assert_allclose(our_axes["view"], their_axes["view"], atol=0.02 * span)


@pytest.mark.parametrize("name", SCRIPTS)
def test_documentation_script_runs_and_draws_what_the_pypi_package_draws(name, script_paths, pypi_triangle):
    ours = _run_script(script_paths[name], triangle_rs)
    theirs = _run_script(script_paths[name], pypi_triangle)
    _assert_same_kind_of_picture(ours, theirs)


@pytest.mark.parametrize("name", USES_GET_DATA)
def test_documentation_script_runs_on_the_examples_of_our_own_making(name, script_paths, monkeypatch):
    # As without the PyPI package installed: get_data falls back to triangle_rs/data.
    monkeypatch.setattr(triangle_rs.data, "pypi_data_directory", lambda: None)
    figures = _run_script(script_paths[name], triangle_rs)
    assert figures and all(figure["axes"] for figure in figures)
    assert all(axes["drawn"] > 0 for figure in figures for axes in figure["axes"])
