"""The Triangulate.jl-style call: ``triangulate(switches, tio) -> (out, vorout)``, and the machinery
every API of this package goes through (errors, warnings, the per-call unsuitable callback,
Ctrl-C)."""

from __future__ import annotations

import ctypes
import math
import os
import queue
import re
import signal
import sys
import threading
import time
import warnings
from typing import Callable, Optional

import numpy as np

from ._library import CTriangulateIO, Library, ProgressCallback, UnsuitableCallback, load_library
from .report import Report, TriangulateWarning, print_notes, set_last_report
from .report import _last as _last_report
from .triangulateio import (
    FIELD_READER,
    OutputReader,
    TriangulateIO,
    input_arrays,
    input_struct,
    read_output,
    read_values,
    release_outputs,
    release_values,
    struct_values,
)

#: ``unsuitable(x1, y1, x2, y2, x3, y3, area) -> bool``: the corners of a triangle (counter-
#: clockwise) and its area; ``True`` asks for the triangle to be split (switch ``u``).
Unsuitable = Callable[[float, float, float, float, float, float, float], bool]

#: ``progress(phase, done, estimate)``: told of a call's progress; ``phase`` is one of
#: :data:`PHASES`, ``estimate`` is 0 when unknown (for refinement: the vertices inserted plus the
#: work waiting, which grows as refinement finds more). ``progress=True`` shows a bar instead.
Progress = Callable[[str, int, int], None]

#: The phases of a call, in the order they run.
PHASES = ("delaunay", "segments", "refinement", "output")

# Running a call in the worker thread that makes it interruptible costs tens of microseconds
# (handing it over and waking the waiting thread), more than a small triangulation takes: the
# lecture's 5-vertex domain with `pq30` took 101 µs through it, 16.5 µs in the library. So only
# calls that can run long use it: those with large inputs, and refining calls (the library polls
# the cancel flag while refining) unless they are predicted small: at most
# `_SHORT_REFINEMENT_POINTS` input points, no user test (`u`, a Python callback) or regional or
# per-triangle bounds (`a` without a number), no mesh to refine (`r`), and a global area bound,
# if any, that the square on the coordinates' range holds at most `_SHORT_REFINEMENT_TRIANGLES`
# times (and no callback or progress display). Such a call usually takes well under a
# millisecond; Ctrl-C during one is handled when it returns. (A misprediction, say a sliver-thin
# domain whose refinement the library stops as a runaway, waits as long as the runs up to that
# limit take: a 1×10⁻⁶ strip, 1.7 s with `pq30`, 2.7 s with `pq40`.)
_REFINING_SWITCHES = frozenset("qauDL")
_LARGE_INPUT_POINTS = 50_000
_SHORT_REFINEMENT_POINTS = 512
_SHORT_REFINEMENT_TRIANGLES = 4096
# `a` and the number after it, as the library reads it (digits, a point, an exponent).
_AREA_SWITCH = re.compile(r"a((?:\d+\.?\d*|\.\d+)(?:e[-+]?\d+)?)?")

# How often the waiting main thread wakes up to let Python run its signal handlers (Ctrl-C) while
# the library works in another thread. A signal that the kernel delivers to the main thread wakes
# it at once; one delivered to another thread (numpy's BLAS threads do not block signals) waits
# for this poll, and two signals that wait together are handled in the order of their numbers.
# Waking up 100 times a second costs nothing measurable; the call itself returns as soon as the
# library does.
_INTERRUPT_POLL_SECONDS = 0.01


class TriangulateError(ValueError, RuntimeError):
    """The library refused the input or failed; the message is the library's.

    It derives from both ``ValueError`` and ``RuntimeError`` so that code written for the PyPI
    ``triangle`` package, which raises ``ValueError`` for too few vertices and ``RuntimeError``
    for failed triangulations, catches it unchanged.
    """

    def __init__(self, message: str, code: int = 1):
        super().__init__(message)
        self.code = code


