"""The rest of the steady table: the axial force, the sail's vertical-plane coupling and the roll moment."""

import json
from pathlib import Path

import numpy as np
import pytest

from hydroderiv.case import KNOT, Condition
from hydroderiv.case.fluid import Fluid
from hydroderiv.derivatives.extended import ROLL_DEFINITIONS, extended_payload, extended_terms, write_extended_csv
from hydroderiv.derivatives.table import DEFINITIONS, derivatives_by_part, fit_parts
from hydroderiv.experiments import resistance_interpolated
from hydroderiv.forces import PrimeScales

VALIDATION = Path(__file__).parents[2] / "validation"


def record(condition, **coefficients):
    base = dict.fromkeys("XYZKMN", 0.0)
    base.update(coefficients)
    return {"condition": condition.__dict__, "coefficients": base}


def gertler_hagen_results(asymmetry=0.0):
    """Loads of the Gertler-Hagen form over drift and yaw turns; ``asymmetry`` adds an odd part to Z' (a
    mesh's), as a fraction of the even Z' at the largest magnitude."""
    out = []
    for beta in (-8, -4, 0, 4, 8):
        c = Condition(3.344, drift_deg=beta)
        u, v, _ = c.body_velocity() / c.speed
        out.append(record(c, X=-0.0013 * u**2 + 0.007 * v**2, Z=-0.00004 * u**2 + 0.09 * v**2,
                          M=-0.00001 * u**2 + 0.012 * v**2, K=-0.0005 * u * v + 0.001 * v * abs(v)))
    for r in (-0.2, -0.1, 0.1, 0.2):
        out.append(record(Condition(3.344, yaw_rate_prime=r), X=-0.0013 + 0.0012 * r**2,
                          Z=-0.00004 - 0.003 * r**2 + asymmetry * 0.003 * 0.04 * r / 0.2,
                          M=-0.00001 - 0.001 * r**2, K=-0.00007 * r))
    return out


def test_each_term_of_the_gertler_hagen_form_comes_back_and_only_xuu_has_a_reference(tmp_path):
    terms = {t.name: t for t in extended_terms(gertler_hagen_results(), xuu_reference=-0.0012)}
    # no pitch sweeps were run, so no X'ww or X'qq
    assert set(terms) == {"Xuu", "Ystar", "Zstar", "Kstar", "Mstar", "Nstar", "Xvv", "Xrr", "Zvv", "Mvv", "Zrr",
                          "Mrr", "Kv", "Kr"}  # and no interaction terms: no condition combines drift and turn
    expected = {"Xuu": -0.0013, "Zstar": -0.00004, "Mstar": -0.00001, "Xvv": 0.007, "Xrr": 0.0012, "Zvv": 0.09,
                "Mvv": 0.012, "Zrr": -0.003, "Mrr": -0.001, "Kr": -0.00007}
    for name, value in expected.items():
        assert terms[name].value == pytest.approx(value, rel=1e-8, abs=1e-14), name
    # K'v: the slope in v' of K' = -0.0005 u'v' + 0.001 v'|v'|, which differs from -0.0005 at O(v'^2)
    assert terms["Kv"].value == pytest.approx(-0.0005, rel=0.02) and terms["Kv"].kind == "odd"
    # single points of an exactly quadratic load are the same at every magnitude
    assert terms["Zvv"].single_point_by_magnitude == pytest.approx({"4": 0.09, "8": 0.09}, rel=1e-8)
    assert terms["Xuu"].error_pct == pytest.approx(100 * (-0.0013 + 0.0012) / 0.0012)
    assert all(t.reference is None for name, t in terms.items() if name != "Xuu")
    payload = extended_payload(list(terms.values()))
    assert payload["values"]["Zvv"] == pytest.approx(0.09) and payload["details"]["Xuu"]["stderr"] is None
    json.dumps(payload, allow_nan=False)  # NaN written as null
    csv_path = write_extended_csv(list(terms.values()), tmp_path / "extended.csv")
    lines = csv_path.read_text().splitlines()
    assert lines[0].startswith("name,value,kind") and len(lines) == 1 + len(terms)


def test_an_odd_part_in_an_even_load_is_left_out_of_the_term_and_reported():
    """A mesh's asymmetry between port and starboard turns does not move Z'rr; it shows as the odd part."""
    terms = {t.name: t for t in extended_terms(gertler_hagen_results(asymmetry=0.1))}
    assert terms["Zrr"].value == pytest.approx(-0.003, rel=1e-8)
    assert terms["Zrr"].odd_part == pytest.approx(0.1, rel=1e-6)
    assert terms["Mrr"].odd_part < 1e-9


