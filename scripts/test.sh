#!/usr/bin/env bash
# Runs every test: Rust unit/property/differential tests, the C programs in ctests/ (driven by a
# cargo test), and the Python package's pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
# Idempotent: also completes a .venv made before a new test dependency was added. First: the
# Rust differential tests read Triangle's example files from the PyPI `triangle` package in it.
bash scripts/setup-python.sh
cargo build --release --lib
cargo test --all-targets
if [ -d python/tests ]; then
  # The tests import the package from python/ (tests/conftest.py) and load this library.
  TRIANGLE_RS_LIBRARY="$PWD/target/release/libtriangle_rs.so" .venv/bin/python -m pytest -q python/tests
fi
