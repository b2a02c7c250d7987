"""Inertial-frame check of a finished classic turn: is OpenFOAM's rotating frame (MRF) the steady turn?

Both turn set-ups (the hybrid frames and the classic rotating domain) rest on OpenFOAM's MRF, so their
agreement tests the hybrid frames against the classic one, not MRF itself. This check leaves MRF out. It
takes a finished classic condition, whose velocity is already the inertial one (the absolute velocity, the
fluid at rest far away), and carries it on in the inertial frame with the mesh itself turning about the turn
centre A: pimpleFoam, solid-body mesh motion, the body's walls moving with the mesh, no MRF and no source.
In exact arithmetic the MRF solution is a steady state of those equations (each cell's values turn with
the cell), so the body-axis loads should stay where MRF put them while the body travels; where the two
discretisations disagree, the loads leave the MRF values as the flow around the body and its wake are
renewed by the inertial equations.

With ``--initial STRAIGHT_CONDITION_DIR`` the run starts instead from that straight-ahead solution (the
frame translating with B, so U + V in the inertial frame), and the turn builds up in the inertial frame
alone: a computation of the turn that owes nothing to MRF. Given the condition folder of the straight run
itself, the same transient procedure runs on a still mesh: the control, which should hold its loads.
With ``--initial`` and ``--translate`` the mesh moves in a straight line through fluid at rest (the classic
turn's far field) instead of turning: the straight run again, the control for the moving mesh.

    .venv/bin/python scripts/inertial_turn_check.py CLASSIC_CONDITION_DIR COPY_DIR [--lengths 2]
        [--time-step 0.004] [--ranks 2] [--initial STRAIGHT_CONDITION_DIR [--translate]] [--out JSON]

    .venv/bin/python scripts/inertial_turn_check.py plot PNG JSON [JSON ...]

draws the loads against the travel of one or more such runs, each against its steady solution.

The copy is replaced; the classic condition is left as it is. Loads are read from a forces function object
about A (a fixed point), then turned back into body axes about the moving moment centre B
(hydroderiv.forces.body_axis_loads).
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
from pathlib import Path

import numpy as np
from foamlib import FoamFieldFile, FoamFile

from hydroderiv._io import atomic_write_text
from hydroderiv.case.conditions import Condition
from hydroderiv.case.setup import latest_time_dir
from hydroderiv.errors import HydroderivError
from hydroderiv.experiments import error_percent
from hydroderiv.forces import COEFFICIENT_NAMES, PrimeScales, body_axis_loads, read_history
from hydroderiv.run.condition import read_result
from hydroderiv.run.openfoam import run_application

FORCES = "forces_about_turn_centre"
WHAT = {  # what a run is, by its mesh motion
    "turning": "a turn carried on in the inertial frame with the mesh turning about the turn centre (pimpleFoam, "
               "solid-body motion, no MRF): body-axis loads against the steady (MRF) solution",
    "straight line": "the straight-ahead run carried on with the mesh moving in a straight line through fluid at "
                     "rest: the moving-mesh control",
    "none": "the straight-ahead run carried on by the same transient procedure on a still mesh: the control",
}
RESULT_FIELDS = ("U", "p", "nut", "nuTilda", "k", "omega", "epsilon")


def _finished(case: Path) -> tuple[dict, Path]:
    """The result record of a finished condition and its last saved solution."""
    result = read_result(case)
    latest = latest_time_dir(case) if result is not None else None
    if latest is None:
        raise HydroderivError(f"{case} is not a finished condition (no result.json or no saved solution)")
    return result, latest


def _is_straight_ahead(result: dict) -> bool:
    condition = Condition(**result["condition"])
    return condition == Condition(condition.speed)


def _body_patches(control: FoamFile) -> list[str]:
    return [str(p) for p in control["functions"]["forces_total"]["patches"]]


def _start_from_straight_run(straight: Path, start: Path, body_velocity: np.ndarray) -> None:
    """Replace the cell values in ``start`` by the straight-ahead solution's, turned into the inertial frame."""
    result, latest = _finished(straight)
    if not _is_straight_ahead(result):
        raise HydroderivError(f"{straight} is not the straight-ahead condition: {result['condition']}")
    for path in start.iterdir():
        if not (latest / path.name).is_file():
            raise HydroderivError(f"{straight} has no field {path.name} to start from")
        values = FoamFieldFile(latest / path.name).internal_field
        # the straight run's frame translates with B: the fluid's velocity in the inertial frame is U + V
        FoamFieldFile(path).internal_field = values + body_velocity if path.name == "U" else values


