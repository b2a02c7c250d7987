"""The ideal-fluid part of the velocity derivatives, and the viscous remainder that the CFD adds.

A body in steady motion through a potential flow feels loads that follow from its added mass alone
(Kirchhoff's equations: F = -omega x P and M = -omega x L - V x P, with P and L the linear and angular
impulse of the fluid; Newman, *Marine Hydrodynamics*, 1977, section 4.13). To first order in v, w, r and q
about straight motion at speed U, in prime units (Gertler & Hagen 1967) and with the acceleration
derivatives of :mod:`hydroderiv.derivatives.added_mass`:

    Y'v = 0          N'v = Y'v. - X'u.      (Munk's moment: it turns the body broadside)
    Y'r = X'u.       N'r = Y'r.
    Z'w = 0          M'w = -(Z'w. - X'u.)
    Z'q = -X'u.      M'q = -Z'q.

The rest of each derivative, its viscous part, is what the boundary layer, the separated flow and the
appendages' lift add: the part a RANS computation is there to predict. Splitting it off shows where a
computed table and an experiment differ: in the potential flow, which follows from the shape, or in the
lift.

The viscous parts also carry a check. If each section x of the body carried the viscous lift that its own
local incidence sets, as it does in drift (quasi-steady strip theory: a section meets v + r x in a yaw turn,
w - q x in a pitch turn), a turn's viscous force would be the first moment of the drift's lift
distribution, which is also the drift's viscous moment: Y'r = N'v and Z'q = M'w, viscous parts alone.
Their ratio (1 in that picture) says how far a turn's loading departs from the drift's moved along the
body: the sail's and the hull's vortices, the wake a fin sits in and the curvature of the flow all move it.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..experiments import error_percent

# velocity derivative -> its ideal-fluid value as a sum of acceleration derivatives times these factors
# (prime units; no term: zero)
IDEAL_FLUID = {
    "Yv": {},
    "Nv": {"Yvdot": 1.0, "Xudot": -1.0},
    "Yr": {"Xudot": 1.0},
    "Nr": {"Yrdot": 1.0},
    "Zw": {},
    "Mw": {"Zwdot": -1.0, "Xudot": 1.0},
    "Zq": {"Xudot": -1.0},
    "Mq": {"Zqdot": -1.0},
}

# (turn's force, drift's or pitch's moment): equal viscous parts in quasi-steady strip theory
QUASI_STEADY_PAIRS = {"Yr/Nv": ("Yr", "Nv"), "Zq/Mw": ("Zq", "Mw")}


def ideal_fluid_derivatives(acceleration: Mapping[str, float]) -> dict[str, float]:
    """The velocity derivatives of the potential flow about the body, from its acceleration derivatives
    (prime units, keys as :class:`~hydroderiv.derivatives.added_mass.AccelerationDerivatives` ``values``)."""
    needed = sorted({key for terms in IDEAL_FLUID.values() for key in terms})
    missing = [k for k in needed if not isinstance(acceleration.get(k), (int, float))]
    if missing:
        raise KeyError(f"the ideal-fluid derivatives need the acceleration derivatives {', '.join(missing)}")
    return {name: float(sum(factor * acceleration[key] for key, factor in terms.items()))
            for name, terms in IDEAL_FLUID.items()}


@dataclass(frozen=True)
class ViscousSplit:
    """One derivative split into its ideal-fluid part and the viscous rest; beside them the experiment's
    viscous part (the measured value less the same ideal-fluid part) and the computed viscous part's error
    against it, (computed - measured) / |measured|, in per cent (None without a measured value)."""

    name: str
    value: float
    ideal: float
    viscous: float
    reference_viscous: float | None = None
    viscous_error_pct: float | None = None


def viscous_split(derivatives: Mapping[str, float], acceleration: Mapping[str, float],
                  reference: Mapping[str, float] | None = None) -> list[ViscousSplit]:
    """Each of ``derivatives`` (Y'v ... M'q, whichever are given) split into its ideal-fluid and viscous
    parts, with ``reference``'s (measured) viscous parts beside them where it has the derivative."""
    ideal = ideal_fluid_derivatives(acceleration)
    rows = []
    for name in IDEAL_FLUID:
        value = derivatives.get(name)
        if not isinstance(value, (int, float)):
            continue
        viscous = value - ideal[name]
        measured = (reference or {}).get(name)
        measured_viscous = None if measured is None else measured - ideal[name]
        rows.append(ViscousSplit(name, float(value), ideal[name], float(viscous), measured_viscous,
                                 error_percent(viscous, measured_viscous)))
    return rows


def quasi_steady_ratios(rows: list[ViscousSplit], measured: bool = False) -> dict[str, float]:
    """A turn's viscous force over the drift's (pitch's) viscous moment, Y'r/N'v and Z'q/M'w (1 in
    quasi-steady strip theory, see the module's docstring), for the pairs ``rows`` hold both of; from the
    experiment's viscous parts with ``measured``."""
    parts = {row.name: (row.reference_viscous if measured else row.viscous) for row in rows}
    return {label: parts[force] / parts[moment] for label, (force, moment) in QUASI_STEADY_PAIRS.items()
            if parts.get(force) is not None and parts.get(moment)}


# A part whose drift (pitch) moment is below this fraction of the whole body's viscous one gets no ratio:
# a fin edge-on to the motion carries next to nothing of either, and their ratio says nothing.
PART_MOMENT_FLOOR = 0.05


def part_quasi_steady_ratios(by_part: Mapping[str, Mapping[str, float]], ideal: Mapping[str, float],
                             hull: str = "hull") -> dict[str, dict[str, float]]:
    """The quasi-steady ratios per body part (``by_part``: derivative -> part -> its share, as a table's
    ``by_part``), the ideal-fluid part ``ideal`` taken off the ``hull``'s shares. The added mass is the
    hull's almost whole (the fins are thin), so a fin's share is viscous lift; for a fin the ratio is 1 if
    its incidence in a turn is r x at its own station, as in drift it is v. Parts whose moment is under
    PART_MOMENT_FLOOR of the body's viscous moment are left out; without a part named ``hull`` nothing
    can carry the ideal fluid, and there are no ratios."""

    def viscous(name: str, part: str) -> float:
        return by_part[name][part] - (ideal.get(name, 0.0) if part == hull else 0.0)

    ratios = {}
    for label, (force, moment) in QUASI_STEADY_PAIRS.items():
        if force not in by_part or moment not in by_part or hull not in by_part[moment]:
            continue
        body_moment = sum(viscous(moment, part) for part in by_part[moment])
        ratios[label] = {part: viscous(force, part) / viscous(moment, part) for part in by_part[moment]
                         if part in by_part[force]
                         and abs(viscous(moment, part)) >= PART_MOMENT_FLOOR * abs(body_moment)}
    return ratios


def viscous_split_payload(rows: list[ViscousSplit], by_part: Mapping[str, Mapping[str, float]] | None = None) -> dict:
    """The split for a derivative table's JSON: per derivative its parts, then the quasi-steady ratios, of the
    whole body and (given ``by_part``) of each part."""
    payload = {"derivatives": {row.name: {k: v for k, v in row.__dict__.items() if k != "name"} for row in rows},
               "quasi_steady_ratio": quasi_steady_ratios(rows)}
    measured = quasi_steady_ratios(rows, measured=True)
    if measured:
        payload["quasi_steady_ratio_measured"] = measured
    per_part = part_quasi_steady_ratios(by_part, {row.name: row.ideal for row in rows}) if by_part else {}
    if any(per_part.values()):
        payload["quasi_steady_ratio_by_part"] = per_part
    return payload
