"""The vehicle's motion from its derivative table: the last stage of the pipeline.

Today the straight-line stability of the linearised equations of motion (:mod:`.stability`).
"""

from .stability import MassProperties, PlaneStability, plane_stability, stability

__all__ = ["MassProperties", "PlaneStability", "plane_stability", "stability"]
