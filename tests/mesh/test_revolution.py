"""The body-fitted mesh of a body of revolution (SUBOFF's bare hull): shape and validity of its grid."""

import numpy as np
import pytest

from hydroderiv.errors import ConfigurationError
from hydroderiv.geometry.suboff import FOOT, MOMENT_CENTRE_FROM_NOSE_M, hull_radius
from hydroderiv.mesh.design import mesh_options
from hydroderiv.mesh.polymesh import hex_faces
from hydroderiv.mesh.revolution import (Fins, Profile, RevolutionDesign, classify_boundary_faces, meridian_grid,
                                        revolution_points_and_cells)

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


def assert_symmetric_closed_and_positive(points, cells) -> np.ndarray:
    """Check the grid of a symmetric body; return its boundary faces."""
    # a symmetric body must not see a lopsided grid: every point has its mirror images in y and in z
    rounded = {tuple(p) for p in np.round(points, 9).tolist()}
    for mirror in ([1, -1, 1], [1, 1, -1]):
        assert {tuple(p) for p in np.round(points * mirror, 9).tolist()} == rounded
    faces = hex_faces(points, cells)
    boundary, _ = faces["boundary"]
    assert cell_volumes(points, cells, faces).min() > 0
    area = face_flux(points, boundary)[1]
    assert np.abs(area.sum(axis=0)).max() < 1e-9 * np.abs(area).sum()  # the boundary is closed
    return boundary


def test_the_mesh_is_mirror_symmetric_closed_and_every_cell_has_a_positive_volume(profile):
    design = RevolutionDesign("coarse", L, yplus_target=50)
    points, cells, surfaces, shape = revolution_points_and_cells(profile, design, lambda s: MOMENT_CENTRE_FROM_NOSE_M - s)
    boundary = assert_symmetric_closed_and_positive(points, cells)
    # the hull's faces enclose the volume of the profile revolved (with polygonal sections)
    assert list(surfaces) == ["hull"]
    on_hull = np.isin(boundary, surfaces["hull"]).all(axis=1)
    hull_volume = -face_flux(points, boundary[on_hull])[0].sum()
    s = np.linspace(0.0, profile.s[-1], 20001)
    exact = np.trapezoid(np.pi * np.interp(s, profile.s, profile.rho) ** 2, s)
    n = shape["around"]
    polygon = exact * n * np.sin(2 * np.pi / n) / (2 * np.pi)  # the grid's sections are n-gons
    assert hull_volume == pytest.approx(polygon, rel=0.003)


def test_the_fins_section_is_suboffs_and_vanishes_off_the_fin():
    fins = Fins.suboff()
    c_root = float(fins.chord(0.1))
    s = fins.trailing_edge - c_root * (1.0 - np.linspace(0.0, 1.0, 2001))
    h = fins.half_thickness(s, np.full_like(s, 0.1))
    assert 2 * h.max() / c_root == pytest.approx(0.20, abs=0.002)  # NACA 0020: 20 % thick
    assert h[0] == 0.0 and h[-1] == pytest.approx(0.0, abs=1e-5 * c_root)  # closed at both edges
    off = [(fins.trailing_edge + 0.01, 0.1), (fins.trailing_edge - c_root - 0.01, 0.1),
           (fins.trailing_edge - 0.05, fins.tip_radius + 0.001)]
    for s_off, y_off in off:
        assert fins.half_thickness(np.array([s_off]), np.array([y_off]))[0] == 0.0
    # trimmed by half a step, a point just inside the tip counts as off the fin
    assert fins.half_thickness(np.array([fins.trailing_edge - 0.05]), np.array([fins.tip_radius - 0.002]),
                               span_trim=0.005)[0] == 0.0
    assert fins.names == ("appendage_starboard", "appendage_bottom", "appendage_port", "appendage_top")


