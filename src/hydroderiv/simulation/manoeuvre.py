"""The vehicle's motion in time, controls fixed, from its derivative table: a manoeuvring simulation.

In one plane (three degrees of freedom: surge, sway and yaw, or surge, heave and pitch), body axes at the
moment centre B (x forward, y starboard, z down; r > 0 turning to starboard, q > 0 nose up), centre of gravity
x_G on the axis, the rigid-body equations of Gertler & Hagen (1967) are, with the hydrodynamic loads split
into the quasi-steady part (simulation/quasi_steady.py, from the steady captive conditions) and the
acceleration part (the added mass, derivatives/added_mass.py):

    horizontal   (m - X_u.) u.                          = X + T + m v r + m x_G r^2
                 (m - Y_v.) v. + (m x_G - Y_r.) r.      = Y - m u r
                 (m x_G - N_v.) v. + (I_z - N_r.) r.    = N - m x_G u r
    vertical     (m - X_u.) u.                          = X + T - m w q + m x_G q^2
                 (m - Z_w.) w. - (m x_G + Z_q.) q.      = Z + m u q
                 -(m x_G + M_w.) w. + (I_y - M_q.) q.   = M - m x_G u q - B z_BG sin(theta)

with the track from  x. = u cos(psi) - v sin(psi), y. = u sin(psi) + v cos(psi), psi. = r  (horizontal) or
x. = u cos(theta) + w sin(theta), z. = -u sin(theta) + w cos(theta), theta. = q  (vertical, z down). The
steady loads X, Y, N (X, Z, M) come from the table at the instantaneous speed V = sqrt(u^2 + v^2):
0.5 rho V^2 L^2 X'(u/V, v/V, r L/V), the usual quasi-steady assumption (the coefficients do not depend on
the Reynolds number). The steady loads already hold the added mass's own share in steady motion (the Munk
moment, the centripetal terms), as the captive conditions measured them; only the accelerations enter
separately. The thrust T is held at the straight run's drag at the table's speed, so that the vehicle
keeps that speed on a straight course and slows in a turn. In the vertical plane a neutrally buoyant
vehicle with its centre of gravity z_BG below its centre of buoyancy feels the hydrostatic moment
-rho g V z_BG sin(theta); the rest of the weight and buoyancy cancel.

Everything is integrated in the prime system (time in L/U, lengths in L, U the table's speed). Linearised
about straight motion, these equations are simulation/stability.py's (a test holds the two to the same
growth rate). The quasi-steady model holds over the range of the table's conditions; the simulation says
when its motion leaves it.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Mapping

import numpy as np
from scipy.integrate import solve_ivp

from ..errors import ConfigurationError
from .quasi_steady import QuasiSteadyLoads
from .stability import GRAVITY, PLANES, MassProperties, checked_hydrostatic_moment, mass_matrix

# plane -> (sway or heave velocity, rate, force, moment, angle): the table's and the quasi-steady model's names
_PLANE = {"horizontal": ("v", "r", "Y", "N", "psi"), "vertical": ("w", "q", "Z", "M", "theta")}


@dataclass(frozen=True)
class Trajectory:
    """A simulated motion: per output time, in prime units (time in L/U, positions in L, velocities in U,
    rates in U/L, angles in radians), and the table's reach that the motion exceeded (empty when none)."""

    plane: str
    time: np.ndarray
    states: dict[str, np.ndarray]  # u, v (w), r (q), x, y (z), psi (theta)
    beyond_range: list[str] = field(default_factory=list)

    def at_end(self) -> dict[str, float]:
        return {name: float(values[-1]) for name, values in self.states.items()}

    def rows(self) -> list[dict[str, float]]:
        return [{"t": float(t), **{name: float(values[k]) for name, values in self.states.items()}}
                for k, t in enumerate(self.time)]


