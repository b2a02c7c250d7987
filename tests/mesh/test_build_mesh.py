"""The single mesh, built by real OpenFOAM utilities on the coarse level."""

import json

import pytest

from hydroderiv.mesh import MeshDesign
from hydroderiv.mesh.design import REFINEMENT_RATIO, first_cell_yplus

pytestmark = pytest.mark.openfoam


def test_levels_share_one_refinement_ratio():
    sizes = [MeshDesign(level, 4.261, 0.254, -2.343, 2.013).base_cell for level in ("coarse", "medium", "fine")]
    assert sizes[0] / sizes[1] == pytest.approx(REFINEMENT_RATIO, rel=0.03)
    assert sizes[1] / sizes[2] == pytest.approx(REFINEMENT_RATIO, rel=0.03)


def test_layers_are_sized_for_wall_functions_at_the_design_speed():
    d = MeshDesign("medium", 4.261, 0.254, -2.343, 2.013)
    layers = d.layers()
    assert first_cell_yplus(layers.first_thickness, 3.344, 4.261, d.nu) == pytest.approx(50.0, rel=1e-9)
    assert 30 <= first_cell_yplus(layers.first_thickness, 5.93 * 0.5144, 4.261, d.nu) <= 100


def test_coarse_mesh_passes_the_quality_gate(coarse_bare_hull):
    case, report = coarse_bare_hull
    assert report["checkMesh"]["ok"]
    assert 150_000 <= report["cells"] <= 300_000
    assert json.loads((case / "mesh.json").read_text())["cells"] == report["cells"]
    boundary = (case / "constant/polyMesh/boundary").read_text()
    assert "farfield" in boundary and "hull" in boundary


def test_rotating_zone_is_a_sphere_not_a_staircase(coarse_bare_hull):
    case, report = coarse_bare_hull
    sphere = report["rotating_sphere"]
    assert sphere["faces"] > 5000 and sphere["interface_on_sphere"]
    # every interface face centre lies on the sphere, inside it only by the sagitta of a flat 0.25 m face
    # (0.01 % of the 8.5 m radius; a staircase of those cubes would deviate by up to ~3 %, and snapping
    # alone leaves 0.5 %)
    assert sphere["max_deviation_pct_of_radius"] < 0.05
    # and faces the sphere squarely: snapping alone left them tilted by up to 21 degrees, through which
    # MRF's frame flux disturbed uniform flow (tests/case/test_hybrid_frames.py)
    assert sphere["tilt_deg_max"] < 1.0
    assert "rotatingZone" in (case / "constant/polyMesh/cellZones").read_text()


def test_a_parallel_mesh_is_merged_back_whole(coarse_bare_hull):
    case, report = coarse_bare_hull
    assert {"snappyHexMesh", "reconstructParMesh", "reconstructPar"} <= set(report["timings"])
    assert not list(case.glob("processor*"))
    assert (case / "constant/polyMesh/cellZones").is_file() and report["layer_coverage"]["hull"]["faces"] > 1000


def test_prism_layers_cover_most_of_the_hull(coarse_bare_hull):
    _, report = coarse_bare_hull
    cover = report["layer_coverage"]["hull"]
    assert cover["any_layer_pct"] > 80
    # the profile along the body accounts for every hull face, and the parallel midbody keeps the full stack
    slices = report["layers_along_x"]["hull"]
    assert sum(s["faces"] for s in slices) == cover["faces"]
    assert max(s["mean_layers"] for s in slices) >= 0.9 * cover["layers_wanted"]


def test_a_second_call_reuses_the_mesh(coarse_bare_hull, suboff):
    from hydroderiv.mesh import build_mesh

    case, report = coarse_bare_hull
    messages = []
    again = build_mesh(suboff("AFF-1"), "coarse", case, log=messages.append)
    assert again == report and "reusing" in messages[0]


def test_the_background_grid_keeps_planes_off_the_hull_axis(coarse_bare_hull):
    """Grid planes through the axis made the nose tip a vertex of four layered cells (a blow-up there)."""
    from foamlib import FoamFile

    from hydroderiv.mesh.snappy import GRID_SHIFT

    case, report = coarse_bare_hull
    vertices = FoamFile(case / "system/blockMeshDict")["vertices"]
    low = min(v[1] for v in vertices)
    h0 = report["base_cell_m"]
    for level in range(8):
        cell = h0 / 2**level
        offset = ((0.0 - low) / cell) % 1.0
        assert min(offset, 1 - offset) > 0.3  # y = 0 is never within 30 % of a cell of a grid plane
    assert GRID_SHIFT[1] * h0 == pytest.approx(low + report["design"]["domain_half_width_L"] * 4.261, abs=1e-6)
