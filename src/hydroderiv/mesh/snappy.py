"""Building the single mesh with blockMesh + snappyHexMesh, then the checkMesh quality gate.

The mesh case holds ``constant/polyMesh`` with the cellZone/faceZone ``rotatingZone`` (the snapped sphere),
one wall patch per body component (all in the patch group ``bodyWalls``) and one far-field patch
``farfield`` covering the six cube faces, so any inflow direction needs no re-meshing.
"""

from __future__ import annotations

import json
import math
import shutil
import time
from dataclasses import asdict
from pathlib import Path
from typing import Callable, Mapping

from .._foam import quoted, write_decomposition, write_foam_dict
from .._io import atomic_write_text
from ..errors import ConfigurationError
from ..geometry import Body
from ..run.openfoam import run_application
from .design import BEFORE_THE_FIELD, GRID_SHIFT, REFINEMENT_RATIO, MeshDesign, is_thin_part, mesh_options
from .interface import project_interface_onto_sphere, sphere_interface_spread
from .quality import MeshQualityError, layer_coverage, layers_along_x, parse_check_mesh

FARFIELD = "farfield"
ROTATING_ZONE = "rotatingZone"
WALL_GROUP = "bodyWalls"
SURFACE = "body"  # the body's STL in constant/triSurface is body.stl; its solids are the components
REPORT_FILE = "mesh.json"


def _vec(values) -> list[float]:
    return [round(float(v), 10) for v in values]


def _write_block_mesh(case: Path, d: MeshDesign) -> None:
    h, n = d.half_width, d.base_cells
    shift = (GRID_SHIFT[0], d.grid_shift_y, GRID_SHIFT[2])
    sx, sy, sz = (f * d.base_cell for f in shift)
    corners = [[-h, -h, -h], [h, -h, -h], [h, h, -h], [-h, h, -h], [-h, -h, h], [h, -h, h], [h, h, h], [-h, h, h]]
    vertices = [_vec([x + sx, y + sy, z + sz]) for x, y, z in corners]
    faces = [[0, 4, 7, 3], [1, 2, 6, 5], [0, 1, 5, 4], [3, 7, 6, 2], [0, 3, 2, 1], [4, 5, 6, 7]]
    write_foam_dict(
        case / "system/blockMeshDict",
        {
            "scale": 1,
            "vertices": vertices,
            # foamlib has no literal for 'hex (...) (...) simpleGrading (...)'; OpenFOAM reads this token list
            "blocks": ["hex", list(range(8)), [n, n, n], "simpleGrading", [1, 1, 1]],
            "edges": [],
            "boundary": [FARFIELD, {"type": "patch", "faces": faces}],
            "mergePatchPairs": [],
        },
    )


def _refinement_boxes(d: MeshDesign) -> dict[str, dict]:
    """Shapes for refinement regions: around the body, and widening cones for the wake."""
    L, R = d.length, d.body_radius
    tail = d.body_x_min
    return {
        "bodyBox": {
            "type": "searchableBox",
            "min": _vec([d.body_x_min - 0.25 * L, -(R + 0.15 * L), -(R + 0.15 * L)]),
            "max": _vec([d.body_x_max + 0.12 * L, R + 0.15 * L, R + 0.15 * L]),
        },
        # near wake: 1 L aft of the tail, opening at 25 deg (drift/pitch to 20 deg plus the turning wake)
        "wakeNear": {
            "type": "searchableCone",
            "point1": _vec([tail + 0.1 * L, 0, 0]),
            "radius1": R + 0.05 * L,
            "innerRadius1": 0,
            "point2": _vec([tail - 1.0 * L, 0, 0]),
            "radius2": R + 0.05 * L + 1.0 * L * math.tan(math.radians(25)),
            "innerRadius2": 0,
        },
        # far wake, up to the sphere, opening at 30 deg
        "wakeFar": {
            "type": "searchableCone",
            "point1": _vec([tail + 0.1 * L, 0, 0]),
            "radius1": R + 0.1 * L,
            "innerRadius1": 0,
            "point2": _vec([-0.97 * d.sphere_radius, 0, 0]),
            "radius2": R + 0.1 * L + (0.97 * d.sphere_radius + tail) * math.tan(math.radians(30)),
            "innerRadius2": 0,
        },
    }


