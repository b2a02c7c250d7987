"""Straight-line dynamic stability of the vehicle from its derivative table, controls fixed.

The first thing a designer does with Y'v, N'v, Y'r, N'r (and Z'w, M'w, Z'q, M'q) is ask whether the
vehicle keeps a straight course when disturbed. Linearised about straight motion at speed U, the
Gertler & Hagen (1967) equations in the prime system on L are, in the horizontal plane (body axes: x
forward, y starboard, z down; origin at the moment centre B; centre of gravity at x_G on the axis)

    (m' - Y'v.) v'. + (m' x_G' - Y'r.) r'.  =  Y'v v' + (Y'r - m') r'
    (m' x_G' - N'v.) v'. + (I'z - N'r.) r'.  =  N'v v' + (N'r - m' x_G') r'

and in the vertical plane (q > 0 nose up)

    (m' - Z'w.) w'. - (m' x_G' + Z'q.) q'.  =  Z'w w' + (Z'q + m') q'
    -(m' x_G' + M'w.) w'. + (I'y - M'q.) q'.  =  M'w w' + (M'q - m' x_G') q'

where m' = m / (0.5 rho L^3) and x_G' = x_G / L. The m' terms on the right are the centripetal
acceleration m u r (and m u q) of the body itself, which the hydrodynamic force must supply in a turn.
Written M x. = K x with the mass matrix M (body plus added mass) positive definite, the product of the
eigenvalues is det K / det M, so a negative det K means two real roots of opposite sign, one of them
positive: a disturbance grows without oscillation (the vehicle turns away on its own), whatever the
acceleration derivatives, which the steady captive tests do not measure. A positive det K leaves both roots
stable while the trace of M^-1 K is negative, as it is with the usual signs (Y'v, N'r, Z'w, M'q negative)
and a mass matrix dominated by its diagonal. Hence the stability criteria (e.g. Renilson, *Submarine
Hydrodynamics*, 2nd ed., 2018):

    C_H = Y'v (N'r - m' x_G') - N'v (Y'r - m')          stable if C_H > 0
    G_H = 1 - N'v (Y'r - m') / (Y'v (N'r - m' x_G'))     = C_H / (Y'v (N'r - m' x_G'))
        = 1 - l'_v / l'_r,   l'_v = N'v / Y'v,   l'_r = (N'r - m' x_G') / (Y'r - m')

and the vertical-plane C_V, G_V with Z'w, M'w, Z'q + m', M'q - m' x_G' and the levers
l'_w = -M'w / Z'w, l'_q = -(M'q - m' x_G') / (Z'q + m'). l'_v (l'_w) is where the sway (heave) force acts,
forward of B; l'_r (l'_q) is the lever of the damping in yaw (pitch): the vehicle is stable when the
damping lever is the longer. C_V and G_V leave out the hydrostatic restoring moment of the metacentric
height, which fades as 1/U^2 and is not a hydrodynamic derivative (it enters the roots below). The
stability index is what the derivatives' errors mean for a designer: a few per cent in Y'r moves l'_r, and
with it G_H, by much more when m' - Y'r is small.

How fast an unstable vehicle turns away does depend on M: the roots of det(K - lambda M) = 0 (:func:`plane_motion`),
with the acceleration derivatives estimated from the body's shape (derivatives/added_mass.py) and the
vehicle's moments of inertia, give the distance over which a disturbance doubles.

In the vertical plane a vehicle whose centre of gravity lies z_BG below its centre of buoyancy also feels the
hydrostatic moment -rho g V z_BG sin(theta), h' theta in prime units with h' = m' g z_BG / U^2 (neutrally
buoyant: buoyancy and weight m g). The pitch attitude theta (theta. = q) joins the state, and the
characteristic equation of (w', q', theta) becomes the cubic

    lambda det(lambda M - K) + h' ((m' - Z'w.) lambda - Z'w) = 0,

whose coefficients are linear in h'. By Routh and Hurwitz its roots all lie in the left half-plane exactly
when the four coefficients are positive and a2 a1 > a3 a0 (a_k the coefficient of lambda^k): each condition
is a half-line in h', so the vehicle is stable over one interval of h', that is one range of speeds
(:func:`vertical_stable_speeds`). The restoring moment fades as 1/U^2: a vehicle unstable in pitch on its
hydrodynamics alone (C_V < 0) is held by it up to a critical speed and no further.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Mapping

import numpy as np

from ..case import KNOT
from ..errors import ConfigurationError
from ..geometry import Body

GRAVITY = 9.80665  # m/s^2
# plane -> (force and moment per velocity, force and moment per rate), in the order of the formulas above
PLANES = {"horizontal": ("Yv", "Nv", "Yr", "Nr"), "vertical": ("Zw", "Mw", "Zq", "Mq")}
# the acceleration derivatives in the same order (derivatives/added_mass.py's names)
ACCELERATION = {"horizontal": ("Yvdot", "Nvdot", "Yrdot", "Nrdot"), "vertical": ("Zwdot", "Mwdot", "Zqdot", "Mqdot")}


@dataclass(frozen=True)
class MassProperties:
    """The rigid body's mass, centre of gravity and (where known) moments of inertia about the moment centre
    in the prime system: m' = m / (0.5 rho L^3), x_G' = x_G / L, I'z = I_z / (0.5 rho L^5), likewise I'y.
    The stability criteria need only the mass and x_G'; how fast a disturbance grows needs the inertia too."""

    mass_prime: float
    xg_prime: float
    source: str
    iz_prime: float | None = None
    iy_prime: float | None = None

    def __post_init__(self):
        if not np.isfinite(self.mass_prime) or self.mass_prime <= 0:
            raise ConfigurationError(f"the vehicle's mass m' must be positive, not {self.mass_prime}")
        if not np.isfinite(self.xg_prime):
            raise ConfigurationError(f"the centre of gravity x_G' must be finite, not {self.xg_prime}")
        for name, inertia in (("I'z", self.iz_prime), ("I'y", self.iy_prime)):
            # about the moment centre, no inertia is below the mass's own m x_G^2
            if inertia is not None and not (np.isfinite(inertia) and inertia >= self.mass_prime * self.xg_prime**2):
                raise ConfigurationError(f"the moment of inertia {name} = {inertia} is impossible for m' = "
                                         f"{self.mass_prime} at x_G' = {self.xg_prime}: it must be at least m' x_G'^2")

    @classmethod
    def neutrally_buoyant(cls, body: Body) -> MassProperties:
        """A vehicle trimmed to neutral buoyancy: its mass is the displaced water's, rho times the hull's
        volume, and its centre of gravity lies at the centre of buoyancy (the volume's centroid), as a
        submerged vehicle on a level course needs. So m' = 2 V / L^3. The moments of inertia are those of
        the displaced water as a rigid solid (the mass spread like the volume), a first estimate that a
        designer replaces with the vehicle's own."""
        length = body.reference.length
        moments = body.surface.second_moments  # \int x_i x_j dV about the moment centre
        return cls(mass_prime=2.0 * body.reference.volume / length**3,
                   xg_prime=float(body.surface.centroid[0]) / length,
                   source=f"neutrally buoyant {body.name}: mass of the displaced water "
                          f"({body.reference.volume:.5f} m^3), centre of gravity at the centre of buoyancy, "
                          f"inertia of the displaced water",
                   iz_prime=float(2.0 * (moments[0, 0] + moments[1, 1]) / length**5),
                   iy_prime=float(2.0 * (moments[0, 0] + moments[2, 2]) / length**5))


