"""The command line as a user meets it: results printed and written, problems named without a traceback."""

import json

import pytest

from hydroderiv.cli import main


def json_output(tmp_path, name, *args):
    """Run the command ``args`` with ``--out`` a new JSON file and return what it wrote."""
    out = tmp_path / f"{name}.json"
    assert main([*args, "--out", str(out)]) == 0
    return json.loads(out.read_text())


def test_geometry_writes_named_solids_and_prints_reference_quantities(tmp_path, capsys):
    assert main(["geometry", "--config", "AFF-8", "--out", str(tmp_path), "--resolution", "0.04"]) == 0
    out = capsys.readouterr().out
    assert "4.2610 m" in out and "wetted area" in out and "SUBOFF AFF-8" in out
    solids = [line.split()[1] for line in (tmp_path / "body.stl").read_text().splitlines() if line.startswith("solid ")]
    assert solids == ["hull", "sail", "appendage_top", "appendage_starboard", "appendage_bottom", "appendage_port"]
    info = json.loads((tmp_path / "body.json").read_text())
    assert info["reference"]["length"] == 4.261 and info["reference"]["max_diameter"] == 0.508


def test_all_configurations_go_to_their_own_directories(tmp_path):
    assert main(["geometry", "--config", "all", "--out", str(tmp_path), "--resolution", "0.05"]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["AFF-1", "AFF-2", "AFF-3", "AFF-8"]


def test_bad_stl_gives_a_clear_error_not_a_traceback(tmp_path, capsys):
    bad = tmp_path / "empty.stl"
    bad.write_text("")
    code = main(["geometry", "--stl", str(bad), "--length", "4.261", "--moment-centre", "0", "0", "0", "--out", str(tmp_path / "o")])
    captured = capsys.readouterr()
    assert code == 2
    assert "error:" in captured.out and "empty" in captured.out and "Traceback" not in captured.out + captured.err


def test_unknown_configuration_is_named(tmp_path, capsys):
    assert main(["geometry", "--config", "AFF-5", "--out", str(tmp_path)]) == 2
    assert "unknown SUBOFF configuration 'AFF-5'" in capsys.readouterr().out


def test_a_bad_mesh_option_is_named_before_anything_runs(tmp_path, capsys):
    assert main(["mesh", "--config", "AFF-8", "--out", str(tmp_path / "m"), "--mesh", "appendage_levels=2"]) == 2
    assert "unknown mesh option 'appendage_levels'" in capsys.readouterr().out
    assert main(["mesh", "--config", "AFF-8", "--out", str(tmp_path / "m"), "--mesh", "thin_max_layers"]) == 2
    assert "expected KEY=VALUE" in capsys.readouterr().out
    assert not (tmp_path / "m").exists()


def test_progress_shows_each_condition_from_its_own_first_iteration(capsys):
    """A study's second condition counts iterations from 0 again; its progress must not wait for the first's count."""
    import numpy as np

    from hydroderiv.cli import _progress_printer
    from hydroderiv.run.solver import Progress

    show = _progress_printer(lambda key: key, every=25)

    def progress(iteration):
        return Progress(iteration, {"p": 1e-3}, np.zeros(6), None, 1.0)

    for iteration in (0, 10, 25, 200):
        show("first", progress(iteration))
    show("second", progress(30))
    lines = [line for line in capsys.readouterr().out.splitlines() if " it " in line]
    assert [line.split()[0] for line in lines] == ["first", "first", "first", "second"]


def test_a_committed_table_is_refitted_from_the_forces_it_carries(tmp_path, capsys):
    """``derivatives --conditions`` refits the medium AFF-8 table of record without its work directory: the
    same fits (the pitch turns' Z'q and M'q too), and per magnitude the mirror pair's single point,
    (Y'(+b) - Y'(-b)) / (2 cos b sin b)."""
    import math
    from pathlib import Path

    root = Path(__file__).parent.parent
    committed = json.loads((root / "validation/derivatives-AFF-8-medium.json").read_text())
    out = tmp_path / "refit.json"
    code = main(["derivatives", str(root / "studies/aff8-medium.toml"), "--conditions",
                 str(root / "validation/derivatives-AFF-8-medium.json"), "--out", str(out)])
    assert code == 0 and "Yv" in capsys.readouterr().out
    refit = json.loads(out.read_text())
    for name in ("Yv", "Nv", "Zw", "Mw", "Yr", "Nr", "Zq", "Mq"):
        assert refit[name] == pytest.approx(committed[name], rel=1e-12)
    assert refit["meta"]["turbulence_model"] == "SpalartAllmaras" and refit["meta"]["method"] == "hybrid"
    # the split into ideal-fluid and viscous parts, printed and written with the table
    assert refit["ideal_fluid"]["quasi_steady_ratio"] == pytest.approx(committed["ideal_fluid"]["quasi_steady_ratio"], rel=1e-12)
    side_force = {c["condition"]["drift_deg"]: c["coefficients"]["Y"] for c in committed["conditions"]
                  if c["condition"]["pitch_deg"] == 0 and c["condition"]["yaw_rate_prime"] == 0}
    b = math.radians(4)
    mirror_pair = -(side_force[4] - side_force[-4]) / (2 * math.cos(b) * math.sin(b))
    assert refit["details"]["Yv"]["single_point_by_magnitude"]["4"] == pytest.approx(mirror_pair, rel=1e-9)


def test_a_table_names_the_turbulence_model_and_frame_method_it_was_computed_with(tmp_path, capsys):
    """The classic AFF-3 table (Shih's model, the whole domain rotating) says so in its meta and its title."""
    from pathlib import Path

    root = Path(__file__).parent.parent
    out = tmp_path / "classic.json"
    code = main(["derivatives", str(root / "studies/aff3-medium-classic.toml"), "--conditions",
                 str(root / "validation/classic-AFF-3-medium.json"), "--out", str(out)])
    assert code == 0 and "ShihQuadraticKE, classic rotating domain" in capsys.readouterr().out
    meta = json.loads(out.read_text())["meta"]
    assert (meta["turbulence_model"], meta["method"]) == ("ShihQuadraticKE", "classic")


def test_a_table_without_conditions_is_named(tmp_path, capsys):
    from pathlib import Path

    study = Path(__file__).parent.parent / "studies/aff8-medium.toml"
    bad = tmp_path / "t.json"
    bad.write_text('{"Yv": -0.02}')
    assert main(["derivatives", str(study), "--conditions", str(bad)]) == 2
    assert "not a derivative table with a 'conditions' list" in capsys.readouterr().out


def test_the_reversed_flow_of_a_study_with_nothing_finished_is_named(tmp_path, capsys):
    study = tmp_path / "s.toml"
    study.write_text(f'[study]\nbody = "AFF-1"\nlevel = "coarse"\nspeed_knots = 6.5\nwork = "{tmp_path / "work"}"\n[sweeps]\ndrift_deg = [4]\n')
    assert main(["study", "flow", str(study)]) == 2
    assert "has finished yet" in capsys.readouterr().out


def test_grid_convergence_of_three_committed_style_tables(tmp_path, capsys):
    # three tables of N'r = -0.0036 + 0.0008 h^2 at r' = 0.1 on the three levels
    paths = []
    for i, level in enumerate(("coarse", "medium", "fine")):
        value = -0.0036 + 0.0008 * 2.0 ** (2 - i)  # h = sqrt(2) ** (2 - i), so h^2 = 2 ** (2 - i)
        path = tmp_path / f"{level}.json"
        path.write_text(json.dumps({"Nr": value, "meta": {"level": level, "body": "AFF-8", "method": "hybrid",
                                                           "turbulence_model": "ShihQuadraticKE", "speed_m_s": 3.344},
                                    "details": {"Nr": {"value": value, "single_point_by_magnitude": {"0.1": value}}}}))
        paths.append(str(path))
    out = tmp_path / "convergence.json"
    assert main(["convergence", *paths, "--magnitude", "0.1", "--out", str(out)]) == 0
    result = json.loads(out.read_text())
    assert result["tables"] == {"coarse": paths[0], "medium": paths[1], "fine": paths[2]}
    assert result["derivatives"]["Nr"]["extrapolated"] == pytest.approx(-0.0036, rel=1e-9)
    assert "grid convergence" in capsys.readouterr().out
    assert main(["convergence", paths[0], paths[1], str(tmp_path / "missing.json")]) == 2
    assert "missing.json: no such derivative table" in capsys.readouterr().out


@pytest.mark.parametrize("text, message", [("{not json", "not JSON"), ("[1, 2]", "not a derivative table")])
def test_a_broken_table_is_named_by_refit_and_grid_convergence(tmp_path, capsys, text, message):
    from pathlib import Path

    study = Path(__file__).parent.parent / "studies/aff8-medium.toml"
    bad = tmp_path / "broken.json"
    bad.write_text(text)
    assert main(["derivatives", str(study), "--conditions", str(bad)]) == 2
    assert f"broken.json: {message}" in capsys.readouterr().out
    assert main(["convergence", str(bad), str(bad), str(bad)]) == 2
    assert f"broken.json: {message}" in capsys.readouterr().out


def test_stability_of_a_committed_table_for_its_own_body_or_a_given_mass(tmp_path, capsys):
    """`hydroderiv stability TABLE` gives the table's recorded stability for its neutrally buoyant body; a
    given mass enters the sway damping as Y'r - m' (the body's own centripetal force), so C_H follows by hand."""
    from pathlib import Path

    table_path = Path(__file__).parent.parent / "validation/derivatives-AFF-3-medium.json"
    table = json.loads(table_path.read_text())
    out = tmp_path / "stability.json"
    assert main(["stability", str(table_path), "--out", str(out)]) == 0
    assert "horizontal" in capsys.readouterr().out
    report = json.loads(out.read_text())
    for key, value in table["stability"]["horizontal"]["computed"].items():
        if key == "motion":  # the roots, with the added mass the table records
            assert report["horizontal"]["computed"][key]["growth_rate"] == pytest.approx(value["growth_rate"], rel=1e-6)
            continue
        assert report["horizontal"]["computed"][key] == (pytest.approx(value, rel=1e-6) if isinstance(value, float) else value)

    assert main(["stability", str(table_path), "--mass-prime", "0.03", "--xg-prime", "0", "--out", str(out)]) == 0
    criterion = table["Yv"] * table["Nr"] - table["Nv"] * (table["Yr"] - 0.03)
    assert json.loads(out.read_text())["horizontal"]["computed"]["criterion"] == pytest.approx(criterion, rel=1e-12)


def test_stability_with_a_hydrostatic_moment_gives_the_speeds_it_holds_the_vertical_plane(tmp_path, capsys):
    """`stability --bg-m` adds the restoring moment in pitch at the table's speed: AFF-8's vertical plane
    gets three roots and the range of stable speeds, which grows as sqrt(z_BG); the horizontal plane is as
    without it; a table without a vertical plane, or a centre of gravity above the buoyancy, is named."""
    from pathlib import Path

    root = Path(__file__).parents[1]
    table = str(root / "validation/derivatives-AFF-8-medium.json")
    reports = [json_output(tmp_path, f"stability{bg}", "stability", table, "--bg-m", bg) for bg in ("0.02", "0.08")]
    assert "the vertical plane is stable up to" in capsys.readouterr().out.replace("\n", " ")
    near, far = (r["vertical"]["computed"] for r in reports)
    assert len(near["motion"]["roots"]) == 3
    assert far["stable_speeds"]["highest_m_s"] == pytest.approx(2 * near["stable_speeds"]["highest_m_s"])
    recorded = json.loads(Path(table).read_text())["stability"]
    assert reports[0]["horizontal"]["computed"]["motion"]["growth_rate"] == pytest.approx(
        recorded["horizontal"]["computed"]["motion"]["growth_rate"], rel=1e-6)
    assert main(["stability", table.replace("AFF-8", "AFF-3"), "--bg-m", "0.02"]) == 2
    assert "--bg-m acts in pitch" in capsys.readouterr().out
    assert main(["stability", table, "--bg-m", "-0.02"]) == 2
    assert "capsizes" in capsys.readouterr().out


def test_stability_names_what_a_table_lacks(tmp_path, capsys):
    bad = tmp_path / "turns.json"
    bad.write_text(json.dumps({"Yr": 0.003, "Nr": -0.003, "meta": {"body": "AFF-8"}}))
    assert main(["stability", str(bad), "--mass-prime", "0.018", "--xg-prime", "0"]) == 2
    assert "no plane has all four derivatives" in capsys.readouterr().out
    assert main(["stability", str(bad).replace("turns", "absent")]) == 2
    assert "no such derivative table" in capsys.readouterr().out
    anonymous = tmp_path / "anonymous.json"
    anonymous.write_text(json.dumps({"Yv": -0.02, "Nv": -0.01, "Yr": 0.005, "Nr": -0.004, "meta": {}}))
    assert main(["stability", str(anonymous)]) == 2
    assert "names no body" in capsys.readouterr().out


def test_loads_of_a_committed_table_at_a_motion_and_beyond_its_range(tmp_path, capsys):
    """`loads` evaluates the table's quasi-steady model; a drift of -4 degrees mirrors +4 (Y', N', K' change
    sign up to the table's zero-incidence offsets, X' stays); beyond the conditions' range it says so."""
    from pathlib import Path

    root = Path(__file__).parents[1]
    table = str(root / "validation/derivatives-AFF-8-medium.json")
    outs = [json_output(tmp_path, f"loads{drift}", "loads", table, "--drift-deg", drift) for drift in ("4", "-4")]
    plus, minus = (o["coefficients"] for o in outs)
    offsets = json.loads(Path(table).read_text())["extended"]["values"]
    for k in "YNK":
        assert plus[k] - offsets[f"{k}star"] == pytest.approx(-(minus[k] - offsets[f"{k}star"]), rel=0.02)
    assert plus["X"] == pytest.approx(minus["X"], rel=1e-3)
    assert "extrapolated" not in capsys.readouterr().out
    assert main(["loads", table, "--yaw-rate-prime", "0.5"]) == 0
    assert "extrapolated beyond the table's range: yaw_rate_prime 0.5" in capsys.readouterr().out.replace("\n", " ")
    assert main(["loads", str(tmp_path / "loads4.json")]) == 2
    assert "not a derivative table" in capsys.readouterr().out


def test_manoeuvre_of_a_committed_table_writes_the_motion_and_flags_its_range(tmp_path, capsys):
    """`manoeuvre` simulates the table's body, trimmed neutrally buoyant, with the added mass estimated from
    its shape: starboard and port disturbances give mirror-image tracks; the turn that the unstable AFF-8
    develops leaves the table's range, and the command says so; bad requests are named."""
    import csv
    from pathlib import Path

    table = str(Path(__file__).parents[1] / "validation/derivatives-AFF-8-medium.json")
    tracks = []
    for rate in ("0.01", "-0.01"):
        out = tmp_path / f"track{rate}.csv"
        assert main(["manoeuvre", table, "--yaw-rate-prime", rate, "--lengths", "10", "--without-straight-offsets",
                     "--out", str(out)]) == 0
        tracks.append(list(csv.DictReader(out.open())))
    printed = capsys.readouterr().out.replace("\n", " ")
    assert "doubles in" in printed and "beyond the table's conditions" in printed
    starboard, port = tracks
    assert (tmp_path / "track0.01.png").stat().st_size > 10_000  # the figure beside the CSV
    assert len(starboard) == 101 and float(starboard[-1]["t"]) == pytest.approx(10.0)
    assert float(starboard[-1]["y"]) > 0.5 and float(port[-1]["y"]) == pytest.approx(-float(starboard[-1]["y"]), rel=1e-6)
    assert main(["manoeuvre", table, "--bg-m", "0.02"]) == 2
    assert "--bg-m acts in pitch" in capsys.readouterr().out
    assert main(["manoeuvre", table, "--plane", "vertical", "--bg-m", "0.02", "--pitch-rate-prime", "0.001",
                 "--lengths", "2"]) == 0
    assert "with the hydrostatic moment h' = 3.2" in capsys.readouterr().out.replace("\n", " ")
    assert main(["manoeuvre", table, "--lengths", "-1"]) == 2
    assert "positive number of body lengths" in capsys.readouterr().out
    aff3 = table.replace("AFF-8", "AFF-3")
    assert main(["manoeuvre", aff3, "--plane", "vertical"]) == 2
    assert "do not cover the vertical plane" in capsys.readouterr().out.replace("\n", " ")
    # a given inertia in one plane only: the other plane's motion is left out, not an error
    assert main(["stability", aff3, "--mass-prime", "0.02", "--xg-prime", "0", "--iz-prime", "0.0012"]) == 0
    assert "doubles in" in capsys.readouterr().out


def test_a_study_of_straight_ahead_alone_reports_its_drag_beside_the_tow(tmp_path, capsys):
    """No sweeps, no derivative: the study is a resistance check. A drag 5 % above the tow's reads +5 %."""
    from hydroderiv.case import KNOT
    from hydroderiv.experiments import resistance_interpolated
    from hydroderiv.forces import PrimeScales
    from hydroderiv.run.condition import RESULT_FILE
    from hydroderiv.studies.study import Study

    path = tmp_path / "s.toml"
    path.write_text(f'[study]\nbody = "AFF-3"\nlevel = "coarse"\nspeed_knots = 6.5\nwork = "{tmp_path / "work"}"\n'
                    'turbulence_model = "LienCubicKE"\n[sweeps]\n')
    assert main(["derivatives", str(path)]) == 2
    message = " ".join(capsys.readouterr().out.split())
    assert "the straight-ahead condition of" in message and "s.toml has not finished" in message
    study = Study.load(path)
    scales = PrimeScales(998.55, study.speed, 4.261)
    towed_n = resistance_interpolated("AFF-3", 6.5)
    x = -1.05 * towed_n / scales.force
    case = study.case_dir(study.conditions[0])
    case.mkdir(parents=True)
    (case / RESULT_FILE).write_text(json.dumps({
        "converged": True, "iterations": 300, "coefficients": {"X": x, "Y": 0, "Z": 0, "K": 0, "M": 0, "N": 0},
        "components": {"hull": {"X": 0.9 * x}, "appendage_top": {"X": 0.1 * x}}}))
    record = json_output(tmp_path, "straight", "derivatives", str(path))
    assert record["drag_error_pct"] == pytest.approx(5.0, rel=1e-9)
    assert record["drag_N"] == pytest.approx(1.05 * towed_n, rel=1e-9)
    assert record["drag_N_by_part"]["hull"] == pytest.approx(0.9 * record["drag_N"], rel=1e-9)
    assert record["turbulence_model"] == "LienCubicKE" and study.speed == pytest.approx(6.5 * KNOT)
    assert "+5.0" in capsys.readouterr().out


def test_resistance_runs_the_turbulence_model_asked_for_in_its_own_conditions_folder(tmp_path, capsys, monkeypatch):
    """The solver is replaced by a stand-in that records what it was given: this checks the bookkeeping."""
    import hydroderiv.studies.resistance as resistance
    from hydroderiv.studies.workspace import Workspace

    assert main(["resistance", "--config", "AFF-3", "--work", str(tmp_path / "w"), "--turbulence-model", "kEpsilonX"]) == 2
    assert "--turbulence-model: unknown turbulence model 'kEpsilonX'" in capsys.readouterr().out
    assert not (tmp_path / "w").exists()
    runs = []

    def stand_in(case, mesh_dir, condition, settings, criterion, warm_start=None, on_progress=None):
        runs.append((case, settings.solver.turbulence_model))
        return {"force_N": [-100.0, 0.0, 0.0], "iterations": 200, "converged": True, "wall_seconds": 1.0,
                "warm_start": warm_start, "yplus": {}}

    monkeypatch.setattr(Workspace, "mesh", lambda self, body, log=print, n_procs=1: {"cells": 1000})
    monkeypatch.setattr(resistance, "run_condition", stand_in)
    monkeypatch.setattr(resistance, "_force_parts", lambda case, window: {"pressure": 20.0, "viscous": 80.0})
    monkeypatch.setattr(resistance, "latest_time_dir", lambda case: None)
    monkeypatch.setattr("hydroderiv.report.resistance.plot_resistance", lambda points, path, title: path)
    results = tmp_path / "r.json"
    assert main(["resistance", "--config", "AFF-3", "--work", str(tmp_path / "w"), "--speeds", "5.92",
                 "--turbulence-model", "LienCubicKE", "--results", str(results)]) == 0
    assert [(case.parent.name, model) for case, model in runs] == [("conditions-LienCubicKE", "LienCubicKE")]
    (point,) = json.loads(results.read_text())
    assert point["turbulence_model"] == "LienCubicKE" and point["experiment_N"] == 95.41
    assert point["error_pct"] == pytest.approx(100 * (100.0 - 95.41) / 95.41, abs=0.01)
    assert "LienCubicKE" in capsys.readouterr().out
    # without --results each model writes its own file: the cubic run leaves the default model's alone
    assert main(["resistance", "--config", "AFF-3", "--work", str(tmp_path / "w"), "--speeds", "5.92",
                 "--turbulence-model", "LienCubicKE"]) == 0
    assert (tmp_path / "w/resistance-LienCubicKE.json").is_file() and not (tmp_path / "w/resistance.json").exists()
