"""The derivative table: sweeps picked out of a study's results, fitted, compared with Roddy (1990)."""

import json

import numpy as np
import pytest

from hydroderiv.case import Condition
from hydroderiv.derivatives.table import (body_parts, derivative_table, derivatives_by_part, fit_parts,
                                          write_table)
from hydroderiv.errors import ConfigurationError


def record(condition, **coefficients):
    base = dict.fromkeys("XYZKMN", 0.0)
    base.update(coefficients)
    return {"condition": condition.__dict__, "coefficients": base}


def synthetic_results(yv=-0.0278, nv=-0.0135, yr=0.00325, nr=-0.00372):
    out = []
    for beta in (-8, -4, 0, 4, 8):
        c = Condition(3.344, drift_deg=beta)
        u, v, _ = c.body_velocity() / c.speed
        out.append(record(c, Y=yv * u * v + 0.02 * v * abs(v), N=nv * u * v))
    for r in (-0.2, -0.1, 0.1, 0.2):
        out.append(record(Condition(3.344, yaw_rate_prime=r), Y=yr * r, N=nr * r + 0.001 * r * abs(r)))
    out.append(record(Condition(3.344, drift_deg=4, yaw_rate_prime=0.1), Y=1.0, N=1.0))  # combined: not in a sweep
    return out


def test_fits_each_sweep_and_compares_with_the_experiment(tmp_path):
    rows = {r.name: r for r in derivative_table(synthetic_results(), reference_key="AFF-8")}
    assert set(rows) == {"Yv", "Nv", "Yr", "Nr"}  # no pitch sweeps were run
    assert rows["Yr"].value == pytest.approx(0.00325, rel=1e-6)
    assert rows["Nr"].value == pytest.approx(-0.00372, rel=1e-6)
    # Y'v: the data carry u'v' = cos(b) v', so the slope in v' differs from -0.0278 only at O(v'^2)
    assert rows["Yv"].value == pytest.approx(-0.0278, rel=0.02)
    assert rows["Yv"].reference == -0.027839 and rows["Yv"].error_pct == pytest.approx(
        100 * (rows["Yv"].value + 0.027839) / 0.027839)
    # the single-point definition Y'/(u'v') is exact for a purely linear force
    assert rows["Nv"].single_point == pytest.approx(-0.0135, rel=1e-9)
    # per magnitude: Y' carries 0.02 v'|v'| on top of the linear term, so its single point grows with the angle
    # by 0.02 |v'|/u' (exact: Y'/(u'v') = yv + 0.02 |v'|/u'); N' is linear, the same at both magnitudes
    by_angle = rows["Yv"].single_point_by_magnitude
    assert set(by_angle) == {"4", "8"}
    for angle in (4, 8):
        b = np.radians(angle)
        assert by_angle[str(angle)] == pytest.approx(-0.0278 + 0.02 * np.tan(b), rel=1e-9)
    assert rows["Nv"].single_point_by_magnitude == pytest.approx({"4": -0.0135, "8": -0.0135}, rel=1e-9)
    assert set(rows["Nr"].single_point_by_magnitude) == {"0.1", "0.2"}
    assert rows["Nv"].experimental_uncertainty_pct == 5 and rows["Nr"].experimental_uncertainty_pct == 10
    # a body without measured derivatives has neither an error nor an experimental uncertainty
    unmeasured = derivative_table(synthetic_results(), reference_key="AFF-1")
    assert all(r.reference is None and r.error_pct is None and r.experimental_uncertainty_pct is None for r in unmeasured)
    results = synthetic_results()
    json_path, csv_path = write_table(list(rows.values()), tmp_path / "d.json", {"level": "x"}, results)
    data = json.loads(json_path.read_text())
    assert len(data["conditions"]) == len(results)  # the points behind the fits travel with the table
    assert data["conditions"][0]["coefficients"] == results[0]["coefficients"]
    assert data["Yr"] == rows["Yr"].value and "Yr" in csv_path.read_text()
    assert data["details"]["Nv"]["single_point_by_magnitude"]["8"] == pytest.approx(-0.0135)
    assert "4:-0.0135 8:-0.0135" in csv_path.read_text()  # one CSV cell per derivative
    assert data["details"]["Yr"]["iterative_stderr"] is None  # records without a window deviation: null, not NaN