@dataclass(frozen=True)
class PlaneStability:
    """Straight-line stability in one plane (see the module docstring for the formulas)."""

    plane: str
    criterion: float  # C_H or C_V: > 0 stable
    index: float  # G_H or G_V = 1 - static lever / damping lever
    static_lever: float  # l'_v or l'_w: where the force per velocity acts, in L forward of the moment centre
    damping_lever: float  # l'_r or l'_q
    index_stderr: float | None  # from the derivatives' standard errors (independent, first order); None if not given

    @property
    def stable(self) -> bool:
        return self.criterion > 0

    def as_dict(self) -> dict:
        return {**asdict(self), "stable": self.stable}


def stiffness_matrix(derivatives: Mapping[str, float], plane: str, mass: MassProperties) -> np.ndarray:
    """K of M x. = K x in ``plane`` for x = (v', r') or (w', q'): the hydrodynamic derivatives with the
    body's own centripetal terms."""
    force_velocity, moment_velocity, force_rate, moment_rate = (derivatives[k] for k in _names(plane))
    m, xg = mass.mass_prime, mass.xg_prime
    # the body's centripetal force enters the yaw plane as -m' r' and the pitch plane as +m' q' (q > 0 nose up)
    sign = -1.0 if plane == "horizontal" else 1.0
    return np.array([[force_velocity, force_rate + sign * m], [moment_velocity, moment_rate - m * xg]])


