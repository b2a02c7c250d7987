"""Forces and moments in the prime system of Gertler & Hagen (1967).

Y' = Y / (0.5 rho U^2 L^2), N' = N / (0.5 rho U^2 L^3), on the reference length L (Roddy 1990 uses the
length between perpendiculars, 4.261 m for SUBOFF).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class PrimeScales:
    rho: float
    speed: float
    length: float

    @property
    def force(self) -> float:
        return 0.5 * self.rho * self.speed**2 * self.length**2

    @property
    def moment(self) -> float:
        return self.force * self.length

    def coefficients(self, force: np.ndarray, moment: np.ndarray) -> np.ndarray:
        """(X', Y', Z', K', M', N') from dimensional force and moment vectors (shape (..., 3) each)."""
        return np.concatenate([np.asarray(force) / self.force, np.asarray(moment) / self.moment], axis=-1)


COEFFICIENT_NAMES = ("X", "Y", "Z", "K", "M", "N")


def body_axis_loads(times: np.ndarray, force: np.ndarray, moment: np.ndarray, *, turn_centre: np.ndarray,
                    axis: np.ndarray, omega: float,
                    velocity: np.ndarray | tuple[float, float, float] = (0.0, 0.0, 0.0)) -> tuple[np.ndarray, np.ndarray]:
    """Force and moment in body axes about B, for a body that moves with the mesh.

    A moving-mesh run in the inertial frame records its loads in the fixed axes, the moment about a fixed
    point (OpenFOAM's forces function object has a fixed centre of rotation). The body either turns about
    ``turn_centre`` A, the point the moments are taken about, by omega t about ``axis`` (a unit vector through
    A) from its position at t = 0, where its axes were the mesh's and B the origin; or, with ``omega`` 0 and
    ``velocity`` V, moves in a straight line, B at V t, the moments taken about B's start A. A body-axis
    vector is the fixed-axis one turned back, and the moment about B is the one about A less (B - A) x F,
    with B - A = -A fixed in body axes while turning and -A + V t in fixed axes when translating.
    """
    # scipy here, not at the top: the load names above are read by the run monitor, which every CLI start
    # imports, and scipy would double that start-up time for a check that only the inertial-turn script runs
    from scipy.spatial.transform import Rotation

    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    times = np.asarray(times, float)
    back = Rotation.from_rotvec(-omega * times[:, None] * axis)  # one rotation per time
    force = np.asarray(force, float).reshape(-1, 3)
    travelled = np.outer(times, np.asarray(velocity, float))  # B's straight-line travel since t = 0
    body_force = back.apply(force)
    body_moment = (back.apply(np.asarray(moment, float).reshape(-1, 3) - np.cross(travelled, force))
                   - np.cross(-np.asarray(turn_centre, float), body_force))
    return body_force.reshape(-1, 3), body_moment.reshape(-1, 3)
