#!/usr/bin/env bash
# Set up what is missing, then run the main job: a quick derivative study of the fully appended SUBOFF
# (AFF-8) on the coarse mesh. It meshes once, runs seven captive conditions (straight ahead, drift, pitch and
# steady turns) on that one mesh and prints the derivative table beside Roddy's (1990) experiments.
# About 19 minutes on 2 cores (2026-11-30; see README); run it again and it resumes from what is finished under
# runs/study-aff8-coarse-quick.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
.venv/bin/hydroderiv study run studies/aff8-coarse-quick.toml