def mass_matrix(acceleration: Mapping[str, float], plane: str, mass: MassProperties) -> np.ndarray:
    """M of M x. = K x in ``plane``: the body's mass and inertia with the added mass of the acceleration
    derivatives (keys as derivatives/added_mass.py names them)."""
    missing = [k for k in ACCELERATION[_check_plane(plane)] if k not in acceleration]
    if missing:
        raise ConfigurationError(f"the {plane} plane's motion needs the acceleration derivatives {', '.join(missing)}")
    force_velocity, moment_velocity, force_rate, moment_rate = (float(acceleration[k]) for k in ACCELERATION[plane])
    inertia, symbol = (mass.iz_prime, "I'z") if plane == "horizontal" else (mass.iy_prime, "I'y")
    if inertia is None:
        raise ConfigurationError(f"the {plane} plane's motion needs the vehicle's moment of inertia {symbol}")
    m, xg = mass.mass_prime, mass.xg_prime
    if plane == "horizontal":
        return np.array([[m - force_velocity, m * xg - force_rate], [m * xg - moment_velocity, inertia - moment_rate]])
    return np.array([[m - force_velocity, -(m * xg + force_rate)], [-(m * xg + moment_velocity), inertia - moment_rate]])


@dataclass(frozen=True)
class PlaneMotion:
    """How a small disturbance of straight motion evolves in one plane, controls fixed: the roots of
    det(K - lambda M) = 0 (three with a hydrostatic moment in pitch, the attitude joining the state), in units
    of U / L (time measured in body lengths travelled). A positive root grows as exp(lambda' s / L) over the
    distance s: it doubles every ln 2 / lambda' body lengths."""

    plane: str
    roots: tuple[complex, ...]
    growth_rate: float  # the largest real part, per body length travelled
    doubling_lengths: float | None  # body lengths for a disturbance to double (None when it decays)
    halving_lengths: float | None  # body lengths for the slowest decaying one to halve (None when one grows)
    hydrostatic_moment_prime: float = 0.0  # h' = m' g z_BG / U^2 (vertical plane), 0 without

    def as_dict(self) -> dict:
        record = {"plane": self.plane, "roots": [[float(r.real), float(r.imag)] for r in self.roots],
                  "growth_rate": self.growth_rate, "doubling_lengths": self.doubling_lengths,
                  "halving_lengths": self.halving_lengths}
        # recorded only where there is one, so that tables written without it read the same
        if self.hydrostatic_moment_prime:
            record["hydrostatic_moment_prime"] = self.hydrostatic_moment_prime
        return record


def hydrostatic_moment_prime(mass: MassProperties, bg_m: float, speed_m_s: float) -> float:
    """h' = rho g V z_BG / (0.5 rho U^2 L^3) = m' g z_BG / U^2 for a neutrally buoyant vehicle whose centre of
    gravity lies ``bg_m`` below its centre of buoyancy, at the speed ``speed_m_s``."""
    if not (np.isfinite(bg_m) and bg_m >= 0):
        raise ConfigurationError(f"the centre of gravity must lie at or below the centre of buoyancy: z_BG = {bg_m} m "
                                 "(a vehicle with it above capsizes; there is no straight motion to disturb)")
    if not (np.isfinite(speed_m_s) and speed_m_s > 0):
        raise ConfigurationError(f"the speed must be positive, not {speed_m_s} m/s")
    return mass.mass_prime * GRAVITY * bg_m / speed_m_s**2


