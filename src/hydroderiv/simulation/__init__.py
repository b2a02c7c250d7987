"""The vehicle's motion from its derivative table: the last stage of the pipeline.

The straight-line stability of the linearised equations of motion (:mod:`.stability`), and the quasi-steady
loads a manoeuvring simulation evaluates at each time step (:mod:`.quasi_steady`).
"""

from .quasi_steady import QuasiSteadyLoads
from .stability import MassProperties, PlaneStability, plane_stability, stability

__all__ = ["MassProperties", "PlaneStability", "QuasiSteadyLoads", "plane_stability", "stability"]
