"""Case set-up details that decide whether results survive and runs are reproducible."""

import pytest

from hydroderiv.case.setup import write_schedule
from hydroderiv.case.solver_options import SolverOptions


@pytest.mark.parametrize("max_iterations", [1, 60, 250, 400, 600, 999, 3000])
def test_the_last_iteration_is_always_a_write_time(max_iterations):
    end, interval = write_schedule(max_iterations, 250)
    assert end % interval == 0 and end >= max_iterations and interval <= 250
    assert end - max_iterations < interval


def test_only_a_cold_start_begins_with_first_order_convection(tmp_path):
    from hydroderiv.case.setup import CaseSettings

    settings = CaseSettings(length=4.261, components=("hull",))
    assert settings.second_order_from(warm_start=None) == settings.first_order_start > 0
    assert settings.second_order_from(warm_start=tmp_path / "200") is None  # a solution to start from
    assert CaseSettings(length=4.261, components=(), second_order=False).second_order_from(None) is None
    assert CaseSettings(length=4.261, components=(), first_order_start=0).second_order_from(None) is None


def test_the_convection_order_is_read_back_from_the_case(tmp_path):
    from hydroderiv.case.numerics import has_second_order_convection, write_numerics

    (tmp_path / "system").mkdir()
    write_numerics(tmp_path, second_order=False)
    assert not has_second_order_convection(tmp_path)
    write_numerics(tmp_path, second_order=True)
    assert has_second_order_convection(tmp_path)


def test_a_limited_pressure_gradient_survives_the_switch_to_second_order(tmp_path):
    """The limiter is chosen when the case is set up; the mid-run switch of the convection schemes must not
    drop it, and a case set up without it stays without it."""
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.numerics import (LIMITED_PRESSURE_GRADIENT, has_second_order_convection,
                                          switch_to_second_order_convection)
    from hydroderiv.case.setup import CaseSettings, write_condition_case

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    for limited in (True, False):
        settings = CaseSettings(length=4.261, components=("hull",), solver=SolverOptions(limit_pressure_gradient=limited))
        case = write_condition_case(tmp_path / str(limited), mesh, Condition(speed=3.344), settings)  # a cold start
        assert not has_second_order_convection(case)
        switch_to_second_order_convection(case, settings.limiters_after_start())  # as the run loop does
        assert has_second_order_convection(case)
        grad = FoamFile(case / "system/fvSchemes")["gradSchemes"]
        assert ("grad(p)" in grad) is limited
        if limited:
            assert " ".join(map(str, grad["grad(p)"])) == LIMITED_PRESSURE_GRADIENT


def test_a_pressure_gradient_limited_at_the_start_is_limited_in_a_cold_start_only_and_dropped_at_the_switch(tmp_path):
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.numerics import switch_to_second_order_convection
    from hydroderiv.case.setup import CaseSettings, write_condition_case
    from hydroderiv.errors import ConfigurationError

    settings = CaseSettings(length=4.261, components=("hull",), solver=SolverOptions(limit_pressure_gradient_at_start=True))
    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    cold = write_condition_case(tmp_path / "cold", mesh, Condition(speed=3.344), settings)
    assert "grad(p)" in FoamFile(cold / "system/fvSchemes")["gradSchemes"]
    # what the run loop does at the switch: the choice from then on is the lasting one, unlimited
    switch_to_second_order_convection(cold, settings.limiters_after_start())
    assert "grad(p)" not in FoamFile(cold / "system/fvSchemes")["gradSchemes"]
    # a warm start runs second order from its first iteration, so it is never limited
    assert settings.second_order_from(tmp_path) is None
    assert not settings.limits_pressure_gradient_only_at_start(tmp_path)
    assert settings.limits_pressure_gradient_only_at_start(None)
    with pytest.raises(ConfigurationError, match="either always or at the start"):
        SolverOptions(limit_pressure_gradient=True, limit_pressure_gradient_at_start=True)