def triangulate(
    switches: str,
    tio: TriangulateIO,
    *,
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
) -> tuple[TriangulateIO, TriangulateIO]:
    """Triangulates, meshes or refines ``tio`` as Triangle does with ``switches``.

    ``switches`` are Triangle's (for instance ``"pq30a0.01Q"``; see the README). Numbers may use
    exponents (``a1e-5``). All indices are 0-based: ``z`` is always added. Returns
    ``(out, vorout)``: the mesh, and the Voronoi diagram (empty unless ``v``).

    ``unsuitable(x1, y1, x2, y2, x3, y3, area) -> bool`` is the user test of switch ``u``: it is
    called for this call only (no global state), from the thread running the call. An exception
    it raises stops the refinement and is re-raised here. Without it, ``u`` applies Triangle's
    built-in test (see the README).

    Raises :class:`TriangulateError` with the library's message when the input or the switches
    are refused. The GIL is released while the library works. Ctrl-C (KeyboardInterrupt), or any
    exception raised while the call runs, asks the library to stop refining and is re-raised once
    it has returned.

    ``progress=True`` shows a progress bar on stderr (tqdm when it is installed, a plain line
    otherwise); a callable ``progress(phase, done, estimate)`` is told instead (see
    :data:`Progress`).
    """
    if not isinstance(switches, str):
        raise TypeError(f"switches must be a str, got {type(switches).__name__}")
    if not isinstance(tio, TriangulateIO):
        raise TypeError(f"tio must be a TriangulateIO, got {type(tio).__name__}")
    if unsuitable is not None and "u" not in switches:
        raise ValueError("an unsuitable callback is used only with the switch 'u': add it to the switches")
    return run(switches + "z", tio, unsuitable=unsuitable, progress=progress)


def encode_switches(switches: str) -> bytes:
    """The switch string as the library reads it (ASCII, no NUL)."""
    if "\0" in switches:
        raise ValueError("switches must not contain a NUL character")
    try:
        return switches.encode("ascii")
    except UnicodeEncodeError:
        raise ValueError(f"switches must be ASCII text, got {switches!r}") from None


def run(
    switches: str,
    tio: TriangulateIO,
    *,
    unsuitable: Optional[Unsuitable] = None,
    library: Optional[Library] = None,
    progress: "Progress | bool | None" = None,
) -> tuple[TriangulateIO, TriangulateIO]:
    """The raw call: ``switches`` as given (no ``z`` added). Every API ends here (or in
    :func:`run_arrays`, the same call on arrays).

    The library always gets ``Q`` (so it prints nothing itself), and what it says besides the
    mesh is sorted here (:mod:`triangle_rs.report`): notes (duplicate vertices ignored, ...) are
    printed to stdout only with ``V`` and kept in :func:`triangle_rs.last_report`; problems (a
    bound not reached, ...) make one :class:`TriangulateWarning`, at the caller's line.
    """
    lib = library if library is not None else load_library()
    set_last_report(None)
    out, vorout, text = _call(lib, switches, tio, unsuitable, progress)
    _report(switches, text)
    return TriangulateIO._from_arrays(out), TriangulateIO._from_arrays(vorout)


def run_arrays(
    switches: str,
    arrays: "dict[str, np.ndarray]",
    *,
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
    read: "tuple[OutputReader | None, OutputReader | None]" = (FIELD_READER, FIELD_READER),
) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
    """:func:`run` without ``TriangulateIO`` objects, for the entry points that take and return
    plain arrays: ``arrays`` maps field names to input arrays as
    :func:`~triangle_rs.triangulateio.normalize` returns them (absent fields left out, in the
    order of ``FIELDS``); returns the mesh and the Voronoi diagram as dictionaries of the arrays
    present that ``read`` asks for (field names -> arrays by default; ``None`` reads nothing)."""
    lib = load_library()
    _last_report.report = None  # `set_last_report(None)`, inline (as below): every call runs this
    out, vorout, text = _call(lib, switches, arrays, unsuitable, progress, read)
    if text or "V" in switches:
        _report(switches, text)
    else:  # nothing to print or warn of: what `_report` does then
        _last_report.report = Report(switches, text)
    return out, vorout


#: switches -> (what the library gets, whether the call may run long): per process, not per call.
_PARSED_SWITCHES: dict[str, tuple[bytes, bool, "float | None"]] = {}
_PARSED_SWITCHES_KEPT = 256


