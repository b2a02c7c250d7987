"""Straight-ahead resistance against speed on one mesh, compared with the towing tank."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Callable

import numpy as np

from .._io import atomic_write_text
from ..case import KNOT, Condition
from ..case.setup import CaseSettings, latest_time_dir
from ..case.solver_options import SolverOptions
from ..experiments import RESISTANCE, error_percent, resistance_at
from ..forces import PrimeScales, read_history
from ..run.condition import run_condition
from ..run.monitor import ConvergenceCriterion
from ..run.solver import TOTAL_FORCES, Progress
from .workspace import Workspace


def _force_parts(case: Path, window: int) -> dict[str, float]:
    """Mean drag (N, -Fx) over the last window, split into pressure and viscous parts."""
    force = read_history(case / "postProcessing", TOTAL_FORCES, "force")
    return {part: float(-values[-window:, 0].mean()) for part, values in force.parts.items()}


def run_resistance(
    work: str | Path,
    level: str,
    speeds_knots: list[float],
    config: str = "AFF-8",
    body_dir: str | Path | None = None,
    n_procs: int = 2,
    criterion: ConvergenceCriterion = ConvergenceCriterion(monitored=("X",)),
    results_path: str | Path | None = None,
    log: Callable[[str], None] = print,
    on_progress: Callable[[float, Progress], None] | None = None,
    mesh_options: dict[str, float] | None = None,
    solver: SolverOptions = SolverOptions(),
) -> list[dict]:
    """Mesh once, then run every speed (lowest first, each warm-started from the one before), with the
    turbulence model and numerics of ``solver`` (their conditions kept apart from other choices').

    Results are saved after every speed (atomically), so an interrupted study loses nothing finished and
    resumes where it stopped.
    """
    ws = Workspace(Path(work), level, mesh_options=tuple(sorted((mesh_options or {}).items())), solver=solver)
    body = ws.body(config, body_dir)
    mesh = ws.mesh(body, log=log, n_procs=n_procs)
    settings = CaseSettings(length=body.reference.length, components=body.component_names, n_procs=n_procs,
                            max_iterations=criterion.max_iterations, solver=solver)
    experiment_key = config.upper() if body_dir is None else None
    points = []
    previous = None
    results_path = Path(results_path) if results_path else ws.root / "resistance.json"
    for knots in sorted(speeds_knots):
        condition = Condition(speed=knots * KNOT)
        case = ws.condition_dir(condition.name)
        log(f"[{body.name} {level}] {knots:.2f} kn ({condition.speed:.3f} m/s): {case}")
        record = run_condition(
            case, ws.mesh_dir, condition, settings, criterion, warm_start=previous,
            on_progress=(lambda p, k=knots: on_progress(k, p)) if on_progress else None,
        )
        previous = latest_time_dir(case)
        parts = _force_parts(case, criterion.window)
        measured = resistance_at(experiment_key, knots) if experiment_key else None
        scales = PrimeScales(settings.fluid.rho, condition.speed, body.reference.length)
        point = {
            "speed_knots": knots,
            "speed_m_s": round(condition.speed, 5),
            "resistance_N": round(-record["force_N"][0], 3),
            "pressure_N": round(parts["pressure"], 3),
            "viscous_N": round(parts["viscous"], 3),
            "side_force_N": round(record["force_N"][1], 4),
            "vertical_force_N": round(record["force_N"][2], 4),
            "CT": -record["force_N"][0] / (scales.force / body.reference.length**2 * body.reference.wetted_area),
            "experiment_N": measured,
            "error_pct": round(error_percent(-record["force_N"][0], measured), 2) if measured else None,
            "iterations": record["iterations"],
            "converged": record["converged"],
            "wall_seconds": record["wall_seconds"],
            "warm_started": record["warm_start"] is not None,
            "yplus": record["yplus"],
        }
        point.update(
            body=body.name,
            level=level,
            turbulence_model=solver.turbulence_model,
            cells=mesh["cells"],
            experiment_source=RESISTANCE[experiment_key]["source"] if experiment_key in RESISTANCE else None,
        )
        points.append(point)
        # The results file is a list of points, rewritten whole after each finished speed.
        atomic_write_text(results_path, json.dumps(points, indent=2) + "\n")
    return points


def max_abs_error_pct(points: list[dict]) -> float | None:
    errors = [abs(p["error_pct"]) for p in points if p["error_pct"] is not None]
    return float(np.max(errors)) if errors else None
