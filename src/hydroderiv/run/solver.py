"""The steady solver run: start simpleFoam, watch residuals and forces, stop at force convergence.

The run is stopped through OpenFOAM's ``abort`` function object (written into controlDict by the case
set-up): creating the file ``STOP`` in the case makes the solver write the current state and exit cleanly
at the next iteration. Forces, not a fixed iteration count, decide when that happens.
"""

from __future__ import annotations

import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from ..case.numerics import GradientLimiters, switch_to_second_order_convection
from ..errors import HydroderivError
from ..forces import PrimeScales, read_history
from .monitor import ConvergenceCriterion, LogWatcher, force_divergence
from .openfoam import OpenFOAMError, application_command, fatal_error_excerpt, foam_environment

STOP_FILE = "STOP"
TOTAL_FORCES = "forces_total"  # name of the function object that integrates over every body patch


class SolverDivergedError(HydroderivError):
    """The solver diverged (NaN or exploding residuals or forces); the message says where and why."""


@dataclass
class Progress:
    """What a progress display needs after each poll of a running solver."""

    iteration: int
    residuals: dict[str, float]
    coefficients: np.ndarray | None  # latest (X', Y', Z', K', M', N')
    drift: np.ndarray | None  # latest window's trend / tolerance per coefficient (<= 1: flat, see is_met)
    elapsed: float


@dataclass
class RunResult:
    iterations: int
    converged: bool
    wall_time: float
    coefficients: np.ndarray  # mean over the convergence window, (X', Y', Z', K', M', N')
    components: dict[str, np.ndarray]  # the same mean, per body component
    history_iterations: np.ndarray = field(repr=False)
    history: np.ndarray = field(repr=False)  # (n, 6) coefficients per iteration


def component_function_name(component: str) -> str:
    """Name of the forces function object of one body component."""
    return f"forces_{component}"


def coefficient_history(case: Path, scales: PrimeScales, function: str = TOTAL_FORCES) -> tuple[np.ndarray, np.ndarray]:
    """Iterations and (X', Y', Z', K', M', N') per iteration from a forces function object's output."""
    post = Path(case) / "postProcessing"
    if not (post / function).is_dir():
        return np.empty(0), np.empty((0, 6))
    force = read_history(post, function, "force")
    moment = read_history(post, function, "moment")
    n = min(len(force), len(moment))
    return force.iterations[:n], scales.coefficients(force.total[:n], moment.total[:n])


def _stop(process: subprocess.Popen, grace_seconds: float = 10.0) -> None:
    """Stop the solver. SIGTERM first: mpirun passes it on to its ranks, while a SIGKILL of mpirun would
    leave the ranks running on the cores."""
    process.terminate()
    try:
        process.wait(timeout=grace_seconds)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()


def run_steady(
    case: Path,
    scales: PrimeScales,
    components: tuple[str, ...] = (),
    criterion: ConvergenceCriterion = ConvergenceCriterion(),
    n_procs: int = 1,
    on_progress: Callable[[Progress], None] | None = None,
    poll_seconds: float = 1.0,
    second_order_from: int | None = None,
    limiters_after_switch: GradientLimiters = GradientLimiters(),
    turbulence_convection: str = "second",
) -> RunResult:
    """Run simpleFoam in ``case`` until the forces converge; raise :class:`SolverDivergedError` on divergence.

    The case must already be set up (fields, controlDict with the ``forces_total`` and ``stop`` function
    objects, and, for ``n_procs > 1``, decomposed). The log is ``case/log.simpleFoam``.

    With ``second_order_from``, the case starts with first-order convection: at that iteration its
    convection schemes are switched to second order (simpleFoam re-reads fvSchemes), and convergence is
    judged only on windows of second-order iterations. ``limiters_after_switch`` are the
    gradient limiters after the switch, and ``turbulence_convection`` the turbulence fields' order after it
    (case/numerics.py, TURBULENCE_CONVECTION_ORDERS).
    """
    case = Path(case)
    (case / STOP_FILE).unlink(missing_ok=True)
    log_path = case / "log.simpleFoam"
    command = application_command(["simpleFoam"], n_procs)
    watcher = LogWatcher()
    start = time.monotonic()
    stop_requested = False
    diverged: str | None = None
    iterations, coefficients = np.empty(0), np.empty((0, 6))
    switch_pending = second_order_from is not None

    # Appending keeps the log of an interrupted run that this call resumes.
    with open(log_path, "a") as log_out, open(log_path) as log_in:
        process = subprocess.Popen(command, cwd=case, env=foam_environment(case), stdout=log_out, stderr=subprocess.STDOUT)
        try:
            while True:
                finished = process.poll() is not None
                watcher.feed(log_in.read())
                iterations, coefficients = coefficient_history(case, scales)
                diverged = watcher.divergence() or force_divergence(coefficients)
                if diverged:
                    _stop(process)
                    break
                drift = criterion.drift(coefficients) if len(coefficients) >= criterion.window else None
                if on_progress:
                    latest = coefficients[-1] if len(coefficients) else None
                    on_progress(Progress(watcher.iteration, dict(watcher.residuals), latest, drift, time.monotonic() - start))
                if finished:
                    break
                if switch_pending and watcher.iteration >= second_order_from:
                    switch_to_second_order_convection(case, limiters_after_switch, turbulence_convection)
                    switch_pending = False
                # the windows judged must hold second-order iterations only
                if not stop_requested and criterion.is_met(iterations, coefficients, since=second_order_from):
                    (case / STOP_FILE).touch()
                    stop_requested = True
                time.sleep(poll_seconds)
        except BaseException:
            _stop(process)
            raise
    (case / STOP_FILE).unlink(missing_ok=True)
    log_text = log_path.read_text(errors="replace")
    if diverged:
        raise SolverDivergedError(f"simpleFoam diverged in {case}: {diverged}; log: {log_path}")
    if process.returncode != 0:
        if "nan" in fatal_error_excerpt(log_text, 40).lower() or "sigFpe" in log_text:
            raise SolverDivergedError(f"simpleFoam diverged (floating-point exception) in {case}; log: {log_path}")
        raise OpenFOAMError(f"simpleFoam failed (exit code {process.returncode}) in {case}; log: {log_path}\n" + fatal_error_excerpt(log_text))
    if len(coefficients) == 0:
        raise OpenFOAMError(f"simpleFoam wrote no forces in {case}; log: {log_path}")
    # Converged if the criterion stopped the run (the solver may run an iteration or two past the request,
    # nudging a drift just over its tolerance), or if it holds at the end.
    converged = stop_requested or (not switch_pending and criterion.is_met(iterations, coefficients, since=second_order_from))
    per_component = {}
    for name in components:
        sampled, history = coefficient_history(case, scales, component_function_name(name))
        recent = sampled > sampled[-1] - criterion.window if len(sampled) else slice(None)
        per_component[name] = history[recent].mean(axis=0)
    return RunResult(
        iterations=int(iterations[-1]),
        converged=converged,
        wall_time=time.monotonic() - start,
        coefficients=coefficients[-criterion.window :].mean(axis=0),
        components=per_component,
        history_iterations=iterations,
        history=coefficients,
    )