def _table(body):
    return json.loads((VALIDATION / f"derivatives-{body}-medium.json").read_text())


def test_without_a_sail_the_vertical_plane_coupling_and_the_roll_moment_vanish():
    """AFF-3 is mirror-symmetric about its horizontal plane as well as its vertical one: the first mirror
    reverses Z', M' and K' and leaves v' and r' alone, so Z'vv, M'vv, Z'rr, M'rr, K'v and K'r vanish. AFF-8's
    sail breaks that mirror. On the tables of record each of AFF-3's is under a tenth of AFF-8's (measured
    0.5-6 %: the meshes' asymmetry)."""
    aff3, aff8 = ({t.name: t.value for t in extended_terms(_table(body)["conditions"], max_angle_deg=4.0)}
                  for body in ("AFF-3", "AFF-8"))
    for name in ("Zvv", "Mvv", "Zrr", "Mrr", "Kv", "Kr"):
        assert abs(aff3[name]) < 0.1 * abs(aff8[name]), (name, aff3[name], aff8[name])


def test_the_roll_moment_acts_at_the_height_of_the_part_that_carries_it(suboff):
    """A fin's side force Y acts across its span: about the body's axis it rolls the body by K = -z Y (z
    down), so -K'/Y' of a fin's share is its centre of pressure's height, which must lie on the fin. For the
    sail of AFF-8 in drift and in a yaw turn (above the hull, z < 0), and for AFF-3's top and bottom rudders,
    whose rolling moments also cancel (mirror about the horizontal plane) to a few per cent."""
    pairs = (("Yv", "Kv"), ("Yr", "Kr"))
    definitions = {**ROLL_DEFINITIONS, "Yv": DEFINITIONS["Yv"], "Yr": DEFINITIONS["Yr"]}
    for body_name, parts in (("AFF-8", ("sail",)), ("AFF-3", ("appendage_top", "appendage_bottom"))):
        table = _table(body_name)
        by_part = derivatives_by_part(fit_parts(table["conditions"], "abs", True, 4.0, definitions))
        body = suboff(body_name)
        for part in parts:
            z = body.component(part).vertices[..., 2] / body.reference.length
            for force, moment in pairs:
                height = -by_part[moment][part] / by_part[force][part]
                assert z.min() <= height <= z.max(), (body_name, part, force, height, z.min(), z.max())
        if body_name == "AFF-3":
            for _, moment in pairs:
                top, bottom = by_part[moment]["appendage_top"], by_part[moment]["appendage_bottom"]
                assert top == pytest.approx(-bottom, rel=0.05)


@pytest.mark.parametrize("body", ["AFF-3", "AFF-8"])
def test_the_straight_runs_drag_is_the_towed_resistance(body, suboff):
    """X'uu of the tables of record against the towed resistance at 6.5 knots (power law between the
    measured speeds either side): Spalart-Allmaras with wall functions gives 8 % more drag on both bodies;
    the test holds it to 10 %."""
    table = _table(body)
    speed = table["meta"]["speed_m_s"]
    newtons = resistance_interpolated(body, speed / KNOT)
    xuu_measured = -newtons / PrimeScales(Fluid().rho, speed, suboff(body).reference.length).force
    terms = {t.name: t for t in extended_terms(table["conditions"], max_angle_deg=4.0, xuu_reference=xuu_measured)}
    assert terms["Xuu"].value < 0
    assert abs(terms["Xuu"].error_pct) < 10


def test_resistance_between_measured_speeds_follows_a_power_law():
    """Through the two nearest measured speeds, exact at each; None outside the measurements."""
    assert resistance_interpolated("AFF-8", 5.93) == 102.3 and resistance_interpolated("AFF-8", 10.0) == 283.8
    mid = resistance_interpolated("AFF-8", 8.0)
    exponent = np.log(283.8 / 102.3) / np.log(10.0 / 5.93)
    assert mid == pytest.approx(102.3 * (8.0 / 5.93) ** exponent) and 1.9 < exponent < 2.0
    assert resistance_interpolated("AFF-8", 5.0) is None and resistance_interpolated("AFF-1", 6.5) is None


