"""The snappyHexMesh dictionary a body gets (written, not run: no OpenFOAM needed)."""

import dataclasses

import pytest
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


def test_without_a_y_shift_the_background_grid_mirrors_about_the_centre_plane(tmp_path):
    """grid_shift_y = 0: the background block spans -h..h in y, so every refinement level mirrors about y = 0;
    x and z stay shifted off the axis."""
    design = MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013)

    def grid(d, name):
        write_mesh_case(tmp_path / name, suboff_body("AFF-8", resolution=0.04), d)
        vertices = FoamFile(tmp_path / name / "system/blockMeshDict")["vertices"]
        return [(min(v[i] for v in vertices), max(v[i] for v in vertices)) for i in range(3)]

    (x0, x1), (y0, y1), (z0, z1) = grid(dataclasses.replace(design, grid_shift_y=0.0), "mirrored")
    assert y0 == pytest.approx(-y1) and y1 == pytest.approx(design.half_width)
    assert z0 == pytest.approx(-design.half_width + design.base_cell / 3)  # the axis stays off grid lines
    (_, _), (y0, y1), (_, _) = grid(design, "default")
    assert y0 == pytest.approx(-design.half_width + design.base_cell / 3)  # default: a third of a cell


def test_a_first_layer_resolving_the_wall_is_admitted_by_the_determinant_limit(tmp_path):
    """snappy refuses cells whose determinant is below minDeterminant; a flat a x a x t cell has about
    27 (t/a)^2. Wall-function layers keep snappy's usual 0.001; a first layer at y+ = 1 needs a lower limit
    that its own cells pass, or snappy drops the layers."""
    design = MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013)
    assert _snappy_dict(tmp_path / "y50", design)["meshQualityControls"]["minDeterminant"] == 0.001
    resolved = dataclasses.replace(design, yplus_target=1.0, max_layers=22)
    limit = _snappy_dict(tmp_path / "y1", resolved)["meshQualityControls"]["minDeterminant"]
    first_cell = 27.0 * (resolved.layers().first_thickness / resolved.hull_cell) ** 2
    assert limit < first_cell < 0.001


def test_thin_parts_can_take_fewer_prism_layers_than_the_hull(tmp_path):
    design = dataclasses.replace(MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013), thin_max_layers=5)
    layers = _snappy_dict(tmp_path, design)["addLayersControls"]["layers"]
    assert layers["hull"]["nSurfaceLayers"] == design.layers().count == 8
    assert layers["sail"]["nSurfaceLayers"] == layers["appendage_port"]["nSurfaceLayers"] == 5


def test_each_part_drops_its_layers_below_a_quarter_of_its_own_stack(tmp_path):
    design = dataclasses.replace(MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013), thin_max_layers=4)
    controls = _snappy_dict(tmp_path, design)["addLayersControls"]
    hull, sail = design.layers_of("hull"), design.layers_of("sail")
    assert sail.first_thickness == hull.first_thickness and sail.count == 4
    assert controls["layers"]["hull"]["minThickness"] == pytest.approx(0.25 * hull.total_thickness, abs=1e-6)
    assert controls["layers"]["sail"]["minThickness"] == pytest.approx(0.25 * sail.total_thickness, abs=1e-6)
    # with the hull's absolute minimum, a 4-layer stack would lose its layers wherever it shrank by a third
    assert controls["layers"]["sail"]["minThickness"] < 0.4 * controls["minThickness"]


def test_relative_layer_sizes_give_each_part_its_absolute_design_on_its_own_cells(tmp_path):
    """relative_layer_sizes: snappy scales every thickness with the local cell, so a part's first layer and
    minimum, times that part's nominal surface cell, must come back to the absolute design."""
    design = MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013)
    absolute = _snappy_dict(tmp_path / "absolute", design)["addLayersControls"]
    relative = _snappy_dict(tmp_path / "relative", dataclasses.replace(design, relative_layer_sizes=True))["addLayersControls"]
    assert absolute["relativeSizes"] is False and relative["relativeSizes"] is True
    hull_cell, thin_cell = design.surface_cell_of("hull"), design.surface_cell_of("sail")
    assert thin_cell == pytest.approx(hull_cell / 2**design.appendage_extra_level)
    assert relative["firstLayerThickness"] * hull_cell == pytest.approx(absolute["firstLayerThickness"], rel=1e-4)
    for part, cell in (("hull", hull_cell), ("sail", thin_cell), ("appendage_top", thin_cell)):
        first = relative["layers"][part].get("firstLayerThickness", relative["firstLayerThickness"])
        assert first * cell == pytest.approx(design.layers_of(part).first_thickness, rel=1e-4)
        assert relative["layers"][part]["minThickness"] * cell == pytest.approx(
            absolute["layers"][part]["minThickness"], rel=1e-3)
        assert relative["layers"][part]["nSurfaceLayers"] == absolute["layers"][part]["nSurfaceLayers"]
    assert 0 < relative["firstLayerThickness"] < relative["layers"]["sail"]["firstLayerThickness"] < 1


