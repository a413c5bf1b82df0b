"""Concurrency (the GIL is released; no global state), the per-call unsuitable callback, Ctrl-C,
and the ownership of the library's output arrays."""

import ctypes
import os
import signal
import threading
import time

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateError, TriangulateIO, triangulate
from triangle_rs._library import load_library
from triangle_rs.core import run
from triangle_rs.triangulateio import ALIASED_FIELDS, FIELDS

from helpers import canonical_triangles, random_points, signed_areas

# --- threads ------------------------------------------------------------------------------------


def test_concurrent_calls_from_threads_match_sequential_results():
    inputs = [random_points(seed=100 + i, n=2000) for i in range(8)]
    expected = [canonical_triangles(triangle_rs.delaunay(p)) for p in inputs]
    results = {}
    barrier = threading.Barrier(4)

    def work(first):
        barrier.wait()
        for i in range(first, len(inputs), 4):
            out, _ = triangulate("Q", TriangulateIO(pointlist=inputs[i]))
            results[i] = canonical_triangles(out.trianglelist)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert [results[i] for i in range(len(inputs))] == expected


def test_large_input_through_the_interruptible_path_matches_a_direct_call():
    # On the main thread a large input runs in a worker thread (so Ctrl-C can reach the
    # library); from another thread it runs directly. Both give the same triangles.
    points = random_points(seed=99, n=60_000)
    direct = {}
    side = threading.Thread(target=lambda: direct.update(out=triangulate("Q", TriangulateIO(pointlist=points))[0]))
    side.start()
    side.join()
    through_worker, _ = triangulate("Q", TriangulateIO(pointlist=points))
    assert through_worker.numberoftriangles > 100_000
    assert canonical_triangles(through_worker.trianglelist) == canonical_triangles(direct["out"].trianglelist)


def test_error_messages_are_per_thread():
    # The library keeps the last error per thread: concurrent failures never swap messages.
    failures = []
    barrier = threading.Barrier(3)

    def too_few():
        barrier.wait()
        for _ in range(200):
            try:
                triangulate("Q", TriangulateIO(pointlist=[[0, 0], [1, 1]]))
            except TriangulateError as error:
                if "at least three" not in str(error):
                    failures.append(str(error))

    def not_finite():
        barrier.wait()
        for _ in range(200):
            try:
                triangulate("Q", TriangulateIO(pointlist=[[0, 0], [1, 1], [np.nan, 0]]))
            except TriangulateError as error:
                if "not finite" not in str(error):
                    failures.append(str(error))

    def succeeding():
        barrier.wait()
        for _ in range(200):
            out, _ = triangulate("Q", TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]]))
            if out.numberoftriangles != 1:
                failures.append("wrong triangulation")

    threads = [threading.Thread(target=f) for f in (too_few, not_finite, succeeding)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert failures == []


# --- the unsuitable callback (switch u) ----------------------------------------------------------

SQUARE_POINTS = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.3, 0.6]], dtype=float)
#: Switches for a refinement of them not predicted small (see `core._predicted_small`): it goes to
#: the worker thread, as a long one must for Ctrl-C.
LONG_REFINEMENT = "Qqa1e-9"


def test_unsuitable_callback_is_honoured():
    calls = []

    def too_big(x1, y1, x2, y2, x3, y3, area):
        calls.append((x1, y1, x2, y2, x3, y3, area))
        return area > 0.02

    out, _ = triangulate("Qu", TriangulateIO(pointlist=SQUARE_POINTS), unsuitable=too_big)
    areas = signed_areas(out.pointlist, out.trianglelist)
    # The contract: no output triangle is unsuitable.
    assert np.all(areas <= 0.02 + 1e-12) and np.isclose(areas.sum(), 1.0)
    assert calls
    for x1, y1, x2, y2, x3, y3, area in calls:
        assert np.isclose(area, 0.5 * ((x1 - x3) * (y2 - y3) - (y1 - y3) * (x2 - x3)))
        assert area > 0  # corners are given counter-clockwise


def test_callback_exception_is_re_raised():
    def broken(*_corners):
        raise ZeroDivisionError("broken callback")

    with pytest.raises(ZeroDivisionError, match="broken callback"):
        triangulate("Qu", TriangulateIO(pointlist=SQUARE_POINTS), unsuitable=broken)


