"""The quasi-steady loads a derivative table implies, for a manoeuvring simulation.

A simulation evaluates the hydrodynamic force and moment at every time step from the body's velocities.
Steady captive tests give the part that depends on the velocities alone (the acceleration terms, added mass,
they do not give). From a table written by `hydroderiv derivatives` (or `study run`), in the prime system:

    X' = X'uu u'^2 + X'vv v'^2 + X'ww w'^2 + X'rr r'^2 + X'qq q'^2 + X'vr v'r'
    Y' = Y'* + Y'v v' + Y'v|v| f(v') + Y'r r' + Y'r|r| f(r') + Y'|v|r |v'|r' + Y'v|r| v'|r'| + Y'p p' + ...
    Z' = Z'* + Z'w w' + Z'w|w| f(w') + Z'q q' + Z'q|q| f(q') + Z'vv v'^2 + Z'rr r'^2 + Z'vr v'r'
    K' = K'* + K'v v' + K'v|v| f(v') + K'r r' + K'r|r| f(r') + K'|v|r |v'|r' + K'v|r| v'|r'| + K'p p' + ...
    M' like Z', N' like Y'

(the roll terms, Y'p p' + Y'p|p| f(p') and likewise in K' and N', where the table's study ran a roll sweep)

with f the nonlinear term each sweep was fitted with (x|x| or x^3, see derivatives/fit.py) and every term the
table lacks taken as zero. The single-variable sweeps add up; what they leave out when drift and turn come
together, the interaction terms, comes from combined conditions where the study ran them
(derivatives/extended.py). The model holds over the range the table was fitted on (the sweeps' largest angle
and rate); beyond it, it extrapolates.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Mapping

import numpy as np

from ..case import Condition
from ..case.conditions import SWEEP_VARIABLES
from ..derivatives.extended import EVEN_TERMS, INTERACTION_TERMS, ROLL_DEFINITIONS, STRAIGHT_TERMS
from ..derivatives.fit import NONLINEAR_TERMS
from ..derivatives.table import DEFINITIONS, motion_variable, straight_loads
from ..errors import HydroderivError

# coefficient -> the straight run's term; (term, motion variable) of the fitted odd terms (main table and
# roll); (term, form) of the even ("vv", ...) and interaction terms: all from the derivatives' definitions
_STRAIGHT = {coefficient: name for name, coefficient in STRAIGHT_TERMS.items()}
_ODD: dict[str, list[tuple[str, str]]] = {}
for _name, (_sweep, _coefficient, _) in {**DEFINITIONS, **ROLL_DEFINITIONS}.items():
    _ODD.setdefault(_coefficient, []).append((_name, SWEEP_VARIABLES[_sweep]))
_FORMS: dict[str, list[tuple[str, str]]] = {coefficient: [] for coefficient in _STRAIGHT}
for _name, (_sweep, _coefficient) in EVEN_TERMS.items():
    _FORMS[_coefficient].append((_name, 2 * SWEEP_VARIABLES[_sweep]))
for _name, (_coefficient, _form) in INTERACTION_TERMS.items():
    _FORMS[_coefficient].append((_name, _form))


class QuasiSteadyLoads:
    """The loads of a derivative table as functions of the velocities (see the module's equations).

    ``table`` is the JSON of a derivative table as a mapping; :meth:`from_file` reads one. The terms found
    are in ``terms`` (name -> (coefficient, nonlinear coefficient, nonlinear form))."""

    def __init__(self, table: Mapping):
        if not isinstance(table, Mapping):
            raise HydroderivError("not a derivative table: a JSON object with 'details' or 'extended' is needed")
        details = dict(table.get("details") or {})
        extended = dict((table.get("extended") or {}).get("details") or {})
        if not details and not extended:
            raise HydroderivError("not a derivative table: it has neither 'details' nor 'extended'")
        self.terms = {name: (float(d["value"]), float(d.get("nonlinear") or 0.0), d.get("nonlinear_term") or "none")
                      for name, d in {**details, **extended}.items()}
        # the straight run's loads; a table written before the extended block takes them from its straight
        # condition, else Y' to N' from the fits' offsets (zero without any) and X' as unknown (NaN): a body
        # has a drag, so zero would be wrong where the other loads' zero is merely their mirror symmetry
        straight = straight_loads(table.get("conditions") or [])
        for coefficient, name in _STRAIGHT.items():
            if name in self.terms:
                continue
            if straight is not None:
                value = float(straight[coefficient])
            else:
                # a fit without an offset (or a table written by hand) holds none: it passes through zero
                offsets = [details[n].get("offset") or 0.0 for n, _ in _ODD.get(coefficient, ()) if n in details]
                value = float(np.mean(offsets)) if offsets else (float("nan") if coefficient == "X" else 0.0)
            self.terms[name] = (value, 0.0, "none")

    @classmethod
    def from_file(cls, path: str | Path) -> QuasiSteadyLoads:
        try:
            return cls(json.loads(Path(path).read_text()))
        except (OSError, json.JSONDecodeError) as error:
            raise HydroderivError(f"{path}: cannot read a derivative table ({error})") from None

    def coefficients(self, v: float = 0.0, w: float = 0.0, r: float = 0.0, q: float = 0.0,
                     u: float = 1.0, p: float = 0.0) -> dict[str, float]:
        """X', Y', Z', K', M', N' at the velocities u' = u/U, v' = v/U, w' = w/U, r' = rL/U, q' = qL/U and
        p' = pL/U (U the table's speed, body axes: x forward, y starboard, z down; q > 0 nose up)."""
        motion = {"v": v, "w": w, "r": r, "q": q, "p": p}
        forms = {"vv": v * v, "ww": w * w, "rr": r * r, "qq": q * q, "vr": v * r, "|v|r": abs(v) * r,
                 "v|r|": v * abs(r)}
        loads = {}
        for coefficient, straight in _STRAIGHT.items():
            total = self._value(straight) * (u * u if coefficient == "X" else 1.0)
            for name, variable in _ODD.get(coefficient, ()):
                if name in self.terms:
                    slope, nonlinear, form = self.terms[name]
                    x = motion[variable]
                    term = NONLINEAR_TERMS.get(form)
                    total += slope * x + (nonlinear * float(term(np.float64(x))) if term is not None else 0.0)
            total += sum(self._value(name) * forms[form] for name, form in _FORMS[coefficient])
            loads[coefficient] = float(total)
        return loads

    def at(self, condition: Condition) -> dict[str, float]:
        """:meth:`coefficients` at a condition as a study gives it (drift and pitch in degrees, r', q')."""
        v, u = motion_variable(condition, "drift_deg")
        w, _ = motion_variable(condition, "pitch_deg")
        return self.coefficients(v=v, w=w, r=condition.yaw_rate_prime, q=condition.pitch_rate_prime, u=u,
                                 p=condition.roll_rate_prime)

    def _value(self, name: str) -> float:
        return self.terms[name][0] if name in self.terms else 0.0