def test_the_stern_region_refines_the_aft_part_of_the_body_only_when_asked(tmp_path):
    """stern_extra_level: a cylinder about the x axis from just behind the tail forward over the asked length,
    refined to the hull's level plus the extra levels; at 0 the dictionary has no such region."""
    design = MeshDesign("coarse", 4.261, 0.476, -2.343, 2.013)
    plain = _snappy_dict(tmp_path / "plain", design)
    assert "sternRegion" not in plain["geometry"]
    assert "sternRegion" not in plain["castellatedMeshControls"]["refinementRegions"]
    stern = _snappy_dict(tmp_path / "stern", dataclasses.replace(design, stern_extra_level=2, stern_region_length_L=0.25))
    cylinder = stern["geometry"]["sternRegion"]
    assert cylinder["type"] == "searchableCylinder"
    aft, fore = sorted([cylinder["point1"][0], cylinder["point2"][0]])
    assert aft < design.body_x_min < fore == pytest.approx(design.body_x_min + 0.25 * design.length)
    assert list(cylinder["point1"][1:]) == list(cylinder["point2"][1:]) == [0, 0]
    assert cylinder["radius"] == pytest.approx(design.stern_region_radius_L * design.length)
    region = stern["castellatedMeshControls"]["refinementRegions"]["sternRegion"]
    assert region["mode"] == "inside" and region["levels"][0][1] == design.hull_surface_level + 2


def test_mesh_options_are_checked_and_named(tmp_path):
    from hydroderiv.errors import ConfigurationError
    from hydroderiv.mesh.design import mesh_options

    assert mesh_options({"appendage_extra_level": "1", "yplus_target": 30}) == {"appendage_extra_level": 1, "yplus_target": 30.0}
    with pytest.raises(ConfigurationError, match="unknown mesh option 'appendage_levels'"):
        mesh_options({"appendage_levels": 1})
    with pytest.raises(ConfigurationError, match="thin_max_layers = 2.5.*whole number"):
        mesh_options({"thin_max_layers": 2.5})
    with pytest.raises(ConfigurationError, match="not a number"):
        mesh_options({"sphere_radius_L": "large"})
    with pytest.raises(ConfigurationError, match="unknown mesh option 'length'"):
        mesh_options({"length": 5.0})  # set by the body, not by the user
    assert mesh_options({"interface_on_sphere": "false"}) == {"interface_on_sphere": False}  # --mesh KEY=VALUE
    assert mesh_options({"interface_on_sphere": True}) == {"interface_on_sphere": True}  # a TOML boolean
    with pytest.raises(ConfigurationError, match="interface_on_sphere = 'maybe' must be true or false"):
        mesh_options({"interface_on_sphere": "maybe"})


def test_a_mesh_built_to_another_design_is_not_reused_silently(tmp_path):
    import json

    from hydroderiv.errors import ConfigurationError
    from hydroderiv.mesh import build_mesh
    from hydroderiv.mesh.snappy import REPORT_FILE

    body = suboff_body("AFF-8", resolution=0.04)
    case = tmp_path / "mesh"
    case.mkdir()
    # an older mesh: its report keeps the design it was built to
    (case / REPORT_FILE).write_text(json.dumps({"cells": 1000, "design": {"appendage_extra_level": 1}}))
    with pytest.raises(ConfigurationError, match=r"appendage_extra_level 1 \(asked 2\)"):
        build_mesh(body, "coarse", case, log=lambda m: None)
    # its report predates interface_on_sphere, so it was built with the interface as snapped
    with pytest.raises(ConfigurationError, match=r"interface_on_sphere False \(asked True\)"):
        build_mesh(body, "coarse", case, log=lambda m: None, options={"appendage_extra_level": 1})
    reused = build_mesh(body, "coarse", case, log=lambda m: None,
                        options={"appendage_extra_level": 1, "interface_on_sphere": False})
    assert reused["cells"] == 1000
