"""The two ways of putting a captive condition on the single mesh: hybrid frames and the classic rotating domain.

Both use OpenFOAM's MRF, which solves for the absolute velocity (the velocity in the inertial frame) and
adds the Coriolis term Omega x U in its zone. Body axes throughout (x forward, y starboard, z down, origin
at the moment centre B; r > 0 turns to starboard), see :mod:`hydroderiv.case.conditions`.

hybrid (the seed paper's method, the default)
    The frame translates with B; the far field is the uniform inflow U_inf = -V. The sphere of radius 2L
    about B rotates with Omega about B, and carries the uniform specific source Omega x U_inf
    (= -Omega x (Omega x R0), R0 = B - A), which cancels the Coriolis term of the free stream. The far field
    and the flow outside the sphere are inertial. Any drift, pitch and turn combine freely.

classic (for verification)
    The whole domain rotates with Omega about the turn centre A, and the fluid far away is at rest
    (absolute velocity zero); the body moves through it with V = Omega x (B - A). This is the textbook
    rotating-arm set-up; it can only represent motions whose velocity at B is normal to Omega (a plane
    turn, possibly with drift in that plane), and a straight run is plain translation, the same as hybrid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import ConfigurationError
from .conditions import Condition

FRAME_METHODS = ("hybrid", "classic")


@dataclass(frozen=True)
class FrameSetup:
    """What a method writes into a condition's case (body axes, SI units)."""

    farfield_velocity: np.ndarray  # velocity of the fluid far away, in the solver's variables
    omega: np.ndarray  # angular velocity of the MRF zone, rad/s
    origin: np.ndarray  # the point the zone rotates about
    source: np.ndarray  # uniform specific momentum source in the zone, m/s^2
    whole_domain_rotates: bool  # classic: the MRF zone is every cell, the far field does not move

    @property
    def rotating(self) -> bool:
        return bool(np.any(self.omega))


def frame_setup(condition: Condition, length: float, method: str = "hybrid") -> FrameSetup:
    """The frame set-up of ``condition`` under ``method`` ('hybrid' or 'classic')."""
    if method not in FRAME_METHODS:
        raise ConfigurationError(f"unknown frame method {method!r}; choose one of {', '.join(FRAME_METHODS)}")
    omega = condition.angular_velocity(length)
    if method == "hybrid" or not condition.is_turning:
        return FrameSetup(condition.inflow(), omega, np.zeros(3), condition.momentum_source(length), False)
    velocity = condition.body_velocity()
    along_axis = float(velocity @ omega) / float(np.linalg.norm(omega))
    if abs(along_axis) > 1e-9 * condition.speed:
        raise ConfigurationError(
            f"the classic method cannot run {condition.name}: the velocity of B has a component "
            f"{along_axis:+.4g} m/s along the rotation axis (a helix, not a plane turn); "
            "use the hybrid method, or drift only in the plane of the turn"
        )
    return FrameSetup(np.zeros(3), omega, condition.turn_centre(length), np.zeros(3), True)
