"""Command line: ``hydroderiv <step> ...``, one subcommand per pipeline step."""

from __future__ import annotations

import argparse
import json
import math
import signal
import sys
from pathlib import Path
from typing import Callable

from rich.console import Console
from rich.table import Table

from ._io import atomic_write_text
from .case.fluid import DEFAULT_TURBULENCE_MODEL, TURBULENCE_MODELS, check_turbulence_model
from .errors import ConfigurationError, HydroderivError
from .experiments import RESISTANCE
from .geometry import CONFIGURATIONS, Body, load_user_body, suboff_body
from .geometry.suboff import CONFIGURATION_TITLES
from .mesh import LEVELS, build_mesh
from .mesh.design import mesh_options
from .run.monitor import ConvergenceCriterion

# Redirected to a log file, rich would wrap at 80 columns: progress lines and tables would break in the
# middle. A terminal keeps its own width.
console = Console(width=None if sys.stdout.isatty() else 200)


def _print_body(body: Body, written: tuple[Path, ...] = ()) -> None:
    table = Table(title=body.name, show_header=False)
    table.add_column("quantity", style="bold")
    table.add_column("value")
    for quantity, value in body.summary():
        table.add_row(quantity, value)
    for name, area in body.component_areas().items():
        table.add_row(f"  wetted area, {name}", f"{area:.4f} m^2")
    for path in written:
        table.add_row("written", str(path))
    console.print(table)


def _geometry(args: argparse.Namespace) -> int:
    if args.stl:
        if args.length is None or args.moment_centre is None:
            raise HydroderivError("--stl needs --length (reference length, m) and --moment-centre X Y Z (m, file coordinates)")
        bodies = [load_user_body(args.stl, args.length, tuple(args.moment_centre), name=args.name)]
        outs = [Path(args.out)]
    else:
        configs = list(CONFIGURATIONS) if args.config.lower() == "all" else [args.config]
        bodies = [suboff_body(c, resolution=args.resolution) for c in configs]
        many = len(bodies) > 1
        outs = [Path(args.out) / c.upper() if many else Path(args.out) for c in configs]
    for body, out in zip(bodies, outs):
        written = body.write(out)
        _print_body(body, written)
    return 0


def _progress_printer(label: Callable[[object], str], every: int = 25):
    """A progress callback printing iteration, residuals, forces and their convergence every few iterations."""
    last: dict = {}  # per condition: each run counts its iterations from its own start

    def show(key, p) -> None:
        if p.coefficients is None or p.iteration - last.get(key, -every) < every:
            return
        last[key] = p.iteration
        residuals = " ".join(f"{k} {v:.1e}" for k, v in p.residuals.items())
        x, y, z, k, m, n = p.coefficients
        drift = "-" if p.drift is None else f"{p.drift.max():.2f}"
        if p.drift is not None and p.drift.max() <= 1.0:
            drift += " (flat: checking an earlier window agrees)"  # see ConvergenceCriterion
        console.print(
            f"  {label(key)} it {p.iteration:5d} | {residuals} | X' {x:+.3e} Y' {y:+.2e} Z' {z:+.2e} "
            f"M' {m:+.2e} N' {n:+.2e} | drift/tol {drift} | {p.elapsed:.0f} s",
            highlight=False,
        )

    return show


def _mesh_options(args: argparse.Namespace) -> dict[str, int | float]:
    """The --mesh KEY=VALUE options, checked (an unknown key or a bad value is named)."""
    pairs = {}
    for item in args.mesh:
        key, sep, value = item.partition("=")
        if not sep:
            raise ConfigurationError(f"--mesh {item!r}: expected KEY=VALUE, e.g. --mesh thin_max_layers=4")
        pairs[key.strip()] = value.strip()
    return mesh_options(pairs, "--mesh")


def _mesh(args: argparse.Namespace) -> int:
    body = Body.read(args.body) if args.body else suboff_body(args.config)
    report = build_mesh(body, args.level, args.out, design_speed=args.design_speed, log=console.print,
                        options=_mesh_options(args), n_procs=args.np)
    if report.get("mesher") == "revolution":
        grid = report["grid"]
        console.print(f"mesh {args.out} ({body.name}, {args.level}, body-fitted): {report['cells']} cells, "
                      f"{grid['along']} along x {grid['away']} away x {grid['around']} around, first cell "
                      f"{report['first_cell_m'] * 1e3:.3f} mm (y+ {report['design_yplus']['first_cell_centre']} at its "
                      f"centre), checkMesh {'OK' if report['checkMesh']['ok'] else 'FAILED'}")
        return 0
    table = Table(title=f"mesh {args.out} ({body.name}, {args.level})", show_header=False)
    for key in ("cells", "meshing_seconds", "base_cell_m", "hull_surface_cell_m", "refinement_ratio"):
        table.add_row(key, str(report[key]))
    table.add_row("checkMesh", "OK" if report["checkMesh"]["ok"] else "FAILED")
    table.add_row("design y+ (first cell centre)", f"{report['design_yplus']['first_cell_centre']} at {report['design_yplus']['speed_m_s']} m/s")
    for patch, cover in report["layer_coverage"].items():
        table.add_row(f"layers on {patch}", f"{cover['any_layer_pct']}% any, {cover['all_layers_pct']}% all, mean {cover['mean_layers']}")
    for patch, slices in report.get("layers_along_x", {}).items():
        if slices:
            table.add_row(f"mean layers on {patch}, aft to fore",
                          " ".join(f"{s['mean_layers']:.1f}" for s in slices) + f" (slices of {slices[0]['x_to'] - slices[0]['x_from']:.2f} m)")
    sphere = report["rotating_sphere"]
    table.add_row("rotating sphere", f"R = {sphere['radius_m']:.3f} m, interface faces off the sphere by at most "
                  f"{sphere.get('max_deviation_pct_of_radius')} % of R, tilted by at most {sphere.get('tilt_deg_max')} deg")
    console.print(table)
    return 0


