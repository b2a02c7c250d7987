"""Controls-fixed motion in time: the straight course kept, the linearised growth rate of the stability
analysis recovered from the nonlinear equations, mirror-image disturbances giving mirror-image motions, and
the table's range flagged."""

import json
from pathlib import Path

import numpy as np
import pytest

from hydroderiv.errors import ConfigurationError
from hydroderiv.simulation.manoeuvre import ManoeuvreSimulation, table_reach
from hydroderiv.simulation.quasi_steady import QuasiSteadyLoads
from hydroderiv.simulation.stability import MassProperties, mass_matrix, plane_motion, stiffness_matrix

VALIDATION = Path(__file__).parents[2] / "validation"
MASS = MassProperties(0.01825, 0.0008, "test", iz_prime=0.00107, iy_prime=0.00107)
ACCELERATION = {"Xudot": -0.00055, "Yvdot": -0.0194, "Yrdot": -0.00014, "Nvdot": -0.00014, "Nrdot": -0.00106,
                "Zwdot": -0.0176, "Zqdot": -0.00024, "Mwdot": -0.00024, "Mqdot": -0.00098}


def linear_table(**values):
    """A derivative table with linear terms only, the straight run's drag and nothing else."""
    return {"details": {k: {"value": v, "nonlinear": 0.0, "nonlinear_term": "none"} for k, v in values.items()},
            "extended": {"details": {"Xuu": {"value": -0.0013}}}, **values}


STABLE = linear_table(Yv=-0.03, Nv=-0.004, Yr=0.006, Nr=-0.005, Zw=-0.03, Mw=0.004, Zq=-0.006, Mq=-0.005)


def aff8_medium():
    return json.loads((VALIDATION / "derivatives-AFF-8-medium.json").read_text())


def growth_rate(trajectory, name, start, stop):
    values = np.abs(trajectory.states[name])
    k0, k1 = np.searchsorted(trajectory.time, [start, stop])
    return np.log(values[k1] / values[k0]) / (trajectory.time[k1] - trajectory.time[k0])


@pytest.mark.parametrize("plane", ["horizontal", "vertical"])
def test_an_undisturbed_vehicle_keeps_its_course_and_speed(plane):
    """The thrust balances the straight run's drag: no disturbance, no motion but ahead at the table's speed."""
    trajectory = ManoeuvreSimulation(QuasiSteadyLoads(STABLE), ACCELERATION, MASS, plane).run(10)
    end = trajectory.at_end()
    assert end["u"] == pytest.approx(1.0, abs=1e-12) and end["x"] == pytest.approx(10.0, rel=1e-9)
    assert all(abs(value) < 1e-12 for key, value in end.items() if key not in ("u", "x"))


@pytest.mark.parametrize("plane", ["horizontal", "vertical"])
def test_a_small_disturbance_grows_at_the_root_of_the_linearised_motion(plane):
    """The nonlinear equations, integrated, reduce near straight motion to those whose roots the stability
    analysis gives: AFF-8's table of record (unstable in both planes, the mesh's straight-course offsets
    dropped) grows at the positive root to 0.1 %, a stable table decays at its slowest root."""
    table = aff8_medium()
    simulation = ManoeuvreSimulation(QuasiSteadyLoads(table), ACCELERATION, MASS, plane, straight_offsets=False)
    rate = "r" if plane == "horizontal" else "q"
    trajectory = simulation.run(12, rate=1e-7)
    assert growth_rate(trajectory, rate, 6, 10) == pytest.approx(
        plane_motion(table, ACCELERATION, plane, MASS).growth_rate, rel=1e-3)
    stable = ManoeuvreSimulation(QuasiSteadyLoads(STABLE), ACCELERATION, MASS, plane).run(6, rate=1e-4)
    motion = plane_motion(STABLE, ACCELERATION, plane, MASS)
    assert motion.growth_rate < 0 and motion.halving_lengths is not None
    assert growth_rate(stable, rate, 3, 6) == pytest.approx(motion.growth_rate, rel=0.01)


def test_mirror_image_disturbances_give_mirror_image_motions():
    """Port and starboard: a yaw rate of either sign from the (mirror-symmetric) AFF-8 table without its
    offsets gives the same speed and advance and opposite sway, yaw rate, transfer and heading, out into the
    nonlinear, extrapolated turn."""
    table = aff8_medium()
    simulation = ManoeuvreSimulation(QuasiSteadyLoads(table), ACCELERATION, MASS, straight_offsets=False)
    starboard, port = (simulation.run(10, rate=sign * 0.01).states for sign in (1.0, -1.0))
    for name in ("u", "x"):
        assert port[name] == pytest.approx(starboard[name], rel=1e-6, abs=1e-9)
    for name in ("v", "r", "y", "psi"):
        assert port[name] == pytest.approx(-starboard[name], rel=1e-6, abs=1e-9)
    assert starboard["psi"][-1] > 1.0  # it did turn, to starboard