def _parse_switches(switches: str) -> tuple[bytes, bool, "float | None"]:
    """The encoded switches, whether they refine, and for a refinement that may be predicted
    small (see `_SHORT_REFINEMENT_POINTS`) its global area bound (``inf`` for none), else None."""
    parsed = _PARSED_SWITCHES.get(switches)
    if parsed is None:
        encoded = encode_switches(switches if "Q" in switches else "Q" + switches)
        refines = bool(_REFINING_SWITCHES.intersection(switches))
        bound: "float | None" = None
        if refines and "u" not in switches and "r" not in switches:
            bound = math.inf
            for match in _AREA_SWITCH.finditer(switches):
                if match.group(1) is None:
                    bound = None  # regional bounds: no prediction
                    break
                bound = min(bound, float(match.group(1)))
        parsed = (encoded, refines, bound)
        if len(_PARSED_SWITCHES) >= _PARSED_SWITCHES_KEPT:
            _PARSED_SWITCHES.clear()
        _PARSED_SWITCHES[switches] = parsed
    return parsed


def _call(
    lib: Library,
    switches: str,
    tio: "TriangulateIO | dict[str, np.ndarray]",
    unsuitable: Optional[Unsuitable] = None,
    progress: "Progress | bool | None" = None,
    read: "tuple[OutputReader | None, OutputReader | None]" = (FIELD_READER, FIELD_READER),
) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray], str]:
    """One library call: the mesh's and the Voronoi diagram's arrays (as ``read`` asks: field
    name -> array, the fields present, by default) and the warning lines (one text). ``tio`` is a
    ``TriangulateIO`` or its input arrays (as for :func:`run_arrays`). Every array the library
    allocated is released, read or not."""
    encoded, refines, bound = _PARSED_SWITCHES.get(switches) or _parse_switches(switches)
    arrays = input_arrays(tio) if isinstance(tio, TriangulateIO) else tio
    c_in = input_struct(arrays)  # points into `arrays`, which this frame keeps alive
    c_out, c_vorout = CTriangulateIO(), CTriangulateIO()
    cancel = ctypes.c_int(0)
    if unsuitable is None and not progress and not refines:
        points = arrays.get("pointlist")
        if points is None or len(points) < _LARGE_INPUT_POINTS:
            # The common short call: no callback, on the calling thread (see `_ForeignCall`).
            # Each output struct is unpacked once, for reading and releasing.
            out_values = vorout_values = None
            try:
                code, message, text = lib.triangulate(encoded, c_in, c_out, c_vorout, None, cancel, None)
                out_values = struct_values(c_out)
                vorout_values = struct_values(c_vorout)
                return _outputs(code, message, text, read, read_values, out_values, vorout_values)
            finally:
                if vorout_values is None:  # the call raised: release whatever it left
                    release_outputs(lib.free, c_out, c_vorout)
                else:
                    release_values(lib.free, out_values, vorout_values)
    callback_errors: list[BaseException] = []
    c_callback = _wrap_unsuitable(unsuitable, cancel, callback_errors) if unsuitable is not None else None
    display = _ProgressDisplay() if progress is True else None
    report = display.update if display is not None else (progress or None)
    c_progress = _wrap_progress(report, cancel, callback_errors) if report is not None else None

    points = arrays.get("pointlist")
    if points is not None and len(points) >= _LARGE_INPUT_POINTS:
        may_run_long = True
    else:
        may_run_long = refines and not (
            unsuitable is None and not progress and _predicted_small(bound, points)
        )
    foreign: Optional[_ForeignCall] = None
    try:
        if may_run_long:

            def call(_inputs: dict = arrays) -> tuple[int, str, str]:
                # `_inputs` holds the input arrays as long as the library may read them.
                return lib.triangulate(encoded, c_in, c_out, c_vorout, c_callback, cancel, c_progress)

            foreign = _ForeignCall(call)
            code, message, text = foreign.run_interruptibly(cancel)
        else:
            # A short call runs on the calling thread (see `_ForeignCall`).
            code, message, text = lib.triangulate(encoded, c_in, c_out, c_vorout, c_callback, cancel, c_progress)
        if callback_errors:
            raise callback_errors[0]
        return _outputs(code, message, text, read, read_output, c_out, c_vorout)
    finally:
        if display is not None:
            display.close()
        # `run_interruptibly` returns or raises only once the library is done with the structs.
        if foreign is None or foreign.finished():
            release_outputs(lib.free, c_out, c_vorout)


