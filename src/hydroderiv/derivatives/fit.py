"""Fitting hydrodynamic derivatives: an estimator in the scikit-learn shape.

A derivative such as Y'v is the slope at the origin of a force coefficient against its motion variable
(Y' against v'). The fit carries a nonlinear term so that points at larger incidence or rate do not bias
the slope: Y' = Yv v' + Yv|v| v'|v'| (Gertler & Hagen 1967), or a cubic term. The model is odd in the
motion variable, as a mirror-symmetric body requires for these pairs; an optional offset absorbs a
small asymmetry (the sail makes Z' and M' non-zero at w' = 0).
"""

from __future__ import annotations

import numpy as np

from ..errors import ConfigurationError

NONLINEAR_TERMS = {
    "abs": lambda x: x * np.abs(x),  # Gertler-Hagen v|v|
    "cubic": lambda x: x**3,
    "none": None,
}


class DerivativeFit:
    """Least-squares fit of ``y = c0 + slope x + nonlinear x|x|`` (or ``x^3``).

    Parameters (configuration only, as in scikit-learn): ``nonlinear`` in {'abs', 'cubic', 'none'} and
    ``fit_offset``. :meth:`fit` returns ``self`` with the fitted attributes ``slope_``, ``slope_stderr_``,
    ``slope_iterative_stderr_``, ``nonlinear_``, ``nonlinear_stderr_``, ``offset_``, ``residual_rms_``,
    ``n_points_`` and ``spare_magnitudes_``.

    Two uncertainties of the slope: ``slope_stderr_`` from the scatter of the points about the fit, and
    ``slope_iterative_stderr_`` from the points' own iterative uncertainty (``y_std`` given to :meth:`fit`,
    the standard deviation of each coefficient over its averaging window) carried through the same fit.

    ``spare_magnitudes_`` is how many distinct non-zero |x| the fit has beyond its odd terms (slope, and the
    nonlinear term). At zero the odd part of the curve passes through the points (a mirror pair per
    magnitude fixes it exactly), so ``slope_stderr_`` measures only how far the pairs are from mirroring
    each other, not how well the model fits the curve.
    """

    def __init__(self, nonlinear: str = "abs", fit_offset: bool = False):
        self.nonlinear = nonlinear
        self.fit_offset = fit_offset

    def has_enough_magnitudes(self, x) -> bool:
        """Whether ``x`` holds the distinct non-zero |x| the odd terms need: one for the slope, one more for
        a nonlinear term."""
        return _magnitudes(x) >= self._odd_terms()

    def _odd_terms(self) -> int:
        return 1 if NONLINEAR_TERMS.get(self.nonlinear) is None else 2

    def _design(self, x: np.ndarray) -> np.ndarray:
        if self.nonlinear not in NONLINEAR_TERMS:
            raise ConfigurationError(f"unknown nonlinear term {self.nonlinear!r}; choose one of {', '.join(NONLINEAR_TERMS)}")
        columns = [x]
        term = NONLINEAR_TERMS[self.nonlinear]
        if term is not None:
            columns.append(term(x))
        if self.fit_offset:
            columns.append(np.ones_like(x))
        return np.column_stack(columns)

    def fit(self, x, y, y_std=None) -> DerivativeFit:
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        design = self._design(x)
        n, p = design.shape
        spare_magnitudes = _magnitudes(x) - self._odd_terms()
        if n < p or spare_magnitudes < 0:
            raise ConfigurationError(
                f"{n} points at {len(np.unique(np.abs(x)))} distinct magnitudes cannot determine {p} terms; "
                "add conditions to the sweep"
            )
        # standard errors from the residual variance; with no spare points there is none to estimate
        coef, stderr = least_squares(design, y)
        residual = y - design @ coef
        if y_std is None:
            self.slope_iterative_stderr_ = np.nan
        else:
            # the coefficients are a linear map of y, (D'D)^-1 D' y, so independent point variances carry
            # through as (D'D)^-1 D' diag(s^2) D (D'D)^-1
            sensitivity = np.linalg.inv(design.T @ design) @ design.T
            self.slope_iterative_stderr_ = float(np.sqrt(sensitivity[0] ** 2 @ np.asarray(y_std, dtype=float) ** 2))
        self.slope_, self.slope_stderr_ = float(coef[0]), float(stderr[0])
        has_nonlinear = NONLINEAR_TERMS[self.nonlinear] is not None
        self.nonlinear_ = float(coef[1]) if has_nonlinear else 0.0
        self.nonlinear_stderr_ = float(stderr[1]) if has_nonlinear else 0.0
        self.offset_ = float(coef[-1]) if self.fit_offset else 0.0
        self.residual_rms_ = float(np.sqrt(np.mean(residual**2)))
        self.n_points_ = n
        self.spare_magnitudes_ = spare_magnitudes
        return self

    def predict(self, x) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        coef = [self.slope_]
        if NONLINEAR_TERMS[self.nonlinear] is not None:
            coef.append(self.nonlinear_)
        if self.fit_offset:
            coef.append(self.offset_)
        return self._design(x) @ np.array(coef)


