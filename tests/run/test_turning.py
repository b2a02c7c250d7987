"""Captive conditions on the coarse bare-hull mesh: mirror symmetry, the pitch turn as the yaw turn turned about
the axis, the Munk moment, and the two frame methods.

A body of revolution is its own mirror image in the x-z plane, so a port turn must give the side force and
yaw moment of the starboard turn with the sign changed, and so must -beta against +beta; X, Z and M are
unchanged. Hybrid frames and the classic rotating domain describe the same turn on the same mesh.
"""

import math

import numpy as np
import pytest

from hydroderiv.case import Condition
from hydroderiv.case.setup import CaseSettings
from hydroderiv.run.condition import run_condition
from hydroderiv.run.monitor import ConvergenceCriterion

pytestmark = pytest.mark.openfoam

L = 4.261
SPEED = 3.344
RATE = 0.2
DRIFT = 6.0
HULL_LENGTH, HULL_DIAMETER, HULL_VOLUME = 4.356, 0.508, 0.6992  # AFF-1 (Groves et al. 1989)


@pytest.fixture(scope="module")
def runs(coarse_bare_hull, tmp_path_factory):
    """Run (and cache) conditions on the coarse AFF-1 mesh; returns a lookup (condition, method) -> record."""
    mesh_case, _ = coarse_bare_hull
    root = tmp_path_factory.mktemp("turning")
    done = {}

    def get(condition: Condition, method: str = "hybrid") -> dict:
        key = (condition, method)
        if key not in done:
            settings = CaseSettings(length=L, components=("hull",), n_procs=2, max_iterations=800, method=method)
            # A mean drifting by 1 % of the load over the window is enough for comparisons at the 5 %
            # level. The classic domain keeps a slow oscillation of about +-0.8 % in X' (a period of ~120
            # iterations; its open far field is swept by the frame at up to 2 U), so it gets 2 %.
            tolerance = 0.02 if method == "classic" else 0.01
            done[key] = run_condition(root / f"{method}-{condition.name}", mesh_case, condition, settings,
                                      ConvergenceCriterion(min_iterations=100, rel_tol=tolerance))
        return done[key]

    return get


def _mirrored(a: dict, b: dict, tolerance: float) -> None:
    """Odd coefficients (Y', N') change sign and even ones (X', M') stay: X' to within ``tolerance`` of
    itself, the others to within ``tolerance`` of the largest lateral load max(|Y'|, |N'|).

    The background grid is shifted by a third of a cell in y as well as z (see GRID_SHIFT), so the mesh is
    only nearly its own mirror image; measured on the coarse bare hull in r' = +-0.2: X' differs by 1.2 %,
    N' by 2.8 % and Y' (~2e-5) by 3e-6.
    """
    ca, cb = a["coefficients"], b["coefficients"]
    odd_scale = max(abs(ca["Y"]), abs(ca["N"]))
    for odd in ("Y", "N"):
        assert abs(ca[odd] + cb[odd]) <= tolerance * odd_scale, (odd, ca[odd], cb[odd])
    assert abs(cb["X"] - ca["X"]) <= tolerance * abs(ca["X"]), (ca["X"], cb["X"])
    assert abs(cb["M"] - ca["M"]) <= tolerance * odd_scale, (ca["M"], cb["M"])


def test_port_turn_mirrors_the_starboard_turn(runs):
    starboard = runs(Condition(SPEED, yaw_rate_prime=RATE))
    port = runs(Condition(SPEED, yaw_rate_prime=-RATE))
    assert starboard["converged"] and port["converged"]
    _mirrored(starboard, port, tolerance=0.05)
    # turning to starboard, the hull's yaw moment opposes the rotation (N'r < 0)
    assert starboard["coefficients"]["N"] < 0


def test_the_loads_along_the_hull_mirror_between_the_turns_and_add_up_to_its_side_force(runs):
    starboard = runs(Condition(SPEED, yaw_rate_prime=RATE))
    port = runs(Condition(SPEED, yaw_rate_prime=-RATE))
    along, mirrored = starboard["loads_along_x"]["hull"], port["loads_along_x"]["hull"]
    largest = max(abs(s["Y"]) for s in along)
    assert [s["faces"] for s in mirrored] == [s["faces"] for s in along]
    assert [s["Y"] for s in mirrored] == pytest.approx([-s["Y"] for s in along], abs=0.05 * largest)
    assert [s["Z"] for s in mirrored] == pytest.approx([s["Z"] for s in along], abs=0.05 * largest)
    # the slices hold the hull's whole side force (at the last iteration, the record's over its window)
    assert sum(s["Y"] for s in along) == pytest.approx(starboard["coefficients"]["Y"], abs=0.02 * largest)
    # turning to starboard, the nose moves to starboard through the water, which pushes it to port
    assert along[-1]["Y"] < -0.5 * largest


