"""Finding and loading the triangle-rs shared library, and the C declarations of its ABI.

Which library is loaded, in this order (the first that exists wins):

1. the file named by the environment variable ``TRIANGLE_RS_LIBRARY`` (read once, at the first
   triangulation; if it is set but cannot be loaded, that is an error: no silent fallback);
2. the library bundled in the installed package (``pip install ./python`` puts it next to this file);
3. in a source checkout, ``target/release`` and then ``target/debug`` of the repository.
"""

from __future__ import annotations

import ctypes
import os
import sys
import threading
from pathlib import Path

ENVIRONMENT_VARIABLE = "TRIANGLE_RS_LIBRARY"


def library_file_name() -> str:
    """The file name cargo gives the library on this platform."""
    if sys.platform.startswith("win"):
        return "triangle_rs.dll"
    if sys.platform == "darwin":
        return "libtriangle_rs.dylib"
    return "libtriangle_rs.so"


class CTriangulateIO(ctypes.Structure):
    """Triangle 1.6's ``struct triangulateio``, field for field (168 bytes on LP64 and LLP64)."""

    _fields_ = [
        ("pointlist", ctypes.POINTER(ctypes.c_double)),
        ("pointattributelist", ctypes.POINTER(ctypes.c_double)),
        ("pointmarkerlist", ctypes.POINTER(ctypes.c_int)),
        ("numberofpoints", ctypes.c_int),
        ("numberofpointattributes", ctypes.c_int),
        ("trianglelist", ctypes.POINTER(ctypes.c_int)),
        ("triangleattributelist", ctypes.POINTER(ctypes.c_double)),
        ("trianglearealist", ctypes.POINTER(ctypes.c_double)),
        ("neighborlist", ctypes.POINTER(ctypes.c_int)),
        ("numberoftriangles", ctypes.c_int),
        ("numberofcorners", ctypes.c_int),
        ("numberoftriangleattributes", ctypes.c_int),
        ("segmentlist", ctypes.POINTER(ctypes.c_int)),
        ("segmentmarkerlist", ctypes.POINTER(ctypes.c_int)),
        ("numberofsegments", ctypes.c_int),
        ("holelist", ctypes.POINTER(ctypes.c_double)),
        ("numberofholes", ctypes.c_int),
        ("regionlist", ctypes.POINTER(ctypes.c_double)),
        ("numberofregions", ctypes.c_int),
        ("edgelist", ctypes.POINTER(ctypes.c_int)),
        ("edgemarkerlist", ctypes.POINTER(ctypes.c_int)),
        ("normlist", ctypes.POINTER(ctypes.c_double)),
        ("numberofedges", ctypes.c_int),
    ]


#: ``int (*)(double ox, double oy, double dx, double dy, double ax, double ay, double area,
#: void *user_data)``: the per-call unsuitable test of ``triangulate_reentrant``.
UnsuitableCallback = ctypes.CFUNCTYPE(
    ctypes.c_int,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_double,
    ctypes.c_void_p,
)

#: ``void (*)(int phase, int64_t done, int64_t estimate, void *user_data)``: the progress report
#: of ``triangulate_progress`` (phase 0 Delaunay, 1 segments, 2 refinement, 3 output).
ProgressCallback = ctypes.CFUNCTYPE(None, ctypes.c_int, ctypes.c_int64, ctypes.c_int64, ctypes.c_void_p)

_IO_POINTER = ctypes.POINTER(CTriangulateIO)
_byref = ctypes.byref


