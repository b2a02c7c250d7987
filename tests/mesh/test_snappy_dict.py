"""The snappyHexMesh dictionary a body gets (written, not run: no OpenFOAM needed)."""

import dataclasses

from foamlib import FoamFile

from hydroderiv import suboff_body
from hydroderiv.mesh.design import MeshDesign
from hydroderiv.mesh.snappy import SURFACE, write_mesh_case


def _snappy_dict(case, design):
    write_mesh_case(case, suboff_body("AFF-8", resolution=0.04), design)
    return FoamFile(case / "system/snappyHexMeshDict")


def _region_levels(case, design):
    regions = _snappy_dict(case, design)["castellatedMeshControls"]["refinementSurfaces"][SURFACE]["regions"]
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


def test_thin_parts_can_take_fewer_prism_layers_than_the_hull(tmp_path):
    design = dataclasses.replace(MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013), thin_max_layers=5)
    layers = _snappy_dict(tmp_path, design)["addLayersControls"]["layers"]
    assert layers["hull"]["nSurfaceLayers"] == design.layers().count == 8
    assert layers["sail"]["nSurfaceLayers"] == layers["appendage_port"]["nSurfaceLayers"] == 5
