"""Hydrodynamic derivatives from captive conditions: the fitting estimator and single-point definitions, the
acceleration derivatives estimated from the body's shape, and each derivative's ideal-fluid part."""

from .added_mass import AccelerationDerivatives, acceleration_derivatives
from .fit import DerivativeFit, EvenFit
from .ideal_fluid import ideal_fluid_derivatives, viscous_split

__all__ = ["AccelerationDerivatives", "DerivativeFit", "EvenFit", "acceleration_derivatives",
           "ideal_fluid_derivatives", "viscous_split"]
