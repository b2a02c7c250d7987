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

    def nu_tilda(self, nu: float) -> float:
        """Spalart-Allmaras' working variable that gives the same eddy viscosity, viscosity_ratio * nu.

        The model's eddy viscosity is nuTilda fv1(chi), chi = nuTilda / nu, fv1 = chi^3 / (chi^3 + cv1^3): so
        chi solves chi^4 / (chi^3 + cv1^3) = viscosity_ratio (Newton's method from chi = ratio + cv1).
        """
        chi = self.viscosity_ratio + SA_CV1
        for _ in range(50):
            residual = chi**4 / (chi**3 + SA_CV1**3) - self.viscosity_ratio
            slope = (chi**6 + 4.0 * chi**3 * SA_CV1**3) / (chi**3 + SA_CV1**3) ** 2
            chi -= residual / slope
        return chi * nu

    def reynolds_stress(self, speed: float) -> tuple[float, ...]:
        """The free stream's Reynolds stress R (xx, xy, xz, yy, yz, zz): isotropic, 2/3 k on the diagonal."""
        normal = 2.0 * self.k(speed) / 3.0
        return (normal, 0.0, 0.0, normal, 0.0, normal)

    def value(self, field: str, speed: float, nu: float) -> float | tuple[float, ...]:
        """The free-stream value of the transported turbulence field ``field`` (k, omega, epsilon, nuTilda,
        or the Reynolds stress R, a symmetric tensor)."""
        values = {"k": lambda: self.k(speed), "omega": lambda: self.omega(speed, nu),
                  "epsilon": lambda: self.epsilon(speed, nu), "nuTilda": lambda: self.nu_tilda(nu),
                  "R": lambda: self.reynolds_stress(speed)}
        if field not in values:
            raise ValueError(f"no free-stream value for the turbulence field {field!r}; known: {', '.join(values)}")
        return values[field]()


# RAS models on offer, each with the fields it transports. All work with wall functions (y+ about 50).
# k-omega SST is the default (the seed paper's model). Shih's quadratic k-epsilon adds stresses quadratic in
# the mean strain and rotation: a linear eddy viscosity cannot drive the secondary flow that keeps a
# junction's corner attached, and SST separated the suction-side corners at the sail's and rudders' trailing
# edges (issue-4 notes, 2026-11-30). Spalart-Allmaras (one equation, for the eddy viscosity itself) was
# made for aerofoils in adverse pressure gradients: SST's boundary layers run back over the last tenth of
# the thick NACA 0020 fins even straight ahead (issue-4 notes, 2026-12-02). Lien, Chen & Leschziner's cubic
# k-epsilon adds stresses cubic in strain and rotation as well: the cubic terms are the ones that make an
# eddy-viscosity model feel streamline curvature and swirl, which a turn adds to what the drift has.
# Launder, Reece & Rodi's Reynolds-stress model (LRR) does not tie the stresses to the strain through an eddy
# viscosity at all: it transports the six stresses R (with epsilon), so curvature, swirl and the anisotropy
# of the crossflow vortices act through the stresses' own production terms. It needs first-order convection
# of R and epsilon and heavier under-relaxation on these meshes (case/numerics.py,
# TURBULENCE_CONVECTION_ORDERS and MODEL_RELAXATION).
TURBULENCE_MODELS = {"kOmegaSST": ("k", "omega"), "ShihQuadraticKE": ("k", "epsilon"), "LienCubicKE": ("k", "epsilon"),
                     "realizableKE": ("k", "epsilon"), "SpalartAllmaras": ("nuTilda",), "LRR": ("R", "epsilon")}
DEFAULT_TURBULENCE_MODEL = "kOmegaSST"
C_MU = 0.09  # epsilon = C_mu k omega
SA_CV1 = 7.1  # Spalart & Allmaras (1994), the constant of the wall-damping function fv1


def check_turbulence_model(name: str, source: str = "") -> str:
    """``name`` if it is a turbulence model offered here; else an error naming ``source`` (a file) and the choices."""
    from ..errors import ConfigurationError

    if name not in TURBULENCE_MODELS:
        where = f"{source}: " if source else ""
        raise ConfigurationError(f"{where}unknown turbulence model {name!r}; choose one of {', '.join(TURBULENCE_MODELS)}")
    return name
