"""Loads recorded on a mesh that turns with the body, taken back into body axes about the moment centre."""

import numpy as np
import pytest

from hydroderiv.forces import body_axis_loads


def _turn(angle: float) -> np.ndarray:
    """A right-handed turn by ``angle`` about +z (z down in body axes: a turn to starboard)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def test_fixed_body_loads_are_recovered_at_every_time():
    # a body turning to starboard about A = (0, R, 0) carries the same body-axis loads all the time
    radius, omega = 42.61, 0.0785
    centre = np.array([0.0, radius, 0.0])
    force_body, moment_body = np.array([-130.0, 40.0, -6.0]), np.array([0.5, -2.0, -100.0])
    times = np.linspace(0.0, 4.0, 9)
    force, moment = [], []
    for t in times:
        turn = _turn(omega * t)
        b = centre + turn @ (-centre)  # where B is at time t
        f = turn @ force_body
        force.append(f)
        moment.append(turn @ moment_body + np.cross(b - centre, f))  # about the fixed point A
    got_force, got_moment = body_axis_loads(times, np.array(force), np.array(moment),
                                            turn_centre=centre, axis=np.array([0.0, 0.0, 2.0]), omega=omega)
    np.testing.assert_allclose(got_force, np.tile(force_body, (len(times), 1)), atol=1e-9)
    np.testing.assert_allclose(got_moment, np.tile(moment_body, (len(times), 1)), atol=1e-7)


def test_side_force_at_b_has_its_lever_about_the_turn_centre_removed():
    # at t = 0 a pure side force at B has the moment (B - A) x F about A, and none about B
    centre = np.array([0.0, 10.0, 0.0])
    force = np.array([[0.0, 5.0, 0.0]])
    moment_about_a = np.cross(-centre, force[0])[None, :]
    assert moment_about_a[0, 2] == pytest.approx(0.0)  # the lever is along the force: no yaw moment either way
    _, moment = body_axis_loads(np.zeros(1), force, moment_about_a, turn_centre=centre,
                                axis=np.array([0.0, 0.0, 1.0]), omega=0.1)
    np.testing.assert_allclose(moment, 0.0, atol=1e-12)
    surge = np.array([[7.0, 0.0, 0.0]])  # a surge force at B, R to port of A: yaw moment R X about A, none about B
    moment_about_a = np.cross(-centre, surge[0])[None, :]
    assert moment_about_a[0, 2] == pytest.approx(70.0)
    _, moment = body_axis_loads(np.zeros(1), surge, moment_about_a, turn_centre=centre,
                                axis=np.array([0.0, 0.0, 1.0]), omega=0.1)
    np.testing.assert_allclose(moment, 0.0, atol=1e-12)


def test_a_quarter_turn_moves_a_forward_force_to_the_side():
    # after a quarter turn to starboard the body's forward axis points along the fixed +y axis
    omega = 0.5
    t = np.pi / 2 / omega
    force, _ = body_axis_loads(np.array([t]), np.array([[0.0, 3.0, 0.0]]), np.zeros((1, 3)),
                               turn_centre=np.zeros(3), axis=np.array([0.0, 0.0, 1.0]), omega=omega)
    np.testing.assert_allclose(force[0], [3.0, 0.0, 0.0], atol=1e-12)


def test_a_translating_body_keeps_its_moment_about_b():
    # a mesh moving in a straight line: a side force at B, which is V t from the fixed moment centre,
    # has a yaw moment about that centre that grows with t, and none about B
    velocity = np.array([-3.344, 0.0, 0.0])
    times = np.linspace(0.0, 2.0, 5)
    force = np.tile([0.0, 40.0, 0.0], (len(times), 1))
    moment = np.cross(np.outer(times, velocity), force)  # about B's start
    assert abs(moment[-1, 2]) > 100.0
    got_force, got_moment = body_axis_loads(times, force, moment, turn_centre=np.zeros(3),
                                            axis=np.array([0.0, 0.0, 1.0]), omega=0.0, velocity=velocity)
    np.testing.assert_allclose(got_force, force, atol=1e-12)
    np.testing.assert_allclose(got_moment, 0.0, atol=1e-9)