def test_the_window_deviation_of_each_point_gives_the_iterative_uncertainty():
    results = synthetic_results()
    for r in results:
        r["window_std"] = [0.0, 2e-6, 0.0, 0.0, 0.0, 0.0]  # Y' swings, N' is still
    rows = {r.name: r for r in derivative_table(results)}
    assert rows["Yr"].iterative_stderr > 0 and rows["Yv"].iterative_stderr > 0
    assert rows["Nr"].iterative_stderr == 0.0
    # four turns at r' = +-0.1, +-0.2 with an offset and a nonlinear term: the slope's deviation is a few
    # times the points' deviation over the sweep's range
    assert 2e-6 / 0.4 < rows["Yr"].iterative_stderr < 20 * 2e-6 / 0.4


def test_mirror_symmetric_data_give_no_offset():
    rows = {r.name: r for r in derivative_table(synthetic_results())}
    assert np.isfinite(rows["Yv"].stderr)


def test_the_fit_plot_is_written(tmp_path):
    from hydroderiv.derivatives.table import fit_sweeps
    from hydroderiv.report.derivatives import plot_fits

    fits = fit_sweeps(synthetic_results())
    path = plot_fits(fits, tmp_path / "fits.png", "synthetic", {"Yv": -0.0278})
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and path.stat().st_size > 10_000


def test_a_linear_fit_needs_only_one_point_each_side():
    def quick(condition):  # straight, drift +-4 and turns r' = +-0.1, as in the quick study
        beta, r = abs(condition["drift_deg"]), abs(condition["yaw_rate_prime"])
        return (beta, r) in ((0, 0), (4, 0), (0, 0.1))

    results = [r for r in synthetic_results() if quick(r["condition"])]
    assert len(results) == 5
    # one magnitude cannot carry a nonlinear term as well: asked for one, every sweep gets the slope alone
    fallback = derivative_table(results)
    assert {r.nonlinear_term for r in fallback} == {"none"}
    rows = {r.name: r for r in derivative_table(results, nonlinear="none")}
    assert [r.value for r in fallback] == [rows[r.name].value for r in fallback]
    assert set(rows) == {"Yv", "Nv", "Yr", "Nr"}
    assert rows["Yr"].value == pytest.approx(0.00325, rel=1e-6) and rows["Nr"].value == pytest.approx(-0.00372, rel=0.05)


def stalled_drift_sweep(yv=-0.0278, yvv=-0.02):
    """Drift to +-12 degrees: Y' = Yv u'v' + Yv|v| v'|v'| up to 8 degrees, and half of that at 12 (a stall)."""
    out = [record(Condition(3.344))]
    for beta in (-12, -8, -4, -2, 2, 4, 8, 12):
        c = Condition(3.344, drift_deg=beta)
        u, v, _ = c.body_velocity() / c.speed
        y = yv * u * v + yvv * v * abs(v)
        out.append(record(c, Y=0.5 * y if abs(beta) > 8 else y))
    for r in (-0.2, -0.1, 0.1, 0.2):
        out.append(record(Condition(3.344, yaw_rate_prime=r), Y=0.003 * r))
    return out


def test_a_fit_range_keeps_a_stall_out_of_the_slope_but_in_the_single_points():
    results = stalled_drift_sweep()
    everything = {r.name: r for r in derivative_table(results, nonlinear="cubic")}
    limited = {r.name: r for r in derivative_table(results, nonlinear="cubic", max_angle_deg=8)}
    # Y' = Yv u'v' + Yv|v| v'|v'| is not exactly linear + cubic in v', but within 8 degrees close to it
    assert limited["Yv"].value == pytest.approx(-0.0278, rel=0.05)
    assert abs(everything["Yv"].value - limited["Yv"].value) > 0.1 * 0.0278  # the stall moves the full fit
    assert limited["Yv"].n_points == 7 and everything["Yv"].n_points == 9
    assert set(limited["Yv"].single_point_by_magnitude) == {"2", "4", "8", "12"}  # all magnitudes still shown
    # the single point at 12 degrees shows the stall: half the load of the unstalled curve
    c12 = Condition(3.344, drift_deg=12)
    u, v, _ = c12.body_velocity() / c12.speed
    assert limited["Yv"].single_point_by_magnitude["12"] == pytest.approx(0.5 * (-0.0278 - 0.02 * abs(v) / u), rel=1e-9)
    # turns are not limited by an angle
    assert limited["Yr"].value == pytest.approx(0.003, rel=1e-9) and limited["Yr"].n_points == 5


