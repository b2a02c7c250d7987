"""The two frame methods: what each writes, and that they describe the same motion of the body."""

import numpy as np
import pytest
from foamlib import FoamFile

from hydroderiv.case import Condition
from hydroderiv.case.frames import frame_setup
from hydroderiv.case.setup import CaseSettings, mesh_cell_count, write_condition_case
from hydroderiv.errors import ConfigurationError

L = 4.261


@pytest.mark.parametrize("kw", [dict(yaw_rate_prime=0.3), dict(yaw_rate_prime=-0.2, drift_deg=6), dict(pitch_rate_prime=0.15, pitch_deg=-5)])
def test_classic_moves_the_body_with_the_velocity_of_the_hybrid_inflow(kw):
    """Classic: the wall velocity at B is Omega x (B - A); it must equal V = -U_inf of the hybrid set-up."""
    c = Condition(speed=3.344, **kw)
    hybrid, classic = frame_setup(c, L, "hybrid"), frame_setup(c, L, "classic")
    np.testing.assert_allclose(np.cross(classic.omega, -classic.origin), -hybrid.farfield_velocity, atol=1e-12)
    np.testing.assert_allclose(classic.omega, hybrid.omega)
    assert classic.whole_domain_rotates and not classic.source.any() and not classic.farfield_velocity.any()
    assert not hybrid.whole_domain_rotates and not hybrid.origin.any()


def test_a_straight_run_is_the_same_translation_in_both_methods():
    c = Condition(speed=3.344, drift_deg=8)
    hybrid, classic = frame_setup(c, L, "hybrid"), frame_setup(c, L, "classic")
    assert not classic.rotating and not classic.whole_domain_rotates
    np.testing.assert_allclose(classic.farfield_velocity, hybrid.farfield_velocity)


def test_classic_refuses_a_helix_and_unknown_methods():
    with pytest.raises(ConfigurationError, match="along the rotation axis"):
        frame_setup(Condition(speed=3.0, yaw_rate_prime=0.2, pitch_deg=5), L, "classic")
    with pytest.raises(ConfigurationError, match="along the rotation axis"):  # a roll is a helix too
        frame_setup(Condition(speed=3.0, roll_rate_prime=0.5), L, "classic")
    with pytest.raises(ConfigurationError, match="unknown frame method 'spinning'"):
        frame_setup(Condition(speed=3.0), L, "spinning")
    with pytest.raises(ConfigurationError, match="unknown frame method"):
        CaseSettings(length=L, components=(), method="spinning")


def _fake_mesh(tmp_path, n_cells=7):
    mesh = tmp_path / "mesh"
    poly = mesh / "constant/polyMesh"
    poly.mkdir(parents=True)
    (poly / "owner").write_text(f'FoamFile\n{{\n    note "nPoints:20  nCells:{n_cells}  nFaces:30  nInternalFaces:9";\n}}\n')
    (poly / "cellZones").write_text("the sphere only\n")
    (poly / "points").write_text("shared\n")
    return mesh


def test_classic_case_rotates_every_cell_and_keeps_the_far_field_still(tmp_path):
    mesh = _fake_mesh(tmp_path)
    assert mesh_cell_count(mesh / "constant/polyMesh") == 7
    settings = CaseSettings(length=L, components=("hull",), method="classic")
    case = write_condition_case(tmp_path / "classic", mesh, Condition(3.344, yaw_rate_prime=0.25), settings)
    poly = case / "constant/polyMesh"
    assert (poly / "points").is_symlink() and not (poly / "cellZones").is_symlink()
    [(name, zone)] = FoamFile(poly / "cellZones")[None]
    assert name == "rotatingZone" and list(zone["cellLabels"][-1]) == list(range(7))
    mrf = FoamFile(case / "constant/MRFProperties")["rotatingFrame"]
    assert list(mrf["nonRotatingPatches"]) == ["farfield"]
    np.testing.assert_allclose(mrf["origin"], [0, L / 0.25, 0])
    assert FoamFile(case / "constant/fvOptions")["hybridFramesSource"]["active"] is False
    # the hybrid case of the same condition links the shared mesh whole
    hybrid = write_condition_case(tmp_path / "hybrid", mesh, Condition(3.344, yaw_rate_prime=0.25), CaseSettings(length=L, components=("hull",)))
    assert (hybrid / "constant/polyMesh").is_symlink()
