"""One condition from set-up to a saved result, resumable and atomic.

A finished condition is marked by its ``result.json`` (written atomically, last). Running it again
reads that file instead of recomputing. An interrupted condition restarts from its latest written
iteration.
"""

from __future__ import annotations

import json
import shutil
import time
from dataclasses import asdict
from pathlib import Path
from typing import Callable

import numpy as np

from .._io import atomic_write_text
from ..case.conditions import Condition
from ..case.numerics import has_second_order_convection
from ..case.setup import CaseSettings, latest_time_dir, write_condition_case
from ..errors import HydroderivError
from ..forces import COEFFICIENT_NAMES, PrimeScales
from ..forces.surface_flow import FIELD as WALL_SHEAR
from ..forces.surface_flow import PRESSURE_FIELD, YPLUS_FIELD, loads_along_x, reversed_flow, yplus_along_x
from ..mesh.design import is_thin_part
from ..mesh.quality import patch_faces, patch_owners
from .monitor import ConvergenceCriterion
from .openfoam import openfoam_version_from_log, run_application
from .solver import Progress, run_steady

RESULT_FILE = "result.json"


def read_result(case: Path) -> dict | None:
    path = Path(case) / RESULT_FILE
    return json.loads(path.read_text()) if path.is_file() else None


def _yplus_summary(case: Path) -> dict:
    """min / mean / max y+ per wall patch at the last write (from the yPlus function object)."""
    out = {}
    for path in sorted((case / "postProcessing/yPlus").glob("*/yPlus*.dat")):
        for line in path.read_text().splitlines():
            if line.startswith("#") or not line.strip():
                continue
            words = line.split()
            if len(words) >= 5:
                out[words[1]] = {"min": float(words[2]), "max": float(words[3]), "mean": float(words[4])}
    return out


# The record keys _wall_reports fills, each with the OpenFOAM fields it reads; those in FUNCTION_OBJECT_FIELDS
# are written by a function object of the same name, which can make them again from a saved solution.
WALL_REPORTS = {"reversed_flow": (WALL_SHEAR,), "yplus_along_x": (YPLUS_FIELD, WALL_SHEAR),
                "loads_along_x": (PRESSURE_FIELD, WALL_SHEAR)}
FUNCTION_OBJECT_FIELDS = (WALL_SHEAR, YPLUS_FIELD)


def _wall_reports(case: Path, condition: Condition, settings: CaseSettings) -> dict[str, dict]:
    """The reports on the wall flow of a run, by record key (empty without a body): the reversed flow per
    body part, the y+ along each part that is not thin (the hull), and the side and vertical force along
    each part.

    Reports, not results: one that cannot be made gives its message instead, and the forces stand. The
    parts' faces and the cells next to them are read once for all (a few seconds on a medium mesh).
    """
    if not settings.components:
        return {key: {} for key in WALL_REPORTS}
    time_dir = latest_time_dir(case)
    scales = PrimeScales(settings.fluid.rho, condition.speed, settings.length)
    makers = {
        "reversed_flow": lambda faces, owners: reversed_flow(time_dir, faces, condition.inflow(),
                                                             condition.angular_velocity(settings.length)),
        "yplus_along_x": lambda faces, owners: {part: yplus_along_x(time_dir, faces, part, owners=owners[part])
                                                for part in faces if not is_thin_part(part)},
        "loads_along_x": lambda faces, owners: loads_along_x(time_dir, faces, owners, scales),
    }
    try:
        faces = patch_faces(case / "constant/polyMesh", settings.components)
        owners = patch_owners(case / "constant/polyMesh", list(faces))
    except (HydroderivError, OSError) as error:
        return {key: {"error": str(error)} for key in makers}
    reports = {}
    for key, make in makers.items():
        try:
            reports[key] = make(faces, owners)
        except (HydroderivError, OSError) as error:
            reports[key] = {"error": str(error)}
    return reports


def lacking_wall_reports(record: dict) -> list[str]:
    """The wall reports of a finished record that add_wall_reports would make (again): absent, an error, or
    y+ slices from before they gave the y+ from the wall shear stress."""
    def lacking(key: str, report: dict | None) -> bool:
        if report is None or "error" in report:
            return True
        return key == "yplus_along_x" and any(slices and "friction_mean" not in slices[0] for slices in report.values())

    return [key for key in WALL_REPORTS if lacking(key, record.get(key))]


