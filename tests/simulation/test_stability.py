"""Straight-line stability from the derivative table: the criterion against the eigenvalues of the
linearised equations of motion, the two planes against each other, and the committed tables."""

import json
from pathlib import Path

import numpy as np
import pytest

from hydroderiv.case import Condition
from hydroderiv.derivatives.table import derivative_table, write_table
from hydroderiv.errors import ConfigurationError
from hydroderiv.experiments import DERIVATIVES
from hydroderiv.geometry.surfaces import cross_section_areas
from hydroderiv.simulation import MassProperties, plane_stability, stability
from hydroderiv.simulation.stability import (
    ACCELERATION,
    GRAVITY,
    PLANES,
    hydrostatic_moment_prime,
    mass_matrix,
    plane_motion,
    stability_report,
    stiffness_matrix,
    vertical_characteristic_coefficients,
    vertical_stable_speeds,
)

ROOT = Path(__file__).parent.parent.parent
SUBOFF_MASS = MassProperties(mass_prime=0.01825, xg_prime=0.0008, source="test")


def random_plane(rng):
    """Derivatives of the usual signs and sizes for a submarine (prime units), drawn at random."""
    return {"force_velocity": -rng.uniform(0.005, 0.05), "moment_velocity": rng.uniform(-0.02, 0.01),
            "force_rate": rng.uniform(-0.01, 0.01), "moment_rate": -rng.uniform(0.001, 0.01)}


def as_plane(plane, d):
    return dict(zip(PLANES[plane], (d["force_velocity"], d["moment_velocity"], d["force_rate"], d["moment_rate"])))


def random_mass_matrix(rng, mass_prime):
    """Body plus added mass: symmetric positive definite, diagonal of the right size, coupled at random."""
    m11 = mass_prime * rng.uniform(1.2, 2.5)
    m22 = 0.001 * rng.uniform(0.3, 2.0)  # I' plus the added moment of inertia
    m12 = rng.uniform(-0.9, 0.9) * np.sqrt(m11 * m22)
    return np.array([[m11, m12], [m12, m22]])


@pytest.mark.parametrize("plane", list(PLANES))
def test_a_negative_criterion_is_a_divergent_root_whatever_the_added_mass(plane):
    """M x. = K x: det K < 0 gives exactly one real positive eigenvalue for any positive-definite M; with
    det K > 0 and a negative trace of M^-1 K every root decays. The criterion needs no acceleration derivative."""
    rng = np.random.default_rng(7)
    unstable = stable = 0
    for _ in range(400):
        derivatives = as_plane(plane, random_plane(rng))
        mass = MassProperties(rng.uniform(0.01, 0.03), rng.uniform(-0.02, 0.02), "random")
        result = plane_stability(derivatives, plane, mass)
        system = np.linalg.solve(random_mass_matrix(rng, mass.mass_prime), stiffness_matrix(derivatives, plane, mass))
        roots = np.linalg.eigvals(system)
        if result.criterion < 0:
            unstable += 1
            assert not result.stable
            positive = [r for r in roots if abs(r.imag) < 1e-12 and r.real > 0]
            assert len(positive) == 1
        elif np.trace(system) < 0:
            stable += 1
            assert result.stable and np.all(roots.real < 0)
    assert unstable > 50 and stable > 50  # both sides were exercised


@pytest.mark.parametrize("plane", list(PLANES))
def test_index_is_one_less_the_ratio_of_the_levers(plane):
    rng = np.random.default_rng(3)
    derivatives = as_plane(plane, random_plane(rng))
    s = plane_stability(derivatives, plane, SUBOFF_MASS)
    (a, b), (c, d) = stiffness_matrix(derivatives, plane, SUBOFF_MASS)
    assert s.index == pytest.approx(1 - s.static_lever / s.damping_lever, rel=1e-12)
    assert s.index == pytest.approx(s.criterion / (a * d), rel=1e-12)
    # the static lever is where the force per velocity acts: N = x Y in yaw, M = -x Z in pitch
    force, moment = derivatives[PLANES[plane][0]], derivatives[PLANES[plane][1]]
    assert s.static_lever == pytest.approx(moment / force if plane == "horizontal" else -moment / force)


