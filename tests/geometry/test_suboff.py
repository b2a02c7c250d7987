"""SUBOFF geometry against Groves et al. (1989): the equations, the dimensions and the closed surfaces."""

import numpy as np
import pytest

from hydroderiv.errors import ConfigurationError
from hydroderiv.geometry import CONFIGURATIONS, suboff_body
from hydroderiv.geometry import suboff as s
from hydroderiv.geometry.surfaces import cross_section_areas

FT = s.FOOT


def to_body_x(x_ft):
    return s.MOMENT_CENTRE_FROM_NOSE_M - np.asarray(x_ft) * FT


# --- the equations at the segment joins (the checks printed with the report) ---------------------------
def test_hull_radius_at_the_segment_joins():
    assert s.hull_radius(0.0) == 0.0
    assert s._bow_radius(s.X_FOREBODY_END) == pytest.approx(s.R_MAX, rel=1e-6)
    assert s._afterbody_radius(s.X_PARALLEL_END) == pytest.approx(s.R_MAX, rel=1e-6)
    assert s._afterbody_radius(s.X_AFTERBODY_END) == pytest.approx(0.0979167, rel=1e-5)
    assert s._cap_radius(s.X_AFTERBODY_END) == pytest.approx(0.0979167, rel=1e-5)
    assert s.hull_radius(s.X_CAP_END) == pytest.approx(0.0, abs=1e-3)


def test_hull_radius_is_continuous_and_never_exceeds_rmax():
    assert s.hull_radius(np.linspace(0, s.X_CAP_END, 20001)).max() <= s.R_MAX * (1 + 1e-9)
    for join in (s.X_FOREBODY_END, s.X_PARALLEL_END, s.X_AFTERBODY_END):
        assert s.hull_radius(join - 1e-7) == pytest.approx(s.hull_radius(join + 1e-7), abs=1e-5)


def test_appendage_and_sail_laws():
    assert s.appendage_chord(s.R_MAX) == pytest.approx(0.5, abs=1e-4)  # tip chord
    assert s.appendage_chord(0.271278) == pytest.approx(0.762091, abs=1e-5)  # chord at the TE-station root
    assert s.hull_radius(s.APPENDAGE_TE_X) == pytest.approx(0.271278, abs=1e-5)
    assert s.appendage_half_thickness(1.0) == pytest.approx(0.0, abs=1e-4)  # closed trailing edge
    assert 2 * s.appendage_half_thickness(np.linspace(0, 1, 2001)).max() == pytest.approx(0.20, abs=2e-3)
    assert s.sail_half_thickness(s.SAIL_X_LE) == 0.0 and s.sail_half_thickness(s.SAIL_X_TE) == 0.0
    x = np.linspace(s.SAIL_X_LE, s.SAIL_X_TE, 4001)
    assert s.sail_half_thickness(x).max() == pytest.approx(s.SAIL_Z_MAX, rel=1e-6)
    # forebody and afterbody laws meet the parallel part smoothly
    assert s.sail_half_thickness(s.SAIL_X_FORE_END - 1e-9) == pytest.approx(s.SAIL_Z_MAX, rel=1e-4)
    assert s.sail_half_thickness(s.SAIL_X_PARALLEL_END + 1e-9) == pytest.approx(s.SAIL_Z_MAX, rel=1e-4)


# --- the bare hull ---------------------------------------------------------------------------------------
def test_bare_hull_volume_area_and_centre_of_buoyancy(suboff):
    body = suboff("AFF-1")
    assert body.reference.volume == pytest.approx(0.6992, rel=0.002)
    assert body.reference.wetted_area == pytest.approx(5.988, rel=0.002)
    centroid = body.surface.centroid
    # Groves et al.: centre of buoyancy 2.0086 m aft of the nose, on the axis
    assert s.MOMENT_CENTRE_FROM_NOSE_M - centroid[0] == pytest.approx(2.0086, abs=1e-3)
    assert np.abs(centroid[1:]).max() < 1e-9


def test_bare_hull_sections_match_the_equations_at_the_joins(suboff):
    body = suboff("AFF-1")
    joins_ft = np.array([s.X_FOREBODY_END, s.X_PARALLEL_END, s.X_AFTERBODY_END, 6.0, 12.0])
    areas = cross_section_areas(body.surface, to_body_x(joins_ft))
    expected = np.pi * (s.hull_radius(joins_ft) * FT) ** 2
    np.testing.assert_allclose(areas, expected, rtol=2e-3)


def test_body_axes_and_extent(suboff):
    lo, hi = suboff("AFF-1").surface.bounds
    assert hi[0] == pytest.approx(2.013, abs=1e-6)  # nose forward of the moment centre
    assert lo[0] == pytest.approx(2.013 - 14.291667 * FT, abs=1e-4)
    assert hi[1] == pytest.approx(0.254, rel=2e-3) and lo[1] == pytest.approx(-0.254, rel=2e-3)


