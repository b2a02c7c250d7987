"""A captive-test study: one TOML file names the body, the mesh level, the speed and the sweeps.

Example::

    [study]
    body = "AFF-8"            # a SUBOFF configuration, or body_dir = "path written by hydroderiv geometry"
    level = "coarse"
    speed_knots = 6.5
    n_procs = 2
    work = "runs/aff8-coarse" # optional; default: runs/<file stem>
    method = "hybrid"         # optional: "hybrid" (default) or "classic" (whole domain rotates, for verification)
    turbulence_model = "kOmegaSST"  # optional: or "ShihQuadraticKE", "LienCubicKE", "realizableKE", "SpalartAllmaras",
                                    # "LRR" (a Reynolds-stress model; needs turbulence_convection = "first") (case/fluid.py)
    limit_pressure_gradient = false  # optional: true, or "start" (case/numerics.py)
    limit_velocity_gradient = "everywhere"  # optional: or "convection", "nowhere" (case/numerics.py)
    velocity_limiter_coefficient = 1.0  # optional: k of that limiter, in (0, 1]; smaller limits less (case/numerics.py)
    pressure_velocity_coupling = "SIMPLE"  # optional: or "SIMPLEC", for walls resolved to y+ ~ 1 (case/numerics.py)
    turbulence_convection = "second"  # optional: or "first", the turbulence fields convected upwind (case/numerics.py)

    [sweeps]                  # one variable at a time about straight-ahead
    drift_deg = [-8, -4, 4, 8]
    pitch_deg = [-8, -4, 4, 8]
    yaw_rate_prime = [-0.2, -0.1, 0.1, 0.2]
    pitch_rate_prime = []
    roll_rate_prime = []      # p' = p L / U: the roll damping K'p (and Y'p, N'p)

    [[conditions]]            # any further combined conditions
    drift_deg = 4
    yaw_rate_prime = 0.2

    [convergence]             # optional, see ConvergenceCriterion
    rel_tol = 0.005

    [mesh]                    # optional: MeshDesign options, e.g. appendage_extra_level = 2
    thin_max_layers = 4

    [fit]                     # optional, see DerivativeFit
    nonlinear = "abs"         # "abs" (Gertler-Hagen v|v|, default), "cubic" or "none" (one point each side)
    offset = true             # fit a constant too (default): absorbs an asymmetry such as the sail's
    max_angle_deg = 8         # optional: fit drift and pitch only up to this angle (beyond it, e.g. a stall,
                              # the points stay in the table's single points per magnitude)
"""

from __future__ import annotations

import json
import os
import tomllib
import traceback
from dataclasses import dataclass, field, fields, replace
from pathlib import Path
from typing import Callable

import numpy as np

from .._io import atomic_write_text
from ..case import KNOT, Condition
from ..case.conditions import SWEEP_KEYS
from ..case.frames import FRAME_METHODS
from ..case.setup import CaseSettings, latest_time_dir
from ..case.solver_options import STUDY_TABLE_KEYS, SolverOptions
from ..derivatives.fit import NONLINEAR_TERMS
from ..errors import ConfigurationError, HydroderivError
from ..forces import PrimeScales
from ..forces.surface_flow import describe_reversed_flow, describe_yplus_along_x
from ..geometry import Body
from ..mesh.design import mesh_options
from ..run.condition import add_wall_reports, lacking_wall_reports, read_result, run_condition
from ..run.monitor import ConvergenceCriterion
from ..run.solver import Progress
from .workspace import Workspace, is_suboff

FAILED_FILE = "failed.json"
STUDY_KEYS = {"body", "body_dir", "level", "speed", "speed_knots", "n_procs", "work", "method", *STUDY_TABLE_KEYS}


def running_marker(case: Path) -> Path:
    """The pid file of a condition being run. It sits beside the case, not in it: a fresh condition's
    case directory is cleared when the run starts, which would delete a marker inside it."""
    return case.parent / f"{case.name}.running"


