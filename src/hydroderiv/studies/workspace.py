"""A study's working directory: the body, its single mesh, and one case per condition.

    <work>/geometry/            body.stl + body.json
    <work>/mesh-<level>/        the mesh case (built once, reused by every condition)
    <work>/conditions/<name>/   one case per condition, result.json when finished
    <work>/conditions-classic/  the same for the classic frame method (never warm-started from hybrid
                                solutions: the two solve for velocities in different frames)
    <work>/conditions-<model>/  the same with another turbulence model than k-omega SST (their fields
                                differ, and a finished result must never stand for another model's);
                                conditions-classic-<model>/ for both
    <work>/conditions-...-limited-grad-p/  the same with the pressure gradient limited
    <work>/conditions-...-grad-U-limited-in-convection/  the same with the velocity gradient limited in the
                                convection scheme only (case/numerics.py), -unlimited-grad-U/ not at all;
                                -SIMPLEC/ with that coupling, -first-order-turbulence/ with the
                                turbulence fields convected first order (case/solver_options.py names them all)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from ..case.solver_options import SolverOptions
from ..geometry import Body, suboff_body
from ..geometry.body import REFERENCE_FILE
from ..geometry.suboff import CONFIGURATIONS
from ..mesh import build_mesh


@dataclass(frozen=True)
class Workspace:
    root: Path
    level: str
    method: str = "hybrid"
    mesh_options: tuple[tuple[str, float | bool], ...] = ()  # MeshDesign fields set by the user, as (name, value)
    solver: SolverOptions = field(default_factory=SolverOptions)  # its choices name the conditions folder

    @property
    def geometry_dir(self) -> Path:
        return self.root / "geometry"

    @property
    def mesh_dir(self) -> Path:
        return self.root / f"mesh-{self.level}"

    def condition_dir(self, name: str) -> Path:
        folder = "conditions" + (f"-{self.method}" if self.method != "hybrid" else "") + self.solver.folder_suffix
        return self.root / folder / name

    def body(self, config: str | None = None, body_dir: str | Path | None = None, write: bool = True) -> Body:
        """The study's body: the one written into this workspace, else a SUBOFF configuration or a body
        directory written by `hydroderiv geometry` (then written here, unless ``write`` is false: reading
        a committed table's body must not create a work directory)."""
        if (self.geometry_dir / REFERENCE_FILE).is_file():
            return Body.read(self.geometry_dir)
        body = Body.read(body_dir) if body_dir else suboff_body(config or "AFF-8")
        if write:
            body.write(self.geometry_dir)
        return body

    def mesh(self, body: Body, log: Callable[[str], None] = print, n_procs: int = 1) -> dict:
        return build_mesh(body, self.level, self.mesh_dir, log=log, options=dict(self.mesh_options), n_procs=n_procs)


def is_suboff(name: str) -> bool:
    return name.upper() in CONFIGURATIONS