class Library:
    """A loaded triangle-rs library with the functions this package calls declared.

    ``ctypes.CDLL`` releases the GIL for the duration of every foreign call, so calls from
    several threads run in parallel.
    """

    def __init__(self, path: str | os.PathLike[str]):
        self.path = str(path)
        self._cdll = ctypes.CDLL(self.path)
        # The same library, for the functions that return at once (the last message, `trifree`):
        # called through `PyDLL`, they keep the GIL, which saves releasing and taking it again
        # (~0.2 µs a call, a few calls per triangulation). `triangulate_*` release it.
        quick = ctypes.PyDLL(self.path, handle=self._cdll._handle)
        try:
            reentrant = self._cdll.triangulate_reentrant
            last_error = quick.triangulate_last_error
            trifree = quick.trifree
        except AttributeError as missing:
            raise OSError(
                f"{self.path} is not a triangle-rs library: {missing}. The Python package needs "
                "triangulate_reentrant, triangulate_last_error and trifree."
            ) from None
        reentrant.argtypes = [
            ctypes.c_char_p,
            _IO_POINTER,
            _IO_POINTER,
            _IO_POINTER,
            UnsuitableCallback,
            ctypes.c_void_p,
            ctypes.POINTER(ctypes.c_int),
        ]
        reentrant.restype = ctypes.c_int
        # `triangulate_progress` (reentrant, with progress reports); absent from older builds.
        self._progress = getattr(self._cdll, "triangulate_progress", None)
        if self._progress is not None:
            self._progress.argtypes = reentrant.argtypes + [ProgressCallback]
            self._progress.restype = ctypes.c_int
        last_error.argtypes = []
        last_error.restype = ctypes.c_char_p
        # `triangulate_last_warning`; absent from older builds.
        self._last_warning = getattr(quick, "triangulate_last_warning", None)
        if self._last_warning is not None:
            self._last_warning.argtypes = []
            self._last_warning.restype = ctypes.c_char_p
        trifree.argtypes = [ctypes.c_void_p]
        trifree.restype = None
        self._reentrant = reentrant
        # The same functions again, without `argtypes`, for the calls themselves: every argument
        # is a pointer object (bytes, `byref`, None, a callback) that ctypes passes as it is, and
        # the declared conversions cost ~1 µs a call, a third of a small triangulation's own time.
        # The declarations above stay: they document the ABI and check any other caller.
        self._reentrant_unchecked = self._unchecked("triangulate_reentrant")
        self._progress_unchecked = self._unchecked("triangulate_progress") if self._progress is not None else None
        self._last_error = last_error
        self._trifree = trifree
        # `free` is `trifree` itself: one foreign call per array released, no Python frame.
        self.free = trifree

    def _unchecked(self, name: str) -> "ctypes._CFuncPtr":
        """A new function object for ``name`` (item access does not cache it, unlike attribute
        access), returning a C int, with no ``argtypes``; it releases the GIL, as ``CDLL``'s do."""
        function = self._cdll[name]
        function.restype = ctypes.c_int
        return function

    def triangulate(
        self,
        switches: bytes,
        tin: CTriangulateIO,
        tout: CTriangulateIO,
        vorout: CTriangulateIO,
        unsuitable: "ctypes._CFuncPtr | None",
        cancel: ctypes.c_int,
        progress: "ctypes._CFuncPtr | None" = None,
    ) -> tuple[int, str, str]:
        """Runs ``triangulate_reentrant`` (``triangulate_progress`` with a ``progress``
        callback); returns its code, on failure the message, and on success the warning lines
        (``triangulate_last_warning``: one text, a line each, "" when none).

        Both are read on the calling thread right after the call, because the library keeps
        them per thread.
        """
        if progress is not None and self._progress is None:
            raise OSError(f"{self.path} has no triangulate_progress: rebuild the library")
        arguments = (
            switches,
            _byref(tin),
            _byref(tout),
            _byref(vorout),
            unsuitable,  # None: NULL, no per-call test
            None,
            _byref(cancel),
        )
        if progress is None:
            code = self._reentrant_unchecked(*arguments)
        else:
            code = self._progress_unchecked(*arguments, progress)
        if code == 0:
            text = self._last_warning() if self._last_warning is not None else None
            return 0, "", text.decode("utf-8", "replace") if text else ""
        message = self._last_error()
        return code, message.decode("utf-8", "replace") if message else "", ""

    def free(self, address: int) -> None:
        """Releases an array that the library allocated (``trifree``). Each instance replaces
        this method by ``trifree`` itself (see ``__init__``): the same call, without a Python
        frame."""
        self._trifree(address)

    def __repr__(self) -> str:
        return f"Library({self.path!r})"


def candidate_paths() -> list[Path]:
    """Where the library is looked for when ``TRIANGLE_RS_LIBRARY`` is not set, in order."""
    here = Path(__file__).resolve().parent
    name = library_file_name()
    candidates = [here / name]
    repository = here.parent.parent
    if (repository / "Cargo.toml").is_file():
        candidates += [repository / "target" / "release" / name, repository / "target" / "debug" / name]
    return candidates


_lock = threading.Lock()
_loaded: Library | None = None


def load_library() -> Library:
    """The library every call uses, loaded on first use (see the module docstring)."""
    global _loaded
    loaded = _loaded
    if loaded is not None:  # every call after the first: no lock needed to read a set global
        return loaded
    with _lock:
        if _loaded is None:
            _loaded = _find_and_load()
        return _loaded


def _find_and_load() -> Library:
    override = os.environ.get(ENVIRONMENT_VARIABLE)
    if override:
        try:
            return Library(override)
        except OSError as error:
            raise OSError(f"{ENVIRONMENT_VARIABLE}={override} cannot be loaded: {error}") from error
    tried = candidate_paths()
    for path in tried:
        if path.is_file():
            return Library(path)
    listing = "".join(f"\n  {path}" for path in tried)
    raise OSError(
        f"The triangle-rs shared library was not found. Looked for:{listing}\n"
        f"Install the package with `pip install ./python` (it builds and bundles the library), "
        f"or build it with `cargo build --release --lib` and set {ENVIRONMENT_VARIABLE} to the "
        f"path of {library_file_name()}."
    )
