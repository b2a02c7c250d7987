"""Watching a steady solver: residuals from its log, force convergence, divergence."""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace

import numpy as np

from ..errors import ConfigurationError
from ..forces.coefficients import COEFFICIENT_NAMES as COEFFICIENTS  # the order of a load record's six columns
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
    """Forces converged: the mean of every monitored coefficient has stopped drifting, and a second look
    half a window or more later finds the same mean.

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

    But a straight line cannot see a V. A load that dips and recovers, as one warm-started from a
    neighbouring condition often does, gives a flat line whenever the bottom of the dip sits mid-window,
    however far the load still has to go: the main job's coarse AFF-8 turn at r' = +0.1 stopped there at
    iteration 127, its side force 8.9 % short of where it settles by iteration 200 (Y' dipped from 0.141e-3
    at iteration 66 to 0.123e-3 at 93 and was rising at 125). So the trend must also have been flat in an
    earlier window ending between one and half a window before, with a mean that agrees with the latest
    one's to the same tolerance. A load that has settled passes half a window after it first does; a V is rejected,
    since the earlier window holds its falling branch; an oscillation about a fixed mean still passes, at
    the same phase one period apart.

    ``min_iterations`` keeps the start-up transient out of the windows (each window's last iteration is at
    least that); ``max_iterations`` ends a run that never settles (it is then reported as not converged). A
    warm start from a neighbouring condition first overshoots and then recovers: with a window that could
    reach back to iteration 21, the AFF-8 resistance runs at 16 and 17.8 knots (warm-started from the speed
    below, their drag dipping by 10 % at iteration 50 and back by 200) stopped at 121 iterations, 4.5-6 %
    below the drag they converge to. So a window starts at iteration 50 at the earliest, after the dip.
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

    def _allowed(self, means: np.ndarray) -> np.ndarray:
        """The change each coefficient may show, from window means (rows: windows, columns: X' ... N')."""
        magnitude = np.abs(means)
        scale = np.repeat(np.stack([magnitude[:, :3].max(axis=1), magnitude[:, 3:].max(axis=1)], axis=1), 3, axis=1)
        own = [COEFFICIENTS.index(name) for name in self.own_scale]
        scale[:, own] = magnitude[:, own]
        return np.maximum(self.rel_tol * scale, self.abs_tol)

    def _windows(self, coefficients: np.ndarray, width: int) -> tuple[np.ndarray, np.ndarray]:
        """Means and trends (rise of the least-squares line across the window over the allowed change) of
        every full window of ``width`` samples, the first one first and the latest last; from running sums,
        so a run of thousands of iterations is judged at every poll without refitting each window."""
        y = np.asarray(coefficients, dtype=float)
        n = len(y)
        offsets = np.arange(width) - (width - 1) / 2.0
        # sum over a window of y and of (index within the window) * y, from cumulative sums
        sum_y = np.concatenate([np.zeros((1, 6)), np.cumsum(y, axis=0)])
        sum_jy = np.concatenate([np.zeros((1, 6)), np.cumsum(np.arange(n)[:, None] * y, axis=0)])
        starts = np.arange(n - width + 1)[:, None]
        window_y = sum_y[width:] - sum_y[:-width]
        window_iy = sum_jy[width:] - sum_jy[:-width] - starts * window_y
        means = window_y / width
        slope = (window_iy - (width - 1) / 2.0 * window_y) / max(offsets @ offsets, 1.0)
        return means, np.abs(slope) * (width - 1) / self._allowed(means)

    def drift(self, coefficients: np.ndarray) -> np.ndarray:
        """Per monitored coefficient: its drift over the latest window (or over every sample, while there
        are fewer) over the tolerance it must meet (<= 1 passes)."""
        recent = np.asarray(coefficients)[-self.window :]
        columns = [COEFFICIENTS.index(name) for name in self.monitored]
        return self._windows(recent, len(recent))[1][-1, columns]

    def is_met(self, iterations: np.ndarray, coefficients: np.ndarray, since: int | None = None) -> bool:
        """Whether the loads have settled; with ``since``, judged on windows of iterations after it only
        (a run that switched its convection scheme there)."""
        iterations = np.asarray(iterations)
        if len(iterations) < self.window or iterations[-1] < self.min_iterations:
            return False
        means, trends = self._windows(coefficients, self.window)
        columns = [COEFFICIENTS.index(name) for name in self.monitored]
        window_ends = iterations[self.window - 1 :]
        window_starts = iterations[: len(iterations) - self.window + 1]
        flat = np.all(trends[:, columns] <= 1.0, axis=1)
        flat &= window_ends >= self.min_iterations
        if since is not None:
            flat &= window_starts > since
        if not flat[-1]:
            return False
        latest = len(flat) - 1
        earlier = np.arange(max(latest - self.window, 0), latest - self.window // 2 + 1)
        earlier = earlier[flat[earlier]]
        agree = np.abs(means[earlier] - means[latest]) <= self._allowed(means[latest : latest + 1])
        return bool(np.any(np.all(agree[:, columns], axis=1)))


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
