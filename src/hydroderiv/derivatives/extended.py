"""The rest of the steady Gertler-Hagen table, from the conditions a study already runs.

The main table (:mod:`.table`) holds the derivatives the captive-model experiments give for SUBOFF. The
same straight run, drift, pitch and turn sweeps carry the other steady terms of Gertler & Hagen's (1967)
equations, which a manoeuvring simulation takes besides them:

- the axial force, even in every motion variable: X' = X'uu u'^2 + X'vv v'^2 in drift, and likewise X'ww
  (pitch), X'rr and X'qq (turns). X'uu is the straight run's X', the resistance with a minus sign;
- the heave force and pitch moment that a sail brings about in the horizontal plane. Mirror symmetry about the
  vertical plane reverses v' and r' and leaves Z' and M' as they are, so these are even in v' and r':
  Z' = Z'* u'^2 + Z'vv v'^2 in drift, likewise M'vv, Z'rr and M'rr; Z'* and M'* are the straight run's;
- the roll moment, which that mirror reverses with v' and r': K'v and K'r, fitted as the main table's
  derivatives are (slope, nonlinear term, offset);
- where the study ran a roll-rate sweep, the roll damping K'p and the side force and yaw moment of a roll,
  Y'p and N'p (odd in p' by the same mirror; they vanish on a body with both mirror planes), fitted alike;
- where the study also ran conditions that combine drift with a yaw rate, the interaction that the
  single-variable sweeps leave out (X'vr, Y'|v|r, Y'v|r|, ...; see :func:`interaction_terms`).

A body that is also mirror-symmetric about its horizontal plane (a bare hull, a cruciform stern without a
sail) has none of the coupling terms: Z'vv, M'vv, Z'rr, M'rr, K'v and K'r vanish, up to its mesh's
asymmetry. Nothing here was measured for SUBOFF except the resistance, so only X'uu has a reference.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from ..case import Condition
from ..experiments import error_percent
from .fit import EvenFit, least_squares
from .table import (DEFINITIONS, fit_sweeps, fitted_range, motion_variable, records_varying_only, straight_loads,
                    sweep_points, table_rows, write_csv)

# term -> (sweep, coefficient): loads even in the sweep's motion variable
EVEN_TERMS = {
    "Xvv": ("drift_deg", "X"),
    "Xww": ("pitch_deg", "X"),
    "Xrr": ("yaw_rate_prime", "X"),
    "Xqq": ("pitch_rate_prime", "X"),
    "Zvv": ("drift_deg", "Z"),
    "Mvv": ("drift_deg", "M"),
    "Zrr": ("yaw_rate_prime", "Z"),
    "Mrr": ("yaw_rate_prime", "M"),
}
# term -> (sweep, coefficient, kind), as the main table's DEFINITIONS: the roll moment, odd in v', r' and p',
# and the side force and yaw moment of a roll
ROLL_DEFINITIONS = {
    "Kv": ("drift_deg", "K", "static"),
    "Kr": ("yaw_rate_prime", "K", "rotary"),
    "Kp": ("roll_rate_prime", "K", "rotary"),
    "Yp": ("roll_rate_prime", "Y", "rotary"),
    "Np": ("roll_rate_prime", "N", "rotary"),
}
# term -> coefficient: the straight run's own loads (u' = 1); all but X'uu vanish on a body with both mirror
# planes, and Y'*, K'* and N'* on any body with the vertical one: there they are the mesh's asymmetry
STRAIGHT_TERMS = {"Xuu": "X", "Ystar": "Y", "Zstar": "Z", "Kstar": "K", "Mstar": "M", "Nstar": "N"}
# term -> (coefficient, form): the drift-turn interaction, from conditions with both drift and yaw rate. The
# port-starboard mirror, (v', r') -> (-v', -r'), reverses Y', K' and N', whose interaction therefore has the
# odd forms |v'|r' and v'|r'| (two terms: both signs of r' with each sign of v' tell them apart), and leaves
# X', Z' and M', whose interaction is v'r'
INTERACTION_TERMS = {
    "Xvr": ("X", "vr"),
    "Zvr": ("Z", "vr"),
    "Mvr": ("M", "vr"),
    "Y|v|r": ("Y", "|v|r"),
    "Yv|r|": ("Y", "v|r|"),
    "K|v|r": ("K", "|v|r"),
    "Kv|r|": ("K", "v|r|"),
    "N|v|r": ("N", "|v|r"),
    "Nv|r|": ("N", "v|r|"),
}
# sweep -> "static" or "rotary", as the main table's definitions have it
_KIND_OF_SWEEP = {sweep: kind for sweep, _, kind in DEFINITIONS.values()}


@dataclass
class ExtendedTerm:
    name: str
    value: float
    # "straight" (the straight run's load), "even" (EvenFit), "odd" (as the main table's fits) or "interaction"
    kind: str
    n_points: int
    stderr: float = float("nan")  # from the points' scatter about the fit; NaN without spare points
    # even: (y - y0 u'^2) / x^2 with y0 the straight run's load; odd: the main table's single points;
    # interaction: each combined condition's interaction load (see interaction_terms) over its v'r'
    single_point_by_magnitude: dict[str, float] = field(default_factory=dict)
    odd_part: float = float("nan")  # even terms: see EvenFit.odd_part_
    # odd terms: the fit's nonlinear term, as the main table's (its coefficient, and "abs", "cubic" or "none")
    nonlinear: float = 0.0
    nonlinear_term: str = "none"
    reference: float | None = None
    error_pct: float | None = None


def extended_terms(results: list[dict], nonlinear: str = "abs", fit_offset: bool = True,
                   max_angle_deg: float | None = None, xuu_reference: float | None = None) -> list[ExtendedTerm]:
    """Every term of this module the study's conditions determine, in the order straight, even, odd.

    Static sweeps are fitted over the same range as the main table's (``max_angle_deg``); ``xuu_reference``
    is the measured resistance as X'uu (see :func:`hydroderiv.experiments.resistance_interpolated`)."""
    terms = []
    straight = straight_loads(results)
    if straight is not None:
        for name, coefficient in STRAIGHT_TERMS.items():
            reference = xuu_reference if name == "Xuu" else None
            value = float(straight[coefficient])
            terms.append(ExtendedTerm(name, value, "straight", 1, reference=reference,
                                      error_pct=error_percent(value, reference)))
    for name, (sweep, coefficient) in EVEN_TERMS.items():
        xs, us, ys, _, values = sweep_points(results, sweep, coefficient)
        inside = fitted_range(values, _KIND_OF_SWEEP[sweep], max_angle_deg)
        if not (xs[inside] != 0).any() or inside.sum() < 2:
            continue  # this sweep was not run (or has no second point besides one condition)
        fit = EvenFit().fit(xs[inside], ys[inside], us[inside])
        level = float(straight[coefficient]) if straight is not None else fit.constant_
        nonzero = xs != 0
        singles = (ys[nonzero] - level * us[nonzero] ** 2) / xs[nonzero] ** 2
        magnitudes = np.abs(values[nonzero])
        terms.append(ExtendedTerm(
            name, fit.quadratic_, "even", fit.n_points_, stderr=fit.quadratic_stderr_,
            single_point_by_magnitude={f"{m:g}": float(np.mean(singles[magnitudes == m])) for m in np.unique(magnitudes)},
            odd_part=fit.odd_part_))
    for row in table_rows(fit_sweeps(results, nonlinear, fit_offset, max_angle_deg, ROLL_DEFINITIONS)):
        terms.append(ExtendedTerm(row.name, row.value, "odd", row.n_points, stderr=row.stderr,
                                  single_point_by_magnitude=row.single_point_by_magnitude,
                                  nonlinear=row.nonlinear, nonlinear_term=row.nonlinear_term))
    return terms + interaction_terms(results)


