"""The single mesh that serves every condition: design, the meshers (snappyHexMesh, or body-fitted for a
body of revolution) and the quality gate."""

from __future__ import annotations

from pathlib import Path
from typing import Callable, Mapping

from ..geometry import Body
from .design import LEVELS, REFINEMENT_RATIO, MeshDesign
from .quality import MeshQualityError
from .revolution import build_revolution_mesh
from .snappy import build_snappy_mesh


def build_mesh(
    body: Body,
    level: str,
    case: str | Path,
    design_speed: float = 3.344,
    log: Callable[[str], None] = print,
    options: Mapping[str, object] | None = None,
    n_procs: int = 1,
) -> dict:
    """Mesh ``body`` at ``level`` into ``case`` (reusing a finished mesh there) and return its report.

    ``options`` (see :func:`~hydroderiv.mesh.design.mesh_options`) choose the mesher: snappyHexMesh on
    ``n_procs`` ranks (:func:`~hydroderiv.mesh.snappy.build_snappy_mesh`), or with ``mesher = "revolution"``
    the body-fitted mesh of a body of revolution (:func:`~hydroderiv.mesh.revolution.build_revolution_mesh`).
    """
    if (options or {}).get("mesher") == "revolution":
        return build_revolution_mesh(body, level, case, design_speed, log, options)
    return build_snappy_mesh(body, level, case, design_speed, log, options, n_procs)


__all__ = ["LEVELS", "REFINEMENT_RATIO", "MeshDesign", "MeshQualityError", "build_mesh"]
