"""The body-fitted mesh of a body of revolution (SUBOFF's bare hull): shape and validity of its grid."""

import numpy as np
import pytest

from hydroderiv.errors import ConfigurationError
from hydroderiv.geometry.suboff import FOOT, MOMENT_CENTRE_FROM_NOSE_M, hull_radius
from hydroderiv.mesh.design import mesh_options
from hydroderiv.mesh.polymesh import hex_faces
from hydroderiv.mesh.revolution import Profile, RevolutionDesign, meridian_grid, revolution_points_and_cells

from .test_polymesh import cell_volumes, face_flux

L = 4.261


@pytest.fixture(scope="module")
def profile():
    return Profile.suboff()


@pytest.mark.parametrize("yplus", [1.0, 50.0])
def test_the_meridian_grid_has_no_folded_cell_and_its_inner_edge_lies_on_the_hull(profile, yplus):
    design = RevolutionDesign("coarse", L, yplus_target=yplus)
    grid = meridian_grid(profile, design)
    p = np.stack([grid.s, grid.rho], axis=-1)
    corners = [(p[1:, :-1], p[:-1, :-1], p[1:, 1:]), (p[1:, 1:], p[1:, :-1], p[:-1, 1:]),
               (p[:-1, 1:], p[1:, 1:], p[:-1, :-1]), (p[:-1, :-1], p[:-1, 1:], p[1:, :-1])]
    for corner, a, b in corners:  # every corner of every cell turns the same way
        u, v = a - corner, b - corner
        assert np.all(u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0] != 0)
    signs = [np.sign((a - c)[..., 0] * (b - c)[..., 1] - (a - c)[..., 1] * (b - c)[..., 0]) for c, a, b in corners]
    assert np.all(np.array(signs) == signs[0][0, 0])
    on_body = slice(grid.nose, grid.tail + 1)
    assert grid.rho[on_body, 0] == pytest.approx(hull_radius(grid.s[on_body, 0] / FOOT) * FOOT, abs=2e-4)
    assert np.all(grid.rho[: grid.nose + 1, 0] == 0) and np.all(grid.rho[grid.tail:, 0] == 0)  # the axis
    # the first cell on the hull is sized for the wall treatment asked for
    first = np.hypot(grid.s[on_body, 1] - grid.s[on_body, 0], grid.rho[on_body, 1] - grid.rho[on_body, 0])
    assert first == pytest.approx(design.wall_cell, rel=0.02)


def test_the_mesh_is_mirror_symmetric_closed_and_every_cell_has_a_positive_volume(profile):
    design = RevolutionDesign("coarse", L, yplus_target=50)
    points, cells, hull, shape = revolution_points_and_cells(profile, design, lambda s: MOMENT_CENTRE_FROM_NOSE_M - s)
    # a symmetric body must not see a lopsided grid: every point has its mirror images in y and in z
    rounded = {tuple(p) for p in np.round(points, 9).tolist()}
    for mirror in ([1, -1, 1], [1, 1, -1]):
        assert {tuple(p) for p in np.round(points * mirror, 9).tolist()} == rounded
    faces = hex_faces(points, cells)
    boundary, _ = faces["boundary"]
    assert cell_volumes(points, cells, faces).min() > 0
    area_b = face_flux(points, boundary)[1]
    assert np.abs(area_b.sum(axis=0)).max() < 1e-9 * np.abs(area_b).sum()  # the boundary is closed
    # the hull's faces enclose the volume of the profile revolved (with polygonal sections)
    on_hull = np.isin(boundary, hull).all(axis=1)
    hull_volume = -face_flux(points, boundary[on_hull])[0].sum()
    s = np.linspace(0.0, profile.s[-1], 20001)
    exact = np.trapezoid(np.pi * np.interp(s, profile.s, profile.rho) ** 2, s)
    n = shape["around"]
    polygon = exact * n * np.sin(2 * np.pi / n) / (2 * np.pi)  # the grid's sections are n-gons
    assert hull_volume == pytest.approx(polygon, rel=0.003)


def test_a_study_asks_for_the_body_fitted_mesher_and_its_own_options_only():
    assert mesh_options({"mesher": "revolution", "yplus_target": "1"}) == {"mesher": "revolution", "yplus_target": 1.0}
    with pytest.raises(ConfigurationError, match="max_layers"):
        mesh_options({"mesher": "revolution", "max_layers": 3})
    with pytest.raises(ConfigurationError, match="unknown mesher"):
        mesh_options({"mesher": "gmsh"})
    with pytest.raises(ConfigurationError, match="outside"):
        RevolutionDesign("coarse", L, yplus_target=1000)


@pytest.mark.openfoam
def test_the_body_fitted_bare_hull_passes_checkmesh_and_is_reused_only_for_its_own_design(tmp_path):
    from hydroderiv.geometry import suboff_body
    from hydroderiv.mesh.revolution import build_revolution_mesh

    body = suboff_body("AFF-1", resolution=0.05)
    case = tmp_path / "mesh"
    report = build_revolution_mesh(body, "coarse", case, log=lambda _: None, options={"yplus_target": 50})
    assert report["checkMesh"]["ok"] and report["cells"] > 100_000
    sphere = report["rotating_sphere"]
    assert 0 < sphere["zone_cells"] < report["cells"]
    # a staircase about the sphere, within a far-field cell of it; the report gives its faces' tilt
    assert sphere["max_deviation_pct_of_radius"] < 15 and "tilt_deg_max" in sphere
    boundary = (case / "constant/polyMesh/boundary").read_text()
    assert "hull" in boundary and "bodyWalls" in boundary and "farfield" in boundary
    assert build_revolution_mesh(body, "coarse", case, log=lambda _: None,
                                 options={"yplus_target": 50})["cells"] == report["cells"]
    with pytest.raises(ConfigurationError, match="another design"):
        build_revolution_mesh(body, "coarse", case, log=lambda _: None, options={"yplus_target": 1})
    with pytest.raises(ConfigurationError, match="bare hull"):
        build_revolution_mesh(suboff_body("AFF-3", resolution=0.05), "coarse", tmp_path / "other", log=lambda _: None)
