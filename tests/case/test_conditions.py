"""Conditions: the frames and the source of the hybrid method, and their sign conventions."""

import numpy as np
import pytest

from hydroderiv.case import Condition
from hydroderiv.errors import ConfigurationError

L = 4.261


def test_straight_ahead_is_a_stream_from_ahead_without_rotation():
    c = Condition(speed=3.344)
    np.testing.assert_allclose(c.inflow(), [-3.344, 0, 0])
    assert not c.angular_velocity(L).any() and not c.momentum_source(L).any()
    assert c.turn_centre(L) is None


def test_drift_and_pitch_follow_the_seed_paper_definitions():
    c = Condition(speed=2.0, drift_deg=10.0)
    u, v, w = c.body_velocity() / 2.0
    assert v == pytest.approx(-np.sin(np.radians(10)))  # Y'v = Y'/(u'v') = -Y'/(cos b sin b)
    a = Condition(speed=2.0, pitch_deg=-8.0)
    assert a.body_velocity()[2] / 2.0 == pytest.approx(np.sin(np.radians(8)))
    both = Condition(speed=2.0, drift_deg=12.0, pitch_deg=-7.0)
    assert np.linalg.norm(both.inflow()) == pytest.approx(2.0)


@pytest.mark.parametrize(
    "kw, loads",
    [
        (dict(), ()),
        (dict(drift_deg=-4), ("Y", "N")),
        (dict(yaw_rate_prime=0.1), ("Y", "N")),
        (dict(pitch_deg=2), ("Z", "M")),
        (dict(pitch_rate_prime=-0.2), ("Z", "M")),
        (dict(yaw_rate_prime=0.2, pitch_deg=4), ("Y", "N", "Z", "M")),
        (dict(roll_rate_prime=0.5), ("K",)),
    ],
)
def test_a_condition_names_the_loads_its_derivatives_come_from(kw, loads):
    assert Condition(speed=3.344, **kw).defining_loads == loads


def test_starboard_turn_centre_lies_to_starboard_at_radius_L_over_r():
    c = Condition(speed=3.344, yaw_rate_prime=0.3)
    np.testing.assert_allclose(c.turn_centre(L), [0, L / 0.3, 0], rtol=1e-12)
    port = Condition(speed=3.344, yaw_rate_prime=-0.3)
    np.testing.assert_allclose(port.turn_centre(L), [0, -L / 0.3, 0], rtol=1e-12)


@pytest.mark.parametrize("kw", [dict(yaw_rate_prime=0.3), dict(pitch_rate_prime=-0.2),
                                dict(yaw_rate_prime=0.2, drift_deg=6, pitch_deg=4),
                                dict(roll_rate_prime=0.5, drift_deg=4, pitch_deg=-3)])
def test_source_equals_minus_omega_cross_omega_cross_R0(kw):
    """Delta/rho = -Omega x (Omega x R0) with R0 = B - A (the seed paper's Eq. 8), B at the origin."""
    c = Condition(speed=3.0, **kw)
    omega, a = c.angular_velocity(L), c.turn_centre(L)
    r0 = -a
    np.testing.assert_allclose(c.momentum_source(L), -np.cross(omega, np.cross(omega, r0)), atol=1e-12)
    # and it cancels the MRF Coriolis term of the free stream: Omega x U_inf - source = 0
    np.testing.assert_allclose(np.cross(omega, c.inflow()) - c.momentum_source(L), 0, atol=1e-12)


@pytest.mark.parametrize(
    "kw, words",
    [
        (dict(speed=0.0), "speed must be positive"),
        (dict(speed=3.0, drift_deg=45), "drift angle 45"),
        (dict(speed=3.0, pitch_deg=float("nan")), "pitch angle"),
        (dict(speed=3.0, yaw_rate_prime=2.0), "impossible"),
        (dict(speed=3.0, roll_rate_prime=-3.0), "roll rate p' = -3.0 is outside"),
    ],
)
def test_impossible_conditions_are_named(kw, words):
    with pytest.raises(ConfigurationError, match=words):
        Condition(**kw)


def test_names_are_distinct_and_file_safe():
    names = {Condition(3.0, b, 0, r).name for b in (-4, 0, 4) for r in (-0.2, 0, 0.2)}
    assert len(names) == 9 and all("/" not in n and " " not in n for n in names)


def test_a_roll_spins_about_the_axis_through_b_and_needs_no_source_straight_ahead():
    """p > 0 rolls the starboard side down: Omega along +x, p' = p L / U. With the inflow along the axis,
    Omega x U_inf vanishes, so a pure roll's sphere carries no source; its axis passes through B."""
    roll = Condition(speed=3.0, roll_rate_prime=0.5)
    np.testing.assert_allclose(roll.angular_velocity(L), [0.5 * 3.0 / L, 0, 0])
    assert not roll.momentum_source(L).any() and roll.is_turning
    np.testing.assert_allclose(roll.turn_centre(L), 0.0, atol=1e-15)
    assert roll.name == "U3_b0_a0_r0_q0_p+0.5"  # the suffix only for a roll: older names stay as they were
    assert Condition(speed=3.0, yaw_rate_prime=0.1).name == "U3_b0_a0_r+0.1_q0"
