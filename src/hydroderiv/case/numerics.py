"""Discretisation and solver settings of the steady RANS runs (simpleFoam).

The entries cover every model of hydroderiv.case.fluid.TURBULENCE_MODELS; OpenFOAM ignores those a model
does not read, so a mesh case and a condition case share one set.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from .._foam import write_foam_dict
from ..errors import ConfigurationError
from .fluid import DEFAULT_TURBULENCE_MODEL, TURBULENCE_MODELS


SECOND_ORDER = "bounded Gauss linearUpwind"  # followed by the name of the gradient scheme it reconstructs with
FIRST_ORDER = "bounded Gauss upwind"


def limited_gradient(coefficient: float = 1.0) -> str:
    """The cell-limited Gauss gradient with limiter coefficient ``coefficient`` (1: no face value beyond the
    neighbouring cells' values)."""
    return f"cellLimited Gauss linear {coefficient:g}"


LIMITED_GRADIENT = limited_gradient(1.0)

# every field some model of TURBULENCE_MODELS transports: k, omega, epsilon, nuTilda, R
TURBULENCE_FIELDS = tuple(dict.fromkeys(field for fields in TURBULENCE_MODELS.values() for field in fields))


# The pressure gradient limited like the others. On a mesh whose first prism layer resolves the wall
# (y+ about 2, 33 um under 8 mm surface cells on the coarse AFF-8 mesh), the first pressure solve of a cold
# start puts kinematic pressures of about 60 m2/s2 (ten times the stagnation pressure) in the layer cells
# wrapped around the sail's leading edge; the unlimited gradient carried them into the momentum predictor,
# which drove 85 m/s against the inflow there at the second iteration, and simpleFoam blew up by the
# eighth. Limited, the same case ran on. Off by default: it is not needed with wall functions, and the
# committed results were computed without it.
# The limiter is not free: it clips the gradient at every pressure extremum, the suction peaks of the sail
# and fins included. On the coarse AFF-8 mesh (Shih's model, 2026-12-01) it cut the side force at 4 degrees
# of drift by 10.5 % (Y'v -0.0229 against -0.0256). A study can therefore limit it only while a cold start
# runs first order, where the blow-up happens, and drop it when second order takes over
# (SolverOptions.limit_pressure_gradient_at_start, case/solver_options.py): the converged solution is then
# the unlimited one.
LIMITED_PRESSURE_GRADIENT = LIMITED_GRADIENT

# Where the velocity gradient is limited. "everywhere" (the default, as OpenFOAM's own case templates do):
# grad(U) is cell-limited for the linear-upwind reconstruction of face velocities and therefore also in
# every other term that takes grad(U), the turbulence models' strain rate and the viscous stress among
# them. "convection": the reconstruction alone uses the limited gradient (named LIMITED_FOR_CONVECTION in
# gradSchemes), which keeps convection bounded, while the strain rate and the stress see the plain
# gradient. "nowhere": no limiter at all, the reconstruction unbounded; a diagnostic only. On the coarse
# AFF-8 mesh (Shih, 2026-12-01) it took 638 iterations from uniform flow against 274, cut the drag by 8 %
# and gave the rudders erratic loads (the top rudder's side force per degree fell sixfold from 1 to 4
# degrees), so the convection scheme needs its limiter. "convection" moved every derivative by 0.3-2.5 %.
# The limiter clips the gradient in cells at a local extremum, such as the suction peaks of the sail and
# fins, where the pressure-gradient limiter was found to cost side force (above).
VELOCITY_GRADIENT_LIMITING = ("everywhere", "convection", "nowhere")
LIMITED_FOR_CONVECTION = "limitedForConvection"

# How hard the velocity gradient is limited: the coefficient k of `cellLimited Gauss linear k`. With k = 1
# no reconstructed face value leaves the range of the cell's and its neighbours' values; a smaller k widens
# that range by (1/k - 1) times itself, so the limiter acts only on overshoots that much larger (k = 0.5:
# twice the range). The limiter is a switch (min(1, r)): it acts at every local extremum of a velocity
# component, however smooth, and how many cells it clips there changes with the incidence. The question
# behind the option was whether the limiter makes the loads grow faster than linearly at small incidences
# (docs/validation.md), which shortens the fitted slopes at the origin. It does not (2026-12-06,
# coarse AFF-8, Spalart-Allmaras: the side force per degree grows by 7 % from 1 to 4 degrees with k = 1
# and with k = 0.5), but k = 0.5 shifts the loads themselves: side force and drag 12-16 % lower, the
# hull's side force in a turn up to half higher, the rudders' small-angle loads erratic; on the medium
# mesh 4-5 % and 6 % of the turn's side force. So the option measures the limiter's share of the
# numerical error; it is not a better default.
DEFAULT_VELOCITY_LIMITER_COEFFICIENT = 1.0

# The surface-normal gradients (diffusion, the pressure equation, the wall shear) with their non-orthogonal
# correction limited to a third of the orthogonal part: snappyHexMesh's meshes reach 75-80 degrees of
# non-orthogonality where prism layers end. The medium AFF-3 table of record's turns (r' = +-0.1) and
# drifts (+-4 degrees) continued 400 iterations with the full correction ("corrected") moved the turns' side
# force and yaw moment by +0.55 and +0.39 % (mirror-pair means) and the drifts' by +0.16 and -0.06 %
# (2026-12-07, scripts/continue_condition.py --non-orthogonal-correction 1): the limit is not what the
# rotary derivatives lack.
NON_ORTHOGONAL_CORRECTION = "limited corrected 0.33"


# The convection of the transported turbulence fields once second order takes over: "second" (the default,
# as momentum's) or "first" (upwind, bounded and diffusive). The Reynolds-stress model needs "first" on these
# meshes (coarse AFF-3, 2026-12-07, by hand): with second-order convection of R and epsilon it diverged within
# 40 iterations of the cubic k-epsilon's solution even with R relaxed by 0.3, and within 146 after 150 stable
# first-order ones. A table computed so is comparable with others computed so, not with the second-order ones.
TURBULENCE_CONVECTION_ORDERS = ("second", "first")

# Under-relaxation a model needs beyond the defaults (U 0.7, the turbulence fields 0.6, p as the coupling
# says; a smaller factor wins). The Reynolds-stress model ran stably on the coarse AFF-3 mesh only with these
# (the same hand runs). The converged steady solution does not depend on them; the iterations to it do.
MODEL_RELAXATION = {"LRR": {"U": 0.5, "R": 0.2, "p": 0.2}}


def check_turbulence_convection(value, source: str = "") -> str:
    """``value`` if it is an order of TURBULENCE_CONVECTION_ORDERS; else an error naming ``source`` and the choices."""
    return _one_of("turbulence_convection", value, TURBULENCE_CONVECTION_ORDERS, source)


# The pressure-velocity coupling. "SIMPLE" (the default, and that of every result before the resolved-wall
# studies of 2026-12-02) relaxes the pressure by 0.3. On meshes that resolve the wall (the body-fitted
# SUBOFF hull at y+ = 1-5, first cells 17-84 um under 5-30 mm steps along the nose) it blew up within ten iterations of a cold start, with or
# without a turbulence model: the wall cells on the nose took velocities of 100-200 m/s straight into the
# wall by the fifth iteration (a decoupled pressure-velocity mode in cells that thin, we think; not checked
# further). "SIMPLEC" (OpenFOAM's `consistent` SIMPLE) keeps the neighbour coefficients in the velocity
# correction, so the pressure needs little relaxation (0.9 here); on the same meshes it ran from uniform
# flow without trouble (2026-12-02).
PRESSURE_VELOCITY_COUPLINGS = {"SIMPLE": {"consistent": False, "p": 0.3}, "SIMPLEC": {"consistent": True, "p": 0.9}}


def check_pressure_velocity_coupling(value, source: str = "") -> str:
    """``value`` if it names a coupling of PRESSURE_VELOCITY_COUPLINGS; else an error naming ``source`` and the choices."""
    return _one_of("pressure_velocity_coupling", value, PRESSURE_VELOCITY_COUPLINGS, source)


def _naming(source: str) -> str:
    """The start of an error message that names ``source`` (the file), if one is given."""
    return f"{source}: " if source else ""


def _one_of(key: str, value, choices, source: str) -> str:
    if value not in choices:
        raise ConfigurationError(f"{_naming(source)}{key} = {value!r} must be one of {', '.join(map(repr, choices))}")
    return value


@dataclass(frozen=True)
class GradientLimiters:
    """Which gradients are cell-limited: the pressure gradient (bool), and where the velocity gradient is
    (one of VELOCITY_GRADIENT_LIMITING)."""

    pressure: bool = False
    velocity: str = "everywhere"
    velocity_coefficient: float = DEFAULT_VELOCITY_LIMITER_COEFFICIENT  # k of the velocity limiter, in (0, 1]

    def __post_init__(self):
        check_velocity_limiter(self.velocity, self.velocity_coefficient)


def check_velocity_limiter(where, coefficient, source: str = "") -> None:
    """An error naming ``source`` unless ``where`` (VELOCITY_GRADIENT_LIMITING) and the limiter coefficient
    make sense, also together."""
    check_velocity_gradient_limiting(where, source)
    check_velocity_limiter_coefficient(coefficient, source)
    if where == "nowhere" and coefficient != DEFAULT_VELOCITY_LIMITER_COEFFICIENT:
        raise ConfigurationError(f"{_naming(source)}velocity_limiter_coefficient = {coefficient!r} needs a velocity limiter, "
                                 "and limit_velocity_gradient = 'nowhere' has none")


def check_velocity_gradient_limiting(value, source: str = "") -> str:
    """``value`` if it is a place to limit the velocity gradient; else an error naming ``source`` and the choices."""
    return _one_of("limit_velocity_gradient", value, VELOCITY_GRADIENT_LIMITING, source)


def check_velocity_limiter_coefficient(value, source: str = "") -> float:
    """``value`` as a float if it is a limiter coefficient k, 0 < k <= 1; else an error naming ``source``."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0.0 < value <= 1.0:
        raise ConfigurationError(f"{_naming(source)}velocity_limiter_coefficient = {value!r} must be a number in (0, 1] "
                                 "(1: fully limited, smaller: only larger overshoots limited)")
    return float(value)


def _convection_schemes(second_order: bool, limiters: GradientLimiters, turbulence_convection: str) -> dict[str, str]:
    def scheme(field: str) -> str:
        if not second_order or (field != "U" and turbulence_convection == "first"):
            return FIRST_ORDER
        limited_for_convection_only = field == "U" and limiters.velocity == "convection"
        return f"{SECOND_ORDER} {LIMITED_FOR_CONVECTION if limited_for_convection_only else f'grad({field})'}"

    return {f"div(phi,{field})": scheme(field) for field in ("U", *TURBULENCE_FIELDS)}


def _gradient_schemes(limiters: GradientLimiters) -> dict[str, str]:
    schemes = {"default": "Gauss linear"}
    velocity_limited = limited_gradient(limiters.velocity_coefficient)
    if limiters.velocity == "everywhere":
        schemes["grad(U)"] = velocity_limited
    elif limiters.velocity == "convection":
        schemes[LIMITED_FOR_CONVECTION] = velocity_limited
    schemes.update({f"grad({field})": LIMITED_GRADIENT for field in TURBULENCE_FIELDS})
    if limiters.pressure:
        schemes["grad(p)"] = LIMITED_PRESSURE_GRADIENT
    return schemes


def _write_schemes(case: Path, second_order: bool, limiters: GradientLimiters, turbulence_convection: str) -> None:
    write_foam_dict(
        Path(case) / "system/fvSchemes",
        {
            "ddtSchemes": {"default": "steadyState"},
            "gradSchemes": _gradient_schemes(limiters),
            "divSchemes": {
                "default": "none",
                **_convection_schemes(second_order, limiters, check_turbulence_convection(turbulence_convection)),
                "div(nonlinearStress)": "Gauss linear",  # the nonlinear stresses of ShihQuadraticKE and LienCubicKE
                # the Reynolds-stress model's stress in the momentum equation, and its viscous part (it
                # takes the molecular viscosity's stress apart from the turbulent one)
                "div(R)": "Gauss linear",
                "div((nu*dev2(T(grad(U)))))": "Gauss linear",
                "div((nuEff*dev2(T(grad(U)))))": "Gauss linear",
            },
            "laplacianSchemes": {"default": f"Gauss linear {NON_ORTHOGONAL_CORRECTION}"},
            "interpolationSchemes": {"default": "linear"},
            "snGradSchemes": {"default": NON_ORTHOGONAL_CORRECTION},
            "wallDist": {"method": "meshWave"},
        },
    )


def write_numerics(case: Path, second_order: bool = True, limiters: GradientLimiters = GradientLimiters(),
                   coupling: str = "SIMPLE", turbulence_model: str = DEFAULT_TURBULENCE_MODEL,
                   turbulence_convection: str = "second") -> None:
    """fvSchemes and fvSolution. Second-order (bounded linear-upwind) convection for validation runs (the
    turbulence fields' as ``turbulence_convection`` says); ``coupling`` is one of PRESSURE_VELOCITY_COUPLINGS;
    ``turbulence_model`` may need more under-relaxation (MODEL_RELAXATION)."""
    _write_schemes(case, second_order, limiters, turbulence_convection)
    simple = PRESSURE_VELOCITY_COUPLINGS[check_pressure_velocity_coupling(coupling)]
    equations = {"U": 0.7, **{field: 0.6 for field in TURBULENCE_FIELDS}}
    fields = {"p": simple["p"]}
    for name, factor in MODEL_RELAXATION.get(turbulence_model, {}).items():
        relaxed = fields if name == "p" else equations
        relaxed[name] = min(relaxed[name], factor)
    write_foam_dict(
        Path(case) / "system/fvSolution",
        {
            "solvers": {
                "p": {"solver": "GAMG", "smoother": "GaussSeidel", "tolerance": 1e-7, "relTol": 0.05},
                f'"(U|{"|".join(TURBULENCE_FIELDS)})"': {"solver": "smoothSolver", "smoother": "symGaussSeidel",
                                                           "tolerance": 1e-8, "relTol": 0.1},
            },
            "SIMPLE": {"nNonOrthogonalCorrectors": 0, "consistent": simple["consistent"]},
            "relaxationFactors": {"fields": fields, "equations": equations},
        },
    )


def switch_to_second_order_convection(case: Path, limiters: GradientLimiters, turbulence_convection: str = "second") -> None:
    """Rewrite the case's schemes with second-order convection (simpleFoam re-reads them; the turbulence
    fields' as ``turbulence_convection`` says) and the gradient limiters that hold from here on
    (CaseSettings.limiters_after_start). The solution controls (fvSolution) stay as the case was set up."""
    _write_schemes(case, second_order=True, limiters=limiters, turbulence_convection=turbulence_convection)


def has_second_order_convection(case: Path) -> bool:
    """Whether the case's fvSchemes convects momentum with the second-order scheme (an interrupted cold
    start may still hold its first-order schemes)."""
    from foamlib import FoamFile

    entry = FoamFile(Path(case) / "system/fvSchemes")["divSchemes"]["div(phi,U)"]
    words = entry.split() if isinstance(entry, str) else [str(word) for word in entry]
    return words[:-1] == SECOND_ORDER.split()