def test_a_velocity_gradient_limited_for_convection_only_leaves_the_strain_rate_unlimited(tmp_path):
    """With limit_velocity_gradient = "convection", the linear-upwind reconstruction of U uses a limited
    gradient of its own, while grad(U) (the turbulence models' strain rate, the viscous stress) is the plain
    Gauss gradient; the default limits grad(U) itself. Both survive the switch to second order, and the
    convection order is still recognised."""
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.numerics import (LIMITED_FOR_CONVECTION, LIMITED_GRADIENT, has_second_order_convection,
                                          switch_to_second_order_convection)
    from hydroderiv.case.setup import CaseSettings, write_condition_case
    from hydroderiv.errors import ConfigurationError

    def words(entry):
        return " ".join(map(str, entry)) if not isinstance(entry, str) else entry

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    for where in ("everywhere", "convection", "nowhere"):
        settings = CaseSettings(length=4.261, components=("hull",), solver=SolverOptions(limit_velocity_gradient=where))
        case = write_condition_case(tmp_path / where, mesh, Condition(speed=3.344), settings)
        switch_to_second_order_convection(case, settings.limiters_after_start())
        assert has_second_order_convection(case)
        schemes = FoamFile(case / "system/fvSchemes")
        grad, div = schemes["gradSchemes"], schemes["divSchemes"]
        if where == "everywhere":
            assert words(grad["grad(U)"]) == LIMITED_GRADIENT and LIMITED_FOR_CONVECTION not in grad
            assert words(div["div(phi,U)"]).endswith("linearUpwind grad(U)")
        elif where == "convection":
            assert "grad(U)" not in grad and words(grad["default"]) == "Gauss linear"
            assert words(grad[LIMITED_FOR_CONVECTION]) == LIMITED_GRADIENT
            assert words(div["div(phi,U)"]).endswith(f"linearUpwind {LIMITED_FOR_CONVECTION}")
        else:  # no limiter on U at all
            assert "grad(U)" not in grad and LIMITED_FOR_CONVECTION not in grad
            assert words(div["div(phi,U)"]).endswith("linearUpwind grad(U)")
        # the turbulence fields' reconstruction is limited either way
        assert words(div["div(phi,k)"]).endswith("linearUpwind grad(k)") and words(grad["grad(k)"]) == LIMITED_GRADIENT
    with pytest.raises(ConfigurationError, match="limit_velocity_gradient = 'sometimes'"):
        SolverOptions(limit_velocity_gradient="sometimes")


@pytest.mark.parametrize("where, entry", [("everywhere", "grad(U)"), ("convection", "limitedForConvection")])
def test_a_relaxed_velocity_limiter_keeps_its_coefficient_through_the_switch_to_second_order(tmp_path, where, entry):
    """velocity_limiter_coefficient = k writes `cellLimited Gauss linear k` wherever the velocity gradient is
    limited; the turbulence fields keep the full limiter."""
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.numerics import LIMITED_GRADIENT, switch_to_second_order_convection
    from hydroderiv.case.setup import CaseSettings, write_condition_case

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    settings = CaseSettings(length=4.261, components=("hull",),
                            solver=SolverOptions(limit_velocity_gradient=where, velocity_limiter_coefficient=0.5))
    case = write_condition_case(tmp_path / "case", mesh, Condition(speed=3.344), settings)
    for _ in range(2):  # as set up, and after the run loop's switch to second order
        grad = FoamFile(case / "system/fvSchemes")["gradSchemes"]
        assert " ".join(map(str, grad[entry])) == "cellLimited Gauss linear 0.5"
        assert " ".join(map(str, grad["grad(nuTilda)"])) == LIMITED_GRADIENT
        switch_to_second_order_convection(case, settings.limiters_after_start())