# --- every configuration ---------------------------------------------------------------------------------
@pytest.mark.parametrize("config", list(CONFIGURATIONS))
def test_configurations_are_watertight_and_named(suboff, config):
    body = suboff(config)
    assert body.surface.is_watertight()
    assert body.surface.is_consistently_oriented()
    assert body.surface.volume > 0.699
    assert body.component_names == CONFIGURATIONS[config]
    assert set(np.unique(body.face_component)) == set(range(len(body.component_names)))


def _radius(points):
    return np.hypot(points[:, 1], points[:, 2])


def _hull_radius_at(points):
    return s.hull_radius((s.MOMENT_CENTRE_FROM_NOSE_M - points[:, 0]) / FT) * FT


@pytest.mark.parametrize("config", ["AFF-2", "AFF-3", "AFF-8"])
def test_appendages_are_closed_onto_the_hull(suboff, config):
    """The open edge of every appendage lies on the hull, and no part of one lies inside the hull."""
    body = suboff(config)
    for name in body.component_names[1:]:
        part = body.component(name)
        assert not part.is_watertight()  # it shares its junction with the hull
        counts = part.edge_use_counts()
        edges = np.sort(part.faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        uniq, inv = np.unique(edges, axis=0, return_inverse=True)
        boundary = part.vertices[np.unique(uniq[counts == 1])]
        np.testing.assert_allclose(_radius(boundary), _hull_radius_at(boundary), atol=2e-3)
        # every vertex of the appendage is outside or on the hull surface
        assert np.all(_radius(part.vertices) >= _hull_radius_at(part.vertices) - 2e-3)


def test_no_hull_surface_is_left_inside_the_sail(suboff):
    hull = suboff("AFF-2").component("hull").triangles.mean(axis=1)  # face centroids
    x_ft = (s.MOMENT_CENTRE_FROM_NOSE_M - hull[:, 0]) / FT
    inside = (np.abs(hull[:, 1]) < s.sail_half_thickness(x_ft) * FT - 1e-4) & (hull[:, 2] < 0)
    assert not inside.any()
    # ...while the bare hull does have surface there: the union really removed it
    bare = suboff("AFF-1").surface.triangles.mean(axis=1)
    x_ft = (s.MOMENT_CENTRE_FROM_NOSE_M - bare[:, 0]) / FT
    assert ((np.abs(bare[:, 1]) < s.sail_half_thickness(x_ft) * FT - 1e-4) & (bare[:, 2] < 0)).sum() > 10


def test_sail_dimensions(suboff):
    sail = suboff("AFF-8").component("sail").vertices
    assert sail[:, 0].max() == pytest.approx(to_body_x(s.SAIL_X_LE), abs=1e-3)
    assert sail[:, 0].min() == pytest.approx(to_body_x(s.SAIL_X_TE), abs=1e-3)
    assert np.ptp(sail[:, 0]) == pytest.approx(1.208333 * FT, abs=2e-3)  # chord
    assert -sail[:, 2].min() == pytest.approx(1.562501 * FT, abs=1e-3)  # top of the cap, above the axis
    thickness = np.ptp(sail[:, 1])
    assert thickness == pytest.approx(2 * 0.109375 * FT, rel=5e-3)
    assert thickness / np.ptp(sail[:, 0]) == pytest.approx(0.181, abs=2e-3)  # thickness ratio
    assert np.all(sail[:, 2] < 0)  # on top dead centre (z down)


@pytest.mark.parametrize(
    "name, axis, sign", [("appendage_top", 2, -1), ("appendage_bottom", 2, 1), ("appendage_starboard", 1, 1), ("appendage_port", 1, -1)]
)
def test_appendage_dimensions(suboff, name, axis, sign):
    fin = suboff("AFF-8").component(name).vertices
    span = sign * fin[:, axis]
    assert span.max() == pytest.approx(s.R_MAX * FT, abs=1e-4)  # tip at R_max
    assert fin[:, 0].min() == pytest.approx(to_body_x(s.APPENDAGE_TE_X), abs=1e-3)  # trailing edge
    tip = fin[span > s.R_MAX * FT - 1e-6]
    assert np.ptp(tip[:, 0]) == pytest.approx(0.5 * FT, abs=2e-3)  # tip chord
    other = 1 if axis == 2 else 2
    assert np.ptp(tip[:, other]) / np.ptp(tip[:, 0]) == pytest.approx(0.20, abs=5e-3)  # thickness ratio
    # exposed span at the trailing-edge station: from the hull (0.271278 ft) to the tip
    assert (span.max() - span.min()) == pytest.approx(0.562 * FT, abs=3e-3)


def test_resolution_controls_the_triangulation():
    coarse, fine = suboff_body("AFF-1", resolution=0.04), suboff_body("AFF-1", resolution=0.015)
    assert len(fine.surface.faces) > 4 * len(coarse.surface.faces)
    assert coarse.reference.volume == pytest.approx(0.6992, rel=0.002)


@pytest.mark.parametrize("config, resolution, words", [("AFF-9", 0.02, "unknown SUBOFF"), ("AFF-1", 5.0, "resolution")])
def test_bad_configuration_is_named(config, resolution, words):
    with pytest.raises(ConfigurationError, match=words):
        suboff_body(config, resolution=resolution)