def _stern_region(d: MeshDesign) -> dict[str, dict]:
    """The cylinder of MeshDesign.stern_extra_level about the aft part of the body (none at level 0)."""
    if d.stern_extra_level <= 0:
        return {}
    L = d.length
    return {
        "sternRegion": {
            "type": "searchableCylinder",
            "point1": _vec([d.body_x_min - 0.02 * L, 0, 0]),
            "point2": _vec([d.body_x_min + d.stern_region_length_L * L, 0, 0]),
            "radius": d.stern_region_radius_L * L,
        }
    }


def layer_min_determinant(d: MeshDesign) -> float:
    """snappy's minDeterminant, low enough to admit the design's first prism layer.

    The determinant of a flat a x a x t cell is about 27 (t/a)^2 on snappy's scale (1 for a cube), so the
    usual 0.001 rejects any layer thinner than a sixth of its surface cell: a first layer sized for y+ = 1
    (17 um under 31 mm on the coarse AFF-8 mesh) was refused on 145,099 faces and only 42 % of the faces
    kept any layer. A tenth of the first layer's determinant leaves room for the cells' own distortion;
    the wall-function designs keep 0.001.
    """
    aspect = d.layers().first_thickness / d.hull_cell
    return min(0.001, 0.1 * 27.0 * aspect**2)


def _mesh_quality_controls(d: MeshDesign) -> dict:
    # minTetQuality must stay positive: with -1e30 snappy keeps every layer but leaves negative
    # decomposition tets that make simpleFoam diverge within ~20 iterations.
    base = {
        "maxNonOrtho": 65,
        "maxBoundarySkewness": 20,
        "maxInternalSkewness": 4,
        "maxConcave": 80,
        "minVol": 1e-13,
        "minTetQuality": 1e-15,
        "minArea": -1,
        "minTwist": 0.02,
        "minDeterminant": float(f"{layer_min_determinant(d):.3g}"),
        "minFaceWeight": 0.05,
        "minVolRatio": 0.01,
        "minTriangleTwist": -1,
        "nSmoothScale": 4,
        "errorReduction": 0.75,
    }
    return {**base, "relaxed": {"maxNonOrtho": 75}}


def _layer_thicknesses(d: MeshDesign, components: tuple[str, ...]) -> dict:
    """The layer sizes of addLayersControls: absolute (sized for y+), or relative to the local surface cell
    (MeshDesign.relative_layer_sizes), scaled per part so that each part's nominal cells get the absolute
    design."""
    relative = d.relative_layer_sizes

    def size(thickness: float, component: str) -> float:
        return round(thickness / d.surface_cell_of(component) if relative else thickness, 7)

    layers = {}
    for c in components:
        stack = d.layers_of(c)
        layers[c] = {"nSurfaceLayers": stack.count, "minThickness": size(d.min_layer_thickness(c), c)}
        if relative:  # a thin part's cells are finer than the hull's, so its relative first layer is thicker
            layers[c].update(firstLayerThickness=size(stack.first_thickness, c), expansionRatio=stack.expansion)
    hull = d.layers()
    return {
        "relativeSizes": relative,
        "firstLayerThickness": size(hull.first_thickness, "hull"),
        "expansionRatio": hull.expansion,
        "minThickness": size(d.min_layer_thickness("hull"), "hull"),
        "layers": layers,
    }


