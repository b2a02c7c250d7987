"""A real straight-ahead simpleFoam run on the coarse mesh: converge on forces, parse, check physics."""

import json

import pytest

from hydroderiv.case import Condition
from hydroderiv.case.setup import CaseSettings
from hydroderiv.case.solver_options import SolverOptions
from hydroderiv.run.condition import RESULT_FILE, run_condition
from hydroderiv.run.monitor import ConvergenceCriterion

pytestmark = pytest.mark.openfoam


@pytest.fixture(scope="module")
def straight(coarse_bare_hull, tmp_path_factory):
    mesh_case, _ = coarse_bare_hull
    case = tmp_path_factory.mktemp("run") / "straight"
    # the pressure gradient limited during the first-order start only: the converged run is the unlimited one
    settings = CaseSettings(length=4.261, components=("hull",), n_procs=2, max_iterations=600,
                            solver=SolverOptions(limit_pressure_gradient_at_start=True))
    progress = []
    record = run_condition(case, mesh_case, Condition(speed=3.344), settings, ConvergenceCriterion(min_iterations=120),
                           on_progress=progress.append)
    return case, record, progress, settings


def test_drag_has_the_right_sign_and_size(straight):
    _, record, _, _ = straight
    drag = -record["force_N"][0]
    # bare hull at 6.5 kn: ITTC-57 friction alone gives ~95 N on 5.99 m^2, the towing tank ~87 N
    assert 70.0 < drag < 130.0
    assert record["converged"]


def test_no_side_or_vertical_force_at_zero_incidence(straight):
    _, record, _, _ = straight
    drag = -record["force_N"][0]
    assert abs(record["force_N"][1]) < 0.01 * drag
    assert abs(record["force_N"][2]) < 0.01 * drag


def test_forces_stopped_the_run_not_an_iteration_count(straight):
    case, record, progress, settings = straight
    assert 120 <= record["iterations"] < settings.max_iterations
    assert progress and progress[-1].iteration >= 100 and "p" in progress[-1].residuals
    assert record["yplus"]["hull"]["mean"] > 20
    assert record["openfoam_version"]  # provenance: the release that produced the result
    assert record["total_seconds"] > record["wall_seconds"] > 0  # set-up and decomposition come on top


def test_yplus_from_the_wall_shear_matches_the_k_based_one_where_the_boundary_layer_is_in_equilibrium(straight):
    """Along the parallel middle body (1.016 to 3.245 m from the nose, Groves et al. 1989) the boundary layer
    is near equilibrium, u_tau^2 = C_mu^0.5 k in the log layer: the wall law's k-based y+ and the one from
    the wall shear stress agree. At the nose the boundary layer is young and its k has not built up, so the
    k-based y+ reads low there (as in a resolved sublayer, where k falls as y^2)."""
    _, record, _, _ = straight
    slices = record["yplus_along_x"]["hull"]
    middle_body = [s for s in slices if s["x_from"] > 2.013 - 3.245 - 0.05 and s["x_to"] < 2.013 - 1.016]
    assert len(middle_body) >= 3
    for s in middle_body:
        assert 30.0 < s["mean"] < 300.0  # the first cells in the log layer
        assert s["friction_mean"] == pytest.approx(s["mean"], rel=0.05), s
    nose = slices[-1]
    assert nose["friction_mean"] > 1.5 * nose["mean"]


def test_a_cold_start_switches_to_second_order_and_converges_on_it(straight):
    from foamlib import FoamFile

    from hydroderiv.case.numerics import has_second_order_convection

    case, record, _, settings = straight
    assert record["second_order_from"] == settings.first_order_start
    assert has_second_order_convection(case)
    # the limiter of the first-order start went with it
    assert record["limited_pressure_gradient_at_start"] and not record["limited_pressure_gradient"]
    assert "grad(p)" not in FoamFile(case / "system/fvSchemes")["gradSchemes"]
    log = (case / "log.simpleFoam").read_text()
    # simpleFoam picked up the rewritten schemes after the first-order iterations
    assert log.index("Re-reading object fvSchemes") > log.index(f"\nTime = {settings.first_order_start}\n")
    # the averaging window holds second-order iterations only
    assert record["iterations"] >= settings.first_order_start + ConvergenceCriterion().window


def test_a_finished_condition_is_not_recomputed(straight, coarse_bare_hull):
    case, record, _, settings = straight
    before = (case / RESULT_FILE).stat().st_mtime_ns
    again = run_condition(case, coarse_bare_hull[0], Condition(speed=3.344), settings)
    assert again == json.loads((case / RESULT_FILE).read_text()) == record
    assert (case / RESULT_FILE).stat().st_mtime_ns == before


def test_a_warm_start_from_the_converged_solution_stays_on_it(straight, coarse_bare_hull, tmp_path):
    """The spliced binary fields are read by simpleFoam as the solution they came from."""
    import re

    from hydroderiv.case.setup import latest_time_dir

    case, record, _, settings = straight
    warm = run_condition(tmp_path / "warm", coarse_bare_hull[0], Condition(speed=3.344), settings,
                         ConvergenceCriterion(min_iterations=120), warm_start=latest_time_dir(case))
    assert warm["second_order_from"] is None  # a warm start needs no first-order iterations
    assert not warm["limited_pressure_gradient_at_start"]  # nor the start's limiter
    first_ux = float(re.search(r"Solving for Ux, Initial residual = ([^,]+),", (tmp_path / "warm/log.simpleFoam").read_text())[1])
    assert first_ux < 1e-2  # a cold start begins at 1
    assert warm["force_N"][0] == pytest.approx(record["force_N"][0], rel=0.01)


