#!/usr/bin/env bash
# Creates (or completes) .venv with what the Python package, its tests and the demo need:
# numpy (the package), matplotlib (plots, examples), pytest (tests), setuptools and wheel (the
# package's build, which tests/test_packaging.py runs without build isolation), and the PyPI
# `triangle` package (its data directory holds Triangle's example files, read in place by the
# differential tests; never copied into the repository), and meshio (triangle_rs.to_meshio, its
# tests and the demo's .vtu), and dask and distributed (triangle_rs.distributed and its
# tests, which start their own LocalCluster). Idempotent.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/pip install -q --disable-pip-version-check numpy matplotlib pytest "setuptools>=64" wheel triangle meshio "dask[array]>=2023.1" "distributed>=2023.1"