@dataclass(frozen=True)
class Study:
    path: Path
    body: str | None
    body_dir: Path | None
    level: str
    speed: float  # m/s
    n_procs: int
    work: Path
    conditions: tuple[Condition, ...]
    criterion: ConvergenceCriterion = field(default_factory=ConvergenceCriterion)
    method: str = "hybrid"
    solver: SolverOptions = field(default_factory=SolverOptions)  # turbulence model and numerics
    nonlinear: str = "abs"  # the derivative fit's nonlinear term
    fit_offset: bool = True
    max_angle_deg: float | None = None  # static fits use the points within this angle (None: all)
    mesh_options: tuple[tuple[str, float | bool], ...] = ()  # the [mesh] table: MeshDesign fields, as (name, value)

    @classmethod
    def load(cls, path: str | Path) -> Study:
        path = Path(path)
        try:
            data = tomllib.loads(path.read_text())
        except FileNotFoundError:
            raise ConfigurationError(f"no study file {path}")
        except tomllib.TOMLDecodeError as error:
            raise ConfigurationError(f"{path}: not valid TOML: {error}")
        head = data.get("study", {})
        unknown = set(data) - {"study", "sweeps", "conditions", "convergence", "fit", "mesh"}
        if unknown:
            raise ConfigurationError(f"{path}: unknown section(s) {', '.join(sorted(unknown))}")
        body, body_dir = head.get("body"), head.get("body_dir")
        if (body is None) == (body_dir is None):
            raise ConfigurationError(f"{path}: [study] needs exactly one of body (a SUBOFF configuration) or body_dir")
        if body is not None and not is_suboff(body):
            raise ConfigurationError(f"{path}: unknown configuration {body!r}; use a SUBOFF name or body_dir")
        if ("speed_knots" in head) == ("speed" in head):
            raise ConfigurationError(f"{path}: [study] needs exactly one of speed (m/s) or speed_knots")
        speed = float(head["speed"]) if "speed" in head else float(head["speed_knots"]) * KNOT
        conditions = [Condition(speed)]
        for key, values in data.get("sweeps", {}).items():
            if key not in SWEEP_KEYS:
                raise ConfigurationError(f"{path}: unknown sweep {key!r}; sweeps are {', '.join(SWEEP_KEYS)}")
            conditions += [Condition(speed, **{key: float(v)}) for v in values]
        for extra in data.get("conditions", []):
            bad = set(extra) - set(SWEEP_KEYS)
            if bad:
                raise ConfigurationError(f"{path}: unknown condition keys {', '.join(sorted(bad))}")
            conditions.append(Condition(speed, **{k: float(v) for k, v in extra.items()}))
        unique = tuple(dict((c.name, c) for c in conditions).values())
        method = head.get("method", "hybrid")
        if method not in FRAME_METHODS:
            raise ConfigurationError(f"{path}: unknown method {method!r}; choose one of {', '.join(FRAME_METHODS)}")
        bad_keys = set(head) - STUDY_KEYS
        if bad_keys:
            raise ConfigurationError(f"{path}: unknown [study] key(s) {', '.join(sorted(bad_keys))}")
        solver = SolverOptions.from_study_table(head, str(path))
        allowed = {f.name for f in fields(ConvergenceCriterion)}
        conv = data.get("convergence", {})
        if set(conv) - allowed:
            raise ConfigurationError(f"{path}: unknown convergence keys {', '.join(sorted(set(conv) - allowed))}")
        fit = data.get("fit", {})
        fit_keys = {"nonlinear", "offset", "max_angle_deg"}
        if set(fit) - fit_keys:
            raise ConfigurationError(f"{path}: unknown [fit] keys {', '.join(sorted(set(fit) - fit_keys))}")
        max_angle = fit.get("max_angle_deg")
        if max_angle is not None and (not isinstance(max_angle, (int, float)) or max_angle <= 0):
            raise ConfigurationError(f"{path}: [fit] max_angle_deg = {max_angle!r} must be a positive angle in degrees")
        nonlinear = fit.get("nonlinear", "abs")
        if nonlinear not in NONLINEAR_TERMS:
            raise ConfigurationError(f"{path}: unknown nonlinear term {nonlinear!r}; choose one of {', '.join(NONLINEAR_TERMS)}")
        return cls(
            path=path,
            body=body.upper() if body else None,
            body_dir=Path(body_dir) if body_dir else None,
            level=head.get("level", "coarse"),
            speed=speed,
            n_procs=int(head.get("n_procs", 2)),
            work=Path(head.get("work", Path("runs") / path.stem)),
            conditions=unique,
            criterion=_criterion(conv, path),
            method=method,
            solver=solver,
            nonlinear=nonlinear,
            fit_offset=bool(fit.get("offset", True)),
            max_angle_deg=None if max_angle is None else float(max_angle),
            mesh_options=tuple(sorted(mesh_options(data.get("mesh", {}), str(path)).items())),
        )

    @property
    def workspace(self) -> Workspace:
        return Workspace(self.work, self.level, self.method, self.mesh_options, self.solver)

    def case_settings(self, body: Body) -> CaseSettings:
        """What every condition of this study needs besides the condition itself."""
        return CaseSettings(length=body.reference.length, components=body.component_names, n_procs=self.n_procs,
                            max_iterations=self.criterion.max_iterations, method=self.method, solver=self.solver)

    def prime_scales(self, body: Body) -> PrimeScales:
        """The prime system's scales of this study's loads: its fluid, its speed and the body's length."""
        return PrimeScales(self.case_settings(body).fluid.rho, self.speed, body.reference.length)

    def criterion_for(self, condition: Condition) -> ConvergenceCriterion:
        """When ``condition`` has converged: the study's criterion, with the loads its derivatives come from
        held to their own size rather than to the largest load's (a turn's side force beside the drag)."""
        return self.criterion.holding_to_own_size(condition.defining_loads)

    def frame_method(self, condition: Condition) -> str:
        """The frame ``condition`` is solved in. Without rotation both methods are the same translation, so
        it is the hybrid set-up's, whatever the study's method."""
        return self.method if condition.is_turning else "hybrid"

    def case_dir(self, condition: Condition) -> Path:
        """Where ``condition`` runs: a classic study shares the straight runs of the hybrid one on the same
        mesh instead of repeating them (see :meth:`frame_method`)."""
        return replace(self.workspace, method=self.frame_method(condition)).condition_dir(condition.name)

    def status(self) -> dict[str, list[str]]:
        """Conditions by state: done, running, failed, left."""
        states: dict[str, list[str]] = {"done": [], "running": [], "failed": [], "left": []}
        for c in self.conditions:
            case = self.case_dir(c)
            if read_result(case) is not None:
                states["done"].append(c.name)
            elif _running(case):
                states["running"].append(c.name)
            elif (case / FAILED_FILE).is_file():
                states["failed"].append(c.name)
            else:
                states["left"].append(c.name)
        return states