def test_over_the_fins_the_grid_is_fine_and_has_lines_on_their_edges(profile):
    design = RevolutionDesign("coarse", L, yplus_target=50)
    fins = Fins.suboff()
    grid = meridian_grid(profile, design, fins)
    sp = design.spacing
    lo, hi = fins.footprint()
    edge_s = grid.s[grid.nose: grid.tail + 1, 0]
    over = (edge_s >= lo) & (edge_s <= hi)
    assert over.sum() > 30 and np.diff(edge_s)[over[:-1]].max() <= sp["fin_cell"] * 1.001
    # away from the wall, on every line, steps no longer than span_cell out to span_reach
    away = np.hypot(np.diff(grid.s, axis=1), np.diff(grid.rho, axis=1))
    reach = np.cumsum(away, axis=1)
    body = slice(grid.nose, grid.tail)
    assert away[body][reach[body] <= design.span_reach].max() <= sp["span_cell"] * 1.05
    # on every line that crosses the fins one node is on the leading edge and one on the trailing edge,
    # each a fine step from the next
    crossing = np.flatnonzero((fins.half_angle(grid.s, grid.rho, sp["span_cell"]) > 0).any(axis=0))
    assert len(crossing) > 10
    for j in crossing:
        s, rho = grid.s[grid.nose: grid.tail, j], grid.rho[grid.nose: grid.tail, j]
        for gap in (s - (hi - fins.chord(np.minimum(rho, fins.tip_radius))), s - hi):
            at = np.argmin(np.abs(gap))
            assert abs(gap[at]) < 1e-6 and s[at + 1] - s[at] <= 2.5 * sp["fin_edge_cell"]
    plain = meridian_grid(profile, design)  # without fins the steps grow all the way
    assert plain.s.shape[1] < grid.s.shape[1]


@pytest.fixture(scope="module")
def finned(profile):
    design = RevolutionDesign("coarse", L, yplus_target=50)
    fins = Fins.suboff()
    points, cells, surfaces, shape = revolution_points_and_cells(
        profile, design, lambda s: MOMENT_CENTRE_FROM_NOSE_M - s, fins)
    return fins, points, cells, surfaces, shape


def test_the_finned_mesh_is_closed_mirror_symmetric_and_every_cell_has_a_positive_volume(finned):
    fins, points, cells, surfaces, shape = finned
    assert shape["around"] == 4 * 16
    assert_symmetric_closed_and_positive(points, cells)  # hull, fins and far field close the domain


def test_each_fin_is_a_patch_with_suboffs_planform(finned):
    fins, points, cells, surfaces, shape = finned
    boundary, _ = hex_faces(points, cells)["boundary"]
    patch = classify_boundary_faces(boundary, surfaces, len(points))
    names = ["farfield", *surfaces]
    # the exposed planform: between the hull and the tip, over the chord at each distance from the axis
    s, y = np.meshgrid(np.linspace(3.6, 4.1, 2001), np.linspace(0.0, fins.tip_radius, 1001), indexing="ij")
    on_fin = fins.half_thickness(s, y) > 0
    hull = Profile.suboff()
    exposed = on_fin & (y > np.interp(s, hull.s, hull.rho))
    planform = exposed.sum() * (s[1, 0] - s[0, 0]) * (y[0, 1] - y[0, 0])
    counts = set()
    for n, (name, angle) in enumerate(zip(fins.names, fins.angles_deg)):
        faces = boundary[patch == names.index(name)]
        counts.add(len(faces))
        area = face_flux(points, faces)[1]
        normal = np.array([0.0, -np.sin(np.radians(angle)), np.cos(np.radians(angle))])  # of its mid-plane
        across = area @ normal
        assert abs(across.sum()) < 1e-9 * np.abs(across).sum()  # its two sides mirror each other
        assert np.abs(across).sum() / 2 == pytest.approx(planform, rel=0.03)
    assert len(counts) == 1  # four identical fins


def test_a_study_asks_for_the_body_fitted_mesher_and_its_own_options_only():
    assert mesh_options({"mesher": "revolution", "yplus_target": "1"}) == {"mesher": "revolution", "yplus_target": 1.0}
    assert mesh_options({"mesher": "revolution", "sector_cells": "24"}) == {"mesher": "revolution", "sector_cells": 24}
    with pytest.raises(ConfigurationError, match="whole number"):
        mesh_options({"mesher": "revolution", "sector_cells": 20.5})
    assert RevolutionDesign("coarse", L, sector_cells=24).spacing["sector"] == 24
    assert RevolutionDesign("coarse", L, span_cell=0.007).spacing["span_cell"] == 0.007
    with pytest.raises(ConfigurationError, match="span_cell"):
        RevolutionDesign("coarse", L, span_cell=1.0)
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
        build_revolution_mesh(suboff_body("AFF-8", resolution=0.05), "coarse", tmp_path / "other", log=lambda _: None)
