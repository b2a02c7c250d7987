"""The Gertler-Hagen derivative table from a study's finished conditions.

Motion variables (prime system on L): v' = v/U and w' = w/U from drift and pitch (see
:mod:`hydroderiv.case.conditions` for the signs), r' = rL/U and q' = qL/U from turns. Each derivative
is the linear term of a :class:`DerivativeFit` over its one-variable sweep (straight-ahead included):

    Y'v, N'v  from drift        Z'w, M'w  from pitch
    Y'r, N'r  from yaw turns    Z'q, M'q  from pitch turns

The seed paper's single-point definitions are reported beside them, e.g. Y'v = Y'/(u'v')
(= -Y'/(cos b sin b)) and Y'r = Y'/r': averaged over the sweep's non-zero points, and per magnitude of the
sweep (4 and 8 degrees, r' = 0.1 and 0.2). The per-magnitude values show how far the force is from linear,
and so how much the fitted slope depends on the nonlinear term chosen: with two magnitudes a slope and a
nonlinear term are interpolated, not over-determined.
"""

from __future__ import annotations

import csv
import io
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._io import atomic_write_text
from ..case import Condition
from ..case.conditions import SWEEP_KEYS
from ..errors import ConfigurationError
from ..experiments import DERIVATIVE_UNCERTAINTY, DERIVATIVES, error_percent
from ..forces import COEFFICIENT_NAMES
from .fit import NONLINEAR_TERMS, DerivativeFit

# derivative -> (sweep variable of Condition, force coefficient, static or rotary)
DEFINITIONS = {
    "Yv": ("drift_deg", "Y", "static"),
    "Nv": ("drift_deg", "N", "static"),
    "Zw": ("pitch_deg", "Z", "static"),
    "Mw": ("pitch_deg", "M", "static"),
    "Yr": ("yaw_rate_prime", "Y", "rotary"),
    "Nr": ("yaw_rate_prime", "N", "rotary"),
    "Zq": ("pitch_rate_prime", "Z", "rotary"),
    "Mq": ("pitch_rate_prime", "M", "rotary"),
}


def motion_variable(condition: Condition, sweep: str) -> tuple[float, float]:
    """(x, u') for a sweep: v' or w' for static sweeps, r', q' or p' for turns and rolls; u' is the axial
    velocity ratio."""
    u, v, w = condition.body_velocity() / condition.speed
    return {"drift_deg": v, "pitch_deg": w, "yaw_rate_prime": condition.yaw_rate_prime,
            "pitch_rate_prime": condition.pitch_rate_prime, "roll_rate_prime": condition.roll_rate_prime}[sweep], u


def _on_sweep(condition: Condition, sweep: str) -> bool:
    """True for the straight-ahead condition and the conditions that vary only ``sweep``."""
    return all(getattr(condition, k) == 0 for k in SWEEP_KEYS if k != sweep)


def records_varying_only(results: list[dict], sweeps: tuple[str, ...]) -> list[dict]:
    """The condition records whose every sweep variable but ``sweeps`` is zero (the records' counterpart of
    ``_on_sweep``; a key a record predates counts as zero)."""
    return [record for record in results
            if all(record["condition"].get(k, 0) == 0 for k in SWEEP_KEYS if k not in sweeps)]


def straight_loads(results: list[dict]) -> dict[str, float] | None:
    """The straight run's coefficients among condition records (every sweep variable zero); None if the
    records have none."""
    return next((record["coefficients"] for record in records_varying_only(results, ())), None)


def sweep_points(results: list[dict], sweep: str, coefficient: str) -> tuple[np.ndarray, ...]:
    """The points of one sweep, the straight run included: motion variable x, axial ratio u', the
    coefficient, its window standard deviation (NaN where a record predates it) and each point's value of
    the sweep as the study gives it (degrees of drift or pitch, r' or q')."""
    xs, us, ys, stds, values = [], [], [], [], []
    for record in results:
        condition = Condition(**record["condition"])
        if not _on_sweep(condition, sweep):
            continue
        x, u = motion_variable(condition, sweep)
        values.append(getattr(condition, sweep))
        xs.append(x)
        us.append(u)
        ys.append(record["coefficients"][coefficient])
        window_std = record.get("window_std")
        stds.append(window_std[COEFFICIENT_NAMES.index(coefficient)] if window_std else np.nan)
    return tuple(map(np.asarray, (xs, us, ys, stds, values)))


