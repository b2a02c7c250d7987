"""The user's choices of turbulence model and numerics, which every condition of a study shares.

One object carries them from the study file's [study] table to the case set-up, the name of the folder the
conditions are kept in, and the record of each result; a new choice is added here once.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..errors import ConfigurationError
from .fluid import DEFAULT_TURBULENCE_MODEL, check_turbulence_model
from .numerics import (DEFAULT_VELOCITY_LIMITER_COEFFICIENT, GradientLimiters, check_pressure_velocity_coupling,
                       check_turbulence_convection, check_velocity_limiter)

# the [study] keys read by SolverOptions.from_study_table
STUDY_TABLE_KEYS = ("turbulence_model", "limit_pressure_gradient", "limit_velocity_gradient", "velocity_limiter_coefficient",
                    "pressure_velocity_coupling", "turbulence_convection")


@dataclass(frozen=True)
class SolverOptions:
    """Turbulence model, gradient limiters, pressure-velocity coupling and the turbulence fields' convection
    order (see case/fluid.py, case/numerics.py)."""

    turbulence_model: str = DEFAULT_TURBULENCE_MODEL  # see hydroderiv.case.fluid.TURBULENCE_MODELS
    limit_pressure_gradient: bool = False  # see hydroderiv.case.numerics.LIMITED_PRESSURE_GRADIENT
    # Limit it only during a cold start's first-order iterations (see the same place); a warm start and
    # everything after the switch to second order run unlimited.
    limit_pressure_gradient_at_start: bool = False
    limit_velocity_gradient: str = "everywhere"  # see hydroderiv.case.numerics.VELOCITY_GRADIENT_LIMITING
    # k of that limiter (see hydroderiv.case.numerics.DEFAULT_VELOCITY_LIMITER_COEFFICIENT)
    velocity_limiter_coefficient: float = DEFAULT_VELOCITY_LIMITER_COEFFICIENT
    pressure_velocity_coupling: str = "SIMPLE"  # see hydroderiv.case.numerics.PRESSURE_VELOCITY_COUPLINGS
    turbulence_convection: str = "second"  # see hydroderiv.case.numerics.TURBULENCE_CONVECTION_ORDERS

    def __post_init__(self):
        if self.limit_pressure_gradient and self.limit_pressure_gradient_at_start:
            raise ConfigurationError("limit the pressure gradient either always or at the start, not both")
        check_turbulence_model(self.turbulence_model)
        check_velocity_limiter(self.limit_velocity_gradient, self.velocity_limiter_coefficient)
        check_pressure_velocity_coupling(self.pressure_velocity_coupling)
        check_turbulence_convection(self.turbulence_convection)

    @classmethod
    def from_study_table(cls, table: dict[str, Any], source: str = "") -> SolverOptions:
        """The options of a study file's [study] table (keys STUDY_TABLE_KEYS; others are ignored here);
        an error names ``source`` (the file) and the choices."""
        limit_pressure_gradient = table.get("limit_pressure_gradient", False)
        if not isinstance(limit_pressure_gradient, bool) and limit_pressure_gradient != "start":
            raise ConfigurationError(f"{source}: [study] limit_pressure_gradient = {limit_pressure_gradient!r} must be "
                                     "true, false or \"start\" (limited during a cold start's first-order iterations only)")
        limit_velocity_gradient = table.get("limit_velocity_gradient", "everywhere")
        velocity_limiter_coefficient = table.get("velocity_limiter_coefficient", DEFAULT_VELOCITY_LIMITER_COEFFICIENT)
        check_velocity_limiter(limit_velocity_gradient, velocity_limiter_coefficient, source)
        return cls(
            turbulence_model=check_turbulence_model(table.get("turbulence_model", DEFAULT_TURBULENCE_MODEL), source),
            limit_pressure_gradient=limit_pressure_gradient is True,
            limit_pressure_gradient_at_start=limit_pressure_gradient == "start",
            limit_velocity_gradient=limit_velocity_gradient,
            velocity_limiter_coefficient=float(velocity_limiter_coefficient),
            pressure_velocity_coupling=check_pressure_velocity_coupling(
                table.get("pressure_velocity_coupling", "SIMPLE"), source),
            turbulence_convection=check_turbulence_convection(table.get("turbulence_convection", "second"), source),
        )

    @property
    def folder_suffix(self) -> str:
        """What sets a study's conditions folder apart from the defaults' ("" for the defaults). A pressure
        gradient limited only at the start is not in it: such runs converge to the unlimited solution and
        share the unlimited conditions."""
        return (f"-{self.turbulence_model}" if self.turbulence_model != DEFAULT_TURBULENCE_MODEL else "") + (
            "-limited-grad-p" if self.limit_pressure_gradient else "") + (
            {"everywhere": "", "convection": "-grad-U-limited-in-convection",
             "nowhere": "-unlimited-grad-U"}[self.limit_velocity_gradient]) + (
            f"-grad-U-limiter-{self.velocity_limiter_coefficient:g}"
            if self.velocity_limiter_coefficient != DEFAULT_VELOCITY_LIMITER_COEFFICIENT else "") + (
            f"-{self.pressure_velocity_coupling}" if self.pressure_velocity_coupling != "SIMPLE" else "") + (
            "-first-order-turbulence" if self.turbulence_convection == "first" else "")

    def gradient_limiters(self, pressure: bool) -> GradientLimiters:
        """The gradient limiters of these options, the pressure gradient limited or not as ``pressure``
        says (it may differ at a cold start; see CaseSettings)."""
        return GradientLimiters(pressure=pressure, velocity=self.limit_velocity_gradient,
                                velocity_coefficient=self.velocity_limiter_coefficient)

    def record(self) -> dict[str, Any]:
        """The options as a results file records them."""
        return {"turbulence_model": self.turbulence_model,
                "limited_pressure_gradient": self.limit_pressure_gradient,
                "limited_velocity_gradient": self.limit_velocity_gradient,  # everywhere, or in convection only
                "velocity_limiter_coefficient": self.velocity_limiter_coefficient,
                "pressure_velocity_coupling": self.pressure_velocity_coupling,
                "turbulence_convection": self.turbulence_convection}
