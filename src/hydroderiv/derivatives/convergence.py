"""Discretisation uncertainty of a derivative from three mesh levels, and its validation against experiment.

The mesh levels coarse, medium and fine differ only in the base cell, by REFINEMENT_RATIO (sqrt 2) per level
(see :mod:`hydroderiv.mesh.design`); the prism layers keep their first-cell height, as in the seed paper's
grid study. So the representative cell size of a level is h = REFINEMENT_RATIO ** -index, and the ratios
r21 = h2/h1 (medium over fine) and r32 = h3/h2 (coarse over medium) are known exactly.

The three-grid estimate follows Celik et al. (2008), "Procedure for estimation and reporting of uncertainty
due to discretization in CFD applications", J. Fluids Eng. 130, 078001, with the convergence ratio
R = eps21/eps32 (eps21 = phi2 - phi1, eps32 = phi3 - phi2) deciding what can be said (Stern et al. 2001,
"Comprehensive approach to verification and validation of CFD simulations - Part 1", J. Fluids Eng. 123,
793-802):

- 0 <= R < 1, monotonic convergence: the observed order p, the Richardson estimate phi_ext and the fine-grid
  convergence index GCI = Fs |eps21| / (r21^p - 1) with Fs = 1.25 (three grids).
- R < 0, oscillatory convergence: no extrapolation; the uncertainty is half the range of the three values.
- R >= 1, divergence: no estimate at all.

The validation comparison is that of ASME V&V 20-2009: the comparison error E = S - D of the fine-grid value
S against the experiment D, and the validation uncertainty U_val = sqrt(U_num^2 + U_D^2). Where |E| <= U_val
the difference is within the noise of the two; where |E| > U_val it is a modelling error of about E.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

from ..case.solver_options import SolverOptions
from ..errors import ConfigurationError
from ..experiments import DERIVATIVE_UNCERTAINTY, DERIVATIVES
from ..mesh.design import LEVELS, REFINEMENT_RATIO
from .table import DEFINITIONS

SAFETY_FACTOR = 1.25  # Celik et al. (2008) for three grids


@dataclass(frozen=True)
class ThreeGridEstimate:
    """What three values on systematically refined meshes say about the discretisation error."""

    fine: float
    medium: float
    coarse: float
    r21: float
    r32: float
    kind: str  # "monotonic", "oscillatory", "divergent" or "exact" (the three values equal)
    convergence_ratio: float | None  # R = eps21 / eps32; None where eps32 = 0
    order: float | None  # observed order p (monotonic only)
    extrapolated: float | None  # Richardson estimate phi_ext (monotonic only)
    uncertainty: float | None  # absolute numerical uncertainty of the fine value; None where divergent

    @property
    def uncertainty_pct(self) -> float | None:
        """The uncertainty relative to the fine value (for monotonic convergence, Celik's GCI_fine21)."""
        if self.uncertainty is None or self.fine == 0:
            return None
        return 100.0 * self.uncertainty / abs(self.fine)


def observed_order(eps21: float, eps32: float, r21: float, r32: float, max_iterations: int = 200) -> float:
    """Celik's observed order: p = |ln|eps32/eps21| + q(p)| / ln r21, q(p) = ln((r21^p - s)/(r32^p - s)).

    With equal ratios q vanishes and p follows directly; otherwise by fixed-point iteration.
    """
    s = math.copysign(1.0, eps32 / eps21)
    log_ratio = math.log(abs(eps32 / eps21))
    p = abs(log_ratio) / math.log(r21)
    for _ in range(max_iterations):
        q = math.log((r21**p - s) / (r32**p - s))
        p_next = abs(log_ratio + q) / math.log(r21)
        if abs(p_next - p) < 1e-12 * max(1.0, p):
            return p_next
        p = p_next
    raise ConfigurationError(f"the observed order did not settle (last {p:.4g}); the three values are too far from "
                             "the asymptotic range for a Richardson estimate")


def three_grid_estimate(fine: float, medium: float, coarse: float, r21: float = REFINEMENT_RATIO,
                        r32: float = REFINEMENT_RATIO) -> ThreeGridEstimate:
    """The discretisation uncertainty of ``fine`` from the same quantity on two coarser meshes."""
    if r21 <= 1.0 or r32 <= 1.0:
        raise ConfigurationError(f"refinement ratios must exceed 1 (coarse to medium {r32}, medium to fine {r21})")
    eps21, eps32 = medium - fine, coarse - medium
    args = dict(fine=fine, medium=medium, coarse=coarse, r21=r21, r32=r32)
    if eps21 == 0.0 and eps32 == 0.0:
        return ThreeGridEstimate(**args, kind="exact", convergence_ratio=None, order=None, extrapolated=fine,
                                 uncertainty=0.0)
    if eps32 == 0.0:  # the finest pair differs but the coarser pair does not: no sign of convergence
        return ThreeGridEstimate(**args, kind="divergent", convergence_ratio=None, order=None, extrapolated=None,
                                 uncertainty=None)
    ratio = eps21 / eps32
    if ratio >= 1.0:
        return ThreeGridEstimate(**args, kind="divergent", convergence_ratio=ratio, order=None, extrapolated=None,
                                 uncertainty=None)
    if ratio < 0.0:
        half_range = 0.5 * (max(fine, medium, coarse) - min(fine, medium, coarse))
        return ThreeGridEstimate(**args, kind="oscillatory", convergence_ratio=ratio, order=None, extrapolated=None,
                                 uncertainty=half_range)
    if ratio == 0.0:  # the two finer meshes agree exactly
        return ThreeGridEstimate(**args, kind="monotonic", convergence_ratio=0.0, order=math.inf, extrapolated=fine,
                                 uncertainty=0.0)
    p = observed_order(eps21, eps32, r21, r32)
    growth = r21**p - 1.0
    return ThreeGridEstimate(**args, kind="monotonic", convergence_ratio=ratio, order=p,
                             extrapolated=fine - eps21 / growth, uncertainty=SAFETY_FACTOR * abs(eps21) / growth)


def level_cell_size(level: str) -> float:
    """Representative cell size of a mesh level, relative to the coarse level's."""
    if level not in LEVELS:
        raise ConfigurationError(f"unknown mesh level {level!r}; choose one of {', '.join(LEVELS)}")
    return REFINEMENT_RATIO ** -LEVELS.index(level)


@dataclass(frozen=True)
class ConvergenceRow:
    """One derivative on three meshes, its numerical uncertainty and its validation comparison."""

    name: str
    estimate: ThreeGridEstimate
    reference: float | None
    experimental_uncertainty: float | None  # absolute, U_D
    iterative_uncertainty: float | None  # the fine value's own standard error from the averaging windows

    @property
    def numerical_uncertainty(self) -> float | None:
        """U_num: the grid uncertainty combined with the fine solution's iterative one (root sum of squares)."""
        grid = self.estimate.uncertainty
        if grid is None:
            return None
        return math.hypot(grid, self.iterative_uncertainty or 0.0)

    @property
    def comparison_error(self) -> float | None:
        """E = S - D: the fine-mesh value less the experiment."""
        return None if self.reference is None else self.estimate.fine - self.reference

    @property
    def validation_uncertainty(self) -> float | None:
        """U_val = sqrt(U_num^2 + U_D^2) (ASME V&V 20)."""
        if self.numerical_uncertainty is None or self.experimental_uncertainty is None:
            return None
        return math.hypot(self.numerical_uncertainty, self.experimental_uncertainty)

    @property
    def validated(self) -> bool | None:
        """True where |E| <= U_val: the difference to the experiment is within the two uncertainties."""
        if self.comparison_error is None or self.validation_uncertainty is None:
            return None
        return abs(self.comparison_error) <= self.validation_uncertainty

    def as_dict(self) -> dict:
        record = {"name": self.name, **asdict(self.estimate), "uncertainty_pct": self.estimate.uncertainty_pct}
        for key in ("reference", "experimental_uncertainty", "iterative_uncertainty", "numerical_uncertainty",
                    "comparison_error", "validation_uncertainty", "validated"):
            value = getattr(self, key)
            record[key] = None if isinstance(value, float) and not math.isfinite(value) else value
        if record["order"] is not None and not math.isfinite(record["order"]):
            record["order"] = None  # the two finer meshes agree exactly; JSON has no infinity
        return record


# What must be the same in the three tables of a grid study (their meta), apart from the mesh level, with
# the value a table written before the key existed stands for (None: no default). A table that predates a
# solver option ran with that option's default.
_SAME_SET_UP = {"body": None, "method": None, "speed_m_s": None, **SolverOptions().record()}


def _table_value(table: dict, name: str, magnitude: str | None, source: str) -> tuple[float, float | None]:
    """A derivative from one table: the fitted value (with its iterative error) or a single point."""
    details = table.get("details", {}).get(name)
    if details is None:
        raise ConfigurationError(f"{source}: no {name} in this table")
    if magnitude is None:
        return details["value"], details.get("iterative_stderr")
    by_magnitude = {float(k): v for k, v in details.get("single_point_by_magnitude", {}).items()}
    if float(magnitude) not in by_magnitude:
        have = ", ".join(f"{k:g}" for k in sorted(by_magnitude)) or "none"
        raise ConfigurationError(f"{source}: {name} has no single point at magnitude {magnitude} (it has: {have})")
    return by_magnitude[float(magnitude)], None


def grid_convergence(tables: dict[str, dict], magnitude: str | None = None) -> list[ConvergenceRow]:
    """Each derivative present in all three tables (derivative table JSONs keyed by their source name).

    ``magnitude`` (e.g. "0.1" or "4") compares the seed paper's single-point values at that sweep magnitude
    instead of the fitted slopes; use it where the tables' fits differ, since a fit's slope also depends on
    which points it is given.
    """
    if len(tables) != 3:
        raise ConfigurationError(f"a grid study needs three derivative tables, one per mesh level; got {len(tables)}")
    by_level = {}
    for source, table in tables.items():
        meta = table.get("meta", {})
        level = meta.get("level")
        if level not in LEVELS:
            raise ConfigurationError(f"{source}: its meta names no mesh level ({level!r}); not a derivative table?")
        if level in by_level:
            raise ConfigurationError(f"{source} and {by_level[level][0]} are both on the {level} mesh")
        by_level[level] = (source, table)
    (first_source, first), *others = by_level.values()
    for source, table in others:
        for key, default in _SAME_SET_UP.items():
            theirs, ours = table["meta"].get(key, default), first["meta"].get(key, default)
            if theirs != ours:
                raise ConfigurationError(f"{source} and {first_source} differ in {key} ({theirs!r} "
                                         f"against {ours!r}): not one grid study")
        if magnitude is None and table["meta"].get("fit") != first["meta"].get("fit"):
            raise ConfigurationError(f"{source} and {first_source} fit their sweeps differently; compare single points "
                                     "with a magnitude instead (e.g. 0.1 for r' = 0.1)")
    coarse, medium, fine = (by_level[level] for level in LEVELS)
    h = {level: level_cell_size(level) for level in LEVELS}
    body = first["meta"].get("body")
    reference = DERIVATIVES.get(body or "", {}).get("values", {})
    rows = []
    for name in DEFINITIONS:
        if not all(name in table.get("details", {}) for _, table in (coarse, medium, fine)):
            continue
        (phi1, iterative), (phi2, _), (phi3, _) = (_table_value(t, name, magnitude, s) for s, t in (fine, medium, coarse))
        estimate = three_grid_estimate(phi1, phi2, phi3, r21=h["medium"] / h["fine"], r32=h["coarse"] / h["medium"])
        ref = reference.get(name)
        kind = DEFINITIONS[name][2]
        rows.append(ConvergenceRow(name, estimate, ref, None if ref is None else abs(ref) * DERIVATIVE_UNCERTAINTY[kind],
                                   iterative))
    if not rows:
        raise ConfigurationError("the three tables have no derivative in common")
    return rows