def test_a_diverging_run_is_stopped_and_named(coarse_bare_hull, tmp_path):
    """Sabotaged numerics (no under-relaxation, central convection) must end in a clear divergence error."""
    from foamlib import FoamFile

    from hydroderiv.case.setup import write_condition_case
    from hydroderiv.forces import PrimeScales
    from hydroderiv.run.solver import SolverDivergedError, run_steady

    settings = CaseSettings(length=4.261, components=("hull",), n_procs=1, max_iterations=400)
    case = write_condition_case(tmp_path / "bad", coarse_bare_hull[0], Condition(speed=3.344), settings)
    with FoamFile(case / "system/fvSolution") as f:
        f["relaxationFactors"] = {"fields": {"p": 1.0}, "equations": {"U": 1.0, "k": 1.0, "omega": 1.0}}
    with FoamFile(case / "system/fvSchemes") as f:
        f["divSchemes"]["div(phi,U)"] = ("Gauss", "linear")
    with pytest.raises(SolverDivergedError, match=r"diverged .*(residual|force|floating)"):
        run_steady(case, PrimeScales(998.55, 3.344, 4.261), ("hull",), ConvergenceCriterion(), n_procs=1)


def test_the_boundary_layer_stays_attached_over_the_whole_hull_area(straight, suboff):
    _, record, _, _ = straight
    flow = record["reversed_flow"]["hull"]
    # the snapped wall faces cover the hull the geometry describes
    assert flow["area_m2"] == pytest.approx(suboff("AFF-1").component_areas()["hull"], rel=0.01)
    # a streamlined body of revolution straight ahead: the flow at the wall runs aft almost everywhere
    # (read with the opposite sign of the shear, this would be nearly 100 %)
    assert flow["reversed_pct"] < 1.0


def test_a_record_without_the_wall_reports_gets_them_from_the_saved_solution(straight):
    from hydroderiv.case.setup import latest_time_dir
    from hydroderiv.run.condition import WALL_REPORTS, add_wall_reports, lacking_wall_reports, read_result

    case, record, _, settings = straight
    stripped = {k: v for k, v in record.items() if k not in WALL_REPORTS}  # as a run from before the reports
    (case / RESULT_FILE).write_text(json.dumps(stripped))
    for field in ("wallShearStress", "yPlus"):
        (latest_time_dir(case) / field).unlink()
    try:
        reports = add_wall_reports(case, settings)
        for field in ("wallShearStress", "yPlus"):  # post-processed from the solution
            assert (latest_time_dir(case) / field).is_file()
        flow, made = reports["reversed_flow"]["hull"], record["reversed_flow"]["hull"]
        assert flow["area_m2"] == made["area_m2"]
        assert flow["reversed_pct"] == pytest.approx(made["reversed_pct"], abs=0.05)
        slices, made = reports["yplus_along_x"]["hull"], record["yplus_along_x"]["hull"]
        assert [s["faces"] for s in slices] == [s["faces"] for s in made]
        assert [s["mean"] for s in slices] == pytest.approx([s["mean"] for s in made], rel=0.01)
        assert [s["friction_mean"] for s in slices] == pytest.approx([s["friction_mean"] for s in made], rel=0.01)
        loads, made = reports["loads_along_x"]["hull"], record["loads_along_x"]["hull"]
        assert [s["faces"] for s in loads] == [s["faces"] for s in made]
        # the pressure and the wall shear are those the run wrote: the same loads slice by slice
        assert [s["Y"] for s in loads] == pytest.approx([s["Y"] for s in made], rel=1e-3, abs=1e-9)
        again = read_result(case)
        assert {k: again[k] for k in WALL_REPORTS} == reports and again["coefficients"] == record["coefficients"]
        # y+ slices from before they gave the y+ from the wall shear stress are made again, and only they
        older = {**again, "yplus_along_x": {"hull": [{k: v for k, v in s.items() if not k.startswith("friction")}
                                                     for s in again["yplus_along_x"]["hull"]]}}
        assert lacking_wall_reports(older) == ["yplus_along_x"] and lacking_wall_reports(again) == []
        (case / RESULT_FILE).write_text(json.dumps(older))
        assert add_wall_reports(case, settings)["yplus_along_x"] == again["yplus_along_x"]
    finally:
        (case / RESULT_FILE).write_text(json.dumps(record))


@pytest.fixture(scope="module")
def straight_quadratic(coarse_bare_hull, tmp_path_factory):
    """The same run with Shih's quadratic k-epsilon model (epsilon, its wall function, nonlinear stresses)."""
    mesh_case, _ = coarse_bare_hull
    case = tmp_path_factory.mktemp("run") / "straight-shih"
    settings = CaseSettings(length=4.261, components=("hull",), n_procs=2, max_iterations=600,
                            solver=SolverOptions(turbulence_model="ShihQuadraticKE"))
    return run_condition(case, mesh_case, Condition(speed=3.344), settings, ConvergenceCriterion(min_iterations=120))


def test_the_quadratic_model_converges_to_a_drag_like_the_default_models(straight, straight_quadratic):
    _, sst, _, _ = straight
    drag, drag_sst = -straight_quadratic["force_N"][0], -sst["force_N"][0]
    assert straight_quadratic["converged"]
    # the friction of a streamlined hull hardly depends on the wall-function model: within 15 % of SST's
    assert drag == pytest.approx(drag_sst, rel=0.15)
    assert abs(straight_quadratic["force_N"][1]) < 0.01 * drag and abs(straight_quadratic["force_N"][2]) < 0.01 * drag
    assert straight_quadratic["reversed_flow"]["hull"]["reversed_pct"] < 1.0