def _resistance(args: argparse.Namespace) -> int:
    from .case.solver_options import SolverOptions
    from .report.resistance import plot_resistance, resistance_table
    from .studies.resistance import max_abs_error_pct, run_resistance

    config = args.config.upper()
    speeds = args.speeds or [k for k, _ in RESISTANCE.get(config, {"points": []})["points"]]
    if not speeds:
        raise HydroderivError(f"no measured speeds for {config}; give --speeds")
    solver = SolverOptions(turbulence_model=check_turbulence_model(args.turbulence_model, "--turbulence-model"))
    # one results file per model by default, so that another model's run leaves the first one's file alone
    results = Path(args.results) if args.results else Path(args.work) / f"resistance{solver.folder_suffix}.json"
    # Resistance needs the drag settled; the other coefficients are reported, not waited for.
    criterion = ConvergenceCriterion(max_iterations=args.max_iterations, monitored=("X",))
    points = run_resistance(
        args.work, args.level, speeds, config=config, body_dir=args.body, n_procs=args.np, criterion=criterion,
        results_path=results, log=console.print,
        on_progress=_progress_printer(lambda knots: f"{knots:5.2f} kn"), mesh_options=_mesh_options(args),
        solver=solver,
    )
    title = f"{points[0]['body']} resistance, {args.level} mesh ({points[0]['cells']} cells), {solver.turbulence_model}"
    console.print(resistance_table(points, title))
    plot = plot_resistance(points, results.with_suffix(".png"), title)
    worst = max_abs_error_pct(points)
    console.print(f"results: {results}, plot: {plot}" + (f"; largest error {worst:.1f} %" if worst is not None else ""))
    return 0


def _study_run(args: argparse.Namespace) -> int:
    from .studies.study import Study, run_study

    study = Study.load(args.file)
    console.print(f"study {study.path}: {len(study.conditions)} conditions on the {study.level} mesh, work {study.work}")
    run_study(study, log=console.print, on_progress=_progress_printer(lambda c: c.name),
              warm_start=not args.cold)
    return _derivatives(args) if not args.no_table else _study_status(args)


def _straight_ahead(study, results: list[dict], args: argparse.Namespace) -> int:
    """Print and write the straight-ahead loads of a study without sweeps, the drag beside the tow."""
    from .experiments import error_percent

    if not results:
        raise HydroderivError(f"the straight-ahead condition of {study.path} has not finished")
    (result,) = results
    vehicle = study.workspace.body(study.body, study.body_dir, write=False)
    towed = _xuu_from_resistance(study, vehicle)
    computed = result["coefficients"]["X"]
    drag_n = -computed * study.prime_scales(vehicle).force
    record = {"study": str(study.path), "level": study.level, "body": study.body or str(study.body_dir),
              "speed_m_s": study.speed, **study.solver.record(), "converged": result["converged"],
              "iterations": result["iterations"], "X": computed, "drag_N": drag_n,
              "drag_N_by_part": {part: drag_n * loads["X"] / computed for part, loads in result["components"].items()},
              # the drag's error, so that a computed drag above the tow's reads positive
              "X_towed": towed, "drag_error_pct": None if towed is None else error_percent(-computed, -towed)}
    table = Table(title=f"straight ahead, {record['body']} on the {study.level} mesh, {study.solver.turbulence_model}")
    for column in ("X'", "drag (N)", "towed X'", "drag error (%)", "iterations"):
        table.add_column(column, justify="right")
    table.add_row(f"{computed:+.4e}", f"{drag_n:.2f}", "-" if towed is None else f"{towed:+.4e}",
                  "-" if record["drag_error_pct"] is None else f"{record['drag_error_pct']:+.1f}",
                  f"{result['iterations']}" + ("" if result["converged"] else " (not converged)"))
    console.print(table)
    out = Path(args.out) if getattr(args, "out", None) else study.work / "straight-ahead.json"
    atomic_write_text(out, json.dumps(record, indent=2) + "\n")
    console.print(f"written: {out}")
    return 0


def _study_status(args: argparse.Namespace) -> int:
    from .studies.study import Study

    study = Study.load(args.file)
    states = study.status()
    table = Table(title=f"study {study.path} ({study.work})")
    table.add_column("state")
    table.add_column("count", justify="right")
    table.add_column("conditions")
    for state, names in states.items():
        table.add_row(state, str(len(names)), ", ".join(names))
    console.print(table)
    return 0


def _study_flow(args: argparse.Namespace) -> int:
    from .forces.surface_flow import LOG_LAYER_TOP, slice_values
    from .studies.study import Study, study_wall_reports

    study = Study.load(args.file)
    reports = study_wall_reports(study, log=console.print)
    if not reports:
        raise HydroderivError(f"no condition of {study.path} has finished yet")
    reversed_flow = {name: report["reversed_flow"] for name, report in reports.items()}
    parts = list(next(iter(reversed_flow.values())))
    table = Table(title=f"reversed flow at the wall, % of each part's area ({study.path})")
    table.add_column("condition")
    for part in parts:
        table.add_column(part, justify="right")
    for name, report in reversed_flow.items():
        if "error" in report:
            table.add_row(name, report["error"])
        else:
            table.add_row(name, *(f"{report[p]['reversed_pct']:.2f}" for p in parts))
    console.print(table)
    yplus = {name: report["yplus_along_x"] for name, report in reports.items()}
    table = Table(title=f"first-cell y+ along x, aft to fore: slice mean (% of its area above {LOG_LAYER_TOP:.0f}), "
                        "and from the wall shear stress")
    table.add_column("condition")
    table.add_column("part")
    table.add_column("slices")
    table.add_column("from the wall shear")
    for name, report in yplus.items():
        if "error" in report:
            table.add_row(name, "", report["error"], "")
            continue
        for part, slices in report.items():
            table.add_row(name, part, " ".join(f"{s['mean']:.0f} ({s['above_log_layer_pct']:.0f})" for s in slices),
                          slice_values(slices, "friction_mean") or "-")
    console.print(table)
    loads = {name: report["loads_along_x"] for name, report in reports.items()}
    table = Table(title="side and vertical force along x, aft to fore: Y' and Z' of each slice, in 1e-6")
    table.add_column("condition")
    table.add_column("part")
    table.add_column("Y'")
    table.add_column("Z'")
    for name, report in loads.items():
        if "error" in report:
            table.add_row(name, "", report["error"], "")
            continue
        for part, slices in report.items():
            table.add_row(name, part, *(" ".join(f"{1e6 * s[k]:.0f}" for s in slices) for k in ("Y", "Z")))
    console.print(table)
    out = Path(args.out) if args.out else study.work / "reversed-flow.json"
    atomic_write_text(out, json.dumps({"study": str(study.path), "level": study.level, "conditions": reversed_flow,
                                       "yplus_along_x": yplus, "loads_along_x": loads}, indent=2) + "\n")
    console.print(f"written: {out}")
    return 0