def _write_snappy(case: Path, d: MeshDesign, components: tuple[str, ...]) -> None:
    boxes = _refinement_boxes(d)
    hull_level = d.hull_surface_level
    fine_level = hull_level + d.appendage_extra_level
    region_levels = {c: d.surface_level_of(c) for c in components}
    location = _vec(d.location_in_mesh())
    with_body = bool(components)
    stern = _stern_region(d) if with_body else {}
    regions = {
        c: {"level": [lv, lv + (d.thin_curvature_levels if is_thin_part(c) else 0)],
            "patchInfo": {"type": "wall", "inGroups": [WALL_GROUP]}}
        for c, lv in region_levels.items()
    }
    geometry = {
        f"{SURFACE}.stl": {"type": "triSurfaceMesh", "name": SURFACE, "regions": {c: {"name": c} for c in components}},
        ROTATING_ZONE: {"type": "searchableSphere", "centre": [0, 0, 0], "radius": d.sphere_radius},
        **boxes,
        **stern,
    }
    castellated = {
        "maxLocalCells": 5_000_000,
        "maxGlobalCells": 50_000_000,
        "minRefinementCells": 10,
        "maxLoadUnbalance": 0.10,
        "nCellsBetweenLevels": 3,
        "features": [{"file": quoted(f"{SURFACE}.eMesh"), "level": fine_level}] if with_body else [],
        "refinementSurfaces": {
            **({SURFACE: {"level": [hull_level, hull_level], "regions": regions}} if with_body else {}),
            # the snapped sphere: faceZone + cellZone of the rotating frame
            ROTATING_ZONE: {
                "level": [d.sphere_surface_level, d.sphere_surface_level],
                "faceZone": ROTATING_ZONE,
                "cellZone": ROTATING_ZONE,
                "cellZoneInside": "inside",
            },
        },
        "resolveFeatureAngle": 30,
        "refinementRegions": {
            ROTATING_ZONE: {"mode": "inside", "levels": [[1e15, d.sphere_inside_level]]},
            "wakeFar": {"mode": "inside", "levels": [[1e15, 2]]},
            "wakeNear": {"mode": "inside", "levels": [[1e15, 3]]},
            "bodyBox": {"mode": "inside", "levels": [[1e15, 3]]},
            **({SURFACE: {"mode": "distance", "levels": [[0.03 * d.length, 4]]}} if with_body else {}),
            **{name: {"mode": "inside", "levels": [[1e15, hull_level + d.stern_extra_level]]} for name in stern},
        },
        "locationInMesh": location,
        "allowFreeStandingZoneFaces": True,
    }
    write_foam_dict(
        case / "system/snappyHexMeshDict",
        {
            "castellatedMesh": True,
            "snap": True,
            "addLayers": with_body,
            "geometry": geometry if with_body else {k: v for k, v in geometry.items() if k != f"{SURFACE}.stl"},
            "castellatedMeshControls": castellated,
            "snapControls": {
                "nSmoothPatch": 5,
                "tolerance": 2.0,
                "nSolveIter": 100,
                "nRelaxIter": 8,
                "nFeatureSnapIter": 10,
                "implicitFeatureSnap": False,
                "explicitFeatureSnap": True,
                "multiRegionFeatureSnap": False,
            },
            "addLayersControls": {
                **_layer_thicknesses(d, components),
                "nGrow": 0,
                "featureAngle": 180,
                "slipFeatureAngle": 30,
                "nRelaxIter": 5,
                "nSmoothSurfaceNormals": 1,
                "nSmoothNormals": 3,
                "nSmoothThickness": 10,
                "maxFaceThicknessRatio": 0.5,
                "maxThicknessToMedialRatio": 0.5,
                "minMedialAxisAngle": 90,
                "nBufferCellsNoExtrude": 0,
                "nLayerIter": 50,
                "nRelaxedIter": 10,
            },
            "meshQualityControls": _mesh_quality_controls(d),
            "writeFlags": ["scalarLevels", "layerSets", "layerFields"],
            "mergeTolerance": 1e-6,
        },
    )
    # A castellation-only first pass that refines boxes around the body. v1912 refines at surfaces
    # before refinement regions, and a slender hull inside ~1 m base cells cuts no base-mesh edge, so
    # without this pass the surface refinement never sees it.
    R, L = d.body_radius, d.length
    tight = {
        "type": "searchableBox",
        "min": _vec([d.body_x_min - 0.05 * L, -(R + 0.05 * L), -(R + 0.05 * L)]),
        "max": _vec([d.body_x_max + 0.05 * L, R + 0.05 * L, R + 0.05 * L]),
    }
    write_foam_dict(
        case / "system/snappyHexMeshDict.pre",
        {
            "castellatedMesh": True,
            "snap": False,
            "addLayers": False,
            "geometry": {"bodyBox": boxes["bodyBox"], "bodyTight": tight},
            "castellatedMeshControls": {
                **{k: castellated[k] for k in ("maxLocalCells", "maxGlobalCells", "maxLoadUnbalance", "nCellsBetweenLevels")},
                "minRefinementCells": 0,
                "features": [],
                "refinementSurfaces": {},
                "resolveFeatureAngle": 30,
                "refinementRegions": {
                    "bodyBox": {"mode": "inside", "levels": [[1e15, 2]]},
                    "bodyTight": {"mode": "inside", "levels": [[1e15, 3]]},
                },
                "locationInMesh": location,
                "allowFreeStandingZoneFaces": True,
            },
            "snapControls": {"nSmoothPatch": 3, "tolerance": 2.0, "nSolveIter": 30, "nRelaxIter": 5},
            "addLayersControls": {"layers": {}, "relativeSizes": True, "expansionRatio": 1, "finalLayerThickness": 0.3,
                                  "minThickness": 0.1, "nGrow": 0, "featureAngle": 60, "nRelaxIter": 3,
                                  "nSmoothSurfaceNormals": 1, "nSmoothNormals": 3, "nSmoothThickness": 10,
                                  "maxFaceThicknessRatio": 0.5, "maxThicknessToMedialRatio": 0.3,
                                  "minMedialAxisAngle": 90, "nBufferCellsNoExtrude": 0, "nLayerIter": 50},
            "meshQualityControls": _mesh_quality_controls(d),
            "mergeTolerance": 1e-6,
        },
    )
    write_foam_dict(
        case / "system/surfaceFeatureExtractDict",
        {
            f"{SURFACE}.stl": {
                "extractionMethod": "extractFromSurface",
                "includedAngle": 150,
                "subsetFeatures": {"nonManifoldEdges": False, "openEdges": True},
                "writeObj": False,
            }
        },
    )


