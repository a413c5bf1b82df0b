"""The per-call path (issue 36, point 1): the dictionary API and delaunay/convex_hull/voronoi read
the library's output straight into their results, with no TriangulateIO in between; the results
must be those of the general path (TriangulateIO in and out, then the dictionary), array for
array. Also: input arrays reach the library without a copy, every output array owns its data,
and the integer checks hold without numpy's same-value casts."""

import ctypes
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateIO, compat, core, triangulateio
from triangle_rs.compat import from_dict, select_outputs, to_dict

PYTHON_DIR = Path(__file__).resolve().parent.parent
LECTURE = {
    "vertices": [[0, 0], [1, 0], [1, 1], [0.8, 0.6], [0, 1]],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 4], [4, 0]],
}
#: A ring with a hole, markers, two point attributes and a region.
RING = {
    "vertices": [[0, 0], [3, 0], [3, 3], [0, 3], [1, 1], [2, 1], [2, 2], [1, 2]],
    "vertex_attributes": np.arange(16.0).reshape(8, 2),
    "vertex_markers": [1, 2, 3, 4, 5, 6, 7, 8],
    "segments": [[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]],
    "segment_markers": [[1], [1], [1], [1], [2], [2], [2], [2]],
    "holes": [[1.5, 1.5]],
    "regions": [[0.5, 0.5, 7.0, 0.1]],
}


def general_path(tri, opts):
    """The dictionary API as it was built before issue 36: TriangulateIO in and out."""
    tio = from_dict(tri)
    out, _ = core.run("Qz" + opts, tio)
    return to_dict(select_outputs(out, tio, opts))


def assert_same_dictionary(fast, general):
    assert list(fast) == list(general)
    for key in general:
        assert fast[key].dtype == general[key].dtype and fast[key].shape == general[key].shape, key
        assert fast[key].tobytes() == general[key].tobytes(), key


@pytest.mark.parametrize(
    "tri, opts",
    [(LECTURE, opts) for opts in ("", "p", "pq30", "pq30a0.01", "pc", "pP", "pne", "cv", "pqo2")]
    + [(RING, opts) for opts in ("p", "pA", "pAa", "pq", "pqAa", "pP", "pe", "pn", "c", "pqo2A")],
)
def test_the_dictionary_is_that_of_the_general_path(tri, opts):
    assert_same_dictionary(triangle_rs.triangulate(tri, opts), general_path(tri, opts))


def test_refining_a_mesh_gives_the_general_paths_dictionary():
    mesh = triangle_rs.triangulate(RING, "pqAa")
    mesh["triangle_max_area"] = np.full(len(mesh["triangles"]), 0.05)
    assert_same_dictionary(triangle_rs.triangulate(dict(mesh), "rpqa"), general_path(dict(mesh), "rpqa"))


def test_holes_and_regions_come_back_in_the_keys_order():
    out = triangle_rs.triangulate(RING, "pn")
    assert list(out) == [key for key in compat.KEYS if key in out]
    assert {"holes", "regions", "neighbors"} <= set(out)


@pytest.mark.parametrize("points", [LECTURE["vertices"], np.random.default_rng(5).random((100, 2)), [[0, 0], [1, 1]]])
def test_delaunay_convex_hull_and_voronoi_are_those_of_the_general_path(points):
    tio = TriangulateIO(pointlist=np.asarray(points, dtype=np.float64))
    if len(points) < 3:
        with pytest.raises(triangle_rs.TriangulateError):
            triangle_rs.delaunay(points)
        return
    out, _ = core.run("Qz", tio)
    assert triangle_rs.delaunay(points).tobytes() == out.trianglelist.tobytes()
    out, _ = core.run("Qzc", tio)
    assert triangle_rs.convex_hull(points).tobytes() == out.segmentlist.tobytes()
    _, vorout = core.run("Qzv", tio)
    vertices, edges, ray_origins, ray_directions = triangle_rs.voronoi(points)
    finite = vorout.edgelist[:, 1] != -1
    assert vertices.tobytes() == vorout.pointlist.tobytes()
    assert edges.tobytes() == vorout.edgelist[finite].tobytes()
    assert ray_origins.tobytes() == vorout.edgelist[~finite][:, 0].tobytes()
    assert ray_directions.tobytes() == vorout.normlist[~finite].tobytes()


