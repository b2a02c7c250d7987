"""Physics set-up of a condition on an existing mesh: fluid, inflow, rotating zone and source."""

from .conditions import KNOT, Condition

__all__ = ["Condition", "KNOT"]