def test_a_body_turned_by_90_degrees_has_the_same_stability_in_the_other_plane():
    """Turn an axisymmetric body about its axis and its yaw plane becomes its pitch plane, with the signs
    of body axes (z down, q > 0 nose up): Z'w = Y'v, M'w = -N'v, Z'q = -Y'r, M'q = N'r. Its stability must not
    change: this checks the vertical plane's formulas (where m' enters with the other sign) against the
    horizontal one's."""
    yaw = DERIVATIVES["AFF-3"]["values"]
    pitch = {"Zw": yaw["Yv"], "Mw": -yaw["Nv"], "Zq": -yaw["Yr"], "Mq": yaw["Nr"]}
    result = stability({**yaw, **pitch}, SUBOFF_MASS)
    h, v = result["horizontal"], result["vertical"]
    for key in ("criterion", "index", "static_lever", "damping_lever"):
        assert getattr(v, key) == pytest.approx(getattr(h, key), rel=1e-12)


def test_the_index_uncertainty_is_the_spread_of_the_index_over_the_derivatives_uncertainty():
    """First-order propagation of independent standard errors against a Monte Carlo draw."""
    values = DERIVATIVES["AFF-8"]["values"]
    stderr = {k: 0.01 * abs(values[k]) for k in PLANES["horizontal"]}
    s = plane_stability(values, "horizontal", SUBOFF_MASS, stderr)
    rng = np.random.default_rng(11)
    draws = [plane_stability({k: values[k] + rng.normal(0, stderr[k]) for k in stderr}, "horizontal", SUBOFF_MASS).index
             for _ in range(4000)]
    assert s.index_stderr == pytest.approx(np.std(draws), rel=0.06)
    assert plane_stability(values, "horizontal", SUBOFF_MASS).index_stderr is None  # none given, none claimed
    assert plane_stability(values, "horizontal", SUBOFF_MASS, {**stderr, "Yr": np.nan}).index_stderr is None


def test_a_plane_without_all_its_derivatives_is_named_or_left_out():
    values = {"Yv": -0.0278, "Nv": -0.0135, "Yr": 0.00325}
    with pytest.raises(ConfigurationError, match="lacks Nr"):
        plane_stability(values, "horizontal", SUBOFF_MASS)
    assert stability(values, SUBOFF_MASS) == {}
    with pytest.raises(ConfigurationError, match="unknown plane"):
        plane_stability(values, "diagonal", SUBOFF_MASS)
    with pytest.raises(ConfigurationError, match="mass m' must be positive"):
        MassProperties(0.0, 0.0, "empty")


def test_neutral_buoyancy_takes_the_displaced_water_and_the_centre_of_buoyancy(suboff):
    body = suboff("AFF-1")
    mass = MassProperties.neutrally_buoyant(body)
    assert mass.mass_prime == pytest.approx(2 * 0.6992 / 4.261**3, rel=0.002)
    # Groves et al.: centre of buoyancy 2.0086 m aft of the nose, the moment centre 2.013 m
    assert mass.xg_prime * 4.261 == pytest.approx(2.013 - 2.0086, abs=1e-3)


def yaw_plane_results(yv=-0.0278, nv=-0.0135, yr=0.00325, nr=-0.00372):
    """Condition records of a drift and a turn sweep with linear loads (what a study's result.json holds)."""
    records = []
    for drift, rate in [(b, 0.0) for b in (-4, 0, 4)] + [(0, r) for r in (-0.2, -0.1, 0.1, 0.2)]:
        c = Condition(3.344, drift_deg=drift, yaw_rate_prime=rate)
        u, v, _ = c.body_velocity() / c.speed
        loads = dict.fromkeys("XYZKMN", 0.0)
        loads.update(Y=yv * u * v + yr * rate, N=nv * u * v + nr * rate)
        records.append({"condition": c.__dict__, "coefficients": loads})
    return records