def test_a_fit_range_must_be_positive():
    with pytest.raises(ConfigurationError, match="max_angle_deg must be positive"):
        derivative_table(stalled_drift_sweep(), max_angle_deg=0)


def test_a_sweep_at_one_magnitude_is_fitted_without_the_nonlinear_term_not_dropped():
    """Turns at r' = +-0.1 only, in a table fitted with v|v| (drift at two magnitudes): three points cannot
    carry a slope, an r|r| term and an offset, but the mirror pair still measures Y'r and N'r."""
    results = [r for r in synthetic_results() if abs(r["condition"]["yaw_rate_prime"]) != 0.2]
    rows = {r.name: r for r in derivative_table(results, nonlinear="abs")}
    assert rows["Yv"].nonlinear_term == "abs" and rows["Yr"].nonlinear_term == "none"
    assert rows["Yr"].value == pytest.approx(0.00325, rel=1e-9)
    # N' carries 0.001 r|r|, which a mirror pair cannot tell from the slope: the slope is the pair's secant
    assert rows["Nr"].value == pytest.approx(-0.00372 + 0.001 * 0.1, rel=1e-9)
    assert rows["Nr"].n_points == 3  # the pair and the straight-ahead run
    assert rows["Nr"].spare_magnitudes == 0  # one pair for one slope: the fit passes through it


def test_each_fit_form_gives_its_own_slope_and_the_spread_between_them_is_reported(tmp_path):
    """Turns at r' = +-0.1, 0.2, 0.3 with N' = Nr r' + Nrr r'|r'|: the x|x| form recovers Nr exactly, a
    straight line through the same points returns Nr + Nrr sum(r'^2 |r'|) / sum(r'^2) (its least-squares
    slope), and the cubic form lies between; a sweep without curvature gives every form the same slope."""
    nr, nrr = -0.0030, -0.0020
    rates = (-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3)
    results = [record(Condition(3.344, yaw_rate_prime=r), Y=0.005 * r, N=nr * r + nrr * r * abs(r)) for r in rates]
    rows = {r.name: r for r in derivative_table(results, nonlinear="abs")}
    forms = rows["Nr"].slope_by_form
    assert set(forms) == {"abs", "cubic", "none"}
    assert forms["abs"] == pytest.approx(nr, rel=1e-9) == rows["Nr"].value
    straight = nr + nrr * sum(r * r * abs(r) for r in rates) / sum(r * r for r in rates)
    assert forms["none"] == pytest.approx(straight, rel=1e-9)
    assert forms["none"] < forms["cubic"] < forms["abs"]
    assert rows["Nr"].form_spread == pytest.approx(forms["abs"] - forms["none"], rel=1e-9)
    assert rows["Yr"].form_spread == pytest.approx(0.0, abs=1e-12)
    # a pair at one magnitude carries only the straight line: no spread to report
    pair = [r for r in results if abs(r["condition"]["yaw_rate_prime"]) in (0.0, 0.1)]
    assert np.isnan(derivative_table(pair)[1].form_spread)
    # two one-sided turns carry a straight line with an offset but no third term: the table still comes out
    one_sided = [r for r in results if r["condition"]["yaw_rate_prime"] in (0.1, 0.2)]
    assert set(derivative_table(one_sided, nonlinear="none")[1].slope_by_form) == {"none"}
    json_path, csv_path = write_table(list(rows.values()), tmp_path / "t.json", {})
    details = json.loads(json_path.read_text())["details"]["Nr"]
    assert details["form_spread"] == pytest.approx(rows["Nr"].form_spread) and details["slope_by_form"] == forms
    assert "form_spread" in csv_path.read_text().splitlines()[0]


