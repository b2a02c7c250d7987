"""The hybrid reference frames on a real mesh: uniform flow is an exact solution in both zones.

With no body, a turn combined with drift and pitch must leave the free stream uniform: MRF in the sphere
adds Omega x U, the momentum source removes it (Delta/rho = Omega x U_inf). So must a roll combined with
drift, whose Omega lies along the body's axis. Without the source the same run is visibly wrong, which
shows the test can fail.
"""

import numpy as np
import pytest
from foamlib import FoamFieldFile

from hydroderiv.case import Condition
from hydroderiv.case.setup import CaseSettings, latest_time_dir, write_condition_case
from hydroderiv.mesh import MeshDesign
from hydroderiv.mesh.snappy import build_empty_domain
from hydroderiv.run.openfoam import run_application

pytestmark = pytest.mark.openfoam

L = 4.261
CONDITION = Condition(speed=3.344, drift_deg=6.0, pitch_deg=-4.0, yaw_rate_prime=0.3)
ROLL = Condition(speed=3.344, drift_deg=6.0, roll_rate_prime=0.5)


@pytest.fixture(scope="module")
def empty_domain(tmp_path_factory, openfoam):
    case = tmp_path_factory.mktemp("empty") / "domain"
    build_empty_domain(case, MeshDesign("coarse", L, 0.254, -2.343, 2.013), log=lambda m: None)
    return case


def _deviation(mesh_case, case_dir, source_active: bool, condition: Condition = CONDITION):
    # second-order convection throughout, as in every validation run (no first-order start: this run is
    # driven for a fixed count, not through run_steady, which would switch the schemes)
    settings = CaseSettings(length=L, components=(), n_procs=2, max_iterations=60, first_order_start=0)
    case = write_condition_case(case_dir, mesh_case, condition, settings)
    if not source_active:
        from foamlib import FoamFile

        with FoamFile(case / "constant/fvOptions") as f:
            f["hybridFramesSource"]["active"] = False
    run_application(case, ["decomposePar", "-force"], log_name="decomposePar")
    run_application(case, ["simpleFoam"], n_procs=2)
    run_application(case, ["reconstructPar", "-latestTime"], log_name="reconstructPar")
    run_application(case, ["postProcess", "-func", "writeCellCentres", "-latestTime"], log_name="cellCentres")
    latest = latest_time_dir(case)
    velocity = np.asarray(FoamFieldFile(latest / "U").internal_field, dtype=float)
    centres = np.asarray(FoamFieldFile(latest / "C").internal_field, dtype=float)
    radius = np.linalg.norm(centres, axis=1)
    error = np.linalg.norm(velocity - condition.inflow(), axis=1) / condition.speed
    core = radius < 1.5 * L  # the body, its near field and its near wake
    return float(error[core].max()), float(error[radius < 2 * L].max())


def test_uniform_flow_stays_uniform_with_turn_drift_and_pitch(empty_domain, tmp_path):
    core, sphere = _deviation(empty_domain, tmp_path / "hybrid", source_active=True)
    assert core < 0.005
    # The target: 1 % of U over the whole sphere. Measured here: 0.06 %, largest next to the
    # interface, where |Omega x r| = 0.6 U. With the interface as snapped (faces tilted by up to 21
    # degrees from the sphere) it was 2.6 %: the test below shows that this bound can fail.
    assert sphere < 0.01


def test_uniform_flow_stays_uniform_in_a_roll_with_drift(empty_domain, tmp_path):
    """p' = 0.5 about the x axis through B, with 6 degrees of drift, so that the source is not zero: at the
    sphere's edge the frame moves at U sideways."""
    core, sphere = _deviation(empty_domain, tmp_path / "roll", source_active=True, condition=ROLL)
    assert core < 0.005 and sphere < 0.01


def test_an_interface_left_as_snapped_disturbs_uniform_flow(tmp_path_factory, openfoam):
    case = tmp_path_factory.mktemp("snapped") / "domain"
    build_empty_domain(case, MeshDesign("coarse", L, 0.254, -2.343, 2.013, interface_on_sphere=False),
                       log=lambda m: None)
    _, sphere = _deviation(case, tmp_path_factory.mktemp("snapped-run") / "hybrid", source_active=True)
    assert sphere > 0.01


def test_without_the_source_the_stream_is_deflected(empty_domain, tmp_path):
    core, _ = _deviation(empty_domain, tmp_path / "no-source", source_active=False)
    assert core > 0.05
