"""hydroderiv: manoeuvring derivatives of underwater vehicles from RANS CFD (hybrid reference frames).

The pipeline: geometry -> mesh -> case -> run -> forces -> derivatives -> report.
"""

from .errors import ConfigurationError, GeometryError, HydroderivError
from .geometry import Body, ReferenceQuantities, load_user_body, suboff_body

__version__ = "0.1.0"
__all__ = [
    "Body",
    "ReferenceQuantities",
    "suboff_body",
    "load_user_body",
    "HydroderivError",
    "GeometryError",
    "ConfigurationError",
]
