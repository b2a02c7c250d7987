"""Forces and moments: OpenFOAM's force histories and the prime system."""

from .coefficients import COEFFICIENT_NAMES, PrimeScales, body_axis_loads
from .history import VectorHistory, read_history, read_vector_dat

__all__ = ["COEFFICIENT_NAMES", "PrimeScales", "body_axis_loads", "VectorHistory", "read_history", "read_vector_dat"]
