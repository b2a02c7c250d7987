"""The vehicle's motion from its derivative table: the last stage of the pipeline.

The straight-line stability of the linearised equations of motion and the roots of that motion
(:mod:`.stability`), the quasi-steady loads a manoeuvring simulation evaluates at each time step
(:mod:`.quasi_steady`), and the controls-fixed motion in time (:mod:`.manoeuvre`).
"""

from .manoeuvre import ManoeuvreSimulation, Trajectory, table_reach
from .quasi_steady import QuasiSteadyLoads
from .stability import MassProperties, PlaneMotion, PlaneStability, plane_motion, plane_stability, stability

__all__ = ["ManoeuvreSimulation", "MassProperties", "PlaneMotion", "PlaneStability", "QuasiSteadyLoads", "Trajectory",
           "plane_motion", "plane_stability", "stability", "table_reach"]
