#!/usr/bin/env bash
# Set up what is missing, then run the test suite (it runs real OpenFOAM utilities).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
.venv/bin/python -m pytest -ra "$@"
