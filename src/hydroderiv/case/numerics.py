"""Discretisation and solver settings of the steady RANS runs (simpleFoam).

The entries cover every model of hydroderiv.case.fluid.TURBULENCE_MODELS; OpenFOAM ignores those a model
does not read, so a mesh case and a condition case share one set.
"""

from __future__ import annotations

from pathlib import Path

from .._foam import write_foam_dict


SECOND_ORDER = "bounded Gauss linearUpwind grad({})"
FIRST_ORDER = "bounded Gauss upwind"


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
# (CaseSettings.limit_pressure_gradient_at_start): the converged solution is then the unlimited one.
LIMITED_PRESSURE_GRADIENT = "cellLimited Gauss linear 1"


def _convection_schemes(second_order: bool) -> dict[str, str]:
    convection = SECOND_ORDER if second_order else FIRST_ORDER
    return {f"div(phi,{field})": convection.format(field) for field in ("U", "k", "omega", "epsilon")}


def write_numerics(case: Path, second_order: bool = True, limit_pressure_gradient: bool = False) -> None:
    """fvSchemes and fvSolution. Second-order (bounded linear-upwind) convection for validation runs."""
    pressure_gradient = {"grad(p)": LIMITED_PRESSURE_GRADIENT} if limit_pressure_gradient else {}
    write_foam_dict(
        Path(case) / "system/fvSchemes",
        {
            "ddtSchemes": {"default": "steadyState"},
            "gradSchemes": {
                "default": "Gauss linear",
                "grad(U)": "cellLimited Gauss linear 1",
                "grad(k)": "cellLimited Gauss linear 1",
                "grad(omega)": "cellLimited Gauss linear 1",
                "grad(epsilon)": "cellLimited Gauss linear 1",
                **pressure_gradient,
            },
            "divSchemes": {
                "default": "none",
                **_convection_schemes(second_order),
                "div(nonlinearStress)": "Gauss linear",  # the quadratic stresses of ShihQuadraticKE
                "div((nuEff*dev2(T(grad(U)))))": "Gauss linear",
            },
            "laplacianSchemes": {"default": "Gauss linear limited corrected 0.33"},
            "interpolationSchemes": {"default": "linear"},
            "snGradSchemes": {"default": "limited corrected 0.33"},
            "wallDist": {"method": "meshWave"},
        },
    )
    write_foam_dict(
        Path(case) / "system/fvSolution",
        {
            "solvers": {
                "p": {"solver": "GAMG", "smoother": "GaussSeidel", "tolerance": 1e-7, "relTol": 0.05},
                '"(U|k|omega|epsilon)"': {"solver": "smoothSolver", "smoother": "symGaussSeidel", "tolerance": 1e-8, "relTol": 0.1},
            },
            "SIMPLE": {"nNonOrthogonalCorrectors": 0, "consistent": False},
            "relaxationFactors": {"fields": {"p": 0.3}, "equations": {"U": 0.7, "k": 0.6, "omega": 0.6, "epsilon": 0.6}},
        },
    )


def switch_to_second_order_convection(case: Path, limit_pressure_gradient: bool) -> None:
    """Rewrite the case's numerics with second-order convection (simpleFoam re-reads them) and the
    pressure-gradient choice that holds from here on (CaseSettings.limit_pressure_gradient)."""
    write_numerics(case, second_order=True, limit_pressure_gradient=limit_pressure_gradient)


def has_second_order_convection(case: Path) -> bool:
    """Whether the case's fvSchemes convects momentum with the second-order scheme (an interrupted cold
    start may still hold its first-order schemes)."""
    from foamlib import FoamFile

    entry = FoamFile(Path(case) / "system/fvSchemes")["divSchemes"]["div(phi,U)"]
    words = entry.split() if isinstance(entry, str) else [str(word) for word in entry]
    return words == SECOND_ORDER.format("U").split()
