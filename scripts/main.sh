#!/usr/bin/env bash
# Set up what is missing, then run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
.venv/bin/hydroderiv geometry --config all --out runs/geometry
