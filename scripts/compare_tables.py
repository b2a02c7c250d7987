"""Two derivative tables of the same conditions, side by side: each shared condition's iterations and the
change of its loads, then the change of each derivative. For a rerun of a table (another convergence
criterion, solver version or machine) against the table it checks.

    .venv/bin/python scripts/compare_tables.py NEW.json REFERENCE.json [--min-load 1e-4]

A load's change is given in per cent of the reference's value where that is at least --min-load in prime
units (smaller loads, such as the side force straight ahead, are noise about zero and are left out).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from hydroderiv.experiments import error_percent
from hydroderiv.forces.coefficients import COEFFICIENT_NAMES


def _conditions(table: dict) -> dict[str, dict]:
    return {record["name"]: record for record in table.get("conditions", [])}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("new", type=Path)
    parser.add_argument("reference", type=Path)
    parser.add_argument("--min-load", type=float, default=1e-4,
                        help="smallest reference load (prime units) whose change is reported")
    args = parser.parse_args(argv)
    new_table, reference_table = (json.loads(path.read_text()) for path in (args.new, args.reference))
    new_conditions, reference_conditions = _conditions(new_table), _conditions(reference_table)
    shared = [name for name in reference_conditions if name in new_conditions]
    if not shared:
        print(f"no condition of {args.reference} is in {args.new}", file=sys.stderr)
        return 1
    print(f"{'condition':28s} {'iterations':>12s}  load change (% of the reference)")
    largest = 0.0
    for name in shared:
        new, reference = new_conditions[name], reference_conditions[name]
        changes = []
        for load in COEFFICIENT_NAMES:
            value = reference["coefficients"].get(load)
            if value is not None and abs(value) >= args.min_load:
                change = error_percent(new["coefficients"][load], value)
                largest = max(largest, abs(change))
                changes.append(f"{load}' {change:+.2f}")
        iterations = f"{new.get('iterations', '?')}/{reference.get('iterations', '?')}"
        print(f"{name:28s} {iterations:>12s}  {'  '.join(changes)}")
    print(f"largest load change: {largest:.2f} % over {len(shared)} conditions")
    names = [key for key in reference_table if isinstance(reference_table[key], (int, float))
             and isinstance(new_table.get(key), (int, float))]
    if names:
        print("derivative  new           reference     change")
        for key in names:
            new, reference = new_table[key], reference_table[key]
            print(f"{key:10s}  {new:+.6f}    {reference:+.6f}    {error_percent(new, reference):+.2f} %")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