def test_every_output_array_owns_its_data_as_the_pypi_packages_do():
    out = triangle_rs.triangulate(RING, "pqneA")
    for key, array in out.items():
        if key in ("holes", "regions"):
            continue  # copies the library made of the input's
        assert array.flags.owndata and array.flags.writeable and array.flags.c_contiguous, key
    assert out["vertex_markers"].shape == (len(out["vertices"]), 1)
    assert out["vertex_attributes"].shape == (len(out["vertices"]), 2)
    tio_out, _ = triangle_rs.triangulate("pqo2", TriangulateIO(pointlist=LECTURE["vertices"], segmentlist=LECTURE["segments"]))
    assert tio_out.trianglelist.shape[1] == 6 and tio_out.trianglelist.flags.owndata
    assert tio_out.pointmarkerlist.ndim == 1 and tio_out.pointmarkerlist.flags.owndata


class PointerRecordingLibrary:
    """The real library, recording the input struct's pointers."""

    def __init__(self, real):
        self.real = real
        self.path = real.path
        self.inputs = {}

    def triangulate(self, switches, tin, *arguments):
        for name in triangulateio.INPUT_FIELDS:
            self.inputs[name] = ctypes.cast(getattr(tin, name), ctypes.c_void_p).value
        return self.real.triangulate(switches, tin, *arguments)

    def free(self, address):
        self.real.free(address)


def test_input_arrays_of_the_right_dtype_reach_the_library_without_a_copy(monkeypatch):
    library = PointerRecordingLibrary(core.load_library())
    monkeypatch.setattr(core, "load_library", lambda: library)
    vertices = np.array(RING["vertices"], dtype=np.float64)
    segments = np.array(RING["segments"], dtype=np.int32)
    attributes = RING["vertex_attributes"]
    triangle_rs.triangulate({"vertices": vertices, "segments": segments, "vertex_attributes": attributes}, "p")
    assert library.inputs["pointlist"] == vertices.ctypes.data
    assert library.inputs["segmentlist"] == segments.ctypes.data
    assert library.inputs["pointattributelist"] == attributes.ctypes.data
    assert library.inputs["holelist"] is None and library.inputs["pointmarkerlist"] is None


def test_the_data_address_is_read_from_the_array_object_on_cpython():
    if sys.implementation.name != "cpython":
        pytest.skip("CPython only")
    assert triangulateio._DATA_POINTER_OFFSET is not None
    for array in (np.arange(5.0), np.arange(12, dtype=np.int32).reshape(3, 4)[1:], np.zeros((3, 2))[::2]):
        assert triangulateio._address(array) == array.ctypes.data


@pytest.mark.parametrize("same_value_casts", [True, False])
def test_integer_fields_are_checked_with_and_without_same_value_casts(monkeypatch, same_value_casts):
    if same_value_casts and not triangulateio._SAME_VALUE_CASTS:
        pytest.skip("numpy < 2.4 has no same-value casts")
    monkeypatch.setattr(triangulateio, "_SAME_VALUE_CASTS", same_value_casts)
    normalize = triangulateio.normalize
    for value in ([[0, 2**31]], [[0, -(2**31) - 1]], np.array([[0, 2**32 - 1]], dtype=np.uint32), [[0.0, 3e9]]):
        with pytest.raises(ValueError, match="outside the range of a 32-bit C int"):
            normalize("segmentlist", value)
    for value in ([[0, 1.5]], [[0, np.nan]]):
        with pytest.raises(ValueError, match="not whole numbers"):
            normalize("segmentlist", value)
    for value in ([[0, 2**31 - 1]], np.array([[0, 7]], dtype=np.uint64), [[0.0, -(2**31)]], np.array([[1, 2]], dtype=np.int8)):
        array = normalize("segmentlist", value)
        assert array.dtype == np.int32 and array.flags.c_contiguous
        assert array.tolist() == np.asarray(value).astype(np.int64).tolist()
    fortran = np.asfortranarray(np.array([[0, 1], [1, 2], [2, 0]], dtype=np.int64))
    assert normalize("segmentlist", fortran).flags.c_contiguous


