"""Watching a steady solver: residuals from its log, force convergence, divergence."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import ConfigurationError

COEFFICIENTS = ("X", "Y", "Z", "K", "M", "N")
_TIME = re.compile(r"^Time = (\S+)", re.M)
_RESIDUAL = re.compile(r"Solving for (\w+), Initial residual = ([^,]+),")


@dataclass
class LogWatcher:
    """Reads a solver log incrementally: the latest iteration and the initial residual of each field.

    A field's first solve in an iteration carries its initial residual. Reads may end anywhere, also right
    after a ``Time = N`` line, so the fields already seen in the current iteration are tracked across reads:
    a later solve of the same field in that iteration (a corrector) must not overwrite its value, and a field
    not yet solved keeps the previous iteration's value on show.
    """

    iteration: int = 0
    residuals: dict[str, float] = field(default_factory=dict)
    _buffer: str = ""
    _seen: set[str] = field(default_factory=set)  # fields solved so far in the current iteration

    def feed(self, text: str) -> None:
        text = self._buffer + text
        # keep an unfinished last line for the next call
        cut = text.rfind("\n") + 1
        self._buffer = text[cut:]
        for block in re.split(r"(?=^Time = )", text[:cut], flags=re.M):
            times = _TIME.findall(block)
            if times:
                try:
                    self.iteration = int(float(times[-1]))
                except ValueError:
                    pass
                self._seen = set()
            for name, value in _RESIDUAL.findall(block):
                if name not in self._seen:
                    self._seen.add(name)
                    self.residuals[name] = _to_float(value)

    def divergence(self, limit: float = 1e3) -> str | None:
        """A reason to call the run diverged, or None."""
        for name, value in self.residuals.items():
            if not math.isfinite(value):
                return f"the {name} residual is {value} at iteration {self.iteration}"
            if value > limit:
                return f"the {name} residual exploded to {value:.3g} at iteration {self.iteration}"
        return None


def _to_float(text: str) -> float:
    try:
        return float(text)
    except ValueError:
        return math.nan  # OpenFOAM prints 'nan' / '-nan'


@dataclass(frozen=True)
class ConvergenceCriterion:
    """Forces converged: the mean of every monitored coefficient has stopped drifting.

    A straight line is fitted to each coefficient over the last ``window`` iterations; its rise across the
    window must be at most ``rel_tol`` of the load scale, or at most ``abs_tol`` (prime units). The load
    scale is the largest force coefficient for the forces and the largest moment coefficient for the
    moments (window means). So a small component of a large load, the Z' beside a drift's Y', is held to
    the accuracy of that load rather than of itself. The loads a condition's derivatives come from
    (``own_scale``, which a study sets for each condition: Y' and N' in a drift or a yaw turn, see
    ``Condition.defining_loads``) are held to their own size instead: in a turn at r' = 0.1 the side force
    is a fifth of the drag, so against the drag it would be settled to five times the tolerance (a coarse
    AFF-8 turn stopped 6.8 % short of its settled side force at a 1.5 % tolerance, and Y'r came out 5 % low).

    A trend, not a peak-to-peak spread, because a steady solution is not always still: flow past the sail
    at drift sheds gently and keeps the side force swinging by a few per cent about a fixed mean. The
    window mean is the result; the window's standard deviation is its iterative uncertainty.

    ``min_iterations`` keeps the start-up transient out of the window; ``max_iterations`` ends a run that
    never settles (it is then reported as not converged). A warm start from a neighbouring condition first
    overshoots and then recovers, and a straight line fitted through such a V is flat: with a window that
    could reach back to iteration 21, the AFF-8 resistance runs at 16 and 17.8 knots (warm-started from the
    speed below, their drag dipping by 10 % at iteration 50 and back by 200) stopped at 121 iterations, 4.5-6 %
    below the drag they converge to. So the window starts at iteration 50 at the earliest, after the dip.
    """

    window: int = 100
    rel_tol: float = 0.005
    abs_tol: float = 2e-6
    min_iterations: int = 150
    max_iterations: int = 3000
    monitored: tuple[str, ...] = ("X", "Y", "Z", "K", "M", "N")  # which of (X', Y', Z', K', M', N') must settle
    own_scale: tuple[str, ...] = ()  # which are held to their own size, not to the largest load's

    def __post_init__(self):
        unknown = sorted(set(self.monitored) - set(COEFFICIENTS)) + sorted(set(self.own_scale) - set(COEFFICIENTS))
        if unknown:
            raise ConfigurationError(f"unknown load coefficient(s) {', '.join(unknown)}: "
                                     f"the loads are {', '.join(COEFFICIENTS)}")

    def holding_to_own_size(self, loads: tuple[str, ...]) -> ConvergenceCriterion:
        """This criterion with ``loads`` held to their own size as well (a condition's defining loads)."""
        return replace(self, own_scale=tuple(dict.fromkeys((*self.own_scale, *loads))))

    def drift(self, coefficients: np.ndarray) -> np.ndarray:
        """Per monitored coefficient: its drift over the window over the tolerance it must meet (<= 1 passes)."""
        recent = np.asarray(coefficients)[-self.window :]
        offsets = np.arange(len(recent)) - (len(recent) - 1) / 2.0
        slope = offsets @ (recent - recent.mean(axis=0)) / max(offsets @ offsets, 1.0)
        drift = np.abs(slope) * (len(recent) - 1)
        mean = np.abs(recent.mean(axis=0))
        scale = np.repeat([mean[:3].max(), mean[3:].max()], 3)
        own = [COEFFICIENTS.index(name) for name in self.own_scale]
        scale[own] = mean[own]
        allowed = np.maximum(self.rel_tol * scale, self.abs_tol)
        columns = [COEFFICIENTS.index(name) for name in self.monitored]
        return (drift / allowed)[columns]

    def is_met(self, iterations: np.ndarray, coefficients: np.ndarray) -> bool:
        if len(iterations) < self.window or iterations[-1] < self.min_iterations:
            return False
        return bool(np.all(self.drift(coefficients) <= 1.0))


def force_divergence(coefficients: np.ndarray, limit: float = 1.0) -> str | None:
    """A reason to call the run diverged from its force coefficients, or None.

    Prime force coefficients of a streamlined body are of order 1e-3; a value beyond ``limit`` (or NaN)
    means the solution has blown up even if the residuals have not noticed yet.
    """
    if len(coefficients) == 0:
        return None
    last = coefficients[-1]
    if not np.all(np.isfinite(last)):
        return "the forces became NaN"
    if np.abs(last).max() > limit:
        return f"the force coefficients blew up to {np.abs(last).max():.3g}"
    return None
