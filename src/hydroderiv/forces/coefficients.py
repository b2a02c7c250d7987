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
