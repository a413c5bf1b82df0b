"""Test setup: the tests import the package from this source tree (python/ goes first on
sys.path), so they need no installation; the library comes from TRIANGLE_RS_LIBRARY when it is
set (scripts/test.sh points it at target/release), else from the package's usual search."""

import os
import sys
from pathlib import Path

PYTHON_DIR = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(PYTHON_DIR))
os.environ.setdefault("MPLBACKEND", "Agg")

import triangle_rs  # noqa: E402


def pytest_report_header(config):
    try:
        return f"triangle_rs from {Path(triangle_rs.__file__).parent}, library {triangle_rs.library_path()}"
    except OSError as error:
        return f"triangle_rs library not loadable: {error}"