def test_callback_is_per_call():
    def never(*_):
        return False

    def small(x1, y1, x2, y2, x3, y3, area):
        return area > 0.005

    tio = TriangulateIO(pointlist=SQUARE_POINTS)
    before, _ = triangulate("Qu", tio, unsuitable=never)
    fine, _ = triangulate("Qu", tio, unsuitable=small)
    after, _ = triangulate("Qu", tio, unsuitable=never)
    assert fine.numberoftriangles > before.numberoftriangles
    assert canonical_triangles(after.trianglelist) == canonical_triangles(before.trianglelist)


def test_concurrent_calls_with_different_callbacks():
    # Each callback, on its first call, waits for the other call's callback: this can only
    # happen if both calls run at once, i.e. if the GIL is released during the foreign call.
    limits = {"A": 0.01, "B": 0.05}
    arrived = {name: threading.Event() for name in limits}
    met = {}
    callers = {name: set() for name in limits}
    results, errors = {}, {}

    def make(name, other):
        def unsuitable(x1, y1, x2, y2, x3, y3, area):
            if name not in met:
                arrived[name].set()
                met[name] = arrived[other].wait(timeout=60)
            callers[name].add(threading.get_ident())
            return area > limits[name]

        return unsuitable

    def work(name, other):
        try:
            results[name] = triangulate("Qu", TriangulateIO(pointlist=SQUARE_POINTS), unsuitable=make(name, other))
        except TriangulateError as error:
            errors[name] = error

    threads = {n: threading.Thread(target=work, args=(n, o)) for n, o in (("A", "B"), ("B", "A"))}
    for t in threads.values():
        t.start()
    for t in threads.values():
        t.join()
    assert not errors
    assert met == {"A": True, "B": True}
    assert callers["A"] == {threads["A"].ident} and callers["B"] == {threads["B"].ident}
    for name, (out, _) in results.items():
        assert np.all(signed_areas(out.pointlist, out.trianglelist) <= limits[name] + 1e-12)


# --- Ctrl-C --------------------------------------------------------------------------------------


@pytest.fixture
def sigint_raises_keyboard_interrupt():
    """Python's own SIGINT handler for the test, restored after it. The tests below send SIGINT
    to this process and expect KeyboardInterrupt: started from a shell that ignores SIGINT (a
    background job, `nohup`), Python inherits SIG_IGN and keeps it, and the signal is lost."""
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


class StallingLibrary:
    """Stands in for the library: raises SIGINT in this process, then works until the cancel
    flag is set (at most ~30 s), as a long refinement polls it."""

    path = "stalling stand-in"

    def __init__(self):
        self.saw_cancel = False

    def triangulate(self, switches, tin, tout, vorout, unsuitable, cancel, progress=None):
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(3000):
            if cancel.value:
                self.saw_cancel = True
                break
            time.sleep(0.01)
        return 1, "Triangulation cancelled by the caller."

    def free(self, address):
        raise AssertionError("nothing was allocated")


def test_keyboard_interrupt_sets_the_cancel_flag_and_is_re_raised(sigint_raises_keyboard_interrupt):
    # `q` refines, and the area bound asks for 10^9 triangles: the call is not predicted small
    # and runs in a worker thread so that Ctrl-C reaches the library.
    library = StallingLibrary()
    with pytest.raises(KeyboardInterrupt):
        run(LONG_REFINEMENT, TriangulateIO(pointlist=SQUARE_POINTS), library=library)
    assert library.saw_cancel


class SlowToStopLibrary:
    """Stands in for the library: raises ``signals`` in this process one after the other, sees
    the cancel flag, and returns only a while later, as a library finishing its current step."""

    path = "slow-to-stop stand-in"

    def __init__(self, signals):
        self.signals = signals
        self.saw_cancel = False
        self.returned = False

    def triangulate(self, switches, tin, tout, vorout, unsuitable, cancel, progress=None):
        for number in self.signals:
            os.kill(os.getpid(), number)
            time.sleep(0.05)
        for _ in range(3000):
            if cancel.value:
                self.saw_cancel = True
                break
            time.sleep(0.01)
        time.sleep(0.3)
        self.returned = True
        return 0, ""

    def free(self, address):
        raise AssertionError("nothing was allocated")


