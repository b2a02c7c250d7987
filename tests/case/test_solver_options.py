"""The solver options a study's conditions share: read from the [study] table, checked, and named."""

import pytest

from hydroderiv.case.solver_options import STUDY_TABLE_KEYS, SolverOptions
from hydroderiv.errors import ConfigurationError


def test_the_defaults_are_the_plain_set_up_and_add_nothing_to_the_folder_name():
    plain = SolverOptions.from_study_table({})
    assert plain == SolverOptions()
    assert plain.folder_suffix == ""
    assert plain.record() == {"turbulence_model": "kOmegaSST", "limited_pressure_gradient": False,
                              "limited_velocity_gradient": "everywhere", "velocity_limiter_coefficient": 1.0,
                              "pressure_velocity_coupling": "SIMPLE", "turbulence_convection": "second"}


def test_every_choice_shows_in_the_folder_name_in_a_fixed_order():
    table = {"turbulence_model": "SpalartAllmaras", "limit_pressure_gradient": True,
             "limit_velocity_gradient": "convection", "velocity_limiter_coefficient": 0.5,
             "pressure_velocity_coupling": "SIMPLEC", "turbulence_convection": "first"}
    assert set(table) == set(STUDY_TABLE_KEYS)
    options = SolverOptions.from_study_table(table, "s.toml")
    assert options.folder_suffix == ("-SpalartAllmaras-limited-grad-p-grad-U-limited-in-convection-grad-U-limiter-0.5"
                                     "-SIMPLEC-first-order-turbulence")
    assert options.record()["turbulence_convection"] == "first"
    assert options.record()["velocity_limiter_coefficient"] == 0.5
    assert options.record()["limited_pressure_gradient"] is True


def test_a_pressure_gradient_limited_only_at_the_start_keeps_the_unlimited_folder():
    options = SolverOptions.from_study_table({"limit_pressure_gradient": "start"}, "s.toml")
    assert options.limit_pressure_gradient_at_start and not options.limit_pressure_gradient
    assert options.folder_suffix == ""


@pytest.mark.parametrize("table, message", [
    ({"limit_pressure_gradient": "always"}, "s.toml: \\[study\\] limit_pressure_gradient = 'always' must be"),
    ({"turbulence_model": "kEpsilonQCR"}, "s.toml: unknown turbulence model 'kEpsilonQCR'"),
    ({"limit_velocity_gradient": "here"}, "s.toml: limit_velocity_gradient = 'here' must be one of"),
    ({"pressure_velocity_coupling": "PIMPLE"}, "s.toml: pressure_velocity_coupling = 'PIMPLE' must be one of"),
    ({"turbulence_convection": "third"}, "s.toml: turbulence_convection = 'third' must be one of 'second', 'first'"),
    ({"velocity_limiter_coefficient": 0}, "s.toml: velocity_limiter_coefficient = 0 must be a number in \\(0, 1\\]"),
    ({"velocity_limiter_coefficient": 1.5}, "s.toml: velocity_limiter_coefficient = 1.5 must be"),
    ({"velocity_limiter_coefficient": "half"}, "s.toml: velocity_limiter_coefficient = 'half' must be"),
    ({"limit_velocity_gradient": "nowhere", "velocity_limiter_coefficient": 0.5},
     "s.toml: velocity_limiter_coefficient = 0.5 needs a velocity limiter"),
])
def test_a_bad_choice_names_the_file_the_key_and_the_value(table, message):
    with pytest.raises(ConfigurationError, match=message):
        SolverOptions.from_study_table(table, "s.toml")