def _write_meshing_controls(case: Path) -> None:
    """controlDict, and fvSchemes/fvSolution, which snappyHexMesh reads too."""
    from ..case.numerics import write_numerics

    write_foam_dict(case / "system/controlDict", {"application": "snappyHexMesh", "startFrom": "latestTime",
                                                  "startTime": 0, "stopAt": "endTime", "endTime": 0, "deltaT": 1,
                                                  "writeControl": "timeStep", "writeInterval": 1,
                                                  # ASCII (the interface check reads the points) with enough
                                                  # digits for sub-millimetre prism layers in a 35 m domain, and
                                                  # for reconstructParMesh's merge tolerance
                                                  "writeFormat": "ascii", "writePrecision": 12})
    write_numerics(case)


def write_mesh_case(case: Path, body: Body, design: MeshDesign, n_procs: int = 1) -> None:
    """Write every dictionary meshing needs, and the body surface, into ``case``."""

    case.mkdir(parents=True, exist_ok=True)
    tri = case / "constant/triSurface"
    tri.mkdir(parents=True, exist_ok=True)
    body.write(tri)
    (tri / "body.json").rename(case / "body.json")
    _write_meshing_controls(case)
    _write_block_mesh(case, design)
    _write_snappy(case, design, body.component_names)
    if n_procs > 1:
        write_decomposition(case, n_procs)


def _snappy_steps(n_procs: int) -> list[tuple[str, list[str], int]]:
    """snappyHexMesh itself, on one core or on ``n_procs`` MPI ranks.

    In parallel the castellated mesh is decomposed (hierarchical: scotch and metis may be stubs), snapped
    with layers on every rank, then merged back into ``constant/polyMesh`` with its zones; snappy's
    layer-count field, which the layer coverage is read from, is merged back too.
    """
    if n_procs <= 1:
        return [("snappyHexMesh", ["snappyHexMesh", "-overwrite"], 1)]
    return [
        ("decomposePar", ["decomposePar", "-force"], 1),
        ("snappyHexMesh", ["snappyHexMesh", "-overwrite"], n_procs),
        ("reconstructParMesh", ["reconstructParMesh", "-constant"], 1),
        ("reconstructPar", ["reconstructPar", "-withZero", "-fields", "(nSurfaceLayers)"], 1),
    ]