def set_up_inertial_case(source: Path, copy: Path, lengths: float, time_step: float,
                         straight: Path | None = None, translate: bool = False) -> dict:
    """Write the moving-mesh inertial case in ``copy`` from the finished classic condition ``source``
    (its set-up and, unless ``straight`` names a straight-ahead condition to start from, its solution).

    ``translate`` (with ``straight``) moves the mesh in a straight line at the turn's speed instead: the
    straight run carried on with the mesh moving through fluid at rest, the control for the moving mesh."""
    result, latest = _finished(source)
    if Condition(**result["condition"]).is_turning:
        mrf = FoamFile(source / "constant/MRFProperties")
        zone = next(iter(mrf.keys()))
        if not mrf[zone].get("nonRotatingPatches"):
            raise HydroderivError(f"{source} is not a classic turn (its MRF zone does not exclude the far field)")
        zone_name = str(mrf[zone]["cellZone"])
        origin = np.asarray(mrf[zone]["origin"], float)
        axis = np.asarray(mrf[zone]["axis"], float)
        omega = float(mrf[zone]["omega"])
    elif _is_straight_ahead(result):
        # straight ahead, the control: the same transient procedure on a still mesh should hold its loads
        zone_name, origin, axis, omega = None, np.zeros(3), np.array([0.0, 0.0, 1.0]), 0.0
    else:
        raise HydroderivError(f"{source} is neither a turn nor straight ahead: {result['condition']}")
    speed = float(result["condition"]["speed"])
    length = float(result["reference"]["length"])

    shutil.rmtree(copy, ignore_errors=True)
    copy.mkdir(parents=True)
    shutil.copytree(source / "system", copy / "system")
    # the frame is inertial (a classic turn has no source); the mesh stays a link: moved points go to the
    # time folders
    shutil.copytree(source / "constant", copy / "constant", symlinks=True,
                    ignore=shutil.ignore_patterns("MRFProperties", "fvOptions"))
    # time 0, not the iteration count: rotatingMotion turns the mesh by omega * t from its stored points
    start = copy / "0"
    start.mkdir()
    for name in RESULT_FIELDS:
        if (latest / name).is_file():
            shutil.copy2(latest / name, start / name)

    body_velocity = np.cross(axis * omega, -origin)  # V = Omega x (B - A)
    if straight is not None and omega:
        _start_from_straight_run(straight, start, body_velocity)
    if translate:
        if straight is None or not omega:
            raise HydroderivError("--translate needs a classic turn (for its far field at rest) and --initial")
        motion = f"linearMotion;\nvelocity ({' '.join(f'{v:.12g}' for v in body_velocity)});\n"
        origin, omega = np.zeros(3), 0.0  # loads about B's start, turned by nothing
    else:
        motion = (f"rotatingMotion;\norigin ({' '.join(f'{v:.10g}' for v in origin)});\n"
                  f"axis ({' '.join(f'{v:.10g}' for v in axis)});\nomega {omega:.12g};\n")
    control = FoamFile(copy / "system/controlDict")
    patches = _body_patches(control)
    rho = float(control["functions"]["forces_total"]["rhoInf"])
    velocity = FoamFile(start / "U")
    for patch in patches:  # the walls move with the mesh: their velocity is the mesh's, Omega x (x - A)
        velocity["boundaryField"][patch] = {"type": "movingWallVelocity", "value": np.zeros(3)}

    end_time = lengths * length / speed
    steps = int(round(end_time / time_step))
    if zone_name is not None:
        (copy / "constant/dynamicMeshDict").write_text(
            "FoamFile { version 2.0; format ascii; class dictionary; object dynamicMeshDict; }\n"
            "dynamicFvMesh dynamicMotionSolverFvMesh;\nmotionSolver solidBody;\n"
            f"cellZone {zone_name};\nsolidBodyMotionFunction {motion}"
        )
    control["application"] = "pimpleFoam"
    control["startFrom"] = "startTime"
    control["startTime"] = 0
    control["endTime"] = steps * time_step
    control["deltaT"] = time_step
    control["writeControl"] = "timeStep"
    control["writeInterval"] = steps
    control["purgeWrite"] = 0
    control["runTimeModifiable"] = False
    control["functions"] = {
        FORCES: {"type": "forces", "libs": ["libforces.so"], "writeControl": "timeStep", "writeInterval": 1,
                 "rho": "rhoInf", "rhoInf": rho, "CofR": origin, "log": False, "patches": patches}
    }
    # The space discretisation stays the steady run's, so that only the treatment of the frame differs. Its
    # 'bounded' convection adds the continuity error times the field, next to nothing once each step's
    # pressure is solved (local continuity errors of about 1e-10 here).
    FoamFile(copy / "system/fvSchemes")["ddtSchemes"] = {"default": "Euler"}
    solution = FoamFile(copy / "system/fvSolution")
    solvers = dict(solution["solvers"])
    # each step is a small change of a flow that should stay steady: a loose final tolerance suffices
    solvers["pFinal"] = {**dict(solvers["p"]), "tolerance": 1e-6, "relTol": 0.01}
    solvers['"(U|k|omega|epsilon|nuTilda)Final"'] = {**dict(solvers['"(U|k|omega|epsilon|nuTilda)"']), "relTol": 0}
    solution["solvers"] = solvers
    solution["PIMPLE"] = {"nOuterCorrectors": 2, "nCorrectors": 2, "nNonOrthogonalCorrectors": 0,
                          "momentumPredictor": True, "correctPhi": False, "moveMeshOuterCorrectors": False}
    solution["relaxationFactors"] = {"fields": {"p": 0.3, "pFinal": 1},
                                     "equations": {'"(U|nuTilda|k|omega|epsilon)"': 0.7, '".*Final"': 1}}
    del solution["SIMPLE"]
    return {"origin": origin, "axis": axis, "omega": omega, "speed": speed, "length": length, "rho": rho,
            "translation": body_velocity if translate else np.zeros(3),
            "end_time": steps * time_step, "time_step": time_step, "steps": steps, "result": result}


