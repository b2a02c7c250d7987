"""force.dat / moment.dat parsing by header names, whatever the column order or release."""

import numpy as np
import pytest

from hydroderiv.errors import HydroderivError
from hydroderiv.forces import PrimeScales, read_history, read_vector_dat

V1912_STYLE = """# Force
# CofR                : (0.000000e+00 0.000000e+00 0.000000e+00)
#
# Time                total_x             total_y             total_z             pressure_x          pressure_y          pressure_z          viscous_x           viscous_y           viscous_z
1                     -1.0                0.5                 0.0                 -0.4                0.5                 0.0                 -0.6                0.0                 0.0
2                     -2.0                0.25                0.0                 -0.8                0.25                0.0                 -1.2                0.0                 0.0
"""

# the same numbers, columns reordered, vectors in parentheses, and no total columns
OTHER_STYLE = """# Time  (viscous_x viscous_y viscous_z) (pressure_x pressure_y pressure_z)
1 (-0.6 0 0) (-0.4 0.5 0)
2 (-1.2 0 0) (-0.8 0.25 0)
3 (-1.2 0"""  # a line still being written


@pytest.mark.parametrize("text", [V1912_STYLE, OTHER_STYLE])
def test_columns_are_found_by_name(tmp_path, text):
    path = tmp_path / "force.dat"
    path.write_text(text)
    h = read_vector_dat(path)
    np.testing.assert_array_equal(h.iterations, [1, 2])
    np.testing.assert_allclose(h.total, [[-1.0, 0.5, 0.0], [-2.0, 0.25, 0.0]])
    np.testing.assert_allclose(h.parts["viscous"][:, 0], [-0.6, -1.2])


def test_a_file_without_a_header_is_refused(tmp_path):
    path = tmp_path / "force.dat"
    path.write_text("1 2 3 4\n")
    with pytest.raises(HydroderivError, match="header"):
        read_vector_dat(path)


def test_restarted_runs_are_joined_in_order(tmp_path):
    first = tmp_path / "forces" / "0"
    second = tmp_path / "forces" / "100"
    first.mkdir(parents=True)
    second.mkdir(parents=True)
    rows = lambda its: "".join(f"{i} {i} 0 0 0 0 0 0 0 0\n" for i in its)  # noqa: E731
    head = "# Time total_x total_y total_z pressure_x pressure_y pressure_z viscous_x viscous_y viscous_z\n"
    (first / "force.dat").write_text(head + rows(range(1, 121)))  # written past the restart point
    (second / "force.dat").write_text(head + rows(range(101, 151)))
    h = read_history(tmp_path, "forces")
    np.testing.assert_array_equal(h.iterations, np.arange(1, 151))
    assert h.total[-1, 0] == 150


def test_prime_scales():
    s = PrimeScales(rho=998.55, speed=3.344, length=4.261)
    c = s.coefficients(np.array([0.0, s.force, 0.0]), np.array([0.0, 0.0, 2 * s.moment]))
    np.testing.assert_allclose(c, [0, 1, 0, 0, 0, 2])
