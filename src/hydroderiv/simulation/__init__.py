"""The vehicle's motion from its derivative table: the last stage of the pipeline.

The straight-line stability of the linearised equations of motion, the roots of that motion and, with a
hydrostatic moment in pitch, the speeds at which it is stable (:mod:`.stability`), the quasi-steady loads
a manoeuvring simulation evaluates at each time step (:mod:`.quasi_steady`), and the controls-fixed motion
in time (:mod:`.manoeuvre`).
"""

from .manoeuvre import ManoeuvreSimulation, Trajectory, table_reach
from .quasi_steady import QuasiSteadyLoads
from .stability import (
    MassProperties,
    PlaneMotion,
    PlaneStability,
    StableSpeeds,
    hydrostatic_moment_prime,
    plane_motion,
    plane_stability,
    stability,
    vertical_stable_speeds,
)

__all__ = ["ManoeuvreSimulation", "MassProperties", "PlaneMotion", "PlaneStability", "QuasiSteadyLoads", "StableSpeeds",
           "Trajectory", "hydrostatic_moment_prime", "plane_motion", "plane_stability", "stability", "table_reach",
           "vertical_stable_speeds"]