def checked_hydrostatic_moment(plane: str, moment_prime: float) -> float:
    """The hydrostatic moment h' for motion in ``plane``, refused where it cannot act: it must be finite and
    zero or positive (the centre of gravity below the buoyancy), and it acts in pitch only."""
    moment_prime = float(moment_prime)
    if not (np.isfinite(moment_prime) and moment_prime >= 0):
        raise ConfigurationError(f"the hydrostatic moment h' must be zero or positive, not {moment_prime}")
    if moment_prime and plane != "vertical":
        raise ConfigurationError("a hydrostatic moment acts in pitch: give it for the vertical plane only")
    return moment_prime


def _state_matrices(derivatives: Mapping[str, float], acceleration: Mapping[str, float], plane: str,
                    mass: MassProperties, hydrostatic: float) -> tuple[np.ndarray, np.ndarray]:
    """(K, M) of M x. = K x: x = (v', r'), (w', q') or, with a hydrostatic moment h', (w', q', theta)."""
    stiffness = stiffness_matrix({k: float(derivatives[k]) for k in _names(plane)}, plane, mass)
    inertia = mass_matrix(acceleration, plane, mass)
    if not checked_hydrostatic_moment(plane, hydrostatic):
        return stiffness, inertia
    # theta. = q'; the moment equation gains -h' theta
    return (np.block([[stiffness, np.array([[0.0], [-hydrostatic]])], [np.array([[0.0, 1.0, 0.0]])]]),
            np.block([[inertia, np.zeros((2, 1))], [np.array([[0.0, 0.0, 1.0]])]]))


def plane_motion(derivatives: Mapping[str, float], acceleration: Mapping[str, float], plane: str,
                 mass: MassProperties, hydrostatic_moment_prime: float = 0.0) -> PlaneMotion:
    """The roots of the linearised motion in ``plane`` (see :class:`PlaneMotion`), with the hydrostatic moment
    h' (:func:`hydrostatic_moment_prime`) in the vertical plane. Without it the pitch attitude is neutral (a
    zero root, left out): the vehicle keeps whatever attitude a disturbance leaves."""
    stiffness, inertia = _state_matrices(derivatives, acceleration, plane, mass, hydrostatic_moment_prime)
    roots = np.linalg.eigvals(np.linalg.solve(inertia, stiffness))
    roots = tuple(sorted((complex(r) for r in roots), key=lambda r: (r.real, r.imag), reverse=True))
    growth = float(roots[0].real)
    return PlaneMotion(plane, roots, growth, float(np.log(2.0) / growth) if growth > 0 else None,
                       float(np.log(2.0) / -growth) if growth < 0 else None, float(hydrostatic_moment_prime))


def vertical_characteristic_coefficients(derivatives: Mapping[str, float], acceleration: Mapping[str, float],
                                         mass: MassProperties) -> tuple[tuple[float, float], ...]:
    """The cubic det(lambda M - K) of the vertical plane with the attitude in the state, as (a3, a2, a1, a0),
    each a pair (value without the hydrostatic moment, change per unit h'): a_k = c_k + s_k h'. See the
    module docstring."""
    stiffness, inertia = _state_matrices(derivatives, acceleration, "vertical", mass, 0.0)
    (m11, m12), (m21, m22) = inertia
    (k11, k12), (k21, k22) = stiffness
    # det(lambda M - K) = det M lambda^2 - (m11 k22 + m22 k11 - m12 k21 - m21 k12) lambda + det K, times lambda,
    # plus h' (m11 lambda - k11)
    return ((float(np.linalg.det(inertia)), 0.0), (float(-(m11 * k22 + m22 * k11 - m12 * k21 - m21 * k12)), 0.0),
            (float(np.linalg.det(stiffness)), float(m11)), (0.0, float(-k11)))