class ManoeuvreSimulation:
    """Controls-fixed motion in one plane from a derivative table (see the module's equations).

    ``loads`` is the table's :class:`QuasiSteadyLoads`; ``acceleration`` the acceleration derivatives in prime
    units (derivatives/added_mass.py); ``mass`` the vehicle's (with its moment of inertia for the plane);
    ``reach`` the largest |v'|, |w'|, |r'|, |q'| the table's conditions hold (the motion is flagged beyond
    it); ``hydrostatic_moment_prime`` is rho g V z_BG / (0.5 rho U^2 L^3) (m' g z_BG / U^2 when neutrally
    buoyant), zero for a vehicle whose centre of gravity lies at its centre of buoyancy.
    ``straight_offsets=False`` drops the plane's force and moment on the straight course (Y', N' or Z', M' at
    rest in the plane): for a body that is its own mirror image in the plane they are the mesh's asymmetry,
    a numerical error that would itself start a turn."""

    def __init__(self, loads: QuasiSteadyLoads, acceleration: Mapping[str, float], mass: MassProperties,
                 plane: str = "horizontal", reach: Mapping[str, float] | None = None,
                 hydrostatic_moment_prime: float = 0.0, straight_offsets: bool = True):
        if plane not in _PLANE:
            raise ConfigurationError(f"unknown plane {plane!r}; choose one of {', '.join(_PLANE)}")
        if "Xudot" not in acceleration:
            raise ConfigurationError("the simulation needs the surge acceleration derivative Xudot")
        missing = [name for name in PLANES[plane] if name not in loads.terms]
        if missing:
            raise ConfigurationError(f"the table has no {', '.join(missing)}: its conditions do not cover the {plane} "
                                     "plane, so it cannot move the vehicle there")
        self.plane = plane
        self.loads = loads
        self.reach = dict(reach or {})
        self.hydrostatic_moment_prime = checked_hydrostatic_moment(plane, hydrostatic_moment_prime)
        self.mass = mass
        self._lateral_inertia = mass_matrix(acceleration, plane, mass)  # also checks that M is complete
        self._surge_inertia = mass.mass_prime - float(acceleration["Xudot"])
        straight = loads.coefficients()
        if not np.isfinite(straight["X"]):
            raise ConfigurationError("the table gives no straight-run drag (X'uu): the thrust is unknown")
        self._thrust = -straight["X"]  # holds the table's speed on a straight course
        _, _, force, moment, _ = _PLANE[plane]
        self._offsets = {force: 0.0, moment: 0.0} if straight_offsets else {force: straight[force], moment: straight[moment]}

    def derivatives_of_state(self, t: float, state: np.ndarray) -> np.ndarray:
        """d/dt' of (u', s', omega', x', n', angle): s the sway (heave) velocity, omega the yaw (pitch) rate,
        n the lateral (vertical) position."""
        u, s, rate, _, _, angle = state
        speed = float(np.hypot(u, s))
        if speed < 1e-6:
            # the quasi-steady loads are defined per unit of speed: a vehicle at rest has no prime velocities
            raise ConfigurationError(f"the vehicle has come to rest at t' = {t:.3g}: the quasi-steady loads are undefined")
        lateral, rate_name, force, moment, _ = _PLANE[self.plane]
        c = self.loads.coefficients(**{lateral: s / speed, rate_name: rate / speed, "u": u / speed})
        c = {k: value - self._offsets.get(k, 0.0) for k, value in c.items()}
        scale = speed * speed
        m, xg = self.mass.mass_prime, self.mass.xg_prime
        if self.plane == "horizontal":
            surge = scale * c["X"] + self._thrust + m * s * rate + m * xg * rate**2
            rhs = np.array([scale * c[force] - m * u * rate, scale * c[moment] - m * xg * u * rate])
            track = (u * np.cos(angle) - s * np.sin(angle), u * np.sin(angle) + s * np.cos(angle))
        else:
            surge = scale * c["X"] + self._thrust - m * s * rate + m * xg * rate**2
            rhs = np.array([scale * c[force] + m * u * rate,
                            scale * c[moment] - m * xg * u * rate - self.hydrostatic_moment_prime * np.sin(angle)])
            track = (u * np.cos(angle) + s * np.sin(angle), -u * np.sin(angle) + s * np.cos(angle))
        accelerations = np.linalg.solve(self._lateral_inertia, rhs)
        return np.array([surge / self._surge_inertia, accelerations[0], accelerations[1], track[0], track[1], rate])

    def run(self, lengths: float, lateral: float = 0.0, rate: float = 0.0, heading: float = 0.0,
            surge: float = 1.0, samples_per_length: int = 10) -> Trajectory:
        """Integrate for ``lengths`` body lengths of time (L/U each) from the velocities u' = ``surge``,
        ``lateral`` (v' or w') and ``rate`` (r' or q') at the heading (pitch attitude) ``heading`` in radians:
        straight motion at the table's speed when all but ``surge`` = 1 are zero."""
        if not (np.isfinite(lengths) and lengths > 0):
            raise ConfigurationError(f"the simulated time must be a positive number of body lengths, not {lengths}")
        if not all(np.isfinite(x) for x in (lateral, rate, heading, surge)):
            raise ConfigurationError("the initial state must be finite")
        if surge <= 0:
            raise ConfigurationError(f"the vehicle must start moving ahead (u' > 0), not u' = {surge}")
        times = np.linspace(0.0, lengths, int(round(lengths * samples_per_length)) + 1)
        solution = solve_ivp(self.derivatives_of_state, (0.0, lengths), [surge, lateral, rate, 0.0, 0.0, heading],
                             t_eval=times, method="DOP853", rtol=1e-9, atol=1e-12)
        if not solution.success:
            raise ConfigurationError(f"the simulation failed: {solution.message}")
        lateral_name, rate_name, _, _, angle_name = _PLANE[self.plane]
        names = ("u", lateral_name, rate_name, "x", "y" if self.plane == "horizontal" else "z", angle_name)
        states = dict(zip(names, solution.y))
        speed = np.hypot(states["u"], states[lateral_name])
        # the table's conditions are at the motion variables v' = v / V (w'), r' = r L / V (q')
        reached = {lateral_name: np.max(np.abs(states[lateral_name] / speed)),
                   rate_name: np.max(np.abs(states[rate_name] / speed))}
        beyond = [f"|{name}'| reaches {value:.3g} (the table's conditions reach {self.reach[name]:.3g})"
                  for name, value in reached.items() if name in self.reach and value > self.reach[name] + 1e-9]
        return Trajectory(self.plane, solution.t, states, beyond)


def table_reach(table: Mapping) -> dict[str, float]:
    """The largest |v'|, |w'|, |r'|, |q'| of a derivative table's conditions (empty without conditions)."""
    from ..case import Condition
    from ..derivatives.table import motion_variable

    reach: dict[str, float] = {}
    for record in table.get("conditions") or []:
        spec = record.get("condition") if isinstance(record, Mapping) else None
        if not isinstance(spec, Mapping):
            continue
        condition = Condition(1.0, **{k: spec.get(k, 0.0) for k in ("drift_deg", "pitch_deg", "yaw_rate_prime",
                                                                       "pitch_rate_prime")})
        v, _ = motion_variable(condition, "drift_deg")
        w, _ = motion_variable(condition, "pitch_deg")
        for name, value in (("v", v), ("w", w), ("r", condition.yaw_rate_prime), ("q", condition.pitch_rate_prime)):
            reach[name] = max(reach.get(name, 0.0), abs(float(value)))
    return reach