def fitted_range(values: np.ndarray, kind: str, max_angle_deg: float | None) -> np.ndarray:
    """Which points of a sweep a fit takes: a static (drift or pitch) sweep's within ``max_angle_deg``
    (see :func:`fit_sweeps`), a turn's all."""
    if max_angle_deg is not None and max_angle_deg <= 0:
        raise ConfigurationError(f"the fit's max_angle_deg must be positive, not {max_angle_deg}")
    if kind == "static" and max_angle_deg is not None:
        return np.abs(values) <= max_angle_deg + 1e-9
    return np.ones(len(values), dtype=bool)


@dataclass
class DerivativeRow:
    name: str
    value: float
    stderr: float  # from the points' scatter about the fit
    iterative_stderr: float  # from the points' iterative (window) uncertainty; NaN for old records
    nonlinear: float
    offset: float
    single_point: float
    single_point_by_magnitude: dict[str, float]  # sweep magnitude (degrees, or r' / q') -> Y'/(u'v') or Y'/r'
    n_points: int
    reference: float | None
    error_pct: float | None
    experimental_uncertainty_pct: float | None  # the reports' stated uncertainty; None where nothing was measured
    nonlinear_term: str = "abs"  # the fit's nonlinear term: the table's, or "none" for a sweep at one magnitude
    # magnitudes beyond the fit's odd terms; at 0 the slope passes through the points (see DerivativeFit)
    spare_magnitudes: int | None = None
    # the slope with each nonlinear term the fitted points can carry ('abs', 'cubic', 'none'), the table's
    # included: how much the derivative depends on the form of the curve assumed beyond the origin
    slope_by_form: dict[str, float] | None = None

    @property
    def form_spread(self) -> float:
        """Largest less smallest slope over the fit forms (NaN with one form)."""
        slopes = list((self.slope_by_form or {}).values())
        return max(slopes) - min(slopes) if len(slopes) > 1 else float("nan")


@dataclass
class SweepFit:
    """One derivative's sweep: motion variable x, axial ratio u', coefficient y (with its window standard
    deviation, NaN where a record predates it), the fitted estimator, and each point's value of the sweep
    as the study gives it (degrees of drift or pitch, r' or q')."""

    xs: np.ndarray
    us: np.ndarray
    ys: np.ndarray
    fit: DerivativeFit
    sweep_values: np.ndarray
    in_fit: np.ndarray  # which points the fit used (see fit_sweeps' max_angle_deg)
    y_std: np.ndarray | None = None
    kind: str = "static"  # "static" (drift, pitch) or "rotary" (turns): which single-point definition applies


def fit_sweeps(results: list[dict], nonlinear: str = "abs", fit_offset: bool = True,
               max_angle_deg: float | None = None, definitions: dict = DEFINITIONS) -> dict[str, SweepFit]:
    """Fit every derivative of ``definitions`` (name -> sweep, coefficient, kind; the main table's by
    default) whose sweep has enough points. ``results`` are condition result records.

    ``max_angle_deg`` limits the static (drift and pitch) fits to the points within that angle, so that
    the slope at the origin is not set by a stall at larger angles; the points beyond it are kept in the
    sweep (and in the single points per magnitude) but not fitted. Turns are not limited.
    """
    fits = {}
    for name, (sweep, coefficient, kind) in definitions.items():
        xs, us, ys, stds, values = sweep_points(results, sweep, coefficient)
        in_fit = fitted_range(values, kind, max_angle_deg)
        estimator = DerivativeFit(nonlinear=nonlinear, fit_offset=fit_offset)
        if not estimator.has_enough_magnitudes(xs[in_fit]):
            # A sweep run at one magnitude (a mirror pair) cannot carry a nonlinear term, but its slope is
            # still the derivative that pair measures: fit the slope alone rather than drop the sweep.
            estimator = DerivativeFit(nonlinear="none", fit_offset=fit_offset)
            if not estimator.has_enough_magnitudes(xs[in_fit]):
                continue  # this sweep was not run
        estimator.fit(xs[in_fit], ys[in_fit], y_std=stds[in_fit])
        fits[name] = SweepFit(xs, us, ys, estimator, sweep_values=values, in_fit=in_fit, y_std=stds, kind=kind)
    return fits