def test_simplec_relaxes_the_pressure_less_and_keeps_its_coupling_through_the_switch_to_second_order(tmp_path):
    """SIMPLEC (consistent) is set when the case is written; the mid-run switch of the convection schemes
    rewrites the schemes only, so the coupling chosen stays."""
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.numerics import has_second_order_convection, switch_to_second_order_convection
    from hydroderiv.case.setup import CaseSettings, write_condition_case
    from hydroderiv.errors import ConfigurationError

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    for coupling, consistent, p_relax in (("SIMPLE", False, 0.3), ("SIMPLEC", True, 0.9)):
        settings = CaseSettings(length=4.261, components=("hull",),
                                solver=SolverOptions(pressure_velocity_coupling=coupling))
        case = write_condition_case(tmp_path / coupling, mesh, Condition(speed=3.344), settings)  # a cold start
        switch_to_second_order_convection(case, settings.limiters_after_start())
        assert has_second_order_convection(case)
        solution = FoamFile(case / "system/fvSolution")
        assert solution["SIMPLE"]["consistent"] is consistent
        assert solution["relaxationFactors"]["fields"]["p"] == pytest.approx(p_relax)
    with pytest.raises(ConfigurationError, match="pressure_velocity_coupling = 'PISO' must be one of 'SIMPLE', 'SIMPLEC'"):
        SolverOptions(pressure_velocity_coupling="PISO")


def test_turbulence_convected_first_order_stays_first_order_through_the_switch_and_momentum_goes_second(tmp_path):
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.numerics import FIRST_ORDER, has_second_order_convection, switch_to_second_order_convection
    from hydroderiv.case.setup import CaseSettings, write_condition_case

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    for order in ("second", "first"):
        settings = CaseSettings(length=4.261, components=("hull",),
                                solver=SolverOptions(turbulence_model="SpalartAllmaras", turbulence_convection=order))
        case = write_condition_case(tmp_path / order, mesh, Condition(speed=3.344), settings)  # a cold start
        switch_to_second_order_convection(case, settings.limiters_after_start(), settings.solver.turbulence_convection)
        assert has_second_order_convection(case)
        div = FoamFile(case / "system/fvSchemes")["divSchemes"]
        nu_tilda = " ".join(map(str, div["div(phi,nuTilda)"]))
        assert (nu_tilda == FIRST_ORDER) is (order == "first")
        assert " ".join(map(str, div["div(phi,U)"])) != FIRST_ORDER


def test_the_reynolds_stress_model_gets_an_isotropic_stress_k_s_wall_function_and_its_heavier_relaxation(tmp_path):
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.fluid import FreestreamTurbulence
    from hydroderiv.case.setup import CaseSettings, write_condition_case

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    cases = {}
    for model in ("LRR", "kOmegaSST"):
        settings = CaseSettings(length=4.261, components=("hull",), solver=SolverOptions(turbulence_model=model))
        cases[model] = write_condition_case(tmp_path / model, mesh, Condition(speed=3.344), settings)
    lrr = cases["LRR"]
    assert (lrr / "0/R").is_file() and (lrr / "0/epsilon").is_file() and not (lrr / "0/k").exists()
    k = FreestreamTurbulence().k(3.344)
    with FoamFile(lrr / "0/R") as f:
        assert f["FoamFile"]["class"] == "volSymmTensorField"
        assert list(f["internalField"]) == pytest.approx([2 * k / 3, 0, 0, 2 * k / 3, 0, 2 * k / 3])
        assert list(f["boundaryField"]["farfield"]["inletValue"]) == pytest.approx(list(f["internalField"]))
        assert f["boundaryField"]["bodyWalls"]["type"] == "kqRWallFunction"
    assert FoamFile(lrr / "0/nut")["boundaryField"]["bodyWalls"]["type"] == "nutkWallFunction"  # its k is half R's trace
    relaxed = FoamFile(lrr / "system/fvSolution")["relaxationFactors"]
    plain = FoamFile(cases["kOmegaSST"] / "system/fvSolution")["relaxationFactors"]
    assert relaxed["equations"]["U"] < plain["equations"]["U"] and relaxed["fields"]["p"] < plain["fields"]["p"]
    assert relaxed["equations"]["R"] < relaxed["equations"]["epsilon"] == plain["equations"]["epsilon"]