def test_the_tables_of_record_repeat_a_yaw_turn_as_a_pitch_turn_turned_by_90_degrees():
    """A pitch turn of AFF-8 meets its sail edge-on, so it sees what a yaw turn of AFF-3 (the same hull and
    cruciform stern) sees turned by 90 degrees about the axis: Z'q = -Y'r and M'q = N'r, at every rate. The two
    committed medium tables come from different meshes (AFF-3's with relative layer sizes), so to within a few
    per cent, not exactly."""
    from pathlib import Path

    root = Path(__file__).parents[2] / "validation"
    aff8 = json.loads((root / "derivatives-AFF-8-medium.json").read_text())
    aff3 = json.loads((root / "derivatives-AFF-3-medium.json").read_text())
    for pitch, yaw, sign in (("Zq", "Yr", -1), ("Mq", "Nr", 1)):
        assert aff8[pitch] == pytest.approx(sign * aff3[yaw], rel=0.04)
        by_rate = aff8["details"][pitch]["single_point_by_magnitude"]
        assert set(by_rate) == {"0.1", "0.2", "0.3"}
        for rate, value in by_rate.items():
            assert value == pytest.approx(sign * aff3["details"][yaw]["single_point_by_magnitude"][rate], rel=0.04)


def test_each_parts_derivatives_add_up_to_the_bodys_and_travel_with_the_table(tmp_path):
    """A hull with curved loads and a fin whose load is linear: each part's fit returns its own slope (the fin's
    exactly, since its load has no nonlinear term), and the parts add up to the body's derivative, since a
    least-squares slope is linear in the loads. The per-part loads go into the table's conditions, so that a
    committed table can be split by part again."""
    hull = dict(Y=(-0.004, 0.03), N=(-0.015, 0.002))  # (slope, v|v| coefficient) per coefficient
    fin = dict(Y=(-0.008, 0.0), N=(0.0035, 0.0))
    results = []
    for beta in (-8, -4, 0, 4, 8):
        c = Condition(3.344, drift_deg=beta)
        v = (c.body_velocity() / c.speed)[1]
        parts = {name: {k: a * v + b * v * abs(v) for k, (a, b) in loads.items()} for name, loads in
                 (("hull", hull), ("fin", fin))}
        total = {k: parts["hull"][k] + parts["fin"][k] for k in "YN"}
        results.append({**record(c, **total), "components": {name: {**record(c, **load)["coefficients"]}
                                                             for name, load in parts.items()}})
    assert body_parts(results) == ["hull", "fin"]
    rows = {r.name: r for r in derivative_table(results)}
    by_part = derivatives_by_part(fit_parts(results))
    assert set(by_part) == {"Yv", "Nv"}
    for name in ("Yv", "Nv"):
        assert sum(by_part[name].values()) == pytest.approx(rows[name].value, rel=1e-12)
    assert by_part["Yv"]["fin"] == pytest.approx(-0.008, rel=1e-9)
    assert by_part["Nv"]["fin"] == pytest.approx(0.0035, rel=1e-9)
    json_path, _ = write_table(list(rows.values()), tmp_path / "t.json", {}, results, by_part=by_part)
    data = json.loads(json_path.read_text())
    assert data["by_part"] == by_part
    assert body_parts(data["conditions"]) == ["hull", "fin"]
    # records written before per-part loads were kept (one is enough) give no parts, not an error
    older = [{k: v for k, v in r.items() if k != "components"} if i == 2 else r for i, r in enumerate(results)]
    assert body_parts(older) == [] and fit_parts(older) == {}
    write_table(list(rows.values()), tmp_path / "o.json", {}, older)
    assert "components" not in json.loads((tmp_path / "o.json").read_text())["conditions"][2]


def test_the_aff3_table_of_record_splits_by_part_as_its_mirror_symmetry_and_fin_geometry_require():
    """AFF-3 is mirror-symmetric about its horizontal plane, which swaps the top and bottom rudders and leaves
    sway and yaw alone: the two rudders must give the same share of Y'v, N'v, Y'r and N'r. The mirror about
    the vertical plane swaps the port and starboard stern planes and reverses v and r, so their shares (of
    the odd loads) must be equal too. A rudder's load in drift and in a turn acts on the rudder: its centre
    of pressure, N'/Y' of its share, lies within the rudder's chordwise extent (from the SUBOFF geometry).
    And the parts add up to the body's derivative: to 0.2 %, since a part's load is the mean of every tenth
    iteration of the averaging window (case.setup.COMPONENT_INTERVAL) and the body's of every iteration, so
    they add up to the body's load only within about 0.05 % per condition. The meshes are not exactly
    symmetric, so a few per cent."""
    from pathlib import Path

    from hydroderiv.geometry.suboff import suboff_body

    table = json.loads((Path(__file__).parents[2] / "validation/derivatives-AFF-3-medium.json").read_text())
    by_part = table["by_part"]
    assert set(by_part) == {"Yv", "Nv", "Yr", "Nr"}
    for name, parts in by_part.items():
        assert sum(parts.values()) == pytest.approx(table[name], rel=2e-3)
        assert parts["appendage_top"] == pytest.approx(parts["appendage_bottom"], rel=0.05)
        assert abs(parts["appendage_port"] - parts["appendage_starboard"]) < 0.02 * abs(table[name])
    body = suboff_body("AFF-3")
    for rudder in ("appendage_top", "appendage_bottom"):
        for force, moment in (("Yv", "Nv"), ("Yr", "Nr")):
            _assert_centre_of_pressure_on_part(body, by_part, rudder, force, moment)


