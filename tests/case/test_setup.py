"""Case set-up details that decide whether results survive and runs are reproducible."""

import pytest

from hydroderiv.case.setup import write_schedule


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
