"""The quasi-steady loads of a derivative table: what a manoeuvring simulation evaluates at each time step."""

import json
from pathlib import Path

import pytest

from hydroderiv.case import Condition
from hydroderiv.derivatives.table import straight_loads
from hydroderiv.errors import HydroderivError
from hydroderiv.simulation.quasi_steady import QuasiSteadyLoads

VALIDATION = Path(__file__).parents[2] / "validation"


def test_an_exact_table_gives_its_gertler_hagen_loads():
    """Each term enters with its form: slope and x|x| for the odd ones, squares and products for the rest."""
    table = {
        "details": {"Yv": {"value": -0.027, "nonlinear": -0.05, "nonlinear_term": "abs", "offset": 0.0},
                    "Nr": {"value": -0.0037, "nonlinear": 0.001, "nonlinear_term": "cubic", "offset": 0.0}},
        "extended": {"details": {"Xuu": {"value": -0.0013}, "Xvv": {"value": 0.007}, "Xvr": {"value": 0.02},
                                 "Zstar": {"value": -0.00004}, "Zrr": {"value": -0.003}, "N|v|r": {"value": 0.02},
                                 "Kv": {"value": -0.0005, "nonlinear": 0.001, "nonlinear_term": "abs"}}},
    }
    loads = QuasiSteadyLoads(table).coefficients(v=-0.07, r=0.2, u=0.9976)
    assert loads["X"] == pytest.approx(-0.0013 * 0.9976**2 + 0.007 * 0.0049 + 0.02 * -0.07 * 0.2, rel=1e-12)
    assert loads["Y"] == pytest.approx(-0.027 * -0.07 - 0.05 * -0.07 * 0.07, rel=1e-12)
    assert loads["Z"] == pytest.approx(-0.00004 - 0.003 * 0.04, rel=1e-12)
    assert loads["K"] == pytest.approx(-0.0005 * -0.07 + 0.001 * -0.07 * 0.07, rel=1e-12)
    assert loads["N"] == pytest.approx(-0.0037 * 0.2 + 0.001 * 0.2**3 + 0.02 * 0.07 * 0.2, rel=1e-12)
    assert loads["M"] == 0.0
    rolled = {"extended": {"details": {"Xuu": {"value": -0.0013},
                                       "Kp": {"value": -0.0004, "nonlinear": -0.0002, "nonlinear_term": "abs"},
                                       "Yp": {"value": 0.0003, "nonlinear": 0.0, "nonlinear_term": "none"}}}}
    roll = QuasiSteadyLoads(rolled).at(Condition(3.344, roll_rate_prime=-0.5))
    assert roll["K"] == pytest.approx(-0.0004 * -0.5 - 0.0002 * -0.5 * 0.5, rel=1e-12)
    assert roll["Y"] == pytest.approx(0.0003 * -0.5, rel=1e-12) and roll["N"] == 0.0


def test_a_file_that_is_not_a_table_is_named(tmp_path):
    path = tmp_path / "t.json"
    path.write_text("[1, 2]")
    with pytest.raises(HydroderivError, match="derivative table"):
        QuasiSteadyLoads.from_file(path)
    with pytest.raises(HydroderivError, match="cannot read"):
        QuasiSteadyLoads.from_file(tmp_path / "missing.json")


@pytest.mark.parametrize("body, coefficients", [("AFF-8-medium", "XYZKMN"), ("AFF-3-medium", "XYN"),
                                                 ("AFF-8-medium-combined", "XYZKMN")])
def test_the_table_of_record_gives_back_the_loads_it_was_fitted_to(body, coefficients):
    """Evaluated at each computed condition (straight, drift, pitch, yaw and pitch turns), the model built
    from the table returns every load within 8 % of that load's largest change from straight ahead over the
    table (measured: 1-5 %; what is left is the mirror pairs' asymmetry and the fits' residuals). A missing,
    misplaced or wrongly signed term would leave tens of per cent. AFF-3 ran drift and yaw turns only, where
    its horizontal mirror plane leaves Z', K' and M' nothing but the mesh's asymmetry to show. The combined
    table adds six conditions of drift and turn together, which the interaction terms take in."""
    table = json.loads((VALIDATION / f"derivatives-{body}.json").read_text())
    model = QuasiSteadyLoads(table)
    straight = straight_loads(table["conditions"])
    for coefficient in coefficients:
        scale = max(abs(r["coefficients"][coefficient] - straight[coefficient]) for r in table["conditions"])
        for record in table["conditions"]:
            predicted = model.at(Condition(**record["condition"]))[coefficient]
            assert abs(predicted - record["coefficients"][coefficient]) < 0.08 * scale, (record["name"], coefficient)