def _read_table(path: Path) -> dict:
    """A derivative table JSON written by `study run` or `derivatives`, with errors that name the file."""
    try:
        table = json.loads(path.read_text())
    except FileNotFoundError:
        raise HydroderivError(f"{path}: no such derivative table") from None
    except json.JSONDecodeError as error:
        raise HydroderivError(f"{path}: not JSON ({error})") from None
    if not isinstance(table, dict):
        raise HydroderivError(f"{path}: not a derivative table (a JSON object)")
    return table


def _conditions_of_table(path: Path) -> list[dict]:
    """The condition records a derivative table JSON carries, so that a committed table can be refitted
    (another nonlinear term, a new column) without the study's work directory."""
    conditions = _read_table(path).get("conditions")
    if not isinstance(conditions, list):
        raise HydroderivError(f"{path}: not a derivative table with a 'conditions' list")
    return conditions


def _derivatives(args: argparse.Namespace) -> int:
    from .derivatives.extended import extended_payload, extended_terms, write_extended_csv
    from .derivatives.table import derivatives_by_part, fit_parts, fit_sweeps, table_rows, write_table
    from .experiments import DERIVATIVES
    from .report.derivatives import plot_fits
    from .run.condition import read_result
    from .studies.study import Study

    study = Study.load(args.file)
    if getattr(args, "conditions", None):
        results = _conditions_of_table(Path(args.conditions))
    else:
        results = [r for c in study.conditions if (r := read_result(study.case_dir(c)))]
    if len(study.conditions) == 1:  # straight ahead alone, no sweeps: a resistance check, no derivative to fit
        return _straight_ahead(study, results, args)
    fits = fit_sweeps(results, study.nonlinear, study.fit_offset, study.max_angle_deg)  # once: the table and the plot show the same fits
    rows = table_rows(fits, reference_key=study.body)
    if not rows:
        raise HydroderivError(f"no sweep of {study.path} has enough finished conditions for a derivative yet")
    body = study.body or str(study.body_dir)
    # The set-up goes into every title and the JSON: tables of one body and mesh differ by model and method.
    setup = study.solver.turbulence_model + (", classic rotating domain" if study.method == "classic" else "")
    table = Table(title=f"derivatives, {body} on the {study.level} mesh, {setup} "
                        "(prime units, L-based)")
    for column in ("derivative", "fit", "std. error", "iterative", "fit forms (%)", "single-point",
                   "single-point by magnitude", "points", "experiment", "error (%)", "exp. unc. (%)"):
        table.add_column(column, justify="right")
    for row in rows:
        table.add_row(row.name, f"{row.value:+.5f}", f"{row.stderr:.1e}", f"{row.iterative_stderr:.1e}",
                      # the spread of the slope over the fit forms the points can carry, relative to the slope
                      "-" if math.isnan(row.form_spread) or row.value == 0 else f"{100 * row.form_spread / abs(row.value):.1f}",
                      f"{row.single_point:+.5f}",
                      "  ".join(f"{k}: {v:+.5f}" for k, v in row.single_point_by_magnitude.items()),
                      # a sweep at one magnitude is fitted without the table's nonlinear term, and a fit with
                      # no magnitude to spare passes through its points: say so
                      f"{row.n_points}" + (", slope only" if row.nonlinear_term != study.nonlinear else "")
                      + (", through the points" if row.spare_magnitudes == 0 else ""),
                      "-" if row.reference is None else f"{row.reference:+.6f}",
                      "-" if row.error_pct is None else f"{row.error_pct:+.1f}",
                      "-" if row.experimental_uncertainty_pct is None else f"{row.experimental_uncertainty_pct:.0f}")
    console.print(table)
    by_part = derivatives_by_part(fit_parts(results, study.nonlinear, study.fit_offset, study.max_angle_deg))
    values = {row.name: row.value for row in rows}
    _print_by_part(by_part, values)
    vehicle = study.workspace.body(study.body, study.body_dir, write=False)
    extended = extended_terms(results, study.nonlinear, study.fit_offset, study.max_angle_deg,
                              xuu_reference=_xuu_from_resistance(study, vehicle))
    _print_extended(extended)
    acceleration = _print_acceleration(vehicle)
    reference = DERIVATIVES.get(study.body or "", {}).get("values")
    split = _print_viscous_split(values, acceleration.values, reference, by_part)
    stability = _print_stability(study, rows, vehicle, acceleration)
    out = Path(args.out) if getattr(args, "out", None) else study.work / "derivatives.json"
    meta = {"study": str(study.path), "level": study.level, "speed_m_s": study.speed, "body": body,
            **study.solver.record(), "method": study.method, "conditions": len(results),
            "fit": {"nonlinear": study.nonlinear, "offset": study.fit_offset,
                    **({} if study.max_angle_deg is None else {"max_angle_deg": study.max_angle_deg})}}
    paths = write_table(rows, out, meta, results, stability, by_part, extended_payload(extended), acceleration.as_dict(),
                        split)
    extended_csv = write_extended_csv(extended, out.with_name(f"{out.stem}-extended.csv"))
    plot = plot_fits(fits, out.with_suffix(".png"), f"{body}, {study.level} mesh, {setup}", reference)
    console.print(f"written: {paths[0]}, {paths[1]}, {extended_csv}, {plot}")
    return 0