def body_axis_coefficients(post: Path, setup: dict) -> dict[str, np.ndarray]:
    """X', Y', Z', K', M', N' per time step in body axes about B, from the loads about the fixed point A."""
    force, moment = (read_history(post, FORCES, quantity) for quantity in ("force", "moment"))
    body_force, body_moment = body_axis_loads(force.iterations, force.total, moment.total,
                                              turn_centre=setup["origin"], axis=setup["axis"], omega=setup["omega"],
                                              velocity=setup["translation"])
    coefficients = PrimeScales(setup["rho"], setup["speed"], setup["length"]).coefficients(body_force, body_moment)
    return {"time": force.iterations, **{name: coefficients[:, k] for k, name in enumerate(COEFFICIENT_NAMES)}}


def plot_histories(png: Path, results: list[Path]) -> None:
    """X', Y' and N' against the body lengths travelled, per run, with the steady solution's as a dashed line."""
    from hydroderiv.report._figures import pyplot, save_figure

    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    shown = {name: [] for name in "XYN"}  # the values past the first steps' start-up spike set the scales
    for path in results:
        record = json.loads(path.read_text())
        history = record["history"]
        label = f"{path.stem} ({record['time_step_s'] * 1000:g} ms)"
        for ax, name in zip(axes, "XYN"):
            line, = ax.plot(history["travel_lengths"], history[name], label=label)
            ax.axhline(record["summary"][name]["steady"], color=line.get_color(), linestyle="--", linewidth=0.8)
            shown[name] += [v for t, v in zip(history["travel_lengths"], history[name]) if t >= 0.1]
            shown[name].append(record["summary"][name]["steady"])
    for ax, name in zip(axes, "XYN"):
        low, high = min(shown[name]), max(shown[name])
        ax.set_ylim(low - 0.1 * (high - low), high + 0.1 * (high - low))
        ax.set_xlabel("body lengths travelled")
        ax.set_ylabel(f"{name}' (body axes, about B)")
        ax.grid(alpha=0.3)
    axes[2].legend(fontsize=7)
    fig.suptitle("turn computed in the inertial frame (mesh turning), against the steady solution (dashed)")
    save_figure(fig, png)