def _predicted_small(bound: "float | None", points: "np.ndarray | None") -> bool:
    """Whether a refinement whose switches give ``bound`` (see :func:`_parse_switches`) of
    ``points`` is predicted small (see `_SHORT_REFINEMENT_POINTS`)."""
    if bound is None or points is None or len(points) > _SHORT_REFINEMENT_POINTS:
        return False
    if math.isinf(bound) or len(points) == 0:
        return True
    # The square on the coordinates' whole range holds the bounding box. In Python's own min and
    # max over at most 1024 numbers: numpy's reductions cost some 4 µs each whatever the size.
    values = points.reshape(-1).tolist()
    extent = max(values) - min(values)
    return extent * extent <= _SHORT_REFINEMENT_TRIANGLES * bound


def _outputs(
    code: int,
    message: str,
    text: "str | list[str]",
    read: "tuple[OutputReader | None, OutputReader | None]",
    read_one: Callable,
    out: object,
    vorout: object,
) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray], str]:
    """What :func:`_call` returns for a finished call: its error raised, else the mesh's and the
    Voronoi diagram's arrays read by ``read_one`` from ``out`` and ``vorout`` (structs or their
    unpacked values) as ``read`` asks, and the warning lines as one text."""
    if code != 0:
        raise TriangulateError(message or f"triangulate failed (code {code})", code)
    if not isinstance(text, str):  # a stand-in library's list of lines
        text = "\n".join(text)
    read_out, read_vorout = read
    return (
        read_one(out, read_out) if read_out is not None else {},
        read_one(vorout, read_vorout) if read_vorout is not None else {},
        text,
    )


def _report(switches: str, text: str) -> None:
    """Sorts what the call said besides its mesh, prints the notes with ``V`` and warns once of
    the problems (see :mod:`triangle_rs.report`). ``V`` takes no number, so each one in the
    switches is one level of verbosity."""
    report = Report(switches, text)
    set_last_report(report)
    if "V" in switches:
        print_notes(report, switches.count("V"))
    if text and report.problems:
        _warn_at_caller(report.warning_message())


_PACKAGE_DIRECTORY = os.path.dirname(os.path.abspath(__file__)) + os.sep
_in_package: dict[str, bool] = {}


def _warn_at_caller(message: str) -> None:
    """One :class:`TriangulateWarning`, attributed to the first frame outside this package:
    the user's line, whichever public function it called (computed, not a fixed
    ``stacklevel``: the entry points are one to three frames above ``run``)."""
    frame = sys._getframe(0)
    level = 1
    while frame is not None:
        filename = frame.f_code.co_filename
        inside = _in_package.get(filename)
        if inside is None:
            inside = _in_package[filename] = os.path.abspath(filename).startswith(_PACKAGE_DIRECTORY)
        if not inside:
            break
        frame = frame.f_back
        level += 1
    warnings.warn(message, TriangulateWarning, stacklevel=level)


def _wrap_unsuitable(
    unsuitable: Unsuitable, cancel: ctypes.c_int, errors: list[BaseException]
) -> "ctypes._CFuncPtr":
    if not callable(unsuitable):
        raise TypeError("unsuitable must be callable as unsuitable(x1, y1, x2, y2, x3, y3, area)")

    def trampoline(x1: float, y1: float, x2: float, y2: float, x3: float, y3: float, area: float, _user_data: int) -> int:
        # ctypes cannot carry an exception through C: keep the first, stop the refinement
        # through the cancel flag, and let `run` re-raise it.
        if errors:
            return 0
        try:
            return 1 if unsuitable(x1, y1, x2, y2, x3, y3, area) else 0
        except BaseException as error:  # noqa: BLE001 - re-raised by `run`
            errors.append(error)
            cancel.value = 1
            return 0

    return UnsuitableCallback(trampoline)


def _wrap_progress(progress: Progress, cancel: ctypes.c_int, errors: list[BaseException]) -> "ctypes._CFuncPtr":
    if not callable(progress):
        raise TypeError("progress must be True or callable as progress(phase, done, estimate)")

    def trampoline(phase: int, done: int, estimate: int, _user_data: int) -> None:
        # As for the unsuitable test: an exception stops the call and is re-raised by `run`.
        if errors:
            return
        try:
            progress(PHASES[phase] if 0 <= phase < len(PHASES) else str(phase), done, estimate)
        except BaseException as error:  # noqa: BLE001 - re-raised by `run`
            errors.append(error)
            cancel.value = 1

    return ProgressCallback(trampoline)


