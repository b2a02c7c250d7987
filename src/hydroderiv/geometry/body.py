"""The body: its closed surface, named components and reference quantities.

Axes (the convention of the captive-model data, Roddy 1990): origin at the moment centre B,
x forward, y starboard, z down. Lengths in metres.
"""

from __future__ import annotations

import json
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .._io import atomic_write_text
from ..errors import GeometryError
from .stl import read_stl, write_stl
from .surfaces import TriSurface

SURFACE_FILE = "body.stl"
REFERENCE_FILE = "body.json"


@dataclass(frozen=True)
class ReferenceQuantities:
    """Quantities that make forces dimensionless and describe the body.

    ``length`` is the L of the prime system (Gertler & Hagen 1967). ``moment_centre`` is where the moment
    centre lies in the coordinates of the source geometry (described by ``moment_centre_frame``); the
    body's surfaces are already translated so that it is the origin.
    """

    length: float
    moment_centre: tuple[float, float, float]
    moment_centre_frame: str
    volume: float
    wetted_area: float
    max_diameter: float


@dataclass(frozen=True)
class Body:
    """A closed vehicle surface in body axes, each face labelled with the component it belongs to."""

    name: str
    surface: TriSurface
    component_names: tuple[str, ...]
    face_component: np.ndarray
    reference: ReferenceQuantities

    def component(self, name: str) -> TriSurface:
        """The faces of one component (an open surface when it meets others: its junctions are shared)."""
        try:
            k = self.component_names.index(name)
        except ValueError:
            raise GeometryError(f"{self.name} has no component {name!r}; it has {', '.join(self.component_names)}")
        return self.surface.subset(self.face_component == k)

    def component_areas(self) -> dict[str, float]:
        return {name: self.component(name).area for name in self.component_names}

    def write(self, directory: str | Path) -> tuple[Path, Path]:
        """Write ``body.stl`` (one named solid per component) and ``body.json`` (reference quantities)."""
        directory = Path(directory)
        directory.mkdir(parents=True, exist_ok=True)
        stl_path = directory / SURFACE_FILE
        write_stl(stl_path, self.surface, self.face_component, self.component_names)
        info = {
            "name": self.name,
            "axes": "origin at the moment centre; x forward, y starboard, z down; metres",
            "components": list(self.component_names),
            "reference": asdict(self.reference),
            "component_wetted_area": self.component_areas(),
        }
        json_path = directory / REFERENCE_FILE
        atomic_write_text(json_path, json.dumps(info, indent=2) + "\n")
        return stl_path, json_path

    @classmethod
    def read(cls, directory: str | Path) -> Body:
        """Read a body written by :meth:`write`."""
        directory = Path(directory)
        json_path = directory / REFERENCE_FILE
        if not json_path.is_file():
            raise GeometryError(f"{directory} holds no {REFERENCE_FILE}; run `hydroderiv geometry` first")
        info = json.loads(json_path.read_text())
        surface, face_component, names = read_stl(directory / SURFACE_FILE)
        ref = info["reference"]
        ref["moment_centre"] = tuple(ref["moment_centre"])
        return cls(info["name"], surface, tuple(names), face_component, ReferenceQuantities(**ref))

    def summary(self) -> list[tuple[str, str]]:
        """(quantity, value) rows for printing."""
        r = self.reference
        lo, hi = self.surface.bounds
        return [
            ("reference length L", f"{r.length:.4f} m"),
            ("moment centre", f"({', '.join(f'{c:.4f}' for c in r.moment_centre)}) [{r.moment_centre_frame}]"),
            ("volume", f"{r.volume:.5f} m^3"),
            ("wetted area", f"{r.wetted_area:.4f} m^2"),
            ("maximum diameter", f"{r.max_diameter:.4f} m"),
            ("extent x (fwd)", f"{lo[0]:+.4f} .. {hi[0]:+.4f} m"),
            ("extent y (stbd)", f"{lo[1]:+.4f} .. {hi[1]:+.4f} m"),
            ("extent z (down)", f"{lo[2]:+.4f} .. {hi[2]:+.4f} m"),
            ("components", ", ".join(self.component_names)),
            ("triangles", f"{len(self.surface.faces)}"),
        ]