def test_drift_and_turn_together_need_the_interaction_terms():
    """At 4 degrees of drift in turns of r' = 0.1 and 0.2 (both relative signs), the single-variable sweeps
    summed miss the computed loads (N' by 37-47 % of itself at r' = 0.2, where the drift's and the turn's yaw
    moments nearly cancel; X' by 8-15 %). With the interaction terms fitted to those conditions the largest
    miss of X', Y', K', M' and N' over them, in units of the load's range over the table, falls 3.6-30 fold
    (to 0.9-4.5 %); the test asks for at least half. Z' is left out: its interaction is within its scatter."""
    table = json.loads((VALIDATION / "derivatives-AFF-8-medium-combined.json").read_text())
    interaction = {k for k, d in table["extended"]["details"].items() if d["kind"] == "interaction"}
    assert {"Xvr", "Mvr", "Y|v|r", "Yv|r|", "K|v|r", "Kv|r|", "N|v|r", "Nv|r|"} <= interaction
    full = QuasiSteadyLoads(table)
    sweeps_only = QuasiSteadyLoads({**table, "extended": {"details": {
        k: d for k, d in table["extended"]["details"].items() if k not in interaction}}})
    combined = [r for r in table["conditions"] if r["condition"]["drift_deg"] and r["condition"]["yaw_rate_prime"]]
    assert len(combined) == 6
    for coefficient in "XYKMN":
        scale = max(abs(r["coefficients"][coefficient] - straight_loads(table["conditions"])[coefficient])
                    for r in table["conditions"])
        misses = [max(abs(model.at(Condition(**r["condition"]))[coefficient] - r["coefficients"][coefficient])
                      for r in combined) / scale for model in (sweeps_only, full)]
        assert misses[1] < 0.5 * misses[0], (coefficient, misses)


def test_the_axial_force_interaction_is_even_under_the_mirror():
    """The port-starboard mirror takes (v', r') to (-v', -r') and leaves X' alone: the interaction load of
    X' over v'r' must come out the same at each mirror pair of combined conditions. Computed: within 3 %, and
    the six conditions within 3 % of their mean (X'vr +0.0153): a clean v'r' term."""
    table = json.loads((VALIDATION / "derivatives-AFF-8-medium-combined.json").read_text())
    singles = table["extended"]["details"]["Xvr"]["single_point_by_magnitude"]
    for plus, minus in (("b+4 r+0.1", "b-4 r-0.1"), ("b+4 r-0.1", "b-4 r+0.1"), ("b+4 r+0.2", "b-4 r-0.2")):
        assert singles[plus] == pytest.approx(singles[minus], rel=0.05)
    mean = sum(singles.values()) / len(singles)
    assert all(value == pytest.approx(mean, rel=0.05) for value in singles.values())


def test_a_table_without_the_extended_block_takes_the_straight_run_from_its_conditions():
    """Tables written before the extended block existed: the straight condition's loads stand in for X'uu,
    Y'* ... N'*; without conditions X' is unknown (NaN), never a silent zero."""
    table = json.loads((VALIDATION / "derivatives-AFF-8-medium.json").read_text())
    old = {k: v for k, v in table.items() if k != "extended"}
    assert QuasiSteadyLoads(old).coefficients() == pytest.approx(straight_loads(table["conditions"]), rel=1e-12)
    bare = {k: v for k, v in old.items() if k != "conditions"}
    loads = QuasiSteadyLoads(bare).coefficients()
    assert loads["X"] != loads["X"] and loads["Y"] == pytest.approx(table["details"]["Yv"]["offset"] / 2
                                                                   + table["details"]["Yr"]["offset"] / 2)