def derivative_table(
    results: list[dict], reference_key: str | None = None, nonlinear: str = "abs", fit_offset: bool = True,
    max_angle_deg: float | None = None,
) -> list[DerivativeRow]:
    """The table rows: each fitted derivative beside its single-point value and the experiment."""
    return table_rows(fit_sweeps(results, nonlinear, fit_offset, max_angle_deg), reference_key)


def table_rows(fits: dict[str, SweepFit], reference_key: str | None = None) -> list[DerivativeRow]:
    """The table rows of sweeps already fitted by :func:`fit_sweeps`."""
    reference = DERIVATIVES.get(reference_key or "", {}).get("values", {})
    rows = []
    for name, sweep in fits.items():
        kind = sweep.kind
        fit, xs, us, ys = sweep.fit, sweep.xs, sweep.us, sweep.ys
        nonzero = xs != 0
        # single-point definitions: static Y'v = Y'/(u'v'); rotary Y'r = Y'/r'
        denominators = xs[nonzero] * (us[nonzero] if kind == "static" else 1.0)
        singles = ys[nonzero] / denominators
        single = float(np.mean(singles[sweep.in_fit[nonzero]]))  # over the fitted range; per magnitude, all
        magnitudes = np.abs(sweep.sweep_values[nonzero])
        by_magnitude = {f"{m:g}": float(np.mean(singles[magnitudes == m])) for m in np.unique(magnitudes)}
        ref = reference.get(name)
        slope_by_form = _slope_by_form(sweep)
        rows.append(
            DerivativeRow(
                name=name,
                value=fit.slope_,
                stderr=fit.slope_stderr_,
                iterative_stderr=fit.slope_iterative_stderr_,
                nonlinear=fit.nonlinear_,
                offset=fit.offset_,
                single_point=single,
                single_point_by_magnitude=by_magnitude,
                n_points=fit.n_points_,
                reference=ref,
                error_pct=error_percent(fit.slope_, ref),
                experimental_uncertainty_pct=None if ref is None else 100.0 * DERIVATIVE_UNCERTAINTY[kind],
                nonlinear_term=fit.nonlinear,
                spare_magnitudes=fit.spare_magnitudes_,
                slope_by_form=slope_by_form,
            )
        )
    return rows


def _slope_by_form(sweep: SweepFit) -> dict[str, float]:
    """The slope at the origin of the sweep's fitted points with every nonlinear term they can carry. Where
    the loads curve, a slope-plus-x|x| fit, a slope-plus-x^3 fit and a straight line through the same points
    differ: the straight line returns the mean slope over the tested range (what a linear manoeuvring model
    used over that range needs), the other two extrapolate the curvature to the origin."""
    x, y = sweep.xs[sweep.in_fit], sweep.ys[sweep.in_fit]
    slopes = {}
    for form in NONLINEAR_TERMS:
        try:
            slopes[form] = DerivativeFit(nonlinear=form, fit_offset=sweep.fit.fit_offset).fit(x, y).slope_
        except ConfigurationError:
            # too few magnitudes or points for this form's terms (one pair, a one-sided sweep): leave it out
            continue
    return slopes


def body_parts(results: list[dict]) -> list[str]:
    """The body parts (hull, sail, each appendage) whose loads every record carries; none where a record
    predates per-part loads."""
    parts = [record.get("components") or {} for record in results]
    return [part for part in parts[0] if all(part in p for p in parts[1:])] if parts else []


