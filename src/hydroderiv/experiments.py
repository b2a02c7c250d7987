"""Published SUBOFF measurements used for validation (figures carried over with their sources).

- Liu, H.-L. and Huang, T.T. (1998), "Summary of DARPA SUBOFF Experimental Program Data",
  CRDKNSWC/HD-1298-11, Table 14: towed resistance of AFF-8 (fully appended).
- Huang, T.T. et al. (1989), as tabulated in the seed paper's Table 1: resistance of AFF-3 (hull + stern
  appendages).
- Roddy, R.F. (1990), "Investigation of the Stability and Control Characteristics of Several Configurations
  of the DARPA SUBOFF Model (DTRC Model 5470) from Captive-Model Experiments", DTRC/SHD-1298-08:
  stability derivatives in the prime system on L = 4.261 m. For AFF-8 Roddy measured the fully appended
  model with a ring wing; the values below remove it as the seed paper does,
  phi_AFF8 = phi_(full+RW) + phi_(bare) - phi_(bare+RW) (vertical-plane increments from the bare hull's
  axisymmetry: Z'w = Y'v, M'w = -N'v).
"""

from __future__ import annotations

import math

# (speed in knots, resistance in N)
RESISTANCE = {
    "AFF-8": {
        "source": "Liu & Huang (1998), CRDKNSWC/HD-1298-11, Table 14",
        "points": [(5.93, 102.3), (10.00, 283.8), (11.85, 389.2), (13.92, 526.6), (16.00, 675.6), (17.79, 821.1)],
    },
    "AFF-3": {
        "source": "Huang et al. (1989), as tabulated in the seed paper's Table 1",
        "points": [(5.92, 95.41), (11.85, 361.80), (17.78, 765.90)],
    },
}

# Prime-system stability derivatives (Roddy 1990); AFF-8 with the ring wing removed (see above).
DERIVATIVES = {
    "AFF-8": {
        "source": "Roddy (1990), DTRC/SHD-1298-08, ring wing removed as in the seed paper",
        "values": {"Yv": -0.027839, "Nv": -0.013504, "Yr": 0.003251, "Nr": -0.003716, "Zw": -0.013915, "Mw": 0.010180},
    },
    "AFF-3": {
        "source": "Roddy (1990), DTRC/SHD-1298-08",
        "values": {"Yv": -0.010494, "Nv": -0.011254, "Yr": 0.006324, "Nr": -0.003064},
    },
}

# Stated experimental uncertainty of the captive tests (Roddy 1990).
DERIVATIVE_UNCERTAINTY = {"static": 0.05, "rotary": 0.10}


def error_percent(computed: float, measured: float | None) -> float | None:
    """The error of a computed value against a measured one, (computed - measured) / |measured| in per cent:
    positive where the computation lies above the measurement, whatever its sign. None without a
    measured value (None or zero)."""
    return 100.0 * (computed - measured) / abs(measured) if measured else None


def resistance_at(config: str, speed_knots: float) -> float | None:
    """The measured resistance at this speed (within 0.02 kn), or None."""
    for knots, newtons in RESISTANCE.get(config.upper(), {}).get("points", []):
        if abs(knots - speed_knots) < 0.02:
            return newtons
    return None


def resistance_interpolated(config: str, speed_knots: float) -> float | None:
    """The measured resistance at this speed: the tabulated point within 0.02 kn, else a power law
    R = a V^n through the nearest tabulated speeds either side (a towed body's resistance grows nearly as
    V^2, n = 1.92-1.95 between SUBOFF's lowest two speeds, so the law is close over one such interval);
    None outside the measured range or for a body without measurements."""
    exact = resistance_at(config, speed_knots)
    if exact is not None:
        return exact
    points = sorted(RESISTANCE.get(config.upper(), {}).get("points", []))
    for (v0, r0), (v1, r1) in zip(points, points[1:]):
        if v0 < speed_knots < v1:
            exponent = math.log(r1 / r0) / math.log(v1 / v0)
            return r0 * (speed_knots / v0) ** exponent
    return None
