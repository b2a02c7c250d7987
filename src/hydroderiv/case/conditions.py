"""Captive-test conditions and their hybrid-reference-frames set-up.

Body axes: x forward, y starboard, z down, origin at the moment centre B (Roddy 1990). A condition is a
speed U plus any combination of a drift angle beta, a pitch angle alpha, a steady turn (yaw rate r,
pitch rate q) and a steady roll (roll rate p about the x axis through B). Sign conventions follow the seed
paper's single-point definitions (Y'v = -Y'/(cos b sin b), Z'w = -Z'/(cos a sin a)):

- beta > 0: the bow is turned to starboard of the path, so v = -U sin(beta) < 0;
- alpha > 0: the bow is pitched down relative to the path, so w = -U sin(alpha) cos(beta) < 0;
- r > 0: turning to starboard (Omega along +z, z down); q > 0: bow pitching up (Omega along +y);
- p > 0: rolling to starboard, the starboard side going down (Omega along +x);
- non-dimensional rates r' = r L / U, q' = q L / U and p' = p L / U on the reference length L.

A steady roll is a steady flow in the body's frame too: about the x axis through B, with the inflow along x,
Omega x U_inf vanishes, so the rotating sphere needs no source (with drift or pitch the same source cancels
the Coriolis term as in a turn). Its axis passes through B: the motion is a helix, not a turn about A.

The solver frame translates with B. The far field is the uniform inflow U_inf = -V. Inside the sphere the
frame also rotates with Omega about B (MRF); a uniform specific momentum source Omega x U_inf
(= -Omega x (Omega x R0), R0 = B - A) cancels the Coriolis term of the free stream, so uniform flow is an
exact solution in both zones (Hu & Lin 2008; the seed paper's Eq. 8).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import ConfigurationError

KNOT = 1852.0 / 3600.0  # m/s

# The condition variables a study can sweep, one at a time about straight-ahead, each with its motion variable
# as the derivatives' names write it (Y'v, Z'w, N'r, M'q, K'p).
SWEEP_VARIABLES = {"drift_deg": "v", "pitch_deg": "w", "yaw_rate_prime": "r", "pitch_rate_prime": "q",
                   "roll_rate_prime": "p"}
SWEEP_KEYS = tuple(SWEEP_VARIABLES)

MAX_INCIDENCE_DEG = 30.0  # the far field accepts any inflow direction; beyond this the wake leaves its refinement
MAX_RATE_PRIME = 1.0  # r' = L/R0 = 1 puts the turn centre one body length away, beyond any rotating-arm test
# p' = 2 moves a point 0.1 L from the axis (SUBOFF's sail tip) at 0.2 U, 11 degrees of helix: about where a
# fin's lift stops being linear in its incidence
MAX_ROLL_RATE_PRIME = 2.0


@dataclass(frozen=True)
class Condition:
    """One captive condition. Angles in degrees, rates non-dimensional on L, speed in m/s."""

    speed: float
    drift_deg: float = 0.0
    pitch_deg: float = 0.0
    yaw_rate_prime: float = 0.0
    pitch_rate_prime: float = 0.0
    roll_rate_prime: float = 0.0

    def __post_init__(self):
        if not (math.isfinite(self.speed) and self.speed > 0):
            raise ConfigurationError(f"speed must be positive, got {self.speed} m/s")
        for label, value in (("drift angle", self.drift_deg), ("pitch angle", self.pitch_deg)):
            if not (math.isfinite(value) and abs(value) <= MAX_INCIDENCE_DEG):
                raise ConfigurationError(f"{label} {value} deg is outside +-{MAX_INCIDENCE_DEG} deg")
        for label, value in (("r'", self.yaw_rate_prime), ("q'", self.pitch_rate_prime)):
            if not (math.isfinite(value) and abs(value) <= MAX_RATE_PRIME):
                raise ConfigurationError(
                    f"turn rate {label} = {value} is impossible here: |{label}| must be at most {MAX_RATE_PRIME} "
                    "(turn radius at least one body length)"
                )
        if not (math.isfinite(self.roll_rate_prime) and abs(self.roll_rate_prime) <= MAX_ROLL_RATE_PRIME):
            raise ConfigurationError(f"roll rate p' = {self.roll_rate_prime} is outside +-{MAX_ROLL_RATE_PRIME} "
                                     "(the fins' helix angle would leave their linear range)")

    @property
    def defining_loads(self) -> tuple[str, ...]:
        """The load coefficients whose change from straight ahead gives this condition's derivatives: Y' and N'
        for drift and yaw turns, Z' and M' for pitch and pitch turns, K' for a roll, none straight ahead."""
        loads: tuple[str, ...] = ()
        if self.drift_deg or self.yaw_rate_prime:
            loads += ("Y", "N")
        if self.pitch_deg or self.pitch_rate_prime:
            loads += ("Z", "M")
        if self.roll_rate_prime:
            loads += ("K",)
        return loads

    @property
    def name(self) -> str:
        """A file-system-safe label, e.g. ``U3.344_b+4_a0_r+0.3_q0`` (``_p+0.5`` added for a roll only, so that
        the conditions of studies written before rolls keep their names and work directories)."""

        def fmt(x: float) -> str:
            return "0" if x == 0 else f"{x:+g}"

        return (
            f"U{self.speed:g}_b{fmt(self.drift_deg)}_a{fmt(self.pitch_deg)}"
            f"_r{fmt(self.yaw_rate_prime)}_q{fmt(self.pitch_rate_prime)}"
            + (f"_p{fmt(self.roll_rate_prime)}" if self.roll_rate_prime else "")
        )

    @property
    def is_turning(self) -> bool:
        return self.yaw_rate_prime != 0.0 or self.pitch_rate_prime != 0.0 or self.roll_rate_prime != 0.0

    def body_velocity(self) -> np.ndarray:
        """Velocity V = (u, v, w) of the moment centre in body axes, m/s."""
        a, b = math.radians(self.pitch_deg), math.radians(self.drift_deg)
        return self.speed * np.array([math.cos(a) * math.cos(b), -math.sin(b), -math.sin(a) * math.cos(b)])

    def inflow(self) -> np.ndarray:
        """Far-field velocity U_inf = -V seen in the frame that translates with B, m/s."""
        return -self.body_velocity()

    def angular_velocity(self, length: float) -> np.ndarray:
        """Omega = (p, q, r) in body axes, rad/s."""
        return np.array([self.roll_rate_prime, self.pitch_rate_prime, self.yaw_rate_prime]) * self.speed / length

    def momentum_source(self, length: float) -> np.ndarray:
        """Uniform specific momentum source of the rotating zone, Delta/rho = Omega x U_inf, m/s^2."""
        return np.cross(self.angular_velocity(length), self.inflow())

    def turn_centre(self, length: float) -> np.ndarray | None:
        """Turn centre A in body axes (None without rotation): Omega x (B - A) is the velocity normal to Omega."""
        omega = self.angular_velocity(length)
        if not omega.any():
            return None
        return np.cross(omega, self.body_velocity()) / float(omega @ omega)
