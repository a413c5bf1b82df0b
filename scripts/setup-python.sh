#!/usr/bin/env bash
# Creates .venv with what the Python package, its tests and the demo need.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/pip install -q --disable-pip-version-check numpy matplotlib pytest