def _criterion(table: dict, path: Path) -> ConvergenceCriterion:
    """The study's [convergence] table as a criterion; a bad load name is reported with the file's name."""
    try:
        return ConvergenceCriterion(**table)
    except ConfigurationError as error:
        raise ConfigurationError(f"{path}: [convergence] {error}") from None


def _running(case: Path) -> bool:
    pid_file = running_marker(case)
    if not pid_file.is_file():
        return False
    try:
        os.kill(int(pid_file.read_text().strip()), 0)
        return True
    except (ValueError, ProcessLookupError, PermissionError):
        return False


def _coordinates(c: Condition) -> np.ndarray:
    """Where a condition sits in the sweep space; degrees and rates scaled to comparable flow changes."""
    return np.array([np.sin(np.radians(c.drift_deg)), np.sin(np.radians(c.pitch_deg)), c.yaw_rate_prime,
                     c.pitch_rate_prime, c.roll_rate_prime])


def run_order(conditions: tuple[Condition, ...]) -> list[Condition]:
    """Straight-ahead first, then outward by distance from it, so each has a near finished neighbour."""
    return sorted(conditions, key=lambda c: (float(np.linalg.norm(_coordinates(c))), c.name))


def nearest_finished(condition: Condition, finished: dict[Path, Condition]) -> Path | None:
    """The solution of the finished condition closest to ``condition`` (finished: case dir -> condition)."""
    if not finished:
        return None
    here = _coordinates(condition)
    case = min(finished, key=lambda d: (float(np.linalg.norm(_coordinates(finished[d]) - here)), finished[d].name))
    return latest_time_dir(case)


