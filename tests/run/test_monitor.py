"""Reading a solver's log and judging force convergence and divergence."""

import numpy as np
import pytest

from hydroderiv.errors import ConfigurationError
from hydroderiv.run.monitor import ConvergenceCriterion, LogWatcher, force_divergence

LOG = """Time = 1

smoothSolver:  Solving for Ux, Initial residual = 1, Final residual = 0.05, No Iterations 2
smoothSolver:  Solving for Uy, Initial residual = 0.9, Final residual = 0.05, No Iterations 2
GAMG:  Solving for p, Initial residual = 1, Final residual = 0.009, No Iterations 5
GAMG:  Solving for p, Initial residual = 0.3, Final residual = 0.009, No Iterations 5
ExecutionTime = 1.2 s  ClockTime = 1 s

Time = 2

smoothSolver:  Solving for Ux, Initial residual = 0.2, Final residual = 0.01, No Iterations 2
GAMG:  Solving for p, Initial residual = 0.5, Final residual = 0.01, No Iterations 4
"""


def test_log_watcher_takes_the_first_initial_residual_of_the_latest_iteration():
    w = LogWatcher()
    w.feed(LOG[:200])  # a partial feed, cut mid-line
    w.feed(LOG[200:])
    assert w.iteration == 2
    assert w.residuals == {"Ux": 0.2, "Uy": 0.9, "p": 0.5}  # Uy not solved yet in iteration 2: last known value
    assert w.divergence() is None


def test_a_read_ending_right_after_the_time_line_does_not_freeze_the_residuals():
    """MPI output often arrives up to 'Time = N' and stops there while the solve runs; the next read's
    residuals belong to iteration N and must replace those of N - 1 (they once stayed at iteration 1)."""
    w = LogWatcher()
    cut = LOG.index("smoothSolver:  Solving for Ux, Initial residual = 0.2")
    w.feed(LOG[:cut])
    assert w.iteration == 2 and w.residuals["Ux"] == 1
    w.feed(LOG[cut:])
    assert w.residuals == {"Ux": 0.2, "Uy": 0.9, "p": 0.5}


def test_nan_and_exploding_residuals_are_divergence():
    w = LogWatcher()
    w.feed("Time = 7\n\nsmoothSolver:  Solving for Ux, Initial residual = nan, Final residual = nan, No Iterations 1000\n")
    assert "Ux residual is nan at iteration 7" in w.divergence()
    w = LogWatcher()
    w.feed("Time = 8\n\nGAMG:  Solving for p, Initial residual = 5e+06, Final residual = 1, No Iterations 1000\n")
    assert "exploded" in w.divergence()


def test_convergence_needs_a_settled_mean_after_the_minimum_iterations():
    c = ConvergenceCriterion(window=50, rel_tol=0.005, abs_tol=1e-6, min_iterations=100)
    it = np.arange(1, 301)
    decaying = np.zeros((len(it), 6))
    decaying[:, 0] = 1e-3 * (1 + np.exp(-it / 20.0))  # drag settles
    decaying[:, 1] = 1e-8 * np.sin(it)  # side force ~0 within the absolute tolerance
    assert not c.is_met(it[:80], decaying[:80])  # before min_iterations
    assert c.is_met(it, decaying)
    assert not c.is_met(it[:120], decaying[:120])  # exp(-6): still falling by 0.6 % over the window


def test_a_warm_start_that_dips_and_recovers_is_not_taken_for_converged():
    """The drag of the medium AFF-8 at 13.92 knots, warm-started from 11.85 knots (X' every 25 iterations from
    its log): it overshoots, dips 10 % below its final value at iteration 52 and recovers by 200. A window
    reaching back to iteration 30 straddles the V, and the straight line through it is flat."""
    logged = [1, 27, 52, 77, 102, 127, 152, 177, 202, 227, 400]
    drag = [-2.135e-3, -1.132e-3, -9.282e-4, -9.585e-4, -9.783e-4, -1.013e-3, -1.026e-3, -1.029e-3, -1.031e-3,
            -1.031e-3, -1.031e-3]
    it = np.arange(1, 401)
    loads = np.zeros((len(it), 6))
    loads[:, 0] = np.interp(it, logged, drag)
    met = [n for n in range(100, 400) if ConvergenceCriterion(monitored=("X",)).is_met(it[:n], loads[:n])]
    assert met[0] > 240  # once the drag has settled
    assert loads[met[0] - 1, 0] == pytest.approx(-1.031e-3, rel=0.005)
    # With windows that may reach back to iteration 1, the straight line through the V is flat around
    # iteration 120; the earlier window that must agree holds the dip, so that is not taken for settled either.
    reaching_back = ConvergenceCriterion(monitored=("X",), min_iterations=100)
    assert any(np.all(reaching_back.drift(loads[:n]) <= 1.0) for n in range(100, 140))
    assert not any(reaching_back.is_met(it[:n], loads[:n]) for n in range(100, 140))


