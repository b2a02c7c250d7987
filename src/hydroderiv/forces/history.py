"""Force and moment histories written by OpenFOAM's ``forces`` function object.

The column layout of ``force.dat`` / ``moment.dat`` differs between OpenFOAM lines and releases, so the
columns are found by name in the file's header (``# Time total_x total_y total_z pressure_x ...``), never by
position. Vector values may be written in parentheses; those are ignored.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import HydroderivError

PARTS = ("total", "pressure", "viscous")


@dataclass(frozen=True)
class VectorHistory:
    """A vector quantity per iteration, split into total, pressure and viscous parts (each (n, 3))."""

    iterations: np.ndarray
    parts: dict[str, np.ndarray]

    @property
    def total(self) -> np.ndarray:
        return self.parts["total"]

    def __len__(self) -> int:
        return len(self.iterations)


def _columns(header: str) -> list[str]:
    return header.lstrip("#").replace("(", " ").replace(")", " ").split()


def read_vector_dat(path: str | Path) -> VectorHistory:
    """Read one ``force.dat``/``moment.dat`` file, locating columns by their header names."""
    path = Path(path)
    header = None
    rows = []
    for line in path.read_text().splitlines():
        if line.startswith("#"):
            names = _columns(line)
            if names and names[0].lower() == "time":
                header = names
            continue
        if line.strip():
            rows.append(line.replace("(", " ").replace(")", " ").split())
    if header is None:
        raise HydroderivError(f"{path}: no '# Time ...' header line; not a forces function object file?")
    index = {name.lower(): k for k, name in enumerate(header)}
    parts = {}
    for part in PARTS:
        wanted = [f"{part}_{axis}" for axis in "xyz"]
        if all(w in index for w in wanted):
            parts[part] = [index[w] for w in wanted]
    if "total" not in parts:
        if "pressure" in parts and "viscous" in parts:
            parts["total"] = None  # summed below
        else:
            raise HydroderivError(f"{path}: header has no total_x/y/z (nor pressure and viscous) columns: {header}")
    complete = [r for r in rows if len(r) >= len(header)]  # a line being written right now may be short
    data = np.array(complete, dtype=float).reshape(-1, len(header)) if complete else np.empty((0, len(header)))
    values = {p: data[:, cols] for p, cols in parts.items() if cols is not None}
    if parts["total"] is None:
        values["total"] = values["pressure"] + values["viscous"]
    return VectorHistory(data[:, index["time"]], values)


def _start_time_dirs(function_dir: Path) -> list[Path]:
    dirs = []
    for d in function_dir.iterdir():
        try:
            dirs.append((float(d.name), d))
        except ValueError:
            continue
    return [d for _, d in sorted(dirs)]


def read_history(postprocessing: str | Path, name: str, quantity: str = "force") -> VectorHistory:
    """The whole history of a forces function object ``name`` (``quantity`` = 'force' or 'moment').

    A restarted run writes a new start-time directory (and OpenFOAM may add a suffix such as
    ``force_0.dat``); the pieces are joined in order, later ones replacing overlapping iterations.
    """
    function_dir = Path(postprocessing) / name
    if not function_dir.is_dir():
        raise HydroderivError(f"no forces output {function_dir}; did the solver start?")
    pieces = []
    for start in _start_time_dirs(function_dir):
        for path in sorted(start.glob(f"{quantity}*.dat")):
            pieces.append(read_vector_dat(path))
    pieces = [p for p in pieces if len(p)]
    if not pieces:
        return VectorHistory(np.empty(0), {p: np.empty((0, 3)) for p in PARTS})
    iterations = pieces[0].iterations
    parts = dict(pieces[0].parts)
    for piece in pieces[1:]:
        keep = iterations < piece.iterations[0]
        iterations = np.concatenate([iterations[keep], piece.iterations])
        parts = {p: np.concatenate([parts[p][keep], piece.parts[p]]) for p in piece.parts if p in parts}
    return VectorHistory(iterations, parts)
