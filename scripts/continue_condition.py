"""Iterative-convergence check of one finished condition.

Copies its case (the finished condition is left as it is), runs simpleFoam on for EXTRA more iterations from
its last solution and prints the body's side force and yaw moment every 60 iterations. A result that the
study's convergence criterion stopped too early shows here as loads that still creep.

    .venv/bin/python scripts/continue_condition.py CONDITION_DIR EXTRA COPY_DIR [--ranks 2]
        [--non-orthogonal-correction LIMIT]

With --non-orthogonal-correction the copy runs on with the surface-normal gradients' non-orthogonal
correction limited at LIMIT of the orthogonal part (1: the full correction) instead of the set-up's
(case/numerics.py, NON_ORTHOGONAL_CORRECTION): how much that limit moves a converged condition.

e.g. CONDITION_DIR = runs/study-aff3-medium-sa/conditions-SpalartAllmaras-grad-U-limited-in-convection/U3.34389_b0_a0_r+0.1_q0
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

from foamlib import FoamFile

from hydroderiv.case.numerics import NON_ORTHOGONAL_CORRECTION
from hydroderiv.case.setup import latest_time_dir
from hydroderiv.errors import HydroderivError
from hydroderiv.forces.history import read_history
from hydroderiv.run.openfoam import run_application
from hydroderiv.run.solver import TOTAL_FORCES


def with_non_orthogonal_correction(schemes: str, limit: float) -> str:
    """fvSchemes text with the set-up's limited non-orthogonal correction (laplacian and snGrad schemes)
    limited at ``limit`` instead, 0 < limit <= 1 (1 writes the full correction, "corrected")."""
    if not 0.0 < limit <= 1.0:
        raise HydroderivError(f"--non-orthogonal-correction {limit} must be in (0, 1] (1: the full correction)")
    if schemes.count(NON_ORTHOGONAL_CORRECTION) != 2:
        raise HydroderivError(f"fvSchemes does not hold the set-up's {NON_ORTHOGONAL_CORRECTION!r} in its "
                              "laplacian and snGrad schemes: not a case hydroderiv wrote, or already changed")
    return schemes.replace(NON_ORTHOGONAL_CORRECTION, "corrected" if limit == 1.0 else f"limited corrected {limit:g}")


def continue_condition(source: Path, extra: int, copy: Path, ranks: int,
                       non_orthogonal_correction: float | None = None) -> Path:
    """Run a copy of the finished condition ``source`` for ``extra`` more iterations, with the non-orthogonal
    correction limited at ``non_orthogonal_correction`` if given; its postProcessing folder."""
    latest = latest_time_dir(source)
    if latest is None:
        raise HydroderivError(f"{source} has no saved solution to continue from")
    schemes = None  # the new schemes, made (so checked) before an earlier copy is removed
    if non_orthogonal_correction is not None:
        schemes = with_non_orthogonal_correction((source / "system/fvSchemes").read_text(), non_orthogonal_correction)
    shutil.rmtree(copy, ignore_errors=True)
    copy.mkdir(parents=True)
    for folder in ("system", "constant"):
        shutil.copytree(source / folder, copy / folder, symlinks=True)  # the mesh stays a link: nothing writes it
    shutil.copytree(latest, copy / latest.name)
    end = round(float(latest.name)) + extra
    control = FoamFile(copy / "system/controlDict")
    control["endTime"] = end
    control["writeInterval"] = end  # one write, at the end
    if schemes is not None:
        (copy / "system/fvSchemes").write_text(schemes)
    if ranks > 1:
        run_application(copy, ["decomposePar", "-latestTime"])
    run_application(copy, ["simpleFoam"], n_procs=ranks)
    return copy / "postProcessing"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("condition", type=Path)
    parser.add_argument("extra", type=int, help="iterations to run on")
    parser.add_argument("copy", type=Path, help="where the copy runs (replaced)")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--non-orthogonal-correction", type=float, metavar="LIMIT",
                        help="run on with the non-orthogonal correction limited at LIMIT (1: full) instead")
    args = parser.parse_args()
    post = continue_condition(args.condition, args.extra, args.copy, args.ranks, args.non_orthogonal_correction)
    force, moment = (read_history(post, TOTAL_FORCES, quantity) for quantity in ("force", "moment"))
    print(f"{'iteration':>9} {'Y (N)':>10} {'N (N m)':>10}")
    for k in [*range(0, len(force), 60), len(force) - 1]:
        print(f"{force.iterations[k]:9.0f} {force.total[k, 1]:10.3f} {moment.total[k, 2]:10.3f}")


if __name__ == "__main__":
    main()
