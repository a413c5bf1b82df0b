"""Errors: raised as TriangulateError (or ValueError/TypeError for malformed arguments) with the
library's message, never a crash; the library keeps working afterwards."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import triangle_rs
from triangle_rs import TriangulateError, TriangulateIO, triangulate

PYTHON_DIR = Path(__file__).resolve().parent.parent


def test_fewer_than_three_points():
    with pytest.raises(TriangulateError, match="at least three") as info:
        triangulate("Q", TriangulateIO(pointlist=[[0, 0], [1, 1]]))
    # Code written for the PyPI package catches ValueError or RuntimeError.
    assert isinstance(info.value, ValueError) and isinstance(info.value, RuntimeError)
    assert info.value.code != 0
    with pytest.raises(ValueError, match="at least three"):
        triangle_rs.triangulate({"vertices": [[0, 0], [1, 1]]})
    with pytest.raises(RuntimeError, match="at least three"):
        triangle_rs.delaunay([])


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_coordinates(bad):
    with pytest.raises(TriangulateError, match="not finite"):
        triangulate("Q", TriangulateIO(pointlist=[[0, 0], [1, 0], [bad, 1]]))


def test_bad_switches():
    tio = TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]])
    with pytest.raises(TriangulateError, match="Maximum area must be greater than zero"):
        triangulate("Qa0", tio)
    with pytest.raises(ValueError, match="ASCII"):
        triangulate("Qé", tio)
    with pytest.raises(ValueError, match="NUL"):
        triangulate("Q\0", tio)


def test_wrong_argument_types():
    with pytest.raises(TypeError):
        triangle_rs.triangulate(42)
    with pytest.raises(TypeError):
        triangle_rs.triangulate({"vertices": [[0, 0], [1, 0], [0, 1]]}, 5)


def test_library_keeps_working_after_errors():
    for _ in range(3):
        with pytest.raises(TriangulateError):
            triangulate("Q", TriangulateIO(pointlist=[[0, 0]]))
        out, _ = triangulate("Q", TriangulateIO(pointlist=[[0, 0], [1, 0], [0, 1]]))
        assert out.numberoftriangles == 1


def _run_python(code: str, **environment: str) -> subprocess.CompletedProcess:
    env = {**os.environ, **environment, "PYTHONPATH": str(PYTHON_DIR)}
    return subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=120)


def test_environment_variable_overrides_the_library(tmp_path):
    missing = tmp_path / "nowhere" / "libtriangle_rs.so"
    result = _run_python(
        "import triangle_rs\n"
        "try:\n    triangle_rs.delaunay([[0, 0], [1, 0], [0, 1]])\n"
        "except OSError as e:\n    print('OSError:', e)\n",
        TRIANGLE_RS_LIBRARY=str(missing),
    )
    assert result.returncode == 0, result.stderr
    assert "OSError: TRIANGLE_RS_LIBRARY=" in result.stdout and str(missing) in result.stdout


def test_a_library_without_the_reentrant_entry_is_refused():
    # Debian's Triangle exports triangulate/trifree only (and exits the process on errors).
    reference = Path("/usr/lib/libtriangle-1.6.so")
    if not reference.exists():
        pytest.skip("the reference Triangle library is not installed")
    result = _run_python(
        "import triangle_rs\n"
        "try:\n    triangle_rs.delaunay([[0, 0], [1, 0], [0, 1]])\n"
        "except OSError as e:\n    print('OSError:', e)\n",
        TRIANGLE_RS_LIBRARY=str(reference),
    )
    assert "is not a triangle-rs library" in result.stdout, result.stdout + result.stderr


def test_import_needs_only_numpy_and_ctypes():
    # `import *` takes every name of __all__, the plot functions included: none may pull in
    # matplotlib (1.3 s) or meshio before it is used.
    result = _run_python(
        "import sys\n"
        "import triangle_rs\n"
        "from triangle_rs import *\n"
        "print(sorted(m for m in ('matplotlib', 'meshio', 'scipy', 'cffi') if m in sys.modules))\n"
        "print(sorted(set(triangle_rs.__all__) - set(globals())))\n"
    )
    assert result.returncode == 0, result.stderr
    first, second = result.stdout.splitlines()
    assert first == "[]" and second == "[]"


def test_a_mesh_short_of_the_asked_quality_warns():
    # 300 points in a square 800 units in the last place wide at 10^15: the coordinates cannot
    # hold a 30° mesh. The call succeeds (a valid mesh) and says so, with or without Q.
    rng = np.random.default_rng(5)
    far = 1e15 + rng.random((300, 2)) * 100.0
    with pytest.warns(RuntimeWarning, match="precision") as record:
        out = triangle_rs.triangulate({"vertices": far}, "q30Q")
    assert len(out["triangles"]) > 0
    # One warning, at this line.
    assert len(record) == 1 and record[0].filename == __file__
    # The same points 10^6 times nearer to their doubles reach the angle, with no warning.
    near = 1e9 + rng.random((300, 2)) * 1e-3
    import warnings as python_warnings

    with python_warnings.catch_warnings():
        python_warnings.simplefilter("error", RuntimeWarning)
        out = triangle_rs.triangulate({"vertices": near}, "q30Q")
    assert len(out["triangles"]) > 0