def _assert_centre_of_pressure_on_part(body, by_part, part, force, moment):
    """The part's share of a force and of its moment put the force at x = N'/Y' (yaw) or -M'/Z' (pitch: a
    downward force aft of the moment centre pitches the nose up); that point must lie on the part."""
    x = body.component(part).vertices[..., 0] / body.reference.length
    sign = -1.0 if force[0] == "Z" else 1.0
    centre_of_pressure = sign * by_part[moment][part] / by_part[force][part]
    assert x.min() <= centre_of_pressure <= x.max(), (part, force, centre_of_pressure, x.min(), x.max())


def test_the_aff8_table_of_record_splits_by_part_as_its_mirror_symmetry_and_geometry_require():
    """AFF-8 (sail on top) is mirror-symmetric about its vertical plane only. That mirror swaps the port and
    starboard stern planes; it reverses v and r and leaves w and q alone, so the two planes must give the same
    share of every derivative, the sway and yaw ones (odd in v and r) as well as the heave and pitch ones
    (even under it). The stern fins' load acts on them: the rudders' centre of pressure in drift and in a yaw
    turn, and the stern planes' in pitch and in a pitch turn, lie within their chordwise extent. The parts
    add up to the body (to 0.2 %: see the AFF-3 test). The mesh is not exactly symmetric, so a few per cent.

    The sail is a fin of aspect ratio below one, for which slender-wing theory puts the whole load of a
    constant-span planform at its leading edge. Computed, its centre of pressure in drift lies 0.013 L ahead
    of its leading edge: the aft three eighths of its chord carry a load of the opposite sign (`hydroderiv
    study flow`, loads along x). So for the sail the test asks the forward half, not the chord: ahead of its
    mid-chord and less than a chord ahead of its leading edge. Ahead of the moment centre it is pushed
    sideways against the sway velocity in drift and against the turn (Y'v < 0, Y'r < 0)."""
    from pathlib import Path

    from hydroderiv.geometry.suboff import suboff_body

    table = json.loads((Path(__file__).parents[2] / "validation/derivatives-AFF-8-medium.json").read_text())
    by_part = table["by_part"]
    assert set(by_part) == {"Yv", "Nv", "Zw", "Mw", "Yr", "Nr", "Zq", "Mq"}
    for name, parts in by_part.items():
        assert set(parts) == {"hull", "sail", "appendage_top", "appendage_starboard", "appendage_bottom",
                              "appendage_port"}
        assert sum(parts.values()) == pytest.approx(table[name], rel=2e-3)
        assert abs(parts["appendage_port"] - parts["appendage_starboard"]) < 0.02 * abs(table[name]), name
    body = suboff_body("AFF-8")
    for rudder in ("appendage_top", "appendage_bottom"):
        for force, moment in (("Yv", "Nv"), ("Yr", "Nr")):
            _assert_centre_of_pressure_on_part(body, by_part, rudder, force, moment)
    for plane in ("appendage_port", "appendage_starboard"):
        for force, moment in (("Zw", "Mw"), ("Zq", "Mq")):
            _assert_centre_of_pressure_on_part(body, by_part, plane, force, moment)
    sail_x = body.component("sail").vertices[..., 0] / body.reference.length
    chord = sail_x.max() - sail_x.min()
    sail_centre_of_pressure = by_part["Nv"]["sail"] / by_part["Yv"]["sail"]
    assert sail_x.max() - 0.5 * chord < sail_centre_of_pressure < sail_x.max() + chord
    assert by_part["Yv"]["sail"] < 0 and by_part["Yr"]["sail"] < 0
