"""What a call says besides its mesh (issue 37, point 4): at most one warning per call, only for
what changes the result asked for, attributed to the caller's line; nothing for what Triangle
does silently under ``Q`` (duplicate vertices, a passing ``C`` check), which ``V`` prints and
``last_report()`` keeps."""

import os
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateIO, TriangulateWarning
from triangle_rs import compat, core
from triangle_rs.report import Report

from helpers import canonical_triangles

PYTHON_DIR = Path(__file__).resolve().parent.parent
#: A polygon that needs many more than five Steiner points for 30° (a notched rectangle with a
#: thin slot).
POLYGON = {
    "vertices": [[0, 0], [4, 0], [4, 1], [2.2, 1], [2.1, 0.2], [2.0, 1], [0, 1]],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 4], [4, 5], [5, 6], [6, 0]],
}


def ten_thousand_duplicates() -> np.ndarray:
    points = np.random.default_rng(37).random((10_000, 2))
    return np.concatenate([points, points])


def by_position(points: np.ndarray, triangles: np.ndarray) -> set:
    return {frozenset(map(tuple, points[t].tolist())) for t in triangles}


def one_warning(record: list) -> warnings.WarningMessage:
    assert len(record) == 1, [str(w.message)[:200] for w in record]
    (warning,) = record
    assert issubclass(warning.category, RuntimeWarning) and issubclass(warning.category, TriangulateWarning)
    # The caller's own line: this file, not the package's.
    assert warning.filename == __file__, warning.filename
    return warning


# --- Notes: no warning ---------------------------------------------------------------------------


def test_ten_thousand_duplicate_vertices_give_no_warning_and_the_right_result():
    import triangle as reference  # the PyPI package: Triangle 1.6 in-process

    points = ten_thousand_duplicates()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        triangles = triangle_rs.delaunay(points)
        report = triangle_rs.last_report()
        out = triangle_rs.triangulate({"vertices": points}, "")
        jl_out, _ = triangle_rs.triangulate("", TriangulateIO(pointlist=points))
        keywords, _ = triangle_rs.mesh(points)
    # Triangle's triangles, by position (which copy of a vertex stays may differ).
    assert by_position(points, triangles) == by_position(points, reference.delaunay(points))
    for other in (out["triangles"], jl_out.trianglelist, keywords.trianglelist):
        assert canonical_triangles(other) == canonical_triangles(triangles)
    assert report.duplicate_vertices == 10_000 and report.problems == ()
    assert report.summary()[0].startswith("10,000 duplicate vertices were ignored; the first at (")


def test_duplicates_under_python_W_error_print_nothing():
    # `python -W error`: the call returns its triangles, and nothing is printed, by the package
    # or by the library (which always gets `Q`), whichever API is used.
    script = (
        "import numpy as np, triangle_rs\n"
        "p = np.random.default_rng(1).random((1000, 2)); p = np.concatenate([p, p])\n"
        "print(len(triangle_rs.delaunay(p)))\n"
        "out, _ = triangle_rs.triangulate('', triangle_rs.TriangulateIO(pointlist=p))\n"
        "print(out.numberoftriangles, triangle_rs.last_report().duplicate_vertices)\n"
    )
    environment = dict(os.environ, PYTHONPATH=str(PYTHON_DIR))
    result = subprocess.run(
        [sys.executable, "-W", "error", "-c", script], capture_output=True, text=True, env=environment, timeout=120
    )
    assert result.returncode == 0, result.stderr
    first, second = result.stdout.splitlines()
    assert first == second.split()[0] and second.split()[1] == "1000"
    assert result.stderr == ""


def test_a_passing_check_is_silent():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = triangle_rs.triangulate(POLYGON, "pq20C")
    assert len(out["triangles"]) > 0
    report = triangle_rs.last_report()
    # The library reports a passing check as no warning line at all (Triangle prints it as a
    # statistic without Q).
    assert report.problems == () and report.lines == ()


def test_a_segment_with_one_vertex_at_both_ends_is_skipped_silently():
    tri = {"vertices": [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]], "segments": [[0, 4], [0, 1]]}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        triangle_rs.triangulate(tri, "p")
    report = triangle_rs.last_report()
    assert report.skipped_segments == 1 and report.duplicate_vertices == 1 and report.problems == ()


def test_V_prints_the_notes_counted_to_stdout_and_without_V_nothing(capfd):
    points = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0, 0], [1, 1], [1, 1]], dtype=float)
    triangle_rs.triangulate({"vertices": points}, "")
    triangle_rs.triangulate("", TriangulateIO(pointlist=points))  # no Q: still quiet
    assert capfd.readouterr() == ("", "")
    triangle_rs.triangulate({"vertices": points}, "V")
    printed = capfd.readouterr()
    assert printed.err == ""
    assert printed.out.splitlines() == [
        "  3 duplicate vertices were ignored; the first at (0, 0) (vertex 4 duplicates vertex 0)."
    ]
    triangle_rs.triangulate({"vertices": points}, "VV")
    assert len(capfd.readouterr().out.splitlines()) == 3  # VV: every line


def test_the_report_is_per_thread_and_cleared_by_a_failed_call():
    triangle_rs.delaunay([[0, 0], [1, 0], [0, 1], [0, 0]])
    assert triangle_rs.last_report().duplicate_vertices == 1
    with pytest.raises(triangle_rs.TriangulateError):
        triangle_rs.delaunay([[0, 0], [1, 0]])
    assert triangle_rs.last_report() is None
    import threading

    seen = []
    thread = threading.Thread(target=lambda: seen.append(triangle_rs.last_report()))
    triangle_rs.delaunay([[0, 0], [1, 0], [0, 1], [0, 0]])
    thread.start()
    thread.join()
    assert seen == [None] and triangle_rs.last_report() is not None