@dataclass(frozen=True)
class StableSpeeds:
    """The speeds at which a vehicle with its centre of gravity ``bg_m`` below its centre of buoyancy is stable
    in the vertical plane, controls fixed: from ``lowest_m_s`` to ``highest_m_s`` (None: at any speed above
    the lowest). ``stable_anywhere`` is False when no speed is stable. The same range in the hydrostatic
    moment h' = m' g z_BG / U^2, which does not depend on z_BG, is ``hydrostatic_moment_range`` (None
    without a stable speed; an upper end of None is unbounded)."""

    bg_m: float
    stable_anywhere: bool
    lowest_m_s: float | None
    highest_m_s: float | None
    hydrostatic_moment_range: tuple[float, float | None] | None = None

    def as_dict(self) -> dict:
        return asdict(self)

    def describe(self) -> str:
        prefix = f"with z_BG = {self.bg_m:g} m the vertical plane is"
        if not self.stable_anywhere:
            return f"{prefix} unstable at every speed"
        if self.highest_m_s is None:
            return (f"{prefix} stable above {self.lowest_m_s:.3f} m/s" if self.lowest_m_s
                    else f"{prefix} stable at every speed")
        low = f"from {self.lowest_m_s:.3f} m/s " if self.lowest_m_s else ""
        return (f"{prefix} stable {low}up to {self.highest_m_s:.3f} m/s ({self.highest_m_s / KNOT:.2f} kn; "
                f"h' = m' g z_BG / U^2 above {self.hydrostatic_moment_range[0]:.3e}), unstable above")


def vertical_stable_speeds(derivatives: Mapping[str, float], acceleration: Mapping[str, float],
                           mass: MassProperties, bg_m: float) -> StableSpeeds:
    """The range of speeds at which the vertical plane is stable with the hydrostatic moment of z_BG =
    ``bg_m`` (the Hurwitz conditions on the cubic, each linear in h' = m' g z_BG / U^2; see the module
    docstring). The derivatives are taken as independent of speed (the Reynolds number's effect neglected)."""
    if not (np.isfinite(bg_m) and bg_m > 0):
        raise ConfigurationError(f"a range of stable speeds needs the centre of gravity below the centre of buoyancy "
                                 f"(z_BG > 0), not z_BG = {bg_m} m")
    a3, a2, a1, a0 = vertical_characteristic_coefficients(derivatives, acceleration, mass)
    # a3 > 0 (M is positive definite) and a2 do not depend on h'; the rest, and a2 a1 - a3 a0, are c + s h'
    hurwitz = (a2, a1, a0, (a2[0] * a1[0] - a3[0] * a0[0], a2[0] * a1[1] - a3[0] * a0[1]))
    lowest_h, highest_h = 0.0, np.inf
    for constant, slope in hurwitz:
        if slope > 0:
            lowest_h = max(lowest_h, -constant / slope)
        elif slope < 0:
            highest_h = min(highest_h, -constant / slope)
        elif constant <= 0:
            highest_h = -np.inf  # fails at every h'
    weight = mass.mass_prime * GRAVITY * bg_m  # h' U^2
    if not highest_h > lowest_h or a3[0] <= 0:
        return StableSpeeds(float(bg_m), False, None, None)
    return StableSpeeds(float(bg_m), True, float(np.sqrt(weight / highest_h)) if np.isfinite(highest_h) else 0.0,
                        float(np.sqrt(weight / lowest_h)) if lowest_h > 0 else None,
                        (float(lowest_h), float(highest_h) if np.isfinite(highest_h) else None))


def _check_plane(plane: str) -> str:
    if plane not in PLANES:
        raise ConfigurationError(f"unknown plane {plane!r}; choose one of {', '.join(PLANES)}")
    return plane


def _names(plane: str) -> tuple[str, ...]:
    return PLANES[_check_plane(plane)]


def _criterion_index_levers(derivatives: Mapping[str, float], plane: str, mass: MassProperties):
    (a, b), (c, d) = stiffness_matrix(derivatives, plane, mass)
    criterion = a * d - c * b
    # levers: where the force per velocity acts (N = x Y in yaw, M = -x Z in pitch) and the damping's lever
    orientation = 1.0 if plane == "horizontal" else -1.0
    static_lever = orientation * c / a
    damping_lever = orientation * d / b
    return criterion, criterion / (a * d), static_lever, damping_lever


