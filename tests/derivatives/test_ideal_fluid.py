"""The ideal-fluid part of the velocity derivatives: Munk's moment of a spheroid from Lamb's coefficients,
the mirror relations of a body whose pitch plane repeats its yaw plane, the quasi-steady strip identity in
both planes, and the committed tables of record carrying their own split."""

import json
from pathlib import Path

import numpy as np
import pytest

from hydroderiv.derivatives.added_mass import acceleration_derivatives, spheroid_coefficients
from hydroderiv.derivatives.ideal_fluid import (
    ideal_fluid_derivatives,
    part_quasi_steady_ratios,
    quasi_steady_ratios,
    viscous_split,
    viscous_split_payload,
)
from hydroderiv.experiments import DERIVATIVES

ROOT = Path(__file__).parent.parent.parent


def spheroid_acceleration(a: float, b: float, length: float) -> dict[str, float]:
    """A prolate spheroid's acceleration derivatives (prime units on ``length``) from Lamb's k1, k2, k'."""
    lamb = spheroid_coefficients(a, b)
    volume = 4.0 / 3.0 * np.pi * a * b * b
    inertia = volume * (a * a + b * b) / 5.0  # the displaced water's moment of inertia about a diameter
    mass = {"Xudot": -lamb["k1"] * volume / (0.5 * length**3), "Yvdot": -lamb["k2"] * volume / (0.5 * length**3),
            "Nrdot": -lamb["k_rotation"] * inertia / (0.5 * length**5)}
    return {**mass, "Zwdot": mass["Yvdot"], "Mqdot": mass["Nrdot"], "Yrdot": 0.0, "Zqdot": 0.0}


def test_a_spheroid_in_drift_feels_munks_moment_and_no_force():
    """Potential flow about a spheroid moving at a drift angle: no side force, and the moment
    -(m22 - m11) u v that turns it broadside (Munk 1924; Newman 1977, section 4.13), negative in the prime
    system (as Roddy's N'v of SUBOFF, which the hull's Munk moment dominates); in a steady turn the side
    force X'u. u r and, fore-aft symmetric, no moment."""
    a, b, length = 2.178, 0.2773, 4.261  # SUBOFF's equivalent spheroid
    lamb = spheroid_coefficients(a, b)
    ideal = ideal_fluid_derivatives(spheroid_acceleration(a, b, length))
    volume = 4.0 / 3.0 * np.pi * a * b * b
    assert ideal["Nv"] == pytest.approx(-(lamb["k2"] - lamb["k1"]) * volume / (0.5 * length**3), rel=1e-12)
    assert ideal["Nv"] < 0 and ideal["Yv"] == ideal["Zw"] == 0.0
    assert ideal["Yr"] < 0 and ideal["Yr"] == pytest.approx(-lamb["k1"] * volume / (0.5 * length**3), rel=1e-12)
    assert ideal["Nr"] == ideal["Mq"] == 0.0


def test_a_cruciform_body_repeats_its_yaw_plane_in_pitch(suboff):
    """AFF-3 (hull of revolution and a cruciform stern) is its own image turned by 90 degrees about its
    axis, which takes (v, r, Y, N) to (w, -q, Z, -M): so Z'q = -Y'r, M'q = N'r and M'w = -N'v in the
    ideal fluid as in the CFD tables."""
    ideal = ideal_fluid_derivatives(acceleration_derivatives(suboff("AFF-3"), n_stations=100, n_panels=320).values)
    assert ideal["Zq"] == pytest.approx(-ideal["Yr"], rel=1e-9)
    assert ideal["Mq"] == pytest.approx(ideal["Nr"], rel=1e-6)
    assert ideal["Mw"] == pytest.approx(-ideal["Nv"], rel=1e-6)


def strip_loads(x: np.ndarray, lift: np.ndarray, turn_factor: float = 1.0) -> dict[str, float]:
    """Velocity derivatives of a viscous lift distribution along x (per unit length and per unit local
    incidence, negative: it opposes the cross-flow) whose sections each see their local incidence: v + r x
    in yaw, w - q x in pitch (z down, q > 0 nose up); the turns' lift scaled by ``turn_factor``."""
    first, second = np.trapezoid(x * lift, x), np.trapezoid(x * x * lift, x)
    return {"Yv": np.trapezoid(lift, x), "Nv": first, "Yr": turn_factor * first, "Nr": turn_factor * second,
            # Z = int z (w - q x), M = -int x dZ
            "Zw": np.trapezoid(lift, x), "Mw": -first, "Zq": -turn_factor * first, "Mq": turn_factor * second}


def test_the_viscous_part_of_a_quasi_steady_strip_loading_gives_turn_over_drift_ratios_of_one():
    """A body whose viscous lift comes from each section's local incidence, on top of its ideal-fluid
    loads: the split recovers the viscous loads exactly, and Y'r/N'v = Z'q/M'w = 1 for their viscous parts;
    a turn carrying 1.2 times that loading gives 1.2 in both planes."""
    acceleration = spheroid_acceleration(2.178, 0.2773, 4.261)
    ideal = ideal_fluid_derivatives(acceleration)
    x = np.linspace(-0.5, 0.5, 201)
    lift = -0.01 - 0.2 * np.clip(-0.3 - x, 0.0, None)  # a little everywhere, most of it aft (fins, afterbody)
    for factor in (1.0, 1.2):
        viscous = strip_loads(x, lift, factor)
        rows = viscous_split({k: ideal[k] + v for k, v in viscous.items()}, acceleration)
        assert [row.name for row in rows] == list(viscous)
        for row in rows:
            assert row.viscous == pytest.approx(viscous[row.name], rel=1e-9, abs=1e-15)
        ratios = quasi_steady_ratios(rows)
        assert ratios == {"Yr/Nv": pytest.approx(factor, rel=1e-9), "Zq/Mw": pytest.approx(factor, rel=1e-9)}


