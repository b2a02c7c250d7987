"""The fluid, the free-stream turbulence and the RANS turbulence models on offer."""

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

    def epsilon(self, speed: float, nu: float) -> float:
        return C_MU * self.k(speed) * self.omega(speed, nu)


# RAS models on offer, each with the variable it transports besides k. All use wall functions (y+ about 50).
# k-omega SST is the default (the seed paper's model). Shih's quadratic k-epsilon adds stresses quadratic in
# the mean strain and rotation: a linear eddy viscosity cannot drive the secondary flow that keeps a
# junction's corner attached, and SST separated the suction-side corners at the sail's and rudders' trailing
# edges (issue-4 notes, 2026-11-30).
TURBULENCE_MODELS = {"kOmegaSST": "omega", "ShihQuadraticKE": "epsilon", "realizableKE": "epsilon"}
DEFAULT_TURBULENCE_MODEL = "kOmegaSST"
C_MU = 0.09  # epsilon = C_mu k omega


def check_turbulence_model(name: str, source: str = "") -> str:
    """``name`` if it is a turbulence model offered here; else an error naming ``source`` (a file) and the choices."""
    from ..errors import ConfigurationError

    if name not in TURBULENCE_MODELS:
        where = f"{source}: " if source else ""
        raise ConfigurationError(f"{where}unknown turbulence model {name!r}; choose one of {', '.join(TURBULENCE_MODELS)}")
    return name