def add_wall_reports(case: str | Path, settings: CaseSettings, record: dict | None = None) -> dict[str, dict]:
    """The wall-flow reports of a finished condition by record key (see ``_wall_reports``).

    A condition finished before a report existed lacks it (one that failed to be made holds its error; y+
    slices may lack the y+ from the wall shear stress): those are made now from the saved solution,
    post-processing the fields they need (seconds), and the record is rewritten atomically with them added.
    ``record`` is the condition's result when the caller has read it already.
    """
    case = Path(case)
    record = record if record is not None else read_result(case)
    if record is None:
        raise HydroderivError(f"{case} has no finished result")
    missing = lacking_wall_reports(record)
    if missing:
        latest = latest_time_dir(case)
        for field in dict.fromkeys(field for key in missing for field in WALL_REPORTS[key]):
            if field in FUNCTION_OBJECT_FIELDS and latest is not None and settings.components and not (latest / field).is_file():
                run_application(case, ["simpleFoam", "-postProcess", "-func", field, "-latestTime"],
                                log_name=field)
        made = _wall_reports(case, Condition(**record["condition"]), settings)
        record.update({key: made[key] for key in missing})
        atomic_write_text(case / RESULT_FILE, json.dumps(record, indent=2) + "\n")
    return {key: record[key] for key in WALL_REPORTS}


def _resumable(case: Path, n_procs: int) -> bool:
    """True if an interrupted run left written iterations to continue from."""
    if n_procs > 1:
        processor = case / "processor0"
        return processor.is_dir() and latest_time_dir(processor) is not None
    return latest_time_dir(case) is not None


def run_condition(
    case: str | Path,
    mesh_case: str | Path,
    condition: Condition,
    settings: CaseSettings,
    criterion: ConvergenceCriterion = ConvergenceCriterion(),
    warm_start: Path | None = None,
    on_progress: Callable[[Progress], None] | None = None,
) -> dict:
    """Run ``condition`` on the mesh of ``mesh_case`` in ``case`` and return its result record."""
    case = Path(case)
    done = read_result(case)
    if done is not None:
        return done
    started = time.monotonic()
    n = settings.n_procs
    resumed = case.is_dir() and _resumable(case, n)
    if not resumed:
        if case.exists():
            shutil.rmtree(case)
        write_condition_case(case, mesh_case, condition, settings, warm_start)
        if n > 1:
            run_application(case, ["decomposePar", "-force"], log_name="decomposePar")
    scales = PrimeScales(settings.fluid.rho, condition.speed, settings.length)
    # An interrupted cold start resumes where its schemes are: still first order before the switch.
    if resumed:
        first_order = settings.second_order and not has_second_order_convection(case)
        second_order_from = settings.first_order_start if first_order else None
    else:
        second_order_from = settings.second_order_from(warm_start)
    result = run_steady(case, scales, settings.components, criterion, n, on_progress,
                        second_order_from=second_order_from, limiters_after_switch=settings.limiters_after_start(),
                        turbulence_convection=settings.solver.turbulence_convection)
    if n > 1:
        run_application(case, ["reconstructPar", "-latestTime"], log_name="reconstructPar")
        for processor in case.glob("processor*"):
            shutil.rmtree(processor)
    force_scale, moment_scale = scales.force, scales.moment
    window = result.history[-criterion.window :]  # the iterations the result is the mean of
    record = {
        "condition": asdict(condition),
        "name": condition.name,
        "converged": result.converged,
        "iterations": result.iterations,
        "wall_seconds": round(result.wall_time, 1),  # the solver alone
        # the solver plus case set-up, warm start, decomposition and reconstruction (this call only)
        "total_seconds": round(time.monotonic() - started, 1),
        "resumed": resumed,
        "warm_start": str(warm_start) if warm_start else None,
        # None: second-order convection from the first iteration (or switched before an interruption)
        "second_order_from": second_order_from,
        **settings.solver.record(),
        # limited during the first-order start only, so the converged solution is the unlimited one
        "limited_pressure_gradient_at_start": settings.limits_pressure_gradient_only_at_start(warm_start),
        "n_procs": n,
        "coefficients": dict(zip(COEFFICIENT_NAMES, map(float, result.coefficients))),
        "force_N": (result.coefficients[:3] * force_scale).tolist(),
        "moment_Nm": (result.coefficients[3:] * moment_scale).tolist(),
        "components": {
            name: dict(zip(COEFFICIENT_NAMES, map(float, values))) for name, values in result.components.items()
        },
        # peak-to-peak and standard deviation of each coefficient over the averaging window: the iterative
        # uncertainty of the mean above
        "window_spread": np.ptp(window, axis=0).tolist(),
        "window_std": np.std(window, axis=0).tolist(),
        "yplus": _yplus_summary(case),
        **_wall_reports(case, condition, settings),
        "reference": {"rho": settings.fluid.rho, "speed": condition.speed, "length": settings.length},
        "openfoam_version": openfoam_version_from_log((case / "log.simpleFoam").read_text(errors="replace")),
    }
    atomic_write_text(case / RESULT_FILE, json.dumps(record, indent=2) + "\n")
    return record
