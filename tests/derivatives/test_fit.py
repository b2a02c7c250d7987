"""The derivative estimator recovers known slopes and says how sure it is."""

import numpy as np
import pytest

from hydroderiv.derivatives import DerivativeFit, EvenFit
from hydroderiv.errors import ConfigurationError


def test_recovers_slope_and_gertler_hagen_nonlinear_term_exactly():
    v = -np.sin(np.radians([-12, -8, -4, 0, 4, 8, 12]))
    y = -0.0278 * v + 0.05 * v * np.abs(v)
    fit = DerivativeFit(nonlinear="abs").fit(v, y)
    assert fit is not None and fit.slope_ == pytest.approx(-0.0278, rel=1e-10)
    assert fit.nonlinear_ == pytest.approx(0.05, rel=1e-9)
    assert fit.slope_stderr_ < 1e-12 and fit.n_points_ == 7
    np.testing.assert_allclose(fit.predict(v), y, atol=1e-15)


def test_standard_error_reflects_scatter():
    rng = np.random.default_rng(1)
    v = np.linspace(-0.2, 0.2, 9)
    clean = -0.0139 * v + 0.01 * v**3
    noisy = clean + rng.normal(0, 2e-5, v.size)
    fit = DerivativeFit(nonlinear="cubic").fit(v, noisy)
    assert fit.slope_stderr_ > 0
    assert abs(fit.slope_ + 0.0139) < 4 * fit.slope_stderr_ + 1e-6


def test_iterative_uncertainty_of_the_points_carries_through_the_fit():
    # A straight line through two points +-h: slope = (y2 - y1) / 2h, so its deviation is sqrt(2) s / 2h.
    fit = DerivativeFit(nonlinear="none").fit([-0.1, 0.1], [0.001, -0.001], y_std=[1e-5, 1e-5])
    assert fit.slope_iterative_stderr_ == pytest.approx(np.sqrt(2) * 1e-5 / 0.2)
    # and it agrees with the spread of slopes over many noisy realisations of a longer sweep
    rng = np.random.default_rng(3)
    v = np.linspace(-0.14, 0.14, 5)
    s = np.array([1e-5, 2e-5, 0.0, 2e-5, 1e-5])
    slopes = [DerivativeFit(fit_offset=True).fit(v, -0.0278 * v + rng.normal(0, 1, 5) * s).slope_ for _ in range(4000)]
    one = DerivativeFit(fit_offset=True).fit(v, -0.0278 * v, y_std=s)
    assert one.slope_iterative_stderr_ == pytest.approx(np.std(slopes), rel=0.05)
    assert np.isnan(DerivativeFit().fit(v, -0.0278 * v).slope_iterative_stderr_)


def test_offset_absorbs_a_constant_asymmetry():
    w = np.linspace(-0.2, 0.2, 7)
    fit = DerivativeFit(nonlinear="abs", fit_offset=True).fit(w, 3e-4 - 0.0139 * w)
    assert fit.offset_ == pytest.approx(3e-4) and fit.slope_ == pytest.approx(-0.0139)


def test_too_few_points_are_refused():
    with pytest.raises(ConfigurationError, match="cannot determine"):
        DerivativeFit(nonlinear="abs").fit([0.1], [0.001])
    with pytest.raises(ConfigurationError, match="unknown nonlinear"):
        DerivativeFit(nonlinear="quartic").fit([0.1, 0.2], [0.001, 0.002])


def test_a_fit_with_no_magnitude_to_spare_passes_through_its_mirror_pairs():
    # Two magnitudes for slope and r|r|: the odd part is fixed by the pairs, so a curve that is not
    # slope-plus-r|r| at all (here cubic) still leaves no odd residual, and the standard error only sees
    # the pairs' asymmetry (none here).
    r = np.array([-0.2, -0.1, 0.0, 0.1, 0.2])
    y = 0.003 * r + 0.5 * r**3
    two = DerivativeFit(nonlinear="abs", fit_offset=True).fit(r, y)
    assert two.spare_magnitudes_ == 0
    np.testing.assert_allclose(two.predict(r), y, atol=1e-15)
    assert two.slope_stderr_ < 1e-12
    assert two.slope_ == pytest.approx(2 * (y[3] / 0.1) - y[4] / 0.2)  # twice the inner secant less the outer
    # a third magnitude over-determines it: the model error now shows in the standard error
    r3 = np.array([-0.3, -0.2, -0.1, 0.0, 0.1, 0.2, 0.3])
    three = DerivativeFit(nonlinear="abs", fit_offset=True).fit(r3, 0.003 * r3 + 0.5 * r3**3)
    assert three.spare_magnitudes_ == 1 and three.slope_stderr_ > 1e-6
    assert DerivativeFit(nonlinear="none").fit([-0.1, 0.1], [0.001, -0.001]).spare_magnitudes_ == 0


def test_the_even_fit_recovers_the_gertler_hagen_axial_force_in_drift_exactly():
    """X' = X'uu u'^2 + X'vv v'^2 with u' = cos(beta), v' = -sin(beta): both terms come back exactly."""
    beta = np.radians([-8, -4, 0, 4, 8])
    u, v = np.cos(beta), -np.sin(beta)
    x_prime = -0.0013 * u**2 + 0.007 * v**2
    fit = EvenFit().fit(v, x_prime, u)
    assert fit is not None and fit.constant_ == pytest.approx(-0.0013, rel=1e-10)
    assert fit.quadratic_ == pytest.approx(0.007, rel=1e-9)
    assert fit.quadratic_stderr_ < 1e-12 and fit.n_points_ == 5 and fit.odd_part_ < 1e-9
    np.testing.assert_allclose(fit.predict(v, u), x_prime, atol=1e-15)


def test_the_even_fit_ignores_an_odd_part_of_mirror_pairs_and_says_how_large_it_is():
    """An odd load on mirror pairs (a mesh's asymmetry) is orthogonal to the even terms: they come back
    unchanged, and odd_part_ is its size beside the largest even load fitted."""
    r = np.array([-0.2, -0.1, 0.0, 0.1, 0.2])
    even = -0.00004 - 0.003 * r**2
    fit = EvenFit().fit(r, even + 0.1 * 0.003 * 0.04 * r / 0.2)  # odd, a tenth of the even load at r' = 0.2
    assert fit.constant_ == pytest.approx(-0.00004, rel=1e-9) and fit.quadratic_ == pytest.approx(-0.003, rel=1e-9)
    assert fit.odd_part_ == pytest.approx(0.1, rel=1e-9)


def test_the_even_fit_needs_a_non_zero_magnitude():
    with pytest.raises(ConfigurationError, match="even load"):
        EvenFit().fit([0.0, 0.0], [1.0, 1.0])
    with pytest.raises(ConfigurationError, match="even load"):
        EvenFit().fit([0.1], [1.0])
