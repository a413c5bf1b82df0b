"""Progress reports (``progress=`` on every triangulate): the phases in order with their counts,
refinement reported while it runs, a bar (or a plain line) with ``progress=True``, and an
exception in the callback stopping the call and re-raised."""

import sys

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateIO

SQUARE = {
    "vertices": np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=float),
    "segments": np.array([[0, 1], [1, 2], [2, 3], [3, 0]]),
}


def test_phases_come_in_order_with_their_counts():
    seen = []
    out = triangle_rs.triangulate(SQUARE, "pq30a0.0001", progress=lambda *report: seen.append(report))
    phases = [phase for phase, _, _ in seen]
    order = [p for i, p in enumerate(phases) if i == 0 or phases[i - 1] != p]
    assert order == ["delaunay", "segments", "refinement", "output"], seen
    assert seen[0] == ("delaunay", 0, 4) and seen[1] == ("delaunay", 4, 4)
    refinement = [(done, estimate) for phase, done, estimate in seen if phase == "refinement"]
    assert len(refinement) >= 3, refinement
    assert all(a[0] <= b[0] for a, b in zip(refinement, refinement[1:])), refinement
    # The total is the vertices refinement inserted in every run: above 28.6° (here 30°) a
    # second run in another order may be tried and the smaller mesh kept.
    inserted = len(out["vertices"]) - 4
    done, estimate = refinement[-1]
    assert done == estimate and inserted <= done <= 3 * inserted, (refinement[-1], inserted)
    seen20 = []
    out20 = triangle_rs.triangulate(SQUARE, "pq20a0.0001", progress=lambda *report: seen20.append(report))
    done20, estimate20 = [(d, e) for phase, d, e in seen20 if phase == "refinement"][-1]
    # One run below 28.6°: its vertices, those kept and the few that Chew's rule deleted again
    # (free vertices in the diametral circle of a subsegment being split).
    kept20 = len(out20["vertices"]) - 4
    assert done20 == estimate20 and kept20 <= done20 <= kept20 + kept20 // 10, ((done20, estimate20), kept20)


def test_the_triangulateio_style_takes_progress_too():
    seen = []
    tio = TriangulateIO(pointlist=np.random.default_rng(1).random((500, 2)))
    triangle_rs.triangulate("Q", tio, progress=lambda *report: seen.append(report))
    assert seen[0] == ("delaunay", 0, 500) and seen[-1][0] == "output", seen


def test_progress_true_shows_a_line_without_tqdm(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "tqdm", None)  # `import tqdm` raises ImportError
    triangle_rs.triangulate(SQUARE, "pq30a0.001", progress=True)
    err = capsys.readouterr().err
    assert "triangle-rs: refinement:" in err and "triangle-rs: output:" in err, err
    assert err.endswith("\n")


def test_an_exception_in_the_callback_stops_the_call_and_is_raised():
    class Stop(Exception):
        pass

    def progress(phase, done, estimate):
        if phase == "refinement" and done > 100:
            raise Stop(done)

    with pytest.raises(Stop):
        triangle_rs.triangulate(SQUARE, "pq30a0.000001", progress=progress)


def test_a_callback_that_is_not_callable_is_refused():
    with pytest.raises(TypeError):
        triangle_rs.triangulate(SQUARE, "pq", progress=42)