def test_the_small_calls_benchmark_runs():
    pytest.importorskip("triangle", reason="the PyPI package is the benchmark's reference")
    result = subprocess.run(
        [sys.executable, str(PYTHON_DIR / "benchmarks" / "small_calls.py"), "--repeat", "2"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert result.returncode == 0, result.stdout + result.stderr
    lines = result.stdout.splitlines()
    assert len(lines) == 2 + 3 + 6 and all(line.split()[-1].replace(".", "").isdigit() for line in lines[2:])


# --- the worker thread of interruptible calls -------------------------------------------------------


def worker_threads():
    return [thread for thread in threading.enumerate() if thread.name.startswith("triangle_rs-")]


#: A refinement not predicted small (its area bound asks for 10^4 triangles of the unit square).
LONG = "pq30a0.0001"


def test_refining_calls_share_one_worker_thread():
    for _ in range(3):
        triangle_rs.triangulate(LECTURE, LONG)
    assert [thread.name for thread in worker_threads()] == ["triangle_rs-worker"]


def test_refinements_predicted_small_run_on_the_calling_thread(monkeypatch):
    """A refinement of few points with no area bound, or one that the bounding box holds few
    times, runs on the calling thread (the worker's hand-off costs more than it takes); one with
    a Python test (`u`), regional bounds, a mesh to refine, or a fine bound goes to the worker."""
    seen = []
    real = core._ForeignCall

    class Watched(real):
        def __init__(self, call):
            seen.append(True)
            super().__init__(call)

    monkeypatch.setattr(core, "_ForeignCall", Watched)
    for switches in ("pq30", "pq30a0.01", "pqD", "pq34"):
        assert len(triangle_rs.triangulate(LECTURE, switches)["triangles"]) > 0
    assert seen == []
    triangle_rs.triangulate(LECTURE, LONG)
    assert seen == [True]
    triangle_rs.triangulate(LECTURE, "pq30u", unsuitable=lambda *_: False)
    assert seen == [True, True]
    regions = dict(LECTURE, regions=[[0.5, 0.5, 1, 0.01]])
    triangle_rs.triangulate(regions, "pq30a")
    assert seen == [True, True, True]
    many = {"vertices": np.random.default_rng(3).random((core._SHORT_REFINEMENT_POINTS + 1, 2))}
    triangle_rs.triangulate(many, "q30")
    assert seen == [True, True, True, True]


class CallingAgainLibrary:
    """The real library; the first call raises SIGUSR1 in this process and waits (up to 10 s) for
    the handler, which makes a second refining call while the worker runs the first."""

    def __init__(self, real):
        self.real = real
        self.path = real.path
        self.inner = None

    def triangulate(self, *arguments):
        if self.inner is None:
            self.inner = "pending"
            os.kill(os.getpid(), signal.SIGUSR1)
            for _ in range(1000):
                if self.inner != "pending":
                    break
                time.sleep(0.01)
        return self.real.triangulate(*arguments)

    def free(self, address):
        self.real.free(address)


@pytest.mark.skipif(not hasattr(signal, "SIGUSR1"), reason="POSIX signals")
def test_a_refining_call_made_while_the_worker_is_busy_gets_a_thread_of_its_own():
    library = CallingAgainLibrary(core.load_library())

    def handler(_number, _frame):
        library.inner = triangle_rs.triangulate(LECTURE, LONG)  # the real library, not the stand-in

    previous = signal.signal(signal.SIGUSR1, handler)
    try:
        out, _ = core.run("Qz" + LONG, TriangulateIO(pointlist=LECTURE["vertices"], segmentlist=LECTURE["segments"]), library=library)
    finally:
        signal.signal(signal.SIGUSR1, previous)
    assert isinstance(library.inner, dict) and len(library.inner["triangles"]) == out.numberoftriangles


@pytest.mark.skipif(not hasattr(os, "fork"), reason="os.fork")
def test_a_forked_child_starts_its_own_worker():
    triangle_rs.triangulate(LECTURE, LONG)  # the parent's worker exists
    script = (
        "import os, sys\n"
        "import triangle_rs\n"
        "LECTURE = %r\n"
        "expected = len(triangle_rs.triangulate(LECTURE, 'pq30a0.0001')['triangles'])\n"
        "pid = os.fork()\n"
        "if pid == 0:\n"
        "    os._exit(0 if len(triangle_rs.triangulate(LECTURE, 'pq30a0.0001')['triangles']) == expected else 1)\n"
        "_, status = os.waitpid(pid, 0)\n"
        "sys.exit(os.waitstatus_to_exitcode(status))\n"
    ) % (LECTURE,)
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60, env={**os.environ, "PYTHONPATH": str(PYTHON_DIR)})
    assert result.returncode == 0, result.stdout + result.stderr
