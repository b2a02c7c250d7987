"""Bodies: the SUBOFF configurations from their equations, or a user's checked STL."""

from .body import Body, ReferenceQuantities
from .suboff import CONFIGURATIONS, suboff_body
from .user import load_user_body

__all__ = ["Body", "ReferenceQuantities", "CONFIGURATIONS", "suboff_body", "load_user_body"]