def interaction_terms(results: list[dict]) -> list[ExtendedTerm]:
    """The drift-turn interaction terms (INTERACTION_TERMS) from the conditions that combine a drift angle b
    with a yaw rate r' and nothing else, where the study also ran drift b alone, r' alone and straight ahead.
    Their interaction load is what the single-variable sweeps leave out,

        I = y(b, r') - y(b, 0) - y(0, r') + y(0, 0),

    fitted by least squares with the term's form (v'r' for X', Z', M'; |v'|r' and v'|r'| together for Y',
    K' and N', which need conditions with both relative signs of b and r'). None without such conditions."""
    loads = {(r["condition"]["drift_deg"], r["condition"]["yaw_rate_prime"]): r
             for r in records_varying_only(results, ("drift_deg", "yaw_rate_prime"))}
    straight = loads.get((0, 0))
    combined = [key for key in loads if key[0] and key[1] and (key[0], 0) in loads and (0, key[1]) in loads]
    if straight is None or not combined:
        return []
    v = np.array([motion_variable(Condition(**loads[key]["condition"]), "drift_deg")[0] for key in combined])
    r = np.array([key[1] for key in combined], dtype=float)
    forms = {"vr": v * r, "|v|r": np.abs(v) * r, "v|r|": v * np.abs(r)}
    terms = []
    for coefficient in dict.fromkeys(c for c, _ in INTERACTION_TERMS.values()):
        names = [name for name, (c, _) in INTERACTION_TERMS.items() if c == coefficient]
        design = np.column_stack([forms[INTERACTION_TERMS[name][1]] for name in names])
        if np.linalg.matrix_rank(design) < design.shape[1]:
            continue  # |v'|r' and v'|r'| coincide where every condition has b and r' of one relative sign
        y = np.array([loads[b, q]["coefficients"][coefficient] - loads[b, 0]["coefficients"][coefficient]
                      - loads[0, q]["coefficients"][coefficient] + straight["coefficients"][coefficient]
                      for b, q in combined])
        values, stderr = least_squares(design, y)
        singles = {f"b{b:+g} r{q:+g}": float(load / (vv * rr)) for (b, q), load, vv, rr in zip(combined, y, v, r)}
        terms += [ExtendedTerm(name, float(value), "interaction", len(y), stderr=float(error),
                               single_point_by_magnitude=singles)
                  for name, value, error in zip(names, values, stderr)]
    return terms


def extended_payload(terms: list[ExtendedTerm]) -> dict:
    """The terms for a derivative table's JSON: name -> value, and each term's details (NaN as null)."""
    return {"values": {t.name: t.value for t in terms},
            "details": {t.name: {k: None if isinstance(v, float) and np.isnan(v) else v for k, v in asdict(t).items()}
                        for t in terms}}


def write_extended_csv(terms: list[ExtendedTerm], path: str | Path) -> Path:
    """The terms as CSV (atomic), one row each."""
    return write_csv(terms, list(ExtendedTerm.__dataclass_fields__), Path(path))
