"""Hydrodynamic derivatives from captive conditions: the fitting estimator and single-point definitions."""

from .fit import DerivativeFit, EvenFit

__all__ = ["DerivativeFit", "EvenFit"]