def test_the_sails_side_force_leans_forward_with_the_inflow():
    """A lifting surface's force is normal to its inflow, less a drag along it. At a drift angle b its side
    force -L cos b comes with an axial component L sin b, so per v'^2 the lift alone gives X'vv = -Y'v, and
    the drag that grows with the angle (induced drag) takes from that. On AFF-8's table of record the
    sail's X'vv is 93 % of minus its Y'v; the test asks between half and all of it."""
    table = _table("AFF-8")
    records = [{**r, "coefficients": r["components"]["sail"]} for r in table["conditions"]]
    sail = {t.name: t.value for t in extended_terms(records, max_angle_deg=4.0)}
    assert 0.5 < sail["Xvv"] / -table["by_part"]["Yv"]["sail"] <= 1.0


def with_combined_conditions(results, signs=((1, 1), (-1, -1), (1, -1), (-1, 1)), rates=(0.1, 0.2)):
    """``results`` plus drift of 4 degrees combined with yaw rates, each load the sum of its drift and turn
    loads less the straight run's, plus an interaction of the Gertler-Hagen forms: X'vr v'r',
    Y'|v|r |v'|r' + Y'v|r| v'|r'|, K' and N' likewise, Z'vr and M'vr."""
    loads = {(r["condition"]["drift_deg"], r["condition"]["yaw_rate_prime"]): r["coefficients"] for r in results}
    out = list(results)
    for sign_b, sign_r in signs:
        for rate in rates:
            beta, r = 4 * sign_b, rate * sign_r
            c = Condition(3.344, drift_deg=beta, yaw_rate_prime=r)
            v = (c.body_velocity() / c.speed)[1]
            interaction = {"X": 0.02 * v * r, "Y": -0.05 * abs(v) * r + 0.01 * v * abs(r), "Z": 0.03 * v * r,
                           "K": 0.001 * abs(v) * r - 0.0003 * v * abs(r), "M": -0.004 * v * r, "N": 0.02 * abs(v) * r - 0.006 * v * abs(r)}
            out.append(record(c, **{k: loads[beta, 0][k] + loads[0, r][k] - loads[0, 0][k] + interaction[k]
                                    for k in "XYZKMN"}))
    return out


def drift_and_turn_results():
    """Drift at 0 and +-4 degrees and yaw turns at +-0.1 and +-0.2 of some loads, as a study runs them."""
    out = []
    for beta in (-4, 0, 4):
        c = Condition(3.344, drift_deg=beta)
        v = (c.body_velocity() / c.speed)[1]
        out.append(record(c, X=-0.0013 + 0.007 * v**2, Y=-0.027 * v, Z=0.09 * v**2, M=0.012 * v**2, N=-0.0135 * v))
    for r in (-0.2, -0.1, 0.1, 0.2):
        out.append(record(Condition(3.344, yaw_rate_prime=r), X=-0.0013 + 0.0012 * r**2, Y=0.003 * r,
                          Z=-0.003 * r**2, M=-0.001 * r**2, N=-0.0037 * r))
    return out


def test_the_drift_turn_interaction_comes_back_from_combined_conditions():
    terms = {t.name: t for t in extended_terms(with_combined_conditions(drift_and_turn_results()))}
    expected = {"Xvr": 0.02, "Zvr": 0.03, "Mvr": -0.004, "Y|v|r": -0.05, "Yv|r|": 0.01, "K|v|r": 0.001,
                "Kv|r|": -0.0003, "N|v|r": 0.02, "Nv|r|": -0.006}
    for name, value in expected.items():
        assert terms[name].value == pytest.approx(value, rel=1e-8), name
        assert terms[name].kind == "interaction" and terms[name].n_points == 8
    # the single point at a condition is its interaction load over v'r'. At b > 0 (v' < 0) and r' > 0,
    # |v'|r' = -v'r' and v'|r'| = v'r', so it is Y'v|r| - Y'|v|r; at b > 0 and r' < 0 both forms are -v'r',
    # so it is -(Y'|v|r + Y'v|r|)
    assert terms["Y|v|r"].single_point_by_magnitude["b+4 r+0.1"] == pytest.approx(0.01 + 0.05, rel=1e-8)
    assert terms["Y|v|r"].single_point_by_magnitude["b+4 r-0.1"] == pytest.approx(-(-0.05 + 0.01), rel=1e-8)


def test_y_and_n_interactions_need_both_relative_signs_of_drift_and_turn():
    """With drift outward in every turn (b and r' of one sign, as in a steady turn) |v'|r' and v'|r'| are the
    same column: the even loads' v'r' terms still come back, Y', K' and N' are left out rather than split at
    random."""
    results = with_combined_conditions(drift_and_turn_results(), signs=((1, 1), (-1, -1)))
    terms = {t.name: t for t in extended_terms(results)}
    assert {"Xvr", "Zvr", "Mvr"} <= set(terms)
    assert not {"Y|v|r", "Yv|r|", "K|v|r", "Kv|r|", "N|v|r", "Nv|r|"} & set(terms)
    assert terms["Zvr"].value == pytest.approx(0.03, rel=1e-8)