def fit_parts(results: list[dict], nonlinear: str = "abs", fit_offset: bool = True,
              max_angle_deg: float | None = None, definitions: dict = DEFINITIONS) -> dict[str, dict[str, SweepFit]]:
    """Each body part's sweeps, fitted as the whole body's are (:func:`fit_sweeps`): the same points, range
    and nonlinear term. A least-squares slope is linear in the coefficients, so the parts' derivatives add
    up to the body's wherever the parts' loads add up to its load; where a part carries its load decides
    what it contributes (a fin aft of the moment centre, x' < 0, adds to N'r about x'^2 times its Y'v)."""
    return {part: fit_sweeps([{**record, "coefficients": record["components"][part], "window_std": None}
                              for record in results], nonlinear, fit_offset, max_angle_deg, definitions)
            for part in body_parts(results)}


def derivatives_by_part(part_fits: dict[str, dict[str, SweepFit]]) -> dict[str, dict[str, float]]:
    """derivative -> part -> the part's contribution (prime units), from :func:`fit_parts`."""
    table: dict[str, dict[str, float]] = {}
    for part, fits in part_fits.items():
        for name, sweep in fits.items():
            table.setdefault(name, {})[part] = sweep.fit.slope_
    return table


def condition_summary(record: dict) -> dict:
    """What a derivative table keeps of one condition's result, so that the fit (the body's, and each
    part's where the record has per-part loads) can be checked and redone."""
    keys = ("name", "condition", "converged", "iterations", "coefficients", "window_std")
    summary = {key: record.get(key) for key in keys}
    if record.get("components"):
        summary["components"] = record["components"]
    return summary


def write_table(rows: list[DerivativeRow], json_path: str | Path, meta: dict, results: list[dict] = (),
                stability: dict | None = None, by_part: dict[str, dict[str, float]] | None = None,
                extended: dict | None = None, acceleration: dict | None = None,
                ideal_fluid: dict | None = None) -> tuple[Path, Path]:
    """JSON (keys Yv, Nv, ... in prime units, plus details, the conditions' coefficients when ``results``
    are given, the straight-line ``stability`` the derivatives imply, see :mod:`hydroderiv.simulation`,
    each body part's contribution ``by_part``, see :func:`derivatives_by_part`, the rest of the steady
    table ``extended``, see :func:`hydroderiv.derivatives.extended.extended_payload`, and the acceleration
    derivatives estimated from the shape, ``acceleration``, see :mod:`hydroderiv.derivatives.added_mass`,
    and each derivative split into its ideal-fluid and viscous parts, ``ideal_fluid``, see
    :mod:`hydroderiv.derivatives.ideal_fluid`) and CSV beside it, both atomic."""
    json_path = Path(json_path)
    payload = {row.name: row.value for row in rows}
    # NaN (no spare points, or records without a window deviation) is written as null: JSON has no NaN
    payload["details"] = {row.name: {k: None if isinstance(v, float) and np.isnan(v) else v
                                     for k, v in {**row.__dict__, "form_spread": row.form_spread}.items()}
                          for row in rows}
    payload["meta"] = meta
    if stability:
        payload["stability"] = stability
    if by_part:
        payload["by_part"] = by_part
    if extended:
        payload["extended"] = extended
    if acceleration:
        payload["acceleration"] = acceleration
    if ideal_fluid:
        payload["ideal_fluid"] = ideal_fluid
    if results:
        payload["conditions"] = [condition_summary(r) for r in results]
    atomic_write_text(json_path, json.dumps(payload, indent=2) + "\n")
    csv_path = json_path.with_suffix(".csv")
    write_csv(rows, [*DerivativeRow.__dataclass_fields__, "form_spread"], csv_path)
    return json_path, csv_path


def write_csv(rows: list, columns: list[str], path: Path) -> Path:
    """One line per row of the attributes ``columns`` (atomic). A dict (the single points per magnitude, the
    slopes per fit form) goes in one cell, "4:-0.0232 8:-0.0291"."""
    buffer = io.StringIO()
    writer = csv.writer(buffer)
    writer.writerow(columns)
    for row in rows:
        writer.writerow([" ".join(f"{k}:{v:.6g}" for k, v in value.items()) if isinstance(value, dict) else value
                         for value in (getattr(row, c) for c in columns)])
    atomic_write_text(path, buffer.getvalue())
    return path
