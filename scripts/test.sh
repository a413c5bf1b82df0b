#!/usr/bin/env bash
# Runs every test: Rust unit/property/differential tests, the C programs in ctests/ (driven by a
# cargo test), and the Python package's pytest suite.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --lib
cargo test --all-targets
if [ -d python/tests ]; then
  [ -x .venv/bin/python ] || bash scripts/setup-python.sh
  TRIANGLE_RS_LIBRARY="$PWD/target/release/libtriangle_rs.so" .venv/bin/python -m pytest -q python/tests
fi
