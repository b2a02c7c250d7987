#!/usr/bin/env bash
# Set up what is missing, then run the main job: a short real computation on the coarse mesh.
# AFF-8 (fully appended SUBOFF): build the geometry and the single coarse mesh, then the straight-ahead
# resistance at two of the towing-tank speeds, printed beside Liu & Huang (1998). About 15 minutes on
# 2 cores; run it again and it resumes from what is finished under runs/demo.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
.venv/bin/hydroderiv resistance --config AFF-8 --level coarse --speeds 5.93 10.0 --work runs/demo