def test_the_table_records_the_stability_beside_the_experiments(tmp_path):
    rows = derivative_table(yaw_plane_results(), reference_key="AFF-8")
    values = {r.name: r.value for r in rows}
    report = stability_report(values, {r.name: r.stderr for r in rows}, SUBOFF_MASS, DERIVATIVES["AFF-8"]["values"])
    assert set(report) == {"mass", "horizontal"}  # no pitch sweeps in the synthetic study
    assert report["horizontal"]["computed"]["index"] == pytest.approx(
        plane_stability(values, "horizontal", SUBOFF_MASS).index, rel=1e-12)
    measured = plane_stability(DERIVATIVES["AFF-8"]["values"], "horizontal", SUBOFF_MASS)
    assert report["horizontal"]["experiment"]["index"] == pytest.approx(measured.index, rel=1e-12)
    json_path, _ = write_table(rows, tmp_path / "d.json", {"level": "x"}, stability=report)
    assert json.loads(json_path.read_text())["stability"]["horizontal"]["experiment"]["stable"] is measured.stable


@pytest.mark.parametrize("config", ["AFF-8", "AFF-3"])
def test_the_committed_tables_of_record_carry_the_stability_of_their_own_derivatives(config):
    """The stability a medium table of record holds is what its own derivatives, standard errors and mass
    give (so a refit cannot leave it stale), the experiment's is Roddy's derivatives with the same mass, and
    the computed table reaches the experiment's verdict: SUBOFF is unstable in the horizontal plane, controls
    fixed, because the static lever is longer than the damping lever."""
    table = json.loads((ROOT / f"validation/derivatives-{config}-medium.json").read_text())
    recorded = table["stability"]
    mass = MassProperties(**recorded["mass"])
    stderr = {k: v["stderr"] for k, v in table["details"].items()}
    for plane in PLANES:
        if not all(k in table for k in PLANES[plane]):
            assert plane not in recorded
            continue
        computed = plane_stability(table, plane, mass, stderr).as_dict()
        computed["motion"] = plane_motion(table, table["acceleration"]["values"], plane, mass).as_dict()
        for key, value in recorded[plane]["computed"].items():
            assert computed[key] == (pytest.approx(value, rel=1e-9) if isinstance(value, float) else value)
    horizontal = recorded["horizontal"]
    measured = plane_stability(DERIVATIVES[config]["values"], "horizontal", mass)
    assert horizontal["experiment"]["index"] == pytest.approx(measured.index, rel=1e-9)
    assert horizontal["computed"]["stable"] is measured.stable is False
    assert horizontal["computed"]["static_lever"] > horizontal["computed"]["damping_lever"] > 0
    # the computed derivatives' shorter damping lever makes the divergence faster than the experiment's
    assert 0 < horizontal["computed"]["motion"]["doubling_lengths"] < horizontal["experiment"]["motion"]["doubling_lengths"]


def test_aff8_in_pitch_is_as_unstable_as_aff3_in_yaw_with_the_sail_edge_on():
    """AFF-8's vertical plane (hull and cruciform stern, the sail edge-on to w and q) repeats AFF-3's
    horizontal plane, on two different meshes, to 5 % in the stability index."""
    def recorded(config):
        return json.loads((ROOT / f"validation/derivatives-{config}-medium.json").read_text())["stability"]

    assert recorded("AFF-8")["vertical"]["computed"]["index"] == pytest.approx(
        recorded("AFF-3")["horizontal"]["computed"]["index"], rel=0.05)


def random_acceleration(rng, plane):
    """Acceleration derivatives of the usual signs and sizes (prime units), the coupling at random."""
    names = ACCELERATION[plane]
    translation, rotation = -rng.uniform(0.01, 0.03), -rng.uniform(0.0005, 0.002)
    coupling = rng.uniform(-0.5, 0.5) * np.sqrt(translation * rotation)
    return dict(zip(names, (translation, coupling, coupling, rotation)))


