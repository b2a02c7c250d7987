"""Study files: what they describe, and clear errors for what they get wrong."""

from pathlib import Path

import pytest

from hydroderiv.case import KNOT, Condition
from hydroderiv.errors import ConfigurationError
from hydroderiv.studies.study import Study, run_order, warm_start_candidates

GOOD = """
[study]
body = "aff-8"
level = "coarse"
speed_knots = 6.5
work = "WORK"

[sweeps]
drift_deg = [-4, 4, 8]
yaw_rate_prime = [0.1, -0.1]

[[conditions]]
drift_deg = 4
yaw_rate_prime = 0.1

[convergence]
rel_tol = 0.01
"""


def write(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text(text.replace("WORK", str(tmp_path / "work")))
    return path


def test_a_study_lists_straight_ahead_sweeps_and_extras(tmp_path):
    study = Study.load(write(tmp_path, GOOD))
    assert study.body == "AFF-8" and study.speed == pytest.approx(6.5 * KNOT)
    assert len(study.conditions) == 1 + 3 + 2 + 1
    assert study.criterion.rel_tol == 0.01
    assert all(s["left"] for s in [study.status()]) and len(study.status()["left"]) == 7


def test_the_fit_model_is_read_from_the_study_file(tmp_path):
    assert (Study.load(write(tmp_path, GOOD)).nonlinear, Study.load(write(tmp_path, GOOD)).fit_offset) == ("abs", True)
    study = Study.load(write(tmp_path, GOOD + '\n[fit]\nnonlinear = "none"\noffset = false\n'))
    assert study.nonlinear == "none" and study.fit_offset is False and study.max_angle_deg is None
    assert Study.load(write(tmp_path, GOOD + "\n[fit]\nmax_angle_deg = 4\n")).max_angle_deg == 4.0


def test_run_order_starts_straight_and_moves_outward():
    cs = (Condition(3, drift_deg=8), Condition(3), Condition(3, drift_deg=-4), Condition(3, yaw_rate_prime=0.3),
          Condition(3, roll_rate_prime=0.5))
    order = run_order(cs)
    assert order[0] == Condition(3) and order[1] == Condition(3, drift_deg=-4)
    assert order[-1] == Condition(3, roll_rate_prime=0.5)  # a roll sits at its own distance, p' = 0.5


def test_a_roll_sweep_is_read_from_the_study_file(tmp_path):
    study = Study.load(write(tmp_path, GOOD.replace("[sweeps]", "[sweeps]\nroll_rate_prime = [-0.5, 0.5]")))
    rolls = [c for c in study.conditions if c.roll_rate_prime]
    assert sorted(c.roll_rate_prime for c in rolls) == [-0.5, 0.5] and len(study.conditions) == 9


@pytest.mark.parametrize(
    "text, words",
    [
        (GOOD.replace('body = "aff-8"', 'body = "AFF-7"'), "unknown configuration"),
        (GOOD.replace("speed_knots = 6.5", ""), "speed"),
        (GOOD.replace("drift_deg = [-4, 4, 8]", "roll_deg = [4]"), "unknown sweep 'roll_deg'"),
        (GOOD.replace("drift_deg = [-4, 4, 8]", "drift_deg = [45]"), "drift angle 45"),
        (GOOD.replace("yaw_rate_prime = [0.1, -0.1]", "yaw_rate_prime = [3.0]"), "impossible"),
        (GOOD.replace("rel_tol", "tolerance"), "unknown convergence keys"),
        (GOOD + 'monitored = ["X", "lift"]\n', r"s\.toml: \[convergence\] unknown load coefficient\(s\) lift"),
        (GOOD.replace('level = "coarse"', 'level = "coarse"\nmethod = "rotating"'), "unknown method 'rotating'"),
        (GOOD.replace('level = "coarse"', 'level = "coarse"\nspeed_kn = 6'), r"unknown \[study\] key\(s\) speed_kn"),
        (GOOD + '\n[fit]\nnonlinear = "quadratic"\n', "unknown nonlinear term 'quadratic'"),
        (GOOD + "\n[fit]\nslope_only = true\n", r"unknown \[fit\] keys slope_only"),
        (GOOD + "\n[fit]\nmax_angle_deg = -4\n", "max_angle_deg = -4 must be a positive angle"),
        (GOOD + '\n[fit]\nmax_angle_deg = "small"\n', "max_angle_deg = 'small' must be a positive angle"),
        (GOOD.replace('level = "coarse"', 'level = "coarse"\nturbulence_model = "kEpsilonQCR"'), r"\.toml: unknown turbulence model 'kEpsilonQCR'"),
        (GOOD.replace('level = "coarse"', 'level = "coarse"\nlimit_pressure_gradient = "yes"'),
         "limit_pressure_gradient = 'yes' must be true, false or \"start\""),
        (GOOD.replace('level = "coarse"', 'level = "coarse"\nlimit_velocity_gradient = "sometimes"'),
         r"\.toml: limit_velocity_gradient = 'sometimes' must be one of 'everywhere', 'convection', 'nowhere'"),
        (GOOD.replace('level = "coarse"', 'level = "coarse"\npressure_velocity_coupling = "PISO"'),
         r"\.toml: pressure_velocity_coupling = 'PISO' must be one of 'SIMPLE', 'SIMPLEC'"),
        ("[study\nbody=", "not valid TOML"),
    ],
)
def test_mistakes_are_named(tmp_path, text, words):
    with pytest.raises(ConfigurationError, match=words):
        Study.load(write(tmp_path, text))


def test_status_tells_running_from_left(tmp_path):
    import os

    from hydroderiv.studies.study import running_marker

    study = Study.load(write(tmp_path, GOOD))
    case = study.workspace.condition_dir(study.conditions[1].name)
    case.parent.mkdir(parents=True)
    running_marker(case).write_text(str(os.getpid()))  # a live process
    assert study.status()["running"] == [study.conditions[1].name]
    running_marker(case).write_text("999999999")  # a process that is gone
    assert study.status()["running"] == []


def test_a_classic_study_shares_the_straight_runs_and_keeps_its_turns_apart(tmp_path):
    hybrid = Study.load(write(tmp_path, GOOD))
    classic = Study.load(write(tmp_path, GOOD.replace('level = "coarse"', 'level = "coarse"\nmethod = "classic"')))
    straight, drift, turn = Condition(hybrid.speed), Condition(hybrid.speed, drift_deg=4), Condition(hybrid.speed, yaw_rate_prime=0.1)
    assert classic.case_dir(straight) == hybrid.case_dir(straight)
    assert classic.case_dir(drift) == hybrid.case_dir(drift)
    assert classic.case_dir(turn) != hybrid.case_dir(turn) and classic.case_dir(turn).parent.name == "conditions-classic"
    # a classic turn holds the fluid at rest far away: no start for a drift run, nor a drift run for a turn
    finished = {classic.case_dir(c): c for c in (drift, turn)}
    other_turn = Condition(hybrid.speed, yaw_rate_prime=0.2)
    assert warm_start_candidates(classic, Condition(hybrid.speed, drift_deg=8), finished) == {classic.case_dir(drift): drift}
    assert warm_start_candidates(classic, other_turn, finished) == {classic.case_dir(turn): turn}
    assert warm_start_candidates(hybrid, other_turn, finished) == finished


@pytest.mark.parametrize("path", sorted((Path(__file__).parents[2] / "studies").glob("*.toml")), ids=lambda p: p.name)
def test_every_committed_study_file_loads(path):
    study = Study.load(path)
    # straight ahead first (a study of it alone checks the resistance), each condition once
    assert study.conditions[0] == Condition(study.speed) and len(set(study.conditions)) == len(study.conditions)


def test_a_retried_condition_warm_starts_from_conditions_finished_by_an_earlier_run(tmp_path, monkeypatch):
    """The solver is replaced by a stand-in that writes a result: this checks the study's bookkeeping."""
    import json

    import hydroderiv.studies.study as study_module
    from hydroderiv.run.solver import SolverDivergedError

    study = Study.load(write(tmp_path, GOOD))
    monkeypatch.setattr(study_module.Workspace, "body", lambda self, *a, **k: None)
    monkeypatch.setattr(study_module.Workspace, "mesh", lambda self, *a, **k: {})
    monkeypatch.setattr(study_module.Study, "case_settings", lambda self, body: None)
    starts, failing = {}, {Condition(study.speed).name}

    held = {}

    def stand_in(case, mesh, condition, settings, criterion, warm_start=None, on_progress=None):
        starts[condition.name] = warm_start
        held[condition.name] = criterion.own_scale
        if condition.name in failing:
            raise SolverDivergedError(f"{condition.name} diverged")
        (case / "100").mkdir()
        (case / "100/U").write_text("solution")
        result = {"converged": True, "iterations": 100, "wall_seconds": 1.0}
        (case / "result.json").write_text(json.dumps(result))
        return result

    monkeypatch.setattr(study_module, "run_condition", stand_in)
    straight = Condition(study.speed).name
    study_module.run_study(study, log=lambda m: None)
    assert starts[straight] is None  # nothing had finished yet: a cold start, and it fails
    # each condition's derivative-giving loads settle to their own size; straight ahead keeps the load scale
    assert held[straight] == () and held[Condition(study.speed, drift_deg=4).name] == ("Y", "N")
    assert held[Condition(study.speed, yaw_rate_prime=-0.1).name] == ("Y", "N")
    assert study.criterion.rel_tol == 0.01 and study.criterion_for(Condition(study.speed, drift_deg=4)).rel_tol == 0.01
    assert study.status()["failed"] == [straight]

    failing.clear()
    starts.clear()
    study_module.run_study(study, log=lambda m: None)
    assert list(starts) == [straight]  # finished conditions are read back, not rerun
    # retried from the nearest finished condition (drift -4 or +4 deg), not from rest
    assert starts[straight] is not None and starts[straight].parent.name in ("U3.34389_b-4_a0_r0_q0", "U3.34389_b+4_a0_r0_q0")


def test_the_mesh_table_sets_mesh_options_for_every_condition(tmp_path):
    study = Study.load(write(tmp_path, GOOD + "\n[mesh]\nappendage_extra_level = 1\nthin_max_layers = 8\n"))
    assert dict(study.mesh_options) == {"appendage_extra_level": 1, "thin_max_layers": 8}
    assert dict(study.workspace.mesh_options) == dict(study.mesh_options)
    with pytest.raises(ConfigurationError, match="unknown mesh option 'layers'"):
        Study.load(write(tmp_path, GOOD + "\n[mesh]\nlayers = 3\n"))


@pytest.mark.parametrize(
    "lines, folder, setting, value, default",
    [
        ('turbulence_model = "ShihQuadraticKE"', "conditions-ShihQuadraticKE", "turbulence_model", "ShihQuadraticKE",
         "kOmegaSST"),
        ("limit_pressure_gradient = true", "conditions-limited-grad-p", "limit_pressure_gradient", True, False),
        ('limit_velocity_gradient = "convection"\nlimit_pressure_gradient = true',
         "conditions-limited-grad-p-grad-U-limited-in-convection", "limit_velocity_gradient", "convection", "everywhere"),
        ('pressure_velocity_coupling = "SIMPLEC"', "conditions-SIMPLEC", "pressure_velocity_coupling", "SIMPLEC", "SIMPLE"),
    ],
)
def test_a_solver_setting_keeps_its_conditions_apart_on_the_same_mesh(tmp_path, lines, folder, setting, value, default):
    plain = Study.load(write(tmp_path, GOOD))
    other = Study.load(write(tmp_path, GOOD.replace('level = "coarse"', f'level = "coarse"\n{lines}')))
    straight = Condition(plain.speed)
    assert other.workspace.mesh_dir == plain.workspace.mesh_dir  # one mesh
    assert other.case_dir(straight).parent.name == folder
    assert plain.case_dir(straight).parent.name == "conditions"
    assert getattr(other.case_settings(other.workspace.body("AFF-1")).solver, setting) == value
    assert getattr(plain.case_settings(plain.workspace.body("AFF-1")).solver, setting) == default


def test_a_pressure_gradient_limited_at_the_start_shares_the_unlimited_conditions(tmp_path):
    """Limited only during a cold start's first-order iterations, a run converges to the unlimited solution."""
    plain = Study.load(write(tmp_path, GOOD))
    at_start = Study.load(write(tmp_path, GOOD.replace('level = "coarse"', 'level = "coarse"\nlimit_pressure_gradient = "start"')))
    straight = Condition(plain.speed)
    assert at_start.case_dir(straight) == plain.case_dir(straight)
    settings = at_start.case_settings(at_start.workspace.body("AFF-1"))
    assert settings.solver.limit_pressure_gradient_at_start and not settings.solver.limit_pressure_gradient