def run_study(
    study: Study,
    log: Callable[[str], None] = print,
    on_progress: Callable[[Condition, Progress], None] | None = None,
    warm_start: bool = True,
) -> dict[str, dict]:
    """Mesh once, then run every condition on that mesh; finished ones are read back, never recomputed.

    A failing condition is recorded in its ``failed.json`` and the study goes on with the others.
    """
    ws = study.workspace
    body = ws.body(study.body, study.body_dir)
    ws.mesh(body, log=log, n_procs=study.n_procs)
    settings = study.case_settings(body)
    order = run_order(study.conditions)
    # Warm-start candidates: every condition already finished, by an earlier run of this study too, so a
    # resumed or retried condition starts from its nearest neighbour even when that one comes later in
    # the run order (a straight run that failed is retried from a finished drift, not from rest).
    finished: dict[Path, Condition] = {study.case_dir(c): c for c in order if read_result(study.case_dir(c))}
    results: dict[str, dict] = {}
    for number, condition in enumerate(order, start=1):
        case = study.case_dir(condition)
        done = read_result(case)
        if done is None:
            start = nearest_finished(condition, warm_start_candidates(study, condition, finished)) if warm_start else None
            log(f"[{number}/{len(order)}] {condition.name}" + (f" (warm start from {start.parent.name})" if start else " (cold start)"))
            case.mkdir(parents=True, exist_ok=True)
            (case / FAILED_FILE).unlink(missing_ok=True)
            atomic_write_text(running_marker(case), str(os.getpid()))
            try:
                done = run_condition(case, ws.mesh_dir, condition, settings, study.criterion_for(condition),
                                     warm_start=start,
                                     on_progress=(lambda p, c=condition: on_progress(c, p)) if on_progress else None)
            except HydroderivError as error:
                atomic_write_text(case / FAILED_FILE, json.dumps({"error": str(error), "trace": traceback.format_exc()}, indent=2))
                log(f"    failed: {error}")
                continue
            finally:
                running_marker(case).unlink(missing_ok=True)
            log(f"    {'converged' if done['converged'] else 'NOT converged'} in {done['iterations']} iterations, {done['wall_seconds']:.0f} s")
            for line in (describe_reversed_flow(done.get("reversed_flow", {})),
                         describe_yplus_along_x(done.get("yplus_along_x", {}))):
                if line:
                    log(f"    {line}")
        else:
            log(f"[{number}/{len(order)}] {condition.name}: done")
        finished[case] = condition
        results[condition.name] = done
    return results


def warm_start_candidates(study: Study, condition: Condition, finished: dict[Path, Condition]) -> dict[Path, Condition]:
    """The finished conditions that ``condition`` may start from: those solved in the same frame.

    A classic turn holds the fluid at rest far away, and the straight and drift runs (shared with the
    hybrid set-up) the inflow: each would be a worse start for the other than none.
    """
    frame = study.frame_method(condition)
    return {case: c for case, c in finished.items() if study.frame_method(c) == frame}


def study_wall_reports(study: Study, log: Callable[[str], None] = print) -> dict[str, dict[str, dict]]:
    """The wall-flow reports of every finished condition, by name and then record key: the reversed flow
    per part, the y+ along the hull and the loads along each part (see forces/surface_flow.py).

    Conditions finished before a report existed get it now from their saved solution.
    """
    body = study.workspace.body(study.body, study.body_dir)
    settings = study.case_settings(body)
    reports = {}
    for condition in run_order(study.conditions):
        case = study.case_dir(condition)
        record = read_result(case)
        if record is None:
            continue
        missing = lacking_wall_reports(record)
        if missing:
            names = {"reversed_flow": "reversed flow", "yplus_along_x": "y+ along x", "loads_along_x": "loads along x"}
            log(f"  {condition.name}: {', '.join(names[k] for k in missing)} from the saved solution ...")
        reports[condition.name] = add_wall_reports(case, settings, record)
    return reports