@pytest.mark.parametrize("plane", list(PLANES))
def test_the_roots_of_the_motion_solve_its_characteristic_equation_and_follow_the_criterion(plane):
    """det(K - lambda M) = 0 at each root; one root is positive exactly when the criterion is negative; a
    disturbance doubles over ln 2 / lambda body lengths."""
    rng = np.random.default_rng(5)
    signs = set()
    for _ in range(200):
        derivatives = as_plane(plane, random_plane(rng))
        mass = MassProperties(rng.uniform(0.01, 0.03), rng.uniform(-0.02, 0.02), "random",
                              iz_prime=rng.uniform(0.0005, 0.002), iy_prime=rng.uniform(0.0005, 0.002))
        acceleration = random_acceleration(rng, plane)
        motion = plane_motion(derivatives, acceleration, plane, mass)
        stiffness, inertia = stiffness_matrix(derivatives, plane, mass), mass_matrix(acceleration, plane, mass)
        for root in motion.roots:
            assert abs(np.linalg.det(stiffness - root * inertia)) < 1e-9 * abs(np.linalg.det(stiffness))
        criterion = plane_stability(derivatives, plane, mass).criterion
        if criterion < 0:
            assert motion.growth_rate > 0 and motion.doubling_lengths == pytest.approx(np.log(2) / motion.growth_rate)
            assert motion.halving_lengths is None
        signs.add(criterion < 0)
    assert signs == {True, False}


def test_the_mass_matrix_holds_the_body_and_its_added_mass_with_the_planes_signs():
    """Yaw: m' - Y'v., m' x_G' - Y'r.; pitch: m' - Z'w., -(m' x_G' + Z'q.) (q > 0 nose up)."""
    mass = MassProperties(0.018, 0.001, "test", iz_prime=0.0011, iy_prime=0.0012)
    yaw = mass_matrix({"Yvdot": -0.017, "Nvdot": 0.0002, "Yrdot": 0.0003, "Nrdot": -0.001}, "horizontal", mass)
    assert yaw == pytest.approx(np.array([[0.035, 0.018e-3 - 0.0003], [0.018e-3 - 0.0002, 0.0021]]))
    pitch = mass_matrix({"Zwdot": -0.017, "Mwdot": -0.0002, "Zqdot": -0.0003, "Mqdot": -0.001}, "vertical", mass)
    assert pitch == pytest.approx(np.array([[0.035, -(0.018e-3 - 0.0003)], [-(0.018e-3 - 0.0002), 0.0022]]))
    with pytest.raises(ConfigurationError, match="Nrdot"):
        mass_matrix({"Yvdot": -0.017}, "horizontal", mass)
    with pytest.raises(ConfigurationError, match="moment of inertia I'z"):
        mass_matrix({"Yvdot": -0.017, "Nvdot": 0.0, "Yrdot": 0.0, "Nrdot": -0.001}, "horizontal", SUBOFF_MASS)
    with pytest.raises(ConfigurationError, match="at least m' x_G'"):
        MassProperties(0.018, 0.3, "test", iz_prime=0.001)


def test_neutral_buoyancy_takes_the_inertia_of_the_displaced_water(suboff):
    """Of the axisymmetric hull, by sections: I = rho \\int (x^2 A + A^2 / (4 pi)) dx, A(x) the section area
    (a disc's second moment about a diameter is pi R^4 / 4), against the surface's own moments."""
    body = suboff("AFF-1")
    mass = MassProperties.neutrally_buoyant(body)
    lo, hi = body.surface.bounds[:, 0]
    x = np.linspace(lo, hi, 4001)
    area = cross_section_areas(body.surface, x)
    by_sections = np.trapezoid(x**2 * area + area**2 / (4 * np.pi), x)
    length = body.reference.length
    assert mass.iz_prime == pytest.approx(2 * by_sections / length**5, rel=0.002)
    assert mass.iy_prime == pytest.approx(mass.iz_prime, rel=1e-6)


