"""Grid convergence: the three-grid Richardson estimate on exact power laws, and the table comparison."""

import json
import math

import pytest

from hydroderiv.derivatives.convergence import (
    SAFETY_FACTOR,
    grid_convergence,
    level_cell_size,
    three_grid_estimate,
)
from hydroderiv.errors import ConfigurationError
from hydroderiv.experiments import DERIVATIVES


def power_law(exact, constant, order, h):
    return exact + constant * h**order


@pytest.mark.parametrize("order", [1.0, 1.6, 2.0, 3.0])
def test_an_exact_power_law_gives_back_its_order_and_limit(order):
    r = math.sqrt(2.0)
    h1, h2, h3 = 1.0, r, r * r
    values = [power_law(-0.0037, 0.0004, order, h) for h in (h1, h2, h3)]
    estimate = three_grid_estimate(*values, r21=r, r32=r)
    assert estimate.kind == "monotonic"
    assert estimate.order == pytest.approx(order, rel=1e-9)
    assert estimate.extrapolated == pytest.approx(-0.0037, abs=1e-12)
    # the fine value's true error is |phi1 - exact|; the GCI is that times the safety factor
    assert estimate.uncertainty == pytest.approx(SAFETY_FACTOR * abs(values[0] + 0.0037), rel=1e-9)


def test_unequal_refinement_ratios_need_the_iteration_and_still_recover_the_order():
    h1, h2, h3 = 1.0, 1.5, 1.5 * 1.3
    values = [power_law(2.0, -0.7, 1.7, h) for h in (h1, h2, h3)]
    estimate = three_grid_estimate(*values, r21=1.5, r32=1.3)
    assert estimate.order == pytest.approx(1.7, rel=1e-8)
    assert estimate.extrapolated == pytest.approx(2.0, rel=1e-10)


def test_oscillation_gives_half_the_range_and_no_extrapolation():
    estimate = three_grid_estimate(1.00, 1.04, 0.98)  # fine, medium, coarse
    assert estimate.kind == "oscillatory" and estimate.convergence_ratio < 0
    assert estimate.extrapolated is None and estimate.order is None
    assert estimate.uncertainty == pytest.approx(0.03)


def test_values_that_move_more_on_the_finer_pair_are_divergent_and_get_no_uncertainty():
    estimate = three_grid_estimate(1.00, 1.10, 1.15)
    assert estimate.kind == "divergent" and estimate.uncertainty is None


def test_equal_values_are_exact_and_ratios_must_refine():
    assert three_grid_estimate(0.5, 0.5, 0.5).uncertainty == 0.0
    with pytest.raises(ConfigurationError, match="refinement ratios"):
        three_grid_estimate(1.0, 1.1, 1.2, r21=1.0)


def test_levels_are_sqrt_two_apart():
    assert level_cell_size("coarse") / level_cell_size("medium") == pytest.approx(math.sqrt(2.0))
    assert level_cell_size("medium") / level_cell_size("fine") == pytest.approx(math.sqrt(2.0))
    with pytest.raises(ConfigurationError, match="unknown mesh level"):
        level_cell_size("extra-fine")


def table(level, nr_at_01, body="AFF-8", model="ShihQuadraticKE", fit=None):
    return {"Nr": nr_at_01,
            "details": {"Nr": {"value": nr_at_01, "iterative_stderr": 1e-6,
                               "single_point_by_magnitude": {"0.1": nr_at_01}}},
            "meta": {"level": level, "body": body, "turbulence_model": model, "method": "hybrid",
                     "speed_m_s": 3.344, "fit": fit or {"nonlinear": "none", "offset": True}}}


def three_tables(order=2.0, exact=-0.0036, model="ShihQuadraticKE"):
    r = math.sqrt(2.0)
    return {f"{level}.json": table(level, power_law(exact, 0.0008, order, r**i), model=model)
            for i, level in enumerate(("fine", "medium", "coarse"))}


def test_tables_are_ordered_by_their_mesh_level_and_validated_against_the_experiment():
    tables = dict(reversed(list(three_tables().items())))  # given coarse first: the meta decides the order
    (row,) = grid_convergence(tables, magnitude="0.1")
    assert row.estimate.order == pytest.approx(2.0, rel=1e-9)
    assert row.estimate.extrapolated == pytest.approx(-0.0036, rel=1e-9)
    reference = DERIVATIVES["AFF-8"]["values"]["Nr"]
    assert row.reference == reference
    assert row.experimental_uncertainty == pytest.approx(0.10 * abs(reference))  # Roddy: rotary about 10 %
    assert row.comparison_error == pytest.approx(row.estimate.fine - reference)
    assert row.validation_uncertainty == pytest.approx(math.hypot(row.numerical_uncertainty, row.experimental_uncertainty))
    assert row.validated == (abs(row.comparison_error) <= row.validation_uncertainty)
    json.dumps(row.as_dict())  # plain JSON, no infinities


def test_a_far_experiment_is_not_validated():
    (row,) = grid_convergence(three_tables(exact=-0.0020), magnitude="0.1")
    assert row.validated is False


def test_mixed_set_ups_and_missing_levels_are_named():
    tables = three_tables()
    tables["medium.json"]["meta"]["turbulence_model"] = "kOmegaSST"
    with pytest.raises(ConfigurationError, match="turbulence_model"):
        grid_convergence(tables, magnitude="0.1")
    tables = three_tables()
    tables["fine.json"]["meta"]["limited_pressure_gradient"] = True
    with pytest.raises(ConfigurationError, match="limited_pressure_gradient"):
        grid_convergence(tables, magnitude="0.1")
    tables["fine.json"]["meta"]["limited_pressure_gradient"] = False
    tables["medium.json"]["meta"]["limited_pressure_gradient"] = False
    grid_convergence(tables, magnitude="0.1")  # the coarse table predates the key: it was unlimited
    tables = three_tables()
    tables["medium.json"]["meta"]["pressure_velocity_coupling"] = "SIMPLEC"
    with pytest.raises(ConfigurationError, match="pressure_velocity_coupling"):
        grid_convergence(tables, magnitude="0.1")
    tables["medium.json"]["meta"]["pressure_velocity_coupling"] = "SIMPLE"
    grid_convergence(tables, magnitude="0.1")  # the others predate the key: they ran SIMPLE
    tables = three_tables(model=None)
    for t in tables.values():
        del t["meta"]["turbulence_model"]
    tables["fine.json"]["meta"]["turbulence_model"] = "kOmegaSST"
    grid_convergence(tables, magnitude="0.1")  # tables before the key ran k-omega SST
    tables = three_tables()
    tables["medium.json"]["meta"]["level"] = "fine"
    with pytest.raises(ConfigurationError, match="both on the fine mesh"):
        grid_convergence(tables)
    with pytest.raises(ConfigurationError, match="three derivative tables"):
        grid_convergence(dict(list(three_tables().items())[:2]))


def test_fitted_slopes_of_differently_fitted_tables_are_refused_but_single_points_compare():
    tables = three_tables()
    tables["medium.json"]["meta"]["fit"] = {"nonlinear": "abs", "offset": True}
    with pytest.raises(ConfigurationError, match="fit their sweeps differently"):
        grid_convergence(tables)
    assert grid_convergence(tables, magnitude="0.1")
    with pytest.raises(ConfigurationError, match="no single point at magnitude 0.2"):
        grid_convergence(tables, magnitude="0.2")
