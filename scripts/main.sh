#!/usr/bin/env bash
# Set up what is missing, then run the main job: a quick derivative study of the fully appended SUBOFF
# (AFF-8) on the coarse mesh, with the turbulence set-up of the medium tables of record (Spalart-Allmaras).
# It meshes once, runs seven captive conditions (straight ahead, drift, pitch and steady turns) on that one
# mesh and prints the derivative table beside Roddy's (1990) experiments. About 10-15 minutes on 2 cores
# (2026-12-07, depending on the machine; see README); run it again and it resumes from what is finished under runs/study-aff8-coarse-sa.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
.venv/bin/hydroderiv study run studies/aff8-coarse-sa.toml
