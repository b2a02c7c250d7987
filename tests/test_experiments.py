"""experiments: the error convention every table reports against the measurements."""

from hydroderiv.experiments import DERIVATIVES, error_percent


def test_the_error_is_signed_by_where_the_computation_lies_whatever_the_measured_sign():
    """(computed - measured) / |measured|: a derivative of smaller magnitude than a negative measured one
    (AFF-8's Z'w) comes out positive and one of larger magnitude negative; one above a positive measured
    value (M'w) positive."""
    measured = DERIVATIVES["AFF-8"]["values"]
    assert error_percent(-0.0125, measured["Zw"]) > 0
    assert abs(error_percent(1.1 * measured["Mw"], measured["Mw"]) - 10.0) < 1e-9
    assert abs(error_percent(1.1 * measured["Zw"], measured["Zw"]) + 10.0) < 1e-9


def test_no_measured_value_gives_no_error():
    assert error_percent(0.01, None) is None
    assert error_percent(0.01, 0.0) is None
