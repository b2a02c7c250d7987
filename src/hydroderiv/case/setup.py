"""Writing one condition's OpenFOAM case onto the shared mesh.

Only the inflow vector, Omega and the momentum source change between conditions; the mesh is linked,
never rebuilt. Far field: the six cube faces form one patch whose conditions switch each face between
inflow and outflow with the local flux (freestreamVelocity / freestreamPressure), so any inflow direction
works on the same mesh. The frame method (hybrid or classic) is described in :mod:`hydroderiv.case.frames`.
"""

from __future__ import annotations

import os
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .._foam import quoted, write_decomposition, write_foam_dict
from ..errors import ConfigurationError
from ..forces.surface_flow import FIELD as WALL_SHEAR
from ..mesh.snappy import FARFIELD, ROTATING_ZONE, WALL_GROUP
from ..run.solver import STOP_FILE, TOTAL_FORCES, component_function_name
from .conditions import Condition
from .fluid import TURBULENCE_MODELS, Fluid, FreestreamTurbulence
from .frames import FRAME_METHODS, FrameSetup, frame_setup
from .numerics import GradientLimiters, write_numerics
from .solver_options import SolverOptions
from .warm_start import take_internal_field

COMPONENT_INTERVAL = 10  # iterations between per-component force samples


@dataclass(frozen=True)
class CaseSettings:
    """What a condition's case needs besides the condition itself."""

    length: float  # reference length L (Omega and the source scale with U/L)
    components: tuple[str, ...]
    fluid: Fluid = field(default_factory=Fluid)
    turbulence: FreestreamTurbulence = field(default_factory=FreestreamTurbulence)
    n_procs: int = 1
    max_iterations: int = 3000
    write_interval: int = 250  # iterations between intermediate writes, for resuming an interrupted run
    second_order: bool = True
    # A cold start (uniform flow everywhere) runs this many iterations with first-order convection before
    # the second-order schemes take over. From uniform flow, second order let k run away in a few poor
    # cells near the appendages' edges (coarse AFF-8, k to 1100 m2/s2 by iteration 45); after 80
    # first-order iterations the same mesh and condition ran on with k below 0.2 m2/s2.
    first_order_start: int = 80
    method: str = "hybrid"  # frame method, see hydroderiv.case.frames
    solver: SolverOptions = field(default_factory=SolverOptions)  # turbulence model and numerics

    def second_order_from(self, warm_start: Path | None) -> int | None:
        """The iteration at which second-order convection starts, or None if the case starts with it."""
        if self.second_order and warm_start is None and self.first_order_start > 0:
            return self.first_order_start
        return None

    def limits_pressure_gradient_only_at_start(self, warm_start: Path | None) -> bool:
        """Whether the case starts with the pressure gradient limited until the switch to second order."""
        return self.solver.limit_pressure_gradient_at_start and self.second_order_from(warm_start) is not None

    def limiters_at_start(self, warm_start: Path | None) -> GradientLimiters:
        """The gradient limiters a case starts with."""
        pressure = self.solver.limit_pressure_gradient or self.limits_pressure_gradient_only_at_start(warm_start)
        return self.solver.gradient_limiters(pressure)

    def limiters_after_start(self) -> GradientLimiters:
        """The gradient limiters from the switch to second-order convection on (and of a warm start)."""
        return self.solver.gradient_limiters(self.solver.limit_pressure_gradient)

    def __post_init__(self):
        if self.method not in FRAME_METHODS:
            raise ConfigurationError(f"unknown frame method {self.method!r}; choose one of {', '.join(FRAME_METHODS)}")


def _vector(v) -> list[float]:
    return [float(f"{x:.10g}") for x in np.asarray(v, dtype=float)]


