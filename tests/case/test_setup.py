"""Case set-up details that decide whether results survive and runs are reproducible."""

import pytest

from hydroderiv.case.setup import write_schedule


@pytest.mark.parametrize("max_iterations", [1, 60, 250, 400, 600, 999, 3000])
def test_the_last_iteration_is_always_a_write_time(max_iterations):
    end, interval = write_schedule(max_iterations, 250)
    assert end % interval == 0 and end >= max_iterations and interval <= 250
    assert end - max_iterations < interval