def _run_steps(case: Path, steps: list[tuple[str, list[str], int]], log: Callable[[str], None]) -> dict[str, float]:
    """Run the meshing utilities in order; returns the wall time of each step.

    Step timings are kept on disk, so a mesh checked again after an interruption still reports its cost.
    """
    timings_path = case / "timings.json"
    timings = json.loads(timings_path.read_text()) if timings_path.is_file() else {}
    for name, command, n_procs in steps:
        log(f"  {name} ..." + (f" ({n_procs} ranks)" if n_procs > 1 else ""))
        t0 = time.monotonic()
        run_application(case, command, log_name=name, n_procs=n_procs)
        timings[name] = round(time.monotonic() - t0, 1)
        atomic_write_text(timings_path, json.dumps(timings))
    return timings


def _place_interface(case: Path, design: MeshDesign, log: Callable[[str], None]) -> None:
    """Put the snapped interface of the rotating sphere exactly onto the sphere, if the design asks for it.

    Before checkMesh, so that the quality gate judges the mesh the solver gets; moving points already on
    the sphere changes nothing, so a mesh checked again after an interruption may pass through here twice.
    """
    if design.interface_on_sphere:
        moved = project_interface_onto_sphere(case, design.sphere_radius, ROTATING_ZONE)
        log(f"  interface of the rotating sphere: {moved['points']} points put on the sphere "
            f"(moved by at most {moved['largest_move_pct_of_radius']} % of its radius)")


def _sphere_report(case: Path, design: MeshDesign) -> dict:
    return {"radius_m": design.sphere_radius, "interface_on_sphere": design.interface_on_sphere,
            **sphere_interface_spread(case, design.sphere_radius, ROTATING_ZONE)}


def _quality_gate(case: Path, log: Callable[[str], None]) -> dict:
    """The checkMesh verdict on ``case``: hard failures raise :class:`MeshQualityError`, soft ones are logged."""
    check = parse_check_mesh((case / "log.checkMesh").read_text())
    if not check["ok"]:
        raise MeshQualityError(
            f"checkMesh failed on {case}: {'; '.join(check['problems']) or 'no cells'}; log: {case / 'log.checkMesh'}"
        )
    for warning in check["warnings"]:
        log(f"  checkMesh warning (accepted): {warning}")
    return check


def _check_same_design(case: Path, built: dict, wanted: dict) -> None:
    """A finished mesh is reused only if it was built to the design asked for now.

    Otherwise results would silently come from another mesh, for example after a default changed. A field
    the stored report lacks (a mesh from before it existed) is compared with the value meshes had then
    (design.BEFORE_THE_FIELD), or not at all when that value is not known.
    """
    built = {**BEFORE_THE_FIELD, **built}
    differ = [f"{name} {built[name]!r} (asked {value!r})" for name, value in wanted.items()
              if name in built and not _same(built[name], value)]
    if differ:
        raise ConfigurationError(
            f"the mesh in {case} was built to another design: {', '.join(differ)}. Remove it to mesh again, use "
            "another work directory, or ask for the design it has (a study's [mesh] table, --mesh KEY=VALUE)")


def _same(a, b) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-12)
    return a == b


def reuse_finished_mesh(case: Path, wanted: dict, log: Callable[[str], None]) -> dict | None:
    """The report of the finished mesh in ``case`` if it was built to the design ``wanted``, else None.

    Raises :class:`ConfigurationError` when it was built to another design (see _check_same_design).
    Shared by every mesher: a mesh is done when its report is written, its last step.
    """
    report_path = case / REPORT_FILE
    if not report_path.is_file():
        return None
    report = json.loads(report_path.read_text())
    _check_same_design(case, report.get("design", {}), wanted)
    log(f"mesh {case} exists ({report['cells']} cells); reusing it")
    return report