def test_a_turn_whose_side_force_dips_mid_window_waits_for_it_to_settle():
    """The main job's coarse AFF-8 turn at r' = +0.1 (Spalart-Allmaras, warm-started from straight ahead): Y'
    every five iterations from a run continued to 201, held at its last value after that (it rose by 0.1 %
    over its last 15 iterations). The 60-iteration line through the dip at iteration 93 is flat around
    iteration 125, when Y' is still 8 % short of where it settles; the main job stopped there."""
    logged = np.arange(66, 202, 5)
    side = 1e-3 * np.array([0.14201, 0.13526, 0.13029, 0.12660, 0.12420, 0.12324, 0.12332, 0.12486, 0.12669,
                            0.12914, 0.13132, 0.13346, 0.13521, 0.13664, 0.13773, 0.13857, 0.13915, 0.13956,
                            0.13988, 0.14010, 0.14025, 0.14040, 0.14047, 0.14055, 0.14066, 0.14068, 0.14072,
                            0.14078])
    it = np.arange(1, 301)
    loads = np.zeros((len(it), 6))
    loads[:, 0] = -1.356e-3
    loads[:, 1] = np.interp(it, logged, side)  # held at 0.142e-3 before iteration 66: no matter, it is flat
    loads[:, 5] = np.interp(it, logged, np.linspace(-0.2833e-3, -0.2791e-3, len(logged)))
    criterion = ConvergenceCriterion(window=60, rel_tol=0.015, min_iterations=110).holding_to_own_size(("Y", "N"))
    trend_flat = [n for n in range(110, 301) if np.all(criterion.drift(loads[:n]) <= 1.0)]
    assert trend_flat[0] < 130 and loads[trend_flat[0] - 60 : trend_flat[0], 1].mean() < 0.94 * side[-1]
    met = [n for n in range(110, 301) if criterion.is_met(it[:n], loads[:n])]
    assert met and met[0] > 190
    assert loads[met[0] - 60 : met[0], 1].mean() == pytest.approx(side[-1], rel=0.015)


def test_the_trend_is_the_least_squares_line_of_each_window():
    """The running-sum trends equal a straight line fitted to each window afresh, and the drift is the
    latest window's, held to the largest load of its kind or, for the loads named, to their own size."""
    rng = np.random.default_rng(4)
    loads = 1e-3 * (rng.normal(size=(90, 6)) * 0.01 + np.array([-1.3, 0.4, -0.05, 0.002, 0.3, -0.2]))
    loads += 1e-6 * np.arange(90)[:, None] * np.array([1, -2, 3, 0.1, -1, 2])
    c = ConvergenceCriterion(window=40, rel_tol=0.01, abs_tol=1e-9, own_scale=("Z",))
    for end in (40, 65, 90):
        window = loads[end - 40 : end]
        rise = np.abs(np.polyfit(np.arange(40), window, 1)[0]) * 39
        mean = np.abs(window.mean(axis=0))
        allowed = 0.01 * np.array([mean[:3].max(), mean[:3].max(), mean[2], *[mean[3:].max()] * 3])
        assert c.drift(loads[:end]) == pytest.approx(rise / allowed, rel=1e-9)
    # before a full window, the drift of the samples there are (the progress display asks for it)
    start = loads[:25]
    mean = np.abs(start.mean(axis=0))
    allowed = 0.01 * np.array([mean[:3].max(), mean[:3].max(), mean[2], *[mean[3:].max()] * 3])
    rise = np.abs(np.polyfit(np.arange(25), start, 1)[0]) * 24
    assert c.drift(start) == pytest.approx(rise / allowed, rel=1e-9)


def test_windows_before_a_scheme_switch_are_not_judged():
    it = np.arange(1, 401)
    loads = np.zeros((len(it), 6))
    loads[:, 0], loads[:, 5] = -1.3e-3, 2e-4  # settled from the start
    c = ConvergenceCriterion(window=100)
    assert c.is_met(it[:200], loads[:200])  # half a window after the first flat window, at 150
    # switched to second-order convection at 150: the latest window and an earlier one must both follow it
    assert not c.is_met(it[:299], loads[:299], since=150)
    assert c.is_met(it[:300], loads[:300], since=150)  # windows 151-250 and 201-300


