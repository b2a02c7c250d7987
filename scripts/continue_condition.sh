#!/usr/bin/env bash
# Iterative-convergence check of one finished condition: copy its case (the finished condition is left as it
# is), run simpleFoam on for EXTRA more iterations from its last solution, and print the body's side force
# and yaw moment every 60 iterations. A result that the study's convergence criterion stopped
# too early shows here as loads that still creep.
#   scripts/continue_condition.sh CONDITION_DIR EXTRA COPY_DIR [RANKS]
# e.g. scripts/continue_condition.sh runs/study-aff3-medium-sa/conditions-SpalartAllmaras-grad-U-limited-in-convection/U3.34389_b0_a0_r+0.1_q0 600 runs/continue-aff3-r0.1
set -euo pipefail
cd "$(dirname "$0")/.."
src=$1 extra=$2 dst=$3 ranks=${4:-2}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
latest=$(ls -d "$src"/[0-9]* | xargs -n1 basename | sort -n | tail -1)
rm -rf "$dst" && mkdir -p "$dst"
cp -rL "$src/system" "$src/constant" "$dst/"
cp -r "$src/$latest" "$dst/"
sed -i "s/^endTime .*/endTime $((latest + extra));/; s/^writeInterval .*/writeInterval $((latest + extra));/" "$dst/system/controlDict"
(cd "$dst" && decomposePar -latestTime > log.decomposePar 2>&1 \
  && mpirun --allow-run-as-root -np "$ranks" simpleFoam -parallel > log.simpleFoam 2>&1 \
  && rm -rf processor*)
.venv/bin/python - "$dst" <<'EOF'
import sys
from pathlib import Path
from hydroderiv.forces.history import read_history
from hydroderiv.run.solver import TOTAL_FORCES

post = Path(sys.argv[1]) / "postProcessing"
force, moment = (read_history(post, TOTAL_FORCES, quantity) for quantity in ("force", "moment"))
print(f"{'iteration':>9} {'Y (N)':>10} {'N (N m)':>10}")
for k in list(range(0, len(force), 60)) + [len(force) - 1]:
    print(f"{force.iterations[k]:9.0f} {force.total[k, 1]:10.3f} {moment.total[k, 2]:10.3f}")
EOF