def test_each_part_of_a_quasi_steady_body_has_a_ratio_of_one_and_an_edge_on_fin_none():
    """A hull (its own strip of viscous lift plus the whole ideal fluid) and two fins (lift at their own
    stations), every section loaded by its local incidence: per part, the hull less the ideal fluid, the
    turn's viscous force equals the drift's viscous moment. A fin edge-on to the motion (no lift of its own,
    a trace of moment) gets no ratio; a fin loaded 1.5 times in the turn gets 1.5, the others keep 1."""
    acceleration = spheroid_acceleration(2.178, 0.2773, 4.261)
    ideal = ideal_fluid_derivatives(acceleration)
    x = np.linspace(-0.5, 0.5, 201)
    hull = strip_loads(x, -0.02 * (1.0 + x), 1.0)
    fin_x = np.array([-0.46, -0.44])  # the chord of a rudder, in L from the moment centre

    def fin(turn_factor):
        return strip_loads(fin_x, np.array([-0.05, -0.05]), turn_factor)

    for top_factor in (1.0, 1.5):
        parts = {"hull": {k: ideal[k] + v for k, v in hull.items()}, "top": fin(top_factor), "bottom": fin(1.0),
                 "side": {k: 1e-4 * v for k, v in fin(1.0).items()}}
        by_part = {name: {part: loads[name] for part, loads in parts.items()} for name in hull}
        ratios = part_quasi_steady_ratios(by_part, ideal)
        expected = {"hull": 1.0, "top": top_factor, "bottom": 1.0}
        for label in ("Yr/Nv", "Zq/Mw"):
            assert ratios[label] == {part: pytest.approx(value, rel=1e-9) for part, value in expected.items()}
        # the payload carries them when it is given the parts, and only then
        rows = viscous_split({name: sum(by_part[name].values()) for name in by_part}, acceleration)
        payload = viscous_split_payload(rows, by_part)
        assert payload["quasi_steady_ratio_by_part"] == ratios
        assert "quasi_steady_ratio_by_part" not in viscous_split_payload(rows)
    # a body whose parts have no hull to carry the ideal fluid gets none
    assert part_quasi_steady_ratios({name: {"body": value["hull"]} for name, value in by_part.items()}, ideal) == {}


def test_the_experiments_viscous_part_and_the_error_are_against_the_same_ideal_part():
    acceleration = spheroid_acceleration(2.178, 0.2773, 4.261)
    ideal = ideal_fluid_derivatives(acceleration)
    rows = {row.name: row for row in viscous_split({"Nv": ideal["Nv"] + 0.004, "Yv": -0.012}, acceleration,
                                                   {"Nv": ideal["Nv"] + 0.005})}
    assert rows["Nv"].reference_viscous == pytest.approx(0.005, rel=1e-9)
    # (computed - measured) / |measured|: the table's error convention, on the viscous parts
    assert rows["Nv"].viscous_error_pct == pytest.approx(-20.0, rel=1e-6)
    assert rows["Yv"].reference_viscous is None and rows["Yv"].viscous_error_pct is None
    assert "quasi_steady_ratio_measured" not in viscous_split_payload(list(rows.values()))
    with pytest.raises(KeyError, match="Zqdot"):
        ideal_fluid_derivatives({k: v for k, v in acceleration.items() if k != "Zqdot"})


@pytest.mark.parametrize("config", ["AFF-8", "AFF-3"])
def test_the_tables_of_record_carry_the_split_of_their_own_derivatives(config):
    """The split a medium table of record holds is its own derivatives less the ideal fluid of its own
    acceleration derivatives, beside Roddy's (so a refit cannot leave it stale). And its physics: the
    yaw moment in drift is mostly Munk's (the viscous lift, aft of the moment centre, takes some of it
    back), and in a turn to starboard, the stern swinging to port, the viscous side force points to
    starboard, against the swing."""
    table = json.loads((ROOT / f"validation/derivatives-{config}-medium.json").read_text())
    rows = viscous_split(table, table["acceleration"]["values"], DERIVATIVES[config]["values"])
    recorded = table["ideal_fluid"]
    assert list(recorded["derivatives"]) == [row.name for row in rows]
    for row in rows:
        for key, value in recorded["derivatives"][row.name].items():
            assert getattr(row, key) == (value if value is None else pytest.approx(value, rel=1e-12))
    assert recorded["quasi_steady_ratio"] == pytest.approx(quasi_steady_ratios(rows), rel=1e-12)
    by_part = part_quasi_steady_ratios(table["by_part"], {row.name: row.ideal for row in rows})
    assert recorded["quasi_steady_ratio_by_part"] == {label: pytest.approx(parts, rel=1e-12) for label, parts in by_part.items()}
    parts = {row.name: row for row in rows}
    assert parts["Nv"].ideal < parts["Nv"].value < 0 < parts["Nv"].viscous
    assert parts["Yr"].viscous > 0 and parts["Yv"].viscous < 0
