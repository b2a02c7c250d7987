"""Resistance tables and plots."""

from __future__ import annotations

from pathlib import Path

from rich.table import Table

from ._figures import pyplot, save_figure


def resistance_table(points: list[dict], title: str) -> Table:
    table = Table(title=title)
    # short headers: the table must stay readable in an 80-column terminal
    for column in ("kn", "CFD N", "press. N", "visc. N", "exp. N", "err %", "iter", "conv", "wall s", "y+ hull"):
        table.add_column(column, justify="right")
    for p in points:
        yplus = p.get("yplus", {}).get("hull", {}).get("mean")
        table.add_row(
            f"{p['speed_knots']:.2f}",
            f"{p['resistance_N']:.1f}",
            f"{p['pressure_N']:.1f}",
            f"{p['viscous_N']:.1f}",
            "-" if p["experiment_N"] is None else f"{p['experiment_N']:.1f}",
            "-" if p["error_pct"] is None else f"{p['error_pct']:+.1f}",
            str(p["iterations"]),
            "yes" if p["converged"] else "NO",
            f"{p['wall_seconds']:.0f}",
            "-" if yplus is None else f"{yplus:.0f}",
        )
    return table


def plot_resistance(points: list[dict], path: str | Path, title: str) -> Path:
    """Resistance against speed: CFD (total, pressure, viscous) and the towing-tank points."""
    plt = pyplot()
    knots = [p["speed_knots"] for p in points]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    ax.plot(knots, [p["resistance_N"] for p in points], "o-", label="CFD total")
    ax.plot(knots, [p["viscous_N"] for p in points], "s--", ms=4, label="CFD viscous")
    ax.plot(knots, [p["pressure_N"] for p in points], "^--", ms=4, label="CFD pressure")
    measured = [(p["speed_knots"], p["experiment_N"]) for p in points if p["experiment_N"] is not None]
    if measured:
        ax.plot(*zip(*measured), "kx", ms=9, mew=2, label="experiment")
    ax.set_xlabel("speed (knots)")
    ax.set_ylabel("resistance (N)")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    return save_figure(fig, path)