def write_schedule(max_iterations: int, wanted_interval: int) -> tuple[int, int]:
    """(endTime, writeInterval) with endTime a multiple of the interval: OpenFOAM writes nothing at an
    endTime that is not a write time, and the last iterations of a capped run would be lost."""
    writes = max(1, -(-max_iterations // wanted_interval))
    interval = -(-max_iterations // writes)
    return interval * writes, interval


def _write_control(case: Path, s: CaseSettings) -> None:
    end, interval = write_schedule(s.max_iterations, s.write_interval)
    functions = {}
    force_common = {
        "type": "forces",
        "libs": [quoted("libforces.so")],
        "writeControl": "timeStep",
        "writeInterval": 1,
        "rho": "rhoInf",
        "rhoInf": s.fluid.rho,
        "CofR": [0.0, 0.0, 0.0],  # moments about the moment centre B, the origin of the body axes
        "log": False,
    }
    if s.components:  # an empty domain (frame verification) has no body to integrate over
        functions[TOTAL_FORCES] = {**force_common, "patches": list(s.components)}
        functions["yPlus"] = {"type": "yPlus", "libs": [quoted("libfieldFunctionObjects.so")], "writeControl": "writeTime"}
        # the direction of the flow at the wall, for the reversed-flow report (forces/surface_flow.py);
        # evaluated only when written: it builds the stress tensor over the whole mesh
        functions[WALL_SHEAR] = {"type": "wallShearStress", "libs": [quoted("libfieldFunctionObjects.so")],
                                 "patches": list(s.components), "executeControl": "writeTime",
                                 "writeControl": "writeTime"}
    # Each forces function object evaluates the viscous stress over the whole mesh; per-component
    # breakdowns only need sampling, so they run every COMPONENT_INTERVAL iterations.
    for component in s.components:
        functions[component_function_name(component)] = {
            **force_common,
            "patches": [component],
            "executeControl": "timeStep",
            "executeInterval": COMPONENT_INTERVAL,
            "writeInterval": COMPONENT_INTERVAL,
        }
    # Creating the file STOP in the case makes the solver write and exit: the convergence monitor's brake.
    functions["stop"] = {
        "type": "abort",
        "libs": [quoted("libutilityFunctionObjects.so")],
        "file": quoted(f"<case>/{STOP_FILE}"),
        "action": "writeNow",
    }
    write_foam_dict(
        case / "system/controlDict",
        {
            "application": "simpleFoam",
            "startFrom": "latestTime",
            "startTime": 0,
            "stopAt": "endTime",
            "endTime": end,
            "deltaT": 1,
            "writeControl": "timeStep",
            "writeInterval": interval,
            "purgeWrite": 1,
            "writeFormat": "binary",
            "writePrecision": 10,
            "writeCompression": False,
            "timeFormat": "general",
            "timePrecision": 8,
            "runTimeModifiable": True,
            "functions": functions,
        },
    )


def _write_physics(case: Path, frame: FrameSetup, s: CaseSettings) -> None:
    write_foam_dict(case / "constant/transportProperties", {"transportModel": "Newtonian", "nu": s.fluid.nu})
    write_foam_dict(
        case / "constant/turbulenceProperties",
        {"simulationType": "RAS", "RAS": {"RASModel": s.solver.turbulence_model, "turbulence": True, "printCoeffs": True}},
    )
    magnitude = float(np.linalg.norm(frame.omega))
    # hybrid: the sphere rotates about B and the far field outside it is inertial; classic: every cell
    # rotates about the turn centre, and the far field (fluid at rest) must not be given the frame velocity.
    write_foam_dict(
        case / "constant/MRFProperties",
        {
            "rotatingFrame": {
                "cellZone": ROTATING_ZONE,
                "active": frame.rotating,
                "nonRotatingPatches": [FARFIELD] if frame.whole_domain_rotates else [],  # the body rotates with the frame
                "origin": _vector(frame.origin),
                "axis": _vector(frame.omega / magnitude) if magnitude > 0 else [0.0, 0.0, 1.0],
                "omega": magnitude,
            }
        },
    )
    # hybrid: Delta/rho = Omega x U_inf on the same zone cancels the Coriolis term of the free stream in
    # OpenFOAM's absolute-velocity MRF, so uniform flow solves both zones exactly. Kinematic: m/s^2.
    write_foam_dict(
        case / "constant/fvOptions",
        {
            "hybridFramesSource": {
                "type": "vectorSemiImplicitSource",
                "active": bool(np.any(frame.source)),
                "selectionMode": "cellZone",
                "cellZone": ROTATING_ZONE,
                "volumeMode": "specific",
                "injectionRateSuSp": {"U": [_vector(frame.source), 0.0]},
            }
        },
    )


# Each transported turbulence field: its dimensions and its condition on the body. k, omega and epsilon
# take wall functions; Spalart-Allmaras' nuTilda is zero at a wall at any y+ (the wall law is nut's). The
# Reynolds stress R takes k's wall function (kqRWallFunction is a zero gradient for k, q and R alike).
_TURBULENCE_FIELDS = {
    "k": ("[0 2 -2 0 0 0 0]", "kqRWallFunction"),
    "R": ("[0 2 -2 0 0 0 0]", "kqRWallFunction"),
    "omega": ("[0 0 -1 0 0 0 0]", "omegaWallFunction"),
    "epsilon": ("[0 2 -3 0 0 0 0]", "epsilonWallFunction"),
    "nuTilda": ("[0 2 -1 0 0 0 0]", "fixedValue"),
}


def _transported_turbulence(field: str, value: float | tuple[float, ...]) -> dict:
    """A transported turbulence field: the free-stream value where the far field flows in, its wall
    condition on the body. A tuple ``value`` is a symmetric tensor's six components (R)."""
    dimensions, wall = _TURBULENCE_FIELDS[field]
    tensor = isinstance(value, tuple)
    if tensor:
        value = list(value)  # foamlib writes a list of numbers as one uniform value, a tuple as several entries
    return {
        "class": "volSymmTensorField" if tensor else "volScalarField",
        "dimensions": dimensions,
        "internal": value,
        "farfield": {"type": "inletOutlet", "inletValue": value, "value": value},
        "wall": {"type": wall, "value": 0.0 if field == "nuTilda" else value},
    }


def _fields(condition: Condition, frame: FrameSetup, s: CaseSettings) -> dict[str, dict]:
    # Field files: foamlib writes a plain value of a field entry as 'uniform <value>'.
    inflow = _vector(frame.farfield_velocity)
    transported = TURBULENCE_MODELS[s.solver.turbulence_model]
    # nut's wall law from k for the models that have a k (the Reynolds-stress model's is half R's trace);
    # Spalding's single law from the velocity, valid at any y+, for Spalart-Allmaras, which has no k
    nut_wall = "nutUSpaldingWallFunction" if "nuTilda" in transported else "nutkWallFunction"
    if frame.whole_domain_rotates:
        # Fluid at rest far away: an open boundary at zero total pressure that lets the body's displacement
        # flow in and out. (freestreamVelocity divides by the free-stream speed, which is zero here.)
        farfield_u = {"type": "pressureInletOutletVelocity", "value": inflow}
        farfield_p = {"type": "totalPressure", "p0": 0.0, "value": 0.0}
    else:
        farfield_u = {"type": "freestreamVelocity", "freestreamValue": inflow, "value": inflow}
        farfield_p = {"type": "freestreamPressure", "freestreamValue": 0.0, "value": 0.0}
    return {
        "U": {
            "class": "volVectorField",
            "dimensions": "[0 1 -1 0 0 0 0]",
            "internal": inflow,
            "farfield": farfield_u,
            "wall": {"type": "noSlip"},
        },
        "p": {
            "class": "volScalarField",
            "dimensions": "[0 2 -2 0 0 0 0]",
            "internal": 0.0,
            "farfield": farfield_p,
            "wall": {"type": "zeroGradient"},
        },
        **{field: _transported_turbulence(field, s.turbulence.value(field, condition.speed, s.fluid.nu)) for field in transported},
        "nut": {
            "class": "volScalarField",
            "dimensions": "[0 2 -1 0 0 0 0]",
            "internal": 0.0,
            "farfield": {"type": "calculated", "value": 0.0},
            "wall": {"type": nut_wall, "value": 0.0},
        },
    }


def _write_fields(
    case: Path, condition: Condition, frame: FrameSetup, s: CaseSettings, warm_start: Path | None, n_cells: int | None
) -> None:
    zero = case / "0"
    if zero.exists():
        shutil.rmtree(zero)
    for name, spec in _fields(condition, frame, s).items():
        # The patch group is written unquoted: a quoted "bodyWalls" would be a regular expression that
        # matches no patch name (groups are only matched by their plain name).
        boundary = {FARFIELD: spec["farfield"], WALL_GROUP: spec["wall"]}
        write_foam_dict(
            zero / name,
            {"dimensions": spec["dimensions"], "internalField": spec["internal"], "boundaryField": boundary},
            foam_class=spec["class"],
        )
        if warm_start is not None:
            take_internal_field(zero / name, warm_start / name, n_cells)


def latest_time_dir(case: Path) -> Path | None:
    """The latest written (reconstructed) time directory other than 0, if any."""
    times = []
    for d in Path(case).iterdir():
        try:
            value = float(d.name)
        except ValueError:
            continue
        if value > 0 and (d / "U").is_file():
            times.append((value, d))
    return max(times)[1] if times else None


def _link_mesh(case: Path, mesh_case: Path, whole_domain_zone: bool) -> None:
    """Link the shared mesh into ``case``. For the classic method the rotating zone must be every cell:
    the case gets its own cellZones file (the rest of the mesh stays linked file by file, never copied)."""
    link = case / "constant/polyMesh"
    if link.is_symlink() or link.exists():
        link.unlink() if link.is_symlink() else shutil.rmtree(link)
    shared = mesh_case / "constant/polyMesh"
    if not whole_domain_zone:
        os.symlink(shared, link, target_is_directory=True)
        return
    link.mkdir()
    for item in shared.iterdir():
        if item.name != "cellZones":
            os.symlink(item, link / item.name, target_is_directory=item.is_dir())
    n_cells = mesh_cell_count(shared)
    labels = "\n".join(map(str, range(n_cells)))
    (link / "cellZones").write_text(
        "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class regIOobject;\n"
        '    location "constant/polyMesh";\n    object cellZones;\n}\n\n'
        f"1\n(\n{ROTATING_ZONE}\n{{\n    type cellZone;\n    cellLabels List<label> {n_cells}\n(\n{labels}\n)\n;\n}}\n)\n"
    )


def mesh_cell_count(poly_mesh: Path) -> int:
    """The number of cells, from the note OpenFOAM writes in the header of polyMesh/owner."""
    head = (Path(poly_mesh) / "owner").read_bytes()[:4096].decode("ascii", errors="replace")
    found = re.search(r"nCells:\s*(\d+)", head)
    if not found:
        raise ConfigurationError(f"{poly_mesh}/owner has no nCells note in its header; cannot count its cells")
    return int(found.group(1))


def write_condition_case(
    case: str | Path,
    mesh_case: str | Path,
    condition: Condition,
    settings: CaseSettings,
    warm_start: Path | None = None,
) -> Path:
    """Write the case of ``condition`` in ``case`` on the mesh of ``mesh_case`` (linked, not copied).

    ``warm_start`` is a finished solution's time directory on the same mesh; its fields become the
    initial fields (the boundary conditions are this condition's own).
    """
    case, mesh_case = Path(case), Path(mesh_case).resolve()
    (case / "constant").mkdir(parents=True, exist_ok=True)
    (case / "system").mkdir(parents=True, exist_ok=True)
    frame = frame_setup(condition, settings.length, settings.method)
    _link_mesh(case, mesh_case, whole_domain_zone=frame.whole_domain_rotates)
    _write_control(case, settings)
    write_numerics(case, settings.second_order and settings.second_order_from(warm_start) is None,
                   limiters=settings.limiters_at_start(warm_start), coupling=settings.solver.pressure_velocity_coupling,
                   turbulence_model=settings.solver.turbulence_model,
                   turbulence_convection=settings.solver.turbulence_convection)
    write_decomposition(case, settings.n_procs)
    _write_physics(case, frame, settings)
    n_cells = mesh_cell_count(mesh_case / "constant/polyMesh") if warm_start is not None else None
    _write_fields(case, condition, frame, settings, warm_start, n_cells)
    return case
