"""Screen a committed derivative table for conditions stopped on a dip in their loads.

A straight line through a V is flat, so a convergence criterion that only asked for a flat trend (the one
before 2026-12-07) could stop a run whose loads had dipped and were recovering. The per-condition force
histories of a table of record are usually gone with its work directory, but the study's log (written
beside the table) keeps the loads every 25 iterations or so. For each condition this prints, for each load
its derivatives come from, how far the last logged value lies from the window mean the table holds, and the
spread of the logged values inside the averaging window, both in per cent of the mean. A run stopped on a
V shows a spread and an offset of several per cent; a settled one a fraction of the tolerance.

    .venv/bin/python scripts/screen_averaging_windows.py validation/derivatives-AFF-8-medium.json [--window 100]

The log is the table's name with ``.log``; ``--window`` is the study's averaging window.
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

from hydroderiv.case.conditions import Condition

_LOADS = re.compile(r"(\w)' (\S+)")


def logged_loads(log: str, name: str) -> list[tuple[int, dict[str, float]]]:
    """The (iteration, {load: value}) progress lines of one condition in a study's log."""
    lines = re.findall(rf"^\s+{re.escape(name)} it\s+(\d+) \|.*?\| (X' .*?) \|", log, re.M)
    return [(int(it), {k: float(v) for k, v in _LOADS.findall(loads)}) for it, loads in lines]


def screen(table: dict, log: str, window: int) -> list[str]:
    rows = []
    for record in table["conditions"]:
        samples = logged_loads(log, record["name"])
        if not samples:
            rows.append(f"{record['name']:28s} not in the log")
            continue
        loads = Condition(**record["condition"]).defining_loads or ("X",)
        figures = []
        for load in loads:
            mean = record["coefficients"][load]
            inside = [values[load] for it, values in samples if it > record["iterations"] - window and load in values]
            if not inside:
                continue
            offset = 100 * (inside[-1] / mean - 1)
            spread = 100 * (max(inside) - min(inside)) / abs(mean)
            figures.append(f"{load}' last {offset:+.1f} %, spread {spread:.1f} % ({len(inside)} logged)")
        rows.append(f"{record['name']:28s} {record['iterations']:5d} its  " + "; ".join(figures))
    return rows


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("table", type=Path, help="a study's derivative table (JSON), its log beside it")
    parser.add_argument("--window", type=int, default=100, help="the study's averaging window in iterations")
    args = parser.parse_args()
    log = args.table.with_suffix(".log")
    if not log.is_file():
        raise SystemExit(f"no log beside {args.table}: expected {log}")
    print("\n".join(screen(json.loads(args.table.read_text()), log.read_text(), args.window)))


if __name__ == "__main__":
    main()