def test_an_oscillation_about_a_fixed_mean_converges_but_a_creeping_mean_does_not():
    c = ConvergenceCriterion(window=100)
    it = np.arange(1, 501)
    loads = np.zeros((len(it), 6))
    loads[:, 0] = -9e-4
    loads[:, 1] = 6e-4 * (1 + 0.03 * np.sin(2 * np.pi * it / 60.0))  # +-3 % shedding about a fixed mean
    loads[:, 5] = 1.5e-3
    # A window's trend swings with the phase of the oscillation; within one period a window passes.
    assert any(c.is_met(it[:n], loads[:n]) for n in range(300, 360))
    creeping = loads.copy()
    creeping[:, 1] = 6e-4 * (1 + 0.005 * np.sin(2 * np.pi * it / 60.0)) * (1 + 2e-4 * it)  # +2 % per 100
    assert not any(c.is_met(it[:n], creeping[:n]) for n in range(100, 501))


def test_a_small_component_is_judged_against_the_largest_load():
    c = ConvergenceCriterion(window=100, abs_tol=1e-9)
    it = np.arange(1, 201)
    loads = np.zeros((len(it), 6))
    loads[:, 0], loads[:, 1] = -9e-4, 6e-4
    loads[:, 2] = -5e-6 + 1e-8 * it  # Z' drifts by 20 % of itself, 0.1 % of the largest force
    loads[:, 5] = 1.5e-3
    assert c.is_met(it, loads)
    loads[:, 2] = -5e-6 + 1e-7 * it  # now 1 % of the largest force
    assert not c.is_met(it, loads)


def test_a_defining_load_is_held_to_its_own_size():
    # A yaw turn at r' = 0.1: the side force that gives Y'r is a fifth of the drag.
    c = ConvergenceCriterion(window=60, rel_tol=0.015, min_iterations=110)
    it = np.arange(1, 201)
    loads = np.zeros((len(it), 6))
    loads[:, 0] = -1.36e-3
    loads[:, 1] = -3e-4 * (1 + 3e-4 * (it - 200))  # still growing: 1.8 % of itself over the window
    loads[:, 5] = 3.4e-4
    assert c.is_met(it, loads)  # against the drag it passes: 0.4 % of X'
    held = c.holding_to_own_size(("Y", "N"))
    assert held.own_scale == ("Y", "N") and not held.is_met(it, loads)
    loads[:, 1] = -3e-4 * (1 + 1e-4 * (it - 200))  # 0.6 % of itself
    assert held.is_met(it, loads)


def test_holding_to_own_size_keeps_what_was_held_and_refuses_unknown_loads():
    c = ConvergenceCriterion(own_scale=("M",)).holding_to_own_size(("Y", "N", "M"))
    assert c.own_scale == ("M", "Y", "N")
    with pytest.raises(ConfigurationError, match="unknown load coefficient.*Q.*X, Y, Z, K, M, N"):
        ConvergenceCriterion(own_scale=("Q",))
    with pytest.raises(ConfigurationError, match="unknown load coefficient.*drag"):
        ConvergenceCriterion(monitored=("drag",))


def test_only_the_monitored_coefficients_must_settle():
    it = np.arange(1, 301)
    forces = np.zeros((len(it), 6))
    forces[:, 0] = -1.25e-3
    forces[:, 1] = 3e-4 * (1 + 1e-3 * it)  # a side force still creeping
    assert not ConvergenceCriterion().is_met(it, forces)
    assert ConvergenceCriterion(monitored=("X",)).is_met(it, forces)


def test_force_blow_up_is_divergence():
    assert force_divergence(np.array([[1e-3, 0.0]])) is None
    assert "NaN" in force_divergence(np.array([[np.nan, 0.0]]))
    assert "blew up" in force_divergence(np.array([[50.0, 0.0]]))


def test_the_openfoam_release_is_read_from_a_log_header():
    from hydroderiv.run.openfoam import openfoam_version_from_log

    assert openfoam_version_from_log("Build  : OPENFOAM=1912 patch=200626\nArch   : ...") == "1912"
    assert openfoam_version_from_log("| Version:  v2312 |") == "2312"
    assert openfoam_version_from_log("no header") is None
