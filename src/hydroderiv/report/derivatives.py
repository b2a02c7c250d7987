"""Plots of the derivative fits: each sweep's coefficients against its motion variable, with the fit."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..case.conditions import SWEEP_VARIABLES
from ..derivatives.table import DEFINITIONS, SweepFit
from ._figures import pyplot, save_figure



def plot_fits(fits: dict[str, SweepFit], path: str | Path, title: str, reference: dict[str, float] | None = None) -> Path:
    """One panel per derivative: the computed points, the fitted curve, and the experiment's slope."""
    plt = pyplot()
    names = list(fits)
    columns = 2
    rows = max(1, math.ceil(len(names) / columns))
    fig, axes = plt.subplots(rows, columns, figsize=(9.0, 3.0 * rows), squeeze=False)
    for ax, name in zip(axes.flat, names):
        sweep, coefficient, _ = DEFINITIONS[name]
        f = fits[name]
        inside = f.in_fit
        x = np.linspace(min(f.xs[inside].min(), 0.0), max(f.xs[inside].max(), 0.0), 100)  # the fitted range
        has_std = f.y_std is not None and np.isfinite(f.y_std).all()
        # error bars: each point's standard deviation over its averaging window (iterative uncertainty)
        ax.errorbar(f.xs[inside], f.ys[inside], yerr=f.y_std[inside] if has_std else None, fmt="o", capsize=3,
                    label="CFD")
        if not inside.all():  # beyond the fit's angle range: shown, not fitted
            ax.plot(f.xs[~inside], f.ys[~inside], "o", mfc="none", color="C0", label="CFD, not fitted")
        ax.plot(x, f.fit.predict(x), "-", label=f"fit, {name}' = {f.fit.slope_:+.5f}")
        if reference and name in reference:
            ax.plot(x, f.fit.offset_ + reference[name] * x, "k--", lw=1, label=f"experiment {reference[name]:+.5f}")
        ax.set_xlabel(f"{SWEEP_VARIABLES[sweep]}'")
        ax.set_ylabel(f"{coefficient}'")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(names):]:
        ax.set_visible(False)
    fig.suptitle(title)
    return save_figure(fig, path, dpi=100)