def build_snappy_mesh(
    body: Body,
    level: str,
    case: str | Path,
    design_speed: float = 3.344,
    log: Callable[[str], None] = print,
    options: Mapping[str, object] | None = None,
    n_procs: int = 1,
) -> dict:
    """Mesh ``body`` at ``level`` into ``case`` (reusing a finished mesh there) and return its report.

    snappyHexMesh runs on ``n_procs`` MPI ranks (the other steps are quick and serial).

    ``options`` set MeshDesign fields (see :func:`~hydroderiv.mesh.design.mesh_options`). Raises
    :class:`MeshQualityError` when checkMesh fails; the report names the failed checks. Raises
    :class:`ConfigurationError` when the mesh found in ``case`` was built to a different design.
    """
    case = Path(case)
    report_path = case / REPORT_FILE
    lo, hi = body.surface.bounds
    radius = float(max(abs(lo[1]), abs(hi[1]), abs(lo[2]), abs(hi[2])))
    design = MeshDesign(level, body.reference.length, radius, float(lo[0]), float(hi[0]), design_speed=design_speed,
                        **mesh_options(options or {}))
    finished = reuse_finished_mesh(case, asdict(design), log)
    if finished is not None:
        return finished
    snappy = _snappy_steps(n_procs)
    snapped = case / f"log.{snappy[-1][0]}"  # the last step that builds the mesh
    check = [("checkMesh", ["checkMesh", "-constant"], 1)]
    if snapped.is_file() and snapped.read_text().rstrip().endswith("End"):
        # snappyHexMesh finished before an interruption (or a failed gate): check it again, don't re-mesh
        log(f"mesh {case} was snapped before; checking it again")
        steps = check
    else:
        if case.exists():
            shutil.rmtree(case)  # an unfinished mesh from an interrupted run
        write_mesh_case(case, body, design, n_procs)
        steps = [
            ("blockMesh", ["blockMesh"], 1),
            ("surfaceFeatureExtract", ["surfaceFeatureExtract"], 1),
            ("snappyHexMesh.pre", ["snappyHexMesh", "-overwrite", "-dict", "system/snappyHexMeshDict.pre"], 1),
            *snappy,
        ]
    _run_steps(case, steps, log)
    for processor in case.glob("processor*"):
        shutil.rmtree(processor)  # merged back into constant/polyMesh
    _place_interface(case, design, log)
    timings = _run_steps(case, check, log)
    check = _quality_gate(case, log)
    layers = design.layers()
    report = {
        "level": level,
        "cells": check["cells"],
        "checkMesh": check,
        "meshing_seconds": round(sum(timings.values()), 1),
        "timings": timings,
        "base_cell_m": design.base_cell,
        "hull_surface_cell_m": design.hull_cell,
        "refinement_ratio": REFINEMENT_RATIO,
        "layers": {**asdict(layers), "total_thickness": layers.total_thickness},
        "layer_coverage": layer_coverage(case, {c: design.layers_of(c).count for c in body.component_names}),
        "layers_along_x": {c: layers_along_x(case, c) for c in body.component_names if not is_thin_part(c)},
        "design_yplus": {
            "speed_m_s": design_speed,
            "first_cell_centre": round(layers.yplus_target, 1),
        },
        "rotating_sphere": _sphere_report(case, design),
        "components": list(body.component_names),
        "design": asdict(design),
    }
    for tmp in ("0",):  # snappy's layer fields (read above) are not initial conditions
        shutil.rmtree(case / tmp, ignore_errors=True)
    atomic_write_text(report_path, json.dumps(report, indent=2) + "\n")
    return report


def build_empty_domain(case: str | Path, design: MeshDesign, log: Callable[[str], None] = print) -> dict:
    """The same domain, rotating sphere and refinement regions, but no body: for verifying the frames.

    With no body, uniform flow must stay uniform in every condition of the hybrid frames.
    """
    case = Path(case)
    if (case / REPORT_FILE).is_file():
        return json.loads((case / REPORT_FILE).read_text())
    if case.exists():
        shutil.rmtree(case)
    _write_meshing_controls(case)
    _write_block_mesh(case, design)
    _write_snappy(case, design, ())
    _run_steps(case, [("blockMesh", ["blockMesh"], 1), ("snappyHexMesh", ["snappyHexMesh", "-overwrite"], 1)], log)
    _place_interface(case, design, log)
    _run_steps(case, [("checkMesh", ["checkMesh", "-constant"], 1)], log)
    check = _quality_gate(case, log)
    report = {"cells": check["cells"], "checkMesh": check, "rotating_sphere": _sphere_report(case, design)}
    atomic_write_text(case / REPORT_FILE, json.dumps(report, indent=2) + "\n")
    return report