def random_vertical_vehicle(rng):
    """A vertical plane of the usual signs (stable or not on its hydrodynamics), its mass and added mass."""
    derivatives = as_plane("vertical", random_plane(rng))
    mass = MassProperties(rng.uniform(0.01, 0.03), rng.uniform(-0.02, 0.02), "random",
                          iy_prime=rng.uniform(0.0005, 0.002))
    return derivatives, mass, random_acceleration(rng, "vertical")


def test_a_hydrostatic_moment_adds_the_attitude_and_its_cubic():
    """With h' > 0 the pitch attitude joins the state: three roots, each a root of the cubic whose
    coefficients are linear in h' (lambda det(lambda M - K) + h' ((m' - Z'w.) lambda - Z'w)); as h' fades the
    two roots without it come back and the third (the attitude's) goes to zero."""
    rng = np.random.default_rng(11)
    for _ in range(100):
        derivatives, mass, acceleration = random_vertical_vehicle(rng)
        h = rng.uniform(1e-5, 1e-2)
        motion = plane_motion(derivatives, acceleration, "vertical", mass, h)
        assert len(motion.roots) == 3 and motion.hydrostatic_moment_prime == h
        cubic = [c + s * h for c, s in vertical_characteristic_coefficients(derivatives, acceleration, mass)]
        for root in motion.roots:
            assert abs(np.polyval(cubic, root)) < 1e-9 * max(abs(c * root**k) for k, c in enumerate(cubic[::-1]))
        faded = plane_motion(derivatives, acceleration, "vertical", mass, 1e-12).roots
        without = plane_motion(derivatives, acceleration, "vertical", mass).roots
        assert len(without) == 2 and min(abs(r) for r in faded) < 1e-6
        kept = sorted(r.real for r in faded if abs(r) > 1e-6)
        assert kept == pytest.approx(sorted(r.real for r in without), abs=1e-6)
    with pytest.raises(ConfigurationError, match="acts in pitch"):
        plane_motion(as_plane("horizontal", random_plane(rng)), random_acceleration(rng, "horizontal"), "horizontal",
                     MassProperties(0.018, 0.0, "test", iz_prime=0.001), 1e-3)


def test_the_stable_speeds_are_where_every_root_decays():
    """The Hurwitz range of speeds against the roots themselves: inside it every root decays, outside one
    grows, at its ends the largest real part is zero. A vehicle unstable on its hydrodynamics (C_V < 0) is
    held by the restoring moment up to a critical speed, which grows as sqrt(z_BG)."""
    rng = np.random.default_rng(12)
    seen = set()
    for _ in range(200):
        derivatives, mass, acceleration = random_vertical_vehicle(rng)
        bg = rng.uniform(0.005, 0.1)
        speeds = vertical_stable_speeds(derivatives, acceleration, mass, bg)

        def growth(speed):
            return plane_motion(derivatives, acceleration, "vertical", mass,
                                hydrostatic_moment_prime(mass, bg, speed)).growth_rate

        if not speeds.stable_anywhere:
            assert all(growth(u) > 0 for u in (0.1, 1.0, 3.0, 10.0))
            seen.add("never")
            continue
        low, high = speeds.lowest_m_s, speeds.highest_m_s
        inside = [low * 1.1 + 0.01] if high is None else [low + (high - low) * f for f in (0.05, 0.5, 0.95)]
        assert all(growth(u) < 0 for u in inside)
        for end in (low, high):
            if end:
                assert growth(end) == pytest.approx(0.0, abs=1e-9)
        if high is not None:
            assert growth(high * 1.05) > 0
            assert plane_stability(derivatives, "vertical", mass).criterion < 0
            quadrupled = vertical_stable_speeds(derivatives, acceleration, mass, 4 * bg)
            assert quadrupled.highest_m_s == pytest.approx(2 * high)
            seen.add("up to a critical speed")
        else:
            seen.add("at any speed")
    assert {"up to a critical speed", "at any speed"} <= seen


