#!/usr/bin/env bash
# The README's main job: builds the library, sets up .venv, installs the Python package from
# python/ (which bundles the library) and runs every lecture example, writing one PNG per example
# to results/ (or to the directory given as the first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --lib
bash scripts/setup-python.sh
.venv/bin/pip install -q --disable-pip-version-check --force-reinstall --no-deps ./python
# Run from outside the source tree's python/ directory so that the installed package is used.
exec .venv/bin/python python/examples/lecture_examples.py "${1:-results}"
