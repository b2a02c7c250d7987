"""The single mesh that serves every condition: design, snappyHexMesh pipeline and quality gate."""

from .design import LEVELS, REFINEMENT_RATIO, MeshDesign
from .quality import MeshQualityError
from .snappy import build_mesh

__all__ = ["LEVELS", "REFINEMENT_RATIO", "MeshDesign", "MeshQualityError", "build_mesh"]
