"""The accuracy-cost figure: error of each quantity against the mesh-converged value
versus solve time, one panel per quantity, one line per speed (studies/accuracy.py).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.figure import Figure

from lubecontact.studies.accuracy import QUANTITIES

REGIME_MARKERS = {"boundary": "s", "mixed": "o", "full film": "^"}


def plot_accuracy_cost(table: xr.Dataset):
    """Figure ``accuracy_cost``: relative error against solve time, one panel per quantity,
    one line per speed (regime), each point labelled with its mesh (nodes a side)."""
    quantities = table.attrs["quantities"].split(",")
    fig = Figure(figsize=(4.6 * len(quantities) + 0.8, 4.4), layout="constrained")
    axes = fig.subplots(1, len(quantities), squeeze=False)[0]
    cmap = colormaps["viridis"]
    speeds = table["speed"].values
    for ax, q in zip(axes, quantities):
        for i, speed in enumerate(speeds):
            error = table[f"{q}_error"].values[i]
            times = table["solve_time"].values[i]
            keep = np.isfinite(error) & (error > 0.0)
            colour = cmap(0.85 * i / max(len(speeds) - 1, 1))
            label = f"U = {speed:g} m/s ({table['regime'].values[i]})"
            ax.plot(times[keep], error[keep], marker=REGIME_MARKERS[str(table["regime"].values[i])], markersize=4,
                    color=colour, label=label)
            for n, t, e in zip(table["mesh"].values[keep], times[keep], error[keep]):
                ax.annotate(f"{n}", (t, e), textcoords="offset points", xytext=(3, 3), fontsize=6, color=colour)
        ax.axhline(0.01, color="0.5", linestyle=":", linewidth=0.8)
        ax.annotate("1 %", (0.0, 0.01), xycoords=("axes fraction", "data"), xytext=(2, 2),
                    textcoords="offset points", fontsize=7, color="0.4")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("solve time (s)")
        ax.set_ylabel(f"relative error of the {QUANTITIES[q].label} (\u2013)")
        ax.set_title(QUANTITIES[q].label, fontsize="medium")
        ax.grid(True, which="major", alpha=0.3)
    axes[-1].legend(fontsize="small", title="points: nodes a side (n \u00d7 n)", title_fontsize="small")
    fig.suptitle("What accuracy costs: error against the Richardson-extrapolated value vs wall time of one solve",
                 fontsize="medium")
    return fig
