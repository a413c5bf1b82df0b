"""`pip install ./python` builds the library with cargo and bundles it in the package, and the
installed package loads the bundled library when TRIANGLE_RS_LIBRARY is not set."""

import os
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

PYTHON_DIR = Path(__file__).resolve().parent.parent


def test_wheel_bundles_the_library_and_loads_it(tmp_path):
    pytest.importorskip("wheel", reason="scripts/setup-python.sh installs wheel for this build")
    build = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(tmp_path / "dist"), str(PYTHON_DIR)],
        capture_output=True,
        text=True,
        timeout=1800,
    )
    assert build.returncode == 0, build.stdout + build.stderr
    (wheel,) = (tmp_path / "dist").glob("*.whl")
    assert "-py3-none-" in wheel.name and not wheel.name.endswith("-any.whl")
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        assert "triangle_rs/libtriangle_rs.so" in names or "triangle_rs/libtriangle_rs.dylib" in names or "triangle_rs/triangle_rs.dll" in names
        assert "triangle_rs/__init__.py" in names and "triangle_rs/plotting.py" in names
        # The examples of our own making that get_data falls back to.
        assert "triangle_rs/data/A.poly" in names and "triangle_rs/data/bbox.1.area" in names
        archive.extractall(tmp_path / "site")

    env = {k: v for k, v in os.environ.items() if k not in ("TRIANGLE_RS_LIBRARY", "PYTHONPATH")}
    env["PYTHONPATH"] = str(tmp_path / "site")
    check = subprocess.run(
        [
            sys.executable,
            "-c",
            "import triangle_rs\n"
            "print(triangle_rs.library_path())\n"
            "print(len(triangle_rs.delaunay([[0, 0], [0, 1], [0.5, 0.5], [1, 1], [1, 0]])))\n"
            "print(len(triangle_rs.load(triangle_rs.data.OWN_DATA_DIRECTORY, 'A')['vertices']))\n",
        ],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert check.returncode == 0, check.stderr
    library, triangles, letter_a_vertices = check.stdout.splitlines()
    assert Path(library).parent == tmp_path / "site" / "triangle_rs"
    assert triangles == "4" and int(letter_a_vertices) > 3
