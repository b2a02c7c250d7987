"""Discretisation and solver settings of the steady RANS runs (simpleFoam).

The entries cover every model of hydroderiv.case.fluid.TURBULENCE_MODELS; OpenFOAM ignores those a model
does not read, so a mesh case and a condition case share one set.
"""

from __future__ import annotations

from pathlib import Path

from .._foam import write_foam_dict


SECOND_ORDER = "bounded Gauss linearUpwind grad({})"
FIRST_ORDER = "bounded Gauss upwind"


def write_numerics(case: Path, second_order: bool = True) -> None:
    """fvSchemes and fvSolution. Second-order (bounded linear-upwind) convection for validation runs."""
    convection = SECOND_ORDER if second_order else FIRST_ORDER
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
            },
            "divSchemes": {
                "default": "none",
                "div(phi,U)": convection.format("U"),
                "div(phi,k)": convection.format("k"),
                "div(phi,omega)": convection.format("omega"),
                "div(phi,epsilon)": convection.format("epsilon"),
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


def has_second_order_convection(case: Path) -> bool:
    """Whether the case's fvSchemes convects momentum with the second-order scheme (an interrupted cold
    start may still hold its first-order schemes)."""
    from foamlib import FoamFile

    entry = FoamFile(Path(case) / "system/fvSchemes")["divSchemes"]["div(phi,U)"]
    words = entry.split() if isinstance(entry, str) else [str(word) for word in entry]
    return words == SECOND_ORDER.format("U").split()