class _ProgressDisplay:
    """``progress=True``: one tqdm bar per phase when tqdm is installed, else a line on stderr
    rewritten in place (at most ten times a second)."""

    def __init__(self) -> None:
        try:
            import tqdm  # noqa: F401 - optional

            self._tqdm = tqdm.tqdm
        except ImportError:
            self._tqdm = None
        self._bar = None
        self._phase: Optional[str] = None
        self._shown = 0.0

    def update(self, phase: str, done: int, estimate: int) -> None:
        if self._tqdm is not None:
            if phase != self._phase:
                self.close()
                self._bar = self._tqdm(total=estimate or None, desc=phase, unit=" items", leave=False)
                self._phase = phase
            bar = self._bar
            bar.total = max(estimate, done) or None
            bar.n = done
            bar.refresh()
            return
        now = time.monotonic()
        if phase == self._phase and now - self._shown < 0.1 and done != estimate:
            return
        self._phase, self._shown = phase, now
        total = f" of about {estimate}" if phase == "refinement" else f" of {estimate}"
        sys.stderr.write(f"\rtriangle-rs: {phase}: {done}{total if estimate else ''}\033[K")
        sys.stderr.flush()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
        elif self._tqdm is None and self._phase is not None:
            sys.stderr.write("\n")
            sys.stderr.flush()
            self._phase = None


#: Signals a thread raises by its own faults: the kernel delivers them to that thread, and
#: blocking them would only make the process die without a report (faulthandler's).
_FAULT_SIGNALS = frozenset(
    getattr(signal, name)
    for name in ("SIGSEGV", "SIGBUS", "SIGFPE", "SIGILL", "SIGTRAP", "SIGABRT", "SIGSYS")
    if hasattr(signal, name)
)


def _block_outside_signals() -> None:
    """In a worker thread: blocks the signals that come from outside (Ctrl-C's SIGINT, SIGTERM,
    SIGUSR1, ...), so that the kernel delivers them to the main thread. Python runs their
    handlers there anyway, but only when that thread is interrupted: a signal delivered to the
    worker would wait for the main thread's next poll, and two such signals would be handled
    together, in the order of their numbers rather than of their arrival."""
    if hasattr(signal, "pthread_sigmask"):
        signal.pthread_sigmask(signal.SIG_BLOCK, set(signal.valid_signals()) - _FAULT_SIGNALS)


def _with_outside_signals_blocked(function: Callable[[], None]) -> None:
    _block_outside_signals()
    function()


class _Worker:
    """The thread that runs the main thread's interruptible calls (see :class:`_ForeignCall`):
    started by the first one and kept for the process, a daemon waiting for the next call.
    Starting a thread for every call costs ~75 µs; handing a call to a waiting thread ~20 µs.
    It runs one call at a time: :meth:`submit` says when it is busy. After ``os.fork`` the child
    makes its own (the parent's thread does not exist there)."""

    def __init__(self) -> None:
        self._calls: "queue.SimpleQueue[tuple[Callable[[Callable[[], None]], None], Callable[[], None]]]" = queue.SimpleQueue()
        # Held from `submit` until the call is done (released by the call through `idle`).
        self._busy = threading.Lock()
        self._thread = threading.Thread(target=self._serve, name="triangle_rs-worker", daemon=True)
        self._thread.start()

    def _serve(self) -> None:
        _block_outside_signals()
        while True:
            call, idle = self._calls.get()
            try:
                call(idle)
            except BaseException:  # noqa: BLE001 - pragma: no cover - the call keeps its errors
                pass

    def submit(self, call: Callable[[Callable[[], None]], None]) -> bool:
        """Runs ``call(idle)`` in the thread, unless it is busy (then returns False); ``call``
        calls ``idle()`` once it no longer needs the thread."""
        if not self._busy.acquire(blocking=False):
            return False
        once = threading.Lock()

        def idle() -> None:
            if once.acquire(blocking=False):  # the first of the call and `submit` frees the thread
                self._busy.release()

        try:
            if not self._thread.is_alive():  # pragma: no cover - it never returns; be safe anyway
                idle()
                return False
            self._calls.put((call, idle))
        except BaseException:
            # E.g. Ctrl-C around `put`: the thread is free again (a call queued all the same finds
            # itself never started, as the caller marks it, and returns at once).
            idle()
            raise
        return True


_the_worker: Optional[_Worker] = None
_worker_lock = threading.Lock()