def test_a_pitch_turn_is_the_yaw_turn_turned_about_the_body_axis(runs):
    """A body of revolution turned by 90 degrees about x (y to z, z to -y) takes a yaw turn r' into a pitch
    turn q' = -r', its side force into Z' = Y' and its yaw moment into M' = -N': so Z'q = -Y'r and M'q = N'r.
    This checks the vertical plane's axes and signs (z down, q > 0 nose up) through the same hybrid frames
    and force reduction as the yaw turns. The background grid is shifted alike in y and z (GRID_SHIFT), so
    the turned mesh is only nearly the same; the mirror tolerance applies."""
    yaw = runs(Condition(SPEED, yaw_rate_prime=RATE))
    pitch = runs(Condition(SPEED, pitch_rate_prime=-RATE))
    assert pitch["converged"]
    cy, cp = yaw["coefficients"], pitch["coefficients"]
    scale = max(abs(cy["Y"]), abs(cy["N"]))
    assert abs(cp["Z"] - cy["Y"]) <= 0.05 * scale, (cp["Z"], cy["Y"])
    assert abs(cp["M"] + cy["N"]) <= 0.05 * scale, (cp["M"], cy["N"])
    # out of the plane of the turn: as the yaw turn's Z' and M', i.e. only the offsets of the mesh
    assert abs(cp["Y"]) <= 0.05 * scale and abs(cp["N"]) <= 0.05 * scale, (cp["Y"], cp["N"])
    assert cp["X"] == pytest.approx(cy["X"], rel=0.05)
    # pitching nose down (q' < 0), the hull's pitch moment opposes the rotation: M'q < 0 gives M' > 0
    assert cp["M"] > 0


def test_negative_drift_mirrors_positive_drift_and_the_moment_is_munk_like(runs):
    plus = runs(Condition(SPEED, drift_deg=DRIFT))
    minus = runs(Condition(SPEED, drift_deg=-DRIFT))
    _mirrored(plus, minus, tolerance=0.05)
    # The destabilising Munk moment of potential flow, N' = -(k2 - k1) Vol v'u' / (0.5 L^3), is cut down by
    # the viscous lift of the afterbody but not reversed; k1, k2 of the spheroid of the hull's fineness ratio.
    e = math.sqrt(1.0 - (HULL_DIAMETER / HULL_LENGTH) ** 2)
    log_term = math.log((1.0 + e) / (1.0 - e))
    alpha0 = 2.0 * (1.0 - e**2) / e**3 * (0.5 * log_term - e)
    beta0 = 1.0 / e**2 - (1.0 - e**2) / (2.0 * e**3) * log_term
    k1, k2 = alpha0 / (2.0 - alpha0), beta0 / (2.0 - beta0)
    munk_nv = -(k2 - k1) * HULL_VOLUME / (0.5 * L**3)
    b = math.radians(DRIFT)
    nv = -plus["coefficients"]["N"] / (math.cos(b) * math.sin(b))  # the seed paper's single-point N'v
    assert 0.4 < nv / munk_nv < 1.0, (nv, munk_nv)


def test_hybrid_and_classic_frames_agree_on_a_turn(runs):
    condition = Condition(SPEED, yaw_rate_prime=RATE)
    hybrid, classic = runs(condition), runs(condition, "classic")
    assert classic["converged"]
    ch, cc = hybrid["coefficients"], classic["coefficients"]
    assert cc["X"] == pytest.approx(ch["X"], rel=0.05)
    # The rotary forces of a bare hull are small; the two methods differ in the wake outside the sphere
    # (straight for hybrid, curved for classic), so agreement is in sign and size, not to the last percent.
    for rotary in ("Y", "N"):
        assert np.sign(cc[rotary]) == np.sign(ch[rotary])
        assert abs(cc[rotary] - ch[rotary]) <= 0.25 * abs(ch[rotary]), (rotary, ch[rotary], cc[rotary])