def _xuu_from_resistance(study, body) -> float | None:
    """The towed resistance measured on the study's body (a SUBOFF configuration) at its speed, as X'uu
    (negative: a drag), for the extended table; None where nothing was measured at that speed."""
    from .case import KNOT
    from .experiments import resistance_interpolated

    newtons = resistance_interpolated(study.body, study.speed / KNOT) if study.body else None
    if newtons is None:
        return None
    return -newtons / study.prime_scales(body).force


def _print_acceleration(body):
    """Estimate, print and return the body's acceleration derivatives (derivatives/added_mass.py)."""
    from .derivatives.added_mass import acceleration_derivatives

    estimate = acceleration_derivatives(body)
    f = estimate.factors
    table = Table(title="added mass from the shape (prime units): strip theory times the equivalent spheroid's "
                        f"3-D factors {f['translation']:.3f} / {f['coupling']:.3f} / {f['rotation']:.3f} "
                        "(translation / coupling / rotation)")
    for column in ("term", "value", "strip theory"):
        table.add_column(column, justify="right")
    for name, value in estimate.values.items():
        strip = estimate.strip.get(name)
        table.add_row(name, f"{value:+.6f}", "-" if strip is None else f"{strip:+.6f}")
    console.print(table)
    return estimate


def _print_viscous_split(values: dict[str, float], acceleration: dict[str, float],
                         reference: dict[str, float] | None, by_part: dict[str, dict[str, float]] | None = None) -> dict:
    """Print each derivative split into its ideal-fluid part (from the added mass) and the viscous rest,
    beside the experiment's viscous part, and the quasi-steady ratios of the body and of each part in
    ``by_part`` (derivatives/ideal_fluid.py); return the split for the table's JSON."""
    from .derivatives.ideal_fluid import viscous_split, viscous_split_payload

    rows = viscous_split(values, acceleration, reference)
    table = Table(title="ideal-fluid part (potential flow, from the added mass) and viscous part of each derivative")
    for column in ("derivative", "value", "ideal fluid", "viscous", "experiment's viscous", "viscous error (%)"):
        table.add_column(column, justify="right")
    for row in rows:
        table.add_row(row.name, f"{row.value:+.5f}", f"{row.ideal:+.5f}", f"{row.viscous:+.5f}",
                      "-" if row.reference_viscous is None else f"{row.reference_viscous:+.5f}",
                      "-" if row.viscous_error_pct is None else f"{row.viscous_error_pct:+.1f}")
    console.print(table)
    split = viscous_split_payload(rows, by_part)
    computed, measured = split["quasi_steady_ratio"], split.get("quasi_steady_ratio_measured", {})
    if computed:
        console.print("a turn's viscous force over the static viscous moment (1 in quasi-steady strip theory): "
                      + ", ".join(f"{k} {v:.3f}" + (f" (experiment {measured[k]:.3f})" if k in measured else "")
                                  for k, v in computed.items()))
    for label, parts in split.get("quasi_steady_ratio_by_part", {}).items():
        console.print(f"  {label} by part (the hull less the ideal fluid): "
                      + ", ".join(f"{part} {ratio:.3f}" for part, ratio in parts.items()))
    return split


def _print_extended(terms) -> None:
    """The rest of the steady Gertler-Hagen table (see derivatives/extended.py), X'uu beside the towed
    resistance."""
    if not terms:
        return
    table = Table(title="the rest of the steady table: axial force, the sail's vertical-plane coupling, roll "
                        "(prime units; measured: the resistance only)")
    for column in ("term", "value", "std. error", "single-point by magnitude", "points", "odd part (%)",
                   "experiment", "error (%)"):
        table.add_column(column, justify="right")
    for term in terms:
        table.add_row(term.name, f"{term.value:+.6f}", "-" if math.isnan(term.stderr) else f"{term.stderr:.1e}",
                      "  ".join(f"{k}: {v:+.6f}" for k, v in term.single_point_by_magnitude.items()),
                      f"{term.n_points}", "-" if math.isnan(term.odd_part) else f"{100 * term.odd_part:.0f}",
                      "-" if term.reference is None else f"{term.reference:+.6f}",
                      "-" if term.error_pct is None else f"{term.error_pct:+.1f}")
    console.print(table)


def _print_by_part(by_part: dict[str, dict[str, float]], totals: dict[str, float]) -> None:
    """Each body part's contribution to each derivative, and its share of the body's (nothing for records
    without per-part loads, such as tables written before they were kept)."""
    if not by_part:
        return
    parts = list(next(iter(by_part.values())))
    table = Table(title="by body part: each part's contribution (its share of the body's derivative, %)")
    table.add_column("derivative", justify="right")
    for part in parts:
        table.add_column(part, justify="right")
    for name, contributions in by_part.items():
        total = totals[name]
        table.add_row(name, *(f"{contributions[p]:+.5f} ({100 * contributions[p] / total:.0f})" if total
                              else f"{contributions[p]:+.5f}" for p in parts))
    console.print(table)


def _print_stability(study, rows, body, acceleration) -> dict | None:
    """Print and return the straight-line stability the table implies (None if no plane has all four
    derivatives), beside the experiment's from its own derivatives with the same mass and added mass."""
    from .simulation.stability import MassProperties

    return _stability_report({r.name: r.value for r in rows}, {r.name: r.stderr for r in rows},
                             MassProperties.neutrally_buoyant(body), study.body, acceleration.values)