def test_the_motion_beyond_the_tables_conditions_is_flagged():
    table = aff8_medium()
    reach = table_reach(table)
    assert reach["r"] == pytest.approx(0.3) and reach["v"] == pytest.approx(np.sin(np.radians(4)))
    simulation = ManoeuvreSimulation(QuasiSteadyLoads(table), ACCELERATION, MASS, reach=reach, straight_offsets=False)
    assert simulation.run(2, rate=0.01).beyond_range == []
    flagged = simulation.run(10, rate=0.01).beyond_range
    assert any(text.startswith("|r'| reaches") for text in flagged)


def test_a_hydrostatic_moment_rights_a_pitch_disturbance():
    """With its centre of gravity below its centre of buoyancy, a vehicle that is stable in pitch returns to
    level: the pitch attitude decays where without the moment it would stay."""
    def attitude(moment):
        simulation = ManoeuvreSimulation(QuasiSteadyLoads(STABLE), ACCELERATION, MASS, "vertical",
                                         hydrostatic_moment_prime=moment)
        return np.abs(simulation.run(20, heading=0.01).states["theta"][-1])

    assert attitude(0.0) == pytest.approx(0.01, rel=1e-6)  # no restoring moment: it keeps its attitude
    assert attitude(0.002) < 0.002


@pytest.mark.parametrize("moment", [0.0003, 0.01])
def test_with_a_hydrostatic_moment_a_small_pitch_disturbance_follows_the_linearised_cubic(moment):
    """AFF-8's table of record (offsets dropped) with the restoring moment h': the nonlinear equations from a
    small pitch rate follow exp(A t) of the linearised (w', q', theta) system, built here from the stiffness
    and mass matrices, to 0.1 % of the motion's size; its largest root is the stability analysis's. With
    h' = 0.0003 one root grows, with 0.01 (below the critical speed) the attitude oscillates and decays."""
    from scipy.linalg import expm

    table = aff8_medium()
    simulation = ManoeuvreSimulation(QuasiSteadyLoads(table), ACCELERATION, MASS, "vertical",
                                     hydrostatic_moment_prime=moment, straight_offsets=False)
    trajectory = simulation.run(8, rate=1e-7)
    stiffness = np.block([[stiffness_matrix(table, "vertical", MASS), np.array([[0.0], [-moment]])],
                          [np.array([[0.0, 1.0, 0.0]])]])
    inertia = np.block([[mass_matrix(ACCELERATION, "vertical", MASS), np.zeros((2, 1))], [np.array([[0.0, 0.0, 1.0]])]])
    system = np.linalg.solve(inertia, stiffness)
    linear = np.array([expm(system * t) @ np.array([0.0, 1e-7, 0.0]) for t in trajectory.time])
    for k, name in enumerate(("w", "q", "theta")):
        assert trajectory.states[name] == pytest.approx(linear[:, k], abs=1e-3 * np.max(np.abs(linear[:, k])))
    motion = plane_motion(table, ACCELERATION, "vertical", MASS, moment)
    assert motion.growth_rate == pytest.approx(max(np.linalg.eigvals(system).real), rel=1e-9)
    assert (motion.growth_rate > 0) == (moment < 0.005)


def test_impossible_simulations_are_named():
    loads = QuasiSteadyLoads(STABLE)
    with pytest.raises(ConfigurationError, match="unknown plane"):
        ManoeuvreSimulation(loads, ACCELERATION, MASS, "diagonal")
    with pytest.raises(ConfigurationError, match="pitch"):
        ManoeuvreSimulation(loads, ACCELERATION, MASS, "horizontal", hydrostatic_moment_prime=0.001)
    with pytest.raises(ConfigurationError, match="zero or positive"):  # centre of gravity above the buoyancy
        ManoeuvreSimulation(loads, ACCELERATION, MASS, "vertical", hydrostatic_moment_prime=-0.001)
    with pytest.raises(ConfigurationError, match="Xudot"):
        ManoeuvreSimulation(loads, {k: v for k, v in ACCELERATION.items() if k != "Xudot"}, MASS)
    with pytest.raises(ConfigurationError, match="moment of inertia"):
        ManoeuvreSimulation(loads, ACCELERATION, MassProperties(0.018, 0.0, "no inertia"))
    no_drag = {k: v for k, v in STABLE.items() if k != "extended"}
    with pytest.raises(ConfigurationError, match="drag"):
        ManoeuvreSimulation(QuasiSteadyLoads(no_drag), ACCELERATION, MASS)
    yaw_only = linear_table(Yv=-0.03, Nv=-0.004, Yr=0.006, Nr=-0.005)
    with pytest.raises(ConfigurationError, match="no Zw, Mw, Zq, Mq"):
        ManoeuvreSimulation(QuasiSteadyLoads(yaw_only), ACCELERATION, MASS, "vertical")
    simulation = ManoeuvreSimulation(loads, ACCELERATION, MASS)
    for bad, message in (({"lengths": 0}, "positive number"), ({"lengths": 5, "surge": -1.0}, "moving ahead"),
                         ({"lengths": 5, "rate": np.nan}, "finite"), ({"lengths": 5, "surge": 1e-8}, "come to rest")):
        with pytest.raises(ConfigurationError, match=message):
            simulation.run(**bad)