@pytest.mark.parametrize("raised", [SystemExit, LookupError])
def test_any_exception_while_waiting_cancels_and_is_raised_after_the_library_returned(raised, sigint_raises_keyboard_interrupt):
    # A signal handler raising SystemExit (or anything else), then a second Ctrl-C while the
    # library winds down: the first exception comes out, and only after the library returned.
    library = SlowToStopLibrary([signal.SIGUSR1, signal.SIGINT])

    def handler(_number, _frame):
        raise raised("from a signal handler")

    previous = signal.signal(signal.SIGUSR1, handler)
    try:
        with pytest.raises(raised):
            run(LONG_REFINEMENT, TriangulateIO(pointlist=SQUARE_POINTS), library=library)
    finally:
        signal.signal(signal.SIGUSR1, previous)
    assert library.saw_cancel and library.returned


def test_keyboard_interrupt_stops_a_real_refinement(sigint_raises_keyboard_interrupt):
    limit = 2_000_000
    calls = []

    def split_everything(*_):
        if not calls:
            os.kill(os.getpid(), signal.SIGINT)
        calls.append(1)
        return len(calls) < limit

    try:
        triangulate("Qu", TriangulateIO(pointlist=SQUARE_POINTS), unsuitable=split_everything)
    except KeyboardInterrupt:
        pass
    else:
        pytest.fail("KeyboardInterrupt was not raised")
    assert len(calls) < limit, "the refinement ran to the end instead of stopping"


# --- memory ----------------------------------------------------------------------------------------


class RecordingLibrary:
    """The real library, recording which output arrays it allocated and which ones are freed."""

    def __init__(self):
        self.real = load_library()
        self.path = self.real.path
        self.allocated, self.freed, self.aliased = [], [], []

    def triangulate(self, switches, tin, tout, vorout, unsuitable, cancel, progress=None):
        result = self.real.triangulate(switches, tin, tout, vorout, unsuitable, cancel)
        for struct in (tout, vorout):
            for name in FIELDS:
                address = ctypes.cast(getattr(struct, name), ctypes.c_void_p).value
                if address:
                    (self.aliased if name in ALIASED_FIELDS else self.allocated).append(address)
        return result

    def free(self, address):
        self.freed.append(address)
        self.real.free(address)


def test_every_output_array_is_freed_once():
    library = RecordingLibrary()
    out, vorout = run("Qzvne", TriangulateIO(pointlist=random_points(seed=12, n=30)), library=library)
    # out: points, markers, triangles, neighbours, edges, edge markers; vorout: points,
    # attributes (allocated even when empty, as Triangle does), edges, norms.
    assert len(library.allocated) == 10
    assert sorted(library.freed) == sorted(library.allocated)
    assert len(set(library.freed)) == len(library.freed)
    assert out.numberoftriangles > 0 and vorout.numberofedges > 0


def test_nothing_is_freed_after_an_error():
    library = RecordingLibrary()
    with pytest.raises(TriangulateError):
        run("Qz", TriangulateIO(pointlist=[[0, 0], [1, 1]]), library=library)
    assert library.allocated == library.freed == []


def test_holes_and_regions_alias_the_input_and_are_never_freed():
    library = RecordingLibrary()
    tio = TriangulateIO(
        pointlist=[[0, 0], [3, 0], [3, 3], [0, 3], [1, 1], [2, 1], [2, 2], [1, 2]],
        segmentlist=[[0, 1], [1, 2], [2, 3], [3, 0], [4, 5], [5, 6], [6, 7], [7, 4]],
        holelist=[[1.5, 1.5]],
        regionlist=[[0.5, 0.5, 1.0, 0.0]],
    )
    out, _ = run("Qzp", tio, library=library)
    assert sorted(library.aliased) == sorted([tio.holelist.ctypes.data, tio.regionlist.ctypes.data])
    assert not set(library.aliased) & set(library.freed)
    assert sorted(library.freed) == sorted(library.allocated)
    assert out.holelist.tolist() == [[1.5, 1.5]] and not np.shares_memory(out.holelist, tio.holelist)


def test_the_foreign_call_releases_the_gil():
    # ctypes releases the GIL around every call through a CDLL function, and keeps it only for
    # PyDLL functions (flag FUNCFLAG_PYTHONAPI). The concurrency tests above show that calls
    # overlap; this pins the mechanism, so that long calls never block other Python threads.
    library = load_library()
    assert isinstance(library._cdll, ctypes.CDLL) and not isinstance(library._cdll, ctypes.PyDLL)
    assert not library._reentrant._flags_ & ctypes._FUNCFLAG_PYTHONAPI
    # The calls go through the same functions without argtypes: those must release it too.
    for function in (library._reentrant_unchecked, library._progress_unchecked):
        assert function is None or not function._flags_ & ctypes._FUNCFLAG_PYTHONAPI