def test_a_roll_sweep_gives_the_roll_damping_and_the_side_force_and_yaw_moment_of_a_roll():
    """K'p, Y'p and N'p are the roll sweep's slopes, fitted as the main table's (with x|x| beside them); the
    drift-turn interaction ignores a roll condition, which has neither drift nor yaw rate, instead of
    taking it for the straight run."""
    results = [record(Condition(3.344, roll_rate_prime=p), X=-0.0013, K=-0.0004 * p - 0.0002 * p * abs(p),
                      Y=0.0003 * p, N=-0.0001 * p) for p in (-1.0, -0.5, 0.0, 0.5, 1.0)]
    terms = {t.name: t for t in extended_terms(results)}
    for name, value in (("Kp", -0.0004), ("Yp", 0.0003), ("Np", -0.0001)):
        assert terms[name].value == pytest.approx(value, rel=1e-8) and terms[name].kind == "odd"
    assert terms["Kp"].nonlinear == pytest.approx(-0.0002, rel=1e-8)
    combined = gertler_hagen_results() + [
        record(Condition(3.344, drift_deg=4, yaw_rate_prime=0.1), X=1.0, Y=1.0, N=1.0, K=1.0, Z=1.0, M=1.0),
        record(Condition(3.344, drift_deg=-4, yaw_rate_prime=0.1), X=1.0, Y=1.0, N=1.0, K=1.0, Z=1.0, M=1.0)]
    with_roll = combined + [record(Condition(3.344, roll_rate_prime=0.5), X=5.0, Y=5.0, Z=5.0, K=5.0, M=5.0, N=5.0)]
    before = {t.name: t.value for t in extended_terms(combined) if t.kind == "interaction"}
    after = {t.name: t.value for t in extended_terms(with_roll) if t.kind == "interaction"}
    assert before and after == pytest.approx(before)


def test_a_roll_is_damped_mostly_by_the_sail_with_its_load_inside_its_span(suboff):
    """AFF-8 rolling (the main job's mesh and set-up, p' = +-0.5 and +-1). The body's roll moment is odd in p'
    (the mirror pairs to 5 %) and damps the roll (K'p < 0). A fin's incidence in a roll grows with its
    distance from the axis, so the sail, the farthest, carries most of K'p (over 80 %), and its
    roll-induced side force acts inside its span (-K'/Y' of its share between its root and tip heights);
    so does the bottom rudder's, clear of the sail's wake. The stern planes, mirror images, roll the body
    as each other's mirror: K' of one at p' as minus the other's at -p', to the straight run's own K'
    (the mesh's asymmetry, 6e-7: the planes' shares are small, 1e-6 to 2e-6 at p' = 1)."""
    table = json.loads((VALIDATION / "derivatives-AFF-8-coarse-sa-roll.json").read_text())
    rolls = {r["condition"]["roll_rate_prime"]: r for r in table["conditions"]
             if r["condition"].get("roll_rate_prime") or not any(r["condition"][k] for k in
                                                                ("drift_deg", "pitch_deg", "yaw_rate_prime"))}
    moment = {p: r["coefficients"]["K"] for p, r in rolls.items()}
    for p in (0.5, 1.0):
        assert moment[p] - moment[0.0] == pytest.approx(-(moment[-p] - moment[0.0]), rel=0.05)
        starboard, port = (rolls[p]["components"][part]["K"] for part in ("appendage_starboard", "appendage_port"))
        mirrored = -rolls[-p]["components"]["appendage_port"]["K"], -rolls[-p]["components"]["appendage_starboard"]["K"]
        assert (starboard, port) == pytest.approx(mirrored, abs=abs(moment[0.0]))
    definitions = {"Kp": ROLL_DEFINITIONS["Kp"], "Yp": ROLL_DEFINITIONS["Yp"]}
    shares = derivatives_by_part(fit_parts(table["conditions"], "none", True, None, definitions))
    total = sum(shares["Kp"].values())
    assert total < 0 and shares["Kp"]["sail"] < 0.8 * total  # both negative: the sail's is over 80 % of it
    body = suboff("AFF-8")
    for part in ("sail", "appendage_bottom"):
        assert shares["Kp"][part] < 0
        height = -shares["Kp"][part] / shares["Yp"][part]  # K = -z Y
        z = body.component(part).vertices[..., 2] / body.reference.length
        assert z.min() <= height <= z.max(), (part, height, z.min(), z.max())