def _worker() -> _Worker:
    """The process's :class:`_Worker`, started on first use."""
    global _the_worker
    worker = _the_worker
    if worker is None:
        with _worker_lock:
            if _the_worker is None:
                _the_worker = _Worker()
            worker = _the_worker
    return worker


def _forget_worker() -> None:
    """In a child made by ``os.fork``: the parent's worker thread is not there."""
    global _the_worker, _worker_lock
    _the_worker = None
    _worker_lock = threading.Lock()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_worker)


class _ForeignCall:
    """One library call that Ctrl-C can stop, and that no exception leaves running.

    Python handles signals only in the main thread and only between bytecodes, never inside a
    foreign call. So on the main thread the call runs in a worker thread while the main thread
    waits. Any exception raised in the waiting thread (KeyboardInterrupt, SystemExit from a
    signal handler, ...) sets the ``cancel`` flag that the library polls, and is re-raised only
    once the library has returned: never while it still runs (it writes into the output structs,
    and a daemon thread inside the library when the interpreter exits aborts the process).
    Further interrupts while waiting are absorbed; the first exception is the one raised.

    Completion is a plain attribute that the worker sets, not ``Thread.is_alive()``, which an
    interrupted ``join`` leaves false on Python 3.11 while the thread still runs. Off the main
    thread, or when the call is not ``interruptible`` (short calls), the call simply runs on the
    calling thread. The worker is the process's :class:`_Worker`, kept between calls.
    """

    _PENDING, _RUNNING, _DONE, _NEVER_STARTED = range(4)

    def __init__(self, function: Callable[[], tuple[int, str]], interruptible: bool = True):
        self._function = function
        self._interruptible = interruptible
        self._result: Optional[tuple[int, str]] = None
        self._error: Optional[BaseException] = None
        self._state_lock = threading.Lock()
        self._state = self._DONE if not interruptible else self._PENDING
        # Held by the caller while the worker runs; released by the worker when it is done, so
        # that the waiting thread wakes at once rather than at its next poll.
        self._finished_signal = threading.Lock()

    def finished(self) -> bool:
        """True once the library cannot touch the call's structs any more."""
        return self._state in (self._DONE, self._NEVER_STARTED)

    def _work(self, idle: Optional[Callable[[], None]] = None) -> None:
        """Runs the call (in the worker thread); ``idle`` tells the persistent worker that it is
        free again, before the waiting thread is woken (so that its next call finds it free)."""
        with self._state_lock:
            if self._state == self._NEVER_STARTED:
                # The caller gave up before this thread began: the library is never called.
                if idle is not None:
                    idle()
                return
            self._state = self._RUNNING
        try:
            self._result = self._function()
        except BaseException as error:  # noqa: BLE001 - re-raised on the calling thread
            self._error = error
        finally:
            with self._state_lock:
                self._state = self._DONE
            if idle is not None:
                idle()
            self._finished_signal.release()

    def run_interruptibly(self, cancel: ctypes.c_int) -> tuple[int, str]:
        if not self._interruptible or threading.current_thread() is not threading.main_thread():
            try:
                return self._function()
            finally:
                self._state = self._DONE
        self._finished_signal.acquire()
        pending: Optional[BaseException] = None
        try:
            if not _worker().submit(self._work):
                # The worker runs another call (this one comes from a signal handler run while
                # the main thread waits for it): a thread of its own.
                threading.Thread(
                    target=_with_outside_signals_blocked,
                    args=(self._work,),
                    name="triangle_rs-triangulate",
                    daemon=True,
                ).start()
        except BaseException as error:  # noqa: BLE001 - e.g. Ctrl-C inside Thread.start()
            pending = error
            cancel.value = 1
            with self._state_lock:
                if self._state == self._PENDING:
                    # The worker has not begun (and may never): make sure it never calls.
                    self._state = self._NEVER_STARTED
        while True:
            # The whole wait is inside `try`, its test and its loop included: a signal handler may
            # run (and raise) at any call or backward jump, and the worker may already be in the
            # library.
            try:
                while not self.finished():
                    self._finished_signal.acquire(timeout=_INTERRUPT_POLL_SECONDS)
                break
            except BaseException as error:  # noqa: BLE001 - re-raised once the library returned
                cancel.value = 1
                if pending is None:
                    pending = error
        if pending is not None:
            raise pending
        if self._error is not None:
            raise self._error
        assert self._result is not None
        return self._result
