"""The fluid and the free-stream turbulence."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Fluid:
    """Density (kg/m^3) and dynamic viscosity (kg/(m s)). Default: water at 18 C as in Roddy (1990)."""

    rho: float = 998.55
    mu: float = 0.001053

    @property
    def nu(self) -> float:
        return self.mu / self.rho


@dataclass(frozen=True)
class FreestreamTurbulence:
    """Inflow turbulence: intensity and eddy-viscosity ratio (a quiet towing tank)."""

    intensity: float = 0.01
    viscosity_ratio: float = 10.0

    def k(self, speed: float) -> float:
        return 1.5 * (self.intensity * speed) ** 2

    def omega(self, speed: float, nu: float) -> float:
        return self.k(speed) / (nu * self.viscosity_ratio)