def test_aff8s_table_of_record_is_held_in_pitch_only_at_low_speed():
    """AFF-8's computed vertical plane is unstable on its hydrodynamics (G_V < 0): with its centre of gravity
    2 cm below its buoyancy the restoring moment holds it only up to a critical speed, far below the 6.5 kn of
    the tests; at that speed the roots are a neutral oscillation; the report records both; bad input is named."""
    table = json.loads((ROOT / "validation/derivatives-AFF-8-medium.json").read_text())
    mass = MassProperties(**table["stability"]["mass"])
    acceleration = table["acceleration"]["values"]
    speed = table["meta"]["speed_m_s"]
    speeds = vertical_stable_speeds(table, acceleration, mass, 0.02)
    assert speeds.lowest_m_s == 0.0 and 0 < speeds.highest_m_s < speed
    critical = hydrostatic_moment_prime(mass, 0.02, speeds.highest_m_s)
    at_critical = plane_motion(table, acceleration, "vertical", mass, critical)
    oscillation = [r for r in at_critical.roots if abs(r.imag) > 1e-6]
    assert len(oscillation) == 2 and all(abs(r.real) < 1e-9 for r in oscillation)
    report = stability_report(table, {}, mass, None, acceleration, bg_m=0.02, speed_m_s=speed)
    vertical = report["vertical"]["computed"]
    assert vertical["stable_speeds"]["highest_m_s"] == pytest.approx(speeds.highest_m_s)
    assert vertical["motion"]["hydrostatic_moment_prime"] == pytest.approx(mass.mass_prime * GRAVITY * 0.02 / speed**2)
    assert len(vertical["motion"]["roots"]) == 3 and vertical["motion"]["growth_rate"] > 0
    assert "stable_speeds" not in report["horizontal"]["computed"]
    with pytest.raises(ConfigurationError, match="needs the speed"):
        stability_report(table, {}, mass, None, acceleration, bg_m=0.02)
    # never dropped in silence: without the vertical plane's motion there are no roots for z_BG to act in
    with pytest.raises(ConfigurationError, match="needs the vertical plane's motion"):
        stability_report(table, {}, mass, None, None, bg_m=0.02, speed_m_s=speed)
    without_pitch_inertia = MassProperties(mass.mass_prime, mass.xg_prime, "no I'y", mass.iz_prime)
    with pytest.raises(ConfigurationError, match="needs the vertical plane's motion"):
        stability_report(table, {}, without_pitch_inertia, None, acceleration, bg_m=0.02, speed_m_s=speed)
    with pytest.raises(ConfigurationError, match="below the centre of buoyancy"):
        vertical_stable_speeds(table, acceleration, mass, 0.0)
    with pytest.raises(ConfigurationError, match="capsizes"):
        hydrostatic_moment_prime(mass, -0.01, speed)


def test_aff8s_critical_moment_in_pitch_repeats_aff3s_turned_by_90_degrees():
    """The sail edge-on to heave and pitch, AFF-8's vertical plane is AFF-3's horizontal one turned
    (Z'w = Y'v, M'w = -N'v, Z'q = -Y'r, M'q = N'r, and likewise the added mass): the least hydrostatic moment
    h' that holds it agrees to 3 % on the two tables of record, computed on different meshes."""
    def critical(config, turn):
        table = json.loads((ROOT / f"validation/derivatives-{config}-medium.json").read_text())
        derivatives = {"Zw": table["Yv"], "Mw": -table["Nv"], "Zq": -table["Yr"], "Mq": table["Nr"]} if turn else table
        speeds = vertical_stable_speeds(derivatives, table["acceleration"]["values"],
                                        MassProperties(**table["stability"]["mass"]), 0.02)
        return speeds.hydrostatic_moment_range[0]

    assert critical("AFF-8", turn=False) == pytest.approx(critical("AFF-3", turn=True), rel=0.03)
