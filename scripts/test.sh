#!/usr/bin/env bash
# Runs every check and test: formatting and lints (cargo fmt --check, clippy -D warnings), Rust
# unit/property/differential tests against Debian's Triangle, the C programs in ctests/ (driven by
# a cargo test), the seeded fuzz driver, and the Python package's pytest suite. Works alone on a
# fresh machine: installs the reference Triangle and the Python environment when missing.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-reference.sh
# Idempotent: also completes a .venv made before a new test dependency was added. Before the Rust
# tests: their differential tests read Triangle's example files from the PyPI `triangle` package in it.
bash scripts/setup-python.sh
if ! cargo fmt --version >/dev/null 2>&1 || ! cargo clippy --version >/dev/null 2>&1; then
  rustup component add rustfmt clippy
fi
cargo fmt --all --check
cargo clippy --all-targets -- -D warnings
cargo build --release --lib
cargo test --all-targets
# The tests import the package from python/ (tests/conftest.py) and load this library.
TRIANGLE_RS_LIBRARY="$PWD/target/release/libtriangle_rs.so" .venv/bin/python -m pytest -q python/tests