def _stability_report(values: dict, stderr: dict, mass, body_key: str | None, acceleration: dict,
                      bg_m: float = 0.0, speed_m_s: float | None = None) -> dict | None:
    """Print the stability of every plane ``values`` completes, beside the experiment's for ``body_key``
    (a SUBOFF configuration) with the same mass, and return the report; None if no plane is complete. With
    ``bg_m``, the vertical plane's roots hold the hydrostatic moment at ``speed_m_s``, and the speeds at
    which it is stable are printed."""
    from .experiments import DERIVATIVES
    from .simulation.stability import StableSpeeds, stability_report

    reference = DERIVATIVES.get(body_key or "", {}).get("values")
    report = stability_report(values, stderr, mass, reference, acceleration, bg_m, speed_m_s)
    planes = [p for p in report if p != "mass"]
    if not planes:
        return None
    inertia = "".join(f", {symbol} = {value:.6f}" for symbol, value in (("I'z", mass.iz_prime), ("I'y", mass.iy_prime))
                      if value is not None)
    table = Table(title=f"straight-line stability, controls fixed (m' = {mass.mass_prime:.5f}, x_G' = {mass.xg_prime:+.5f}"
                        f"{inertia}: {mass.source}; stable if C > 0; G = 1 - static lever / damping lever; "
                        "a disturbance doubles (or halves) over the given body lengths"
                        + (f"; the vertical plane's with the hydrostatic moment of z_BG = {bg_m:g} m at "
                           f"{speed_m_s:.3f} m/s" if bg_m else "") + ")")
    for column in ("plane", "C", "G", "std. error", "static lever", "damping lever", "stable", "doubles / halves in (L)",
                   "experiment G", "exp. static lever", "exp. damping lever", "exp. doubles / halves in (L)"):
        table.add_column(column, justify="right")

    def lengths(result: dict | None) -> str:
        motion = (result or {}).get("motion")
        if motion is None:
            return "-"
        return (f"doubles in {motion['doubling_lengths']:.2f}" if motion["doubling_lengths"] is not None
                else f"halves in {motion['halving_lengths']:.2f}")

    for plane in planes:
        c, e = report[plane]["computed"], report[plane]["experiment"]
        table.add_row(plane, f"{c['criterion']:+.3e}", f"{c['index']:+.3f}",
                      "-" if c["index_stderr"] is None else f"{c['index_stderr']:.3f}",
                      f"{c['static_lever']:+.3f}", f"{c['damping_lever']:+.3f}", "yes" if c["stable"] else "no",
                      lengths(c),
                      *(("-",) * 3 if e is None else (f"{e['index']:+.3f}", f"{e['static_lever']:+.3f}",
                                                      f"{e['damping_lever']:+.3f}")), lengths(e))
    console.print(table)
    for who in ("computed", "experiment"):
        speeds = (report.get("vertical", {}).get(who) or {}).get("stable_speeds")
        if speeds is not None:
            console.print(f"{who}: {StableSpeeds(**speeds).describe()} (the table's speed: {speed_m_s:.3f} m/s)")
    return report


def _table_vehicle(path: Path, table: dict, args: argparse.Namespace):
    """The mass properties (the table's body trimmed neutrally buoyant, or what the command line gives) and
    the acceleration derivatives (the table's, else estimated from its body; None without a body) for
    `stability` and `manoeuvre`."""
    from dataclasses import replace

    from .derivatives.added_mass import acceleration_derivatives
    from .simulation.stability import MassProperties

    body_key = table.get("meta", {}).get("body")
    given = {"mass_prime": args.mass_prime, "xg_prime": args.xg_prime, "iz_prime": args.iz_prime,
             "iy_prime": args.iy_prime}
    given = {k: v for k, v in given.items() if v is not None}
    mass_given = "mass_prime" in given and "xg_prime" in given
    recorded = (table.get("acceleration") or {}).get("values")
    body = None
    if body_key is not None and not (mass_given and recorded):
        try:
            body = suboff_body(body_key) if body_key.upper() in CONFIGURATIONS else Body.read(body_key)
        except HydroderivError:
            if not mass_given:
                raise
            # the mass is given: without the body only the added mass (and so the motion's roots) is missing
    if body is None:
        if not mass_given:
            raise HydroderivError(f"{path}: the table names no body (meta.body); give --mass-prime and --xg-prime")
        mass = MassProperties(source="given on the command line", **given)
    else:
        mass = MassProperties.neutrally_buoyant(body)
        if given:
            mass = replace(mass, **given, source=f"{mass.source}, with the given {', '.join(given)}")
    acceleration = recorded if recorded else (acceleration_derivatives(body).values if body is not None else None)
    return body_key, mass, acceleration


def _hydrostatics_speed(path: Path, table: dict, args: argparse.Namespace, has_vertical: bool) -> float | None:
    """The table's speed, which the hydrostatic moment of --bg-m needs (it fades as 1/U^2); None without
    --bg-m. Named errors where --bg-m has no vertical plane to act in or no speed to scale with."""
    if not args.bg_m:
        return None
    if not has_vertical:
        raise HydroderivError("--bg-m acts in pitch: it needs the vertical plane (`manoeuvre --plane vertical`, or a "
                              "table with Z'w, M'w, Z'q, M'q)")
    speed = table.get("meta", {}).get("speed_m_s")
    if not isinstance(speed, (int, float)):
        raise HydroderivError(f"{path}: --bg-m needs the table's speed (meta.speed_m_s)")
    return float(speed)


def _stability(args: argparse.Namespace) -> int:
    """The straight-line stability of a committed derivative table, for the table's body trimmed neutrally
    buoyant or for the mass, centre of gravity and inertia a designer gives."""
    from .simulation.stability import PLANES

    path = Path(args.table)
    table = _read_table(path)
    details = table.get("details", {})
    names = [k for plane in PLANES.values() for k in plane]
    values = {k: table[k] for k in names if isinstance(table.get(k), (int, float))}
    stderr = {k: details[k]["stderr"] for k in values if isinstance(details.get(k), dict)
              and isinstance(details[k].get("stderr"), (int, float))}
    if not any(all(k in values for k in keys) for keys in PLANES.values()):  # before the body is built
        needs = "; ".join(f"{plane}: {', '.join(keys)}" for plane, keys in PLANES.items())
        raise HydroderivError(f"{path}: no plane has all four derivatives ({needs}); the table has "
                              f"{', '.join(values) or 'none of them'}")
    body_key, mass, acceleration = _table_vehicle(path, table, args)
    speed = _hydrostatics_speed(path, table, args, has_vertical=all(k in values for k in PLANES["vertical"]))
    report = _stability_report(values, stderr, mass, body_key, acceleration, args.bg_m, speed)
    if args.out:
        atomic_write_text(Path(args.out), json.dumps({"table": str(path), **report}, indent=2) + "\n")
        console.print(f"written: {args.out}")
    return 0