def _magnitudes(x) -> int:
    """The number of distinct non-zero |x|."""
    x = np.asarray(x, dtype=float)
    return len(np.unique(np.abs(x[x != 0])))


class EvenFit:
    """Least-squares fit of ``y = constant u'^2 + quadratic x^2``: a load even in its motion variable.

    The Gertler-Hagen form of the axial force in drift, X' = X'uu u'^2 + X'vv v'^2, and of the loads that
    port-starboard mirror symmetry makes even in v' and r' (Z'vv, M'vv, Z'rr, M'rr). ``u`` is the axial
    velocity ratio u' of each point (1 in a turn, cos of the incidence in drift and pitch). No
    configuration; :meth:`fit` returns ``self`` with ``constant_``, ``quadratic_``, ``quadratic_stderr_``
    (NaN without a spare point), ``n_points_`` and ``odd_part_``.

    ``odd_part_`` is how far the mirror pairs (+x, -x) are from equal: half their largest
    difference, relative to the largest even load ``quadratic x^2`` fitted (NaN without a pair). An even
    model ignores the odd part of the points, which for a mirror-symmetric body is the mesh's asymmetry and
    the iterative scatter; this says how large that part is beside what was fitted.
    """

    def fit(self, x, y, u=None) -> EvenFit:
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        u = np.ones_like(x) if u is None else np.asarray(u, dtype=float)
        if _magnitudes(x) < 1 or len(x) < 2:
            raise ConfigurationError(f"{len(x)} points at {_magnitudes(x)} non-zero magnitudes cannot determine "
                                     "an even load's two terms; add conditions to the sweep")
        coef, stderr = least_squares(np.column_stack([u**2, x**2]), y)
        self.constant_, self.quadratic_ = float(coef[0]), float(coef[1])
        self.quadratic_stderr_ = float(stderr[1])
        self.n_points_ = len(x)
        pairs = [(y[x == m].mean(), y[x == -m].mean()) for m in np.unique(np.abs(x[x != 0]))
                 if (x == m).any() and (x == -m).any()]
        even_size = float(np.max(np.abs(self.quadratic_ * x**2)))
        odd_size = max((abs(plus - minus) / 2 for plus, minus in pairs), default=np.nan)
        self.odd_part_ = float(odd_size / even_size) if pairs and even_size > 0 else np.nan
        return self

    def predict(self, x, u=None) -> np.ndarray:
        x = np.asarray(x, dtype=float)
        u = np.ones_like(x) if u is None else np.asarray(u, dtype=float)
        return self.constant_ * u**2 + self.quadratic_ * x**2


def least_squares(design: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The least-squares coefficients of ``y`` on the columns of ``design`` and their standard errors from
    the residual variance (NaN with no point to spare)."""
    coef, *_ = np.linalg.lstsq(design, y, rcond=None)
    residual = y - design @ coef
    dof = len(y) - design.shape[1]
    sigma2 = float(residual @ residual) / dof if dof > 0 else np.nan
    return coef, np.sqrt(np.diag(sigma2 * np.linalg.inv(design.T @ design)))