# --- Problems: one warning, at the caller's line --------------------------------------------------


def test_an_S_budget_that_stops_refinement_short_of_the_angle_warns_once_at_the_callers_line():
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = triangle_rs.triangulate(POLYGON, "pq30S5")
    warning = one_warning(record)
    assert "S budget of 5 Steiner points" in str(warning.message)
    assert len(out["vertices"]) <= len(POLYGON["vertices"]) + 5
    assert triangle_rs.last_report().problems == (str(warning.message),)
    # The drop-in module's own function, the Triangulate.jl style and the keywords alike.
    for call in (
        lambda: compat.triangulate(POLYGON, "pq30S5"),
        lambda: triangle_rs.triangulate(
            "pq30S5", TriangulateIO(pointlist=POLYGON["vertices"], segmentlist=POLYGON["segments"])
        ),
        lambda: triangle_rs.mesh(POLYGON["vertices"], POLYGON["segments"], min_angle=30, max_steiner=5),
    ):
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            call()
        assert str(one_warning(record).message) == str(warning.message)


def test_an_S_budget_that_does_not_stop_refinement_is_silent():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        budgeted = triangle_rs.triangulate(POLYGON, "pq30S100000")
    # The smallest budget that gives the same mesh (refinement may delete vertices it
    # inserted, which S counts): spent to the last point, yet it stopped nothing.
    budget = len(budgeted["vertices"]) - len(POLYGON["vertices"])
    while True:
        with warnings.catch_warnings(record=True) as record:
            warnings.simplefilter("always")
            out = triangle_rs.triangulate(POLYGON, f"pq30S{budget}")
        if np.array_equal(out["vertices"], budgeted["vertices"]):
            assert record == []
            break
        one_warning(record)  # short of it: the budget stopped refinement
        budget += 1


def test_an_angle_above_the_guarantee_that_falls_back_warns_once():
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = triangle_rs.triangulate(POLYGON, "pq40")
    assert "28.6" in str(one_warning(record).message)
    assert len(out["triangles"]) > 0


def test_under_filterwarnings_error_a_real_problem_raises_the_one_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(TriangulateWarning, match="S budget"):
            triangle_rs.triangulate(POLYGON, "pq30S5")


class ReportingLibrary:
    """The real library, its warning text replaced by ``text`` (problems no plain Delaunay call
    has), to see where every entry point's warning points."""

    def __init__(self, real, text):
        self.real = real
        self.path = self.real.path
        self.text = text

    def triangulate(self, *arguments):
        code, message, _ = self.real.triangulate(*arguments)
        return code, message, self.text

    def free(self, address):
        self.real.free(address)


PROBLEMS = [
    "Refinement left 3 triangles or segments unsplit: the precision of floating-point numbers is exhausted.",
    "Mesh check: 1 triangles are inverted or flat and 0 edges are not locally Delaunay.",
]
TEXT = "\n".join(
    [f"A duplicate vertex at ({k}, 0) appeared and was ignored (vertex {k + 9} duplicates vertex {k})." for k in range(1000)]
    + PROBLEMS
    + ["A line of a later library that this package does not know."]
)


@pytest.mark.parametrize(
    "entry",
    ["delaunay", "convex_hull", "voronoi", "triangulate dict", "triangulate tio", "mesh", "compat.triangulate"],
)
def test_every_entry_point_warns_once_of_all_the_problems_at_the_callers_line(monkeypatch, entry):
    library = ReportingLibrary(core.load_library(), TEXT)
    monkeypatch.setattr(core, "load_library", lambda: library)
    points = [[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.4]]
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        if entry == "delaunay":
            triangle_rs.delaunay(points)
        elif entry == "convex_hull":
            triangle_rs.convex_hull(points)
        elif entry == "voronoi":
            triangle_rs.voronoi(points)
        elif entry == "triangulate dict":
            triangle_rs.triangulate({"vertices": points}, "")
        elif entry == "triangulate tio":
            triangle_rs.triangulate("", TriangulateIO(pointlist=points))
        elif entry == "mesh":
            triangle_rs.mesh(points)
        else:
            compat.triangulate({"vertices": points})
    message = str(one_warning(record).message)
    assert message == " ".join(PROBLEMS + ["A line of a later library that this package does not know."])
    assert "duplicate" not in message
    assert triangle_rs.last_report().duplicate_vertices == 1000


def test_the_distributed_driver_reports_duplicates_without_a_warning():
    pytest.importorskip("dask", reason="the [distributed] extra")
    # Its tasks' calls (on the workers) warn of nothing; the count is on the result.
    from triangle_rs.distributed import tasks

    points = ten_thousand_duplicates()[::20]
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        triangles, _ = tasks._local_delaunay(points)
    assert len(triangles) > 0


# --- The pieces -----------------------------------------------------------------------------------


def test_notes_are_counted_without_splitting_and_unknown_lines_are_problems():
    text = "\n".join(["A duplicate vertex at (1, 2) appeared and was ignored (vertex 5 duplicates vertex 1)."] * 3)
    report = Report("Qz", text)
    assert report.problems == () and report.duplicate_vertices == 3 and len(report.notes) == 3
    report = Report("Qz", text + "\nSomething new.")
    assert report.problems == ("Something new.",) and report.duplicate_vertices == 3
    assert Report("Qz", "").lines == () and Report("Qz", "").summary() == []
