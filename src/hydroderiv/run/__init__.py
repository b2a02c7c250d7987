"""Running OpenFOAM: utilities, the steady solver with convergence control, and progress."""

from .openfoam import OpenFOAMError, run_application

__all__ = ["OpenFOAMError", "run_application"]