def plane_stability(derivatives: Mapping[str, float], plane: str, mass: MassProperties,
                    stderr: Mapping[str, float] | None = None) -> PlaneStability:
    """The stability criterion, index and levers of ``plane`` from ``derivatives`` (prime units, keys as in
    the derivative table). ``stderr`` (the same keys) carries the fits' standard errors to the index."""
    names = _names(plane)
    missing = [k for k in names if k not in derivatives]
    if missing:
        raise ConfigurationError(f"the {plane} plane needs {', '.join(names)}; the table lacks {', '.join(missing)}")
    values = {k: float(derivatives[k]) for k in names}
    criterion, index, static_lever, damping_lever = _criterion_index_levers(values, plane, mass)
    index_stderr = None
    if stderr is not None and all(k in stderr and np.isfinite(stderr[k]) for k in names):
        # first-order propagation, the derivatives taken as independent; central differences on each
        variance = 0.0
        for k in names:
            step = 1e-6 * max(abs(values[k]), 1e-9)
            up, down = dict(values), dict(values)
            up[k] += step
            down[k] -= step
            slope = (_criterion_index_levers(up, plane, mass)[1] - _criterion_index_levers(down, plane, mass)[1]) / (2 * step)
            variance += (slope * float(stderr[k])) ** 2
        index_stderr = float(np.sqrt(variance))
    return PlaneStability(plane, float(criterion), float(index), float(static_lever), float(damping_lever), index_stderr)


def stability(derivatives: Mapping[str, float], mass: MassProperties,
              stderr: Mapping[str, float] | None = None) -> dict[str, PlaneStability]:
    """Every plane whose four derivatives ``derivatives`` holds."""
    return {plane: plane_stability(derivatives, plane, mass, stderr)
            for plane, names in PLANES.items() if all(k in derivatives for k in names)}


def stability_report(values: Mapping[str, float], stderr: Mapping[str, float], mass: MassProperties,
                     reference: Mapping[str, float] | None = None,
                     acceleration: Mapping[str, float] | None = None,
                     bg_m: float = 0.0, speed_m_s: float | None = None) -> dict:
    """What a derivative table records: the mass properties, and per plane the computed stability beside
    the experiment's, from its own derivatives with the same mass (None where they were not all measured).
    With the acceleration derivatives (and the mass's inertia), each also carries the roots of the motion
    (``motion``, see :class:`PlaneMotion`), the experiment's with the same added mass. With the centre of
    gravity ``bg_m`` below the centre of buoyancy, the vertical plane's roots hold the hydrostatic moment at
    ``speed_m_s`` and ``stable_speeds`` gives the speeds at which it is stable (:class:`StableSpeeds`)."""
    computed = stability(values, mass, stderr)
    measured = stability(reference or {}, mass)

    def has_motion(plane: str) -> bool:
        inertia = mass.iz_prime if plane == "horizontal" else mass.iy_prime
        return acceleration is not None and inertia is not None and all(k in acceleration for k in ACCELERATION[plane])

    if bg_m and speed_m_s is None:
        raise ConfigurationError("the hydrostatic moment needs the speed: it fades as 1/U^2")
    if bg_m and not ("vertical" in computed and has_motion("vertical")):
        # said here rather than dropped: z_BG acts only through the vertical plane's roots
        raise ConfigurationError("the hydrostatic moment needs the vertical plane's motion: its four derivatives, "
                                 "the acceleration derivatives and I'y")
    hydrostatic = hydrostatic_moment_prime(mass, bg_m, speed_m_s) if bg_m else 0.0

    def entry(result: PlaneStability, derivatives: Mapping[str, float]) -> dict:
        plane = result.plane
        if not has_motion(plane):
            return result.as_dict()
        moment = hydrostatic if plane == "vertical" else 0.0  # the hydrostatic moment acts in pitch only
        record = {**result.as_dict(), "motion": plane_motion(derivatives, acceleration, plane, mass, moment).as_dict()}
        if moment:
            record["stable_speeds"] = vertical_stable_speeds(derivatives, acceleration, mass, bg_m).as_dict()
        return record

    return {"mass": asdict(mass),
            **{plane: {"computed": entry(s, values),
                       "experiment": entry(measured[plane], reference) if plane in measured else None}
               for plane, s in computed.items()}}