def test_a_k_epsilon_model_gets_epsilon_from_the_same_free_stream_and_its_own_wall_function(tmp_path):
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.fluid import C_MU, FreestreamTurbulence
    from hydroderiv.case.setup import CaseSettings, write_condition_case

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    condition, nu = Condition(speed=3.344), 0.001053 / 998.55
    cases = {}
    for model in ("kOmegaSST", "ShihQuadraticKE", "LienCubicKE"):
        settings = CaseSettings(length=4.261, components=("hull",), solver=SolverOptions(turbulence_model=model))
        cases[model] = write_condition_case(tmp_path / model, mesh, condition, settings)
        with FoamFile(cases[model] / "constant/turbulenceProperties") as f:
            assert f["RAS"]["RASModel"] == model
    assert (cases["kOmegaSST"] / "0/omega").is_file() and not (cases["kOmegaSST"] / "0/epsilon").exists()
    for model in ("ShihQuadraticKE", "LienCubicKE"):
        assert (cases[model] / "0/epsilon").is_file() and not (cases[model] / "0/omega").exists()
    with FoamFile(cases["ShihQuadraticKE"] / "0/epsilon") as f:
        free = FreestreamTurbulence()
        # the same free-stream turbulence, in the other variable: epsilon = C_mu k omega
        expected = C_MU * free.k(3.344) * free.omega(3.344, nu)
        assert f["boundaryField"]["farfield"]["inletValue"] == pytest.approx(expected, rel=1e-6)
        assert f["boundaryField"]["bodyWalls"]["type"] == "epsilonWallFunction"
        assert f["internalField"] == pytest.approx(expected, rel=1e-6)


def test_spalart_allmaras_gets_the_same_free_stream_eddy_viscosity_no_k_and_spaldings_wall_law(tmp_path):
    from foamlib import FoamFile

    from hydroderiv.case import Condition
    from hydroderiv.case.fluid import FreestreamTurbulence
    from hydroderiv.case.setup import CaseSettings, write_condition_case

    mesh = tmp_path / "mesh"
    (mesh / "constant/polyMesh").mkdir(parents=True)
    nu = 0.001053 / 998.55
    settings = CaseSettings(length=4.261, components=("hull",),
                            solver=SolverOptions(turbulence_model="SpalartAllmaras"))
    case = write_condition_case(tmp_path / "sa", mesh, Condition(speed=3.344), settings)
    assert sorted(p.name for p in (case / "0").iterdir()) == ["U", "nuTilda", "nut", "p"]  # no k, omega, epsilon
    with FoamFile(case / "0/nuTilda") as f:
        free = f["boundaryField"]["farfield"]["inletValue"]
        assert f["boundaryField"]["bodyWalls"]["type"] == "fixedValue" and f["boundaryField"]["bodyWalls"]["value"] == 0
    # the model's eddy viscosity nuTilda chi^3 / (chi^3 + 7.1^3), chi = nuTilda / nu, is the k models'
    # free-stream 10 nu
    chi = free / nu
    assert free * chi**3 / (chi**3 + 7.1**3) == pytest.approx(FreestreamTurbulence().viscosity_ratio * nu, rel=1e-9)
    with FoamFile(case / "0/nut") as f:
        assert f["boundaryField"]["bodyWalls"]["type"] == "nutUSpaldingWallFunction"
    schemes, solution = FoamFile(case / "system/fvSchemes"), FoamFile(case / "system/fvSolution")
    assert "div(phi,nuTilda)" in schemes["divSchemes"] and "grad(nuTilda)" in schemes["gradSchemes"]
    assert solution["relaxationFactors"]["equations"]["nuTilda"] == pytest.approx(0.6)


def test_an_unknown_turbulence_model_is_named():
    from hydroderiv.errors import ConfigurationError

    with pytest.raises(ConfigurationError, match="unknown turbulence model 'kEpsilonQCR'"):
        SolverOptions(turbulence_model="kEpsilonQCR")
