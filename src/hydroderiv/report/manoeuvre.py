"""Figure of a simulated controls-fixed motion: the track, and the velocities against the distance run."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ._figures import pyplot, save_figure


def plot_trajectory(trajectory, path: str | Path, title: str) -> Path:
    """The track in body lengths (beside the straight course it left) and the disturbance's growth: the
    lateral velocity and the rate against time in L/U, on a log scale, where exponential growth is a line."""
    plt = pyplot()
    names = list(trajectory.states)
    lateral, rate, across = names[1], names[2], names[4]
    fig, (track, growth) = plt.subplots(1, 2, figsize=(11, 4.5))
    states = trajectory.states
    # the vertical plane's z is down: plot depth downwards, as a profile is drawn
    sign = -1.0 if across == "z" else 1.0
    track.plot(states["x"], sign * states[across], color="tab:blue")
    track.plot([0, states["x"].max()], [0, 0], color="0.6", linestyle="--", linewidth=0.8, label="straight course")
    track.set_xlabel("x' (body lengths)")
    track.set_ylabel("-z' (body lengths, up)" if across == "z" else "y' (body lengths, starboard)")
    track.set_aspect("equal", adjustable="datalim")
    track.legend(loc="best", fontsize=8)
    for name, colour in ((lateral, "tab:orange"), (rate, "tab:green")):
        magnitude = np.abs(states[name])
        # an exact zero (the undisturbed start) has no place on a log scale: leave it out
        shown = np.where(magnitude > 1e-9 * max(magnitude.max(), 1e-300), magnitude, np.nan)
        growth.semilogy(trajectory.time, shown, color=colour, label=f"|{name}'|")
    growth.set_xlabel("t' = t U / L (body lengths run)")
    growth.set_ylabel("magnitude (prime units)")
    growth.legend(loc="best", fontsize=8)
    if trajectory.beyond_range:
        growth.set_title("beyond the table's conditions: extrapolated", fontsize=9, color="tab:red")
    fig.suptitle(title, fontsize=10)
    return save_figure(fig, path)
