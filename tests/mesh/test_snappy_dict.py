"""The snappyHexMesh dictionary a body gets (written, not run: no OpenFOAM needed)."""

import dataclasses

from foamlib import FoamFile

from hydroderiv import suboff_body
from hydroderiv.mesh.design import MeshDesign
from hydroderiv.mesh.snappy import SURFACE, write_mesh_case


def _region_levels(case, design):
    write_mesh_case(case, suboff_body("AFF-8", resolution=0.04), design)
    surfaces = FoamFile(case / "system/snappyHexMeshDict")["castellatedMeshControls"]["refinementSurfaces"]
    regions = surfaces[SURFACE]["regions"]
    return {name: list(regions[name]["level"]) for name in regions}


def test_thin_parts_get_finer_cells_and_curvature_levels_but_the_hull_does_not(tmp_path):
    design = MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013)
    hull = design.hull_surface_level
    fine = hull + design.appendage_extra_level
    curvature = dataclasses.replace(design, thin_curvature_levels=1)
    levels = _region_levels(tmp_path / "curvature", curvature)
    assert levels["hull"] == [hull, hull]
    assert levels["sail"] == levels["appendage_top"] == [fine, fine + 1]
    assert _region_levels(tmp_path / "plain", dataclasses.replace(design, thin_curvature_levels=0))["sail"] == [fine, fine]
