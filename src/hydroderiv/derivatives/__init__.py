"""Hydrodynamic derivatives from captive conditions: the fitting estimator and single-point definitions, and
the acceleration derivatives estimated from the body's shape."""

from .added_mass import AccelerationDerivatives, acceleration_derivatives
from .fit import DerivativeFit, EvenFit

__all__ = ["AccelerationDerivatives", "DerivativeFit", "EvenFit", "acceleration_derivatives"]