def main() -> None:
    if sys.argv[1:2] == ["plot"]:
        if len(sys.argv) < 4:
            raise SystemExit("usage: inertial_turn_check.py plot PNG JSON [JSON ...]")
        plot_histories(Path(sys.argv[2]), [Path(p) for p in sys.argv[3:]])
        return
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("condition", type=Path, help="a finished classic turn (its condition folder)")
    parser.add_argument("copy", type=Path, help="where the inertial case runs (replaced)")
    parser.add_argument("--lengths", type=float, default=2.0, help="body lengths of travel (default 2)")
    parser.add_argument("--time-step", type=float, default=0.004,
                        help="seconds (default 0.004: a Courant number of about 5 in the finest cells)")
    parser.add_argument("--ranks", type=int, default=2)
    parser.add_argument("--initial", type=Path, help="start from this straight-ahead condition instead")
    parser.add_argument("--translate", action="store_true",
                        help="with --initial: move the mesh in a straight line instead (the moving-mesh control)")
    parser.add_argument("--out", type=Path, help="JSON of the comparison")
    args = parser.parse_args()

    setup = set_up_inertial_case(args.condition, args.copy, args.lengths, args.time_step, args.initial, args.translate)
    if args.ranks > 1:
        run_application(args.copy, ["decomposePar"])
    run_application(args.copy, ["pimpleFoam"], n_procs=args.ranks)
    history = body_axis_coefficients(args.copy / "postProcessing", setup)
    travel = history["time"] * setup["speed"] / setup["length"]  # body lengths travelled
    # the steady solution: MRF's for a turn, the straight run's when the mesh only translates
    reference = _finished(args.initial)[0] if args.translate else setup["result"]
    steady = reference["coefficients"]
    last = travel >= travel[-1] - 0.25  # the last quarter of a body length
    print(f"{'travel (L)':>10} " + " ".join(f"{name + chr(39):>11}" for name in "XYN"))
    print(f"{'steady':>10} " + " ".join(f"{steady[name]:+11.4e}" for name in "XYN"))
    for k in [*range(0, len(travel), max(1, len(travel) // 16)), len(travel) - 1]:
        print(f"{travel[k]:10.3f} " + " ".join(f"{history[name][k]:+11.4e}" for name in "XYN"))
    summary = {}
    for name in "XYN":
        settled = float(np.mean(history[name][last]))
        summary[name] = {"steady": steady[name], "transient_last_quarter_length": settled,
                         "difference_percent": error_percent(settled, steady[name])}  # against MRF's steady value
    for name, row in summary.items():
        print(f"{name}': steady {row['steady']:+.5e}, inertial (last 0.25 L of travel) "
              f"{row['transient_last_quarter_length']:+.5e}, {row['difference_percent']:+.2f} %")
    if args.out:
        motion = "straight line" if args.translate else ("turning" if setup["omega"] else "none")
        samples = np.unique(np.linspace(0, len(travel) - 1, 41).astype(int))
        atomic_write_text(args.out, json.dumps({
            "what": WHAT[motion],
            "command": " ".join([".venv/bin/python", "scripts/inertial_turn_check.py", *sys.argv[1:]]),
            "condition": reference["condition"], "classic_case": str(args.condition),
            "started_from": str(args.initial) if args.initial else "the classic (MRF) solution",
            "mesh_motion": motion,
            "turbulence_model": setup["result"]["turbulence_model"],
            "time_step_s": setup["time_step"], "steps": setup["steps"], "travel_lengths": float(travel[-1]),
            "summary": summary,
            "history": {"travel_lengths": travel[samples].tolist(),
                        **{name: history[name][samples].tolist() for name in "XYZKMN"}},
        }, indent=1) + "\n")


if __name__ == "__main__":
    main()
