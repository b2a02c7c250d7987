"""Benchmark of a captive-test study: solver throughput, warm against cold starts, MPI scaling, total time.

    python benchmarks/study_benchmark.py studies/aff8-coarse-sa.toml

Prints, and writes to benchmarks/results/<study>.json:
- per condition: iterations, wall time of the solver, cell-iterations and cell-iterations per second;
- iterations to convergence of a few conditions started cold (uniform flow) against the study's warm starts;
- the speed-up of 2 MPI ranks over 1 (seconds per iteration over a fixed number of iterations);
- the total time for the table: meshing plus every condition.

The study itself is run (or read back, it is resumable) first. The cold runs and the scaling runs go to
<work>/benchmark/ and are reused when present, so the script can be interrupted and run again. Run it on an
otherwise idle machine: any other CFD on the same cores spoils every figure.
"""

from __future__ import annotations

import argparse
import json
import re
import shutil
import sys
import time
from dataclasses import replace
from pathlib import Path

from hydroderiv._io import atomic_write_text
from hydroderiv.case.setup import CaseSettings, latest_time_dir, write_condition_case
from hydroderiv.run.condition import read_result, run_condition
from hydroderiv.run.openfoam import run_application
from hydroderiv.studies.study import Study, run_order, run_study

_EXECUTION_TIME = re.compile(r"^ExecutionTime = ([0-9.eE+-]+) s", re.M)


def seconds_per_iteration(log: Path) -> float:
    """Mean solver time per iteration from a simpleFoam log, leaving out the first (start-up) iteration."""
    times = [float(t) for t in _EXECUTION_TIME.findall(log.read_text())]
    if len(times) < 3:
        raise RuntimeError(f"{log}: too few iterations to time")
    return (times[-1] - times[0]) / (len(times) - 1)


def fixed_iterations(study: Study, settings: CaseSettings, n_procs: int, iterations: int, warm: Path) -> float:
    """Seconds per iteration of the straight-ahead condition over ``iterations`` iterations on ``n_procs`` ranks."""
    case = study.work / "benchmark" / f"ranks-{n_procs}"
    log = case / "log.simpleFoam"
    if not (case / "done").is_file():
        shutil.rmtree(case, ignore_errors=True)  # an interrupted timing restarts from scratch, not mid-run
        fixed = replace(settings, n_procs=n_procs, max_iterations=iterations, write_interval=iterations)
        straight = study.conditions[0]
        write_condition_case(case, study.workspace.mesh_dir, straight, fixed, warm_start=warm)
        if n_procs > 1:
            run_application(case, ["decomposePar", "-force"], log_name="decomposePar")
        run_application(case, ["simpleFoam"], n_procs=n_procs)
        (case / "done").write_text("")
    return seconds_per_iteration(log)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("study", nargs="?", default="studies/aff8-coarse-sa.toml")  # the main job's study
    parser.add_argument("--cold", type=int, default=2, help="conditions to repeat from a cold start (default 2)")
    parser.add_argument("--iterations", type=int, default=30, help="iterations for the 1-against-2-ranks timing")
    parser.add_argument("--out", help="JSON output (default benchmarks/results/<study stem>.json)")
    args = parser.parse_args(argv)

    study = Study.load(args.study)
    started = time.time()
    results = run_study(study, log=print)
    mesh = json.loads((study.workspace.mesh_dir / "mesh.json").read_text())
    cells = int(mesh["cells"])
    body = study.workspace.body(study.body, study.body_dir)
    settings = study.case_settings(body)

    rows = []
    for condition in run_order(study.conditions):
        r = results.get(condition.name)
        if r is None:
            continue  # failed; the study reported it
        rate = cells * r["iterations"] / r["wall_seconds"]
        rows.append({"condition": condition.name, "iterations": r["iterations"], "wall_s": r["wall_seconds"],
                     # with set-up, decomposition and reconstruction; results older than that record lack it
                     "total_s": r.get("total_seconds"),
                     "n_procs": r["n_procs"], "warm_start": bool(r["warm_start"]),
                     "cell_iterations": cells * r["iterations"], "cell_iterations_per_s": round(rate)})

    # Warm against cold: repeat the first few warm-started conditions from uniform flow.
    cold = []
    warm_started = [row for row in rows if row["warm_start"]][: args.cold]
    for row in warm_started:
        condition = next(c for c in study.conditions if c.name == row["condition"])
        case = study.work / "benchmark" / "cold" / condition.name
        record = read_result(case) or run_condition(case, study.workspace.mesh_dir, condition, settings,
                                                    study.criterion_for(condition))
        cold.append({"condition": condition.name, "warm_iterations": row["iterations"], "cold_iterations": record["iterations"],
                     "warm_wall_s": row["wall_s"], "cold_wall_s": record["wall_seconds"]})

    straight = latest_time_dir(study.case_dir(study.conditions[0]))
    one = fixed_iterations(study, settings, 1, args.iterations, straight)
    two = fixed_iterations(study, settings, 2, args.iterations, straight)

    total_s = mesh["meshing_seconds"] + sum(row["total_s"] or row["wall_s"] for row in rows)
    overhead_known = all(row["total_s"] is not None for row in rows)
    report = {
        "study": str(study.path), "level": study.level, "method": study.method, "cells": cells,
        "meshing_s": mesh["meshing_seconds"], "conditions": rows, "warm_vs_cold": cold,
        "seconds_per_iteration": {"1_rank": round(one, 4), "2_ranks": round(two, 4)},
        "speedup_2_over_1": round(one / two, 3),
        "total_time_for_table_s": round(total_s, 1),
        # False: some conditions only recorded their solver time, so the total leaves out their set-up
        "total_includes_case_overhead": overhead_known,
        "benchmark_wall_s": round(time.time() - started, 1),
    }
    out = Path(args.out or Path(__file__).parent / "results" / f"{study.path.stem}.json")
    atomic_write_text(out, json.dumps(report, indent=2) + "\n")

    print(f"\n{study.path}: {cells} cells, {study.level} mesh, meshing {mesh['meshing_seconds']:.0f} s")
    print(f"{'condition':34s} {'its':>5s} {'wall s':>8s} {'Mcell-it':>9s} {'Mcell-it/s':>11s}  start")
    for row in rows:
        print(f"{row['condition']:34s} {row['iterations']:5d} {row['wall_s']:8.0f} {row['cell_iterations'] / 1e6:9.1f} "
              f"{row['cell_iterations_per_s'] / 1e6:11.3f}  {'warm' if row['warm_start'] else 'cold'}")
    for c in cold:
        print(f"warm against cold, {c['condition']}: {c['warm_iterations']} against {c['cold_iterations']} iterations "
              f"({c['warm_wall_s']:.0f} s against {c['cold_wall_s']:.0f} s)")
    print(f"seconds per iteration: 1 rank {one:.3f}, 2 ranks {two:.3f}; speed-up {one / two:.2f}")
    scope = "with" if overhead_known else "solver time only, without"
    print(f"total time for the table (meshing + conditions, {scope} case set-up): {total_s / 60:.1f} min; written {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