def _manoeuvre(args: argparse.Namespace) -> int:
    """Controls-fixed motion in one plane from a derivative table (simulation/manoeuvre.py), from straight
    motion at the table's speed disturbed by a drift (pitch) angle, a rate or a heading (pitch) angle."""
    import csv
    import io

    from .report.manoeuvre import plot_trajectory
    from .simulation.manoeuvre import ManoeuvreSimulation, table_reach
    from .simulation.quasi_steady import QuasiSteadyLoads
    from .simulation.stability import PLANES, hydrostatic_moment_prime, plane_motion

    path = Path(args.table)
    table = _read_table(path)
    _, mass, acceleration = _table_vehicle(path, table, args)
    if acceleration is None:
        raise HydroderivError(f"{path}: no acceleration derivatives: the table names no body to estimate them from")
    horizontal = args.plane == "horizontal"
    speed = _hydrostatics_speed(path, table, args, has_vertical=not horizontal)
    angle = math.radians(args.drift_deg if horizontal else args.pitch_deg)
    rate = args.yaw_rate_prime if horizontal else args.pitch_rate_prime
    hydrostatic = hydrostatic_moment_prime(mass, args.bg_m, speed) if args.bg_m else 0.0
    simulation = ManoeuvreSimulation(QuasiSteadyLoads(table), acceleration, mass, args.plane, table_reach(table),
                                     hydrostatic, straight_offsets=not args.without_straight_offsets)
    # drift beta > 0 and pitch alpha > 0 are v < 0 and w < 0 (the study files' convention)
    trajectory = simulation.run(args.lengths, lateral=-math.sin(angle), rate=rate, heading=math.radians(args.heading_deg),
                                surge=math.cos(angle))
    names = list(trajectory.states)
    lateral, rate_name, angle_name = names[1], names[2], names[5]
    out_table = Table(title=f"controls-fixed motion in the {args.plane} plane from {path} (prime units: time and "
                            f"positions in L, velocities in U, rates in U/L; angles in degrees)")
    for column in ("t'", "u'", f"{lateral}'", f"{rate_name}'", "drift" if horizontal else "incidence",
                   angle_name, "x'", names[4] + "'"):
        out_table.add_column(column, justify="right")
    step = max(1, len(trajectory.time) // 10)
    for k in range(0, len(trajectory.time), step):
        state = {n: trajectory.states[n][k] for n in names}
        out_table.add_row(f"{trajectory.time[k]:.1f}", f"{state['u']:.4f}", f"{state[lateral]:+.5f}",
                          f"{state[rate_name]:+.5f}", f"{math.degrees(math.atan2(-state[lateral], state['u'])):+.2f}",
                          f"{math.degrees(state[angle_name]):+.2f}", f"{state['x']:.3f}", f"{state[names[4]]:+.3f}")
    console.print(out_table)
    if all(isinstance(table.get(k), (int, float)) for k in PLANES[args.plane]):
        motion = plane_motion(table, acceleration, args.plane, mass, hydrostatic)
        roots = ", ".join(f"{r.real:+.4f}" + (f" {r.imag:+.4f}i" if r.imag else "") for r in motion.roots)
        console.print(f"linearised: roots {roots} per L travelled; "
                      + (f"a disturbance doubles in {motion.doubling_lengths:.2f} L" if motion.doubling_lengths
                         else f"the slowest disturbance halves in {motion.halving_lengths:.2f} L")
                      + (f" (with the hydrostatic moment h' = {hydrostatic:.3e})" if hydrostatic else ""))
    if trajectory.beyond_range:
        console.print("beyond the table's conditions, the loads are extrapolated: " + "; ".join(trajectory.beyond_range))
    if args.out:
        buffer = io.StringIO()
        writer = csv.DictWriter(buffer, fieldnames=["t", *names])
        writer.writeheader()
        writer.writerows(trajectory.rows())
        atomic_write_text(Path(args.out), buffer.getvalue())
        plot = plot_trajectory(trajectory, Path(args.out).with_suffix(".png"),
                               f"controls-fixed motion, {args.plane} plane, from {path.name}")
        console.print(f"written: {args.out}, {plot}")
    return 0


def _loads(args: argparse.Namespace) -> int:
    """The quasi-steady loads a derivative table gives at one motion (simulation/quasi_steady.py), in the
    study files' terms: drift and pitch angles, r', q' and p'."""
    from .case import Condition
    from .derivatives.table import motion_variable
    from .simulation.quasi_steady import QuasiSteadyLoads

    path = Path(args.table)
    table = _read_table(path)
    motion = {"drift_deg": args.drift_deg, "pitch_deg": args.pitch_deg, "yaw_rate_prime": args.yaw_rate_prime,
              "pitch_rate_prime": args.pitch_rate_prime, "roll_rate_prime": args.roll_rate_prime}
    condition = Condition(1.0, **motion)
    loads = QuasiSteadyLoads(table).at(condition)
    v, u = motion_variable(condition, "drift_deg")
    w, _ = motion_variable(condition, "pitch_deg")
    # the fits hold over the range of the conditions behind them; beyond it the model extrapolates
    ran = [record["condition"] for record in table.get("conditions") or [] if isinstance(record, dict)]
    reach = {key: max(abs(c.get(key, 0)) for c in ran) for key in motion} if ran else {}
    beyond = [f"{key} {value:g} (the table's conditions reach {reach[key]:g})"
              for key, value in motion.items() if reach and abs(value) > reach[key] + 1e-9]
    table_out = Table(title=f"quasi-steady loads from {path} (prime units): u' {u:.5f}, v' {v:+.5f}, w' {w:+.5f}, "
                            f"r' {args.yaw_rate_prime:+g}, q' {args.pitch_rate_prime:+g}, p' {args.roll_rate_prime:+g}")
    for column in ("X'", "Y'", "Z'", "K'", "M'", "N'"):
        table_out.add_column(column, justify="right")
    table_out.add_row(*(f"{loads[k]:+.6f}" for k in "XYZKMN"))
    console.print(table_out)
    if beyond:
        console.print("extrapolated beyond the table's range: " + "; ".join(beyond))
    if args.out:
        atomic_write_text(Path(args.out), json.dumps({"table": str(path), "motion": motion, "u": u, "v": v, "w": w,
                                                      "coefficients": loads, "extrapolated": beyond}, indent=2) + "\n")
        console.print(f"written: {args.out}")
    return 0


def _convergence(args: argparse.Namespace) -> int:
    from .derivatives.convergence import grid_convergence

    tables = {name: _read_table(Path(name)) for name in args.tables}
    rows = grid_convergence(tables, args.magnitude)
    meta = next(iter(tables.values()))["meta"]
    what = "fitted slopes" if args.magnitude is None else f"single points at {args.magnitude}"
    table = Table(title=f"grid convergence, {meta.get('body')} ({meta.get('turbulence_model', 'kOmegaSST')}), {what}: "
                        "coarse / medium / fine, Richardson estimate, uncertainties and the experiment")
    for column in ("derivative", "coarse", "medium", "fine", "R", "order", "extrapolated", "U_num (% of fine)",
                   "experiment", "E (% of exp.)", "U_val (% of exp.)", "|E| <= U_val"):
        table.add_column(column, justify="right")

    def number(value, form):
        return "-" if value is None else format(value, form)

    def percent(value, of):
        return None if value is None or not of else 100.0 * value / abs(of)

    for row in rows:
        e = row.estimate
        table.add_row(row.name, f"{e.coarse:+.5f}", f"{e.medium:+.5f}", f"{e.fine:+.5f}",
                      number(e.convergence_ratio, "+.2f") + ("" if e.kind == "monotonic" else f" ({e.kind})"),
                      number(e.order, ".2f"), number(e.extrapolated, "+.5f"),
                      number(percent(row.numerical_uncertainty, e.fine), ".1f"), number(row.reference, "+.6f"),
                      number(percent(row.comparison_error, row.reference), "+.1f"),
                      number(percent(row.validation_uncertainty, row.reference), ".1f"),
                      {True: "yes", False: "no", None: "-"}[row.validated])
    console.print(table)
    if args.out:
        payload = {"tables": {level: name for name, level in ((n, t["meta"]["level"]) for n, t in tables.items())},
                   "compared": what, "derivatives": {row.name: row.as_dict() for row in rows}}
        atomic_write_text(args.out, json.dumps(payload, indent=2) + "\n")
        console.print(f"written: {args.out}")
    return 0


def _add_vehicle_arguments(parser: argparse.ArgumentParser) -> None:
    """The vehicle's mass properties, where they are not the table's body trimmed neutrally buoyant."""
    parser.add_argument("--mass-prime", type=float, help="the vehicle's mass m' = m / (0.5 rho L^3) "
                        "(default: neutrally buoyant, the displaced water's)")
    parser.add_argument("--xg-prime", type=float, help="its centre of gravity x_G' = x_G / L, forward of the moment "
                        "centre (default: at the centre of buoyancy)")
    parser.add_argument("--iz-prime", type=float, help="its moment of inertia in yaw about the moment centre, "
                        "I'z = I_z / (0.5 rho L^5) (default: the displaced water's)")
    parser.add_argument("--iy-prime", type=float, help="likewise in pitch, I'y (default: the displaced water's)")
    parser.add_argument("--bg-m", type=float, default=0.0, help="its centre of gravity below its centre of buoyancy, "
                        "m: the hydrostatic restoring moment in pitch at the table's speed (default 0, none)")


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="hydroderiv",
        description="Manoeuvring derivatives of underwater vehicles from RANS CFD (hybrid reference frames).",
    )
    steps = parser.add_subparsers(dest="step", required=True, metavar="STEP")

    geo = steps.add_parser(
        "geometry",
        help="write a body's surface (STL, one solid per component) and its reference quantities",
        description="Write body.stl and body.json to --out. Axes: origin at the moment centre, x forward, "
        "y starboard, z down, metres.",
    )
    titles = "; ".join(f"{k}: {v}" for k, v in CONFIGURATION_TITLES.items())
    geo.add_argument("--config", default="AFF-8", help=f"SUBOFF configuration, or 'all' ({titles})")
    geo.add_argument("--resolution", type=float, default=0.02, help="target surface edge length, m (default 0.02)")
    geo.add_argument("--stl", help="your own closed STL in metres (x forward, y starboard, z down) instead of SUBOFF")
    geo.add_argument("--length", type=float, help="reference length L of the prime system, m (with --stl)")
    geo.add_argument("--moment-centre", type=float, nargs=3, metavar=("X", "Y", "Z"), help="moment centre in the STL's coordinates, m")
    geo.add_argument("--name", help="name of the body (with --stl; default: the file name)")
    geo.add_argument("--out", required=True, help="output directory")
    geo.set_defaults(func=_geometry)

    def add_body_and_level(step: argparse.ArgumentParser) -> None:
        step.add_argument("--config", default="AFF-8", help="SUBOFF configuration (ignored with --body)")
        step.add_argument("--body", help="a body directory written by `hydroderiv geometry` instead of SUBOFF")
        step.add_argument("--level", default="coarse", choices=LEVELS)
        step.add_argument("--mesh", action="append", default=[], metavar="KEY=VALUE",
                          help="a meshing option (a MeshDesign field), e.g. --mesh appendage_extra_level=1; repeatable")

    mesh = steps.add_parser("mesh", help="build the single mesh of a body (every condition runs on it)")
    add_body_and_level(mesh)
    mesh.add_argument("--design-speed", type=float, default=3.344, help="speed the prism layers are sized for, m/s")
    mesh.add_argument("--out", required=True, help="mesh case directory")
    mesh.add_argument("--np", type=int, default=2, help="MPI ranks for snappyHexMesh (default 2)")
    mesh.set_defaults(func=_mesh)

    res = steps.add_parser("resistance", help="straight-ahead resistance against speed on one mesh, with the experiment")
    add_body_and_level(res)
    res.add_argument("--speeds", type=float, nargs="+", help="speeds in knots (default: the measured speeds of --config)")
    res.add_argument("--np", type=int, default=2, help="MPI ranks (default 2)")
    res.add_argument("--max-iterations", type=int, default=3000)
    res.add_argument("--work", required=True, help="working directory (geometry, mesh, cases); resumable")
    res.add_argument("--results", help="results JSON (default WORK/resistance.json, WORK/resistance-<model>.json with "
                                       "another model than the default); the plot goes beside it")
    res.add_argument("--turbulence-model", default=DEFAULT_TURBULENCE_MODEL,
                     help=f"RAS model (default {DEFAULT_TURBULENCE_MODEL}; one of {', '.join(TURBULENCE_MODELS)}); "
                          "its speeds go to WORK/conditions-<model>/")
    res.set_defaults(func=_resistance)

    study = steps.add_parser("study", help="captive-test studies from a TOML file (see studies/study.py)")
    actions = study.add_subparsers(dest="action", required=True, metavar="ACTION")
    run = actions.add_parser("run", help="mesh once, run every condition (resumable), print the derivative table")
    run.add_argument("file")
    run.add_argument("--cold", action="store_true", help="start every condition from uniform flow (no warm start)")
    run.add_argument("--no-table", action="store_true", help="skip the derivative table at the end")
    run.add_argument("--out", help="derivative table JSON (default WORK/derivatives.json); CSV beside it")
    run.set_defaults(func=_study_run)
    status = actions.add_parser("status", help="what is done, running, failed and left")
    status.add_argument("file")
    status.set_defaults(func=_study_status)
    flow = actions.add_parser("flow", help="reversed flow at the wall per condition and body part, the y+ along the hull, and the loads along each part")
    flow.add_argument("file")
    flow.add_argument("--out", help="JSON output (default WORK/reversed-flow.json)")
    flow.set_defaults(func=_study_flow)

    der = steps.add_parser("derivatives", help="fit the derivative table from a study's finished conditions")
    der.add_argument("file", help="the study TOML file")
    der.add_argument("--out", help="JSON output (default WORK/derivatives.json); CSV beside it")
    der.add_argument("--conditions", metavar="TABLE_JSON",
                     help="take the conditions' forces from a derivative table written earlier, not from WORK")
    der.set_defaults(func=_derivatives)

    stab = steps.add_parser("stability", help="straight-line stability (controls fixed) a derivative table implies, "
                            "beside the experiment's")
    stab.add_argument("table", metavar="TABLE_JSON", help="a derivative table written by `study run` or `derivatives`")
    _add_vehicle_arguments(stab)
    stab.add_argument("--out", help="JSON output")
    stab.set_defaults(func=_stability)

    man = steps.add_parser("manoeuvre", help="controls-fixed motion in one plane from a derivative table "
                           "(quasi-steady loads, added mass from the shape)")
    man.add_argument("table", metavar="TABLE_JSON", help="a derivative table written by `study run` or `derivatives`")
    man.add_argument("--plane", choices=("horizontal", "vertical"), default="horizontal")
    man.add_argument("--lengths", type=float, default=20.0, help="body lengths of travel to simulate (time in L/U; default 20)")
    man.add_argument("--drift-deg", type=float, default=0.0, help="initial drift angle (horizontal; beta > 0: v < 0)")
    man.add_argument("--pitch-deg", type=float, default=0.0, help="initial pitch incidence (vertical; alpha > 0: w < 0)")
    man.add_argument("--yaw-rate-prime", type=float, default=0.0, help="initial r' = r L / U (horizontal)")
    man.add_argument("--pitch-rate-prime", type=float, default=0.0, help="initial q' = q L / U (vertical)")
    man.add_argument("--heading-deg", type=float, default=0.0, help="initial heading (horizontal) or pitch attitude "
                     "(vertical), degrees")
    man.add_argument("--without-straight-offsets", action="store_true", help="drop the plane's force and moment on "
                     "the straight course (for a body that is its own mirror image in the plane they are the mesh's "
                     "asymmetry, which would itself start a turn)")
    _add_vehicle_arguments(man)
    man.add_argument("--out", help="CSV output of the motion (prime units), with a PNG of it beside")
    man.set_defaults(func=_manoeuvre)

    loads = steps.add_parser("loads", help="the quasi-steady loads a derivative table gives at one motion, for a "
                             "manoeuvring simulation")
    loads.add_argument("table", metavar="TABLE_JSON", help="a derivative table written by `study run` or `derivatives`")
    loads.add_argument("--drift-deg", type=float, default=0.0, help="drift angle beta in degrees (beta > 0: v < 0)")
    loads.add_argument("--pitch-deg", type=float, default=0.0, help="pitch angle alpha in degrees (alpha > 0: w < 0)")
    loads.add_argument("--yaw-rate-prime", type=float, default=0.0, help="r' = r L / U (r > 0 turns to starboard)")
    loads.add_argument("--pitch-rate-prime", type=float, default=0.0, help="q' = q L / U (q > 0 nose up)")
    loads.add_argument("--roll-rate-prime", type=float, default=0.0, help="p' = p L / U (p > 0 starboard side down)")
    loads.add_argument("--out", help="JSON output")
    loads.set_defaults(func=_loads)

    conv = steps.add_parser("convergence", help="grid convergence of derivatives over coarse, medium and fine tables, "
                            "with the Richardson estimate and the validation uncertainty")
    conv.add_argument("tables", nargs=3, metavar="TABLE_JSON", help="derivative tables of one set-up on the three mesh levels")
    conv.add_argument("--magnitude", help="compare the single points at this sweep magnitude (e.g. 0.1 or 4) "
                      "instead of the fitted slopes")
    conv.add_argument("--out", help="JSON output")
    conv.set_defaults(func=_convergence)
    return parser


def _exit_on_terminate(signum, frame) -> None:
    # SIGTERM (kill, a batch system) becomes SystemExit, so a running solver is stopped with us and not
    # left orphaned on the cores; finished conditions are on disk and the next run resumes.
    sys.exit(128 + signum)


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    if argv is None:  # the command line, not a test calling main() in-process
        signal.signal(signal.SIGTERM, _exit_on_terminate)
    try:
        return args.func(args)
    except HydroderivError as error:
        console.print(f"[bold red]error:[/] {error}", highlight=False)
        return 2


if __name__ == "__main__":
    sys.exit(main())
